//! `meshbool._native`: the Python extension behind the `meshbool` package. A thin layer
//! over the library's front door (`meshbool::ops`): numpy arrays in, one call per command
//! with the GIL released, numpy arrays and JSON reports out. The Python package
//! (`python/meshbool/__init__.py`) turns these into `Mesh` objects and dicts.
//!
//! Meshes cross as two arrays: vertices `float64 (n, 3)` and faces `uint32 (m, 3)`, both
//! C-contiguous (the Python side converts). Results are handed to numpy without a copy
//! (the library's vectors become the arrays' buffers).
#![forbid(unsafe_code)]

use meshbool::ops::{
    self, BooleanOptions, Cancel, Checks, CurvesOptions, InfoReport, Measures, PickOptions,
    PieceSpec, RunOptions, SplitOptions, SplitOutput,
};
use meshbool::repair::{CloseMode, CloseOptions, Facing, RepairConfig};
use meshbool::{Error, Format, Mesh, Op, Source};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

/// mimalloc, as the command line uses it: a boolean's stages allocate and free large
/// buffers one after another on the thread pool's workers, where the system allocator
/// maps and zeroes fresh pages each time (2M-triangle union in process: see
/// BENCHMARKS.md, "Measured settings").
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The library's errors as Python exceptions: `OSError` for what the operating system
/// refused (reading or writing files), `ValueError` for everything else (bad geometry,
/// bad arguments, malformed files).
fn py_err(e: Error) -> PyErr {
    let os = match &e {
        Error::Io(_) => true,
        Error::File { error, .. } => matches!(**error, Error::Io(_)),
        _ => false,
    };
    if os {
        PyOSError::new_err(e.to_string())
    } else {
        PyValueError::new_err(e.to_string())
    }
}

/// A report as JSON text (the Python side makes it a dict).
fn json(report: &impl serde::Serialize) -> PyResult<String> {
    serde_json::to_string(report).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// Rows of three of a contiguous `(n, 3)` array.
fn rows<T: numpy::Element + Copy>(
    a: &PyReadonlyArray2<'_, T>,
    what: &str,
) -> PyResult<Vec<[T; 3]>> {
    if a.ndim() != 2 || a.shape()[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (n, 3), got {:?}",
            a.shape()
        )));
    }
    let flat = a.as_slice().map_err(|_| {
        PyValueError::new_err(format!(
            "{what} must be C-contiguous and aligned (numpy.require(a, requirements=\"CA\"))"
        ))
    })?;
    Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
}

/// A mesh from vertices and faces; an error naming the first bad face when an index is out
/// of range.
fn mesh(v: &PyReadonlyArray2<'_, f64>, f: &PyReadonlyArray2<'_, u32>) -> PyResult<Mesh> {
    Mesh::new(rows(v, "vertices")?, rows(f, "faces")?).map_err(py_err)
}

/// Vertices and faces of a result, as numpy arrays owning the mesh's buffers.
type Arrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<u32>>);

/// One mesh's arrays and a report.
type WithReport<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<u32>>, String);

fn arrays(py: Python<'_>, mesh: Mesh) -> PyResult<Arrays<'_>> {
    let (positions, triangles) = mesh.into_parts();
    let (n, m) = (positions.len(), triangles.len());
    Ok((
        PyArray1::from_vec(py, positions.into_flattened()).reshape([n, 3])?,
        PyArray1::from_vec(py, triangles.into_flattened()).reshape([m, 3])?,
    ))
}

fn checks(force: bool, self_check: bool, resolve: bool, orient: bool) -> Checks {
    Checks {
        self_intersections: self_check,
        resolve,
        orient,
        force,
        ..Checks::default()
    }
}

fn run(threads: Option<usize>) -> RunOptions {
    RunOptions {
        threads,
        cancel: Some(Cancel::new()),
        ..RunOptions::default()
    }
}

/// Calls on at least this many triangles run on a thread of their own while the calling
/// thread watches for Ctrl-C ([`interruptible`]); smaller ones end sooner than a key press
/// is noticed, and run directly.
const INTERRUPTIBLE_FROM: usize = 1 << 15;

/// Runs `f` (a library call on `size` triangles, `run` its run options) without the GIL
/// so that Ctrl-C stops it: the call runs on a thread of its own while this one waits for
/// it, looking at Python's signals every 50 ms; on `KeyboardInterrupt` (or any exception
/// a signal handler raises) the call is cancelled, stops at its next stage, and the
/// exception is raised.
fn interruptible<T: Send>(
    py: Python<'_>,
    run: &RunOptions,
    size: usize,
    f: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    let cancel = match &run.cancel {
        Some(c) if size >= INTERRUPTIBLE_FROM => c.clone(),
        _ => return Ok(py.detach(f)),
    };
    std::thread::scope(|s| {
        let (tx, mut rx) = std::sync::mpsc::channel();
        s.spawn(move || {
            let _ = tx.send(f());
        });
        loop {
            // The receiver goes into the GIL-free wait and comes back.
            let (got, back) = py.detach(move || {
                let got = rx.recv_timeout(std::time::Duration::from_millis(50));
                (got, rx)
            });
            rx = back;
            match got {
                Ok(v) => return Ok(v),
                Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                    if let Err(e) = py.check_signals() {
                        cancel.cancel();
                        // The call's result (Err(Cancelled), or what it finished with) is
                        // not wanted; its thread ends at its next stage.
                        py.detach(move || {
                            let _ = rx.recv();
                        });
                        return Err(e);
                    }
                }
                // The call's thread panicked: the scope raises its panic.
                Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(PyValueError::new_err(
                        "meshbool: the call ended without a result",
                    ))
                }
            }
        }
    })
}

