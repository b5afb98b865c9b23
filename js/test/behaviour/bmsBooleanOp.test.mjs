// bmsBooleanOp (JS_BEHAVIOUR.md section 2): classifier labels, verification, pool and
// splitReport, indexed groups, open sheets and leaky cutters against boxes, nested solids,
// the UTM stand-in for the Kirra pair (seam quality), a giant face against a dense seam,
// seams ending on shared edges and coplanar overlaps.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const GROUPS = ["aInside", "aOutside", "bInside", "bOutside"];

/** A 10×10-style square of two +z triangles with low corner (x, y). */
function square(x, y, s = 10, z = 0) {
	return [F.tri([x, y, z], [x + s, y, z], [x + s, y + s, z]), F.tri([x, y, z], [x + s, y + s, z], [x, y + s, z])];
}

describe("bmsBooleanOp: classifier labels", () => {
	const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);

	it('clean inputs under "auto" (the default) and "hybrid": "hybrid"', () => {
		assert.deepEqual(mb.bmsBooleanOp(A, B).classifier, { A: "hybrid", B: "hybrid" });
		assert.deepEqual(mb.bmsBooleanOp(A, B, "union", { classifier: "auto" }).classifier, { A: "hybrid", B: "hybrid" });
		assert.deepEqual(mb.bmsBooleanOp(A, B, "union", { classifier: "hybrid" }).classifier, { A: "hybrid", B: "hybrid" });
	});

	it('classifier "heffalump" and the deprecated forceHeffalump: "heffalump (forced)"', () => {
		const want = { A: "heffalump (forced)", B: "heffalump (forced)" };
		assert.deepEqual(mb.bmsBooleanOp(A, B, "union", { classifier: "heffalump" }).classifier, want);
		assert.deepEqual(mb.bmsBooleanOp(A, B, "union", { forceHeffalump: true }).classifier, want);
	});

	it('an operand with an edge of three triangles: "heffalump (census: non-manifold edges)" on both', () => {
		const r = mb.bmsBooleanOp(F.finnedCube(), B, "union");
		assert.deepEqual(r.classifier, { A: "heffalump (census: non-manifold edges)", B: "heffalump (census: non-manifold edges)" });
	});

	it('no segments: "none (no intersection)"', () => {
		const r = mb.bmsBooleanOp(F.cube(0, 1), F.cube([10, 10, 10], 1), "union");
		assert.equal(r.segments.length, 0);
		assert.deepEqual(r.classifier, { A: "none (no intersection)", B: "none (no intersection)" });
	});
});

describe("bmsBooleanOp: verification", () => {
	it("auto with segments: {ok, failures[]}, ok for cube(0,2) vs cube((1,1,1),2), all four groups non-empty", () => {
		const r = mb.bmsBooleanOp(F.cube(0, 2), F.cube([1, 1, 1], 2), "union");
		for (const g of GROUPS) assert.ok(r.groups[g].length > 0, g);
		assert.ok(r.verification && typeof r.verification === "object");
		assert.ok(Array.isArray(r.verification.failures));
		assert.equal(r.verification.ok, true);
		assert.equal(r.verification.failures.length, 0);
	});

	it('null for classifier "hybrid"', () => {
		const r = mb.bmsBooleanOp(F.cube(0, 2), F.cube([1, 1, 1], 2), "union", { classifier: "hybrid" });
		assert.equal(r.verification, null);
	});

	it("null without segments when the boxes are apart or only touch", () => {
		assert.equal(mb.bmsBooleanOp(square(0, 0), square(10, 0), "union").verification, null);
		assert.equal(mb.bmsBooleanOp(square(0, 0), square(1000, 1000), "union").verification, null);
	});

	it('no segments yet overlapping boxes (coplanar squares, coplanar: false): ok false, "no-segments-but-bboxes-overlap"', () => {
		const r = mb.bmsBooleanOp(square(0, 0), square(5, 5), "union", { coplanar: false });
		assert.equal(r.segments.length, 0);
		assert.ok(r.verification);
		assert.equal(r.verification.ok, false);
		assert.equal(r.verification.failures[0].check, "no-segments-but-bboxes-overlap");
	});
});

