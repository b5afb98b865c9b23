// orientSolid (JS_BEHAVIOUR.md section 7): coherent winding per component, outward
// direction for closed components, the reference's diagnostics, input never mutated.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const DIAG = ["windingViolationsBefore", "windingViolationsAfter", "flippedForCoherence", "componentsFlippedForDirection", "components", "closedComponents", "openComponents", "signedVolume"];

const everyThirdFlipped = (soup) => soup.map((t, i) => (i % 3 === 2 ? F.flipTri(t) : t));

describe("orientSolid: geometry", () => {
	it("cube(0,1) with every third triangle flipped: consistent, outward, volume +1", () => {
		const r = mb.orientSolid(everyThirdFlipped(F.cube(0, 1)));
		const e = F.edgeCounts(r.soup);
		assert.equal(e.inconsistent, 0);
		assert.equal(e.open, 0);
		assert.ok(Math.abs(F.signedVolume(r.soup) - 1) < 1e-12);
	});

	it("a fully inverted cube comes out with volume +1", () => {
		const r = mb.orientSolid(F.flipSoup(F.cube(0, 1)));
		assert.ok(Math.abs(F.signedVolume(r.soup) - 1) < 1e-12);
	});

	it("the input is never mutated", () => {
		const s = everyThirdFlipped(F.cube(0, 1));
		const snapshot = JSON.stringify(s);
		mb.orientSolid(s);
		mb.orientSolid(F.flipSoup(s), { coherenceOnly: true });
		assert.equal(JSON.stringify(s), snapshot);
	});

	it("coherenceOnly leaves an inverted cube inverted (volume -1), consistent", () => {
		const r = mb.orientSolid(F.flipSoup(F.cube(0, 1)), { coherenceOnly: true });
		assert.ok(Math.abs(F.signedVolume(r.soup) + 1) < 1e-12);
		assert.equal(F.edgeCounts(r.soup).inconsistent, 0);
	});
});

describe("orientSolid: diagnostics", () => {
	it("has the reference's fields", () => {
		const { diagnostics } = mb.orientSolid(F.cube(0, 1));
		for (const k of DIAG) assert.equal(typeof diagnostics[k], "number", k);
	});

	it("every third flipped: before > 0, after 0, 1 component, 1 closed, volume +1", () => {
		const { diagnostics: d } = mb.orientSolid(everyThirdFlipped(F.cube(0, 1)));
		assert.ok(d.windingViolationsBefore > 0);
		assert.equal(d.windingViolationsAfter, 0);
		assert.equal(d.components, 1);
		assert.equal(d.closedComponents, 1);
		assert.ok(Math.abs(d.signedVolume - 1) < 1e-12);
	});

	it("fully inverted cube: before 0, flippedForCoherence 0, 1 component flipped for direction, volume +1", () => {
		const { diagnostics: d } = mb.orientSolid(F.flipSoup(F.cube(0, 1)));
		assert.equal(d.windingViolationsBefore, 0);
		assert.equal(d.flippedForCoherence, 0);
		assert.equal(d.componentsFlippedForDirection, 1);
		assert.ok(Math.abs(d.signedVolume - 1) < 1e-12);
	});

	it("cube(0,2) oriented twice: the second run flips nothing (volume 8)", () => {
		const once = mb.orientSolid(everyThirdFlipped(F.cube(0, 2)));
		const { diagnostics: d } = mb.orientSolid(once.soup);
		assert.equal(d.flippedForCoherence, 0);
		assert.equal(d.componentsFlippedForDirection, 0);
		assert.equal(d.windingViolationsBefore, 0);
		assert.ok(Math.abs(d.signedVolume - 8) < 1e-12);
	});

	it("patch(10, 3) with alternate triangles flipped: after 0, 1 open component, no direction flip", () => {
		const p = F.patch(10, 3).map((t, i) => (i % 2 === 1 ? F.flipTri(t) : t));
		const r = mb.orientSolid(p);
		assert.equal(r.diagnostics.windingViolationsAfter, 0);
		assert.equal(r.diagnostics.components, 1);
		assert.equal(r.diagnostics.openComponents, 1);
		assert.equal(r.diagnostics.closedComponents, 0);
		assert.equal(r.diagnostics.componentsFlippedForDirection, 0);
		assert.ok(r.diagnostics.windingViolationsBefore > 0);
	});

	it("cube(0,1) + inverted cube((10,0,0),1): 2 components, 2 closed, 1 direction flip, volume 2, after 0", () => {
		const s = [...F.cube(0, 1), ...F.flipSoup(F.cube([10, 0, 0], 1))];
		const r = mb.orientSolid(s);
		const d = r.diagnostics;
		assert.equal(d.components, 2);
		assert.equal(d.closedComponents, 2);
		assert.equal(d.componentsFlippedForDirection, 1);
		assert.ok(Math.abs(d.signedVolume - 2) < 1e-12);
		assert.equal(d.windingViolationsAfter, 0);
		assert.ok(Math.abs(F.signedVolume(r.soup) - 2) < 1e-9);
	});
});
