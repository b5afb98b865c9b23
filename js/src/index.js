// meshbool for JavaScript: the API of the trimesh-boolean library (every export of its
// 0.7.5 index; the BMS stages in bms.js and stages.js, solids in solids.js, finishing in
// finish.js), computed by meshbool's exact pipeline in WebAssembly, plus a typed-array
// fast path (`*Indexed` functions, `readMesh`, `writeMesh`) and the library's generated
// shapes (`make*`: primitives, a terrain and a pit to try things on). The same in a Web
// Worker: async.js (`meshbool/async`).
//
// The WebAssembly module is instantiated when this module is imported (top-level await):
// `import * as mb from "meshbool"` resolves once it is ready, and every call is synchronous
// after that, as in the reference. `repairMesh` is async as in the reference.
//
// Exact where the reference is heuristic: its weld tolerances, `toFixed(6)` keys, ray votes
// and nearest-segment fallbacks are not used to decide anything. Tolerance arguments that
// only served those heuristics are accepted and ignored (documented per function);
// tolerances a user chooses (weld distances, stitch gaps) keep their meaning.
import { buildInfo, call, construct, nativeVersion } from "./native.js";
import {
	arraysOf,
	arraysToPoints,
	arraysToSoup,
	edgeKey,
	flippedSoup,
	indexedArrays,
	isIndexed,
	parseReport,
	soupToArrays,
	toResult,
	vKey,
} from "./convert.js";

export { isIndexed, vKey, edgeKey };
export {
	verifyOutput,
	violationCount,
	assessRepair,
	describeAssessment,
	DEFAULT_STAGES,
	finishMesh,
	indexGroups,
	indexGroupsToTypedArrays,
	connectedComponentsIndexed,
	mergeSmallIndexedComponents,
	decomposeIndexedGroups,
	dedupCoincidentTriangles,
} from "./finish.js";
import { finishMesh, indexGroups, verifyOutput } from "./finish.js";
export { orientSolid, closeSolid, cancelCoincidentFaces } from "./solids.js";
import { closeSolid, conditioned, edgeTable, selfResolveArrays } from "./solids.js";
import { boxesOverlapWithArea, chainById, createVertexPool, meanEdge, nonManifoldEdgeCount, overlapPairs, poolOfSplit, seamInPool, verifyBmsClassification } from "./bms.js";
export { createVertexPool, verifyBmsClassification } from "./bms.js";
export {
	NEAR_PARALLEL,
	bmsChain,
	bmsClassify,
	bmsClosePolylines,
	bmsSelfArrange,
	bmsSelfIntersect,
	buildEdgeSteinerMap,
	chainedOpenEdge,
	classifyByFloodFill,
	conditionArrangement,
	coplanarOverlap,
	emitCoplanarSegments,
	extractByWinding,
	extractByWindingPatches,
	fanTriangulate,
	retriangulateWithSteinerPoints,
	snapCoincidentSheets,
	snapEndpointsToVertices,
	weldTaggedSoup,
} from "./stages.js";
import { classifyPieces, rememberSide, selfPieces } from "./stages.js";

/** The version of meshbool inside this package. */
export const version = nativeVersion;
export { buildInfo };

const EMPTY_F64 = new Float64Array(0);
const EMPTY_U32 = new Uint32Array(0);

// ── options ────────────────────────────────────────────────────────────────────────────

const OPS = {
	union: "union",
	intersect: "intersection",
	intersection: "intersection",
	subtract: "difference",
	difference: "difference",
	"reverse-difference": "reverse-difference",
	reverseDifference: "reverse-difference",
};

function opName(op) {
	const name = OPS[op];
	if (name === undefined) {
		throw new Error(`meshbool: unknown operation ${JSON.stringify(op)}: use "union", "intersect" or "subtract" (also "intersection", "difference", "reverse-difference")`);
	}
	return name;
}

/** The operand checks of the library from an options object (see BooleanOptions). */
function checkOptions(opts) {
	const o = opts || {};
	const out = {};
	for (const key of ["force", "selfCheck", "resolve", "orient", "keepNonmanifold", "keepSeamPoints", "coplanarRefinement", "withCoplanar", "sliverGuard"]) {
		if (o[key] !== undefined) {
			if (typeof o[key] !== "boolean") throw new Error(`meshbool: option ${key} must be true or false`);
			out[key] = o[key];
		}
	}
	if (o.snap !== undefined) {
		if (typeof o.snap !== "number" || !Number.isFinite(o.snap) || o.snap < 0) {
			throw new Error(`meshbool: option snap must be a distance >= 0, got ${o.snap}`);
		}
		out.snap = o.snap;
	}
	return JSON.stringify(out);
}

function emptyCheck(arrays, what) {
	if (arrays.index.length === 0) {
		throw new Error(`meshbool: ${what} has no triangles`);
	}
}

// ── typed-array fast path ────────────────────────────────────────────────────────────────

/**
 * A boolean of two indexed meshes `{positions: Float64Array, index: Uint32Array}`:
 * `{positions, index, source, triangle, flipped, report}` without building an object per
 * triangle. `op`: "union", "intersect"/"intersection", "subtract"/"difference",
 * "reverse-difference". Options: `force`, `selfCheck`, `resolve`, `orient` (the operand
 * checks, all on but `force` by default), `keepNonmanifold`, `snap` (a tolerance D:
 * edges shorter than D collapsed and needles removed where that makes no defect; the
 * report's `snap` says what was done), `keepSeamPoints` (default true, as the reference
 * library's booleans equal their merged split groups; `false` runs the exact clean-up:
 * seam points where the result is flat or straight removed and zero-area triangles made
 * by rounding gone, no surface moving; the report's `cleanup` says what was done),
 * `coplanarRefinement` (default true, as the reference's shared faces hold the common
 * refinement of both triangulations; `false`: coplanar overlaps meet along their
 * boundaries only, fewer triangles and much faster on fanned CAD caps).
 */
export function booleanIndexed(a, b, op, options) {
	const A = indexedArrays(a, "a"), B = indexedArrays(b, "b");
	const out = call("boolean", A.positions, A.index, B.positions, B.index, opName(op), checkOptions(options));
	out.report = parseReport(out.report);
	return out;
}

/**
 * Splits two indexed meshes along their intersection: `{groups, report}`, `groups` keyed by
 * the library's group names (`a_in_b`, `a_out_b`, `b_in_a`, `b_out_a`, and the coplanar
 * `a_on_b_same`, ...) each `{positions, index, source, triangle, flipped}`. Options as for
 * `booleanIndexed` (`snap` cleans all groups together, the report's `snap` says how).
 */
export function splitIndexed(a, b, options) {
	const A = indexedArrays(a, "a"), B = indexedArrays(b, "b");
	return splitArrays(A, B, options);
}

function splitArrays(A, B, options) {
	const out = call("split", A.positions, A.index, B.positions, B.index, checkOptions(options));
	const groups = {};
	for (const g of out.groups) groups[g.name] = g;
	return { groups, report: parseReport(out.report) };
}

/**
 * Intersection curves of two indexed meshes (or of one mesh with itself when `b` is null),
 * chained: `{polylines: Float64Array[], closed: boolean[], report}`. Option `withCoplanar`
 * adds the outlines of coplanar overlaps.
 */
export function curvesIndexed(a, b, options) {
	const A = indexedArrays(a, "a");
	const B = b == null ? { positions: EMPTY_F64, index: EMPTY_U32 } : indexedArrays(b, "b");
	const out = call("curves", A.positions, A.index, B.positions, B.index, checkOptions(options));
	return { polylines: out.polylines, closed: Array.from(out.closed, (c) => c === 1), report: parseReport(out.report) };
}

/**
 * Cut and fill between a design surface and the topography (indexed meshes or soups;
 * both faced up first): the report `{cut, fill, net, design_plan_area, topo_plan_area,
 * common_plan_area, zero_lines, zero_line_length, faced_up, ...}` with `lines` (the
 * zero-thickness polylines as Float64Arrays) and `closed` added. Volumes over the plan
 * area both cover, from exact booleans of the solids under each surface.
 */
export function cutFill(design, topo) {
	const D = arraysOf(design, "design"), T = arraysOf(topo, "topo");
	const out = call("cutfill", D.positions, D.index, T.positions, T.index);
	const report = parseReport(out.report);
	report.lines = out.lines;
	report.closed = Array.from(out.closed, (c) => c === 1);
	return report;
}

const CLASS_NAMES = ["outside", "inside", "on"];

/**
 * Where points lie against a mesh (indexed or soup): `{classes, winding, report}` with
 * `classes[i]` 0 outside, 1 inside, 2 exactly on the surface (decided exactly) and the
 * winding number at each. Inside a closed mesh: winding number ≥ 1/2; for an open
 * surface: behind it (winding number > 0). `points`: a Float64Array (three numbers per
 * point) or an array of `{x, y, z}`. Options: the operand checks (see booleanIndexed).
 */
export function classifyPointsIndexed(mesh, points, options) {
	const M = arraysOf(mesh, "mesh");
	let flat = points;
	if (!(points instanceof Float64Array)) {
		if (!Array.isArray(points)) throw new Error("meshbool: points must be a Float64Array or an array of {x, y, z}");
		flat = new Float64Array(3 * points.length);
		points.forEach((p, i) => { flat[3 * i] = p.x; flat[3 * i + 1] = p.y; flat[3 * i + 2] = p.z; });
	}
	const out = call("classify", M.positions, M.index, flat, checkOptions(options));
	out.report = parseReport(out.report);
	return out;
}

/** Where each point `{x, y, z}` lies against a soup: `"inside"`, `"outside"` or `"on"` (see classifyPointsIndexed). */
export function classifyPoints(soup, points, options) {
	const out = classifyPointsIndexed(soup, points, options);
	return Array.from(out.classes, (c) => CLASS_NAMES[c]);
}

/** The solid a self-overlapping indexed mesh encloses (fill rule "positive", "nonzero" or "evenodd"): `{positions, index, parent, report}`. */
export function resolveIndexed(m, options) {
	const M = indexedArrays(m);
	const o = options || {};
	const out = call("resolve", M.positions, M.index, o.rule || "positive", !!o.keepNonmanifold);
	out.report = parseReport(out.report);
	return out;
}

