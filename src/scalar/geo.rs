//! The arithmetic of the clipping geometry ([`Geo`]): field operations, square
//! roots, two-piece division, "possibly" comparisons.
//!
//! Three kernels: [`GeoIv`] (the certified solver's: every answer is a proof
//! about all members, with inari's endpoints but no rounding-mode switches),
//! [`Interval`] (inari itself, the reference `GeoIv` is tested against) and
//! `f64` (the same iteration without proofs, used to measure the cost of
//! rigor). The `possibly_*` predicates are the conservative direction: for
//! intervals they answer `true` unless the opposite is proven.

use super::convert::{interval, point};
use super::eft::{add_up, mul_up, round_up, select};
use super::iv::{down, up, Iv};
use super::kernel::{Scalar, Sign};
use inari::Interval;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// The arithmetic of the fat-curve candidate geometry: the field operations
/// and the few queries the candidate enumeration makes. For a rigorous kernel
/// every value is an enclosure and every `lower`/`upper` a bound on all its
/// members; the float kernel answers with the value itself (and tolerances
/// where an enclosure would be).
pub trait Geo:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    /// `true` if the answers are proofs.
    const RIGOROUS: bool;
    /// The point value `x` (finite).
    fn pt(x: f64) -> Self;
    /// A lower bound of every member (`−∞` when none is known).
    fn lower(self) -> f64;
    /// An upper bound of every member (`+∞` when none is known).
    fn upper(self) -> f64;
    /// An upper bound of `|x|` over the members (`+∞` when none is known).
    fn mag(self) -> f64;
    /// A lower bound of `|x|` over the members.
    fn mig(self) -> f64;
    /// The sign shared by every member.
    fn sign_class(self) -> Sign;
    /// Provably non-zero.
    fn nonzero(self) -> bool;
    /// `√(x ∩ [0, ∞))`, or `None` when `x < 0` provably.
    fn sqrt_nonneg(self) -> Option<Self>;
    /// `num / den` as at most two pieces (two when `den` straddles 0).
    /// Pieces are `None` when empty.
    fn div_pieces(num: Self, den: Self) -> [Option<Self>; 2];
    /// `self ∩ [lo, hi]`, `None` if empty.
    fn clamp_to(self, lo: f64, hi: f64) -> Option<Self>;
    /// The smallest enclosure of both (the midpoint for floats).
    fn hull(self, other: Self) -> Self;
    /// Possibly `≤ x` (some member is).
    fn possibly_le(self, x: f64) -> bool {
        self.lower() <= x
    }
    /// Possibly `≥ x` (some member is).
    fn possibly_ge(self, x: f64) -> bool {
        self.upper() >= x
    }
}

