//! The [`Scalar`] trait and its three kernels: `f64`, [`Interval`],
//! [`BigRational`].

use super::cache::MatrixCache;
use super::convert::{point, rational_to_f64, rational_to_interval};
use inari::Interval;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// What a kernel can say about the sign of a value.
///
/// For the rigorous kernels a definite answer is a proof about every member of
/// the enclosure; for `f64` it is only the sign of the rounded value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Every member is `< 0`.
    Negative,
    /// The value is exactly zero (a point interval `[0, 0]`).
    Zero,
    /// Every member is `> 0`.
    Positive,
    /// The enclosure contains values of both signs, or zero and non-zero ones.
    Straddles,
}

/// Which arithmetic a kernel performs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// Plain `f64`: round-to-nearest, may propose, never proves.
    Float,
    /// `inari::Interval`: outward rounding, proves.
    Interval,
    /// `BigRational`: exact, proves.
    Exact,
}

impl Kernel {
    /// `true` for kernels whose sign and magnitude answers are proofs.
    pub fn is_rigorous(self) -> bool {
        !matches!(self, Kernel::Float)
    }
}

/// A number type the Bernstein–Bézier algebra can run on.
///
/// Implemented for `f64`, [`Interval`] and [`BigRational`] (and sealed: the
/// algebra relies on each kernel's exact-matrix cache). Arithmetic is by
/// value (`Copy` kernels pay nothing for the clones generic code makes).
///
/// Contract for the rigorous kernels ([`Kernel::is_rigorous`]): every
/// operation returns an enclosure of the exact result for all members of its
/// inputs; [`Scalar::sign_class`] and [`Scalar::mag`] answer for every member.
pub trait Scalar:
    MatrixCache
    + Clone
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The kind of arithmetic.
    const KERNEL: Kernel;
    /// The additive identity.
    fn zero() -> Self;
    /// The multiplicative identity.
    fn one() -> Self;
    /// An integer (exact for `|n| <= 2^53` in the float kernels; the interval
    /// kernel encloses larger ones).
    fn from_i64(n: i64) -> Self;
    /// A finite float, exactly; `None` for NaN or ±∞.
    fn from_f64(x: f64) -> Option<Self>;
    /// A rational: exact (rational kernel), tightest enclosure (interval
    /// kernel, see [`rational_to_interval`]), nearest float (`f64`).
    fn from_rational(q: &BigRational) -> Self;
    /// A representative float: the value, the interval midpoint, or the
    /// nearest float to the rational.
    fn to_f64(&self) -> f64;
    /// The sign; see [`Sign`].
    fn sign_class(&self) -> Sign;
    /// An upper bound on `|x|` over the enclosure, rounded up (rigorous
    /// kernels) or to nearest (`f64`).
    fn mag(&self) -> f64;
    /// A lower bound on every member (rounded down for the rigorous kernels).
    fn lower(&self) -> f64;
    /// An upper bound on every member (rounded up for the rigorous kernels).
    fn upper(&self) -> f64;
    /// `false` if the value is NaN, infinite or an unbounded/empty interval.
    fn is_finite(&self) -> bool;
    /// `|x|` (for intervals: the enclosure of `|t|` over members `t`).
    fn abs(&self) -> Self;
    /// The larger of two values (for intervals: the enclosure of `max(s, t)`).
    fn max(self, other: Self) -> Self;
    /// A single representative as a value of this kernel: the point interval
    /// at the midpoint for intervals, the value itself otherwise.
    fn to_point(&self) -> Self;
}

