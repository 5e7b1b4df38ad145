//! Interval arithmetic on bare endpoint pairs, with exactly inari's results,
//! for the hot loops of the Bernstein–Bézier algebra.
//!
//! # Why
//! inari rounds outward by setting the MXCSR rounding mode around every
//! operation (with `target-cpu=haswell`), and each MXCSR write stalls the
//! pipeline: those stalls made the interval kernels 10–25 times slower than
//! `f64`. Getting a value into and out of an [`Interval`] through its public
//! API (`inf`, `sup`, `try_from`) costs about as much as the arithmetic, so
//! the hot loops convert once, compute on [`Endpoints`], and convert back once.
//!
//! # How, and why the results are identical
//! Each endpoint is computed rounded to nearest together with its exact
//! rounding error, by an error-free transformation: Knuth's TwoSum for sums,
//! one FMA for products. The correctly rounded-up result is the nearest one if
//! the error is `≤ 0` and the next float above otherwise (rounding down mirrors
//! this). A directed rounding of an exact value is unique, so every endpoint is
//! *the same float* inari computes, and the sequence of operations in the
//! callers is the same as with the `Interval` operators: same enclosures, bit
//! for bit (checked against inari by the tests below and in `poly::triangle`).
//!
//! The transformations are exact only away from overflow and underflow, so
//! every operation first checks that its operands lie in a safe range and hands
//! anything else (empty, unbounded, huge or tiny endpoints) to inari itself.

use super::cache::{local_matrix, remember_local_matrix, MatrixCache, MatrixKey};
use super::eft::{add_up, mul_up, select};
use super::kernel::Scalar;
use inari::Interval;
use num_rational::BigRational;
use std::any::{Any, TypeId};
use std::sync::Arc;

/// The arithmetic of the hot polynomial loops, on a working representation of
/// a kernel's values. Every [`Scalar`] works as itself, through its operators;
/// the interval kernel also works as [`Endpoints`].
pub(crate) trait Arith: Clone {
    /// The additive identity.
    fn zero_value() -> Self;
    /// `a · b`.
    fn product(a: &Self, b: &Self) -> Self;
    /// `acc + a · b`, two operations with two roundings (never fused).
    fn add_product(acc: Self, a: &Self, b: &Self) -> Self;
    /// `max(acc, |a − b|)`.
    fn max_abs_diff_step(acc: Self, a: &Self, b: &Self) -> Self;
    /// The representative point, as [`Scalar::to_point`].
    fn point_of(&self) -> Self;

    /// `true` if the kernel has a fast path that needs no per-operation range
    /// checks for these values: each is `0` or of magnitude in
    /// `[2^−bits, 2^bits]` (`bits ≤ 480`). Then a product of two such values,
    /// and a sum of up to `2^36` such products, may use the `_unchecked`
    /// operations. Kernels without a fast path say `false`.
    fn in_fast_range(values: &[Self], bits: u32) -> bool {
        let _ = (values, bits);
        false
    }
    /// [`Arith::product`] for operands vetted by [`Arith::in_fast_range`]: the
    /// same value, without range checks.
    fn product_unchecked(a: &Self, b: &Self) -> Self {
        Self::product(a, b)
    }
    /// [`Arith::add_product`] for operands vetted by [`Arith::in_fast_range`]:
    /// the same value, without range checks.
    fn add_product_unchecked(acc: Self, a: &Self, b: &Self) -> Self {
        Self::add_product(acc, a, b)
    }
}

impl<S: Scalar> Arith for S {
    #[inline]
    fn zero_value() -> Self {
        S::zero()
    }
    #[inline]
    fn product(a: &Self, b: &Self) -> Self {
        a.clone() * b.clone()
    }
    #[inline]
    fn add_product(acc: Self, a: &Self, b: &Self) -> Self {
        acc + a.clone() * b.clone()
    }
    #[inline]
    fn max_abs_diff_step(acc: Self, a: &Self, b: &Self) -> Self {
        S::max(acc, (a.clone() - b.clone()).abs())
    }
    #[inline]
    fn point_of(&self) -> Self {
        self.to_point()
    }
}

/// An [`Interval`] as `[−lo, hi]`, inari's own layout: with the lower end
/// negated, rounding outward is rounding *up* in both lanes, so every
/// operation below is the same code on both lanes (which the compiler turns
/// into two-lane vector instructions). The empty interval is `[−∞, −∞]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Endpoints([f64; 2]);

impl Endpoints {
    #[inline]
    fn of(x: Interval) -> Self {
        Self([-x.inf(), x.sup()])
    }

    #[inline]
    fn interval(self) -> Interval {
        // Every pair here comes from an interval or from an operation below, so
        // the only pair `try_from` rejects is the empty one.
        Interval::try_from((-self.0[0], self.0[1])).unwrap_or(Interval::EMPTY)
    }
}

