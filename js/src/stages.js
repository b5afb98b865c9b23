// The reference's inner stages, public in its index (the classic pipeline's triangle
// splitting and flood fill, the BMS chain/close/classify steps, the self-arrangement and
// winding-extraction helpers), offered with the reference's names and shapes. meshbool's
// own pipeline needs none of them: where a stage decides geometry, these compute it with
// the library (exact splits, exact point classification); where a stage is a tolerance
// utility of the reference (snaps, welds, edge maps), it keeps that tolerance, which the
// caller names.
import { call } from "./native.js";
import { arraysToSoup, edgeKey, soupToArrays, vKey } from "./convert.js";
import { chainById, createVertexPool, overlapPairs, poolOfSplit } from "./bms.js";
import { closeSolid, conditioned, simpleBoundaryLoops } from "./solids.js";

/**
 * The reference's near-parallel gate of its triangle–triangle test (|nA · nB| above which
 * it called two triangles parallel): 1 − 1e-14. meshbool's triangle tests are exact and
 * do not use it.
 */
export const NEAR_PARALLEL = 1 - 1e-14;

const EMPTY_F64 = new Float64Array(0);
const EMPTY_U32 = new Uint32Array(0);

function centroid(t) {
	return { x: (t.v0.x + t.v1.x + t.v2.x) / 3, y: (t.v0.y + t.v1.y + t.v2.y) / 3, z: (t.v0.z + t.v1.z + t.v2.z) / 3 };
}

/** The classes (0 outside, 1 inside, 2 on) of points against a soup, by the library. */
function classesOf(soup, points) {
	const S = soupToArrays(soup, "soup");
	const flat = new Float64Array(3 * points.length);
	points.forEach((p, i) => {
		flat[3 * i] = p.x;
		flat[3 * i + 1] = p.y;
		flat[3 * i + 2] = p.z;
	});
	// As given: a defective other mesh (non-manifold, self-crossing) still has a winding
	// number at each point.
	return call("classify", S.positions, S.index, flat, JSON.stringify({ force: true })).classes;
}

/**
 * The classic pipeline's classification of the triangles of `tris` against `otherTris`:
 * an Int8Array, 1 inside, −1 outside, and 0 for the triangles listed in `crossedMap`
 * (crossed: they are split first). Each triangle's centroid is classified exactly by the
 * library (on the other surface: inside); `otherGrids` is not needed.
 */
export function classifyByFloodFill(tris, crossedMap, otherTris, otherGrids) {
	void otherGrids;
	const out = new Int8Array(tris.length);
	const crossed = crossedMap || {};
	const idx = [], points = [];
	tris.forEach((t, i) => {
		if (crossed[i] !== undefined) return;
		idx.push(i);
		points.push(centroid(t));
	});
	if (idx.length > 0 && Array.isArray(otherTris) && otherTris.length > 0) {
		const classes = classesOf(otherTris, points);
		idx.forEach((t, k) => {
			out[t] = classes[k] === 0 ? -1 : 1;
		});
	} else {
		for (const t of idx) out[t] = -1;
	}
	return out;
}

/**
 * A triangle split along segments `[{p0, p1}]` lying in it: the library cuts it exactly
 * along a thin cutting surface through each segment (the segment swept along the
 * triangle's normal), so the pieces tile the triangle and every segment is an edge of
 * them; pieces keep the triangle's orientation. The soup of pieces (the triangle itself
 * when no segment crosses it).
 */
export function retriangulateWithSteinerPoints(tri, segments) {
	return splitAlong(tri, segments);
}

/**
 * The reference's fan split of a crossed triangle; here the same exact split as
 * retriangulateWithSteinerPoints (a fan from a chain point leaves needles; the
 * library's triangulation does not).
 */
export function fanTriangulate(tri, segments) {
	return splitAlong(tri, segments);
}

