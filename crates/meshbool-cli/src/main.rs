//! `meshbool`: the command-line client of the meshbool library. Turns flags into library
//! calls and errors into messages with exit codes (1: failure, 2: usage).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use meshbool::edges::EdgeCounts;
use meshbool::io::{self, Format};
use meshbool::measure::{mesh_stats, MeshStats};
use meshbool::repair::{
    self, orient, CloseMode, CloseOptions, DegenerateOptions, Facing, RepairConfig,
};
use meshbool::{boolean, intersect, weld_exact, Mesh};

/// mimalloc keeps freed memory for reuse: a boolean's stages allocate and free large
/// buffers one after another, which with the system allocator cost a fresh mapping and
/// kernel page zeroing each time. Version 2 (`v2`), which keeps freed memory longer than 3:
/// 2M-triangle union file to file 1.9-2.3 -> 1.06-1.08 s, system time 1.3-1.5 -> 0.25 s.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

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
    /// A ∪ B: the union of two meshes.
    Union(OperandArgs),
    /// A ∩ B: the intersection of two meshes.
    #[command(alias = "intersect")]
    Intersection(OperandArgs),
    /// A − B (or B − A with --reverse).
    #[command(alias = "subtract")]
    Difference {
        #[command(flatten)]
        args: OperandArgs,
        /// Compute B − A instead.
        #[arg(long)]
        reverse: bool,
    },
    /// Split both meshes along their intersection into groups (a_in_b, a_out_b, b_in_a,
    /// b_out_a, and coplanar a_on_b_same/opposite, b_on_a_same/opposite) and their
    /// connected components; writes one file per group and per component plus manifest.json.
    Split {
        /// First mesh.
        a: PathBuf,
        /// Second mesh.
        b: PathBuf,
        /// Output directory.
        #[arg(short, long)]
        output: PathBuf,
        /// File format of the pieces (obj, ply, ...; f64-exact formats keep seam vertices shared).
        #[arg(long, default_value = "ply", value_parser = parse_format)]
        format: Format,
        /// Merge components of fewer triangles than this into the nearest larger component
        /// of the same group (stray fragments); components are numbered largest first.
        #[arg(long, default_value_t = 0)]
        merge_small: usize,
        #[command(flatten)]
        opts: BoolOpts,
    },
    /// Merge pieces of a split into one welded mesh: `--keep a_out_b --keep b_in_a:flip
    /// --keep a_in_b#2` (group, optional #component, optional :flip).
    Pick {
        /// Directory written by `meshbool split`.
        dir: PathBuf,
        /// A piece to keep: GROUP[#COMPONENT][:flip].
        #[arg(long = "keep", required = true)]
        keep: Vec<String>,
        /// Output mesh file.
        #[arg(short, long)]
        output: PathBuf,
        /// Print a JSON report on stdout.
        #[arg(long)]
        json: bool,
    },
    /// Close open meshes into solids. Modes: `cap` (triangulate every boundary loop,
    /// non-planar loops too), `stitch` (join pairs of loops with bands of triangles),
    /// `curtain` (vertical walls from the boundary down to `floor = min z − floor-offset`,
    /// floor capped; orient the surface up first), `stitch+curtain` (stitch what pairs up,
    /// curtain the rest).
    Close {
        /// Input mesh.
        input: PathBuf,
        /// Output mesh file.
        #[arg(short, long)]
        output: PathBuf,
        /// How to close.
        #[arg(long, value_enum, default_value = "cap")]
        mode: CloseArg,
        /// Curtain: distance of the floor below the lowest point.
        #[arg(long, default_value_t = 10.0)]
        floor_offset: f64,
        /// Stitch: the largest gap between two loops that may be bridged (default: any).
        #[arg(long)]
        max_gap: Option<f64>,
        /// Print a JSON report on stdout.
        #[arg(long)]
        json: bool,
    },
    /// Repair pipeline. Steps, in this order, each only when asked for: weld within a
    /// distance, duplicate removal, T-junctions, degenerate/sliver removal, orientation
    /// (on by default: consistent, majority facing), terrain folds, closing, capping
    /// small gaps left.
    /// Every removed triangle is counted in the report. `--config FILE.json` gives the
    /// whole configuration (the library's `RepairConfig`); flags override it.
    Repair {
        /// Input mesh.
        input: PathBuf,
        /// Output mesh file.
        #[arg(short, long)]
        output: PathBuf,
        /// A JSON configuration (fields of `RepairConfig`; left-out fields default).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Weld vertices closer than this distance (no chaining; see the library docs).
        #[arg(long)]
        weld: Option<f64>,
        /// Remove duplicate triangles; anti-parallel pairs (double walls) cancel.
        #[arg(long)]
        remove_duplicates: bool,
        /// Split boundary edges at vertices lying exactly on them (closes T-junction cracks).
        #[arg(long)]
        tjunctions: bool,
        /// Remove zero-area triangles (exact) by edge collapse or flip, without cracks.
        #[arg(long)]
        remove_degenerate: bool,
        /// With --remove-degenerate: also triangles of at most this area.
        #[arg(long, requires = "remove_degenerate")]
        min_area: Option<f64>,
        /// With --remove-degenerate: also triangles whose longest edge over smallest
        /// height exceeds this (1.15 for equilateral).
        #[arg(long, requires = "remove_degenerate")]
        max_aspect: Option<f64>,
        /// Orientation: consistent, then facing `majority` (default), `z-up`, `outward`;
        /// `none` skips the step.
        #[arg(long, value_enum)]
        orient: Option<OrientArg>,
        /// Shorthand for `--orient z-up`.
        #[arg(long, conflicts_with = "orient")]
        z_up: bool,
        /// Terrain: remove folds (triangles facing down after orienting up) by taking out
        /// a vertex and re-triangulating in plan view. Needs --z-up.
        #[arg(long)]
        remove_folds: bool,
        /// Close into a solid: none (default), cap, stitch, curtain, stitch+curtain.
        #[arg(long, value_enum)]
        close: Option<CloseArg>,
        /// Curtain: distance of the floor below the lowest point (default 10).
        #[arg(long)]
        floor_offset: Option<f64>,
        /// Stitch: the largest gap between two loops that may be bridged (default: any).
        #[arg(long)]
        max_gap: Option<f64>,
        /// Finally cap every hole left whose bounding-box diagonal is at most this.
        #[arg(long)]
        close_gaps: Option<f64>,
        /// Print a JSON report on stdout.
        #[arg(long)]
        json: bool,
    },
    /// Make triangle orientation consistent across every manifold edge, component by
    /// component, and face each component as asked (default: as most triangles already did).
    Orient {
        /// Input mesh.
        input: PathBuf,
        /// Output mesh file.
        #[arg(short, long)]
        output: PathBuf,
        /// Normals up (positive projected XY area): terrain and other open surfaces.
        #[arg(long, conflicts_with = "outward")]
        z_up: bool,
        /// Closed components outward (positive volume).
        #[arg(long)]
        outward: bool,
        /// Print a JSON report on stdout.
        #[arg(long)]
        json: bool,
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

/// Ways of closing an open mesh (`repair::CloseMode`).
#[derive(clap::ValueEnum, Clone, Copy)]
enum CloseArg {
    /// Leave boundaries open.
    None,
    /// Triangulate every boundary loop.
    Cap,
    /// Join pairs of boundary loops with bands.
    Stitch,
    /// Walls down to a floor, then the floor capped.
    Curtain,
    /// Stitch the loops that pair up, curtain the rest.
    #[value(name = "stitch+curtain")]
    StitchCurtain,
}

impl From<CloseArg> for CloseMode {
    fn from(c: CloseArg) -> Self {
        match c {
            CloseArg::None => CloseMode::None,
            CloseArg::Cap => CloseMode::Cap,
            CloseArg::Stitch => CloseMode::Stitch,
            CloseArg::Curtain => CloseMode::Curtain,
            CloseArg::StitchCurtain => CloseMode::StitchCurtain,
        }
    }
}

/// Facing after orientation, or no orientation step.
#[derive(clap::ValueEnum, Clone, Copy)]
enum OrientArg {
    /// Skip the orientation step.
    None,
    /// Keep the facing most triangles had.
    Majority,
    /// Normals up.
    ZUp,
    /// Closed components outward.
    Outward,
}

/// The operands and output of a boolean command.
#[derive(clap::Args, Clone)]
struct OperandArgs {
    /// First mesh (A).
    a: PathBuf,
    /// Second mesh (B).
    b: PathBuf,
    /// Output mesh file.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    opts: BoolOpts,
}

/// Options shared by the boolean commands.
#[derive(clap::Args, Clone)]
struct BoolOpts {
    /// Proceed even when an input has inconsistently oriented or non-manifold edges (the
    /// result then assumes the orientation as given; the JSON report lists what was assumed).
    #[arg(long)]
    force: bool,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
    /// Skip the check for self-intersecting inputs (it costs about as much as the boolean
    /// on large meshes); only for inputs known to be clean.
    #[arg(long)]
    no_self_check: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
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
    Ok(read_as(path, from)?.0)
}

/// [`read`], also giving the format the file was read as.
fn read_as(path: &Path, from: Option<Format>) -> Result<(Mesh, Format)> {
    let run = || -> meshbool::Result<(Mesh, Format)> {
        let bytes = std::fs::read(path)?;
        let format = io::detect_format(&bytes, from.or_else(|| Format::for_path(path)))
            .ok_or_else(|| meshbool::Error::UnknownFormat(path.display().to_string()))?;
        Ok((io::read_bytes(&bytes, format)?, format))
    };
    run().with_context(|| format!("reading {}", path.display()))
}

/// Reads a mesh file and welds exactly equal positions (what every operation expects);
/// formats whose reader welds already are not welded twice.
fn read_welded(path: &Path) -> Result<Mesh> {
    let (mesh, format) = read_as(path, None)?;
    Ok(if format.welds_on_read() {
        mesh
    } else {
        weld_exact(&mesh).mesh
    })
}

/// Writes a mesh in the format its file name says, naming the file in any error.
fn write_mesh(path: &Path, mesh: &Mesh) -> Result<()> {
    io::write_path(path, mesh).with_context(|| format!("writing {}", path.display()))
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

/// Reads, validates and welds a boolean operand; refuses inconsistent orientation and
/// non-manifold edges unless `force`, in which case what was assumed is returned.
fn operand(path: &Path, opts: &BoolOpts, assumed: &mut Vec<String>) -> Result<Mesh> {
    let force = opts.force;
    let mesh = read_welded(path)?;
    // Only what decides whether inside/outside is well defined: edge kinds (linear time).
    let counts = EdgeCounts::of(&mesh);
    let (inconsistent, non_manifold) = (counts.inconsistent, counts.non_manifold);
    let mut problems = Vec::new();
    if inconsistent > 0 {
        problems.push(format!("{inconsistent} inconsistently oriented edges"));
    }
    if non_manifold > 0 {
        problems.push(format!("{non_manifold} non-manifold edges"));
    }
    let crossings = if opts.no_self_check {
        assumed.push(format!(
            "{}: not checked for self-intersections",
            path.display()
        ));
        Vec::new()
    } else {
        intersect::self_intersections(&mesh)
    };
    if let Some(&(i, j)) = crossings.first() {
        let [a, b, c] = mesh.corners(i as usize);
        let near: [f64; 3] = std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0);
        problems.push(format!(
            "{} self-intersecting triangle pairs (first: triangles {i} and {j}, near {near:?})",
            crossings.len()
        ));
    }
    if !problems.is_empty() {
        let what = format!("{}: {}", path.display(), problems.join(", "));
        if !force {
            anyhow::bail!(
                "{what}; inside/outside would be ambiguous. Repair the input, or pass --force \
                 to proceed with the input as given"
            );
        }
        assumed.push(format!("{what} (input taken as given)"));
    }
    Ok(mesh)
}

/// Both operands of a boolean, read and checked side by side ([`operand`]), each with
/// what was assumed about it.
type Checked = (Mesh, Vec<String>);
fn both(a: &Path, b: &Path, opts: &BoolOpts) -> Result<(Checked, Checked)> {
    let one = |p: &Path| -> Result<Checked> {
        let mut assumed = Vec::new();
        let m = operand(p, opts, &mut assumed)?;
        Ok((m, assumed))
    };
    let (ra, rb) = rayon::join(|| one(a), || one(b));
    Ok((ra?, rb?))
}

/// Edge counts, volume and area of a result: the part of [`mesh_stats`] a report needs.
fn result_measures(m: &Mesh) -> (usize, usize, f64, f64) {
    let counts = EdgeCounts::of(m);
    (
        counts.boundary,
        counts.non_manifold,
        meshbool::measure::signed_volume(m),
        meshbool::measure::area(m),
    )
}

/// A spinner with the elapsed time and the current stage on standard error; drawn only
/// when standard error is a terminal (never into pipes, files or tests). Cleared when
/// dropped, so an error message never lands after a stale spinner line.
struct Spinner(indicatif::ProgressBar);

impl Spinner {
    fn set_message(&self, msg: &'static str) {
        self.0.set_message(msg);
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}

fn progress() -> Spinner {
    let bar = indicatif::ProgressBar::new_spinner();
    if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} [{elapsed}] {msg}") {
        bar.set_style(style);
    }
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    Spinner(bar)
}

