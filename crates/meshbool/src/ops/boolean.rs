//! Booleans at the front door: union, intersection, difference (both ways) of two inputs,
//! with the report the CLI prints.

use serde::Serialize;

use web_time::Instant;

use crate::par::{with_threads_for, Grain};
use rayon::prelude::*;

use super::{Checks, Input, Measures, Operand, OperandReport, RunOptions, SCHEMA};
use crate::arrange::FailReason;
use crate::boolean::nary::{boolean_in_one, reduce, reduce_in_one, Part};
use crate::boolean::{CleanupReport, FailedTriangle, Op, PipelineOptions, Provenance, Stage};
use crate::repair::{NonManifoldReport, SnapOptions, SnapReport};
use crate::{Error, Mesh, Result};

/// Options of [`boolean`].
#[derive(Clone, Debug, Default)]
pub struct BooleanOptions {
    /// Checks of inputs given as meshes (operands made earlier keep theirs).
    pub checks: Checks,
    /// Keep the result's topology where it is not manifold (solids touching along an edge
    /// or at a vertex then share it). By default such edges and vertices are split so that
    /// the result is manifold ([`crate::repair::split_nonmanifold`]; positions unchanged).
    pub keep_nonmanifold: bool,
    /// Keep every seam point of the arrangement: no exact clean-up of the result. By
    /// default seam points where the result is flat or straight are removed and zero-area
    /// triangles made by rounding seam points are collapsed or flipped away, changing no
    /// geometry ([`CleanupReport`]).
    pub keep_seam_points: bool,
    /// Snap tolerance `D` (a length; 0, the default: the exact result as it is). With
    /// `D > 0` the assembled result is cleaned by [`crate::repair::snap_with`]: edges
    /// shorter than `D` collapsed and needles (altitude below `D`) removed, only where that
    /// keeps the result manifold, turns no triangle over, makes no self-intersection,
    /// moves no vertex more than `D` (seam points move before input vertices) and keeps the
    /// volume within `D × area`; no edge of the seam is flipped. Provenance follows.
    /// Only the bad triangles at the seam are fixed (and those the fixes make bad): the
    /// inputs' own short edges and needles elsewhere stay as they were. [`boolean_many`]
    /// keeps flips off the edges between two inputs' parts but does not tell seam points
    /// from input vertices: it fixes every bad triangle.
    pub snap: f64,
    /// [`boolean_many`] of more than two closed inputs in one arrangement of all of them
    /// ([`Combined::OneArrangement`]): exact to the end (no intermediate result rounded),
    /// slower than the pairwise tree (it cuts the crossings the union or intersection
    /// buries too). Inputs it does not apply to go through the tree. Ignored by
    /// [`boolean`].
    pub one_arrangement: bool,
    /// Interior points for large triangles cut by a dense seam (a floor crossed by a
    /// fine fence), so that their pieces are not needles from their corners: flat faces
    /// then hold extra vertices. Off by default.
    pub sliver_guard: bool,
    /// Cut coplanar overlaps (shared faces) along every edge of either input that
    /// crosses them: the result's faces there hold the common refinement of both
    /// triangulations, as the reference JS library's do. Off (the default), coplanar
    /// regions meet along their boundaries only: the same surface with fewer seam points
    /// (two fanned caps in one plane would otherwise cross in a number of points that
    /// grows as the product of their triangle counts).
    pub coplanar_refinement: bool,
    /// Threads and progress.
    pub run: RunOptions,
}

/// The result of [`boolean`]: the mesh, where each of its triangles comes from, and what
/// was found and assumed on the way.
#[derive(Clone, Debug)]
pub struct BooleanOutput {
    /// The operation.
    pub op: Op,
    /// The result (seam vertices shared between the parts of A and B, unreferenced
    /// vertices removed).
    pub mesh: Mesh,
    /// The origin of every triangle of `mesh`.
    pub provenance: Vec<Provenance>,
    /// Where the result was not manifold and was split (see
    /// [`BooleanOptions::keep_nonmanifold`]).
    pub nonmanifold: NonManifoldReport,
    /// What the checks found in A and B.
    pub operands: [OperandReport; 2],
    /// Points of the intersection curves.
    pub seam_points: usize,
    /// Zero-area triangles of A and of B where the meshes meet, left out of the
    /// intersection.
    pub degenerate: [usize; 2],
    /// Input triangles kept uncut; empty for valid inputs.
    pub failed: Vec<FailedTriangle>,
    /// Result triangles that turn over when their seam points are rounded to `f64`
    /// (exact before rounding); 0 in almost every case.
    pub rounding_flips: usize,
    /// What the exact clean-up did ([`BooleanOptions::keep_seam_points`]).
    pub cleanup: CleanupReport,
    /// What snapping did ([`BooleanOptions::snap`]); `None` without it.
    pub snap: Option<SnapReport>,
    /// Time of the boolean itself and of snapping (not of checking the inputs), in
    /// seconds.
    pub seconds: f64,
}

