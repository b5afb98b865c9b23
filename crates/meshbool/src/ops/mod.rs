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

pub use crate::par::{with_threads, SERIAL_BELOW};
// The scalings of extreme inputs, for this module's files (`super::scaled`).
use crate::scale::{extreme_scale, scale_points, scaled, scaled_measure, scaled_mesh};
pub use crate::stage::Cancel;

mod boolean;
mod curves;
mod cutfill;
mod envelope;
mod make;
mod operand;
mod points;
mod shape_json;
mod single;
mod split;
mod transform;

// The parts of the reports that the stages below make.
pub use crate::arrange::FailReason;
pub use crate::boolean::{CleanupReport, FailedTriangle, ResolveReport};
pub use crate::intersect::PolylineXyz;
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
pub use shape_json::{ShapeJsonError, ShapeKeys};
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
    pub const MAX_THREADS: usize = crate::par::MAX_THREADS;

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
    /// True when the mesh has neither boundary nor non-manifold edges. An empty result
    /// (the empty solid: closed operands that do not meet in an intersection, a
    /// difference that removes everything) is closed too; [`Measures::empty`] says so.
    pub closed: bool,
    /// True when the mesh has no triangles.
    pub empty: bool,
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
            closed: counts.boundary == 0 && counts.non_manifold == 0,
            empty: mesh.is_empty(),
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
