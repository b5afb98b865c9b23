// The Web Worker (or Node.js worker thread) of the async API (async.js): runs the
// package's functions off the calling thread. Each request `{id, name, args}` calls the
// export `name` of index.js and answers `{id, ok: true, value, report}` (typed arrays
// transferred, not copied) or `{id, ok: false, message}`; `{id, progress: stage}` is
// posted as each stage of a long call begins.
import * as mb from "./index.js";
import { onStage } from "./native.js";
import { buffersOf } from "./transfer.js";

const inNode = typeof process !== "undefined" && process.versions != null && process.versions.node != null && typeof self === "undefined";
const port = inNode ? (await import("node:worker_threads")).parentPort : self;

function post(message, transfer) {
	port.postMessage(message, transfer || []);
}

/**
 * A result as it can cross to the other thread: a vertex pool (it has methods) as its
 * tolerance and vertices, rebuilt by async.js.
 */
function cloneable(value) {
	if (value != null && typeof value === "object" && value.pool && typeof value.pool.getAll === "function") {
		return { ...value, pool: { poolVertices: value.pool.getAll(), tolerance: value.pool.tolerance } };
	}
	return value;
}

async function handle({ id, name, args }) {
	const f = mb[name];
	if (typeof f !== "function") {
		post({ id, ok: false, message: `meshbool: no function ${JSON.stringify(name)} in the package` });
		return;
	}
	onStage((stage) => post({ id, progress: stage }));
	try {
		const value = await f(...(args || []));
		const report = value != null && typeof value === "object" ? value.report : undefined;
		const out = cloneable(value);
		post({ id, ok: true, value: out, report }, [...buffersOf(out)]);
	} catch (e) {
		post({ id, ok: false, message: e instanceof Error ? e.message : String(e) });
	} finally {
		onStage(null);
	}
}

if (inNode) port.on("message", handle);
else port.onmessage = (e) => handle(e.data);
post({ ready: true, version: mb.version });
