// Browser benchmarks of the package in headless Chromium (Debian's, through
// playwright-core), in one page, against manifold-3d's WebAssembly in the same page:
//   node bench/browser.mjs [--reps N (default 3)]
// manifold-3d is optional (not a dependency): `npm install --no-save manifold-3d@3.5.4`
// puts it where the page loads it (/node_modules/manifold-3d/manifold.js).
// Cases: unions of two UV spheres of 998,000 and of 2,002,224 triangles each (closed), and the
// Kirra terrain − cylinder (an open surface: manifold-3d takes closed meshes only). Each
// time is the median of N runs, conversions into each library's mesh type included;
// meshbool runs on the page's thread (single-threaded WebAssembly) and through
// meshbool/async (the same in a Web Worker, inputs copied across).
import fs from "node:fs";
import path from "node:path";
import { chromium } from "playwright-core";
import { startServer, packageRoot } from "../demo/serve.mjs";

const args = process.argv.slice(2);
const reps = Number(args[args.indexOf("--reps") + 1]) || 3;
const executablePath = process.env.CHROMIUM || "/usr/bin/chromium";
const hasManifold = fs.existsSync(path.join(packageRoot, "node_modules", "manifold-3d", "manifold.js"));

const server = await startServer({ port: 0 });
const browser = await chromium.launch({ executablePath, headless: true, args: ["--headless", "--no-sandbox", "--disable-gpu"] });
try {
	const page = await browser.newPage();
	page.on("pageerror", (e) => console.error(`page error: ${e.message}`));
	await page.goto(`${server.url}bench/browser.html`);
	const rows = await page.evaluate(async ({ reps, hasManifold }) => {
		const mb = await import("/src/index.js");
		const { createWorker } = await import("/src/async.js");
		const out = [];
		const median = async (f) => {
			const times = [];
			let r;
			for (let i = 0; i < reps; i++) {
				const t0 = performance.now();
				r = await f();
				times.push(performance.now() - t0);
			}
			times.sort((a, b) => a - b);
			return { ms: times[Math.floor(times.length / 2)], r };
		};
		// A UV sphere of radius 1 centred at (cx, 0, 0): 2n meridians, n bands, 4n(n − 1) triangles, closed.
		const sphere = (n, cx) => {
			const around = 2 * n, positions = [cx, 0, 1];
			for (let i = 1; i < n; i++) {
				for (let j = 0; j < around; j++) {
					const th = (Math.PI * i) / n, ph = (Math.PI * j) / n;
					positions.push(cx + Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th));
				}
			}
			positions.push(cx, 0, -1);
			const last = positions.length / 3 - 1, ring = (i, j) => 1 + (i - 1) * around + (j % around), index = [];
			for (let j = 0; j < around; j++) index.push(0, ring(1, j), ring(1, j + 1));
			for (let i = 1; i < n - 1; i++) for (let j = 0; j < around; j++) index.push(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
			for (let j = 0; j < around; j++) index.push(last, ring(n - 1, j + 1), ring(n - 1, j));
			return { positions: Float64Array.from(positions), index: Uint32Array.from(index) };
		};
		const worker = createWorker();
		await worker.start();
		let manifold = null;
		if (hasManifold) {
			const Module = (await import("/node_modules/manifold-3d/manifold.js")).default;
			manifold = await Module();
			manifold.setup();
		}
		for (const k of [500, 708]) {
			const a = sphere(k, 0), b = sphere(k, 0.5);
			const n = (a.index.length + b.index.length) / 3;
			const label = `union of two spheres, ${n} triangles`;
			let m = await median(() => mb.booleanIndexed(a, b, "union"));
			out.push([`${label}: meshbool, page thread`, m.ms, `${m.r.index.length / 3} triangles, volume ${m.r.report.volume.toFixed(6)}`]);
			m = await median(() => mb.booleanIndexed(a, b, "union", { selfCheck: false }));
			out.push([`${label}: meshbool, no self-check`, m.ms, `volume ${m.r.report.volume.toFixed(6)}`]);
			m = await median(() => worker.booleanIndexed(a, b, "union"));
			out.push([`${label}: meshbool/async (Web Worker)`, m.ms, `volume ${m.r.report.volume.toFixed(6)}`]);
			if (manifold) {
				const { Manifold, Mesh } = manifold;
				const make = (x) => new Manifold(new Mesh({ numProp: 3, vertProperties: Float32Array.from(x.positions), triVerts: x.index }));
				m = await median(() => {
					const A = make(a), B = make(b), U = A.add(B);
					const tris = U.getMesh().triVerts.length / 3, vol = U.volume();
					A.delete();
					B.delete();
					U.delete();
					return { tris, vol };
				});
				out.push([`${label}: manifold-3d`, m.ms, `${m.r.tris} triangles, volume ${m.r.vol.toFixed(6)}`]);
			}
		}
		let m;
		const read = async (name) => mb.readMesh(new Uint8Array(await (await fetch(`/data/${name}`)).arrayBuffer()), "obj");
		const terrain = await read("kirra_terrain.obj"), cylinder = await read("kirra_cylinder.obj");
		m = await median(() => mb.booleanIndexed(terrain, cylinder, "subtract"));
		out.push(["kirra terrain − cylinder: meshbool, page thread", m.ms, `${m.r.index.length / 3} triangles`]);
		m = await median(() => worker.booleanIndexed(terrain, cylinder, "subtract"));
		out.push(["kirra terrain − cylinder: meshbool/async (Web Worker)", m.ms, `${m.r.index.length / 3} triangles`]);
		worker.terminate();
		return out;
	}, { reps, hasManifold });
	for (const [name, ms, note] of rows) console.log(`${name.padEnd(60)} ${ms.toFixed(0).padStart(8)} ms  ${note}`);
	console.log(`\nChromium ${browser.version()}, ${reps} runs each (median)${hasManifold ? "" : "; manifold-3d not installed (npm install --no-save manifold-3d@3.5.4)"}`);
} finally {
	await browser.close();
	await server.close();
}
