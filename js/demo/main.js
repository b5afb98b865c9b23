// The demo page: two meshes (files read by meshbool's WebAssembly readers, or examples
// generated in the page: a terrain, a pit, a drill hole, a sphere, and two spheres of
// 998,000 triangles each), a boolean or a split-and-pick of the two computed in a Web
// Worker (the page stays responsive; the stages show as they begin; Cancel stops it), the
// result drawn with three.js and measured, and an STL download of it. Needs no data
// files and no network. Served cross-origin isolated (serve.mjs --isolated), the worker
// runs the threaded build where it is installed; the footer says which build runs.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { meshInfo, readFormats, readMesh, version, writeMesh } from "../src/index.js";
import { createWorker } from "../src/async.js";
import { indexedToGeometry } from "../src/three.js";
import { EXAMPLES, bigSphere } from "./examples.js";

const $ = (id) => document.getElementById(id);

const COLORS = { a: 0x6fb3ff, b: 0xffb15e, result: 0x7fd18b };
const GROUPS = ["a_in_b", "a_out_b", "b_in_a", "b_out_a"];
/** The file picker's choices: the extensions of the formats this build reads. */
const ACCEPT = [...new Set(readFormats().map((f) => `.${f.extension}`))].join(",");
const STAGES = { check: "checking the inputs", intersect: "intersecting", arrange: "cutting along the seam", classify: "classifying", merge: "merging", snap: "snapping" };

/** The worker the operations run in, and the controller of the running one. */
const worker = createWorker();
let running = null;

// Started now (its WebAssembly loads while the page is read): which build it runs.
worker.buildInfo().then(
	(info) => {
		const shown = info.build === "threads" ? `threaded, ${info.threads} threads` : "single-threaded";
		$("build").textContent = `WebAssembly build: ${shown} (${info.reason})`;
		document.body.dataset.build = info.build;
		document.body.dataset.threads = String(info.threads);
	},
	(e) => {
		$("build").textContent = `WebAssembly build: failed to start (${e.message})`;
		setMessage(e.message, true);
	},
);

/** What the page holds: the two inputs `{name, mesh}` and the last result `{mesh, name}`. */
const state = { a: null, b: null, result: null };

// ── viewer ───────────────────────────────────────────────────────────────────────────────

const viewer = createViewer($("viewport"));

/**
 * The 3-D view: renderer, Z-up camera with orbit controls, lights, and one group per
 * shown mesh. Draws on demand. Coordinates are shifted by `origin` (the inputs' centre)
 * before they are rounded to single precision, so that far-off (UTM) data draws cleanly.
 */
