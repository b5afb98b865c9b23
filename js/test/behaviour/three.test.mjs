// The three.js adapter (JS_BEHAVIOUR.md section 13): soupToMesh with recentring at UTM
// coordinates, meshToSoup with world matrices, booleanFromMeshes with its engine,
// quality and material options, and the re-exports.
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import * as THREE from "three";
import * as mb from "../../src/index.js";
import * as three from "../../src/three.js";
import * as F from "./fixtures.mjs";

const ORIGIN = { x0: 748291.234, y0: 6771845.678, z: 120.5 };
const utmGrid = () => F.grid(4, 4, 2.5, ORIGIN);

/** World coordinates of a soupToMesh mesh's non-indexed positions (local + mesh.position, doubles). */
function worldCorners(mesh) {
	const a = mesh.geometry.getAttribute("position");
	const out = [];
	for (let i = 0; i < a.count; i++) out.push({ x: a.getX(i) + mesh.position.x, y: a.getY(i) + mesh.position.y, z: a.getZ(i) + mesh.position.z });
	return out;
}

function maxError(mesh, soup) {
	const w = worldCorners(mesh);
	const corners = soup.flatMap((t) => [t.v0, t.v1, t.v2]);
	assert.equal(w.length, corners.length);
	let e = 0;
	corners.forEach((v, i) => {
		e = Math.max(e, Math.abs(v.x - w[i].x), Math.abs(v.y - w[i].y), Math.abs(v.z - w[i].z));
	});
	return e;
}

describe("soupToMesh", () => {
	it("recentres by default: every world ordinate within 1e-3 m, position on the centroid", () => {
		const s = utmGrid();
		const m = three.soupToMesh(s);
		assert.ok(m.isMesh);
		assert.ok(m.position.x > 748000);
		assert.ok(m.position.y > 6771000);
		assert.ok(maxError(m, s) < 1e-3, `error ${maxError(m, s)}`);
	});

	it("recenter: false: position 0, error > 1 cm at y ≈ 6.77e6", () => {
		const s = utmGrid();
		const m = three.soupToMesh(s, { recenter: false });
		assert.deepEqual([m.position.x, m.position.y, m.position.z], [0, 0, 0]);
		assert.ok(maxError(m, s) > 0.01);
	});

	it("empty soup: 0 vertices, position 0", () => {
		const m = three.soupToMesh([]);
		assert.equal(m.geometry.getAttribute("position").count, 0);
		assert.deepEqual([m.position.x, m.position.y, m.position.z], [0, 0, 0]);
	});

	it("a non-indexed BufferGeometry with vertex normals and a MeshPhongMaterial; color, doubleSide, wireframe", () => {
		const m = three.soupToMesh(F.cube(0, 2), { color: 0xff0000, doubleSide: false, wireframe: true });
		assert.equal(m.geometry.index, null);
		assert.ok(m.geometry.getAttribute("normal"));
		assert.ok(m.material.isMeshPhongMaterial);
		assert.equal(m.material.color.getHex(), 0xff0000);
		assert.equal(m.material.side, THREE.FrontSide);
		assert.equal(m.material.wireframe, true);
	});
});

