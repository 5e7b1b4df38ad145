//! A small interval kernel for the rectangle solver's hot loops: each
//! endpoint is computed rounded to nearest and then moved one float outward.
//!
//! # Why it is rigorous
//! For one IEEE operation with exact result `x` and nearest result `r`,
//! `|x − r| ≤ 2⁻⁵²|r|` when `r` is normal, and `≤ 2⁻¹⁰⁷⁵` when it is
//! subnormal. Each endpoint is `r` moved outward by
//! `e = 2⁻⁵¹|r| + 2⁻¹⁰⁶⁰` ([`down`]/[`up`]): `e` covers that error twice
//! over, so the final rounded subtraction (which moves the result back by at
//! most half an ulp, `≤ 2⁻⁵³|r|(1 + 2⁻⁵⁰)`) still lands beyond `x`. No
//! branches and no rounding-mode switches (inari sets MXCSR around every
//! operation), so this is several times cheaper per operation; the price is
//! about two floats of width per endpoint more than inari's.
//!
//! An overflowed endpoint stays infinite on its own side (and `down(+∞)` is
//! `MAX`, still a lower bound of the overflowed exact value).
//!
//! # NaN
//! `∞ − ∞` and `0 · ∞` give NaN; a NaN endpoint makes every comparison false.
//! Callers must therefore state their proofs positively (`lo > 0` proves
//! positivity; `!(hi < 0)` proves nothing) and check [`Iv::is_finite`] where
//! a bound feeds a decision.

/// A float below the exact value that rounded to nearest gave `r` (module docs).
#[inline]
pub fn down(r: f64) -> f64 {
    let d = r - (r.abs() * REL + ABS);
    // `+∞ − ∞`: an exact value that overflowed upward is above MAX.
    if d.is_nan() && r == f64::INFINITY {
        f64::MAX
    } else {
        d
    }
}

/// A float above the exact value that rounded to nearest gave `r`.
#[inline]
pub fn up(r: f64) -> f64 {
    let u = r + (r.abs() * REL + ABS);
    if u.is_nan() && r == f64::NEG_INFINITY {
        -f64::MAX
    } else {
        u
    }
}

const REL: f64 = 1.0 / (1u64 << 51) as f64;
/// `≥ 2⁻¹⁰⁶⁰`: covers the absolute error of subnormal results.
const ABS: f64 = 1e-319;

/// A closed interval `[lo, hi]` (see the module docs for the rounding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iv {
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
}

impl Iv {
    /// The point interval `[x, x]`.
    #[inline]
    pub fn point(x: f64) -> Self {
        Self { lo: x, hi: x }
    }

    /// `[lo, hi]` (no check; callers pass `lo ≤ hi`).
    #[inline]
    pub fn new(lo: f64, hi: f64) -> Self {
        Self { lo, hi }
    }

    /// Both endpoints finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }

    /// `hi − lo`, rounded up.
    #[inline]
    pub fn wid(self) -> f64 {
        up(self.hi - self.lo)
    }

    /// The midpoint rounded to nearest (inside the interval when finite).
    #[inline]
    pub fn mid(self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }

    /// `a + b`.
    #[inline]
    pub fn add(self, b: Self) -> Self {
        Self {
            lo: down(self.lo + b.lo),
            hi: up(self.hi + b.hi),
        }
    }

    /// `a − b`.
    #[inline]
    pub fn sub(self, b: Self) -> Self {
        Self {
            lo: down(self.lo - b.hi),
            hi: up(self.hi - b.lo),
        }
    }

    /// `a · b`.
    #[inline]
    pub fn mul(self, b: Self) -> Self {
        let p = [self.lo * b.lo, self.lo * b.hi, self.hi * b.lo, self.hi * b.hi];
        Self {
            lo: down(p[0].min(p[1]).min(p[2]).min(p[3])),
            hi: up(p[0].max(p[1]).max(p[2]).max(p[3])),
        }
    }

    /// `a · s` for a float `s ≥ 0`.
    #[inline]
    pub fn scale(self, s: f64) -> Self {
        Self {
            lo: down(self.lo * s),
            hi: up(self.hi * s),
        }
    }

