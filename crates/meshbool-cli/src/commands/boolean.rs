//! `meshbool union | intersection | difference`: a boolean of two mesh files or more (a
//! difference of more: the first less all the others).

use std::path::{Path, PathBuf};

use anyhow::Result;
use meshbool::ops::{self, BooleanOptions, BooleanReport, Input, Operand};
use meshbool::Op;
use rayon::prelude::*;

use super::{print_json, warn, OperandFlags, Spinner};

/// The operands and output of a boolean command.
#[derive(clap::Args, Clone)]
pub struct Args {
    /// First mesh (A).
    a: PathBuf,
    /// Second mesh (B).
    b: PathBuf,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Keep the result's non-manifold edges and vertices (solids touching along an edge or
    /// at a vertex) instead of splitting them.
    #[arg(long)]
    keep_nonmanifold: bool,
    /// Keep every seam point of the exact arrangement. By default seam points where the
    /// result is flat or straight are removed and zero-area triangles made by rounding are
    /// collapsed or flipped away (no surface moves).
    #[arg(long)]
    keep_seam_points: bool,
    /// Cut coplanar overlaps (shared faces) along every edge of either input that crosses
    /// them, so that the result's faces there hold the common refinement of both
    /// triangulations (as the reference JS library's do). By default coplanar regions meet
    /// along their boundaries only: the same surface with fewer seam points.
    #[arg(long)]
    coplanar_refinement: bool,
    #[command(flatten)]
    snap: super::Snap,
    #[command(flatten)]
    flags: OperandFlags,
}

/// `union`, `intersection` and `difference`: two inputs or more.
#[derive(clap::Args, Clone)]
pub struct ManyArgs {
    /// The meshes: A and B, or more (computed in one call, pairwise in a balanced tree).
    #[arg(num_args = 2.., required = true)]
    inputs: Vec<PathBuf>,
    /// More than two closed inputs: cut all of them along one another in one arrangement
    /// and keep each piece by the exact winding numbers on its sides. Exact to the end (no
    /// intermediate result rounded); slower than the pairwise tree. The report's
    /// `combined` says which was used.
    #[arg(long)]
    one_arrangement: bool,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Keep the result's non-manifold edges and vertices (solids touching along an edge or
    /// at a vertex) instead of splitting them.
    #[arg(long)]
    keep_nonmanifold: bool,
    /// Keep every seam point of the exact arrangement. By default seam points where the
    /// result is flat or straight are removed and zero-area triangles made by rounding are
    /// collapsed or flipped away (no surface moves).
    #[arg(long)]
    keep_seam_points: bool,
    /// Cut coplanar overlaps (shared faces) along every edge of either input that crosses
    /// them, so that the result's faces there hold the common refinement of both
    /// triangulations (as the reference JS library's do). By default coplanar regions meet
    /// along their boundaries only: the same surface with fewer seam points.
    #[arg(long)]
    coplanar_refinement: bool,
    #[command(flatten)]
    snap: super::Snap,
    #[command(flatten)]
    flags: OperandFlags,
}

impl ManyArgs {
    /// Runs `op` (union, intersection or difference): the two-input boolean for two
    /// inputs.
    pub fn run(&self, op: Op) -> Result<()> {
        if let [a, b] = &self.inputs[..] {
            let args = Args {
                a: a.clone(),
                b: b.clone(),
                output: self.output.clone(),
                keep_nonmanifold: self.keep_nonmanifold,
                keep_seam_points: self.keep_seam_points,
                coplanar_refinement: self.coplanar_refinement,
                snap: self.snap,
                flags: self.flags.clone(),
            };
            return run(&args, op);
        }
        let flags = &self.flags;
        ops::with_threads(flags.threads, || {
            let spinner = flags.spinner();
            let operands: Vec<Operand> = self
                .inputs
                .par_iter()
                .map(|p| Operand::read(p, &flags.checks()))
                .collect::<meshbool::Result<_>>()?;
            let inputs: Vec<Input> = operands.iter().map(Input::from).collect();
            let opts = BooleanOptions {
                keep_nonmanifold: self.keep_nonmanifold,
                keep_seam_points: self.keep_seam_points,
                coplanar_refinement: self.coplanar_refinement,
                snap: self.snap.tolerance,
                one_arrangement: self.one_arrangement,
                run: flags.run(&spinner),
                ..BooleanOptions::default()
            };
            let out = match op {
                Op::Difference => ops::difference_many(&inputs, &opts)?,
                op => ops::boolean_many(&inputs, op, &opts)?,
            };
            finish(
                spinner,
                &out.mesh,
                || out.report(),
                &self.output,
                flags.json,
            )
        })?
    }
}

/// `difference`: the inputs and the direction.
#[derive(clap::Args, Clone)]
pub struct DifferenceArgs {
    #[command(flatten)]
    args: ManyArgs,
    /// Compute B − A instead (two inputs only).
    #[arg(long)]
    reverse: bool,
}

impl DifferenceArgs {
    /// A − B − C ..., or B − A with `--reverse` (more inputs with it: a usage error).
    pub fn run(&self) -> Result<()> {
        if !self.reverse {
            return self.args.run(Op::Difference);
        }
        match self.args.inputs.len() {
            2 => self.args.run(Op::ReverseDifference),
            n => Err(crate::exit::usage(format!(
                "--reverse takes two inputs (it computes B − A), got {n}: put the mesh to \
                 keep first instead (`difference A B C` is A − B − C)"
            ))),
        }
    }
}

/// Reads and checks both operands, computes `op`, writes the result while measuring it,
/// then prints the report.
pub fn run(args: &Args, op: Op) -> Result<()> {
    let flags = &args.flags;
    ops::with_threads(flags.threads, || {
        let spinner = flags.spinner();
        let (a, b) = Operand::read_pair(&args.a, &args.b, &flags.checks())?;
        // The operands were checked as they were read.
        let opts = BooleanOptions {
            keep_nonmanifold: args.keep_nonmanifold,
            keep_seam_points: args.keep_seam_points,
            coplanar_refinement: args.coplanar_refinement,
            snap: args.snap.tolerance,
            run: flags.run(&spinner),
            ..BooleanOptions::default()
        };
        let out = ops::boolean(&a, &b, op, &opts)?;
        finish(
            spinner,
            &out.mesh,
            || out.report(),
            &args.output,
            flags.json,
        )
    })?
}

/// Writes the result while its report measures it, then warns about what the result
/// assumes and prints the report or a summary line.
fn finish(
    spinner: Spinner,
    mesh: &meshbool::Mesh,
    report: impl FnOnce() -> BooleanReport + Send,
    output: &Path,
    json: bool,
) -> Result<()> {
    spinner.set_message("writing");
    let (written, report) = rayon::join(|| ops::write(output, mesh, None), report);
    drop(spinner);
    written?;
    let report = &report;
    warn(&report.assumed);
    warn(&report.failed_triangles);
    if json {
        print_json(report)
    } else {
        eprintln!(
            "wrote {} ({} triangles, volume {}, {} boundary edges, {:.3} s)",
            output.display(),
            report.result.triangles,
            report.result.volume,
            report.result.boundary_edges,
            report.seconds
        );
        if let Some(s) = &report.snap {
            super::print_snap(s);
        }
        Ok(())
    }
}
