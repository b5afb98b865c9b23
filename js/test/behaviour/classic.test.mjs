// The classic pipeline and utilities (JS_BEHAVIOUR.md section 14, semantics of JS_API.md):
// boolean, splitMeshPair, mergeSplitGroups, selectSplits, mergeComponents,
// splitToComponents, mergeSmallComponents, reclassify*, triTriIntersection(Detailed),
// intersectMeshPair(Tagged), chainSegments, simplifyPolyline, grids and boxes, repair
// helpers, normals and measures, and the small utilities.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const A = F.cube(0, 2), B = F.cube([1, 0, 0], 2);

describe("boolean, splitMeshPair, mergeSplitGroups", () => {
	it("splitMeshPair on cube(0,2) vs cube((1,0,0),2): 4 non-empty groups, with segments", () => {
		const r = mb.splitMeshPair(A, B);
		for (const g of ["aInside", "aOutside", "bInside", "bOutside"]) assert.ok(r.groups[g].length > 0, g);
		assert.ok(r.segments.length > 0);
		// A's surface inside B = [0,2]×[-1,1]²: the x = 0..1 halves of four faces (2 each) and the x = 1 face (4)
		assert.ok(Math.abs(F.area(r.groups.aInside) - (4 * 2 + 4)) < 1e-9);
	});

	for (const [op, vol] of [["union", 12], ["intersect", 4], ["subtract", 4]]) {
		it(`${op}: mergeSplitGroups equals boolean, volume ${vol}, closed`, () => {
			const m = mb.mergeSplitGroups(mb.splitMeshPair(A, B).groups, op);
			const b = mb.boolean(A, B, op);
			assert.ok(Math.abs(F.signedVolume(m.soup) - vol) < 1e-9);
			assert.ok(Math.abs(F.signedVolume(b.soup) - vol) < 1e-9);
			assert.deepEqual(F.soupKeys(m.soup, F.triOrientedKey), F.soupKeys(b.soup, F.triOrientedKey));
			const e = F.edgeCounts(b.soup);
			assert.equal(e.open + e.nonManifold + e.inconsistent, 0);
			assert.ok(Array.isArray(b.points) && Array.isArray(b.triangles));
			assert.equal(b.triangles.length, b.soup.length);
		});
	}

	it("boolean(null, null) → null; splitMeshPair(null, null) → null", () => {
		assert.equal(mb.boolean(null, null, "union"), null);
		assert.equal(mb.splitMeshPair(null, null), null);
	});

	it("disjoint cubes: 0 segments, everything outside", () => {
		const r = mb.splitMeshPair(F.cube(0, 2), F.cube([10, 0, 0], 2));
		assert.equal(r.segments.length, 0);
		assert.equal(r.groups.aInside.length, 0);
		assert.equal(r.groups.bInside.length, 0);
		assert.equal(r.groups.aOutside.length, 12);
		assert.equal(r.groups.bOutside.length, 12);
	});

	it("selectSplits: aOutside + flipped bInside is the difference; nothing selected gives null", () => {
		const g = mb.splitMeshPair(A, B).groups;
		const r = mb.selectSplits(g, { aOutside: true, bInside: "flip" });
		assert.ok(Math.abs(F.signedVolume(r.soup) - 4) < 1e-9);
		assert.equal(mb.selectSplits(g, {}), null);
	});

	it("mergeComponents concatenates picks with flips", () => {
		const g = mb.splitMeshPair(A, B).groups;
		const r = mb.mergeComponents([{ soup: g.aInside }, { soup: g.bInside }]);
		assert.ok(Math.abs(F.signedVolume(r.soup) - 4) < 1e-9);
		const s = mb.mergeComponents([{ soup: g.aOutside }, { soup: g.bInside, flip: true }]);
		assert.ok(Math.abs(F.signedVolume(s.soup) - 4) < 1e-9);
	});

	it("boolean with preRepair gives the same exact union", () => {
		const r = mb.boolean(A, B, "union", { preRepair: true });
		assert.ok(Math.abs(F.signedVolume(r.soup) - 12) < 1e-9);
	});
});

