//! Where the convex hull of a coefficient envelope meets zero: the clipping
//! step shared by the box solver (`rect`) and the n-variate solver (`nd`).

/// The widening of hull crossings.
const MARGIN: f64 = 4e-15;

/// The span of `[0, 1]` where the convex hull of the points
/// `(i/k, [lo[i], hi[i]])`, `k = lo.len() − 1`, meets the axis, widened by
/// `4e-15` and clamped to `[0, 1]`; `None` if it does not. Every zero of a
/// polynomial whose BB coefficients in this direction lie in the envelope lies
/// in the span (convex hull property). The crossings are computed in `f64`;
/// the margin covers their rounding on `[0, 1]`. Inputs must be finite and
/// `lo.len() == hi.len() ≥ 1`.
pub(crate) fn zero_span(lo: &[f64], hi: &[f64]) -> Option<(f64, f64)> {
    zero_span_inline(lo, hi)
}

/// [`zero_span`] inlined into its caller, for callers whose `lo.len()` is a
/// constant there (the box solver's small bidegrees): the loops unroll.
#[inline(always)]
pub(crate) fn zero_span_inline(lo: &[f64], hi: &[f64]) -> Option<(f64, f64)> {
    let k = lo.len() - 1;
    if k == 0 {
        return (lo[0] <= 0.0 && hi[0] >= 0.0).then_some((0.0, 1.0));
    }
    let kf = k as f64;
    let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=k {
        let xi = i as f64 / kf;
        if lo[i] <= 0.0 && hi[i] >= 0.0 {
            a = a.min(xi);
            b = b.max(xi);
        }
        for j in i + 1..=k {
            let xj = j as f64 / kf;
            for yi in [lo[i], hi[i]] {
                for yj in [lo[j], hi[j]] {
                    if (yi < 0.0 && yj > 0.0) || (yi > 0.0 && yj < 0.0) {
                        let x = xi + (xj - xi) * (yi / (yi - yj));
                        a = a.min(x);
                        b = b.max(x);
                    }
                }
            }
        }
    }
    if a > b {
        return None;
    }
    Some(((a - MARGIN).max(0.0), (b + MARGIN).min(1.0)))
}