/// What the input stage does, for the progress display.
fn checking(opts: &BoolOpts) -> &'static str {
    if opts.no_self_check {
        "reading and checking the inputs"
    } else {
        "reading the inputs, checking for self-intersections"
    }
}

fn set_threads(n: Option<usize>) -> Result<()> {
    if let Some(n) = n {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()?;
    }
    Ok(())
}

#[derive(serde::Serialize)]
struct BoolReport {
    operation: &'static str,
    triangles: usize,
    vertices: usize,
    boundary_edges: usize,
    non_manifold_edges: usize,
    closed: bool,
    volume: f64,
    area: f64,
    seam_points: usize,
    /// Result triangles turned over by rounding seam points to f64.
    rounding_flips: usize,
    failed_triangles: Vec<String>,
    assumed: Vec<String>,
    seconds: f64,
}

fn run_boolean(args: &OperandArgs, op: boolean::Op) -> Result<()> {
    let (a, b, output, opts) = (&args.a, &args.b, &args.output, &args.opts);
    set_threads(opts.threads)?;
    let bar = progress();
    bar.set_message(checking(opts));
    let mut assumed = Vec::new();
    let ((ma, assumed_a), (mb, assumed_b)) = both(a, b, opts)?;
    assumed.extend(assumed_a);
    assumed.extend(assumed_b);
    let start = std::time::Instant::now();
    let r = boolean::boolean_with_progress(&ma, &mb, op, &|s| bar.set_message(s.describe()));
    let seconds = start.elapsed().as_secs_f64();
    bar.set_message("writing");
    let (written, (boundary_edges, non_manifold_edges, volume, area)) =
        rayon::join(|| write_mesh(output, &r.mesh), || result_measures(&r.mesh));
    drop(bar);
    written?;
    if r.rounding_flips > 0 {
        assumed.push(format!(
            "{} result triangles are thinner than f64 rounding of their seam points and turned over when written (exact before rounding)",
            r.rounding_flips
        ));
    }
    if r.degenerate != [0, 0] {
        assumed.push(format!(
            "degenerate (zero-area) triangles where the meshes meet were left out: {} in A, {} in B",
            r.degenerate[0], r.degenerate[1]
        ));
    }
    let report = BoolReport {
        operation: match op {
            boolean::Op::Union => "union",
            boolean::Op::Intersection => "intersection",
            boolean::Op::Difference => "difference",
            boolean::Op::ReverseDifference => "reverse-difference",
        },
        triangles: r.mesh.triangles.len(),
        vertices: r.mesh.positions.len(),
        boundary_edges,
        non_manifold_edges,
        closed: !r.mesh.is_empty() && boundary_edges == 0 && non_manifold_edges == 0,
        volume,
        area,
        seam_points: r.seam_points,
        rounding_flips: r.rounding_flips,
        failed_triangles: r
            .failed
            .iter()
            .map(|(src, t, why)| format!("{src:?} triangle {t}: {why}"))
            .collect(),
        assumed,
        seconds,
    };
    for w in report.assumed.iter().chain(&report.failed_triangles) {
        eprintln!("warning: {w}");
    }
    if opts.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        eprintln!(
            "wrote {} ({} triangles, volume {}, {} boundary edges, {:.3} s)",
            output.display(),
            report.triangles,
            report.volume,
            report.boundary_edges,
            seconds
        );
    }
    Ok(())
}

