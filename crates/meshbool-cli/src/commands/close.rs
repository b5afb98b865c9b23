//! `meshbool close`: open meshes closed into solids (cap, stitch, curtain).

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, Checks, Operand};
use meshbool::repair::{CloseMode, CloseOptions};

use super::{one_of, print_json};

/// Arguments of `close`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Input mesh.
    input: PathBuf,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// How to close.
    #[arg(long, ignore_case = true, default_value = "cap", value_parser = one_of::<CloseMode>(CloseMode::ALL.map(CloseMode::name)))]
    mode: CloseMode,
    /// Curtain: distance of the floor below the lowest point.
    #[arg(long, default_value_t = 10.0)]
    floor_offset: f64,
    /// Stitch: the largest gap between two loops that may be bridged (default: any).
    #[arg(long)]
    max_gap: Option<f64>,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

/// Closes the input, writes it, prints the report.
pub fn run(args: &Args) -> Result<()> {
    let opts = CloseOptions {
        stitch_max_gap: args.max_gap,
        floor_offset: args.floor_offset,
    };
    let out = ops::close(
        &Operand::read(&args.input, &Checks::NONE)?,
        args.mode,
        &opts,
    )?;
    ops::write(&args.output, &out.mesh, None)?;
    let report = out.report();
    if args.json {
        return print_json(&report);
    }
    eprintln!(
        "wrote {}: {} boundary edges left, closed: {}, volume {} ({})",
        args.output.display(),
        report.boundary_edges,
        report.closed,
        report.volume,
        serde_json::to_string(&report)?
    );
    Ok(())
}
