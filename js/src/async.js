// meshbool/async: the package's functions run in a Web Worker (in Node.js, a worker
// thread), so that a long boolean never blocks the page. Every call returns a Promise;
// typed arrays cross without copies (the results' always; the arguments' with
// `transfer: true`); each call can report the stages of the computation as they begin
// and be cancelled with an AbortSignal, which stops the worker at once (a fresh one
// starts for the next call).
//
//   import { createWorker } from "meshbool/async";
//   const worker = createWorker();
//   const controller = new AbortController();
//   const out = await worker.booleanIndexed(a, b, "union", {}, {
//       signal: controller.signal,
//       onProgress: (stage) => console.log(stage),  // "check", "intersect", "arrange", ...
//   });
//
// This module does not load the WebAssembly on the calling thread: only the worker does.
// In a cross-origin isolated page the worker runs the threaded build where it is
// installed (its pool: `threads`, default navigator.hardwareConcurrency; `buildInfo()`
// says which build runs); its stages, and a panic on its pool, arrive here through a
// BroadcastChannel of the call's own, since the worker's thread waits for the pool.

import { checkThreads } from "./threads.js";
import { buffersOf } from "./transfer.js";

const inNode = typeof process !== "undefined" && process.versions != null && process.versions.node != null && typeof window === "undefined";

/** The error a cancelled call rejects with: name "AbortError", as fetch's. */
function abortError(signal) {
	if (signal && signal.reason instanceof Error) return signal.reason;
	const message = "meshbool: the call was cancelled";
	if (typeof DOMException === "function") return new DOMException(message, "AbortError");
	const e = new Error(message);
	e.name = "AbortError";
	return e;
}

/** A vertex pool rebuilt from what crossed (see worker.js): `get`, `getAll`, `size`, `find`. */
function revivePool(p) {
	const all = p.poolVertices;
	const at = new Map(all.map((v) => [`${v.x},${v.y},${v.z}`, v]));
	return {
		tolerance: p.tolerance,
		get: (id) => all[id],
		getAll: () => all.slice(),
		size: () => all.length,
		find: (x, y, z) => at.get(`${x},${y},${z}`),
	};
}

function revive(value, report) {
	if (value != null && typeof value === "object") {
		if (value.pool && Array.isArray(value.pool.poolVertices)) value.pool = revivePool(value.pool);
		if (report !== undefined && !Object.prototype.hasOwnProperty.call(value, "report")) {
			Object.defineProperty(value, "report", { value: report, enumerable: false });
		}
	}
	return value;
}

/**
 * A worker running the package: `run(name, args, control)` calls the export `name` with
 * `args` there; the named methods below are the same for the long calls. `control`:
 * `{signal, onProgress(stage), transfer}` (`transfer: true` hands the arguments' typed
 * arrays to the worker instead of copying them: they are empty here afterwards).
 * Calls run one after another in the order made. `terminate()` stops the worker.
 */
