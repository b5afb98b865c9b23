//! `meshbool curves`: the exact intersection curves of two meshes (or where one mesh
//! crosses itself) as polylines.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, Checks, CurvesOptions, Operand};

use super::{print_json, warn};

/// Arguments of `curves`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// First mesh.
    a: PathBuf,
    /// Second mesh; without it, the curves where the first crosses itself.
    b: Option<PathBuf>,
    #[arg(short, long, help = super::POLYLINE_OUTPUT, value_parser = super::polyline_output)]
    output: Option<PathBuf>,
    /// Leave out segments that only bound coplanar overlaps (shared faces).
    #[arg(long)]
    no_coplanar: bool,
    /// Also the segments where an edge of either mesh crosses a coplanar overlap (the
    /// common refinement of both triangulations there, as the reference JS library lists
    /// them). By default coplanar overlaps give their boundaries only.
    #[arg(long, conflicts_with = "no_coplanar")]
    coplanar_refinement: bool,
    /// Thin the written polylines: leave out points closer than D to the last kept point
    /// along a line (first and last points kept; the curves' topology does not change).
    #[arg(long, value_name = "D")]
    simplify: Option<f64>,
    /// Add every raw seam segment, with the triangle of A and of B it lies in, to the
    /// JSON summary (`tagged_segments`).
    #[arg(long, requires = "json")]
    tagged: bool,
    /// Print a JSON summary on stdout.
    #[arg(long)]
    json: bool,
}

/// Reads both meshes, computes the curves, writes them if asked, prints the summary.
pub fn run(args: &Args) -> Result<()> {
    let opts = CurvesOptions {
        with_coplanar: !args.no_coplanar,
        simplify: args.simplify,
        tagged: args.tagged,
        coplanar_refinement: args.coplanar_refinement,
        ..CurvesOptions::default()
    };
    let out = match &args.b {
        Some(b) => {
            let (a, b) = Operand::read_pair(&args.a, b, &Checks::NONE)?;
            ops::curves(&a, &b, &opts)?
        }
        None => ops::self_curves(&Operand::read(&args.a, &Checks::NONE)?, &opts)?,
    };
    if let Some(path) = &args.output {
        out.write(path)?;
    }
    let report = out.report();
    if args.json {
        print_json(&report)?;
    } else {
        eprintln!(
            "{} loops, {} open chains, total length {}, {} seam points ({:.3} s)",
            report.loops, report.open_chains, report.total_length, report.points, report.seconds
        );
    }
    warn(&out.warnings());
    Ok(())
}