function splitAlong(tri, segments) {
	const own = [{ v0: { ...tri.v0 }, v1: { ...tri.v1 }, v2: { ...tri.v2 } }];
	const segs = Array.isArray(segments) ? segments.filter((s) => s && s.p0 && s.p1) : [];
	if (segs.length === 0) return own;
	const u = [tri.v1.x - tri.v0.x, tri.v1.y - tri.v0.y, tri.v1.z - tri.v0.z];
	const v = [tri.v2.x - tri.v0.x, tri.v2.y - tri.v0.y, tri.v2.z - tri.v0.z];
	const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
	const len = Math.hypot(n[0], n[1], n[2]);
	if (!(len > 0)) return own;
	const h = Math.max(Math.hypot(...u), Math.hypot(...v));
	const d = n.map((c) => (c / len) * h);
	const cutter = [];
	for (const s of segs) {
		const a = [s.p0.x, s.p0.y, s.p0.z], b = [s.p1.x, s.p1.y, s.p1.z];
		const up = (p) => ({ x: p[0] + d[0], y: p[1] + d[1], z: p[2] + d[2] });
		const down = (p) => ({ x: p[0] - d[0], y: p[1] - d[1], z: p[2] - d[2] });
		cutter.push({ v0: down(a), v1: down(b), v2: up(b) }, { v0: down(a), v1: up(b), v2: up(a) });
	}
	const A = soupToArrays(own, "tri"), B = soupToArrays(cutter, "segments");
	let raw;
	try {
		raw = call("split", A.positions, A.index, B.positions, B.index, JSON.stringify({ force: true }));
	} catch {
		return own;
	}
	const pieces = [];
	for (const g of raw.groups) {
		if (!g.name.startsWith("a_")) continue;
		for (const t of arraysToSoup(g.positions, g.index)) pieces.push(t);
	}
	return pieces.length > 0 ? pieces : own;
}

/** Chains segments `[{p0, p1}]` into polylines by vertex identity (pool id, else position). */
export function bmsChain(segments) {
	return chainById(Array.isArray(segments) ? segments : []);
}

/**
 * The reference's closing of chained polylines against the mesh boundaries into
 * barriers for its flood fill. meshbool classifies without barriers, so the polylines
 * come back as they are: `{closedPolylines, meshEdgePolys: {A: {segments: [], closed},
 * B: {...}}}` (`closed`: whether that mesh has no open edge).
 */
export function bmsClosePolylines(polylines, trisA, trisB, megaSoup, segments) {
	void megaSoup;
	void segments;
	const closed = (soup) => {
		const S = soupToArrays(soup || [], "soup");
		return S.index.length > 0 && call("measures", ...weld(S))[3] === 0;
	};
	return {
		closedPolylines: Array.isArray(polylines) ? polylines.slice() : [],
		meshEdgePolys: { A: { segments: [], closed: closed(trisA) }, B: { segments: [], closed: closed(trisB) } },
	};
}

function weld(S) {
	const w = conditioned(S, false);
	return [w.positions, w.index];
}

/**
 * The largest boundary loop of a soup as an ordered closed polygon of points (the mesh
 * runs along it in that order); [] for a closed soup. Vertices as the library takes them
 * (equal up to rounding noise), loops through a pinch vertex split there.
 */
export function chainedOpenEdge(tris) {
	const S = soupToArrays(tris || [], "tris");
	if (S.index.length === 0) return [];
	const M = conditioned(S, false);
	const loops = simpleBoundaryLoops(M.index);
	if (loops.length === 0) return [];
	const best = loops.reduce((a, b) => (b.length > a.length ? b : a));
	return best.map((v) => ({ x: M.positions[3 * v], y: M.positions[3 * v + 1], z: M.positions[3 * v + 2] }));
}

/**
 * The reference's hybrid classification of split pieces: `{aInside, aOutside, bInside,
 * bOutside, componentWalks}`. Pieces that came from `bmsSplit` (or `bmsBooleanOp`) keep
 * the side the library's exact split gave them; others are classified by their
 * centroid, exactly (see classifyPoints). `closedPolylines`, `segments` and
 * `meshEdgePolys` are not needed; `componentWalks` is empty.
 */
export function bmsClassify(megaSoup, closedPolylines, segments, trisA, trisB, meshEdgePolys) {
	void closedPolylines;
	void meshEdgePolys;
	return classifyPieces(megaSoup, segments, trisA, trisB);
}

// The side the library's split gave each piece it made (pieces of bmsSplit).
const splitSide = new WeakMap();

/** Records the library's side (1 inside, −1 outside) of a piece of its split. */
export function rememberSide(piece, side) {
	splitSide.set(piece, side);
}

/**
 * Pieces sorted into the four groups: each by the side its split gave it when known,
 * else by its centroid against the other input (on the other surface: inside for A,
 * outside for B, the grouping under which merged groups give exact booleans).
 */
