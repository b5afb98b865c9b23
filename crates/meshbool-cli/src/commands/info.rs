//! `meshbool info`: counts and measures of mesh files.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::measure::MeshStats;
use meshbool::ops::{self, InfoReport};
use meshbool::Format;

use super::{format_names, one_of, print_json};

/// Arguments of `info`.
#[derive(clap::Args)]
pub struct Args {
    /// Mesh files (.stl .obj .ply .dxf .json .glb; the content decides where the name does not).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Print JSON: one object for one file, an array for several.
    #[arg(long)]
    json: bool,
    /// Read the inputs as this format whatever their names say.
    #[arg(long, ignore_case = true, value_parser = one_of::<Format>(format_names()))]
    from: Option<Format>,
}

/// Measures each file; prints a table per file as it goes, or JSON at the end.
pub fn run(args: &Args) -> Result<()> {
    let mut reports = Vec::new();
    for f in &args.files {
        let stats = ops::info(&ops::read(f, args.from)?.0)?;
        let name = f.display().to_string();
        if !args.json {
            print_human(&name, &stats)?;
        }
        reports.push(InfoReport::new(name, stats));
    }
    if !args.json {
        Ok(())
    } else if let [one] = &reports[..] {
        print_json(one)
    } else {
        print_json(&reports)
    }
}

fn print_human(file: &str, s: &MeshStats) -> Result<()> {
    let mut text = format!("{file}\n");
    let rows: [(&str, String); 13] = [
        ("triangles", s.triangles.to_string()),
        (
            "vertices",
            format!("{} ({} unreferenced)", s.vertices, s.unreferenced_vertices),
        ),
        ("edges", s.edges.to_string()),
        ("boundary edges", s.boundary_edges.to_string()),
        ("non-manifold edges", s.non_manifold_edges.to_string()),
        ("inconsistent edges", s.inconsistent_edges.to_string()),
        ("degenerate triangles", s.degenerate_triangles.to_string()),
        ("duplicate triangles", s.duplicate_triangles.to_string()),
        ("components", s.components.to_string()),
        ("closed", if s.closed { "yes".into() } else { "no".into() }),
        (
            "volume",
            if s.closed {
                format!("{}", s.volume)
            } else {
                format!("{} (open mesh: not meaningful)", s.volume)
            },
        ),
        (
            "area",
            format!(
                "{} (projected xy {}, yz {}, xz {})",
                s.area, s.projected_area.xy, s.projected_area.yz, s.projected_area.xz
            ),
        ),
        (
            "bbox",
            s.bbox
                .map_or("none".into(), |b| format!("{:?} .. {:?}", b.min, b.max)),
        ),
    ];
    for (k, v) in rows {
        text.push_str(&format!("  {k:<21} {v}\n"));
    }
    super::out(&text)
}
