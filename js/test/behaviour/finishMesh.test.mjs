// finishMesh and DEFAULT_STAGES (JS_BEHAVIOUR.md section 6): gated stages, the report,
// harmful, throwing and empty stages, force, the empty soup, violations never rising.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

describe("DEFAULT_STAGES", () => {
	it("are dedupCoincident, resolveTJunctionsHoleFree, orientWinding as {name, run}", () => {
		assert.deepEqual(mb.DEFAULT_STAGES.map((s) => s.name), ["dedupCoincident", "resolveTJunctionsHoleFree", "orientWinding"]);
		for (const s of mb.DEFAULT_STAGES) assert.equal(typeof s.run, "function");
	});
});

describe("finishMesh", () => {
	it("returns {soup, ok, before, after, applied, skipped, stages}", () => {
		const r = mb.finishMesh(F.tjunctionStrip());
		for (const k of ["soup", "ok", "before", "after", "applied", "skipped", "stages"]) assert.ok(k in r, k);
		assert.ok(Array.isArray(r.applied) && Array.isArray(r.skipped) && Array.isArray(r.stages));
	});

	it("strip with tolerance 1e-4: ok, after.ok, 0 violations, resolveTJunctionsHoleFree applied, area kept", () => {
		const strip = F.tjunctionStrip();
		const r = mb.finishMesh(strip, { tolerance: 1e-4 });
		assert.equal(r.ok, true);
		assert.equal(r.after.ok, true);
		assert.equal(mb.violationCount(r.after), 0);
		assert.ok(r.applied.includes("resolveTJunctionsHoleFree"));
		assert.ok(Math.abs(F.area(r.soup) - 70) < 1e-9);
	});

	it("tetra: ok, nothing applied, soup is the input array itself", () => {
		const t = F.tetra();
		const r = mb.finishMesh(t);
		assert.equal(r.ok, true);
		assert.deepEqual(r.applied, []);
		assert.equal(r.soup, t);
	});

	it('a stage appending a duplicate: the input itself comes back, skipped "would damage the mesh"', () => {
		const t = F.tetra();
		const dup = { name: "dup", run: (s) => [...s, s[0]] };
		const r = mb.finishMesh(t, { stages: [dup] });
		assert.equal(r.soup, t);
		assert.deepEqual(r.applied, []);
		assert.equal(r.skipped.length, 1);
		assert.equal(r.skipped[0].stage, "dup");
		assert.equal(r.skipped[0].reason, "would damage the mesh");
	});

	it("with force the duplicating stage is applied and violations rise", () => {
		const t = F.tetra();
		const dup = { name: "dup", run: (s) => [...s, s[0]] };
		const r = mb.finishMesh(t, { stages: [dup], force: true });
		assert.deepEqual(r.applied, ["dup"]);
		assert.equal(r.soup.length, 5);
		assert.ok(mb.violationCount(r.after) > mb.violationCount(r.before));
	});

	it('a stage that throws: no throw, ok, reason "threw", violations holds the message', () => {
		const boom = { name: "boom", run: () => { throw new Error("boom went the stage"); } };
		const r = mb.finishMesh(F.tetra(), { stages: [boom] });
		assert.equal(r.ok, true);
		assert.equal(r.skipped[0].reason, "threw");
		assert.ok(String(r.skipped[0].violations).includes("boom went the stage"));
	});

	it('a stage returning [] or nothing: reason "produced nothing"', () => {
		for (const run of [() => [], () => undefined]) {
			const r = mb.finishMesh(F.tetra(), { stages: [{ name: "empty", run }] });
			assert.equal(r.skipped[0].reason, "produced nothing");
			assert.equal(r.soup.length, 4);
		}
	});

	it("stages run on a copy: a stage mutating its argument does not change the input", () => {
		const t = F.tetra();
		const snapshot = JSON.stringify(t);
		const mutate = { name: "mutate", run: (s) => { s[0].v0.x = 99; s.pop(); return s; } };
		mb.finishMesh(t, { stages: [mutate] });
		assert.equal(JSON.stringify(t), snapshot);
	});

	it("empty soup: ok false, soup [], no throw", () => {
		const r = mb.finishMesh([]);
		assert.equal(r.ok, false);
		assert.deepEqual(r.soup, []);
	});

	it("violations never rise (tetra, strips of 8 and 3 cells, T)", () => {
		for (const [name, soup] of [["tetra", F.tetra()], ["strip 8", F.tjunctionStrip(8)], ["strip 3", F.tjunctionStrip(3)], ["T", F.T()]]) {
			const r = mb.finishMesh(soup);
			assert.ok(mb.violationCount(r.after) <= mb.violationCount(r.before), name);
			assert.ok(mb.violationCount(r.after) <= mb.violationCount(mb.verifyOutput(soup)), name);
		}
	});
});