fn parse<T: std::str::FromStr<Err = Error>>(s: &str) -> PyResult<T> {
    s.parse().map_err(py_err)
}

/// Raises `ValueError` when a vertex has a non-finite coordinate or an index is out of range.
#[pyfunction]
fn check(v: PyReadonlyArray2<'_, f64>, f: PyReadonlyArray2<'_, u32>) -> PyResult<()> {
    mesh(&v, &f)?.validate().map_err(py_err)
}

/// `(volume, area, closed)` of a mesh.
#[pyfunction]
fn measures(
    py: Python<'_>,
    v: PyReadonlyArray2<'_, f64>,
    f: PyReadonlyArray2<'_, u32>,
) -> PyResult<(f64, f64, bool)> {
    let m = mesh(&v, &f)?;
    let r = py.detach(move || Measures::of(&m));
    // A mesh with no triangles is not a closed mesh (a result says `empty` beside).
    Ok((r.volume, r.area, r.closed && !r.empty))
}

/// The `meshbool info --json` report of a mesh.
#[pyfunction]
fn info(
    py: Python<'_>,
    v: PyReadonlyArray2<'_, f64>,
    f: PyReadonlyArray2<'_, u32>,
) -> PyResult<String> {
    let m = mesh(&v, &f)?;
    let stats = py.detach(move || ops::info(&m)).map_err(py_err)?;
    json(&InfoReport::new("", stats))
}

/// What a boolean found besides its mesh: the report is measured and the provenance
/// made into arrays when asked for ([`Boolean::report`], [`Boolean::provenance`]), so
/// that a call that only wants the mesh does not pay for them.
#[pyclass(module = "meshbool._native", frozen)]
struct Boolean {
    /// The output without its mesh (it went to numpy).
    out: ops::BooleanOutput,
}

/// A boolean's provenance as arrays: source (0 = A, 1 = B), triangle, flipped.
type ProvenanceArrays<'py> = (
    Bound<'py, PyArray1<u8>>,
    Bound<'py, PyArray1<u32>>,
    Bound<'py, PyArray1<bool>>,
);

#[pymethods]
impl Boolean {
    /// The report (the `--json` of the CLI) of this boolean, whose result is `v`, `f`.
    fn report(
        &self,
        py: Python<'_>,
        v: PyReadonlyArray2<'_, f64>,
        f: PyReadonlyArray2<'_, u32>,
    ) -> PyResult<String> {
        let mut out = self.out.clone();
        out.mesh = mesh(&v, &f)?;
        json(&py.detach(move || out.report()))
    }

    /// What the result assumes, one line each.
    fn assumed(&self) -> Vec<String> {
        self.out.assumed()
    }

    /// The origin of each result triangle: its source (0 = A, 1 = B), its triangle there
    /// and whether it was flipped.
    fn provenance<'py>(&self, py: Python<'py>) -> ProvenanceArrays<'py> {
        let p = &self.out.provenance;
        (
            PyArray1::from_iter(py, p.iter().map(|p| u8::from(p.source == Source::B))),
            PyArray1::from_iter(py, p.iter().map(|p| p.triangle)),
            PyArray1::from_iter(py, p.iter().map(|p| p.flipped)),
        )
    }
}

