// The package's API against geometry: volumes and volume identities, exact triangle and
// edge counts, the Kirra terrain cases against the CLI's numbers, the typed-array path
// against the soup path, and bad input. Run: node --test test/
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import * as mb from "../src/index.js";
import { call } from "../src/native.js";
import { missing as noKirra, sharedData } from "./shared-data.mjs";

function cube(cx, cy, cz, size) {
	const h = size / 2;
	const v = [
		[cx - h, cy - h, cz - h], [cx + h, cy - h, cz - h], [cx + h, cy + h, cz - h], [cx - h, cy + h, cz - h],
		[cx - h, cy - h, cz + h], [cx + h, cy - h, cz + h], [cx + h, cy + h, cz + h], [cx - h, cy + h, cz + h],
	];
	const f = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]];
	const p = (i) => ({ x: v[i][0], y: v[i][1], z: v[i][2] });
	return f.map(([a, b, c]) => ({ v0: p(a), v1: p(b), v2: p(c) }));
}

/** A flat square grid patch at height z facing up. */
function patch(cx, cy, z, size, n) {
	const out = [];
	const s = size / n, x0 = cx - size / 2, y0 = cy - size / 2;
	for (let i = 0; i < n; i++) for (let j = 0; j < n; j++) {
		const a = { x: x0 + i * s, y: y0 + j * s, z }, b = { x: x0 + (i + 1) * s, y: y0 + j * s, z };
		const c = { x: x0 + (i + 1) * s, y: y0 + (j + 1) * s, z }, d = { x: x0 + i * s, y: y0 + (j + 1) * s, z };
		out.push({ v0: a, v1: b, v2: c }, { v0: a, v1: c, v2: d });
	}
	return out;
}

const vol = (r) => mb.computeSignedVolume(r.soup);
const closed = (soup) => {
	const c = mb.countOpenEdges(soup);
	return c.openEdges === 0 && c.overShared === 0;
};

test("booleans of overlapping cubes: exact volumes, closed, and the volume identity", () => {
	const a = cube(0, 0, 0, 2), b = cube(0.5, 0.25, 0.125, 2);
	const u = mb.boolean(a, b, "union"), i = mb.boolean(a, b, "intersect");
	const d = mb.boolean(a, b, "subtract"), r = mb.boolean(a, b, "reverse-difference");
	const inter = 1.5 * 1.75 * 1.875;
	assert.equal(vol(i), inter);
	assert.equal(vol(d), 8 - inter);
	assert.equal(vol(r), 8 - inter);
	assert.equal(vol(u) + vol(i), 16);
	for (const res of [u, i, d, r]) {
		assert.ok(closed(res.soup));
		assert.equal(res.triangles.length, res.soup.length);
		assert.equal(res.report.closed, true);
	}
	// points and triangles describe the same mesh as the soup
	assert.equal(mb.computeSignedVolume(mb.weldedToSoup(u.triangles)), vol(u));
	assert.ok(u.points.length < 3 * u.soup.length);
});

/** An axis-aligned box from `lo` to `hi`, facing outward. */
function box(lo, hi) {
	const c = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
	const h = [(hi[0] - lo[0]) / 2, (hi[1] - lo[1]) / 2, (hi[2] - lo[2]) / 2];
	const at = (p) => ({ x: c[0] + h[0] * p.x, y: c[1] + h[1] * p.y, z: c[2] + h[2] * p.z });
	return cube(0, 0, 0, 2).map((t) => ({ v0: at(t.v0), v1: at(t.v1), v2: at(t.v2) }));
}