describe("splitToComponents, mergeSmallComponents, reclassify*", () => {
	it("splitToComponents: [{mesh, side, index, soup, triCount}]", () => {
		const comps = mb.splitToComponents(mb.splitMeshPair(A, B).groups);
		assert.equal(comps.length, 4);
		for (const c of comps) {
			assert.ok(["A", "B"].includes(c.mesh) && ["inside", "outside"].includes(c.side));
			assert.equal(c.triCount, c.soup.length);
			assert.equal(c.index, 0);
		}
	});

	it("mergeSmallComponents merges small components into the nearest larger one of the same mesh and side", () => {
		const big = F.patch(4, 4), small = F.translate(F.T(), 10, 0, 0), far = F.translate(F.patch(4, 4), 100, 0, 0);
		const comps = [
			{ mesh: "A", side: "outside", index: 0, soup: big, triCount: big.length },
			{ mesh: "A", side: "outside", index: 1, soup: far, triCount: far.length },
			{ mesh: "A", side: "outside", index: 2, soup: small, triCount: 1 },
		];
		const out = mb.mergeSmallComponents(comps, 5);
		assert.equal(out.length, 2);
		const withSmall = out.find((c) => c.soup.length === 33);
		assert.ok(withSmall);
		assert.ok(withSmall.soup.some((t) => t.v0.x === 10));
		assert.ok(Math.max(...withSmall.soup.map((t) => t.v0.x)) < 50);
	});

	it("reclassifyTriangles moves listed triangles to the other side, in place", () => {
		const g = mb.splitMeshPair(A, B).groups;
		const n = g.aInside.length, m = g.aOutside.length;
		mb.reclassifyTriangles(g, "A", "inside", [0, 1]);
		assert.equal(g.aInside.length, n - 2);
		assert.equal(g.aOutside.length, m + 2);
	});

	it("reclassifyAtPoint toggles the triangle whose centroid is there", () => {
		const g = mb.splitMeshPair(A, B).groups;
		const t = g.bOutside[0], c = F.centroid(t);
		const r = mb.reclassifyAtPoint(g, c.x, c.y, c.z);
		assert.deepEqual(r, { moved: true, mesh: "B", from: "outside", to: "inside" });
		assert.ok(g.bInside.includes(t));
		assert.deepEqual(mb.reclassifyAtPoint(g, 99, 99, 99), { moved: false });
	});

	it("reclassifyRegion moves the whole connected region of a seed", () => {
		const g = mb.splitMeshPair(A, B).groups;
		const n = g.aOutside.length;
		assert.equal(mb.reclassifyRegion(g, "A", "outside", 0), n);
		assert.equal(g.aOutside.length, 0);
	});
});

describe("intersection", () => {
	it("triTriIntersection: null for parallel triangles 0.001 apart", () => {
		const t = F.T()[0];
		assert.equal(mb.triTriIntersection(t, F.translate([t], 0, 0, 0.001)[0]), null);
	});

	it("triTriIntersection: shallow crossings exact (x = 7.5, z = 0 within 1e-9) at slopes 1e-9 … 1e-2", () => {
		const flat = F.tri([0, 0, 0], [20, 0, 0], [0, 20, 0]);
		for (let e = -9; e <= -2; e++) {
			const s = 10 ** e, z = (x) => s * (x - 7.5);
			const tilt = F.tri([5, 5, z(5)], [15, 5, z(15)], [5, 8, z(5)]);
			const seg = mb.triTriIntersection(flat, tilt);
			assert.ok(seg, `slope ${s}`);
			for (const p of [seg.p0, seg.p1]) {
				assert.ok(Math.abs(p.x - 7.5) < 1e-9 && Math.abs(p.z) < 1e-9, `slope ${s}: ${F.key(p)}`);
			}
			const d = mb.triTriIntersectionDetailed(flat, tilt);
			assert.ok(d && d.segLen > 0, `detailed, slope ${s}`);
		}
	});

	it("intersectMeshPair and intersectMeshPairTagged: the same segments, tags index the inputs", () => {
		const plain = mb.intersectMeshPair(A, F.cube([1, 1, 1], 2));
		const tagged = mb.intersectMeshPairTagged(A, F.cube([1, 1, 1], 2));
		assert.equal(plain.length, tagged.length);
		assert.ok(tagged.length > 0);
		for (const s of tagged) assert.ok(s.idxA >= 0 && s.idxA < 12 && s.idxB >= 0 && s.idxB < 12);
	});

	it("chainSegments chains the cube crossing into one closed loop", () => {
		const chains = mb.chainSegments(mb.intersectMeshPair(A, F.cube([1, 1, 1], 2)), 1e-9);
		assert.equal(chains.length, 1);
	});

	it("simplifyPolyline decimates by distance and keeps the ends", () => {
		const pts = [];
		for (let i = 0; i <= 100; i++) pts.push({ x: i * 0.1, y: 0, z: 0 });
		const s = mb.simplifyPolyline(pts, 1);
		assert.ok(s.length < pts.length && s.length >= 2);
		assert.deepEqual(s[0], pts[0]);
		assert.deepEqual(s[s.length - 1], pts[pts.length - 1]);
	});

	it("computeBBox, triBBox, bboxOverlap, estimateAvgEdge", () => {
		const bb = mb.computeBBox(A);
		assert.deepEqual([bb.minX, bb.minY, bb.minZ, bb.maxX, bb.maxY, bb.maxZ], [-1, -1, -1, 1, 1, 1]);
		const tb = mb.triBBox(F.T()[0]);
		assert.deepEqual([tb.minX, tb.maxX, tb.minY, tb.maxY], [0, 1, 0, 1]);
		assert.equal(mb.bboxOverlap(bb, mb.computeBBox(F.cube([1.5, 0, 0], 2))), true);
		assert.equal(mb.bboxOverlap(bb, mb.computeBBox(F.cube([5, 0, 0], 2))), false);
		const avg = mb.estimateAvgEdge(A);
		assert.ok(avg > 2 && avg < 2 * Math.SQRT2);
	});

	it("buildSpatialGrid / queryGrid find the triangles under a box", () => {
		const p = F.grid(4, 4, 1);
		const grid = mb.buildSpatialGrid(p, 1);
		const hits = mb.queryGrid(grid, { minX: 0.2, maxX: 0.4, minY: 0.2, maxY: 0.4 }, 1);
		const ids = [...hits];
		assert.ok(ids.includes(0) && ids.includes(1));
		assert.ok(ids.length < p.length);
	});
});

