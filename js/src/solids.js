// Solids from soups: the vertex-identity rule of the package's door, orientation with the
// reference's diagnostics, closing by capping small holes, and coincident-face
// cancellation. Topology (which edges are shared, which loops are holes) is counted here
// on vertex indices; every geometric decision (welds, orientation facing, the triangles
// of a cap) is the library's.
import { call } from "./native.js";
import { arraysToSoup, soupToArrays } from "./convert.js";

/**
 * A soup's flat arrays with the library's vertex-identity rule applied: exactly equal
 * positions are one vertex, and boundary positions within rounding noise (a few units in
 * the last place of the largest coordinate) are merged where that closes edges and makes
 * none non-manifold (nor, with `keepConsistent`, inconsistently wound). Triangles keep
 * their places and count. `{positions, index, merged}`.
 */
export function conditioned(S, keepConsistent = true) {
	if (S.index.length === 0) return { positions: S.positions, index: S.index, merged: 0 };
	return call("condition", S.positions, S.index, keepConsistent);
}

/** Whether triangle `t` of `index` has two equal corners. */
function collapsedAt(index, t) {
	const a = index[3 * t], b = index[3 * t + 1], c = index[3 * t + 2];
	return a === b || b === c || c === a;
}

/**
 * The edges of an indexed mesh: `Map(key → {a, b, uses: [[t, forward]]})` with `a < b`
 * and `forward` true where triangle `t` runs from `a` to `b`. Collapsed triangles are
 * left out.
 */
export function edgeTable(index) {
	const edges = new Map();
	const n = index.length / 3;
	for (let t = 0; t < n; t++) {
		if (collapsedAt(index, t)) continue;
		for (let k = 0; k < 3; k++) {
			const u = index[3 * t + k], v = index[3 * t + ((k + 1) % 3)];
			const a = Math.min(u, v), b = Math.max(u, v);
			const key = a * 4294967296 + b;
			let e = edges.get(key);
			if (e === undefined) {
				e = { a, b, uses: [] };
				edges.set(key, e);
			}
			e.uses.push([t, u === a]);
		}
	}
	return edges;
}

/** Edges used by exactly two triangles running the same way (winding violations). */
export function windingViolations(index) {
	let n = 0;
	for (const e of edgeTable(index).values()) {
		if (e.uses.length === 2 && e.uses[0][1] === e.uses[1][1]) n++;
	}
	return n;
}

/** Whether the corners of triangle `t` in `p` are those of `q` in reverse cyclic order. */
function reversedAt(p, q, t) {
	const a = p[3 * t], b = p[3 * t + 1], c = p[3 * t + 2];
	const x = q[3 * t], y = q[3 * t + 1], z = q[3 * t + 2];
	const same = (a === x && b === y && c === z) || (a === y && b === z && c === x) || (a === z && b === x && c === y);
	return !same;
}

/** Edge-connected components of an indexed mesh: `{count, ids, closed: [bool]}`. */
function componentsOf(positions, index) {
	const { count, ids } = call("components", positions, index);
	const closed = new Array(count).fill(true);
	for (const e of edgeTable(index).values()) {
		if (e.uses.length !== 2) for (const [t] of e.uses) closed[ids[t]] = false;
	}
	return { count, ids, closed };
}

/**
 * Makes the winding coherent across every shared edge and (unless `coherenceOnly` or
 * `outward: false`) points each closed component outward; open components are made
 * coherent only. The input is not changed. `{soup, diagnostics}` with the reference's
 * fields: `windingViolationsBefore`, `windingViolationsAfter` (edges of two triangles
 * running the same way), `flippedForCoherence` (triangles), `componentsFlippedForDirection`,
 * `components`, `closedComponents`, `openComponents`, `signedVolume`.
 */
export function orientSolid(soup, options) {
	const r = orientArrays(soupToArrays(soup, "soup"), options);
	return { soup: r.index.length === 0 ? [] : arraysToSoup(r.positions, r.index), diagnostics: r.diagnostics };
}