test("snap: a cutter drawn a little larger leaves no needles, closed, volume within D × area", () => {
	// The unit cube minus a box over its corner x > 0.5, z > 0.5 whose other walls lie 1e-3
	// outside the cube: the exact difference has edges and altitudes of about 1e-3.
	const a = box([0, 0, 0], [1, 1, 1]), b = box([0.5, -0.001, 0.5], [1.001, 1.001, 1.001]);
	const worst = (soup) => {
		let edge = Infinity, height = Infinity;
		for (const t of soup) {
			const p = [t.v0, t.v1, t.v2].map((q) => [q.x, q.y, q.z]);
			const sub = (u, v) => [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
			const len = (v) => Math.hypot(v[0], v[1], v[2]);
			const l = [0, 1, 2].map((k) => len(sub(p[(k + 1) % 3], p[k])));
			const [u, v] = [sub(p[1], p[0]), sub(p[2], p[0])];
			const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
			edge = Math.min(edge, ...l);
			height = Math.min(height, len(n) / Math.max(...l));
		}
		return Math.min(edge, height);
	};
	// (on the arrangement as it is: by default the exact clean-up takes these needles)
	const exact = mb.boolean(a, b, "subtract", { keepSeamPoints: true });
	assert.equal(exact.report.snap, undefined);
	assert.ok(worst(exact.soup) < 1e-3);
	const D = 0.01;
	const snapped = mb.boolean(a, b, "subtract", { snap: D, keepSeamPoints: true });
	assert.ok(closed(snapped.soup));
	assert.ok(worst(snapped.soup) >= D);
	assert.ok(Math.abs(vol(snapped) - vol(exact)) <= D * mb.compute3DSurfaceArea(exact.soup));
	const s = snapped.report.snap;
	assert.equal(s.tolerance, D);
	assert.equal(s.left, 0);
	assert.ok(s.collapsed > 0 && s.max_move <= D);
	const t = mb.booleanIndexed(mb.soupToTyped(a), mb.soupToTyped(b), "subtract", { snap: D, keepSeamPoints: true });
	assert.equal(t.index.length, 3 * snapped.soup.length);
	assert.equal(t.source.length, snapped.soup.length);
	assert.throws(() => mb.boolean(a, b, "union", { snap: -1 }), /snap must be a distance/);
	// A split snapped: its groups together, the difference picked from them closed.
	const sp = mb.splitIndexed(mb.soupToTyped(a), mb.soupToTyped(b), { snap: D });
	assert.equal(sp.report.snap.left, 0);
	assert.ok(sp.report.snap.collapsed > 0);
	assert.equal(mb.splitIndexed(mb.soupToTyped(a), mb.soupToTyped(b)).report.snap, undefined);
	const g = sp.groups;
	assert.ok(g.a_in_b.index.length < mb.splitIndexed(mb.soupToTyped(a), mb.soupToTyped(b)).groups.a_in_b.index.length);
	for (const name of ["a_in_b", "a_out_b", "b_in_a", "b_out_a"]) {
		assert.equal(g[name].source.length * 3, g[name].index.length, name);
	}
});

test("identical and touching meshes", () => {
	const a = cube(0, 0, 0, 2);
	assert.equal(vol(mb.boolean(a, a, "union")), 8);
	assert.equal(vol(mb.boolean(a, a, "intersect")), 8);
	assert.equal(mb.boolean(a, a, "subtract"), null);
	const b = cube(2, 0, 0, 2); // shares the face x = 1
	const u = mb.boolean(a, b, "union");
	assert.equal(vol(u), 16);
	assert.ok(closed(u.soup));
	assert.equal(mb.boolean(a, b, "intersect"), null);
	assert.equal(vol(mb.boolean(a, b, "subtract")), 8);
	// disjoint: union keeps both, intersection is empty, difference is A
	const far = cube(10, 10, 10, 1);
	assert.equal(vol(mb.boolean(a, far, "union")), 9);
	assert.equal(mb.boolean(a, far, "intersect"), null);
	assert.equal(vol(mb.boolean(a, far, "subtract")), 8);
	// nested: the difference is a shell
	const inner = cube(0, 0, 0, 1);
	const shell = mb.boolean(a, inner, "subtract");
	assert.equal(vol(shell), 7);
	assert.equal(mb.findConnectedComponents(shell.soup).length, 2);
});

test("split, merge, select and components give the booleans", () => {
	const a = cube(0, 0, 0, 2), b = cube(1, 0, 0, 2); // coplanar faces at y, z = ±1
	const s = mb.splitMeshPair(a, b);
	assert.ok(s.segments.length > 0);
	for (const seg of s.segments) {
		assert.ok(Number.isInteger(seg.idxA) && seg.idxA < a.length);
		assert.ok(Number.isInteger(seg.idxB) && seg.idxB < b.length);
	}
	const g = s.groups;
	// Every group lies wholly on its side: centroids inside or outside the other cube.
	const inside = (t, cx) => {
		const c = { x: (t.v0.x + t.v1.x + t.v2.x) / 3, y: (t.v0.y + t.v1.y + t.v2.y) / 3, z: (t.v0.z + t.v1.z + t.v2.z) / 3 };
		return c.x >= cx - 1 && c.x <= cx + 1;
	};
	assert.ok(g.aOutside.every((t) => !inside(t, 1)));
	assert.ok(g.bOutside.filter((t) => !inside(t, 0)).length > 0);
	for (const op of ["union", "intersect", "subtract"]) {
		// (the split keeps every seam point: compare with the boolean that keeps them too)
		const m = mb.mergeSplitGroups(g, op), d = mb.boolean(a, b, op, { keepSeamPoints: true });
		assert.ok(mb.boolean(a, b, op, { keepSeamPoints: false }).soup.length <= d.soup.length, op);
		assert.equal(vol(m), vol(d), op);
		assert.equal(m.soup.length, d.soup.length, op);
		assert.ok(closed(m.soup), op);
	}
	assert.equal(vol(mb.selectSplits(g, { aOutside: true, bInside: "flip" })), 4);
	assert.equal(mb.selectSplits(g, {}), null);
	const comps = mb.splitToComponents(g);
	assert.deepEqual(comps.map((c) => c.mesh + c.side), ["Ainside", "Aoutside", "Binside", "Boutside"]);
	assert.equal(comps.reduce((n, c) => n + c.triCount, 0), g.aInside.length + g.aOutside.length + g.bInside.length + g.bOutside.length);
	const picked = mb.mergeComponents([{ soup: comps[1].soup }, { soup: comps[2].soup, flip: true }]);
	assert.equal(vol(picked), 4);
	assert.equal(mb.mergeSmallComponents(comps, 0).length, 4);
	assert.equal(mb.splitMeshPair(null, b), null);
	const bms = mb.bmsBooleanOp(a, b, "union");
	assert.equal(vol(bms.result), 12);
	assert.ok(bms.polylines.length >= 1 && bms.megaSoup.length > 0);
	assert.ok(bms.megaSoup.every((t) => (t.mesh === "A" ? t.origIdx < a.length : t.origIdx < b.length)));
});

test("reclassify functions move triangles between sides", () => {
	const s = mb.splitMeshPair(cube(0, 0, 0, 2), cube(1, 0.5, 0.25, 2));
	const g = s.groups;
	const n = g.aInside.length;
	assert.equal(mb.reclassifyTriangles(g, "A", "inside", [0]), 1);
	assert.equal(g.aInside.length, n - 1);
	const t = g.aOutside[g.aOutside.length - 1];
	const c = { x: (t.v0.x + t.v1.x + t.v2.x) / 3, y: (t.v0.y + t.v1.y + t.v2.y) / 3, z: (t.v0.z + t.v1.z + t.v2.z) / 3 };
	assert.deepEqual(mb.reclassifyAtPoint(g, c.x, c.y, c.z, 1e-9), { moved: true, mesh: "A", from: "outside", to: "inside" });
	const before = g.bInside.length;
	const moved = mb.reclassifyRegion(g, "B", "inside", 0);
	assert.equal(moved, before);
	assert.equal(g.bInside.length, 0);
});

test("Kirra terrain − cylinder and terrain ∩ cup equal the CLI's numbers", { skip: noKirra }, () => {
	const read = (name) => mb.readMesh(sharedData(name), name);
	const terrain = read("kirra_terrain.obj"), cyl = read("kirra_cylinder.obj"), cup = read("kirra_cup.obj");
	assert.equal(terrain.format, "obj");
	// meshbool difference ../shared/data/kirra_terrain.obj ../shared/data/kirra_cylinder.obj -o out.ply --json
	// (with --keep-seam-points: the package keeps every seam point by default)
	const d = mb.booleanIndexed(terrain, cyl, "subtract");
	assert.equal(d.index.length / 3, 10846);
	assert.equal(d.report.cleanup.removed_points, 0);
	// the CLI's default: 16 seam points where the hole's rim is straight go
	const clean = mb.booleanIndexed(terrain, cyl, "subtract", { keepSeamPoints: false });
	assert.equal(clean.index.length / 3, 10814);
	assert.equal(clean.report.cleanup.removed_points, 16);
	assert.equal(clean.report.volume, 179953.76307633775);
	assert.equal(d.report.volume, 179953.76307633775);
	assert.equal(d.report.area, 36079.86143207988);
	assert.equal(d.report.boundary_edges, 560);
	assert.ok(d.report.assumed[0].includes("46 inconsistently oriented edges"));
	// meshbool intersection ../shared/data/kirra_terrain.obj ../shared/data/kirra_cup.obj -o out.ply --json
	const i = mb.booleanIndexed(terrain, cup, "intersect");
	assert.equal(i.index.length / 3, 846);
	assert.equal(i.report.volume, 33457.89820801892);
	assert.equal(i.report.closed, true);
	// the soup path gives the same mesh
	const soup = mb.boolean(mb.typedToSoup(terrain), mb.typedToSoup(cup), "intersect");
	assert.equal(soup.soup.length, 846);
	assert.equal(mb.computeSignedVolume(soup.soup), i.report.volume);
	const s = mb.splitIndexed(terrain, cyl);
	assert.ok(s.groups.a_in_b.index.length > 0 && s.groups.b_in_a.index.length > 0);
});

/** The z of each triangle's normal (twice its area projected on xy). */
function normalZ(m, t) {
	const [a, b, c] = [0, 1, 2].map((k) => 3 * m.index[3 * t + k]);
	const p = m.positions;
	return (p[b] - p[a]) * (p[c + 1] - p[a + 1]) - (p[b + 1] - p[a + 1]) * (p[c] - p[a]);
}

test("generated primitives: the library's counts, exact volumes and meshbool make's defaults", () => {
	const box = mb.makeCube();
	assert.deepEqual([box.index.length / 3, box.positions.length / 3, box.report.volume, box.report.closed], [12, 8, 1, true]);
	assert.deepEqual(box.report.bbox, { min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5] });
	assert.equal(box.report.shape, "cube");
	const slab = mb.makeCube({ center: [1, 2, 3], size: [1, 2, 4] });
	assert.deepEqual([slab.report.volume, slab.report.bbox.min], [8, [0.5, 1, 1]]);
	assert.equal(mb.makeCube({ min: [0, 0, 0], max: [1, 1, 2] }).report.volume, 2);
	// The default sphere: 32 meridians, 16 bands, the inscribed polyhedron of radius 1.
	const ball = mb.makeSphere();
	assert.deepEqual([ball.index.length / 3, ball.positions.length / 3, ball.report.closed], [960, 482, true]);
	assert.equal(ball.report.volume, 4.1219417407858465);
	assert.ok(ball.report.volume < (4 / 3) * Math.PI);
	assert.equal(mb.makeSphere({ segments: 4, rings: 2 }).report.volume, 4 / 3); // an octahedron, vertices on the axes
	// Quarter turns are exact: a 4-sided cylinder is a square prism, a 4-sided cone a pyramid.
	const prism = mb.makeCylinder({ height: 3, segments: 4 });
	assert.deepEqual([prism.index.length / 3, prism.report.volume], [16, 6]);
	assert.equal(mb.makeCylinder().index.length / 3, 128);
	assert.equal(mb.makeCone({ height: 3, segments: 4 }).report.volume, 2);
	assert.equal(mb.makeCone({ topRadius: 0.5, segments: 8 }).index.length / 3, 32);
	// The CSG documents' spelling too, the same cone; null is left out.
	assert.deepEqual(mb.makeCone({ top_radius: 0.5, segments: 8 }).positions, mb.makeCone({ topRadius: 0.5, segments: 8 }).positions);
	assert.equal(mb.makeCone({ radius: null, height: 3, segments: 4 }).report.volume, 2);
	const sheet = mb.makePlane({ center: [1, 1, 2], width: 4, depth: 2, nx: 4, ny: 2 });
	assert.deepEqual([sheet.index.length / 3, sheet.positions.length / 3, sheet.report.boundary_edges, sheet.report.closed], [16, 15, 12, false]);
	for (let t = 0; t < 16; t++) assert.ok(normalZ(sheet, t) > 0, `triangle ${t} faces down`);
	// Bad options say what is wrong; a misspelt one is not silently the default.
	assert.throws(() => mb.makeSphere({ radus: 2 }), /no option "radus" \(its options: center, radius, segments, rings\)/);
	assert.throws(() => mb.makeSphere({ radius: NaN }), /radius must be finite/);
	assert.throws(() => mb.makeSphere({ segments: 2.5 }), /segments must be a whole number/);
	assert.throws(() => mb.makeSphere({ segments: 2 }), /segments must be at least 3/);
	assert.throws(() => mb.makeCylinder({ base: [0, 0] }), /base must be an array of 3 numbers/);
	assert.throws(() => mb.makeCube({ size: 1, min: [0, 0, 0], max: [1, 1, 1] }), /not both/);
	assert.throws(() => mb.makeCube({ min: [0, 0, 0], max: [1, 0, 1] }), /min must be below its max/);
	assert.throws(() => mb.makePlane([1, 2]), /options must be an object/);
});

