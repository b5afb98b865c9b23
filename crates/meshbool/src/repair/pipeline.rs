//! The repair pipeline: the repair steps composed in a fixed order under one
//! configuration, with one report of what every step did.

use serde::{Deserialize, Serialize};

use super::{
    cap_holes, cap_small_holes, curtain, orient, remove_degenerates, remove_duplicates,
    remove_folds, remove_overlapping, resolve_t_junctions, resolve_t_junctions_within, stitch,
    weld_boundary, weld_within, CapReport, CurtainReport, DegenerateOptions, DegenerateReport,
    DuplicateReport, Facing, FoldReport, OrientReport, SnapReport, StitchReport, TJunctionReport,
    WeldReport,
};
use crate::measure::{mesh_stats, MeshStats};
use crate::stage::Stage;
use crate::{Error, Mesh};

/// How [`close`] turns an open mesh into a solid.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CloseMode {
    /// Leave boundaries open.
    #[default]
    None,
    /// Triangulate every boundary loop ([`cap_holes`]).
    Cap,
    /// Join pairs of loops with bands ([`stitch`]); unpaired loops stay open.
    Stitch,
    /// Walls from every loop down to a floor, floor capped ([`curtain`]).
    Curtain,
    /// Stitch the loops that pair up, curtain the rest.
    #[serde(rename = "stitch+curtain")]
    StitchCurtain,
}

impl CloseMode {
    /// Every mode.
    pub const ALL: [CloseMode; 5] = [
        CloseMode::None,
        CloseMode::Cap,
        CloseMode::Stitch,
        CloseMode::Curtain,
        CloseMode::StitchCurtain,
    ];

    /// The mode's name: `none`, `cap`, `stitch`, `curtain`, `stitch+curtain`.
    pub fn name(self) -> &'static str {
        match self {
            CloseMode::None => "none",
            CloseMode::Cap => "cap",
            CloseMode::Stitch => "stitch",
            CloseMode::Curtain => "curtain",
            CloseMode::StitchCurtain => "stitch+curtain",
        }
    }
}

by_name!(CloseMode, "close mode");

/// Parameters of [`close`] besides the mode.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CloseOptions {
    /// Stitch: the largest gap between two loops that may be bridged (`None`: any).
    pub stitch_max_gap: Option<f64>,
    /// Curtain: the floor lies this far below the lowest point.
    pub floor_offset: f64,
}

impl Default for CloseOptions {
    fn default() -> Self {
        CloseOptions {
            stitch_max_gap: None,
            floor_offset: 10.0,
        }
    }
}

impl CloseOptions {
    /// The options for a mesh scaled by `2^e` (closed at unit size): the distances times
    /// `2^e`, clamped to the largest `f64`; a non-finite distance stays as given, for the
    /// check to name it.
    pub(crate) fn scaled(&self, e: i32) -> CloseOptions {
        let length = |x: f64| match x.is_finite() {
            true => crate::scale::scaled(x, e).min(f64::MAX),
            false => x,
        };
        CloseOptions {
            stitch_max_gap: self.stitch_max_gap.map(length),
            floor_offset: length(self.floor_offset),
        }
    }
}

impl CloseReport {
    /// The report of a closing done at unit size, for the mesh scaled by `2^e`: the
    /// stitch's largest gap and the curtain's floor times `2^e`.
    pub(crate) fn scale_back(&mut self, e: i32) {
        if let Some(s) = &mut self.stitch {
            s.largest_gap = crate::scale::scaled(s.largest_gap, e);
        }
        if let Some(c) = &mut self.curtain {
            c.floor = crate::scale::scaled(c.floor, e);
        }
    }
}

/// What [`close`] did (the steps its mode ran).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CloseReport {
    /// Capping, for [`CloseMode::Cap`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cap: Option<CapReport>,
    /// Stitching, for the stitch modes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stitch: Option<StitchReport>,
    /// Curtain, for the curtain modes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curtain: Option<CurtainReport>,
}

/// Closes `mesh` as `mode` says. Orient the mesh first (curtains need normals up).
pub fn close(
    mesh: &Mesh,
    mode: CloseMode,
    opts: &CloseOptions,
) -> Result<(Mesh, CloseReport), Error> {
    let offset = opts.floor_offset;
    if matches!(mode, CloseMode::Curtain | CloseMode::StitchCurtain)
        && !(offset.is_finite() && offset >= 0.0)
    {
        return Err(Error::InvalidParameter(format!(
            "floor offset must be a finite number >= 0, got {offset}"
        )));
    }
    if let Some(g) = opts.stitch_max_gap {
        if g.is_nan() || g < 0.0 {
            return Err(Error::InvalidParameter(format!(
                "stitch gap must be >= 0, got {g}"
            )));
        }
    }
    if matches!(mode, CloseMode::Curtain | CloseMode::StitchCurtain) {
        // The solid's volume must stay a number: its height times its plan extent.
        if let Some(b) = mesh.bounds() {
            let height = b.max[2] - (b.min[2] - offset);
            let extent = (b.max[0] - b.min[0]).max(b.max[1] - b.min[1]);
            if !(height * extent * extent).is_finite() {
                return Err(Error::InvalidParameter(format!(
                    "floor offset {offset:e} is too large: the closed solid's volume would overflow"
                )));
            }
        }
    }
    let gap = opts.stitch_max_gap.unwrap_or(f64::INFINITY);
    let mut report = CloseReport::default();
    let out = match mode {
        CloseMode::None => mesh.clone(),
        CloseMode::Cap => {
            let (m, r) = cap_holes(mesh);
            report.cap = Some(r);
            m
        }
        CloseMode::Stitch => {
            let (m, r) = stitch(mesh, gap);
            report.stitch = Some(r);
            m
        }
        CloseMode::Curtain => {
            let (m, r) = curtain(mesh, offset);
            report.curtain = Some(r);
            m
        }
        CloseMode::StitchCurtain => {
            let (m, r) = stitch(mesh, gap);
            report.stitch = Some(r);
            let (m, r) = curtain(&m, offset);
            report.curtain = Some(r);
            m
        }
    };
    Ok((out, report))
}

