//! WebAssembly bindings of meshbool: the native layer of the `meshbool` npm package
//! (`js/`). A thin layer over the library's front door (`meshbool::ops`), as the Python
//! package's is: flat typed arrays in, one call per operation, typed arrays and JSON
//! reports out. The JavaScript package (`js/src/index.js`) builds the reference API's
//! shapes (soups of `{v0,v1,v2}`, `{soup, points, triangles}`, the four groups) on top.
//!
//! Meshes cross as two arrays: `positions` (`Float64Array`, three numbers per vertex) and
//! `index` (`Uint32Array`, three vertex indices per triangle). A result is a plain object
//! `{positions, index, report}` (`report`: the JSON text of the command's report, the
//! same as the CLI's `--json`), with extra arrays where an operation has more to say.
//!
//! Errors are thrown as JavaScript `Error`s carrying the library's message. A panic (a bug)
//! aborts the WebAssembly call; [`last_panic`] then gives its message so that the package
//! can throw an `Error` that says what happened instead of "unreachable".
//!
//! With the feature `threads` (the second build, `npm run build:threads`: nightly,
//! `+atomics`), rayon's global pool runs on Web Workers (`initThreadPool`, from
//! wasm-bindgen-rayon). A long call then runs on the pool while the thread that made it
//! waits, so its stages, and a panic on one of the pool's threads (which stops that thread
//! and leaves the call waiting), are also posted to a BroadcastChannel
//! ([`set_progress_channel`]) that a thread which is not waiting can listen to.
#![forbid(unsafe_code)]

use std::cell::RefCell;

use js_sys::{Array, Float64Array, Object, Reflect, Uint32Array, Uint8Array};
use meshbool::ops::{
    self, BooleanOptions, Checks, CurvesOptions, Measures, PickOptions, ResolveOptions,
    SplitOptions,
};
use meshbool::repair::{CloseMode, CloseOptions, Facing, RepairConfig};
use meshbool::{EdgeTopology, Error, FillRule, Format, Mesh, Op, Source};
use serde_json::Value;
use wasm_bindgen::prelude::*;

#[cfg(feature = "threads")]
pub use threads::{init_thread_pool, panic_in_pool_for_test, set_progress_channel};

thread_local! {
    static PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    static PROGRESS: RefCell<Option<js_sys::Function>> = const { RefCell::new(None) };
}

/// Sets (or, with `null`, clears) the function called with each stage's name (`check`,
/// `intersect`, `arrange`, `classify`, `merge`, `snap`, ...) as the long operations
/// (boolean, split, resolve) begin it. Kept per thread: the callback is only ever called
/// on the thread that set it, the one running the call in this single-threaded build.
#[wasm_bindgen(js_name = setProgress)]
pub fn set_progress(f: Option<js_sys::Function>) {
    PROGRESS.with(|p| *p.borrow_mut() = f);
}

/// The run options of a long call: progress reported to the function of [`set_progress`]
/// (when the stage runs on the thread that set it) and, in the threaded build, to the
/// channel of [`set_progress_channel`].
fn run_options() -> ops::RunOptions {
    ops::RunOptions {
        progress: Some(ops::Progress::new(|stage| {
            PROGRESS.with(|p| {
                if let Some(f) = &*p.borrow() {
                    // A throwing callback does not stop the call.
                    let _ = f.call1(&JsValue::NULL, &JsValue::from_str(stage.name()));
                }
            });
            #[cfg(feature = "threads")]
            threads::broadcast("stage", stage.name());
        })),
        ..ops::RunOptions::default()
    }
}

/// Installs the panic hook that keeps a panic's message for [`last_panic`] (and, in the
/// threaded build, posts a panic on one of the pool's threads to the progress channel).
/// Runs when the module is instantiated (the hook is the process's, for every thread).
#[wasm_bindgen(start)]
pub fn start() {
    std::panic::set_hook(Box::new(|info| {
        let text = info.to_string();
        #[cfg(feature = "threads")]
        if rayon::current_thread_index().is_some() {
            threads::broadcast("panic", &text);
        }
        PANIC.with(|p| *p.borrow_mut() = Some(text));
    }));
}

/// The threaded build's side: the pool, and the channel that reports what happens on it.
#[cfg(feature = "threads")]
mod threads {
    use std::sync::Mutex;

    use js_sys::{Array, Function, Object, Reflect};
    use wasm_bindgen::prelude::*;
    pub use wasm_bindgen_rayon::init_thread_pool;

    /// The name of the BroadcastChannel of [`set_progress_channel`], shared by the threads.
    static CHANNEL: Mutex<Option<String>> = Mutex::new(None);

    /// Sets (or, with `null`, clears) the name of the BroadcastChannel to which the long
    /// calls post `{stage}` as they begin each stage, and `{panic}` (the message) when one
    /// of the pool's threads panics, from whichever thread that happens on.
    #[wasm_bindgen(js_name = setProgressChannel)]
    pub fn set_progress_channel(name: Option<String>) {
        *CHANNEL.lock().unwrap_or_else(|e| e.into_inner()) = name;
    }

    /// Posts `{key: value}` to the channel, if one is set (quietly nothing where the
    /// global has no BroadcastChannel).
    pub(crate) fn broadcast(key: &str, value: &str) {
        let Some(name) = CHANNEL.lock().unwrap_or_else(|e| e.into_inner()).clone() else {
            return;
        };
        let _ = post(&name, key, value);
    }