test("a generated terrain: an open grid facing up, one boundary loop, its relief's range, the same for the same seed", () => {
	const t = mb.makeTerrain();
	const info = mb.meshInfo(t);
	assert.deepEqual(
		[info.triangles, info.vertices, info.boundary_edges, info.non_manifold_edges, info.inconsistent_edges, info.degenerate_triangles, info.components, info.closed],
		[20000, 10201, 400, 0, 0, 0, 1, false],
	);
	assert.deepEqual(info.bbox, { min: [-500, -500, -20], max: [500, 500, 20] });
	assert.equal(info.projected_area.xy, 1e6);
	const rim = mb.extractBoundaryLoops(mb.typedToSoup(t));
	assert.deepEqual([rim.loops.length, rim.loops[0].length], [1, 400]);
	for (let k = 0; k < 20000; k++) assert.ok(normalZ(t, k) > 0, `triangle ${k} faces down`);
	// Deterministic by seed: bit-identical again, every height different for another seed.
	assert.deepEqual(mb.makeTerrain({ seed: 1 }).positions, t.positions);
	const other = mb.makeTerrain({ seed: 2 });
	assert.deepEqual(other.index, t.index);
	let moved = 0;
	for (let k = 2; k < t.positions.length; k += 3) if (other.positions[k] !== t.positions[k]) moved++;
	assert.equal(moved, 10201);
	assert.deepEqual(mb.meshInfo(other).bbox, info.bbox);
	// Placed, sized and sampled as asked; relief 0 is flat.
	const small = mb.makeTerrain({ center: [478600, 6772300, 400], size: [300, 200], cells: [6, 4], relief: 10, seed: 7 });
	assert.deepEqual([small.index.length / 3, small.report.boundary_edges], [48, 20]);
	assert.deepEqual(small.report.bbox, { min: [478450, 6772200, 395], max: [478750, 6772400, 405] });
	assert.equal(mb.makeTerrain({ cells: 4, relief: 0 }).report.volume, 0);
	assert.throws(() => mb.makeTerrain({ cells: [4, 0] }), /cells along y must be at least 1/);
	assert.throws(() => mb.makeTerrain({ relief: -1 }), /relief must be 0 or positive/);
});

test("a generated pit: an open benched shell facing up, its rim one loop, crossing the terrain", () => {
	const p = mb.makePit();
	const info = mb.meshInfo(p);
	// 5 benches with berms: 10 rings of 64, 64 · (4 · 5 − 1) triangles, the rim open.
	assert.deepEqual(
		[info.triangles, info.vertices, info.boundary_edges, info.non_manifold_edges, info.inconsistent_edges, info.components, info.closed],
		[1216, 641, 64, 0, 0, 1, false],
	);
	assert.deepEqual(info.bbox, { min: [-220, -160, -80], max: [220, 160, 60] });
	for (let k = 0; k < 1216; k++) assert.ok(normalZ(p, k) > 0, `triangle ${k} faces down`);
	const rim = mb.extractBoundaryLoops(mb.typedToSoup(p)).loops;
	assert.deepEqual([rim.length, rim[0].length, rim[0].every((v) => v.z === 60)], [1, 64, true]);
	assert.equal(mb.makePit({ berm: 0, benches: 3, segments: 16 }).index.length / 3, 16 * 7);
	assert.throws(() => mb.makePit({ radius: 60 }), /faces and berms reach 102 in from the rim .* radius 60/);
	// The default pit crosses the default terrain in one closed curve, its rim above the
	// ground all round and its floor below.
	const t = mb.makeTerrain();
	const c = mb.curvesIndexed(t, p);
	assert.deepEqual([c.polylines.length, c.closed[0], c.polylines[0].length / 3], [1, true, 314]);
	const s = mb.splitIndexed(t, p);
	const counts = Object.fromEntries(["a_in_b", "a_out_b", "b_in_a", "b_out_a"].map((g) => [g, s.groups[g].index.length / 3]));
	assert.deepEqual(counts, { a_in_b: 19166, a_out_b: 1462, b_in_a: 954, b_out_a: 890 });
	// terrain ∩ pit: the ground after mining, one open sheet over the whole plan whose
	// only boundary is the terrain's.
	const after = mb.meshInfo(mb.booleanIndexed(t, p, "intersect"));
	assert.deepEqual([after.triangles, after.boundary_edges, after.non_manifold_edges, after.inconsistent_edges, after.components], [19166 + 954, 400, 0, 0, 1]);
	assert.equal(after.projected_area.xy, 1e6);
	// terrain − pit: the closed solid mined out, its volume the cut of the pit design
	// against the terrain (cut and fill, computed another way).
	const mined = mb.booleanIndexed(t, p, "subtract");
	assert.deepEqual([mined.report.triangles, mined.report.closed, mined.report.boundary_edges], [1462 + 954, true, 0]);
	assert.equal(mined.report.volume, 2389263.205998871);
	const cf = mb.cutFill(p, t);
	assert.ok(Math.abs(cf.cut - mined.report.volume) < 1e-9 * mined.report.volume, `${cf.cut} vs ${mined.report.volume}`);
});

test("readFormats lists what readMesh reads: each round-trips, the mining formats' errors list only these", () => {
	const formats = mb.readFormats();
	const names = formats.map((f) => f.name);
	assert.deepEqual(names, ["stl", "stl-ascii", "obj", "ply", "ply-ascii", "ply-be", "dxf", "json", "kirra-json", "glb", "off"]);
	assert.deepEqual([...new Set(formats.map((f) => f.extension))], ["stl", "obj", "ply", "dxf", "json", "glb", "off"]);
	assert.equal(formats.find((f) => f.name === "glb").label, "binary glTF");
	const box = mb.makeCube();
	for (const f of formats) {
		const bytes = mb.writeMesh(box, f.name);
		for (const hint of [f.name, `box.${f.extension}`, ""]) {
			const back = mb.readMesh(bytes, hint);
			assert.equal(back.index.length / 3, 12, `${f.name} read with ${JSON.stringify(hint)}`);
			assert.equal(mb.meshInfo(back).volume, 1);
		}
	}
	// The list is a copy: changing it changes nothing.
	formats[0].name = "changed";
	assert.equal(mb.readFormats()[0].name, "stl");
	const listed = " .stl .obj .ply .dxf .json .glb .off files";
	const text = (t) => new TextEncoder().encode(t);
	assert.throws(() => mb.readMesh(text("GOCAD TSurf 1\nTFACE\nEND\n"), "pit.ts"), (e) => e.message === `GOCAD TSurf files are not read by this build of meshbool; it reads${listed}`);
	assert.throws(() => mb.readMesh(text("<LandXML/>"), "surface.xml"), /LandXML files are not read by this build of meshbool; it reads \.stl/);
	assert.throws(() => mb.readMesh(text("hello"), "notes.txt"), (e) => e.message === `cannot tell the file's format from its contents; this build reads${listed}`);
	assert.throws(() => mb.readMesh(text("hello"), "gocad"), (e) => e.message === `unknown format "gocad": this build reads ${names.join(", ")}`);
});

test("typed-array path equals the soup path", () => {
	const a = cube(0, 0, 0, 2), b = cube(0.5, 0.5, 0.5, 2);
	const ta = mb.soupToTyped(a), tb = mb.soupToTyped(b);
	assert.equal(ta.positions.length, 24);
	assert.equal(ta.index.length, 36);
	for (const op of ["union", "intersect", "subtract"]) {
		const t = mb.booleanIndexed(ta, tb, op), s = mb.boolean(a, b, op);
		assert.deepEqual(mb.typedToSoup(t), s.soup, op);
		assert.equal(t.source.length, t.index.length / 3);
		assert.equal(t.triangle.length, t.index.length / 3);
	}
	const d = mb.booleanIndexed(ta, tb, "subtract");
	assert.ok(Array.from(d.flipped).some((f, k) => f === 1 && d.source[k] === 1));
	const bytes = mb.writeMesh(ta, "ply");
	const back = mb.readMesh(bytes);
	assert.equal(back.format, "ply");
	assert.deepEqual(Array.from(back.positions), Array.from(ta.positions));
	assert.deepEqual(Array.from(back.index), Array.from(ta.index));
	const info = mb.meshInfo(ta);
	assert.equal(info.volume, 8);
	assert.equal(info.closed, true);
	assert.equal(info.boundary_edges, 0);
});