/**
 * `orientSolid` on flat arrays: `{positions, index, diagnostics, reversed}` (`reversed`:
 * the triangles whose winding changed).
 */
export function orientArrays(S, options) {
	const o = options || {};
	const outward = !(o.coherenceOnly || o.outward === false);
	const M = conditioned(S, false);
	const diagnostics = {
		windingViolationsBefore: 0,
		windingViolationsAfter: 0,
		flippedForCoherence: 0,
		componentsFlippedForDirection: 0,
		components: 0,
		closedComponents: 0,
		openComponents: 0,
		signedVolume: 0,
	};
	if (M.index.length === 0) return { positions: M.positions, index: M.index, diagnostics, reversed: 0 };
	diagnostics.windingViolationsBefore = windingViolations(M.index);
	const coherent = call("orient", M.positions, M.index, "majority");
	const n = M.index.length / 3;
	for (let t = 0; t < n; t++) if (reversedAt(M.index, coherent.index, t)) diagnostics.flippedForCoherence++;
	const comps = componentsOf(coherent.positions, coherent.index);
	const index = Uint32Array.from(coherent.index);
	if (outward) {
		const facing = call("orient", coherent.positions, coherent.index, "outward");
		const flip = new Array(comps.count).fill(false);
		for (let t = 0; t < n; t++) {
			if (comps.closed[comps.ids[t]] && reversedAt(coherent.index, facing.index, t)) flip[comps.ids[t]] = true;
		}
		for (let t = 0; t < n; t++) {
			if (flip[comps.ids[t]]) index.set(facing.index.subarray(3 * t, 3 * t + 3), 3 * t);
		}
		diagnostics.componentsFlippedForDirection = flip.filter(Boolean).length;
	}
	diagnostics.components = comps.count;
	diagnostics.closedComponents = comps.closed.filter(Boolean).length;
	diagnostics.openComponents = comps.count - diagnostics.closedComponents;
	diagnostics.windingViolationsAfter = windingViolations(index);
	diagnostics.signedVolume = call("measures", coherent.positions, index)[0];
	let reversed = 0;
	for (let t = 0; t < n; t++) if (reversedAt(M.index, index, t)) reversed++;
	return { positions: coherent.positions, index, diagnostics, reversed };
}

/**
 * The solid a self-crossing or self-overlapping mesh encloses (flat arrays), in the
 * reference's terms: `{positions, index, changed, diagnostics}`. With `preOrient` (the
 * default) the mesh is first oriented coherently and outward (`orientArrays`); then the
 * library's resolve (fill rule `rule`, default "positive": winding number at least 1)
 * cuts it where it crosses itself and keeps the pieces that bound the solid. When
 * nothing changed, the caller's own arrays come back. Diagnostics: `coplanarPairs`
 * (pairs of triangles overlapping in one plane), `crossingPairs` (pairs that meet other
 * than in shared vertices and edges), `preOrient`, `preOrientFlips` (triangles reversed
 * by it), `preOrientSeamViolations` (edges it could not make consistent: the surface is
 * not orientable there), `outputTris`, `orient` (orientSolid's diagnostics of the
 * output), and beside them the library's resolve report (`closed`, `volume`, `resolve`,
 * ...); `error`, with the input returned, when the mesh cannot be resolved (a
 * non-orientable surface, say).
 */
