//! `meshbool transform`: a mesh moved, turned, scaled, mirrored or mapped by a matrix,
//! the operations applied in the order they are given on the command line.

use std::path::PathBuf;

use anyhow::Result;
use clap::{Arg, ArgAction, ArgGroup, ArgMatches, Command};
use meshbool::ops;
use meshbool::Transform;

use super::print_json;

/// The operations, by argument id, each a [`Transform`] parsed from its value.
const STEPS: [&str; 4] = ["translate", "rotate", "scale", "matrix"];

/// What `--help` says after the options.
const AFTER_HELP: &str = "\
Operations apply in the order given: `--scale 2 --translate 1,0,0` scales, then moves; \
each may be given several times. Rotations are right-handed about an axis through the \
origin (90 about z takes x to y). A transform that mirrors (negative determinant) reverses \
every triangle, so solids keep facing outward.

--matrix is row-major for column vectors (p' = M p): the four rows one after another, the \
translation in the last column (numbers 4, 8, 12), the last row 0,0,0,1. \
`--matrix 2,0,0,1,0,2,0,2,0,0,2,3,0,0,0,1` is `--scale 2 --translate 1,2,3`.

Examples:
  meshbool transform part.stl -o placed.stl --rotate x,90 --translate 500000,7000000,120
  meshbool transform left.obj -o right.obj --scale -1,1,1
  meshbool transform a.ply -o b.ply --rotate 1,1,0,45 --json";

/// Arguments of `transform` (parsed by hand from clap's matches: the operations keep the
/// order of the command line).
pub struct Args {
    /// Input mesh.
    input: PathBuf,
    /// Output mesh file.
    output: PathBuf,
    /// The operations in command-line order.
    steps: Vec<Transform>,
    /// Print a JSON report.
    json: bool,
}

/// Numbers separated by commas (or, without commas, by white space), each finite.
pub(crate) fn numbers(s: &str) -> Result<Vec<f64>, String> {
    let tokens: Vec<&str> = if s.contains(',') {
        s.split(',').map(str::trim).collect()
    } else {
        s.split_whitespace().collect()
    };
    tokens
        .into_iter()
        .map(|t| match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(format!("`{t}` is not a finite number")),
            Err(_) => Err(format!("`{t}` is not a number")),
        })
        .collect()
}

/// Three numbers `X,Y,Z`.
pub(crate) fn point(s: &str) -> Result<[f64; 3], String> {
    match numbers(s)?[..] {
        [x, y, z] => Ok([x, y, z]),
        ref v => Err(format!("expected three numbers X,Y,Z, got {}", v.len())),
    }
}

/// `--translate X,Y,Z`.
fn translate(s: &str) -> Result<Transform, String> {
    point(s).map(Transform::translation)
}

/// `--scale S` or `--scale SX,SY,SZ`: factors not zero (negative ones mirror).
fn scale(s: &str) -> Result<Transform, String> {
    let f = match numbers(s)?[..] {
        [k] => [k; 3],
        [x, y, z] => [x, y, z],
        ref v => {
            return Err(format!(
                "expected one factor S or three SX,SY,SZ, got {} numbers",
                v.len()
            ))
        }
    };
    if f.contains(&0.0) {
        return Err("a scale factor of 0 would flatten the mesh".into());
    }
    Ok(Transform::scaling_xyz(f))
}

/// `--rotate AXIS,DEGREES`: AXIS `x`, `y`, `z` or a vector `AX,AY,AZ`.
fn rotate(s: &str) -> Result<Transform, String> {
    const USE: &str = "use AXIS,DEGREES with AXIS x, y or z, or AX,AY,AZ,DEGREES for any axis";
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let (axis, degrees) = match parts[..] {
        [name, deg] => {
            let axis = match name.to_ascii_lowercase().as_str() {
                "x" => [1.0, 0.0, 0.0],
                "y" => [0.0, 1.0, 0.0],
                "z" => [0.0, 0.0, 1.0],
                _ => return Err(format!("unknown axis `{name}`: {USE}")),
            };
            (axis, numbers(deg)?)
        }
        [_, _, _, deg] => (point(&parts[..3].join(","))?, numbers(deg)?),
        _ => {
            return Err(format!(
                "expected 2 or 4 values, got {}: {USE}",
                parts.len()
            ))
        }
    };
    let [degrees] = degrees[..] else {
        return Err(format!("missing angle: {USE}"));
    };
    Transform::rotation(axis, degrees).map_err(message)
}

/// `--matrix`: 16 numbers, row-major, last row `0,0,0,1`, not singular.
fn matrix(s: &str) -> Result<Transform, String> {
    let v = numbers(s)?;
    let m: [f64; 16] = v.as_slice().try_into().map_err(|_| {
        format!(
            "expected 16 numbers (4 rows of 4, row-major, translation in the last column), got {}",
            v.len()
        )
    })?;
    let t = Transform::from_row_major(m).map_err(message)?;
    if t.determinant() == 0.0 {
        return Err("the matrix is singular (determinant 0): it would flatten the mesh".into());
    }
    Ok(t)
}

