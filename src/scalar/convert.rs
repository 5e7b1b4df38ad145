//! Conversions between the kernels: rationals to floats and to their
//! tightest enclosing intervals.

use inari::Interval;

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

/// The point interval `[x, x]`. `x` must be finite (the caller's invariant).
pub(crate) fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
}

/// The interval `[lo, hi]`; the entire line if the bounds are NaN or reversed
/// (always an enclosure, never a panic).
pub(crate) fn interval(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE)
}

/// The nearest `f64` to `q` (ties to even); ±∞ beyond the float range.
pub fn rational_to_f64(q: &BigRational) -> f64 {
    match ToPrimitive::to_f64(q) {
        Some(x) if !x.is_nan() => x,
        _ if q.is_negative() => f64::NEG_INFINITY,
        _ => f64::INFINITY,
    }
}

/// The tightest interval `[lo, hi]` with `f64` endpoints that contains `q`.
///
/// Exact when `q` is a float (a point interval); otherwise `lo` and `hi` are
/// adjacent floats with `lo < q < hi`. Beyond the float range the outer end is
/// infinite (`[f64::MAX, +∞]`).
///
/// ```
/// use num_rational::BigRational;
/// use rootclip::scalar::rational_to_interval;
/// let tenth = BigRational::new(1.into(), 10.into());
/// let x = rational_to_interval(&tenth);
/// assert!(x.inf() < 0.1 && 0.1 <= x.sup() || x.inf() <= 0.1 && 0.1 < x.sup());
/// assert_eq!(x.sup().next_down(), x.inf());
/// ```
pub fn rational_to_interval(q: &BigRational) -> Interval {
    if let Some(x) = small_rational_to_interval(q).or_else(|| dyadic_to_interval(q)) {
        return x;
    }
    let approx = rational_to_f64(q);
    if !approx.is_finite() {
        return if q.is_negative() {
            interval(f64::NEG_INFINITY, -f64::MAX)
        } else {
            interval(f64::MAX, f64::INFINITY)
        };
    }
    let exact = |x: f64| BigRational::from_float(x).expect("finite float");
    let back = exact(approx);
    if &back == q {
        return point(approx);
    }
    // `to_f64` is correctly rounded in num-rational 0.4, but the bracket is
    // verified exactly rather than trusted, so this stays an enclosure even if
    // the conversion were off by more than an ulp.
    if &back < q {
        let mut hi = approx.next_up();
        while hi.is_finite() && &exact(hi) < q {
            hi = hi.next_up();
        }
        let lo = if hi.is_finite() { hi.next_down() } else { approx };
        interval(lo, hi)
    } else {
        let mut lo = approx.next_down();
        while lo.is_finite() && &exact(lo) > q {
            lo = lo.next_down();
        }
        let hi = if lo.is_finite() { lo.next_up() } else { approx };
        interval(lo, hi)
    }
}

/// [`rational_to_interval`] for `q = n/d` with `|n|, d ≤ 2⁵³` (both exact in
/// `f64`), without big-integer work: the nearest quotient `x = n ⊘ d` has the
/// exact remainder `r = n − x·d` (one FMA; exact for a correctly rounded
/// quotient of floats, Boldo–Muller), and `n/d − x = r/d` with `d > 0`
/// (num-rational keeps denominators positive), so the sign of `r` says on
/// which side of `x` the rational lies — and the adjacent float on that side
/// closes the tightest bracket. `None` outside that range.
fn small_rational_to_interval(q: &BigRational) -> Option<Interval> {
    const EXACT: u64 = 1 << 53;
    let (n, d) = (q.numer().to_i64()?, q.denom().to_i64()?);
    if n.unsigned_abs() > EXACT || d <= 0 || d as u64 > EXACT {
        return None;
    }
    let (n, d) = (n as f64, d as f64);
    let x = n / d;
    let r = (-x).mul_add(d, n);
    Some(if r == 0.0 {
        point(x)
    } else if r > 0.0 {
        interval(x, x.next_up())
    } else {
        interval(x.next_down(), x)
    })
}

