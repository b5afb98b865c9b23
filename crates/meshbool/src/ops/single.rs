//! Commands on one mesh at the front door: measures (`info`), orientation, closing and the
//! repair pipeline. Orientation, closing and repair take an [`Input`]: a mesh, validated
//! and welded exactly on the way in (what their edge walks expect), or an [`Operand`]
//! made earlier (the CLI reads its file as one, which does not weld twice formats that
//! weld on read).

use serde::Serialize;

use super::{with_threads, Checks, Input, Measures, Operand, RunOptions, SCHEMA};
use crate::boolean::{FillRule, PipelineOptions, ResolveReport, Stage};
use crate::edges::EdgeCounts;
use crate::intersect::self_intersections;
use crate::measure::{mesh_stats, MeshStats};
use crate::repair::{
    self, CloseMode, CloseOptions, CloseReport, Facing, OrientReport, RepairConfig, RepairReport,
    SnapOptions, SnapReport,
};
use crate::{Error, Mesh, Result};

/// The JSON of `meshbool info --json` for one file (an array of them for several).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct InfoReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The file measured.
    pub file: String,
    /// Every measure.
    #[serde(flatten)]
    pub stats: MeshStats,
}

impl InfoReport {
    /// The report of `stats` measured on `file`.
    pub fn new(file: impl Into<String>, stats: MeshStats) -> Self {
        InfoReport {
            schema: SCHEMA,
            file: file.into(),
            stats,
        }
    }
}

/// Measures a mesh as it is (no weld): counts, edge kinds, components, volume, areas,
/// bounding box. Errors only when the mesh breaks the data model.
pub fn info(mesh: &Mesh) -> Result<MeshStats> {
    mesh.validate()?;
    Ok(mesh_stats(mesh))
}

/// The result of [`orient()`].
#[derive(Clone, Debug)]
pub struct OrientOutput {
    /// The oriented mesh.
    pub mesh: Mesh,
    /// What was flipped.
    pub orient: OrientReport,
}

/// The JSON of `meshbool orient --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrientCommandReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// What was flipped.
    #[serde(flatten)]
    pub orient: OrientReport,
}

impl OrientOutput {
    /// The report.
    pub fn report(&self) -> OrientCommandReport {
        OrientCommandReport {
            schema: SCHEMA,
            orient: self.orient.clone(),
        }
    }
}

/// The welded, validated mesh of one input.
fn welded<'a>(input: impl Into<Input<'a>>) -> Result<std::borrow::Cow<'a, Operand>> {
    input.into().operand("mesh", &Checks::NONE)
}

/// Makes orientation consistent and faces each component as `facing` says
/// ([`repair::orient`]), on the exactly welded mesh.
pub fn orient<'a>(mesh: impl Into<Input<'a>>, facing: Facing) -> Result<OrientOutput> {
    let (mesh, orient) = repair::orient(welded(mesh)?.mesh(), facing);
    Ok(OrientOutput { mesh, orient })
}

/// The result of [`close()`].
#[derive(Clone, Debug)]
pub struct CloseOutput {
    /// The closed mesh.
    pub mesh: Mesh,
    /// What the closing steps did.
    pub close: CloseReport,
}

/// The JSON of `meshbool close --json`: what the steps did and the result's measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CloseCommandReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The steps' reports (`cap`, `stitch`, `curtain`; those that ran).
    #[serde(flatten)]
    pub close: CloseReport,
    /// Edges used by one triangle, left open.
    pub boundary_edges: usize,
    /// True when the result has triangles and neither boundary nor non-manifold edges.
    pub closed: bool,
    /// The result's signed volume.
    pub volume: f64,
}

impl CloseOutput {
    /// The report, with the result's measures.
    pub fn report(&self) -> CloseCommandReport {
        let counts = EdgeCounts::of(&self.mesh);
        CloseCommandReport {
            schema: SCHEMA,
            close: self.close.clone(),
            boundary_edges: counts.boundary,
            closed: !self.mesh.is_empty() && counts.boundary == 0 && counts.non_manifold == 0,
            volume: crate::measure::signed_volume(&self.mesh),
        }
    }
}

