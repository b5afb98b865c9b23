//! The exit-code rule, in one place: a failed command's error is mapped to its code here,
//! by what went wrong, whichever command met it.
//!
//! - **0**: done; also when the reader of standard output stopped early
//!   (`meshbool info F | head -3`).
//! - **1**: an input or the work failed: a file missing, unreadable or malformed (a mesh,
//!   a points file, a `--config` file that does not parse, a split's directory), a mesh
//!   refused by the checks, an output that cannot be written or would replace what is not
//!   a command's own ([`crate::output`]).
//! - **2**: usage: the command line asks for what cannot be: an unknown command or
//!   option, a missing argument, a value that does not parse, an unknown format name, an
//!   output extension no writer handles, a number out of range (given as a flag or in
//!   `--config`), options that conflict. The parser finds most of these before any work;
//!   the rest are [`Usage`] errors the commands raise, and the library's
//!   [`meshbool::Error::InvalidParameter`].
//! - **130**: cancelled by Ctrl-C (nothing written).

use std::fmt;

/// An input or the work failed.
pub const FAILURE: u8 = 1;
/// The command line asks for what cannot be.
pub const USAGE: u8 = 2;
/// Cancelled by Ctrl-C.
pub const CANCELLED: u8 = 130;

/// A usage error a command finds after parsing (options the parser cannot judge alone,
/// such as `difference --reverse` with three inputs).
#[derive(Debug)]
pub struct Usage(pub String);

impl fmt::Display for Usage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Usage {}

/// A [`Usage`] error saying `message`.
pub fn usage(message: impl Into<String>) -> anyhow::Error {
    Usage(message.into()).into()
}

/// The exit code of a command that returned `e`: the first cause in its chain that says
/// what kind of failure it is decides (0 for a closed standard output).
pub fn code(e: &anyhow::Error) -> u8 {
    for cause in e.chain() {
        if cause.is::<Usage>() || cause.is::<clap::Error>() {
            return USAGE;
        }
        if let Some(e) = cause.downcast_ref::<meshbool::Error>() {
            return library(e);
        }
        if cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
        {
            return 0;
        }
    }
    FAILURE
}

/// The code of a library error: a parameter out of range is a usage error, the rest are
/// failures of an input or of the work.
fn library(e: &meshbool::Error) -> u8 {
    use meshbool::Error;
    match e {
        Error::File { error, .. } => library(error),
        Error::InvalidParameter(_) => USAGE,
        Error::Cancelled => CANCELLED,
        Error::Io(io) if io.kind() == std::io::ErrorKind::BrokenPipe => 0,
        _ => FAILURE,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each kind of error maps to its code, also when wrapped in context or in a file.
    #[test]
    fn errors_map_to_their_codes() {
        use anyhow::Context;
        use meshbool::Error;
        let file = |e: Error| e.in_file("reading", std::path::Path::new("x.ply"));
        let cases: [(anyhow::Error, u8); 8] = [
            (usage("--reverse takes two inputs"), USAGE),
            (
                Err::<(), _>(usage("bad"))
                    .context("in a command")
                    .unwrap_err(),
                USAGE,
            ),
            (Error::InvalidParameter("weld".into()).into(), USAGE),
            (file(Error::InvalidParameter("name".into())).into(), USAGE),
            (Error::Cancelled.into(), CANCELLED),
            (
                file(Error::Io(std::io::ErrorKind::NotFound.into())).into(),
                FAILURE,
            ),
            (
                Error::Operand {
                    name: "a.ply".into(),
                    problems: vec!["1 non-manifold edges".into()],
                }
                .into(),
                FAILURE,
            ),
            (
                std::io::Error::from(std::io::ErrorKind::BrokenPipe).into(),
                0,
            ),
        ];
        for (e, expected) in cases {
            assert_eq!(code(&e), expected, "{e:#}");
        }
        assert_eq!(code(&anyhow::anyhow!("a plain failure")), FAILURE);
    }
}
