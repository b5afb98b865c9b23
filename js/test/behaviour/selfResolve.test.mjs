// bmsSelfResolve, bmsSelfResolveIndexed, windingNumber and windingNumberIndexed
// (JS_BEHAVIOUR.md section 11): membranes, the pleated and incoherent prisms (also at UTM
// offsets), nothing to resolve, pre-orientation, the tetrahemihexahedron, winding numbers.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const UTM = [476300, 6771250, 642];

/** Asserts a clean closed solid: closed, manifold, consistent, Euler characteristic 2, volume v. */
function assertCleanSolid(soup, v, tol = 1e-6) {
	const e = F.edgeCounts(soup);
	assert.equal(e.open, 0, "open edges");
	assert.equal(e.nonManifold, 0, "non-manifold edges");
	assert.equal(e.inconsistent, 0, "winding violations");
	assert.equal(e.euler, 2, "Euler characteristic");
	assert.ok(Math.abs(F.signedVolume(soup) - v) < tol, `volume ${F.signedVolume(soup)}`);
}

/** The cube(0,4) with a triangle and its reverse inside at z = 0.3. */
function membraneCube() {
	const m = F.tri([-1, -1, 0.3], [1, -1, 0.3], [0, 1, 0.3]);
	return [...F.cube(0, 4), m, F.flipTri(m)];
}

describe("fixtures of this section", () => {
	it("the pleated prism is closed and manifold on exact keys, volume 2, winding 1 inside and 0 above", () => {
		const p = F.pleatedPrism();
		const e = F.edgeCounts(p);
		assert.equal(e.open + e.nonManifold + e.inconsistent, 0);
		assert.equal(e.euler, 2);
		assert.ok(Math.abs(mb.computeSignedVolume(p) - 2) < 1e-12);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 0.5 }, p) - 1) < 1e-9);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 0.99 }, p) - 1) < 1e-9);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 1.2 }, p)) < 1e-9);
		// three coincident layers over 0.4 ≤ x ≤ 0.6 on the top, and one reversed cap triangle per end
		const top = p.filter((t) => [t.v0, t.v1, t.v2].every((v) => v.z === 1));
		assert.equal(top.length, 6);
		const capsDown = p.filter((t) => [t.v0, t.v1, t.v2].every((v) => v.y === 0) && F.normalOf(t)[1] > 0);
		assert.equal(capsDown.length, 1);
	});

	it("the incoherent prism has winding violations (orientSolid before > 0)", () => {
		assert.ok(mb.orientSolid(F.incoherentPrism()).diagnostics.windingViolationsBefore > 0);
		assert.ok(F.edgeCounts(F.incoherentPrism()).inconsistent > 0);
	});

	it("the tetrahemihexahedron: 10 triangles, every edge in two, Euler characteristic 1", () => {
		const e = F.edgeCounts(F.tetrahemihexahedron());
		assert.equal(e.faces, 10);
		assert.equal(e.open + e.nonManifold, 0);
		assert.equal(e.euler, 1);
	});
});

