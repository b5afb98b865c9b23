//! Booleans at the front door: union, intersection, difference (both ways) of two inputs,
//! with the report the CLI prints.

use serde::Serialize;

use super::{Checks, Input, Measures, Operand, OperandReport, RunOptions, SCHEMA};
use crate::boolean::{FailedTriangle, Op, PipelineOptions, Provenance};
use crate::repair::NonManifoldReport;
use crate::{Mesh, Result};

/// Options of [`boolean`].
#[derive(Clone, Debug, Default)]
pub struct BooleanOptions {
    /// Checks of inputs given as meshes (operands made earlier keep theirs).
    pub checks: Checks,
    /// Keep the result's topology where it is not manifold (solids touching along an edge
    /// or at a vertex then share it). By default such edges and vertices are split so that
    /// the result is manifold ([`crate::repair::split_nonmanifold`]; positions unchanged).
    pub keep_nonmanifold: bool,
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
    /// Time of the boolean itself (not of checking the inputs), in seconds.
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
    /// What the checks found in A and B.
    pub operands: [OperandReport; 2],
    /// [`BooleanOutput::seconds`].
    pub seconds: f64,
}

impl BooleanOutput {
    /// What the result assumes, one line each (see [`BooleanReport::assumed`]).
    pub fn assumed(&self) -> Vec<String> {
        let mut lines: Vec<String> = self.operands.iter().flat_map(|o| o.assumed()).collect();
        if self.rounding_flips > 0 {
            lines.push(format!(
                "{} result triangles are thinner than f64 rounding of their seam points and turned over when written (exact before rounding)",
                self.rounding_flips
            ));
        }
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
            operands: self.operands.clone(),
            seconds: self.seconds,
        }
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
    let run = |a: &Operand, b: &Operand| {
        let pipeline = PipelineOptions {
            keep_nonmanifold: opts.keep_nonmanifold,
            ..opts.run.pipeline()
        };
        let mut r = crate::boolean::boolean(a.mesh(), b.mesh(), op, &pipeline);
        Operand::to_input_triangles(&mut r.provenance, a, b);
        for f in &mut r.failed {
            f.triangle = match f.source {
                crate::Source::A => a.input_triangle(f.triangle),
                crate::Source::B => b.input_triangle(f.triangle),
            };
        }
        (r, [a.report().clone(), b.report().clone()])
    };
    let ((r, operands), seconds) =
        Input::with_both(a.into(), b.into(), &opts.checks, &opts.run, run)?;
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
        seconds,
    })
}