/// A boolean: the result's arrays and what else it found, provenance included
/// ([`Boolean`]).
#[pyfunction]
#[pyo3(signature = (av, af, bv, bf, op, force, self_check, resolve, orient, threads, keep_nonmanifold, snap=0.0, keep_seam_points=false, coplanar_refinement=false))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn boolean<'py>(
    py: Python<'py>,
    av: PyReadonlyArray2<'py, f64>,
    af: PyReadonlyArray2<'py, u32>,
    bv: PyReadonlyArray2<'py, f64>,
    bf: PyReadonlyArray2<'py, u32>,
    op: &str,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Option<usize>,
    keep_nonmanifold: bool,
    snap: f64,
    keep_seam_points: bool,
    coplanar_refinement: bool,
) -> PyResult<BooleanResult<'py>> {
    let (a, b, op) = (mesh(&av, &af)?, mesh(&bv, &bf)?, parse::<Op>(op)?);
    let opts = BooleanOptions {
        checks: checks(force, self_check, resolve, orient),
        keep_nonmanifold,
        keep_seam_points,
        coplanar_refinement,
        snap,
        run: run(threads),
        ..BooleanOptions::default()
    };
    let size = a.triangles().len() + b.triangles().len();
    let run = opts.run.clone();
    let out =
        interruptible(py, &run, size, move || ops::boolean(&a, &b, op, &opts))?.map_err(py_err)?;
    boolean_result(py, out)
}

/// What [`boolean`] returns, from the library's output.
type BooleanResult<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<u32>>,
    Boolean,
);

/// The result's arrays and the rest of the output (its provenance made into arrays only
/// when asked for: three arrays were a tenth of a small boolean's time outside the
/// library).
fn boolean_result(py: Python<'_>, mut out: ops::BooleanOutput) -> PyResult<BooleanResult<'_>> {
    let (v, f) = arrays(py, std::mem::take(&mut out.mesh))?;
    Ok((v, f, Boolean { out }))
}

/// A mesh welded and checked once, for many booleans ([`ops::Operand`]).
#[pyclass(module = "meshbool._native", frozen)]
struct Operand {
    operand: ops::Operand,
}

#[pymethods]
impl Operand {
    /// Welds and checks the mesh `v`, `f` as the flags say, naming it `name` in reports
    /// and errors.
    #[new]
    #[pyo3(signature = (v, f, name, force, self_check, resolve, orient, threads))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        v: PyReadonlyArray2<'_, f64>,
        f: PyReadonlyArray2<'_, u32>,
        name: String,
        force: bool,
        self_check: bool,
        resolve: bool,
        orient: bool,
        threads: Option<usize>,
    ) -> PyResult<Self> {
        let m = mesh(&v, &f)?;
        let checks = checks(force, self_check, resolve, orient);
        let operand = py
            .detach(move || {
                ops::with_threads(threads, || ops::Operand::new(name, &m, &checks)).and_then(|r| r)
            })
            .map_err(py_err)?;
        Ok(Operand { operand })
    }

    /// What the checks found, as JSON.
    fn report(&self) -> PyResult<String> {
        json(self.operand.report())
    }

    /// The checked mesh's arrays (welded; the solid it encloses when it was resolved).
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Arrays<'py>> {
        arrays(py, self.operand.mesh().clone())
    }
}

/// [`boolean`] of two operands checked before ([`Operand`]).
#[pyfunction]
#[pyo3(signature = (a, b, op, threads, keep_nonmanifold, snap=0.0, keep_seam_points=false, coplanar_refinement=false))]
#[allow(clippy::too_many_arguments)]
fn boolean_operands<'py>(
    py: Python<'py>,
    a: &Operand,
    b: &Operand,
    op: &str,
    threads: Option<usize>,
    keep_nonmanifold: bool,
    snap: f64,
    keep_seam_points: bool,
    coplanar_refinement: bool,
) -> PyResult<BooleanResult<'py>> {
    let op = parse::<Op>(op)?;
    let opts = BooleanOptions {
        keep_nonmanifold,
        keep_seam_points,
        coplanar_refinement,
        snap,
        run: run(threads),
        ..BooleanOptions::default()
    };
    let (a, b) = (&a.operand, &b.operand);
    let size = a.mesh().triangles().len() + b.mesh().triangles().len();
    let run = opts.run.clone();
    let out =
        interruptible(py, &run, size, move || ops::boolean(a, b, op, &opts))?.map_err(py_err)?;
    boolean_result(py, out)
}

/// A split of two meshes along their intersection: its groups and their components.
#[pyclass(module = "meshbool._native", frozen)]
struct Split {
    out: SplitOutput,
}

