// T-junction repair (JS_BEHAVIOUR.md section 10): resolveTJunctionsHoleFree, the legacy
// resolveTJunctions, and repairMesh with removeDegenerate on the strip.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const count = (soup, name) => mb.verifyOutput(soup).checks.find((c) => c.check === name).count;
const allUp = (soup) => soup.every((t) => F.normalOf(t)[2] > 0);

describe("resolveTJunctionsHoleFree", () => {
	it("on the strip: adds triangles, all normals stay +z, area unchanged (1e-6)", () => {
		const s = F.tjunctionStrip();
		const out = mb.resolveTJunctionsHoleFree(s);
		assert.ok(out.length > s.length);
		assert.ok(allUp(out));
		assert.ok(Math.abs(F.area(out) - F.area(s)) < 1e-6);
	});

	for (const kind of ["edge", "diagonal"]) {
		it(`3-triangle patch with a mid-edge vertex (${kind}): 0 T-junctions, 0 degenerate, 0 coincident, open edges not increased, area kept`, () => {
			const s = F.midEdgePatch(kind);
			const out = mb.resolveTJunctionsHoleFree(s);
			assert.equal(count(out, "noTJunctions"), 0);
			assert.equal(count(out, "noDegenerateTriangles"), 0);
			assert.equal(count(out, "noDuplicateTriangles"), 0);
			assert.ok(F.edgeCounts(out).open <= F.edgeCounts(s).open);
			assert.ok(Math.abs(F.area(out) - F.area(s)) < 1e-9);
			assert.ok(allUp(out));
			assert.ok(count(s, "noTJunctions") > 0, "the fixture has a T-junction");
		});

		it(`3-triangle patch (${kind}): idempotent`, () => {
			const once = mb.resolveTJunctionsHoleFree(F.midEdgePatch(kind));
			const twice = mb.resolveTJunctionsHoleFree(once);
			assert.deepEqual(F.soupKeys(twice, F.triOrientedKey), F.soupKeys(once, F.triOrientedKey));
		});
	}

	it("tetra unchanged", () => {
		const t = F.tetra();
		assert.deepEqual(F.soupKeys(mb.resolveTJunctionsHoleFree(t), F.triOrientedKey), F.soupKeys(t, F.triOrientedKey));
	});

	it("a 30×30 grid of 30 m cells at x, y ≈ 478,000 plus one T-junction triangle: < 3 s, ≥ n − 5 triangles kept", () => {
		const s = F.utmGridWithTJunction();
		const t0 = performance.now();
		const out = mb.resolveTJunctionsHoleFree(s);
		const ms = performance.now() - t0;
		assert.ok(ms < 3000, `${ms} ms`);
		assert.ok(out.length >= s.length - 5);
		assert.equal(count(out, "noTJunctions"), 0);
		assert.ok(Math.abs(F.area(out) - F.area(s)) < 1e-3);
	});
});

describe("repairMesh removeDegenerate on the strip", () => {
	it("all normals +z, area kept (1e-4)", async () => {
		const s = F.tjunctionStrip();
		const r = await mb.repairMesh(s, { removeDegenerate: true });
		assert.ok(r.soup.length > 0);
		assert.ok(allUp(r.soup));
		assert.ok(Math.abs(F.area(r.soup) - F.area(s)) < 1e-4);
	});
});

describe("legacy resolveTJunctions", () => {
	// [keep] documented difference: the reference pins its legacy resolveTJunctions
	// flipping some triangles (a bug); meshbool's keeps every triangle's orientation.
	it("[keep] splits the strip's T-junctions and flips nothing", () => {
		const s = F.tjunctionStrip();
		const out = mb.resolveTJunctions(s);
		assert.ok(out.length > s.length);
		assert.ok(allUp(out));
		assert.equal(count(out, "noTJunctions"), 0);
		assert.ok(Math.abs(F.area(out) - F.area(s)) < 1e-6);
	});
});
