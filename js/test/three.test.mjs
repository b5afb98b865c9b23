// Tests of the three.js adapter (src/three.js) with the real three package; no DOM needed.
import { test } from "node:test";
import assert from "node:assert/strict";
import * as THREE from "three";
import { CsgCache, computeSignedVolume, meshInfo, repairMesh, soupToTyped, boolean as coreBoolean, intersectMeshPairTagged } from "../src/index.js";
import {
	boolean,
	booleanFromMeshes,
	booleanGeometry,
	csgGroup,
	geometryToIndexed,
	indexedToGeometry,
	intersect,
	intersectFromMeshes,
	meshToSoup,
	repair,
	repairFromMesh,
	soupToMesh,
} from "../src/three.js";

/** A box mesh of edge 2 centred at (x, y, z). */
function box(x = 0, y = 0, z = 0) {
	const mesh = new THREE.Mesh(new THREE.BoxGeometry(2, 2, 2), new THREE.MeshBasicMaterial());
	mesh.position.set(x, y, z);
	return mesh;
}

/** The signed volume of a THREE.Mesh's world-space triangles. */
function volumeOf(object3d) {
	return computeSignedVolume(meshToSoup(object3d));
}

/**
 * meshInfo of a THREE object's triangles welded exactly (geometryToIndexed keeps three's
 * vertices as they are, and BoxGeometry has separate vertices per face).
 */
function weldedInfo(object3d) {
	return meshInfo(soupToTyped(meshToSoup(object3d)));
}

test("re-exports the core functions", () => {
	assert.equal(boolean, coreBoolean);
	assert.equal(repair, repairMesh);
	assert.equal(intersect, intersectMeshPairTagged);
});

test("meshToSoup reads an indexed BoxGeometry in world coordinates", () => {
	const soup = meshToSoup(box(1, 2, 3));
	assert.equal(soup.length, 12);
	for (const t of soup) {
		for (const v of [t.v0, t.v1, t.v2]) {
			assert.ok(v.x === 0 || v.x === 2, `x ${v.x}`);
			assert.ok(v.y === 1 || v.y === 3, `y ${v.y}`);
			assert.ok(v.z === 2 || v.z === 4, `z ${v.z}`);
		}
	}
	assert.equal(computeSignedVolume(soup), 8);
});

test("meshToSoup reads a non-indexed geometry", () => {
	const mesh = box();
	mesh.geometry = mesh.geometry.toNonIndexed();
	assert.equal(mesh.geometry.index, null);
	const soup = meshToSoup(mesh);
	assert.equal(soup.length, 12);
	assert.equal(computeSignedVolume(soup), 8);
});

test("booleanFromMeshes: union, intersect, subtract of offset boxes are exact", () => {
	const a = box(0, 0, 0), b = box(1, 0, 0);
	const expected = { union: 12, intersect: 4, subtract: 4 };
	for (const [op, volume] of Object.entries(expected)) {
		const result = booleanFromMeshes(a, b, op, { color: 0xff0000 });
		assert.ok(result instanceof THREE.Mesh, op);
		assert.ok(result.material instanceof THREE.MeshPhongMaterial, op);
		assert.equal(result.material.side, THREE.DoubleSide);
		assert.equal(result.material.color.getHex(), 0xff0000);
		assert.equal(result.geometry.index, null, "soupToMesh builds a non-indexed geometry");
		assert.ok(result.geometry.getAttribute("normal"), "normals computed");
		assert.equal(volumeOf(result), volume, op);
		assert.ok(weldedInfo(result).closed, `${op} is closed`);
	}
});

test("booleanFromMeshes gives null for an empty result", () => {
	assert.equal(booleanFromMeshes(box(0, 0, 0), box(5, 0, 0), "intersect"), null);
});

test("soupToMesh options", () => {
	const mesh = soupToMesh(meshToSoup(box()), { doubleSide: false, wireframe: true });
	assert.equal(mesh.material.side, THREE.FrontSide);
	assert.equal(mesh.material.wireframe, true);
	assert.equal(mesh.material.color.getHex(), 0x4488ff);
	assert.equal(mesh.geometry.getAttribute("position").count, 36);
});

