//! Bézier clipping's hull bounds ([`bezier_bounds`]) and the combination of
//! two equations' bounds ([`intersect_bounds`]).

use super::curves::{keep_or_empty, ClipBounds};
use crate::poly::{tri_indices, TriBall};
use crate::scalar::iv;
use smallvec::SmallVec;

/// Bézier clipping bounds of one equation (Roth et al. 2000, as used in Liu et
/// al. 2016 §4): the control net `(i/n, j/n, f_ijk)` bounds the graph, so the
/// zero set projects into the hull of the points `(i/n, f_ijk)` cut by
/// `f = 0`, and likewise for `j` and `k`. The hull meets the axis in the
/// convex hull of the zero-valued points and the crossings of segments between
/// a positive and a negative point; the minimum of those is the bound.
///
/// Each coefficient enters as the two ends of its range over the ball: the
/// surface of every member lies in the convex hull of all of them. `rigorous`
/// subtracts the proven rounding margin from each crossing (the certified
/// solver); without it the crossings are plain `f64` proposals.
pub fn bezier_bounds(f: &TriBall, rigorous: bool) -> ClipBounds {
    let n = f.degree().max(1);
    // The control points (i/n, j/n, k/n; f_ijk) with each coefficient's
    // enclosure as its two endpoints: the surface lies in the convex hull of
    // all of them (whatever the exact coefficients are), and the hull meets
    // z = 0 in the hull of the endpoints that are 0, of the points whose
    // enclosure holds 0, and of the crossings of segments joining a positive
    // and a negative endpoint. (An enclosure that straddles 0 is not a point
    // at 0: its negative end pairs with positive neighbours, and the crossing
    // can lie away from it.)
    let mut pos: SmallVec<[([usize; 3], f64); 72]> = SmallVec::new();
    let mut neg: SmallVec<[([usize; 3], f64); 72]> = SmallVec::new();
    let mut mins = [f64::INFINITY; 3];
    for (idx, (i, j, k)) in tri_indices(f.degree()).enumerate() {
        let (lo, hi) = f.bounds(idx);
        if lo.is_nan() || hi.is_nan() {
            return ClipBounds::Keep([0.0; 3]);
        }
        if lo <= 0.0 && hi >= 0.0 {
            for (m, x) in mins.iter_mut().zip([i, j, k]) {
                *m = m.min(x as f64 / n as f64);
            }
        }
        for y in if hi != lo {
            [Some(lo), Some(hi)]
        } else {
            [Some(lo), None]
        }
        .into_iter()
        .flatten()
        {
            if y > 0.0 {
                pos.push(([i, j, k], y));
            } else if y < 0.0 {
                neg.push(([i, j, k], y));
            }
        }
    }
    if mins[0].is_infinite() && (pos.is_empty() || neg.is_empty()) {
        return ClipBounds::Empty;
    }
    // The crossing of the segment from (a, yp) to (b, yq), yp > 0 > yq, with
    // the axis is x = a + (b − a)·t, t = yp / (yp − yq) ∈ (0, 1), with
    // a = i/n, b = j/n. Evaluated in `f64`, every quantity (a, b, b − a, t, x)
    // lies in [−1, 1], and each of the six roundings (i/n, j/n, b − a,
    // yp − yq, the quotient, the product, the sum) errs by at most one ulp
    // of 1 relative to its operands: the computed x is within 7·2⁻⁵² of the
    // exact crossing (plus 2⁻¹⁰⁷⁴ for a subnormal quotient), so subtracting
    // 16·2⁻⁵² gives a lower bound. This is 20–40× cheaper than interval
    // operations, and this loop is most of a Bézier clip.
    let margin = if rigorous { 16.0 * f64::EPSILON } else { 0.0 };
    let nn = n as f64;
    for (coord, m) in mins.iter_mut().enumerate() {
        for p in &pos {
            for q in &neg {
                let (yp, yq) = (p.1, q.1);
                let span = yp - yq;
                let (a, b) = (p.0[coord] as f64 / nn, q.0[coord] as f64 / nn);
                let x = if span.is_finite() {
                    a + (b - a) * (yp / span) - margin
                } else {
                    // Overflow of yp − yq: enclose with outward rounding.
                    let (xp, xq) = (iv::Iv::point(p.0[coord] as f64), iv::Iv::point(q.0[coord] as f64));
                    let (xp, xq) = (xp.div(iv::Iv::point(nn)), xq.div(iv::Iv::point(nn)));
                    let (yp, yq) = (iv::Iv::point(yp), iv::Iv::point(yq));
                    xp.add(xq.sub(xp).mul(yp.div(yp.sub(yq)))).lo
                };
                *m = m.min(x);
            }
        }
    }
    let m = mins.map(|x| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) });
    keep_or_empty(m, rigorous)
}

