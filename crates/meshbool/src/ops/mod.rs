//! The front door: one function per command, shared by every front end (the `meshbool`
//! command-line tool, the Python and JavaScript packages, and Rust code calling the library).
//!
//! Each function takes its inputs and an options struct and returns an output: the result
//! mesh (or meshes) with what was found, assumed and measured. Each output's `report()` is
//! a serialisable struct whose JSON is exactly what the CLI prints with `--json`
//! (documented with every key in `docs/json.md`; [`SCHEMA`] is its version).
//!
//! | command | function | output | report |
//! |---|---|---|---|
//! | `union`, `intersection`, `difference` | [`boolean`] | [`BooleanOutput`] | [`BooleanReport`] |
//! | `split` | [`split`] | [`SplitOutput`] | [`SplitReport`] (the split's `manifest.json`) |
//! | `pick` | [`pick`], [`SplitOutput::pick`], [`pick_dir`] | [`PickOutput`] | [`PickReport`] |
//! | `curves` | [`curves`] | [`CurvesOutput`] | [`CurvesReport`] |
//! | `info` | [`info`] | [`MeshStats`](crate::measure::MeshStats) | [`InfoReport`] |
//! | `orient` | [`orient`] | [`OrientOutput`] | [`OrientCommandReport`] |
//! | `close` | [`close`] | [`CloseOutput`] | [`CloseCommandReport`] |
//! | `repair` | [`repair`], [`repair_with`] | [`RepairOutput`] | [`RepairCommandReport`] |
//! | `transform` | [`transform()`] | [`TransformOutput`] | [`TransformReport`] |
//! | `make` | [`make()`] | [`MakeOutput`] | [`MakeReport`] |
//! | `classify` | [`classify_points`] | [`ClassifyOutput`] | [`ClassifyReport`] |
//! | `cutfill` | [`cutfill()`] | [`CutFillOutput`] | [`CutFillReport`] |
//! | `convert` | [`read`], [`write()`] | | |
//!
//! Inputs are plain [`Mesh`]es, checked at the door: non-finite
//! coordinates are an [`Error`], never a panic. Functions of two meshes take anything that
//! is an [`Input`]: a `&Mesh`, checked and exactly welded on the way in as their options'
//! [`Checks`] say, or an [`Operand`] made earlier (checked once, usable many times; the
//! CLI reads its files as operands named by their paths).
//!
//! ```
//! use meshbool::ops::{boolean, BooleanOptions};
//! use meshbool::{Mesh, Op};
//!
//! let a = Mesh::unit_cube();
//! let b = Mesh::cuboid([0.5; 3], [1.5; 3]);
//! let out = boolean(&a, &b, Op::Union, &BooleanOptions::default())?;
//! let report = out.report();
//! assert_eq!(report.result.volume, 1.875);
//! assert!(report.result.closed);
//! # Ok::<(), meshbool::Error>(())
//! ```

use std::fmt;
use std::path::Path;
use std::sync::Arc;

use serde::Serialize;

use crate::boolean::Stage;
use crate::edges::EdgeCounts;
use crate::measure::{area, signed_volume};
use crate::{Error, Format, Mesh, Result};

mod boolean;
mod curves;
mod cutfill;
mod envelope;
mod make;
mod operand;
mod points;
mod single;
mod split;
mod transform;

pub use crate::boolean::FailedTriangle;
pub use boolean::{
    boolean, boolean_many, difference_many, BooleanManyOutput, BooleanOptions, BooleanOutput,
    BooleanReport, Combined,
};
pub use curves::{
    curves, self_arrangement, self_curves, CurvesOptions, CurvesOutput, CurvesReport,
    SelfArrangement, TaggedSegment,
};
pub use cutfill::{cutfill, CutFillOptions, CutFillOutput, CutFillReport};
pub use envelope::{
    envelope, Envelope, EnvelopeCommandReport, EnvelopeOptions, EnvelopeOutput, EnvelopeReport,
};
pub use make::{make, MakeOutput, MakeReport, Shape};
pub use operand::{
    weld_rounding_noise, Checks, Input, NoiseMerge, Operand, OperandReport, SelfIntersections,
    ROUNDING_ULPS,
};
pub use points::{
    classify_points, ClassifyOptions, ClassifyOutput, ClassifyReport, PointClass, PointResult,
};
pub use single::{
    close, info, orient, repair, repair_with, resolve, CloseCommandReport, CloseOutput, InfoReport,
    OrientCommandReport, OrientOutput, RepairCommandReport, RepairOutput, ResolveCommandReport,
    ResolveOptions, ResolveOutput,
};
pub use split::{
    pick, pick_dir, pick_dir_op, split, GroupInfo, GroupPieces, PickOptions, PickOutput,
    PickReport, PieceInfo, PieceSpec, SplitOptions, SplitOutput, SplitReport,
};
pub use transform::{transform, TransformOutput, TransformReport};