/// What [`BooleanOutput::report`] tells: the JSON of `meshbool union|intersection|difference
/// --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BooleanReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The operation.
    pub operation: Op,
    /// Measures of the result.
    #[serde(flatten)]
    pub result: Measures,
    /// Points of the intersection curves.
    pub seam_points: usize,
    /// [`BooleanOutput::rounding_flips`].
    pub rounding_flips: usize,
    /// Triangles kept uncut, one line each.
    pub failed_triangles: Vec<String>,
    /// Where the result was not manifold and was split.
    pub split_nonmanifold: NonManifoldReport,
    /// What the result assumes: skipped checks, problems taken as given, rounding and
    /// left-out degenerate triangles, one line each.
    pub assumed: Vec<String>,
    /// What the checks found in A and B (in every input, for [`boolean_many`]).
    pub operands: Vec<OperandReport>,
    /// What the exact clean-up did (all zero with [`BooleanOptions::keep_seam_points`]).
    pub cleanup: CleanupReport,
    /// What snapping did (only with a snap tolerance).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub snap: Option<SnapReport>,
    /// How the inputs of [`boolean_many`] were combined; `None` for two inputs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub combined: Option<Combined>,
    /// [`BooleanOutput::seconds`].
    pub seconds: f64,
}

/// How [`boolean_many`] combined its inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Combined {
    /// Pairwise booleans in a balanced tree (the default; also where one arrangement was
    /// asked for and does not apply: an open or non-manifold input, a triangle it could
    /// not cut).
    PairwiseTree,
    /// In one arrangement ([`BooleanOptions::one_arrangement`]): every input cut along
    /// all the others at once, each piece kept by the exact winding number of every input
    /// on its two sides.
    OneArrangement,
}

impl BooleanOutput {
    /// Multiplies the output's coordinates by `2^e` (for a computation done at unit size).
    fn scale_back(&mut self, e: i32) {
        scale_back(&mut self.mesh, &mut self.operands, &mut self.snap, e);
    }

    /// What the result assumes, one line each (see [`BooleanReport::assumed`]).
    pub fn assumed(&self) -> Vec<String> {
        let mut lines: Vec<String> = self.operands.iter().flat_map(|o| o.assumed()).collect();
        lines.extend(rounding_line(self.rounding_flips));
        if self.degenerate != [0, 0] {
            lines.push(format!(
                "degenerate (zero-area) triangles where the meshes meet were left out: {} in A, {} in B",
                self.degenerate[0], self.degenerate[1]
            ));
        }
        lines
    }

    /// The triangles kept uncut, one line each.
    pub fn failed_lines(&self) -> Vec<String> {
        self.failed
            .iter()
            .map(|f| format!("{:?} triangle {}: {}", f.source, f.triangle, f.reason))
            .collect()
    }

    /// The report, with the result's measures (which take a pass over the mesh).
    pub fn report(&self) -> BooleanReport {
        BooleanReport {
            schema: SCHEMA,
            operation: self.op,
            result: Measures::of(&self.mesh),
            seam_points: self.seam_points,
            rounding_flips: self.rounding_flips,
            failed_triangles: self.failed_lines(),
            split_nonmanifold: self.nonmanifold.clone(),
            assumed: self.assumed(),
            operands: self.operands.to_vec(),
            cleanup: self.cleanup,
            snap: self.snap.clone(),
            combined: None,
            seconds: self.seconds,
        }
    }
}

/// Multiplies the coordinates of a boolean's output computed at unit size by `2^e`: the
/// mesh, the operands' reports and the snap report ([`BooleanOutput`] and
/// [`BooleanManyOutput`] alike).
fn scale_back(
    mesh: &mut Mesh,
    operands: &mut [OperandReport],
    snap: &mut Option<SnapReport>,
    e: i32,
) {
    super::scale_points(&mut mesh.positions, e);
    for o in operands {
        o.scale_back(e);
    }
    if let Some(s) = snap {
        s.scale_back(e);
    }
}

