// Type declarations of the `meshbool` package (js/src/index.js).

// ── data model ─────────────────────────────────────────────────────────────────────────

/** A point. */
export interface Vertex {
	x: number;
	y: number;
	z: number;
}

/** A triangle of a soup; its normal follows v0 → v1 → v2 (right hand). */
export interface Triangle {
	v0: Vertex;
	v1: Vertex;
	v2: Vertex;
}

/** Triangles that share no vertex objects. */
export type TriangleSoup = Triangle[];

/** A triangle of an indexed mesh: its three point objects. */
export interface WeldedTriangle {
	vertices: [Vertex, Vertex, Vertex];
}

/** An indexed ("welded") mesh of point objects. */
export interface WeldedMesh {
	points: Vertex[];
	triangles: WeldedTriangle[];
}

/** A result: the soup and the same mesh indexed. `report` is meshbool's report (non-enumerable). */
export interface BooleanResult extends WeldedMesh {
	soup: TriangleSoup;
	readonly report?: Report;
}

/** The typed-array mesh of the fast path: three numbers per vertex, three indices per triangle. */
export interface IndexedMesh {
	positions: Float64Array;
	index: Uint32Array;
}

/** A JSON report of the library (the CLI's `--json`; keys in docs/json.md). */
export type Report = Record<string, any>;

/** An axis-aligned box. */
export interface AABB {
	minX: number;
	maxX: number;
	minY: number;
	maxY: number;
	minZ: number;
	maxZ: number;
}

/** An intersection segment. */
export interface Segment {
	p0: Vertex;
	p1: Vertex;
}

/** An intersection segment with the triangle of A and of B it lies in. */
export interface TaggedSegment extends Segment {
	idxA: number;
	idxB: number;
}

/** The reference's operation names, and meshbool's. */
export type Operation = "union" | "intersect" | "subtract" | "intersection" | "difference" | "reverse-difference" | "reverseDifference";

/** meshbool's operand checks (all on but `force` by default). */
export interface CheckOptions {
	/** Proceed when a check finds a problem (listed in the report's `assumed`). */
	force?: boolean;
	/** Look for self-intersections (exact). */
	selfCheck?: boolean;
	/** Resolve self-intersecting closed operands into the solid they enclose. */
	resolve?: boolean;
	/** Make inconsistently oriented operands consistent. */
	orient?: boolean;
	/** Keep edges used by more than two triangles (default: split apart). */
	keepNonmanifold?: boolean;
	/**
	 * Snap tolerance D (booleans and splits; default 0, the exact result): edges shorter
	 * than D collapsed and needles (altitude below D) removed where that keeps the result
	 * manifold, turns no triangle over, makes no self-intersection and moves no vertex more
	 * than D; a split's groups are snapped together, so that any pick of them is closed
	 * where the exact pick is. The report's `snap` says what was done.
	 */
	snap?: number;
	/**
	 * Keep every seam point of the exact arrangement (booleans and splits; default true,
	 * so that a boolean equals its merged split groups as in the reference library).
	 * `false` runs the exact clean-up: seam points where the result is flat or straight
	 * are removed and zero-area triangles made by rounding are collapsed or flipped away,
	 * no surface moving (a split's groups together, each keeping its shape, only where
	 * the seam runs straight through flat faces of both meshes); the report's `cleanup`
	 * says what was done.
	 */
	keepSeamPoints?: boolean;
	/**
	 * Cut coplanar overlaps (shared faces) along every edge of either mesh that crosses
	 * them (booleans, splits and raw segments; default true: the common refinement of
	 * both triangulations, as in the reference library). `false`: coplanar regions meet
	 * along their boundaries only, the same surface with fewer triangles (two fanned CAD
	 * caps in one plane otherwise cross in a number of points that grows as the product
	 * of their triangle counts).
	 */
	coplanarRefinement?: boolean;
}

export interface BooleanOptions extends CheckOptions {
	/** Exact T-junction repair of the inputs (and a weld within `tolerance` when given). */
	preRepair?: boolean;
	/** Cap the result's holes. */
	fillGaps?: boolean;
	/** Cap the result's holes. */
	forceClose?: boolean;
	/** Weld distance for `preRepair`. */
	tolerance?: number;
	/** No effect (the T-junction repair is exact). */
	tjunctionPasses?: number;
}

// ── boolean ────────────────────────────────────────────────────────────────────────────

export interface SoupGroups {
	aInside: TriangleSoup;
	aOutside: TriangleSoup;
	bInside: TriangleSoup;
	bOutside: TriangleSoup;
}