/// The version of the JSON reports (the `schema` key of every report). Raised when a key
/// is removed or changes meaning; new keys may appear within a version.
pub const SCHEMA: u32 = 1;

/// A progress callback: called with each [`Stage`] as it begins, on the calling thread.
#[derive(Clone)]
pub struct Progress(Arc<dyn Fn(Stage) + Send + Sync>);

impl Progress {
    /// A callback from a closure.
    pub fn new(f: impl Fn(Stage) + Send + Sync + 'static) -> Self {
        Progress(Arc::new(f))
    }
}

impl fmt::Debug for Progress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Progress(..)")
    }
}

/// A request to stop a running call, shared between the call and whoever may cancel it
/// (another thread, a signal handler, a progress callback): the call checks it as each
/// stage begins (and skips the intersection when it is set before that starts) and then
/// returns [`Error::Cancelled`], leaving nothing half done behind. Clones share the flag.
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<std::sync::atomic::AtomicBool>);

impl Cancel {
    /// A flag not set.
    pub fn new() -> Self {
        Cancel::default()
    }

    /// Asks the calls that hold this flag to stop.
    pub fn cancel(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Whether [`Cancel::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }
}

/// How an operation runs: worker threads, progress reporting and cancellation. Shared by
/// the options of every command.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Worker threads (`None` or `Some(0)`: rayon's current pool, by default one thread
    /// per core). `Some(n)` runs the call in a pool of its own of `n` threads (at most
    /// [`RunOptions::MAX_THREADS`]); a call already running in a pool of `n` threads uses it.
    /// A call on fewer than [`SERIAL_BELOW`] triangles runs on the calling thread
    /// whatever this says.
    pub threads: Option<usize>,
    /// Called as each stage begins.
    pub progress: Option<Progress>,
    /// Checked as each stage begins: once set, the call returns [`Error::Cancelled`].
    pub cancel: Option<Cancel>,
}

impl RunOptions {
    /// The most worker threads a call may ask for.
    pub const MAX_THREADS: usize = 1024;

    /// Begins `stage`: [`Error::Cancelled`] when the call was cancelled, else the
    /// progress callback is told.
    fn stage(&self, stage: Stage) -> Result<()> {
        self.check()?;
        self.report(stage);
        Ok(())
    }

    /// Tells the progress callback that `stage` begins (where the caller cannot stop:
    /// the next [`RunOptions::check`] does), unless the call was cancelled.
    fn report(&self, stage: Stage) {
        if let Some(p) = self.progress.as_ref().filter(|_| !self.cancelled()) {
            (p.0)(stage);
        }
    }

    /// [`Error::Cancelled`] when the call was cancelled.
    fn check(&self) -> Result<()> {
        match self.cancelled() {
            true => Err(Error::Cancelled),
            false => Ok(()),
        }
    }

    /// Whether the call was cancelled.
    fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(Cancel::is_cancelled)
    }

    /// The pipeline's options: this progress callback and cancellation flag, the default
    /// crossovers.
    fn pipeline(&self) -> crate::boolean::PipelineOptions<'_> {
        crate::boolean::PipelineOptions {
            progress: self.progress.as_ref().map(|p| &*p.0 as _),
            cancel: self.cancel.as_ref(),
            ..Default::default()
        }
    }
}

/// Runs `f` in a pool of `threads` worker threads (`None` or `Some(0)`: the current
/// pool). A call already on a worker of a pool that size runs directly. Errors when
/// `threads` is over [`RunOptions::MAX_THREADS`] or the threads cannot be started.
pub fn with_threads<R: Send>(threads: Option<usize>, f: impl FnOnce() -> R + Send) -> Result<R> {
    check_threads(threads)?;
    let n = match threads {
        // Inside a small call ([`with_threads_for`]): serial on this thread, as it is.
        _ if crate::par::is_serial() => return Ok(f()),
        None | Some(0) => return Ok(in_current_pool(f)),
        Some(n) => n,
    };
    if rayon::current_thread_index().is_some() && rayon::current_num_threads() == n {
        return Ok(f());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| Error::InvalidParameter(format!("cannot start {n} threads: {e}")))?;
    Ok(pool.install(|| awake(f)))
}

/// Calls on fewer triangles than this (their meshes together) run serially on the
/// calling thread, whatever their threads: moving a call into a pool and back, and
/// handing its steps to other threads, costs more than those steps save. Measured on 2
/// cores: two cubes of 12 triangles, 71 µs serially against 117 µs on two threads (130
/// µs moved into the pool from outside); 48 + 48 triangles, 83 against 93 (111); 192 +
/// 192, even; 768 + 768, 957 against 555.
pub const SERIAL_BELOW: usize = 256;

/// [`with_threads`] for a call on `triangles` triangles in all: under [`SERIAL_BELOW`],
/// `f` runs serially on the calling thread (after the same check of `threads`).
pub(crate) fn with_threads_for<R: Send>(
    threads: Option<usize>,
    triangles: usize,
    f: impl FnOnce() -> R + Send,
) -> Result<R> {
    if triangles < SERIAL_BELOW {
        check_threads(threads)?;
        return Ok(crate::par::serially(f));
    }
    with_threads(threads, f)
}

/// Runs `f`, a call on `triangles` triangles in all, as [`with_threads_for`] does with
/// the default threads: serially on this thread under [`SERIAL_BELOW`], else on a worker
/// of the current pool (moved there once from outside). For the pipeline's own entry
/// points ([`crate::boolean::boolean`]), called directly from outside a pool: there every
/// parallel step would otherwise wake the pool from outside.
pub(crate) fn run_for<R: Send>(triangles: usize, f: impl FnOnce() -> R + Send) -> R {
    if triangles < SERIAL_BELOW || crate::par::is_serial() {
        crate::par::serially(f)
    } else {
        in_current_pool(f)
    }
}

/// Runs `f` on a worker of the current pool: directly on one, else moved there once
/// from outside, so that its many parallel steps start as local tasks rather than each
/// waking the pool from outside (tens of microseconds each: most of a small boolean),
/// with the pool's other workers kept awake ([`awake`]).
fn in_current_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    if rayon::current_thread_index().is_some() {
        f()
    } else {
        rayon::scope(|_| awake(f))
    }
}

/// An error for more threads than [`RunOptions::MAX_THREADS`].
fn check_threads(threads: Option<usize>) -> Result<()> {
    match threads {
        Some(n) if n > RunOptions::MAX_THREADS => Err(Error::InvalidParameter(format!(
            "threads must be at most {}, got {n}",
            RunOptions::MAX_THREADS
        ))),
        _ => Ok(()),
    }
}

/// How long a worker kept awake by [`awake`] waits without finding work before it
/// goes back to the pool's own idling (and sleep).
const AWAKE_IDLE: std::time::Duration = std::time::Duration::from_micros(500);

/// Runs `f` on the current worker with the pool's other workers kept awake: each takes a
/// task that looks for work (`rayon::yield_now`) until `f` is done, instead of going to
/// sleep in `f`'s serial steps and waking for its next parallel one (a woken thread
/// took about 20 µs on a 2-core virtual machine, a parallel step a few tens). Only for a
/// call that has just moved into its pool ([`with_threads`]): a call made from inside
/// parallel work, where the other workers are busy, leaves them as they are. A task
/// that finds no work for [`AWAKE_IDLE`] ends early, so that one taken late, by a worker
/// waiting inside `f`'s own work, holds that work back no longer than that; one taken
/// by `f`'s own thread ends at once.
fn awake<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    use std::sync::atomic::{AtomicBool, Ordering};
    let n = rayon::current_num_threads();
    let Some(me) = rayon::current_thread_index().filter(|_| n > 1) else {
        return f();
    };
    let done = AtomicBool::new(false);
    rayon::scope(|s| {
        for _ in 1..n {
            s.spawn(|_| {
                if rayon::current_thread_index() == Some(me) {
                    return;
                }
                let mut last = web_time::Instant::now();
                while !done.load(Ordering::Acquire) {
                    if rayon::yield_now() == Some(rayon::Yield::Executed) {
                        last = web_time::Instant::now();
                    } else if last.elapsed() > AWAKE_IDLE {
                        return;
                    } else {
                        std::hint::spin_loop();
                    }
                }
            });
        }
        let r = f();
        done.store(true, Ordering::Release);
        r
    })
}

/// Inputs whose coordinates are all tiny or all huge (the largest below 2^-200 or above
/// 2^200) are computed at unit size: the exact kernel's filters and implicit points work
/// in products of several coordinates, which would underflow or overflow `f64` there.
/// Multiplying by a power of two is exact (for normal numbers), and every step commutes
/// with it, so the result is the unit-size result scaled back bit for bit.
///
/// The exponent `e` that brings the meshes' largest magnitude into `[1, 2)`, when outside
/// the safe range; `None` when they are computed as given.
fn extreme_scale(meshes: &[&Mesh]) -> Option<i32> {
    use rayon::prelude::*;
    // The largest magnitude, from the bits without the sign: for non-negative floats the
    // order of the bit patterns is the numeric one (infinity and NaN above every finite
    // one). Chunks side by side on large meshes.
    let most = |ps: &[[f64; 3]]| {
        ps.iter()
            .flatten()
            .map(|x| x.to_bits() & !(1 << 63))
            .max()
            .unwrap_or(0)
    };
    let bits = meshes
        .iter()
        .map(|m| match m.positions.len() {
            n if n >= 1 << 16 => m.positions.par_chunks(1 << 14).map(most).max().unwrap_or(0),
            _ => most(&m.positions),
        })
        .max()
        .unwrap_or(0);
    let largest = f64::from_bits(bits);
    if !(largest.is_finite() && largest > 0.0) {
        return None;
    }
    let e = largest.log2().floor() as i32;
    (!(-200..=200).contains(&e)).then_some(-e)
}

/// Runs `f` on `a` and `b` at unit size when they are of extreme magnitude together
/// ([`extreme_scale`]; meshes or operands, scaled copies), and `back` on its output to
/// scale it back by the inverse power of two; `None` when the inputs are computed as given.
fn at_unit_scale<T>(
    a: Input<'_>,
    b: Input<'_>,
    f: impl FnOnce(Input<'_>, Input<'_>) -> Result<T>,
    back: impl FnOnce(&mut T, i32),
) -> Option<Result<T>> {
    let e = extreme_scale(&[a.mesh(), b.mesh()])?;
    let (a, b) = (a.scaled(e), b.scaled(e));
    Some(f(a.input(), b.input()).map(|mut out| {
        back(&mut out, -e);
        out
    }))
}

/// `m` with every coordinate multiplied by `2^e` (exact for normal numbers).
fn scaled_mesh(m: &Mesh, e: i32) -> Mesh {
    let mut out = m.clone();
    scale_points(&mut out.positions, e);
    out
}

/// `x · 2^e`, in two steps where `2^e` alone is not a normal `f64` (a length given with
/// meshes computed at unit size).
pub(crate) fn scaled(x: f64, e: i32) -> f64 {
    let (half, rest) = (e / 2, e - e / 2);
    x * 2f64.powi(half) * 2f64.powi(rest)
}

/// `x · 2^(n·e)`: a measure of dimension `n` (1 a length, 2 an area, 3 a volume) of a
/// mesh scaled by `2^e`, one [`scaled`] per dimension so that no step leaves `f64`'s range.
pub(crate) fn scaled_measure(x: f64, e: i32, n: u32) -> f64 {
    (0..n).fold(x, |x, _| scaled(x, e))
}

/// Multiplies every coordinate by `2^e`, in two steps where `2^e` alone is not a normal
/// `f64`.
pub(crate) fn scale_points(points: &mut [[f64; 3]], e: i32) {
    let (half, rest) = (e / 2, e - e / 2);
    let (f, g) = (2f64.powi(half), 2f64.powi(rest));
    for p in points {
        for x in p.iter_mut() {
            *x = *x * f * g;
        }
    }
}

/// The measures of a result mesh that every report carries: counts, closedness, volume
/// and area. Cheaper than [`MeshStats`](crate::measure::MeshStats) (edge kinds are counted without building the
/// adjacency).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Measures {
    /// Triangles.
    pub triangles: usize,
    /// Vertices (the result's vertices are all used).
    pub vertices: usize,
    /// Edges used by one triangle.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// True when the mesh has triangles and neither boundary nor non-manifold edges.
    pub closed: bool,
    /// Signed volume (meaningful when closed).
    pub volume: f64,
    /// Surface area.
    pub area: f64,
}

impl Measures {
    /// Measures `mesh`.
    pub fn of(mesh: &Mesh) -> Measures {
        let counts = EdgeCounts::of(mesh);
        Measures {
            triangles: mesh.triangles.len(),
            vertices: mesh.positions.len(),
            boundary_edges: counts.boundary,
            non_manifold_edges: counts.non_manifold,
            closed: !mesh.is_empty() && counts.boundary == 0 && counts.non_manifold == 0,
            volume: signed_volume(mesh),
            area: area(mesh),
        }
    }
}

/// Reads a mesh file: the format from `from`, else from the name and the content
/// ([`crate::io::detect_format`]). Errors name the file. The mesh is as the file has it
/// (welded only where the format stores corners per triangle).
pub fn read(path: impl AsRef<Path>, from: Option<Format>) -> Result<(Mesh, Format)> {
    let path = path.as_ref();
    crate::io::read_file(path, from).map_err(|e| e.in_file("reading", path))
}

/// Writes `mesh` to a file in `format`, or the format the file's name says. Errors name
/// the file.
pub fn write(path: impl AsRef<Path>, mesh: &Mesh, format: Option<Format>) -> Result<()> {
    let path = path.as_ref();
    let format = match format.or_else(|| Format::for_path(path)) {
        Some(f) => f,
        None => return Err(Error::UnknownFormat(path.display().to_string())),
    };
    crate::io::write_path_as(path, mesh, format).map_err(|e| e.in_file("writing", path))
}

#[cfg(test)]
mod tests;