impl Arith for Endpoints {
    #[inline]
    fn zero_value() -> Self {
        Self([0.0, 0.0])
    }
    #[inline(always)]
    fn product(a: &Self, b: &Self) -> Self {
        mul(*a, *b)
    }
    #[inline(always)]
    fn add_product(acc: Self, a: &Self, b: &Self) -> Self {
        add(acc, mul(*a, *b))
    }
    #[inline]
    fn max_abs_diff_step(acc: Self, a: &Self, b: &Self) -> Self {
        max_abs(acc, sub(*a, *b))
    }
    #[inline]
    fn point_of(&self) -> Self {
        Self::of(Scalar::to_point(&self.interval()))
    }

    fn in_fast_range(values: &[Self], bits: u32) -> bool {
        debug_assert!(bits <= 480);
        let bits = u64::from(bits.min(480));
        let (min, max) = (f64::from_bits((1023 - bits) << 52), f64::from_bits((1023 + bits) << 52));
        let ok = |v: f64| {
            let m = v.abs();
            (m == 0.0) | ((m >= min) & (m <= max))
        };
        values.iter().all(|e| ok(e.0[0]) & ok(e.0[1]))
    }
    #[inline(always)]
    fn product_unchecked(a: &Self, b: &Self) -> Self {
        Endpoints(mul_unchecked(*a, *b))
    }
    #[inline(always)]
    fn add_product_unchecked(acc: Self, a: &Self, b: &Self) -> Self {
        Endpoints(add_up(acc.0, mul_unchecked(*a, *b)))
    }
}

/// `v` as endpoint pairs if `S` is the interval kernel, `None` otherwise.
pub(crate) fn endpoints_of<S: Scalar>(v: &[S]) -> Option<Vec<Endpoints>> {
    if TypeId::of::<S>() != TypeId::of::<Interval>() {
        return None;
    }
    v.iter()
        .map(|x| (x as &dyn Any).downcast_ref::<Interval>().map(|&i| Endpoints::of(i)))
        .collect()
}

/// A coefficient vector (`&Vec<S>`) as endpoint pairs on the stack for the
/// usual degrees, if `S` is the interval kernel: one type check for the
/// whole vector (the hot loop of Krawczyk's evaluations).
pub(crate) fn endpoint_net(coeffs: &dyn Any) -> Option<smallvec::SmallVec<[Endpoints; 36]>> {
    let v = coeffs.downcast_ref::<Vec<Interval>>()?;
    Some(v.iter().map(|&i| Endpoints::of(i)).collect())
}

/// One value as an endpoint pair, if `S` is the interval kernel.
#[inline]
pub(crate) fn endpoint_of<S: Scalar>(x: &S) -> Option<Endpoints> {
    (x as &dyn Any).downcast_ref::<Interval>().map(|&i| Endpoints::of(i))
}

/// One endpoint pair back in the interval kernel `S`; same precondition as
/// [`from_endpoints`].
#[inline]
pub(crate) fn from_endpoint<S: Scalar>(e: Endpoints) -> S {
    let mut slot: Option<S> = None;
    if let Some(s) = (&mut slot as &mut dyn Any).downcast_mut::<Option<Interval>>() {
        *s = Some(e.interval());
    }
    slot.expect("from_endpoint is only called for the interval kernel")
}

/// Endpoint pairs back in the interval kernel `S`.
///
/// Only called after [`endpoints_of`] succeeded for the same `S`; panics
/// otherwise (a bug in this crate, never a property of user data).
pub(crate) fn from_endpoints<S: Scalar>(v: &[Endpoints]) -> Vec<S> {
    let mut slot: Option<Vec<S>> = None;
    if let Some(s) = (&mut slot as &mut dyn Any).downcast_mut::<Option<Vec<Interval>>>() {
        *s = Some(v.iter().map(|e| e.interval()).collect());
    }
    slot.expect("from_endpoints is only called for the interval kernel")
}

/// Overwrites `dst` with `src` in the interval kernel `S` (equal lengths);
/// same precondition as [`from_endpoints`].
pub(crate) fn store_endpoints<S: Scalar>(dst: &mut [S], src: &[Endpoints]) {
    debug_assert_eq!(dst.len(), src.len());
    for (d, e) in dst.iter_mut().zip(src) {
        let d = (d as &mut dyn Any)
            .downcast_mut::<Interval>()
            .expect("store_endpoints is only called for the interval kernel");
        *d = e.interval();
    }
}

