// The WebAssembly module, instantiated when this module is first imported (top-level
// await: every call of the package is synchronous afterwards), and the one door through
// which the package calls it.
//
// In Node.js the .wasm file is read from beside this package; in a browser (or a bundler
// that keeps `new URL(..., import.meta.url)` assets) it is fetched.
import * as wasm from "../wasm/meshbool_wasm.js";

const url = new URL("../wasm/meshbool_wasm_bg.wasm", import.meta.url);
const inNode = typeof process !== "undefined" && process.versions != null && process.versions.node != null;

let bytes;
if (inNode && url.protocol === "file:") {
	const fs = await import("node:fs");
	bytes = fs.readFileSync(url);
} else {
	const response = await fetch(url);
	if (!response.ok) {
		throw new Error(`meshbool: cannot load its WebAssembly module from ${url}: HTTP ${response.status}`);
	}
	bytes = await response.arrayBuffer();
}
wasm.initSync({ module: bytes });

/**
 * Calls the WebAssembly function `name`. The library's errors arrive as `Error`s with its
 * message; a panic (a bug in meshbool) traps the WebAssembly call, and is rethrown as an
 * `Error` that carries the panic's message instead of "unreachable".
 */
export function call(name, ...args) {
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

/** The version of the Rust library inside. */
export const nativeVersion = wasm.version();

/**
 * Sets the function called with each stage's name as the long calls (boolean, split,
 * resolve) begin it, or clears it with `null`.
 */
export function onStage(f) {
	wasm.setProgress(typeof f === "function" ? f : null);
}