export function selfResolveArrays(S, options) {
	const o = options || {};
	const preOrient = o.preOrient !== false;
	const diagnostics = { coplanarPairs: 0, crossingPairs: 0, preOrient, preOrientFlips: 0, preOrientSeamViolations: 0, outputTris: S.index.length / 3 };
	if (S.index.length === 0) return { positions: S.positions, index: S.index, changed: false, diagnostics };
	let M = S;
	if (preOrient) {
		const r = orientArrays(S);
		diagnostics.preOrientFlips = r.reversed;
		diagnostics.preOrientSeamViolations = r.diagnostics.windingViolationsAfter;
		M = { positions: r.positions, index: r.index };
	}
	const pairs = call("intersect", M.positions, M.index, new Float64Array(0), new Uint32Array(0), JSON.stringify({ withCoplanar: true }));
	const coplanar = new Set(), crossing = new Set();
	for (let i = 0; i < pairs.triA.length; i++) {
		const a = Math.min(pairs.triA[i], pairs.triB[i]), b = Math.max(pairs.triA[i], pairs.triB[i]);
		(pairs.coplanar[i] === 1 ? coplanar : crossing).add(a * 4294967296 + b);
	}
	// Coplanar pairs: overlaps the seam shows, and triangles on the same three vertices
	// (a membrane: a face and its reverse), which share all their corners.
	const sameCorners = new Map();
	for (let t = 0; t < M.index.length / 3; t++) {
		const key = Array.from(M.index.subarray(3 * t, 3 * t + 3)).sort((p, q) => p - q).join(",");
		sameCorners.set(key, (sameCorners.get(key) || 0) + 1);
	}
	let coincident = 0;
	for (const n of sameCorners.values()) coincident += (n * (n - 1)) / 2;
	diagnostics.coplanarPairs = coplanar.size + coincident;
	diagnostics.crossingPairs = new Set([...coplanar, ...crossing]).size;
	let out;
	try {
		out = call("resolve", M.positions, M.index, o.rule || "positive", !!o.keepNonmanifold);
	} catch (e) {
		diagnostics.error = e instanceof Error ? e.message : String(e);
		return { positions: S.positions, index: S.index, changed: false, diagnostics };
	}
	const report = JSON.parse(out.report);
	Object.assign(diagnostics, report, { preOrient });
	diagnostics.crossingPairs = Math.max(diagnostics.crossingPairs, report.self_intersections);
	const r = report.resolve;
	const changed = diagnostics.preOrientFlips > 0 || report.self_intersections > 0 || r.dropped_components > 0 || r.flipped_components > 0 || r.patches_dropped > 0 || r.patches_flipped > 0;
	if (!changed) {
		diagnostics.orient = orientArrays(S, { coherenceOnly: true }).diagnostics;
		return { positions: S.positions, index: S.index, changed: false, diagnostics };
	}
	diagnostics.outputTris = out.index.length / 3;
	diagnostics.orient = orientArrays(out, { coherenceOnly: true }).diagnostics;
	return { positions: out.positions, index: out.index, changed: true, diagnostics };
}

/**
 * The boundary of an indexed mesh as simple loops: each loop a list of vertices
 * `[v0, v1, ...]` such that the mesh runs `v_i → v_{i+1}` along its open edges. A loop
 * through a vertex twice (two holes meeting at a pinch vertex) is split there into
 * simple loops.
 */
export function simpleBoundaryLoops(index) {
	const next = new Map(); // vertex → [vertices it runs to along open edges]
	let open = 0;
	for (const e of edgeTable(index).values()) {
		if (e.uses.length !== 1) continue;
		const [, forward] = e.uses[0];
		const from = forward ? e.a : e.b, to = forward ? e.b : e.a;
		if (!next.has(from)) next.set(from, []);
		next.get(from).push(to);
		open++;
	}
	const loops = [];
	while (open > 0) {
		let start = -1;
		for (const [v, outs] of next) {
			if (outs.length > 0) {
				start = v;
				break;
			}
		}
		if (start < 0) break;
		// Walk until the walk comes back to a vertex on it: the part from that vertex's
		// first visit is a simple loop; cut it off and carry on from there.
		const path = [start];
		const at = new Map([[start, 0]]);
		let v = start;
		for (;;) {
			const outs = next.get(v);
			if (!outs || outs.length === 0) {
				// An open chain (an edge used once whose end has no open edge onward: only
				// at non-manifold vertices); left as it is.
				path.length = 0;
				break;
			}
			const w = outs.pop();
			open--;
			if (at.has(w)) {
				const i = at.get(w);
				const loop = path.splice(i);
				for (const u of loop) at.delete(u);
				loops.push(loop);
				if (path.length === 0) break;
				v = path[path.length - 1];
				continue;
			}
			at.set(w, path.length);
			path.push(w);
			v = w;
		}
	}
	return loops;
}