/// [`rational_to_interval`] for a dyadic `q = n / 2^k` whose enclosure has
/// normal float endpoints (exact sums and products of floats, the common
/// exact input), with integer operations only: the 53 leading bits `m` of
/// `|n|` give `m·2^e ≤ |q| < (m + 1)·2^e`, both floats, equal bounds when
/// the dropped bits are zero. `None` for other rationals (and near the
/// subnormal and overflow ranges).
fn dyadic_to_interval(q: &BigRational) -> Option<Interval> {
    let d = q.denom();
    let k = d.trailing_zeros()?;
    if d.bits() != k + 1 {
        return None; // not a power of two
    }
    let n = q.numer().magnitude();
    let bits = n.bits();
    if bits == 0 {
        return Some(point(0.0));
    }
    // |q| = m·2^e + rest, m with exactly 53 bits.
    let (m, exact, e) = if bits > 53 {
        let shift = bits - 53;
        let m = n >> shift;
        let exact = n.trailing_zeros().is_some_and(|z| z >= shift);
        (m.to_u64()?, exact, shift as i64 - k as i64)
    } else {
        (n.to_u64()? << (53 - bits), true, -(k as i64) - (53 - bits) as i64)
    };
    // m·2^e is a normal float iff its biased exponent e + 52 + 1023 is in 1..=2046.
    let biased = e + 1075;
    if !(1..=2045).contains(&biased) {
        return None;
    }
    let lo = f64::from_bits(((biased as u64) << 52) | (m & ((1 << 52) - 1)));
    let hi = if exact { lo } else { lo.next_up() };
    Some(if q.is_negative() {
        interval(-hi, -lo)
    } else {
        interval(lo, hi)
    })
}