    fn post(name: &str, key: &str, value: &str) -> Result<(), JsValue> {
        let global = js_sys::global();
        let class: Function = Reflect::get(&global, &"BroadcastChannel".into())?.dyn_into()?;
        let channel = Reflect::construct(&class, &Array::of1(&name.into()))?;
        let message = Object::new();
        Reflect::set(&message, &key.into(), &value.into())?;
        let method = |m: &str| -> Result<Function, JsValue> {
            Reflect::get(&channel, &m.into())?.dyn_into()
        };
        method("postMessage")?.call1(&channel, &message)?;
        // A message posted is on its way to the other channels of that name: closing
        // this end loses nothing.
        method("close")?.call0(&channel)?;
        Ok(())
    }

    /// Panics on one of the pool's threads, to test that such a panic reaches the
    /// listener of the progress channel.
    #[doc(hidden)]
    #[wasm_bindgen(js_name = __panicInPoolForTest)]
    pub fn panic_in_pool_for_test() {
        rayon::join(|| panic!("a test panic in the pool"), || ());
    }
}

/// The message of the last panic, if any, cleared by reading it.
#[wasm_bindgen(js_name = lastPanic)]
pub fn last_panic() -> Option<String> {
    PANIC.with(|p| p.borrow_mut().take())
}

/// Panics, to test that a panic reaches JavaScript as an `Error` with its message.
#[doc(hidden)]
#[wasm_bindgen(js_name = __panicForTest)]
pub fn panic_for_test() {
    panic!("a test panic");
}

fn js_err(e: Error) -> JsError {
    JsError::new(&e.to_string())
}

fn bad(msg: impl AsRef<str>) -> JsError {
    JsError::new(msg.as_ref())
}

/// A mesh from flat arrays, validated (finite coordinates, indices in range).
fn mesh(positions: &[f64], index: &[u32]) -> Result<Mesh, JsError> {
    if positions.len() % 3 != 0 {
        return Err(bad(format!(
            "positions must hold three numbers per vertex, got {} numbers",
            positions.len()
        )));
    }
    if index.len() % 3 != 0 {
        return Err(bad(format!(
            "index must hold three vertex indices per triangle, got {} indices",
            index.len()
        )));
    }
    let p = positions.chunks_exact(3).map(|c| [c[0], c[1], c[2]]);
    let t = index.chunks_exact(3).map(|c| [c[0], c[1], c[2]]);
    let m = Mesh::new(p.collect(), t.collect()).map_err(js_err)?;
    m.validate().map_err(js_err)?;
    Ok(m)
}

/// A plain JavaScript object built key by key.
struct Out(Object);

impl Out {
    fn new() -> Self {
        Out(Object::new())
    }

    fn set(self, key: &str, value: impl Into<JsValue>) -> Self {
        // Setting a property of a fresh plain object cannot fail.
        let _ = Reflect::set(&self.0, &JsValue::from_str(key), &value.into());
        self
    }

    fn mesh(self, m: &Mesh) -> Self {
        let p = m.positions().as_flattened();
        let t = m.triangles().as_flattened();
        self.set("positions", Float64Array::from(p))
            .set("index", Uint32Array::from(t))
    }

    /// Polylines under `key` (a `Float64Array` each, three numbers per point) and their
    /// `closed` flags (1 for loops).
    fn polylines(self, key: &str, lines: &[meshbool::ops::PolylineXyz]) -> Self {
        let arr = Array::new();
        for l in lines {
            arr.push(&Float64Array::from(l.points.as_flattened()));
        }
        let closed: Vec<u8> = lines.iter().map(|l| u8::from(l.closed)).collect();
        self.set(key, arr)
            .set("closed", Uint8Array::from(&closed[..]))
    }

    fn report(self, report: &impl serde::Serialize) -> Result<Self, JsError> {
        let text = serde_json::to_string(report).map_err(|e| bad(e.to_string()))?;
        Ok(self.set("report", text))
    }

    fn done(self) -> JsValue {
        self.0.into()
    }
}

/// The options object's JSON text, parsed (empty text: no options).
fn options(text: &str) -> Result<Value, JsError> {
    if text.trim().is_empty() {
        return Ok(Value::Object(Default::default()));
    }
    let v: Value = serde_json::from_str(text).map_err(|e| bad(format!("bad options: {e}")))?;
    if !v.is_object() {
        return Err(bad("options must be an object"));
    }
    Ok(v)
}

fn flag(o: &Value, key: &str, default: bool) -> Result<bool, JsError> {
    match o.get(key) {
        None | Some(Value::Null) => Ok(default),
        Some(Value::Bool(b)) => Ok(*b),
        Some(v) => Err(bad(format!("option {key} must be true or false, got {v}"))),
    }
}

fn number(o: &Value, key: &str) -> Result<Option<f64>, JsError> {
    match o.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Number(n)) => Ok(n.as_f64()),
        Some(v) => Err(bad(format!("option {key} must be a number, got {v}"))),
    }
}

/// The operand checks from options `force`, `selfCheck`, `resolve`, `orient` (all on but
/// `force` by default, as on the command line).
fn checks(o: &Value) -> Result<Checks, JsError> {
    Ok(Checks {
        self_intersections: flag(o, "selfCheck", true)?,
        resolve: flag(o, "resolve", true)?,
        orient: flag(o, "orient", true)?,
        force: flag(o, "force", false)?,
        ..Checks::default()
    })
}