export class MeshboolWorker {
	/**
	 * `options.url`: the worker script (default: worker.js beside this module);
	 * `options.threads`: the size of the threaded build's pool in the worker (1: the
	 * single-threaded build; default: navigator.hardwareConcurrency where the page is
	 * cross-origin isolated; browsers only).
	 */
	constructor(options) {
		const o = options || {};
		this.url = o.url || new URL("./worker.js", import.meta.url);
		if (o.threads !== undefined) checkThreads(o.threads);
		if (o.threads != null && !inNode) {
			this.url = new URL(this.url, import.meta.url);
			this.url.searchParams.set("threads", String(o.threads));
		}
		this.channelPrefix = `meshbool-${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;
		this.build = null;
		this.worker = null;
		this.ready = null;
		this.pending = new Map();
		this.nextId = 1;
	}

	/** Starts the worker when none runs; resolves once its WebAssembly is loaded. */
	start() {
		if (this.ready) return this.ready;
		this.ready = (async () => {
			let worker;
			if (inNode) {
				const { Worker } = await import("node:worker_threads");
				worker = new Worker(this.url);
			} else {
				worker = new Worker(this.url, { type: "module" });
			}
			this.worker = worker;
			await new Promise((resolve, reject) => {
				const onMessage = (data) => this.receive(data, resolve);
				const onError = (e) => {
					const err = e instanceof Error ? e : new Error(`meshbool: the worker failed: ${e.message || e}`);
					this.failAll(err);
					reject(err);
				};
				if (inNode) {
					worker.on("message", onMessage);
					worker.on("error", onError);
				} else {
					worker.onmessage = (e) => onMessage(e.data);
					worker.onerror = (e) => {
						e.preventDefault();
						onError(e);
					};
				}
			});
		})();
		return this.ready;
	}

	receive(data, ready) {
		if (data.ready) {
			this.version = data.version;
			this.build = data.build;
			ready();
			return;
		}
		const call = this.pending.get(data.id);
		if (!call) return;
		if (data.progress !== undefined) {
			if (call.onProgress) {
				try {
					call.onProgress(data.progress);
				} catch {
					// A throwing progress callback does not stop the call.
				}
			}
			return;
		}
		this.pending.delete(data.id);
		call.cleanup();
		if (data.ok) call.resolve(revive(data.value, data.report));
		else call.reject(new Error(data.message));
	}

	failAll(err) {
		for (const call of this.pending.values()) {
			call.cleanup();
			call.reject(err);
		}
		this.pending.clear();
	}

	/**
	 * Which build the worker runs: `{build: "single" | "threads", threads, reason}`, as
	 * `buildInfo()` of the package there (starts the worker).
	 */
	async buildInfo() {
		while (!this.worker) await this.start();
		return { ...this.build };
	}

	/** Calls the package's export `name` with `args` in the worker (see the class). */
	async run(name, args, control) {
		const c = control || {};
		if (c.signal && c.signal.aborted) throw abortError(c.signal);
		while (!this.worker) await this.start();
		if (c.signal && c.signal.aborted) throw abortError(c.signal);
		const id = this.nextId++;
		return new Promise((resolve, reject) => {
			const onAbort = () => this.cancel(abortError(c.signal));
			// The threaded build's stages and pool panics come through a channel of this call's.
			const channel = this.build && this.build.build === "threads" ? `${this.channelPrefix}-${id}` : null;
			const listener = channel ? new BroadcastChannel(channel) : null;
			const cleanup = () => {
				if (c.signal) c.signal.removeEventListener("abort", onAbort);
				if (listener) listener.close();
			};
			if (listener) {
				listener.onmessage = ({ data }) => {
					if (data.stage !== undefined) this.receive({ id, progress: data.stage });
					else if (data.panic !== undefined) {
						// The pool's thread has stopped and the call would wait for ever.
						this.cancel(new Error(`meshbool: internal error in ${name} (please report it): ${data.panic}`));
					}
				};
			}
			this.pending.set(id, { resolve, reject, cleanup, onProgress: c.onProgress });
			if (c.signal) c.signal.addEventListener("abort", onAbort, { once: true });
			const transfer = c.transfer ? [...buffersOf(args)] : [];
			this.worker.postMessage({ id, name, args, channel }, transfer);
		});
	}

	/**
	 * Stops the running call (and those queued behind it): the worker is terminated, each
	 * pending call rejects with `reason` (an AbortError by default); the next call starts
	 * a fresh worker.
	 */
	cancel(reason) {
		const worker = this.worker;
		this.worker = null;
		this.ready = null;
		this.failAll(reason || abortError());
		if (worker) worker.terminate();
	}

	/** Stops the worker; pending calls reject. */
	terminate() {
		this.cancel(new Error("meshbool: the worker was terminated"));
	}

	/** `booleanIndexed` in the worker. */
	booleanIndexed(a, b, op, options, control) {
		return this.run("booleanIndexed", [a, b, op, options], control);
	}

	/** `splitIndexed` in the worker. */
	splitIndexed(a, b, options, control) {
		return this.run("splitIndexed", [a, b, options], control);
	}

	/** `curvesIndexed` in the worker. */
	curvesIndexed(a, b, options, control) {
		return this.run("curvesIndexed", [a, b, options], control);
	}

	/** `resolveIndexed` in the worker. */
	resolveIndexed(m, options, control) {
		return this.run("resolveIndexed", [m, options], control);
	}

	/** `boolean` (soups) in the worker. */
	boolean(a, b, op, options, control) {
		return this.run("boolean", [a, b, op, options], control);
	}

	/** `booleanAuto` in the worker. */
	booleanAuto(a, b, op, options, control) {
		return this.run("booleanAuto", [a, b, op, options], control);
	}

	/** `bmsBooleanOp` in the worker. */
	bmsBooleanOp(a, b, op, options, control) {
		return this.run("bmsBooleanOp", [a, b, op, options], control);
	}

	/** `splitMeshPair` in the worker. */
	splitMeshPair(a, b, options, control) {
		return this.run("splitMeshPair", [a, b, options], control);
	}

	/** `repairMesh` in the worker (its `onProgress` argument is `control.onProgress`). */
	repairMesh(soup, config, control) {
		return this.run("repairMesh", [soup, config], control);
	}
}

/** A worker running the package (see MeshboolWorker). */
export function createWorker(options) {
	return new MeshboolWorker(options);
}