describe("bmsSelfResolve: geometry", () => {
	it("cube(0,4) with an inner membrane: changed, the 12 cube triangles, clean, volume 64", () => {
		const r = mb.bmsSelfResolve(membraneCube());
		assert.equal(r.changed, true);
		assert.equal(r.soup.length, 12);
		assertCleanSolid(r.soup, 64, 1e-9);
	});

	it("pleated prism: changed, clean box, volume 2, winding 1 at (0.5,1,0.5) and (0.5,1,0.99), 0 at (0.5,1,1.2)", () => {
		const r = mb.bmsSelfResolve(F.pleatedPrism());
		assert.equal(r.changed, true);
		assertCleanSolid(r.soup, 2);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 0.5 }, r.soup) - 1) < 1e-9);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 0.99 }, r.soup) - 1) < 1e-9);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 1.2 }, r.soup)) < 1e-9);
	});

	it("pleated prism offset by (476300, 6771250, 642): volume 2 within 1e-4, output in world coordinates", () => {
		const r = mb.bmsSelfResolve(F.pleatedPrism(UTM));
		assertCleanSolid(r.soup, 2, 1e-4);
		for (const t of r.soup) {
			for (const v of [t.v0, t.v1, t.v2]) {
				assert.ok(v.x >= UTM[0] - 1e-6 && v.x <= UTM[0] + 1 + 1e-6);
				assert.ok(v.y >= UTM[1] - 1e-6 && v.y <= UTM[1] + 2 + 1e-6);
				assert.ok(v.z >= UTM[2] - 1e-6 && v.z <= UTM[2] + 1 + 1e-6);
			}
		}
	});

	it("nothing to resolve (cube(0,2)): changed false, soup is the input array itself", () => {
		const c = F.cube(0, 2);
		const r = mb.bmsSelfResolve(c);
		assert.equal(r.changed, false);
		assert.equal(r.soup, c);
	});

	it("pleated prism with its two bottom triangles reversed (default preOrient): the clean box, volume +2", () => {
		const r = mb.bmsSelfResolve(F.pleatedPrismBottomReversed());
		assertCleanSolid(r.soup, 2);
	});

	it("incoherent prism (default preOrient): the clean box, volume +2, winding 1 inside", () => {
		const r = mb.bmsSelfResolve(F.incoherentPrism());
		assertCleanSolid(r.soup, 2);
		assert.ok(Math.abs(mb.windingNumber({ x: 0.5, y: 1, z: 0.5 }, r.soup) - 1) < 1e-9);
	});

	// [keep] documented difference: the reference pins preOrient: false returning a torn
	// result; refusing (a throw, or the input handed back unchanged), or a correct result, is
	// what meshbool does instead.
	it("[keep] incoherent prism with preOrient: false: refused, or a correct solid (never a torn one)", () => {
		const input = F.incoherentPrism();
		let r;
		try {
			r = mb.bmsSelfResolve(input, { preOrient: false });
		} catch (e) {
			assert.ok(e instanceof Error);
			return;
		}
		// a refusal without throwing: nothing done, the input handed back as it is
		if (r.changed === false && r.soup === input) return;
		assertCleanSolid(r.soup, 2);
	});
});

describe("bmsSelfResolve: diagnostics", () => {
	it("membrane cube: coplanarPairs > 0, orient.windingViolationsAfter 0, orient.signedVolume 64", () => {
		const { diagnostics: d } = mb.bmsSelfResolve(membraneCube());
		assert.ok(d.coplanarPairs > 0);
		assert.equal(d.orient.windingViolationsAfter, 0);
		assert.ok(Math.abs(d.orient.signedVolume - 64) < 1e-9);
	});

	it("pleated prism: coplanarPairs > 0, orient and preOrientFlips present", () => {
		const { diagnostics: d } = mb.bmsSelfResolve(F.pleatedPrism());
		assert.ok(d.coplanarPairs > 0);
		assert.equal(typeof d.orient, "object");
		assert.equal(d.orient.windingViolationsAfter, 0);
		assert.equal(typeof d.preOrientFlips, "number");
	});

	it("incoherent prism: preOrientFlips > 0", () => {
		const { diagnostics: d } = mb.bmsSelfResolve(F.incoherentPrism());
		assert.ok(d.preOrientFlips > 0);
	});

	it("exactSeamSnap appears only when that opt-in snap ran: absent on a clean cube", () => {
		const r = mb.bmsSelfResolve(F.cube(0, 2));
		assert.ok(r.diagnostics && typeof r.diagnostics === "object");
		assert.ok(!("exactSeamSnap" in r.diagnostics));
	});
});