impl Scalar for f64 {
    const KERNEL: Kernel = Kernel::Float;
    fn zero() -> Self {
        0.0
    }
    fn one() -> Self {
        1.0
    }
    fn from_i64(n: i64) -> Self {
        n as f64
    }
    fn from_f64(x: f64) -> Option<Self> {
        x.is_finite().then_some(x)
    }
    fn from_rational(q: &BigRational) -> Self {
        rational_to_f64(q)
    }
    fn to_f64(&self) -> f64 {
        *self
    }
    fn sign_class(&self) -> Sign {
        if *self > 0.0 {
            Sign::Positive
        } else if *self < 0.0 {
            Sign::Negative
        } else if *self == 0.0 {
            Sign::Zero
        } else {
            Sign::Straddles
        }
    }
    fn mag(&self) -> f64 {
        f64::abs(*self)
    }
    fn lower(&self) -> f64 {
        *self
    }
    fn upper(&self) -> f64 {
        *self
    }
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    fn abs(&self) -> Self {
        f64::abs(*self)
    }
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    fn to_point(&self) -> Self {
        *self
    }
}

impl Scalar for Interval {
    const KERNEL: Kernel = Kernel::Interval;
    fn zero() -> Self {
        point(0.0)
    }
    fn one() -> Self {
        point(1.0)
    }
    fn from_i64(n: i64) -> Self {
        // Integers up to 2^53 are floats: the point is the tightest enclosure,
        // as the rational route would find, without the big-integer detour.
        if n.unsigned_abs() <= 1 << 53 {
            return point(n as f64);
        }
        rational_to_interval(&BigRational::from_integer(BigInt::from(n)))
    }
    fn from_f64(x: f64) -> Option<Self> {
        x.is_finite().then(|| point(x))
    }
    fn from_rational(q: &BigRational) -> Self {
        rational_to_interval(q)
    }
    fn to_f64(&self) -> f64 {
        self.mid()
    }
    fn sign_class(&self) -> Sign {
        if self.is_empty() {
            Sign::Straddles
        } else if self.inf() > 0.0 {
            Sign::Positive
        } else if self.sup() < 0.0 {
            Sign::Negative
        } else if self.inf() == 0.0 && self.sup() == 0.0 {
            Sign::Zero
        } else {
            Sign::Straddles
        }
    }
    fn mag(&self) -> f64 {
        if self.is_empty() {
            f64::INFINITY
        } else {
            Interval::mag(*self)
        }
    }
    fn lower(&self) -> f64 {
        if self.is_empty() {
            f64::NEG_INFINITY
        } else {
            self.inf()
        }
    }
    fn upper(&self) -> f64 {
        if self.is_empty() {
            f64::INFINITY
        } else {
            self.sup()
        }
    }
    fn is_finite(&self) -> bool {
        !self.is_empty() && self.inf().is_finite() && self.sup().is_finite()
    }
    fn abs(&self) -> Self {
        Interval::abs(*self)
    }
    fn max(self, other: Self) -> Self {
        Interval::max(self, other)
    }
    fn to_point(&self) -> Self {
        let m = self.mid();
        if m.is_finite() {
            point(m)
        } else {
            *self
        }
    }
}

impl Scalar for BigRational {
    const KERNEL: Kernel = Kernel::Exact;
    fn zero() -> Self {
        <BigRational as Zero>::zero()
    }
    fn one() -> Self {
        BigRational::from_integer(BigInt::from(1))
    }
    fn from_i64(n: i64) -> Self {
        BigRational::from_integer(BigInt::from(n))
    }
    fn from_f64(x: f64) -> Option<Self> {
        BigRational::from_float(x)
    }
    fn from_rational(q: &BigRational) -> Self {
        q.clone()
    }
    fn to_f64(&self) -> f64 {
        rational_to_f64(self)
    }
    fn sign_class(&self) -> Sign {
        if self.is_positive() {
            Sign::Positive
        } else if self.is_negative() {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
    fn mag(&self) -> f64 {
        rational_to_interval(self).mag()
    }
    fn lower(&self) -> f64 {
        rational_to_interval(self).inf()
    }
    fn upper(&self) -> f64 {
        rational_to_interval(self).sup()
    }
    fn is_finite(&self) -> bool {
        true
    }
    fn abs(&self) -> Self {
        Signed::abs(self)
    }
    fn max(self, other: Self) -> Self {
        Ord::max(self, other)
    }
    fn to_point(&self) -> Self {
        self.clone()
    }
}