describe("bmsBooleanOp: pool, splitReport, indexed", () => {
	const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);

	it("pool.getAll() returns the pool vertices, each with a numeric id", () => {
		const r = mb.bmsBooleanOp(A, B, "union");
		const all = r.pool.getAll();
		assert.ok(all.length > 0);
		for (const v of all) {
			assert.equal(typeof v.id, "number");
			for (const c of ["x", "y", "z"]) assert.equal(typeof v[c], "number");
		}
		assert.equal(new Set(all.map((v) => v.id)).size, all.length);
	});

	it("splitReport.lostSegments counts segments missing from the split (0 here)", () => {
		const r = mb.bmsBooleanOp(A, B, "union");
		assert.equal(r.splitReport.lostSegments, 0);
	});

	it("indexed: true reproduces the groups exactly with shared points", () => {
		const r = mb.bmsBooleanOp(A, B, "union", { indexed: true });
		const ix = r.indexed;
		assert.ok(ix && Array.isArray(ix.points) && ix.groups);
		let tris = 0;
		for (const g of GROUPS) {
			const soup = ix.groups[g].map(([i, j, k]) => ({ v0: ix.points[i], v1: ix.points[j], v2: ix.points[k] }));
			assert.deepEqual(F.soupKeys(soup, F.triOrientedKey), F.soupKeys(r.groups[g], F.triOrientedKey), g);
			tris += soup.length;
		}
		assert.ok(ix.points.length < 3 * tris);
		assert.ok(!("components" in r) && !("componentList" in r));
		assert.ok(!("components" in ix) && !("componentList" in ix));
	});

	it("no indexed field without the flag", () => {
		assert.ok(!("indexed" in mb.bmsBooleanOp(A, B, "union")));
	});

	it("result is the plain concat for op: union = aOutside + bOutside", () => {
		const r = mb.bmsBooleanOp(A, B, "union");
		assert.ok(Math.abs(F.signedVolume(r.result.soup) - 15) < 1e-9);
		assert.ok(Math.abs(F.area(r.result.soup) - (F.area(r.groups.aOutside) + F.area(r.groups.bOutside))) < 1e-9);
	});
});

describe("bmsBooleanOp: diagonal sheet of corner-touching squares vs a closed box", () => {
	const sheet = F.diagonalSheet(), box = F.box5();
	const shift = [0.31731, 0.31731, 0.11731];

	it("heffalump: aInside exactly the pieces whose centroid is strictly inside the box, aOutside the rest", () => {
		const r = mb.bmsBooleanOp(sheet, box, undefined, { classifier: "heffalump" });
		assert.ok(r.groups.aInside.length > 0 && r.groups.aOutside.length > 0);
		for (const t of r.groups.aInside) assert.ok(F.insideBox(F.centroid(t), 5));
		for (const t of r.groups.aOutside) assert.ok(!F.insideBox(F.centroid(t), 5));
		// the pieces tile the sheet
		assert.ok(Math.abs(F.area(r.groups.aInside) + F.area(r.groups.aOutside) - F.area(sheet)) < 1e-9);
		// inside: 3 whole squares and the corners [-5,-3.6]², [3.6,5]² of two more
		assert.ok(Math.abs(F.area(r.groups.aInside) - (3 * 2.4 * 2.4 + 2 * 1.4 * 1.4)) < 1e-9);
	});

	it("heffalump: identical counts after translating everything by (0.31731, 0.31731, 0.11731)", () => {
		const r = mb.bmsBooleanOp(sheet, box, undefined, { classifier: "heffalump" });
		const s = mb.bmsBooleanOp(F.translate(sheet, ...shift), F.translate(box, ...shift), undefined, { classifier: "heffalump" });
		assert.equal(s.groups.aInside.length, r.groups.aInside.length);
		assert.equal(s.groups.aOutside.length, r.groups.aOutside.length);
	});

	it("heffalump subtract: violationCount(verifyOutput(result)) < its length", () => {
		const r = mb.bmsBooleanOp(sheet, box, "subtract", { classifier: "heffalump" });
		const soup = r.result.soup;
		assert.ok(soup.length > 0);
		assert.ok(mb.violationCount(mb.verifyOutput(soup)) < soup.length);
	});

	it("auto: aInside count equals the heffalump's", () => {
		const h = mb.bmsBooleanOp(sheet, box, undefined, { classifier: "heffalump" });
		const a = mb.bmsBooleanOp(sheet, box);
		assert.equal(a.groups.aInside.length, h.groups.aInside.length);
	});

	// [keep] documented difference: the reference pins its hybrid classifier putting 0
	// diagonal-sheet pieces inside (a bug); meshbool's exact answer is 10 under every
	// classifier.
	for (const classifier of ["auto", "hybrid", "heffalump"]) {
		it(`[keep] ${classifier}: 10 pieces inside (not the reference's 0 under hybrid)`, () => {
			const r = mb.bmsBooleanOp(sheet, box, undefined, { classifier });
			assert.equal(r.groups.aInside.length, 10);
		});
	}
});