test("intersection curves and segments", () => {
	const a = cube(0, 0, 0, 2), b = cube(0.5, 0.5, 0.5, 2);
	const segs = mb.intersectMeshPairTagged(a, b);
	assert.ok(segs.length > 0);
	assert.equal(mb.intersectMeshPair(a, b).length, segs.length);
	const lines = mb.chainSegments(segs, 0);
	assert.equal(lines.length, 1); // one closed loop
	const loop = lines[0];
	assert.deepEqual(loop[0], loop[loop.length - 1]);
	const c = mb.curvesIndexed(mb.soupToTyped(a), mb.soupToTyped(b));
	assert.equal(c.polylines.length, 1);
	assert.equal(c.closed[0], true);
	// the loop's length: three unit... the seam of two offset cubes is 6 edges of length 1.5
	assert.equal(c.report.total_length, 9);
	const t = mb.triTriIntersectionDetailed(a[0], b[4]);
	assert.equal(t, null);
	const crossing = mb.triTriIntersection(
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 2, y: 0, z: 0 }, v2: { x: 0, y: 2, z: 0 } },
		{ v0: { x: 0.5, y: 0.5, z: -1 }, v1: { x: 0.5, y: 0.5, z: 1 }, v2: { x: 3, y: 0.5, z: 0 } },
	);
	assert.ok(crossing);
	assert.equal(crossing.p0.y, 0.5);
	assert.equal(mb.simplifyPolyline(loop, 100).length, 2);
});

test("repair functions", async () => {
	const a = cube(0, 0, 0, 2);
	const open = a.slice(2); // bottom face removed: one square hole
	const loops = mb.extractBoundaryLoops(open);
	assert.equal(loops.loops.length, 1);
	assert.equal(loops.boundaryEdgeCount, 4);
	const capped = mb.capBoundaryLoops(open);
	assert.equal(capped.length, 12);
	assert.equal(mb.computeSignedVolume(capped), 8);
	assert.equal(mb.fillOpenEdgeLoops(open).length, 12);
	assert.equal(mb.triangulateLoop(loops.loops[0]).length, 2);
	const closedRes = mb.closeSolid(open);
	assert.equal(closedRes.diagnostics.closed, true);
	assert.equal(closedRes.diagnostics.volume, 8);
	const fc = mb.forceCloseIndexedMesh([], mb.weldVertices(open, 1e-9).triangles);
	assert.equal(fc.triangles.length, 12);
	// a terrain patch closed by a curtain to a floor 10 below: walls + floor added
	const p = patch(0, 0, 5, 4, 4);
	const added = mb.buildCurtainAndCap(p, 10);
	const solid = p.concat(added);
	assert.ok(closed(solid));
	assert.equal(mb.computeSignedVolume(solid), 4 * 4 * 10);
	// duplicates: an exact copy removed, an anti-parallel pair cancels
	assert.equal(mb.cleanCrossingTriangles(a.concat([a[0]])).length, 12);
	assert.equal(mb.removeOverlappingTriangles(a.concat(mb.flipAllNormals([a[0]]))).length, 11);
	// weld: vertices within the tolerance merged
	const shifted = a.map((t) => ({ v0: t.v0, v1: t.v1, v2: { x: t.v2.x + 1e-7, y: t.v2.y, z: t.v2.z } }));
	assert.ok(mb.countOpenEdges(shifted).openEdges > 0);
	assert.ok(closed(mb.deduplicateSeamVertices(shifted, 1e-5)));
	const w = mb.weldVertices(shifted, 1e-5);
	assert.equal(w.points.length, 8);
	assert.equal(mb.weldVertices(a, 0).points.length, 36);
	// T-junction: a vertex on an edge of the neighbour gets the edge split
	const tj = [
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 2, y: 0, z: 0 }, v2: { x: 1, y: 1, z: 0 } },
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 1, y: -1, z: 0 }, v2: { x: 1, y: 0, z: 0 } },
		{ v0: { x: 1, y: 0, z: 0 }, v1: { x: 1, y: -1, z: 0 }, v2: { x: 2, y: 0, z: 0 } },
	];
	assert.equal(mb.countOpenEdges(tj).openEdges, 7);
	const fixed = mb.resolveTJunctions(tj);
	assert.equal(fixed.length, 4);
	assert.equal(mb.countOpenEdges(fixed).openEdges, 4);
	// degenerate: a zero-area triangle removed
	const degenerate = { v0: { x: 0, y: 0, z: 0 }, v1: { x: 1, y: 0, z: 0 }, v2: { x: 2, y: 0, z: 0 } };
	assert.deepEqual(mb.removeDegenerateTriangles([degenerate, ...cube(5, 5, 5, 2)], 0, 0).length, 12);
	const cleaned = mb.removeDegenerateTriangles([...tj, degenerate], 0, 0);
	assert.ok(cleaned.every((t) => mb.triangleArea3D(t) > 0));
	assert.equal(mb.compute3DSurfaceArea(cleaned), mb.compute3DSurfaceArea(tj));
	// the async pipeline
	let calls = 0;
	const r = await mb.repairMesh(shifted, { closeMode: "weld", snapTolerance: 1e-5 }, () => calls++);
	assert.ok(closed(r.soup));
	// welded within 1e-5: each vertex lands on the first of its cluster (moved at most 1e-7)
	assert.ok(Math.abs(mb.computeSignedVolume(r.soup) - 8) < 1e-6);
	assert.ok(calls >= 2);
	const st = await mb.repairMesh(open, { closeMode: "stitch" });
	assert.ok(closed(st.soup));
	// orientation
	const messy = a.map((t, k) => (k % 3 === 0 ? mb.flipAllNormals([t])[0] : t));
	const o = mb.orientSolid(messy);
	assert.equal(mb.computeSignedVolume(o.soup), 8);
	const inward = mb.orientSolid(mb.flipAllNormals(a));
	assert.equal(mb.computeSignedVolume(inward.soup), 8);
	const stitchAdded = mb.stitchByProximity(open, 1);
	assert.ok(Array.isArray(stitchAdded));
});

test("self-overlapping input resolved", () => {
	// (cubes sharing coplanar faces: the even-odd self-arrangement fails there, issue 14)
	const two = cube(0, 0, 0, 2).concat(cube(0.5, 0.25, 0.125, 2));
	const inter = 1.5 * 1.75 * 1.875;
	assert.equal(mb.computeSignedVolume(two), 16);
	const r = mb.bmsSelfResolve(two);
	assert.equal(r.changed, true);
	assert.equal(mb.computeSignedVolume(r.soup), 16 - inter);
	assert.ok(closed(r.soup));
	const e = mb.bmsSelfResolveIndexed(mb.soupToTyped(two), { rule: "evenodd" });
	assert.equal(mb.meshInfo(e).volume, 16 - 2 * inter);
	// two solids touching along the seam: closed and manifold with the seam's vertices
	// doubled (an exact weld joins them again: 14 edges of four triangles)
	assert.equal(e.diagnostics.closed, true);
	assert.equal(e.diagnostics.non_manifold_edges, 0);
	assert.equal(mb.meshInfo(e).non_manifold_edges, 14);
});

