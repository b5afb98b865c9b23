//! Times every stage of a file-to-file boolean on a pool of a given number of threads (a
//! profiling aid for scaling with cores):
//! `cargo run --release -p meshbool --example scaling -- A B OUT [threads] [reps]`.
//! Prints one line per repetition: reading the files' bytes, parsing and welding them,
//! the main operand checks (edge counts, inside-out components) and an exact weld of
//! the welded mesh, reading and checking both files together, each stage of the boolean, measuring the result (its report) and
//! writing it, in milliseconds. Run it under `taskset` to pin the process to as many cores.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use meshbool::io::{detect_format, read_bytes};
use meshbool::ops::{boolean, write, BooleanOptions, Checks, Operand, Progress};
use meshbool::Op;

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

fn main() -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 3 {
        return Err("usage: scaling A B OUT [threads] [reps]".into());
    }
    let threads: usize = args.get(3).map_or(Ok(0), |r| r.parse())?;
    let reps: usize = args.get(4).map_or(Ok(2), |r| r.parse())?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let checks = Checks {
        self_intersections: false,
        ..Checks::default()
    };
    for _ in 0..reps {
        pool.install(|| -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
            let mut line = format!("threads {:2}:", rayon::current_num_threads());
            let t = Instant::now();
            let bytes = [std::fs::read(&args[0])?, std::fs::read(&args[1])?];
            line += &format!(" bytes {:.1}", ms(t));
            for (name, b) in ["A", "B"].iter().zip(&bytes) {
                let t = Instant::now();
                let format = detect_format(b, None).ok_or("unknown format")?;
                let m = read_bytes(b, format)?;
                line += &format!(" parse{name} {:.1}", ms(t));
                let t = Instant::now();
                let _ = meshbool::edges::EdgeCounts::of(&m);
                line += &format!(" edges{name} {:.1}", ms(t));
                let t = Instant::now();
                let _ = meshbool::repair::inside_out(&m);
                line += &format!(" inside_out{name} {:.1}", ms(t));
                let t = Instant::now();
                let _ = meshbool::weld_exact(&m);
                line += &format!(" weld{name} {:.1}", ms(t));
            }
            drop(bytes);
            let t = Instant::now();
            let (a, b) = Operand::read_pair(&args[0], &args[1], &checks)?;
            line += &format!(" | read_pair {:.1} |", ms(t));
            let marks: Arc<Mutex<Vec<(String, Instant)>>> = Arc::default();
            let m = marks.clone();
            let mut opts = BooleanOptions::default();
            opts.run.progress = Some(Progress::new(move |s| {
                m.lock().unwrap().push((format!("{s:?}"), Instant::now()))
            }));
            let start = Instant::now();
            let out = boolean(&a, &b, Op::Union, &opts)?;
            let end = Instant::now();
            let marks = marks.lock().unwrap();
            for (k, (name, t)) in marks.iter().enumerate() {
                let next = marks.get(k + 1).map_or(end, |x| x.1);
                line += &format!(" {name} {:.1}", (next - *t).as_secs_f64() * 1e3);
            }
            line += &format!(" | boolean {:.1} |", (end - start).as_secs_f64() * 1e3);
            let t = Instant::now();
            let report = out.report();
            line += &format!(" report {:.1}", ms(t));
            let t = Instant::now();
            write(&args[2], &out.mesh, None)?;
            line += &format!(" write {:.1}", ms(t));
            println!("{line} ({} triangles)", report.result.triangles);
            Ok(())
        })?;
    }
    Ok(())
}
