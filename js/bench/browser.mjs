// Browser benchmarks of the package in headless Chromium (Debian's, through
// playwright-core), in one cross-origin isolated page (serve.mjs --isolated), against
// manifold-3d's WebAssembly in the same page:
//   node bench/browser.mjs [--reps N (default 3)]
// manifold-3d is optional (not a dependency): `npm install --no-save manifold-3d@3.5.4`
// puts it where the page loads it (/node_modules/manifold-3d/manifold.js). The threaded
// build is measured where it is built (npm run build:threads).
// Cases: unions of two UV spheres of 998,000 and of 2,002,224 triangles each (closed; the
// demo's bigSphere), the generated terrain − pit and the Kirra terrain − cylinder (open
// surfaces: manifold-3d takes closed meshes only; the Kirra files are read here from
// ../shared/data beside the repository and handed to the page, skipped where absent). Each
// time is the median of N runs, conversions into each library's mesh type included.
// meshbool runs on the page's thread (the single-threaded build: the main thread's
// default) and through meshbool/async in Web Workers, the inputs copied across: one
// running the single-threaded build (createWorker({threads: 1})), one the threaded build
// with navigator.hardwareConcurrency threads (createWorker()).
import fs from "node:fs";
import path from "node:path";
import { chromium } from "playwright-core";
import { startServer, packageRoot } from "../demo/serve.mjs";
import { missing as noKirra, sharedData } from "../test/shared-data.mjs";

const args = process.argv.slice(2);
const reps = Number(args[args.indexOf("--reps") + 1]) || 3;
const executablePath = process.env.CHROMIUM || "/usr/bin/chromium";
const hasManifold = fs.existsSync(path.join(packageRoot, "node_modules", "manifold-3d", "manifold.js"));
// The Kirra files' text (OBJ), or null.
const kirra = noKirra ? null : Object.fromEntries(["kirra_terrain.obj", "kirra_cylinder.obj"].map((n) => [n, sharedData(n).toString("latin1")]));

const server = await startServer({ port: 0, isolated: true });
const browser = await chromium.launch({ executablePath, headless: true, args: ["--headless", "--no-sandbox", "--disable-gpu"] });
try {
	const page = await browser.newPage();
	page.on("pageerror", (e) => console.error(`page error: ${e.message}`));
	await page.goto(new URL("../bench/browser.html", server.url).href);
	const rows = await page.evaluate(async ({ reps, hasManifold, kirra }) => {
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
		const { bigSphere } = await import("/demo/examples.js");
		const single = createWorker({ threads: 1 });
		const threaded = createWorker();
		const info = await threaded.buildInfo();
		const pool = info.build === "threads" ? `threads (${info.threads})` : null;
		let manifold = null;
		if (hasManifold) {
			const Module = (await import("/node_modules/manifold-3d/manifold.js")).default;
			manifold = await Module();
			manifold.setup();
		}
		// Each case: `[label, a, b, op]`; each row: [case, column, ms, note].
		const run = async (label, a, b, op, closed) => {
			const note = (r) => `${r.index.length / 3} triangles, volume ${r.report.volume.toFixed(6)}`;
			let m = await median(() => mb.booleanIndexed(a, b, op));
			out.push([label, "page thread", m.ms, note(m.r)]);
			if (closed) {
				m = await median(() => mb.booleanIndexed(a, b, op, { selfCheck: false }));
				out.push([label, "page thread, no self-check", m.ms, note(m.r)]);
			}
			m = await median(() => single.booleanIndexed(a, b, op));
			out.push([label, "Worker, single-threaded", m.ms, note(m.r)]);
			if (closed) {
				m = await median(() => single.booleanIndexed(a, b, op, { selfCheck: false }));
				out.push([label, "Worker, single-threaded, no self-check", m.ms, note(m.r)]);
			}
			if (pool) {
				m = await median(() => threaded.booleanIndexed(a, b, op));
				out.push([label, `Worker, ${pool}`, m.ms, note(m.r)]);
				if (closed) {
					m = await median(() => threaded.booleanIndexed(a, b, op, { selfCheck: false }));
					out.push([label, `Worker, ${pool}, no self-check`, m.ms, note(m.r)]);
				}
			}
			if (manifold && closed) {
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
				out.push([label, "manifold-3d", m.ms, `${m.r.tris} triangles, volume ${m.r.vol.toFixed(6)}`]);
			}
		};
		for (const k of [500, 708]) {
			const a = bigSphere("a", k), b = bigSphere("b", k);
			await run(`union of two spheres, ${a.index.length / 3} triangles each`, a, b, "union", true);
		}
		await run("terrain − pit (generated)", mb.makeTerrain(), mb.makePit(), "subtract", false);
		if (kirra) {
			const read = (name) => mb.readMesh(Uint8Array.from(kirra[name], (c) => c.charCodeAt(0)), name);
			await run("kirra terrain − cylinder", read("kirra_terrain.obj"), read("kirra_cylinder.obj"), "subtract", false);
		}
		single.terminate();
		threaded.terminate();
		out.push(["", "", 0, `threaded build: ${info.build === "threads" ? `${info.threads} threads` : `not used (${info.reason})`}`]);
		return out;
	}, { reps, hasManifold, kirra });
	const info = rows.pop()[3];
	for (const [label, column, ms, note] of rows) console.log(`${`${label}: ${column}`.padEnd(78)} ${ms.toFixed(0).padStart(8)} ms  ${note}`);
	// The same as a table: a row per case, a column per way of running it.
	const columns = [...new Set(rows.map((r) => r[1]))];
	const cases = [...new Set(rows.map((r) => r[0]))];
	console.log(`\n| case | ${columns.join(" | ")} |\n|---|${columns.map(() => "---").join("|")}|`);
	for (const c of cases) {
		const cell = (col) => {
			const r = rows.find((x) => x[0] === c && x[1] === col);
			return r ? `${r[2].toFixed(0)} ms` : "";
		};
		console.log(`| ${c} | ${columns.map(cell).join(" | ")} |`);
	}
	console.log(`\nChromium ${browser.version()}, ${reps} runs each (median), navigator.hardwareConcurrency ${await page.evaluate(() => navigator.hardwareConcurrency)}, ${info}${hasManifold ? "" : "; manifold-3d not installed (npm install --no-save manifold-3d@3.5.4)"}`);
	if (noKirra) console.log(`kirra terrain − cylinder: skipped, ${noKirra}`);
} finally {
	await browser.close();
	await server.close();
}
