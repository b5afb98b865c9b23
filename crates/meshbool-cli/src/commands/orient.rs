//! `meshbool orient`: consistent orientation, each component facing as asked.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, Checks, Operand};
use meshbool::repair::Facing;

use super::print_json;

/// Arguments of `orient`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh.
    input: PathBuf,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Normals up (positive projected XY area): terrain and other open surfaces.
    #[arg(long, conflicts_with = "outward")]
    z_up: bool,
    /// Closed components outward (positive volume).
    #[arg(long)]
    outward: bool,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

/// Orients the input, writes it, prints the report.
pub fn run(args: &Args) -> Result<()> {
    let facing = match (args.z_up, args.outward) {
        (true, _) => Facing::ZUp,
        (_, true) => Facing::Outward,
        _ => Facing::Majority,
    };
    let out = ops::orient(&Operand::read(&args.input, &Checks::NONE)?, facing)?;
    ops::write(&args.output, &out.mesh, None)?;
    if args.json {
        return print_json(&out.report());
    }
    let r = &out.orient;
    eprintln!(
        "wrote {}: {} triangles flipped, {} components, {} edges could not be made consistent, {} non-manifold edges",
        args.output.display(),
        r.flipped,
        r.components,
        r.conflicting_edges,
        r.non_manifold_edges
    );
    Ok(())
}
