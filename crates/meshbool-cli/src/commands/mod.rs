//! One module per command: its arguments (a clap struct) and `run`, which calls the
//! library's front door and prints what it returns. What every command shares is here:
//! the boolean operands' flags, the progress spinner and printing.

use anyhow::Result;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::OnceLock;

use meshbool::ops::{Cancel, Checks, Progress, RunOptions};

/// What `--help` says of every output file: the rule of [`crate::output`].
macro_rules! output_rule {
    () => {
        "Missing directories are created; an existing file is replaced whole (written beside \
         it, then renamed over it)"
    };
}

pub mod boolean;
pub mod classify;
pub mod close;
pub mod convert;
pub mod csg;
pub mod curves;
pub mod cutfill;
pub mod info;
pub mod make;
pub mod orient;
pub mod pick;
pub mod repair;
pub mod resolve;
pub mod split;
pub mod transform;

/// Flags shared by the commands that take two operands (booleans, split).
#[derive(clap::Args, Clone)]
pub struct OperandFlags {
    /// Proceed even when an input has problems the door cannot fix: non-manifold edges,
    /// orientation that cannot be made consistent, self-intersections that cannot be
    /// resolved (the result takes the input as given; the JSON report lists what was
    /// assumed).
    #[arg(long)]
    pub force: bool,
    /// Print a JSON report on stdout.
    #[arg(long)]
    pub json: bool,
    /// Skip the check for self-intersecting inputs (it costs about as much as the boolean
    /// on large meshes); only for inputs known to be clean.
    #[arg(long)]
    pub no_self_check: bool,
    /// Refuse an input whose closed parts cross or nest one another instead of resolving
    /// it into the solid they enclose (their union; see `meshbool resolve`).
    #[arg(long)]
    pub no_resolve: bool,
    /// Refuse an input whose triangles are not consistently oriented instead of orienting
    /// it at the door (each component facing as most of its triangles do).
    #[arg(long)]
    pub no_orient: bool,
    /// Take positions as exactly as written: do not merge boundary vertices that differ
    /// by rounding (within 4 units in the last place of the largest coordinate, in the
    /// precision the file stores) into one vertex.
    #[arg(long)]
    pub exact_positions: bool,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long, value_parser = thread_count)]
    pub threads: Option<usize>,
    /// Print on standard error how long each stage took (reading, each stage of the
    /// boolean, writing while the result is measured), in seconds; for the commands that
    /// show progress (booleans, split).
    #[arg(long)]
    pub timings: bool,
}

/// The command's cancellation flag: the first Ctrl-C sets it (the library stops at the
/// next stage and writes nothing); a third ends the process at once.
pub fn cancel() -> Cancel {
    static CANCEL: OnceLock<Cancel> = OnceLock::new();
    CANCEL.get_or_init(Cancel::new).clone()
}

/// Makes Ctrl-C cancel the command ([`cancel`]) instead of killing it mid-write. Where
/// no handler can be installed, Ctrl-C keeps its default (the output files are written
/// under temporary names and renamed when complete, so none is left half written).
pub fn cancel_on_ctrl_c() {
    let flag = cancel();
    let presses = AtomicU32::new(0);
    let _ = ctrlc::set_handler(move || {
        if presses.fetch_add(1, Ordering::Relaxed) >= 2 {
            std::process::exit(130);
        }
        flag.cancel();
    });
}

impl OperandFlags {
    /// The checks the flags ask for.
    pub fn checks(&self) -> Checks {
        Checks {
            self_intersections: !self.no_self_check,
            resolve: !self.no_resolve,
            orient: !self.no_orient,
            force: self.force,
            rounding_noise: !self.exact_positions,
            ..Checks::default()
        }
    }

    /// Progress shown on `spinner` (the command runs in its thread pool as a whole),
    /// cancelled by Ctrl-C ([`cancel`]).
    pub fn run(&self, spinner: &Spinner) -> RunOptions {
        let marker = spinner.0.clone();
        RunOptions {
            threads: None,
            progress: Some(Progress::new(move |s| marker.set_message(s.describe()))),
            cancel: Some(cancel()),
        }
    }

