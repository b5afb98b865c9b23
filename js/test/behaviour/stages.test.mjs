// The BMS stage exports (JS_BEHAVIOUR.md section 3): createVertexPool, bmsIntersect,
// bmsSplit, shouldUseHeffalump, heffalumpClassify, fanTriangulate,
// verifyBmsClassification and extractByCellComplex, called through index.js.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

function square(x, y, s = 10, z = 0) {
	return [F.tri([x, y, z], [x + s, y, z], [x + s, y + s, z]), F.tri([x, y, z], [x + s, y + s, z], [x, y + s, z])];
}

/** The square (5..15)² tilted about x = 7.5 with slope s: z = s·(x − 7.5). */
function tilted(s) {
	const z = (x) => s * (x - 7.5);
	return [F.tri([5, 5, z(5)], [15, 5, z(15)], [15, 15, z(15)]), F.tri([5, 5, z(5)], [15, 15, z(15)], [5, 15, z(5)])];
}

describe("createVertexPool", () => {
	it("getOrCreate returns the same object within tol, getAll and size", () => {
		const pool = mb.createVertexPool(1e-3);
		const a = pool.getOrCreate(1, 2, 3, 0);
		const b = pool.getOrCreate(1 + 1e-4, 2, 3 - 1e-4, 1);
		const c = pool.getOrCreate(5, 5, 5, 2);
		assert.equal(a, b);
		assert.notEqual(a, c);
		assert.equal(pool.size(), 2);
		assert.equal(pool.getAll().length, 2);
		assert.equal(typeof a.id, "number");
	});
});

describe("bmsIntersect", () => {
	it("returns {segments: [{p0, p1, idxA, idxB}], crossedSetA, crossedSetB, pool, coplanarPairs}, ends pool vertices with id", () => {
		const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);
		const r = mb.bmsIntersect(A, B);
		for (const k of ["segments", "crossedSetA", "crossedSetB", "pool", "coplanarPairs"]) assert.ok(k in r, k);
		assert.ok(r.segments.length > 0);
		const ids = new Set(r.pool.getAll().map((v) => v.id));
		for (const s of r.segments) {
			assert.equal(typeof s.idxA, "number");
			assert.equal(typeof s.idxB, "number");
			assert.ok(ids.has(s.p0.id) && ids.has(s.p1.id));
		}
		// crossedSetA/B map each crossed triangle to its segments
		for (const s of r.segments) {
			assert.ok(r.crossedSetA[s.idxA].includes(s));
			assert.ok(r.crossedSetB[s.idxB].includes(s));
		}
	});

	it("shallow crossings give segments at every slope from 1e-9 to 1e-2, covering x = 7.5, 5 ≤ y ≤ 10 without a gap", () => {
		const A = square(0, 0);
		for (let e = -9; e <= -2; e++) {
			const s = 10 ** e;
			const r = mb.bmsIntersect(A, tilted(s));
			assert.ok(r.segments.length > 0, `slope ${s}`);
			let len = 0;
			for (const g of r.segments) {
				for (const p of [g.p0, g.p1]) {
					assert.ok(Math.abs(p.x - 7.5) < 1e-9 && Math.abs(p.z) < 1e-9, `slope ${s}: ${F.key(p)}`);
				}
				len += Math.hypot(g.p1.x - g.p0.x, g.p1.y - g.p0.y, g.p1.z - g.p0.z);
			}
			// each stretch of the line is cut once per pair: the union covers y 5..10
			const ys = r.segments.map((g) => [Math.min(g.p0.y, g.p1.y), Math.max(g.p0.y, g.p1.y)]).sort((p, q) => p[0] - q[0]);
			let reach = 5;
			for (const [lo, hi] of ys) {
				assert.ok(lo <= reach + 1e-9, `slope ${s}: gap at y ${reach}`);
				reach = Math.max(reach, hi);
			}
			assert.ok(Math.abs(reach - 10) < 1e-9, `slope ${s}: covered to ${reach}`);
			assert.ok(len >= 5 - 1e-9);
		}
	});

	it("exactly coplanar overlapping squares: overlap-boundary segments and coplanarPairs > 0; coplanar: false gives 0 and 0", () => {
		const r = mb.bmsIntersect(square(0, 0), square(5, 5));
		assert.ok(r.segments.length > 0);
		assert.ok(r.coplanarPairs > 0);
		for (const s of r.segments) {
			for (const p of [s.p0, s.p1]) assert.ok(p.x >= 5 && p.x <= 10 && p.y >= 5 && p.y <= 10 && p.z === 0);
		}
		const off = mb.bmsIntersect(square(0, 0), square(5, 5), { coplanar: false });
		assert.equal(off.segments.length, 0);
		assert.equal(off.coplanarPairs, 0);
	});
});

