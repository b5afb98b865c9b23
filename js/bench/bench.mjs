// Node benchmarks of the package (single-threaded WebAssembly) against the reference
// library and manifold-3d (npm, WebAssembly) on the same machine, in one run:
//   node bench/bench.mjs [--reps N (default 11)] [--slow]
// Peers are optional, named by environment variables (they are not dependencies):
//   REF=/path/to/trimesh-boolean/src/index.js   MANIFOLD=/path/to/manifold-3d/manifold.js
// Cases: Kirra terrain − cylinder (open surface, soup API and typed arrays), and unions of
// two overlapping UV spheres of 50k and 200k triangles in all (closed). Each time is the
// median of N runs (the reference: one run; its 200k case only with --slow) and includes
// the conversions in and out of each library's own mesh type.
import { readFileSync, statSync } from "node:fs";
import { gzipSync } from "node:zlib";
import { performance } from "node:perf_hooks";
import * as mb from "../src/index.js";

const args = process.argv.slice(2);
const reps = Number(args[args.indexOf("--reps") + 1]) || 11;
const slow = args.includes("--slow");
const data = (name) => new URL(`../../data/${name}`, import.meta.url);

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

/** A welded UV sphere: `slices * (stacks - 1) * 2` triangles. */
function sphere(cx, cy, cz, r, slices, stacks) {
	const pos = [cx, cy, cz + r];
	for (let i = 1; i < stacks; i++) {
		const th = (Math.PI * i) / stacks;
		for (let j = 0; j < slices; j++) {
			const ph = (2 * Math.PI * j) / slices;
			pos.push(cx + r * Math.sin(th) * Math.cos(ph), cy + r * Math.sin(th) * Math.sin(ph), cz + r * Math.cos(th));
		}
	}
	pos.push(cx, cy, cz - r);
	const south = pos.length / 3 - 1, ring = (i, j) => 1 + (i - 1) * slices + (j % slices);
	const idx = [];
	for (let j = 0; j < slices; j++) idx.push(0, ring(1, j), ring(1, j + 1));
	for (let i = 1; i < stacks - 1; i++) {
		for (let j = 0; j < slices; j++) {
			idx.push(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
		}
	}
	for (let j = 0; j < slices; j++) idx.push(south, ring(stacks - 1, j + 1), ring(stacks - 1, j));
	return { positions: Float64Array.from(pos), index: Uint32Array.from(idx) };
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

// Kirra terrain − cylinder
const terrain = mb.readMesh(readFileSync(data("kirra_terrain.obj")), "obj");
const cylinder = mb.readMesh(readFileSync(data("kirra_cylinder.obj")), "obj");
const tSoup = mb.typedToSoup(terrain), cSoup = mb.typedToSoup(cylinder);
{
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
	const a = sphere(0, 0, 0, 1, slices, stacks), b = sphere(0.3, 0.2, 0.1, 1, slices, stacks);
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
