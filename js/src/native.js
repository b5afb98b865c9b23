// The WebAssembly module, instantiated when this module is first imported (top-level
// await: every call of the package is synchronous afterwards), and the one door through
// which the package calls it.
//
// Two builds: the single-threaded one (wasm/), and, where it is installed (npm run
// build:threads) and the thread can run it, the threaded one (wasm-threads/: rayon's pool
// on Web Workers). The threaded build is picked in a Web Worker of a cross-origin
// isolated page (crossOriginIsolated, so SharedArrayBuffer), with
// navigator.hardwareConcurrency threads unless setThreads (threads.js) asked for another
// number; elsewhere, and on 1 thread, the single-threaded one. Not on a page's main
// thread by default: a call there would wait for the pool's threads by spinning (a
// browser's main thread may not block), and the page is frozen during a long call
// whatever the build; meshbool/async moves the call into a worker, where the pool works
// while the page stays free. setThreads(n > 1) before the import picks it there too.
// Node.js: the single-threaded build (wasm-bindgen-rayon's workers are the browser's).
//
// In Node.js the .wasm file is read from beside this package; in a browser (or a bundler
// that keeps `new URL(..., import.meta.url)` assets) it is fetched.
import * as single from "../wasm/meshbool_wasm.js";
import { lockThreads, requestedThreads } from "./threads.js";

const inNode = typeof process !== "undefined" && process.versions != null && process.versions.node != null;
const inWorker = typeof WorkerGlobalScope === "function" && globalThis instanceof WorkerGlobalScope;
const isolated = !inNode && globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === "function";
const cores = (globalThis.navigator && globalThis.navigator.hardwareConcurrency) || 1;

/** Fetches (or, in Node.js, reads) a file beside this package. */
async function bytesOf(url) {
	if (inNode && url.protocol === "file:") {
		const fs = await import("node:fs");
		return fs.readFileSync(url);
	}
	const response = await fetch(url);
	if (!response.ok) {
		throw new Error(`meshbool: cannot load its WebAssembly module from ${url}: HTTP ${response.status}`);
	}
	return response.arrayBuffer();
}

/**
 * The threaded build with a pool of `n` threads, or a string saying why not (its glue
 * absent: not built). Imported by a URL that bundlers leave alone: its files are not part
 * of a bundle (copy wasm-threads/ beside the package's src/ to serve them).
 */
async function threaded(n) {
	const glue = new URL("../wasm-threads/meshbool_wasm.js", import.meta.url);
	let api;
	try {
		api = await import(/* @vite-ignore */ /* webpackIgnore: true */ glue.href);
	} catch (e) {
		return `the threaded build is not installed (npm run build:threads): ${e.message}`;
	}
	try {
		await api.default({ module_or_path: new URL("../wasm-threads/meshbool_wasm_bg.wasm", import.meta.url) });
		await api.initThreadPool(n);
	} catch (e) {
		// A shared memory of 4 GiB that cannot be reserved (a 32-bit browser), a worker
		// that may not start workers, ...
		return `the threaded build did not start: ${e.message}`;
	}
	return api;
}

/** The build chosen for this thread, its pool's size, and why. */
async function load() {
	const asked = requestedThreads();
	lockThreads();
	const n = asked ?? (inWorker ? cores : 1);
	let why;
	if (inNode) why = "Node.js";
	else if (n <= 1) why = asked === 1 ? "setThreads(1)" : inWorker ? "one core (navigator.hardwareConcurrency)" : "a page's main thread (meshbool/async runs the calls in a worker; setThreads(n) before the import picks the threads here)";
	else if (!isolated) why = "the page is not cross-origin isolated (no SharedArrayBuffer)";
	else if (typeof Worker !== "function") why = "no Worker constructor on this thread";
	else {
		const api = await threaded(n);
		if (typeof api !== "string") return { api, info: { build: "threads", threads: n, reason: asked ? `setThreads(${n})` : "navigator.hardwareConcurrency" } };
		why = api;
	}
	single.initSync({ module: await bytesOf(new URL("../wasm/meshbool_wasm_bg.wasm", import.meta.url)) });
	return { api: single, info: { build: "single", threads: 1, reason: why } };
}

const { api: wasm, info } = await load();

/**
 * Which WebAssembly build this thread runs: `{build: "single" | "threads", threads,
 * reason}` (`threads`: the pool's size, 1 for the single-threaded build; `reason`: why
 * this one).
 */
export function buildInfo() {
	return { ...info };
}

/**
 * Calls the WebAssembly function `name`. The library's errors arrive as `Error`s with its
 * message; a panic (a bug in meshbool) traps the WebAssembly call, and is rethrown as an
 * `Error` that carries the panic's message instead of "unreachable".
 */
export function call(name, ...args) {
	if (typeof wasm[name] !== "function") throw new Error(`meshbool: no function ${name} in the ${info.build === "threads" ? "threaded" : "single-threaded"} build`);
	try {
		return wasm[name](...args);
	} catch (e) {
		if (e instanceof WebAssembly.RuntimeError) {
			let message = null;
			try {
				message = wasm.lastPanic();
			} catch {
				message = null;
			}
			const err = new Error(`meshbool: internal error in ${name} (please report it): ${message ?? e.message}`);
			err.cause = e;
			throw err;
		}
		if (e instanceof Error) {
			throw e;
		}
		throw new Error(String(e));
	}
}

/** A new instance of the WebAssembly build's class `name` (a CSG cache). */
export function construct(name, ...args) {
	return new wasm[name](...args);
}

/** The version of the Rust library inside. */
export const nativeVersion = wasm.version();

/**
 * Sets the function called with each stage's name as the long calls (boolean, split,
 * resolve) begin it, or clears it with `null`.
 */
export function onStage(f) {
	wasm.setProgress(typeof f === "function" ? f : null);
}

/**
 * The threaded build only: sets (or clears, with `null`) the name of the BroadcastChannel
 * to which the long calls post `{stage}` as they begin each stage and `{panic}` when one of
 * the pool's threads panics (from whichever thread; this one is waiting for the call).
 */
export function stageChannel(name) {
	wasm.setProgressChannel(name);
}
