// closeSolid and repairMesh's closeMode "closeSolid" (JS_BEHAVIOUR.md section 8): weld,
// cap small boundary loops only, list the large ones, split pinched boundaries, never
// delete, diagnostics.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const keysOf = (t) => [t.v0, t.v1, t.v2].map(F.key);
const shared = (a, b) => {
	const s = new Set(keysOf(a));
	return keysOf(b).filter((k) => s.has(k));
};

describe("closeSolid", () => {
	it("diagnostics: closed, openEdges, capTriangles, cappedLoops, skippedLargeLoops, nonManifoldEdges", () => {
		const { diagnostics: d } = mb.closeSolid(F.cube(0, 2).slice(1));
		assert.equal(typeof d.closed, "boolean");
		for (const k of ["openEdges", "capTriangles", "cappedLoops", "nonManifoldEdges"]) assert.equal(typeof d[k], "number", k);
		assert.ok(Array.isArray(d.skippedLargeLoops));
	});

	it("a closed cube: closed, 0 open edges, 0 caps, 12 triangles", () => {
		const r = mb.closeSolid(F.cube(0, 2));
		assert.equal(r.diagnostics.closed, true);
		assert.equal(r.diagnostics.openEdges, 0);
		assert.equal(r.diagnostics.capTriangles, 0);
		assert.equal(r.soup.length, 12);
	});

	it("cube minus one triangle: closed, 1 loop capped with 1 triangle, 12 triangles, volume 8, input unchanged", () => {
		const s = F.cube(0, 2).slice(1);
		const snapshot = JSON.stringify(s);
		const r = mb.closeSolid(s);
		assert.equal(r.diagnostics.closed, true);
		assert.equal(r.diagnostics.cappedLoops, 1);
		assert.equal(r.diagnostics.capTriangles, 1);
		assert.equal(r.soup.length, 12);
		assert.equal(s.length, 11);
		assert.equal(JSON.stringify(s), snapshot);
		const e = F.edgeCounts(r.soup);
		assert.equal(e.open + e.nonManifold + e.inconsistent, 0);
		assert.ok(Math.abs(F.signedVolume(r.soup) - 8) < 1e-9);
	});

	it("patch(100, 20) (80-vertex rim): not closed, 0 caps, skippedLargeLoops [80], triangle count unchanged", () => {
		const p = F.patch(100, 20);
		const r = mb.closeSolid(p);
		assert.equal(r.diagnostics.closed, false);
		assert.equal(r.diagnostics.capTriangles, 0);
		assert.deepEqual(r.diagnostics.skippedLargeLoops, [80]);
		assert.equal(r.soup.length, p.length);
	});

	it("patch(10, 2) (8-vertex rim): no caps with maxCapLoopVerts 4, caps with 16", () => {
		const p = F.patch(10, 2);
		const small = mb.closeSolid(p, { maxCapLoopVerts: 4 });
		assert.equal(small.diagnostics.capTriangles, 0);
		assert.equal(small.soup.length, 8);
		assert.deepEqual(small.diagnostics.skippedLargeLoops, [8]);
		const big = mb.closeSolid(p, { maxCapLoopVerts: 16 });
		assert.ok(big.diagnostics.capTriangles > 0);
		assert.equal(big.diagnostics.cappedLoops, 1);
		assert.equal(big.soup.length, 8 + big.diagnostics.capTriangles);
	});

	it("pinch holes: cube minus any two triangles sharing exactly one vertex (30 pairs) → closed, 0 open edges", () => {
		const c = F.cube(0, 2);
		const pairs = [];
		for (let i = 0; i < 12; i++) for (let j = i + 1; j < 12; j++) if (shared(c[i], c[j]).length === 1) pairs.push([i, j]);
		assert.equal(pairs.length, 30);
		const bad = [];
		for (const [i, j] of pairs) {
			const r = mb.closeSolid(c.filter((_, k) => k !== i && k !== j));
			const e = F.edgeCounts(r.soup);
			if (!(r.diagnostics.closed && r.diagnostics.openEdges === 0 && e.open === 0 && e.nonManifold === 0)) bad.push(`${i},${j}`);
		}
		assert.deepEqual(bad, []);
	});

	it("three holes meeting at one vertex → closed, 0 open edges", () => {
		const c = F.cube(0, 2);
		const triples = [];
		for (let i = 0; i < 12; i++) for (let j = i + 1; j < 12; j++) for (let k = j + 1; k < 12; k++) {
			const a = shared(c[i], c[j]), b = shared(c[j], c[k]), d = shared(c[i], c[k]);
			if (a.length === 1 && b.length === 1 && d.length === 1 && a[0] === b[0] && b[0] === d[0]) triples.push([i, j, k]);
		}
		assert.ok(triples.length > 0);
		for (const [i, j, k] of triples) {
			const r = mb.closeSolid(c.filter((_, n) => n !== i && n !== j && n !== k));
			assert.equal(r.diagnostics.closed, true, `${i},${j},${k}`);
			assert.equal(r.diagnostics.openEdges, 0);
			assert.equal(F.edgeCounts(r.soup).nonManifold, 0);
		}
	});

	it("welds within snapTolerance first: a cube whose corner copies are 1e-5 off closes", () => {
		const c = F.cube(0, 2);
		c[3] = { ...c[3], v1: { x: c[3].v1.x + 1e-5, y: c[3].v1.y, z: c[3].v1.z } };
		const r = mb.closeSolid(c);
		assert.equal(r.diagnostics.closed, true);
		assert.equal(r.soup.length, 12);
	});
});

describe('repairMesh closeMode "closeSolid"', () => {
	it("runs closeSolid and returns its diagnostics with the soup (cube minus one triangle → closed, 12)", async () => {
		const r = await mb.repairMesh(F.cube(0, 2).slice(1), { closeMode: "closeSolid", snapTolerance: 0.001 });
		assert.equal(r.soup.length, 12);
		assert.ok(r.diagnostics);
		assert.equal(r.diagnostics.closed, true);
	});
});