export function classifyPieces(megaSoup, segments, soupA, soupB) {
	void segments;
	const soup = Array.isArray(megaSoup) ? megaSoup : [];
	const out = { aInside: [], aOutside: [], bInside: [], bOutside: [], componentWalks: [] };
	for (const mesh of ["A", "B"]) {
		const other = mesh === "A" ? soupB : soupA;
		const [inside, outside] = mesh === "A" ? [out.aInside, out.aOutside] : [out.bInside, out.bOutside];
		const unknown = [];
		for (const t of soup) {
			if ((t.mesh === "B" ? "B" : "A") !== mesh) continue;
			const side = splitSide.get(t);
			if (side === undefined) unknown.push(t);
			else (side > 0 ? inside : outside).push(t);
		}
		if (unknown.length === 0) continue;
		if (!Array.isArray(other) || other.length === 0) {
			outside.push(...unknown);
			continue;
		}
		const classes = classesOf(other, unknown.map(centroid));
		unknown.forEach((t, k) => {
			const c = classes[k];
			(c === 1 || (c === 2 && mesh === "A") ? inside : outside).push(t);
		});
	}
	return out;
}

/**
 * The overlap of two coplanar triangles: `{polygon, area, areaRatio}` (the convex
 * overlap polygon, its area, and the area over the smaller triangle's), or null when the
 * triangles are not coplanar or overlap in no area (neighbours sharing an edge). Decided
 * by the library's exact intersection; `options` (the reference's tolerances) are not
 * needed.
 */
export function coplanarOverlap(triA, triB, options) {
	void options;
	const A = soupToArrays([triA], "triA"), B = soupToArrays([triB], "triB");
	const raw = call("intersect", A.positions, A.index, B.positions, B.index, JSON.stringify({ withCoplanar: true }));
	if (overlapPairs(raw).size === 0) return null;
	const pool = createVertexPool(0);
	const segs = [];
	const s = raw.segments;
	for (let i = 0; i < raw.triA.length; i++) {
		if (raw.coplanar[i] !== 1) continue;
		const k = 6 * i;
		segs.push({ p0: pool.getOrCreate(s[k], s[k + 1], s[k + 2]), p1: pool.getOrCreate(s[k + 3], s[k + 4], s[k + 5]) });
	}
	const loop = chainById(segs).find((l) => l.length > 3 && l[0] === l[l.length - 1]);
	if (!loop) return null;
	const polygon = loop.slice(0, -1).map((p) => ({ x: p.x, y: p.y, z: p.z }));
	const area = polygonArea(polygon);
	const smaller = Math.min(triArea(triA), triArea(triB));
	return { polygon, area, areaRatio: smaller > 0 ? area / smaller : 0 };
}

function triArea(t) {
	return polygonArea([t.v0, t.v1, t.v2]);
}

function polygonArea(poly) {
	let x = 0, y = 0, z = 0;
	for (let i = 0; i < poly.length; i++) {
		const p = poly[i], q = poly[(i + 1) % poly.length];
		x += p.y * q.z - p.z * q.y;
		y += p.z * q.x - p.x * q.z;
		z += p.x * q.y - p.y * q.x;
	}
	return 0.5 * Math.hypot(x, y, z);
}

/**
 * The edges of an overlap polygon as segments on pool vertices: `[{p0, p1, idxA, idxB}]`
 * with `idxA`/`idxB` the `triIdx` of `refA`/`refB`.
 */
export function emitCoplanarSegments(polygon, pool, refA, refB) {
	const out = [];
	if (!Array.isArray(polygon) || polygon.length < 2) return out;
	const P = pool || createVertexPool(0);
	const verts = polygon.map((p) => P.getOrCreate(p.x, p.y, p.z));
	for (let i = 0; i < verts.length; i++) {
		const a = verts[i], b = verts[(i + 1) % verts.length];
		if (a !== b) out.push({ p0: a, p1: b, idxA: refA ? refA.triIdx : -1, idxB: refB ? refB.triIdx : -1 });
	}
	return out;
}

/**
 * Where a soup crosses or overlaps itself: `{segments, crossedSet, pool, stats}`, the
 * library's exact self-intersection (triangles that share a vertex or an edge are not a
 * crossing there), segments on pool vertices with the two triangles in `idxA`/`idxB`,
 * `crossedSet` each crossed triangle → its segments, `stats: {candidatePairs,
 * coplanarPairs, crossingPairs, refinementSplits}`.
 */
