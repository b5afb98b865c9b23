//! `meshbool pick`: chosen pieces of a split merged into one welded mesh.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, PickOptions, PieceSpec};
use meshbool::Op;

use super::{one_of, parse_value, print_json};

/// Arguments of `pick`.
#[derive(clap::Args)]
pub struct Args {
    /// Directory written by `meshbool split`.
    dir: PathBuf,
    /// A piece to keep: GROUP[#COMPONENT][:flip].
    #[arg(long = "keep", required_unless_present = "op", conflicts_with = "op",
          value_parser = parse_value::<PieceSpec>)]
    keep: Vec<PieceSpec>,
    /// Keep the pieces a boolean keeps instead: `union`, `intersection`, `difference`,
    /// `reverse-difference` (the same result as the boolean of the split's inputs).
    #[arg(long, ignore_case = true, value_parser = one_of::<Op>(Op::ALL.map(Op::name)))]
    op: Option<Op>,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Keep the merged mesh's non-manifold edges and vertices (pieces touching along an
    /// edge or at a vertex) instead of splitting them.
    #[arg(long)]
    keep_nonmanifold: bool,
    #[command(flatten)]
    snap: super::Snap,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

/// Picks the pieces from the split's directory, writes the merged mesh, prints its report.
pub fn run(args: &Args) -> Result<()> {
    let opts = PickOptions {
        keep_nonmanifold: args.keep_nonmanifold,
        snap: args.snap.tolerance,
    };
    let out = match args.op {
        Some(op) => ops::pick_dir_op(&args.dir, op, &opts)?,
        None => ops::pick_dir(&args.dir, &args.keep, &opts)?,
    };
    ops::write(&args.output, &out.mesh, None)?;
    let report = out.report();
    if args.json {
        return print_json(&report);
    }
    eprintln!(
        "wrote {} ({} triangles, {} boundary edges)",
        args.output.display(),
        report.stats.triangles,
        report.stats.boundary_edges
    );
    if let Some(s) = &report.snap {
        super::print_snap(s);
    }
    Ok(())
}
