//! `meshbool split`: both meshes cut along their intersection into groups and components,
//! written to a directory with a manifest.

use std::path::PathBuf;

use anyhow::{Context, Result};
use meshbool::ops::{self, Operand, SplitOptions};
use meshbool::Format;

use super::{format_names, one_of, print_json, warn, OperandFlags};

/// Arguments of `split`.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// First mesh.
    a: PathBuf,
    /// Second mesh.
    b: PathBuf,
    /// Output directory, made with its missing parents. One that is not empty is refused
    /// unless --overwrite is given.
    #[arg(short, long)]
    output: PathBuf,
    /// Replace the split in the output directory: its files (manifest.json and the pieces
    /// it lists) are removed before the new pieces are written, so none is left stale. A
    /// directory holding anything else is still refused (nothing of it is removed).
    #[arg(long)]
    overwrite: bool,
    /// File format of the pieces (obj, ply, ...; f64-exact formats keep seam vertices shared).
    #[arg(long, ignore_case = true, default_value = "ply", value_parser = one_of::<Format>(format_names()))]
    format: Format,
    /// Merge components of fewer triangles than this into the nearest larger component
    /// of the same group (stray fragments); components are numbered largest first.
    #[arg(long, default_value_t = 0)]
    merge_small: usize,
    /// Keep every seam point of the exact arrangement. By default seam points where the
    /// seam runs straight through flat faces of both meshes are removed and zero-area
    /// triangles made by rounding are flipped away (no group changes shape; the groups
    /// stay conforming).
    #[arg(long)]
    keep_seam_points: bool,
    /// Cut coplanar overlaps (shared faces) along every edge of either input that crosses
    /// them, so that the coplanar groups hold the common refinement of both triangulations
    /// (as the reference JS library's do). By default coplanar regions meet along their
    /// boundaries only.
    #[arg(long)]
    coplanar_refinement: bool,
    #[command(flatten)]
    snap: super::Snap,
    #[command(flatten)]
    flags: OperandFlags,
}

/// Reads and checks both operands, splits them, writes the pieces and the manifest, then
/// prints the manifest (`--json`) or a line per group.
pub fn run(args: &Args) -> Result<()> {
    let flags = &args.flags;
    ops::with_threads(flags.threads, || {
        let spinner = flags.spinner();
        let (a, b) = Operand::read_pair(&args.a, &args.b, &flags.checks())?;
        warn(&[a.report().assumed(), b.report().assumed()].concat());
        spinner.set_message("splitting");
        // The operands were checked as they were read.
        let opts = SplitOptions {
            merge_small: args.merge_small,
            snap: args.snap.tolerance,
            keep_seam_points: args.keep_seam_points,
            coplanar_refinement: args.coplanar_refinement,
            run: flags.run(&spinner),
            ..SplitOptions::default()
        };
        let out = ops::split(&a, &b, &opts)?;
        spinner.set_message("writing");
        for file in crate::output::split_leftovers(&args.output, args.overwrite)? {
            std::fs::remove_file(&file)
                .with_context(|| format!("removing the earlier split's {}", file.display()))?;
        }
        let manifest = out.write_dir(&args.output, args.format)?;
        drop(spinner);
        if flags.json {
            return print_json(&manifest);
        }
        for g in &manifest.groups {
            eprintln!(
                "{:<16} {:>8} triangles  area {:<14} {} components",
                g.name.name(),
                g.piece.triangles,
                g.piece.area,
                g.components.len().max(1)
            );
        }
        if let Some(s) = &manifest.snap {
            super::print_snap(s);
        }
        Ok(())
    })?
}