export function bmsSelfIntersect(soup, options) {
	void options;
	const S = soupToArrays(soup, "soup");
	const pool = createVertexPool(0);
	const out = { segments: [], crossedSet: {}, pool, stats: { candidatePairs: 0, coplanarPairs: 0, crossingPairs: 0, refinementSplits: 0 } };
	if (S.index.length === 0) return out;
	const raw = call("intersect", S.positions, S.index, EMPTY_F64, EMPTY_U32, JSON.stringify({ withCoplanar: true }));
	const report = JSON.parse(raw.report);
	const coplanar = new Set(), crossing = new Set();
	const s = raw.segments;
	for (let i = 0; i < raw.triA.length; i++) {
		const k = 6 * i;
		const seg = { p0: pool.getOrCreate(s[k], s[k + 1], s[k + 2]), p1: pool.getOrCreate(s[k + 3], s[k + 4], s[k + 5]), idxA: raw.triA[i], idxB: raw.triB[i] };
		out.segments.push(seg);
		(out.crossedSet[seg.idxA] ||= []).push(seg);
		(out.crossedSet[seg.idxB] ||= []).push(seg);
		const key = Math.min(seg.idxA, seg.idxB) * 4294967296 + Math.max(seg.idxA, seg.idxB);
		(raw.coplanar[i] === 1 ? coplanar : crossing).add(key);
	}
	// The self-seam lists each segment once; the report counts every pair that meets.
	const pairs = Math.max(new Set([...coplanar, ...crossing]).size, report.candidate_pairs || 0);
	out.stats.candidatePairs = pairs;
	out.stats.coplanarPairs = coplanar.size;
	out.stats.crossingPairs = pairs;
	return out;
}

/**
 * A soup cut where it crosses itself into a conforming "mega soup" of pieces `{v0, v1,
 * v2, mesh: "A", origIdx}` on pool vertices: `{megaSoup, segments, crossedSet, pool,
 * stats}` (the library's self-arrangement).
 */
export function bmsSelfArrange(soup, options) {
	const isect = bmsSelfIntersect(soup, options);
	const S = soupToArrays(soup, "soup");
	if (S.index.length === 0) return { megaSoup: [], ...isect, stats: { ...isect.stats, edgeSteinerPoints: 0, edgeSteinerTris: 0 } };
	const megaSoup = selfPieces(S, isect.pool);
	return { megaSoup, ...isect, stats: { ...isect.stats, ...edgeSteiner(S, megaSoup, isect.pool) } };
}

/** The pieces of the library's self-arrangement of `S`, on the vertices of `pool`. */
export function selfPieces(S, pool) {
	const arranged = call("selfArrange", S.positions, S.index);
	const group = { name: "a", positions: arranged.positions, index: arranged.index, source: new Uint8Array(arranged.parent.length), triangle: arranged.parent };
	return poolOfSplit([group], pool).pieces.map((t) => ({ v0: t.v0, v1: t.v1, v2: t.v2, mesh: "A", origIdx: t.origIdx }));
}

// The points the arrangement put on edges shared by two input triangles (the pieces of
// both use them: two neighbours meet only along their edge), and the input triangles
// with such a point on an edge.
function edgeSteiner(S, pieces, pool) {
	const n = S.index.length / 3;
	const id = (v) => {
		const p = pool.find(S.positions[3 * v], S.positions[3 * v + 1], S.positions[3 * v + 2]);
		return p === undefined ? `v${v}` : p.id;
	};
	const corners = Array.from({ length: n }, (_, t) => [id(S.index[3 * t]), id(S.index[3 * t + 1]), id(S.index[3 * t + 2])]);
	const used = Array.from({ length: n }, () => new Set());
	for (const t of pieces) for (const v of [t.v0, t.v1, t.v2]) used[t.origIdx].add(v.id);
	const byEdge = new Map();
	corners.forEach((c, t) => {
		for (let k = 0; k < 3; k++) {
			const a = c[k], b = c[(k + 1) % 3];
			const key = a < b ? `${a}|${b}` : `${b}|${a}`;
			if (!byEdge.has(key)) byEdge.set(key, []);
			byEdge.get(key).push(t);
		}
	});
	const points = new Set(), tris = new Set();
	for (const [key, owners] of byEdge) {
		if (owners.length !== 2) continue;
		const ends = new Set(key.split("|").map(String));
		const [t1, t2] = owners;
		for (const v of used[t1]) {
			if (ends.has(String(v)) || !used[t2].has(v)) continue;
			points.add(v);
			tris.add(t1);
			tris.add(t2);
		}
	}
	return { edgeSteinerPoints: points.size, edgeSteinerTris: tris.size };
}

