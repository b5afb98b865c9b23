//! What snapping at a tolerance adds to a large boolean (issue 21's target: under 15 %
//! over the union of the 2M-triangle spheres of the benches), measured so that the
//! machine's drift hits both sides alike:
//! `cargo run --release -p meshbool --example snap_cost -- [reps] [tolerance]`.
//!
//! Each repetition times the union alone, then the union followed by
//! [`snap_result`] (the snap timed on its own inside it), in one process, alternating; the
//! results are dropped outside the timings. Prints the fastest and the median of each and
//! the snap's share of the union both ways. Runs with mimalloc, the allocator of the
//! command line and the Python package.

use std::time::Instant;

use meshbool::boolean::{boolean, snap_result, Op};
use meshbool::shapes::{rigid_motion, uv_sphere};

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The fastest and the median of `v`.
fn fastest_median(v: &[f64]) -> (f64, f64) {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    (s[0], s[s.len() / 2])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let reps: usize = args.next().map_or(Ok(10), |a| a.parse())?;
    let tolerance: f64 = args.next().map_or(Ok(1e-4), |a| a.parse())?;
    if reps == 0 {
        return Err("reps must be at least 1".into());
    }
    // The benches' 2M pair: UV spheres of radius 1, 2,000,000 triangles each, the second
    // rotated 0.1 rad about z and shifted 0.5 along x.
    let a = uv_sphere([0.0; 3], 1.0, 2000, 501);
    let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    let ms = |t: Instant| t.elapsed().as_secs_f64() * 1e3;
    let (mut union, mut both, mut snap, mut before) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut report = None;
    for _ in 0..reps {
        let t = Instant::now();
        let r = boolean(&a, &b, Op::Union, &Default::default());
        union.push(ms(t));
        drop(r);
        let t = Instant::now();
        let mut r = boolean(&a, &b, Op::Union, &Default::default());
        before.push(ms(t));
        let s = Instant::now();
        let rep = snap_result(&mut r, tolerance)?;
        snap.push(ms(s));
        both.push(ms(t));
        drop(r);
        report = Some(rep);
    }
    let (u, b, s, ub) = (
        fastest_median(&union),
        fastest_median(&both),
        fastest_median(&snap),
        fastest_median(&before),
    );
    println!("{reps} repetitions, tolerance {tolerance:e}; fastest / median in ms:");
    println!("union         {:8.1} / {:8.1}", u.0, u.1);
    println!("union + snap  {:8.1} / {:8.1}", b.0, b.1);
    println!("  its union   {:8.1} / {:8.1}", ub.0, ub.1);
    println!("  its snap    {:8.1} / {:8.1}", s.0, s.1);
    println!(
        "snap / union: {:.1} % / {:.1} %; (union + snap) / union - 1: {:.1} % / {:.1} %",
        100.0 * s.0 / u.0,
        100.0 * s.1 / u.1,
        100.0 * (b.0 / u.0 - 1.0),
        100.0 * (b.1 / u.1 - 1.0)
    );
    if let Some(r) = report {
        println!(
            "snap: {} bad found, {} collapsed, {} flipped, {} left",
            r.found, r.collapsed, r.flipped, r.left
        );
    }
    Ok(())
}
