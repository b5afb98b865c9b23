//! `meshbool csg`: a CSG document evaluated, the root's result written, with a report per
//! node; `--cache DIR` keeps results between runs.

use std::path::PathBuf;

use anyhow::{bail, Result};
use meshbool::csg::{evaluate, Cache, CsgOptions, NodeProgress, Scene, Source};
use meshbool::ops::{self, BooleanOptions};

use super::{print_json, warn, OperandFlags};

/// What `--help` says after the options.
const AFTER_HELP: &str = "\
The document (docs/csg.md, schema docs/csg.schema.json):
  { \"root\": { \"op\": \"difference\", \"name\": \"housing\", \"children\": [
      { \"mesh\": \"parts/body.stl\", \"transform\": { \"rotate\": [\"z\", 30], \"translate\": [10, 0, 0] } },
      { \"primitive\": \"cylinder\", \"radius\": 3, \"height\": 30, \"base\": [0, 0, -15], \"role\": \"cutter\" } ] } }
Mesh paths are relative to the document. Nodes computed, taken from the cache and failed \
are listed with --json; a node that fails makes the command fail, naming it.

Examples:
  meshbool csg housing.json -o housing.stl
  meshbool csg housing.json -o housing.glb --cache .csg-cache --json";

/// Arguments of `csg`.
#[derive(clap::Args)]
#[command(after_help = AFTER_HELP)]
pub struct Args {
    /// The CSG document (JSON).
    scene: PathBuf,
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Keep every node's result in DIR (created if missing), one file per operation node
    /// named by its key: a later run takes unchanged nodes from there.
    #[arg(long, value_name = "DIR")]
    cache: Option<PathBuf>,
    /// With a .glb output: also one glTF node per named node of the document (its
    /// result where it lies in the root's, named as in the document, hidden with
    /// KHR_node_visibility; `extras.csg` holds its path, kind and role), after the root's
    /// node, so that a viewer or an exporter has every named part resolved.
    #[arg(long)]
    each: bool,
    /// Keep the results' non-manifold edges and vertices instead of splitting them.
    #[arg(long)]
    keep_nonmanifold: bool,
    /// Keep every seam point of the exact arrangements (no clean-up).
    #[arg(long)]
    keep_seam_points: bool,
    #[command(flatten)]
    snap: super::Snap,
    #[command(flatten)]
    flags: OperandFlags,
}

/// Reads the document, evaluates it, writes the root's result and reports.
pub fn run(args: &Args) -> Result<()> {
    let flags = &args.flags;
    let glb = meshbool::Format::for_path(&args.output) == Some(meshbool::Format::Glb);
    if args.each && !glb {
        return Err(crate::exit::usage(format!(
            "--each writes one glTF node per named node: the output must be a .glb file, not {}",
            args.output.display()
        )));
    }
    let scene = Scene::read(&args.scene)?;
    let cache = match &args.cache {
        Some(dir) => Cache::in_dir(dir)?,
        None => Cache::new(),
    };
    let spinner = super::Spinner::new("evaluating");
    let show = spinner.texts();
    let mut run = flags.run(&spinner);
    run.threads = flags.threads;
    let opts = CsgOptions {
        boolean: BooleanOptions {
            checks: flags.checks(),
            keep_nonmanifold: args.keep_nonmanifold,
            keep_seam_points: args.keep_seam_points,
            snap: args.snap.tolerance,
            run,
            ..BooleanOptions::default()
        },
        progress: Some(NodeProgress::new(move |node, done| {
            let how = match node.source {
                Source::Computed => "computed",
                Source::Memory | Source::Disk => "from the cache",
            };
            show(format!("{done} nodes done; {} {how}", node.path));
        })),
        named: args.each,
    };
    let out = evaluate(&scene, &cache, &opts)?;
    let report = out.report();
    for n in &out.nodes {
        let lines: Vec<String> = n.notes.iter().map(|l| format!("{}: {l}", n.path)).collect();
        warn(&lines);
    }
    let Some(mesh) = &out.mesh else {
        drop(spinner);
        if flags.json {
            print_json(&report)?;
        }
        let f = out.failed.expect("no result: a node failed");
        bail!("node {} failed: {}", f.path, f.error);
    };
    spinner.set_message("writing");
    if args.each {
        write_each(&args.output, &out.named)?;
    } else {
        ops::write(&args.output, mesh, None)?;
    }
    drop(spinner);
    if flags.json {
        print_json(&report)
    } else {
        let m = report.result.expect("a result");
        eprintln!(
            "wrote {} ({} triangles, volume {}, {} boundary edges; {} nodes computed, {} from the cache, {:.3} s)",
            args.output.display(),
            m.triangles,
            m.volume,
            m.boundary_edges,
            report.computed,
            report.cached,
            report.seconds
        );
        Ok(())
    }
}

/// Writes the root's result and every named node's as the nodes of one GLB (the root
/// shown, the others hidden).
fn write_each(path: &std::path::Path, named: &[meshbool::csg::NamedResult]) -> Result<()> {
    use meshbool::io::GlbPart;
    let parts: Vec<GlbPart> = named
        .iter()
        .enumerate()
        .map(|(k, n)| GlbPart {
            name: Some(n.name.clone()),
            mesh: &n.mesh,
            visible: k == 0,
            extras: Some(
                serde_json::json!({ "csg": { "path": n.path, "kind": n.kind, "role": n.role } }),
            ),
        })
        .collect();
    let mut bytes = Vec::new();
    meshbool::io::write_glb(&mut bytes, &parts)?;
    meshbool::io::write_bytes(path, &bytes)?;
    Ok(())
}