fn provenance_arrays(out: Out, prov: &[meshbool::Provenance]) -> Out {
    let source: Vec<u8> = prov
        .iter()
        .map(|p| u8::from(p.source == Source::B))
        .collect();
    let triangle: Vec<u32> = prov.iter().map(|p| p.triangle).collect();
    let flipped: Vec<u8> = prov.iter().map(|p| u8::from(p.flipped)).collect();
    out.set("source", Uint8Array::from(&source[..]))
        .set("triangle", Uint32Array::from(&triangle[..]))
        .set("flipped", Uint8Array::from(&flipped[..]))
}

/// A boolean of two meshes: `{positions, index, source, triangle, flipped, report}`
/// (`source[t]`: 0 when result triangle `t` comes from A, 1 from B; `triangle[t]`: the
/// input triangle it is part of; `flipped[t]`: 1 when reversed). `op`: `union`,
/// `intersection` (`intersect`), `difference` (`subtract`), `reverse-difference`.
/// Options (JSON): `force`, `selfCheck`, `resolve`, `orient`, `keepNonmanifold`, `snap`
/// (a tolerance, [`BooleanOptions::snap`]), `sliverGuard`
/// ([`BooleanOptions::sliver_guard`]), `keepSeamPoints`
/// ([`BooleanOptions::keep_seam_points`]; **true** by default here, unlike the library:
/// the reference library's contract is that a boolean equals its merged split groups,
/// which keep every seam point; `false` turns the exact clean-up on), `coplanarRefinement`
/// ([`BooleanOptions::coplanar_refinement`]; **true** by default here, for the same
/// contract: the reference's shared faces hold the common refinement of both
/// triangulations; `false` for their boundaries only, fewer triangles).
#[wasm_bindgen]
pub fn boolean(
    a_positions: &[f64],
    a_index: &[u32],
    b_positions: &[f64],
    b_index: &[u32],
    op: &str,
    opts: &str,
) -> Result<JsValue, JsError> {
    let (a, b) = (mesh(a_positions, a_index)?, mesh(b_positions, b_index)?);
    let op: Op = op.parse().map_err(js_err)?;
    let o = options(opts)?;
    let opts = BooleanOptions {
        checks: checks(&o)?,
        keep_nonmanifold: flag(&o, "keepNonmanifold", false)?,
        keep_seam_points: flag(&o, "keepSeamPoints", true)?,
        snap: number(&o, "snap")?.unwrap_or(0.0),
        sliver_guard: flag(&o, "sliverGuard", false)?,
        coplanar_refinement: flag(&o, "coplanarRefinement", true)?,
        run: run_options(),
        ..BooleanOptions::default()
    };
    let out = ops::boolean(&a, &b, op, &opts).map_err(js_err)?;
    let res = Out::new().mesh(&out.mesh).report(&out.report())?;
    Ok(provenance_arrays(res, &out.provenance).done())
}

/// Splits two meshes along their intersection: `{groups, report}` where `groups` is an
/// array of `{name, positions, index, source, triangle, flipped}`, one per group of the
/// library (`a_in_b`, `a_out_b`, `b_in_a`, `b_out_a` and the four coplanar groups), each
/// group's mesh welded. Options as for [`boolean`].
#[wasm_bindgen]
pub fn split(
    a_positions: &[f64],
    a_index: &[u32],
    b_positions: &[f64],
    b_index: &[u32],
    opts: &str,
) -> Result<JsValue, JsError> {
    let (a, b) = (mesh(a_positions, a_index)?, mesh(b_positions, b_index)?);
    let o = options(opts)?;
    let opts = SplitOptions {
        checks: checks(&o)?,
        snap: number(&o, "snap")?.unwrap_or(0.0),
        keep_seam_points: flag(&o, "keepSeamPoints", true)?,
        sliver_guard: flag(&o, "sliverGuard", false)?,
        coplanar_refinement: flag(&o, "coplanarRefinement", true)?,
        run: run_options(),
        ..SplitOptions::default()
    };
    let out = ops::split(&a, &b, &opts).map_err(js_err)?;
    let groups = Array::new();
    for g in &out.groups {
        let item = Out::new().set("name", g.group.name()).mesh(&g.mesh);
        groups.push(&provenance_arrays(item, &g.provenance).done());
    }
    Ok(Out::new()
        .set("groups", groups)
        .report(&out.report(Format::PlyBinaryLe))?
        .done())
}

/// The names of the groups a boolean keeps and whether each is reversed, as
/// `"name"` or `"name:flip"` (`op` as for [`boolean`]).
#[wasm_bindgen(js_name = groupsForOp)]
pub fn groups_for_op(op: &str) -> Result<Vec<String>, JsError> {
    let op: Op = op.parse().map_err(js_err)?;
    Ok(ops::PieceSpec::for_op(op)
        .iter()
        .map(|s| {
            let name = s.group.name();
            if s.flip {
                format!("{name}:flip")
            } else {
                name.to_string()
            }
        })
        .collect())
}

