//! Clipping a box: the span of each axis that may hold a zero, by the
//! projected-polyhedron method (Sherbrooke & Patrikalakis 1993,
//! doi:10.1016/0167-8396(93)90039-5), on the equations and on preconditioned
//! combinations of them; the widening and aspect rules; degree elevation for
//! the combinations.
//!
//! # The projected polyhedron
//! Project the control points `(i/n_d, c_i)` of one equation onto the plane
//! `(x_d, value)`: for each index `i` of axis `d` the values lie in
//! `[L_i, U_i] = [min c, max c]` over the other indices. Since
//! `p(x) = Σ_i B^{n_d}_i(x_d) q_i(x_{¬d})` with `q_i(x_{¬d}) ∈ [L_i, U_i]`, a
//! zero `x*` puts `(x*_d, 0)` in the convex hull of the segments
//! `{i/n_d} × [L_i, U_i]`, so `x*_d` lies between the smallest and the
//! largest abscissa where a segment joining two endpoints of opposite sign
//! crosses zero (or where `L_i ≤ 0 ≤ U_i`). The kept span of axis `d` is the
//! intersection of the equations' spans.
//!
//! The crossings are computed in `f64` and widened by `4·10⁻¹⁵` (abscissae
//! lie in `[0, 1]`, and the quotient `y_i/(y_i − y_j)` of opposite signs never
//! cancels: its error is below `7·2⁻⁵³`), the argument of the bivariate box
//! solver.

use super::tensor::{len_of, project, stride};
use crate::scalar::iv::Iv;
use crate::solve::envelope;

/// The smallest ratio of a clipped box's side to its widest ([`keep_aspect`]).
const MIN_ASPECT: f64 = 1e-3;

/// Scratch size for one projected line.
const LINE: usize = 48;

/// The span of `[0, 1]` on axis `d` where the projected polyhedron of the
/// equation meets zero; `None` if it provably does not.
pub(crate) fn zero_span(c: &[Iv], deg: &[usize], d: usize) -> Option<(f64, f64)> {
    let k = deg[d];
    if k + 1 > LINE {
        return Some((0.0, 1.0));
    }
    let mut lo = [0.0f64; LINE];
    let mut hi = [0.0f64; LINE];
    project(c, deg, d, &mut lo, &mut hi);
    if !lo[..=k].iter().chain(&hi[..=k]).all(|x| x.is_finite()) {
        return Some((0.0, 1.0));
    }
    envelope::zero_span(&lo[..=k], &hi[..=k])
}

/// The spans of every axis where all of `eqs` may vanish; `None` if one is
/// provably empty.
pub(crate) fn hull_spans<const N: usize>(eqs: &[(&[usize; N], &[Iv])]) -> Option<[(f64, f64); N]> {
    let mut spans = [(0.0f64, 1.0f64); N];
    for (d, span) in spans.iter_mut().enumerate() {
        for (deg, c) in eqs {
            let (a, b) = zero_span(c, &deg[..], d)?;
            *span = (span.0.max(a), span.1.min(b));
        }
        if span.0 > span.1 {
            return None;
        }
    }
    Some(spans)
}

/// Widens each span by a quarter of its width on each side (so that a
/// simple zero never ends within rounding of a new face, where
/// `K(X) ⊂ int X` cannot hold again) and keeps every side of the new box at
/// least [`MIN_ASPECT`] of its widest (`w`: the box's widths relative to the
/// domain).
pub(crate) fn widen<const N: usize>(spans: &mut [(f64, f64); N], w: [f64; N]) {
    for span in spans.iter_mut() {
        let r = 0.25 * (span.1 - span.0);
        *span = ((span.0 - r).max(0.0), (span.1 + r).min(1.0));
    }
    let new: [f64; N] = std::array::from_fn(|d| (spans[d].1 - spans[d].0) * w[d]);
    let widest = new.iter().fold(0.0f64, |m, &x| m.max(x));
    for d in 0..N {
        let want = MIN_ASPECT * widest;
        if new[d] < want && w[d] > 0.0 {
            let r = 0.5 * (want / w[d] - (spans[d].1 - spans[d].0));
            spans[d] = ((spans[d].0 - r).max(0.0), (spans[d].1 + r).min(1.0));
        }
    }
}

/// The tensor raised to degrees `to` (each `≥` the current one), enclosed:
/// `c'_j = Σ_i C(k, i) C(r, j − i) / C(k + r, j) c_i` per axis.
pub(crate) fn elevate(c: &[Iv], deg: &[usize], to: &[usize]) -> Vec<Iv> {
    let mut cur = c.to_vec();
    let mut cd = deg.to_vec();
    for d in 0..deg.len() {
        if to[d] == cd[d] {
            continue;
        }
        let (k, n) = (cd[d], to[d]);
        let r = n - k;
        let w = stride(&cd, d);
        let outer = len_of(&cd) / ((k + 1) * w);
        let mut nd = cd.clone();
        nd[d] = n;
        let mut out = vec![Iv::point(0.0); len_of(&nd)];
        // The weights once per axis (their binomials are u128 divisions).
        let mut weights = Vec::with_capacity((n + 1) * (k + 1));
        for j in 0..=n {
            for i in j.saturating_sub(r)..=k.min(j) {
                let num = binom(k, i) * binom(r, j - i);
                weights.push(exact_ish(num).div(exact_ish(binom(n, j))));
            }
        }
        for o in 0..outer {
            let mut at = 0;
            for j in 0..=n {
                for i in j.saturating_sub(r)..=k.min(j) {
                    let wt = weights[at];
                    at += 1;
                    for x in 0..w {
                        let src = cur[(o * (k + 1) + i) * w + x];
                        let dst = &mut out[(o * (n + 1) + j) * w + x];
                        *dst = dst.add(wt.mul(src));
                    }
                }
            }
        }
        cur = out;
        cd = nd;
    }
    cur
}

/// `C(n, k)`, exact (`n ≤ 80` here: `C(80, 40) < 2¹²⁸`).
fn binom(n: usize, k: usize) -> u128 {
    let mut r: u128 = 1;
    for i in 0..k {
        r = r * (n - i) as u128 / (i + 1) as u128;
    }
    r
}

/// An enclosure of an integer: the nearest float moved outward when the
/// conversion may have rounded.
fn exact_ish(x: u128) -> Iv {
    let f = x as f64;
    if x < (1u128 << 53) {
        Iv::point(f)
    } else {
        Iv::new(crate::scalar::iv::down(f), crate::scalar::iv::up(f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::nd::tensor::eval_point;

    #[test]
    fn spans_of_a_linear_equation() {
        // p(x, y) = x − 1/4 on degree (2, 1): coefficients i/2 − 1/4.
        let c: Vec<Iv> = (0..3)
            .flat_map(|i| (0..2).map(move |_| Iv::point(i as f64 / 2.0 - 0.25)))
            .collect();
        let deg = [2usize, 1];
        let (a, b) = zero_span(&c, &deg, 0).unwrap();
        assert!(a <= 0.25 && 0.25 <= b && b - a < 1e-14);
        assert_eq!(zero_span(&c, &deg, 1), Some((0.0, 1.0)));
        let e = elevate(&c, &deg, &[4, 3]);
        let v = eval_point(&e, &[4, 3], &[0.7, 0.2]);
        assert!(v.lo <= 0.45 && 0.45 <= v.hi && v.hi - v.lo < 1e-14);
    }
}