export interface SplitResult {
	groups: SoupGroups;
	segments: TaggedSegment[];
	readonly report?: Report;
}

export type GroupChoice = boolean | "flip";

export interface SplitSelection {
	aInside?: GroupChoice;
	aOutside?: GroupChoice;
	bInside?: GroupChoice;
	bOutside?: GroupChoice;
}

export interface SplitComponent {
	mesh: "A" | "B";
	side: "inside" | "outside";
	index: number;
	soup: TriangleSoup;
	triCount: number;
}

export interface Pick {
	soup: TriangleSoup;
	flip?: boolean;
}

export function boolean(soupA: TriangleSoup | null, soupB: TriangleSoup | null, operation: Operation, options?: BooleanOptions): BooleanResult | null;
export function splitMeshPair(soupA: TriangleSoup | null, soupB: TriangleSoup | null, options?: CheckOptions): SplitResult | null;
export function mergeSplitGroups(groups: SoupGroups, operation: Operation): BooleanResult | null;
export function selectSplits(groups: SoupGroups, selection: SplitSelection): BooleanResult | null;
export function splitToComponents(groups: SoupGroups): SplitComponent[];
export function mergeSmallComponents(components: SplitComponent[], threshold?: number): SplitComponent[];
export function mergeComponents(picks: Pick[]): BooleanResult | null;

// ── typed-array fast path ──────────────────────────────────────────────────────────────

export interface IndexedResult extends IndexedMesh {
	report: Report;
}

export interface IndexedBooleanResult extends IndexedResult {
	/** 0: the triangle comes from A, 1: from B. */
	source: Uint8Array;
	/** The input triangle each result triangle is part of. */
	triangle: Uint32Array;
	/** 1 where the triangle's orientation was reversed. */
	flipped: Uint8Array;
}

export interface IndexedGroup extends IndexedMesh {
	name: string;
	source: Uint8Array;
	triangle: Uint32Array;
	flipped: Uint8Array;
}

export function booleanIndexed(a: IndexedMesh, b: IndexedMesh, operation: Operation, options?: CheckOptions): IndexedBooleanResult;
export function splitIndexed(a: IndexedMesh, b: IndexedMesh, options?: CheckOptions): { groups: Record<string, IndexedGroup>; report: Report };
export function curvesIndexed(a: IndexedMesh, b: IndexedMesh | null, options?: { withCoplanar?: boolean }): { polylines: Float64Array[]; closed: boolean[]; report: Report };
export function cutFill(design: IndexedMesh | TriangleSoup, topo: IndexedMesh | TriangleSoup): Report & { cut: number; fill: number; net: number; common_plan_area: number; lines: Float64Array[]; closed: boolean[] };
export function classifyPointsIndexed(mesh: IndexedMesh | TriangleSoup, points: Float64Array | Vertex[], options?: CheckOptions): { classes: Uint8Array; winding: Float64Array; report: Report };
export function classifyPoints(soup: TriangleSoup | IndexedMesh, points: Vertex[], options?: CheckOptions): Array<"inside" | "outside" | "on">;
export function resolveIndexed(mesh: IndexedMesh, options?: { rule?: "positive" | "nonzero" | "evenodd"; keepNonmanifold?: boolean }): IndexedResult & { parent: Uint32Array };
/** The upper or lower envelope of a folded open surface (terrain): single-valued, exact, faced up; `report` is `meshbool resolve --envelope SIDE --json`. */
export function envelopeIndexed(mesh: IndexedMesh, side?: "upper" | "lower"): IndexedResult & { parent: Uint32Array };
export function repairIndexed(mesh: IndexedMesh, config?: Record<string, any>): IndexedResult;
export function closeIndexed(mesh: IndexedMesh, mode: "cap" | "stitch" | "curtain" | "stitch+curtain", options?: { floorOffset?: number; maxGap?: number }): IndexedResult;
export function orientIndexed(mesh: IndexedMesh, facing?: "majority" | "z-up" | "outward"): IndexedResult;
export function meshInfo(mesh: IndexedMesh | TriangleSoup): Report;
export function readMesh(bytes: Uint8Array | ArrayBuffer, format?: string): IndexedMesh & { format: string };
export function writeMesh(mesh: IndexedMesh | TriangleSoup, format?: string): Uint8Array;
/** A format `readMesh` reads in this build. */
export interface ReadFormat {
	/** The name `readMesh` takes: "stl", "stl-ascii", "obj", "ply", ... */
	name: string;
	/** The file name extension, without its dot: "stl", "obj", ... */
	extension: string;
	/** As the messages name it: "binary STL", "OBJ", ... */
	label: string;
}
/** The formats `readMesh` reads in this build (the WebAssembly's readers, asked). */
export function readFormats(): ReadFormat[];

