// Node benchmarks of the package (single-threaded WebAssembly) against the reference
// library and manifold-3d (npm, WebAssembly) on the same machine, in one run:
//   node bench/bench.mjs [--reps N (default 11)] [--slow]
// Peers are optional, named by environment variables (they are not dependencies):
//   REF=/path/to/trimesh-boolean/src/index.js   MANIFOLD=/path/to/manifold-3d/manifold.js
// Cases: the generated terrain − pit (open surfaces), the Kirra terrain − cylinder (open
// surface, soup API and typed arrays; read from ../shared/data beside the repository,
// skipped with a note where absent), and unions of two overlapping UV spheres of 50k and
// 200k triangles in all (closed; the package's makeSphere). Each time is the
// median of N runs (the reference: one run; its 200k case only with --slow) and includes
// the conversions in and out of each library's own mesh type.
import { readFileSync, statSync } from "node:fs";
import { gzipSync } from "node:zlib";
import { performance } from "node:perf_hooks";
import * as mb from "../src/index.js";
import { missing as noKirra, sharedData } from "../test/shared-data.mjs";

const args = process.argv.slice(2);
const reps = Number(args[args.indexOf("--reps") + 1]) || 11;
const slow = args.includes("--slow");

function median(f, n) {
	const times = [];
	let out;
	for (let i = 0; i < n; i++) {
		const t0 = performance.now();
		out = f();
		times.push(performance.now() - t0);
	}
	times.sort((a, b) => a - b);
	return { ms: times[Math.floor(times.length / 2)], out };
}

const ref = process.env.REF ? await import(process.env.REF) : null;
let manifold = null;
if (process.env.MANIFOLD) {
	const Module = (await import(process.env.MANIFOLD)).default;
	manifold = await Module();
	manifold.setup();
}

function manifoldUnion(a, b) {
	const { Manifold, Mesh } = manifold;
	const make = (m) => new Manifold(new Mesh({ numProp: 3, vertProperties: Float32Array.from(m.positions), triVerts: m.index }));
	const A = make(a), B = make(b);
	const U = A.add(B);
	const mesh = U.getMesh();
	const tris = mesh.triVerts.length / 3, vol = U.volume();
	A.delete(); B.delete(); U.delete();
	return { tris, vol };
}

const rows = [];
const row = (name, ms, note = "") => {
	rows.push([name, ms, note]);
	console.log(`${name.padEnd(52)} ${ms.toFixed(1).padStart(10)} ms  ${note}`);
};

// Generated terrain − pit (both open; the result is the mined-out solid)
{
	const terrain = mb.makeTerrain(), pit = mb.makePit();
	const t = median(() => mb.booleanIndexed(terrain, pit, "subtract"), reps);
	row("terrain − pit (generated): meshbool booleanIndexed", t.ms, `${t.out.index.length / 3} triangles, volume ${t.out.report.volume.toFixed(3)}`);
}

// Kirra terrain − cylinder (other projects' data, beside the repository)
if (noKirra) {
	console.log(`kirra terrain − cylinder: skipped, ${noKirra}`);
} else {
	const terrain = mb.readMesh(sharedData("kirra_terrain.obj"), "obj");
	const cylinder = mb.readMesh(sharedData("kirra_cylinder.obj"), "obj");
	const tSoup = mb.typedToSoup(terrain), cSoup = mb.typedToSoup(cylinder);
	const r = median(() => mb.boolean(tSoup, cSoup, "subtract"), reps);
	row("kirra terrain − cylinder: meshbool boolean (soups)", r.ms, `${r.out.soup.length} triangles`);
	const t = median(() => mb.booleanIndexed(terrain, cylinder, "subtract"), reps);
	row("kirra terrain − cylinder: meshbool booleanIndexed", t.ms, `${t.out.index.length / 3} triangles`);
	if (ref) {
		const b = median(() => ref.bmsBooleanOp(tSoup, cSoup, "subtract"), 1);
		row("kirra terrain − cylinder: reference bmsBooleanOp", b.ms, `${b.out.result ? b.out.result.soup.length : "null"} triangles`);
		const c = median(() => ref.boolean(tSoup, cSoup, "subtract"), 1);
		row("kirra terrain − cylinder: reference boolean", c.ms, `${c.out ? c.out.soup.length : "null"} triangles`);
	}
}

// Sphere unions
for (const [label, slices, stacks, refOk] of [["50k", 125, 101, true], ["200k", 250, 201, slow]]) {
	// `2 · slices · (stacks − 1)` triangles each.
	const a = mb.makeSphere({ segments: slices, rings: stacks }), b = mb.makeSphere({ center: [0.3, 0.2, 0.1], segments: slices, rings: stacks });
	const n = (a.index.length + b.index.length) / 3;
	const r = median(() => mb.booleanIndexed(a, b, "union", { selfCheck: false }), reps);
	row(`union of two spheres, ${label} (${n}): meshbool, no self-check`, r.ms, `volume ${r.out.report.volume.toFixed(6)}`);
	const d = median(() => mb.booleanIndexed(a, b, "union"), reps);
	row(`union of two spheres, ${label}: meshbool, default checks`, d.ms, `${d.out.index.length / 3} triangles`);
	if (manifold) {
		const m = median(() => manifoldUnion(a, b), reps);
		row(`union of two spheres, ${label}: manifold-3d`, m.ms, `volume ${m.out.vol.toFixed(6)}`);
	}
	if (ref && refOk) {
		const sa = mb.typedToSoup(a), sb = mb.typedToSoup(b);
		const q = median(() => ref.boolean(sa, sb, "union"), 1);
		row(`union of two spheres, ${label}: reference boolean`, q.ms, `${q.out ? q.out.soup.length : "null"} triangles`);
	}
}

const wasm = new URL("../wasm/meshbool_wasm_bg.wasm", import.meta.url);
const bytes = readFileSync(wasm);
console.log(`\nmeshbool_wasm_bg.wasm: ${(statSync(wasm).size / 1024).toFixed(0)} KiB, ${(gzipSync(bytes, { level: 9 }).length / 1024).toFixed(0)} KiB gzipped; node ${process.version}`);
