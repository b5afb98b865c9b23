//! `meshbool repair`: the repair pipeline, configured by a JSON file and flags.

use std::path::PathBuf;

use anyhow::{Context, Result};
use meshbool::ops::{self, Checks, Operand, Progress, RunOptions};
use meshbool::repair::{CloseMode, DegenerateOptions, Facing, RepairConfig};

use super::{one_of, print_json, Spinner};

/// Arguments of `repair`: each flag overrides the configuration file's field.
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Input mesh.
    input: PathBuf,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
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
    /// Remove duplicates taking triangles whose corresponding corners are within this
    /// distance as copies: near double walls cancel, near copies keep one.
    #[arg(long, value_name = "D")]
    remove_overlapping: Option<f64>,
    /// Weld boundary vertices (ends of edges used by one triangle) within this distance;
    /// other vertices stay as they are.
    #[arg(long, value_name = "D")]
    weld_boundary: Option<f64>,
    /// Split boundary edges at vertices lying exactly on them (closes T-junction cracks);
    /// with a distance D, also at vertices within D of them (the edge bends through the
    /// vertex).
    #[arg(long, value_name = "D", num_args = 0..=1)]
    tjunctions: Option<Option<f64>>,
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
    /// Collapse edges shorter than D and remove needles (altitude below D) where that
    /// keeps the mesh manifold, turns no triangle over, makes no self-intersection and
    /// moves no vertex more than D (after degenerate removal, before orientation).
    #[arg(long, value_name = "D", allow_hyphen_values = true, value_parser = super::snap_tolerance)]
    snap: Option<f64>,
    /// Orientation: consistent, then facing as named (default: majority); `none` skips
    /// the step.
    #[arg(long, ignore_case = true, value_parser = one_of::<Orientation>(["none"].into_iter().chain(Facing::ALL.map(Facing::name))))]
    orient: Option<Orientation>,
    /// Shorthand for `--orient z-up`.
    #[arg(long, conflicts_with = "orient")]
    z_up: bool,
    /// Terrain: remove folds (triangles facing down after orienting up) by taking out
    /// a vertex and re-triangulating in plan view. Needs --z-up.
    #[arg(long)]
    remove_folds: bool,
    /// Close into a solid (default: none).
    #[arg(long, ignore_case = true, value_parser = one_of::<CloseMode>(CloseMode::ALL.map(CloseMode::name)))]
    close: Option<CloseMode>,
    /// Curtain: distance of the floor below the lowest point (default 10).
    #[arg(long)]
    floor_offset: Option<f64>,
    /// Stitch: the largest gap between two loops that may be bridged (default: any).
    #[arg(long)]
    max_gap: Option<f64>,
    /// Finally cap every hole left whose bounding-box diagonal is at most this.
    #[arg(long)]
    close_gaps: Option<f64>,
    /// Keep every step's result, even one that makes the mesh worse (by default a step
    /// that adds boundary, non-manifold or inconsistent edges or self-intersections, or
    /// changes a closed mesh's volume by more than 0.5 %, is undone and reported).
    #[arg(long)]
    no_gate: bool,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

/// `--orient`: a facing, or `none` (no orientation step).
#[derive(Clone, Copy)]
struct Orientation(Option<Facing>);

impl std::str::FromStr for Orientation {
    type Err = meshbool::Error;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s.eq_ignore_ascii_case("none") {
            Ok(Orientation(None))
        } else {
            s.parse().map(|f| Orientation(Some(f)))
        }
    }
}

impl Args {
    /// The configuration: the file's (or the default), with the flags given over it.
    fn config(&self) -> Result<RepairConfig> {
        let mut c: RepairConfig = match &self.config {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .with_context(|| format!("reading {}", path.display()))?;
                serde_json::from_str(&text)
                    .with_context(|| format!("{}: not a repair configuration", path.display()))?
            }
            None => RepairConfig::default(),
        };
        if self.weld.is_some() {
            c.weld = self.weld;
        }
        c.remove_duplicates |= self.remove_duplicates;
        if self.remove_overlapping.is_some() {
            c.remove_overlapping = self.remove_overlapping;
        }
        if self.weld_boundary.is_some() {
            c.weld_boundary = self.weld_boundary;
        }
        if let Some(tolerance) = self.tjunctions {
            c.tjunctions = true;
            if tolerance.is_some() {
                c.tjunction_tolerance = tolerance;
            }
        }
        if self.remove_degenerate {
            let d = c.degenerate.get_or_insert_with(DegenerateOptions::default);
            if let Some(a) = self.min_area {
                d.min_area = a;
            }
            if self.max_aspect.is_some() {
                d.max_aspect = self.max_aspect;
            }
        }
        if self.snap.is_some() {
            c.snap = self.snap;
        }
        if self.z_up {
            c.orient = Some(Facing::ZUp);
        } else if let Some(Orientation(o)) = self.orient {
            c.orient = o;
        }
        c.remove_folds |= self.remove_folds;
        if let Some(m) = self.close {
            c.close = m;
        }
        if let Some(f) = self.floor_offset {
            c.close_options.floor_offset = f;
        }
        if self.max_gap.is_some() {
            c.close_options.stitch_max_gap = self.max_gap;
        }
        if self.close_gaps.is_some() {
            c.close_gaps = self.close_gaps;
        }
        c.gate &= !self.no_gate;
        Ok(c)
    }
}

/// Repairs the input as configured, writes it, prints the report.
pub fn run(args: &Args) -> Result<()> {
    let config = args.config()?;
    let spinner = Spinner::new("reading the input");
    let input = Operand::read(&args.input, &Checks::NONE)?;
    let bar = spinner.0.clone();
    let run = RunOptions {
        threads: None,
        progress: Some(Progress::new(move |s| bar.set_message(s.describe()))),
        cancel: Some(super::cancel()),
    };
    let out = ops::repair_with(&input, &config, &run)?;
    spinner.set_message("writing the result");
    ops::write(&args.output, &out.mesh, None)?;
    drop(spinner);
    if args.json {
        return print_json(&out.report());
    }
    let (b, a) = (&out.repair.before, &out.repair.after);
    for u in &out.repair.undone {
        eprintln!(
            "undone: {} (it would have made the mesh worse: {}; --no-gate keeps it)",
            u.step,
            u.damage.join(", ")
        );
    }
    eprintln!(
        "wrote {}: triangles {} -> {}, boundary edges {} -> {}, non-manifold edges {} -> {}, inconsistent edges {} -> {}, degenerate {} -> {}, closed: {}, volume {} (--json for every step)",
        args.output.display(),
        b.triangles, a.triangles,
        b.boundary_edges, a.boundary_edges,
        b.non_manifold_edges, a.non_manifold_edges,
        b.inconsistent_edges, a.inconsistent_edges,
        b.degenerate_triangles, a.degenerate_triangles,
        a.closed, a.volume
    );
    Ok(())
}