/** The "upper" (default) or "lower" envelope of a folded open surface (terrain), exact and faced up: `{positions, index, parent, report}` (`meshbool resolve --envelope`). */
export function envelopeIndexed(m, side) {
	const M = indexedArrays(m);
	const out = call("envelope", M.positions, M.index, side || "upper");
	out.report = parseReport(out.report);
	return out;
}

/** The library's repair pipeline on an indexed mesh; `config` is meshbool's RepairConfig (docs/json.md). */
export function repairIndexed(m, config) {
	const M = indexedArrays(m);
	const out = call("repair", M.positions, M.index, JSON.stringify(config || {}));
	out.report = parseReport(out.report);
	return out;
}

/** Closes an open indexed mesh: `mode` "cap", "stitch", "curtain" or "stitch+curtain"; options `floorOffset`, `maxGap`. */
export function closeIndexed(m, mode, options) {
	const M = indexedArrays(m);
	const out = call("close", M.positions, M.index, mode, JSON.stringify(options || {}));
	out.report = parseReport(out.report);
	return out;
}

/** Consistent orientation of an indexed mesh, each component facing "majority", "z-up" or "outward". */
export function orientIndexed(m, facing = "majority") {
	const M = indexedArrays(m);
	const out = call("orient", M.positions, M.index, facing);
	out.report = parseReport(out.report);
	return out;
}

/**
 * `meshbool info` of a mesh (indexed or soup), welded exactly first: counts, edge kinds,
 * components, closed, volume, areas, bounds.
 */
export function meshInfo(m) {
	const M = arraysOf(m, "mesh");
	return JSON.parse(call("info", M.positions, M.index));
}

let readable = null;

/**
 * The formats `readMesh` reads in this build, as the WebAssembly's readers answer:
 * `{name, extension, label}` each (`name` as `readMesh` takes it, `extension` without its
 * dot, `label` as the messages name it). STL, OBJ, PLY, DXF, JSON soups, glTF `.glb` and
 * OFF; the Rust library's GOCAD, Surpac and LandXML readers are not in this build.
 */
export function readFormats() {
	readable ??= call("readFormats");
	return readable.map((f) => ({ ...f }));
}

/**
 * Reads a mesh file from its bytes (Uint8Array or ArrayBuffer) in one of the formats of
 * `readFormats()`: `{positions, index, format}`. `format` names the format ("stl",
 * "obj", ...) or is the file's name (its extension is the hint; an extension no format
 * has leaves it to the bytes); without it the format is detected from the bytes. A
 * format this build does not read, or bytes that fit none, throws an Error listing the
 * formats it reads.
 */
export function readMesh(bytes, format = "") {
	const data = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
	return call("read", data, String(format || ""));
}

/** A mesh file's bytes (Uint8Array) in `format` ("stl", "obj", "ply", ...). */
export function writeMesh(m, format = "stl") {
	const M = arraysOf(m, "mesh");
	return call("write", M.positions, M.index, format);
}

// ── generated shapes ───────────────────────────────────────────────────────────────────

/** Options as JSON for the WebAssembly, a number that is not finite refused (JSON would make it null: the default). */
function shapeOptions(name, options) {
	if (options == null) return "{}";
	if (typeof options !== "object" || Array.isArray(options)) {
		throw new Error(`meshbool: ${name}'s options must be an object, got ${Array.isArray(options) ? "an array" : typeof options}`);
	}
	return JSON.stringify(options, (key, v) => {
		if (typeof v === "number" && !Number.isFinite(v)) throw new Error(`meshbool: ${name} option ${key} must be finite, got ${v}`);
		return v;
	});
}

/** A generated shape of the library (`meshbool make`): `{positions, index, report}`. */
function make(name, options) {
	const out = call("make", name, shapeOptions(name, options));
	out.report = parseReport(out.report);
	return out;
}

/**
 * An axis-aligned cube or box, outward-facing, 8 vertices and 12 triangles: `size` (one
 * edge length or three, default 1) about `center` (default [0, 0, 0]), or from `min` to
 * `max`. `{positions, index, report}` (the report as `meshbool make --json`).
 */
export function makeCube(options) {
	return make("cube", options);
}

/**
 * A UV sphere about `center` (default [0, 0, 0]) of `radius` (default 1), its axis along
 * z: `segments` meridians (default 32, at least 3), `rings` bands from pole to pole
 * (default 16, at least 2); `2 · segments · (rings − 1)` triangles, closed,
 * outward-facing, every vertex on the sphere. `{positions, index, report}`.
 */
export function makeSphere(options) {
	return make("sphere", options);
}

/**
 * A cylinder standing on `base` (its bottom centre, default [0, 0, 0]) along +z, of
 * `radius` and `height` (default 1 each), the circles as regular polygons of `segments`
 * sides (default 32, the first vertex on +x): `4 · segments` triangles, closed,
 * outward-facing (a drill hole). `{positions, index, report}`.
 */
export function makeCylinder(options) {
	return make("cylinder", options);
}

/**
 * A cone standing on `base` along +z up to an apex, or a frustum with `topRadius` > 0
 * (also spelled `top_radius`, as in `evaluateCsg` scenes); `radius`, `height`,
 * `segments` as for `makeCylinder`. Closed, outward-facing.
 * `{positions, index, report}`.
 */
export function makeCone(options) {
	return make("cone", options);
}

/**
 * A flat rectangle about `center`, `width` along x by `depth` along y (default 1 each),
 * in `nx` by `ny` cells (default 1) of two triangles, facing +z: an open surface.
 * `{positions, index, report}`.
 */
export function makePlane(options) {
	return make("plane", options);
}

/**
 * A seeded terrain (an example to try the operations on, in place of survey data): an
 * open height field over `center.xy ± size / 2` (default centre [0, 0, 0], size [1000,
 * 1000]; one number for both), `cells` (default [100, 100]) of two triangles, facing +z;
 * hills, hollows, ridges and valleys scaled so that the heights span `relief` (default
 * 40) about `center.z`. The same `seed` (default 1) gives the same mesh, bit for bit.
 * `2 · cells[0] · cells[1]` triangles, one boundary loop of `2 (cells[0] + cells[1])`
 * edges. `{positions, index, report}`.
 */
export function makeTerrain(options) {
	return make("terrain", options);
}

/**
 * An open-pit design shell facing up (into the pit's air): a benched bowl, its rim the
 * ellipse of semi-axes `radius` (default [220, 160]) about `center` (default [0, 0, 60])
 * at height `center.z`, its floor `depth` (default 140) below, `benches` faces (default
 * 5) at a batter of 2:1 with flat berms `berm` wide (default 8) between them, rings of
 * `segments` vertices (default 64). With the defaults it crosses the default terrain,
 * its rim above the ground all round. One boundary loop, the rim, of `segments` edges.
 * `{positions, index, report}`.
 */
export function makePit(options) {
	return make("pit", options);
}

/**
 * Results of CSG nodes by key, kept between calls of `evaluateCsg` (in memory): with one
 * cache, a call after an edit computes only the edited node and its ancestors.
 */
export class CsgCache {
	constructor() {
		this._native = construct("CsgCache");
	}

	/** Results held. */
	get size() {
		return this._native.size();
	}

	/** Forgets every result. */
	clear() {
		this._native.clear();
	}
}

/**
 * Evaluates a CSG document (docs/csg.md): `scene` is `{root: NODE}`, NODE an operation
 * `{op: "union" | "intersection" | "difference", children: [NODE, ...]}`, a mesh
 * `{mesh: M}` (M an indexed mesh `{positions, index}` or a soup), or a primitive
 * `{primitive: "cube" | "sphere" | ..., ...parameters}` (as `meshbool make`: `size`,
 * `center`, `radius`, `top_radius`, ...); any node may have `transform` (`{scale, rotate,
 * translate}` or `{matrix}`, or a list of them), `role: "cutter"` (subtracted in a
 * difference) and `name`. Options: `cache` (a `CsgCache`; default a fresh one), and the
 * booleans' `force`, `selfCheck`, `resolve`, `orient`, `keepNonmanifold`,
 * `keepSeamPoints`, `snap`. Returns `{positions, index, report}` (`report.nodes`: every
 * node visited, with `source` "computed" or "memory"); throws an `Error` naming the node
 * that failed (`err.report` holds the report) or saying where the document is malformed.
 */
export function evaluateCsg(scene, options = {}) {
	const { cache, ...rest } = options;
	const meshes = [];
	const inline = (node, at) => {
		if (node === null || typeof node !== "object" || Array.isArray(node)) {
			throw new Error(`malformed CSG scene: ${at}: expected an object`);
		}
		const out = { ...node };
		if (node.mesh !== undefined && typeof node.mesh !== "string" && typeof node.mesh !== "number") {
			out.mesh = meshes.length;
			meshes.push(arraysOf(node.mesh, `${at}.mesh`));
		}
		if (Array.isArray(node.children)) out.children = node.children.map((c, k) => inline(c, `${at}.children[${k}]`));
		return out;
	};
	const doc = scene !== null && typeof scene === "object" && scene.root !== undefined ? { ...scene, root: inline(scene.root, "root") } : scene;
	const vertices = Uint32Array.from(meshes, (m) => m.positions.length / 3);
	const triangles = Uint32Array.from(meshes, (m) => m.index.length / 3);
	const positions = new Float64Array(meshes.reduce((n, m) => n + m.positions.length, 0));
	const index = new Uint32Array(meshes.reduce((n, m) => n + m.index.length, 0));
	let p = 0, t = 0;
	for (const m of meshes) {
		positions.set(m.positions, p);
		index.set(m.index, t);
		p += m.positions.length;
		t += m.index.length;
	}
	const store = cache ?? new CsgCache();
	if (!(store instanceof CsgCache)) throw new Error("evaluateCsg: cache must be a CsgCache");
	const out = call("csg", JSON.stringify(doc), positions, index, vertices, triangles, store._native, JSON.stringify(rest));
	const report = parseReport(out.report);
	if (out.positions === undefined) {
		const err = new Error(`meshbool: CSG node ${report.failed.path} failed: ${report.failed.error}`);
		err.report = report;
		throw err;
	}
	return { positions: out.positions, index: out.index, report };
}