#[pymethods]
impl Split {
    /// The names of the non-empty groups.
    fn groups(&self) -> Vec<String> {
        self.out
            .groups
            .iter()
            .map(|g| g.group.to_string())
            .collect()
    }

    /// A group's arrays, or `None` when the split has no such (non-empty) group.
    fn group<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Option<Arrays<'py>>> {
        let group = parse(name)?;
        match self.out.groups.iter().find(|g| g.group == group) {
            Some(g) => Ok(Some(arrays(py, g.mesh.clone())?)),
            None => Ok(None),
        }
    }

    /// A group's components, largest first (one: the group itself).
    fn components<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Vec<Arrays<'py>>> {
        let group = parse(name)?;
        let Some(g) = self.out.groups.iter().find(|g| g.group == group) else {
            return Ok(Vec::new());
        };
        if g.components.is_empty() {
            return Ok(vec![arrays(py, g.mesh.clone())?]);
        }
        g.components.iter().map(|c| arrays(py, c.clone())).collect()
    }

    /// Merges pieces (`GROUP[#COMPONENT][:flip]`) into one welded mesh: its arrays and
    /// the pick report.
    #[pyo3(signature = (specs, keep_nonmanifold, snap=0.0))]
    fn pick<'py>(
        &self,
        py: Python<'py>,
        specs: Vec<String>,
        keep_nonmanifold: bool,
        snap: f64,
    ) -> PyResult<WithReport<'py>> {
        let specs = specs
            .iter()
            .map(|s| parse::<PieceSpec>(s))
            .collect::<PyResult<Vec<_>>>()?;
        let opts = PickOptions {
            keep_nonmanifold,
            snap,
        };
        let out = py.detach(|| self.out.pick(&specs, &opts)).map_err(py_err)?;
        let report = json(&out.report())?;
        let (v, f) = arrays(py, out.mesh)?;
        Ok((v, f, report))
    }

    /// The split's report (the manifest's content) with the file names `format` gives.
    fn report(&self, format: &str) -> PyResult<String> {
        json(&self.out.report(parse::<Format>(format)?))
    }

    /// Writes the pieces and the manifest to a directory; returns the manifest.
    fn write(&self, py: Python<'_>, dir: std::path::PathBuf, format: &str) -> PyResult<String> {
        let format = parse::<Format>(format)?;
        let manifest = py
            .detach(|| self.out.write_dir(&dir, format))
            .map_err(py_err)?;
        json(&manifest)
    }
}

/// Splits two meshes along their intersection.
#[pyfunction]
#[pyo3(signature = (av, af, bv, bf, force, self_check, resolve, orient, threads, merge_small, snap=0.0, keep_seam_points=false, coplanar_refinement=false))]
#[allow(clippy::too_many_arguments)]
fn split(
    py: Python<'_>,
    av: PyReadonlyArray2<'_, f64>,
    af: PyReadonlyArray2<'_, u32>,
    bv: PyReadonlyArray2<'_, f64>,
    bf: PyReadonlyArray2<'_, u32>,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Option<usize>,
    merge_small: usize,
    snap: f64,
    keep_seam_points: bool,
    coplanar_refinement: bool,
) -> PyResult<Split> {
    let (a, b) = (mesh(&av, &af)?, mesh(&bv, &bf)?);
    let opts = SplitOptions {
        checks: checks(force, self_check, resolve, orient),
        merge_small,
        snap,
        keep_seam_points,
        sliver_guard: false,
        coplanar_refinement,
        run: run(threads),
    };
    let size = a.triangles().len() + b.triangles().len();
    let run = opts.run.clone();
    let out = interruptible(py, &run, size, move || ops::split(&a, &b, &opts))?.map_err(py_err)?;
    Ok(Split { out })
}