function createViewer(container) {
	let renderer;
	try {
		renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
	} catch (e) {
		$("overlay").textContent = `WebGL is not available in this browser (${e.message}); the operations and statistics still work.`;
		container.dataset.webgl = "failed";
		return null;
	}
	container.dataset.webgl = "ok";
	renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
	renderer.setClearColor(0x14171c);
	container.prepend(renderer.domElement);

	const scene = new THREE.Scene();
	const camera = new THREE.PerspectiveCamera(45, 1, 0.1, 1000);
	camera.up.set(0, 0, 1);
	camera.position.set(1, -1.5, 1);
	scene.add(camera);
	scene.add(new THREE.HemisphereLight(0xffffff, 0x303040, 1.4));
	const headlight = new THREE.DirectionalLight(0xffffff, 1.6);
	headlight.position.set(0.4, 0.6, 1);
	camera.add(headlight);

	const controls = new OrbitControls(camera, renderer.domElement);
	const layers = { a: new THREE.Group(), b: new THREE.Group(), result: new THREE.Group() };
	for (const g of Object.values(layers)) scene.add(g);
	const origin = new THREE.Vector3();

	let pending = false;
	function render() {
		if (pending) return;
		pending = true;
		requestAnimationFrame(() => {
			pending = false;
			renderer.render(scene, camera);
		});
	}
	controls.addEventListener("change", render);

	new ResizeObserver(() => {
		const w = Math.max(container.clientWidth, 1), h = Math.max(container.clientHeight, 1);
		renderer.setSize(w, h, false);
		camera.aspect = w / h;
		camera.updateProjectionMatrix();
		render();
	}).observe(container);

	function clear(group) {
		for (const child of [...group.children]) {
			group.remove(child);
			child.geometry.dispose();
			child.material.dispose();
		}
	}

	function geometryOf(mesh) {
		const p = new Float64Array(mesh.positions.length);
		for (let i = 0; i < p.length; i += 3) {
			p[i] = mesh.positions[i] - origin.x;
			p[i + 1] = mesh.positions[i + 1] - origin.y;
			p[i + 2] = mesh.positions[i + 2] - origin.z;
		}
		return indexedToGeometry({ positions: p, index: mesh.index });
	}

	return {
		/** Shows an input faint: a thin wireframe over a barely visible surface. */
		setInput(slot, mesh) {
			clear(layers[slot]);
			if (mesh) {
				const geometry = geometryOf(mesh);
				layers[slot].add(new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: COLORS[slot], wireframe: true, transparent: true, opacity: 0.22, depthWrite: false })));
				layers[slot].add(new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: COLORS[slot], transparent: true, opacity: 0.06, side: THREE.DoubleSide, depthWrite: false })));
			}
			render();
		},
		/** Shows the result solid (flat shaded, both faces, the back darker). */
		setResult(mesh) {
			clear(layers.result);
			if (mesh) {
				const geometry = geometryOf(mesh);
				layers.result.add(new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({ color: COLORS.result, flatShading: true, side: THREE.FrontSide, shininess: 20 })));
				layers.result.add(new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({ color: 0x8a5a9e, flatShading: true, side: THREE.BackSide, shininess: 5 })));
			}
			render();
		},
		showInputs(visible) {
			layers.a.visible = layers.b.visible = visible;
			render();
		},
		/** Centres the drawing on the inputs' box and frames the camera on it. */
		frame(meshes) {
			const box = new THREE.Box3();
			const p = new THREE.Vector3();
			for (const m of meshes) {
				for (let i = 0; i < m.positions.length; i += 3) {
					box.expandByPoint(p.set(m.positions[i], m.positions[i + 1], m.positions[i + 2]));
				}
			}
			if (box.isEmpty()) return;
			box.getCenter(origin);
			const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
			const half = Math.atan(Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) * Math.min(camera.aspect, 1));
			const dist = (1.05 * radius) / Math.sin(half);
			camera.near = dist / 1000;
			camera.far = dist * 100;
			camera.position.set(0.55, -0.75, 0.45).normalize().multiplyScalar(dist);
			camera.updateProjectionMatrix();
			controls.target.set(0, 0, 0);
			controls.update();
		},
		/** How many distinct colours the last frame has (a check that something was drawn). */
		colourCount() {
			renderer.render(scene, camera);
			const gl = renderer.getContext();
			const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
			const px = new Uint8Array(4 * w * h);
			gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
			const seen = new Set();
			for (let i = 0; i < px.length; i += 4 * 97) seen.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
			return seen.size;
		},
	};
}

// ── inputs ───────────────────────────────────────────────────────────────────────────────

function setMessage(text, isError = false) {
	$("message").textContent = text;
	$("message").classList.toggle("error", isError);
}

/**
 * Puts a mesh into slot "a" or "b" and shows it: `counts` (a report's or meshInfo's
 * `triangles`, `vertices`, `closed`, `boundary_edges`) for the slot's line.
 */