test("measures, normals and utilities", () => {
	const a = cube(0, 0, 0, 2);
	assert.equal(mb.computeSignedVolume(a), 8);
	assert.equal(mb.compute3DSurfaceArea(a), 24);
	assert.equal(mb.computeProjectedArea(a, "xy"), 4);
	assert.equal(mb.computeProjectedArea(patch(0, 0, 1, 2, 2), "yz"), 0);
	assert.deepEqual(mb.triNormal(patch(0, 0, 0, 1, 1)[0]), { x: 0, y: 0, z: 1 });
	assert.equal(mb.classifyNormalDirection(a, true, 8), "Out");
	assert.equal(mb.classifyNormalDirection(patch(0, 0, 0, 1, 2), false), "Z+");
	assert.equal(mb.classifyNormalDirection([], false), "N/A");
	const down = mb.flipAllNormals(patch(0, 0, 0, 1, 2));
	assert.ok(mb.ensureZUpNormals(down).every((t) => mb.triNormal(t).z > 0));
	assert.equal(mb.windingNumber({ x: 0.1, y: 0.2, z: 0.3 }, a).toFixed(12), "1.000000000000");
	assert.equal(Math.abs(mb.windingNumber({ x: 5, y: 0, z: 0 }, a)) < 1e-12, true);
	const t = mb.soupToTyped(a);
	assert.ok(Math.abs(mb.windingNumberIndexed(0, 0, 0, t.positions, t.index) - 1) < 1e-12);
	assert.equal(mb.classifyPointMultiAxis({ x: 0.3, y: 0.2, z: -0.5 }, a), 1);
	assert.equal(mb.classifyPointMultiAxis({ x: 3, y: 0.2, z: -0.5 }, a), -1);
	assert.equal(mb.dist3({ x: 0, y: 0, z: 0 }, { x: 3, y: 4, z: 0 }), 5);
	assert.equal(mb.triangleArea3D(patch(0, 0, 0, 2, 1)[0]), 2);
	assert.deepEqual(mb.computeBounds([{ x: 1, y: 2, z: 3 }]), { minX: 1, maxX: 1, minY: 2, maxY: 2, minZ: 3, maxZ: 3 });
	assert.deepEqual(mb.lerpVert({ x: 0, y: 0, z: 0 }, { x: 2, y: 2, z: 2 }, 0.5), { x: 1, y: 1, z: 1 });
	assert.equal(mb.vKey({ x: 1, y: 2, z: 3 }), "1.000000,2.000000,3.000000");
	assert.equal(mb.edgeKey("b", "a"), "a|b");
	assert.deepEqual(mb.countOpenEdges(a), { openEdges: 0, overShared: 0, total: 18 });
	const two = a.concat(cube(10, 0, 0, 1), cube(20, 0, 0, 1).slice(0, 4));
	assert.deepEqual(mb.findConnectedComponents(two).map((c) => c.length), [12, 12, 2, 2]);
	assert.equal(mb.findConnectedComponentsPooled(two).length, 4);
	const grid = mb.buildSpatialGrid(a, 1);
	assert.ok(mb.queryGrid(grid, mb.triBBox(a[0]), 1).includes(0));
	assert.ok(mb.bboxOverlap(mb.computeBBox(a), mb.triBBox(a[5])));
	assert.equal(mb.estimateAvgEdge(patch(0, 0, 0, 1, 1)), (2 + Math.SQRT2) / 3);
	assert.match(mb.version, /^\d+\.\d+\.\d+/);
});

test("bad input throws an Error that says what is wrong", () => {
	const a = cube(0, 0, 0, 2);
	const nan = [{ v0: { x: NaN, y: 0, z: 0 }, v1: { x: 1, y: 0, z: 0 }, v2: { x: 0, y: 1, z: 0 } }];
	assert.throws(() => mb.boolean(nan, a, "union"), /non-finite/);
	assert.throws(() => mb.boolean([{ v0: { x: Infinity, y: 0, z: 0 }, v1: { x: 1, y: 0, z: 0 }, v2: { x: 0, y: 1, z: 0 } }], a, "union"), /non-finite/);
	assert.throws(() => mb.boolean([], a, "union"), /no triangles/);
	assert.throws(() => mb.boolean(a, [], "union"), /no triangles/);
	assert.throws(() => mb.boolean([{ v0: { x: 0, y: 0 } }], a, "union"), /soupA\[0\]\.v0 is not a vertex/);
	assert.throws(() => mb.boolean(a, [[0, 0, 0]], "union"), /soupB\[0\]\.v0 is not a vertex/);
	assert.throws(() => mb.boolean({ length: 3 }, a, "union"), /must be an array/);
	assert.throws(() => mb.boolean(a, a, "xor"), /unknown operation/);
	assert.throws(() => mb.booleanIndexed({ positions: new Float64Array(4), index: new Uint32Array(3) }, mb.soupToTyped(a), "union"), /three numbers per vertex/);
	assert.throws(() => mb.booleanIndexed({ positions: new Float64Array(9), index: new Uint32Array([0, 1, 7]) }, mb.soupToTyped(a), "union"), /index|range|vertex/i);
	assert.throws(() => mb.readMesh(new TextEncoder().encode("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0")), Error);
	assert.throws(() => mb.readMesh(new Uint8Array([1, 2, 3])), Error);
	assert.throws(() => mb.boolean(a, a, "union", { force: "yes" }), /true or false/);
	assert.throws(() => mb.orientIndexed(mb.soupToTyped(a), "sideways"), Error);
	// an open operand crossing itself (two sheets) has no inside of its own: taken as
	// given, as the reference takes it, and the report says so
	const tilt = (p) => ({ x: p.x, y: p.y, z: p.x + 0.1 });
	const folded = patch(0, 0, 0, 2, 2).concat(patch(0.05, 0.05, 0, 2, 2).map((t) => ({ v0: tilt(t.v0), v1: tilt(t.v1), v2: tilt(t.v2) })));
	const crossed = mb.booleanIndexed(mb.soupToTyped(folded), mb.soupToTyped(a), "subtract");
	assert.ok(crossed.report.assumed.some((l) => l.includes("of its open parts")), crossed.report.assumed.join("; "));
	assert.equal(crossed.report.operands[0].self_intersections.open_kept, true);
	// null inputs: null, as in the reference
	assert.equal(mb.boolean(null, a, "union"), null);
});

test("a panic in the WebAssembly reaches JavaScript as an Error with its message, and the module keeps working", () => {
	assert.throws(() => call("__panicForTest"), (e) => e instanceof Error && /internal error in __panicForTest.*a test panic/s.test(e.message));
	assert.equal(vol(mb.boolean(cube(0, 0, 0, 2), cube(1, 0, 0, 2), "union")), 12);
});

test("coincident faces: two cubes sharing faces resolved under each fill rule", () => {
	const two = cube(0, 0, 0, 2).concat(cube(1, 0, 0, 2));
	for (const [rule, volume] of [["positive", 12], ["nonzero", 12], ["evenodd", 8]]) {
		const r = mb.bmsSelfResolveIndexed(mb.soupToTyped(two), { rule });
		assert.equal(r.diagnostics.resolve.failed_triangles, 0, rule);
		assert.equal(r.diagnostics.volume, volume, rule);
		assert.equal(r.diagnostics.closed, true, rule);
	}
	// the same cube twice shares every vertex: its edges have four triangles, paired into
	// the two copies first; winding number 2 inside: one cube (nonzero), nothing (evenodd)
	const twice = cube(0, 0, 0, 2).concat(cube(0, 0, 0, 2));
	const once = mb.bmsSelfResolve(twice, { rule: "nonzero" });
	assert.equal(once.diagnostics.volume, 8);
	assert.equal(once.diagnostics.closed, true);
	assert.equal(once.diagnostics.resolve.separated_input.edges_split, 18);
	assert.equal(mb.bmsSelfResolve(twice, { rule: "evenodd" }).soup.length, 0);
});

