// Builds the WebAssembly module and its JavaScript glue into js/wasm/:
//   cargo build -p meshbool-wasm --target wasm32-unknown-unknown --release (LTO, one
//   codegen unit, no debug info: smaller and faster), then wasm-bindgen --target web,
//   then wasm-opt -O3 (binaryen, from npm).
// Needs the wasm32-unknown-unknown target (rustup target add wasm32-unknown-unknown) and
// the wasm-bindgen CLI at the crate's version (cargo install wasm-bindgen-cli --version V).
//
// With --threads (npm run build:threads), the second build, into js/wasm-threads/: the
// feature `threads` (rayon's pool on Web Workers, wasm-bindgen-rayon) on the nightly
// toolchain, its standard library rebuilt with atomics (-Z build-std; needs
// `rustup +nightly component add rust-src` and `rustup +nightly target add
// wasm32-unknown-unknown`), the memory shared and its maximum 4 GiB (what the
// single-threaded build can grow to; the union of two spheres of 2M triangles needs more
// than 1 GiB), in a target directory of its own (target/wasm-threads) so that the two builds
// do not displace each other's artefacts.
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, readFileSync, statSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { gzipSync } from "node:zlib";

const js = dirname(dirname(fileURLToPath(import.meta.url)));
const root = dirname(js);
const run = (cmd, args, env) =>
	execFileSync(cmd, args, { cwd: root, stdio: "inherit", env: { ...process.env, ...env } });

const threads = process.argv.includes("--threads");
const release = {
	CARGO_PROFILE_RELEASE_LTO: "true",
	CARGO_PROFILE_RELEASE_CODEGEN_UNITS: "1",
	CARGO_PROFILE_RELEASE_DEBUG: "false",
};
const cargo = ["build", "-p", "meshbool-wasm", "--target", "wasm32-unknown-unknown", "--release", "--locked"];
let targetDir = join(root, "target");
if (threads) {
	targetDir = join(root, "target", "wasm-threads");
	run("cargo", ["+nightly", ...cargo, "--features", "threads", "-Z", "build-std=panic_abort,std", "--target-dir", targetDir], {
		...release,
		RUSTFLAGS: [
			"-C target-feature=+atomics,+bulk-memory,+mutable-globals",
			// A shared memory, imported (each thread instantiates the module on the same
			// one), and the thread-local storage's symbols that wasm-bindgen's glue sets
			// up on each thread: rustc asked the linker for these itself with +atomics
			// until nightly 2025-10 (rust-lang/rust#147225).
			...["--shared-memory", "--import-memory", "--max-memory=4294967296"].map((a) => `-C link-arg=${a}`),
			...["__wasm_init_tls", "__tls_size", "__tls_align", "__tls_base"].map((s) => `-C link-arg=--export=${s}`),
		].join(" "),
	});
} else {
	run("cargo", cargo, release);
}

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
const out = join(js, threads ? "wasm-threads" : "wasm");
mkdirSync(out, { recursive: true });
run("wasm-bindgen", [
	"--target", "web",
	"--remove-name-section",
	"--remove-producers-section",
	"--out-dir", out,
	join(targetDir, "wasm32-unknown-unknown", "release", "meshbool_wasm.wasm"),
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
		...(threads ? ["--enable-threads"] : []),
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
