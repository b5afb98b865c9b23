//! `meshbool make`: a primitive (cube, sphere, cylinder, cone, plane) or a mining example
//! (terrain, pit) written to a file.

use std::path::PathBuf;

use anyhow::Result;
use meshbool::ops::{self, Shape};

use super::print_json;
use super::transform::point;

/// Arguments of `make`: the shape and its options.
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    shape: ShapeArgs,
}

/// The shapes.
#[derive(clap::Subcommand)]
enum ShapeArgs {
    /// An axis-aligned cube or box: --size about --center (default: edge 1 about the
    /// origin), or --min and --max. 12 triangles.
    Cube(CubeArgs),
    /// A UV sphere about --center, its axis along z: --segments meridians, --rings bands
    /// from pole to pole (vertices on the sphere: the inscribed polyhedron).
    Sphere(SphereArgs),
    /// A cylinder standing on --base (the bottom centre) along +z, the circles as regular
    /// polygons of --segments sides (first vertex on +x).
    Cylinder(CylinderArgs),
    /// A cone standing on --base along +z up to an apex, or a frustum with --top-radius.
    Cone(ConeArgs),
    /// A flat rectangle about --center, --width along x by --depth along y, in --nx by
    /// --ny cells of two triangles, facing +z (an open surface).
    Plane(PlaneArgs),
    /// A seeded, realistic terrain: an open height field over --size about --center, in
    /// --cells of two triangles, facing +z; hills, hollows, a regional slope and a little
    /// roughness, its heights spanning exactly --relief about the centre's z. The same
    /// --seed gives the same surface on every platform. With the defaults, crossed by the
    /// default pit along one closed curve.
    Terrain(TerrainArgs),
    /// An open-pit design shell: a benched bowl, elliptical in plan (--radius at the rim,
    /// rim at the centre's z, floor --depth below), --benches faces at a 2:1 batter with
    /// flat berms --berm wide between them and a flat floor, rings of --segments
    /// vertices; open (the rim its one boundary), facing up.
    Pit(PitArgs),
}

/// What every shape takes.
#[derive(clap::Args)]
struct Out {
    #[arg(short, long, help = super::MESH_OUTPUT, value_parser = super::mesh_output)]
    output: PathBuf,
    /// Print a JSON report on stdout.
    #[arg(long)]
    json: bool,
}

/// A positive finite number.
fn positive(s: &str) -> Result<f64, String> {
    match super::transform::numbers(s)?[..] {
        [v] if v > 0.0 => Ok(v),
        [v] => Err(format!("must be positive, got {v}")),
        _ => Err("expected one number".into()),
    }
}

/// Zero or a positive finite number.
fn non_negative(s: &str) -> Result<f64, String> {
    match super::transform::numbers(s)?[..] {
        [v] if v >= 0.0 => Ok(v),
        [v] => Err(format!("must be 0 or positive, got {v}")),
        _ => Err("expected one number".into()),
    }
}

/// One edge length `S` or three `SX,SY,SZ`, each positive.
fn sizes(s: &str) -> Result<[f64; 3], String> {
    let v = match super::transform::numbers(s)?[..] {
        [k] => [k; 3],
        [x, y, z] => [x, y, z],
        ref v => {
            return Err(format!(
                "expected one size S or three SX,SY,SZ, got {} numbers",
                v.len()
            ))
        }
    };
    if v.iter().any(|&k| k <= 0.0) {
        return Err(format!("sizes must be positive, got {s}"));
    }
    Ok(v)
}

/// One length `A` (for both) or two `A,B`, each positive.
fn lengths(s: &str) -> Result<[f64; 2], String> {
    let v = match super::transform::numbers(s)?[..] {
        [a] => [a; 2],
        [a, b] => [a, b],
        ref v => return Err(format!("expected one number or two A,B, got {}", v.len())),
    };
    if v.iter().any(|&k| k <= 0.0) {
        return Err(format!("must be positive, got {s}"));
    }
    Ok(v)
}

/// One count `N` (for both) or two `N,M`, each at least 1.
fn counts(s: &str) -> Result<[u32; 2], String> {
    let v = s
        .split(',')
        .map(|t| match t.trim().parse::<u32>() {
            Ok(0) => Err("counts must be at least 1, got 0".to_string()),
            Ok(n) => Ok(n),
            Err(_) => Err(format!("`{}` is not a whole number", t.trim())),
        })
        .collect::<Result<Vec<u32>, String>>()?;
    match v[..] {
        [n] => Ok([n; 2]),
        [n, m] => Ok([n, m]),
        _ => Err(format!("expected one count N or two N,M, got {}", v.len())),
    }
}