function setSlot(slot, name, mesh, counts, note = "") {
	state[slot] = { name, mesh: { positions: mesh.positions, index: mesh.index } };
	const shape = counts.closed ? "closed" : `open, ${counts.boundary_edges} boundary edges`;
	$(`info-${slot}`).textContent = `${name}: ${counts.triangles} triangles, ${counts.vertices} vertices, ${shape}${note}`;
	$(`info-${slot}`).classList.remove("error");
	$(`slot-${slot}`).dataset.loaded = name;
	inputsChanged();
}

/** Reads a mesh file's bytes into slot "a" or "b" (the file's name tells the format). */
function loadInto(slot, name, bytes) {
	let mesh;
	try {
		mesh = readMesh(new Uint8Array(bytes), name);
	} catch (e) {
		// The slot keeps saying why (the message line is the last action's).
		state[slot] = null;
		delete $(`slot-${slot}`).dataset.loaded;
		$(`info-${slot}`).textContent = `${name}: ${e.message}`;
		$(`info-${slot}`).classList.add("error");
		inputsChanged();
		throw e;
	}
	setSlot(slot, name, mesh, meshInfo(mesh));
}

/** After an input changes: forget the result, redraw and reframe. */
function inputsChanged() {
	setResult(null);
	const meshes = ["a", "b"].filter((s) => state[s]).map((s) => state[s].mesh);
	if (viewer) {
		viewer.frame(meshes);
		viewer.setInput("a", state.a && state.a.mesh);
		viewer.setInput("b", state.b && state.b.mesh);
		$("overlay").hidden = meshes.length > 0;
	}
	$("run").disabled = !(state.a && state.b);
	for (const g of GROUPS) $(`count-${g}`).textContent = "";
}

/** Generates an example (EXAMPLES) into a slot. */
function loadExample(slot, example) {
	$(`file-${slot}`).value = "";
	const mesh = example.make();
	setSlot(slot, example.key, mesh, mesh.report, " (generated)");
}

/**
 * Puts a generated sphere of `n` bands (default 500: 998,000 triangles) into a slot
 * ("a": centred at the origin, "b": moved by 0.5).
 */
function loadSphere(slot, n = 500) {
	$(`file-${slot}`).value = "";
	const mesh = bigSphere(slot, n);
	setSlot(slot, `sphere-${slot}`, mesh, mesh.report, " (generated)");
}

async function loadFile(slot, input) {
	const file = input.files && input.files[0];
	if (!file) return;
	setMessage(`reading ${file.name}…`);
	loadInto(slot, file.name, await file.arrayBuffer());
	setMessage("");
}

/** Runs an async UI action, showing its error instead of letting it escape. */
function guarded(action) {
	return (...args) =>
		action(...args).catch((e) => {
			setMessage(e.message, true);
			$("stats").dataset.state = "error";
		});
}

// ── operations ───────────────────────────────────────────────────────────────────────────

/**
 * The chosen split groups concatenated into one mesh: each group's vertices appended, its
 * triangles renumbered, flipped ones with their corners in reverse order.
 */
function concatGroups(picks) {
	let vertices = 0, corners = 0;
	for (const { group } of picks) {
		vertices += group.positions.length;
		corners += group.index.length;
	}
	const positions = new Float64Array(vertices);
	const index = new Uint32Array(corners);
	let v = 0, c = 0;
	for (const { group, flip } of picks) {
		positions.set(group.positions, v);
		const base = v / 3, src = group.index;
		for (let i = 0; i < src.length; i += 3, c += 3) {
			index[c] = base + src[i];
			index[c + 1] = base + src[flip ? i + 2 : i + 1];
			index[c + 2] = base + src[flip ? i + 1 : i + 2];
		}
		v += group.positions.length;
	}
	return { positions, index };
}

/**
 * Vertices with exactly equal coordinates merged (the groups of a split meet on the
 * intersection curves at equal points; merged, the edge counts of the pick are meaningful).
 */
