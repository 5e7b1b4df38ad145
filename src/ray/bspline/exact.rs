//! Exact Bézier nets of B-spline pieces, for settling hits that rounding
//! leaves on a piece's edge (`crate::solve::settle`).
//!
//! The stored pieces come from knot insertion in `f64` (their nets carry a
//! bounded error, which makes their certificates valid but not exact). A hit
//! whose root the piece could not place on its side of an edge is settled
//! here against the piece's exact net: the Bézier control points of the span
//! `[a, b] × [c, d]` are the blossoms `P[a^{p−i} b^i; c^{q−j} d^j]` of the
//! surface, computed by de Boor's algorithm in rationals on the homogeneous
//! control points `(w x, w y, w z, w)`.

use super::surface::{BezierPiece, BsplineSurface};
use crate::ray::settle::exact_hom;
use num_rational::BigRational;
use num_traits::{One, Zero};

type Q = BigRational;
type Hom = [Q; 4];

/// The homogeneous Bézier net of `piece`, exactly, row-major (`i` along
/// `u`, `j` along `v`); `None` if a knot or point is not finite.
pub(crate) fn exact_piece_net(s: &BsplineSurface, piece: &BezierPiece) -> Option<Vec<Hom>> {
    let (p, q) = s.degree;
    let (nu, nv) = s.counts;
    let ku = span(&s.knots_u, p, nu, piece.u)?;
    let kv = span(&s.knots_v, q, nv, piece.v)?;
    let exact = |x: f64| Q::from_float(x);
    let uk: Vec<Q> = s.knots_u.iter().map(|&x| exact(x)).collect::<Option<_>>()?;
    let vk: Vec<Q> = s.knots_v.iter().map(|&x| exact(x)).collect::<Option<_>>()?;
    let hom = |i: usize, j: usize| -> Option<Hom> {
        let k = i * nv + j;
        exact_hom(s.points[k], s.weights.as_ref().map(|w| w[k]))
    };
    let args = |lo: &Q, hi: &Q, deg: usize, i: usize| -> Vec<Q> {
        (0..deg)
            .map(|r| if r < deg - i { lo.clone() } else { hi.clone() })
            .collect()
    };
    let (ua, ub) = (&uk[ku], &uk[ku + 1]);
    let (va, vb) = (&vk[kv], &vk[kv + 1]);
    // Along u for every control row j that the span touches, then along v.
    let mut rows: Vec<Vec<Hom>> = Vec::with_capacity(q + 1);
    for j in kv - q..=kv {
        let ctrl: Vec<Hom> = (ku - p..=ku).map(|i| hom(i, j)).collect::<Option<_>>()?;
        rows.push(
            (0..=p)
                .map(|a| blossom(&uk, p, ku, &ctrl, &args(ua, ub, p, a)))
                .collect(),
        );
    }
    let mut net = Vec::with_capacity((p + 1) * (q + 1));
    for a in 0..=p {
        let ctrl: Vec<Hom> = rows.iter().map(|r| r[a].clone()).collect();
        for b in 0..=q {
            net.push(blossom(&vk, q, kv, &ctrl, &args(va, vb, q, b)));
        }
    }
    Some(net)
}

/// The index `k` of the knot span `[knots[k], knots[k + 1]) = [lo, hi)`.
fn span(knots: &[f64], p: usize, n: usize, range: [f64; 2]) -> Option<usize> {
    (p..n).rev().find(|&k| knots[k] == range[0] && knots[k + 1] == range[1])
}

/// The blossom of the degree-`p` B-spline with `knots` at `args` on span
/// `k` (de Boor's algorithm, one argument per level); `ctrl` holds the
/// control points `k − p ..= k`.
fn blossom(knots: &[Q], p: usize, k: usize, ctrl: &[Hom], args: &[Q]) -> Hom {
    let mut d: Vec<Hom> = ctrl.to_vec();
    for (r, x) in (1..=p).zip(args) {
        for i in (k - p + r..=k).rev() {
            let (lo, hi) = (&knots[i], &knots[i + p + 1 - r]);
            let alpha = (x - lo) / (hi - lo);
            let one_minus = Q::one() - &alpha;
            let idx = i - (k - p);
            let next: Hom = std::array::from_fn(|c| &one_minus * &d[idx - 1][c] + &alpha * &d[idx][c]);
            d[idx] = next;
        }
    }
    d.pop().unwrap_or_else(|| std::array::from_fn(|_| Q::zero()))
}