/// Closes the exactly welded mesh as `mode` says ([`repair::close`]): capping holes,
/// stitching loop pairs, curtain walls to a floor. Orient a surface up before a curtain.
///
/// A mesh of extreme magnitude (coordinates beyond 2^±200) is closed at unit size, its
/// distances with it, and scaled back (powers of two: exact), so that no decision
/// overflows or underflows.
pub fn close<'a>(
    mesh: impl Into<Input<'a>>,
    mode: CloseMode,
    opts: &CloseOptions,
) -> Result<CloseOutput> {
    let input: Input<'a> = mesh.into();
    if let Input::Mesh(m) = input {
        if let Some(e) = super::extreme_scale(&[m]) {
            let mut out = close(&super::scaled_mesh(m, e), mode, &opts.scaled(e))?;
            super::scale_points(&mut out.mesh.positions, -e);
            out.close.scale_back(-e);
            return Ok(out);
        }
    }
    let (mesh, close) = repair::close(welded(input)?.mesh(), mode, opts)?;
    Ok(CloseOutput { mesh, close })
}

/// The result of [`repair()`].
#[derive(Clone, Debug)]
pub struct RepairOutput {
    /// The repaired mesh.
    pub mesh: Mesh,
    /// Measures before and after and what every step did.
    pub repair: RepairReport,
}

/// The JSON of `meshbool repair --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RepairCommandReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// Measures before and after and what every step did.
    #[serde(flatten)]
    pub repair: RepairReport,
}

impl RepairOutput {
    /// The report.
    pub fn report(&self) -> RepairCommandReport {
        RepairCommandReport {
            schema: SCHEMA,
            repair: self.repair.clone(),
        }
    }
}

/// Runs the repair pipeline `config` asks for ([`repair::repair`]) on the exactly welded
/// mesh. [`repair_with`] takes threads and a progress callback as well.
pub fn repair<'a>(mesh: impl Into<Input<'a>>, config: &RepairConfig) -> Result<RepairOutput> {
    repair_with(mesh, config, &RunOptions::default())
}

/// [`repair()`] run as `run` says: in its threads, `run.progress` called with the
/// [`Stage`] of each step that runs as it begins (from [`Stage::Weld`] to
/// [`Stage::CloseGaps`], in the pipeline's order).
///
/// A mesh of extreme magnitude (coordinates beyond 2^±200) is repaired at unit size, its
/// distances and thresholds with it, and scaled back with its report (powers of two:
/// exact), so that no distance, area or exact test underflows or overflows.
pub fn repair_with<'a>(
    mesh: impl Into<Input<'a>>,
    config: &RepairConfig,
    run: &RunOptions,
) -> Result<RepairOutput> {
    let input: Input<'a> = mesh.into();
    if let Input::Mesh(m) = input {
        if let Some(e) = super::extreme_scale(&[m]) {
            // Parameters are checked as given, then scaled with the mesh.
            config.check(m)?;
            let mut out = repair_with(&super::scaled_mesh(m, e), &config.scaled(e), run)?;
            super::scale_points(&mut out.mesh.positions, -e);
            out.repair.scale_back(-e);
            return Ok(out);
        }
    }
    with_threads(run.threads, || {
        let input = welded(input)?;
        let (mesh, repair) =
            repair::repair_with_progress(input.mesh(), config, &|s| run.report(s))?;
        run.check()?;
        Ok(RepairOutput { mesh, repair })
    })?
}

/// Options of [`resolve()`].
#[derive(Clone, Debug, Default)]
pub struct ResolveOptions {
    /// Which points the mesh encloses, by winding number.
    pub rule: FillRule,
    /// Keep the result's topology where it is not manifold (parts touching along an edge
    /// or at a vertex then share it).
    pub keep_nonmanifold: bool,
    /// Snap tolerance (0, the default: the exact result), as
    /// [`BooleanOptions::snap`](super::BooleanOptions::snap) but with no seam told apart:
    /// any vertex may move, any edge may be flipped.
    pub snap: f64,
    /// Threads and progress.
    pub run: RunOptions,
}

