//! Closed intervals with exact rational endpoints: the exact kernel's
//! interval, for Krawczyk in exact arithmetic
//! ([`krawczyk::exact`](crate::solve::krawczyk::exact)) and the settling of
//! boundary roots ([`settle`](crate::solve::settle)). Every operation is
//! exact; only [`RI::mid_rounded`] and [`RI::round_out`] round, to dyadics,
//! which keeps the rationals' sizes bounded (outward, so enclosures stay
//! enclosures).
//!
//! # Dyadics without gcds
//! A [`BigRational`] is kept reduced: every operation ends in a gcd of its
//! numerator and denominator, and num-bigint's (binary, allocating) gcd
//! costs about 250 multiplications of the same numbers (15 µs at 400 bits
//! against 60 ns). The operations here ([`q_add`], [`q_sub`], [`q_mul`],
//! [`round_to`]) take a fast path when both operands are *dyadic* (the
//! denominator a power of two): the result is then dyadic too, and reducing
//! it needs only its trailing zero bits. The exact systems are scaled to
//! integer coefficients (`settle`), box ends are floats and the rounded
//! midpoints, inverses and endpoints are dyadic, so every operation of an
//! exact Krawczyk step takes that path. Anything else falls back to
//! num-rational, with the same (exact) result.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

type Q = BigRational;

/// `k` when `q = n/2^k` in lowest terms (its denominator a power of two).
fn dyadic_exp(q: &Q) -> Option<u64> {
    let d = q.denom();
    let tz = d.trailing_zeros()?;
    (d.bits() == tz + 1).then_some(tz)
}

/// `n/2^k` in lowest terms: only a power of two can divide both.
fn dyadic(n: BigInt, k: u64) -> Q {
    if n.is_zero() {
        return Q::zero();
    }
    let s = n.trailing_zeros().expect("non-zero").min(k);
    Q::new_raw(n >> s, BigInt::one() << (k - s))
}

/// `a + b`, exactly.
pub(crate) fn q_add(a: &Q, b: &Q) -> Q {
    match (dyadic_exp(a), dyadic_exp(b)) {
        (Some(ka), Some(kb)) => {
            let k = ka.max(kb);
            dyadic((a.numer() << (k - ka)) + (b.numer() << (k - kb)), k)
        }
        _ => a + b,
    }
}

/// `a − b`, exactly.
pub(crate) fn q_sub(a: &Q, b: &Q) -> Q {
    match (dyadic_exp(a), dyadic_exp(b)) {
        (Some(ka), Some(kb)) => {
            let k = ka.max(kb);
            dyadic((a.numer() << (k - ka)) - (b.numer() << (k - kb)), k)
        }
        _ => a - b,
    }
}

/// `a · b`, exactly.
pub(crate) fn q_mul(a: &Q, b: &Q) -> Q {
    match (dyadic_exp(a), dyadic_exp(b)) {
        (Some(ka), Some(kb)) => dyadic(a.numer() * b.numer(), ka + kb),
        _ => a * b,
    }
}

/// How [`round_to`] rounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Round {
    /// Towards −∞.
    Down,
    /// Towards +∞.
    Up,
    /// To the nearest, a tie away from zero (as `BigRational::round`).
    Nearest,
}

/// `q` rounded to a multiple of `2^-bits` in the direction `mode`.
pub(crate) fn round_to(q: &Q, bits: u64, mode: Round) -> Q {
    match dyadic_exp(q) {
        Some(k) if k <= bits => q.clone(),
        Some(k) => round_ratio(q.numer().clone(), BigInt::one() << (k - bits), bits, mode),
        None => round_ratio(q.numer() << bits, q.denom().clone(), bits, mode),
    }
}

/// `a / b` rounded to a multiple of `2^-bits` (`b ≠ 0`), without forming
/// the reduced quotient.
pub(crate) fn div_round(a: &Q, b: &Q, bits: u64, mode: Round) -> Q {
    let n = a.numer() * b.denom();
    let d = a.denom() * b.numer();
    let (n, d) = if d.is_negative() { (-n, -d) } else { (n, d) };
    round_ratio(n << bits, d, bits, mode)
}

/// `round(n/d)/2^bits` for `d > 0`, by integer division.
fn round_ratio(n: BigInt, d: BigInt, bits: u64, mode: Round) -> Q {
    let r = match mode {
        Round::Down => n.div_floor(&d),
        Round::Up => n.div_ceil(&d),
        Round::Nearest => {
            let twice = &d * 2;
            if n.is_negative() {
                let m: BigInt = -n * 2 + &d;
                -m.div_floor(&twice)
            } else {
                let m: BigInt = n * 2 + &d;
                m.div_floor(&twice)
            }
        }
    };
    dyadic(r, bits)
}

/// `a` against `b`, by one cross multiplication (the denominators of a
/// reduced [`BigRational`] are positive). num-rational's `Ord` compares the
/// continued fraction expansions term by term, and the terms of two nearly
/// equal numbers agree for as long as the numbers do: on the ends of a box
/// 2⁻⁴⁰⁰⁰ wide, thousands of bigint divisions per comparison.
pub(crate) fn cmp(a: &Q, b: &Q) -> Ordering {
    if a.denom() == b.denom() {
        return a.numer().cmp(b.numer());
    }
    (a.numer() * b.denom()).cmp(&(b.numer() * a.denom()))
}