    /// `(1 − t)·a + t·b` for a float `t ∈ [0, 1]` (one de Casteljau step),
    /// without branches: each endpoint is evaluated rounded to nearest and
    /// moved outward by `e = 2⁻⁵⁰(|p| + |q|) + 2⁻¹⁰⁶⁰`, where `p = (1−t)·a`,
    /// `q = t·b` are the two products.
    ///
    /// Error budget (`u = 2⁻⁵³`): the weight `s = fl(1 − t) ≥ ½` is off by at
    /// most `u`, i.e. `2u·|p|`; the two products, the sum and the final shift
    /// by `e` each add at most `u(|p| + |q|)`; in all `≤ 5u(|p| + |q|) < e`, and
    /// `e` itself, computed rounded, is still above that (its factor is
    /// `8u`). Underflow adds at most `2⁻¹⁰⁷⁵` per operation, covered by the
    /// constant.
    #[inline]
    pub fn lerp(a: Self, b: Self, t: f64) -> Self {
        const REL: f64 = 1.0 / (1u64 << 50) as f64;
        const ABS: f64 = 1e-319;
        let s = 1.0 - t;
        let (p, q) = (a.lo * s, b.lo * t);
        let lo = (p + q) - ((p.abs() + q.abs()) * REL + ABS);
        let (p, q) = (a.hi * s, b.hi * t);
        let hi = (p + q) + ((p.abs() + q.abs()) * REL + ABS);
        Self { lo, hi }
    }

    /// `(1 − t)·a + t·b` for any float `t` (extrapolation too), through
    /// general products.
    #[inline]
    pub fn lerp_any(a: Self, b: Self, t: f64) -> Self {
        let s = Self::point(1.0).sub(Self::point(t));
        s.mul(a).add(Self::point(t).mul(b))
    }

    /// An enclosure of `{(1 − t)·x + t·y : x ∈ a, y ∈ b, t ∈ [t0, t1]}`: the
    /// hull of the two endpoint values (for fixed `x`, `y` the value is linear
    /// in `t`; over `x`, `y` its minimum is concave and its maximum convex in
    /// `t`, so both extremes are at `t0` or `t1`).
    #[inline(always)]
    pub fn lerp_range(a: Self, b: Self, t0: f64, t1: f64) -> Self {
        if t0 == t1 {
            // A point: one evaluation (the hot case of bounds at points).
            return if (0.0..=1.0).contains(&t0) {
                Self::lerp(a, b, t0)
            } else {
                Self::lerp_any(a, b, t0)
            };
        }
        let (x, y) = if (0.0..=1.0).contains(&t0) && (0.0..=1.0).contains(&t1) {
            (Self::lerp(a, b, t0), Self::lerp(a, b, t1))
        } else {
            (Self::lerp_any(a, b, t0), Self::lerp_any(a, b, t1))
        };
        x.hull(y)
    }

    /// `a / b`; the whole line when `b` contains 0.
    #[inline]
    pub fn div(self, b: Self) -> Self {
        if !(b.lo > 0.0 || b.hi < 0.0) {
            return Self::new(f64::NEG_INFINITY, f64::INFINITY);
        }
        let p = [self.lo / b.lo, self.lo / b.hi, self.hi / b.lo, self.hi / b.hi];
        Self {
            lo: down(p[0].min(p[1]).min(p[2]).min(p[3])),
            hi: up(p[0].max(p[1]).max(p[2]).max(p[3])),
        }
    }

    /// The hull of two intervals (NaN endpoints stay NaN: `f64::min` would
    /// drop them).
    #[inline]
    pub fn hull(self, b: Self) -> Self {
        let nan = self.lo.is_nan() || self.hi.is_nan() || b.lo.is_nan() || b.hi.is_nan();
        if nan {
            return Self::new(f64::NAN, f64::NAN);
        }
        Self {
            lo: self.lo.min(b.lo),
            hi: self.hi.max(b.hi),
        }
    }

    /// `true` if `self ⊂ (lo, hi)` strictly.
    #[inline]
    pub fn inside_open(self, lo: f64, hi: f64) -> bool {
        self.lo > lo && self.hi < hi
    }