/** A soup as an indexed mesh `{positions, index}` welded exactly (equal coordinates only). */
export function soupToTyped(soup) {
	const S = soupToArrays(soup);
	const w = call("weld", S.positions, S.index, 0);
	return { positions: w.positions, index: w.index };
}

/** An indexed mesh as a soup. */
export function typedToSoup(m) {
	const M = indexedArrays(m);
	return arraysToSoup(M.positions, M.index);
}

// ── Boolean (the reference's classic pipeline, computed exactly) ───────────────────────

/**
 * The boolean of two soups: `{soup, points, triangles}` (welded; the library's report as a
 * non-enumerable `report`), or `null` when the result is empty or an input is null.
 * `op`: "union", "intersect", "subtract". Options of the reference: `preRepair` (exact
 * T-junction repair of the inputs, and a weld within `tolerance` when given), `fillGaps`
 * and `forceClose` (cap the result's holes), `tolerance`, `tjunctionPasses` (no effect:
 * the T-junction repair is exact). meshbool's: `force`, `selfCheck`, `resolve`, `orient`,
 * `keepNonmanifold` (see booleanIndexed).
 */
export function boolean(soupA, soupB, op, options) {
	if (soupA == null || soupB == null) return null;
	const o = options || {};
	const [A, B] = operands(soupA, soupB, o);
	const out = call("boolean", A.positions, A.index, B.positions, B.index, opName(op), checkOptions(o));
	let { positions, index } = out;
	if ((o.fillGaps || o.forceClose) && index.length > 0) {
		const closed = call("close", positions, index, "cap", "{}");
		positions = closed.positions;
		index = closed.index;
	}
	if (index.length === 0) return null;
	return toResult(positions, index, parseReport(out.report));
}

/** Both soups as flat arrays, checked non-empty, repaired first with `preRepair`. */
function operands(soupA, soupB, o) {
	let A = soupToArrays(soupA, "soupA"), B = soupToArrays(soupB, "soupB");
	emptyCheck(A, "soupA");
	emptyCheck(B, "soupB");
	if (o.preRepair) {
		A = preRepair(A, o.tolerance);
		B = preRepair(B, o.tolerance);
	}
	return [A, B];
}

function preRepair(M, tolerance) {
	const config = { tjunctions: true, orient: null, gate: false };
	if (typeof tolerance === "number" && tolerance > 0) config.weld = tolerance;
	const out = call("repair", M.positions, M.index, JSON.stringify(config));
	return { positions: out.positions, index: out.index };
}

// The library's eight groups folded into the reference's four so that the reference's
// merges give exact booleans: A's faces lying on B's go with A inside (one copy kept by
// intersect; the same-facing copy of union comes from B outside; the opposite-facing pair
// of a difference comes from B inside, flipped), and merges cancel exactly coincident
// opposite pairs.
const FOLD = {
	aInside: ["a_in_b", "a_on_b_same", "a_on_b_opposite"],
	aOutside: ["a_out_b"],
	bInside: ["b_in_a", "b_on_a_opposite"],
	bOutside: ["b_out_a", "b_on_a_same"],
};

function groupSoup(groups, names) {
	const soup = [];
	for (const name of names) {
		const g = groups[name];
		if (g === undefined) continue;
		for (const t of arraysToSoup(g.positions, g.index)) soup.push(t);
	}
	return soup;
}

function taggedSegments(A, B, withCoplanar) {
	const out = call("intersect", A.positions, A.index, B.positions, B.index, JSON.stringify({ withCoplanar: !!withCoplanar }));
	const n = out.triA.length, s = out.segments;
	const segments = new Array(n);
	for (let i = 0; i < n; i++) {
		const o = 6 * i;
		segments[i] = {
			p0: { x: s[o], y: s[o + 1], z: s[o + 2] },
			p1: { x: s[o + 3], y: s[o + 4], z: s[o + 5] },
			idxA: out.triA[i],
			idxB: out.triB[i],
		};
	}
	return segments;
}

/**
 * Splits A and B along their intersection: `{groups: {aInside, aOutside, bInside,
 * bOutside}, segments}` (soups; `segments` the tagged intersection segments), or `null`
 * when an input is null. Exact: every triangle lies wholly on one side. Faces shared by
 * both meshes are grouped so that `mergeSplitGroups` gives the exact boolean (A's shared
 * faces in aInside; B's same-facing ones in bOutside, opposite-facing ones in bInside).
 */
export function splitMeshPair(soupA, soupB, options) {
	if (soupA == null || soupB == null) return null;
	const A = soupToArrays(soupA, "soupA"), B = soupToArrays(soupB, "soupB");
	emptyCheck(A, "soupA");
	emptyCheck(B, "soupB");
	const s = splitArrays(A, B, options);
	const groups = {};
	for (const key of Object.keys(FOLD)) groups[key] = groupSoup(s.groups, FOLD[key]);
	const result = { groups, segments: taggedSegments(A, B, false) };
	Object.defineProperty(result, "report", { value: s.report, enumerable: false });
	return result;
}

function concatPicks(picks) {
	let total = 0;
	for (const p of picks) total += p.soup.length;
	const positions = new Float64Array(9 * total);
	let o = 0;
	for (const p of picks) {
		const flip = p.flip === true || p.flip === "flip";
		const arr = soupToArrays(p.soup, "soup").positions;
		for (let t = 0; t < p.soup.length; t++, o += 9) {
			const i = 9 * t;
			positions.set(arr.subarray(i, i + 3), o);
			if (flip) {
				positions.set(arr.subarray(i + 6, i + 9), o + 3);
				positions.set(arr.subarray(i + 3, i + 6), o + 6);
			} else {
				positions.set(arr.subarray(i + 3, i + 9), o + 3);
			}
		}
	}
	const index = new Uint32Array(3 * total);
	for (let i = 0; i < index.length; i++) index[i] = i;
	return { positions, index };
}

function mergePicks(picks, keepNonmanifold) {
	const M = concatPicks(picks);
	if (M.index.length === 0) return null;
	const out = call("merge", M.positions, M.index, !!keepNonmanifold, true);
	if (out.index.length === 0) return null;
	const report = parseReport(out.report);
	report.duplicates_removed = out.duplicates;
	return toResult(out.positions, out.index, report);
}

/**
 * A boolean from the four groups of `splitMeshPair`: union = aOutside + bOutside,
 * intersect = aInside + bInside, subtract = aOutside + flipped bInside; merged as
 * `mergeComponents` does. `null` when empty.
 */
export function mergeSplitGroups(groups, op) {
	const sel = {
		union: { aOutside: true, bOutside: true },
		intersection: { aInside: true, bInside: true },
		difference: { aOutside: true, bInside: "flip" },
		"reverse-difference": { bOutside: true, aInside: "flip" },
	}[opName(op)];
	return selectSplits(groups, sel);
}

/**
 * Any subset of the four groups (`true`, `false` or `"flip"` each) merged into one mesh:
 * welded exactly, exactly coincident triangles removed (opposite pairs cancel), edges used
 * by more than two triangles split apart. `null` when nothing is selected.
 */
export function selectSplits(groups, selection) {
	if (groups == null) return null;
	const picks = [];
	for (const key of ["aInside", "aOutside", "bInside", "bOutside"]) {
		const s = selection ? selection[key] : false;
		if (s === true || s === "flip") {
			if (!Array.isArray(groups[key])) throw new Error(`meshbool: groups.${key} must be a soup`);
			picks.push({ soup: groups[key], flip: s === "flip" });
		}
	}
	return mergePicks(picks);
}

function componentSoups(soup) {
	if (soup.length === 0) return [];
	const S = conditioned(soupToArrays(soup), false);
	const { count, ids } = call("components", S.positions, S.index);
	const parts = Array.from({ length: count }, () => []);
	for (let t = 0; t < soup.length; t++) parts[ids[t]].push(soup[t]);
	parts.sort((p, q) => q.length - p.length);
	return parts;
}

/**
 * The edge-connected components of each group (triangles sharing an edge, vertices
 * taken as the library takes them: exactly equal, or equal up to rounding noise):
 * `[{mesh: "A"|"B", side: "inside"|"outside", index, soup, triCount}]`, largest first in
 * each group, groups in the order aInside, aOutside, bInside, bOutside. (`options`, the
 * reference's `{pooled}`: the same components either way.)
 */
export function splitToComponents(groups, options) {
	void options;
	const out = [];
	const keys = [["aInside", "A", "inside"], ["aOutside", "A", "outside"], ["bInside", "B", "inside"], ["bOutside", "B", "outside"]];
	for (const [key, mesh, side] of keys) {
		const soup = groups && groups[key];
		if (!Array.isArray(soup)) continue;
		componentSoups(soup).forEach((part, index) => out.push({ mesh, side, index, soup: part, triCount: part.length }));
	}
	return out;
}

function soupCentroid(soup) {
	let x = 0, y = 0, z = 0;
	for (const t of soup) {
		x += t.v0.x + t.v1.x + t.v2.x;
		y += t.v0.y + t.v1.y + t.v2.y;
		z += t.v0.z + t.v1.z + t.v2.z;
	}
	const n = 3 * Math.max(soup.length, 1);
	return { x: x / n, y: y / n, z: z / n };
}

/**
 * Merges every component of at most `threshold` triangles into the nearest larger
 * component (by centroid distance) of the same mesh and side; components are renumbered
 * largest first. With no larger component in a group, its small ones stay.
 */
