// The reference's newer (0.6–0.7) exports around results: verification of a finished soup,
// gated finishing stages, the one-call `booleanAuto`, and indexed views of split groups.
// Every check is decided exactly by meshbool (vertices equal when their coordinates are
// equal, zero area and T-junctions by exact predicates); a `tolerance` welds first.
import { call } from "./native.js";
import { arraysToSoup, parseReport, soupToArrays } from "./convert.js";
import { conditioned, weldAligned } from "./solids.js";

const GROUPS = ["aInside", "aOutside", "bInside", "bOutside"];

// A soup's arrays welded: within `tolerance` when one is given, else by the library's
// vertex-identity rule (equal, or equal up to rounding noise where that closes edges).
function welded(soup, tolerance) {
	const S = soupToArrays(soup, "soup");
	return tolerance > 0 ? call("weld", S.positions, S.index, tolerance) : conditioned(S, false);
}

// One repair step as the reference runs it, ungated: the finishing stages judge their
// results themselves (assessRepair).
function repaired(M, config) {
	return call("repair", M.positions, M.index, JSON.stringify({ orient: null, gate: false, ...config }));
}

/**
 * Read-only checks of a finished soup: no degenerate (zero-area, or at most `minArea`)
 * triangles, no duplicates, consistent winding, no non-manifold edges, no T-junctions
 * and, with `expectClosed`, no open edges. `{ok, checks: [{check, ok, count, detail}],
 * stats: {triangles, vertices, openEdges, nonManifoldEdges, area, components, volume}}`;
 * the check names are the reference's (`noDegenerateTriangles`, `noDuplicateTriangles`,
 * `consistentWinding`, `manifoldEdges`, `noTJunctions`, `closed`). An empty soup is not
 * ok: its only check is `nonEmpty` (count 0, as the reference reports it). Vertices are
 * the same when equal up to rounding noise (the library's rule), or within `tolerance`
 * when one is given.
 */
export function verifyOutput(soup, options) {
	const o = options || {};
	const M = welded(soup || [], o.tolerance);
	const check = (name, count, what) => ({ check: name, ok: count === 0, count, detail: count === 0 ? `no ${what}` : `${count} ${what}` });
	if (M.index.length === 0) {
		return {
			ok: false,
			checks: [{ check: "nonEmpty", ok: false, count: 0, detail: "the soup has no triangles" }],
			stats: { triangles: 0, vertices: 0, openEdges: 0, nonManifoldEdges: 0, area: 0, components: 0, volume: 0 },
		};
	}
	const info = JSON.parse(call("info", M.positions, M.index));
	let small = 0;
	if (o.minArea > 0) {
		for (const t of arraysToSoup(M.positions, M.index)) {
			const u = [t.v1.x - t.v0.x, t.v1.y - t.v0.y, t.v1.z - t.v0.z], v = [t.v2.x - t.v0.x, t.v2.y - t.v0.y, t.v2.z - t.v0.z];
			const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
			if (0.5 * Math.hypot(n[0], n[1], n[2]) <= o.minArea) small++;
		}
	}
	const tj = parseReport(repaired(M, { tjunctions: true }).report).tjunctions.vertices_inserted;
	const checks = [
		check("noDegenerateTriangles", Math.max(info.degenerate_triangles, small), "degenerate triangles"),
		check("noDuplicateTriangles", info.duplicate_triangles, "duplicate triangles"),
		check("consistentWinding", info.inconsistent_edges, "inconsistently wound edges"),
		check("manifoldEdges", info.non_manifold_edges, "edges of more than two triangles"),
		check("noTJunctions", tj, "vertices on other triangles' edges (T-junctions)"),
	];
	if (o.expectClosed) checks.push(check("closed", info.boundary_edges, "open edges"));
	return {
		ok: checks.every((c) => c.ok),
		checks,
		stats: {
			triangles: M.index.length / 3,
			vertices: info.vertices,
			openEdges: info.boundary_edges,
			nonManifoldEdges: info.non_manifold_edges,
			area: info.area,
			components: info.components,
			volume: info.volume,
		},
	};
}

