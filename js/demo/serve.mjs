// The demo's static server (node:http only, no dependencies): the package folder js/ at
// `/` (so /demo/, /src/, /wasm/ and /node_modules/ resolve as the page imports them).
// The page generates its example meshes; it needs no data files.
//
//   node demo/serve.mjs [--isolated] [port]        (or PORT=8377; port 0 picks a free one)
//
// --isolated (or ISOLATED=1) sends Cross-Origin-Opener-Policy: same-origin and
// Cross-Origin-Embedder-Policy: require-corp with every answer: the page is then
// cross-origin isolated (SharedArrayBuffer), and its worker runs the threaded build where
// it is installed (npm run build:threads).
//
// Binds 127.0.0.1 unless HOST says otherwise. Importing this module starts nothing; call
// `startServer`.
import http from "node:http";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
/** The folder served at `/` (js/). */
export const packageRoot = path.resolve(here, "..");

const MIME = {
	".html": "text/html; charset=utf-8",
	".js": "text/javascript; charset=utf-8",
	".mjs": "text/javascript; charset=utf-8",
	".css": "text/css; charset=utf-8",
	".json": "application/json; charset=utf-8",
	".map": "application/json; charset=utf-8",
	".wasm": "application/wasm",
	".svg": "image/svg+xml",
	".png": "image/png",
	".ico": "image/x-icon",
	".txt": "text/plain; charset=utf-8",
	".md": "text/plain; charset=utf-8",
	".ts": "text/plain; charset=utf-8",
	".obj": "text/plain; charset=utf-8",
	".stl": "model/stl",
	".ply": "application/octet-stream",
	".off": "text/plain; charset=utf-8",
	".dxf": "text/plain; charset=utf-8",
};

/** The file a URL path names, or null when it leaves the served folder. */
function resolvePath(urlPath) {
	let decoded;
	try {
		decoded = decodeURIComponent(urlPath);
	} catch {
		return null;
	}
	if (decoded.includes("\0")) return null;
	const file = path.resolve(packageRoot, "." + path.posix.normalize("/" + decoded));
	return file === packageRoot || file.startsWith(packageRoot + path.sep) ? file : null;
}

/** The headers that make a page cross-origin isolated (`startServer({isolated: true})`). */
export const ISOLATION_HEADERS = { "Cross-Origin-Opener-Policy": "same-origin", "Cross-Origin-Embedder-Policy": "require-corp" };

function send(res, status, body, type = "text/plain; charset=utf-8") {
	res.writeHead(status, { "Content-Type": type, "Content-Length": Buffer.byteLength(body), "Cache-Control": "no-store" });
	res.end(body);
}

/** Answers one request from the served folder (GET and HEAD). */
function handle(req, res) {
	if (req.method !== "GET" && req.method !== "HEAD") {
		res.setHeader("Allow", "GET, HEAD");
		return send(res, 405, "method not allowed\n");
	}
	const { pathname } = new URL(req.url, "http://localhost");
	if (pathname === "/") {
		res.writeHead(302, { Location: "/demo/" });
		return res.end();
	}
	let file = resolvePath(pathname);
	if (file === null) return send(res, 403, "forbidden\n");
	fs.stat(file, (err, stat) => {
		if (!err && stat.isDirectory()) {
			if (!pathname.endsWith("/")) {
				res.writeHead(301, { Location: pathname + "/" });
				return res.end();
			}
			file = path.join(file, "index.html");
			return fs.stat(file, (err2, stat2) => serveFile(req, res, file, err2 ? null : stat2));
		}
		serveFile(req, res, file, err ? null : stat);
	});
}

function serveFile(req, res, file, stat) {
	if (stat === null || !stat.isFile()) return send(res, 404, "not found\n");
	const type = MIME[path.extname(file).toLowerCase()] || "application/octet-stream";
	res.writeHead(200, { "Content-Type": type, "Content-Length": stat.size, "Cache-Control": "no-store" });
	if (req.method === "HEAD") return res.end();
	fs.createReadStream(file).on("error", () => res.destroy()).pipe(res);
}

/**
 * Starts the server: resolves to `{server, url, port, close()}` once it listens, `url`
 * the demo page's address.
 *
 * @param {{port?: number, host?: string, isolated?: boolean}} [options] port default 8377 (0: a free one), host default 127.0.0.1, isolated: send ISOLATION_HEADERS
 * @returns {Promise<{server: http.Server, url: string, port: number, close: () => Promise<void>}>}
 */
export function startServer(options = {}) {
	const port = options.port ?? 8377;
	const host = options.host ?? "127.0.0.1";
	const server = http.createServer((req, res) => {
		if (options.isolated) for (const [k, v] of Object.entries(ISOLATION_HEADERS)) res.setHeader(k, v);
		handle(req, res);
	});
	return new Promise((resolve, reject) => {
		server.once("error", reject);
		server.listen(port, host, () => {
			const actual = server.address().port;
			const shown = host.includes(":") ? `[${host}]` : host;
			resolve({
				server,
				port: actual,
				url: `http://${shown}:${actual}/demo/`,
				close: () => new Promise((done) => server.close(() => done())),
			});
		});
	});
}

if (process.argv[1] && import.meta.url === pathToFileURL(path.resolve(process.argv[1])).href) {
	const args = process.argv.slice(2);
	const isolated = args.includes("--isolated") || process.env.ISOLATED === "1";
	const rest = args.filter((a) => a !== "--isolated");
	const arg = rest[0] ?? process.env.PORT ?? "8377";
	const port = Number(arg);
	if (rest.length > 1 || !Number.isInteger(port) || port < 0 || port > 65535) {
		console.error(`serve.mjs: usage: node demo/serve.mjs [--isolated] [port] (not a port: ${arg})`);
		process.exit(2);
	}
	startServer({ port, host: process.env.HOST || "127.0.0.1", isolated }).then(
		({ url }) => console.log(`meshbool demo: ${url}${isolated ? " (cross-origin isolated)" : ""}`),
		(err) => {
			console.error(`serve.mjs: cannot listen on port ${port}: ${err.message}`);
			process.exit(1);
		},
	);
}