test("geometryToIndexed / indexedToGeometry round trip", () => {
	const source = box(0.5, -1, 2);
	const m = geometryToIndexed(source);
	assert.ok(m.positions instanceof Float64Array);
	assert.ok(m.index instanceof Uint32Array);
	assert.equal(m.index.length, 36);
	assert.equal(m.positions.length, 3 * source.geometry.getAttribute("position").count);
	assert.equal(meshInfo(m).volume, 8);

	const geometry = indexedToGeometry(m);
	assert.ok(geometry instanceof THREE.BufferGeometry);
	assert.ok(geometry.getAttribute("position").array instanceof Float32Array);
	assert.ok(geometry.index.array instanceof Uint32Array);
	assert.ok(geometry.getAttribute("normal"), "normals computed");
	assert.deepEqual(Array.from(geometry.index.array), Array.from(m.index));

	// A geometry is read as it is (no matrix); the positions come back unchanged.
	const back = geometryToIndexed(geometry);
	assert.deepEqual(Array.from(back.positions), Array.from(m.positions));
	assert.deepEqual(Array.from(back.index), Array.from(m.index));
	assert.equal(meshInfo(back).volume, 8);
});

test("geometryToIndexed applies world matrices of nested objects", () => {
	const group = new THREE.Group();
	group.position.set(10, 0, 0);
	group.scale.set(2, 1, 1);
	const child = box(1, 0, 0);
	group.add(child);
	// Not updated by hand: the adapter calls updateWorldMatrix itself.
	const m = geometryToIndexed(group);
	let minX = Infinity, maxX = -Infinity;
	for (let i = 0; i < m.positions.length; i += 3) {
		minX = Math.min(minX, m.positions[i]);
		maxX = Math.max(maxX, m.positions[i]);
	}
	assert.equal(minX, 10);
	assert.equal(maxX, 14);
	assert.equal(meshInfo(m).volume, 16);
	assert.equal(computeSignedVolume(meshToSoup(group)), 16);

	// Two meshes in one group are concatenated, each with its own matrix.
	group.add(box(-5, 0, 0));
	const two = geometryToIndexed(group);
	assert.equal(two.index.length, 72);
	assert.equal(meshInfo(two).volume, 32);
	assert.equal(weldedInfo(group).components, 2);
	assert.equal(weldedInfo(group).closed, true);
});

test("a mirroring world matrix keeps the solid facing outward", () => {
	const mesh = box(3, 0, 0);
	mesh.scale.set(-1, 1, 1);
	assert.equal(meshInfo(geometryToIndexed(mesh)).volume, 8);
	assert.equal(volumeOf(mesh), 8);
});

test("geometryToIndexed reads interleaved positions", () => {
	const box = new THREE.BoxGeometry(2, 2, 2);
	const pos = box.getAttribute("position");
	// Position and a padding float per vertex in one interleaved buffer.
	const data = new Float32Array(4 * pos.count);
	for (let i = 0; i < pos.count; i++) data.set([pos.getX(i), pos.getY(i), pos.getZ(i), 7], 4 * i);
	const geometry = new THREE.BufferGeometry();
	geometry.setAttribute("position", new THREE.InterleavedBufferAttribute(new THREE.InterleavedBuffer(data, 4), 3, 0));
	geometry.setIndex(box.index);
	const m = geometryToIndexed(new THREE.Mesh(geometry));
	assert.deepEqual(Array.from(m.positions), Array.from(pos.array));
	assert.equal(meshInfo(m).volume, 8);
});

test("geometryToIndexed rejects what is not a THREE object", () => {
	assert.throws(() => geometryToIndexed({}), /Object3D or THREE.BufferGeometry/);
	assert.throws(() => geometryToIndexed(null), /Object3D or THREE.BufferGeometry/);
});