/** The total number of violations in a `verifyOutput` report. */
export function violationCount(report) {
	return report.checks.reduce((n, c) => n + c.count, 0);
}

/**
 * Compares a soup before and after a candidate repair, both measured by `verifyOutput`
 * at the same `tolerance`: `{harmful, recommend: "keep" | "discard", benefits, damage,
 * before, after, violationsBefore, violationsAfter, trisDelta, volumeDeltaPct}`.
 * "keep" only when violations strictly fall and nothing got worse: no check's count
 * rose, a closed mesh was not opened ("Opens the mesh"), and, when the baseline is a
 * sound solid (closed and manifold: the only case where its volume means something),
 * the volume moved at most `volumeTolPct` percent (default 0.5).
 */
export function assessRepair(before, after, options) {
	const o = options || {};
	const b = verifyOutput(before, o), a = verifyOutput(after, o);
	const benefits = [], damage = [];
	const countOf = (report, name) => {
		const c = report.checks.find((x) => x.check === name);
		return c ? c.count : 0;
	};
	for (const c of b.checks) {
		if (c.check === "nonEmpty") continue;
		const now = countOf(a, c.check);
		if (now < c.count) benefits.push(`${c.check}: ${c.count} → ${now}`);
		if (now > c.count) damage.push(`${c.check}: ${c.count} → ${now}`);
	}
	for (const c of a.checks) {
		if (c.check !== "nonEmpty" && !b.checks.some((x) => x.check === c.check) && c.count > 0) damage.push(`${c.check}: 0 → ${c.count}`);
	}
	if (b.stats.triangles > 0 && a.stats.triangles === 0) damage.push("Empties the mesh: no triangles left");
	const sound = b.stats.triangles > 0 && b.stats.openEdges === 0 && b.stats.nonManifoldEdges === 0;
	if (sound && a.stats.openEdges > 0) damage.push(`Opens the mesh: 0 → ${a.stats.openEdges} open edges`);
	const volBefore = b.stats.volume, volAfter = a.stats.volume;
	const volumeDeltaPct = volBefore !== 0 ? (100 * (volAfter - volBefore)) / Math.abs(volBefore) : volAfter === 0 ? 0 : 100;
	const tol = o.volumeTolPct !== undefined ? o.volumeTolPct : 0.5;
	if (sound && Math.abs(volumeDeltaPct) > tol) damage.push(`volume changed by ${volumeDeltaPct.toFixed(3)} %`);
	const violationsBefore = violationCount(b), violationsAfter = violationCount(a);
	const harmful = damage.length > 0;
	return {
		harmful,
		recommend: !harmful && violationsAfter < violationsBefore ? "keep" : "discard",
		benefits,
		damage,
		before: b,
		after: a,
		violationsBefore,
		violationsAfter,
		trisDelta: a.stats.triangles - b.stats.triangles,
		volumeDeltaPct,
	};
}

/** An assessment as plain text. */
export function describeAssessment(a) {
	const lines = [`${a.recommend.toUpperCase()}: violations ${a.violationsBefore} → ${a.violationsAfter}, triangles ${a.trisDelta >= 0 ? "+" : ""}${a.trisDelta}, volume ${a.volumeDeltaPct.toFixed(3)} %`];
	for (const b of a.benefits) lines.push(`  + ${b}`);
	for (const d of a.damage) lines.push(`  - ${d}`);
	return lines.join("\n");
}

function stage(name, config) {
	return {
		name,
		run(soup) {
			const M = soupToArrays(soup, "soup");
			if (M.index.length === 0) return [];
			const out = repaired(M, config);
			return arraysToSoup(out.positions, out.index);
		},
	};
}

/**
 * The default finishing stages: coincident duplicates removed (opposite pairs cancel),
 * T-junctions split, winding made consistent — each exact.
 */
export const DEFAULT_STAGES = Object.freeze([
	stage("dedupCoincident", { remove_duplicates: true }),
	stage("resolveTJunctionsHoleFree", { tjunctions: true }),
	stage("orientWinding", { orient: "majority" }),
]);