/// Which repair steps to run, and how. Steps run in this order: weld, duplicates, boundary
/// weld, T-junctions, degenerates, snap, orientation, folds, close, close small gaps. The default
/// only makes orientation consistent (keeping the majority's facing). Every step is exact
/// unless given a distance. Reads from and writes to JSON (the CLI's `--config`): fields
/// left out take their defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RepairConfig {
    /// Weld vertices within this distance ([`weld_within`]).
    pub weld: Option<f64>,
    /// Remove duplicate triangles; anti-parallel pairs cancel ([`remove_duplicates`]).
    pub remove_duplicates: bool,
    /// Remove duplicates as `remove_duplicates` does, taking triangles whose corresponding
    /// corners are within this distance as copies ([`remove_overlapping`]); setting it runs
    /// the duplicates step.
    pub remove_overlapping: Option<f64>,
    /// Weld boundary vertices (ends of edges used by one triangle) within this distance,
    /// the others left as they are ([`weld_boundary`]).
    pub weld_boundary: Option<f64>,
    /// Split boundary edges at vertices exactly on them ([`resolve_t_junctions`]).
    pub tjunctions: bool,
    /// Split boundary edges also at vertices within this distance of them
    /// ([`resolve_t_junctions_within`]; 0: exactly on them); setting it runs the T-junction
    /// step.
    pub tjunction_tolerance: Option<f64>,
    /// Remove degenerate (and, with thresholds, sliver) triangles ([`remove_degenerates`]).
    pub degenerate: Option<DegenerateOptions>,
    /// Collapse edges shorter than this distance and remove needles (altitude below it)
    /// where that makes no defect ([`super::snap`]).
    pub snap: Option<f64>,
    /// Make orientation consistent, facing as given ([`orient`]); `None` skips it.
    pub orient: Option<Facing>,
    /// Remove the folds of a terrain-like surface ([`remove_folds`]); needs `orient` to be
    /// [`Facing::ZUp`].
    pub remove_folds: bool,
    /// Close into a solid ([`close`]).
    pub close: CloseMode,
    /// Parameters of the close step.
    pub close_options: CloseOptions,
    /// Finally cap every hole left whose bounding-box diagonal is at most this
    /// ([`cap_small_holes`]).
    pub close_gaps: Option<f64>,
    /// Undo every step that makes the mesh worse (on by default): more boundary edges,
    /// non-manifold edges, orientation conflicts or self-intersecting pairs than its input
    /// had, no triangles left, or a closed mesh's volume changed by more than
    /// `gate_volume`. An undone step is listed in [`RepairReport::undone`] with what it
    /// would have made worse; `false` keeps every step's result as it is.
    pub gate: bool,
    /// The largest relative change of a closed, consistently oriented mesh's volume a
    /// step may make under the gate (default 0.005: half a percent); the volume of a mesh
    /// that is not closed is not judged.
    pub gate_volume: f64,
}

impl Default for RepairConfig {
    fn default() -> Self {
        RepairConfig {
            weld: None,
            remove_duplicates: false,
            remove_overlapping: None,
            weld_boundary: None,
            tjunctions: false,
            tjunction_tolerance: None,
            degenerate: None,
            snap: None,
            orient: Some(Facing::Majority),
            remove_folds: false,
            close: CloseMode::None,
            close_options: CloseOptions::default(),
            close_gaps: None,
            gate: true,
            gate_volume: 0.005,
        }
    }
}

impl RepairConfig {
    /// Checks the parameters before any work: distances finite and ≥ 0, fold removal
    /// only on a surface oriented up, the degenerate thresholds
    /// ([`DegenerateOptions::validate`]), and, with `snap`, finite coordinates in `mesh`.
    pub(crate) fn check(&self, mesh: &Mesh) -> Result<(), Error> {
        let distance = |name: &str, x: Option<f64>| match x {
            Some(d) if !(d.is_finite() && d >= 0.0) => Err(Error::InvalidParameter(format!(
                "{name} must be a finite distance >= 0, got {d}"
            ))),
            _ => Ok(()),
        };
        distance("weld", self.weld)?;
        distance("remove_overlapping", self.remove_overlapping)?;
        distance("weld_boundary", self.weld_boundary)?;
        distance("tjunction_tolerance", self.tjunction_tolerance)?;
        distance("close_gaps", self.close_gaps)?;
        distance("snap", self.snap)?;
        if !(self.gate_volume.is_finite() && self.gate_volume >= 0.0) {
            return Err(Error::InvalidParameter(format!(
                "gate_volume must be a finite fraction >= 0, got {}",
                self.gate_volume
            )));
        }
        if self.snap.is_some() {
            mesh.validate()?; // the snap's exact tests need finite coordinates
        }
        if self.remove_folds && self.orient != Some(Facing::ZUp) {
            return Err(Error::InvalidParameter(
                "fold removal works on a surface oriented up: set orient to z-up".into(),
            ));
        }
        if let Some(d) = &self.degenerate {
            d.validate()?;
        }
        Ok(())
    }

