// The demo in a real browser: serves js/ with demo/serve.mjs on a free port, opens the
// page in headless Chromium (Debian's, through playwright-core), checks that the file
// pickers offer exactly the formats this build reads and that files that do not read
// leave their reason in their slots, generates the terrain as A and the pit as B (the
// page's own examples, no data files), runs A − B, and checks the statistics shown
// against booleanIndexed of the same examples computed here in Node; then the STL
// download and the split-and-pick of the same result; then the union of two generated
// spheres of 2,002,224 triangles each, during which the page must answer within 100 ms,
// cancelled. Any page error, console error or failed request fails the test. Saves a
// screenshot of the A − B view.
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

	const server = await startServer({ port: 0 });
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
	const problems = [];
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
			if (problems.length > 0) fail(`${step}:\n  ${problems.join("\n  ")}`);
		};

		await page.goto(server.url);
		await page.waitForSelector("body[data-ready=true]").catch(() => check("the page did not start"));
		check("opening the demo");
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

		const colours = await page.evaluate(() => window.meshboolDemo.colourCount());
		if (colours < 8) fail(`the 3-D view looks blank (${colours} colours drawn)`);

		fs.mkdirSync(path.dirname(screenshot), { recursive: true });
		await page.screenshot({ path: screenshot });
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

		// Responsive during a long boolean, and cancellable: two generated spheres of
		// 2,002,224 triangles each (the page's sphere generator, 708 bands), their union
		// in the worker; while it runs the page answers timers and an input event within
		// 100 ms; Cancel stops it. (The buttons load spheres of 998,000 triangles.)
		await page.click("#load-a-sphere-1m");
		await page.waitForSelector("#slot-a[data-loaded='sphere-a']");
		await page.evaluate(() => {
			window.meshboolDemo.loadSphere("a", 708);
			window.meshboolDemo.loadSphere("b", 708);
		});
		await page.waitForSelector("#slot-b[data-loaded='sphere-b']");
		await page.selectOption("#op", "union");
		await page.click("#run");
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
		console.log(
			`ok: during the union of 4M triangles (stage ${stage}) timers answered in at most ${Math.max(...lags).toFixed(1)} ms and an input event in ${inputMs} ms; Cancel stopped it in ${cancelMs} ms; the next run matches`,
		);
		console.log(
			`ok: terrain − pit shows ${shown.triangles} triangles, volume ${shown.volume}, area ${shown.area}, ` +
				`closed ${shown.closed}, ${shown.time} ms (Chromium ${browser.version()}, ${colours} colours drawn)`,
		);
		console.log(`ok: the STL download holds them; split and pick (A outside B + flipped B inside A) shows the same`);
		console.log(`ok: the file pickers accept ${accept}; a broken STL and a GOCAD file leave their reasons in their slots`);
		console.log(`screenshot: ${screenshot}`);
	} finally {
		await browser.close();
		await server.close();
	}
}

main().catch((e) => {
	console.error(`browser test FAILED: ${e.message}`);
	process.exitCode = 1;
});