// ── generated shapes (`meshbool make`) ─────────────────────────────────────────────────

/** A point as three numbers [x, y, z]. */
export type Point3 = [number, number, number];

/** A generated shape: the mesh and `report` as `meshbool make --json` (shape, measures, bbox). */
export type MadeMesh = IndexedResult;

/** An axis-aligned box, 12 triangles, outward: `size` (one edge or three, default 1) about `center` (default origin), or `min` to `max`. */
export function makeCube(options?: { center?: Point3; size?: number | Point3 } | { min: Point3; max: Point3 }): MadeMesh;
/** A UV sphere, axis along z: `2 · segments · (rings − 1)` triangles, closed, outward. Defaults: centre origin, radius 1, 32 segments, 16 rings. */
export function makeSphere(options?: { center?: Point3; radius?: number; segments?: number; rings?: number }): MadeMesh;
/** A cylinder standing on `base` along +z: `4 · segments` triangles, closed, outward. Defaults: base origin, radius 1, height 1, 32 segments. */
export function makeCylinder(options?: { base?: Point3; radius?: number; height?: number; segments?: number }): MadeMesh;
/** A cone (apex; a frustum with `topRadius` > 0) standing on `base` along +z. Defaults as the cylinder's, `topRadius` 0. */
export function makeCone(options?: { base?: Point3; radius?: number; topRadius?: number; height?: number; segments?: number }): MadeMesh;
/** A flat rectangle facing +z, `nx` × `ny` cells of two triangles: an open surface. Defaults: centre origin, 1 × 1, one cell. */
export function makePlane(options?: { center?: Point3; width?: number; depth?: number; nx?: number; ny?: number }): MadeMesh;
/** A seeded terrain, an open height field facing +z spanning `relief` in height. Defaults: centre origin, size 1000 × 1000, 100 × 100 cells, relief 40, seed 1. */
export function makeTerrain(options?: { center?: Point3; size?: number | [number, number]; cells?: number | [number, number]; relief?: number; seed?: number }): MadeMesh;
/** An open benched pit shell facing up, rim at `center.z`. Defaults: centre [0, 0, 60], radius 220 × 160, depth 140, 5 benches, berm 8, 64 segments. */
export function makePit(options?: { center?: Point3; radius?: number | [number, number]; depth?: number; benches?: number; berm?: number; segments?: number }): MadeMesh;
/** Results of CSG nodes by key, kept between calls of `evaluateCsg` (in memory). */
export class CsgCache {
	constructor();
	/** Results held. */
	readonly size: number;
	/** Forgets every result. */
	clear(): void;
}
/** A transform step of a CSG node: scale, then rotate, then translate; or a matrix (16 numbers, row-major). */
export type CsgStep = { scale?: number | Point3; rotate?: [string, number] | [number, number, number, number]; translate?: Point3 } | { matrix: number[] };
/** A node of a CSG document (docs/csg.md). */
export type CsgNode = ({ op: "union" | "intersection" | "difference"; children: CsgNode[] } | { mesh: IndexedMesh | TriangleSoup } | { primitive: string; [parameter: string]: unknown }) & { name?: string; role?: "base" | "cutter"; transform?: CsgStep | CsgStep[] };
/** One node of an evaluation's report. */
export interface CsgNodeReport { path: string; name?: string; kind: string; role: "base" | "cutter"; key: string; source: "computed" | "memory" | "disk"; triangles?: number; volume?: number; closed?: boolean; seconds: number; notes: string[]; error?: string; [key: string]: unknown }
/** The report of `evaluateCsg` (the JSON of `meshbool csg --json`). */
export interface CsgReport { computed: number; cached: number; nodes: CsgNodeReport[]; failed: { path: string; error: string } | null; triangles?: number; volume?: number; closed?: boolean; seconds: number; [key: string]: unknown }
/** Evaluates a CSG document: the root's result; throws naming the node that failed (`err.report`). */
export function evaluateCsg(scene: { root: CsgNode }, options?: { cache?: CsgCache; force?: boolean; selfCheck?: boolean; resolve?: boolean; orient?: boolean; keepNonmanifold?: boolean; keepSeamPoints?: boolean; snap?: number }): IndexedMesh & { report: CsgReport };
export function soupToTyped(soup: TriangleSoup): IndexedMesh;
export function typedToSoup(mesh: IndexedMesh): TriangleSoup;
export function isIndexed(value: unknown): value is IndexedMesh;
export const version: string;
/** Which WebAssembly build this thread runs (chosen as the package loads): the single-threaded one, or the threaded one (rayon's pool on Web Workers) in a worker of a cross-origin isolated page. `threads`: the pool's size (1 for the single-threaded build); `reason`: why this build. */
export interface BuildInfo {
	build: "single" | "threads";
	threads: number;
	reason: string;
}
export function buildInfo(): BuildInfo;