    /// The configuration for `mesh` scaled by `2^e` (a mesh of extreme magnitude repaired
    /// at unit size): distances times `2^e`, the area threshold `2^2e` (clamped to the
    /// largest `f64`), the aspect threshold as it is.
    pub(crate) fn scaled(&self, e: i32) -> RepairConfig {
        let length = |x: f64| crate::scale::scaled(x, e).min(f64::MAX);
        let area = |x: f64| length(length(x));
        RepairConfig {
            weld: self.weld.map(length),
            remove_overlapping: self.remove_overlapping.map(length),
            weld_boundary: self.weld_boundary.map(length),
            tjunction_tolerance: self.tjunction_tolerance.map(length),
            degenerate: self.degenerate.map(|d| DegenerateOptions {
                min_area: area(d.min_area),
                ..d
            }),
            snap: self.snap.map(length),
            close_options: self.close_options.scaled(e),
            close_gaps: self.close_gaps.map(length),
            ..self.clone()
        }
    }
}

impl RepairReport {
    /// The report of a repair done at unit size, for the mesh scaled by `2^e`: lengths
    /// times `2^e`, areas `2^2e`, volumes `2^3e`.
    pub(crate) fn scale_back(&mut self, e: i32) {
        let length = |x: &mut f64| *x = crate::scale::scaled(*x, e);
        let volume = |x: &mut f64| *x = crate::scale::scaled_measure(*x, e, 3);
        self.before.scale_back(e);
        self.after.scale_back(e);
        if let Some(d) = &mut self.duplicates {
            length(&mut d.largest_distance);
        }
        if let Some(t) = &mut self.tjunctions {
            length(&mut t.largest_distance);
        }
        if let Some(d) = &mut self.degenerate {
            volume(&mut d.volume_change);
        }
        if let Some(s) = &mut self.snap {
            s.scale_back(e);
        }
        if let Some(c) = &mut self.close {
            c.scale_back(e);
        }
    }
}

/// What [`repair`] did: the measures before and after and the report of every step that
/// ran (`None`: not asked for). Every triangle removed is counted in some step's report;
/// a step in [`undone`](Self::undone) removed nothing from the result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RepairReport {
    /// The input's measures.
    pub before: MeshStats,
    /// Tolerance weld.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weld: Option<WeldReport>,
    /// Duplicate (or overlapping) triangle removal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub duplicates: Option<DuplicateReport>,
    /// Boundary weld.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weld_boundary: Option<WeldReport>,
    /// T-junction resolution.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tjunctions: Option<TJunctionReport>,
    /// Degenerate removal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub degenerate: Option<DegenerateReport>,
    /// Snapping.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub snap: Option<SnapReport>,
    /// Orientation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orient: Option<OrientReport>,
    /// Fold removal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub folds: Option<FoldReport>,
    /// Closing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub close: Option<CloseReport>,
    /// Capping the small holes left.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub close_gaps: Option<CapReport>,
    /// The steps undone because they made the mesh worse ([`RepairConfig::gate`]), in
    /// the order they ran. Their reports above say what they did before being undone.
    pub undone: Vec<UndoneStep>,
    /// Vertices no triangle uses any more (left by welding, collapses, fold removal or
    /// in the input), dropped at the end.
    pub unreferenced_removed: usize,
    /// The result's measures.
    pub after: MeshStats,
}

/// Runs the repair steps `config` asks for on `mesh`, in the order of
/// [`RepairConfig`]. Errors only on invalid parameters (negative or non-finite
/// distances) and, with `snap`, on a mesh with a non-finite coordinate, before any work.
pub fn repair(mesh: &Mesh, config: &RepairConfig) -> Result<(Mesh, RepairReport), Error> {
    repair_with_progress(mesh, config, &|_| {})
}

