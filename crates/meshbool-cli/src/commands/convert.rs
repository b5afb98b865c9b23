//! `meshbool convert`: a mesh file in another format.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops;
use meshbool::Format;

use super::{format_names, one_of};

/// Arguments of `convert`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh file.
    input: PathBuf,
    #[arg(help = concat!(
        "Output mesh file (in the format --to names, else its extension does). ",
        output_rule!()
    ))]
    output: PathBuf,
    /// Read the input as this format whatever its name says.
    #[arg(long, ignore_case = true, value_parser = one_of::<Format>(format_names()))]
    from: Option<Format>,
    /// Write this format.
    #[arg(long, ignore_case = true, value_parser = one_of::<Format>(format_names()))]
    to: Option<Format>,
}

/// Reads the input and writes it in the format `--to` or the output's name says (neither:
/// a usage error, before reading).
pub fn run(args: &Args) -> Result<()> {
    let format = args
        .to
        .or_else(|| Format::for_path(&args.output))
        .ok_or_else(|| {
            crate::exit::usage(format!(
                "{}, or name it with --to",
                super::unknown_mesh_extension(&args.output.display().to_string())
            ))
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