/// The union or intersection of several meshes in one call: the result's arrays, the
/// input and triangle of each result triangle, the report.
#[pyfunction]
#[pyo3(signature = (meshes, op, force, self_check, resolve, orient, threads, keep_nonmanifold, snap=0.0, keep_seam_points=false, one_arrangement=false))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn boolean_many<'py>(
    py: Python<'py>,
    meshes: Vec<(PyReadonlyArray2<'py, f64>, PyReadonlyArray2<'py, u32>)>,
    op: &str,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Option<usize>,
    keep_nonmanifold: bool,
    snap: f64,
    keep_seam_points: bool,
    one_arrangement: bool,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<u32>>,
    Bound<'py, PyArray1<u32>>,
    Bound<'py, PyArray1<u32>>,
    String,
)> {
    let meshes = meshes
        .iter()
        .map(|(v, f)| mesh(v, f))
        .collect::<PyResult<Vec<_>>>()?;
    let op = parse::<Op>(op)?;
    let opts = BooleanOptions {
        checks: checks(force, self_check, resolve, orient),
        keep_nonmanifold,
        keep_seam_points,
        snap,
        one_arrangement,
        sliver_guard: false,
        coplanar_refinement: false,
        run: run(threads),
    };
    let size = meshes.iter().map(|m| m.triangles().len()).sum();
    let run = opts.run.clone();
    let (out, report) = interruptible(py, &run, size, move || {
        let inputs: Vec<ops::Input> = meshes.iter().map(ops::Input::from).collect();
        // A difference of many: the first less all the others, in one call.
        let out = match op {
            Op::Difference => ops::difference_many(&inputs, &opts)?,
            op => ops::boolean_many(&inputs, op, &opts)?,
        };
        let report = out.report();
        Ok::<_, Error>((out, report))
    })?
    .map_err(py_err)?;
    let input = PyArray1::from_iter(py, out.provenance.iter().map(|p| p[0]));
    let triangle = PyArray1::from_iter(py, out.provenance.iter().map(|p| p[1]));
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, input, triangle, json(&report)?))
}

/// The pieces of a split that the boolean `op` keeps (`GROUP[:flip]`), by its rule.
#[pyfunction]
fn pieces_for_op(op: &str) -> PyResult<Vec<String>> {
    Ok(PieceSpec::for_op(parse::<Op>(op)?)
        .iter()
        .map(ToString::to_string)
        .collect())
}

/// Merges meshes, each flipped where its flag says, welding exactly equal positions.
#[pyfunction]
#[pyo3(signature = (pieces, keep_nonmanifold, snap=0.0))]
fn pick<'py>(
    py: Python<'py>,
    pieces: Vec<(PyReadonlyArray2<'py, f64>, PyReadonlyArray2<'py, u32>, bool)>,
    keep_nonmanifold: bool,
    snap: f64,
) -> PyResult<WithReport<'py>> {
    let meshes = pieces
        .iter()
        .map(|(v, f, flip)| Ok((mesh(v, f)?, *flip)))
        .collect::<PyResult<Vec<_>>>()?;
    let opts = PickOptions {
        keep_nonmanifold,
        snap,
    };
    let out = py
        .detach(move || {
            let refs: Vec<(&Mesh, bool)> = meshes.iter().map(|(m, f)| (m, *f)).collect();
            ops::pick(&refs, &opts)
        })
        .map_err(py_err)?;
    let report = json(&out.report())?;
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, report))
}

/// Polylines as `(points (k, 3), closed)`, the points handed to numpy without a copy.
fn polylines(
    py: Python<'_>,
    lines: Vec<meshbool::ops::PolylineXyz>,
) -> PyResult<Vec<(Bound<'_, PyArray2<f64>>, bool)>> {
    lines
        .into_iter()
        .map(|l| {
            let k = l.points.len();
            let points = PyArray1::from_vec(py, l.points.into_flattened()).reshape([k, 3])?;
            Ok((points, l.closed))
        })
        .collect()
}

