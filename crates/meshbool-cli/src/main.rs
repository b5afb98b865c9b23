//! `meshbool`: the command-line client of the meshbool library. Parses arguments, calls the
//! library's front door (`meshbool::ops`, one function per command) and prints or writes
//! what it returns; errors become messages with exit codes by one rule ([`exit`]: 1 an
//! input or the work failed, 2 usage, 130 Ctrl-C), and every output is written by one
//! rule ([`output`]).

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

mod commands;
mod exit;
mod output;

use commands::{
    boolean, classify, close, convert, csg, curves, cutfill, info, make, orient, pick, repair,
    resolve, split, transform,
};

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
    Info(info::Args),
    /// Convert a mesh file to another format (chosen by the output's extension or --to).
    Convert(convert::Args),
    /// A ∪ B (∪ C ...): the union of two meshes or more.
    Union(boolean::ManyArgs),
    /// A ∩ B (∩ C ...): the intersection of two meshes or more.
    #[command(alias = "intersect")]
    Intersection(boolean::ManyArgs),
    /// A − B (− C ...): A less every other input (those united first), in one call; B − A
    /// with --reverse (two inputs).
    #[command(alias = "subtract")]
    Difference(boolean::DifferenceArgs),
    /// Split both meshes along their intersection into groups (a_in_b, a_out_b, b_in_a,
    /// b_out_a, and coplanar a_on_b_same/opposite, b_on_a_same/opposite) and their
    /// connected components; writes one file per group and per component plus manifest.json.
    Split(split::Args),
    /// Merge pieces of a split into one welded mesh: `--keep a_out_b --keep b_in_a:flip
    /// --keep a_in_b#2` (group, optional #component, optional :flip), or the pieces a
    /// boolean keeps: `--op union|intersection|difference|reverse-difference`.
    Pick(pick::Args),
    /// Close open meshes into solids. Modes: `cap` (triangulate every boundary loop,
    /// non-planar loops too), `stitch` (join pairs of loops with bands of triangles),
    /// `curtain` (vertical walls from the boundary down to `floor = min z − floor-offset`,
    /// floor capped; orient the surface up first), `stitch+curtain` (stitch what pairs up,
    /// curtain the rest).
    Close(close::Args),
    /// Repair pipeline. Steps, in this order, each only when asked for: weld within a
    /// distance, duplicate removal, boundary weld, T-junctions, degenerate/sliver removal,
    /// orientation (on by default: consistent, majority facing), terrain folds, closing,
    /// capping small gaps left.
    /// Every removed triangle is counted in the report. `--config FILE.json` gives the
    /// whole configuration (the library's `RepairConfig`); flags override it.
    Repair(repair::Args),
    /// The solid a self-overlapping mesh encloses, as a clean closed mesh: closed parts
    /// that cross are united, parts nested in others dropped (or kept reversed, as the
    /// fill rule says); a part that crosses itself is cut along its own seam.
    Resolve(resolve::Args),
    /// Make triangle orientation consistent across every manifold edge, component by
    /// component, and face each component as asked (default: as most triangles already did).
    Orient(orient::Args),
    /// Move, rotate (degrees), scale, mirror or map by a 4x4 matrix: `--translate X,Y,Z`,
    /// `--rotate AXIS,DEGREES` (AXIS x, y, z or AX,AY,AZ), `--scale S|SX,SY,SZ`, `--matrix`
    /// (16 numbers, row-major), applied in the order given. Mirroring reverses the
    /// triangles.
    Transform(transform::Args),
    /// Make a primitive or a mining example: `make
    /// cube|sphere|cylinder|cone|plane|terrain|pit -o OUT [options]`
    /// (closed ones outward-facing, exactly welded).
    Make(make::Args),
    /// Compute the exact intersection curves of two meshes (of one mesh: where it crosses
    /// itself) and write them as polylines (.obj `l` elements, .dxf 3D POLYLINEs, or .json).
    Curves(curves::Args),
    /// Where points lie against a mesh: inside, outside, or exactly on its surface (exact),
    /// with the winding number at each; points from a file (`x y z` per line, CSV or JSON)
    /// or standard input (`-`).
    Classify(classify::Args),
    /// Cut and fill between two surfaces: the volume where TOPO is above DESIGN (cut) and
    /// below it (fill) over the plan area both cover, exactly from the booleans of the
    /// solids under each; both are faced up first. `-o` writes the lines where they meet.
    Cutfill(cutfill::Args),
    /// Evaluate a CSG document (JSON: a tree of unions, intersections and differences
    /// over mesh files and primitives, each node with its transform; cutters subtracted
    /// in differences) and write the root's result; `--cache DIR` keeps every node's
    /// result so that a later run computes only what changed (docs/csg.md).
    Csg(csg::Args),
}

fn main() -> ExitCode {
    let matches = Cli::command().get_matches();
    let cli =
        Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.format(&mut Cli::command()).exit());
    commands::cancel_on_ctrl_c();
    let result = output::prepare(&matches).and_then(|prepared| {
        let result = run(cli.command);
        if result.is_err() {
            prepared.undo();
        }
        result
    });
    let Err(e) = result else {
        return ExitCode::SUCCESS;
    };
    let code = exit::code(&e);
    match code {
        // A reader that stopped early (`meshbool info F | head -3`): nothing to report.
        0 => {}
        // Ctrl-C: the library stopped at a stage boundary and nothing was written.
        exit::CANCELLED => eprintln!("meshbool: cancelled (Ctrl-C); nothing was written"),
        _ => {
            // The library says how to proceed in its own terms; name the flag.
            let hint = match e.downcast_ref::<meshbool::Error>() {
                Some(meshbool::Error::Operand { .. }) => " (--force)",
                _ => "",
            };
            eprintln!("meshbool: error: {e:#}{hint}");
        }
    }
    ExitCode::from(code)
}

/// Runs the command.
fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Info(args) => info::run(&args),
        Command::Convert(args) => convert::run(&args),
        Command::Union(args) => args.run(meshbool::Op::Union),
        Command::Intersection(args) => args.run(meshbool::Op::Intersection),
        Command::Difference(args) => args.run(),
        Command::Split(args) => split::run(&args),
        Command::Pick(args) => pick::run(&args),
        Command::Close(args) => close::run(&args),
        Command::Repair(args) => repair::run(&args),
        Command::Resolve(args) => resolve::run(&args),
        Command::Orient(args) => orient::run(&args),
        Command::Transform(args) => transform::run(&args),
        Command::Make(args) => make::run(&args),
        Command::Curves(args) => curves::run(&args),
        Command::Classify(args) => classify::run(&args),
        Command::Cutfill(args) => cutfill::run(&args),
        Command::Csg(args) => csg::run(&args),
    }
}

#[cfg(test)]
mod tests {
    /// Every command's definition is consistent (arguments named in conflicts and
    /// requirements exist, no two share a flag): clap checks this only where debug
    /// assertions are on, as in the tests' `checked` profile, and otherwise ignores what
    /// it cannot resolve (a conflict with a misnamed argument was once silently not
    /// enforced).
    #[test]
    fn every_command_definition_is_consistent() {
        use clap::CommandFactory;
        super::Cli::command().debug_assert();
    }
}
