//! What a ray query returns: hits with one status each, and the outcome of a
//! ray (hits, or why no hit list can be given).

use crate::solve::UndecidedReason;
use glam::DVec3;

/// What is proven about a [`Hit`].
///
/// JSON (feature `serde`): `"status": "certified"`, or `"status":
/// "undecided"` with `"reason"` the [`UndecidedReason`] code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "status", content = "reason", rename_all = "snake_case")
)]
pub enum HitStatus {
    /// The `(u, v)` box holds exactly one intersection of the ray's line with
    /// the surface, a transversal one; it lies on the closed patch and its
    /// `t` in the requested range (Krawczyk, and exact arithmetic where
    /// rounding left either in doubt).
    Certified,
    /// Nothing is proven about the count: the box may hold any number of
    /// hits, including none (except as the reason says).
    Undecided(UndecidedReason),
}

/// Closed boxes of a hit.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HitBox {
    /// `[lo, hi]` in `u`.
    pub u: [f64; 2],
    /// `[lo, hi]` in `v`.
    pub v: [f64; 2],
    /// `[lo, hi]` in `t`.
    pub t: [f64; 2],
}

/// One intersection of the ray with the patch (or an undecided region that
/// may hold some).
///
/// JSON (feature `serde`): the fields, `"status"` and `"reason"` as for
/// [`HitStatus`], and, derived from the status for readers that want them
/// spelled out, `"reason_text"` (the reason in English), `"certified"`,
/// `"on_edge"` (`reason = "boundary"`) and `"t_straddles_zero"` (`reason =
/// "range_end"`); they are ignored when read back.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Deserialize), serde(from = "super::json::HitIn"))]
pub struct Hit {
    /// Midpoint of the `t` box (the hit is `o + t·d`, `d` as given).
    pub t: f64,
    /// Midpoint of the `u` box.
    pub u: f64,
    /// Midpoint of the `v` box.
    pub v: f64,
    /// `S(u, v)` in `f64`.
    pub point: DVec3,
    /// Unit normal `S_u × S_v / |S_u × S_v|` at `(u, v)` in `f64` (zero where
    /// undefined).
    pub normal: DVec3,
    /// What is proven; see [`HitStatus`].
    pub status: HitStatus,
    /// The boxes; every hit the entry stands for lies in them.
    pub bx: HitBox,
}

impl Hit {
    /// `true` for [`HitStatus::Certified`].
    pub fn is_certified(&self) -> bool {
        self.status == HitStatus::Certified
    }

    /// Why the hit is not certified (`None` if it is).
    pub fn undecided_reason(&self) -> Option<UndecidedReason> {
        match self.status {
            HitStatus::Certified => None,
            HitStatus::Undecided(r) => Some(r),
        }
    }

    /// The box holds exactly one simple root of the ray's equations, on the
    /// patch or within rounding of its edge: certified, or undecided only at
    /// the edge.
    pub(crate) fn is_proven_root(&self) -> bool {
        matches!(
            self.status,
            HitStatus::Certified | HitStatus::Undecided(UndecidedReason::Boundary)
        )
    }

    /// Undecided only because the root may lie just past the patch's edge.
    pub(crate) fn on_edge(&self) -> bool {
        self.status == HitStatus::Undecided(UndecidedReason::Boundary)
    }
}

/// The hits of one ray, sorted by `t`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct RayHits {
    /// `true`: every hit in the `t` range lies in one of `hits` (certified or
    /// not). `false`: a budget stopped the solve (only inside
    /// [`Degeneracy::Unresolved`]).
    pub complete: bool,
    /// The hits, sorted by `t` (midpoint), then `u`, `v`.
    pub hits: Vec<Hit>,
}

