//! The CLI's JSON: the library's serde derives inside a versioned envelope,
//! plus the English text and legacy flags beside the machine-readable codes.

use serde::{Serialize, Serializer};
use std::io::{self, Write};

/// Bumped whenever a key changes meaning or disappears (adding keys does not
/// bump it).
pub(super) const SCHEMA_VERSION: u32 = 1;

#[derive(Serialize)]
struct Envelope<'a, T: Serialize> {
    schema_version: u32,
    #[serde(flatten)]
    body: &'a T,
}

/// `body` as one line of JSON with `"schema_version"` first (the small
/// documents: `bernstein`, `tables`, `heuristics`, `ssi`).
pub(super) fn document<T: Serialize>(body: &T) -> String {
    let env = Envelope {
        schema_version: SCHEMA_VERSION,
        body,
    };
    serde_json::to_string(&env).unwrap_or_else(|e| format!("{{\"schema_version\":{SCHEMA_VERSION},\"error\":\"{e}\"}}"))
}

/// The same line as [`document`] and a newline, serialized straight into
/// `out`. A serialization error (none of the CLI's types can produce one)
/// comes back as an `InvalidData` I/O error, after part of the line.
pub(super) fn write_document<T: Serialize>(out: &mut impl Write, body: &T) -> io::Result<()> {
    let env = Envelope {
        schema_version: SCHEMA_VERSION,
        body,
    };
    serde_json::to_writer(&mut *out, &env)?;
    out.write_all(b"\n")
}

/// A batch item that failed: `{"error": {"code", "message", "line"}}` in the
/// item's place (`code` is [`Error::code`](crate::Error::code); `line` the
/// 1-based line of the input file the item came from).
#[derive(Clone, Debug, Serialize)]
pub(super) struct ItemError {
    pub(super) code: &'static str,
    pub(super) message: String,
    pub(super) line: usize,
}

impl ItemError {
    pub(super) fn new(e: &crate::Error, line: usize) -> Self {
        Self {
            code: e.code(),
            message: e.to_string(),
            line,
        }
    }

    /// `item k (line L): message`, for text output.
    pub(super) fn text(&self, what: &str, k: usize) -> String {
        format!("{what} {k} (line {}): error: {}", self.line, self.message)
    }
}

/// One batch item as printed: the library result's own JSON, or
/// `{"error": …}` ([`ItemError`]).
#[derive(Serialize)]
#[serde(untagged)]
pub(super) enum Item<T: Serialize> {
    Ok(T),
    Err { error: ItemError },
}

/// A JSON array of `view(item)` for the items, each element made just
/// before it is written: no `Vec` of the views is built.
pub(super) struct LazySeq<'a, T, U> {
    pub(super) items: &'a [T],
    pub(super) view: &'a dyn Fn(&'a T) -> U,
}

impl<T, U: Serialize> Serialize for LazySeq<'_, T, U> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.items.iter().map(self.view))
    }
}
