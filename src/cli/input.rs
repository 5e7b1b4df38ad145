//! Reading the CLI's input files, `-` for standard input.

use crate::error::{Error, Result};
use std::io::Read;

/// The text of a file, or of standard input for `-`.
pub(super) fn read_input(path: &str) -> Result<String> {
    let io = |e: std::io::Error| Error::Io {
        path: path.to_string(),
        message: e.to_string(),
    };
    if path == "-" {
        let mut text = String::new();
        std::io::stdin().read_to_string(&mut text).map_err(io)?;
        Ok(text)
    } else {
        std::fs::read_to_string(path).map_err(io)
    }
}

/// A `--timeout`-like option in seconds as a duration; an error for a
/// negative, NaN or too large number.
pub(super) fn duration(flag: &str, seconds: f64) -> Result<std::time::Duration> {
    std::time::Duration::try_from_secs_f64(seconds).map_err(|_| {
        Error::InvalidOption(format!(
            "{flag} must be a non-negative number of seconds, got {seconds}"
        ))
    })
}