test("booleanGeometry equals booleanFromMeshes", () => {
	const a = box(0, 0, 0), b = box(1, 0, 0);
	for (const op of ["union", "intersect", "subtract", "reverse-difference"]) {
		const geometry = booleanGeometry(a, b, op);
		assert.ok(geometry instanceof THREE.BufferGeometry, op);
		assert.ok(geometry.index, "indexed result");
		const report = geometry.userData.report;
		assert.equal(report.triangles, geometry.index.count / 3);
		assert.equal(report.closed, true);
		const volume = meshInfo(geometryToIndexed(geometry)).volume;
		assert.equal(report.volume, volume, op);
		assert.equal(volume, volumeOf(booleanFromMeshes(a, b, op)), op);
	}
	// Geometries (no matrices) as operands.
	const shifted = new THREE.BoxGeometry(2, 2, 2).translate(1, 0, 0);
	assert.equal(booleanGeometry(new THREE.BoxGeometry(2, 2, 2), shifted, "union").userData.report.volume, 12);
	assert.equal(booleanGeometry(box(0, 0, 0), box(5, 0, 0), "intersect"), null);
});

test("intersectFromMeshes gives the tagged intersection segments", () => {
	const segments = intersectFromMeshes(box(0, 0, 0), box(1, 0.5, 0.5));
	assert.ok(segments.length > 0);
	for (const s of segments) {
		assert.ok(Number.isInteger(s.idxA) && s.idxA >= 0 && s.idxA < 12);
		assert.ok(Number.isInteger(s.idxB) && s.idxB >= 0 && s.idxB < 12);
		for (const p of [s.p0, s.p1]) {
			assert.ok(p.x >= 0 && p.x <= 1, `x ${p.x}`);
		}
	}
	assert.deepEqual(intersectFromMeshes(box(0, 0, 0), box(5, 0, 0)), []);
});

test("repairFromMesh returns a THREE.Mesh", async () => {
	const progress = [];
	const mesh = await repairFromMesh(box(0, 0, 1), { closeMode: "weld" }, (f) => progress.push(f), { color: "#00ff00" });
	assert.ok(mesh instanceof THREE.Mesh);
	assert.equal(mesh.material.color.getHex(), 0x00ff00);
	assert.equal(volumeOf(mesh), 8);
	assert.ok(progress.length > 0 && progress.at(-1) === 1, `progress ${progress}`);
});

test("csgGroup: a group as a CSG tree (nested groups, cutters, local transforms) at UTM coordinates", () => {
	// A 2 × 2 × 2 box with a 1 × 1 × 4 bar through it, and a second box beside it, in a
	// group placed at x ≈ 750,000; the union of the boxes less the bar.
	const site = new THREE.Group();
	site.position.set(750000.25, 6500000.5, 120);
	site.userData.csg = { op: "difference" };
	const body = new THREE.Group();
	body.name = "body";
	body.userData.csg = { op: "union" };
	body.add(box(0, 0, 0), box(1.5, 0, 0));
	const bar = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 4), new THREE.MeshBasicMaterial());
	bar.userData.csg = { role: "cutter" };
	bar.rotation.x = Math.PI / 2; // along y
	site.add(body, bar);
	const cache = new CsgCache();
	const out = csgGroup(site, { cache });
	const report = out.geometry.userData.report;
	assert.equal(report.closed, true);
	// 2 · 8 − overlap (0.5 · 2 · 2 = 2) = 14, less the bar inside the union: 1 · 1 · 2 = 2.
	assert.ok(Math.abs(report.volume - 12) < 1e-6, report.volume);
	assert.ok(Math.abs(volumeOf(out) - 12) < 1e-3);
	// Recentred: the offset on the position, the positions near the origin.
	out.geometry.computeBoundingBox();
	assert.ok(out.position.x > 749000 && Math.abs(out.geometry.boundingBox.max.x) < 10);
	const world = geometryToIndexed(out);
	const xs = Array.from({ length: world.positions.length / 3 }, (_, i) => world.positions[3 * i]);
	assert.ok(Math.abs(Math.min(...xs) - (750000.25 - 1)) < 1e-3, Math.min(...xs));
	// Moving the bar recomputes the root only (and the bar): the body from the cache.
	bar.position.x = 0.25;
	const moved = csgGroup(site, { cache });
	const computed = moved.geometry.userData.report.nodes.filter((n) => n.source === "computed").map((n) => n.path);
	assert.deepEqual(computed, ["root.children[1]", "root"]);
});