describe("bmsBooleanOp: leaky cutter (box without its +X and +Y walls) vs a sheet", () => {
	const sheet = F.leakySheet(), cutter = F.leakyBox();
	const inFootprint = (p) => Math.abs(p.x) < 5 && Math.abs(p.y) < 5;

	for (const classifier of ["auto", "heffalump"]) {
		it(`${classifier}: aInside non-empty and exactly the pieces whose centroid's (x, y) is inside the footprint`, { todo: "not yet: an open cutter's sides follow whole regions of the sheet; 641 pieces outside the footprint are marked inside" }, () => {
			const r = mb.bmsBooleanOp(sheet, cutter, undefined, { classifier });
			assert.ok(r.groups.aInside.length > 0);
			const wrongIn = r.groups.aInside.filter((t) => !inFootprint(F.centroid(t))).length;
			const wrongOut = r.groups.aOutside.filter((t) => inFootprint(F.centroid(t))).length;
			assert.equal(wrongIn, 0, "pieces outside the footprint marked inside");
			assert.equal(wrongOut, 0, "pieces inside the footprint marked outside");
		});
	}
});

describe("bmsBooleanOp: open patch vs closed cube", () => {
	it("heffalump: bInside and bOutside non-empty, each wholly on one side of z = 0, opposite sides", () => {
		const r = mb.bmsBooleanOp(F.patch(8, 5), F.cube(0, 2), undefined, { classifier: "heffalump" });
		const side = (soup) => {
			const zs = soup.map((t) => F.centroid(t).z).filter((z) => Math.abs(z) >= 0.05);
			if (zs.every((z) => z > 0)) return 1;
			if (zs.every((z) => z < 0)) return -1;
			return 0;
		};
		assert.ok(r.groups.bInside.length > 0 && r.groups.bOutside.length > 0);
		const a = side(r.groups.bInside), b = side(r.groups.bOutside);
		assert.notEqual(a, 0);
		assert.notEqual(b, 0);
		assert.equal(a, -b);
		// "inside" of an open surface is its anti-normal side: below the +z patch
		assert.equal(a, -1);
	});
});

describe("bmsBooleanOp: nested boxes", () => {
	it("heffalump: 0 segments", () => {
		const r = mb.bmsBooleanOp(F.cube(0, 4), F.cube(0, 20), undefined, { classifier: "heffalump" });
		assert.equal(r.segments.length, 0);
	});

	// [keep] documented difference: the reference calls everything outside when nothing
	// crosses; meshbool puts the inner box in aInside.
	it("[keep] the inner box is in aInside, the outer in bOutside", () => {
		const r = mb.bmsBooleanOp(F.cube(0, 4), F.cube(0, 20), undefined, { classifier: "heffalump" });
		assert.equal(r.groups.aInside.length, 12);
		assert.equal(r.groups.aOutside.length, 0);
		assert.ok(Math.abs(F.signedVolume(r.groups.aInside) - 64) < 1e-9);
		assert.equal(r.groups.bInside.length, 0);
		assert.equal(r.groups.bOutside.length, 12);
	});
});