/// The intersection curves: `(points (k, 3), closed)` per polyline, and the report.
#[pyfunction]
#[pyo3(signature = (av, af, b, with_coplanar, simplify=None, tagged=false, coplanar_refinement=false))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn curves<'py>(
    py: Python<'py>,
    av: PyReadonlyArray2<'py, f64>,
    af: PyReadonlyArray2<'py, u32>,
    b: Option<(PyReadonlyArray2<'py, f64>, PyReadonlyArray2<'py, u32>)>,
    with_coplanar: bool,
    simplify: Option<f64>,
    tagged: bool,
    coplanar_refinement: bool,
) -> PyResult<(Vec<(Bound<'py, PyArray2<f64>>, bool)>, String)> {
    let a = mesh(&av, &af)?;
    let b = b.map(|(bv, bf)| mesh(&bv, &bf)).transpose()?;
    let opts = CurvesOptions {
        with_coplanar,
        simplify,
        tagged,
        coplanar_refinement,
        ..CurvesOptions::default()
    };
    let out = py
        .detach(move || match &b {
            Some(b) => ops::curves(&a, b, &opts),
            None => ops::self_curves(&a, &opts),
        })
        .map_err(py_err)?;
    let report = json(&out.report())?;
    Ok((polylines(py, out.polylines)?, report))
}

/// Cut and fill between a design surface and a topography: the report (JSON) and the
/// zero-thickness lines as `(points (k, 3), closed)`.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn cutfill<'py>(
    py: Python<'py>,
    dv: PyReadonlyArray2<'py, f64>,
    df: PyReadonlyArray2<'py, u32>,
    tv: PyReadonlyArray2<'py, f64>,
    tf: PyReadonlyArray2<'py, u32>,
    threads: Option<usize>,
) -> PyResult<(String, Vec<(Bound<'py, PyArray2<f64>>, bool)>)> {
    let (d, t) = (mesh(&dv, &df)?, mesh(&tv, &tf)?);
    let opts = ops::CutFillOptions { run: run(threads) };
    let size = d.triangles().len() + t.triangles().len();
    let run = opts.run.clone();
    let out =
        interruptible(py, &run, size, move || ops::cutfill(&d, &t, &opts))?.map_err(py_err)?;
    let report = json(&out.report())?;
    Ok((report, polylines(py, out.lines)?))
}

/// Where points lie against a mesh: per point 0 outside, 1 inside, 2 on the surface, the
/// winding numbers, and the report.
#[pyfunction]
#[allow(clippy::type_complexity)]
fn classify<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, u32>,
    points: PyReadonlyArray2<'py, f64>,
    force: bool,
    threads: Option<usize>,
) -> PyResult<(Bound<'py, PyArray1<u8>>, Bound<'py, PyArray1<f64>>, String)> {
    let m = mesh(&v, &f)?;
    let pts = rows(&points, "points")?;
    let opts = ops::ClassifyOptions {
        checks: checks(force, true, true, true),
        run: run(threads),
    };
    let out = py
        .detach(move || ops::classify_points(&m, &pts, &opts))
        .map_err(py_err)?;
    let report = json(&out.report(false))?;
    let classes: Vec<u8> = out.classes.iter().map(|c| c.code()).collect();
    Ok((
        PyArray1::from_vec(py, classes),
        PyArray1::from_vec(py, out.winding),
        report,
    ))
}

/// Consistent orientation, each component facing as `facing` says.
#[pyfunction]
fn orient<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, u32>,
    facing: &str,
) -> PyResult<WithReport<'py>> {
    let (m, facing) = (mesh(&v, &f)?, parse::<Facing>(facing)?);
    let out = py.detach(move || ops::orient(&m, facing)).map_err(py_err)?;
    let report = json(&out.report())?;
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, report))
}

/// The solid a self-overlapping mesh encloses: its arrays, the input triangle of each
/// result triangle, the report.
#[pyfunction]
#[pyo3(signature = (v, f, rule, keep_nonmanifold, threads, snap=0.0))]
#[allow(clippy::type_complexity)]
fn resolve<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, u32>,
    rule: &str,
    keep_nonmanifold: bool,
    threads: Option<usize>,
    snap: f64,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<u32>>,
    Bound<'py, PyArray1<u32>>,
    String,
)> {
    let m = mesh(&v, &f)?;
    let opts = ops::ResolveOptions {
        rule: parse::<meshbool::FillRule>(rule)?,
        keep_nonmanifold,
        snap,
        run: run(threads),
    };
    let size = m.triangles().len();
    let run = opts.run.clone();
    let mut out =
        interruptible(py, &run, size, move || ops::resolve(&m, &opts))?.map_err(py_err)?;
    let report = json(&py.detach(|| out.report()))?;
    let parent = PyArray1::from_vec(py, std::mem::take(&mut out.parent));
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, parent, report))
}

/// The upper or lower envelope of a folded open surface: its arrays, the input triangle
/// of each result triangle, the report.
#[pyfunction]
#[pyo3(signature = (v, f, side, threads))]
#[allow(clippy::type_complexity)]
fn envelope<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, u32>,
    side: &str,
    threads: Option<usize>,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<u32>>,
    Bound<'py, PyArray1<u32>>,
    String,
)> {
    let m = mesh(&v, &f)?;
    let opts = ops::EnvelopeOptions {
        side: parse::<ops::Envelope>(side)?,
        run: run(threads),
    };
    let mut out = py
        .detach(move || ops::envelope(&m, &opts))
        .map_err(py_err)?;
    let report = json(&py.detach(|| out.report()))?;
    let parent = PyArray1::from_vec(py, std::mem::take(&mut out.parent));
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, parent, report))
}

