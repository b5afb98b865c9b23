//! Times the stages of a boolean of two mesh files, in process (a profiling aid):
//! `cargo run --release -p meshbool --example stages -- A B [union|intersection|difference] [reps]`.
//! First, per file, how long reading its bytes, parsing and welding them, counting its
//! edges and finding inside-out parts take; then, per repetition, the time from each
//! stage's start to the next one's and the whole call, with the inputs read and checked
//! beforehand (the self-intersection check only with the environment variable `CHECKED`
//! set). Over 10 repetitions (small inputs), one line of mean times per stage in
//! microseconds instead. Everything runs on a pool of `POOL` threads (environment;
//! default: one per core).

use std::sync::{Arc, Mutex};
use std::time::Instant;

use meshbool::io::{detect_format, read_bytes};
use meshbool::ops::{boolean, BooleanOptions, Checks, Operand, Progress};
use meshbool::Op;

/// The allocator of the command line and the Python package, so that the times are theirs.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// How long the steps of reading and checking the file at `path` take, in one line.
fn read_steps(path: &str) -> Result<String, Box<dyn std::error::Error + Send + Sync>> {
    let t = Instant::now();
    let bytes = std::fs::read(path)?;
    let mut line = format!("{path}: bytes {:.1}", ms(t));
    let t = Instant::now();
    let mesh = read_bytes(&bytes, detect_format(&bytes, None).ok_or("unknown format")?)?;
    line += &format!(", parse and weld {:.1}", ms(t));
    let t = Instant::now();
    meshbool::edges::EdgeCounts::of(&mesh);
    line += &format!(", edge counts {:.1}", ms(t));
    let t = Instant::now();
    meshbool::repair::inside_out(&mesh);
    Ok(line + &format!(", inside-out parts {:.1} ms", ms(t)))
}

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
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
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(
            std::env::var("POOL")
                .ok()
                .and_then(|v| v.parse().ok())
                .unwrap_or(0),
        )
        .build()?;
    for path in &args[..2] {
        println!("{}", pool.install(|| read_steps(path))?);
    }
    let start = Instant::now();
    let (a, b) = pool.install(|| Operand::read_pair(&args[0], &args[1], &checks))?;
    println!(
        "read and check both ({}self-intersections): {:.1} ms",
        if checks.self_intersections { "" } else { "no " },
        ms(start)
    );
    // With many repetitions (small inputs), the mean per stage in microseconds instead.
    let mut sums: Vec<(String, f64)> = Vec::new();
    let mut total = 0.0;
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
