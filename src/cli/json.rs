//! The CLI's JSON: the library's serde derives inside a versioned envelope,
//! plus the English text and legacy flags beside the machine-readable codes.

use crate::ray::{Hit, RayOutcome};
use crate::solve::{Cluster, Solution, UndecidedReason};
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
#[allow(dead_code)] // (wired into the batch commands one by one)
pub(super) struct ItemError {
    pub(super) code: &'static str,
    pub(super) message: String,
    pub(super) line: usize,
}

#[allow(dead_code)]
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
#[allow(dead_code)]
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

/// An undecided region with its reason's English text.
#[derive(Serialize)]
pub(super) struct ClusterJson<'a> {
    #[serde(flatten)]
    cluster: &'a Cluster,
    reason_text: &'static str,
}

/// A solution as the CLI prints it: the derive's keys, roots with
/// `"certified": true` (every listed root is), clusters with their text, and
/// the counters with the run time.
#[derive(Serialize)]
pub(super) struct SolutionJson<'a> {
    complete: bool,
    roots: Vec<RootJson<'a>>,
    clusters: Vec<ClusterJson<'a>>,
    leftovers: &'a [crate::solve::Leftover],
    stats: StatsJson<'a>,
}

#[derive(Serialize)]
struct RootJson<'a> {
    #[serde(flatten)]
    root: &'a crate::solve::Root,
    certified: bool,
}

#[derive(Serialize)]
struct StatsJson<'a> {
    #[serde(flatten)]
    stats: &'a crate::solve::Stats,
    seconds: f64,
}

impl<'a> SolutionJson<'a> {
    pub(super) fn new(sol: &'a Solution, seconds: f64) -> Self {
        Self {
            complete: sol.complete,
            roots: sol
                .roots
                .iter()
                .map(|root| RootJson { root, certified: true })
                .collect(),
            clusters: sol
                .clusters
                .iter()
                .map(|c| ClusterJson {
                    cluster: c,
                    reason_text: c.reason.describe(),
                })
                .collect(),
            leftovers: &sol.leftovers,
            stats: StatsJson {
                stats: &sol.stats,
                seconds,
            },
        }
    }
}

/// A hit as the CLI prints it: the derive's keys (`status`, `reason`), the
/// reason's text, and the flags of schema 0 (`certified`, `on_edge`,
/// `t_straddles_zero`) derived from the status.
#[derive(Serialize)]
pub(super) struct HitJson<'a> {
    #[serde(flatten)]
    hit: &'a Hit,
    #[serde(skip_serializing_if = "Option::is_none")]
    reason_text: Option<&'static str>,
    certified: bool,
    on_edge: bool,
    t_straddles_zero: bool,
}

impl<'a> HitJson<'a> {
    pub(super) fn new(hit: &'a Hit) -> Self {
        let reason = hit.undecided_reason();
        Self {
            hit,
            reason_text: reason.map(UndecidedReason::describe),
            certified: hit.is_certified(),
            on_edge: reason == Some(UndecidedReason::Boundary),
            t_straddles_zero: reason == Some(UndecidedReason::RangeEnd),
        }
    }
}

/// One ray's answer: `complete`, the hits, and for a degenerate ray its
/// reason (code and text).
#[derive(Serialize)]
pub(super) struct RayJson<'a> {
    complete: bool,
    hits: Vec<HitJson<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    degenerate: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    degenerate_code: Option<&'static str>,
}

impl<'a> RayJson<'a> {
    pub(super) fn new(outcome: &'a RayOutcome, complete: bool, hits: Vec<&'a Hit>) -> Self {
        let degeneracy = match outcome {
            RayOutcome::Degenerate(d) => Some(d),
            _ => None,
        };
        Self {
            complete,
            hits: hits.into_iter().map(HitJson::new).collect(),
            degenerate: degeneracy.map(|d| d.describe()),
            degenerate_code: degeneracy.map(|d| d.code()),
        }
    }
}
