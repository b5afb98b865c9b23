// meshbool/threads: how many threads the package's WebAssembly may use, chosen before the
// package loads (the build and its pool are fixed when the WebAssembly is instantiated,
// on the first import of "meshbool" in a thread).
//
//   import { setThreads } from "meshbool/threads";
//   setThreads(4);                          // or 1: the single-threaded build
//   const mb = await import("meshbool");    // a dynamic import: after the call above
//
// meshbool/async passes `createWorker({threads})` this way into its worker.

let requested = null;

/**
 * Asks for `n` threads (a whole number ≥ 1; `null` for the default) in the builds loaded
 * after this call on this thread: more than 1 loads the threaded build where it can run
 * (see `buildInfo()`), 1 the single-threaded one. Throws on anything else, and when the
 * package has already loaded on this thread with another choice.
 */
export function setThreads(n) {
	checkThreads(n);
	if (locked && loaded !== n) {
		throw new Error("meshbool: the package is already loaded on this thread: call setThreads before its first import");
	}
	requested = n;
}

/** Throws unless `n` is a number of threads setThreads takes (also for async.js). */
export function checkThreads(n) {
	if (n !== null && !(Number.isInteger(n) && n >= 1 && n <= 1024)) {
		throw new Error(`meshbool: threads must be a whole number from 1 to 1024 or null, got ${String(n)}`);
	}
}

/** The number asked for with `setThreads`, or null. */
export function requestedThreads() {
	return requested;
}

let locked = false;
let loaded = null;

/** Marks the choice as taken (by native.js, as it loads). */
export function lockThreads() {
	locked = true;
	loaded = requested;
}