/// The boolean `op` of `a` and `b`: meshes, checked as `opts.checks` say (named `A` and
/// `B`), or [`super::Operand`]s. Closed meshes must face outward; open surfaces have
/// "inside" behind them (the side their normals point away from).
///
/// Errors: an invalid mesh, an operand failing its checks, a thread count out of range.
pub fn boolean<'a>(
    a: impl Into<Input<'a>>,
    b: impl Into<Input<'a>>,
    op: Op,
    opts: &BooleanOptions,
) -> Result<BooleanOutput> {
    let (a, b): (Input<'a>, Input<'a>) = (a.into(), b.into());
    crate::repair::check_tolerance(opts.snap)?;
    // At unit size the tolerance is scaled as the meshes are.
    let to_unit = (opts.snap > 0.0)
        .then(|| super::extreme_scale(&[a.mesh(), b.mesh()]))
        .flatten();
    let unit_opts = BooleanOptions {
        snap: super::scaled(opts.snap, to_unit.unwrap_or(0)).min(f64::MAX),
        ..opts.clone()
    };
    let unit = |a: Input<'_>, b: Input<'_>| boolean(a, b, op, &unit_opts);
    if let Some(out) = super::at_unit_scale(a, b, unit, BooleanOutput::scale_back) {
        return out;
    }
    let run = |a: &Operand, b: &Operand| {
        let pipeline = PipelineOptions {
            keep_nonmanifold: opts.keep_nonmanifold,
            cleanup: !opts.keep_seam_points,
            split_everywhere: a.glued() || b.glued(),
            kept: [Some(a.keeps()), Some(b.keeps())],
            first_votes: a.clean() && b.clean(),
            sliver_guard: opts.sliver_guard,
            coplanar_refinement: opts.coplanar_refinement,
            ..opts.run.pipeline()
        };
        // An operand resolved at the door is resolved again together with the boolean,
        // in one arrangement of both (nothing rounded in between); where that route does
        // not decide, the boolean takes the resolved surfaces.
        let in_one = (a.unresolved().is_some() || b.unresolved().is_some())
            .then(|| {
                fn as_given(o: &Operand) -> (&Mesh, &[(u32, u32)]) {
                    match o.unresolved() {
                        Some(u) => (&u.mesh, &u.pairs),
                        None => (o.mesh(), &[]),
                    }
                }
                let ((ma, pa), (mb, pb)) = (as_given(a), as_given(b));
                crate::par::run_for(ma.triangles.len() + mb.triangles.len(), || {
                    boolean_in_one(ma, mb, pa, pb, op, &pipeline)
                })
            })
            .flatten();
        let resolved_in_one = in_one.is_some();
        let mut r = match in_one {
            Some(r) => r,
            None => crate::boolean::boolean(a.mesh(), b.mesh(), op, &pipeline),
        };
        let snap = if opts.snap > 0.0 && !opts.run.cancelled() {
            opts.run.report(Stage::Snap);
            // The tolerance was checked above: never an error here.
            crate::boolean::snap_result(&mut r, opts.snap).ok()
        } else {
            None
        };
        if resolved_in_one {
            Operand::unresolved_to_input_triangles(&mut r.provenance, a, b);
        } else {
            Operand::to_input_triangles(&mut r.provenance, a, b);
        }
        for f in &mut r.failed {
            f.triangle = match f.source {
                crate::Source::A => a.input_triangle(f.triangle),
                crate::Source::B => b.input_triangle(f.triangle),
            };
        }
        (r, snap, [a.report().clone(), b.report().clone()])
    };
    let ((r, snap, operands), seconds) = Input::with_both(a, b, &opts.checks, &opts.run, run)?;
    Ok(BooleanOutput {
        op,
        mesh: r.mesh,
        provenance: r.provenance,
        nonmanifold: r.nonmanifold,
        operands,
        seam_points: r.seam_points,
        degenerate: r.degenerate,
        failed: r.failed,
        rounding_flips: r.rounding_flips,
        cleanup: r.cleanup,
        snap,
        seconds,
    })
}

