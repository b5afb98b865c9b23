// Conversions between the reference API's plain objects and the flat typed arrays that
// cross into WebAssembly, with the checks that make bad input an Error that says where.

/** True for `{positions, index}` meshes (the typed-array fast path). */
export function isIndexed(m) {
	return m != null && typeof m === "object" && !Array.isArray(m) && m.positions != null && m.index != null;
}

function vertexError(what, t, corner, v) {
	const shown = v === undefined ? "undefined" : JSON.stringify(v);
	return new Error(`meshbool: ${what}[${t}].${corner} is not a vertex {x, y, z} of numbers (got ${shown})`);
}

/**
 * Flat arrays of a soup (`[{v0, v1, v2}]`, each corner `{x, y, z}`): nine numbers and three
 * indices per triangle, corners not welded (every operation welds exactly on the way in).
 * Throws on anything that is not a soup; non-finite numbers are refused by the library.
 */
export function soupToArrays(soup, what = "soup") {
	if (!Array.isArray(soup)) {
		throw new Error(`meshbool: ${what} must be an array of triangles {v0, v1, v2}, got ${soup === null ? "null" : typeof soup}`);
	}
	const n = soup.length;
	const positions = new Float64Array(9 * n);
	for (let t = 0; t < n; t++) {
		const tri = soup[t];
		if (tri == null || typeof tri !== "object") {
			throw new Error(`meshbool: ${what}[${t}] is not a triangle {v0, v1, v2}`);
		}
		const v0 = tri.v0, v1 = tri.v1, v2 = tri.v2;
		if (v0 == null || typeof v0.x !== "number" || typeof v0.y !== "number" || typeof v0.z !== "number") throw vertexError(what, t, "v0", v0);
		if (v1 == null || typeof v1.x !== "number" || typeof v1.y !== "number" || typeof v1.z !== "number") throw vertexError(what, t, "v1", v1);
		if (v2 == null || typeof v2.x !== "number" || typeof v2.y !== "number" || typeof v2.z !== "number") throw vertexError(what, t, "v2", v2);
		const o = 9 * t;
		positions[o] = v0.x; positions[o + 1] = v0.y; positions[o + 2] = v0.z;
		positions[o + 3] = v1.x; positions[o + 4] = v1.y; positions[o + 5] = v1.z;
		positions[o + 6] = v2.x; positions[o + 7] = v2.y; positions[o + 8] = v2.z;
	}
	return { positions, index: identity(3 * n) };
}

let identityCache = new Uint32Array(0);

/** `0, 1, ..., n - 1` (a view of a shared array: the WebAssembly calls copy it). */
export function identity(n) {
	if (identityCache.length < n) {
		const grown = new Uint32Array(Math.max(n, 2 * identityCache.length));
		for (let i = 0; i < grown.length; i++) grown[i] = i;
		identityCache = grown;
	}
	return identityCache.subarray(0, n);
}

/**
 * A `{positions, index}` mesh checked for shape: `positions` a Float64Array (other
 * array-likes are copied into one), `index` a Uint32Array, both multiples of three.
 */
export function indexedArrays(m, what = "mesh") {
	if (!isIndexed(m)) {
		throw new Error(`meshbool: ${what} must be {positions: Float64Array, index: Uint32Array}`);
	}
	const positions = m.positions instanceof Float64Array ? m.positions : Float64Array.from(m.positions);
	const index = m.index instanceof Uint32Array ? m.index : Uint32Array.from(m.index);
	if (positions.length % 3 !== 0) {
		throw new Error(`meshbool: ${what}.positions must hold three numbers per vertex, got ${positions.length}`);
	}
	if (index.length % 3 !== 0) {
		throw new Error(`meshbool: ${what}.index must hold three indices per triangle, got ${index.length}`);
	}
	return { positions, index };
}

/** Flat arrays of either a soup or an indexed mesh. */
export function arraysOf(m, what) {
	return isIndexed(m) ? indexedArrays(m, what) : soupToArrays(m, what);
}

/** A soup from flat arrays: fresh vertex objects for every corner. */
export function arraysToSoup(positions, index) {
	const n = index.length / 3;
	const soup = new Array(n);
	for (let t = 0; t < n; t++) {
		const a = 3 * index[3 * t], b = 3 * index[3 * t + 1], c = 3 * index[3 * t + 2];
		soup[t] = {
			v0: { x: positions[a], y: positions[a + 1], z: positions[a + 2] },
			v1: { x: positions[b], y: positions[b + 1], z: positions[b + 2] },
			v2: { x: positions[c], y: positions[c + 1], z: positions[c + 2] },
		};
	}
	return soup;
}

/** The points of flat positions, one object per vertex. */
export function arraysToPoints(positions) {
	const n = positions.length / 3;
	const points = new Array(n);
	for (let i = 0; i < n; i++) {
		points[i] = { x: positions[3 * i], y: positions[3 * i + 1], z: positions[3 * i + 2] };
	}
	return points;
}

/**
 * The reference's result shape `{soup, points, triangles}` of a welded mesh: `points` one
 * object per vertex, `triangles[t].vertices` the three point objects of triangle `t` (shared
 * with `points`), `soup` fresh objects per corner. `report` (the library's report) is
 * attached as a non-enumerable property when given.
 */
export function toResult(positions, index, report) {
	const points = arraysToPoints(positions);
	const n = index.length / 3;
	const triangles = new Array(n);
	for (let t = 0; t < n; t++) {
		triangles[t] = { vertices: [points[index[3 * t]], points[index[3 * t + 1]], points[index[3 * t + 2]]] };
	}
	const result = { soup: arraysToSoup(positions, index), points, triangles };
	if (report !== undefined) {
		Object.defineProperty(result, "report", { value: report, enumerable: false });
	}
	return result;
}

/** Parses a report's JSON text. */
export function parseReport(text) {
	return typeof text === "string" ? JSON.parse(text) : text;
}

/** The soup with every triangle's winding reversed (fresh objects). */
export function flippedSoup(soup) {
	return soup.map((t) => ({
		v0: { x: t.v0.x, y: t.v0.y, z: t.v0.z },
		v1: { x: t.v2.x, y: t.v2.y, z: t.v2.z },
		v2: { x: t.v1.x, y: t.v1.y, z: t.v1.z },
	}));
}

/** The reference's vertex key (coordinates to 6 decimals); meshbool itself never keys by it. */
export function vKey(v) {
	return v.x.toFixed(6) + "," + v.y.toFixed(6) + "," + v.z.toFixed(6);
}

/** An undirected edge key of two vertex keys. */
export function edgeKey(ka, kb) {
	return ka < kb ? ka + "|" + kb : kb + "|" + ka;
}