// ── intersection ───────────────────────────────────────────────────────────────────────

export function intersectMeshPair(soupA: TriangleSoup, soupB: TriangleSoup, options?: { withCoplanar?: boolean }): Segment[];
export function intersectMeshPairTagged(soupA: TriangleSoup, soupB: TriangleSoup, options?: { withCoplanar?: boolean }): TaggedSegment[];
export function triTriIntersection(triA: Triangle, triB: Triangle): Segment | null;
export function triTriIntersectionDetailed(triA: Triangle, triB: Triangle): (Segment & { dA: [number, number, number]; dB: [number, number, number]; segLen: number }) | null;
export function chainSegments(segments: Segment[], threshold?: number): Vertex[][];
export function simplifyPolyline(points: Vertex[], spacing: number): Vertex[];
export type SpatialGrid = Record<string, number[]>;
export function buildSpatialGrid(tris: TriangleSoup, cellSize: number): SpatialGrid;
export function buildSpatialGridOnAxes(tris: TriangleSoup, cellSize: number, getA: (v: Vertex) => number, getB: (v: Vertex) => number): SpatialGrid;
export function queryGrid(grid: SpatialGrid, bb: AABB, cellSize: number): number[];
export function queryGridOnAxes(grid: SpatialGrid, a: number, b: number, cellSize: number): number[];
export function computeBBox(tris: TriangleSoup): AABB;
export function triBBox(tri: Triangle): AABB;
export function bboxOverlap(a: AABB, b: AABB): boolean;
export function estimateAvgEdge(tris: TriangleSoup): number;

// ── repair ─────────────────────────────────────────────────────────────────────────────

export interface RepairConfig {
	closeMode?: "none" | "weld" | "stitch";
	snapTolerance?: number;
	stitchTolerance?: number;
	removeDegenerate?: boolean;
	sliverRatio?: number;
	cleanCrossings?: boolean;
	removeOverlapping?: boolean;
	overlapTolerance?: number;
}

export interface BoundaryLoopResult {
	loops: Vertex[][];
	boundaryEdgeCount: number;
	overSharedEdgeCount: number;
}

export function repairMesh(soup: TriangleSoup, config?: RepairConfig, onProgress?: (fraction: number, message: string) => void): Promise<BooleanResult>;
export function deduplicateSeamVertices(tris: TriangleSoup, tolerance?: number): TriangleSoup;
export function resolveTJunctions(soup: TriangleSoup, tolerance?: number, passes?: number): TriangleSoup;
export function resolveTJunctionsHoleFree(soup: TriangleSoup, tolerance?: number, maxPasses?: number): TriangleSoup;
export function weldVertices(tris: TriangleSoup, tolerance: number): WeldedMesh;
export function soupToIndexed(tris: TriangleSoup, tolerance: number): WeldedMesh;
export function weldedToSoup(triangles: WeldedTriangle[]): TriangleSoup;
export function indexedToSoup(triangles: WeldedTriangle[]): TriangleSoup;
export function removeDegenerateTriangles(tris: TriangleSoup, minArea?: number, sliverRatio?: number): TriangleSoup;
export function extractBoundaryLoops(tris: TriangleSoup): BoundaryLoopResult;
export function triangulateLoop(loop: Vertex[]): TriangleSoup;
export function capBoundaryLoops(tris: TriangleSoup): TriangleSoup;
export function capBoundaryLoopsSequential(soup: TriangleSoup, snapTolerance: number, passes?: number): TriangleSoup;
export function stitchByProximity(tris: TriangleSoup, tolerance?: number): TriangleSoup;
export function cleanCrossingTriangles(tris: TriangleSoup): TriangleSoup;
export function removeOverlappingTriangles(tris: TriangleSoup, tolerance?: number): TriangleSoup;
export function cancelCoincidentFaces(soup: TriangleSoup, tolerance?: number): TriangleSoup;
export function forceCloseIndexedMesh(points: Vertex[], triangles: WeldedTriangle[]): WeldedMesh;
export function fillOpenEdgeLoops(soup: TriangleSoup, tolerance?: number): TriangleSoup;
export function weldBoundaryVertices(tris: TriangleSoup, tolerance: number): TriangleSoup;
export function buildCurtainAndCap(tris: TriangleSoup, floorOffset?: number): TriangleSoup;
export function generateClosingTriangles(tris: TriangleSoup, maxDist: number): TriangleSoup;
/** What `closeSolid` did. */
export interface CloseSolidDiagnostics {
	closed: boolean;
	openEdges: number;
	nonManifoldEdges: number;
	/** Triangles added as caps. */
	capTriangles: number;
	cappedLoops: number;
	/** Vertex counts of the loops larger than `maxCapLoopVerts`, left open. */
	skippedLargeLoops: number[];
	/** Loops left open. */
	openLoops: number;
	/** Vertex counts of every boundary loop found first. */
	loopSizes: number[];
	/** Signed volume of the result. */
	volume: number;
}
export function closeSolid(soup: TriangleSoup, options?: { snapTolerance?: number; maxCapLoopVerts?: number; maxPasses?: number }): { soup: TriangleSoup; diagnostics: CloseSolidDiagnostics };