/// [`repair`], calling `progress` with each step's [`Stage`] as it begins (only the steps
/// that run, in their order).
pub fn repair_with_progress(
    mesh: &Mesh,
    config: &RepairConfig,
    progress: &dyn Fn(Stage),
) -> Result<(Mesh, RepairReport), Error> {
    config.check(mesh)?;
    let mut report = RepairReport {
        before: mesh_stats(mesh),
        weld: None,
        duplicates: None,
        weld_boundary: None,
        tjunctions: None,
        degenerate: None,
        snap: None,
        orient: None,
        folds: None,
        close: None,
        close_gaps: None,
        undone: Vec::new(),
        unreferenced_removed: 0,
        after: mesh_stats(&Mesh::default()),
    };
    // The steps asked for, in their order: each runs on the mesh as it stands and says
    // what it did in its field of the report. `moves`: it moves vertices or adds
    // triangles, so it may make self-intersections.
    let mut steps: Vec<Step> = Vec::new();
    let RepairReport {
        weld,
        duplicates,
        weld_boundary: boundary_weld,
        tjunctions,
        degenerate,
        snap,
        orient: oriented,
        folds,
        close: closed,
        close_gaps,
        ..
    } = &mut report;
    if let Some(tol) = config.weld {
        steps.push(Step::new(Stage::Weld, true, move |m| {
            let (x, w) = weld_within(m, tol);
            *weld = Some(w);
            Ok(x)
        }));
    }
    if let Some(tol) = config.remove_overlapping {
        steps.push(Step::new(Stage::Duplicates, false, move |m| {
            let (x, d) = remove_overlapping(m, tol);
            *duplicates = Some(d);
            Ok(x)
        }));
    } else if config.remove_duplicates {
        steps.push(Step::new(Stage::Duplicates, false, move |m| {
            let (x, d) = remove_duplicates(m);
            *duplicates = Some(d);
            Ok(x)
        }));
    }
    if let Some(tol) = config.weld_boundary {
        steps.push(Step::new(Stage::WeldBoundary, true, move |m| {
            let (x, w) = weld_boundary(m, tol);
            *boundary_weld = Some(w);
            Ok(x)
        }));
    }
    if let Some(tol) = config.tjunction_tolerance {
        // Within a distance the edge bends through the vertex: geometry moves.
        steps.push(Step::new(Stage::TJunctions, tol > 0.0, move |m| {
            let (x, t) = resolve_t_junctions_within(m, tol);
            *tjunctions = Some(t);
            Ok(x)
        }));
    } else if config.tjunctions {
        steps.push(Step::new(Stage::TJunctions, false, move |m| {
            let (x, t) = resolve_t_junctions(m);
            *tjunctions = Some(t);
            Ok(x)
        }));
    }
    if let Some(opts) = &config.degenerate {
        steps.push(Step::new(Stage::Degenerate, true, move |m| {
            let (x, d) = remove_degenerates(m, opts);
            *degenerate = Some(d);
            Ok(x)
        }));
    }
    if let Some(tol) = config.snap {
        let opts = super::SnapOptions {
            tolerance: tol,
            ..Default::default()
        };
        // The snap makes no self-intersection, by its own exact test.
        steps.push(Step::new(Stage::Snap, false, move |m| {
            let mut x = m.clone();
            *snap = Some(super::snap_unchecked(&mut x, &opts).0);
            Ok(x)
        }));
    }
    if let Some(facing) = config.orient {
        steps.push(Step::new(Stage::Orient, false, move |m| {
            let (x, o) = orient(m, facing);
            *oriented = Some(o);
            Ok(x)
        }));
    }
    if config.remove_folds {
        steps.push(Step::new(Stage::Folds, true, move |m| {
            let (x, f) = remove_folds(m);
            *folds = Some(f);
            Ok(x)
        }));
    }
    if config.close != CloseMode::None {
        steps.push(Step::new(Stage::Close, true, move |m| {
            let (x, c) = close(m, config.close, &config.close_options)?;
            *closed = Some(c);
            Ok(x)
        }));
    }
    if let Some(size) = config.close_gaps {
        steps.push(Step::new(Stage::CloseGaps, true, move |m| {
            let (x, c) = cap_small_holes(m, size);
            *close_gaps = Some(c);
            Ok(x)
        }));
    }
    let gate = Gate {
        on: config.gate,
        volume: config.gate_volume,
        orient_at: steps.iter().position(|s| s.stage == Stage::Orient),
    };
    let (m, undone) = gate.run(mesh, &mut steps, progress)?;
    drop(steps);
    report.undone = undone;
    let (m, unreferenced) = m.without_unreferenced();
    report.unreferenced_removed = unreferenced;
    report.after = mesh_stats(&m);
    Ok((m, report))
}

/// A repair step undone because it made the mesh worse ([`RepairConfig::gate`]).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct UndoneStep {
    /// The step, by its key in the report (`weld`, `duplicates`, …: [`Stage::name`]).
    pub step: &'static str,
    /// What it would have made worse, a line each (`non-manifold edges 0 -> 2`).
    pub damage: Vec<String>,
}

/// How a step runs: the mesh in, its result out (its report written aside).
type RunStep<'a> = Box<dyn FnMut(&Mesh) -> Result<Mesh, Error> + 'a>;

/// A step of the pipeline: its stage, whether it moves vertices or adds triangles, and
/// how it runs.
struct Step<'a> {
    stage: Stage,
    moves: bool,
    run: RunStep<'a>,
}

impl<'a> Step<'a> {
    fn new(stage: Stage, moves: bool, run: impl FnMut(&Mesh) -> Result<Mesh, Error> + 'a) -> Self {
        Step {
            stage,
            moves,
            run: Box::new(run),
        }
    }
}

/// What the gate compares between a mesh before some steps and after them.
#[derive(Clone, Copy, Debug)]
struct Quality {
    empty: bool,
    boundary: usize,
    non_manifold: usize,
    /// Edges two triangles use the same way.
    inconsistent: usize,
    /// Manifold edges that stay inconsistent once oriented (measured when needed).
    conflicting: Option<usize>,
    /// Pairs of triangles crossing (measured when needed).
    crossings: Option<usize>,
    volume: f64,
}

impl Quality {
    fn of(m: &Mesh) -> Quality {
        let counts = crate::edges::EdgeCounts::of(m);
        Quality {
            empty: m.is_empty(),
            boundary: counts.boundary,
            non_manifold: counts.non_manifold,
            inconsistent: counts.inconsistent,
            conflicting: None,
            crossings: None,
            volume: crate::measure::signed_volume(m),
        }
    }

    /// Closed, manifold and consistently oriented: its volume means something.
    fn sound(&self) -> bool {
        !self.empty && self.boundary == 0 && self.non_manifold == 0 && self.inconsistent == 0
    }

    fn conflicting(&mut self, m: &Mesh) -> usize {
        *self
            .conflicting
            .get_or_insert_with(|| orient(m, Facing::Majority).1.conflicting_edges)
    }

    fn crossings(&mut self, m: &Mesh) -> usize {
        *self
            .crossings
            .get_or_insert_with(|| crate::intersect::self_intersections(m).len())
    }
}

/// The repair pipeline's gate ([`RepairConfig::gate`]).
///
/// The mesh is kept as it stood before the first step that made it worse (the *kept*
/// mesh); the steps after that one run on its result, and as soon as the mesh is no worse
/// than the kept one again, every step since is kept (a double wall cancelled opens a
/// closed mesh that the boundary weld after it closes). When the pipeline ends worse
/// than the kept mesh, the first of those steps is undone and the ones after it run
/// again on the kept mesh, judged the same way.
struct Gate {
    on: bool,
    volume: f64,
    /// The orientation step's place among the steps: before it, orientation is judged by
    /// the conflicts orienting would leave (a weld of a mixed-up soup makes edges
    /// inconsistent that orientation then mends); from it on (or with no orientation
    /// step), by the inconsistent edges themselves.
    orient_at: Option<usize>,
}

