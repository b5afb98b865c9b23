// What crosses between the calling thread and the worker of meshbool/async without a
// copy: the ArrayBuffers of the typed arrays in a value. No WebAssembly here: async.js
// imports it on the calling thread.

/** The ArrayBuffers of the typed arrays in `value` (up to three levels of objects and arrays deep). */
export function buffersOf(value, out = new Set(), depth = 0) {
	if (value == null || typeof value !== "object" || depth > 3) return out;
	if (ArrayBuffer.isView(value)) {
		out.add(value.buffer);
		return out;
	}
	for (const v of Array.isArray(value) ? value : Object.values(value)) buffersOf(v, out, depth + 1);
	return out;
}
