// The reference's BMS stages ("boolean by mesh split") as views of meshbool's exact split:
// the vertex pool of the pieces, the seam segments read off the pieces themselves (so
// that every segment is an edge of a piece of A and of a piece of B), and the
// reference's read-only classification checks. Nothing here decides a side: the split
// is exact; these functions describe it in the reference's terms.
import { call } from "./native.js";
import { edgeKey } from "./convert.js";

/**
 * A pool of vertices `{x, y, z, id}` (ids 0, 1, ... in order of creation):
 * `getOrCreate(x, y, z, triRef)` returns the pool's vertex at that position, made when
 * there is none; positions within `tolerance` (default 0: exactly equal) of a vertex are
 * that vertex (the nearest such). `triRef` (the reference's triangle reference) is
 * accepted and not used. `find(x, y, z)` (the vertex there, or undefined), `get(id)`,
 * `getAll()` (the vertices, by id), `size()`.
 */
export function createVertexPool(tolerance = 0) {
	if (!(tolerance >= 0) || !Number.isFinite(tolerance)) throw new Error(`meshbool: the pool tolerance must be a finite number >= 0, got ${tolerance}`);
	const all = [];
	const exact = new Map();
	const cell = tolerance > 0 ? 2 * tolerance : 0;
	const grid = new Map();
	const cellKey = (x, y, z) => `${Math.floor(x / cell)},${Math.floor(y / cell)},${Math.floor(z / cell)}`;
	function find(x, y, z) {
		const hit = exact.get(`${x},${y},${z}`);
		if (hit !== undefined || cell === 0) return hit;
		const cx = Math.floor(x / cell), cy = Math.floor(y / cell), cz = Math.floor(z / cell);
		let best, bestD = tolerance * tolerance;
		for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
			for (const v of grid.get(`${cx + dx},${cy + dy},${cz + dz}`) || []) {
				const d = (v.x - x) ** 2 + (v.y - y) ** 2 + (v.z - z) ** 2;
				if (d <= bestD) {
					bestD = d;
					best = v;
				}
			}
		}
		return best;
	}
	function getOrCreate(x, y, z) {
		if (!Number.isFinite(x) || !Number.isFinite(y) || !Number.isFinite(z)) throw new Error(`meshbool: a pool vertex needs finite coordinates, got (${x}, ${y}, ${z})`);
		const found = find(x, y, z);
		if (found !== undefined) return found;
		const v = { x, y, z, id: all.length };
		all.push(v);
		exact.set(`${x},${y},${z}`, v);
		if (cell > 0) {
			const k = cellKey(x, y, z);
			if (!grid.has(k)) grid.set(k, []);
			grid.get(k).push(v);
		}
		return v;
	}
	return {
		tolerance,
		getOrCreate,
		find,
		get: (id) => all[id],
		getAll: () => all.slice(),
		size: () => all.length,
	};
}

/**
 * The pieces of the library's split (its groups, as the `split` call returns them) in
 * one pool: `{pool, pieces: [{v0, v1, v2, mesh, origIdx, group}]}`. Piece corners are
 * the pool's vertices (shared, with ids). `pool`: the pool to add the vertices to (a
 * fresh exact one by default).
 */