/// Combines bounds that must hold together (both equations vanish at a root).
pub fn intersect_bounds(a: ClipBounds, b: ClipBounds, rigorous: bool) -> ClipBounds {
    match (a, b) {
        (ClipBounds::Keep(x), ClipBounds::Keep(y)) => {
            keep_or_empty([x[0].max(y[0]), x[1].max(y[1]), x[2].max(y[2])], rigorous)
        }
        _ => ClipBounds::Empty,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The float evaluation of the hull crossings in `bezier_bounds` stays a
    /// lower bound of the exact crossings (rationals), on random nets with
    /// coefficients of mixed magnitudes, including subnormal and huge ones.
    #[test]
    fn bezier_bounds_are_below_the_exact_hull_crossings() {
        use num_rational::BigRational;
        use num_traits::{Signed, Zero};
        let mut rng = crate::rng::Rng(0x9e3779b97f4a7c15);
        let mut rnd = move || rng.next_u64();
        for case in 0..600 {
            let n = 1 + case % 6;
            let len = (n + 1) * (n + 2) / 2;
            let scale = [1.0, 1e-300, 1e300, 1e-310, 3.0][case % 5];
            let mids: Vec<f64> = (0..len)
                .map(|_| ((rnd() % 2001) as f64 - 1000.0) / 997.0 * scale)
                .collect();
            let rad = if rnd() % 3 == 0 { 0.0 } else { scale * 1e-3 };
            let f = TriBall::new(n, &mids, rad).unwrap();
            let q = |x: f64| BigRational::from_float(x).unwrap();
            // The exact coefficient ranges [m − r, m + r].
            let ends: Vec<[BigRational; 2]> = mids.iter().map(|&m| [q(m) - q(rad), q(m) + q(rad)]).collect();
            let ClipBounds::Keep(mins) = bezier_bounds(&f, true) else {
                // Empty: every endpoint strictly of one sign.
                assert!(
                    ends.iter().all(|e| e[0].is_positive()) || ends.iter().all(|e| e[1].is_negative()),
                    "case {case}"
                );
                continue;
            };
            // Exact: the smallest abscissa of the hull's crossings, per coordinate.
            let nq = BigRational::from_integer(n.into());
            let pts: Vec<([usize; 3], BigRational)> = crate::poly::tri_indices(n)
                .zip(&ends)
                .flat_map(|((i, j, k), e)| [([i, j, k], e[0].clone()), ([i, j, k], e[1].clone())])
                .collect();
            for (coord, &m) in mins.iter().enumerate() {
                let mut exact: Option<BigRational> = None;
                let mut take = |x: BigRational| {
                    if exact.as_ref().is_none_or(|e| x < *e) {
                        exact = Some(x);
                    }
                };
                for (a, ya) in &pts {
                    if ya.is_zero() {
                        take(BigRational::from_integer(a[coord].into()) / &nq);
                    }
                    for (b, yb) in &pts {
                        if ya.is_positive() && yb.is_negative() {
                            let (xa, xb) = (
                                BigRational::from_integer(a[coord].into()) / &nq,
                                BigRational::from_integer(b[coord].into()) / &nq,
                            );
                            take(&xa + (&xb - &xa) * (ya / (ya - yb)));
                        }
                    }
                }
                if let Some(e) = exact {
                    let e = e.max(BigRational::zero()).min(BigRational::from_integer(1.into()));
                    assert!(
                        q(m) <= e,
                        "case {case} coord {coord}: bound {m} above the exact crossing {e}"
                    );
                }
            }
        }
    }
}