export function mergeSmallComponents(components, threshold = 50) {
	const byGroup = new Map();
	for (const c of components) {
		const key = c.mesh + ":" + c.side;
		if (!byGroup.has(key)) byGroup.set(key, []);
		byGroup.get(key).push(c);
	}
	const out = [];
	for (const list of byGroup.values()) {
		const large = list.filter((c) => c.triCount > threshold).map((c) => ({ ...c, soup: c.soup.slice() }));
		const small = list.filter((c) => c.triCount <= threshold);
		if (large.length === 0) {
			out.push(...list);
			continue;
		}
		const centres = large.map((c) => soupCentroid(c.soup));
		for (const s of small) {
			const p = soupCentroid(s.soup);
			let best = 0, bestD = Infinity;
			centres.forEach((q, i) => {
				const d = distSq3(p, q);
				if (d < bestD) { bestD = d; best = i; }
			});
			for (const t of s.soup) large[best].soup.push(t);
		}
		large.forEach((c) => { c.triCount = c.soup.length; });
		large.sort((p, q) => q.triCount - p.triCount);
		large.forEach((c, i) => { c.index = i; out.push(c); });
	}
	return out;
}

/**
 * Concatenates picked pieces `[{soup, flip?}]` (flipped where asked) into one mesh: welded
 * exactly, exactly coincident triangles removed (opposite pairs cancel), edges used by
 * more than two triangles split apart. `{soup, points, triangles}`, or `null` when empty.
 */
export function mergeComponents(picks) {
	if (!Array.isArray(picks)) throw new Error("meshbool: mergeComponents takes an array of {soup, flip?}");
	return mergePicks(picks);
}

// ── Intersection ────────────────────────────────────────────────────────────────────────

/** Every triangle–triangle intersection segment of A and B, exact points rounded once: `[{p0, p1}]`. */
export function intersectMeshPair(soupA, soupB, options) {
	return intersectMeshPairTagged(soupA, soupB, options).map((s) => ({ p0: s.p0, p1: s.p1 }));
}

/** The same with the triangle of each input: `[{p0, p1, idxA, idxB}]`. Option `withCoplanar` adds the outlines of coplanar overlaps. */
export function intersectMeshPairTagged(soupA, soupB, options) {
	if (soupA == null || soupB == null) return [];
	const A = soupToArrays(soupA, "soupA"), B = soupToArrays(soupB, "soupB");
	if (A.index.length === 0 || B.index.length === 0) return [];
	return taggedSegments(A, B, options && options.withCoplanar);
}

/**
 * The segment where two triangles cross, exactly (rounded once), or `null` when they do
 * not cross in a segment (apart, touching at a point, or coplanar).
 */
export function triTriIntersection(triA, triB) {
	const segs = intersectMeshPairTagged([triA], [triB]);
	if (segs.length === 0) return null;
	const s = segs[0];
	if (s.p0.x === s.p1.x && s.p0.y === s.p1.y && s.p0.z === s.p1.z) return null;
	return { p0: s.p0, p1: s.p1 };
}

function orient3d(a, b, c, d) {
	const adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
	const bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
	const cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
	return adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy);
}

/**
 * `triTriIntersection` plus `dA` (the orientation of each corner of A against B's plane),
 * `dB` (of B's corners against A's plane) and `segLen`; `null` when they do not cross.
 */
export function triTriIntersectionDetailed(triA, triB) {
	const seg = triTriIntersection(triA, triB);
	if (seg === null) return null;
	const dA = [triA.v0, triA.v1, triA.v2].map((p) => orient3d(triB.v0, triB.v1, triB.v2, p));
	const dB = [triB.v0, triB.v1, triB.v2].map((p) => orient3d(triA.v0, triA.v1, triA.v2, p));
	return { p0: seg.p0, p1: seg.p1, dA, dB, segLen: dist3(seg.p0, seg.p1) };
}

/**
 * Chains segments `[{p0, p1}]` into polylines (arrays of points) by joining ends closer
 * than `threshold` (0 or absent: only equal ends). A closed chain repeats its first point
 * at the end, as the reference's do.
 */
export function chainSegments(segments, threshold = 0) {
	if (!Array.isArray(segments) || segments.length === 0) return [];
	const t = Math.max(threshold || 0, 0);
	const cell = t > 0 ? 2 * t : 0;
	const key = (p) => (cell > 0 ? `${Math.floor(p.x / cell)},${Math.floor(p.y / cell)},${Math.floor(p.z / cell)}` : `${p.x},${p.y},${p.z}`);
	const ends = new Map();
	segments.forEach((s, i) => {
		for (const e of [0, 1]) {
			const k = key(e === 0 ? s.p0 : s.p1);
			if (!ends.has(k)) ends.set(k, []);
			ends.get(k).push([i, e]);
		}
	});
	const used = new Uint8Array(segments.length);
	const near = (p) => {
		const cands = [];
		if (cell > 0) {
			const cx = Math.floor(p.x / cell), cy = Math.floor(p.y / cell), cz = Math.floor(p.z / cell);
			for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
				const list = ends.get(`${cx + dx},${cy + dy},${cz + dz}`);
				if (list) cands.push(...list);
			}
		} else {
			const list = ends.get(key(p));
			if (list) cands.push(...list);
		}
		let best = null, bestD = Infinity;
		for (const [i, e] of cands) {
			if (used[i]) continue;
			const q = e === 0 ? segments[i].p0 : segments[i].p1;
			const d = distSq3(p, q);
			if (d <= t * t && d < bestD) { best = [i, e]; bestD = d; }
		}
		return best;
	};
	const lines = [];
	for (let s = 0; s < segments.length; s++) {
		if (used[s]) continue;
		used[s] = 1;
		const tail = [segments[s].p0, segments[s].p1];
		const head = [];
		for (let m = near(tail[tail.length - 1]); m; m = near(tail[tail.length - 1])) {
			used[m[0]] = 1;
			tail.push(m[1] === 0 ? segments[m[0]].p1 : segments[m[0]].p0);
		}
		for (let m = near(head.length ? head[head.length - 1] : tail[0]); m; m = near(head[head.length - 1])) {
			used[m[0]] = 1;
			head.push(m[1] === 0 ? segments[m[0]].p1 : segments[m[0]].p0);
		}
		lines.push(head.reverse().concat(tail));
	}
	return lines;
}

/** A polyline thinned to points at least `spacing` apart along it (first and last kept). */
export function simplifyPolyline(points, spacing) {
	if (!Array.isArray(points) || points.length <= 2 || !(spacing > 0)) return points ? points.slice() : [];
	const out = [points[0]];
	for (let i = 1; i < points.length - 1; i++) {
		if (dist3(points[i], out[out.length - 1]) >= spacing) out.push(points[i]);
	}
	out.push(points[points.length - 1]);
	return out;
}

/** An XY hash grid of triangle indices by bounding box: `{"ix,iy": [t, ...]}`. */
export function buildSpatialGrid(tris, cellSize) {
	return buildSpatialGridOnAxes(tris, cellSize, (v) => v.x, (v) => v.y);
}

/** The same on two chosen axes (`getA(v)`, `getB(v)`). */
export function buildSpatialGridOnAxes(tris, cellSize, getA, getB) {
	const grid = {};
	tris.forEach((t, i) => {
		const as = [getA(t.v0), getA(t.v1), getA(t.v2)], bs = [getB(t.v0), getB(t.v1), getB(t.v2)];
		const a0 = Math.floor(Math.min(...as) / cellSize), a1 = Math.floor(Math.max(...as) / cellSize);
		const b0 = Math.floor(Math.min(...bs) / cellSize), b1 = Math.floor(Math.max(...bs) / cellSize);
		for (let a = a0; a <= a1; a++) for (let b = b0; b <= b1; b++) {
			const k = a + "," + b;
			(grid[k] || (grid[k] = [])).push(i);
		}
	});
	return grid;
}

/** The triangle indices in the cell holding `(a, b)`. */
export function queryGridOnAxes(grid, a, b, cellSize) {
	return grid[Math.floor(a / cellSize) + "," + Math.floor(b / cellSize)] || [];
}

/** The unique triangle indices in the XY cells a bounding box covers. */
export function queryGrid(grid, bb, cellSize) {
	const seen = new Set();
	const x0 = Math.floor(bb.minX / cellSize), x1 = Math.floor(bb.maxX / cellSize);
	const y0 = Math.floor(bb.minY / cellSize), y1 = Math.floor(bb.maxY / cellSize);
	for (let x = x0; x <= x1; x++) for (let y = y0; y <= y1; y++) {
		const cell = grid[x + "," + y];
		if (cell) for (const i of cell) seen.add(i);
	}
	return Array.from(seen);
}

/** The bounding box of a soup: `{minX, minY, minZ, maxX, maxY, maxZ}`. */
export function computeBBox(tris) {
	const points = [];
	for (const t of tris) points.push(t.v0, t.v1, t.v2);
	const b = computeBounds(points);
	return { minX: b.minX, minY: b.minY, minZ: b.minZ, maxX: b.maxX, maxY: b.maxY, maxZ: b.maxZ };
}

/** The bounding box of one triangle. */
export function triBBox(t) {
	return computeBBox([t]);
}

/** True when two boxes overlap (touching counts). */
export function bboxOverlap(a, b) {
	return a.minX <= b.maxX && a.maxX >= b.minX && a.minY <= b.maxY && a.maxY >= b.minY && a.minZ <= b.maxZ && a.maxZ >= b.minZ;
}

/** The mean edge length of a soup (1 for an empty one). */
export function estimateAvgEdge(tris) {
	if (!tris || tris.length === 0) return 1.0;
	let sum = 0;
	for (const t of tris) sum += dist3(t.v0, t.v1) + dist3(t.v1, t.v2) + dist3(t.v2, t.v0);
	return sum / (3 * tris.length);
}

// ── Repair ──────────────────────────────────────────────────────────────────────────────

// One of the reference's repair functions: the step it names, ungated (as the reference
// runs it; finishMesh is the gated pipeline).
function repairSoup(soup, config, what = "soup") {
	const S = soupToArrays(soup, what);
	if (S.index.length === 0) return { soup: [], report: null, positions: S.positions, index: S.index };
	const out = call("repair", S.positions, S.index, JSON.stringify({ gate: false, ...config }));
	return { soup: arraysToSoup(out.positions, out.index), report: parseReport(out.report), positions: out.positions, index: out.index };
}