/// Closing an open mesh into a solid.
#[pyfunction]
fn close<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, u32>,
    mode: &str,
    floor_offset: f64,
    max_gap: Option<f64>,
) -> PyResult<WithReport<'py>> {
    let (m, mode) = (mesh(&v, &f)?, parse::<CloseMode>(mode)?);
    let opts = CloseOptions {
        stitch_max_gap: max_gap,
        floor_offset,
    };
    let out = py
        .detach(move || ops::close(&m, mode, &opts))
        .map_err(py_err)?;
    let report = json(&out.report())?;
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, report))
}

/// The repair pipeline, configured by the JSON of a `RepairConfig`.
#[pyfunction]
fn repair<'py>(
    py: Python<'py>,
    v: PyReadonlyArray2<'py, f64>,
    f: PyReadonlyArray2<'py, u32>,
    config: &str,
) -> PyResult<WithReport<'py>> {
    let config: RepairConfig = serde_json::from_str(config)
        .map_err(|e| PyValueError::new_err(format!("not a repair configuration: {e}")))?;
    let m = mesh(&v, &f)?;
    let out = py
        .detach(move || ops::repair(&m, &config))
        .map_err(py_err)?;
    let report = json(&out.report())?;
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, report))
}

/// A generated shape's arrays and its report (`meshbool make ... --json`).
fn made(py: Python<'_>, shape: ops::Shape) -> PyResult<WithReport<'_>> {
    let out = py.detach(move || ops::make(&shape)).map_err(py_err)?;
    let report = json(&out.report())?;
    let (v, f) = arrays(py, out.mesh)?;
    Ok((v, f, report))
}

/// A seeded terrain (`meshbool::shapes::terrain`).
#[pyfunction]
fn terrain(
    py: Python<'_>,
    center: [f64; 3],
    size: [f64; 2],
    cells: [u32; 2],
    relief: f64,
    seed: u64,
) -> PyResult<WithReport<'_>> {
    let shape = ops::Shape::Terrain {
        center,
        size,
        cells,
        relief,
        seed,
    };
    made(py, shape)
}

/// The library's defaults of `terrain` and `pit` (`ops::Shape::TERRAIN`, `ops::Shape::PIT`)
/// as JSON: `{"terrain": {...}, "pit": {...}}`, keyed by the Python parameters' names
/// (which the package's signatures must show: a test compares them).
#[pyfunction]
fn shape_defaults() -> PyResult<String> {
    let (
        ops::Shape::Terrain {
            center,
            size,
            cells,
            relief,
            seed,
        },
        ops::Shape::Pit {
            center: pit_center,
            radius,
            depth,
            benches,
            berm,
            segments,
        },
    ) = (ops::Shape::TERRAIN, ops::Shape::PIT)
    else {
        return Err(PyValueError::new_err(
            "the library's example shapes changed kind",
        ));
    };
    let defaults = serde_json::json!({
        "terrain": {"center": center, "size": size, "cells": cells, "relief": relief, "seed": seed},
        "pit": {"center": pit_center, "radius": radius, "depth": depth, "benches": benches,
                "berm": berm, "segments": segments},
    });
    Ok(defaults.to_string())
}

/// An open-pit design shell (`meshbool::shapes::pit`).
#[pyfunction]
fn pit(
    py: Python<'_>,
    center: [f64; 3],
    radius: [f64; 2],
    depth: f64,
    benches: u32,
    berm: f64,
    segments: u32,
) -> PyResult<WithReport<'_>> {
    let shape = ops::Shape::Pit {
        center,
        radius,
        depth,
        benches,
        berm,
        segments,
    };
    made(py, shape)
}

/// Reads a mesh file as the file has it (operations weld their inputs themselves): its
/// arrays and the name of the format it was read as.
#[pyfunction]
#[pyo3(signature = (path, format=None))]
#[allow(clippy::type_complexity)]
fn read<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    format: Option<&str>,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<u32>>,
    &'static str,
)> {
    let format = format.map(parse::<Format>).transpose()?;
    let (m, format) = py
        .detach(move || ops::read(&path, format))
        .map_err(py_err)?;
    let (v, f) = arrays(py, m)?;
    Ok((v, f, format.name()))
}

/// Writes a mesh file in `format`, or the format the file's name says.
#[pyfunction]
#[pyo3(signature = (path, v, f, format=None))]
fn write(
    py: Python<'_>,
    path: std::path::PathBuf,
    v: PyReadonlyArray2<'_, f64>,
    f: PyReadonlyArray2<'_, u32>,
    format: Option<&str>,
) -> PyResult<()> {
    let format = format.map(parse::<Format>).transpose()?;
    let m = mesh(&v, &f)?;
    py.detach(move || ops::write(&path, &m, format))
        .map_err(py_err)
}