function weldExact(mesh) {
	const ids = new Map();
	const remap = new Uint32Array(mesh.positions.length / 3);
	const out = [];
	for (let i = 0; i < remap.length; i++) {
		const x = mesh.positions[3 * i], y = mesh.positions[3 * i + 1], z = mesh.positions[3 * i + 2];
		const key = `${x} ${y} ${z}`;
		let id = ids.get(key);
		if (id === undefined) {
			id = out.length / 3;
			ids.set(key, id);
			out.push(x, y, z);
		}
		remap[i] = id;
	}
	return { positions: Float64Array.from(out), index: mesh.index.map((i) => remap[i]) };
}

/** A boolean of the two inputs (in the worker): the result mesh and its statistics. */
async function runBoolean(op, control) {
	const t0 = performance.now();
	const out = await worker.booleanIndexed(state.a.mesh, state.b.mesh, op, {}, control);
	const ms = performance.now() - t0;
	const r = out.report;
	return {
		mesh: { positions: out.positions, index: out.index },
		stats: { triangles: r.triangles, closed: r.closed, volume: r.volume, area: r.area, ms },
		notes: [...(r.assumed || []), `${r.vertices} vertices, ${r.boundary_edges} boundary edges, ${r.seam_points} seam points`],
	};
}

/** A split of the inputs (in the worker) with the groups ticked in the table, concatenated and measured. */
async function runSplit(control) {
	const t0 = performance.now();
	const { groups, report } = await worker.splitIndexed(state.a.mesh, state.b.mesh, {}, control);
	const picks = [];
	for (const g of GROUPS) {
		const group = groups[g];
		$(`count-${g}`).textContent = group ? String(group.index.length / 3) : "0";
		if (group && $(`pick-${g}`).checked) picks.push({ group, flip: $(`flip-${g}`).checked });
	}
	const mesh = weldExact(concatGroups(picks));
	const ms = performance.now() - t0;
	const info = meshInfo(mesh);
	const others = Object.keys(groups).filter((g) => !GROUPS.includes(g) && groups[g].index.length > 0);
	const notes = [...(report.assumed || []), `${info.vertices} vertices, ${info.boundary_edges} boundary edges, ${info.non_manifold_edges} non-manifold edges`];
	if (others.length > 0) notes.push(`coplanar groups not offered here: ${others.join(", ")}`);
	return { mesh, stats: { triangles: info.triangles, closed: info.closed, volume: info.volume, area: info.area, ms }, notes };
}

function showStats(stats, notes) {
	// The figures unrounded, for tests and the console.
	if (window.meshboolDemo) window.meshboolDemo.stats = stats;
	$("stat-triangles").textContent = stats ? String(stats.triangles) : "–";
	$("stat-closed").textContent = stats ? (stats.closed ? "yes" : "no") : "–";
	$("stat-volume").textContent = stats ? stats.volume.toFixed(3) : "–";
	$("stat-area").textContent = stats ? stats.area.toFixed(3) : "–";
	$("stat-time").textContent = stats ? stats.ms.toFixed(1) : "–";
	$("notes").replaceChildren(...(notes || []).map((n) => Object.assign(document.createElement("li"), { textContent: n })));
}

function setResult(result) {
	state.result = result;
	$("download").disabled = !result || result.mesh.index.length === 0;
	if (viewer) viewer.setResult(result && result.mesh);
	if (!result) {
		showStats(null);
		$("stats").dataset.state = "idle";
	}
}

async function run() {
	if (!state.a || !state.b) throw new Error("load both meshes first");
	const op = $("op").value;
	$("stats").dataset.state = "running";
	$("run").disabled = true;
	$("cancel").disabled = false;
	setMessage("computing…");
	running = new AbortController();
	const control = {
		signal: running.signal,
		onProgress: (stage) => {
			$("stats").dataset.stage = stage;
			setMessage(`computing: ${STAGES[stage] || stage}…`);
		},
	};
	try {
		const { mesh, stats, notes } = op === "split" ? await runSplit(control) : await runBoolean(op, control);
		const label = op === "split" ? "split" : op;
		setResult({ mesh, name: `${stem(state.a.name)}-${label}-${stem(state.b.name)}` });
		showStats(stats, notes);
		setMessage(mesh.index.length === 0 ? "the result is empty" : "");
		$("stats").dataset.state = "done";
	} catch (e) {
		if (e.name !== "AbortError") throw e;
		setMessage("cancelled");
		$("stats").dataset.state = "cancelled";
	} finally {
		running = null;
		delete $("stats").dataset.stage;
		$("run").disabled = false;
		$("cancel").disabled = true;
	}
}

