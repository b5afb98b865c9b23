//! The library's error type. Every fallible public function returns [`Result`]; nothing in
//! the library panics on user input.

use std::fmt;

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
    #[error("cannot tell the mesh format of {0}: use a known extension (.stl .obj .ply .dxf .json) or name the format")]
    UnknownFormat(String),
    /// A mesh violates the data model: non-finite coordinates, indices out of range, too many vertices.
    #[error("invalid mesh at {location}: {message}")]
    InvalidMesh {
        /// The offending vertex or triangle.
        location: Location,
        /// What is wrong.
        message: String,
    },
    /// A parameter given to an operation is out of its range (a negative distance, NaN).
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
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

    pub(crate) fn invalid(location: Location, message: impl Into<String>) -> Self {
        Error::InvalidMesh {
            location,
            message: message.into(),
        }
    }
}