/// The smaller of `a` and `b` by [`cmp`].
fn min_q<'a>(a: &'a Q, b: &'a Q) -> &'a Q {
    if cmp(a, b) == Ordering::Greater {
        b
    } else {
        a
    }
}

/// The larger of `a` and `b` by [`cmp`].
fn max_q<'a>(a: &'a Q, b: &'a Q) -> &'a Q {
    if cmp(a, b) == Ordering::Less {
        b
    } else {
        a
    }
}

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
        Self::new(q_add(&self.lo, &b.lo), q_add(&self.hi, &b.hi))
    }
    pub(crate) fn sub(&self, b: &Self) -> Self {
        Self::new(q_sub(&self.lo, &b.hi), q_sub(&self.hi, &b.lo))
    }
    pub(crate) fn sub_point(&self, b: &Q) -> Self {
        Self::new(q_sub(&self.lo, b), q_sub(&self.hi, b))
    }
    pub(crate) fn scale(&self, s: &Q) -> Self {
        let (a, b) = (q_mul(&self.lo, s), q_mul(&self.hi, s));
        if s.is_negative() {
            Self::new(b, a)
        } else {
            Self::new(a, b)
        }
    }
    pub(crate) fn mul(&self, b: &Self) -> Self {
        if self.lo == self.hi && b.lo == b.hi {
            return Self::point(q_mul(&self.lo, &b.lo));
        }
        let p = [
            q_mul(&self.lo, &b.lo),
            q_mul(&self.lo, &b.hi),
            q_mul(&self.hi, &b.lo),
            q_mul(&self.hi, &b.hi),
        ];
        let lo = p.iter().fold(&p[0], |m, x| min_q(m, x)).clone();
        let hi = p.iter().fold(&p[0], |m, x| max_q(m, x)).clone();
        Self::new(lo, hi)
    }
    pub(crate) fn width(&self) -> Q {
        q_sub(&self.hi, &self.lo)
    }
    pub(crate) fn meet(&self, b: &Self) -> Option<Self> {
        let lo = max_q(&self.lo, &b.lo).clone();
        let hi = min_q(&self.hi, &b.hi).clone();
        (cmp(&lo, &hi) != Ordering::Greater).then(|| Self::new(lo, hi))
    }
    /// The midpoint rounded to a multiple of `2^-bits`.
    pub(crate) fn mid_rounded(&self, bits: u64) -> Q {
        let sum = q_add(&self.lo, &self.hi);
        round_to(
            &q_mul(&sum, &Q::new_raw(BigInt::one(), BigInt::from(2))),
            bits,
            Round::Nearest,
        )
    }
    /// Endpoints moved outward to multiples of `2^-bits`.
    pub(crate) fn round_out(&self, bits: u64) -> Self {
        Self::new(
            round_to(&self.lo, bits, Round::Down),
            round_to(&self.hi, bits, Round::Up),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples() -> Vec<Q> {
        let mut vals: Vec<Q> = Vec::new();
        for n in -9i64..=9 {
            for d in [1i64, 2, 3, 4, 6, 8, 10, 16, 1024] {
                vals.push(Q::new(n.into(), d.into()));
            }
        }
        let big = Q::new(BigInt::one(), BigInt::one() << 300);
        let third = Q::new(1.into(), 3.into());
        vals.extend([
            &third + &big,
            &third - &big,
            -(&third + &big),
            big.clone(),
            -&big,
            &big * BigInt::from(3) + Q::one(),
        ]);
        vals
    }

    /// The dyadic fast paths give num-rational's results, reduced (so `==`
    /// and hashing stay meaningful), on dyadic and other operands.
    #[test]
    fn fast_operations_agree_with_num_rational() {
        let vals = samples();
        let reduced = |q: &Q| q.numer().gcd(q.denom()).is_one() && q.denom().is_positive();
        for a in &vals {
            for b in &vals {
                for (got, want) in [(q_add(a, b), a + b), (q_sub(a, b), a - b), (q_mul(a, b), a * b)] {
                    assert_eq!(got, want, "{a}, {b}");
                    assert!(reduced(&got), "{got}");
                }
            }
            for bits in [0u64, 1, 3, 10, 64, 400] {
                let s = Q::from_integer(BigInt::one() << bits);
                let (lo, hi, near) = (
                    round_to(a, bits, Round::Down),
                    round_to(a, bits, Round::Up),
                    round_to(a, bits, Round::Nearest),
                );
                assert_eq!(lo, (a * &s).floor() / &s, "{a} {bits}");
                assert_eq!(hi, (a * &s).ceil() / &s, "{a} {bits}");
                assert_eq!(near, (a * &s).round() / &s, "{a} {bits}");
                assert!(reduced(&lo) && reduced(&hi) && reduced(&near));
                for b in vals.iter().filter(|b| !b.is_zero()) {
                    for mode in [Round::Down, Round::Up, Round::Nearest] {
                        assert_eq!(div_round(a, b, bits, mode), round_to(&(a / b), bits, mode), "{a} / {b}");
                    }
                }
            }
        }
    }

    /// [`cmp`] agrees with num-rational's `Ord` (including nearly equal
    /// numbers, negative ones and equal denominators).
    #[test]
    fn cmp_agrees_with_ord() {
        let vals = samples();
        for a in &vals {
            for b in &vals {
                assert_eq!(cmp(a, b), a.cmp(b), "{a} vs {b}");
            }
        }
    }
}