/// The result of [`boolean_many`] and [`difference_many`]: as [`BooleanOutput`], with
/// provenance naming the input by its position.
#[derive(Clone, Debug)]
pub struct BooleanManyOutput {
    /// The operation ([`Op::Union`], [`Op::Intersection`], or [`Op::Difference`]: the
    /// first input less the others).
    pub op: Op,
    /// The result.
    pub mesh: Mesh,
    /// For every triangle of `mesh`: `[input, triangle of that input]` (facing as that
    /// triangle, except for inside-out components reversed at the door:
    /// [`OperandReport::reversed_components`]).
    pub provenance: Vec<[u32; 2]>,
    /// Where the result was not manifold and was split.
    pub nonmanifold: NonManifoldReport,
    /// What the checks found in each input.
    pub operands: Vec<OperandReport>,
    /// Points of the intersection curves of all the pairwise booleans.
    pub seam_points: usize,
    /// Input triangles kept uncut (`[input, triangle]`, reason); empty for valid inputs.
    pub failed: Vec<([u32; 2], FailReason)>,
    /// Result triangles that turn over when their seam points are rounded to `f64`.
    pub rounding_flips: usize,
    /// What the exact clean-up did ([`BooleanOptions::keep_seam_points`]).
    pub cleanup: CleanupReport,
    /// What snapping did ([`BooleanOptions::snap`]); `None` without it.
    pub snap: Option<SnapReport>,
    /// How the inputs were combined.
    pub combined: Combined,
    /// Time of the booleans (not of checking the inputs), in seconds.
    pub seconds: f64,
}

impl BooleanManyOutput {
    /// The report, as for two inputs (`operands` lists every input).
    pub fn report(&self) -> BooleanReport {
        let mut assumed: Vec<String> = self.operands.iter().flat_map(|o| o.assumed()).collect();
        assumed.extend(rounding_line(self.rounding_flips));
        BooleanReport {
            schema: SCHEMA,
            operation: self.op,
            result: Measures::of(&self.mesh),
            seam_points: self.seam_points,
            rounding_flips: self.rounding_flips,
            failed_triangles: self
                .failed
                .iter()
                .map(|([i, t], reason)| {
                    format!("{} triangle {t}: {reason}", self.operands[*i as usize].name)
                })
                .collect(),
            split_nonmanifold: self.nonmanifold.clone(),
            assumed,
            operands: self.operands.clone(),
            cleanup: self.cleanup,
            snap: self.snap.clone(),
            combined: Some(self.combined),
            seconds: self.seconds,
        }
    }
}

/// The union or intersection of any number of inputs (at least one), in one call:
/// pairwise booleans in a balanced tree, a round's pairs in parallel, rather than a
/// chain; or in one arrangement of all of them ([`BooleanOptions::one_arrangement`],
/// `boolean::nary`, [`Combined`]). Inputs are meshes, checked as `opts.checks` say and named `1`,
/// `2`, ..., or [`Operand`]s.
///
/// Errors: a difference (not associative: use [`difference_many`] or [`boolean`]), no
/// input, an invalid mesh, an operand failing its checks, a thread count out of range.
pub fn boolean_many<'a>(
    inputs: &[Input<'a>],
    op: Op,
    opts: &BooleanOptions,
) -> Result<BooleanManyOutput> {
    if !matches!(op, Op::Union | Op::Intersection) {
        return Err(Error::InvalidParameter(format!(
            "{op} of many inputs: only union and intersection take more than two \
             (difference_many: the first less the others)"
        )));
    }
    many(inputs, op, opts)
}

/// The first input less all the others, in one call: the others united ([`boolean_many`]'s
/// tree, or one arrangement of all of them with [`BooleanOptions::one_arrangement`]),
/// then one difference; the report lists every input. Inputs as for [`boolean_many`].
///
/// Errors: as [`boolean_many`].
///
/// ```
/// use meshbool::ops::{difference_many, BooleanOptions, Input};
/// use meshbool::Mesh;
///
/// let block = Mesh::cuboid([0.0; 3], [4.0, 1.0, 1.0]);
/// let (a, b) = (Mesh::cuboid([0.5, -1.0, -1.0], [1.0, 2.0, 2.0]), Mesh::cuboid([2.5, -1.0, -1.0], [3.0, 2.0, 2.0]));
/// let inputs = [Input::from(&block), Input::from(&a), Input::from(&b)];
/// let out = difference_many(&inputs, &BooleanOptions::default())?;
/// assert_eq!(meshbool::measure::signed_volume(&out.mesh), 3.0);
/// assert_eq!(out.operands.len(), 3);
/// # Ok::<(), meshbool::Error>(())
/// ```
pub fn difference_many<'a>(
    inputs: &[Input<'a>],
    opts: &BooleanOptions,
) -> Result<BooleanManyOutput> {
    many(inputs, Op::Difference, opts)
}

