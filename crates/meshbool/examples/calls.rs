//! Times many booleans of two mesh files from the calling thread, as a program or the
//! Python package makes them (a profiling aid for small inputs, where how a call reaches
//! its threads weighs most):
//! `cargo run --release -p meshbool --example calls -- A B [union|intersection|difference] [calls]`.
//! The inputs are read and checked once (as operands); then three rounds of `calls`
//! booleans, each printed as the mean time of a call in microseconds. With the
//! environment variable `MESHES` set, the meshes are passed instead of the operands (the
//! door's checks run in every call).

use std::time::Instant;

use meshbool::ops::{boolean, BooleanOptions, Checks, Operand};
use meshbool::Op;

/// The allocator of the command line and the Python package, so that the times are theirs.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 2 {
        return Err("usage: calls A B [union|intersection|difference] [calls]".into());
    }
    let op = match args.get(2).map(String::as_str).unwrap_or("union") {
        "intersection" => Op::Intersection,
        "difference" => Op::Difference,
        _ => Op::Union,
    };
    let calls: usize = args.get(3).map_or(Ok(10_000), |r| r.parse())?;
    let checks = Checks {
        self_intersections: false,
        ..Checks::default()
    };
    let (a, b) = Operand::read_pair(&args[0], &args[1], &checks)?;
    let opts = BooleanOptions {
        checks,
        ..BooleanOptions::default()
    };
    let meshes = std::env::var_os("MESHES").is_some();
    for _ in 0..3 {
        let start = Instant::now();
        let mut triangles = 0;
        for _ in 0..calls {
            let out = match meshes {
                true => boolean(a.mesh(), b.mesh(), op, &opts)?,
                false => boolean(&a, &b, op, &opts)?,
            };
            triangles = out.mesh.triangles().len();
        }
        let each = start.elapsed().as_secs_f64() / calls as f64 * 1e6;
        println!("{each:.1} µs a call, {triangles} triangles");
    }
    Ok(())
}