/// `--min X,Y,Z --max X,Y,Z`, or `--size` about `--center`.
#[derive(clap::Args)]
struct CubeArgs {
    #[command(flatten)]
    out: Out,
    /// Edge length S, or SX,SY,SZ for a box [default: 1].
    #[arg(long, value_name = "S|SX,SY,SZ", value_parser = sizes, allow_hyphen_values = true, conflicts_with_all = ["min", "max"])]
    size: Option<[f64; 3]>,
    /// Centre [default: 0,0,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = point, allow_hyphen_values = true, conflicts_with_all = ["min", "max"])]
    center: Option<[f64; 3]>,
    /// Smallest corner (with --max).
    #[arg(long, value_name = "X,Y,Z", value_parser = point, allow_hyphen_values = true, requires = "max")]
    min: Option<[f64; 3]>,
    /// Largest corner (with --min).
    #[arg(long, value_name = "X,Y,Z", value_parser = point, allow_hyphen_values = true, requires = "min")]
    max: Option<[f64; 3]>,
}

/// A sphere's options.
#[derive(clap::Args)]
struct SphereArgs {
    #[command(flatten)]
    out: Out,
    /// Centre.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,0", value_parser = point, allow_hyphen_values = true)]
    center: [f64; 3],
    /// Radius.
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    radius: f64,
    /// Meridians (at least 3).
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(3..))]
    segments: u32,
    /// Bands from pole to pole (at least 2).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..))]
    rings: u32,
}

/// A cylinder's options.
#[derive(clap::Args)]
struct CylinderArgs {
    #[command(flatten)]
    out: Out,
    /// Centre of the bottom disc.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,0", value_parser = point, allow_hyphen_values = true)]
    base: [f64; 3],
    /// Radius.
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    radius: f64,
    /// Height (along +z).
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    height: f64,
    /// Sides of the polygons (at least 3).
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(3..))]
    segments: u32,
}

/// A cone's options.
#[derive(clap::Args)]
struct ConeArgs {
    #[command(flatten)]
    out: Out,
    /// Centre of the bottom disc.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,0", value_parser = point, allow_hyphen_values = true)]
    base: [f64; 3],
    /// Bottom radius.
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    radius: f64,
    /// Top radius: 0 for an apex, positive for a frustum.
    #[arg(long, default_value = "0", value_parser = non_negative, allow_hyphen_values = true)]
    top_radius: f64,
    /// Height (along +z).
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    height: f64,
    /// Sides of the polygons (at least 3).
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(3..))]
    segments: u32,
}

/// A plane's options.
#[derive(clap::Args)]
struct PlaneArgs {
    #[command(flatten)]
    out: Out,
    /// Centre.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,0", value_parser = point, allow_hyphen_values = true)]
    center: [f64; 3],
    /// Extent along x.
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    width: f64,
    /// Extent along y.
    #[arg(long, default_value = "1", value_parser = positive, allow_hyphen_values = true)]
    depth: f64,
    /// Cells along x (at least 1).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    nx: u32,
    /// Cells along y (at least 1).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    ny: u32,
}

/// A terrain's options.
#[derive(clap::Args)]
struct TerrainArgs {
    #[command(flatten)]
    out: Out,
    /// Centre: of the plan rectangle, and the middle of the heights' range.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,0", value_parser = point, allow_hyphen_values = true)]
    center: [f64; 3],
    /// Extent along x and y (one number: a square).
    #[arg(long, value_name = "W[,D]", default_value = "1000", value_parser = lengths, allow_hyphen_values = true)]
    size: [f64; 2],
    /// Cells along x and y, each two triangles (one number: both).
    #[arg(long, value_name = "N[,M]", default_value = "100", value_parser = counts)]
    cells: [u32; 2],
    /// Highest less lowest height (0: flat).
    #[arg(long, default_value = "40", value_parser = non_negative, allow_hyphen_values = true)]
    relief: f64,
    /// Seed of the relief (any whole number from 0 to 2^64 − 1).
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

/// A pit's options.
#[derive(clap::Args)]
struct PitArgs {
    #[command(flatten)]
    out: Out,
    /// Centre of the rim, at the rim's height.
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,60", value_parser = point, allow_hyphen_values = true)]
    center: [f64; 3],
    /// Semi-axes of the rim along x and y (one number: a circle).
    #[arg(long, value_name = "R[,R2]", default_value = "220,160", value_parser = lengths, allow_hyphen_values = true)]
    radius: [f64; 2],
    /// Rim less floor height.
    #[arg(long, default_value = "140", value_parser = positive, allow_hyphen_values = true)]
    depth: f64,
    /// Faces from rim to floor (at least 1).
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..))]
    benches: u32,
    /// Width of the flat berms between faces (0: none).
    #[arg(long, default_value = "8", value_parser = non_negative, allow_hyphen_values = true)]
    berm: f64,
    /// Vertices of each ring (at least 3).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(3..))]
    segments: u32,
}