/// [`boolean_many`] and [`difference_many`]: `op` a union, an intersection or a
/// difference (the first less the others).
fn many<'a>(inputs: &[Input<'a>], op: Op, opts: &BooleanOptions) -> Result<BooleanManyOutput> {
    if inputs.is_empty() {
        return Err(Error::InvalidParameter(format!("{op} of no inputs")));
    }
    crate::repair::check_tolerance(opts.snap)?;
    // Inputs of extreme magnitude together are computed at unit size, as pairs are.
    let meshes: Vec<&Mesh> = inputs.iter().map(|i| i.mesh()).collect();
    if let Some(e) = super::extreme_scale(&meshes) {
        let scaled: Vec<_> = inputs.iter().map(|i| i.scaled(e)).collect();
        let unit: Vec<Input> = scaled.iter().map(|s| s.input()).collect();
        let unit_opts = BooleanOptions {
            snap: super::scaled(opts.snap, e).min(f64::MAX),
            ..opts.clone()
        };
        let mut out = many(&unit, op, &unit_opts)?;
        scale_back(&mut out.mesh, &mut out.operands, &mut out.snap, -e);
        return Ok(out);
    }
    let triangles = inputs.iter().map(|i| i.mesh().triangles.len()).sum();
    with_threads_for(opts.run.threads, triangles, || {
        if inputs.iter().any(|i| matches!(i, Input::Mesh(_))) {
            opts.run.stage(Stage::Check)?;
        }
        let operands: Vec<_> = inputs
            .par_iter()
            .grained()
            .enumerate()
            .map(|(k, i)| i.operand(&(k + 1).to_string(), &opts.checks))
            .collect::<Result<_>>()?;
        let start = Instant::now();
        opts.run.stage(Stage::Intersect)?;
        let mut offsets = Vec::with_capacity(operands.len() + 1);
        offsets.push(0u32);
        for o in &operands {
            let next = offsets[offsets.len() - 1] as usize + o.mesh().triangles().len();
            offsets.push(u32::try_from(next).map_err(|_| Error::InvalidMesh {
                location: crate::error::Location::Whole,
                message: "more than 2^32 triangles in all the operands".to_string(),
            })?);
        }
        let parts: Vec<Part> = operands
            .iter()
            .zip(&offsets)
            .map(|(o, &first)| Part {
                mesh: o.mesh().clone(),
                parent: (0..o.mesh().triangles().len() as u32)
                    .map(|t| first + o.input_triangle(t))
                    .collect(),
            })
            .collect();
        let pipeline = PipelineOptions {
            keep_nonmanifold: opts.keep_nonmanifold,
            cleanup: !opts.keep_seam_points,
            first_votes: operands.iter().all(|o| o.clean()),
            coplanar_refinement: opts.coplanar_refinement,
            ..opts.run.pipeline()
        };
        let in_one = if opts.one_arrangement {
            reduce_in_one(&parts, op, &pipeline)
        } else {
            None
        };
        let r = in_one.unwrap_or_else(|| reduce(parts, op, &pipeline));
        opts.run.check()?;
        let input_of = |g: u32| {
            let k = offsets.partition_point(|&o| o <= g) - 1;
            [k as u32, g - offsets[k]]
        };
        let mut provenance: Vec<[u32; 2]> = r.part.parent.iter().map(|&g| input_of(g)).collect();
        let mut mesh = r.part.mesh;
        let mut snap = None;
        if opts.snap > 0.0 {
            // Labels by input: no edge between two inputs' parts is flipped.
            opts.run.stage(Stage::Snap)?;
            let labels: Vec<u32> = provenance.iter().map(|p| p[0]).collect();
            let opts = SnapOptions {
                tolerance: opts.snap,
                labels: Some(&labels),
                ..SnapOptions::default()
            };
            snap = Some(crate::repair::snap_carrying(&mut mesh, &opts, &mut provenance).0);
        }
        Ok(BooleanManyOutput {
            op,
            provenance,
            mesh,
            nonmanifold: r.nonmanifold,
            operands: operands.iter().map(|o| o.report().clone()).collect(),
            seam_points: r.seam_points,
            failed: r
                .failed
                .iter()
                .map(|&(g, why)| (input_of(g), why))
                .collect(),
            rounding_flips: r.rounding_flips,
            cleanup: r.cleanup,
            snap,
            combined: if r.one_arrangement {
                Combined::OneArrangement
            } else {
                Combined::PairwiseTree
            },
            seconds: start.elapsed().as_secs_f64(),
        })
    })?
}

/// The `assumed` line for result triangles turned over by rounding, if any.
fn rounding_line(flips: usize) -> Option<String> {
    (flips > 0).then(|| {
        format!(
            "{flips} result triangles are thinner than f64 rounding of their seam points and turned over when written (exact before rounding)"
        )
    })
}