/// A CSG cache ([`meshbool::csg::Cache`]): node results by key, in memory and
/// optionally in a folder, kept between calls of `csg`.
#[pyclass(module = "meshbool._native", frozen)]
struct CsgCache(meshbool::csg::Cache);

#[pymethods]
impl CsgCache {
    /// A cache in memory, or also in the folder `dir` (created if missing).
    #[new]
    #[pyo3(signature = (dir=None))]
    fn new(dir: Option<std::path::PathBuf>) -> PyResult<Self> {
        Ok(CsgCache(match dir {
            Some(d) => meshbool::csg::Cache::in_dir(d).map_err(py_err)?,
            None => meshbool::csg::Cache::new(),
        }))
    }

    /// Results held in memory.
    fn __len__(&self) -> usize {
        self.0.len()
    }

    /// Forgets the results held in memory.
    fn clear(&self) {
        self.0.clear();
    }
}

/// A CSG document evaluated (`meshbool::csg::evaluate`): `text` its JSON (mesh paths
/// relative to `base`), `meshes` the meshes in memory its leaves name by index. The root's
/// arrays (`None` when a node failed) and the report.
#[pyfunction]
#[pyo3(signature = (text, base, meshes, cache, force, self_check, resolve, orient, threads, keep_nonmanifold, snap, keep_seam_points))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn csg<'py>(
    py: Python<'py>,
    text: &str,
    base: std::path::PathBuf,
    meshes: Vec<(PyReadonlyArray2<'py, f64>, PyReadonlyArray2<'py, u32>)>,
    cache: &CsgCache,
    force: bool,
    self_check: bool,
    resolve: bool,
    orient: bool,
    threads: Option<usize>,
    keep_nonmanifold: bool,
    snap: f64,
    keep_seam_points: bool,
) -> PyResult<(Option<Arrays<'py>>, String)> {
    let meshes = meshes
        .iter()
        .map(|(v, f)| mesh(v, f).map(std::sync::Arc::new))
        .collect::<PyResult<Vec<_>>>()?;
    let scene = meshbool::csg::Scene::from_json_with(text, &base, &meshes).map_err(py_err)?;
    let opts = meshbool::csg::CsgOptions {
        boolean: BooleanOptions {
            checks: checks(force, self_check, resolve, orient),
            keep_nonmanifold,
            keep_seam_points,
            snap,
            run: run(threads),
            ..BooleanOptions::default()
        },
        progress: None,
        named: false,
    };
    let size = meshes
        .iter()
        .map(|m| m.triangles().len())
        .sum::<usize>()
        .max(INTERRUPTIBLE_FROM);
    let run = opts.boolean.run.clone();
    let cache = &cache.0;
    let out = interruptible(py, &run, size, move || {
        meshbool::csg::evaluate(&scene, cache, &opts)
    })?
    .map_err(py_err)?;
    let report = json(&out.report())?;
    let arrays = out.mesh.map(|m| arrays(py, m)).transpose()?;
    Ok((arrays, report))
}

/// The extension module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SCHEMA", ops::SCHEMA)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Boolean>()?;
    m.add_class::<Operand>()?;
    m.add_class::<Split>()?;
    m.add_class::<CsgCache>()?;
    for f in [
        wrap_pyfunction!(check, m)?,
        wrap_pyfunction!(measures, m)?,
        wrap_pyfunction!(info, m)?,
        wrap_pyfunction!(boolean, m)?,
        wrap_pyfunction!(boolean_operands, m)?,
        wrap_pyfunction!(boolean_many, m)?,
        wrap_pyfunction!(pieces_for_op, m)?,
        wrap_pyfunction!(split, m)?,
        wrap_pyfunction!(pick, m)?,
        wrap_pyfunction!(curves, m)?,
        wrap_pyfunction!(classify, m)?,
        wrap_pyfunction!(cutfill, m)?,
        wrap_pyfunction!(resolve, m)?,
        wrap_pyfunction!(envelope, m)?,
        wrap_pyfunction!(orient, m)?,
        wrap_pyfunction!(close, m)?,
        wrap_pyfunction!(repair, m)?,
        wrap_pyfunction!(terrain, m)?,
        wrap_pyfunction!(pit, m)?,
        wrap_pyfunction!(shape_defaults, m)?,
        wrap_pyfunction!(csg, m)?,
        wrap_pyfunction!(read, m)?,
        wrap_pyfunction!(write, m)?,
    ] {
        m.add_function(f)?;
    }
    Ok(())
}
