//! Writing a command's answer: straight into standard output, locked once and
//! buffered. Large answers (`ray --rays`, `project`) are written as they are
//! formatted — JSON by the serde derives, element by element — never
//! gathered into one `String` first.

use super::json::write_document;
use serde::Serialize;
use std::io::{self, BufWriter, StdoutLock, Write};

/// Standard output, locked once and buffered.
pub(super) type Out = BufWriter<StdoutLock<'static>>;

/// Writes a command's output, ending it with a newline.
type Writer = Box<dyn FnOnce(&mut Out) -> io::Result<()>>;

/// What a command prints. The command computes it in full before anything
/// is written, so a failing command leaves standard output empty (one error
/// line on stderr, exit 2); only the writing is left here. A batch whose
/// items failed one by one (a bad ray, point or claim) prints every item,
/// the failed ones as errors, and counts them in `failed` (exit 1).
pub(super) struct Answer {
    write: Writer,
    /// Batch items that failed (each printed as its error), and the items.
    pub(super) failed: (usize, usize),
}

impl Answer {
    /// The output `write` writes (ending it with a newline).
    pub(super) fn new(write: impl FnOnce(&mut Out) -> io::Result<()> + 'static) -> Self {
        Self {
            write: Box::new(write),
            failed: (0, 0),
        }
    }

    /// The same answer, noting that `failed` of `items` batch items failed.
    pub(super) fn with_failed(mut self, failed: usize, items: usize) -> Self {
        self.failed = (failed, items);
        self
    }

    /// `text` and a newline.
    pub(super) fn text(text: String) -> Self {
        Self::new(move |out| writeln!(out, "{text}"))
    }

    /// `body` as the CLI's JSON document (see [`write_document`]).
    pub(super) fn json<T: Serialize + 'static>(body: T) -> Self {
        Self::new(move |out| write_document(out, &body))
    }

    /// Writes the answer to standard output. A closed pipe
    /// (`rootclip … | head`) ends the writing quietly, as a success: the
    /// reader has what it wanted.
    pub(super) fn print(self) -> io::Result<()> {
        let mut out = BufWriter::with_capacity(1 << 16, io::stdout().lock());
        match (self.write)(&mut out).and_then(|()| out.flush()) {
            Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
            done => done,
        }
    }
}