describe("bmsSelfResolveIndexed", () => {
	const DIAG = ["coplanarPairs", "outputTris", "preOrient", "preOrientFlips", "crossingPairs", "preOrientSeamViolations"];

	it("pleated prism → {positions, index, changed, diagnostics}: the clean box", () => {
		const r = mb.bmsSelfResolveIndexed(F.toIndexed(F.pleatedPrism()));
		assert.ok(r.positions instanceof Float64Array && r.index instanceof Uint32Array);
		assert.equal(r.changed, true);
		assertCleanSolid(F.fromIndexed(r), 2);
	});

	it("diagnostics: coplanarPairs, outputTris, preOrient, preOrientFlips, crossingPairs, preOrientSeamViolations", () => {
		const r = mb.bmsSelfResolveIndexed(F.toIndexed(F.pleatedPrism()));
		for (const k of DIAG) assert.ok(k in r.diagnostics, k);
		assert.equal(r.diagnostics.outputTris, r.index.length / 3);
		assert.ok(r.diagnostics.coplanarPairs > 0);
	});

	it("incoherent prism with preOrient: the clean box", () => {
		const r = mb.bmsSelfResolveIndexed(F.toIndexed(F.incoherentPrism()), { preOrient: true });
		assertCleanSolid(F.fromIndexed(r), 2);
	});

	it("incoherent prism with preOrient: diagnostics.preOrient true, preOrientFlips > 0", () => {
		const r = mb.bmsSelfResolveIndexed(F.toIndexed(F.incoherentPrism()), { preOrient: true });
		assert.equal(r.diagnostics.preOrient, true);
		assert.ok(r.diagnostics.preOrientFlips > 0);
	});

	it("clean cube: changed false and the very same typed arrays returned", () => {
		const m = F.toIndexed(F.cube(0, 2));
		const r = mb.bmsSelfResolveIndexed(m);
		assert.equal(r.changed, false);
		assert.equal(r.positions, m.positions);
		assert.equal(r.index, m.index);
	});

	it("tetrahemihexahedron: no throw", () => {
		mb.bmsSelfResolveIndexed(F.toIndexed(F.tetrahemihexahedron()));
		mb.bmsSelfResolve(F.tetrahemihexahedron());
	});

	it("tetrahemihexahedron: crossingPairs > 0 and preOrientSeamViolations > 0 (non-orientability flagged)", () => {
		const r = mb.bmsSelfResolveIndexed(F.toIndexed(F.tetrahemihexahedron()));
		assert.ok(r.diagnostics.crossingPairs > 0);
		assert.ok(r.diagnostics.preOrientSeamViolations > 0);
	});
});

describe("windingNumber and windingNumberIndexed", () => {
	const c = F.cube(0, 2);
	const nested = [...F.cube(0, 2), ...F.cube(0, 6)];

	it("1 inside and 0 outside cube(0,2) (1e-9)", () => {
		assert.ok(Math.abs(mb.windingNumber({ x: 0.1, y: -0.2, z: 0.3 }, c) - 1) < 1e-9);
		assert.ok(Math.abs(mb.windingNumber({ x: 3, y: 0.2, z: -0.1 }, c)) < 1e-9);
		const m = F.toIndexed(c);
		assert.ok(Math.abs(mb.windingNumberIndexed(0.1, -0.2, 0.3, m.positions, m.index) - 1) < 1e-9);
		assert.ok(Math.abs(mb.windingNumberIndexed(3, 0.2, -0.1, m.positions, m.index)) < 1e-9);
	});

	it("2 inside two nested cubes, 1 between them", () => {
		assert.ok(Math.abs(mb.windingNumber({ x: 0.1, y: 0.2, z: 0.3 }, nested) - 2) < 1e-9);
		assert.ok(Math.abs(mb.windingNumber({ x: 2, y: 0.2, z: 0.3 }, nested) - 1) < 1e-9);
		const m = F.toIndexed(nested);
		assert.ok(Math.abs(mb.windingNumberIndexed(0.1, 0.2, 0.3, m.positions, m.index) - 2) < 1e-9);
		assert.ok(Math.abs(mb.windingNumberIndexed(2, 0.2, 0.3, m.positions, m.index) - 1) < 1e-9);
	});

	it("solidAngle and solidAngleAt agree, and sum to 4π over a closed cube from inside", () => {
		const p = { x: 0.1, y: 0.2, z: -0.3 };
		let sum = 0;
		for (const t of c) {
			const a = mb.solidAngle(p, t);
			const b = mb.solidAngleAt(p.x, p.y, p.z, t.v0.x, t.v0.y, t.v0.z, t.v1.x, t.v1.y, t.v1.z, t.v2.x, t.v2.y, t.v2.z);
			assert.ok(Math.abs(a - b) < 1e-12);
			sum += a;
		}
		assert.ok(Math.abs(sum - 4 * Math.PI) < 1e-9);
	});
});
