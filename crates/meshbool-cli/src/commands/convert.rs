//! `meshbool convert`: a mesh file in another format.

use std::path::PathBuf;

use anyhow::{Context, Result};
use meshbool::ops;
use meshbool::Format;

use super::parse_value;

/// Arguments of `convert`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh file.
    input: PathBuf,
    /// Output mesh file.
    output: PathBuf,
    /// Read the input as this format whatever its name says.
    #[arg(long, value_parser = parse_value::<Format>)]
    from: Option<Format>,
    /// Write this format (stl, stl-ascii, obj, ply, ply-ascii, ply-be, dxf, json, kirra-json).
    #[arg(long, value_parser = parse_value::<Format>)]
    to: Option<Format>,
}

/// Reads the input and writes it in the format `--to` or the output's name says.
pub fn run(args: &Args) -> Result<()> {
    let format = args
        .to
        .or_else(|| Format::for_path(&args.output))
        .with_context(|| {
            format!(
                "cannot tell the output format from {}: use --to",
                args.output.display()
            )
        })?;
    let (mesh, _) = ops::read(&args.input, args.from)?;
    ops::write(&args.output, &mesh, Some(format))?;
    eprintln!(
        "wrote {} ({format}, {} triangles, {} vertices)",
        args.output.display(),
        mesh.triangle_count(),
        mesh.vertex_count()
    );
    Ok(())
}