impl RayHits {
    /// The hits that may be the nearest one: every hit whose `t` lower bound
    /// is at most the smallest `t` upper bound of a certified hit (all hits
    /// when none is certified). A single certified entry is a proven nearest
    /// hit.
    pub fn nearest(&self) -> Vec<&Hit> {
        let best = self
            .hits
            .iter()
            .filter(|h| h.is_certified())
            .map(|h| h.bx.t[1])
            .fold(f64::INFINITY, f64::min);
        self.hits.iter().filter(|h| h.bx.t[0] <= best).collect()
    }
}

/// Why a ray could not be answered with a list of hits.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Degeneracy {
    /// An equation may vanish identically (every coefficient enclosure
    /// contains 0): the ray lies in the plane of the patch, or in a plane
    /// holding the whole control net.
    ZeroEquation,
    /// The solve exhausted its budget or deadline, or ended in more
    /// undecided regions than a transversal ray can have. The hits found so
    /// far are kept.
    Unresolved(RayHits),
    /// Proven: the ray runs along the surface — its two plane equations share
    /// a factor (exact test), so its hits include a curve of the patch. The
    /// hits found before the test are kept (`complete = false`).
    AlongSurface(RayHits),
}

impl Degeneracy {
    /// The stable machine-readable code: `"zero_equation"`, `"unresolved"`
    /// or `"along_surface"`.
    pub fn code(&self) -> &'static str {
        match self {
            Degeneracy::ZeroEquation => "zero_equation",
            Degeneracy::Unresolved(_) => "unresolved",
            Degeneracy::AlongSurface(_) => "along_surface",
        }
    }

    /// A one-line English description for output.
    pub fn describe(&self) -> &'static str {
        match self {
            Degeneracy::ZeroEquation => {
                "the ray lies in a plane containing the whole control net (a planar patch): an equation vanishes identically"
            }
            Degeneracy::Unresolved(_) => {
                "solver budget or deadline exhausted, or too many undecided regions: the ray may run along the surface"
            }
            Degeneracy::AlongSurface(_) => {
                "the ray runs along the surface (proven: its plane equations share a factor): its hits include a curve"
            }
        }
    }
}

/// The answer for one ray.
///
/// JSON (feature `serde`; what `rootclip ray --json` prints per ray):
/// `{"complete": bool, "hits": [Hit, …]}`, and for a degenerate ray
/// `"degenerate_code"` ([`Degeneracy::code`]), `"degenerate"` (its
/// [description](Degeneracy::describe)) and, for `unresolved` and
/// `along_surface`, `"hits_complete"` (the inner [`RayHits::complete`]).
/// `"complete"` is [`RayOutcome::is_complete`].
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(into = "super::json::OutcomeRepr", try_from = "super::json::OutcomeRepr")
)]
pub enum RayOutcome {
    /// Every hit in the `t` range; see [`RayHits`].
    Hits(RayHits),
    /// No hit list can be given; see [`Degeneracy`].
    Degenerate(Degeneracy),
}

impl RayOutcome {
    /// The hits listed: all of them for [`RayOutcome::Hits`], those found so
    /// far for [`Degeneracy::Unresolved`] and [`Degeneracy::AlongSurface`],
    /// none for a zero equation.
    pub fn hits(&self) -> &[Hit] {
        match self {
            RayOutcome::Hits(h)
            | RayOutcome::Degenerate(Degeneracy::Unresolved(h))
            | RayOutcome::Degenerate(Degeneracy::AlongSurface(h)) => &h.hits,
            RayOutcome::Degenerate(Degeneracy::ZeroEquation) => &[],
        }
    }

    /// `true` for [`RayOutcome::Hits`]: every hit in the range is listed.
    pub fn is_complete(&self) -> bool {
        matches!(self, RayOutcome::Hits(h) if h.complete)
    }

    /// A short description of a degenerate outcome (`None` for hits).
    pub fn degenerate_reason(&self) -> Option<&'static str> {
        match self {
            RayOutcome::Hits(_) => None,
            RayOutcome::Degenerate(d) => Some(d.describe()),
        }
    }
}
