// meshbool/three: the three.js adapter. Converts THREE objects to the core's triangle
// soups (`meshToSoup`, `soupToMesh`, and the reference adapter's one-call helpers), and
// to the typed-array meshes of the fast path (`geometryToIndexed`, `indexedToGeometry`,
// `booleanGeometry`), which never build an object per vertex.
//
// three is a peer dependency: this module imports "three" and leaves resolving it to the
// application (node_modules, a bundler or an import map).
import * as THREE from "three";
import { boolean, booleanAuto, booleanIndexed, evaluateCsg, intersectMeshPairTagged, repairMesh, typedToSoup } from "./index.js";

export { boolean, repairMesh as repair, intersectMeshPairTagged as intersect };

const DEFAULT_COLOR = 0x4488ff;

// ── reading THREE objects ────────────────────────────────────────────────────────────────

/**
 * Calls `visit(geometry, matrix)` for every mesh geometry of `source` that has positions:
 * a BufferGeometry itself (matrix null), or every THREE.Mesh in an Object3D's subtree
 * with its world matrix (brought up to date first).
 */
function eachGeometry(source, visit) {
	if (source == null || typeof source !== "object") {
		throw new Error("meshbool/three: expected a THREE.Object3D or THREE.BufferGeometry");
	}
	if (source.isBufferGeometry) {
		if (source.getAttribute("position")) visit(source, null);
		return;
	}
	if (!source.isObject3D) {
		throw new Error("meshbool/three: expected a THREE.Object3D or THREE.BufferGeometry");
	}
	source.updateWorldMatrix(true, true);
	source.traverse((child) => {
		if (child.isMesh && child.geometry && child.geometry.getAttribute("position")) {
			visit(child.geometry, child.matrixWorld);
		}
	});
}

/** The number of triangles a geometry draws from its index, or from its positions when it has none. */
function triangleCount(geometry) {
	const n = geometry.index ? geometry.index.count : geometry.getAttribute("position").count;
	return Math.floor(n / 3);
}

/**
 * Copies a geometry's positions into `out` from `offset` (three numbers per vertex), in
 * double precision, transformed by `matrix` when given (three's `applyMatrix4`: affine
 * part, then the division by w).
 */
function copyPositions(geometry, matrix, out, offset) {
	const attr = geometry.getAttribute("position");
	const n = attr.count;
	const plain = !attr.isInterleavedBufferAttribute && attr.itemSize === 3 && !attr.normalized;
	if (plain) {
		out.set(attr.array.subarray(0, 3 * n), offset);
	} else {
		for (let i = 0, o = offset; i < n; i++, o += 3) {
			out[o] = attr.getX(i);
			out[o + 1] = attr.getY(i);
			out[o + 2] = attr.getZ(i);
		}
	}
	if (matrix) {
		const e = matrix.elements;
		const projective = e[3] !== 0 || e[7] !== 0 || e[11] !== 0 || e[15] !== 1;
		for (let i = 0, o = offset; i < n; i++, o += 3) {
			const x = out[o], y = out[o + 1], z = out[o + 2];
			const w = projective ? 1 / (e[3] * x + e[7] * y + e[11] * z + e[15]) : 1;
			out[o] = (e[0] * x + e[4] * y + e[8] * z + e[12]) * w;
			out[o + 1] = (e[1] * x + e[5] * y + e[9] * z + e[13]) * w;
			out[o + 2] = (e[2] * x + e[6] * y + e[10] * z + e[14]) * w;
		}
	}
	return n;
}

/**
 * Writes a geometry's triangles into `out` from `offset` as vertex numbers shifted by
 * `base`; each triangle reversed when `mirror` (a world matrix of negative determinant
 * turns the winding inside out, which three compensates for when drawing).
 */
function copyTriangles(geometry, base, mirror, out, offset) {
	const count = 3 * triangleCount(geometry);
	const index = geometry.index;
	for (let i = 0; i < count; i += 3) {
		const a = index ? index.getX(i) : i;
		const b = index ? index.getX(i + 1) : i + 1;
		const c = index ? index.getX(i + 2) : i + 2;
		out[offset + i] = base + a;
		out[offset + i + 1] = base + (mirror ? c : b);
		out[offset + i + 2] = base + (mirror ? b : c);
	}
	return count;
}

/**
 * The triangles of a THREE object as one typed-array mesh `{positions: Float64Array,
 * index: Uint32Array}`: every THREE.Mesh in the subtree of an Object3D (world matrices
 * applied, `updateWorldMatrix(true, true)` called first; meshes whose world matrix
 * mirrors have their triangles reversed so that they keep facing outward), or a
 * BufferGeometry as it is. Float32 positions are copied into doubles; indexed and
 * non-indexed geometries are both read (a non-indexed one gives vertices `0, 1, 2, ...`).
 * Vertices are not welded here (BoxGeometry, for one, has separate vertices per face):
 * the booleans weld equal coordinates themselves, but edge counts such as meshInfo's
 * `closed` need a welded mesh.
 *
 * @param {THREE.Object3D | THREE.BufferGeometry} source
 * @returns {{positions: Float64Array, index: Uint32Array}}
 */