/**
 * The repair pipeline (async, as in the reference; `onProgress(fraction, message)` is
 * called between steps). Config of the reference: `closeMode` "none" | "weld" | "stitch"
 * (stitch: join boundary loops, then cap what is left), `snapTolerance` (weld distance),
 * `stitchTolerance` (largest gap stitched), `removeDegenerate` (default true),
 * `sliverRatio` (smallest height / longest edge below which a triangle is a sliver),
 * `cleanCrossings` and `removeOverlapping` (remove exactly coincident triangles; opposite
 * pairs cancel), `overlapTolerance` (no effect: coincidence is exact).
 * `closeMode: "closeSolid"` runs `closeSolid` (options `snapTolerance`, `maxCapLoopVerts`,
 * `maxPasses`) and adds its `diagnostics`.
 * `{soup, points, triangles}`, the library's report as non-enumerable `report`.
 */
export async function repairMesh(soup, config, onProgress) {
	const c = config || {};
	const progress = typeof onProgress === "function" ? onProgress : () => {};
	const rc = { orient: "majority" };
	const mode = c.closeMode || "none";
	if (!["none", "weld", "stitch", "closeSolid"].includes(mode)) throw new Error(`meshbool: unknown closeMode ${JSON.stringify(mode)}: use "none", "weld", "stitch" or "closeSolid"`);
	if (mode === "closeSolid") {
		progress(0, "closeSolid");
		await Promise.resolve();
		const closed = closeSolid(soup, { snapTolerance: c.snapTolerance, maxCapLoopVerts: c.maxCapLoopVerts, maxPasses: c.maxPasses });
		const S = soupToArrays(closed.soup, "soup");
		const w = S.index.length > 0 ? call("weld", S.positions, S.index, 0) : S;
		const r = toResult(w.positions, w.index, null);
		r.diagnostics = closed.diagnostics;
		progress(1, "done");
		return r;
	}
	if (mode !== "none" || c.snapTolerance !== undefined) rc.weld = c.snapTolerance !== undefined ? c.snapTolerance : 0.001;
	if (c.cleanCrossings || c.removeOverlapping) rc.remove_duplicates = true;
	if (c.removeDegenerate !== false) {
		rc.degenerate = { min_area: 0 };
		const r = c.sliverRatio !== undefined ? c.sliverRatio : 0.01;
		if (r > 0) rc.degenerate.max_aspect = 1 / r;
	}
	if (mode === "stitch") {
		rc.close = "stitch";
		rc.close_options = { stitch_max_gap: c.stitchTolerance !== undefined ? c.stitchTolerance : 1.0, floor_offset: 10 };
	}
	progress(0, "repair");
	await Promise.resolve();
	const S = soupToArrays(soup, "soup");
	if (S.index.length === 0) return toResult(S.positions, S.index, null);
	let out = call("repair", S.positions, S.index, JSON.stringify(rc));
	const report = parseReport(out.report);
	if (mode === "stitch" && out.index.length > 0) {
		progress(0.8, "cap");
		const capped = call("close", out.positions, out.index, "cap", "{}");
		report.cap = parseReport(capped.report);
		out = capped;
	}
	progress(1, "done");
	return toResult(out.positions, out.index, report);
}

/** Merges vertices within `tolerance` (default 1e-4) and drops triangles that collapse. */
export function deduplicateSeamVertices(tris, tolerance = 1e-4) {
	const S = soupToArrays(tris, "tris");
	if (S.index.length === 0) return [];
	const w = call("weld", S.positions, S.index, tolerance);
	return arraysToSoup(w.positions, w.index);
}

/**
 * Splits edges at vertices that lie exactly on them (decided exactly; `tolerance` and
 * `passes` have no effect). Orientation and every other triangle are kept.
 */
export function resolveTJunctions(soup, tolerance, passes) {
	void tolerance;
	void passes;
	return repairSoup(soup, { tjunctions: true, orient: null }).soup;
}

/** The T-junction repair that splits a shared edge the same way on both sides and keeps each piece's orientation: meshbool's exact repair already does. */
export function resolveTJunctionsHoleFree(soup, tolerance, maxPasses) {
	return resolveTJunctions(soup, tolerance, maxPasses);
}

/**
 * A soup as an indexed mesh `{points, triangles}` (`triangles[t].vertices` are point
 * objects): vertices within `tolerance` merged and collapsed triangles dropped; with
 * `tolerance` 0 or less no vertices are merged, as in the reference (see soupToTyped for
 * an exact weld).
 */
export function weldVertices(tris, tolerance) {
	const S = soupToArrays(tris, "tris");
	if (!(tolerance > 0) || S.index.length === 0) {
		const r = toResult(S.positions, S.index);
		return { points: r.points, triangles: r.triangles };
	}
	const w = call("weld", S.positions, S.index, tolerance);
	const r = toResult(w.positions, w.index);
	return { points: r.points, triangles: r.triangles };
}

/** Indexed triangles `[{vertices: [a, b, c]}]` as a soup. */
export function weldedToSoup(weldedTriangles) {
	return (weldedTriangles || []).map((t) => {
		const [a, b, c] = t.vertices;
		return { v0: { x: a.x, y: a.y, z: a.z }, v1: { x: b.x, y: b.y, z: b.z }, v2: { x: c.x, y: c.y, z: c.z } };
	});
}

export { weldVertices as soupToIndexed, weldedToSoup as indexedToSoup };

/**
 * Removes zero-area triangles (decided exactly), triangles of area at most `minArea`, and
 * slivers whose smallest height over longest edge is below `sliverRatio` (default 0.01);
 * neighbours are re-triangulated so that no hole opens where an edge collapses.
 */
export function removeDegenerateTriangles(tris, minArea = 0, sliverRatio = 0.01) {
	const degenerate = { min_area: minArea > 0 ? minArea : 0 };
	if (sliverRatio > 0) degenerate.max_aspect = 1 / sliverRatio;
	return repairSoup(tris, { degenerate, orient: null }).soup;
}

/**
 * The open-edge loops of a soup (welded exactly): `{loops: Vertex[][],
 * boundaryEdgeCount, overSharedEdgeCount}`.
 */
export function extractBoundaryLoops(tris) {
	const S = soupToArrays(tris, "tris");
	if (S.index.length === 0) return { loops: [], boundaryEdgeCount: 0, overSharedEdgeCount: 0 };
	const b = call("boundaryLoops", S.positions, S.index);
	const points = arraysToPoints(b.positions);
	const loops = b.loops.map((l) => Array.from(l, (v) => ({ ...points[v] })));
	const boundaryEdgeCount = loops.reduce((n, l) => n + l.length, 0);
	const counts = countOpenEdges(tris);
	return { loops, boundaryEdgeCount, overSharedEdgeCount: counts.overShared };
}

/** Triangulates a closed 3-D loop of points (not repeating the first): a soup wound as the loop runs. */
export function triangulateLoop(loop) {
	if (!Array.isArray(loop) || loop.length < 3) return [];
	const pts = new Float64Array(3 * loop.length);
	loop.forEach((p, i) => { pts[3 * i] = p.x; pts[3 * i + 1] = p.y; pts[3 * i + 2] = p.z; });
	const idx = call("triangulateLoop", pts);
	const out = [];
	for (let i = 0; i < idx.length; i += 3) {
		const a = loop[idx[i]], b = loop[idx[i + 1]], c = loop[idx[i + 2]];
		out.push({ v0: { x: a.x, y: a.y, z: a.z }, v1: { x: b.x, y: b.y, z: b.z }, v2: { x: c.x, y: c.y, z: c.z } });
	}
	return out;
}

function closeSoup(tris, mode, options) {
	const S = soupToArrays(tris, "tris");
	if (S.index.length === 0) return { soup: [], report: null };
	const out = call("close", S.positions, S.index, mode, JSON.stringify(options || {}));
	return { soup: arraysToSoup(out.positions, out.index), report: parseReport(out.report), positions: out.positions, index: out.index };
}

/** Every boundary loop capped: the soup with the caps added. */
export function capBoundaryLoops(tris) {
	return closeSoup(tris, "cap").soup;
}

/** Vertices within `snapTol` welded, then every boundary loop capped (`passes`: no effect). */
export function capBoundaryLoopsSequential(soup, snapTol, passes) {
	void passes;
	const welded = snapTol > 0 ? deduplicateSeamVertices(soup, snapTol) : soup;
	return capBoundaryLoops(welded);
}

/** The triangles that join boundary loops closer than `tolerance` (default 1): only the added triangles, as in the reference. */
export function stitchByProximity(tris, tolerance = 1.0) {
	const r = closeSoup(tris, "stitch", { maxGap: tolerance });
	return addedTriangles(tris, r.soup);
}

function triKey(t) {
	return `${t.v0.x},${t.v0.y},${t.v0.z}|${t.v1.x},${t.v1.y},${t.v1.z}|${t.v2.x},${t.v2.y},${t.v2.z}`;
}

function addedTriangles(before, after) {
	const have = new Map();
	for (const t of before) {
		const keys = [triKey(t), triKey({ v0: t.v1, v1: t.v2, v2: t.v0 }), triKey({ v0: t.v2, v1: t.v0, v2: t.v1 })];
		for (const k of keys) have.set(k, (have.get(k) || 0) + 1);
	}
	return after.filter((t) => {
		const k = triKey(t);
		const n = have.get(k) || 0;
		if (n > 0) {
			have.set(k, n - 1);
			return false;
		}
		return true;
	});
}

/** Exactly coincident triangles removed: same orientation keeps one, opposite pairs cancel. */
export function cleanCrossingTriangles(tris) {
	return repairSoup(tris, { remove_duplicates: true, orient: null }).soup;
}

/** Anti-parallel coincident pairs ("internal walls") removed, exactly (`tolerance`: no effect). */
export function removeOverlappingTriangles(tris, tolerance) {
	void tolerance;
	return cleanCrossingTriangles(tris);
}

/** An indexed mesh `{points, triangles}` closed by capping its holes: `{points, triangles}`. */
export function forceCloseIndexedMesh(points, triangles) {
	void points;
	const soup = weldedToSoup(triangles);
	const r = closeSoup(soup, "cap");
	if (!r.positions) return { points: [], triangles: [] };
	const res = toResult(r.positions, r.index);
	return { points: res.points, triangles: res.triangles };
}