/// The raw intersection segments of two meshes, exact points rounded once:
/// `{segments, triA, triB, coplanar}`: `segments` six numbers per segment (its two ends),
/// `triA`/`triB` the triangle of each input it lies in (a segment along an edge is listed
/// once per pair of triangles it lies in), `coplanar[s]` 1 for segments of coplanar
/// overlaps. Options (JSON): `withCoplanar` (default true), `coplanarRefinement` (as for
/// [`boolean`]: default true, every edge of either mesh that crosses a coplanar overlap
/// gives its segments, as the reference's tagged segments do). With `b_positions` and
/// `b_index` empty, the self-intersections of A (`triA`, `triB` both triangles of A).
#[wasm_bindgen]
pub fn intersect(
    a_positions: &[f64],
    a_index: &[u32],
    b_positions: &[f64],
    b_index: &[u32],
    opts: &str,
) -> Result<JsValue, JsError> {
    let a = mesh(a_positions, a_index)?;
    let o = options(opts)?;
    let with_coplanar = flag(&o, "withCoplanar", true)?;
    let out = if b_positions.is_empty() && b_index.is_empty() {
        let copts = CurvesOptions {
            with_coplanar,
            ..CurvesOptions::default()
        };
        ops::self_curves(&a, &copts)
    } else {
        let copts = CurvesOptions {
            coplanar_refinement: flag(&o, "coplanarRefinement", true)?,
            ..CurvesOptions::default()
        };
        ops::curves(&a, &mesh(b_positions, b_index)?, &copts)
    }
    .map_err(js_err)?;
    let (mut segments, mut tri_a, mut tri_b, mut coplanar) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for s in out.tagged_segments() {
        if s.coplanar && !with_coplanar {
            continue;
        }
        segments.extend_from_slice(&s.p0);
        segments.extend_from_slice(&s.p1);
        tri_a.push(s.tri_a);
        tri_b.push(s.tri_b);
        coplanar.push(u8::from(s.coplanar));
    }
    Ok(Out::new()
        .set("segments", Float64Array::from(&segments[..]))
        .set("triA", Uint32Array::from(&tri_a[..]))
        .set("triB", Uint32Array::from(&tri_b[..]))
        .set("coplanar", Uint8Array::from(&coplanar[..]))
        .report(&out.report())?
        .done())
}

/// The intersection curves of two meshes (or of one mesh with itself when `b_positions`
/// is empty), chained into polylines: `{polylines, closed, report}` (`polylines`: an array
/// of `Float64Array`s, three numbers per point; `closed[i]` 1 for loops). Options (JSON):
/// `withCoplanar` (default false).
#[wasm_bindgen]
pub fn curves(
    a_positions: &[f64],
    a_index: &[u32],
    b_positions: &[f64],
    b_index: &[u32],
    opts: &str,
) -> Result<JsValue, JsError> {
    let a = mesh(a_positions, a_index)?;
    let o = options(opts)?;
    let copts = CurvesOptions {
        with_coplanar: flag(&o, "withCoplanar", false)?,
        ..CurvesOptions::default()
    };
    let out = if b_positions.is_empty() && b_index.is_empty() {
        ops::self_curves(&a, &copts)
    } else {
        ops::curves(&a, &mesh(b_positions, b_index)?, &copts)
    }
    .map_err(js_err)?;
    Ok(Out::new()
        .polylines("polylines", &out.polylines)
        .report(&out.report())?
        .done())
}

/// A mesh cut where it crosses itself (`ops::self_arrangement`), nothing classified:
/// `{positions, index, parent}` (`parent[t]`: the input triangle of piece `t`).
#[wasm_bindgen(js_name = selfArrange)]
pub fn self_arrange(positions: &[f64], index: &[u32]) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let out = ops::self_arrangement(&m).map_err(js_err)?;
    Ok(Out::new()
        .mesh(&out.mesh)
        .set("parent", Uint32Array::from(&out.parent[..]))
        .done())
}

/// Cut and fill between a design surface and a topography: `{lines, closed, report}`
/// (`lines`: the zero-thickness polylines, three numbers per point; the report as
/// `meshbool cutfill --json`).
#[wasm_bindgen]
pub fn cutfill(
    d_positions: &[f64],
    d_index: &[u32],
    t_positions: &[f64],
    t_index: &[u32],
) -> Result<JsValue, JsError> {
    let (d, t) = (mesh(d_positions, d_index)?, mesh(t_positions, t_index)?);
    let out = ops::cutfill(&d, &t, &ops::CutFillOptions::default()).map_err(js_err)?;
    Ok(Out::new()
        .polylines("lines", &out.lines)
        .report(&out.report())?
        .done())
}

/// Where points (three numbers each) lie against a mesh: `{classes, winding, report}`,
/// `classes[i]` 0 outside, 1 inside, 2 exactly on the surface; `winding[i]` the winding
/// number. Options (JSON) as for [`boolean`]'s operand checks.
#[wasm_bindgen]
pub fn classify(
    positions: &[f64],
    index: &[u32],
    points: &[f64],
    opts: &str,
) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    if points.len() % 3 != 0 {
        return Err(bad("points must hold three numbers per point"));
    }
    let pts: Vec<[f64; 3]> = points.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let o = options(opts)?;
    let copts = ops::ClassifyOptions {
        checks: checks(&o)?,
        ..Default::default()
    };
    let out = ops::classify_points(&m, &pts, &copts).map_err(js_err)?;
    let classes: Vec<u8> = out.classes.iter().map(|c| c.code()).collect();
    Ok(Out::new()
        .set("classes", Uint8Array::from(&classes[..]))
        .set("winding", Float64Array::from(&out.winding[..]))
        .report(&out.report(false))?
        .done())
}