export function geometryToIndexed(source) {
	const parts = [];
	let vertices = 0, corners = 0;
	eachGeometry(source, (geometry, matrix) => {
		parts.push({ geometry, matrix });
		vertices += geometry.getAttribute("position").count;
		corners += 3 * triangleCount(geometry);
	});
	const positions = new Float64Array(3 * vertices);
	const index = new Uint32Array(corners);
	let v = 0, c = 0;
	for (const { geometry, matrix } of parts) {
		const mirror = matrix != null && matrix.determinant() < 0;
		c += copyTriangles(geometry, v, mirror, index, c);
		v += copyPositions(geometry, matrix, positions, 3 * v);
	}
	return { positions, index };
}

/**
 * The triangles of a THREE object as a soup `[{v0, v1, v2}]` with `{x, y, z}` corners:
 * every THREE.Mesh in the subtree of `object3d` (a Mesh or a Group), world matrices
 * applied, indexed or non-indexed BufferGeometry (see geometryToIndexed).
 *
 * @param {THREE.Object3D} object3d
 * @returns {Array<{v0: {x: number, y: number, z: number}, v1: {x: number, y: number, z: number}, v2: {x: number, y: number, z: number}}>}
 */
export function meshToSoup(object3d) {
	return typedToSoup(geometryToIndexed(object3d));
}

// ── building THREE objects ───────────────────────────────────────────────────────────────

/** The adapter's material: MeshPhongMaterial, double-sided unless `doubleSide` is false. */
function makeMaterial(options) {
	const o = options || {};
	return new THREE.MeshPhongMaterial({
		color: o.color !== undefined ? o.color : DEFAULT_COLOR,
		side: o.doubleSide === false ? THREE.FrontSide : THREE.DoubleSide,
		wireframe: !!o.wireframe,
	});
}

/**
 * `c` rounded to a multiple of the power of two nearest below the largest extent of the
 * box `lo`..`hi`: positions less it stay within about twice the extent (full single
 * precision for them), and corners on a coarse grid (small integers, say) stay exactly
 * representable after the subtraction.
 */
function roundedCentre(c, lo, hi) {
	const extent = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
	const step = extent > 0 && Number.isFinite(extent) ? 2 ** Math.floor(Math.log2(extent)) : 1;
	return c.map((x) => Math.round(x / step) * step);
}

/** The centroid of a soup's corners (in double precision), rounded by `roundedCentre`. */
function roundedCentroid(soup) {
	const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity], sum = [0, 0, 0];
	for (const t of soup) {
		for (const v of [t.v0, t.v1, t.v2]) {
			const p = [v.x, v.y, v.z];
			for (let k = 0; k < 3; k++) {
				sum[k] += p[k];
				if (p[k] < lo[k]) lo[k] = p[k];
				if (p[k] > hi[k]) hi[k] = p[k];
			}
		}
	}
	return roundedCentre(sum.map((x) => x / (3 * soup.length)), lo, hi);
}

/** The centroid of flat positions (three numbers per vertex), rounded by `roundedCentre`. */
function roundedVertexCentroid(p) {
	const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity], sum = [0, 0, 0];
	for (let i = 0; i < p.length; i += 3) {
		for (let k = 0; k < 3; k++) {
			sum[k] += p[i + k];
			if (p[i + k] < lo[k]) lo[k] = p[i + k];
			if (p[i + k] > hi[k]) hi[k] = p[i + k];
		}
	}
	return roundedCentre(sum.map((x) => x / (p.length / 3)), lo, hi);
}

/**
 * A THREE.Mesh of a soup: a non-indexed BufferGeometry (Float32 positions, vertex normals
 * computed, so each triangle is shaded flat) and a MeshPhongMaterial. With `recenter`
 * (the default) the positions are stored relative to the soup's centroid, computed in
 * double precision and rounded to a power-of-two step near the soup's size, and that
 * point is the mesh's `position`: single-precision
 * positions then keep sub-millimetre detail at UTM coordinates (x ≈ 750,000 rounds to
 * 6 cm in Float32 on its own). `recenter: false` stores world coordinates as they are.
 *
 * @param {Array<{v0: {x: number, y: number, z: number}, v1: {x: number, y: number, z: number}, v2: {x: number, y: number, z: number}}>} soup
 * @param {{recenter?: boolean, color?: number | string, doubleSide?: boolean, wireframe?: boolean}} [options]
 *   `recenter` default true, `color` default 0x4488ff, `doubleSide` default true,
 *   `wireframe` default false.
 * @returns {THREE.Mesh}
 */