/**
 * Runs each stage (`{name, run(soup, ctx)}`) on a copy and keeps its result only when
 * `assessRepair` recommends it, so the output is never worse than the input (`force`:
 * keep every stage's result that is not empty). `{soup, ok, before, after, applied,
 * skipped: [{stage, reason, violations}], stages}`; reasons: "would damage the mesh",
 * "no improvement", "produced nothing" (an empty or missing result), "threw" (then
 * `violations` holds the error's message). When no stage is applied `soup` is the
 * caller's own array. An empty soup is not ok (nothing to finish).
 */
export function finishMesh(soup, options) {
	const o = options || {};
	const stages = o.stages || DEFAULT_STAGES;
	const tolerance = o.tolerance || 0;
	const input = Array.isArray(soup) ? soup : [];
	let current = input;
	const applied = [], skipped = [], log = [];
	if (input.length > 0) {
		for (const s of stages) {
			let candidate;
			try {
				candidate = s.run(copySoup(current), { tolerance, options: o });
			} catch (e) {
				skipped.push({ stage: s.name, reason: "threw", violations: e instanceof Error ? e.message : String(e) });
				continue;
			}
			if (!Array.isArray(candidate) || candidate.length === 0) {
				skipped.push({ stage: s.name, reason: "produced nothing", violations: null });
				continue;
			}
			const assessment = assessRepair(current, candidate, o);
			log.push({ stage: s.name, assessment });
			if (o.force || assessment.recommend === "keep") {
				current = candidate;
				applied.push(s.name);
			} else {
				const reason = assessment.harmful ? "would damage the mesh" : "no improvement";
				skipped.push({ stage: s.name, reason, violations: `${assessment.violationsBefore} → ${assessment.violationsAfter}` });
			}
		}
	}
	const before = verifyOutput(input, o), after = current === input ? before : verifyOutput(current, o);
	return { soup: current, ok: after.ok, before, after, applied, skipped, stages: log };
}

// A soup copied triangle by triangle (corners too), so a stage cannot change its input.
function copySoup(soup) {
	return soup.map((t) => ({ ...t, v0: { ...t.v0 }, v1: { ...t.v1 }, v2: { ...t.v2 } }));
}

/**
 * One shared vertex pool (points exactly equal are one, or within `tolerance`) and
 * `[i, j, k]` triples per group: `{points, groups: {aInside, aOutside, bInside, bOutside}}`.
 */
export function indexGroups(groups, tolerance) {
	const all = [];
	const counts = [];
	for (const g of GROUPS) {
		const soup = (groups && groups[g]) || [];
		counts.push(soup.length);
		for (const t of soup) all.push(t);
	}
	const points = [];
	const out = { points, groups: { aInside: [], aOutside: [], bInside: [], bOutside: [] } };
	if (all.length === 0) return out;
	const S = soupToArrays(all, "groups");
	const w = tolerance > 0 ? weldAligned(S, tolerance) : call("weld", S.positions, S.index, 0);
	for (let i = 0; i < w.positions.length; i += 3) points.push({ x: w.positions[i], y: w.positions[i + 1], z: w.positions[i + 2] });
	let t = 0;
	GROUPS.forEach((g, k) => {
		for (let n = 0; n < counts[k]; n++, t++) out.groups[g].push([w.index[3 * t], w.index[3 * t + 1], w.index[3 * t + 2]]);
	});
	return out;
}

/** Indexed groups as typed arrays: `{positions: Float64Array, index: {aInside, ...: Uint32Array}}`. */
export function indexGroupsToTypedArrays(indexed) {
	const positions = new Float64Array(3 * indexed.points.length);
	indexed.points.forEach((p, i) => { positions[3 * i] = p.x; positions[3 * i + 1] = p.y; positions[3 * i + 2] = p.z; });
	const index = {};
	for (const g of GROUPS) {
		const tris = indexed.groups[g] || [];
		const a = new Uint32Array(3 * tris.length);
		tris.forEach((t, i) => a.set(t, 3 * i));
		index[g] = a;
	}
	return { positions, index };
}

