//! `meshbool union | intersection | difference`: a boolean of two mesh files.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, BooleanOptions, Operand};
use meshbool::Op;

use super::{print_json, warn, OperandFlags, Spinner};

/// The operands and output of a boolean command.
#[derive(clap::Args, Clone)]
pub struct Args {
    /// First mesh (A).
    a: PathBuf,
    /// Second mesh (B).
    b: PathBuf,
    /// Output mesh file.
    #[arg(short, long)]
    output: PathBuf,
    /// Keep the result's non-manifold edges and vertices (solids touching along an edge or
    /// at a vertex) instead of splitting them.
    #[arg(long)]
    keep_nonmanifold: bool,
    #[command(flatten)]
    flags: OperandFlags,
}

/// `difference`: the boolean's arguments and the direction.
#[derive(clap::Args, Clone)]
pub struct DifferenceArgs {
    #[command(flatten)]
    pub args: Args,
    /// Compute B − A instead.
    #[arg(long)]
    reverse: bool,
}

impl DifferenceArgs {
    /// A − B, or B − A with `--reverse`.
    pub fn op(&self) -> Op {
        if self.reverse {
            Op::ReverseDifference
        } else {
            Op::Difference
        }
    }
}

/// Reads and checks both operands, computes `op`, writes the result while measuring it,
/// then prints the report.
pub fn run(args: &Args, op: Op) -> Result<()> {
    let flags = &args.flags;
    ops::with_threads(flags.threads, || {
        let spinner = Spinner::new(flags.reading());
        let (a, b) = Operand::read_pair(&args.a, &args.b, &flags.checks())?;
        // The operands were checked as they were read.
        let opts = BooleanOptions {
            keep_nonmanifold: args.keep_nonmanifold,
            run: flags.run(&spinner),
            ..BooleanOptions::default()
        };
        let out = ops::boolean(&a, &b, op, &opts)?;
        spinner.set_message("writing");
        let (written, report) = rayon::join(
            || ops::write(&args.output, &out.mesh, None),
            || out.report(),
        );
        drop(spinner);
        written?;
        warn(&report.assumed);
        warn(&report.failed_triangles);
        if flags.json {
            print_json(&report)
        } else {
            eprintln!(
                "wrote {} ({} triangles, volume {}, {} boundary edges, {:.3} s)",
                args.output.display(),
                report.result.triangles,
                report.result.volume,
                report.result.boundary_edges,
                report.seconds
            );
            Ok(())
        }
    })?
}