#[derive(serde::Serialize, serde::Deserialize)]
struct PieceInfo {
    file: String,
    triangles: usize,
    area: f64,
    volume: f64,
}

#[derive(serde::Serialize, serde::Deserialize)]
struct GroupInfo {
    name: String,
    #[serde(flatten)]
    piece: PieceInfo,
    components: Vec<PieceInfo>,
    /// Small components merged into larger ones (`--merge-small`).
    #[serde(default)]
    merged_small_components: usize,
}

#[derive(serde::Serialize, serde::Deserialize)]
struct Manifest {
    a: String,
    b: String,
    seam_points: usize,
    groups: Vec<GroupInfo>,
}

fn piece_info(file: String, m: &Mesh) -> PieceInfo {
    let s = mesh_stats(m);
    PieceInfo {
        file,
        triangles: s.triangles,
        area: s.area,
        volume: s.volume,
    }
}

fn run_split(
    a: &Path,
    b: &Path,
    dir: &Path,
    format: Format,
    merge_small: usize,
    opts: &BoolOpts,
) -> Result<()> {
    set_threads(opts.threads)?;
    let bar = progress();
    bar.set_message(checking(opts));
    let ((ma, mut assumed), (mb, assumed_b)) = both(a, b, opts)?;
    assumed.extend(assumed_b);
    for w in &assumed {
        eprintln!("warning: {w}");
    }
    bar.set_message("splitting");
    let s = boolean::split_with_progress(&ma, &mb, &|s| bar.set_message(s.describe()));
    bar.set_message("writing");
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let ext = Format::NAMES
        .iter()
        .find(|(_, f)| *f == format)
        .map_or("ply", |(n, _)| n.split('-').next().unwrap_or("ply"));
    let mut groups = Vec::new();
    for g in boolean::Group::ALL {
        let (mesh, _) = s.group(g);
        if mesh.is_empty() {
            continue;
        }
        let write = |name: String, m: &Mesh| -> Result<PieceInfo> {
            let path = dir.join(&name);
            io::write_path_as(&path, m, format)
                .with_context(|| format!("writing {}", path.display()))?;
            Ok(piece_info(name, m))
        };
        let piece = write(format!("{}.{ext}", g.name()), &mesh)?;
        let parts = meshbool::edges::components_merged(&mesh, merge_small);
        let mut components = Vec::new();
        if parts.parts.len() > 1 {
            for (k, part) in parts.parts.iter().enumerate() {
                let tris = part.iter().map(|&t| mesh.triangles[t as usize]).collect();
                let sub = boolean::pick(&[(&Mesh::new(mesh.positions.clone(), tris), false)]);
                components.push(write(format!("{}.{k}.{ext}", g.name()), &sub)?);
            }
        }
        groups.push(GroupInfo {
            name: g.name().to_string(),
            piece,
            components,
            merged_small_components: parts.merged,
        });
    }
    let manifest = Manifest {
        a: a.display().to_string(),
        b: b.display().to_string(),
        seam_points: s.seam.points.len(),
        groups,
    };
    let text = serde_json::to_string_pretty(&manifest)?;
    std::fs::write(dir.join("manifest.json"), &text)?;
    drop(bar);
    if opts.json {
        println!("{text}");
    } else {
        for g in &manifest.groups {
            eprintln!(
                "{:<16} {:>8} triangles  area {:<14} {} components",
                g.name,
                g.piece.triangles,
                g.piece.area,
                g.components.len().max(1)
            );
        }
    }
    Ok(())
}

