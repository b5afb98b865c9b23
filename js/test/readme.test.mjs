// Every JavaScript example of README.md runs: the ```js blocks are written out in order as
// modules inside the package (so that `import ... from "meshbool"` resolves to this
// package, as it does for a user) and run one after another in one folder (files an
// example reads are written by an earlier one). A line `console.log(...); // → TEXT`
// must print TEXT. The README's statement of the WebAssembly's size must be the build's.
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import { mkdirSync, readFileSync, rmSync, statSync, writeFileSync } from "node:fs";
import { fileURLToPath } from "node:url";
import { gzipSync } from "node:zlib";

const readme = readFileSync(new URL("../README.md", import.meta.url), "utf8");
const folder = new URL("../test-out/readme/", import.meta.url);

/** The ```js blocks of the README: `{line, code}` (`line`: the README's line of the block's first line). */
function jsBlocks(text) {
	const blocks = [];
	const lines = text.split("\n");
	for (let i = 0; i < lines.length; i++) {
		if (lines[i].trim() !== "```js") continue;
		const start = i + 1;
		let end = start;
		while (end < lines.length && lines[end].trim() !== "```") end++;
		blocks.push({ line: start + 1, code: lines.slice(start, end) });
		i = end;
	}
	return blocks;
}

const CHECKED = /^(\s*)console\.log\((.*)\);\s*\/\/ → (.*)$/;

/**
 * The module run for a block: each checked line calls `__readme` instead of console.log,
 * which prints the same, says on stderr that the line ran, and fails the run when the
 * printed text is not the comment's.
 */
function instrumented({ line, code }) {
	const head = [
		'import { format as __format } from "node:util";',
		"const __readme = (line, want, ...args) => {",
		"	const got = __format(...args);",
		"	console.log(got);",
		"	console.error(`README-CHECKED ${line}`);",
		"	if (got !== want) {",
		"		console.error(`README.md line ${line} prints ${JSON.stringify(got)}; its comment says ${JSON.stringify(want)}`);",
		"		process.exitCode = 1;",
		"	}",
		"};",
	];
	const body = code.map((text, k) => {
		const m = CHECKED.exec(text);
		return m ? `${m[1]}__readme(${line + k}, ${JSON.stringify(m[3])}, ${m[2]});` : text;
	});
	return [...head, ...body].join("\n");
}

test("every JavaScript example of README.md runs, in order, and prints what its comments say", () => {
	const blocks = jsBlocks(readme);
	assert.ok(blocks.length >= 3, `${blocks.length} js blocks`);
	rmSync(folder, { recursive: true, force: true });
	mkdirSync(folder, { recursive: true });
	const cwd = fileURLToPath(folder);
	let checks = 0;
	blocks.forEach((block, k) => {
		const want = block.code.filter((l) => CHECKED.test(l)).length;
		const file = new URL(`example-${k + 1}.mjs`, folder);
		writeFileSync(file, instrumented(block));
		const run = spawnSync(process.execPath, [fileURLToPath(file)], { cwd, encoding: "utf8", timeout: 120_000 });
		const stderr = run.stderr || "";
		const said = stderr.split("\n").filter((l) => !l.startsWith("README-CHECKED ")).join("\n").trim();
		assert.equal(run.status, 0, `the example at README.md line ${block.line} failed (${run.error ? run.error.message : `exit ${run.status}`}):\n${said}`);
		const ran = stderr.split("\n").filter((l) => l.startsWith("README-CHECKED ")).length;
		assert.equal(ran, want, `the example at README.md line ${block.line}: ${ran} of its ${want} checked lines ran`);
		checks += want;
	});
	assert.ok(checks >= 5, `${checks} printed figures checked`);
});

test("README.md states the WebAssembly's size as the build gives it (within 1 %)", () => {
	const m = /`meshbool_wasm_bg\.wasm` is ([\d.]+) MB \(([\d,]+) bytes\), (\d+) KiB gzipped/.exec(readme);
	assert.ok(m, "the README's size statement is not found");
	const [mb, bytes, gzKiB] = [Number(m[1]), Number(m[2].replaceAll(",", "")), Number(m[3])];
	assert.equal(mb, Number((bytes / 1e6).toFixed(2)), "the README's MB and bytes disagree");
	const wasm = new URL("../wasm/meshbool_wasm_bg.wasm", import.meta.url);
	const size = statSync(wasm).size;
	const gz = gzipSync(readFileSync(wasm), { level: 9 }).length / 1024;
	assert.ok(Math.abs(size - bytes) <= 0.01 * size, `the README says ${bytes} bytes, the build is ${size}`);
	assert.ok(Math.abs(gz - gzKiB) <= 0.01 * gz, `the README says ${gzKiB} KiB gzipped, the build is ${gz.toFixed(0)}`);
});
