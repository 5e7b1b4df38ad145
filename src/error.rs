//! Typed errors for bad input. Library functions return these; they never panic
//! on user data. The CLI prints one line and exits with code 2.

use std::fmt;

/// Why an input was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// An expression could not be parsed: what went wrong and the byte offset.
    Parse {
        /// What was expected or found.
        message: String,
        /// Byte offset into the expression (0-based).
        at: usize,
    },
    /// A coefficient, point or parameter is NaN or infinite.
    NonFinite(String),
    /// Shapes do not fit (wrong number of coefficients, degrees, empty input).
    Shape(String),
    /// A domain or parameter is degenerate (empty interval, collapsed triangle).
    Degenerate(String),
    /// A size limit protects against runaway work (e.g. degree too large).
    TooLarge(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Parse { message, at } => write!(f, "parse error at offset {at}: {message}"),
            Error::NonFinite(s) => write!(f, "non-finite input: {s}"),
            Error::Shape(s) => write!(f, "shape error: {s}"),
            Error::Degenerate(s) => write!(f, "degenerate input: {s}"),
            Error::TooLarge(s) => write!(f, "too large: {s}"),
        }
    }
}

impl std::error::Error for Error {}

/// `Result` with [`Error`].
pub type Result<T> = std::result::Result<T, Error>;