test("verification, finishing and the one-call boolean", () => {
	const a = cube(0, 0, 0, 2), b = cube(1, 0.5, 0.25, 2);
	const good = mb.verifyOutput(a, { expectClosed: true });
	assert.equal(good.ok, true);
	assert.equal(mb.violationCount(good), 0);
	assert.deepEqual(good.stats, { triangles: 12, vertices: 8, openEdges: 0, nonManifoldEdges: 0, area: 24, components: 1, volume: 8 });
	// a duplicate, a reversed triangle and a missing one
	const bad = a.slice(1).concat([a[3]]);
	bad[4] = mb.flipAllNormals([bad[4]])[0];
	const v = mb.verifyOutput(bad, { expectClosed: true });
	const count = Object.fromEntries(v.checks.map((c) => [c.check, c.count]));
	assert.equal(v.ok, false);
	assert.equal(count.noDuplicateTriangles, 1);
	assert.ok(count.consistentWinding > 0);
	assert.ok(count.closed > 0);
	const t = mb.verifyOutput([
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 2, y: 0, z: 0 }, v2: { x: 1, y: 1, z: 0 } },
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 1, y: -1, z: 0 }, v2: { x: 1, y: 0, z: 0 } },
	]);
	assert.equal(t.checks.find((c) => c.check === "noTJunctions").count, 1);
	// a zero-thickness membrane on a face (a triangle and its reverse): cancelled, the
	// volume unchanged; the other stages change nothing and are skipped
	const finished = mb.finishMesh(a.concat([a[0]], mb.flipAllNormals([a[0]])));
	assert.deepEqual(finished.applied, ["dedupCoincident"]);
	assert.equal(finished.soup.length, 12);
	assert.equal(finished.ok, true);
	assert.equal(mb.violationCount(finished.before) > 0, true);
	// a plain duplicate removed: the baseline is not a sound solid (three triangles on an
	// edge), so its volume is not held against the repair, which closes the cube again
	const dup = mb.finishMesh(a.concat([a[0]]));
	assert.deepEqual(dup.applied, ["dedupCoincident"]);
	assert.equal(dup.soup.length, 12);
	assert.equal(mb.computeSignedVolume(dup.soup), 8);
	// a stage that would open a closed mesh is refused, with the reason
	const opener = { name: "opener", run: (s) => s.slice(1) };
	const refused = mb.finishMesh(a, { stages: [opener] });
	assert.equal(refused.soup, a);
	assert.deepEqual(refused.skipped.map((x) => x.reason), ["would damage the mesh"]);
	assert.deepEqual(mb.finishMesh(a.concat([a[0]]), { force: true }).applied.length, 3);
	const assess = mb.assessRepair(a, a.slice(1));
	assert.equal(assess.recommend, "discard");
	assert.ok(assess.harmful);
	assert.match(mb.describeAssessment(assess), /^DISCARD/);
	assert.equal(mb.DEFAULT_STAGES.length, 3);
	const auto = mb.booleanAuto(a, b, "subtract");
	assert.equal(auto.ok, true);
	assert.equal(auto.operation, "subtract");
	assert.equal(mb.computeSignedVolume(auto.soup), 8 - 1 * 1.5 * 1.75);
	assert.ok(auto.boolean.groups.aOutside.length > 0);
	assert.equal(mb.booleanAuto(a, b, "union", { quality: "raw" }).report, null);
	// indexed groups: one pool, triples per group, the same triangles
	const s = mb.splitMeshPair(a, b);
	const ig = mb.indexGroups(s.groups);
	for (const g of ["aInside", "aOutside", "bInside", "bOutside"]) {
		assert.equal(ig.groups[g].length, s.groups[g].length);
		const back = ig.groups[g].map(([i, j, k]) => ({ v0: ig.points[i], v1: ig.points[j], v2: ig.points[k] }));
		assert.deepEqual(back, s.groups[g]);
	}
	const typed = mb.indexGroupsToTypedArrays(ig);
	assert.equal(typed.positions.length, 3 * ig.points.length);
	assert.equal(typed.index.aOutside.length, 3 * s.groups.aOutside.length);
	assert.deepEqual(mb.bmsBooleanOp(a, b, null, { indexed: true }).indexed.points.length, ig.points.length);
	const comps = mb.decomposeIndexedGroups(ig);
	assert.equal(comps.reduce((n, c) => n + c.triCount, 0), s.groups.aInside.length + s.groups.aOutside.length + s.groups.bInside.length + s.groups.bOutside.length);
	assert.deepEqual(mb.connectedComponentsIndexed([[0, 1, 2], [2, 3, 4], [7, 8, 9]]).map((c) => c.length), [2, 1]);
	assert.deepEqual(mb.mergeSmallIndexedComponents([[[0, 1, 2]], [[3, 4, 5], [5, 6, 7]]], 2).map((c) => c.length), [3]);
	const d = mb.dedupCoincidentTriangles(a.concat([a[0], a[0]], mb.flipAllNormals([a[1]])));
	assert.equal(d.soup.length, 11);
	assert.equal(d.duplicateGroups, 2);
	assert.equal(d.duplicatesRemoved, 4);
});

test("the remaining exports, each against geometry", () => {
	const a = cube(0, 0, 0, 2);
	const t = mb.soupToTyped(a);
	assert.equal(mb.isIndexed(t), true);
	assert.equal(mb.isIndexed(a), false);
	// typed-array repair, close, orient, resolve
	const open = mb.soupToTyped(a.slice(2));
	const capped = mb.closeIndexed(open, "cap");
	assert.equal(capped.report.closed, true);
	assert.equal(mb.meshInfo(capped).volume, 8);
	const curtain = mb.closeIndexed(mb.soupToTyped(patch(0, 0, 5, 4, 2)), "curtain", { floorOffset: 1 });
	assert.equal(mb.meshInfo(curtain).volume, 16 * 1); // the floor 1 below the lowest point
	const inward = mb.soupToTyped(mb.flipAllNormals(a));
	assert.equal(mb.meshInfo(mb.orientIndexed(inward, "outward")).volume, 8);
	const rep = mb.repairIndexed(mb.soupToTyped(a.concat([a[0]])), { remove_duplicates: true });
	assert.equal(rep.index.length, 36);
	assert.equal(rep.report.duplicates.same_orientation_removed, 1);
	const two = mb.soupToTyped(a.concat(cube(1, 0.5, 0.25, 2)));
	const res = mb.resolveIndexed(two, { rule: "nonzero" });
	assert.equal(mb.meshInfo(res).volume, 16 - 1 * 1.5 * 1.75);
	assert.equal(res.parent.length, res.index.length / 3);
	// aliases and welds
	const w = mb.soupToIndexed(a, 1e-9);
	assert.equal(w.points.length, 8);
	assert.deepEqual(mb.indexedToSoup(w.triangles), a);
	const gap = a.map((t) => ({ v0: t.v0, v1: t.v1, v2: t.v2.z > 0 ? { x: t.v2.x, y: t.v2.y, z: t.v2.z + 1e-6 } : t.v2 }));
	assert.ok(closed(mb.weldBoundaryVertices(gap, 1e-4)));
	// hole filling: weld then cap; stitch-or-cap
	const holed = a.slice(2).map((t) => ({ ...t }));
	assert.equal(mb.computeSignedVolume(mb.capBoundaryLoopsSequential(holed, 1e-9)), 8);
	assert.equal(mb.computeSignedVolume(mb.generateClosingTriangles(holed, 0.1)), 8);
	// exact T-junction repair (the hole-free name) and coincident faces
	const tj = [
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 2, y: 0, z: 0 }, v2: { x: 1, y: 1, z: 0 } },
		{ v0: { x: 0, y: 0, z: 0 }, v1: { x: 1, y: -1, z: 0 }, v2: { x: 1, y: 0, z: 0 } },
		{ v0: { x: 1, y: 0, z: 0 }, v1: { x: 1, y: -1, z: 0 }, v2: { x: 2, y: 0, z: 0 } },
	];
	assert.equal(mb.countOpenEdges(mb.resolveTJunctionsHoleFree(tj)).openEdges, 4);
	assert.equal(mb.cancelCoincidentFaces(a.concat(mb.flipAllNormals([a[2]]))).length, 11);
	// vector helpers and solid angles: an octant of a sphere around a corner is 4π/8
	assert.deepEqual(mb.cross({ x: 1, y: 0, z: 0 }, { x: 0, y: 1, z: 0 }), { x: 0, y: 0, z: 1 });
	assert.equal(mb.distSq3({ x: 0, y: 0, z: 0 }, { x: 1, y: 2, z: 2 }), 9);
	const tri = { v0: { x: 1, y: 0, z: 0 }, v1: { x: 0, y: 1, z: 0 }, v2: { x: 0, y: 0, z: 1 } };
	const o = { x: 0, y: 0, z: 0 };
	assert.ok(Math.abs(mb.solidAngle(o, tri) - Math.PI / 2) < 1e-12);
	assert.equal(mb.solidAngleAt(0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1), mb.solidAngle(o, tri));
	// the grid on other axes (YZ)
	const grid = mb.buildSpatialGridOnAxes(a, 1, (v) => v.y, (v) => v.z);
	const cell = mb.queryGridOnAxes(grid, 0.5, 0.5, 1);
	assert.ok(cell.length > 0 && cell.every((i) => i >= 0 && i < a.length));
});

test("points classified exactly on the surface, else by the winding number", () => {
	const a = cube(0, 0, 0, 2);
	const pts = [{ x: 0, y: 0, z: 0 }, { x: 3, y: 0, z: 0 }, { x: 1, y: 0.5, z: -0.25 }, { x: 1, y: 1, z: 1 }];
	assert.deepEqual(mb.classifyPoints(a, pts), ["inside", "outside", "on", "on"]);
	const t = mb.classifyPointsIndexed(mb.soupToTyped(a), new Float64Array([0, 0, 0.999, 0, 0, 1.001]));
	assert.deepEqual(Array.from(t.classes), [1, 0]);
	assert.equal(t.report.points, 2);
	// an open terrain-like patch facing up: below is behind it
	assert.deepEqual(mb.classifyPoints(patch(0, 0, 0, 4, 4), [{ x: 0.3, y: 0.2, z: -1 }, { x: 0.3, y: 0.2, z: 1 }]), ["inside", "outside"]);
	assert.throws(() => mb.classifyPoints(a, [{ x: NaN, y: 0, z: 0 }]), /non-finite/);
});

test("cut and fill of a slope against flat ground", () => {
	// z = 0 and z = x over [-2, 2]²: two wedges of 4 · 2 · 2 / 2 = 8, meeting along x = 0.
	const ground = patch(0, 0, 0, 4, 2);
	const slope = ground.map((t) => ({ v0: { ...t.v0, z: t.v0.x }, v1: { ...t.v1, z: t.v1.x }, v2: { ...t.v2, z: t.v2.x } }));
	const r = mb.cutFill(ground, slope);
	assert.ok(Math.abs(r.cut - 8) < 1e-12 && Math.abs(r.fill - 8) < 1e-12, `${r.cut} ${r.fill}`);
	assert.ok(Math.abs(r.common_plan_area - 16) < 1e-12);
	assert.equal(r.lines.length, 1);
	assert.equal(r.zero_lines, 1);
});