export function soupToMesh(soup, options) {
	if (!Array.isArray(soup)) throw new Error("meshbool/three: soupToMesh takes an array of triangles {v0, v1, v2}");
	const o = options || {};
	const [cx, cy, cz] = o.recenter !== false && soup.length > 0 ? roundedCentroid(soup) : [0, 0, 0];
	const positions = new Float32Array(9 * soup.length);
	for (let t = 0, k = 0; t < soup.length; t++, k += 9) {
		const { v0, v1, v2 } = soup[t];
		positions[k] = v0.x - cx; positions[k + 1] = v0.y - cy; positions[k + 2] = v0.z - cz;
		positions[k + 3] = v1.x - cx; positions[k + 4] = v1.y - cy; positions[k + 5] = v1.z - cz;
		positions[k + 6] = v2.x - cx; positions[k + 7] = v2.y - cy; positions[k + 8] = v2.z - cz;
	}
	const geometry = new THREE.BufferGeometry();
	geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
	geometry.computeVertexNormals();
	const mesh = new THREE.Mesh(geometry, makeMaterial(o));
	mesh.position.set(cx, cy, cz);
	return mesh;
}

/**
 * A BufferGeometry of a typed-array mesh `{positions, index}`: positions rounded to a
 * Float32 attribute (translate far-off coordinates, such as UTM, near the origin first
 * if single precision is not enough), the index as a Uint32 index attribute, vertex
 * normals computed.
 *
 * @param {{positions: ArrayLike<number>, index: ArrayLike<number>}} mesh
 * @returns {THREE.BufferGeometry}
 */
export function indexedToGeometry(mesh) {
	if (mesh == null || mesh.positions == null || mesh.index == null) {
		throw new Error("meshbool/three: indexedToGeometry takes {positions, index}");
	}
	const geometry = new THREE.BufferGeometry();
	geometry.setAttribute("position", new THREE.BufferAttribute(Float32Array.from(mesh.positions), 3));
	const index = mesh.index instanceof Uint32Array ? mesh.index.slice() : Uint32Array.from(mesh.index);
	geometry.setIndex(new THREE.BufferAttribute(index, 1));
	geometry.computeVertexNormals();
	return geometry;
}

// ── one-call helpers ─────────────────────────────────────────────────────────────────────

/**
 * The boolean of two THREE objects (their meshes in world coordinates): a new THREE.Mesh
 * (see soupToMesh), or null when the result is empty. `engine` "bms" (the default) runs
 * the core's `booleanAuto` (with its `quality`, "strict" by default, and `tolerance`);
 * "classic" runs the core's `boolean`. The material options (`color`, `doubleSide`,
 * `wireframe`, `recenter`) come from the same object.
 *
 * @param {THREE.Object3D} a
 * @param {THREE.Object3D} b
 * @param {"union" | "intersect" | "subtract" | "intersection" | "difference" | "reverse-difference"} op
 * @param {{engine?: "bms" | "classic", quality?: "strict" | "raw", tolerance?: number, recenter?: boolean, color?: number | string, doubleSide?: boolean, wireframe?: boolean}} [options]
 * @returns {THREE.Mesh | null}
 */
export function booleanFromMeshes(a, b, op, options) {
	const o = options || {};
	const soupA = meshToSoup(a), soupB = meshToSoup(b);
	let soup;
	if (o.engine === "classic") {
		const result = boolean(soupA, soupB, op);
		soup = result ? result.soup : [];
	} else {
		const auto = { quality: o.quality };
		if (o.tolerance !== undefined) auto.tolerance = o.tolerance;
		const result = booleanAuto(soupA, soupB, op, auto);
		soup = result ? result.soup : [];
	}
	return soup.length > 0 ? soupToMesh(soup, o) : null;
}

/**
 * The intersection segments of two THREE objects (world coordinates):
 * `[{p0, p1, idxA, idxB}]`, `idxA`/`idxB` the crossing triangles in meshToSoup's order.
 *
 * @param {THREE.Object3D} a
 * @param {THREE.Object3D} b
 * @returns {Array<{p0: {x: number, y: number, z: number}, p1: {x: number, y: number, z: number}, idxA: number, idxB: number}>}
 */
export function intersectFromMeshes(a, b) {
	return intersectMeshPairTagged(meshToSoup(a), meshToSoup(b));
}

/**
 * The core's repair pipeline (`repairMesh`) on a THREE object: resolves to a new
 * THREE.Mesh (see soupToMesh).
 *
 * @param {THREE.Object3D} mesh
 * @param {object} [config] repairMesh's config (`closeMode`, `snapTolerance`, ...)
 * @param {(fraction: number, message: string) => void} [onProgress]
 * @param {{color?: number | string, doubleSide?: boolean, wireframe?: boolean}} [meshOptions]
 * @returns {Promise<THREE.Mesh>}
 */
