//! The box solver's options and results: what is asked ([`RectOptions`],
//! [`Query`], [`RectClip`], an [`Objective`]) and what comes back
//! ([`RectSolution`]).

use crate::poly::TensorBezier;
use crate::solve::solution::Solution;
use inari::Interval;

/// What the caller wants from the roots, ordered by an objective `k` (for
/// rays: `t`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum Query {
    /// Every root.
    #[default]
    All,
    /// The roots of smallest objective: boxes are explored depth first, the
    /// child with the smaller objective bound first, and once a root is
    /// certified every box whose objective is provably above its upper bound
    /// is dropped (bounds by interval evaluation over the box, computed only
    /// then: the objective is not carried through the subdivision).
    Nearest,
    /// Any one certified root with `k ≥ k_min`: the search stops at the first.
    Any,
}

/// How a box is clipped (step 4 of the [`rect`](super) docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RectClip {
    /// Bézier clipping (Nishita, Sederberg & Kakimoto 1990): the convex hull
    /// of each equation's control points projected on each axis.
    #[default]
    Bezier,
    /// Fat lines (linear clipping on boxes; see `src/solve/rect/fatline.rs`): a rigorous
    /// strip around each equation's least-squares plane, the box cut to the
    /// parallelogram where both strips meet. Falls back to Bézier hulls
    /// where the strips are parallel within rounding.
    FatLine,
    /// Hybrid clipping on boxes (see `src/solve/rect/hybrid.rs`): a fat line
    /// for `f` and a fat conic for `g`, the box cut to the extremes of the
    /// region where the strip meets the conic band (vertices and tangencies,
    /// enclosed in interval arithmetic). Falls back to Bézier hulls where
    /// an enclosure is not possible.
    Hybrid,
}

/// Options of [`solve_rect`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectOptions {
    /// Boxes narrower than `eps` (relative to the domain's sides) become
    /// leaves; see the [`rect`](super) docs.
    pub eps: f64,
    /// Boxes processed before the run stops with `complete = false`.
    pub max_boxes: usize,
    /// All roots, the nearest, or any.
    pub query: Query,
    /// The floor of the objective, enclosed: `[lo, hi]` holds the exact
    /// floor (a point when it is a float). Regions whose objective is
    /// provably below `lo` are dropped; a root counts for the queries only
    /// when its objective is provably at least `hi`.
    pub key_min: Option<[f64; 2]>,
    /// The clipping method.
    pub clip: RectClip,
    /// No box is processed after this instant (`complete = false`).
    pub deadline: Option<std::time::Instant>,
    /// [`Query::Nearest`] only: an upper bound of the objective's minimum
    /// known from elsewhere (a point where the caller's objective was
    /// enclosed). Boxes whose objective is provably above it are dropped
    /// from the start, as if a root with that bound had been certified;
    /// `complete = true` then speaks of the roots whose objective is at most
    /// the smaller of the two bounds.
    pub key_max: Option<f64>,
}

impl Default for RectOptions {
    fn default() -> Self {
        Self {
            eps: 1e-12,
            max_boxes: 50_000,
            query: Query::All,
            key_min: None,
            clip: RectClip::default(),
            deadline: None,
            key_max: None,
        }
    }
}

/// An objective `k = num/den` over the domain, with `den > 0` on it.
#[derive(Clone, Copy, Debug)]
pub struct Objective<'a> {
    /// The numerator.
    pub num: &'a TensorBezier<Interval>,
    /// The denominator (`1` if absent); its coefficients must be positive.
    pub den: Option<&'a TensorBezier<Interval>>,
}

/// The result of [`solve_rect`].
///
/// # Contract
/// The [`Solution`] contract, with these amendments for the queries:
/// * [`Query::All`]: as stated there (with `key_min`: for the roots where the
///   objective is `≥ key_min`; roots with a smaller objective may or may not
///   be returned).
/// * [`Query::Nearest`]: `complete = true` means every root whose objective
///   is at most the smallest certified upper bound `k*` (over roots with
///   objective provably `≥ key_min`) lies in a returned region; regions whose
///   objective is provably above `k*` were not explored.
/// * [`Query::Any`]: if `stopped_early`, the first certified root is returned
///   and nothing is claimed about the rest.
#[derive(Clone, Debug)]
pub struct RectSolution {
    /// Roots, clusters, leftovers and counters.
    pub solution: Solution,
    /// [`Query::Any`] found its root and stopped.
    #[cfg_attr(not(feature = "internals"), allow(dead_code))]
    pub stopped_early: bool,
}