test("envelopes of the folded Kirra terrain equal the CLI's", { skip: noKirra }, () => {
	const terrain = mb.readMesh(sharedData("kirra_terrain.obj"), "kirra_terrain.obj");
	for (const side of ["upper", "lower"]) {
		// meshbool resolve ../shared/data/kirra_terrain.obj --envelope SIDE -o out.ply --json
		const e = mb.envelopeIndexed(terrain, side);
		assert.equal(e.report.envelope.side, side);
		assert.equal(e.report.envelope.folded_triangles, 22);
		assert.equal(e.report.envelope.hidden_triangles, 22);
		assert.equal(e.report.boundary_edges, 560);
		assert.equal(e.parent.length, e.index.length / 3);
	}
	assert.throws(() => mb.envelopeIndexed(mb.soupToTyped(cube(0, 0, 0, 1))), /closed/);
});

test("the BMS stages: pool, intersection, split, classification checks", () => {
	const a = cube(0, 0, 0, 2), b = cube(1, 1, 1, 2);
	// A pool: equal positions are one vertex, ids in order; within a tolerance too.
	const pool = mb.createVertexPool();
	const p = pool.getOrCreate(1, 2, 3);
	assert.equal(pool.getOrCreate(1, 2, 3), p);
	assert.equal(pool.getOrCreate(1, 2, 3 + 1e-9).id, 1);
	assert.equal(pool.size(), 2);
	const near = mb.createVertexPool(1e-6);
	assert.equal(near.getOrCreate(1, 2, 3), near.getOrCreate(1, 2, 3 + 1e-9));
	assert.deepEqual(pool.getAll().map((v) => v.id), [0, 1]);
	// The cubes cross in a hexagon-like loop: segments on pool vertices, one closed chain,
	// every segment an edge of a piece of A.
	const isect = mb.bmsIntersect(a, b);
	assert.ok(isect.segments.length >= 6);
	assert.equal(isect.coplanarPairs, 0);
	assert.ok(isect.segments.every((s) => typeof s.p0.id === "number" && isect.pool.get(s.p0.id) === s.p0));
	const pieces = mb.bmsSplit(a, b, isect);
	const edges = new Set();
	for (const t of pieces.filter((t) => t.mesh === "A")) {
		const ids = [t.v0.id, t.v1.id, t.v2.id];
		for (let k = 0; k < 3; k++) edges.add(Math.min(ids[k], ids[(k + 1) % 3]) + "|" + Math.max(ids[k], ids[(k + 1) % 3]));
	}
	assert.ok(isect.segments.every((s) => edges.has(Math.min(s.p0.id, s.p1.id) + "|" + Math.max(s.p0.id, s.p1.id))));
	// Sides of the pieces by centroid: A's pieces inside B and B's inside A bound the
	// overlap, a unit cube.
	const groups = mb.heffalumpClassify(pieces, isect.segments, a, b);
	assert.equal(mb.computeSignedVolume(groups.aInside.concat(groups.bInside)), 1);
	assert.equal(groups.aInside.length + groups.aOutside.length, pieces.filter((t) => t.mesh === "A").length);
	const sides = pieces.map((t) => (groups.aInside.includes(t) || groups.bInside.includes(t) ? 1 : -1));
	assert.equal(mb.verifyBmsClassification(pieces, sides, isect.segments, [], a, b).ok, true);
	// All of A outside although the seam crosses it: the partition fails for A, and the
	// seam edges have A's pieces on one side both ways; nothing is said of B.
	const wrong = sides.map((s, i) => (pieces[i].mesh === "A" ? -1 : s));
	const v = mb.verifyBmsClassification(pieces, wrong, isect.segments, [], a, b);
	assert.deepEqual(v.failures.map((f) => [f.check, f.mesh]), [["partition", "A"], ["barrierConstraint", "A"]]);
	// Census: an operand with an edge of three triangles.
	assert.equal(mb.shouldUseHeffalump(a, b), false);
	const fin = a.concat([{ v0: a[0].v0, v1: a[0].v1, v2: { x: 0, y: -3, z: -3 } }]);
	assert.equal(mb.shouldUseHeffalump(fin, b), true);
	assert.equal(mb.bmsBooleanOp(fin, b, "union").classifier.A, "heffalump (census: non-manifold edges)");
	// A triangle split along a segment across it: the pieces tile it, the segment an edge.
	const tri = { v0: { x: 0, y: 0, z: 0 }, v1: { x: 4, y: 0, z: 0 }, v2: { x: 0, y: 4, z: 0 } };
	const cut = [{ p0: { x: 1, y: 0, z: 0 }, p1: { x: 1, y: 3, z: 0 } }];
	for (const split of [mb.fanTriangulate(tri, cut), mb.retriangulateWithSteinerPoints(tri, cut)]) {
		assert.ok(split.length >= 3);
		assert.equal(mb.computeProjectedArea(split), 8);
		assert.ok(split.every((t) => mb.triNormal(t).z > 0));
		assert.ok(split.some((t) => [t.v0, t.v1, t.v2].some((v) => v.x === 1 && v.y === 3)));
	}
	// Nested cubes: winding 2 in the inner one; the solid of winding >= 1 is the outer.
	const nested = cube(0, 0, 0, 6).concat(cube(0, 0, 0, 2));
	const cells = mb.extractByCellComplex(nested, null, { threshold: 1 });
	assert.equal(cells.diagnostics.windingMax, 2);
	assert.equal(cells.diagnostics.cells, 3);
	assert.equal(mb.computeSignedVolume(cells.kept), 216);
	assert.throws(() => mb.extractByCellComplex(nested, null, { threshold: 2 }), /\(0, 1\]/);
});