/// [`Scalar::cached_matrix`] of the interval kernel, as endpoint pairs.
pub(crate) fn cached_endpoints(key: MatrixKey, build: impl FnOnce() -> Vec<BigRational>) -> Arc<[Endpoints]> {
    if let Some(m) = local_matrix::<Endpoints>(key) {
        return m;
    }
    let m: Arc<[Endpoints]> = Interval::cached_matrix(key, build)
        .iter()
        .map(|&x| Endpoints::of(x))
        .collect();
    remember_local_matrix(key, m.clone());
    m
}

/// Operands of sums up to this size cannot overflow inside TwoSum.
const ADD_MAX: f64 = 1.0e300;
/// Non-zero factors of magnitude in `[2^−480, 2^480]` give products in
/// `[2^−960, 2^960]`: no overflow, and far enough above the subnormals
/// (`2^−1022`, more than 53 bits to spare) that `fma(a, b, −a·b)` is exact.
const MUL_MIN: f64 = f64::from_bits((1023 - 480) << 52);
const MUL_MAX: f64 = f64::from_bits((1023 + 480) << 52);

// Branches on data signs mispredict about half the time in these loops
// (coefficient signs are effectively random), so the rounding below is
// branch-free. Only the range checks and the sign class of a product's first
// factor branch; both are stable within the callers' loops.

#[inline(always)]
fn add_safe(x: Endpoints, y: Endpoints) -> bool {
    // An empty pair holds ±∞ and fails here too.
    let ok = |v: f64| v.abs() <= ADD_MAX;
    ok(x.0[0]) & ok(x.0[1]) & ok(y.0[0]) & ok(y.0[1])
}

#[inline(always)]
fn mul_safe(x: Endpoints, y: Endpoints) -> bool {
    let ok = |v: f64| {
        let m = v.abs();
        (m == 0.0) | (MUL_MIN..=MUL_MAX).contains(&m)
    };
    ok(x.0[0]) & ok(x.0[1]) & ok(y.0[0]) & ok(y.0[1])
}

/// `x + y`, equal to inari's `x + y`: `[−a; b] + [−c; d]` rounded up.
#[inline(always)]
fn add(x: Endpoints, y: Endpoints) -> Endpoints {
    if !add_safe(x, y) {
        return Endpoints::of(x.interval() + y.interval());
    }
    Endpoints(add_up(x.0, y.0))
}

/// `x − y`, equal to inari's `x - y`: `[−a; b] + [d; −c]` rounded up.
#[inline(always)]
fn sub(x: Endpoints, y: Endpoints) -> Endpoints {
    if !add_safe(x, y) {
        return Endpoints::of(x.interval() - y.interval());
    }
    Endpoints(add_up(x.0, [y.0[1], y.0[0]]))
}

/// `max(acc, |x|)`, equal to inari's `acc.max(x.abs())` (neither rounds).
#[inline(always)]
fn max_abs(acc: Endpoints, x: Endpoints) -> Endpoints {
    let finite = |e: Endpoints| e.0[0].abs() <= f64::MAX && e.0[1].abs() <= f64::MAX;
    if !(finite(acc) && finite(x)) {
        // Empty or unbounded: inari's case analysis.
        return Endpoints::of(acc.interval().max(x.interval().abs()));
    }
    let [neg_a, b] = x.0;
    let abs = if neg_a <= 0.0 {
        x.0 // a ≥ 0
    } else if b <= 0.0 {
        [b, neg_a] // [−b, −a] as [b; −a]
    } else {
        [0.0, neg_a.max(b)] // [0, max(−a, b)]
    };
    // [max(lo, lo'), max(hi, hi')] = [min(−lo, −lo'); max(hi, hi')].
    Endpoints([acc.0[0].min(abs[0]), acc.0[1].max(abs[1])])
}

/// `x · y`, equal to inari's `x * y`: the extreme endpoint products, rounded
/// outward.
///
/// The product is bilinear, so its extremes are at corners. With `x = [a, b]`
/// and `t` an end of `y`, the smaller of `a·t`, `b·t` is `a·t` if `t ≥ 0` and
/// `b·t` otherwise. So `lo = min(RD(x_c·c), RD(x_d·d))` with `x_t` chosen by
/// the sign of `t`, and `hi` alike: right in every sign case without a branch.
/// Rounding is monotone, so the min of rounded products is the rounded min
/// inari computes. When `x ≥ 0` (de Casteljau weights, elevation and product
/// weights) one product per end suffices. In the `[−lo, hi]` layout,
/// `−lo = max(RU(x_c·(−c)), RU(x_d·(−d)))`.
#[inline(always)]
fn mul(x: Endpoints, y: Endpoints) -> Endpoints {
    if !mul_safe(x, y) {
        return Endpoints::of(x.interval() * y.interval());
    }
    Endpoints(mul_unchecked(x, y))
}