describe("bmsSplit", () => {
	it("tagged pieces {v0, v1, v2, mesh, origIdx} on the pool vertices, tiling each input", () => {
		const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);
		const isect = mb.bmsIntersect(A, B);
		const mega = mb.bmsSplit(A, B, isect);
		assert.ok(mega.length > A.length + B.length);
		for (const t of mega) {
			assert.ok(t.mesh === "A" || t.mesh === "B");
			assert.ok(Number.isInteger(t.origIdx));
		}
		const partsA = mega.filter((t) => t.mesh === "A"), partsB = mega.filter((t) => t.mesh === "B");
		assert.ok(Math.abs(F.area(partsA) - 24) < 1e-9);
		assert.ok(Math.abs(F.area(partsB) - 24) < 1e-9);
		const keys = new Set(mega.flatMap((t) => [t.v0, t.v1, t.v2]).map(F.key));
		for (const s of isect.segments) assert.ok(keys.has(F.key(s.p0)) && keys.has(F.key(s.p1)));
	});

	it("the fence's dense seam splits the floor into well-shaped pieces (aspect ≤ 100 but for < 10)", () => {
		const { floor, fence } = F.fenceAndFloor();
		const isect = mb.bmsIntersect(floor, fence);
		const floorParts = mb.bmsSplit(floor, fence, isect).filter((t) => t.mesh === "A");
		assert.ok(floorParts.length > 10);
		const bad = floorParts.filter((t) => F.longestEdge(t) ** 2 / F.triArea(t) / 2.309 > 100).length;
		assert.ok(bad < 10, `${bad} of ${floorParts.length}`);
	});
});

describe("shouldUseHeffalump, heffalumpClassify, fanTriangulate", () => {
	it("shouldUseHeffalump: true with an edge of three triangles, false for clean cubes", () => {
		assert.equal(mb.shouldUseHeffalump(F.finnedCube(), F.cube([1, 1, 1], 2)), true);
		assert.equal(mb.shouldUseHeffalump(F.cube(0, 2), F.cube([1, 1, 1], 2)), false);
	});

	it("heffalumpClassify returns the four groups and componentWalks", () => {
		const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);
		const isect = mb.bmsIntersect(A, B);
		const mega = mb.bmsSplit(A, B, isect);
		const r = mb.heffalumpClassify(mega, isect.segments, A, B);
		for (const g of ["aInside", "aOutside", "bInside", "bOutside"]) assert.ok(Array.isArray(r[g]) && r[g].length > 0, g);
		assert.ok("componentWalks" in r);
		// A's part inside B is the unit cube [0,1]³: area 3 of A's surface
		assert.ok(Math.abs(F.area(r.aInside) - 3) < 1e-9);
	});

	it("fanTriangulate is a function", () => {
		assert.equal(typeof mb.fanTriangulate, "function");
	});
});