/// Merges picked pieces into one mesh the way `meshbool pick` does: welded exactly, with
/// edges used by more than two triangles split apart (unless `keep_nonmanifold`). With
/// `dedupe`, exactly coincident triangles are removed first (same orientation: one kept;
/// opposite orientations: the pair cancels, a zero-thickness wall). `{positions, index,
/// duplicates, report}` (`duplicates`: triangles removed by `dedupe`).
#[wasm_bindgen]
pub fn merge(
    positions: &[f64],
    index: &[u32],
    keep_nonmanifold: bool,
    dedupe: bool,
) -> Result<JsValue, JsError> {
    let mut m = mesh(positions, index)?;
    let mut removed = 0;
    if dedupe {
        let (d, r) = meshbool::repair::remove_duplicates(&meshbool::weld_exact(&m).mesh);
        removed = r.same_orientation_removed + r.anti_parallel_removed;
        m = d;
    }
    let out = ops::pick(
        &[(&m, false)],
        &PickOptions {
            keep_nonmanifold,
            ..PickOptions::default()
        },
    )
    .map_err(js_err)?;
    Ok(Out::new()
        .mesh(&out.mesh)
        .set("duplicates", removed as u32)
        .report(&out.report())?
        .done())
}

/// Triangulates a closed polygon loop in 3-D (three numbers per point, not repeating the
/// first), as meshbool caps holes (ear clipping in the loop's Newell plane): the triangles
/// as indices into the loop, wound as the loop runs. Empty for fewer than three points.
#[wasm_bindgen(js_name = triangulateLoop)]
pub fn triangulate_loop(points: &[f64]) -> Result<Vec<u32>, JsError> {
    let n = points.len() / 3;
    if points.len() % 3 != 0 {
        return Err(bad("a loop needs three numbers per point"));
    }
    if n < 3 {
        return Ok(Vec::new());
    }
    // A cone over the loop (apex off its plane) has the loop as its one boundary; capping
    // that boundary triangulates the loop. The cap runs against the cone, so against the
    // loop: its triangles are turned back.
    let mut p: Vec<[f64; 3]> = points.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let (mut c, mut nn) = ([0.0; 3], [0.0; 3]);
    for i in 0..n {
        let (a, b) = (p[i], p[(i + 1) % n]);
        for k in 0..3 {
            c[k] += a[k] / n as f64;
        }
        nn[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nn[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nn[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let size = p
        .iter()
        .map(|q| (0..3).map(|k| (q[k] - c[k]).abs()).fold(0.0, f64::max))
        .fold(1.0, f64::max);
    let len = (nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]).sqrt();
    let dir = if len > 0.0 {
        nn.map(|x| x / len)
    } else {
        [0.0, 0.0, 1.0]
    };
    p.push([0, 1, 2].map(|k| c[k] + dir[k] * size));
    let apex = n as u32;
    let cone = (0..n as u32)
        .map(|i| [apex, i, (i + 1) % n as u32])
        .collect();
    let m = Mesh::new(p, cone).map_err(js_err)?;
    m.validate().map_err(js_err)?;
    let (capped, _) = meshbool::repair::cap_holes(&m);
    Ok(capped.triangles()[n..]
        .iter()
        .flat_map(|t| [t[0], t[2], t[1]])
        .collect())
}

/// The solid a self-overlapping mesh encloses under a fill rule (`positive`, `nonzero`,
/// `evenodd`): `{positions, index, parent, report}` (`parent[t]`: the input triangle of
/// result triangle `t`).
#[wasm_bindgen]
pub fn resolve(
    positions: &[f64],
    index: &[u32],
    rule: &str,
    keep_nonmanifold: bool,
) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let opts = ResolveOptions {
        rule: rule.parse::<FillRule>().map_err(js_err)?,
        keep_nonmanifold,
        run: run_options(),
        ..ResolveOptions::default()
    };
    let out = ops::resolve(&m, &opts).map_err(js_err)?;
    Ok(Out::new()
        .mesh(&out.mesh)
        .set("parent", Uint32Array::from(&out.parent[..]))
        .report(&out.report())?
        .done())
}

/// The `upper` or `lower` envelope of an open surface that folds over itself (terrain):
/// `{positions, index, parent, report}` (`parent[t]`: the input triangle of result
/// triangle `t`; for a jump wall, the triangle it hangs from).
#[wasm_bindgen]
pub fn envelope(positions: &[f64], index: &[u32], side: &str) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let opts = ops::EnvelopeOptions {
        side: side.parse::<ops::Envelope>().map_err(js_err)?,
        ..ops::EnvelopeOptions::default()
    };
    let out = ops::envelope(&m, &opts).map_err(js_err)?;
    Ok(Out::new()
        .mesh(&out.mesh)
        .set("parent", Uint32Array::from(&out.parent[..]))
        .report(&out.report())?
        .done())
}

/// The repair pipeline, configured by the JSON of the library's `RepairConfig`
/// (`docs/json.md`): `{positions, index, report}`.
#[wasm_bindgen]
pub fn repair(positions: &[f64], index: &[u32], config: &str) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let config: RepairConfig = if config.trim().is_empty() {
        RepairConfig::default()
    } else {
        serde_json::from_str(config).map_err(|e| bad(format!("not a repair configuration: {e}")))?
    };
    let out = ops::repair(&m, &config).map_err(js_err)?;
    Ok(Out::new().mesh(&out.mesh).report(&out.report())?.done())
}

