//! Krawczyk's operator for a continuous, piecewise polynomial system: `G(x)
//! = F_k(x)` on the closed cell of piece `k`, the cells covering the plane
//! and the pieces agreeing where cells meet (the ray front end's B-spline
//! surfaces, whose hits on knot lines are roots of several pieces).
//!
//! # The operator
//! Along a segment in a box `X`, `G` runs through the pieces in turn, so
//! `G(x) − G(y) = A (x − y)` with `A = Σ λ_k A_k` a convex combination of the
//! pieces' Jacobians `A_k ∈ J_k(X)` over `X`. Hence
//!
//! ```text
//! K(X) = x̃ − Y G(x̃) + hull ⋃_k (I − Y J_k(X)) (X − x̃),    Y ≈ (mid hull_k J_k(X))⁻¹,
//! ```
//! encloses `x − Y G(x)` for every `x ∈ X` (`(I − Y A) d = Σ λ_k (I − Y A_k) d`),
//! and Krawczyk's proofs go through (Krawczyk 1969; Neumaier 1990, *Interval
//! Methods for Systems of Equations*, ch. 5): `K(X) ⊂ int X` gives a zero by
//! Brouwer, and `|I − Y A_k| r < r` for every `k` (`r = rad X`) gives it for
//! every convex combination, so every such `A` is regular and the zero is
//! unique. Multiplying by the interval hull of the `J_k` instead would mix
//! entries of different pieces and fail across a crease, where the pieces'
//! `∂G/∂u` differ while `∂G/∂v` (along the line) agree; the per-piece form
//! succeeds there whenever both sides face the same way (for boxes small
//! enough that each `J_k(X)` is nearly a point).
//!
//! The pieces are [`Bivariate`] polynomials enclosed in inari, as for
//! [`System`](super::System); only the assembly of `K` differs.

use super::interval::{inflate, width, Bivariate};
use super::verdict::IBox;
use super::verdict::Verdict;
use crate::scalar::point;
use crate::solve::linalg::inverse2;
use inari::Interval;

/// One piece `F_k = (f, g)` of a piecewise system, with its Jacobian.
pub(crate) struct Piece<P: Bivariate> {
    f: [P; 2],
    jac: [P; 4],
}

impl<P: Bivariate> Piece<P> {
    /// The piece `(f, g)`.
    pub(crate) fn new(f: P, g: P) -> Self {
        let [fu, fv] = f.partials();
        let [gu, gv] = g.partials();
        Self {
            f: [f, g],
            jac: [fu, fv, gu, gv],
        }
    }
}

/// A continuous piecewise polynomial system `G` (module docs).
pub(crate) trait Piecewise {
    /// The pieces' polynomials.
    type P: Bivariate;
    /// The pieces whose closed cells meet the box `x`; `None` if one of them
    /// cannot be formed (then nothing is proven).
    fn pieces(&self, x: IBox) -> Option<Vec<Piece<Self::P>>>;
}

/// One step of the operator `K` of the module docs: `G(x̃)` enclosed by the
/// hull over the pieces holding `x̃`, `J_k(X)` for every piece meeting `X`
/// (over all of `X`), `Y ≈ (mid hull J_k)⁻¹` — the midpoint of the hull, not
/// one piece's Jacobian, as the pieces' Jacobians may differ by a large
/// factor across a cell boundary (B-spline spans of different lengths).
pub(crate) fn step<G: Piecewise>(system: &G, x: IBox) -> Verdict {
    let mid = [x[0].mid(), x[1].mid()];
    if !(mid[0].is_finite() && mid[1].is_finite()) {
        return Verdict::Undecided(x);
    }
    let xm = mid.map(point);
    let hull2 = |a: [Interval; 2], b: [Interval; 2]| [a[0].convex_hull(b[0]), a[1].convex_hull(b[1])];
    let mut gx = [Interval::EMPTY; 2];
    let Some(at_mid) = system.pieces(xm) else {
        return Verdict::Undecided(x);
    };
    for piece in &at_mid {
        gx = hull2(gx, piece.f.each_ref().map(|f| f.value(xm[0], xm[1])));
    }
    let Some(over_x) = system.pieces(x) else {
        return Verdict::Undecided(x);
    };
    let jacobians: Vec<[Interval; 4]> = over_x
        .iter()
        .map(|piece| piece.jac.each_ref().map(|p| p.value(x[0], x[1])))
        .collect();
    let j = jacobians.iter().fold([Interval::EMPTY; 4], |acc, jk| {
        std::array::from_fn(|i| acc[i].convex_hull(jk[i]))
    });
    let Some(y) = inverse2(j.map(|c| c.mid()), 1e-14) else {
        return Verdict::Undecided(x);
    };
    let y = y.map(point);
    let yg = [y[0] * gx[0] + y[1] * gx[1], y[2] * gx[0] + y[3] * gx[1]];
    let dx = [x[0] - xm[0], x[1] - xm[1]];
    let one = point(1.0);
    let spread = jacobians.iter().fold([Interval::EMPTY; 2], |acc, jk| {
        let m = [
            one - (y[0] * jk[0] + y[1] * jk[2]),
            -(y[0] * jk[1] + y[1] * jk[3]),
            -(y[2] * jk[0] + y[3] * jk[2]),
            one - (y[2] * jk[1] + y[3] * jk[3]),
        ];
        hull2(acc, [m[0] * dx[0] + m[1] * dx[1], m[2] * dx[0] + m[3] * dx[1]])
    });
    let k = [xm[0] - yg[0] + spread[0], xm[1] - yg[1] + spread[1]];
    if k.iter().any(|c| c.is_empty()) {
        return Verdict::Undecided(x);
    }
    if k[0].interior(x[0]) && k[1].interior(x[1]) {
        return Verdict::Unique(k);
    }
    let meet = [k[0].intersection(x[0]), k[1].intersection(x[1])];
    if meet[0].is_empty() || meet[1].is_empty() {
        Verdict::NoRoot
    } else {
        Verdict::Undecided(meet)
    }
}

/// Tries to prove that `G` has exactly one zero in a box containing `x0`, by
/// [`step`] with epsilon-inflation (every box tried contains `x0`, as in
/// [`System::certify`](super::System::certify)): `Unique` with a box holding
/// it, contracted while steps narrow it; `NoRoot` when a tried box (which
/// contains `x0`) holds none; otherwise `Undecided` with the last box tried.
pub(crate) fn certify<G: Piecewise>(system: &G, x0: IBox) -> Verdict {
    let mut x = x0.map(|c| inflate(c, 0.1));
    for _ in 0..10 {
        match step(system, x) {
            Verdict::Unique(mut k) => {
                // Each further K(K) ⊂ int K is proven to hold the same zero.
                for _ in 0..8 {
                    match step(system, k) {
                        Verdict::Unique(next) if width(next) < width(k) => k = next,
                        _ => break,
                    }
                }
                return Verdict::Unique(k);
            }
            Verdict::NoRoot => return Verdict::NoRoot,
            Verdict::Undecided(k) => x = [0, 1].map(|i| inflate(k[i].convex_hull(x0[i]), 1.0)),
        }
    }
    Verdict::Undecided(x)
}