describe("meshToSoup", () => {
	it("round-trips a recentred UTM mesh within 1e-3 m, triangle for triangle", () => {
		const s = utmGrid();
		const back = three.meshToSoup(three.soupToMesh(s));
		assert.equal(back.length, s.length);
		s.forEach((t, i) => {
			for (const c of ["v0", "v1", "v2"]) {
				for (const k of ["x", "y", "z"]) assert.ok(Math.abs(t[c][k] - back[i][c][k]) < 1e-3, `${i}.${c}.${k}`);
			}
		});
	});

	it("applies world matrices, updating them first (a moved child of a moved group)", () => {
		const geom = new THREE.BufferGeometry();
		geom.setAttribute("position", new THREE.BufferAttribute(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), 3));
		const mesh = new THREE.Mesh(geom);
		const group = new THREE.Group();
		group.add(mesh);
		group.position.set(10, 0, 0);
		mesh.position.set(0, 5, 0);
		// no updateMatrixWorld call here
		const s = three.meshToSoup(group);
		assert.equal(s.length, 1);
		assert.deepEqual([s[0].v0.x, s[0].v0.y, s[0].v0.z], [10, 5, 0]);
		assert.deepEqual([s[0].v1.x, s[0].v1.y, s[0].v1.z], [11, 5, 0]);
	});

	it("reads indexed geometry", () => {
		const s = three.meshToSoup(new THREE.Mesh(new THREE.BoxGeometry(2, 2, 2)));
		assert.equal(s.length, 12);
		assert.ok(Math.abs(F.signedVolume(s) - 8) < 1e-6);
	});
});

describe("booleanFromMeshes", () => {
	const { grid, box } = F.gridAndBox();
	const a = three.soupToMesh(grid), b = three.soupToMesh(box);

	for (const op of ["union", "intersect", "subtract"]) {
		it(`${op}: non-empty with the default engine, engine "classic", and quality "raw"`, () => {
			for (const opts of [undefined, { engine: "classic" }, { quality: "raw" }]) {
				const m = three.booleanFromMeshes(a, b, op, opts);
				assert.ok(m && m.isMesh, JSON.stringify(opts));
				assert.ok(m.geometry.getAttribute("position").count > 0, JSON.stringify(opts));
			}
		});
	}

	it("default engine is the BMS path (booleanAuto); classic is the core boolean", () => {
		const sa = three.meshToSoup(a), sb = three.meshToSoup(b);
		const count = (m) => m.geometry.getAttribute("position").count / 3;
		assert.equal(count(three.booleanFromMeshes(a, b, "subtract")), mb.booleanAuto(sa, sb, "subtract").soup.length);
		assert.equal(count(three.booleanFromMeshes(a, b, "subtract", { quality: "raw" })), mb.booleanAuto(sa, sb, "subtract", { quality: "raw" }).soup.length);
		assert.equal(count(three.booleanFromMeshes(a, b, "subtract", { engine: "classic" })), mb.boolean(sa, sb, "subtract").soup.length);
	});

	it("material options come from the same object", () => {
		const m = three.booleanFromMeshes(a, b, "union", { wireframe: true, color: 0x00ff00 });
		assert.equal(m.material.wireframe, true);
		assert.equal(m.material.color.getHex(), 0x00ff00);
	});

	it("cube meshes: the subtract keeps the exact volume", () => {
		const m = three.booleanFromMeshes(three.soupToMesh(F.cube(0, 2)), three.soupToMesh(F.cube([1, 1, 1], 2)), "subtract");
		assert.ok(Math.abs(F.signedVolume(three.meshToSoup(m)) - 7) < 1e-5);
	});
});

describe("intersectFromMeshes, repairFromMesh and re-exports", () => {
	it("intersectFromMeshes gives tagged segments", () => {
		const segs = three.intersectFromMeshes(three.soupToMesh(F.cube(0, 2)), three.soupToMesh(F.cube([1, 1, 1], 2)));
		assert.ok(segs.length > 0);
		for (const s of segs) assert.ok("p0" in s && "p1" in s && "idxA" in s && "idxB" in s);
	});

	it("repairFromMesh resolves to a THREE.Mesh", async () => {
		const m = await three.repairFromMesh(three.soupToMesh(F.tjunctionStrip()));
		assert.ok(m.isMesh);
		assert.ok(m.geometry.getAttribute("position").count > 0);
	});

	it("boolean, repair, intersect are the core's boolean, repairMesh, intersectMeshPairTagged", () => {
		assert.equal(three.boolean, mb.boolean);
		assert.equal(three.repair, mb.repairMesh);
		assert.equal(three.intersect, mb.intersectMeshPairTagged);
	});
});