/// Closes an open mesh into a solid: `mode` `cap`, `stitch`, `curtain` or
/// `stitch+curtain`; options (JSON) `floorOffset`, `maxGap`. `{positions, index, report}`.
#[wasm_bindgen]
pub fn close(positions: &[f64], index: &[u32], mode: &str, opts: &str) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let mode: CloseMode = mode.parse().map_err(js_err)?;
    let o = options(opts)?;
    let copts = CloseOptions {
        stitch_max_gap: number(&o, "maxGap")?,
        floor_offset: number(&o, "floorOffset")?.unwrap_or(CloseOptions::default().floor_offset),
    };
    let out = ops::close(&m, mode, &copts).map_err(js_err)?;
    Ok(Out::new().mesh(&out.mesh).report(&out.report())?.done())
}

/// Consistent orientation, each component facing `majority`, `z-up` or `outward`:
/// `{positions, index, report}`.
#[wasm_bindgen]
pub fn orient(positions: &[f64], index: &[u32], facing: &str) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let facing: Facing = facing.parse().map_err(js_err)?;
    let out = ops::orient(&m, facing).map_err(js_err)?;
    Ok(Out::new().mesh(&out.mesh).report(&out.report())?.done())
}

/// The measures of a mesh as the JSON of `meshbool info` (its `stats`), after an exact
/// weld (vertices with equal coordinates are one vertex, as every operation takes them).
#[wasm_bindgen]
pub fn info(positions: &[f64], index: &[u32]) -> Result<String, JsError> {
    let m = meshbool::weld_exact(&mesh(positions, index)?).mesh;
    let stats = ops::info(&m).map_err(js_err)?;
    serde_json::to_string(&stats).map_err(|e| bad(e.to_string()))
}

/// `[volume, area, closed (0 or 1), boundary edges, non-manifold edges]` of a mesh, as
/// is (not welded): the cheap measures every result carries.
#[wasm_bindgen]
pub fn measures(positions: &[f64], index: &[u32]) -> Result<Vec<f64>, JsError> {
    let m = mesh(positions, index)?;
    let r = Measures::of(&m);
    Ok(vec![
        r.volume,
        r.area,
        f64::from(u8::from(r.closed && !r.empty)),
        r.boundary_edges as f64,
        r.non_manifold_edges as f64,
    ])
}

/// Welds vertices: exactly equal ones when `tolerance` is 0, else within `tolerance`.
/// `{positions, index, map}` (`map[v]`: the new index of input vertex `v`; with a
/// tolerance, triangles that collapse are dropped and `map` is absent).
#[wasm_bindgen]
pub fn weld(positions: &[f64], index: &[u32], tolerance: f64) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(bad(format!(
            "the weld tolerance must be a finite number ≥ 0, got {tolerance}"
        )));
    }
    if tolerance == 0.0 {
        let w = meshbool::weld_exact(&m);
        return Ok(Out::new()
            .mesh(&w.mesh)
            .set("map", Uint32Array::from(&w.vertex_map[..]))
            .done());
    }
    let (welded, report) = meshbool::repair::weld_within(&m, tolerance);
    Ok(Out::new().mesh(&welded).report(&report)?.done())
}

/// The library's vertex-identity rule for soups (`ops::weld_rounding_noise`): exactly
/// equal positions are one vertex, and boundary positions within rounding noise of each
/// other are merged where that opens no edge and makes none non-manifold
/// (nor, with `keep_consistent`, inconsistently wound). Triangles keep their places and
/// count. `{positions, index, merged}` (`merged`: boundary vertices merged, 0 if none).
#[wasm_bindgen]
pub fn condition(
    positions: &[f64],
    index: &[u32],
    keep_consistent: bool,
) -> Result<JsValue, JsError> {
    let m = mesh(positions, index)?;
    let (welded, merge) = ops::weld_rounding_noise(&m, keep_consistent);
    Ok(Out::new()
        .mesh(&welded)
        .set("merged", merge.map_or(0, |n| n.vertices) as u32)
        .done())
}

/// Edge-connected components of a mesh welded exactly: `{count, ids}` (`ids[t]`: the
/// component of triangle `t`, numbered in order of first triangle).
#[wasm_bindgen]
pub fn components(positions: &[f64], index: &[u32]) -> Result<JsValue, JsError> {
    let m = meshbool::weld_exact(&mesh(positions, index)?).mesh;
    let (count, ids) = EdgeTopology::new(&m).components();
    Ok(Out::new()
        .set("count", count as u32)
        .set("ids", Uint32Array::from(&ids[..]))
        .done())
}

/// The boundary loops of a mesh welded exactly: `{positions, loops, nonManifold}`
/// (`loops`: an array of `Uint32Array`s of vertex indices into the welded `positions`;
/// `nonManifold`: edges used by more than two triangles).
#[wasm_bindgen(js_name = boundaryLoops)]
pub fn boundary_loops(positions: &[f64], index: &[u32]) -> Result<JsValue, JsError> {
    let m = meshbool::weld_exact(&mesh(positions, index)?).mesh;
    let (loops, non_manifold) = meshbool::repair::boundary_loops(&m);
    let arr = Array::new();
    for l in &loops {
        arr.push(&Uint32Array::from(&l[..]));
    }
    Ok(Out::new()
        .set(
            "positions",
            Float64Array::from(m.positions().as_flattened()),
        )
        .set("loops", arr)
        .set("nonManifold", non_manifold as u32)
        .done())
}