/**
 * The seam points that lie on triangle edges, registered with every triangle owning the
 * edge (so that all sides split the edge at the same vertex): triangle → the pool
 * vertices on its edges. `triOf(t)` gives triangle `t`, `keyOf(t, corner)` its corner's
 * vertex key (equal keys: one vertex); a point is on an edge within `tol` of it
 * (a tolerance the caller names; 0: only points exactly on the segment's line between
 * its ends, as computed in floating point).
 */
export function buildEdgeSteinerMap(triCount, triOf, keyOf, segments, tol) {
	const owners = new Map(); // edge key → {a, b, tris: []}
	for (let t = 0; t < triCount; t++) {
		const tri = triOf(t);
		const corners = [tri.v0, tri.v1, tri.v2];
		for (let c = 0; c < 3; c++) {
			const ka = keyOf(t, c), kb = keyOf(t, (c + 1) % 3);
			const key = ka < kb ? `${ka}|${kb}` : `${kb}|${ka}`;
			if (!owners.has(key)) owners.set(key, { a: corners[c], b: corners[(c + 1) % 3], tris: [] });
			owners.get(key).tris.push(t);
		}
	}
	const out = {};
	const eps = Math.max(tol || 0, 0);
	const points = new Set();
	for (const s of segments || []) for (const p of [s.p0, s.p1]) points.add(p);
	for (const e of owners.values()) {
		const d = [e.b.x - e.a.x, e.b.y - e.a.y, e.b.z - e.a.z];
		const len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
		if (!(len2 > 0)) continue;
		for (const p of points) {
			const w = [p.x - e.a.x, p.y - e.a.y, p.z - e.a.z];
			const t = (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / len2;
			if (!(t > 0 && t < 1)) continue;
			const off = Math.hypot(w[0] - t * d[0], w[1] - t * d[1], w[2] - t * d[2]);
			if (off > eps) continue;
			for (const tri of e.tris) {
				const list = (out[tri] ||= []);
				if (!list.includes(p)) list.push(p);
			}
		}
	}
	return out;
}

/**
 * Moves every segment end within `snapTol` of a vertex of `soup` onto that vertex (the
 * segments are changed in place); the number of ends moved.
 */
export function snapEndpointsToVertices(soup, segments, snapTol) {
	const pool = createVertexPool(Math.max(snapTol || 0, 0));
	for (const t of soup || []) for (const v of [t.v0, t.v1, t.v2]) pool.getOrCreate(v.x, v.y, v.z);
	let moved = 0;
	for (const s of segments || []) {
		for (const end of ["p0", "p1"]) {
			const p = s[end];
			const v = pool.find(p.x, p.y, p.z);
			if (v !== undefined && (v.x !== p.x || v.y !== p.y || v.z !== p.z)) {
				p.x = v.x;
				p.y = v.y;
				p.z = v.z;
				moved++;
			}
		}
	}
	return moved;
}

/**
 * A tagged soup welded within `tol` to shared representative vertices (the first seen
 * of each cluster; `seedVertices` first): `{soup, repOf(x, y, z)}`, `mesh` and `origIdx`
 * kept, `repOf` the representative within `tol` of a point, or null.
 */
export function weldTaggedSoup(soup, tol, seedVertices) {
	const pool = createVertexPool(Math.max(tol || 0, 0));
	for (const v of seedVertices || []) pool.getOrCreate(v.x, v.y, v.z);
	const out = (soup || []).map((t) => {
		const w = { v0: pool.getOrCreate(t.v0.x, t.v0.y, t.v0.z), v1: pool.getOrCreate(t.v1.x, t.v1.y, t.v1.z), v2: pool.getOrCreate(t.v2.x, t.v2.y, t.v2.z) };
		if (t.mesh !== undefined) w.mesh = t.mesh;
		if (t.origIdx !== undefined) w.origIdx = t.origIdx;
		return w;
	});
	return { soup: out, repOf: (x, y, z) => pool.find(x, y, z) || null };
}

/**
 * Brings a nearly conforming arrangement toward watertight: open-edge vertices within
 * `seamTol` welded, then boundary loops capped (closeSolid, up to `maxPasses` rounds, no
 * limit on loop size). A watertight soup comes back as it is (the same array). `{soup,
 * openBefore, openAfter, capsAdded, snaps}`.
 */
export function conditionArrangement(soup, seamTol, maxPasses = 3) {
	const S = soupToArrays(soup || [], "soup");
	const open = (arrays) => (arrays.index.length === 0 ? 0 : call("measures", ...weld(arrays))[3]);
	const openBefore = open(S);
	if (openBefore === 0) return { soup, openBefore, openAfter: 0, capsAdded: 0, snaps: 0 };
	const before = conditioned(S, false).positions.length / 3;
	const closed = closeSolid(soup, { snapTolerance: Math.max(seamTol || 0, 0), maxCapLoopVerts: Infinity, maxPasses });
	const C = soupToArrays(closed.soup, "soup");
	const after = C.index.length > 0 ? conditioned(C, false).positions.length / 3 : 0;
	return { soup: closed.soup, openBefore, openAfter: closed.diagnostics.openEdges, capsAdded: closed.diagnostics.capTriangles, snaps: Math.max(0, before - after) };
}

/**
 * Near-coincident faces made coincident: pairs of triangles whose corners match within
 * `tol` (and are not already equal) have the second's corners moved onto the first's.
 * `{soup, snappedVertices, coincidentPairs}`; a soup with no such pair comes back as the
 * same array.
 */
export function snapCoincidentSheets(soup, tol) {
	const t = Math.max(tol || 0, 0);
	const list = Array.isArray(soup) ? soup : [];
	const cell = 2 * Math.max(t, 1e-300);
	const grid = new Map();
	const key = (p) => `${Math.floor(p.x / cell)},${Math.floor(p.y / cell)},${Math.floor(p.z / cell)}`;
	list.forEach((tri, i) => {
		const k = key(centroid(tri));
		if (!grid.has(k)) grid.set(k, []);
		grid.get(k).push(i);
	});
	const near = (p, q) => Math.abs(p.x - q.x) <= t && Math.abs(p.y - q.y) <= t && Math.abs(p.z - q.z) <= t;
	const same = (p, q) => p.x === q.x && p.y === q.y && p.z === q.z;
	const moves = new Map(); // triangle index → its corners moved
	let pairs = 0;
	list.forEach((tri, i) => {
		const c = centroid(tri);
		const cx = Math.floor(c.x / cell), cy = Math.floor(c.y / cell), cz = Math.floor(c.z / cell);
		for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
			for (const j of grid.get(`${cx + dx},${cy + dy},${cz + dz}`) || []) {
				if (j <= i || moves.has(j)) continue;
				const other = list[j];
				const mine = [tri.v0, tri.v1, tri.v2];
				const theirs = [other.v0, other.v1, other.v2];
				const match = theirs.map((q) => mine.find((p) => near(p, q)));
				if (match.some((m) => m === undefined) || new Set(match).size !== 3) continue;
				if (match.every((m, k) => same(m, theirs[k]))) continue;
				pairs++;
				moves.set(j, match);
			}
		}
	});
	if (pairs === 0) return { soup, snappedVertices: 0, coincidentPairs: 0 };
	let snapped = 0;
	const out = list.map((tri, i) => {
		const m = moves.get(i);
		if (!m) return tri;
		const corners = [tri.v0, tri.v1, tri.v2];
		m.forEach((p, k) => {
			if (!same(p, corners[k])) snapped++;
		});
		return { ...tri, v0: { x: m[0].x, y: m[0].y, z: m[0].z }, v1: { x: m[1].x, y: m[1].y, z: m[1].z }, v2: { x: m[2].x, y: m[2].y, z: m[2].z } };
	});
	return { soup: out, snappedVertices: snapped, coincidentPairs: pairs };
}