impl Gate {
    /// Runs `steps` on `mesh` under the gate, announcing each to `progress`: the result
    /// and the steps undone.
    fn run(
        &self,
        mesh: &Mesh,
        steps: &mut [Step],
        progress: &dyn Fn(Stage),
    ) -> Result<(Mesh, Vec<UndoneStep>), Error> {
        let mut kept = mesh.clone();
        let mut kept_quality = None;
        let mut undone = Vec::new();
        let mut from = 0;
        loop {
            // Steps run since the kept mesh (with the first one's damage) and their result.
            let mut held: Option<(usize, Vec<String>, Mesh, Quality)> = None;
            let mut moved = false;
            for (i, step) in steps.iter_mut().enumerate().skip(from) {
                progress(step.stage);
                let input = held.as_ref().map_or(&kept, |h| &h.2);
                let next = (step.run)(input)?;
                if !self.on {
                    kept = next;
                    continue;
                }
                if next == *input {
                    continue;
                }
                moved |= step.moves;
                let base = kept_quality.get_or_insert_with(|| Quality::of(&kept));
                let mut after = Quality::of(&next);
                let oriented = self.orient_at.is_none_or(|o| o <= i);
                let damage = self.damage(base, &kept, &mut after, &next, oriented, moved);
                if damage.is_empty() {
                    (kept, kept_quality, held, moved) = (next, Some(after), None, false);
                } else {
                    held = Some(match held {
                        Some((first, d, _, _)) => (first, d, next, after),
                        None => (i, damage, next, after),
                    });
                }
            }
            match held {
                None => return Ok((kept, undone)),
                Some((first, damage, _, _)) => {
                    undone.push(UndoneStep {
                        step: steps[first].stage.name(),
                        damage,
                    });
                    from = first + 1;
                }
            }
        }
    }

