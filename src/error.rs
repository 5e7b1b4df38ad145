//! Typed errors for bad input. Library functions return these; they never
//! panic on user data. The CLI prints one line and exits with code 2.

use std::fmt;

/// Why an input was rejected.
///
/// Each variant names one kind of fault; [`Error::code`] gives it as a stable
/// machine-readable string (the CLI's JSON and scripts match on it, not on the
/// English text).
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// A file or stream could not be read.
    Io {
        /// The path (`-` for standard input).
        path: String,
        /// What the operating system said.
        message: String,
    },
    /// An option is out of range (a NaN or non-positive `eps`, an empty `t`
    /// range, an unknown method name).
    InvalidOption(String),
    /// An expression could not be parsed: what went wrong and the byte offset.
    Parse {
        /// What was expected or found.
        message: String,
        /// Byte offset into the expression (0-based).
        at: usize,
    },
    /// An input document is malformed: JSON syntax, an unknown or missing
    /// key, a line with the wrong number of fields. The message names the
    /// document and the line.
    Format(String),
    /// A coefficient, point or parameter is NaN or infinite.
    NonFinite(String),
    /// Shapes do not fit (wrong number of coefficients, degrees, empty input).
    Shape(String),
    /// The input is degenerate: a zero ray direction, a weight that is not
    /// positive, a collapsed domain.
    Degenerate(String),
    /// An equation of the system is identically zero: every point of the
    /// other equation's curve is a root. Names the equation.
    ZeroEquation(String),
    /// The two equations share a non-constant factor: its zeros are a curve
    /// of roots. `factor` is the exact factor (the gcd over ℚ, leading
    /// coefficient 1) as an expression [`parse_polynomial`](crate::parse_polynomial)
    /// reads back; [`solve_reduced`](crate::solve::solve_reduced) solves what
    /// remains.
    CommonFactor {
        /// The common factor, exactly.
        factor: String,
    },
    /// A size limit protects against runaway work (e.g. degree too large).
    TooLarge(String),
}

impl Error {
    /// A stable machine-readable name of the variant: `"io"`,
    /// `"invalid_option"`, `"parse"`, `"format"`, `"non_finite"`, `"shape"`,
    /// `"degenerate"`, `"zero_equation"`, `"common_factor"` or `"too_large"`.
    ///
    /// ```
    /// let e = rootclip::poly::parse_polynomial("u^-1").unwrap_err();
    /// assert_eq!(e.code(), "parse");
    /// ```
    pub fn code(&self) -> &'static str {
        match self {
            Error::Io { .. } => "io",
            Error::InvalidOption(_) => "invalid_option",
            Error::Parse { .. } => "parse",
            Error::Format(_) => "format",
            Error::NonFinite(_) => "non_finite",
            Error::Shape(_) => "shape",
            Error::Degenerate(_) => "degenerate",
            Error::ZeroEquation(_) => "zero_equation",
            Error::CommonFactor { .. } => "common_factor",
            Error::TooLarge(_) => "too_large",
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { path, message } => write!(f, "cannot read {path}: {message}"),
            Error::InvalidOption(s) => write!(f, "invalid option: {s}"),
            Error::Parse { message, at } => write!(f, "parse error at offset {at}: {message}"),
            Error::Format(s) => write!(f, "malformed input: {s}"),
            Error::NonFinite(s) => write!(f, "non-finite input: {s}"),
            Error::Shape(s) => write!(f, "shape error: {s}"),
            Error::Degenerate(s) => write!(f, "degenerate input: {s}"),
            Error::ZeroEquation(s) => write!(f, "degenerate input: {s}"),
            Error::CommonFactor { factor } => write!(
                f,
                "degenerate input: f and g share the factor {factor}: the system has a curve of roots"
            ),
            Error::TooLarge(s) => write!(f, "too large: {s}"),
        }
    }
}

impl std::error::Error for Error {}

/// `Result` with [`Error`].
pub type Result<T> = std::result::Result<T, Error>;