/**
 * The reference's winding-step extraction: each sub-triangle kept where
 * `windingFn` on its two sides (at its centroid moved `offsetFactor` (default 1e-4) ×
 * its longest edge along its normal) straddles `threshold` (default 0.5), reversed
 * where its front is the inside. `{kept, dropped, flipped, keptFlags, flipFlags}`. The
 * decision is the caller's winding function's; meshbool's own resolve decides exactly
 * (bmsSelfResolve).
 */
export function extractByWinding(subTris, windingFn, options) {
	const o = options || {};
	const threshold = o.threshold !== undefined ? o.threshold : 0.5;
	const factor = o.offsetFactor !== undefined ? o.offsetFactor : 1e-4;
	const tris = Array.isArray(subTris) ? subTris : [];
	const keptFlags = new Uint8Array(tris.length), flipFlags = new Uint8Array(tris.length);
	const kept = [];
	let dropped = 0, flipped = 0;
	tris.forEach((t, i) => {
		const side = sidesOf(t, windingFn, factor, threshold);
		if (side === 0) {
			dropped++;
			return;
		}
		keptFlags[i] = 1;
		if (side < 0) {
			flipFlags[i] = 1;
			flipped++;
			kept.push({ ...t, v0: t.v0, v1: t.v2, v2: t.v1 });
		} else kept.push(t);
	});
	return { kept, dropped, flipped, keptFlags, flipFlags };
}

