//! `meshbool`: the command-line client of the meshbool library. Turns flags into library
//! calls and errors into messages with exit codes (1: failure, 2: usage).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use meshbool::io::{self, Format};
use meshbool::measure::{mesh_stats, MeshStats};
use meshbool::{intersect, weld_exact, Mesh};

#[derive(Parser)]
#[command(
    name = "meshbool",
    version,
    about = "Exact booleans, curves, repair and measures for triangle meshes"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print counts and measures of mesh files: triangles, vertices, boundary / non-manifold /
    /// inconsistent edges, degenerate and duplicate triangles, components, closed, volume,
    /// area, projected areas, bounding box.
    Info {
        /// Mesh files (.stl .obj .ply .dxf .json; the content decides where the name does not).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print JSON: one object for one file, an array for several.
        #[arg(long)]
        json: bool,
        /// Read the inputs as this format whatever their names say.
        #[arg(long, value_parser = parse_format)]
        from: Option<Format>,
    },
    /// Convert a mesh file to another format (chosen by the output's extension or --to).
    Convert {
        /// Input mesh file.
        input: PathBuf,
        /// Output mesh file.
        output: PathBuf,
        /// Read the input as this format whatever its name says.
        #[arg(long, value_parser = parse_format)]
        from: Option<Format>,
        /// Write this format (stl, stl-ascii, obj, ply, ply-ascii, ply-be, dxf, json, kirra-json).
        #[arg(long, value_parser = parse_format)]
        to: Option<Format>,
    },
    /// Compute the exact intersection curves of two meshes and write them as polylines
    /// (.obj `l` elements, .dxf 3D POLYLINEs, or .json).
    Curves {
        /// First mesh.
        a: PathBuf,
        /// Second mesh.
        b: PathBuf,
        /// Output file for the polylines (.obj, .dxf or .json).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Leave out segments that only bound coplanar overlaps (shared faces).
        #[arg(long)]
        no_coplanar: bool,
        /// Print a JSON summary on stdout.
        #[arg(long)]
        json: bool,
    },
}

#[derive(serde::Serialize)]
struct CurvesSummary {
    loops: usize,
    open_chains: usize,
    total_length: f64,
    points: usize,
    segments: usize,
    coplanar_segments: usize,
    touching_points: usize,
    candidate_pairs: usize,
    degenerate_triangles: [usize; 2],
    seconds: f64,
}

fn parse_format(s: &str) -> Result<Format, String> {
    Format::from_name(s).ok_or_else(|| {
        let names: Vec<_> = Format::NAMES.iter().map(|(n, _)| *n).collect();
        format!("unknown format {s:?}; one of: {}", names.join(", "))
    })
}

fn read(path: &Path, from: Option<Format>) -> Result<Mesh> {
    let run = || -> meshbool::Result<Mesh> {
        let bytes = std::fs::read(path)?;
        let format = io::detect_format(&bytes, from.or_else(|| Format::for_path(path)))
            .ok_or_else(|| meshbool::Error::UnknownFormat(path.display().to_string()))?;
        io::read_bytes(&bytes, format)
    };
    run().with_context(|| format!("reading {}", path.display()))
}

#[derive(serde::Serialize)]
struct FileStats<'a> {
    file: &'a str,
    #[serde(flatten)]
    stats: MeshStats,
}

fn print_human(file: &str, s: &MeshStats) {
    println!("{file}");
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
        println!("  {k:<21} {v}");
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Info { files, json, from } => {
            let mut all = Vec::new();
            for f in &files {
                let stats = mesh_stats(&read(f, from)?);
                let name = f.display().to_string();
                if !json {
                    print_human(&name, &stats);
                }
                all.push((name, stats));
            }
            if json {
                let items: Vec<_> = all
                    .iter()
                    .map(|(file, stats)| FileStats {
                        file,
                        stats: stats.clone(),
                    })
                    .collect();
                let text = if items.len() == 1 {
                    serde_json::to_string_pretty(&items[0])?
                } else {
                    serde_json::to_string_pretty(&items)?
                };
                println!("{text}");
            }
        }
        Command::Convert {
            input,
            output,
            from,
            to,
        } => {
            let mesh = read(&input, from)?;
            let format = to.or_else(|| Format::for_path(&output)).with_context(|| {
                format!(
                    "cannot tell the output format from {}: use --to",
                    output.display()
                )
            })?;
            io::write_path_as(&output, &mesh, format)
                .with_context(|| format!("writing {}", output.display()))?;
            eprintln!(
                "wrote {} ({format}, {} triangles, {} vertices)",
                output.display(),
                mesh.triangle_count(),
                mesh.vertex_count()
            );
        }
        Command::Curves {
            a,
            b,
            output,
            no_coplanar,
            json,
        } => {
            let (ma, mb) = (
                weld_exact(&read(&a, None)?).mesh,
                weld_exact(&read(&b, None)?).mesh,
            );
            let start = std::time::Instant::now();
            let seam = intersect::intersect(&ma, &mb);
            let curves = intersect::chain(&seam, !no_coplanar);
            let seconds = start.elapsed().as_secs_f64();
            let summary = CurvesSummary {
                loops: curves.iter().filter(|c| c.closed).count(),
                open_chains: curves.iter().filter(|c| !c.closed).count(),
                total_length: curves.iter().map(|c| c.length(&seam)).sum(),
                points: seam.points.len(),
                segments: seam.segments.len(),
                coplanar_segments: seam.segments.iter().filter(|s| s.coplanar).count(),
                touching_points: seam.touching.len(),
                candidate_pairs: seam.candidate_pairs,
                degenerate_triangles: seam.degenerate,
                seconds,
            };
            if let Some(out) = &output {
                let format = Format::for_path(out).with_context(|| {
                    format!(
                        "cannot tell the output format from {}: use .obj, .dxf or .json",
                        out.display()
                    )
                })?;
                let lines: Vec<_> = curves.iter().map(|c| c.to_xyz(&seam)).collect();
                let mut file = std::io::BufWriter::new(
                    std::fs::File::create(out)
                        .with_context(|| format!("creating {}", out.display()))?,
                );
                io::write_polylines(&mut file, &lines, format)
                    .with_context(|| format!("writing {}", out.display()))?;
                std::io::Write::flush(&mut file)?;
            }
            if json {
                println!("{}", serde_json::to_string_pretty(&summary)?);
            } else {
                eprintln!(
                    "{} loops, {} open chains, total length {}, {} seam points ({:.3} s)",
                    summary.loops,
                    summary.open_chains,
                    summary.total_length,
                    summary.points,
                    seconds
                );
            }
            if seam.degenerate != [0, 0] {
                eprintln!(
                    "warning: left out degenerate (zero-area) triangles: {} in {}, {} in {}",
                    seam.degenerate[0],
                    a.display(),
                    seam.degenerate[1],
                    b.display()
                );
            }
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("meshbool: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