/** What `orientSolid` did. */
export interface OrientDiagnostics {
	/** Edges of two triangles running the same way, before and after. */
	windingViolationsBefore: number;
	windingViolationsAfter: number;
	/** Triangles reversed to make the winding coherent. */
	flippedForCoherence: number;
	/** Closed components reversed to face outward. */
	componentsFlippedForDirection: number;
	components: number;
	closedComponents: number;
	openComponents: number;
	signedVolume: number;
}
export function orientSolid(soup: TriangleSoup, options?: { outward?: boolean; coherenceOnly?: boolean }): { soup: TriangleSoup; diagnostics: OrientDiagnostics };

/** Options of `bmsSelfResolve`. */
export interface SelfResolveOptions {
	/** Orient coherently and outward first (default true). */
	preOrient?: boolean;
	/** The fill rule (default "positive": winding number at least 1). */
	rule?: "positive" | "nonzero" | "evenodd";
	keepNonmanifold?: boolean;
}
/** What `bmsSelfResolve` found and did, beside the library's resolve report. */
export interface SelfResolveDiagnostics extends Report {
	coplanarPairs: number;
	crossingPairs: number;
	preOrient: boolean;
	preOrientFlips: number;
	preOrientSeamViolations: number;
	outputTris: number;
	orient?: OrientDiagnostics;
	/** Why the mesh could not be resolved (the input is returned). */
	error?: string;
}
export function bmsSelfResolve(soup: TriangleSoup, options?: SelfResolveOptions): { soup: TriangleSoup; changed: boolean; diagnostics: SelfResolveDiagnostics };
export function bmsSelfResolveIndexed(mesh: IndexedMesh, options?: SelfResolveOptions): IndexedMesh & { changed: boolean; diagnostics: SelfResolveDiagnostics };

// ── normals, measures, winding ─────────────────────────────────────────────────────────

export function triNormal(tri: Triangle): Vertex;
export function ensureZUpNormals(tris: TriangleSoup): TriangleSoup;
export function flipAllNormals(tris: TriangleSoup): TriangleSoup;
export function classifyNormalDirection(tris: TriangleSoup, isClosed: boolean, signedVolume?: number): string;
export function computeSignedVolume(tris: TriangleSoup): number;
export function computeProjectedArea(tris: TriangleSoup, plane?: "xy" | "yz" | "xz"): number;
export function compute3DSurfaceArea(tris: TriangleSoup): number;
export function solidAngleAt(px: number, py: number, pz: number, ax: number, ay: number, az: number, bx: number, by: number, bz: number, cx: number, cy: number, cz: number): number;
export function solidAngle(p: Vertex, tri: Triangle): number;
export function windingNumber(p: Vertex, soup: TriangleSoup): number;
export function windingNumberIndexed(px: number, py: number, pz: number, positions: ArrayLike<number>, index: ArrayLike<number>): number;
export function classifyPointMultiAxis(p: Vertex, tris: TriangleSoup, grids?: unknown): 1 | -1;

// ── utilities ──────────────────────────────────────────────────────────────────────────

