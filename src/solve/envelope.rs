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
///
/// `a`, `b` are the smallest and largest abscissa `i/k` of a range holding 0
/// or crossing of a segment joining `(i/k, y_i)` and `(j/k, y_j)`, `y` an
/// endpoint of its range, of opposite signs (`x_i + (x_j − x_i)·y_i/(y_i −
/// y_j)`). A pair whose four endpoints share a sign has no crossing and is
/// skipped, and once `a ≤ 0 ≤ 1 ≤ b` no crossing changes the clamped result.
/// With finite ranges every candidate is in `[0, 1]` and never `−0`, so the
/// `<` selections ([`least`], [`most`]) pick what `f64::min`/`max` would.
#[inline(always)]
pub(crate) fn zero_span_inline(lo: &[f64], hi: &[f64]) -> Option<(f64, f64)> {
    let k = lo.len() - 1;
    if k == 0 {
        return (lo[0] <= 0.0 && hi[0] >= 0.0).then_some((0.0, 1.0));
    }
    let kf = k as f64;
    let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=k {
        if lo[i] <= 0.0 && hi[i] >= 0.0 {
            let xi = i as f64 / kf;
            a = least(a, xi);
            b = most(b, xi);
        }
    }
    if a <= 0.0 && b >= 1.0 {
        return Some((0.0, 1.0));
    }
    for i in 0..k {
        let xi = i as f64 / kf;
        for j in i + 1..=k {
            if (lo[i] >= 0.0 && lo[j] >= 0.0) || (hi[i] <= 0.0 && hi[j] <= 0.0) {
                continue;
            }
            let xj = j as f64 / kf;
            for yi in [lo[i], hi[i]] {
                for yj in [lo[j], hi[j]] {
                    if (yi < 0.0 && yj > 0.0) || (yi > 0.0 && yj < 0.0) {
                        let x = xi + (xj - xi) * (yi / (yi - yj));
                        a = least(a, x);
                        b = most(b, x);
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

/// The smaller of two numbers (no NaN).
#[inline(always)]
fn least(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The larger of two numbers (no NaN).
#[inline(always)]
fn most(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Every pair, `f64::min`/`max`: the plain form of the definition.
    fn reference(lo: &[f64], hi: &[f64]) -> Option<(f64, f64)> {
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

    #[test]
    fn hull_crossings_give_the_envelope_floats() {
        let mut rng = Rng(11);
        for k in 0..=5 {
            for _ in 0..2000 {
                let lo: Vec<f64> = (0..=k).map(|_| rng.next_signed()).collect();
                let hi: Vec<f64> = lo.iter().map(|x| x + 0.3 * rng.next_f64()).collect();
                let want = reference(&lo, &hi);
                assert_eq!(zero_span_inline(&lo, &hi), want, "{lo:?} {hi:?}");
            }
        }
    }
}