/** Every closed loop of open edges filled (`tolerance`: no effect): the soup with the fills. */
export function fillOpenEdgeLoops(soup, tolerance) {
	void tolerance;
	return capBoundaryLoops(soup);
}

/** Vertices within `tolerance` welded (all vertices: interior ones within a tolerance are welded too). */
export function weldBoundaryVertices(tris, tolerance) {
	return deduplicateSeamVertices(tris, tolerance);
}

/**
 * Walls from every boundary loop down to a floor `floorOffset` (default 10) below the
 * lowest point, and the floor capped: only the added triangles, as in the reference (the
 * surface faces up first).
 */
export function buildCurtainAndCap(tris, floorOffset = 10) {
	const up = ensureZUpNormals(tris);
	const r = closeSoup(up, "curtain", { floorOffset });
	return addedTriangles(up, r.soup);
}

/** Boundary gaps closed: loops within `maxDist` stitched, the rest capped. The whole soup. */
export function generateClosingTriangles(tris, maxDist) {
	const stitched = closeSoup(tris, "stitch", { maxGap: maxDist }).soup;
	return capBoundaryLoops(stitched);
}

// ── Normals / measures ──────────────────────────────────────────────────────────────────

/** The unit normal of a triangle (zero vector for a degenerate one). */
export function triNormal(t) {
	const u = { x: t.v1.x - t.v0.x, y: t.v1.y - t.v0.y, z: t.v1.z - t.v0.z };
	const v = { x: t.v2.x - t.v0.x, y: t.v2.y - t.v0.y, z: t.v2.z - t.v0.z };
	const n = cross(u, v);
	const len = Math.sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
	return len > 0 ? { x: n.x / len, y: n.y / len, z: n.z / len } : { x: 0, y: 0, z: 0 };
}

/** Every triangle whose normal points down (z below −0.01) reversed; a new soup. */
export function ensureZUpNormals(tris) {
	return tris.map((t) => (triNormal(t).z < -0.01 ? flippedSoup([t])[0] : { v0: { ...t.v0 }, v1: { ...t.v1 }, v2: { ...t.v2 } }));
}

/** Every triangle reversed; a new soup. */
export function flipAllNormals(tris) {
	return flippedSoup(tris);
}

/**
 * A label for the dominant facing: "Out"/"In" for solids (sign of the volume), "~Out"/"~In"
 * for open ones that mostly enclose, "Z+", "Z-", "X+", ... when one axis dominates,
 * "Aligned", "Chaos", or "N/A" for an empty or zero-area soup.
 */
export function classifyNormalDirection(tris, isClosed, signedVolume) {
	if (!tris || tris.length === 0) return "N/A";
	let nx = 0, ny = 0, nz = 0, total = 0;
	for (const t of tris) {
		const n = cross({ x: t.v1.x - t.v0.x, y: t.v1.y - t.v0.y, z: t.v1.z - t.v0.z }, { x: t.v2.x - t.v0.x, y: t.v2.y - t.v0.y, z: t.v2.z - t.v0.z });
		nx += n.x; ny += n.y; nz += n.z;
		total += Math.sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
	}
	if (total < 1e-12) return "N/A";
	const vol = signedVolume !== undefined ? signedVolume : computeSignedVolume(tris);
	if (isClosed) {
		if (vol > 1e-6) return "Out";
		if (vol < -1e-6) return "In";
	}
	const consistency = Math.sqrt(nx * nx + ny * ny + nz * nz) / total;
	if (consistency < 0.1) {
		if (vol > 1e-6) return isClosed ? "Out" : "~Out";
		if (vol < -1e-6) return isClosed ? "In" : "~In";
		return "Chaos";
	}
	const ax = Math.abs(nx), ay = Math.abs(ny), az = Math.abs(nz);
	const m = Math.max(ax, ay, az);
	if (m > 0.7 * Math.sqrt(nx * nx + ny * ny + nz * nz)) {
		if (m === az) return nz > 0 ? "Z+" : "Z-";
		if (m === ax) return nx > 0 ? "X+" : "X-";
		return ny > 0 ? "Y+" : "Y-";
	}
	return consistency > 0.5 ? "Aligned" : "Chaos";
}

/** Signed volume by the divergence theorem (positive for outward normals), computed by meshbool. */
export function computeSignedVolume(tris) {
	if (!tris || tris.length === 0) return 0;
	const S = soupToArrays(tris, "tris");
	return call("measures", S.positions, S.index)[0];
}

/**
 * Area projected on "xy" (default), "yz" or "xz", counting the triangles that face the
 * plane's positive axis (z, x, y): a closed solid's footprint, a terrain's plan area.
 */
export function computeProjectedArea(tris, plane = "xy") {
	const axes = { xy: ["x", "y", "z"], yz: ["y", "z", "x"], xz: ["x", "z", "y"], zx: ["x", "z", "y"] }[plane];
	if (axes === undefined) throw new Error(`meshbool: unknown plane ${JSON.stringify(plane)}: use "xy", "yz" or "xz"`);
	const [u, v, w] = axes;
	let area = 0;
	for (const t of tris || []) {
		const n = cross({ x: t.v1.x - t.v0.x, y: t.v1.y - t.v0.y, z: t.v1.z - t.v0.z }, { x: t.v2.x - t.v0.x, y: t.v2.y - t.v0.y, z: t.v2.z - t.v0.z });
		if (n[w] <= 0) continue;
		area += Math.abs((t.v1[u] - t.v0[u]) * (t.v2[v] - t.v0[v]) - (t.v2[u] - t.v0[u]) * (t.v1[v] - t.v0[v])) / 2;
	}
	return area;
}

/** Surface area. */
export function compute3DSurfaceArea(tris) {
	if (!tris || tris.length === 0) return 0;
	const S = soupToArrays(tris, "tris");
	return call("measures", S.positions, S.index)[1];
}

// ── Winding numbers and point classification ────────────────────────────────────────────

/** Signed solid angle of triangle (a, b, c) seen from p (scalar form). */
export function solidAngleAt(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz) {
	const x1 = ax - px, y1 = ay - py, z1 = az - pz;
	const x2 = bx - px, y2 = by - py, z2 = bz - pz;
	const x3 = cx - px, y3 = cy - py, z3 = cz - pz;
	const l1 = Math.sqrt(x1 * x1 + y1 * y1 + z1 * z1), l2 = Math.sqrt(x2 * x2 + y2 * y2 + z2 * z2), l3 = Math.sqrt(x3 * x3 + y3 * y3 + z3 * z3);
	const det = x1 * (y2 * z3 - z2 * y3) - y1 * (x2 * z3 - z2 * x3) + z1 * (x2 * y3 - y2 * x3);
	const div = l1 * l2 * l3 + (x1 * x2 + y1 * y2 + z1 * z2) * l3 + (x1 * x3 + y1 * y3 + z1 * z3) * l2 + (x2 * x3 + y2 * y3 + z2 * z3) * l1;
	return 2 * Math.atan2(det, div);
}

/** Signed solid angle of a triangle `{v0, v1, v2}` seen from `p`. */
export function solidAngle(p, t) {
	return solidAngleAt(p.x, p.y, p.z, t.v0.x, t.v0.y, t.v0.z, t.v1.x, t.v1.y, t.v1.z, t.v2.x, t.v2.y, t.v2.z);
}

/** Generalized winding number of a point against a soup (1 inside a closed outward solid, 0 outside). */
export function windingNumber(p, soup) {
	let sum = 0;
	for (const t of soup) sum += solidAngle(p, t);
	return sum / (4 * Math.PI);
}

/** The same on flat arrays. */
export function windingNumberIndexed(px, py, pz, positions, index) {
	let sum = 0;
	for (let i = 0; i < index.length; i += 3) {
		const a = 3 * index[i], b = 3 * index[i + 1], c = 3 * index[i + 2];
		sum += solidAngleAt(px, py, pz, positions[a], positions[a + 1], positions[a + 2], positions[b], positions[b + 1], positions[b + 2], positions[c], positions[c + 1], positions[c + 2]);
	}
	return sum / (4 * Math.PI);
}

/**
 * 1 when `p` is inside the solid `tris` (winding number at least 1/2), −1 otherwise. The
 * reference votes with three ray casts over `grids`; here `grids` is not needed (accepted
 * and ignored) and the answer does not depend on where rays happen to hit edges.
 */
export function classifyPointMultiAxis(p, tris, grids) {
	void grids;
	return windingNumber(p, tris) >= 0.5 ? 1 : -1;
}

// ── Utilities ───────────────────────────────────────────────────────────────────────────

/** Distance between two points. */
export function dist3(a, b) {
	return Math.sqrt(distSq3(a, b));
}

/** Squared distance between two points. */
export function distSq3(a, b) {
	const dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
	return dx * dx + dy * dy + dz * dz;
}

/** Area of one triangle. */
export function triangleArea3D(t) {
	const n = cross({ x: t.v1.x - t.v0.x, y: t.v1.y - t.v0.y, z: t.v1.z - t.v0.z }, { x: t.v2.x - t.v0.x, y: t.v2.y - t.v0.y, z: t.v2.z - t.v0.z });
	return 0.5 * Math.sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
}

/** The bounds of points: `{minX, maxX, minY, maxY, minZ, maxZ}`. */
export function computeBounds(points) {
	let minX = Infinity, minY = Infinity, minZ = Infinity, maxX = -Infinity, maxY = -Infinity, maxZ = -Infinity;
	for (const p of points) {
		if (p.x < minX) minX = p.x;
		if (p.y < minY) minY = p.y;
		if (p.z < minZ) minZ = p.z;
		if (p.x > maxX) maxX = p.x;
		if (p.y > maxY) maxY = p.y;
		if (p.z > maxZ) maxZ = p.z;
	}
	return { minX, maxX, minY, maxY, minZ, maxZ };
}

/** Cross product. */
export function cross(a, b) {
	return { x: a.y * b.z - a.z * b.y, y: a.z * b.x - a.x * b.z, z: a.x * b.y - a.y * b.x };
}