// 1 when the back of `t` is inside and its front outside, −1 the other way, 0 when both
// sides agree (or the triangle has no normal).
function sidesOf(t, windingFn, factor, threshold) {
	const u = [t.v1.x - t.v0.x, t.v1.y - t.v0.y, t.v1.z - t.v0.z], v = [t.v2.x - t.v0.x, t.v2.y - t.v0.y, t.v2.z - t.v0.z];
	const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
	const len = Math.hypot(n[0], n[1], n[2]);
	if (!(len > 0)) return 0;
	const w = [t.v2.x - t.v1.x, t.v2.y - t.v1.y, t.v2.z - t.v1.z];
	const h = factor * Math.max(Math.hypot(...u), Math.hypot(...v), Math.hypot(...w));
	const c = centroid(t);
	const at = (s) => windingFn(c.x + (s * h * n[0]) / len, c.y + (s * h * n[1]) / len, c.z + (s * h * n[2]) / len) >= threshold;
	const front = at(1), back = at(-1);
	if (front === back) return 0;
	return back ? 1 : -1;
}

/**
 * The reference's patch extraction: sub-triangles grouped into patches (edge-connected,
 * not across edges whose keys are in `barrierKeys`: `edgeKey(vKey(a), vKey(b))`), one
 * decision per patch by the majority of up to `samplesPerPatch` (default 5) of its
 * triangles (see extractByWinding). `{kept, patches, keptPatches, droppedPatches}`.
 */
export function extractByWindingPatches(subTris, barrierKeys, windingFn, options) {
	const o = options || {};
	const threshold = o.threshold !== undefined ? o.threshold : 0.5;
	const factor = o.offsetFactor !== undefined ? o.offsetFactor : 1e-4;
	const samples = Math.max(1, o.samplesPerPatch || 5);
	const tris = Array.isArray(subTris) ? subTris : [];
	const barrier = barrierKeys || {};
	const ek = (a, b) => edgeKey(vKey(a), vKey(b));
	const byEdge = new Map();
	tris.forEach((t, i) => {
		for (const [a, b] of [[t.v0, t.v1], [t.v1, t.v2], [t.v2, t.v0]]) {
			const k = ek(a, b);
			if (!byEdge.has(k)) byEdge.set(k, []);
			byEdge.get(k).push(i);
		}
	});
	const patch = new Int32Array(tris.length).fill(-1);
	let patches = 0;
	for (let s = 0; s < tris.length; s++) {
		if (patch[s] >= 0) continue;
		const stack = [s];
		patch[s] = patches;
		while (stack.length) {
			const i = stack.pop();
			const t = tris[i];
			for (const [a, b] of [[t.v0, t.v1], [t.v1, t.v2], [t.v2, t.v0]]) {
				const k = ek(a, b);
				if (barrier[k]) continue;
				for (const j of byEdge.get(k)) {
					if (patch[j] < 0) {
						patch[j] = patches;
						stack.push(j);
					}
				}
			}
		}
		patches++;
	}
	const members = Array.from({ length: patches }, () => []);
	tris.forEach((_, i) => members[patch[i]].push(i));
	const kept = [];
	let keptPatches = 0;
	for (const list of members) {
		const step = Math.max(1, Math.floor(list.length / samples));
		let vote = 0;
		for (let k = 0; k < list.length; k += step) vote += sidesOf(tris[list[k]], windingFn, factor, threshold);
		if (vote === 0) continue;
		keptPatches++;
		for (const i of list) {
			const t = tris[i];
			kept.push(vote > 0 ? t : { ...t, v0: t.v0, v1: t.v2, v2: t.v1 });
		}
	}
	return { kept, patches, keptPatches, droppedPatches: patches - keptPatches };
}
