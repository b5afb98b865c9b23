//! `meshbool classify`: where points lie against a mesh — inside, outside or exactly on its
//! surface — with the winding number at each.

use std::io::Read;
use std::path::PathBuf;

use anyhow::{Context, Result};
use meshbool::ops::{self, ClassifyOptions, Operand};

use super::print_json;

/// Arguments of `classify`.
#[derive(clap::Args)]
pub struct Args {
    /// The mesh.
    mesh: PathBuf,
    /// The points: a text file with `x y z` (or `x,y,z`) per line, or a JSON array of
    /// `[x, y, z]`; `-` reads standard input.
    points: PathBuf,
    #[arg(short, long, help = concat!(
        "Write one line per point (`x,y,z,class,winding`) to this file (`.csv`), or a JSON \
         array of `{class, winding}` (`.json`). Without it the lines go to standard output \
         (with --json: into the report). ",
        output_rule!()
    ))]
    output: Option<PathBuf>,
    /// The mesh's checks (as for a boolean operand), --json and --threads.
    #[command(flatten)]
    flags: super::OperandFlags,
}

/// Reads the mesh and the points, classifies, writes what was asked.
pub fn run(args: &Args) -> Result<()> {
    let bytes = if args.points.as_os_str() == "-" {
        let mut b = Vec::new();
        std::io::stdin()
            .read_to_end(&mut b)
            .context("reading points from standard input")?;
        b
    } else {
        std::fs::read(&args.points).with_context(|| format!("reading {}", args.points.display()))?
    };
    let points = meshbool::io::read_points(&bytes)
        .with_context(|| format!("reading points from {}", args.points.display()))?;
    let checks = args.flags.checks();
    let mesh = Operand::read(&args.mesh, &checks)?;
    let opts = ClassifyOptions {
        checks,
        run: ops::RunOptions {
            threads: args.flags.threads,
            cancel: Some(super::cancel()),
            ..Default::default()
        },
    };
    let out = ops::classify_points(&mesh, &points, &opts)?;
    let lines = || {
        let mut text = String::new();
        for ((p, c), w) in points.iter().zip(&out.classes).zip(&out.winding) {
            text.push_str(&format!("{},{},{},{},{}\n", p[0], p[1], p[2], c.name(), w));
        }
        text
    };
    match &args.output {
        Some(path)
            if path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("json")) =>
        {
            let results = out.report(true).results;
            meshbool::io::write_bytes(path, serde_json::to_string(&results)?.as_bytes())?;
        }
        Some(path) => {
            meshbool::io::write_bytes(path, format!("x,y,z,class,winding\n{}", lines()).as_bytes())?
        }
        None if !args.flags.json => super::out(&lines())?,
        None => {}
    }
    let report = out.report(args.flags.json && args.output.is_none());
    if args.flags.json {
        print_json(&report)?;
    } else {
        eprintln!(
            "{} points: {} inside, {} outside, {} on the surface ({} mesh, {:.3} s)",
            report.points,
            report.inside,
            report.outside,
            report.on,
            if report.closed { "closed" } else { "open" },
            report.seconds
        );
    }
    Ok(())
}
