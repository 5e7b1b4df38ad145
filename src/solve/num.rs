//! The operations the clipping geometry needs beyond [`Scalar`]: square roots,
//! two-piece division, "possibly" comparisons.
//!
//! Two kernels: [`Interval`] (every answer is a proof about all members) and
//! `f64` (the same iteration without proofs, used to measure the cost of
//! rigor). The `possibly_*` predicates are the conservative direction: for
//! intervals they answer `true` unless the opposite is proven.

use crate::scalar::{interval, point, Scalar};
use inari::Interval;

/// A kernel the clipping driver runs on.
pub trait Num: Scalar + Copy {
    /// The point value `x` (finite).
    fn pt(x: f64) -> Self;
    /// `√(x ∩ [0, ∞))`, or `None` when `x < 0` provably.
    fn sqrt_nonneg(self) -> Option<Self>;
    /// `num / den` as at most two pieces (two when `den` straddles 0).
    /// Pieces are `None` when empty.
    fn div_pieces(num: Self, den: Self) -> [Option<Self>; 2];
    /// `self ∩ [lo, hi]`, `None` if empty.
    fn clamp_to(self, lo: f64, hi: f64) -> Option<Self>;
    /// Provably non-zero.
    fn nonzero(self) -> bool;
    /// Possibly `≤ x` (some member is).
    fn possibly_le(self, x: f64) -> bool {
        self.lower() <= x
    }
    /// Possibly `≥ x` (some member is).
    fn possibly_ge(self, x: f64) -> bool {
        self.upper() >= x
    }
    /// The smallest interval containing both.
    fn hull(self, other: Self) -> Self;
}

impl Num for Interval {
    fn pt(x: f64) -> Self {
        point(x)
    }
    fn sqrt_nonneg(self) -> Option<Self> {
        let nonneg = self.intersection(interval(0.0, f64::INFINITY));
        (!nonneg.is_empty()).then(|| nonneg.sqrt())
    }
    fn div_pieces(num: Self, den: Self) -> [Option<Self>; 2] {
        den.mul_rev_to_pair(num).map(|p| (!p.is_empty()).then_some(p))
    }
    fn clamp_to(self, lo: f64, hi: f64) -> Option<Self> {
        let c = self.intersection(interval(lo, hi));
        (!c.is_empty()).then_some(c)
    }
    fn nonzero(self) -> bool {
        !self.contains(0.0)
    }
    fn hull(self, other: Self) -> Self {
        self.convex_hull(other)
    }
}

impl Num for f64 {
    fn pt(x: f64) -> Self {
        x
    }
    fn sqrt_nonneg(self) -> Option<Self> {
        (self >= 0.0).then(|| self.sqrt())
    }
    fn div_pieces(num: Self, den: Self) -> [Option<Self>; 2] {
        let q = num / den;
        [q.is_finite().then_some(q), None]
    }
    fn clamp_to(self, lo: f64, hi: f64) -> Option<Self> {
        // No enclosure to intersect: accept values a rounding error outside.
        let tol = 1e-12 * (hi - lo).abs().max(1.0);
        (lo - tol <= self && self <= hi + tol).then(|| self.clamp(lo, hi))
    }
    fn nonzero(self) -> bool {
        self != 0.0
    }
    fn hull(self, other: Self) -> Self {
        // A float cannot hold a range; the midpoint is the f64 proposal.
        0.5 * (self + other)
    }
    // A candidate computed on a constraint curve evaluates to that curve's
    // level up to rounding: without an enclosure, compare with a relative
    // tolerance, or boundary points (all the critical points) are lost.
    fn possibly_le(self, x: f64) -> bool {
        self <= x + 1e-9 * (self.abs() + x.abs()) + f64::MIN_POSITIVE
    }
    fn possibly_ge(self, x: f64) -> bool {
        self >= x - 1e-9 * (self.abs() + x.abs()) - f64::MIN_POSITIVE
    }
}