describe("verifyBmsClassification", () => {
	const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);
	const bms = mb.bmsBooleanOp(A, B);
	const mega = bms.megaSoup;
	const truth = () => mega.map((t) => (mb.windingNumber(F.centroid(t), t.mesh === "A" ? B : A) > 0.5 ? 1 : -1));

	it("passes the true sides: {ok, counts: {A: {inside, outside}, B}, failures: []}", () => {
		const r = mb.verifyBmsClassification(mega, truth(), bms.segments, bms.polylines, A, B);
		assert.equal(r.ok, true);
		assert.deepEqual(r.failures, []);
		for (const m of ["A", "B"]) {
			assert.ok(r.counts[m].inside > 0 && r.counts[m].outside > 0, m);
		}
	});

	it('"partition" fails for a mesh all on one side although segments exist, naming only that mesh', () => {
		const sides = truth().map((s, i) => (mega[i].mesh === "A" ? 1 : s));
		const r = mb.verifyBmsClassification(mega, sides, bms.segments, bms.polylines, A, B);
		assert.equal(r.ok, false);
		const part = r.failures.filter((f) => f.check === "partition");
		assert.ok(part.length > 0);
		assert.ok(part.every((f) => f.mesh === "A"));
	});

	it('"chainClosure" fails for an open polyline whose ends are far from any boundary and not shared', () => {
		const loop = bms.polylines[0];
		const open = [loop.slice(0, Math.max(3, Math.floor(loop.length / 2)))];
		const r = mb.verifyBmsClassification(mega, truth(), bms.segments, open, A, B);
		assert.ok(r.failures.some((f) => f.check === "chainClosure"));
	});

	it("closed chains and chains joined end to end pass chainClosure", () => {
		const loop = bms.polylines[0];
		const closed = mb.verifyBmsClassification(mega, truth(), bms.segments, bms.polylines, A, B);
		assert.ok(!closed.failures.some((f) => f.check === "chainClosure"));
		const h = Math.floor(loop.length / 2);
		const halves = [loop.slice(0, h + 1), loop.slice(h)];
		const joined = mb.verifyBmsClassification(mega, truth(), bms.segments, halves, A, B);
		assert.ok(!joined.failures.some((f) => f.check === "chainClosure"));
	});

	it('"barrierConstraint" fails when both triangles on several barrier edges of one mesh carry the same side', () => {
		const seam = new Set(bms.segments.flatMap((s) => [F.key(s.p0), F.key(s.p1)]));
		const sides = truth().map((s, i) => {
			const t = mega[i];
			const onSeam = [t.v0, t.v1, t.v2].some((v) => seam.has(F.key(v)));
			return t.mesh === "A" && onSeam ? 1 : s;
		});
		const r = mb.verifyBmsClassification(mega, sides, bms.segments, bms.polylines, A, B);
		assert.ok(r.failures.some((f) => f.check === "barrierConstraint" && f.mesh === "A"));
	});
});

describe("extractByCellComplex", () => {
	const w = (soup) => (x, y, z) => mb.windingNumber({ x, y, z }, soup);

	it("a cube: 2 cells, no violations, no leaks, all 12 kept, closed, volume 8", () => {
		const c = F.cube(0, 2);
		const r = mb.extractByCellComplex(c, w(c), { threshold: 0.5 });
		assert.equal(r.diagnostics.cells, 2);
		assert.equal(r.diagnostics.propagationViolations, 0);
		assert.equal(r.diagnostics.leakedFaceFraction, 0);
		assert.equal(r.kept.length, 12);
		assert.equal(F.edgeCounts(r.kept).open, 0);
		assert.ok(Math.abs(F.signedVolume(r.kept) - 8) < 1e-9);
	});

	it("cubes of edge 2 and 6 nested: windingMax 2, only the outer 12 kept (volume 216)", () => {
		const s = [...F.cube(0, 2), ...F.cube(0, 6)];
		const r = mb.extractByCellComplex(s, w(s), { threshold: 0.5 });
		assert.equal(r.diagnostics.windingMax, 2);
		assert.equal(r.kept.length, 12);
		assert.ok(Math.abs(F.signedVolume(r.kept) - 216) < 1e-9);
	});

	it("a cube plus an extra copy and reverse of one face: 12 kept, volume 8", () => {
		const c = F.cube(0, 2);
		const s = [...c, F.copySoup([c[0]])[0], F.flipTri(c[0])];
		const r = mb.extractByCellComplex(s, w(s), { threshold: 0.5 });
		assert.equal(r.kept.length, 12);
		assert.ok(Math.abs(F.signedVolume(r.kept) - 8) < 1e-9);
	});
});