    /// The intersection, or `None` when provably empty.
    #[inline]
    pub fn meet(self, b: Self) -> Option<Self> {
        let (lo, hi) = (self.lo.max(b.lo), self.hi.min(b.hi));
        (lo <= hi).then_some(Self { lo, hi })
    }
}

#[cfg(test)]
mod tests {
    use super::Iv;
    use num_rational::BigRational;
    use num_traits::FromPrimitive;

    fn q(x: f64) -> BigRational {
        BigRational::from_f64(x).unwrap()
    }

    fn contains(i: Iv, x: &BigRational) -> bool {
        let lo_ok = i.lo == f64::NEG_INFINITY || (i.lo.is_finite() && q(i.lo) <= *x);
        let hi_ok = i.hi == f64::INFINITY || (i.hi.is_finite() && *x <= q(i.hi));
        lo_ok && hi_ok
    }

    /// Deterministic operands spanning signs, magnitudes and subnormals.
    fn operands() -> Vec<f64> {
        let mut v = vec![
            0.0, -0.0, 1.0, -1.0, 0.1, -0.3, 1e-300, -5e-324, 3e-310, 1e300, -7.25e18,
        ];
        let mut x = 0.123_456_789_f64;
        for _ in 0..40 {
            x = (x * 7919.0 + 0.377).fract();
            v.push((x - 0.5) * 10f64.powi((x * 40.0) as i32 - 20));
        }
        v
    }

    #[test]
    fn operations_enclose_the_exact_results() {
        let ops = operands();
        for &a in &ops {
            for &b in &ops {
                let (ia, ib) = (Iv::point(a), Iv::point(b));
                let (qa, qb) = (q(a), q(b));
                assert!(contains(ia.add(ib), &(&qa + &qb)), "{a} + {b}");
                assert!(contains(ia.sub(ib), &(&qa - &qb)), "{a} - {b}");
                assert!(contains(ia.mul(ib), &(&qa * &qb)), "{a} * {b}");
                if b >= 0.0 {
                    assert!(contains(ia.scale(b), &(&qa * &qb)), "{a} scale {b}");
                }
                if b != 0.0 {
                    assert!(contains(ia.div(ib), &(&qa / &qb)), "{a} / {b}");
                }
                for t in [-0.75, 1.5, 0.25] {
                    let qt = q(t);
                    let exact = (BigRational::from_integer(1.into()) - &qt) * &qa + &qt * &qb;
                    assert!(contains(Iv::lerp_any(ia, ib, t), &exact), "lerp_any {a} {b} {t}");
                }
                for t in [0.0, 0.3, 0.5, 0.7109375, 1.0, 1e-17] {
                    let qt = q(t);
                    let exact = (BigRational::from_integer(1.into()) - &qt) * &qa + &qt * &qb;
                    assert!(contains(Iv::lerp(ia, ib, t), &exact), "lerp {a} {b} {t}");
                }
            }
        }
    }

    #[test]
    fn lerp_range_encloses_every_parameter() {
        let (a, b) = (Iv::new(-1.0, 0.5), Iv::new(2.0, 2.25));
        for (t0, t1) in [(0.25, 0.75), (-0.5, 0.1), (0.9, 1.7)] {
            let r = Iv::lerp_range(a, b, t0, t1);
            for k in 0..=16 {
                let t = t0 + (t1 - t0) * k as f64 / 16.0;
                for x in [a.lo, a.hi] {
                    for y in [b.lo, b.hi] {
                        let exact = (BigRational::from_integer(1.into()) - q(t)) * q(x) + q(t) * q(y);
                        assert!(contains(r, &exact), "{t}");
                    }
                }
            }
        }
    }

    #[test]
    fn lerp_encloses_every_point_of_interval_operands() {
        let a = Iv::new(-1.5, 0.25);
        let b = Iv::new(2.0, 3.0);
        let t = 0.3;
        let r = Iv::lerp(a, b, t);
        for x in [-1.5, 0.25] {
            for y in [2.0, 3.0] {
                let exact = (BigRational::from_integer(1.into()) - q(t)) * q(x) + q(t) * q(y);
                assert!(contains(r, &exact));
            }
        }
    }
}