/// True when this build reads `format` from bytes: the readers behind a feature left out
/// of the build answer with [`Error::InvalidParameter`] whatever the bytes, and a Surpac
/// DTM is never read from its `.dtm` alone (its points are in the `.str` beside it).
/// Asking the readers themselves keeps one list, the library's, whatever the features.
fn reads(format: Format) -> bool {
    format != Format::SurpacDtm
        && !matches!(
            meshbool::io::read_bytes(b"?", format),
            Err(Error::InvalidParameter(_))
        )
}

/// The formats [`read`] reads in this build, in the order of [`Format::NAMES`]: `{name,
/// extension, label}` each (`name` as `read` takes it, `extension` without its dot,
/// `label` as the library's messages name it: `binary STL`, `OBJ`, ...).
#[wasm_bindgen(js_name = readFormats)]
pub fn read_formats() -> Array {
    let list = Array::new();
    for (name, format) in Format::NAMES.into_iter().filter(|(_, f)| reads(*f)) {
        let item = Out::new()
            .set("name", name)
            .set("extension", format.extension())
            .set("label", format.to_string());
        list.push(&item.done());
    }
    list
}

/// What this build reads, for error messages: the formats' extensions (`.stl .obj ...`)
/// or, with `names`, the names `read` takes (`stl, stl-ascii, obj, ...`).
fn readable(names: bool) -> String {
    let mut list: Vec<String> = Vec::new();
    for (name, format) in Format::NAMES.into_iter().filter(|(_, f)| reads(*f)) {
        let item = if names {
            name.to_string()
        } else {
            format!(".{}", format.extension())
        };
        if !list.contains(&item) {
            list.push(item);
        }
    }
    list.join(if names { ", " } else { " " })
}

/// Reads a mesh file's bytes: `{positions, index, format}`. `format`: a format's name
/// (`stl`, `obj`, `ply`, ... as [`read_formats`] lists them), a file name (its extension
/// is the hint; an extension no format has leaves the format to the bytes), or empty to
/// detect the format from the bytes. A format this build does not read, or bytes that fit
/// none, is an error listing the formats it reads.
#[wasm_bindgen]
pub fn read(bytes: &[u8], format: &str) -> Result<JsValue, JsError> {
    let hint = if format.is_empty() {
        None
    } else if format.contains('.') {
        Format::for_path(format)
    } else {
        let named = format.parse::<Format>().ok();
        Some(named.ok_or_else(|| {
            bad(format!(
                "unknown format {format:?}: this build reads {}",
                readable(true)
            ))
        })?)
    };
    let format = meshbool::io::detect_format(bytes, hint).ok_or_else(|| {
        bad(format!(
            "cannot tell the file's format from its contents; this build reads {} files",
            readable(false)
        ))
    })?;
    if !reads(format) {
        return Err(bad(format!(
            "{format} files are not read by this build of meshbool; it reads {} files",
            readable(false)
        )));
    }
    let m = meshbool::io::read_bytes(bytes, format).map_err(js_err)?;
    Ok(Out::new().mesh(&m).set("format", format.name()).done())
}

/// A mesh file's bytes in `format` (`stl`, `obj`, `ply`, ...).
#[wasm_bindgen]
pub fn write(positions: &[f64], index: &[u32], format: &str) -> Result<Vec<u8>, JsError> {
    let m = mesh(positions, index)?;
    let format: Format = format.parse().map_err(js_err)?;
    let mut bytes = Vec::new();
    meshbool::io::write(&mut bytes, &m, format).map_err(js_err)?;
    Ok(bytes)
}

/// The shape `name` with its options (JSON; every option has a default, those of
/// `meshbool make`): `cube` (`center` [0,0,0] and `size` 1 — a number or three — or
/// `min` and `max`), `sphere` (`center` [0,0,0], `radius` 1, `segments` 32, `rings` 16),
/// `cylinder` (`base` [0,0,0], `radius` 1, `height` 1, `segments` 32), `cone` (as the
/// cylinder, with `topRadius` 0, also spelled `top_radius` as CSG documents do), `plane` (`center` [0,0,0], `width` 1, `depth` 1, `nx` 1,
/// `ny` 1), `terrain` (`center` [0,0,0], `size` [1000,1000], `cells` [100,100], `relief`
/// 40, `seed` 1) and `pit` (`center` [0,0,60], `radius` [220,160], `depth` 140, `benches`
/// 5, `berm` 8, `segments` 64): the pit crosses the terrain, its rim above the ground all
/// round. `size`, `cells` and the pit's `radius` take one number for both axes.
fn shape(name: &str, o: &Value) -> Result<ops::Shape, JsError> {
    use ops::{Shape, ShapeJsonError, ShapeKeys};
    let none = serde_json::Map::new();
    let obj = match o {
        Value::Object(m) => m,
        _ => &none,
    };
    Shape::from_json(name, obj, ShapeKeys::Js, &[]).map_err(|e| match e {
        ShapeJsonError::UnknownShape(name) => bad(format!(
            "unknown shape {name:?}: cube, sphere, cylinder, cone, plane, terrain or pit"
        )),
        ShapeJsonError::UnknownKey { key, known } => bad(format!(
            "{name} takes no option {key:?} (its options: {})",
            known.join(", ")
        )),
        ShapeJsonError::Value { key, message } => bad(format!("option {key} {message}")),
        ShapeJsonError::Keys(message) => bad(message),
    })
}