describe("bmsBooleanOp: closed solid cut by an open surface at UTM coordinates (Kirra stand-in)", () => {
	const solid = F.kirraSolid(), cutter = F.kirraCutter();
	const cache = new Map();
	const run = (classifier) => {
		if (!cache.has(classifier)) cache.set(classifier, mb.bmsBooleanOp(solid, cutter, undefined, { classifier }));
		return cache.get(classifier);
	};
	const mm = (v) => F.roundedKey(v, 0.001);

	it("the fixture: a closed solid and an open cutter with 24 open edges crossing in one loop", () => {
		const e = F.edgeCounts(solid), c = F.edgeCounts(cutter);
		assert.equal(e.open + e.nonManifold + e.inconsistent, 0);
		assert.ok(F.signedVolume(solid) > 0);
		assert.equal(c.open, 24);
		const meanEdge = F.meanEdge(solid);
		assert.ok(meanEdge > 12 && meanEdge < 20, `mean edge ${meanEdge}`);
		const loops = mb.chainSegments(mb.intersectMeshPair(solid, cutter), 0);
		assert.equal(loops.length, 1);
	});

	for (const classifier of ["auto", "hybrid", "heffalump"]) {
		it(`${classifier}: lostSegments 0; each group non-empty and one edge-connected region (mm keys); pieces cover both inputs`, () => {
			const r = run(classifier);
			assert.equal(r.splitReport.lostSegments, 0);
			for (const g of GROUPS) {
				assert.ok(r.groups[g].length > 0, g);
				assert.equal(F.edgeComponents(r.groups[g], mm).length, 1, g);
			}
			assert.ok(r.groups.aInside.length + r.groups.aOutside.length >= solid.length);
			assert.ok(r.groups.bInside.length + r.groups.bOutside.length >= cutter.length);
		});

		it(`${classifier}: needles (altitude < 5 mm): 0 in bInside and bOutside, < 10 in aInside, < 120 in aOutside`, () => {
			const r = run(classifier);
			const needles = (g) => r.groups[g].filter((t) => F.altitude(t) < 0.005).length;
			assert.equal(needles("bInside"), 0);
			assert.equal(needles("bOutside"), 0);
			assert.ok(needles("aInside") < 10, `aInside ${needles("aInside")}`);
			assert.ok(needles("aOutside") < 120, `aOutside ${needles("aOutside")}`);
		});

		it(`${classifier}: no two pool points 1–5 mm apart`, () => {
			const r = run(classifier);
			const pts = r.pool.getAll();
			assert.ok(pts.length > 0);
			const cell = 0.005;
			const grid = new Map();
			const k = (x, y, z) => `${Math.floor(x / cell)},${Math.floor(y / cell)},${Math.floor(z / cell)}`;
			for (const p of pts) {
				const key = k(p.x, p.y, p.z);
				if (!grid.has(key)) grid.set(key, []);
				grid.get(key).push(p);
			}
			let close = 0;
			for (const p of pts) {
				const cx = Math.floor(p.x / cell), cy = Math.floor(p.y / cell), cz = Math.floor(p.z / cell);
				for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
					for (const q of grid.get(`${cx + dx},${cy + dy},${cz + dz}`) || []) {
						if (q === p) continue;
						const d = Math.hypot(p.x - q.x, p.y - q.y, p.z - q.z);
						if (d >= 0.001 && d <= 0.005) close++;
					}
				}
			}
			assert.equal(close / 2, 0);
		});

		it(`${classifier}: segments are reported after the snap: every segment end is a vertex of A's and of B's pieces`, () => {
			const r = run(classifier);
			assert.ok(r.segments.length > 0);
			const ka = new Set(), kb = new Set();
			for (const g of ["aInside", "aOutside"]) for (const t of r.groups[g]) for (const v of [t.v0, t.v1, t.v2]) ka.add(F.key(v));
			for (const g of ["bInside", "bOutside"]) for (const t of r.groups[g]) for (const v of [t.v0, t.v1, t.v2]) kb.add(F.key(v));
			for (const s of r.segments) {
				for (const p of [s.p0, s.p1]) {
					assert.ok(ka.has(F.key(p)) && kb.has(F.key(p)), `segment end ${F.key(p)}`);
				}
			}
		});
	}
});