describe("repair helpers", () => {
	it("weldVertices / soupToIndexed and weldedToSoup / indexedToSoup round-trip", () => {
		const w = mb.weldVertices(A, 1e-6);
		assert.equal(w.points.length, 8);
		assert.equal(w.triangles.length, 12);
		const back = mb.weldedToSoup(w.triangles);
		assert.deepEqual(F.soupKeys(back, F.triOrientedKey), F.soupKeys(A, F.triOrientedKey));
		assert.equal(mb.soupToIndexed, mb.weldVertices);
		assert.equal(mb.indexedToSoup, mb.weldedToSoup);
	});

	it("deduplicateSeamVertices merges vertices within tol and drops collapsed triangles", () => {
		const s = [...A, F.tri([0, 0, 5], [1e-6, 0, 5], [0, 1, 5])];
		const out = mb.deduplicateSeamVertices(s, 1e-4);
		assert.equal(out.length, 12);
	});

	it("removeDegenerateTriangles removes zero-area triangles", () => {
		const out = mb.removeDegenerateTriangles([...F.T(), F.tri([0, 0, 0], [1, 0, 0], [2, 0, 0])]);
		assert.equal(out.length, 1);
	});

	it("extractBoundaryLoops: one loop of 3 for T, none for a cube", () => {
		const r = mb.extractBoundaryLoops(F.T());
		assert.equal(r.loops.length, 1);
		assert.equal(r.loops[0].length, 3);
		assert.equal(r.boundaryEdgeCount, 3);
		assert.equal(r.overSharedEdgeCount, 0);
		assert.equal(mb.extractBoundaryLoops(A).loops.length, 0);
	});

	it("triangulateLoop triangulates a square loop into 2 triangles of area 1", () => {
		const tris = mb.triangulateLoop([{ x: 0, y: 0, z: 0 }, { x: 1, y: 0, z: 0 }, { x: 1, y: 1, z: 0 }, { x: 0, y: 1, z: 0 }]);
		assert.equal(tris.length, 2);
		assert.ok(Math.abs(F.area(tris) - 1) < 1e-12);
	});

	it("capBoundaryLoops and fillOpenEdgeLoops close a cube with a missing triangle", () => {
		const open = A.slice(1);
		for (const out of [mb.capBoundaryLoops(open), mb.fillOpenEdgeLoops(open)]) {
			assert.equal(F.edgeCounts(out).open, 0);
			assert.ok(Math.abs(F.signedVolume(out) - 8) < 1e-9);
		}
	});

	it("removeOverlappingTriangles removes anti-parallel coincident pairs", () => {
		const t = F.T()[0];
		const out = mb.removeOverlappingTriangles([...A, F.translate([t], 5, 5, 5)[0], F.flipTri(F.translate([t], 5, 5, 5)[0])]);
		assert.equal(out.length, 12);
	});

	it("repairMesh resolves to {soup, points, triangles}", async () => {
		const r = await mb.repairMesh(A);
		assert.equal(r.soup.length, 12);
		assert.ok(Array.isArray(r.points) && Array.isArray(r.triangles));
	});

	it("buildCurtainAndCap turns a surface into a closed solid", () => {
		const surface = F.grid(2, 2, 1);
		const out = mb.buildCurtainAndCap(surface, 10);
		// JS_API.md leaves open whether the surface itself is returned with the curtain and cap
		const keys = new Set(out.map(F.triSetKey));
		const solid = surface.every((t) => keys.has(F.triSetKey(t))) ? out : [...surface, ...out];
		const e = F.edgeCounts(solid);
		assert.equal(e.open, 0);
		assert.ok(Math.abs(Math.abs(F.signedVolume(solid)) - 40) < 1e-9);
	});
});