    /// The spinner of a command taking these flags, first showing what reading does; it
    /// prints the stages' timings when dropped if `--timings` asks for them.
    pub fn spinner(&self) -> Spinner {
        Spinner::with_timings(self.reading(), self.timings)
    }

    /// What reading the inputs does, for the spinner.
    pub fn reading(&self) -> &'static str {
        if self.no_self_check {
            "reading and checking the inputs"
        } else {
            "reading the inputs, checking for self-intersections"
        }
    }
}

/// A spinner with the elapsed time and the current stage on standard error; drawn only
/// when standard error is a terminal (never into pipes, files or tests). Cleared when
/// dropped, so an error message never lands after a stale spinner line; with timings
/// asked for, it then prints how long each stage it showed lasted.
pub struct Spinner(Marker);

/// What a spinner shows, shared with progress callbacks: the bar, and the stages with the
/// time each began when timings are kept.
#[derive(Clone)]
struct Marker {
    bar: indicatif::ProgressBar,
    stages: Option<std::sync::Arc<std::sync::Mutex<Stages>>>,
}

/// Each stage a spinner showed, with the time it began.
type Stages = Vec<(&'static str, std::time::Instant)>;

impl Marker {
    fn set_message(&self, msg: &'static str) {
        if let Some(stages) = &self.stages {
            if let Ok(mut s) = stages.lock() {
                s.push((msg, std::time::Instant::now()));
            }
        }
        self.bar.set_message(msg);
    }
}

impl Spinner {
    /// A spinner showing `msg`.
    pub fn new(msg: &'static str) -> Self {
        Spinner::with_timings(msg, false)
    }

    /// A spinner showing `msg`, keeping the stages' timings when `timings` is set.
    pub fn with_timings(msg: &'static str, timings: bool) -> Self {
        let bar = indicatif::ProgressBar::new_spinner();
        if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} [{elapsed}] {msg}") {
            bar.set_style(style);
        }
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        let marker = Marker {
            bar,
            stages: timings.then(Default::default),
        };
        marker.set_message(msg);
        Spinner(marker)
    }

    /// Shows `msg`.
    pub fn set_message(&self, msg: &'static str) {
        self.0.set_message(msg);
    }

    /// A handle that shows lines made as the work goes (not kept as stages for
    /// `--timings`), from any thread.
    pub fn texts(&self) -> impl Fn(String) + Send + Sync + 'static {
        let bar = self.0.bar.clone();
        move |text| bar.set_message(text)
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.0.bar.finish_and_clear();
        let Some(stages) = &self.0.stages else { return };
        let Ok(stages) = stages.lock() else { return };
        let end = std::time::Instant::now();
        for (k, (msg, start)) in stages.iter().enumerate() {
            let next = stages.get(k + 1).map_or(end, |s| s.1);
            eprintln!("{:9.3} s  {msg}", (next - *start).as_secs_f64());
        }
        if let Some((_, first)) = stages.first() {
            eprintln!("{:9.3} s  in all", (end - *first).as_secs_f64());
        }
    }
}

/// `--help` of a mesh output.
pub const MESH_OUTPUT: &str = concat!(
    "Output mesh file (its extension names the format). ",
    output_rule!()
);

/// `--help` of a polyline output.
pub const POLYLINE_OUTPUT: &str = concat!(
    "Output file for the polylines (.obj, .dxf or .json). ",
    output_rule!()
);

/// Parses a worker thread count: 0 (all cores) to [`RunOptions::MAX_THREADS`]; out of
/// range is a usage error (exit 2), before any work.
pub fn thread_count(s: &str) -> Result<usize, String> {
    let n: usize = s
        .parse()
        .map_err(|_| format!("{s:?} is not a number of threads"))?;
    if n > RunOptions::MAX_THREADS {
        return Err(format!(
            "at most {} threads, got {n}",
            RunOptions::MAX_THREADS
        ));
    }
    Ok(n)
}

/// Parses an output mesh path, refusing (a usage error, before any work) one whose format
/// the extension does not name. Where it is written is [`crate::output`]'s.
pub fn mesh_output(s: &str) -> Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(s);
    if meshbool::Format::for_path(&path).is_none() {
        return Err(unknown_mesh_extension(s));
    }
    Ok(path)
}