/** Components of indexed triangles `[[i, j, k], ...]` joined through shared vertices (union-find), largest first. */
export function connectedComponentsIndexed(tris) {
	const parent = new Map();
	const find = (x) => {
		while (parent.get(x) !== x) {
			parent.set(x, parent.get(parent.get(x)));
			x = parent.get(x);
		}
		return x;
	};
	for (const t of tris) for (const v of t) if (!parent.has(v)) parent.set(v, v);
	for (const [a, b, c] of tris) {
		const ra = find(a), rb = find(b), rc = find(c);
		parent.set(rb, ra);
		parent.set(find(rc), ra);
	}
	const parts = new Map();
	for (const t of tris) {
		const r = find(t[0]);
		if (!parts.has(r)) parts.set(r, []);
		parts.get(r).push(t);
	}
	return [...parts.values()].sort((p, q) => q.length - p.length);
}

/** Folds every component of fewer than `threshold` triangles into the largest one. */
export function mergeSmallIndexedComponents(comps, threshold) {
	if (comps.length === 0) return [];
	const sorted = [...comps].sort((p, q) => q.length - p.length);
	const big = sorted.filter((c, i) => i === 0 || c.length >= threshold).map((c) => c.slice());
	for (const c of sorted.slice(1)) if (c.length < threshold) big[0].push(...c);
	return big;
}

/**
 * The indexed counterpart of `splitToComponents`: `[{mesh, side, index, points,
 * triangles, tris, triCount}]` per group, components by shared vertices, pieces under
 * `smallThreshold` folded into the group's largest. `triangles` index the entry's own
 * `points`; `tris` index the shared `indexed.points`.
 */
export function decomposeIndexedGroups(indexed, smallThreshold = 0) {
	const out = [];
	for (const g of GROUPS) {
		const mesh = g[0] === "a" ? "A" : "B", side = g.endsWith("Inside") ? "inside" : "outside";
		let comps = connectedComponentsIndexed(indexed.groups[g] || []);
		if (smallThreshold > 0) comps = mergeSmallIndexedComponents(comps, smallThreshold);
		comps.forEach((tris, index) => {
			const local = new Map();
			const points = [];
			const triangles = tris.map((t) => t.map((v) => {
				if (!local.has(v)) {
					local.set(v, points.length);
					points.push(indexed.points[v]);
				}
				return local.get(v);
			}));
			out.push({ mesh, side, index, points, triangles, tris, triCount: tris.length });
		});
	}
	return out;
}

/**
 * Coincident duplicate sheets removed, exactly: of triangles on the same three vertices,
 * one copy per orientation kept and opposite pairs cancelled. `{soup, duplicateGroups,
 * duplicatesRemoved, clusters, clusterTrisIn, clusterTrisOut}` (no clusters are
 * re-triangulated: overlapping coplanar triangles that are not identical stay).
 */
export function dedupCoincidentTriangles(tris, options) {
	void options;
	const M = soupToArrays(tris, "tris");
	if (M.index.length === 0) return { soup: [], duplicateGroups: 0, duplicatesRemoved: 0, clusters: 0, clusterTrisIn: 0, clusterTrisOut: 0 };
	const sets = new Map();
	for (const t of tris) {
		const key = [t.v0, t.v1, t.v2].map((v) => `${v.x},${v.y},${v.z}`).sort().join("|");
		sets.set(key, (sets.get(key) || 0) + 1);
	}
	const duplicateGroups = [...sets.values()].filter((n) => n > 1).length;
	const out = repaired(M, { remove_duplicates: true });
	const r = parseReport(out.report).duplicates;
	const removed = r.same_orientation_removed + r.anti_parallel_removed;
	return { soup: arraysToSoup(out.positions, out.index), duplicateGroups, duplicatesRemoved: removed, clusters: 0, clusterTrisIn: 0, clusterTrisOut: 0 };
}
