//! One module per command: its arguments (a clap struct) and `run`, which calls the
//! library's front door and prints what it returns. What every command shares is here:
//! the boolean operands' flags, the progress spinner and printing.

use anyhow::Result;
use meshbool::ops::{Checks, Progress, RunOptions};

pub mod boolean;
pub mod close;
pub mod convert;
pub mod curves;
pub mod info;
pub mod orient;
pub mod pick;
pub mod repair;
pub mod split;

/// Flags shared by the commands that take two operands (booleans, split).
#[derive(clap::Args, Clone)]
pub struct OperandFlags {
    /// Proceed even when an input has inconsistently oriented or non-manifold edges (the
    /// result then assumes the orientation as given; the JSON report lists what was assumed).
    #[arg(long)]
    pub force: bool,
    /// Print a JSON report on stdout.
    #[arg(long)]
    pub json: bool,
    /// Skip the check for self-intersecting inputs (it costs about as much as the boolean
    /// on large meshes); only for inputs known to be clean.
    #[arg(long)]
    pub no_self_check: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
}

impl OperandFlags {
    /// The checks the flags ask for.
    pub fn checks(&self) -> Checks {
        Checks {
            self_intersections: !self.no_self_check,
            force: self.force,
            ..Checks::default()
        }
    }

    /// Threads, and progress shown on `spinner`.
    pub fn run(&self, spinner: &Spinner) -> RunOptions {
        let bar = spinner.0.clone();
        RunOptions {
            threads: self.threads,
            progress: Some(Progress::new(move |s| bar.set_message(s.describe()))),
        }
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
/// dropped, so an error message never lands after a stale spinner line.
pub struct Spinner(indicatif::ProgressBar);

impl Spinner {
    /// A spinner showing `msg`.
    pub fn new(msg: &'static str) -> Self {
        let bar = indicatif::ProgressBar::new_spinner();
        if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} [{elapsed}] {msg}") {
            bar.set_style(style);
        }
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        bar.set_message(msg);
        Spinner(bar)
    }

    /// Shows `msg`.
    pub fn set_message(&self, msg: &'static str) {
        self.0.set_message(msg);
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}

/// Prints a report as pretty JSON on standard output.
pub fn print_json(report: &impl serde::Serialize) -> Result<()> {
    println!("{}", serde_json::to_string_pretty(report)?);
    Ok(())
}

/// Prints each line as a warning on standard error.
pub fn warn(lines: &[String]) {
    for w in lines {
        eprintln!("warning: {w}");
    }
}

/// Parses a value the library can read from text (a format, close mode, facing, piece of
/// a split) for clap, with the library's message (which lists the names).
pub fn parse_value<T: std::str::FromStr<Err = meshbool::Error>>(s: &str) -> Result<T, String> {
    s.parse::<T>().map_err(|e| match e {
        meshbool::Error::InvalidParameter(m) => m,
        e => e.to_string(),
    })
}