/// The message for an output whose extension names no mesh format: it lists those that do.
pub fn unknown_mesh_extension(path: &str) -> String {
    format!(
        "cannot tell the mesh format of {path} from its extension: use one of {}",
        meshbool::Format::NAMES
            .iter()
            .map(|(_, f)| format!(".{}", f.extension()))
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect::<Vec<_>>()
            .join(" ")
    )
}

/// Parses an output polyline path (.obj, .dxf or .json), checked as [`mesh_output`] is.
pub fn polyline_output(s: &str) -> Result<std::path::PathBuf, String> {
    let path = std::path::PathBuf::from(s);
    let ok = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["obj", "dxf", "json"].contains(&e.to_ascii_lowercase().as_str()));
    if !ok {
        return Err(format!(
            "polylines are written as .obj, .dxf or .json, not {s}"
        ));
    }
    Ok(path)
}

/// `--snap D` of the commands that make a mesh from a boolean or resolve.
#[derive(clap::Args, Clone, Copy, Debug)]
pub struct Snap {
    /// Snap tolerance D: collapse edges shorter than D and remove needles (altitude
    /// below D) where that keeps the result manifold, turns no triangle over, makes no
    /// self-intersection and moves no vertex more than D (0: the exact result).
    #[arg(long = "snap", value_name = "D", default_value_t = 0.0, allow_hyphen_values = true,
          value_parser = snap_tolerance)]
    pub tolerance: f64,
}

/// Prints a line on what snapping did (`--snap D`, without `--json`).
pub fn print_snap(s: &meshbool::repair::SnapReport) {
    eprintln!(
        "snapped at {}: {} edges collapsed, {} flipped, {} of {} short edges or needles left \
         (vertices moved at most {}, volume change {})",
        s.tolerance, s.collapsed, s.flipped, s.left, s.found, s.max_move, s.volume_change
    );
}

/// Parses a snap tolerance (`--snap D`): a finite distance ≥ 0 (a usage error, before any
/// work, otherwise).
pub fn snap_tolerance(s: &str) -> Result<f64, String> {
    match transform::numbers(s)?[..] {
        [v] if v >= 0.0 => Ok(v),
        [v] => Err(format!(
            "the snap tolerance must be a distance >= 0, got {v}"
        )),
        _ => Err("expected one number".into()),
    }
}

/// Writes `text` to standard output: a failure (a closed pipe, a full disk) is an error
/// naming standard output, never a panic (`main` ends quietly on a closed pipe).
pub fn out(text: &str) -> Result<()> {
    use anyhow::Context;
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .context("writing standard output")
}

/// Prints a report as pretty JSON on standard output.
pub fn print_json(report: &impl serde::Serialize) -> Result<()> {
    out(&(serde_json::to_string_pretty(report)? + "\n"))
}

/// Prints each line as a warning on standard error.
pub fn warn(lines: &[String]) {
    for w in lines {
        eprintln!("warning: {w}");
    }
}

/// A parser for one of the library's named values: `--help` lists `names`, and the text
/// is read with the library's `FromStr` (arguments using it set `ignore_case`).
pub fn one_of<T>(
    names: impl IntoIterator<Item = &'static str>,
) -> impl clap::builder::TypedValueParser<Value = T>
where
    T: std::str::FromStr<Err = meshbool::Error> + Clone + Send + Sync + 'static,
{
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(names).try_map(|s| s.parse::<T>())
}

/// The names of the formats (`--from`, `--to`, `--format`).
pub fn format_names() -> [&'static str; meshbool::Format::NAMES.len()] {
    meshbool::Format::NAMES.map(|(n, _)| n)
}

/// Parses a value the library can read from text (a format, close mode, facing, piece of
/// a split) for clap, with the library's message (which lists the names).
pub fn parse_value<T: std::str::FromStr<Err = meshbool::Error>>(s: &str) -> Result<T, String> {
    s.parse::<T>().map_err(|e| match e {
        meshbool::Error::InvalidParameter(m) => m,
        e => e.to_string(),
    })
}
