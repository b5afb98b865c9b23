//! `meshbool resolve`: the solid a self-overlapping mesh encloses, as a clean closed mesh.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, Checks, Envelope, EnvelopeOptions, Operand, ResolveOptions, RunOptions};
use meshbool::FillRule;

use super::{one_of, print_json, Spinner};

/// Arguments of `resolve`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh.
    input: PathBuf,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Which points are inside, by winding number w: `positive` (w >= 1, the union of the
    /// parts), `nonzero` (w != 0), `evenodd` (w odd).
    #[arg(long, default_value = "positive", ignore_case = true,
          value_parser = one_of::<FillRule>(FillRule::ALL.map(FillRule::name)))]
    rule: FillRule,
    /// Keep non-manifold edges and vertices (parts touching along an edge or at a vertex)
    /// instead of splitting them.
    #[arg(long)]
    keep_nonmanifold: bool,
    /// For an open surface that folds over itself (terrain): keep its `upper` or `lower`
    /// envelope instead, the single-valued surface seen from above or below (exact; walls
    /// kept where it jumps from a sheet to the one under it; faced up).
    // `tolerance` is the id of `--snap` (the field of the flattened `Snap`).
    #[arg(long, ignore_case = true, conflicts_with_all = ["rule", "keep_nonmanifold", "tolerance"],
          value_parser = one_of::<Envelope>(Envelope::ALL.map(Envelope::name)))]
    envelope: Option<Envelope>,
    #[command(flatten)]
    snap: super::Snap,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = super::thread_count)]
    threads: Option<usize>,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

/// Resolves the input, writes the result, prints the report.
pub fn run(args: &Args) -> Result<()> {
    let spinner = Spinner::new("reading the input");
    let input = Operand::read(&args.input, &Checks::NONE)?;
    let run = RunOptions {
        threads: args.threads,
        progress: None,
        cancel: Some(super::cancel()),
    };
    if let Some(side) = args.envelope {
        spinner.set_message("taking the envelope");
        let out = ops::envelope(&input, &EnvelopeOptions { side, run })?;
        spinner.set_message("writing the result");
        ops::write(&args.output, &out.mesh, None)?;
        drop(spinner);
        let report = out.report();
        if args.json {
            return print_json(&report);
        }
        let e = &report.envelope;
        eprintln!(
            "wrote {}: {} envelope, {} triangles, {} boundary edges ({} folded input triangles, {} hidden, {} jump-wall triangles)",
            args.output.display(),
            side.name(),
            report.result.triangles,
            report.result.boundary_edges,
            e.folded_triangles,
            e.hidden_triangles,
            e.jump_walls
        );
        return Ok(());
    }
    spinner.set_message("resolving");
    let opts = ResolveOptions {
        rule: args.rule,
        keep_nonmanifold: args.keep_nonmanifold,
        snap: args.snap.tolerance,
        run,
    };
    let out = ops::resolve(&input, &opts)?;
    spinner.set_message("writing the result");
    ops::write(&args.output, &out.mesh, None)?;
    drop(spinner);
    let report = out.report();
    if args.json {
        return print_json(&report);
    }
    let r = &report.resolve;
    eprintln!(
        "wrote {}: {} triangles, volume {}, {} ({} self-intersecting pairs; {} components: {} united, {} dropped, {} flipped)",
        args.output.display(),
        report.result.triangles,
        report.result.volume,
        match (report.result.empty, report.result.closed) {
            (true, _) => "empty",
            (false, true) => "closed",
            (false, false) => "NOT closed",
        },
        report.self_intersections,
        r.components,
        r.united_components,
        r.dropped_components,
        r.flipped_components
    );
    if let Some(s) = &report.snap {
        super::print_snap(s);
    }
    Ok(())
}