fn run_pick(dir: &Path, keep: &[String], output: &Path, json: bool) -> Result<()> {
    let manifest: Manifest = serde_json::from_slice(
        &std::fs::read(dir.join("manifest.json"))
            .with_context(|| format!("reading {}/manifest.json", dir.display()))?,
    )
    .context("manifest.json is not a meshbool split manifest")?;
    let mut meshes = Vec::new();
    for spec in keep {
        let (body, flip) = match spec.strip_suffix(":flip") {
            Some(b) => (b, true),
            None => (spec.as_str(), false),
        };
        let (name, comp) = match body.split_once('#') {
            Some((n, c)) => (
                n,
                Some(
                    c.parse::<usize>()
                        .with_context(|| format!("bad component in {spec:?}"))?,
                ),
            ),
            None => (body, None),
        };
        let g = manifest
            .groups
            .iter()
            .find(|g| g.name == name)
            .with_context(|| format!("{spec:?}: no group {name:?} in this split"))?;
        let file = match comp {
            None => &g.piece.file,
            Some(k) if g.components.is_empty() && k == 0 => &g.piece.file,
            Some(k) => {
                &g.components
                    .get(k)
                    .with_context(|| {
                        format!(
                            "{spec:?}: group {name} has {} components",
                            g.components.len().max(1)
                        )
                    })?
                    .file
            }
        };
        meshes.push((read(&dir.join(file), None)?, flip));
    }
    let refs: Vec<(&Mesh, bool)> = meshes.iter().map(|(m, f)| (m, *f)).collect();
    let merged = boolean::pick(&refs);
    write_mesh(output, &merged)?;
    let s = mesh_stats(&merged);
    if json {
        println!("{}", serde_json::to_string_pretty(&s)?);
    } else {
        eprintln!(
            "wrote {} ({} triangles, {} boundary edges)",
            output.display(),
            s.triangles,
            s.boundary_edges
        );
    }
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Union(args) => run_boolean(&args, boolean::Op::Union)?,
        Command::Intersection(args) => run_boolean(&args, boolean::Op::Intersection)?,
        Command::Difference { args, reverse } => {
            let op = if reverse {
                boolean::Op::ReverseDifference
            } else {
                boolean::Op::Difference
            };
            run_boolean(&args, op)?
        }
        Command::Split {
            a,
            b,
            output,
            format,
            merge_small,
            opts,
        } => run_split(&a, &b, &output, format, merge_small, &opts)?,
        Command::Pick {
            dir,
            keep,
            output,
            json,
        } => run_pick(&dir, &keep, &output, json)?,
        Command::Close {
            input,
            output,
            mode,
            floor_offset,
            max_gap,
            json,
        } => {
            let mesh = read_welded(&input)?;
            let opts = CloseOptions {
                stitch_max_gap: max_gap,
                floor_offset,
            };
            let (closed, report) = repair::close(&mesh, mode.into(), &opts)?;
            write_mesh(&output, &closed)?;
            let s = mesh_stats(&closed);
            let mut v = serde_json::to_value(&report)?;
            v["closed"] = s.closed.into();
            v["volume"] = s.volume.into();
            v["boundary_edges"] = s.boundary_edges.into();
            if json {
                println!("{}", serde_json::to_string_pretty(&v)?);
            } else {
                eprintln!(
                    "wrote {}: {} boundary edges left, closed: {}, volume {} ({v})",
                    output.display(),
                    s.boundary_edges,
                    s.closed,
                    s.volume
                );
            }
        }
        Command::Repair {
            input,
            output,
            config,
            weld,
            remove_duplicates,
            tjunctions,
            remove_degenerate,
            min_area,
            max_aspect,
            orient,
            z_up,
            remove_folds,
            close,
            floor_offset,
            max_gap,
            close_gaps,
            json,
        } => {
            let mut c: RepairConfig = match &config {
                Some(path) => {
                    let text = std::fs::read_to_string(path)
                        .with_context(|| format!("reading {}", path.display()))?;
                    serde_json::from_str(&text).with_context(|| {
                        format!("{}: not a repair configuration", path.display())
                    })?
                }
                None => RepairConfig::default(),
            };
            if weld.is_some() {
                c.weld = weld;
            }
            c.remove_duplicates |= remove_duplicates;
            c.tjunctions |= tjunctions;
            if remove_degenerate {
                let d = c.degenerate.get_or_insert_with(DegenerateOptions::default);
                if let Some(a) = min_area {
                    d.min_area = a;
                }
                if max_aspect.is_some() {
                    d.max_aspect = max_aspect;
                }
            }
            let orient = if z_up { Some(OrientArg::ZUp) } else { orient };
            if let Some(o) = orient {
                c.orient = match o {
                    OrientArg::None => None,
                    OrientArg::Majority => Some(Facing::Majority),
                    OrientArg::ZUp => Some(Facing::ZUp),
                    OrientArg::Outward => Some(Facing::Outward),
                };
            }
            c.remove_folds |= remove_folds;
            if let Some(m) = close {
                c.close = m.into();
            }
            if let Some(f) = floor_offset {
                c.close_options.floor_offset = f;
            }
            if max_gap.is_some() {
                c.close_options.stitch_max_gap = max_gap;
            }
            if close_gaps.is_some() {
                c.close_gaps = close_gaps;
            }
            let mesh = read_welded(&input)?;
            let (mesh, report) = repair::repair(&mesh, &c)?;
            write_mesh(&output, &mesh)?;
            if json {
                println!("{}", serde_json::to_string_pretty(&report)?);
            } else {
                let (b, a) = (&report.before, &report.after);
                eprintln!(
                    "wrote {}: triangles {} -> {}, boundary edges {} -> {}, non-manifold edges {} -> {}, inconsistent edges {} -> {}, degenerate {} -> {}, closed: {}, volume {} (--json for every step)",
                    output.display(),
                    b.triangles, a.triangles,
                    b.boundary_edges, a.boundary_edges,
                    b.non_manifold_edges, a.non_manifold_edges,
                    b.inconsistent_edges, a.inconsistent_edges,
                    b.degenerate_triangles, a.degenerate_triangles,
                    a.closed, a.volume
                );
            }
        }
        Command::Orient {
            input,
            output,
            z_up,
            outward,
            json,
        } => {
            let mesh = read_welded(&input)?;
            let facing = match (z_up, outward) {
                (true, _) => Facing::ZUp,
                (_, true) => Facing::Outward,
                _ => Facing::Majority,
            };
            let (oriented, report) = orient(&mesh, facing);
            write_mesh(&output, &oriented)?;
            if json {
                println!("{}", serde_json::to_string_pretty(&report)?);
            } else {
                eprintln!(
                    "wrote {}: {} triangles flipped, {} components, {} edges could not be made consistent, {} non-manifold edges",
                    output.display(),
                    report.flipped,
                    report.components,
                    report.conflicting_edges,
                    report.non_manifold_edges
                );
            }
        }
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
            let (ma, mb) = (read_welded(&a)?, read_welded(&b)?);
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
