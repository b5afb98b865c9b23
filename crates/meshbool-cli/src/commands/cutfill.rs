//! `meshbool cutfill`: cut and fill volumes between a design surface and a topography.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, Checks, CutFillOptions, Operand};

use super::print_json;

/// Arguments of `cutfill`.
#[derive(clap::Args)]
pub struct Args {
    /// The design surface (a pit shell, a bench plan, a pad).
    design: PathBuf,
    /// The topography (the surveyed ground).
    topo: PathBuf,
    #[arg(short, long, value_parser = super::polyline_output, help = concat!(
        "Write the lines where the surfaces meet (zero thickness) as polylines (.obj, .dxf \
         or .json). ",
        output_rule!()
    ))]
    output: Option<PathBuf>,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = super::thread_count)]
    threads: Option<usize>,
}

/// Reads both surfaces, computes cut and fill, writes the lines if asked, prints the
/// report.
pub fn run(args: &Args) -> Result<()> {
    let (design, topo) = Operand::read_pair(&args.design, &args.topo, &Checks::NONE)?;
    let opts = CutFillOptions {
        run: ops::RunOptions {
            threads: args.threads,
            cancel: Some(super::cancel()),
            ..Default::default()
        },
    };
    let out = ops::cutfill(&design, &topo, &opts)?;
    if let Some(path) = &args.output {
        let format = meshbool::Format::for_path(path).ok_or_else(|| {
            anyhow::anyhow!(
                "cannot tell the polyline format of {}: use .obj, .dxf or .json",
                path.display()
            )
        })?;
        let mut bytes = Vec::new();
        meshbool::io::write_polylines(&mut bytes, &out.lines, format)?;
        meshbool::io::write_bytes(path, &bytes)?;
    }
    let r = out.report();
    if args.json {
        return print_json(&r);
    }
    super::out(&format!(
        "cut {} fill {} net {} over a common plan area of {} (design {}, topography {}); {} zero-thickness lines\n",
        r.cut, r.fill, r.net, r.common_plan_area, r.design_plan_area, r.topo_plan_area, r.zero_lines
    ))
}