test("the reference's inner stages, computed by the library", () => {
	const a = cube(0, 0, 0, 2), b = cube(1, 1, 1, 2);
	assert.equal(mb.NEAR_PARALLEL, 1 - 1e-14);
	// Centroids classified exactly; the crossed triangle listed is left at 0.
	const classes = mb.classifyByFloodFill(a, { 0: [] }, b);
	assert.equal(classes[0], 0);
	assert.ok(Array.from(classes).slice(1).every((c) => c === 1 || c === -1));
	assert.equal(mb.classifyByFloodFill([{ v0: { x: 0.4, y: 0.4, z: 0.9 }, v1: { x: 0.6, y: 0.4, z: 0.9 }, v2: { x: 0.5, y: 0.6, z: 0.9 } }], {}, b)[0], 1);
	// The seam of the two cubes chains into one loop; a cube without a triangle has a
	// 3-vertex hole.
	const loops = mb.bmsChain(mb.bmsIntersect(a, b).segments);
	assert.equal(loops.length, 1);
	assert.equal(loops[0][0], loops[0][loops[0].length - 1]);
	assert.equal(mb.chainedOpenEdge(a.slice(1)).length, 3);
	assert.deepEqual(mb.chainedOpenEdge(a), []);
	const closing = mb.bmsClosePolylines(loops, a, b.slice(1), [], []);
	assert.equal(closing.closedPolylines.length, 1);
	assert.deepEqual([closing.meshEdgePolys.A.closed, closing.meshEdgePolys.B.closed], [true, false]);
	// bmsClassify of bmsSplit's pieces: the split's own sides, the overlap a unit cube.
	const isect = mb.bmsIntersect(a, b);
	const g = mb.bmsClassify(mb.bmsSplit(a, b, isect), [], isect.segments, a, b, null);
	assert.equal(mb.computeSignedVolume(g.aInside.concat(g.bInside)), 1);
	// Coplanar triangles overlapping in a quad of area 19/12; neighbours sharing an edge
	// touch and do not overlap.
	const t1 = { v0: { x: 0, y: 0, z: 0 }, v1: { x: 4, y: 0, z: 0 }, v2: { x: 0, y: 4, z: 0 } };
	const t2 = { v0: { x: 1, y: -1, z: 0 }, v1: { x: 3, y: 3, z: 0 }, v2: { x: 3, y: -1, z: 0 } };
	const overlap = mb.coplanarOverlap(t1, t2);
	assert.equal(overlap.polygon.length, 4);
	assert.ok(Math.abs(overlap.area - 19 / 12) < 1e-12);
	assert.equal(mb.coplanarOverlap(t1, { v0: { x: 4, y: 0, z: 0 }, v1: { x: 4, y: 4, z: 0 }, v2: { x: 0, y: 4, z: 0 } }), null);
	const pool = mb.createVertexPool();
	const segs = mb.emitCoplanarSegments(overlap.polygon, pool, { mesh: "A", triIdx: 0 }, { mesh: "B", triIdx: 3 });
	assert.equal(segs.length, 4);
	assert.equal(pool.size(), 4);
	assert.ok(segs.every((s) => s.idxA === 0 && s.idxB === 3));
	// Two overlapping cubes as one soup: 18 pairs meet; cut there, the pieces of winding
	// straddling 1/2 bound the union (volume 15).
	const two = a.concat(b);
	const self = mb.bmsSelfIntersect(two);
	assert.equal(self.stats.crossingPairs, 18);
	assert.ok(self.segments.length > 0);
	const arranged = mb.bmsSelfArrange(two);
	assert.ok(arranged.megaSoup.length > two.length);
	assert.equal(mb.compute3DSurfaceArea(arranged.megaSoup), 48);
	assert.equal(mb.bmsSplit(two, [], self).length, arranged.megaSoup.length);
	// A segment ending on the edge two triangles share splits that edge on both sides.
	const T1 = { v0: { x: 0, y: 0, z: 0 }, v1: { x: 4, y: 0, z: 0 }, v2: { x: 0, y: 4, z: 0 } };
	const T2 = { v0: { x: 4, y: 0, z: 0 }, v1: { x: 4, y: 4, z: 0 }, v2: { x: 0, y: 4, z: 0 } };
	const T3 = { v0: { x: 1, y: 1, z: -1 }, v1: { x: 1, y: 1, z: 1 }, v2: { x: 2, y: 2, z: 0 } };
	const fold = mb.bmsSelfArrange([T1, T2, T3]);
	assert.equal(fold.stats.edgeSteinerPoints, 1);
	assert.equal(fold.stats.edgeSteinerTris, 2);
	const w = (x, y, z) => mb.windingNumber({ x, y, z }, two);
	const kept = mb.extractByWinding(arranged.megaSoup, w);
	assert.ok(Math.abs(mb.computeSignedVolume(kept.kept) - 15) < 1e-9);
	assert.equal(kept.keptFlags.length, arranged.megaSoup.length);
	// Patches split by the seam: one decision each; the same union.
	const barrier = {};
	for (const s of self.segments) barrier[mb.edgeKey(mb.vKey(s.p0), mb.vKey(s.p1))] = true;
	const byPatch = mb.extractByWindingPatches(arranged.megaSoup, barrier, w);
	assert.ok(byPatch.patches >= 4);
	assert.ok(Math.abs(mb.computeSignedVolume(byPatch.kept) - 15) < 1e-9);
	// Edge Steiner map: a point in the middle of the cube's bottom diagonal belongs to
	// both triangles on it.
	const bottom = a.slice(0, 2);
	const mid = { x: 0, y: 0, z: -1 };
	const map = mb.buildEdgeSteinerMap(2, (t) => bottom[t], (t, c) => mb.vKey([bottom[t].v0, bottom[t].v1, bottom[t].v2][c]), [{ p0: mid, p1: { x: 5, y: 5, z: 5 } }], 1e-9);
	assert.deepEqual(Object.keys(map).sort(), ["0", "1"]);
	// Snaps and welds within the caller's tolerance.
	const seg = { p0: { x: 1 + 1e-7, y: 1, z: 1 }, p1: { x: 9, y: 9, z: 9 } };
	assert.equal(mb.snapEndpointsToVertices(a, [seg], 1e-6), 1);
	assert.equal(seg.p0.x, 1);
	const welded = mb.weldTaggedSoup([{ ...a[0], mesh: "A", origIdx: 0 }, { v0: { x: a[0].v0.x + 1e-9, y: a[0].v0.y, z: a[0].v0.z }, v1: a[1].v1, v2: a[1].v2, mesh: "B", origIdx: 1 }], 1e-6);
	assert.equal(welded.soup[0].v0, welded.soup[1].v0);
	assert.equal(welded.soup[1].mesh, "B");
	assert.equal(welded.repOf(a[0].v0.x, a[0].v0.y, a[0].v0.z + 1e-9), welded.soup[0].v0);
	const cond = mb.conditionArrangement(a.slice(1), 1e-9);
	assert.deepEqual([cond.openBefore, cond.openAfter, cond.capsAdded], [3, 0, 1]);
	assert.equal(mb.conditionArrangement(a, 1e-9).soup, a);
	const near = { v0: { x: a[0].v0.x + 1e-4, y: a[0].v0.y, z: a[0].v0.z }, v1: a[0].v2, v2: a[0].v1 };
	const snapped = mb.snapCoincidentSheets([a[0], near], 0.01);
	assert.deepEqual([snapped.coincidentPairs, snapped.snappedVertices], [1, 1]);
	assert.deepEqual(snapped.soup[1].v0, a[0].v0);
	assert.equal(mb.snapCoincidentSheets(a, 0.01).soup, a);
});

test("Node.js runs the single-threaded build, and setThreads takes a choice only before the package loads", async () => {
	assert.deepEqual(mb.buildInfo(), { build: "single", threads: 1, reason: "Node.js" });
	const { setThreads } = await import("../src/threads.js");
	assert.throws(() => setThreads(0), /whole number from 1 to 1024 or null, got 0/);
	assert.throws(() => setThreads(2.5), /got 2.5/);
	// Loaded here with the default: another choice now would not be honoured.
	assert.throws(() => setThreads(4), /already loaded on this thread: call setThreads before its first import/);
	setThreads(null);
});

// CSG documents: evaluateCsg on the library's csg.
/** The signed volume of an indexed mesh. */
function signedVolumeOf({ positions: p, index: t }) {
	let v = 0;
	for (let k = 0; k < t.length; k += 3) {
		const [a, b, c] = [3 * t[k], 3 * t[k + 1], 3 * t[k + 2]];
		v += p[a] * (p[b + 1] * p[c + 2] - p[b + 2] * p[c + 1])
			- p[a + 1] * (p[b] * p[c + 2] - p[b + 2] * p[c])
			+ p[a + 2] * (p[b] * p[c + 1] - p[b + 1] * p[c]);
	}
	return v / 6;
}

const slotted = (width) => ({
	root: {
		op: "difference",
		name: "slotted",
		children: [
			{ op: "union", children: [{ mesh: mb.makeCube({ min: [0, 0, 0], max: [4, 2, 2] }) }, { primitive: "cube", min: [4, 0, 0], max: [6, 2, 2] }] },
			{ primitive: "cube", min: [1, -1, -1], max: [1 + width, 3, 3], role: "cutter" },
		],
	},
});

test("evaluateCsg: the volume the booleans give; a cache computes only an edit's path", () => {
	const cache = new mb.CsgCache();
	const out = mb.evaluateCsg(slotted(1), { cache });
	assert.equal(signedVolumeOf(out), 20);
	assert.equal(out.report.closed, true);
	assert.equal(out.report.computed, 5);
	assert.equal(out.report.nodes.at(-1).name, "slotted");
	const again = mb.evaluateCsg(slotted(1), { cache });
	assert.equal(again.report.computed, 0);
	assert.deepEqual(again.positions, out.positions);
	const edited = mb.evaluateCsg(slotted(2), { cache });
	assert.equal(signedVolumeOf(edited), 16);
	assert.deepEqual(edited.report.nodes.filter((n) => n.source === "computed").map((n) => n.path), ["root.children[1]", "root"]);
	assert.ok(cache.size >= 7);
	cache.clear();
	assert.equal(cache.size, 0);
});

test("evaluateCsg: a failing node is named, a malformed document says where", () => {
	assert.throws(
		() => mb.evaluateCsg({ root: { op: "union", children: [{ primitive: "cube" }, { mesh: "parts/a.stl" }] } }),
		(e) => /CSG node root\.children\[1\] failed/.test(e.message) && e.report.failed.path === "root.children[1]",
	);
	assert.throws(() => mb.evaluateCsg({ root: { primitive: "sphere", radus: 2 } }), /root\.radus: unknown key/);
});

test("every export is exercised by this file", () => {
	const src = readFileSync(new URL(import.meta.url), "utf8");
	const missing = Object.keys(mb).filter((n) => !new RegExp(`mb\\.${n}\\b`).test(src));
	assert.deepEqual(missing, []);
});

test("every export is declared in index.d.ts and every declaration is exported", () => {
	const dts = readFileSync(new URL("../src/index.d.ts", import.meta.url), "utf8");
	const declared = new Set([...dts.matchAll(/^export (?:function|const|class) (\w+)/gm)].map((m) => m[1]));
	const exported = new Set(Object.keys(mb));
	assert.deepEqual([...exported].filter((n) => !declared.has(n)), []);
	assert.deepEqual([...declared].filter((n) => !exported.has(n)), []);
});
