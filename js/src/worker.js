// The Web Worker (or Node.js worker thread) of the async API (async.js): runs the
// package's functions off the calling thread. Each request `{id, name, args}` calls the
// export `name` of index.js and answers `{id, ok: true, value, report}` (typed arrays
// transferred, not copied) or `{id, ok: false, message}`; `{id, progress: stage}` is
// posted as each stage of a long call begins (by the threaded build, whose calls run on
// its pool while this thread waits, to the BroadcastChannel the request names, which
// async.js listens to; a panic on the pool's threads is posted there too).
//
// `?threads=N` on this script's URL (async.js's `createWorker({threads})`) is passed to
// setThreads before the package loads.
import { setThreads } from "./threads.js";
import { buffersOf } from "./transfer.js";

const asked = new URL(import.meta.url).searchParams.get("threads");
if (asked !== null) setThreads(Number(asked));
const mb = await import("./index.js");
const { call, onStage, stageChannel } = await import("./native.js");
const threaded = mb.buildInfo().build === "threads";

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

async function handle({ id, name, args, channel }) {
	// The package's exports; the WebAssembly's hidden test hooks (`__...`) too.
	const f = mb[name] ?? (name.startsWith("__") ? (...a) => call(name, ...a) : undefined);
	if (typeof f !== "function") {
		post({ id, ok: false, message: `meshbool: no function ${JSON.stringify(name)} in the package` });
		return;
	}
	if (threaded) stageChannel(channel || null);
	else onStage((stage) => post({ id, progress: stage }));
	try {
		const value = await f(...(args || []));
		const report = value != null && typeof value === "object" ? value.report : undefined;
		const out = cloneable(value);
		post({ id, ok: true, value: out, report }, [...buffersOf(out)]);
	} catch (e) {
		post({ id, ok: false, message: e instanceof Error ? e.message : String(e) });
	} finally {
		if (threaded) stageChannel(null);
		else onStage(null);
	}
}

if (inNode) port.on("message", handle);
else port.onmessage = (e) => handle(e.data);
post({ ready: true, version: mb.version, build: mb.buildInfo() });