export function poolOfSplit(rawGroups, pool = createVertexPool(0)) {
	const pieces = [];
	for (const g of rawGroups) {
		const p = g.positions, ix = g.index;
		const verts = new Array(p.length / 3);
		for (let v = 0; v < verts.length; v++) verts[v] = pool.getOrCreate(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
		for (let t = 0; t < ix.length / 3; t++) {
			pieces.push({
				v0: verts[ix[3 * t]],
				v1: verts[ix[3 * t + 1]],
				v2: verts[ix[3 * t + 2]],
				mesh: g.source[t] === 1 ? "B" : "A",
				origIdx: g.triangle[t],
				group: g.name,
			});
		}
	}
	return { pool, pieces };
}

/**
 * The seam of a split in its pool's vertices: the library's exact crossing segments
 * (the `intersect` call's output; coplanar ones only with `coplanar`, and only those
 * outlining an overlap with area, see overlapPairs), each end taken to
 * the pool vertex at its position (within `tolerance` where the split was snapped).
 * Segments whose ends became one vertex are gone, and a segment listed for several
 * triangle pairs is one. `{segments: [{p0, p1, idxA, idxB}], lost}` (`lost`: segments
 * with an end that is no vertex of the pieces).
 */
export function seamInPool(raw, pool, tolerance, coplanar) {
	const finder = createVertexPool(tolerance);
	const byId = new Map();
	for (const v of pool.getAll()) {
		const f = finder.getOrCreate(v.x, v.y, v.z);
		if (!byId.has(f.id)) byId.set(f.id, v);
	}
	const segments = [], seen = new Set();
	let lost = 0;
	const s = raw.segments;
	const overlap = overlapPairs(raw);
	for (let i = 0; i < raw.triA.length; i++) {
		if (raw.coplanar[i] === 1 && (!coplanar || !overlap.has(pairKey(raw, i)))) continue;
		const k = 6 * i;
		const f0 = finder.find(s[k], s[k + 1], s[k + 2]), f1 = finder.find(s[k + 3], s[k + 4], s[k + 5]);
		if (f0 === undefined || f1 === undefined) {
			lost++;
			continue;
		}
		const p0 = byId.get(f0.id), p1 = byId.get(f1.id);
		if (p0 === p1) continue;
		const key = Math.min(p0.id, p1.id) * 4294967296 + Math.max(p0.id, p1.id);
		if (seen.has(key)) continue;
		seen.add(key);
		segments.push({ p0, p1, idxA: raw.triA[i], idxB: raw.triB[i] });
	}
	return { segments, lost };
}

function pairKey(raw, i) {
	return raw.triA[i] * 4294967296 + raw.triB[i];
}

/**
 * The triangle pairs whose coplanar segments outline an overlap with area (three or more
 * segments for the pair); pairs of coplanar neighbours that only share an edge or touch
 * at a corner have fewer, and are a touch, not an overlap.
 */
export function overlapPairs(raw) {
	const count = new Map();
	for (let i = 0; i < raw.triA.length; i++) {
		if (raw.coplanar[i] !== 1) continue;
		const k = pairKey(raw, i);
		count.set(k, (count.get(k) || 0) + 1);
	}
	const out = new Set();
	for (const [k, n] of count) if (n >= 3) out.add(k);
	return out;
}

/** A key of a vertex: its pool id when it has one, else its exact coordinates. */
function vertexKey(v) {
	return typeof v.id === "number" ? `#${v.id}` : `${v.x},${v.y},${v.z}`;
}

function edgeKeyOf(p, q) {
	return edgeKey(vertexKey(p), vertexKey(q));
}

/** The vertex keys on open edges (edges of one triangle) of a soup. */
function openVertexKeys(soup) {
	const uses = new Map();
	for (const t of soup) {
		for (const [p, q] of [[t.v0, t.v1], [t.v1, t.v2], [t.v2, t.v0]]) {
			const k = edgeKeyOf(p, q);
			const e = uses.get(k);
			if (e) e.n++;
			else uses.set(k, { n: 1, p, q });
		}
	}
	const keys = new Set();
	for (const e of uses.values()) {
		if (e.n === 1) {
			keys.add(vertexKey(e.p));
			keys.add(vertexKey(e.q));
			keys.add(`${e.p.x},${e.p.y},${e.p.z}`);
			keys.add(`${e.q.x},${e.q.y},${e.q.z}`);
		}
	}
	return keys;
}

/**
 * The reference's read-only checks of a split classification. `megaSoup`: the pieces
 * `{v0, v1, v2, mesh: "A" | "B"}`; `sides[i]`: 1 inside, −1 outside; `segments`: the seam
 * `{p0, p1}`; `polylines`: the seam chained (arrays of points); `A`, `B`: the input soups.
 * `{ok, counts: {A: {inside, outside}, B: {...}}, failures: [{check, mesh, ...}]}`:
 * - "partition": a mesh crossed by the seam with all its pieces on one side;
 * - "chainClosure": an open chain whose end is on no open edge of the pieces or the
 *   inputs, and not (by vertex id, else position) the end of another chain;
 * - "barrierConstraint": seam edges of a mesh whose two pieces of that mesh carry the
 *   same side (`count` of them; a failure when there are at least `minBarrierViolations`,
 *   default 2, so that a single tangent touch is not called a failure).
 */
export function verifyBmsClassification(megaSoup, sides, segments, polylines, A, B, options) {
	const o = options || {};
	const soup = Array.isArray(megaSoup) ? megaSoup : [];
	const counts = { A: { inside: 0, outside: 0 }, B: { inside: 0, outside: 0 } };
	soup.forEach((t, i) => {
		const c = counts[t.mesh === "B" ? "B" : "A"];
		if (sides[i] > 0) c.inside++;
		else if (sides[i] < 0) c.outside++;
	});
	const failures = [];
	const segs = Array.isArray(segments) ? segments : [];
	if (segs.length > 0) {
		for (const mesh of ["A", "B"]) {
			const c = counts[mesh];
			if (c.inside + c.outside > 0 && (c.inside === 0 || c.outside === 0)) {
				failures.push({ check: "partition", mesh, detail: `${mesh} has ${c.inside} pieces inside and ${c.outside} outside although the seam crosses it` });
			}
		}
	}
	const lines = Array.isArray(polylines) ? polylines : [];
	const open = new Set([...openVertexKeys(soup), ...openVertexKeys(A || []), ...openVertexKeys(B || [])]);
	const ends = new Map();
	for (const line of lines) {
		if (!Array.isArray(line) || line.length < 2) continue;
		for (const p of [line[0], line[line.length - 1]]) ends.set(vertexKey(p), (ends.get(vertexKey(p)) || 0) + 1);
	}
	lines.forEach((line, index) => {
		if (!Array.isArray(line) || line.length < 2) return;
		const first = line[0], last = line[line.length - 1];
		if (vertexKey(first) === vertexKey(last)) return;
		for (const p of [first, last]) {
			const onBoundary = open.has(vertexKey(p)) || open.has(`${p.x},${p.y},${p.z}`);
			const joined = ends.get(vertexKey(p)) > 1;
			if (!onBoundary && !joined) {
				failures.push({ check: "chainClosure", mesh: null, polyline: index, detail: `chain ${index} ends at (${p.x}, ${p.y}, ${p.z}), on no open edge and no other chain's end` });
				return;
			}
		}
	});
	const seam = new Set(segs.map((s) => edgeKeyOf(s.p0, s.p1)));
	const minViolations = o.minBarrierViolations !== undefined ? o.minBarrierViolations : 2;
	for (const mesh of ["A", "B"]) {
		const onEdge = new Map();
		soup.forEach((t, i) => {
			if ((t.mesh === "B" ? "B" : "A") !== mesh) return;
			for (const [p, q] of [[t.v0, t.v1], [t.v1, t.v2], [t.v2, t.v0]]) {
				const k = edgeKeyOf(p, q);
				if (!seam.has(k)) continue;
				if (!onEdge.has(k)) onEdge.set(k, []);
				onEdge.get(k).push(sides[i]);
			}
		});
		let violations = 0;
		for (const s of onEdge.values()) if (s.length === 2 && s[0] === s[1]) violations++;
		if (violations >= minViolations) {
			failures.push({ check: "barrierConstraint", mesh, count: violations, detail: `${violations} seam edges of ${mesh} with the same side on both pieces` });
		}
	}
	return { ok: failures.length === 0, counts, failures };
}

/** The boxes of two soups: whether they are apart, touch, or overlap with area or volume. */
export function boxesOverlapWithArea(A, B) {
	const box = (soup) => {
		const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
		for (const t of soup) {
			for (const v of [t.v0, t.v1, t.v2]) {
				const p = [v.x, v.y, v.z];
				for (let k = 0; k < 3; k++) {
					if (p[k] < lo[k]) lo[k] = p[k];
					if (p[k] > hi[k]) hi[k] = p[k];
				}
			}
		}
		return { lo, hi };
	};
	const a = box(A), b = box(B);
	let positive = 0;
	for (let k = 0; k < 3; k++) {
		const lo = Math.max(a.lo[k], b.lo[k]), hi = Math.min(a.hi[k], b.hi[k]);
		if (hi < lo) return false;
		if (hi > lo) positive++;
	}
	return positive >= 2;
}

/** The number of edges of more than two triangles of a soup's flat arrays (exact weld). */
export function nonManifoldEdgeCount(S) {
	if (S.index.length === 0) return 0;
	return call("measures", ...weldedArrays(S))[4];
}

function weldedArrays(S) {
	const w = call("weld", S.positions, S.index, 0);
	return [w.positions, w.index];
}

/** The mean edge length of the first `n` (default 200) triangles of a soup's arrays. */
export function meanEdge(S, n = 200) {
	const p = S.positions, ix = S.index;
	const count = Math.min(n, ix.length / 3);
	let sum = 0;
	for (let t = 0; t < count; t++) {
		for (let k = 0; k < 3; k++) {
			const a = 3 * ix[3 * t + k], b = 3 * ix[3 * t + ((k + 1) % 3)];
			sum += Math.hypot(p[a] - p[b], p[a + 1] - p[b + 1], p[a + 2] - p[b + 2]);
		}
	}
	return count > 0 ? sum / (3 * count) : 0;
}

/**
 * Chains segments into polylines by vertex identity (pool id, else exact position):
 * chains run through vertices of two segments and stop at others; a closed chain repeats
 * its first point at the end.
 */
export function chainById(segments) {
	const at = new Map();
	segments.forEach((s, i) => {
		for (const v of [s.p0, s.p1]) {
			const k = vertexKey(v);
			if (!at.has(k)) at.set(k, []);
			at.get(k).push(i);
		}
	});
	const used = new Uint8Array(segments.length);
	const other = (s, v) => (vertexKey(s.p0) === vertexKey(v) ? s.p1 : s.p0);
	const degree = (v) => at.get(vertexKey(v)).length;
	const walk = (line, from) => {
		for (let v = from; ; ) {
			const next = at.get(vertexKey(v)).filter((i) => !used[i]);
			if (degree(v) !== 2 || next.length === 0) return;
			used[next[0]] = 1;
			v = other(segments[next[0]], v);
			line.push(v);
		}
	};
	const lines = [];
	// Chains from the ends first (vertices not of two segments), then the loops left.
	for (const pass of [0, 1]) {
		segments.forEach((s, i) => {
			if (used[i]) return;
			const startAtEnd = degree(s.p0) !== 2 ? s.p0 : degree(s.p1) !== 2 ? s.p1 : null;
			if (pass === 0 && startAtEnd === null) return;
			const first = startAtEnd || s.p0;
			used[i] = 1;
			const line = [first, other(s, first)];
			walk(line, line[1]);
			lines.push(line);
		});
	}
	return lines;
}