/** The point a + t (b − a). */
export function lerpVert(a, b, t) {
	return { x: a.x + t * (b.x - a.x), y: a.y + t * (b.y - a.y), z: a.z + t * (b.z - a.z) };
}

/**
 * Edge counts of a soup, vertices taken as the library takes them (exactly equal, or
 * equal up to rounding noise where that closes edges): `{openEdges, overShared, total}`
 * (edges used once; more than twice; all).
 */
export function countOpenEdges(tris) {
	const S = soupToArrays(tris, "tris");
	let openEdges = 0, overShared = 0, total = 0;
	if (S.index.length === 0) return { openEdges, overShared, total };
	for (const e of edgeTable(conditioned(S, false).index).values()) {
		total++;
		if (e.uses.length === 1) openEdges++;
		else if (e.uses.length > 2) overShared++;
	}
	return { openEdges, overShared, total };
}

/**
 * The edge-connected sub-soups of a soup, largest first; vertices are shared when equal
 * or equal up to rounding noise (the library's rule), so a grid whose shared corners
 * differ in the last bits is one component.
 */
export function findConnectedComponents(soup) {
	if (!Array.isArray(soup)) throw new Error("meshbool: findConnectedComponents takes a soup");
	return componentSoups(soup);
}

/** The same (`tolerance`: no effect; vertices are shared as the library takes them). */
export function findConnectedComponentsPooled(soup, options) {
	void options;
	return findConnectedComponents(soup);
}

// ── BMS pipeline: the reference's default entry point, computed by meshbool ─────────────

const CLASSIFIERS = ["auto", "hybrid", "heffalump"];

// The side of each of the library's groups in the reference's four (see FOLD).
const SIDE = { a_in_b: 1, a_on_b_same: 1, a_on_b_opposite: 1, a_out_b: -1, b_in_a: 1, b_on_a_opposite: 1, b_out_a: -1, b_on_a_same: -1 };

/**
 * The snap tolerance of the BMS path: `snap`, else `tolerance` (the reference's pool
 * tolerance), else 0.001 × the mean edge of the first 200 triangles of each operand
 * (the reference's default pool tolerance), so that crossing points closer than that
 * do not leave needles. 0 gives the exact split.
 */
function bmsSnap(o, A, B) {
	const given = o.snap !== undefined ? o.snap : o.tolerance;
	if (given !== undefined) {
		if (typeof given !== "number" || !Number.isFinite(given) || given < 0) throw new Error(`meshbool: option tolerance must be a distance >= 0, got ${given}`);
		return given;
	}
	return 0.001 * 0.5 * (meanEdge(A) + meanEdge(B));
}

/**
 * The reference's BMS boolean, computed by meshbool's exact split: `{groups, segments,
 * polylines, rawPolylines, meshEdgePolys, componentWalks, megaSoup, pool, classifier,
 * verification, splitReport}` and, when `op` is given, `result: {soup, points,
 * triangles}`; with `indexed: true` also `indexed: {points, groups}` (indexGroups).
 *
 * - The split is snapped at `tolerance` (see below; the report's `splitReport.snap` says
 *   what moved): crossing points closer than that are merged, needles removed, where that
 *   makes no defect. Default 0.001 × the mean edge (the reference's pool tolerance);
 *   `tolerance: 0` is the exact split. A large triangle cut by a dense seam gets points
 *   inside it (`sliverGuard`, on by default here) so that its pieces are not needles.
 * - `megaSoup` is every piece `{v0, v1, v2, mesh: "A" | "B", origIdx}` with corners from
 *   `pool` (`getAll()`: vertices `{x, y, z, id}`); `segments` (`{p0, p1, idxA, idxB}`) are
 *   the exact crossing segments with their ends on the pool's vertices (after the snap:
 *   segments it shrank to a point are gone); `polylines` chain them. `coplanar: false`
 *   leaves segments of coplanar contact out (the pieces are split there all the same).
 * - `classifier` `{A, B}` names the reference's classifier for such inputs: "none (no
 *   intersection)" without segments, "heffalump (forced)" for `classifier: "heffalump"`
 *   (or `forceHeffalump`), "heffalump (census: non-manifold edges)" when an operand has
 *   edges of more than two triangles (such operands are taken as given), else "hybrid".
 *   Every side is decided by meshbool's exact classification whichever is named.
 * - `verification` is `verifyBmsClassification` of the pieces (null for `classifier:
 *   "hybrid"`, and without segments when the operands' boxes are apart or only touch;
 *   a failure "no-segments-but-bboxes-overlap" without segments when they overlap).
 * - `splitReport`: `{lostSegments, segments, seamPoints, snap}`: `lostSegments` counts
 *   the exact crossing segments with an end that is no vertex of the pieces (within the
 *   snap tolerance); `snap` is the library's report of the snap.
 */
export function bmsBooleanOp(soupA, soupB, op, options) {
	const o = options || {};
	const choice = o.forceHeffalump ? "heffalump" : o.classifier === undefined ? "auto" : o.classifier;
	if (!CLASSIFIERS.includes(choice)) throw new Error(`meshbool: unknown classifier ${JSON.stringify(choice)}: use "auto", "hybrid" or "heffalump"`);
	const [A, B] = operands(soupA, soupB, o);
	const census = nonManifoldEdgeCount(A) > 0 || nonManifoldEdgeCount(B) > 0;
	const snap = bmsSnap(o, A, B);
	const splitOptions = { ...o, snap, sliverGuard: o.sliverGuard !== false };
	delete splitOptions.tolerance;
	if (census && o.force === undefined) splitOptions.force = true;
	const raw = call("split", A.positions, A.index, B.positions, B.index, checkOptions(splitOptions));
	const report = parseReport(raw.report);
	const named = {};
	for (const g of raw.groups) named[g.name] = g;
	const groups = {};
	for (const key of Object.keys(FOLD)) groups[key] = groupSoup(named, FOLD[key]);
	const { pool, pieces } = poolOfSplit(raw.groups);
	const crossings = call("intersect", A.positions, A.index, B.positions, B.index, JSON.stringify({ withCoplanar: true }));
	const { segments, lost } = seamInPool(crossings, pool, snap, o.coplanar !== false);
	const sides = pieces.map((t) => SIDE[t.group]);
	const megaSoup = pieces.map((t, i) => {
		const piece = { v0: t.v0, v1: t.v1, v2: t.v2, mesh: t.mesh, origIdx: t.origIdx };
		rememberSide(piece, sides[i]);
		return piece;
	});
	const polylines = chainById(segments);
	const label = segments.length === 0 ? "none (no intersection)" : choice === "heffalump" ? "heffalump (forced)" : census ? "heffalump (census: non-manifold edges)" : "hybrid";
	let verification = null;
	if (choice !== "hybrid") {
		if (segments.length > 0) {
			verification = verifyBmsClassification(megaSoup, sides, segments, polylines, soupA, soupB);
		} else if (boxesOverlapWithArea(soupA, soupB)) {
			const counts = verifyBmsClassification(megaSoup, sides, [], [], soupA, soupB).counts;
			verification = { ok: false, counts, failures: [{ check: "no-segments-but-bboxes-overlap", mesh: null, detail: "no crossing segments, yet the bounding boxes overlap with area: the meshes may lie on one another or be nested" }] };
		}
	}
	const splitReport = { lostSegments: lost, segments: segments.length, seamPoints: report.seam_points, snap: report.snap || null };
	const out = { groups, segments, polylines, rawPolylines: polylines, meshEdgePolys: [], componentWalks: [], megaSoup, pool, classifier: { A: label, B: label }, verification, splitReport };
	if (op !== undefined && op !== null) {
		out.result = mergeSplitGroups(groups, op);
	}
	if (o.indexed) out.indexed = indexGroups(groups);
	Object.defineProperty(out, "report", { value: report, enumerable: false });
	return out;
}

/**
 * The reference's intersection stage: the exact crossing segments of A and B with their
 * ends in a vertex pool, `{segments: [{p0, p1, idxA, idxB}], crossedSetA, crossedSetB,
 * pool, coplanarPairs}` (`crossedSetA`/`B`: crossed triangle → its segments; ends are
 * pool vertices `{x, y, z, id}`, shared between segments). With `coplanar` (default
 * true) the outlines of coplanar overlaps with area are segments too and `coplanarPairs`
 * counts the overlapping pairs (coplanar neighbours that only share an edge touch, and
 * give none); `coplanar: false` leaves both out.
 */
export function bmsIntersect(soupA, soupB, options) {
	const o = options || {};
	const coplanar = o.coplanar !== false;
	const A = soupToArrays(soupA, "soupA"), B = soupToArrays(soupB, "soupB");
	const pool = createVertexPool(0);
	const out = { segments: [], crossedSetA: {}, crossedSetB: {}, pool, coplanarPairs: 0 };
	if (A.index.length === 0 || B.index.length === 0) return out;
	const raw = call("intersect", A.positions, A.index, B.positions, B.index, JSON.stringify({ withCoplanar: coplanar }));
	const overlap = overlapPairs(raw);
	const s = raw.segments;
	for (let i = 0; i < raw.triA.length; i++) {
		if (raw.coplanar[i] === 1 && !overlap.has(raw.triA[i] * 4294967296 + raw.triB[i])) continue;
		const k = 6 * i;
		const seg = { p0: pool.getOrCreate(s[k], s[k + 1], s[k + 2]), p1: pool.getOrCreate(s[k + 3], s[k + 4], s[k + 5]), idxA: raw.triA[i], idxB: raw.triB[i] };
		out.segments.push(seg);
		(out.crossedSetA[seg.idxA] ||= []).push(seg);
		(out.crossedSetB[seg.idxB] ||= []).push(seg);
	}
	out.coplanarPairs = coplanar ? overlap.size : 0;
	return out;
}

/**
 * The reference's split stage: A and B cut along their intersection into pieces
 * `{v0, v1, v2, mesh: "A" | "B", origIdx}` whose corners are vertices of `isect.pool`
 * (from `bmsIntersect`, so seam points carry the segments' ids; a fresh pool without
 * it). Exact: every piece lies wholly on one side of the other mesh. With `soupB` empty,
 * `soupA` cut where it crosses itself (its self-arrangement, as for `bmsSelfIntersect`'s
 * segments). Options as for the library's split (`snap`, `force`, and `sliverGuard`, on
 * by default here: a large triangle cut by a dense seam gets points inside it, so that
 * its pieces are not needles).
 */
