//! Closed intervals with exact rational endpoints: the exact kernel's
//! interval, for Krawczyk in exact arithmetic
//! ([`krawczyk::exact`](crate::solve::krawczyk::exact)) and the settling of
//! boundary roots ([`settle`](crate::solve::settle)). Every operation is
//! exact; only [`RI::mid_rounded`] and [`RI::round_out`] round, to dyadics,
//! which keeps the rationals' sizes bounded (outward, so enclosures stay
//! enclosures).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed};

type Q = BigRational;

/// A closed interval with exact rational endpoints.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RI {
    /// Lower bound.
    pub(crate) lo: Q,
    /// Upper bound.
    pub(crate) hi: Q,
}

impl RI {
    pub(crate) fn new(lo: Q, hi: Q) -> Self {
        Self { lo, hi }
    }
    pub(crate) fn point(x: Q) -> Self {
        Self { lo: x.clone(), hi: x }
    }
    pub(crate) fn add(&self, b: &Self) -> Self {
        Self::new(&self.lo + &b.lo, &self.hi + &b.hi)
    }
    pub(crate) fn sub(&self, b: &Self) -> Self {
        Self::new(&self.lo - &b.hi, &self.hi - &b.lo)
    }
    pub(crate) fn sub_point(&self, b: &Q) -> Self {
        Self::new(&self.lo - b, &self.hi - b)
    }
    pub(crate) fn scale(&self, s: &Q) -> Self {
        let (a, b) = (&self.lo * s, &self.hi * s);
        if s.is_negative() {
            Self::new(b, a)
        } else {
            Self::new(a, b)
        }
    }
    pub(crate) fn mul(&self, b: &Self) -> Self {
        let p = [&self.lo * &b.lo, &self.lo * &b.hi, &self.hi * &b.lo, &self.hi * &b.hi];
        let lo = p.iter().min().expect("four").clone();
        let hi = p.iter().max().expect("four").clone();
        Self::new(lo, hi)
    }
    pub(crate) fn width(&self) -> Q {
        &self.hi - &self.lo
    }
    pub(crate) fn meet(&self, b: &Self) -> Option<Self> {
        let lo = (&self.lo).max(&b.lo).clone();
        let hi = (&self.hi).min(&b.hi).clone();
        (lo <= hi).then(|| Self::new(lo, hi))
    }
    /// The midpoint rounded to a multiple of `2^-bits`.
    pub(crate) fn mid_rounded(&self, bits: u64) -> Q {
        let m = (&self.lo + &self.hi) / Q::from_integer(2.into());
        let s = Q::from_integer(BigInt::one() << bits);
        (m * &s).round() / s
    }
    /// Endpoints moved outward to multiples of `2^-bits`.
    pub(crate) fn round_out(&self, bits: u64) -> Self {
        let s = Q::from_integer(BigInt::one() << bits);
        Self::new((&self.lo * &s).floor() / &s, (&self.hi * &s).ceil() / &s)
    }
}