function stem(name) {
	return name.replace(/\.[^.]*$/, "");
}

function download() {
	if (!state.result) return;
	const bytes = writeMesh(state.result.mesh, "stl");
	const url = URL.createObjectURL(new Blob([bytes], { type: "model/stl" }));
	const a = Object.assign(document.createElement("a"), { href: url, download: `${state.result.name}.stl` });
	document.body.append(a);
	a.click();
	a.remove();
	setTimeout(() => URL.revokeObjectURL(url), 1000);
}

// ── wiring ───────────────────────────────────────────────────────────────────────────────

/** A button of a slot's examples row: `load-SLOT-KEY`, which runs `action` when clicked. */
function exampleButton(slot, key, label, title, action) {
	const button = Object.assign(document.createElement("button"), { type: "button", id: `load-${slot}-${key}`, textContent: label, title });
	button.addEventListener("click", () => {
		try {
			action();
			setMessage("");
		} catch (e) {
			setMessage(e.message, true);
		}
	});
	return button;
}

for (const row of document.querySelectorAll(".examples")) {
	const slot = row.dataset.slot;
	for (const example of EXAMPLES) {
		row.append(exampleButton(slot, example.key, example.label, example.title, () => loadExample(slot, example)));
	}
	row.append(exampleButton(slot, "sphere-1m", "sphere 1M", "a sphere of 998,000 triangles (radius 1; B's moved by 0.5)", () => loadSphere(slot)));
}
for (const slot of ["a", "b"]) {
	$(`file-${slot}`).accept = ACCEPT;
	$(`file-${slot}`).addEventListener("change", guarded((e) => loadFile(slot, e.target)));
}
$("swap").addEventListener("click", () => {
	[state.a, state.b] = [state.b, state.a];
	$("file-a").value = $("file-b").value = "";
	const [infoA, infoB] = [$("info-a").textContent, $("info-b").textContent];
	[$("info-a").textContent, $("info-b").textContent] = [infoB, infoA];
	const [badA, badB] = [$("info-a").classList.contains("error"), $("info-b").classList.contains("error")];
	$("info-a").classList.toggle("error", badB);
	$("info-b").classList.toggle("error", badA);
	for (const slot of ["a", "b"]) {
		if (state[slot]) $(`slot-${slot}`).dataset.loaded = state[slot].name;
		else delete $(`slot-${slot}`).dataset.loaded;
	}
	inputsChanged();
});
$("op").addEventListener("change", () => {
	$("picks").hidden = $("op").value !== "split";
});
$("run").addEventListener("click", guarded(run));
$("cancel").addEventListener("click", () => running && running.abort());
$("download").addEventListener("click", download);
$("show-inputs").addEventListener("change", (e) => viewer && viewer.showInputs(e.target.checked));
$("picks").hidden = $("op").value !== "split";
$("version").textContent = `meshbool ${version}, three.js r${THREE.REVISION}`;

// For tests and the console: the page's state and a rendering check.
window.meshboolDemo = { state, colourCount: () => (viewer ? viewer.colourCount() : 0), inputEvents: 0, loadSphere };
// How long each input event waited before its handler ran (the page's responsiveness).
$("show-inputs").addEventListener("change", (e) => {
	window.meshboolDemo.inputEvents++;
	window.meshboolDemo.inputDelay = performance.now() - e.timeStamp;
});
document.body.dataset.ready = "true";
