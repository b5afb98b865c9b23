// Vertex identity and input conditioning (JS_BEHAVIOUR.md section 0), across
// findConnectedComponents, findConnectedComponentsPooled, countOpenEdges, verifyOutput,
// bmsBooleanOp, booleanAuto and boolean: corners that differ only by float rounding are
// one vertex, corner-touching coplanar sheets are not self-intersections, non-manifold
// operands are taken as given.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

describe("vertex identity: float rounding is one vertex", () => {
	const big = F.patch(1000, 316);

	it("the patch fixture really has rounding-different shared corners", () => {
		// (a check of the fixture: exact keys split it apart)
		assert.equal(big.length, 199712);
		assert.ok(F.edgeComponents(big).length > 1);
	});

	it("patch(1000, 316) is one component for findConnectedComponents", () => {
		const comps = mb.findConnectedComponents(big);
		assert.equal(comps.length, 1);
		assert.equal(comps[0].length, 199712);
	});

	it("patch(1000, 316) is one component of 199,712 triangles for findConnectedComponentsPooled", () => {
		const comps = mb.findConnectedComponentsPooled(big);
		assert.equal(comps.length, 1);
		assert.equal(comps[0].length, 199712);
	});

	it("patch(1000, 316) edge counts: only the rim is open", () => {
		const c = mb.countOpenEdges(big);
		assert.equal(c.openEdges, 4 * 316);
		assert.equal(c.overShared, 0);
	});

	it("verifyOutput counts patch(8, 5) as one sheet with a 20-edge rim", () => {
		const r = mb.verifyOutput(F.patch(8, 5));
		assert.equal(r.stats.openEdges, 20);
		assert.equal(r.stats.components, 1);
		assert.equal(r.stats.vertices, 36);
	});

	/** cube(0,2) with the first corner of triangle 0 moved by rounding-sized amounts. */
	const nudged = (dx, dz) => {
		const c = F.cube(0, 2);
		const v = c[0].v0; // (-1, -1, -1)
		c[0].v0 = { x: v.x * dx, y: v.y, z: v.z * dz };
		assert.notEqual(c[0].v0.x, v.x);
		return c;
	};

	it("a cube with one corner copy a few ulps off is closed and one component (countOpenEdges, findConnectedComponents)", () => {
		const c = nudged(1 + 2 * Number.EPSILON, 1 - Number.EPSILON);
		const e = mb.countOpenEdges(c);
		assert.equal(e.openEdges, 0);
		assert.equal(e.overShared, 0);
		assert.equal(mb.findConnectedComponents(c).length, 1);
		assert.equal(mb.findConnectedComponentsPooled(c).length, 1);
	});

	it("verifyOutput takes a corner copy a few ulps off as the same vertex", () => {
		const r = mb.verifyOutput(nudged(1 + 2 * Number.EPSILON, 1 - Number.EPSILON), { expectClosed: true });
		assert.equal(r.stats.openEdges, 0);
		assert.equal(r.ok, true);
	});

	// Documented difference: the reference welds within 1e-6 × the mean edge when no
	// tolerance is given; meshbool's rule merges rounding noise only (a few units in the
	// last place), so a 1e-10 gap on a cube of edge 2 is geometry until the caller names a
	// tolerance.
	it("a corner copy 1e-10 off is a gap without a tolerance and the same vertex within one", () => {
		const c = F.cube(0, 2);
		const v = c[0].v0;
		c[0].v0 = { x: v.x + 1e-10, y: v.y, z: v.z };
		assert.equal(mb.countOpenEdges(c).openEdges, 4);
		assert.equal(mb.verifyOutput(c).stats.openEdges, 4);
		assert.equal(mb.verifyOutput(c, { tolerance: 1e-9 }).stats.openEdges, 0);
	});
});

describe("input conditioning of boolean operands", () => {
	it("corner-touching coplanar squares (diagonal sheet) are not self-intersections: bmsBooleanOp proceeds", () => {
		const r = mb.bmsBooleanOp(F.diagonalSheet(), F.box5(), "subtract");
		assert.ok(r.groups.aInside.length > 0);
		assert.ok(r.groups.aOutside.length > 0);
	});

	it("a patch grid with rounding-different corners is accepted as an operand (boolean)", () => {
		const r = mb.boolean(F.patch(8, 5), F.cube(0, 2), "subtract");
		assert.ok(r !== null && r.soup.length > 0);
	});

	it("a patch grid is accepted by bmsBooleanOp and splits the cube", () => {
		const r = mb.bmsBooleanOp(F.patch(8, 5), F.cube(0, 2));
		assert.ok(r.groups.bInside.length > 0 && r.groups.bOutside.length > 0);
	});

	it("a non-manifold operand (cube with a fin) is classified, not refused", () => {
		const r = mb.bmsBooleanOp(F.finnedCube(), F.cube([1, 1, 1], 2), "union");
		for (const g of ["aInside", "aOutside", "bInside", "bOutside"]) assert.ok(r.groups[g].length > 0, g);
		assert.ok(r.result.soup.length > 0);
	});

	it("booleanAuto takes the diagonal sheet against the box", () => {
		const r = mb.booleanAuto(F.diagonalSheet(), F.box5(), "intersect");
		assert.ok(r.soup.length > 0);
	});
});
