// cancelCoincidentFaces (JS_BEHAVIOUR.md section 9): only oppositely wound coincident
// pairs go; survivors are the caller's own triangle objects; tolerance welds first.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

describe("cancelCoincidentFaces", () => {
	it("T, reversed T and a far triangle → exactly [the far triangle object]", () => {
		const [t] = F.T();
		const far = F.tri([10, 10, 10], [11, 10, 10], [10, 11, 10]);
		const out = mb.cancelCoincidentFaces([t, F.flipTri(t), far]);
		assert.equal(out.length, 1);
		assert.equal(out[0], far);
	});

	it("vertices within tolerance count as equal: T vs its reverse with corners moved 1e-7, tolerance 1e-4 → []", () => {
		const [t] = F.T();
		const moved = F.flipTri(t);
		moved.v0.x += 1e-7;
		moved.v1.y -= 1e-7;
		moved.v2.z += 1e-7;
		assert.deepEqual(mb.cancelCoincidentFaces([t, moved], 1e-4), []);
	});

	it("same-winding duplicates are kept (2 stay 2)", () => {
		const out = mb.cancelCoincidentFaces([...F.T(), ...F.T()]);
		assert.equal(out.length, 2);
	});

	it("a clean tetra is untouched: the same 4 objects, closed", () => {
		const t = F.tetra();
		const out = mb.cancelCoincidentFaces(t);
		assert.equal(out.length, 4);
		out.forEach((x, i) => assert.equal(x, t[i]));
		assert.equal(F.edgeCounts(out).open, 0);
	});

	it("tetra plus both windings of a copy of one face → closed, manifold, no coincident pair left", () => {
		const t = F.tetra();
		const s = [...t, F.copySoup([t[0]])[0], F.flipTri(t[0])];
		const out = mb.cancelCoincidentFaces(s);
		const e = F.edgeCounts(out);
		assert.equal(out.length, 4);
		assert.equal(e.open, 0);
		assert.equal(e.nonManifold, 0);
		assert.equal(e.inconsistent, 0);
		assert.equal(new Set(out.map(F.triSetKey)).size, out.length);
		assert.ok(Math.abs(F.signedVolume(out) - 1 / 6) < 1e-12);
		for (const x of out) assert.ok(s.includes(x));
	});
});