export function dist3(a: Vertex, b: Vertex): number;
export function distSq3(a: Vertex, b: Vertex): number;
export function triangleArea3D(tri: Triangle): number;
export function computeBounds(points: Vertex[]): AABB;
export function cross(a: Vertex, b: Vertex): Vertex;
export function lerpVert(a: Vertex, b: Vertex, t: number): Vertex;
export function vKey(v: Vertex): string;
export function edgeKey(ka: string, kb: string): string;
export function countOpenEdges(tris: TriangleSoup): { openEdges: number; overShared: number; total: number };
export function findConnectedComponents(soup: TriangleSoup): TriangleSoup[];
export function findConnectedComponentsPooled(soup: TriangleSoup, options?: { tolerance?: number }): TriangleSoup[];

// ── BMS pipeline ───────────────────────────────────────────────────────────────────────

export interface MegaTriangle extends Triangle {
	mesh: "A" | "B";
	origIdx: number;
}

/** A vertex of a pool. */
export interface PoolVertex extends Vertex {
	id: number;
}

/** A pool of vertices (see createVertexPool). */
export interface VertexPool {
	tolerance: number;
	/** The pool's vertex at that position (within the tolerance), made when there is none; `triRef` is not used. */
	getOrCreate(x: number, y: number, z: number, triRef?: unknown): PoolVertex;
	find(x: number, y: number, z: number): PoolVertex | undefined;
	get(id: number): PoolVertex | undefined;
	getAll(): PoolVertex[];
	size(): number;
}

/** A pool of vertices: positions within `tolerance` (default 0: equal) are one vertex. */
export function createVertexPool(tolerance?: number): VertexPool;

/** A seam segment whose ends are pool vertices. */
export interface PoolSegment {
	p0: PoolVertex;
	p1: PoolVertex;
	idxA: number;
	idxB: number;
}

/** The result of `verifyBmsClassification`. */
export interface BmsVerification {
	ok: boolean;
	counts: { A: { inside: number; outside: number }; B: { inside: number; outside: number } };
	failures: Array<{ check: string; mesh: "A" | "B" | null; detail?: string; count?: number; polyline?: number }>;
}

/** Options of the BMS path. */
export interface BmsOptions extends BooleanOptions {
	/** "auto" (default), "hybrid" or "heffalump": names the reference path; sides are exact either way. */
	classifier?: "auto" | "hybrid" | "heffalump";
	/** Deprecated: `classifier: "heffalump"`. */
	forceHeffalump?: boolean;
	/** Report the outlines of coplanar overlaps as segments (default true). */
	coplanar?: boolean;
	/** The snap tolerance (default 0.001 × the mean edge; 0: the exact split). */
	tolerance?: number;
	/** Add `indexed` (indexGroups of the groups). */
	indexed?: boolean;
}

export interface BmsResult {
	groups: SoupGroups;
	segments: PoolSegment[];
	polylines: PoolVertex[][];
	rawPolylines: PoolVertex[][];
	meshEdgePolys: never[];
	componentWalks: never[];
	megaSoup: MegaTriangle[];
	pool: VertexPool;
	classifier: { A: string; B: string };
	verification: BmsVerification | null;
	splitReport: { lostSegments: number; segments: number; seamPoints: number; snap: Report | null };
	result?: BooleanResult | null;
	/** With the option `indexed: true`. */
	indexed?: IndexedGroups;
}

export function bmsBooleanOp(soupA: TriangleSoup, soupB: TriangleSoup, operation?: Operation | null, options?: BmsOptions): BmsResult;
export function bmsIntersect(soupA: TriangleSoup, soupB: TriangleSoup, options?: { coplanar?: boolean }): { segments: PoolSegment[]; crossedSetA: Record<number, PoolSegment[]>; crossedSetB: Record<number, PoolSegment[]>; pool: VertexPool; coplanarPairs: number };
export function bmsSplit(soupA: TriangleSoup, soupB: TriangleSoup, isect?: { pool: VertexPool } | null, options?: BooleanOptions): MegaTriangle[];
export function verifyBmsClassification(megaSoup: MegaTriangle[], sides: number[], segments: Array<{ p0: Vertex; p1: Vertex }>, polylines: Vertex[][], soupA: TriangleSoup, soupB: TriangleSoup, options?: { minBarrierViolations?: number }): BmsVerification;
// ── the reference's inner stages, with its names and shapes (stages.js) ──────────────