/// The library's message without its "invalid parameter: " prefix.
fn message(e: meshbool::Error) -> String {
    match e {
        meshbool::Error::InvalidParameter(m) => m,
        e => e.to_string(),
    }
}

impl clap::FromArgMatches for Args {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut steps: Vec<(usize, Transform)> = Vec::new();
        for id in STEPS {
            if let (Some(values), Some(indices)) = (m.get_many::<Transform>(id), m.indices_of(id)) {
                steps.extend(indices.zip(values.copied()));
            }
        }
        steps.sort_by_key(|&(i, _)| i);
        let path = |id: &str| m.get_one::<PathBuf>(id).cloned().unwrap_or_default();
        Ok(Args {
            input: path("input"),
            output: path("output"),
            steps: steps.into_iter().map(|(_, t)| t).collect(),
            json: m.get_flag("json"),
        })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl clap::Args for Args {
    fn augment_args(cmd: Command) -> Command {
        let step = |id: &'static str, parser: fn(&str) -> Result<Transform, String>| {
            Arg::new(id)
                .long(id)
                .action(ArgAction::Append)
                .num_args(1)
                .allow_hyphen_values(true)
                .value_parser(parser)
        };
        cmd.arg(
            Arg::new("input")
                .required(true)
                .value_name("INPUT")
                .value_parser(clap::value_parser!(PathBuf))
                .help("Input mesh"),
        )
        .arg(
            Arg::new("output")
                .short('o')
                .long("output")
                .required(true)
                .value_name("OUTPUT")
                .value_parser(super::mesh_output)
                .help(super::MESH_OUTPUT),
        )
        .arg(
            step("translate", translate)
                .value_name("X,Y,Z")
                .help("Move by X,Y,Z"),
        )
        .arg(
            step("rotate", rotate)
                .value_name("AXIS,DEGREES")
                .help("Rotate by DEGREES about AXIS through the origin: x, y, z, or a vector AX,AY,AZ (--rotate 1,1,0,45)"),
        )
        .arg(
            step("scale", scale)
                .value_name("S|SX,SY,SZ")
                .help("Scale about the origin by S, or per axis (a negative factor mirrors)"),
        )
        .arg(
            step("matrix", matrix)
                .value_name("16 NUMBERS")
                .help("Apply an affine 4x4 matrix given row-major (translation in the last column; last row 0,0,0,1), comma-separated"),
        )
        .group(ArgGroup::new("operations").args(STEPS).multiple(true).required(true))
        .arg(
            Arg::new("json")
                .long("json")
                .action(ArgAction::SetTrue)
                .help("Print a JSON report on stdout"),
        )
        .after_help(AFTER_HELP)
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// Reads the input, applies the operations in order, writes it, prints the report.
pub fn run(args: &Args) -> Result<()> {
    let t = args
        .steps
        .iter()
        .fold(Transform::IDENTITY, |acc, step| acc.then(step));
    let (mesh, _) = ops::read(&args.input, None)?;
    let out = ops::transform(&mesh, &t)?;
    ops::write(&args.output, &out.mesh, None)?;
    let report = out.report();
    if args.json {
        return print_json(&report);
    }
    eprintln!(
        "wrote {}: {} triangles, determinant {}{}, volume {}",
        args.output.display(),
        report.result.triangles,
        report.determinant,
        if report.reversed {
            " (mirrored: triangles reversed)"
        } else {
            ""
        },
        report.result.volume
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parsers_accept_and_refuse() {
        assert_eq!(numbers("1, 2,3").unwrap(), [1.0, 2.0, 3.0]);
        assert_eq!(numbers("1 2 3").unwrap(), [1.0, 2.0, 3.0]);
        assert!(numbers("1,,3").is_err());
        assert!(numbers("1,inf,3").is_err());
        assert!(point("1,2").is_err());
        assert_eq!(rotate("Z,90").unwrap(), Transform::rotation_z(90.0));
        assert_eq!(rotate("0,0,2,90").unwrap(), Transform::rotation_z(90.0));
        assert!(rotate("q,45").unwrap_err().contains("unknown axis `q`"));
        assert!(rotate("0,0,0,45").unwrap_err().contains("not zero"));
        assert!(rotate("x").is_err() && rotate("x,").is_err());
        assert_eq!(scale("2").unwrap(), Transform::scaling(2.0));
        assert!(scale("1,0,1").is_err() && scale("1,2").is_err());
        assert!(matrix(&["1"; 15].join(",")).unwrap_err().contains("got 15"));
        assert!(matrix("1,0,0,0,0,1,0,0,0,0,0,0,0,0,0,1")
            .unwrap_err()
            .contains("singular"));
    }
}