impl Geo for f64 {
    const RIGOROUS: bool = false;
    fn pt(x: f64) -> Self {
        x
    }
    fn lower(self) -> f64 {
        self
    }
    fn upper(self) -> f64 {
        self
    }
    fn mag(self) -> f64 {
        self.abs()
    }
    fn mig(self) -> f64 {
        self.abs()
    }
    fn sign_class(self) -> Sign {
        Scalar::sign_class(&self)
    }
    fn nonzero(self) -> bool {
        self != 0.0
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

/// inari's intervals as a geometry kernel: the reference the fast kernel
/// [`GeoIv`] is tested against.
impl Geo for Interval {
    const RIGOROUS: bool = true;
    fn pt(x: f64) -> Self {
        point(x)
    }
    fn lower(self) -> f64 {
        Scalar::lower(&self)
    }
    fn upper(self) -> f64 {
        Scalar::upper(&self)
    }
    fn mag(self) -> f64 {
        Scalar::mag(&self)
    }
    fn mig(self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            Interval::mig(self)
        }
    }
    fn sign_class(self) -> Sign {
        Scalar::sign_class(&self)
    }
    fn nonzero(self) -> bool {
        !self.contains(0.0)
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
    fn hull(self, other: Self) -> Self {
        self.convex_hull(other)
    }
}

/// An enclosure `[lo, hi]`: the interval kernel's [`Geo`], with the same
/// endpoints as inari's operations but without inari's rounding-mode switches.
///
/// # Why the endpoints are inari's
/// Each endpoint is computed rounded to nearest together with its exact
/// rounding error — TwoSum for sums, one FMA for products, the FMA remainder
/// `a − q·b` for quotients and `x − s²` for square roots (all exact for
/// operands in the ranges checked below: Boldo and Muller, *Exact and
/// approximated error of the FMA*, IEEE TC 2011) — and moved one float
/// outward when that error points outward. A directed rounding of an exact
/// value is unique, so each endpoint is the float inari computes (checked
/// against inari by the tests below). Keeping inari's endpoints keeps the
/// exact cases exact: a difference of equal points is `[0, 0]`, which the
/// degenerate-case tests of the candidate geometry rely on (a widened zero
/// would send a degenerate line to the "whole segment" fallback).
///
/// The pair is stored as `[−lo, hi]` (inari's own layout): rounding outward
/// is then rounding *up* in both lanes, the same code on both, which the
/// compiler turns into two-lane vector instructions (as in
/// `scalar::endpoints`, the same technique for the Bernstein kernels).
///
/// Operands outside the ranges (huge, tiny, infinite) go to `Iv`'s
/// operations instead: outward by a relative `2⁻⁵¹` plus a tiny absolute
/// term, also rigorous, just not inari's floats.
///
/// A NaN endpoint (from `∞ − ∞` or `0 · ∞` there) means "unknown": `lower`
/// and `upper` report it as `∓∞`, so every decision stays conservative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeoIv([f64; 2]);

/// Sums of operands up to this size cannot overflow inside TwoSum.
const ADD_MAX: f64 = 1.0e300;
/// Non-zero operands of products, quotients and square roots in
/// `[2^−480, 2^480]` give results and exact error terms far from overflow and
/// from the subnormals.
const EXACT_MIN: f64 = f64::from_bits((1023 - 480) << 52);
const EXACT_MAX: f64 = f64::from_bits((1023 + 480) << 52);

#[inline(always)]
fn add_safe(x: [f64; 2], y: [f64; 2]) -> bool {
    let ok = |v: f64| v.abs() <= ADD_MAX;
    ok(x[0]) & ok(x[1]) & ok(y[0]) & ok(y[1])
}

#[inline(always)]
fn exact_safe(v: f64) -> bool {
    let m = v.abs();
    (m == 0.0) | (EXACT_MIN..=EXACT_MAX).contains(&m)
}

#[inline(always)]
fn exact_safe2(x: [f64; 2], y: [f64; 2]) -> bool {
    exact_safe(x[0]) & exact_safe(x[1]) & exact_safe(y[0]) & exact_safe(y[1])
}

/// `a / b` rounded up (`b ≠ 0`, both [`exact_safe`]): the remainder
/// `a − q·b` of the nearest quotient is exact, and `a/b − q` is it over `b`.
#[inline(always)]
fn div_up(a: f64, b: f64) -> f64 {
    let q = a / b;
    let r = (-q).mul_add(b, a);
    round_up(q, if b > 0.0 { r } else { -r })
}

impl GeoIv {
    /// The enclosure `[lo, hi]` (`lo ≤ hi`).
    #[inline]
    pub fn new(lo: f64, hi: f64) -> Self {
        Self([-lo, hi])
    }

    /// The same set as `x` (the empty interval, which no caller passes,
    /// becomes the whole line: a superset, so still an enclosure).
    pub fn of(x: Interval) -> Self {
        if x.is_empty() {
            Self::ENTIRE
        } else {
            Self::new(x.inf(), x.sup())
        }
    }

    const ENTIRE: Self = Self([f64::INFINITY, f64::INFINITY]);

    #[inline(always)]
    fn lo(self) -> f64 {
        -self.0[0]
    }

    #[inline(always)]
    fn hi(self) -> f64 {
        self.0[1]
    }

    #[inline]
    fn iv(self) -> Iv {
        Iv::new(self.lo(), self.hi())
    }

    #[inline]
    fn of_iv(x: Iv) -> Self {
        Self::new(x.lo, x.hi)
    }

    fn has_nan(self) -> bool {
        self.0[0].is_nan() || self.0[1].is_nan()
    }

    /// `{x / y : x ∈ num, y ∈ den, y ≠ 0}` for `den ∋ 0` (and `num`, `den`
    /// without NaN): at most two unbounded pieces, as inari's
    /// `mul_rev_to_pair`. The finite ends are quotients of endpoints,
    /// rounded outward ([`iv::down`](crate::scalar::iv::down)/`up` after a
    /// nearest division: rigorous, though possibly a float wider than inari's).
    fn div_through_zero(num: Self, den: Self) -> [Option<Self>; 2] {
        let (a, b, c, d) = (num.lo(), num.hi(), den.lo(), den.hi());
        let (inf, ninf) = (f64::INFINITY, f64::NEG_INFINITY);
        if a <= 0.0 && b >= 0.0 {
            return [Some(Self::ENTIRE), None];
        }
        if c == 0.0 && d == 0.0 {
            return [None, None];
        }
        // num > 0: the quotient is ≤ a/c on the negative side of den and
        // ≥ a/d on the positive side; num < 0 mirrors this with b.
        let (lower_piece, upper_piece) = if a > 0.0 {
            ((c < 0.0).then(|| up(a / c)), (d > 0.0).then(|| down(a / d)))
        } else {
            ((d > 0.0).then(|| up(b / d)), (c < 0.0).then(|| down(b / c)))
        };
        [
            lower_piece.map(|hi| Self::new(ninf, hi)),
            upper_piece.map(|lo| Self::new(lo, inf)),
        ]
    }
}

impl Add for GeoIv {
    type Output = Self;
    /// `[−a; b] + [−c; d]` rounded up.
    #[inline]
    fn add(self, y: Self) -> Self {
        if !add_safe(self.0, y.0) {
            return Self::of_iv(self.iv().add(y.iv()));
        }
        Self(add_up(self.0, y.0))
    }
}

impl Sub for GeoIv {
    type Output = Self;
    /// `[−a; b] + [d; −c]` rounded up.
    #[inline]
    fn sub(self, y: Self) -> Self {
        self + -y
    }
}

impl Mul for GeoIv {
    type Output = Self;
    /// The extreme corner products, rounded outward (rounding is monotone,
    /// so the extreme of the rounded products is inari's rounded extreme).
    /// With `x = [a, b]` and `t` an end of `y`, the smaller of `a·t`, `b·t`
    /// is `a·t` if `t ≥ 0` and `b·t` otherwise, so the low end is
    /// `min(x_c·c, x_d·d)` with `x_t` chosen by the sign of `t`, and the high
    /// end alike; when `x ≥ 0` one product per end suffices (the low end at
    /// `c`, the high end at `d`).
    #[inline(always)]
    fn mul(self, y: Self) -> Self {
        if !exact_safe2(self.0, y.0) {
            return Self::of_iv(self.iv().mul(y.iv()));
        }
        let (a, b) = (self.lo(), self.hi());
        let [neg_c, d] = y.0;
        let (c_pos, d_pos) = (neg_c <= 0.0, d >= 0.0);
        // In the [−lo; hi] layout: −lo ≥ x_c·(−c) and hi ≥ x_d·d.
        let first = mul_up([select(c_pos, a, b), select(d_pos, b, a)], [neg_c, d]);
        if a >= 0.0 {
            return Self(first);
        }
        let second = mul_up([select(d_pos, a, b), select(c_pos, b, a)], [-d, -neg_c]);
        let max = |p: f64, q: f64| if p > q { p } else { q };
        Self([max(first[0], second[0]), max(first[1], second[1])])
    }
}

/// The whole line when the divisor contains 0.
impl Div for GeoIv {
    type Output = Self;
    /// The extreme endpoint quotients, rounded outward (as inari).
    #[inline]
    fn div(self, y: Self) -> Self {
        let (a, b, c, d) = (self.lo(), self.hi(), y.lo(), y.hi());
        if !(c > 0.0 || d < 0.0) {
            return Self::ENTIRE;
        }
        if !exact_safe2(self.0, y.0) {
            return Self::of_iv(self.iv().div(y.iv()));
        }
        // x / y = (−x) / (−y): make the divisor positive, `[c, d]` with c > 0.
        let (a, b, c, d) = if c > 0.0 { (a, b, c, d) } else { (-b, -a, -d, -c) };
        // For y > 0, x/y is increasing in x and, for fixed x, decreasing in y
        // when x ≥ 0 and increasing when x < 0: the low end is a/d (a ≥ 0) or
        // a/c, the high end b/c (b ≥ 0) or b/d. Rounding is monotone, so these
        // two quotients are the extremes of all four, as inari's (rounded
        // outward: −lo = RU(−a / ·)).
        let neg_lo = div_up(-a, select(a >= 0.0, d, c));
        let hi = div_up(b, select(b >= 0.0, c, d));
        Self([neg_lo, hi])
    }
}

/// Exact.
impl Neg for GeoIv {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self([self.0[1], self.0[0]])
    }
}

/// `√x` rounded down (`up_end == false`) or up, for `x ≥ 0`: the nearest
/// root `s` has the exact residual `x − s²` in the checked range; elsewhere
/// the nearest root (correctly rounded) is moved outward as in [`Iv`].
fn sqrt_rounded(x: f64, up_end: bool) -> f64 {
    let s = x.sqrt();
    if exact_safe(x) {
        let r = (-s).mul_add(s, x);
        if up_end {
            round_up(s, r)
        } else {
            -round_up(-s, -r)
        }
    } else if up_end {
        up(s)
    } else {
        down(s).max(0.0)
    }
}

impl Geo for GeoIv {
    const RIGOROUS: bool = true;
    #[inline]
    fn pt(x: f64) -> Self {
        Self::new(x, x)
    }
    #[inline]
    fn lower(self) -> f64 {
        let lo = self.lo();
        if lo.is_nan() {
            f64::NEG_INFINITY
        } else {
            lo
        }
    }
    #[inline]
    fn upper(self) -> f64 {
        let hi = self.hi();
        if hi.is_nan() {
            f64::INFINITY
        } else {
            hi
        }
    }
    #[inline]
    fn mag(self) -> f64 {
        self.lower().abs().max(self.upper().abs())
    }
    #[inline]
    fn mig(self) -> f64 {
        if self.lo() > 0.0 {
            self.lo()
        } else if self.hi() < 0.0 {
            -self.hi()
        } else {
            0.0
        }
    }
    #[inline]
    fn sign_class(self) -> Sign {
        let (lo, hi) = (self.lo(), self.hi());
        if lo > 0.0 {
            Sign::Positive
        } else if hi < 0.0 {
            Sign::Negative
        } else if lo == 0.0 && hi == 0.0 {
            Sign::Zero
        } else {
            Sign::Straddles
        }
    }
    #[inline]
    fn nonzero(self) -> bool {
        self.lo() > 0.0 || self.hi() < 0.0
    }
    fn sqrt_nonneg(self) -> Option<Self> {
        if self.hi() < 0.0 {
            return None;
        }
        let (lo, hi) = (self.lower().max(0.0), self.upper());
        Some(Self::new(sqrt_rounded(lo, false), sqrt_rounded(hi, true)))
    }
    fn div_pieces(num: Self, den: Self) -> [Option<Self>; 2] {
        if den.nonzero() {
            [Some(num / den), None]
        } else if num.has_nan() || den.has_nan() {
            [Some(Self::ENTIRE), None]
        } else {
            Self::div_through_zero(num, den)
        }
    }
    /// NaN ends count as unbounded.
    #[inline]
    fn clamp_to(self, lo: f64, hi: f64) -> Option<Self> {
        let (l, h) = (self.lower().max(lo), self.upper().min(hi));
        (l <= h).then(|| Self::new(l, h))
    }
    #[inline]
    fn hull(self, other: Self) -> Self {
        Self::of_iv(self.iv().hull(other.iv()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same endpoints (`−0` and `+0` are the same end).
    fn same(x: GeoIv, y: Interval) -> bool {
        x.lower() == y.inf() && x.upper() == y.sup()
    }

    fn contains(outer: GeoIv, inner: Interval) -> bool {
        outer.lower() <= inner.inf() && inner.sup() <= outer.upper()
    }

    /// Endpoints of every sign and scale, values a rounding error apart, and
    /// the edges of the exact ranges and beyond.
    fn samples() -> Vec<f64> {
        let mut v = vec![
            0.0,
            1.0,
            0.1,
            1.0 / 3.0,
            2.0 / 3.0,
            1.0 + f64::EPSILON,
            7.0,
            123456.789,
            1e-300,
            1e200,
            EXACT_MIN,
            EXACT_MIN.next_down(),
            EXACT_MAX,
            EXACT_MAX.next_up(),
            ADD_MAX.next_up(),
        ];
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..24 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let mantissa = (x >> 11) as f64 / (1u64 << 53) as f64;
            v.push(mantissa * 2f64.powi((x & 0x3f) as i32 - 32));
        }
        let negated: Vec<f64> = v.iter().map(|x| -x).collect();
        v.extend(negated);
        v
    }

    fn intervals() -> Vec<Interval> {
        let s = samples();
        let mut out = Vec::new();
        for (i, &lo) in s.iter().enumerate() {
            out.push(interval(lo, lo));
            for &hi in s.iter().skip(i % 5).step_by(5) {
                if lo <= hi {
                    out.push(interval(lo, hi));
                }
            }
        }
        out
    }

    fn in_range(x: Interval) -> bool {
        exact_safe(x.inf()) && exact_safe(x.sup())
    }

    #[test]
    fn geo_iv_equals_inari_in_range_and_encloses_elsewhere() {
        let ivs = intervals();
        assert!(ivs.len() > 300);
        for &x in &ivs {
            let gx = GeoIv::of(x);
            assert!(same(-gx, -x));
            match (<Interval as Geo>::sqrt_nonneg(x), Geo::sqrt_nonneg(gx)) {
                (Some(r), Some(g)) => assert!(if in_range(x) { same(g, r) } else { contains(g, r) }, "sqrt {x:?}"),
                (r, g) => assert!(r.is_none() && g.is_none(), "sqrt {x:?}"),
            }
            for &y in &ivs {
                let gy = GeoIv::of(y);
                let exact = in_range(x) && in_range(y);
                let check = |g: GeoIv, r: Interval, op: &str| {
                    let ok = if exact { same(g, r) } else { contains(g, r) };
                    assert!(ok, "{x:?} {op} {y:?}: {g:?} vs {r:?}");
                };
                check(gx + gy, x + y, "+");
                check(gx - gy, x - y, "-");
                check(gx * gy, x * y, "*");
                if !y.contains(0.0) {
                    check(gx / gy, x / y, "/");
                }
                // Every piece of inari's lies in a piece of ours.
                let fast = <GeoIv as Geo>::div_pieces(gx, gy);
                for p in <Interval as Geo>::div_pieces(x, y).into_iter().flatten() {
                    assert!(fast.iter().flatten().any(|&f| contains(f, p)), "{x:?} / {y:?} pieces");
                }
            }
        }
    }

    #[test]
    fn geo_iv_keeps_exact_zeros() {
        let x = GeoIv::pt(0.3);
        assert_eq!((x * GeoIv::pt(2.0) - (x + x)).sign_class(), Sign::Zero);
        assert_eq!((GeoIv::pt(-1.0) / GeoIv::pt(1.0)).sign_class(), Sign::Negative);
        assert_eq!(GeoIv::pt(-1.0) / GeoIv::pt(1.0), GeoIv::pt(-1.0));
    }
}