/**
 * Closes a soup into a solid without deleting anything: vertices within `snapTolerance`
 * (default 0.001) welded, then each boundary loop of at most `maxCapLoopVerts` vertices
 * (default 32) capped with triangles on that loop; larger loops are listed, never capped.
 * Boundaries through a pinch vertex are split into simple loops first. Up to `maxPasses`
 * (default 3) rounds while a round caps something. The input is not changed. `{soup,
 * diagnostics: {closed, openEdges, nonManifoldEdges, capTriangles, cappedLoops,
 * skippedLargeLoops, openLoops, loopSizes, volume}}` (`skippedLargeLoops`, `loopSizes`:
 * vertex counts of the loops too large to cap, and of every loop found in the first
 * round; `volume`: the signed volume of the result).
 */
export function closeSolid(soup, options) {
	const o = options || {};
	const snap = o.snapTolerance !== undefined ? o.snapTolerance : 0.001;
	const maxVerts = o.maxCapLoopVerts !== undefined ? o.maxCapLoopVerts : 32;
	const passes = o.maxPasses !== undefined ? o.maxPasses : 3;
	const diagnostics = { closed: false, openEdges: 0, nonManifoldEdges: 0, capTriangles: 0, cappedLoops: 0, skippedLargeLoops: [], openLoops: 0, loopSizes: [] };
	let S = soupToArrays(soup, "soup");
	if (S.index.length === 0) return { soup: [], diagnostics };
	S = snap > 0 ? call("weld", S.positions, S.index, snap) : conditioned(S);
	let positions = S.positions, index = S.index;
	let skipped = [];
	for (let pass = 0; pass < Math.max(1, passes); pass++) {
		const loops = simpleBoundaryLoops(index);
		if (pass === 0) diagnostics.loopSizes = loops.map((l) => l.length);
		skipped = [];
		const caps = [];
		for (const loop of loops) {
			if (loop.length < 3 || loop.length > maxVerts) {
				skipped.push(loop.length);
				continue;
			}
			const tris = capOf(positions, loop);
			if (tris.length === 0) {
				skipped.push(loop.length);
				continue;
			}
			caps.push(...tris);
			diagnostics.cappedLoops++;
			diagnostics.capTriangles += tris.length / 3;
		}
		if (caps.length === 0) break;
		const grown = new Uint32Array(index.length + caps.length);
		grown.set(index);
		grown.set(caps, index.length);
		index = grown;
	}
	const m = call("measures", positions, index);
	diagnostics.openEdges = m[3];
	diagnostics.nonManifoldEdges = m[4];
	diagnostics.closed = m[3] === 0 && m[4] === 0;
	diagnostics.volume = m[0];
	diagnostics.skippedLargeLoops = skipped.filter((n) => n > maxVerts);
	diagnostics.openLoops = skipped.length;
	return { soup: arraysToSoup(positions, index), diagnostics };
}

/**
 * The triangles (vertex indices) that cap the simple loop `loop` of the mesh, wound
 * against the loop's direction so that they join the mesh consistently; `[]` when the
 * loop cannot be triangulated.
 */
function capOf(positions, loop) {
	const flat = new Float64Array(3 * loop.length);
	loop.forEach((v, i) => flat.set(positions.subarray(3 * v, 3 * v + 3), 3 * i));
	let local;
	try {
		local = call("triangulateLoop", flat);
	} catch {
		return [];
	}
	if (local.length === 0) return [];
	// The cap must run each loop edge v_i → v_{i+1} backwards: find a cap triangle on a
	// loop edge and flip the whole cap if it runs that edge forwards.
	const k = loop.length;
	let flip = false;
	search: for (let t = 0; t < local.length; t += 3) {
		for (let c = 0; c < 3; c++) {
			const u = local[t + c], w = local[t + ((c + 1) % 3)];
			if ((u + 1) % k === w) {
				flip = true;
				break search;
			}
			if ((w + 1) % k === u) break search;
		}
	}
	const out = [];
	for (let t = 0; t < local.length; t += 3) {
		const a = loop[local[t]], b = loop[local[t + 1]], c = loop[local[t + 2]];
		if (flip) out.push(a, c, b);
		else out.push(a, b, c);
	}
	return out;
}