/// [`mul`] without the range check, for factors whose non-zero endpoint
/// magnitudes multiply to between `2^−968` and `2^960` (as
/// [`Arith::in_fast_range`] guarantees: `[2^−480, 2^480]` each, or
/// `[2^−320, 2^320]` for the three factors of a product `(w·f)·g`). Then the
/// exponents of the factors sum to at least `e_min + 52 = −970`, so every FMA
/// error term is exact (Boldo and Muller), and nothing overflows.
#[inline(always)]
fn mul_unchecked(x: Endpoints, y: Endpoints) -> [f64; 2] {
    let (a, b) = (-x.0[0], x.0[1]);
    let [neg_c, d] = y.0;
    let (c_pos, d_pos) = (neg_c <= 0.0, d >= 0.0);
    // x_c·(−c) and x_d'·d, where x_d' is the end giving the larger product.
    let first = mul_up([select(c_pos, a, b), select(d_pos, b, a)], [neg_c, d]);
    if a >= 0.0 {
        // x ≥ 0: the low end comes from c and the high end from d.
        return first;
    }
    let second = mul_up([select(d_pos, a, b), select(c_pos, b, a)], [-d, -neg_c]);
    let max = |p: f64, q: f64| if p > q { p } else { q };
    [max(first[0], second[0]), max(first[1], second[1])]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Endpoints that exercise every branch: signs, zeros of both signs,
    /// values a rounding error apart, the edges of the safe ranges and beyond.
    fn samples() -> Vec<f64> {
        let mut v = vec![
            0.0,
            -0.0,
            1.0,
            0.1,
            1.0 / 3.0,
            2.0 / 3.0,
            1.0e-300,
            1.0e-200,
            MUL_MIN,
            MUL_MIN.next_down(),
            MUL_MAX,
            MUL_MAX.next_up(),
            ADD_MAX,
            ADD_MAX.next_up(),
            1.0e308,
            f64::MAX,
            f64::MIN_POSITIVE,
            5.0e-324,
            f64::INFINITY,
            1.0 + f64::EPSILON,
            123456.789,
            2f64.powi(-500),
            2f64.powi(500),
        ];
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..40 {
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
        let mut out = vec![Interval::EMPTY, Interval::ENTIRE];
        for (i, &lo) in s.iter().enumerate() {
            // Every point, and a spread of pairs (all pairs would be slow).
            out.extend(Interval::try_from((lo, lo)));
            for &hi in s.iter().skip(i % 7).step_by(7) {
                out.extend(Interval::try_from((lo, hi)));
            }
        }
        out
    }

    fn same(x: Endpoints, y: Interval) -> bool {
        let x = x.interval();
        x.is_empty() && y.is_empty() || x.inf().to_bits() == y.inf().to_bits() && x.sup().to_bits() == y.sup().to_bits()
    }

    #[test]
    fn equals_inari_everywhere() {
        let iv = intervals();
        assert!(iv.len() > 1000);
        for &x in &iv {
            for &y in &iv {
                let (ex, ey) = (Endpoints::of(x), Endpoints::of(y));
                assert!(same(add(ex, ey), x + y), "{x:?} + {y:?}");
                assert!(same(sub(ex, ey), x - y), "{x:?} - {y:?}");
                assert!(same(mul(ex, ey), x * y), "{x:?} * {y:?}");
                let step = Endpoints::max_abs_diff_step(ex, &ey, &ex);
                assert!(same(step, x.max((y - x).abs())), "max({x:?}, |{y:?} - {x:?}|)");
                if Endpoints::in_fast_range(&[ex, ey], 480) {
                    let p = Endpoints::product_unchecked(&ex, &ey);
                    assert!(same(p, x * y), "{x:?} * {y:?} unchecked");
                    let s = Endpoints::add_product_unchecked(ey, &ex, &ey);
                    assert!(same(s, y + x * y), "{y:?} + {x:?} * {y:?} unchecked");
                }
            }
        }
    }

    #[test]
    fn rounds_outward() {
        let third = Endpoints::of(Interval::try_from((1.0 / 3.0, 1.0 / 3.0)).unwrap());
        let tenth = Endpoints::of(Interval::try_from((0.1, 0.1)).unwrap());
        let p = mul(third, tenth).interval();
        assert_eq!(p.inf().next_up(), p.sup());
        let s = add(third, tenth).interval();
        assert_eq!(s.inf().next_up(), s.sup());
    }

    #[test]
    fn conversions_only_for_intervals() {
        let x = [Interval::try_from((-1.0, 2.0)).unwrap(), Interval::EMPTY];
        let e = endpoints_of(&x).unwrap();
        assert_eq!(from_endpoints::<Interval>(&e), x.to_vec());
        assert!(endpoints_of(&[1.0f64]).is_none());
    }
}