#[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
/// `true` if the interval `x` contains the rational `q` (exact comparison).
pub(crate) fn interval_contains_rational(x: Interval, q: &BigRational) -> bool {
    if x.is_empty() {
        return false;
    }
    let below = match BigRational::from_float(x.inf()) {
        Some(lo) => &lo <= q,
        None => x.inf() == f64::NEG_INFINITY,
    };
    let above = match BigRational::from_float(x.sup()) {
        Some(hi) => q <= &hi,
        None => x.sup() == f64::INFINITY,
    };
    below && above
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Scalar, Sign};
    use num_bigint::BigInt;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    #[test]
    fn tenth_is_not_a_point() {
        let x = rational_to_interval(&q(1, 10));
        assert!(x.inf() < x.sup());
        assert_eq!(x.inf().next_up(), x.sup());
        assert!(interval_contains_rational(x, &q(1, 10)));
    }

    /// The small-rational fast path gives exactly the interval of the
    /// exact bracket search, including near the ends of its range.
    #[test]
    fn small_rationals_match_the_exact_bracket() {
        let slow = |q: &BigRational| {
            let approx = rational_to_f64(q);
            let back = BigRational::from_float(approx).unwrap();
            if &back == q {
                (approx, approx)
            } else if &back < q {
                (approx, approx.next_up())
            } else {
                (approx.next_down(), approx)
            }
        };
        let big = 1i64 << 53;
        let mut rng = crate::rng::Rng(0x9e3779b97f4a7c15);
        let mut next = || rng.next_u64() >> 11;
        let mut cases: Vec<(i64, i64)> = vec![
            (0, 1),
            (1, 3),
            (-1, 3),
            (big, 3),
            (-big, big - 1),
            (big - 1, big),
            (7, big),
        ];
        for _ in 0..20_000 {
            let n = (next() % (2 * big as u64 + 1)) as i64 - big;
            let d = 1 + (next() % big as u64) as i64;
            let small = 1 + (next() % 1000) as i64;
            cases.push((n, d));
            cases.push((n % 1000, small));
        }
        for (n, d) in cases {
            let q = BigRational::new(n.into(), d.into());
            let x = small_rational_to_interval(&q).expect("in range");
            assert_eq!((x.inf(), x.sup()), slow(&q), "{n}/{d}");
            assert!(interval_contains_rational(x, &q));
        }
        // Beyond 2^53 the exact path takes over.
        assert!(small_rational_to_interval(&q(big + 1, 2)).is_none());
    }

    /// The dyadic fast path gives exactly the slow path's interval.
    #[test]
    fn dyadics_match_the_exact_bracket() {
        let slow = |q: &BigRational| {
            let approx = rational_to_f64(q);
            let exact = |x: f64| BigRational::from_float(x).unwrap();
            if exact(approx) == *q {
                (approx, approx)
            } else if exact(approx) < *q {
                (approx, approx.next_up())
            } else {
                (approx.next_down(), approx)
            }
        };
        let mut rng = crate::rng::Rng(0x2545f4914f6cdd1d);
        let mut cases = Vec::new();
        for _ in 0..20_000 {
            // Sums and products of random floats of random magnitudes.
            let x = |r: &mut crate::rng::Rng| {
                let e = (r.next_u64() % 120) as i32 - 60;
                BigRational::from_float(r.next_signed() * 2f64.powi(e)).unwrap()
            };
            let (a, b, c) = (x(&mut rng), x(&mut rng), x(&mut rng));
            cases.push(&a * &b - &c);
            cases.push(&a + &b * &c);
        }
        let big = BigRational::from_integer(BigInt::from(1) << 1100u32);
        cases.push(BigRational::from_float(f64::MAX).unwrap());
        cases.push(BigRational::from_float(f64::MIN_POSITIVE).unwrap() * BigRational::new(3.into(), 4.into()));
        cases.push(
            BigRational::new(1.into(), BigInt::from(1) << 1000u32)
                + BigRational::new(1.into(), BigInt::from(1) << 1100u32),
        );
        cases.push(big);
        let mut fast = 0;
        for q in cases {
            let x = rational_to_interval(&q);
            if dyadic_to_interval(&q).is_some() {
                fast += 1;
            }
            if x.sup().is_finite() && x.inf().is_finite() {
                assert_eq!((x.inf(), x.sup()), slow(&q), "{q}");
            }
            assert!(interval_contains_rational(x, &q), "{q}");
        }
        assert!(fast > 30_000);
    }

    #[test]
    fn dyadic_is_a_point() {
        let x = rational_to_interval(&q(-3, 8));
        assert_eq!((x.inf(), x.sup()), (-0.375, -0.375));
        assert_eq!(x.sign_class(), Sign::Negative);
    }

    #[test]
    fn huge_and_tiny() {
        let big = BigRational::from_integer(BigInt::from(10).pow(400));
        let x = rational_to_interval(&big);
        assert_eq!(x.sup(), f64::INFINITY);
        assert!(interval_contains_rational(x, &big));
        let tiny = BigRational::new(1.into(), BigInt::from(10).pow(400));
        let y = rational_to_interval(&tiny);
        assert!(y.inf() == 0.0 && y.sup() > 0.0);
        assert!(interval_contains_rational(y, &tiny));
        assert_eq!(y.sign_class(), Sign::Straddles);
    }

    #[test]
    fn signs() {
        assert_eq!(interval(-1.0, 1.0).sign_class(), Sign::Straddles);
        assert_eq!(interval(0.0, 0.0).sign_class(), Sign::Zero);
        assert_eq!(Interval::EMPTY.sign_class(), Sign::Straddles);
        assert_eq!(Interval::ENTIRE.mag(), f64::INFINITY);
        assert_eq!(<f64 as Scalar>::sign_class(&f64::NAN), Sign::Straddles);
        assert_eq!(<BigRational as Scalar>::from_f64(f64::NAN), None);
    }
}