/**
 * Removes pairs of coincident, oppositely wound faces (zero-thickness membranes), and only
 * those: corners within `tolerance` are one vertex first (exactly equal, or equal up to
 * rounding noise, without one); triangles on the same three vertices cancel in opposite
 * pairs; same-winding copies stay. The survivors are the caller's own triangle objects.
 */
export function cancelCoincidentFaces(soup, tolerance) {
	const S = soupToArrays(soup, "soup");
	if (S.index.length === 0) return [];
	const W = tolerance > 0 ? weldAligned(S, tolerance) : conditioned(S);
	const index = W.index;
	const n = index.length / 3;
	const byKey = new Map(); // sorted vertices → {up: [t], down: [t]}
	for (let t = 0; t < n; t++) {
		if (collapsedAt(index, t)) continue;
		const a = index[3 * t], b = index[3 * t + 1], c = index[3 * t + 2];
		const s = [a, b, c].sort((p, q) => p - q);
		// Even permutations of the sorted corners wind one way, odd ones the other.
		const even = (a === s[0] && b === s[1]) || (b === s[0] && c === s[1]) || (c === s[0] && a === s[1]);
		const key = `${s[0]},${s[1]},${s[2]}`;
		let g = byKey.get(key);
		if (g === undefined) {
			g = { up: [], down: [] };
			byKey.set(key, g);
		}
		(even ? g.up : g.down).push(t);
	}
	const drop = new Set();
	for (const g of byKey.values()) {
		const pairs = Math.min(g.up.length, g.down.length);
		for (let i = 0; i < pairs; i++) {
			drop.add(g.up[i]);
			drop.add(g.down[i]);
		}
	}
	return soup.filter((_, t) => !drop.has(t));
}

/**
 * A weld within `tolerance` that keeps every triangle in its place (collapsed ones too):
 * each corner moved onto the nearest vertex of the library's weld (it moved at most
 * `tolerance`), then welded exactly. `{positions, index}`.
 */
export function weldAligned(S, tolerance) {
	const w = call("weld", S.positions, S.index, tolerance);
	const snapped = new Float64Array(S.positions.length);
	const cell = 2 * tolerance;
	const grid = new Map();
	const key = (x, y, z) => `${Math.floor(x / cell)},${Math.floor(y / cell)},${Math.floor(z / cell)}`;
	for (let v = 0; v < w.positions.length / 3; v++) {
		const k = key(w.positions[3 * v], w.positions[3 * v + 1], w.positions[3 * v + 2]);
		if (!grid.has(k)) grid.set(k, []);
		grid.get(k).push(v);
	}
	for (let i = 0; i < S.positions.length; i += 3) {
		const x = S.positions[i], y = S.positions[i + 1], z = S.positions[i + 2];
		const cx = Math.floor(x / cell), cy = Math.floor(y / cell), cz = Math.floor(z / cell);
		let best = -1, bestD = Infinity;
		for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
			for (const v of grid.get(`${cx + dx},${cy + dy},${cz + dz}`) || []) {
				const d = (w.positions[3 * v] - x) ** 2 + (w.positions[3 * v + 1] - y) ** 2 + (w.positions[3 * v + 2] - z) ** 2;
				if (d < bestD) {
					bestD = d;
					best = v;
				}
			}
		}
		snapped.set(best >= 0 ? w.positions.subarray(3 * best, 3 * best + 3) : [x, y, z], i);
	}
	return call("weld", snapped, S.index, 0);
}