/// A generated shape (`meshbool make`): `{positions, index, report}` (the report as
/// `meshbool make --json`: the shape's name, measures and bounding box). `name` and the
/// options (JSON) as for [`shape`]. Parameters out of range (a radius ≤ 0, too few
/// segments, a shape too fine for `f64`) are errors with the library's message.
#[wasm_bindgen]
pub fn make(name: &str, opts: &str) -> Result<JsValue, JsError> {
    let o = options(opts)?;
    let out = ops::make(&shape(name, &o)?).map_err(js_err)?;
    Ok(Out::new().mesh(&out.mesh).report(&out.report())?.done())
}

/// Results of CSG nodes by key, kept between calls of [`csg`] (in memory).
#[wasm_bindgen]
pub struct CsgCache(meshbool::csg::Cache);

#[wasm_bindgen]
impl CsgCache {
    /// An empty cache.
    #[wasm_bindgen(constructor)]
    #[allow(clippy::new_without_default)]
    pub fn new() -> CsgCache {
        CsgCache(meshbool::csg::Cache::new())
    }

    /// Results held.
    pub fn size(&self) -> usize {
        self.0.len()
    }

    /// Forgets every result.
    pub fn clear(&self) {
        self.0.clear();
    }
}

/// A CSG document evaluated (`meshbool::csg::evaluate`): `text` its JSON, whose mesh
/// leaves name by index (`{"mesh": K}`) the meshes in memory given as one array of
/// positions and one of indices, `vertices[k]` and `triangles[k]` the counts of mesh `k`
/// (its indices counted from its own first vertex); mesh files are not read here.
/// `{positions, index, report}`, without `positions` and `index` when a node failed (the
/// report's `failed` names it). Options (JSON): `force`, `selfCheck`, `resolve`,
/// `orient`, `keepNonmanifold`, `keepSeamPoints` (false by default, as in the library),
/// `snap`.
#[wasm_bindgen]
pub fn csg(
    text: &str,
    positions: &[f64],
    index: &[u32],
    vertices: &[u32],
    triangles: &[u32],
    cache: &CsgCache,
    opts: &str,
) -> Result<JsValue, JsError> {
    if vertices.len() != triangles.len() {
        return Err(bad("one vertex count and one triangle count per mesh"));
    }
    let (mut p, mut t) = (0usize, 0usize);
    let mut meshes = Vec::with_capacity(vertices.len());
    for (&nv, &nt) in vertices.iter().zip(triangles) {
        let (nv, nt) = (3 * nv as usize, 3 * nt as usize);
        if p + nv > positions.len() || t + nt > index.len() {
            return Err(bad("the meshes' counts exceed the arrays given"));
        }
        meshes.push(std::sync::Arc::new(mesh(
            &positions[p..p + nv],
            &index[t..t + nt],
        )?));
        (p, t) = (p + nv, t + nt);
    }
    let scene = meshbool::csg::Scene::from_json_with(text, std::path::Path::new(""), &meshes)
        .map_err(js_err)?;
    let o = options(opts)?;
    let opts = meshbool::csg::CsgOptions {
        boolean: BooleanOptions {
            checks: checks(&o)?,
            keep_nonmanifold: flag(&o, "keepNonmanifold", false)?,
            keep_seam_points: flag(&o, "keepSeamPoints", false)?,
            snap: number(&o, "snap")?.unwrap_or(0.0),
            run: run_options(),
            ..BooleanOptions::default()
        },
        progress: None,
        named: false,
    };
    let out = meshbool::csg::evaluate(&scene, &cache.0, &opts).map_err(js_err)?;
    let report = out.report();
    let res = match &out.mesh {
        Some(m) => Out::new().mesh(m),
        None => Out::new(),
    };
    Ok(res.report(&report)?.done())
}

/// The library's version.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use meshbool::Group;

    #[test]
    fn the_readers_of_every_build_are_listed_and_a_dtm_alone_never() {
        for f in [
            Format::StlBinary,
            Format::Obj,
            Format::PlyAscii,
            Format::Dxf,
            Format::JsonSoup,
            Format::Glb,
            Format::Off,
        ] {
            assert!(reads(f), "{f}");
        }
        assert!(!reads(Format::SurpacDtm));
        assert!(readable(false).starts_with(".stl .obj .ply .dxf .json .glb"));
        assert!(readable(true).starts_with("stl, stl-ascii, obj, ply,"));
    }

    #[test]
    fn shapes_take_meshbool_makes_defaults() {
        let none = Value::Object(Default::default());
        let made = |name| shape(name, &none).ok().and_then(|s| s.mesh().ok());
        let counts = [
            "cube", "sphere", "cylinder", "cone", "plane", "terrain", "pit",
        ]
        .map(|n| made(n).map_or(0, |m| m.triangle_count()));
        assert_eq!(counts, [12, 960, 128, 64, 2, 20000, 1216]);
    }

    #[test]
    fn groups_for_each_op_are_named() {
        let union = groups_for_op("union").unwrap_or_default();
        assert!(union.iter().any(|g| g == Group::AOutB.name()));
        let diff = groups_for_op("subtract").unwrap_or_default();
        assert!(diff.iter().any(|g| g == "b_in_a:flip"), "{diff:?}");
    }
}