impl ShapeArgs {
    /// The shape asked for and where to write it.
    fn shape(&self) -> (Shape, &Out) {
        match self {
            ShapeArgs::Cube(a) => {
                let (min, max) = match (a.min, a.max) {
                    (Some(min), Some(max)) => (min, max),
                    _ => {
                        let (c, s) = (a.center.unwrap_or([0.0; 3]), a.size.unwrap_or([1.0; 3]));
                        (
                            std::array::from_fn(|k| c[k] - s[k] / 2.0),
                            std::array::from_fn(|k| c[k] + s[k] / 2.0),
                        )
                    }
                };
                (Shape::Cube { min, max }, &a.out)
            }
            ShapeArgs::Sphere(a) => (
                Shape::Sphere {
                    center: a.center,
                    radius: a.radius,
                    segments: a.segments,
                    rings: a.rings,
                },
                &a.out,
            ),
            ShapeArgs::Cylinder(a) => (
                Shape::Cylinder {
                    base: a.base,
                    radius: a.radius,
                    height: a.height,
                    segments: a.segments,
                },
                &a.out,
            ),
            ShapeArgs::Cone(a) => (
                Shape::Cone {
                    base: a.base,
                    radius: a.radius,
                    top_radius: a.top_radius,
                    height: a.height,
                    segments: a.segments,
                },
                &a.out,
            ),
            ShapeArgs::Plane(a) => (
                Shape::Plane {
                    center: a.center,
                    width: a.width,
                    depth: a.depth,
                    nx: a.nx,
                    ny: a.ny,
                },
                &a.out,
            ),
            ShapeArgs::Terrain(a) => (
                Shape::Terrain {
                    center: a.center,
                    size: a.size,
                    cells: a.cells,
                    relief: a.relief,
                    seed: a.seed,
                },
                &a.out,
            ),
            ShapeArgs::Pit(a) => (
                Shape::Pit {
                    center: a.center,
                    radius: a.radius,
                    depth: a.depth,
                    benches: a.benches,
                    berm: a.berm,
                    segments: a.segments,
                },
                &a.out,
            ),
        }
    }
}

/// Generates the shape, writes it, prints the report. Parameters the library refuses
/// (a box's min not below its max, a pit's benches wider than its radius, a shape too
/// fine for `f64`) are usage errors (exit 2).
pub fn run(args: &Args) -> Result<()> {
    let (shape, out) = args.shape.shape();
    // The library's `InvalidParameter` maps to exit 2 in `main` (exit.rs), which also
    // removes directories made for the output.
    let made = ops::make(&shape)?;
    ops::write(&out.output, &made.mesh, None)?;
    let report = made.report();
    if out.json {
        return print_json(&report);
    }
    let r = &report.result;
    eprintln!(
        "wrote {}: {}, {} triangles, {} vertices, {}{}",
        out.output.display(),
        report.shape,
        r.triangles,
        r.vertices,
        if r.closed { "closed" } else { "open" },
        if r.closed {
            format!(", volume {}", r.volume)
        } else {
            String::new()
        }
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::Args;
    use clap::FromArgMatches;
    use meshbool::ops::Shape;

    /// `make terrain` and `make pit` without options are the library's example shapes
    /// (`Shape::TERRAIN`, `Shape::PIT`), which the Python and JavaScript packages share.
    #[test]
    fn defaults_are_the_library_examples() {
        let cmd = clap::Command::new("make").no_binary_name(true);
        let cmd = <Args as clap::Args>::augment_args(cmd);
        for (name, expected) in [("terrain", Shape::TERRAIN), ("pit", Shape::PIT)] {
            let matches = cmd.clone().get_matches_from([name, "-o", "x.ply"]);
            let args = Args::from_arg_matches(&matches).unwrap();
            assert_eq!(args.shape.shape().0, expected, "{name}");
        }
    }
}