export function bmsSplit(soupA, soupB, isect, options) {
	const A = soupToArrays(soupA, "soupA"), B = soupToArrays(soupB || [], "soupB");
	emptyCheck(A, "soupA");
	if (B.index.length === 0) {
		// One soup (bmsSelfIntersect's): its self-arrangement.
		const pool = isect && isect.pool && typeof isect.pool.getOrCreate === "function" ? isect.pool : createVertexPool(0);
		return selfPieces(A, pool);
	}
	const o = { ...(options || {}) };
	if (o.sliverGuard === undefined) o.sliverGuard = true;
	const raw = call("split", A.positions, A.index, B.positions, B.index, checkOptions(o));
	const pool = isect && isect.pool && typeof isect.pool.getOrCreate === "function" ? isect.pool : createVertexPool(0);
	return poolOfSplit(raw.groups, pool).pieces.map((t) => {
		const piece = { v0: t.v0, v1: t.v1, v2: t.v2, mesh: t.mesh, origIdx: t.origIdx };
		rememberSide(piece, SIDE[t.group]);
		return piece;
	});
}

/**
 * Whether the reference would route a pair to its "heffalump" classifier: true when an
 * operand has edges of more than two triangles (meshbool takes such operands as given,
 * and its classification is exact either way).
 */
export function shouldUseHeffalump(soupA, soupB) {
	const A = soupToArrays(soupA || [], "soupA"), B = soupToArrays(soupB || [], "soupB");
	return nonManifoldEdgeCount(A) > 0 || nonManifoldEdgeCount(B) > 0;
}

/**
 * The reference's classifier for defective meshes, on split pieces `{v0, v1, v2, mesh:
 * "A" | "B"}` (`megaSoup`): `{aInside, aOutside, bInside, bOutside, componentWalks}`.
 * Pieces of `bmsSplit` keep the side the library's exact split gave them; others are
 * classified by their centroid against the other input, exactly (see classifyPoints).
 * `segments` and `options` are not needed; `componentWalks` is empty.
 */
export function heffalumpClassify(megaSoup, segments, soupA, soupB, options) {
	void options;
	return classifyPieces(megaSoup, segments, soupA, soupB);
}

/**
 * The solid a soup bounds under a winding threshold, in the reference's terms: `kept`
 * the triangles between space of winding number at least `threshold` and space below it
 * (meshbool's exact resolve, fill rule "positive": `threshold` must lie in (0, 1], the
 * thresholds that rule answers for integer winding numbers), `diagnostics: {cells,
 * propagationViolations, leakedFaceFraction, windingMax}`. `windingMax` is the largest
 * of `windingFn(x, y, z)` (default: the soup's own winding number) at points a hair to
 * either side of up to 256 of the soup's triangles, rounded; `cells` the regions of
 * distinct winding those points see (at least 2 for a non-empty solid); the exact
 * resolve leaves nothing to propagate or leak, so those two are 0.
 */
export function extractByCellComplex(soup, windingFn, options) {
	const o = options || {};
	const threshold = o.threshold !== undefined ? o.threshold : 0.5;
	if (!(threshold > 0 && threshold <= 1)) throw new Error(`meshbool: extractByCellComplex answers thresholds in (0, 1] (fill rule "positive"), got ${threshold}`);
	const diagnostics = { cells: 0, propagationViolations: 0, leakedFaceFraction: 0, windingMax: 0 };
	const S = soupToArrays(soup, "soup");
	if (S.index.length === 0) return { kept: [], diagnostics };
	const w = typeof windingFn === "function" ? windingFn : (x, y, z) => windingNumber({ x, y, z }, soup);
	const seen = new Set([0]);
	const box = computeBBox(soup);
	const hair = 1e-7 * Math.max(box.maxX - box.minX, box.maxY - box.minY, box.maxZ - box.minZ, 1e-300);
	const step = Math.max(1, Math.floor(soup.length / 256));
	for (let t = 0; t < soup.length; t += step) {
		const tri = soup[t];
		const n = triNormal(tri);
		if (n.x === 0 && n.y === 0 && n.z === 0) continue;
		const c = { x: (tri.v0.x + tri.v1.x + tri.v2.x) / 3, y: (tri.v0.y + tri.v1.y + tri.v2.y) / 3, z: (tri.v0.z + tri.v1.z + tri.v2.z) / 3 };
		for (const sgn of [1, -1]) seen.add(Math.round(w(c.x + sgn * hair * n.x, c.y + sgn * hair * n.y, c.z + sgn * hair * n.z)));
	}
	diagnostics.windingMax = Math.max(...seen);
	diagnostics.cells = seen.size;
	const out = call("resolve", S.positions, S.index, "positive", false);
	return { kept: arraysToSoup(out.positions, out.index), diagnostics };
}

function otherSide(side) {
	return side === "inside" ? "outside" : "inside";
}

function groupKey(mesh, side) {
	return (mesh === "A" || mesh === "a" ? "a" : "b") + (side === "inside" ? "Inside" : "Outside");
}

/** Moves the listed triangles of `mesh`'s `fromSide` group to the other side, in place. */
export function reclassifyTriangles(groups, mesh, fromSide, indices) {
	const from = groups[groupKey(mesh, fromSide)], to = groups[groupKey(mesh, otherSide(fromSide))];
	const move = new Set(indices);
	const keep = [];
	from.forEach((t, i) => (move.has(i) ? to.push(t) : keep.push(t)));
	from.length = 0;
	from.push(...keep);
	return move.size;
}

/**
 * Toggles the side of the triangle whose centroid lies within `tol` of `(x, y, z)`:
 * `{moved, mesh?, from?, to?}`.
 */
export function reclassifyAtPoint(groups, x, y, z, tol = 0.01) {
	const p = { x, y, z };
	for (const mesh of ["A", "B"]) {
		for (const side of ["inside", "outside"]) {
			const list = groups[groupKey(mesh, side)] || [];
			for (let i = 0; i < list.length; i++) {
				const t = list[i];
				const c = { x: (t.v0.x + t.v1.x + t.v2.x) / 3, y: (t.v0.y + t.v1.y + t.v2.y) / 3, z: (t.v0.z + t.v1.z + t.v2.z) / 3 };
				if (dist3(c, p) <= tol) {
					reclassifyTriangles(groups, mesh, side, [i]);
					return { moved: true, mesh, from: side, to: otherSide(side) };
				}
			}
		}
	}
	return { moved: false };
}

/** Moves the edge-connected region of `seedIdx` in `mesh`'s `fromSide` group to the other side; the number moved. */
export function reclassifyRegion(groups, mesh, fromSide, seedIdx) {
	const list = groups[groupKey(mesh, fromSide)];
	if (!list || seedIdx < 0 || seedIdx >= list.length) return 0;
	const S = soupToArrays(list);
	const { ids } = call("components", S.positions, S.index);
	const region = [];
	for (let i = 0; i < list.length; i++) if (ids[i] === ids[seedIdx]) region.push(i);
	return reclassifyTriangles(groups, mesh, fromSide, region);
}

// ── meshbool's own soup-level extras ────────────────────────────────────────────────────

/**
 * The solid a self-crossing or self-overlapping soup encloses: `{soup, changed,
 * diagnostics}` (see `selfResolveArrays` in solids.js for the options `preOrient`, `rule`
 * and the diagnostics). When nothing changed, `soup` is the caller's own array.
 */
export function bmsSelfResolve(soup, options) {
	const S = soupToArrays(soup, "soup");
	const r = selfResolveArrays(S, options);
	return { soup: r.changed ? arraysToSoup(r.positions, r.index) : soup, changed: r.changed, diagnostics: r.diagnostics };
}

/**
 * `bmsSelfResolve` on flat arrays `{positions, index}`: `{positions, index, changed,
 * diagnostics}`; when nothing changed, the caller's own typed arrays.
 */
export function bmsSelfResolveIndexed(m, options) {
	const M = indexedArrays(m, "mesh");
	const r = selfResolveArrays(M, options);
	if (!r.changed) return { positions: m.positions, index: m.index, changed: false, diagnostics: r.diagnostics };
	return { positions: r.positions, index: r.index, changed: true, diagnostics: r.diagnostics };
}

/**
 * The reference's recommended entry point: the BMS boolean (`bmsBooleanOp`, snapped at
 * its `tolerance`), then (quality "strict", the default) the gated finishing stages
 * (`finishMesh` at the same `tolerance`), so the result is never worse than the boolean's.
 * `{soup, ok, operation, report, verification, classifier, boolean}`: `report` the
 * finishMesh report (null for quality "raw"), `boolean` the `bmsBooleanOp` result,
 * `verification` and `classifier` its own. An empty result is not ok (`soup` [], `ok`
 * false: the intersection of operands apart, say); operands apart still unite and
 * subtract exactly. `null` when an input is null; an Error when `op` is missing.
 */
export function booleanAuto(soupA, soupB, op, options) {
	if (op === undefined || op === null || op === "") throw new Error("meshbool: booleanAuto requires an operation: \"union\", \"intersect\" or \"subtract\"");
	if (soupA == null || soupB == null) return null;
	const o = options || {};
	const operation = { union: "union", intersection: "intersect", difference: "subtract", "reverse-difference": "reverse-difference" }[opName(op)];
	const bms = bmsBooleanOp(soupA, soupB, op, o);
	const soup = bms.result ? bms.result.soup : [];
	const checks = { expectClosed: o.expectClosed, minArea: o.minArea, volumeTolPct: o.volumeTolPct, tolerance: o.tolerance };
	if (o.quality === "raw") {
		return { soup, ok: soup.length > 0 && verifyOutput(soup, checks).ok, operation, report: null, verification: bms.verification, classifier: bms.classifier, boolean: bms };
	}
	const report = finishMesh(soup, checks);
	return { soup: report.soup, ok: report.ok, operation, report, verification: bms.verification, classifier: bms.classifier, boolean: bms };
}