/// The result of [`resolve()`].
#[derive(Clone, Debug)]
pub struct ResolveOutput {
    /// The solid's surface.
    pub mesh: Mesh,
    /// For every triangle of `mesh`, the triangle of the (welded) input it is part of.
    pub parent: Vec<u32>,
    /// The fill rule.
    pub rule: FillRule,
    /// Self-intersecting triangle pairs found in the input.
    pub self_intersections: usize,
    /// What resolving did.
    pub resolve: ResolveReport,
    /// What snapping did ([`ResolveOptions::snap`]); `None` without it.
    pub snap: Option<SnapReport>,
    /// Time of the whole call, in seconds.
    pub seconds: f64,
}

/// The JSON of `meshbool resolve --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ResolveCommandReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The fill rule.
    pub rule: FillRule,
    /// Self-intersecting triangle pairs found in the input.
    pub self_intersections: usize,
    /// Measures of the result.
    #[serde(flatten)]
    pub result: Measures,
    /// What resolving did.
    pub resolve: ResolveReport,
    /// What snapping did (only with a snap tolerance).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub snap: Option<SnapReport>,
    /// [`ResolveOutput::seconds`].
    pub seconds: f64,
}

impl ResolveOutput {
    /// The report, with the result's measures.
    pub fn report(&self) -> ResolveCommandReport {
        ResolveCommandReport {
            schema: SCHEMA,
            rule: self.rule,
            self_intersections: self.self_intersections,
            result: Measures::of(&self.mesh),
            resolve: self.resolve.clone(),
            snap: self.snap.clone(),
            seconds: self.seconds,
        }
    }
}

/// The solid a self-overlapping mesh encloses under `opts.rule`, as a closed mesh
/// (`boolean::resolve`): overlapping parts united, nested ones dropped. Built
/// for meshes of closed, consistently oriented components; anything else that crosses
/// itself is an [`Error::Unresolvable`](crate::Error::Unresolvable).
pub fn resolve<'a>(mesh: impl Into<Input<'a>>, opts: &ResolveOptions) -> Result<ResolveOutput> {
    let input: Input<'a> = mesh.into();
    repair::check_tolerance(opts.snap)?;
    if let Input::Mesh(m) = input {
        if let Some(e) = super::extreme_scale(&[m]) {
            let unit = ResolveOptions {
                snap: super::scaled(opts.snap, e).min(f64::MAX),
                ..opts.clone()
            };
            let mut out = resolve(&super::scaled_mesh(m, e), &unit)?;
            super::scale_points(&mut out.mesh.positions, -e);
            if let Some(s) = &mut out.snap {
                s.scale_back(-e);
            }
            return Ok(out);
        }
    }
    with_threads(opts.run.threads, || {
        let start = web_time::Instant::now();
        let input = welded(input)?;
        opts.run.stage(Stage::Check)?;
        let pairs = self_intersections(input.mesh());
        opts.run.stage(Stage::Intersect)?;
        let pipeline = PipelineOptions {
            keep_nonmanifold: opts.keep_nonmanifold,
            ..opts.run.pipeline()
        };
        let mut r = crate::boolean::resolve(input.mesh(), &pairs, opts.rule, &pipeline).map_err(
            |reason| Error::Unresolvable {
                name: input.name().to_string(),
                reason,
            },
        )?;
        opts.run.check()?;
        let snap = (opts.snap > 0.0).then(|| {
            opts.run.report(Stage::Snap);
            let snap = SnapOptions {
                tolerance: opts.snap,
                ..SnapOptions::default()
            };
            repair::snap_carrying(&mut r.mesh, &snap, &mut r.parent).0
        });
        Ok(ResolveOutput {
            mesh: r.mesh,
            parent: r.parent.iter().map(|&t| input.input_triangle(t)).collect(),
            snap,
            rule: opts.rule,
            self_intersections: pairs.len(),
            resolve: r.report,
            seconds: start.elapsed().as_secs_f64(),
        })
    })?
}
