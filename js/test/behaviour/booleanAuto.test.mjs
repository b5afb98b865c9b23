// booleanAuto (JS_BEHAVIOUR.md section 1), with violationCount, verifyOutput and
// finishMesh as its report: the operation argument, the return shape, open grids against
// closed boxes, quality "raw" and "strict", operands provably apart.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const OPS = ["union", "intersect", "subtract"];

describe("booleanAuto: the operation", () => {
	for (const op of [null, undefined, ""]) {
		it(`op ${JSON.stringify(op)} throws an Error saying it requires an operation`, () => {
			assert.throws(() => mb.booleanAuto(F.cube(0, 2), F.cube([1, 1, 1], 2), op), (e) => e instanceof Error && /requires an operation/.test(e.message));
		});
	}
});

describe("booleanAuto: return shape", () => {
	const A = F.cube(0, 2), B = F.cube([1, 1, 1], 2);

	for (const op of OPS) {
		it(`${op}: {soup, ok, operation, report, verification, classifier, boolean}, operation echoes op`, () => {
			const r = mb.booleanAuto(A, B, op);
			for (const k of ["soup", "ok", "operation", "report", "verification", "classifier", "boolean"]) assert.ok(k in r, k);
			assert.equal(r.operation, op);
			assert.ok(Array.isArray(r.soup) && r.soup.length > 0);
			assert.equal(typeof r.ok, "boolean");
			assert.ok(r.boolean && r.boolean.groups, "boolean is the bmsBooleanOp result");
			for (const g of ["aInside", "aOutside", "bInside", "bOutside"]) assert.ok(Array.isArray(r.boolean.groups[g]), g);
		});
	}

	it("classifier is truthy: the {A, B} labels of bmsBooleanOp", () => {
		const r = mb.booleanAuto(A, B, "union");
		assert.ok(r.classifier);
		assert.equal(typeof r.classifier.A, "string");
		assert.equal(typeof r.classifier.B, "string");
		assert.deepEqual(r.classifier, r.boolean.classifier);
	});

	it("verification is bmsBooleanOp's", () => {
		const r = mb.booleanAuto(A, B, "union");
		assert.ok(r.verification, "crossing cubes under auto have a verification");
		assert.deepEqual(r.verification, r.boolean.verification);
	});

	it("cube(0,2) minus cube((1,0,0),2) is non-empty, volume 4", () => {
		const r = mb.booleanAuto(F.cube(0, 2), F.cube([1, 0, 0], 2), "subtract");
		assert.ok(r.soup.length > 0);
		assert.ok(Math.abs(F.signedVolume(r.soup) - 4) < 1e-9);
	});

	it("cube(0,2) and cube((1,1,1),2): exact volumes 15, 1, 7", () => {
		const want = { union: 15, intersect: 1, subtract: 7 };
		for (const op of OPS) {
			const r = mb.booleanAuto(A, B, op);
			assert.ok(Math.abs(F.signedVolume(r.soup) - want[op]) < 1e-9, `${op}: ${F.signedVolume(r.soup)}`);
			const e = F.edgeCounts(r.soup);
			assert.equal(e.open, 0, op);
			assert.equal(e.nonManifold, 0, op);
		}
	});
});

describe("booleanAuto: 6×6 grid against a box", () => {
	const { grid, box } = F.gridAndBox();

	for (const op of OPS) {
		it(`${op}: non-empty soup, ok`, () => {
			const r = mb.booleanAuto(grid, box, op);
			assert.ok(r.soup.length > 0);
			assert.equal(r.ok, true);
		});
		it(`${op} with tolerance 1e-5: non-empty soup, ok`, () => {
			const r = mb.booleanAuto(grid, box, op, { tolerance: 1e-5 });
			assert.ok(r.soup.length > 0);
			assert.equal(r.ok, true);
		});
	}

	it("the grid's pieces keep the grid's area (union keeps all of it outside, intersect the 3×3 inside)", () => {
		// The box's footprint on z = 0 is [1.5, 4.5]²: 9 of the grid's 36 square units.
		const inter = mb.booleanAuto(grid, box, "intersect", { quality: "raw" });
		const gridPart = inter.boolean.groups.aInside;
		assert.ok(Math.abs(F.area(gridPart) - 9) < 1e-9);
		assert.ok(Math.abs(F.area(inter.boolean.groups.aOutside) - 27) < 1e-9);
	});

	it('quality "raw": no finishing, report null, non-empty soup', () => {
		for (const op of OPS) {
			const r = mb.booleanAuto(grid, box, op, { quality: "raw" });
			assert.equal(r.report, null, op);
			assert.ok(r.soup.length > 0, op);
		}
	});

	it('default quality ("strict"): report is the finishMesh result', () => {
		const r = mb.booleanAuto(grid, box, "union");
		assert.ok(r.report);
		for (const k of ["soup", "ok", "before", "after", "applied", "skipped"]) assert.ok(k in r.report, k);
		assert.ok(Array.isArray(r.report.applied) && Array.isArray(r.report.skipped));
		assert.equal(r.report.soup, r.soup);
	});

	it("strict: violationCount(report.after) is 0 for subtract", () => {
		const r = mb.booleanAuto(grid, box, "subtract");
		assert.equal(mb.violationCount(r.report.after), 0);
	});

	it("strict: violations never above the raw soup's, for every op", () => {
		for (const op of OPS) {
			const raw = mb.booleanAuto(grid, box, op, { quality: "raw" });
			const strict = mb.booleanAuto(grid, box, op);
			assert.ok(mb.violationCount(strict.report.after) <= mb.violationCount(mb.verifyOutput(raw.soup)), op);
		}
	});
});

describe("booleanAuto: operands provably apart", () => {
	const grid4 = F.grid(4, 4, 1);
	const far = F.cube([500, 500, 500], 2);

	// The spec names no operation here; "intersect" is the one whose result is empty under
	// any reading (a union or difference of apart operands keeps them).
	it("intersect: no throw, soup [], ok false, verification null", () => {
		const r = mb.booleanAuto(grid4, far, "intersect");
		assert.deepEqual(r.soup, []);
		assert.equal(r.ok, false);
		assert.equal(r.verification, null);
	});
});
