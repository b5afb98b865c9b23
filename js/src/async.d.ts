// Types of meshbool/async: the package's functions in a Web Worker (Node.js: a worker
// thread), as Promises, with progress and cancellation.

import type { BuildInfo, IndexedMesh, Operation, TriangleSoup } from "./index.js";

/** How one call runs. */
export interface CallControl {
	/** Cancels the call: the worker is stopped, the Promise rejects with an AbortError. */
	signal?: AbortSignal;
	/** Called with each stage's name as it begins ("check", "intersect", "arrange", "classify", "merge", "snap", ...). */
	onProgress?: (stage: string) => void;
	/** Hand the arguments' typed arrays to the worker instead of copying them (they are empty here afterwards). */
	transfer?: boolean;
}

/** A worker running the package. Calls run one after another in the order made. */
export class MeshboolWorker {
	/** `threads`: the threaded build's pool size in the worker (1: the single-threaded build; default navigator.hardwareConcurrency where the page is cross-origin isolated). */
	constructor(options?: { url?: string | URL; threads?: number });
	/** The package version in the worker, once started. */
	version?: string;
	/** Which build the worker runs, as `buildInfo()` there (starts the worker). */
	buildInfo(): Promise<BuildInfo>;
	/** Starts the worker (calls start it when needed); resolves once its WebAssembly is loaded. */
	start(): Promise<void>;
	/** Calls the package's export `name` with `args` in the worker. */
	run<T = unknown>(name: string, args: unknown[], control?: CallControl): Promise<T>;
	/** Stops the running call and those queued: each rejects with `reason` (an AbortError by default). */
	cancel(reason?: unknown): void;
	/** Stops the worker; pending calls reject. */
	terminate(): void;
	booleanIndexed(a: IndexedMesh, b: IndexedMesh, op: Operation, options?: object, control?: CallControl): Promise<IndexedMesh & { source: Uint8Array; triangle: Uint32Array; flipped: Uint8Array; report: Record<string, unknown> }>;
	splitIndexed(a: IndexedMesh, b: IndexedMesh, options?: object, control?: CallControl): Promise<{ groups: Record<string, IndexedMesh>; report: Record<string, unknown> }>;
	curvesIndexed(a: IndexedMesh, b: IndexedMesh | null, options?: object, control?: CallControl): Promise<{ polylines: Float64Array[]; closed: boolean[]; report: Record<string, unknown> }>;
	resolveIndexed(m: IndexedMesh, options?: object, control?: CallControl): Promise<IndexedMesh & { parent: Uint32Array; report: Record<string, unknown> }>;
	boolean(a: TriangleSoup, b: TriangleSoup, op: Operation, options?: object, control?: CallControl): Promise<unknown>;
	booleanAuto(a: TriangleSoup, b: TriangleSoup, op: Operation, options?: object, control?: CallControl): Promise<unknown>;
	bmsBooleanOp(a: TriangleSoup, b: TriangleSoup, op?: Operation | null, options?: object, control?: CallControl): Promise<unknown>;
	splitMeshPair(a: TriangleSoup, b: TriangleSoup, options?: object, control?: CallControl): Promise<unknown>;
	repairMesh(soup: TriangleSoup, config?: object, control?: CallControl): Promise<unknown>;
}

/** A worker running the package. */
export function createWorker(options?: { url?: string | URL; threads?: number }): MeshboolWorker;
