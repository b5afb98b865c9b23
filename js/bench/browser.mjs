// Browser benchmarks of the package in headless Chromium (Debian's, through
// playwright-core), in one page, against manifold-3d's WebAssembly in the same page:
//   node bench/browser.mjs [--reps N (default 3)]
// manifold-3d is optional (not a dependency): `npm install --no-save manifold-3d@3.5.4`
// puts it where the page loads it (/node_modules/manifold-3d/manifold.js).
// Cases: unions of two UV spheres of 998,000 and of 2,002,224 triangles each (closed; the
// demo's bigSphere), the generated terrain − pit and the Kirra terrain − cylinder (open
// surfaces: manifold-3d takes closed meshes only; the Kirra files are read here from
// ../shared/data beside the repository and handed to the page, skipped where absent). Each
// time is the median of N runs, conversions into each library's mesh type included;
// meshbool runs on the page's thread (single-threaded WebAssembly) and through
// meshbool/async (the same in a Web Worker, inputs copied across).
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

const server = await startServer({ port: 0 });
const browser = await chromium.launch({ executablePath, headless: true, args: ["--headless", "--no-sandbox", "--disable-gpu"] });
try {
	const page = await browser.newPage();
	page.on("pageerror", (e) => console.error(`page error: ${e.message}`));
	await page.goto(`${server.url}bench/browser.html`);
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
		const worker = createWorker();
		await worker.start();
		let manifold = null;
		if (hasManifold) {
			const Module = (await import("/node_modules/manifold-3d/manifold.js")).default;
			manifold = await Module();
			manifold.setup();
		}
		for (const k of [500, 708]) {
			const a = bigSphere("a", k), b = bigSphere("b", k);
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
		const pairs = [["terrain − pit (generated)", mb.makeTerrain(), mb.makePit()]];
		if (kirra) {
			const read = (name) => mb.readMesh(Uint8Array.from(kirra[name], (c) => c.charCodeAt(0)), name);
			pairs.push(["kirra terrain − cylinder", read("kirra_terrain.obj"), read("kirra_cylinder.obj")]);
		}
		for (const [label, a, b] of pairs) {
			m = await median(() => mb.booleanIndexed(a, b, "subtract"));
			out.push([`${label}: meshbool, page thread`, m.ms, `${m.r.index.length / 3} triangles`]);
			m = await median(() => worker.booleanIndexed(a, b, "subtract"));
			out.push([`${label}: meshbool/async (Web Worker)`, m.ms, `${m.r.index.length / 3} triangles`]);
		}
		worker.terminate();
		return out;
	}, { reps, hasManifold, kirra });
	for (const [name, ms, note] of rows) console.log(`${name.padEnd(60)} ${ms.toFixed(0).padStart(8)} ms  ${note}`);
	console.log(`\nChromium ${browser.version()}, ${reps} runs each (median)${hasManifold ? "" : "; manifold-3d not installed (npm install --no-save manifold-3d@3.5.4)"}`);
	if (noKirra) console.log(`kirra terrain − cylinder: skipped, ${noKirra}`);
} finally {
	await browser.close();
	await server.close();
}
