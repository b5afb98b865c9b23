//! Times the stages of a boolean of two mesh files, in process (a profiling aid):
//! `cargo run --release -p meshbool --example stages -- A B [union|intersection|difference] [reps]`.
//! Prints, per repetition, the time from each stage's start to the next one's and the
//! whole call, with the inputs read and checked beforehand (the self-intersection check
//! only with the environment variable `CHECKED` set). Over 10 repetitions (small inputs),
//! one line of mean times per stage in microseconds instead. Calls run on a pool of
//! `POOL` threads (environment; default: one per core).

use std::sync::{Arc, Mutex};
use std::time::Instant;

use meshbool::ops::{boolean, BooleanOptions, Checks, Operand, Progress};
use meshbool::Op;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 2 {
        return Err("usage: stages A B [union|intersection|difference] [reps]".into());
    }
    let op = match args.get(2).map(String::as_str).unwrap_or("difference") {
        "union" => Op::Union,
        "intersection" => Op::Intersection,
        _ => Op::Difference,
    };
    let reps: usize = args.get(3).map_or(Ok(3), |r| r.parse())?;
    let checks = Checks {
        self_intersections: std::env::var_os("CHECKED").is_some(),
        ..Checks::default()
    };
    let start = Instant::now();
    let a = Operand::read(&args[0], &checks)?;
    let b = Operand::read(&args[1], &checks)?;
    println!(
        "read and check ({}self-intersections): {:.1} ms",
        if checks.self_intersections { "" } else { "no " },
        start.elapsed().as_secs_f64() * 1e3
    );
    // With many repetitions (small inputs), the mean per stage in microseconds instead.
    let mut sums: Vec<(String, f64)> = Vec::new();
    let mut total = 0.0;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(
            std::env::var("POOL")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(0),
        )
        .build()?;
    for _ in 0..reps {
        let marks: Arc<Mutex<Vec<(String, Instant)>>> = Arc::default();
        let m = marks.clone();
        let mut opts = BooleanOptions::default();
        opts.run.progress = Some(Progress::new(move |s| {
            m.lock().unwrap().push((format!("{s:?}"), Instant::now()))
        }));
        let start = Instant::now();
        let out = pool.install(|| boolean(&a, &b, op, &opts))?;
        let end = Instant::now();
        let marks = marks.lock().unwrap();
        if reps > 10 {
            for (k, (name, t)) in marks.iter().enumerate() {
                let next = marks.get(k + 1).map_or(end, |x| x.1);
                if sums.len() <= k {
                    sums.push((name.clone(), 0.0));
                }
                sums[k].1 += (next - *t).as_secs_f64();
            }
            total += (end - start).as_secs_f64();
            continue;
        }
        let mut line = String::new();
        for (k, (name, t)) in marks.iter().enumerate() {
            let next = marks.get(k + 1).map_or(end, |x| x.1);
            line += &format!("{name} {:.1} ms  ", (next - *t).as_secs_f64() * 1e3);
        }
        println!(
            "{line}| total {:.1} ms, {} triangles",
            (end - start).as_secs_f64() * 1e3,
            out.mesh.triangles().len()
        );
    }
    if reps > 10 {
        let mut line = String::new();
        for (name, s) in &sums {
            line += &format!("{name} {:.1} µs  ", s / reps as f64 * 1e6);
        }
        println!("{line}| mean total {:.1} µs", total / reps as f64 * 1e6);
    }
    Ok(())
}
