// meshbool/async: the package's calls in a worker thread give the same answers as on the
// calling thread, report their stages, and stop when cancelled.
import { test } from "node:test";
import assert from "node:assert/strict";
import { createWorker } from "../src/async.js";
import { booleanIndexed, makeSphere, meshInfo } from "../src/index.js";

/** A UV sphere of radius 1 centred at (cx, 0, 0): 2n meridians, n bands, 4n(n − 1) triangles, closed. */
function sphere(n, cx) {
	const { positions, index } = makeSphere({ center: [cx, 0, 0], segments: 2 * n, rings: n });
	return { positions, index };
}

test("a boolean in the worker equals the one on this thread, with its stages", async () => {
	const worker = createWorker();
	try {
		const a = sphere(24, 0), b = sphere(24, 0.6);
		assert.equal(meshInfo(a).closed, true);
		const here = booleanIndexed(a, b, "union");
		const stages = [];
		const there = await worker.booleanIndexed(a, b, "union", {}, { onProgress: (s) => stages.push(s) });
		assert.deepEqual(Array.from(there.index), Array.from(here.index));
		assert.deepEqual(Array.from(there.positions), Array.from(here.positions));
		assert.equal(there.report.volume, here.report.volume);
		assert.deepEqual(stages.slice(0, 2), ["check", "intersect"]);
		assert.ok(stages.includes("classify"), stages.join(","));
		// Soup calls too, with the report as a non-enumerable property, and pools rebuilt.
		const cube = (c) => {
			const v = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]].map(([x, y, z]) => ({ x: x + c, y, z }));
			const f = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]];
			return f.map(([p, q, r]) => ({ v0: v[p], v1: v[q], v2: v[r] }));
		};
		const r = await worker.boolean(cube(0), cube(0.5), "subtract");
		assert.equal(Object.keys(r).includes("report"), false);
		assert.equal(r.report.volume, 0.5);
		const bms = await worker.bmsBooleanOp(cube(0), cube(0.5), "union");
		assert.ok(bms.pool.size() > 0);
		assert.equal(bms.pool.get(bms.segments[0].p0.id).x, bms.segments[0].p0.x);
		// Transferred arguments are handed over: empty here afterwards.
		const c = sphere(8, 0), d = sphere(8, 0.5);
		const moved = await worker.booleanIndexed(c, d, "intersect", {}, { transfer: true });
		assert.ok(moved.index.length > 0);
		assert.equal(c.positions.length, 0);
		// Errors arrive as Errors with the library's message.
		await assert.rejects(worker.booleanIndexed(a, b, "xor"), /unknown operation/);
	} finally {
		worker.terminate();
	}
});

test("a cancelled call rejects at once with an AbortError, and the worker serves the next", async () => {
	const worker = createWorker();
	try {
		const a = sphere(300, 0), b = sphere(300, 0.5); // 358,800 triangles each
		const controller = new AbortController();
		const started = [];
		const t0 = performance.now();
		const call = worker.booleanIndexed(a, b, "union", {}, {
			signal: controller.signal,
			onProgress: (s) => {
				started.push(s);
				if (s === "intersect") controller.abort();
			},
		});
		await assert.rejects(call, (e) => e.name === "AbortError");
		assert.ok(started.includes("intersect"), started.join(","));
		// Stopped within the stage it was in, not at the end of the call.
		assert.ok(!started.includes("merge"), started.join(","));
		assert.ok(performance.now() - t0 < 10_000);
		// An aborted signal rejects before anything runs.
		await assert.rejects(worker.booleanIndexed(a, b, "union", {}, { signal: AbortSignal.abort() }), (e) => e.name === "AbortError");
		const small = await worker.booleanIndexed(sphere(8, 0), sphere(8, 0.5), "intersect");
		assert.ok(small.report.volume > 0);
	} finally {
		worker.terminate();
	}
});

test("the worker says which build it runs (single-threaded in Node.js), and a bad number of threads is refused at once", async () => {
	assert.throws(() => createWorker({ threads: 0 }), /threads must be a whole number from 1 to 1024 or null, got 0/);
	assert.throws(() => createWorker({ threads: "4" }), /got 4/);
	const worker = createWorker({ threads: 4 });
	try {
		assert.deepEqual(await worker.buildInfo(), { build: "single", threads: 1, reason: "Node.js" });
	} finally {
		worker.terminate();
	}
});
