// Components and indexed groups (JS_BEHAVIOUR.md section 12): splitToComponents (also
// pooled), decomposeIndexedGroups, indexGroups, indexGroupsToTypedArrays,
// findConnectedComponentsPooled, connectedComponentsIndexed, mergeSmallIndexedComponents.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as mb from "../../src/index.js";
import * as F from "./fixtures.mjs";

const GROUPS = ["aInside", "aOutside", "bInside", "bOutside"];
const groupOf = (c) => (c.mesh === "A" ? "a" : "b") + (c.side === "inside" ? "Inside" : "Outside");

/** Two disjoint cubes crossed by one long bar: several components per group. */
function groups() {
	const A = [...F.cube(0, 2), ...F.cube([5, 0, 0], 2)];
	const B = F.box(-0.5, -0.5, -0.5, 5.5, 0.5, 0.5);
	return mb.splitMeshPair(A, B).groups;
}

/** Components as a sorted list of "group: sorted triangle keys". */
function signature(comps, soupOf = (c) => c.soup) {
	return comps.map((c) => `${groupOf(c)}: ${F.soupKeys(soupOf(c)).join(";")}`).sort();
}

describe("splitToComponents", () => {
	it("the fixture has several components per group", () => {
		const comps = mb.splitToComponents(groups());
		assert.equal(comps.filter((c) => c.mesh === "A" && c.side === "inside").length, 2);
		assert.equal(comps.filter((c) => c.mesh === "B" && c.side === "inside").length, 2);
		assert.equal(comps.filter((c) => c.mesh === "A" && c.side === "outside").length, 2);
		assert.equal(comps.filter((c) => c.mesh === "B" && c.side === "outside").length, 1);
		for (const c of comps) assert.equal(c.triCount, c.soup.length);
	});

	it("{pooled: true} equals the default (multiset of components)", () => {
		const g = groups();
		assert.deepEqual(signature(mb.splitToComponents(g, { pooled: true })), signature(mb.splitToComponents(g)));
	});

	it("largest first within each group", () => {
		const comps = mb.splitToComponents(groups());
		for (const g of GROUPS) {
			const sizes = comps.filter((c) => groupOf(c) === g).map((c) => c.triCount);
			assert.deepEqual(sizes, [...sizes].sort((p, q) => q - p), g);
		}
	});
});

describe("decomposeIndexedGroups", () => {
	const g = groups();
	const indexed = mb.indexGroups(g);
	const entries = mb.decomposeIndexedGroups(indexed);
	const soupOf = (e) => e.triangles.map(([i, j, k]) => ({ v0: e.points[i], v1: e.points[j], v2: e.points[k] }));

	it("entries {mesh, side, points, triangles: [[i,j,k]]} with indices into the entry's points", () => {
		assert.ok(entries.length > 0);
		for (const e of entries) {
			assert.ok(e.mesh === "A" || e.mesh === "B");
			assert.ok(e.side === "inside" || e.side === "outside");
			assert.ok(Array.isArray(e.points) && Array.isArray(e.triangles));
			for (const t of e.triangles) {
				assert.equal(t.length, 3);
				for (const i of t) assert.ok(Number.isInteger(i) && i >= 0 && i < e.points.length);
			}
		}
	});

	it("the same triangles as splitToComponents, no more components, every edge component inside one entry", () => {
		const comps = mb.splitToComponents(g);
		assert.ok(entries.length <= comps.length);
		for (const grp of GROUPS) {
			const mine = entries.filter((e) => groupOf(e) === grp);
			const theirs = comps.filter((c) => groupOf(c) === grp);
			assert.deepEqual(F.soupKeys(mine.flatMap(soupOf)), F.soupKeys(theirs.flatMap((c) => c.soup)), grp);
			const entryKeys = mine.map((e) => new Set(F.soupKeys(soupOf(e))));
			for (const c of theirs) {
				const keys = F.soupKeys(c.soup);
				assert.ok(entryKeys.some((s) => keys.every((k) => s.has(k))), `${grp} component inside one entry`);
			}
		}
	});
});

describe("indexGroups and indexGroupsToTypedArrays", () => {
	const g = groups();

	it("indexGroups reproduces each group on one shared pool", () => {
		const ix = mb.indexGroups(g);
		let tris = 0;
		for (const grp of GROUPS) {
			const soup = ix.groups[grp].map(([i, j, k]) => ({ v0: ix.points[i], v1: ix.points[j], v2: ix.points[k] }));
			assert.deepEqual(F.soupKeys(soup, F.triOrientedKey), F.soupKeys(g[grp], F.triOrientedKey), grp);
			tris += soup.length;
		}
		assert.ok(ix.points.length < 3 * tris);
		assert.equal(new Set(ix.points.map(F.key)).size, ix.points.length);
	});

	it("indexGroupsToTypedArrays: Float64 positions (3 × points), Uint32 indices (3 × triangles) per group", () => {
		const ix = mb.indexGroups(g);
		const ta = mb.indexGroupsToTypedArrays(ix);
		assert.ok(ta.positions instanceof Float64Array);
		assert.equal(ta.positions.length, 3 * ix.points.length);
		for (const grp of GROUPS) {
			assert.ok(ta.index[grp] instanceof Uint32Array, grp);
			assert.equal(ta.index[grp].length, 3 * ix.groups[grp].length, grp);
			assert.deepEqual(Array.from(ta.index[grp]), ix.groups[grp].flat());
		}
		ix.points.forEach((p, i) => assert.deepEqual([ta.positions[3 * i], ta.positions[3 * i + 1], ta.positions[3 * i + 2]], [p.x, p.y, p.z]));
	});
});

describe("findConnectedComponentsPooled", () => {
	it("two disjoint patches: 2 components, same sizes (largest first) and triangle sets as the classic one", () => {
		const s = [...F.patch(4, 2), ...F.patch(6, 3, { origin: [10, 10] })];
		const pooled = mb.findConnectedComponentsPooled(s);
		const classic = mb.findConnectedComponents(s);
		assert.equal(pooled.length, 2);
		assert.deepEqual(pooled.map((c) => c.length), [18, 8]);
		assert.deepEqual(pooled.map((c) => c.length), classic.map((c) => c.length));
		pooled.forEach((c, i) => assert.deepEqual(F.soupKeys(c), F.soupKeys(classic[i])));
	});

	it("[] for [], 1 for one triangle", () => {
		assert.deepEqual(mb.findConnectedComponentsPooled([]), []);
		assert.equal(mb.findConnectedComponentsPooled(F.T()).length, 1);
	});
});

describe("connectedComponentsIndexed and mergeSmallIndexedComponents", () => {
	it("components by shared vertices (coarser than edges): two triangles touching at a vertex are one", () => {
		const tris = [[0, 1, 2], [2, 3, 4], [5, 6, 7]];
		const comps = mb.connectedComponentsIndexed(tris);
		assert.equal(comps.length, 2);
		assert.deepEqual(comps.map((c) => c.length), [2, 1]);
	});

	it("mergeSmallIndexedComponents folds small pieces into the largest one", () => {
		const comps = [[[0, 1, 2], [1, 2, 3], [2, 3, 4]], [[5, 6, 7]], [[8, 9, 10]]];
		const out = mb.mergeSmallIndexedComponents(comps, 2);
		assert.equal(out.length, 1);
		assert.equal(out[0].length, 5);
	});
});
