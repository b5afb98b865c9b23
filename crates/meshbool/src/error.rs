//! The library's error type. Every fallible public function returns [`Result`]; nothing in
//! the library panics on user input.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::format::Format;

/// Where in an input something went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// A 1-based line number in a text file.
    Line(usize),
    /// A 0-based byte offset in a binary file.
    Byte(u64),
    /// A 0-based vertex index in a mesh.
    Vertex(usize),
    /// A 0-based triangle (or face record) index.
    Triangle(usize),
    /// The input as a whole (for example, an empty file).
    Whole,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(n) => write!(f, "line {n}"),
            Location::Byte(n) => write!(f, "byte {n}"),
            Location::Vertex(n) => write!(f, "vertex {n}"),
            Location::Triangle(n) => write!(f, "triangle {n}"),
            Location::Whole => write!(f, "start of input"),
        }
    }
}

/// Everything that can go wrong in the library.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading or writing a file failed at the operating-system level (displayed as the
    /// operating system's message, which is also the source, so that error chains do not
    /// repeat it).
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// A file's content does not follow its format.
    #[error("malformed {format} at {location}: {message}")]
    Parse {
        /// The format the content was read as.
        format: Format,
        /// Where the problem was found.
        location: Location,
        /// What is wrong.
        message: String,
    },
    /// The format could not be told from the file name nor from the content.
    #[error("cannot tell the mesh format of {0}: use a known extension (.stl .obj .ply .dxf .json .glb .ts .dtm .xml) or name the format")]
    UnknownFormat(String),
    /// A mesh violates the data model: non-finite coordinates, indices out of range, too many vertices.
    #[error("invalid mesh at {location}: {message}")]
    InvalidMesh {
        /// The offending vertex or triangle.
        location: Location,
        /// What is wrong.
        message: String,
    },
    /// A file the library wrote for itself (a split's `manifest.json`), or a list of
    /// points, does not read as one.
    #[error("malformed {what}: {message}")]
    Malformed {
        /// What the content should have been.
        what: &'static str,
        /// What is wrong.
        message: String,
    },
    /// A parameter given to an operation is out of its range (a negative distance, NaN).
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
    /// An operand of a boolean, split or curves failed its checks ([`crate::ops::Checks`]):
    /// inside and outside would be ambiguous. Set `force` to take the input as given.
    #[error("{name}: {}; inside/outside would be ambiguous. Repair the input, or force the operation to take it as given", problems.join(", "))]
    Operand {
        /// The operand's name (its file, or `A` / `B`).
        name: String,
        /// What was found, one phrase each ("46 inconsistently oriented edges").
        problems: Vec<String>,
    },
    /// A mesh could not be resolved into the solid it encloses
    /// ([`crate::ops::resolve()`]): the reason, one phrase.
    #[error("{name} cannot be resolved: {reason}")]
    Unresolvable {
        /// The mesh's name (its file, or `mesh`).
        name: String,
        /// Why.
        reason: String,
    },
    /// The call was cancelled ([`crate::ops::Cancel`]) before it finished; it left no
    /// result.
    #[error("cancelled")]
    Cancelled,
    /// An operation that needs triangles got an input without any (cut and fill of an
    /// empty surface).
    #[error("{name}: no triangles; {needs}")]
    Empty {
        /// The input's name (its file, or `design` / `topography`).
        name: String,
        /// What the operation needs, one phrase ("cut and fill need two surfaces").
        needs: &'static str,
    },
    /// Reading or writing a file failed; the message names the file, then the cause.
    #[error("{action} {}: {error}", path.display())]
    File {
        /// What was being done: "reading", "writing", "creating".
        action: &'static str,
        /// The file.
        path: PathBuf,
        /// What went wrong.
        error: Box<Error>,
    },
}

/// `Result` with the library's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub(crate) fn parse(format: Format, location: Location, message: impl Into<String>) -> Self {
        Error::Parse {
            format,
            location,
            message: message.into(),
        }
    }

    /// This error, as met while `action` ("reading", "writing") the file at `path`.
    pub fn in_file(self, action: &'static str, path: &Path) -> Self {
        Error::File {
            action,
            path: path.to_path_buf(),
            error: Box::new(self),
        }
    }

    pub(crate) fn invalid(location: Location, message: impl Into<String>) -> Self {
        Error::InvalidMesh {
            location,
            message: message.into(),
        }
    }
}

/// The item of `all` whose `name` is `s` (ignoring ASCII case), or an error naming `what`
/// was asked for and listing the names: the `FromStr` of the library's named enums.
pub(crate) fn parse_name<T: Copy>(
    s: &str,
    all: &[T],
    name: impl Fn(T) -> &'static str,
    what: &str,
) -> Result<T> {
    all.iter()
        .copied()
        .find(|&x| name(x).eq_ignore_ascii_case(s))
        .ok_or_else(|| {
            let names: Vec<&str> = all.iter().map(|&x| name(x)).collect();
            Error::InvalidParameter(format!(
                "unknown {what} {s:?}; one of: {}",
                names.join(", ")
            ))
        })
}

impl std::str::FromStr for Format {
    type Err = Error;

    /// The format named `s` ([`Format::NAMES`], any ASCII case), with an error listing the
    /// names.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let formats = Format::NAMES.map(|(_, f)| f);
        parse_name(s, &formats, Format::name, "format")
    }
}