describe("normals and measures", () => {
	it("triNormal is the unit face normal", () => {
		const n = mb.triNormal(F.T()[0]);
		assert.deepEqual([n.x, n.y, n.z], [0, 0, 1]);
	});

	it("ensureZUpNormals flips downward triangles; flipAllNormals reverses all", () => {
		const down = F.flipSoup(F.grid(2, 2, 1));
		assert.ok(mb.ensureZUpNormals(down).every((t) => F.normalOf(t)[2] > 0));
		assert.ok(mb.flipAllNormals(F.grid(2, 2, 1)).every((t) => F.normalOf(t)[2] < 0));
	});

	it("computeSignedVolume, compute3DSurfaceArea, computeProjectedArea", () => {
		assert.ok(Math.abs(mb.computeSignedVolume(A) - 8) < 1e-12);
		assert.ok(Math.abs(mb.computeSignedVolume(F.flipSoup(A)) + 8) < 1e-12);
		assert.ok(Math.abs(mb.compute3DSurfaceArea(A) - 24) < 1e-12);
		assert.ok(Math.abs(mb.computeProjectedArea(F.grid(2, 3, 1), "xy") - 6) < 1e-12);
		assert.ok(Math.abs(mb.computeProjectedArea(F.grid(2, 3, 1), "yz")) < 1e-12);
	});

	it("classifyNormalDirection returns a label", () => {
		assert.equal(typeof mb.classifyNormalDirection(A, true, 8), "string");
	});

	it("classifyPointMultiAxis: 1 inside, -1 outside", () => {
		assert.equal(mb.classifyPointMultiAxis({ x: 0.1, y: 0.2, z: 0.3 }, A), 1);
		assert.equal(mb.classifyPointMultiAxis({ x: 3, y: 0.2, z: 0.3 }, A), -1);
	});
});

describe("utilities", () => {
	it("dist3, distSq3, triangleArea3D, cross, lerpVert, computeBounds", () => {
		const a = { x: 0, y: 0, z: 0 }, b = { x: 3, y: 4, z: 0 };
		assert.equal(mb.dist3(a, b), 5);
		assert.equal(mb.distSq3(a, b), 25);
		assert.equal(mb.triangleArea3D(F.T()[0]), 0.5);
		const c = mb.cross({ x: 1, y: 0, z: 0 }, { x: 0, y: 1, z: 0 });
		assert.deepEqual([c.x, c.y, c.z], [0, 0, 1]);
		assert.deepEqual(mb.lerpVert(a, b, 0.5), { x: 1.5, y: 2, z: 0 });
		const bb = mb.computeBounds([a, b, { x: -1, y: 2, z: 7 }]);
		assert.deepEqual([bb.minX, bb.minY, bb.minZ, bb.maxX, bb.maxY, bb.maxZ], [-1, 0, 0, 3, 4, 7]);
	});

	it("vKey keys at 6 decimals; edgeKey is undirected", () => {
		const k = mb.vKey({ x: 1, y: 2, z: 3 });
		assert.ok(k.includes("1.000000") && k.includes("2.000000") && k.includes("3.000000"));
		assert.equal(mb.vKey({ x: 1 + 1e-9, y: 2, z: 3 }), k);
		assert.notEqual(mb.vKey({ x: 1 + 1e-5, y: 2, z: 3 }), k);
		const k2 = mb.vKey({ x: 4, y: 5, z: 6 });
		assert.equal(mb.edgeKey(k, k2), mb.edgeKey(k2, k));
	});

	it("countOpenEdges: {openEdges, overShared, total}", () => {
		assert.deepEqual(mb.countOpenEdges(F.T()), { openEdges: 3, overShared: 0, total: 3 });
		assert.deepEqual(mb.countOpenEdges(A), { openEdges: 0, overShared: 0, total: 18 });
		const fin = mb.countOpenEdges(F.finnedCube());
		assert.equal(fin.overShared, 1);
		assert.equal(fin.openEdges, 2);
	});

	it("findConnectedComponents returns edge-connected sub-soups, largest first", () => {
		const comps = mb.findConnectedComponents([...F.T(), ...F.translate(A, 10, 0, 0)]);
		assert.deepEqual(comps.map((c) => c.length), [12, 1]);
	});
});