    /// What `after` (of `next`) has worse than `before` (of `kept`), a line each.
    /// `oriented`: judge orientation by inconsistent edges, not by what orienting leaves;
    /// `moved`: compare self-intersections.
    fn damage(
        &self,
        before: &mut Quality,
        kept: &Mesh,
        after: &mut Quality,
        next: &Mesh,
        oriented: bool,
        moved: bool,
    ) -> Vec<String> {
        let mut damage = Vec::new();
        let mut worse = |what: &str, a: usize, b: usize| {
            if b > a {
                damage.push(format!("{what} {a} -> {b}"));
            }
        };
        if before.boundary == 0 && after.boundary > 0 && !before.empty {
            worse("opens the mesh: boundary edges", 0, after.boundary);
        } else {
            worse("boundary edges", before.boundary, after.boundary);
        }
        worse(
            "non-manifold edges",
            before.non_manifold,
            after.non_manifold,
        );
        if oriented {
            worse(
                "inconsistent edges",
                before.inconsistent,
                after.inconsistent,
            );
        } else {
            let (a, b) = (before.conflicting(kept), after.conflicting(next));
            worse("edges no orientation makes consistent", a, b);
        }
        if moved {
            let (a, b) = (before.crossings(kept), after.crossings(next));
            worse("self-intersecting pairs", a, b);
        }
        if after.empty && !before.empty {
            damage.push("removes every triangle".to_string());
        }
        if before.sound() && after.sound() && before.volume != 0.0 {
            let change = (after.volume.abs() - before.volume.abs()) / before.volume.abs();
            if change.abs() > self.volume {
                damage.push(format!(
                    "volume {} -> {} ({:+.3} %)",
                    before.volume.abs(),
                    after.volume.abs(),
                    100.0 * change
                ));
            }
        }
        damage
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube broken in every way the pipeline mends: a 1e-4 crack (weld), a
    /// duplicated triangle and an anti-parallel pair (duplicates), a flipped triangle
    /// (orientation) and a missing face (cap).
    fn broken_cube() -> Mesh {
        let mut m = Mesh::unit_cube();
        // Crack: a copy of vertex 0 moved by 1e-4, used by the first triangle using 0.
        let t = m.triangles.iter().position(|t| t.contains(&0)).unwrap_or(0);
        let p = m.positions[0];
        m.positions.push([p[0] + 1e-4, p[1], p[2]]);
        let copy = (m.positions.len() - 1) as u32;
        for v in &mut m.triangles[t] {
            if *v == 0 {
                *v = copy;
            }
        }
        // A missing face: the last two triangles (face of the cube not touching t).
        let last = m.triangles.len() - 2;
        m.triangles.truncate(last);
        // A duplicate, an anti-parallel pair, a flipped triangle.
        m.triangles.push(m.triangles[1]);
        let [a, b, c] = m.triangles[2];
        m.triangles.push([a, b, c]);
        m.triangles.push([a, c, b]);
        m.triangles[3] = [m.triangles[3][0], m.triangles[3][2], m.triangles[3][1]];
        m
    }

    #[test]
    fn the_pipeline_mends_a_broken_cube_and_counts_every_step() {
        let m = broken_cube();
        let config = RepairConfig {
            weld: Some(1e-3),
            remove_duplicates: true,
            orient: Some(Facing::Outward),
            close: CloseMode::Cap,
            ..RepairConfig::default()
        };
        let (r, rep) = repair(&m, &config).expect("valid config");
        assert!(!rep.before.closed);
        assert!(rep.before.inconsistent_edges > 0);
        let a = &rep.after;
        assert_eq!(
            (
                a.boundary_edges,
                a.non_manifold_edges,
                a.inconsistent_edges,
                a.closed
            ),
            (0, 0, 0, true)
        );
        assert_eq!(a.volume, 1.0);
        assert_eq!(r.triangles.len(), 12);
        assert_eq!((r.positions.len(), a.unreferenced_vertices), (8, 0));
        assert_eq!(rep.weld.as_ref().map(|w| w.merged_vertices), Some(1));
        let d = rep.duplicates.as_ref().expect("ran");
        assert_eq!(
            (d.same_orientation_removed, d.anti_parallel_removed),
            (1, 2)
        );
        assert_eq!(rep.orient.as_ref().map(|o| o.flipped), Some(1));
        let cap = rep
            .close
            .as_ref()
            .and_then(|c| c.cap.clone())
            .expect("capped");
        assert_eq!((cap.loops, cap.capped, cap.triangles_added), (1, 1, 2));
        assert!(rep.tjunctions.is_none() && rep.degenerate.is_none() && rep.close_gaps.is_none());
    }

    #[test]
    fn unused_vertices_are_dropped_and_counted() {
        let mut m = Mesh::unit_cube();
        m.positions.insert(0, [5.0, 5.0, 5.0]);
        m.positions.push([7.0, 7.0, 7.0]);
        for t in &mut m.triangles {
            *t = t.map(|v| v + 1);
        }
        let (r, rep) = repair(&m, &RepairConfig::default()).expect("valid config");
        assert_eq!(rep.before.unreferenced_vertices, 2);
        assert_eq!(rep.unreferenced_removed, 2);
        assert_eq!((r.positions.len(), rep.after.unreferenced_vertices), (8, 0));
        assert_eq!(rep.after.volume, 1.0);
        assert!(rep.after.closed);
    }

    #[test]
    fn close_gaps_caps_small_holes_only() {
        // A sphere with one small hole (the fan at the north pole removed: a 16-gon of
        // radius sin(pi/8), box diagonal about 1.08) and a large one on the side.
        let s = crate::shapes::uv_sphere([0.0; 3], 1.0, 16, 8);
        let pole: Vec<usize> = (0..s.triangles.len())
            .filter(|&t| s.corners(t).iter().any(|p| p[2] == 1.0))
            .collect();
        let equator: Vec<usize> = (0..s.triangles.len())
            .filter(|&t| s.corners(t).iter().all(|p| p[2].abs() < 0.75) && s.corners(t)[0][0] > 0.0)
            .collect();
        let mut m = s.clone();
        m.triangles = (0..s.triangles.len())
            .filter(|t| !pole.contains(t) && !equator.contains(t))
            .map(|t| s.triangles[t])
            .collect();
        let (_, before) = super::super::boundary_loops(&m);
        assert_eq!(before, 0);
        let config = RepairConfig {
            close_gaps: Some(1.2),
            ..RepairConfig::default()
        };
        let (r, rep) = repair(&m, &config).expect("valid");
        let cap = rep.close_gaps.expect("ran");
        assert_eq!((cap.loops, cap.capped), (2, 1));
        // The large hole stays: its boundary edges are all that is left.
        assert!(rep.after.boundary_edges > 0);
        assert_eq!(rep.after.boundary_edges + 16, rep.before.boundary_edges);
        assert_eq!(r.triangles.len(), m.triangles.len() + 14);
    }

    #[test]
    fn invalid_parameters_are_refused_before_any_work() {
        let m = Mesh::unit_cube();
        for config in [
            RepairConfig {
                weld: Some(-1.0),
                ..RepairConfig::default()
            },
            RepairConfig {
                weld: Some(f64::NAN),
                ..RepairConfig::default()
            },
            RepairConfig {
                close_gaps: Some(f64::INFINITY),
                ..RepairConfig::default()
            },
            RepairConfig {
                tjunction_tolerance: Some(-1e-3),
                ..RepairConfig::default()
            },
            RepairConfig {
                remove_overlapping: Some(f64::NAN),
                ..RepairConfig::default()
            },
            RepairConfig {
                weld_boundary: Some(f64::INFINITY),
                ..RepairConfig::default()
            },
            RepairConfig {
                remove_folds: true,
                ..RepairConfig::default()
            },
            RepairConfig {
                close: CloseMode::Curtain,
                close_options: CloseOptions {
                    floor_offset: -2.0,
                    ..CloseOptions::default()
                },
                ..RepairConfig::default()
            },
        ] {
            assert!(
                matches!(repair(&m, &config), Err(Error::InvalidParameter(_))),
                "{config:?}"
            );
        }
    }

    #[test]
    fn config_reads_from_json_with_defaults() {
        let c: RepairConfig = serde_json::from_str(
            r#"{"weld": 0.01, "close": "stitch+curtain", "close_options": {"floor_offset": 5}}"#,
        )
        .expect("parses");
        assert_eq!(c.weld, Some(0.01));
        assert_eq!(c.close, CloseMode::StitchCurtain);
        assert_eq!(c.close_options.floor_offset, 5.0);
        assert_eq!(c.orient, Some(Facing::Majority));
        let back: RepairConfig =
            serde_json::from_str(&serde_json::to_string(&c).expect("writes")).expect("reads");
        assert_eq!(back, c);
        assert!(serde_json::from_str::<RepairConfig>(r#"{"wled": 1}"#).is_err());
        // The distances of the toleranced steps: keys of their own, `tjunctions: true`
        // still the exact step.
        let c: RepairConfig = serde_json::from_str(
            r#"{"tjunctions": true, "tjunction_tolerance": 0.001, "remove_overlapping": 0.01,
                "weld_boundary": 0.1}"#,
        )
        .expect("parses");
        assert!(c.tjunctions);
        assert_eq!(
            (c.tjunction_tolerance, c.remove_overlapping, c.weld_boundary),
            (Some(0.001), Some(0.01), Some(0.1))
        );
        let c: RepairConfig = serde_json::from_str(r#"{"tjunctions": true}"#).expect("parses");
        assert_eq!((c.tjunctions, c.tjunction_tolerance), (true, None));
    }

    #[test]
    fn invalid_distances_name_their_key() {
        let m = Mesh::unit_cube();
        for (config, key) in [
            (
                RepairConfig {
                    tjunction_tolerance: Some(-1.0),
                    ..RepairConfig::default()
                },
                "tjunction_tolerance must be a finite distance >= 0, got -1",
            ),
            (
                RepairConfig {
                    remove_overlapping: Some(f64::NEG_INFINITY),
                    ..RepairConfig::default()
                },
                "remove_overlapping must be a finite distance >= 0, got -inf",
            ),
            (
                RepairConfig {
                    weld_boundary: Some(f64::NAN),
                    ..RepairConfig::default()
                },
                "weld_boundary must be a finite distance >= 0, got NaN",
            ),
        ] {
            match repair(&m, &config) {
                Err(Error::InvalidParameter(msg)) => assert_eq!(msg, key),
                other => panic!("{other:?}"),
            }
        }
    }

    /// The unit cube as two closed boxes stacked at z = 0.5, the upper one's bottom face
    /// (its own vertices, facing down) lifted by `gap`: a double wall `gap` thick.
    fn stacked(gap: f64) -> Mesh {
        let mut m = Mesh::cuboid([0.0; 3], [1.0, 1.0, 0.5]);
        let mut high = Mesh::cuboid([0.0; 3], [1.0; 3]);
        for p in &mut high.positions {
            if p[2] == 0.0 {
                p[2] = 0.5 + gap;
            }
        }
        let off = m.positions.len() as u32;
        m.positions.extend(&high.positions);
        m.triangles
            .extend(high.triangles.iter().map(|t| t.map(|v| v + off)));
        m
    }

    #[test]
    fn a_near_double_wall_goes_and_the_boundary_weld_closes_the_cut() {
        let m = stacked(1e-4);
        let config = RepairConfig {
            remove_overlapping: Some(1e-3),
            weld_boundary: Some(1e-3),
            ..RepairConfig::default()
        };
        let (r, rep) = repair(&m, &config).expect("valid");
        let d = rep.duplicates.expect("ran");
        assert_eq!(
            (d.same_orientation_removed, d.anti_parallel_removed),
            (0, 4)
        );
        assert_eq!(d.largest_distance, (0.5f64 + 1e-4) - 0.5);
        let w = rep.weld_boundary.expect("ran");
        assert_eq!((w.merged_vertices, w.collapsed_triangles), (4, 0));
        let a = &rep.after;
        assert_eq!(
            (
                a.boundary_edges,
                a.non_manifold_edges,
                a.inconsistent_edges,
                a.closed
            ),
            (0, 0, 0, true)
        );
        assert_eq!(
            (r.triangles.len(), r.positions.len(), a.volume),
            (20, 12, 1.0)
        );
        // Exactly: the walls are not coincident, nothing goes; two closed boxes, so no
        // boundary to weld either.
        let exact = RepairConfig {
            remove_duplicates: true,
            weld_boundary: Some(1e-3),
            ..RepairConfig::default()
        };
        let (r, rep) = repair(&m, &exact).expect("valid");
        let d = rep.duplicates.expect("ran");
        assert_eq!((d.anti_parallel_removed, d.largest_distance), (0, 0.0));
        assert_eq!(rep.weld_boundary.map(|w| w.merged_vertices), Some(0));
        assert_eq!((r.triangles.len(), rep.after.closed), (24, true));
    }

    /// `repair` with only a weld at `d` (orientation as by default), gated or not.
    fn weld_only(m: &Mesh, d: f64, gate: bool) -> (Mesh, RepairReport) {
        let config = RepairConfig {
            weld: Some(d),
            gate,
            ..RepairConfig::default()
        };
        repair(m, &config).expect("valid config")
    }

    #[test]
    fn a_weld_that_would_join_two_solids_is_undone() {
        // Two unit cubes 1e-5 apart: welding at 1e-4 makes their facing sides one
        // (edges of four triangles, a double wall).
        let mut m = Mesh::unit_cube();
        m.append(&Mesh::cuboid([1.0 + 1e-5, 0.0, 0.0], [2.0, 1.0, 1.0]))
            .unwrap();
        let (r, rep) = weld_only(&m, 1e-4, true);
        eprintln!("DEBUG {:?} {:?}", rep.undone, rep.weld);
        assert_eq!(rep.undone.len(), 1);
        let u = &rep.undone[0];
        assert_eq!(u.step, "weld");
        // The four edges of the facing squares and their common diagonal; the two
        // triangles of each square lie on each other.
        assert_eq!(
            u.damage,
            [
                "non-manifold edges 0 -> 5",
                "self-intersecting pairs 0 -> 2"
            ]
        );
        assert_eq!(r, m.clone().without_unreferenced().0); // as it was, vertices in order of use
        assert!(rep.after.closed);
        assert_eq!(rep.after.volume, rep.before.volume);
        // Ungated, the weld is kept, and the mesh is no longer manifold.
        let (_, rep) = weld_only(&m, 1e-4, false);
        assert!(rep.undone.is_empty());
        assert_eq!(rep.after.non_manifold_edges, 5);
        assert!(!rep.after.closed);
    }

    /// A unit cube with a hip roof of height 0.3 whose ridge, along y, is `2 * half`
    /// long, oriented outward.
    fn hip_roofed_cube(half: f64) -> Mesh {
        let (mut positions, mut triangles) = Mesh::unit_cube().into_parts();
        triangles.retain(|t| t.iter().any(|&v| positions[v as usize][2] < 1.0));
        let corner = |p: [f64; 3]| positions.iter().position(|q| *q == p).unwrap() as u32;
        let [t0, t1, t2, t3] = [[0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]].map(corner);
        let (c, r) = (positions.len() as u32, positions.len() as u32 + 1);
        positions.push([0.5, 0.5 - half, 1.3]);
        positions.push([0.5, 0.5 + half, 1.3]);
        triangles.extend([
            [t0, t1, c],
            [t1, t2, r],
            [t1, r, c],
            [t2, t3, r],
            [t3, t0, c],
            [t3, c, r],
        ]);
        orient(&Mesh::new(positions, triangles).unwrap(), Facing::Outward).0
    }

    #[test]
    fn a_step_that_changes_a_solids_volume_beyond_the_gate_is_undone() {
        // Welding the hip roof's ridge (1e-4 long) into a point: still closed and
        // manifold, the volume 0.3 * 1e-4 / 6 = 5e-6 less (0.0004 %).
        let m = hip_roofed_cube(5e-5);
        let before = mesh_stats(&m);
        assert!(before.closed && before.inconsistent_edges == 0);
        let (r, rep) = weld_only(&m, 1e-3, true);
        assert!(rep.undone.is_empty(), "{:?}", rep.undone);
        assert_eq!(
            rep.weld.map(|w| (w.merged_vertices, w.collapsed_triangles)),
            Some((1, 2))
        );
        assert!(rep.after.closed);
        let change = (rep.after.volume - before.volume) / before.volume;
        assert!((change + 5e-6 / before.volume).abs() < 1e-12, "{change}");
        assert_eq!(r.triangles.len(), m.triangles.len() - 2);
        // Under a gate of 1e-6 (0.0001 %) the same weld is undone.
        let strict = RepairConfig {
            weld: Some(1e-3),
            gate_volume: 1e-6,
            ..RepairConfig::default()
        };
        let (r, rep) = repair(&m, &strict).expect("valid");
        assert_eq!(rep.undone.len(), 1);
        let damage = &rep.undone[0].damage;
        assert!(
            damage.len() == 1 && damage[0].starts_with("volume "),
            "{damage:?}"
        );
        assert_eq!(r, m.clone().without_unreferenced().0); // as it was, vertices in order of use
        let bad = RepairConfig {
            gate_volume: -1.0,
            ..RepairConfig::default()
        };
        assert!(matches!(repair(&m, &bad), Err(Error::InvalidParameter(_))));
    }

    #[test]
    fn a_weld_that_would_make_a_crossing_is_undone() {
        // A floor fanned around its centre c; a sheet 5e-4 above it; a wall standing on
        // the sheet from 1e-3 above c. Welding at 2e-3 brings the wall's foot down to c,
        // through the sheet: one crossing that was not there, and nothing else worse.
        let e = 1e-3;
        let positions = vec![
            [0.5, 0.5, 0.0],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, e],
            [0.5, 0.5, 1.0],
            [0.6, 0.5, 1.0],
            [0.3, 0.3, e / 2.0],
            [0.7, 0.3, e / 2.0],
            [0.5, 0.8, e / 2.0],
        ];
        let triangles = vec![
            [0, 1, 2],
            [0, 2, 3],
            [0, 3, 4],
            [0, 4, 1],
            [5, 6, 7],
            [8, 9, 10],
        ];
        let m = Mesh::new(positions, triangles).unwrap();
        assert!(crate::intersect::self_intersections(&m).is_empty());
        let (r, rep) = weld_only(&m, 2.0 * e, true);
        assert_eq!(rep.weld.as_ref().map(|w| w.merged_vertices), Some(1));
        assert_eq!(
            rep.undone,
            vec![UndoneStep {
                step: "weld",
                damage: vec!["self-intersecting pairs 0 -> 1".to_string()],
            }]
        );
        assert_eq!(r, m.clone().without_unreferenced().0); // as it was, vertices in order of use
        let (r, _) = weld_only(&m, 2.0 * e, false);
        assert_eq!(crate::intersect::self_intersections(&r).len(), 1);
    }

    #[test]
    fn a_weld_of_a_mixed_up_soup_is_kept_for_the_orientation_step_to_mend() {
        // A cube as a soup, each triangle's corners moved apart by up to 3e-7 and one
        // triangle turned over: welded, its edges are inconsistent, which orienting
        // mends; judged by what orienting leaves, the weld makes nothing worse.
        let cube = Mesh::unit_cube();
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for (i, t) in cube.triangles.iter().enumerate() {
            let base = positions.len() as u32;
            for (k, &v) in t.iter().enumerate() {
                let p = cube.positions[v as usize];
                let jitter = 1e-7 * ((i * 3 + k) % 4) as f64;
                positions.push([p[0] + jitter, p[1] - jitter, p[2]]);
            }
            triangles.push(if i == 5 {
                [base, base + 2, base + 1]
            } else {
                [base, base + 1, base + 2]
            });
        }
        let m = Mesh::new(positions, triangles).unwrap();
        let (r, rep) = weld_only(&m, 1e-5, true);
        assert!(rep.undone.is_empty(), "{:?}", rep.undone);
        assert_eq!(rep.orient.as_ref().map(|o| o.flipped), Some(1));
        let a = &rep.after;
        assert_eq!(
            (a.boundary_edges, a.non_manifold_edges, a.inconsistent_edges),
            (0, 0, 0)
        );
        assert_eq!(r.triangles.len(), 12);
        assert!(a.closed && (a.volume - 1.0).abs() < 1e-6, "{}", a.volume);
    }
}