/** The reference's near-parallel gate, 1 − 1e-14 (meshbool's triangle tests are exact). */
export const NEAR_PARALLEL: number;
export function classifyByFloodFill(tris: TriangleSoup, crossedMap: Record<number, unknown> | null, otherTris: TriangleSoup, otherGrids?: unknown): Int8Array;
export function retriangulateWithSteinerPoints(tri: Triangle, segments: Array<{ p0: Vertex; p1: Vertex }>): TriangleSoup;
export function fanTriangulate(tri: Triangle, segments: Array<{ p0: Vertex; p1: Vertex }>): TriangleSoup;
export function bmsChain(segments: Array<{ p0: Vertex; p1: Vertex }>): Vertex[][];
export function bmsClosePolylines(polylines: Vertex[][], trisA: TriangleSoup, trisB: TriangleSoup, megaSoup?: MegaTriangle[], segments?: unknown[]): { closedPolylines: Vertex[][]; meshEdgePolys: { A: { segments: never[]; closed: boolean }; B: { segments: never[]; closed: boolean } } };
export function chainedOpenEdge(tris: TriangleSoup): Vertex[];
export function bmsClassify(megaSoup: MegaTriangle[], closedPolylines: unknown, segments: unknown, trisA: TriangleSoup, trisB: TriangleSoup, meshEdgePolys?: unknown): SoupGroups & { componentWalks: never[] };
export function coplanarOverlap(triA: Triangle, triB: Triangle, options?: object): { polygon: Vertex[]; area: number; areaRatio: number } | null;
export function emitCoplanarSegments(polygon: Vertex[], pool: VertexPool, refA: { mesh: string; triIdx: number }, refB: { mesh: string; triIdx: number }): PoolSegment[];
export function bmsSelfIntersect(soup: TriangleSoup, options?: object): { segments: PoolSegment[]; crossedSet: Record<number, PoolSegment[]>; pool: VertexPool; stats: { candidatePairs: number; coplanarPairs: number; crossingPairs: number; refinementSplits: number } };
export function bmsSelfArrange(soup: TriangleSoup, options?: object): { megaSoup: MegaTriangle[]; segments: PoolSegment[]; crossedSet: Record<number, PoolSegment[]>; pool: VertexPool; stats: { candidatePairs: number; coplanarPairs: number; crossingPairs: number; refinementSplits: number } };
export function buildEdgeSteinerMap(triCount: number, triOf: (t: number) => Triangle, keyOf: (t: number, corner: number) => string | number, segments: Array<{ p0: Vertex; p1: Vertex }>, tol: number): Record<number, Vertex[]>;
export function snapEndpointsToVertices(soup: TriangleSoup, segments: Array<{ p0: Vertex; p1: Vertex }>, snapTol: number): number;
export function weldTaggedSoup(soup: Array<Triangle & { mesh?: string; origIdx?: number }>, tol: number, seedVertices?: Vertex[]): { soup: Array<Triangle & { mesh?: string; origIdx?: number }>; repOf: (x: number, y: number, z: number) => Vertex | null };
export function conditionArrangement(soup: TriangleSoup, seamTol: number, maxPasses?: number): { soup: TriangleSoup; openBefore: number; openAfter: number; capsAdded: number; snaps: number };
export function snapCoincidentSheets(soup: TriangleSoup, tol: number): { soup: TriangleSoup; snappedVertices: number; coincidentPairs: number };
export function extractByWinding(subTris: TriangleSoup, windingFn: (x: number, y: number, z: number) => number, options?: { threshold?: number; offsetFactor?: number }): { kept: TriangleSoup; dropped: number; flipped: number; keptFlags: Uint8Array; flipFlags: Uint8Array };
export function extractByWindingPatches(subTris: TriangleSoup, barrierKeys: Record<string, boolean>, windingFn: (x: number, y: number, z: number) => number, options?: { threshold?: number; offsetFactor?: number; samplesPerPatch?: number }): { kept: TriangleSoup; patches: number; keptPatches: number; droppedPatches: number };
export function shouldUseHeffalump(soupA: TriangleSoup, soupB: TriangleSoup): boolean;
export function heffalumpClassify(megaSoup: MegaTriangle[], segments: unknown, soupA: TriangleSoup, soupB: TriangleSoup, options?: object): SoupGroups & { componentWalks: never[] };
export function extractByCellComplex(soup: TriangleSoup, windingFn?: ((x: number, y: number, z: number) => number) | null, options?: { threshold?: number }): { kept: TriangleSoup; diagnostics: { cells: number; propagationViolations: number; leakedFaceFraction: number; windingMax: number } };
export function reclassifyTriangles(groups: SoupGroups, mesh: "A" | "B", fromSide: "inside" | "outside", indices: number[]): number;
export function reclassifyAtPoint(groups: SoupGroups, x: number, y: number, z: number, tol?: number): { moved: boolean; mesh?: "A" | "B"; from?: string; to?: string };
export function reclassifyRegion(groups: SoupGroups, mesh: "A" | "B", fromSide: "inside" | "outside", seedIdx: number): number;

