//! What [`solve_uni`](super::solve_uni) is asked and what it returns.

use crate::error::{Error, Result};
use crate::solve::solution::UndecidedReason;

/// Options of [`solve_uni`](super::solve_uni). Start from
/// [`UniOptions::default`] and change what you need:
///
/// ```
/// use rootclip::solve::UniOptions;
/// let opts = UniOptions::default().with_eps(1e-9).with_max_boxes(500);
/// assert!(opts.validate().is_ok());
/// assert!(UniOptions::default().with_eps(0.0).validate().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct UniOptions {
    /// Sub-intervals that are neither excluded nor isolated are refined
    /// until they are narrower than `eps` (in the local parameter of
    /// `[0, 1]`; default `1e-12`, any positive finite number). Certified
    /// root intervals are then contracted to the rounding floor, usually far
    /// below `eps`.
    pub eps: f64,
    /// Budget: sub-intervals examined (default 10,000). A run that reaches
    /// it ends with `complete = false` and its leftovers.
    pub max_boxes: usize,
}

impl Default for UniOptions {
    fn default() -> Self {
        Self {
            eps: 1e-12,
            max_boxes: 10_000,
        }
    }
}

impl UniOptions {
    /// The same options with `eps`.
    pub fn with_eps(mut self, eps: f64) -> Self {
        self.eps = eps;
        self
    }

    /// The same options with the budget `max_boxes`.
    pub fn with_max_boxes(mut self, max_boxes: usize) -> Self {
        self.max_boxes = max_boxes;
        self
    }

    /// Checks the options: `eps` positive and finite, `max_boxes` at least 1
    /// ([`Error::InvalidOption`]).
    pub fn validate(&self) -> Result<()> {
        if !(self.eps.is_finite() && self.eps > 0.0) {
            return Err(Error::InvalidOption(format!(
                "eps must be a positive finite number, got {}",
                self.eps
            )));
        }
        if self.max_boxes == 0 {
            return Err(Error::InvalidOption("max_boxes must be at least 1".into()));
        }
        Ok(())
    }
}

/// A certified root: its interval holds exactly one root of the polynomial,
/// a simple one, and that root lies in the closed domain (see
/// [`UniSolution`]).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct UniRoot {
    /// Midpoint of the interval.
    pub x: f64,
    /// The closed interval `[lo, hi]`.
    pub interval: [f64; 2],
    /// The interval contains an end of the domain: the root is that end or
    /// within the interval's width of it (inside the domain: settled).
    pub on_boundary: bool,
}

/// An undecided region: it may hold any number of roots (including none),
/// except as its reason says.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct UniCluster {
    /// The closed interval `[lo, hi]`, within the domain.
    pub interval: [f64; 2],
    /// Why it is undecided: [`UndecidedReason::MultipleOrClose`] (a
    /// multiple root, or roots closer than rounding lets the tests
    /// separate) or [`UndecidedReason::Boundary`] (interval input only:
    /// one simple root on the line within rounding of an end of the domain,
    /// its side not proven for every member).
    pub reason: UndecidedReason,
}

/// Counters of a univariate solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(default))]
pub struct UniStats {
    /// Sub-intervals examined by the subdivision (the budget's unit).
    pub intervals: usize,
    /// Sub-intervals proven root-free by Descartes' rule or the hull clip.
    pub exclusions: usize,
    /// Sub-intervals where Descartes' rule proved exactly one root.
    pub isolations: usize,
    /// Clips (Bézier hull or Newton) that at least halved a sub-interval.
    pub clips: usize,
    /// Bisections.
    pub bisections: usize,
    /// Interval Newton tests in the search and the certification.
    pub newton_tests: usize,
    /// Sub-intervals proven root-free by interval Newton.
    pub newton_exclusions: usize,
    /// Exact rational tests (restrictions with Descartes and Newton) on the
    /// regions rounding left undecided (exact input only).
    pub exact_tests: usize,
    /// Certified roots dropped because they lie provably outside the domain.
    pub outside_domain: usize,
}

/// The result of [`solve_uni`](super::solve_uni).
///
/// # Contract
/// For the polynomial `p` on its domain `[a, b]`:
/// * If `complete` is `true`, every root of `p` in the closed `[a, b]`
///   lies in a `roots[..].interval` or a `clusters[..].interval`.
/// * Whatever `complete` says, every root in no such interval lies in a
///   `leftovers` interval (the budget stopped there); `complete` is `true`
///   iff `leftovers` is empty.
/// * Each `roots[i].interval` contains exactly one root of `p`, a simple
///   one, and it lies in the closed `[a, b]`. Distinct entries are distinct
///   roots.
/// * Clusters promise nothing about their content.
///
/// For exact input (`f64` or rational coefficients) this is about that
/// polynomial, and a root at or within rounding of an end of the domain is
/// settled in exact arithmetic; for interval coefficients it holds for every
/// polynomial whose coefficients lie in the enclosures.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct UniSolution {
    /// See the contract.
    pub complete: bool,
    /// Certified roots, sorted by `x`.
    pub roots: Vec<UniRoot>,
    /// Undecided regions, sorted.
    pub clusters: Vec<UniCluster>,
    /// Intervals a budget left unexplored, sorted.
    pub leftovers: Vec<[f64; 2]>,
    /// Counters.
    pub stats: UniStats,
}
