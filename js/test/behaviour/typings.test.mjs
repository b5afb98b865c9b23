// The TypeScript declarations (JS_BEHAVIOUR.md section 15): src/index.d.ts against the
// runtime exports of src/index.js, both ways (and src/three.d.ts against src/three.js).
import { describe, it } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import * as mb from "../../src/index.js";
import * as three from "../../src/three.js";

/**
 * The value names a declaration file exports: `export [declare] function|const|let|var|
 * class|enum NAME`, and the names of `export { a, b as c } [from "..."]` lists (type-only
 * lists and members excluded). Comments are stripped first.
 */
function declaredValues(path) {
	const text = readFileSync(new URL(path, import.meta.url), "utf8").replace(/\/\*[\s\S]*?\*\//g, "").replace(/\/\/[^\n]*/g, "");
	const names = new Set();
	for (const m of text.matchAll(/^\s*export\s+(?:declare\s+)?(?:async\s+)?(?:function\*?|const|let|var|class|enum)\s+([A-Za-z_$][\w$]*)/gm)) names.add(m[1]);
	for (const m of text.matchAll(/^\s*export\s+(type\s+)?\{([^}]*)\}/gm)) {
		if (m[1]) continue;
		for (const part of m[2].split(",")) {
			const p = part.trim();
			if (p === "" || p.startsWith("type ")) continue;
			const as = p.split(/\s+as\s+/);
			names.add(as[as.length - 1].trim());
		}
	}
	return names;
}

const runtime = (mod) => new Set(Object.keys(mod).filter((k) => k !== "default"));
const BMS = ["bmsIntersect", "heffalumpClassify", "shouldUseHeffalump", "verifyBmsClassification", "createVertexPool", "fanTriangulate", "bmsBooleanOp"];
const FINISH = ["verifyOutput", "assessRepair", "describeAssessment", "violationCount", "finishMesh"];

describe("index.d.ts", () => {
	const declared = declaredValues("../../src/index.d.ts");
	const actual = runtime(mb);

	it("declares every runtime export of index.js", () => {
		assert.deepEqual([...actual].filter((n) => !declared.has(n)).sort(), []);
	});

	it("every declared value exists at runtime", () => {
		assert.deepEqual([...declared].filter((n) => !actual.has(n)).sort(), []);
	});

	it("has more than 50 value declarations", () => {
		assert.ok(declared.size > 50, `${declared.size}`);
	});

	it("the BMS stage names are declared and callable", () => {
		for (const n of BMS) {
			assert.ok(declared.has(n), `${n} declared`);
			assert.equal(typeof mb[n], "function", `${n} callable`);
		}
	});

	it("verifyOutput, assessRepair, describeAssessment, violationCount, finishMesh are declared and callable", () => {
		for (const n of FINISH) {
			assert.ok(declared.has(n), `${n} declared`);
			assert.equal(typeof mb[n], "function", `${n} callable`);
		}
	});

	it("DEFAULT_STAGES is declared as a const", () => {
		assert.ok(declared.has("DEFAULT_STAGES"));
		assert.ok(Array.isArray(mb.DEFAULT_STAGES));
	});
});

describe("three.d.ts", () => {
	const declared = declaredValues("../../src/three.d.ts");
	const actual = runtime(three);

	it("declares every runtime export of three.js, and nothing more", () => {
		assert.deepEqual([...actual].filter((n) => !declared.has(n)).sort(), []);
		assert.deepEqual([...declared].filter((n) => !actual.has(n)).sort(), []);
	});

	it("declares the adapter's 8 reference names", () => {
		for (const n of ["meshToSoup", "soupToMesh", "booleanFromMeshes", "intersectFromMeshes", "repairFromMesh", "boolean", "repair", "intersect"]) {
			assert.ok(declared.has(n), n);
		}
	});
});
