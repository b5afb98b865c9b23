// The demo in a real browser: serves js/ with demo/serve.mjs on a free port, opens the
// page in headless Chromium (Debian's, through playwright-core), checks that the file
// pickers offer exactly the formats this build reads and that files that do not read
// leave their reason in their slots, generates the terrain as A and the pit as B (the
// page's own examples, no data files), runs A − B, and checks the statistics shown
// against booleanIndexed of the same examples computed here in Node; then the STL
// download and the split-and-pick of the same result; then the union of two generated
// spheres of 179,400 triangles each; then the union of two spheres of 2,002,224 triangles
// each, during which the page must answer within 100 ms, cancelled. Any page error,
// console error or failed request fails the test. Saves a screenshot of the A − B view.
//
// All of it twice: served as it is (the page's worker runs the single-threaded build),
// and served cross-origin isolated (serve.mjs --isolated: its worker runs the threaded
// build with navigator.hardwareConcurrency threads, more than 1, where js/wasm-threads is
// built; skipped with a note where it is not, or with MESHBOOL_THREADS=0). Both runs must
// give exactly the same triangle counts, volumes and areas. Isolated, a panic on one of
// the pool's threads must reject the call with its message, and the next call must work.
//
//   node test/browser/run.mjs            (npm run test:browser)
//   CHROMIUM=/path/to/chrome SCREENSHOT=out.png node test/browser/run.mjs
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { booleanIndexed, readFormats, readMesh } from "../../src/index.js";
import { startServer, packageRoot } from "../../demo/serve.mjs";
import { EXAMPLES } from "../../demo/examples.js";

const here = path.dirname(fileURLToPath(import.meta.url));
const screenshot = path.resolve(process.env.SCREENSHOT || path.join(here, "..", "..", "test-out", "demo.png"));
const executablePath = process.env.CHROMIUM || "/usr/bin/chromium";
const TIMEOUT = 60_000;

function fail(message) {
	throw new Error(message);
}

/** What the page must show for terrain − pit (the mined-out solid), computed in Node. */
function expected() {
	const make = (key) => EXAMPLES.find((e) => e.key === key).make();
	const out = booleanIndexed(make("terrain"), make("pit"), "subtract");
	return { triangles: out.report.triangles, volume: out.report.volume, area: out.report.area, closed: out.report.closed };
}

/** The message readMesh gives for `bytes` named `name`, here in Node (the page must show the same). */
function readError(bytes, name) {
	try {
		readMesh(bytes, name);
	} catch (e) {
		return e.message;
	}
	return fail(`${name} reads in Node`);
}

/** A number shown on the page (digits, sign, point), or NaN. */
function shownNumber(text) {
	return Number(String(text).trim());
}

async function main() {
	if (!fs.existsSync(executablePath)) {
		fail(`no Chromium at ${executablePath}: install it (apt-get install -y chromium) or set CHROMIUM`);
	}
	if (!fs.existsSync(path.join(packageRoot, "wasm", "meshbool_wasm_bg.wasm"))) {
		fail("js/wasm is missing: build it first (node scripts/build.mjs)");
	}
	if (!fs.existsSync(path.join(packageRoot, "node_modules", "three", "build", "three.module.js"))) {
		fail("three is not installed: run npm install in js/");
	}
	const want = expected();
	const threadsBuilt = fs.existsSync(path.join(packageRoot, "wasm-threads", "meshbool_wasm_bg.wasm")) && process.env.MESHBOOL_THREADS !== "0";

	const browser = await chromium.launch({
		executablePath,
		headless: true,
		args: [
			"--headless",
			"--no-sandbox",
			"--disable-gpu",
			"--disable-quic",
			"--no-first-run",
			"--disable-background-networking",
			"--disable-component-update",
			"--disable-sync",
			// WebGL without a GPU: ANGLE on SwiftShader (software).
			"--use-angle=swiftshader",
			"--enable-unsafe-swiftshader",
		],
	});
	try {
		const single = await checkPage(browser, want, false);
		if (!threadsBuilt) {
			console.log(`threaded build: ${process.env.MESHBOOL_THREADS === "0" ? "left out (MESHBOOL_THREADS=0)" : "not built (npm run build:threads)"}, the cross-origin isolated run skipped`);
			return;
		}
		const threaded = await checkPage(browser, want, true);
		for (const key of Object.keys(single.results)) {
			const [a, b] = [single.results[key], threaded.results[key]];
			if (JSON.stringify(a) !== JSON.stringify(b)) fail(`${key}: the single-threaded build gives ${JSON.stringify(a)}, the threaded one ${JSON.stringify(b)}`);
		}
		console.log(`ok: both builds give exactly the same ${Object.entries(single.results).map(([k, r]) => `${k} (${r.triangles} triangles, volume ${r.volume}, area ${r.area})`).join(" and ")}`);
	} finally {
		await browser.close();
	}
}

