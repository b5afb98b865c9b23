// assessRepair and describeAssessment (JS_BEHAVIOUR.md section 5): the assessment's
// shape, "keep" only when violations strictly fall, damage lines for duplicates, opened
// meshes and (against a sound baseline only) volume.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

describe("assessRepair", () => {
	it("returns {harmful, recommend, benefits, damage, before, after, violationsBefore, violationsAfter, trisDelta, volumeDeltaPct}", () => {
		const a = mb.assessRepair(F.T(), F.T());
		for (const k of ["harmful", "recommend", "benefits", "damage", "before", "after", "violationsBefore", "violationsAfter", "trisDelta", "volumeDeltaPct"]) {
			assert.ok(k in a, k);
		}
		assert.ok(Array.isArray(a.benefits) && Array.isArray(a.damage));
	});

	it("both soups measured at the same tolerance: before/after stats count each one's triangles", () => {
		const before = F.tjunctionStrip(), after = mb.resolveTJunctionsHoleFree(before);
		const a = mb.assessRepair(before, after, { tolerance: 1e-4 });
		assert.equal(a.before.stats.triangles, before.length);
		assert.equal(a.after.stats.triangles, after.length);
		assert.equal(a.trisDelta, after.length - before.length);
	});

	it('strip → hole-free resolved strip: violations fall, "keep", benefits non-empty', () => {
		const before = F.tjunctionStrip();
		const a = mb.assessRepair(before, mb.resolveTJunctionsHoleFree(before));
		assert.ok(a.violationsAfter < a.violationsBefore);
		assert.equal(a.recommend, "keep");
		assert.equal(a.harmful, false);
		assert.ok(a.benefits.length > 0);
	});

	it('T → T + duplicate: "discard", harmful, a damage line naming noDuplicateTriangles', () => {
		const a = mb.assessRepair(F.T(), [...F.T(), ...F.T()]);
		assert.equal(a.recommend, "discard");
		assert.equal(a.harmful, true);
		assert.ok(a.damage.some((d) => d.includes("noDuplicateTriangles")));
	});

	it('no-op (T → T): equal counts, "discard"', () => {
		const a = mb.assessRepair(F.T(), F.T());
		assert.equal(a.violationsAfter, a.violationsBefore);
		assert.equal(a.recommend, "discard");
	});

	it('tetra → its first 3 faces: harmful, a damage line containing "Opens the mesh"', () => {
		const t = F.tetra();
		const a = mb.assessRepair(t, t.slice(0, 3));
		assert.equal(a.harmful, true);
		assert.ok(a.damage.some((d) => d.includes("Opens the mesh")));
	});

	it("volume is judged only against a sound baseline: T → T + a far triangle has no volume damage line", () => {
		const a = mb.assessRepair(F.T(), [...F.T(), F.tri([100, 0, 0], [101, 0, 0], [100, 1, 5])]);
		assert.ok(!a.damage.some((d) => /volume/i.test(d)));
	});
});

describe("describeAssessment", () => {
	it("renders an assessment as text naming the recommendation and the damage", () => {
		const a = mb.assessRepair(F.T(), [...F.T(), ...F.T()]);
		const s = mb.describeAssessment(a);
		assert.equal(typeof s, "string");
		assert.ok(/discard/i.test(s));
		assert.ok(s.includes("noDuplicateTriangles"));
	});
});