// ── verification, finishing, indexed groups (the reference's 0.6–0.7 exports) ─────────

export interface OutputCheck {
	check: string;
	ok: boolean;
	count: number;
	detail: string;
}

export interface VerifyOutputResult {
	ok: boolean;
	checks: OutputCheck[];
	stats: { triangles: number; vertices: number; openEdges: number; nonManifoldEdges: number; area: number; components: number; volume: number };
}

export interface CheckOptionsOfOutput {
	tolerance?: number;
	expectClosed?: boolean;
	minArea?: number;
}

export interface RepairAssessment {
	harmful: boolean;
	recommend: "keep" | "discard";
	benefits: string[];
	damage: string[];
	before: VerifyOutputResult;
	after: VerifyOutputResult;
	violationsBefore: number;
	violationsAfter: number;
	trisDelta: number;
	volumeDeltaPct: number;
}

export interface FinishStage {
	name: string;
	run: (soup: TriangleSoup, ctx: { tolerance: number; options: object }) => TriangleSoup;
}

export interface FinishMeshResult {
	soup: TriangleSoup;
	ok: boolean;
	before: VerifyOutputResult;
	after: VerifyOutputResult;
	applied: string[];
	skipped: Array<{ stage: string; reason: string; violations: string }>;
	stages: Array<{ stage: string; assessment: RepairAssessment }>;
}

export interface IndexedGroups {
	points: Vertex[];
	groups: { aInside: number[][]; aOutside: number[][]; bInside: number[][]; bOutside: number[][] };
}

export interface IndexedComponent {
	mesh: "A" | "B";
	side: "inside" | "outside";
	index: number;
	/** The component's own vertices; `triangles` index them. */
	points: Vertex[];
	triangles: number[][];
	/** The same triangles as indices into the shared `indexed.points`. */
	tris: number[][];
	triCount: number;
}

export interface BooleanAutoResult {
	soup: TriangleSoup;
	ok: boolean;
	operation: string;
	report: FinishMeshResult | null;
	verification: BmsVerification | null;
	classifier: { A: string; B: string } | null;
	boolean: BmsResult | null;
}

export function verifyOutput(soup: TriangleSoup, options?: CheckOptionsOfOutput): VerifyOutputResult;
export function violationCount(report: VerifyOutputResult): number;
export function assessRepair(before: TriangleSoup, after: TriangleSoup, options?: CheckOptionsOfOutput & { volumeTolPct?: number }): RepairAssessment;
export function describeAssessment(assessment: RepairAssessment): string;
export const DEFAULT_STAGES: readonly FinishStage[];
export function finishMesh(soup: TriangleSoup, options?: CheckOptionsOfOutput & { volumeTolPct?: number; stages?: FinishStage[]; force?: boolean }): FinishMeshResult;
export function booleanAuto(soupA: TriangleSoup | null, soupB: TriangleSoup | null, operation: Operation, options?: BmsOptions & CheckOptionsOfOutput & { quality?: "strict" | "raw"; volumeTolPct?: number }): BooleanAutoResult | null;
export function indexGroups(groups: SoupGroups, tolerance?: number): IndexedGroups;
export function indexGroupsToTypedArrays(indexed: IndexedGroups): { positions: Float64Array; index: { aInside: Uint32Array; aOutside: Uint32Array; bInside: Uint32Array; bOutside: Uint32Array } };
export function connectedComponentsIndexed(tris: number[][]): number[][][];
export function mergeSmallIndexedComponents(comps: number[][][], threshold: number): number[][][];
export function decomposeIndexedGroups(indexed: IndexedGroups, smallThreshold?: number): IndexedComponent[];
export function dedupCoincidentTriangles(tris: TriangleSoup, options?: { minAreaRatio?: number }): { soup: TriangleSoup; duplicateGroups: number; duplicatesRemoved: number; clusters: number; clusterTrisIn: number; clusterTrisOut: number };