/**
 * The demo page served as it is or cross-origin isolated: every check above, in one
 * page. Returns the exact figures `{results: {name: {triangles, volume, area}}}` of
 * terrain − pit and of the spheres' union, for the comparison of the two builds.
 */
async function checkPage(browser, want, isolated) {
	const mode = isolated ? "isolated" : "not isolated";
	const server = await startServer({ port: 0, isolated });
	const problems = [];
	const results = {};
	try {
		const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
		page.setDefaultTimeout(TIMEOUT);
		page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
		page.on("console", (m) => {
			if (m.type() === "error") problems.push(`console error: ${m.text()}`);
		});
		page.on("requestfailed", (r) => problems.push(`request failed: ${r.url()} (${r.failure()?.errorText})`));
		page.on("response", (r) => {
			if (r.status() >= 400) problems.push(`HTTP ${r.status()}: ${r.url()}`);
		});
		const check = (step) => {
			if (problems.length > 0) fail(`${mode}, ${step}:\n  ${problems.join("\n  ")}`);
		};

		await page.goto(server.url);
		await page.waitForSelector("body[data-ready=true][data-threads]").catch(() => check("the page did not start"));
		check("opening the demo");
		// The build: the threaded one with more than one thread exactly when isolated.
		const build = await page.evaluate(() => ({ isolated: crossOriginIsolated, build: document.body.dataset.build, threads: Number(document.body.dataset.threads) }));
		const cores = await page.evaluate(() => navigator.hardwareConcurrency);
		if (build.isolated !== isolated) fail(`${mode}: crossOriginIsolated is ${build.isolated}`);
		if (isolated ? build.build !== "threads" || build.threads !== cores || !(build.threads > 1) : build.build !== "single" || build.threads !== 1) {
			fail(`${mode}: the page's worker runs ${JSON.stringify(build)} (navigator.hardwareConcurrency ${cores})`);
		}
		const webgl = await page.getAttribute("#viewport", "data-webgl");
		if (webgl !== "ok") fail(`WebGL did not start in Chromium (viewport data-webgl=${webgl})`);

		// The file pickers offer the extensions of the formats this build reads, no others.
		const accept = [...new Set(readFormats().map((f) => `.${f.extension}`))].join(",");
		for (const slot of ["a", "b"]) {
			const shown = await page.getAttribute(`#file-${slot}`, "accept");
			if (shown !== accept) fail(`file picker ${slot} accepts ${JSON.stringify(shown)}, this build reads ${accept}`);
		}

		// A file that does not read: its slot says why, and keeps saying it when the
		// other slot is loaded (the message line is the last action's).
		await page.setInputFiles("#file-a", { name: "broken.stl", mimeType: "model/stl", buffer: Buffer.from("solid broken\nfacet normal 0 0 1\n") });
		await page.waitForSelector("#info-a.error");
		const badInfo = await page.textContent("#info-a");
		if (!badInfo.includes("broken.stl")) fail(`a file that does not read: slot A shows ${JSON.stringify(badInfo)}`);
		await page.click("#load-b-drill-hole");
		await page.waitForSelector("#slot-b[data-loaded='drill-hole']");
		if ((await page.textContent("#info-a")) !== badInfo) fail("slot A's error went when B was loaded");
		if (!(await page.isDisabled("#run"))) fail("Run is enabled without a mesh A");
		// A format this build does not read (GOCAD TSurf): the slot names the ones it reads.
		const tsurf = Buffer.from("GOCAD TSurf 1\nHEADER {\nname: pit\n}\nTFACE\nVRTX 1 0 0 0\nEND\n");
		await page.setInputFiles("#file-b", { name: "pit.ts", mimeType: "text/plain", buffer: tsurf });
		await page.waitForSelector("#info-b.error");
		const tsInfo = await page.textContent("#info-b");
		const tsWant = `pit.ts: ${readError(tsurf, "pit.ts")}`;
		if (tsInfo !== tsWant) fail(`a GOCAD file: slot B shows ${JSON.stringify(tsInfo)}, not ${JSON.stringify(tsWant)}`);
		if (!tsInfo.endsWith(`it reads ${accept.replaceAll(",", " ")} files`)) fail(`the GOCAD file's error does not list what this build reads: ${tsInfo}`);
		check("files that do not read");

		await page.click("#load-a-terrain");
		await page.waitForSelector("#slot-a[data-loaded='terrain']");
		if (await page.$("#info-a.error")) fail("slot A still marked as an error after a good load");
		if ((await page.textContent("#info-b")) !== tsInfo) fail("slot B's error went when A was loaded");
		await page.click("#load-b-pit");
		await page.waitForSelector("#slot-b[data-loaded='pit']");
		await page.selectOption("#op", "subtract");
		await page.click("#run");
		await page.waitForSelector("#stats[data-state=done], #stats[data-state=error]");
		check("running terrain − pit");
		const state = await page.getAttribute("#stats", "data-state");
		if (state !== "done") fail(`the demo failed: ${await page.textContent("#message")}`);

		const shown = {};
		for (const key of ["triangles", "closed", "volume", "area", "time"]) {
			shown[key] = (await page.textContent(`#stat-${key}`)).trim();
		}
		const triangles = shownNumber(shown.triangles);
		if (!(Number.isInteger(triangles) && triangles > 0)) fail(`triangles shown: ${JSON.stringify(shown.triangles)}`);
		if (triangles !== want.triangles) fail(`triangles shown ${triangles}, booleanIndexed in Node gives ${want.triangles}`);
		const volume = shownNumber(shown.volume);
		if (!(Math.abs(volume - want.volume) <= 0.0005 + 1e-9 * Math.abs(want.volume))) {
			fail(`volume shown ${shown.volume}, booleanIndexed in Node gives ${want.volume}`);
		}
		const area = shownNumber(shown.area);
		if (!(Math.abs(area - want.area) <= 0.0005 + 1e-9 * Math.abs(want.area))) fail(`area shown ${shown.area}, Node gives ${want.area}`);
		if (shown.closed !== (want.closed ? "yes" : "no")) fail(`closed shown ${shown.closed}, Node gives ${want.closed}`);
		if (!(shownNumber(shown.time) >= 0)) fail(`time shown: ${JSON.stringify(shown.time)}`);
		results["terrain − pit"] = await exactStats(page);
		if (results["terrain − pit"].triangles !== want.triangles || results["terrain − pit"].volume !== want.volume || results["terrain − pit"].area !== want.area) {
			fail(`${mode}: terrain − pit gives ${JSON.stringify(results["terrain − pit"])}, booleanIndexed in Node ${JSON.stringify(want)}`);
		}

		const colours = await page.evaluate(() => window.meshboolDemo.colourCount());
		if (colours < 8) fail(`the 3-D view looks blank (${colours} colours drawn)`);

		fs.mkdirSync(path.dirname(screenshot), { recursive: true });
		await page.screenshot({ path: shotOf(isolated) });
		check("after the run");

		// Download: the result as binary STL (84 bytes of header and count, 50 per triangle).
		const [download] = await Promise.all([page.waitForEvent("download"), page.click("#download")]);
		const stl = fs.readFileSync(await download.path());
		if (stl.length !== 84 + 50 * want.triangles || stl.readUInt32LE(80) !== want.triangles) {
			fail(`the downloaded STL (${download.suggestedFilename()}, ${stl.length} bytes) does not hold the ${want.triangles} triangles`);
		}

		// Split and pick: A outside B with B inside A flipped (the page's default picks) is A − B.
		await page.selectOption("#op", "split");
		await page.click("#run");
		await page.waitForSelector("#stats[data-state=done], #stats[data-state=error]");
		check("split and pick");
		if ((await page.getAttribute("#stats", "data-state")) !== "done") fail(`split and pick failed: ${await page.textContent("#message")}`);
		const pickTriangles = shownNumber(await page.textContent("#stat-triangles"));
		const pickVolume = shownNumber(await page.textContent("#stat-volume"));
		if (pickTriangles !== want.triangles || !(Math.abs(pickVolume - want.volume) <= 0.0015)) {
			fail(`split and pick of A outside B + flipped B inside A shows ${pickTriangles} triangles, volume ${pickVolume}; A − B has ${want.triangles}, ${want.volume}`);
		}
		check("after split and pick");

		// A union of two spheres that runs to its end: its figures, for the comparison of
		// the builds.
		await runSphereUnion(page, 300);
		await page.waitForSelector("#stats[data-state=done], #stats[data-state=error]", { timeout: 120_000 });
		check("the union of two spheres");
		if ((await page.getAttribute("#stats", "data-state")) !== "done") fail(`${mode}: the spheres' union failed: ${await page.textContent("#message")}`);
		results["sphere ∪ sphere"] = await exactStats(page);

		// Responsive during a long boolean, and cancellable: two generated spheres of
		// 2,002,224 triangles each (the page's sphere generator, 708 bands), their union
		// in the worker; while it runs the page answers timers and an input event within
		// 100 ms; Cancel stops it. (The buttons load spheres of 998,000 triangles.)
		await page.click("#load-a-sphere-1m");
		await page.waitForSelector("#slot-a[data-loaded='sphere-a']");
		await runSphereUnion(page, 708);
		await page.waitForSelector("#stats[data-state=running][data-stage]", { timeout: 60_000 });
		const lags = [];
		for (let i = 0; i < 5; i++) {
			lags.push(await page.evaluate(() => new Promise((resolve) => {
				const t0 = performance.now();
				setTimeout(() => resolve(performance.now() - t0), 0);
			})));
		}
		const before = await page.evaluate(() => window.meshboolDemo.inputEvents);
		await page.click("#show-inputs");
		await page.waitForFunction((n) => window.meshboolDemo.inputEvents > n, before, { timeout: 5000 });
		// From the event's creation by the browser to its handler.
		const inputMs = Math.round(await page.evaluate(() => window.meshboolDemo.inputDelay));
		const stillRunning = (await page.getAttribute("#stats", "data-state")) === "running";
		if (!stillRunning) fail("the union ended before the page could be probed");
		if (Math.max(...lags) > 100 || inputMs > 100) fail(`the page was blocked during the union: timer lags ${lags.map((x) => x.toFixed(1)).join(", ")} ms, input event ${inputMs} ms`);
		const stage = await page.getAttribute("#stats", "data-stage");
		const c0 = Date.now();
		await page.click("#cancel");
		await page.waitForSelector("#stats[data-state=cancelled]", { timeout: 5000 });
		const cancelMs = Date.now() - c0;
		if (!(await page.textContent("#message")).includes("cancelled")) fail("no cancelled message after Cancel");
		check("the union, cancelled");
		// A fresh worker serves the next run.
		await page.click("#load-a-terrain");
		await page.waitForSelector("#slot-a[data-loaded='terrain']");
		await page.click("#load-b-pit");
		await page.waitForSelector("#slot-b[data-loaded='pit']");
		await page.selectOption("#op", "subtract");
		await page.click("#run");
		await page.waitForSelector("#stats[data-state=done], #stats[data-state=error]");
		if (shownNumber(await page.textContent("#stat-triangles")) !== want.triangles) fail("the run after a cancel differs");
		check("the run after the cancel");

		let panic = "";
		if (isolated) {
			// A panic on one of the pool's threads: that thread stops (its error reaches
			// the page as "unreachable", expected here), the call rejects with the
			// panic's message, the worker is replaced.
			const out = await page.evaluate(async () => {
				const { createWorker } = await import("/src/async.js");
				const { makeCube } = await import("/src/index.js");
				const w = createWorker();
				let message = "no error";
				try {
					await w.run("__panicInPoolForTest", []);
				} catch (e) {
					message = e.message;
				}
				const cube = makeCube();
				const next = await w.booleanIndexed(cube, makeCube({ center: [0.5, 0.5, 0.5] }), "union");
				w.terminate();
				return { message, next: next.report.triangles };
			});
			if (!out.message.includes("internal error in __panicInPoolForTest (please report it): panicked at") || !out.message.endsWith("a test panic in the pool")) {
				fail(`${mode}: a panic on the pool gives ${JSON.stringify(out.message)}`);
			}
			if (!(out.next > 0)) fail(`${mode}: the call after a panic on the pool gives ${out.next} triangles`);
			const trap = problems.indexOf("page error: unreachable");
			if (trap >= 0) problems.splice(trap, 1);
			check("a panic on the pool");
			panic = "; a panic on the pool rejects the call with its message and the next call works";
		}
		const shownBuild = build.build === "threads" ? `the threaded build, ${build.threads} threads` : "the single-threaded build";
		console.log(`== ${mode}: the page's worker runs ${shownBuild}${panic}`);
		console.log(
			`ok: during the union of 4M triangles (stage ${stage}) timers answered in at most ${Math.max(...lags).toFixed(1)} ms and an input event in ${inputMs} ms; Cancel stopped it in ${cancelMs} ms; the next run matches`,
		);
		console.log(
			`ok: terrain − pit shows ${shown.triangles} triangles, volume ${shown.volume}, area ${shown.area}, ` +
				`closed ${shown.closed}, ${shown.time} ms (Chromium ${browser.version()}, ${colours} colours drawn)`,
		);
		console.log(`ok: the STL download holds them; split and pick (A outside B + flipped B inside A) shows the same`);
		console.log(`ok: the file pickers accept ${accept}; a broken STL and a GOCAD file leave their reasons in their slots`);
		console.log(`screenshot: ${shotOf(isolated)}`);
		await page.close();
		return { results };
	} finally {
		await server.close();
	}
}

/** The last result's figures as the page computed them (unrounded). */
/** Loads the demo's spheres of `bands` bands into both slots and starts their union. */
async function runSphereUnion(page, bands) {
	await page.evaluate((n) => {
		window.meshboolDemo.loadSphere("a", n);
		window.meshboolDemo.loadSphere("b", n);
	}, bands);
	await page.waitForSelector("#slot-b[data-loaded='sphere-b']");
	await page.selectOption("#op", "union");
	await page.click("#run");
}

async function exactStats(page) {
	return page.evaluate(() => {
		const s = window.meshboolDemo.stats;
		return { triangles: s.triangles, volume: s.volume, area: s.area };
	});
}

/** Where the screenshot of a mode goes (the isolated one beside the other, "-isolated" added). */
function shotOf(isolated) {
	return isolated ? screenshot.replace(/(\.png)?$/, "-isolated.png") : screenshot;
}

main().catch((e) => {
	console.error(`browser test FAILED: ${e.message}`);
	process.exitCode = 1;
});