describe("bmsBooleanOp: giant face vs dense seam (floor and fence)", () => {
	const { floor, fence } = F.fenceAndFloor();
	const r = mb.bmsBooleanOp(floor, fence);
	const pieces = [...r.groups.aInside, ...r.groups.aOutside];
	const aspect = (t) => (F.longestEdge(t) ** 2 / F.triArea(t)) / 2.309;

	it("> 100 segments; the floor's pieces tile it and number > 10", () => {
		assert.ok(r.segments.length > 100, `${r.segments.length}`);
		assert.ok(pieces.length > 10);
		assert.ok(Math.abs(F.area(pieces) - 10000) < 1e-6);
	});

	it("fewer than 10 floor pieces of normalised aspect > 100", () => {
		const bad = pieces.filter((t) => aspect(t) > 100).length;
		assert.ok(bad < 10, `${bad} of ${pieces.length} pieces have aspect > 100`);
	});

	it("≥ 95 % of segments are edges of floor pieces", () => {
		const edges = new Set();
		for (const t of pieces) {
			const k = [F.key(t.v0), F.key(t.v1), F.key(t.v2)];
			for (let i = 0; i < 3; i++) edges.add([k[i], k[(i + 1) % 3]].sort().join("|"));
		}
		const hits = r.segments.filter((s) => edges.has([F.key(s.p0), F.key(s.p1)].sort().join("|"))).length;
		assert.ok(hits >= 0.95 * r.segments.length, `${hits} of ${r.segments.length}`);
	});
});

describe("bmsBooleanOp: seams on shared edges and coplanar overlaps", () => {
	it("a seam point on an edge shared with an uncrossed neighbour splits the neighbour too", () => {
		const { square: sq, blade } = F.sharedEdgeCase();
		const r = mb.bmsBooleanOp(sq, blade);
		const at = "2,2,0";
		for (const orig of [0, 1]) {
			const parts = r.megaSoup.filter((t) => t.mesh === "A" && t.origIdx === orig);
			assert.ok(parts.length > 0);
			assert.ok(parts.some((t) => [t.v0, t.v1, t.v2].some((v) => F.key(v) === at)), `piece of square triangle ${orig} at (2,2,0)`);
			assert.ok(Math.abs(F.area(parts) - 8) < 1e-12);
		}
	});

	it("coplanar opposite triangles are both cut along their overlap quad (area 19/12), seam vertices shared, pieces tiling each parent", () => {
		const { a, b } = F.coplanarOpposite();
		const r = mb.bmsBooleanOp(a, b);
		const inTri = (p, t) => {
			const s = (u, v, w) => (v.x - u.x) * (w.y - u.y) - (v.y - u.y) * (w.x - u.x);
			const d1 = s(t.v0, t.v1, p), d2 = s(t.v1, t.v2, p), d3 = s(t.v2, t.v0, p);
			return (d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0);
		};
		const quad = ["1.5,0,0", "3,0,0", "3,1,0"];
		for (const [mesh, parent, other] of [["A", a[0], b[0]], ["B", b[0], a[0]]]) {
			const parts = r.megaSoup.filter((t) => t.mesh === mesh);
			assert.ok(parts.length > 1, mesh);
			assert.ok(Math.abs(F.area(parts) - F.triArea(parent)) < 1e-12, `${mesh} tiles its parent`);
			for (const t of parts) assert.ok(inTri(F.centroid(t), parent), `${mesh} piece inside its parent`);
			const overlap = parts.filter((t) => inTri(F.centroid(t), other));
			assert.ok(Math.abs(F.area(overlap) - 19 / 12) < 1e-12, `${mesh} overlap area ${F.area(overlap)}`);
			const keys = new Set(parts.flatMap((t) => [t.v0, t.v1, t.v2]).map(F.key));
			for (const q of quad) assert.ok(keys.has(q), `${mesh} has seam vertex ${q}`);
			// (7/3, 5/3) is not exactly representable: compare within rounding
			assert.ok(parts.some((t) => [t.v0, t.v1, t.v2].some((v) => Math.abs(v.x - 7 / 3) < 1e-12 && Math.abs(v.y - 5 / 3) < 1e-12)));
		}
	});
});
