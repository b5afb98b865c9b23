// Builds the WebAssembly module and its JavaScript glue into js/wasm/:
//   cargo build -p meshbool-wasm --target wasm32-unknown-unknown --release (LTO, one
//   codegen unit, no debug info: smaller and faster), then wasm-bindgen --target web,
//   then wasm-opt -O3 (binaryen, from npm).
// Needs the wasm32-unknown-unknown target (rustup target add wasm32-unknown-unknown) and
// the wasm-bindgen CLI at the crate's version (cargo install wasm-bindgen-cli --version V).
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, statSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { gzipSync } from "node:zlib";

const js = dirname(dirname(fileURLToPath(import.meta.url)));
const root = dirname(js);
const run = (cmd, args, env) =>
	execFileSync(cmd, args, { cwd: root, stdio: "inherit", env: { ...process.env, ...env } });

run("cargo", ["build", "-p", "meshbool-wasm", "--target", "wasm32-unknown-unknown", "--release", "--locked"], {
	CARGO_PROFILE_RELEASE_LTO: "true",
	CARGO_PROFILE_RELEASE_CODEGEN_UNITS: "1",
	CARGO_PROFILE_RELEASE_DEBUG: "false",
});

// The CLI must match the crate's wasm-bindgen version (the lock file's).
const lock = readFileSync(join(root, "Cargo.lock"), "utf8");
const want = /name = "wasm-bindgen"\nversion = "([^"]+)"/.exec(lock)[1];
let have = "";
try {
	have = execFileSync("wasm-bindgen", ["--version"], { encoding: "utf8" }).trim().split(" ")[1];
} catch {
	have = "";
}
if (have !== want) {
	console.error(`wasm-bindgen ${want} is needed (found ${have || "none"}): cargo install wasm-bindgen-cli --version ${want}`);
	process.exit(1);
}
const out = join(js, "wasm");
mkdirSync(out, { recursive: true });
run("wasm-bindgen", [
	"--target", "web",
	"--remove-name-section",
	"--remove-producers-section",
	"--out-dir", out,
	join(root, "target/wasm32-unknown-unknown/release/meshbool_wasm.wasm"),
]);
const wasm = join(out, "meshbool_wasm_bg.wasm");
// wasm-opt -O3 from the binaryen npm package (a dev dependency): about 5 % smaller and no
// slower (BENCHMARKS.md). Skipped with a note when it is not installed.
const wasmOpt = join(js, "node_modules", ".bin", "wasm-opt");
if (existsSync(wasmOpt)) {
	run(wasmOpt, [
		"-O3",
		"--enable-bulk-memory",
		"--enable-nontrapping-float-to-int",
		"--enable-sign-ext",
		"--enable-mutable-globals",
		"--enable-reference-types",
		"--enable-multivalue",
		wasm,
		"-o",
		wasm,
	]);
} else {
	console.log("wasm-opt not installed (npm install): the module is left as wasm-bindgen wrote it");
}
const size = statSync(wasm).size;
const gz = gzipSync(readFileSync(wasm), { level: 9 }).length;
console.log(`built ${wasm}: ${(size / 1024).toFixed(0)} KiB, ${(gz / 1024).toFixed(0)} KiB gzipped`);
