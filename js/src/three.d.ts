// Type declarations of meshbool/three, the three.js adapter (src/three.js).
import type { BufferGeometry, ColorRepresentation, Mesh, Object3D } from "three";
import type { IndexedMesh, RepairConfig, TaggedSegment, TriangleSoup } from "./index.js";

export { boolean, repairMesh as repair, intersectMeshPairTagged as intersect } from "./index.js";

/** Look of the meshes the adapter builds. */
export interface MeshOptions {
	/** Material colour (default 0x4488ff). */
	color?: ColorRepresentation;
	/** Draw both faces (default true). */
	doubleSide?: boolean;
	/** Draw edges only (default false). */
	wireframe?: boolean;
	/**
	 * Store positions relative to the soup's centroid (computed in double precision) and
	 * put the centroid on the mesh's `position` (default true): keeps UTM-scale
	 * coordinates exact to well under a millimetre in single precision.
	 */
	recenter?: boolean;
}

/** Options of `booleanFromMeshes`: the engine and its quality, and the material. */
export interface BooleanMeshOptions extends MeshOptions {
	/** "bms" (default): the core's `booleanAuto`; "classic": the core's `boolean`. */
	engine?: "bms" | "classic";
	/** `booleanAuto`'s quality: "strict" (default, finished) or "raw". */
	quality?: "strict" | "raw";
	/** `booleanAuto`'s tolerance. */
	tolerance?: number;
}

/** The operations of the adapter's booleans. */
export type BooleanOperation =
	| "union"
	| "intersect"
	| "subtract"
	| "intersection"
	| "difference"
	| "reverse-difference"
	| "reverseDifference";

/** The operand options of booleanIndexed, used by booleanGeometry. */
export interface BooleanGeometryOptions {
	/** Compute even when an operand check fails (default false). */
	force?: boolean;
	/** Check the operands for self-intersections (default true). */
	selfCheck?: boolean;
	/** Resolve self-overlapping operands (default true). */
	resolve?: boolean;
	/** Make the operands' winding consistent (default true). */
	orient?: boolean;
	/** Keep edges shared by more than two triangles of the result (default false). */
	keepNonmanifold?: boolean;
}

/** The library's report of a boolean (the fields the adapter's users read most, and the rest). */
export interface BooleanGeometryReport {
	triangles: number;
	vertices: number;
	closed: boolean;
	volume: number;
	area: number;
	boundary_edges: number;
	non_manifold_edges: number;
	[key: string]: unknown;
}

/** A BufferGeometry made by booleanGeometry. */
export type BooleanGeometry = BufferGeometry & { userData: { report: BooleanGeometryReport } };

/**
 * The triangles of every THREE.Mesh under `object3d` (world matrices applied) as a soup.
 */
export function meshToSoup(object3d: Object3D): TriangleSoup;

/**
 * A THREE.Mesh of a soup: non-indexed BufferGeometry with vertex normals, MeshPhongMaterial.
 */
export function soupToMesh(soup: TriangleSoup, options?: MeshOptions): Mesh<BufferGeometry>;

/**
 * The boolean of two THREE objects (world coordinates) through `booleanAuto` (or, with
 * `engine: "classic"`, `boolean`); null when the result is empty.
 */
export function booleanFromMeshes(a: Object3D, b: Object3D, op: BooleanOperation, options?: BooleanMeshOptions): Mesh<BufferGeometry> | null;

/**
 * The intersection segments of two THREE objects (world coordinates), tagged with the
 * crossing triangles.
 */
export function intersectFromMeshes(a: Object3D, b: Object3D): TaggedSegment[];

/**
 * The repair pipeline on a THREE object; resolves to a new THREE.Mesh.
 */
export function repairFromMesh(
	mesh: Object3D,
	config?: RepairConfig,
	onProgress?: (fraction: number, message: string) => void,
	meshOptions?: MeshOptions,
): Promise<Mesh<BufferGeometry>>;

/**
 * The triangles of every THREE.Mesh under an Object3D (world matrices applied), or of a
 * BufferGeometry as it is, as typed arrays (no object per vertex).
 */
export function geometryToIndexed(source: Object3D | BufferGeometry): IndexedMesh;

/**
 * A BufferGeometry (Float32 positions, Uint32 index, vertex normals) of a typed-array mesh.
 */
export function indexedToGeometry(mesh: { positions: ArrayLike<number>; index: ArrayLike<number> }): BufferGeometry;

/**
 * The boolean of two THREE objects or geometries on the typed-array fast path; the
 * library's report in `userData.report`; null when the result is empty.
 */
export function booleanGeometry(
	a: Object3D | BufferGeometry,
	b: Object3D | BufferGeometry,
	op: BooleanOperation,
	options?: BooleanGeometryOptions,
): BooleanGeometry | null;

/**
 * Evaluates a THREE group as a CSG tree: `userData.csg = {op}` on the group and on nested
 * groups, `userData.csg = {role: "cutter"}` on children subtracted in a difference, every
 * object's local transform applied, the root's world transform placing the result. A new
 * Mesh (recentred: the offset on its position), its geometry's `userData.report` the
 * evaluation's report; null when the result is empty.
 */
export function csgGroup(
	group: Object3D,
	options?: { cache?: import("./index.js").CsgCache; recenter?: boolean; color?: number | string; doubleSide?: boolean; wireframe?: boolean; force?: boolean; selfCheck?: boolean; snap?: number },
): Mesh | null;