export async function repairFromMesh(mesh, config, onProgress, meshOptions) {
	const result = await repairMesh(meshToSoup(mesh), config, onProgress);
	return soupToMesh(result.soup, meshOptions);
}

/**
 * The boolean of two THREE objects or geometries on the typed-array fast path
 * (geometryToIndexed → booleanIndexed → indexedToGeometry): a new indexed BufferGeometry
 * whose `userData.report` is the library's report (triangles, volume, area, closed, ...),
 * or null when the result has no triangles.
 *
 * @param {THREE.Object3D | THREE.BufferGeometry} a
 * @param {THREE.Object3D | THREE.BufferGeometry} b
 * @param {"union" | "intersect" | "subtract" | "intersection" | "difference" | "reverse-difference"} op
 * @param {{force?: boolean, selfCheck?: boolean, resolve?: boolean, orient?: boolean, keepNonmanifold?: boolean}} [options]
 *   booleanIndexed's operand options.
 * @returns {THREE.BufferGeometry | null}
 */
export function booleanGeometry(a, b, op, options) {
	const out = booleanIndexed(geometryToIndexed(a), geometryToIndexed(b), op, options);
	if (out.index.length === 0) return null;
	const geometry = indexedToGeometry(out);
	geometry.userData.report = out.report;
	return geometry;
}

// ── CSG groups ───────────────────────────────────────────────────────────────────────────

/** A three.js matrix (column-major elements) as a CSG transform step (row-major). */
function matrixStep(m) {
	const e = m.elements;
	return { matrix: [e[0], e[4], e[8], e[12], e[1], e[5], e[9], e[13], e[2], e[6], e[10], e[14], e[3], e[7], e[11], e[15]] };
}

/**
 * The CSG node of a THREE object: an Object3D whose `userData.csg.op` is "union",
 * "intersection" or "difference" is an operation over its children; a Mesh is a leaf (its
 * geometry in its own coordinates); any other Object3D unites its children. Each node
 * carries its object's local matrix and `userData.csg.role` ("cutter": subtracted in a
 * difference) and `name`.
 */
function csgNode(object) {
	const csg = object.userData && object.userData.csg ? object.userData.csg : {};
	let node;
	if (csg.op) {
		node = { op: csg.op, children: object.children.map(csgNode) };
	} else if (object.isMesh && object.geometry && object.geometry.getAttribute("position")) {
		node = { mesh: geometryToIndexed(object.geometry) };
	} else {
		node = { op: "union", children: object.children.map(csgNode) };
	}
	object.updateMatrix();
	node.transform = matrixStep(object.matrix);
	if (csg.role) node.role = csg.role;
	if (object.name) node.name = object.name;
	return node;
}

/**
 * Evaluates a THREE group as a CSG tree (the library's `evaluateCsg`): the group's
 * `userData.csg = {op}` says its operation, each child's `userData.csg = {op, role}` its
 * own (nested groups are nested nodes), every object's local transform applies, and the
 * root's world transform places the result. A new THREE.Mesh (recentred as soupToMesh
 * does: the offset on its position, so that UTM-sized coordinates keep their precision),
 * its geometry's `userData.report` the evaluation's report; null when the result is empty.
 * Pass one `cache` (a CsgCache) between calls to compute only what changed. Options: the
 * material's (`color`, `doubleSide`, `wireframe`), `recenter`, `cache` and the booleans'.
 *
 * @param {THREE.Object3D} group
 * @param {{cache?: import("./index.js").CsgCache, recenter?: boolean, color?: number | string, doubleSide?: boolean, wireframe?: boolean, force?: boolean, selfCheck?: boolean, snap?: number}} [options]
 * @returns {THREE.Mesh | null}
 */
export function csgGroup(group, options) {
	const { recenter, color, doubleSide, wireframe, ...csgOptions } = options || {};
	group.updateWorldMatrix(true, false);
	const root = csgNode(group);
	// The root's place in the world, not only in its parent.
	root.transform = matrixStep(group.matrixWorld);
	const out = evaluateCsg({ root }, csgOptions);
	if (out.index.length === 0) return null;
	const p = out.positions;
	const center = recenter !== false ? roundedVertexCentroid(p) : [0, 0, 0];
	const local = new Float64Array(p.length);
	for (let i = 0; i < p.length; i += 3) {
		local[i] = p[i] - center[0];
		local[i + 1] = p[i + 1] - center[1];
		local[i + 2] = p[i + 2] - center[2];
	}
	const geometry = indexedToGeometry({ positions: local, index: out.index });
	geometry.userData.report = out.report;
	const mesh = new THREE.Mesh(geometry, makeMaterial({ color, doubleSide, wireframe }));
	mesh.position.set(center[0], center[1], center[2]);
	return mesh;
}
