//! Duplicate hits at knot lines: a hit on a knot line is a root of both
//! neighbouring pieces (all four at a corner) and is reported by each; this
//! module merges such reports only when a proof says they are one hit.
//!
//! # Why overlapping boxes are not enough
//! Near a crease (an interior knot of multiplicity `p`) a ray can cross both
//! sheets within a box width of the line, and a piece may report a root of its
//! polynomial *extension* beyond the line. Neither is "the same hit twice".
//!
//! # The proof
//! Certified hits of different pieces whose `(u, v)` boxes overlap
//! (transitively) form a group; it is replaced by one hit only if Krawczyk's
//! operator proves that the *piecewise* system
//!
//! ```text
//! G(x) = F_k(x)   for x in the rectangle of piece k (the outer pieces' unbounded),
//! F_k = (n₁·(X_k − W_k o), n₂·(X_k − W_k o))   (the ray's two planes, as in ray::intersect)
//! ```
//! has exactly one zero in a box `X` holding all of the group's boxes. The
//! stored pieces join exactly (they share their boundary control points bit
//! for bit), so `G` is continuous and piecewise polynomial, and every true
//! hit in `X` is a zero of `G`. Along a segment in `X`, `G` runs through the
//! pieces in turn, so `G(x) − G(y) = A (x − y)` with `A = Σ λ_k A_k` a convex
//! combination of the pieces' Jacobians `A_k ∈ J_k(X)` over `X`. Hence
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
//! enough that each `J_k(X)` is nearly a point). On success the
//! group becomes one certified hit with the contracted box and `t` enclosed
//! over it.
//!
//! # Degenerate cases
//! Where the pieces meeting at the hit do not all face the same way as seen
//! along the ray (a fold, or a pyramid apex seen partly from behind), `G` is
//! not one-to-one near the hit and no proof exists: the group's reports are
//! all kept. A hit is never dropped; at worst each piece reports it.

use super::{BezierPiece, BsplineSurface};
use crate::poly::{Direction, TensorBezier};
use crate::ray::{Hit, HitBox, Planes, Ray};
use crate::scalar::{interval, point};
use crate::solve::krawczyk::{IBox, Verdict};
use crate::solve::linalg::inverse2;
use inari::Interval;
use std::collections::BTreeMap;

/// A piece proved exactly one root of its polynomial in the hit's box (on
/// the piece, or within rounding of its edge).
fn proven_root(h: &Hit) -> bool {
    h.certified || h.on_edge
}

fn overlaps(a: [f64; 2], b: [f64; 2]) -> bool {
    a[0] <= b[1] && b[0] <= a[1]
}

/// Groups certified hits of different pieces whose `(u, v)` boxes overlap
/// (transitively) and replaces a group by one hit where
/// [`certify_piecewise`] proves a single zero; everything else is kept.
pub(super) fn merge_knot_line_duplicates(surface: &BsplineSurface, ray: &Ray, found: Vec<(Hit, usize)>) -> Vec<Hit> {
    let n = found.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for i in 0..n {
        for j in i + 1..n {
            let ((a, pa), (b, pb)) = (&found[i], &found[j]);
            if proven_root(a) && proven_root(b) && pa != pb && overlaps(a.bx.u, b.bx.u) && overlaps(a.bx.v, b.bx.v) {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                parent[ri] = rj;
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<Hit>> = BTreeMap::new();
    for (i, (hit, _)) in found.into_iter().enumerate() {
        let r = root(&mut parent, i);
        groups.entry(r).or_default().push(hit);
    }
    let mut planes = None;
    let mut out = Vec::new();
    for group in groups.into_values() {
        // A single report needs the piecewise proof only when its piece
        // could not place its root on the piece (the box crosses a knot line).
        if group.len() == 1 && !group[0].on_edge {
            out.extend(group);
            continue;
        }
        let hull = |f: fn(&Hit) -> [f64; 2]| {
            group
                .iter()
                .map(|h| interval(f(h)[0], f(h)[1]))
                .fold(Interval::EMPTY, |a, b| a.convex_hull(b))
        };
        let x0 = [hull(|h| h.bx.u), hull(|h| h.bx.v)];
        let planes = planes.get_or_insert_with(|| Planes::of(ray));
        match certify_piecewise(surface, planes, x0) {
            Some(k) => out.extend(merged_hit(surface, planes, k)),
            None => out.extend(group),
        }
    }
    out
}

/// The merged hit of a proven box `k`: `t` enclosed over `k` on every piece
/// meeting it; `None` if `t` is provably negative.
fn merged_hit(surface: &BsplineSurface, planes: &Planes, k: IBox) -> Option<Hit> {
    let t = meeting(surface, k)
        .map(|piece| {
            let h: [Interval; 4] = std::array::from_fn(|c| piece.hom[c].eval(k[0], k[1]));
            planes.t_of([h[0] / h[3], h[1] / h[3], h[2] / h[3]])
        })
        .fold(Interval::EMPTY, |a, b| a.convex_hull(b));
    if t.sup() < 0.0 {
        return None;
    }
    let (u, v) = (k[0].mid(), k[1].mid());
    let (su, sv) = surface.partials(u, v);
    // The zero of the piecewise system is a hit if it lies on the surface's
    // closed parameter domain (the outer pieces' extensions are not) and
    // t ≥ 0 is proven.
    let (bu, bv) = (&surface.breaks_u, &surface.breaks_v);
    let inside =
        k[0].inf() >= bu[0] && k[0].sup() <= bu[bu.len() - 1] && k[1].inf() >= bv[0] && k[1].sup() <= bv[bv.len() - 1];
    Some(Hit {
        t: t.mid(),
        u,
        v,
        point: surface.eval(u, v),
        normal: su.cross(sv).normalize_or_zero(),
        certified: inside && t.inf() >= 0.0 && t.sup().is_finite(),
        on_edge: !inside,
        t_straddles_zero: t.inf() <= 0.0,
        bx: HitBox {
            u: [k[0].inf(), k[0].sup()],
            v: [k[1].inf(), k[1].sup()],
            t: [t.inf(), t.sup()],
        },
    })
}

/// The pieces whose extended rectangles meet the box `x` (the outer pieces
/// extend to infinity, so every point of the plane belongs to a piece).
fn meeting(surface: &BsplineSurface, x: IBox) -> impl Iterator<Item = &BezierPiece> {
    let cols = spans_meeting(&surface.breaks_u, x[0]);
    let rows = spans_meeting(&surface.breaks_v, x[1]);
    let nv = surface.breaks_v.len() - 1;
    cols.flat_map(move |a| rows.clone().map(move |b| &surface.pieces[a * nv + b]))
}

fn spans_meeting(breaks: &[f64], x: Interval) -> std::ops::Range<usize> {
    let inner = &breaks[1..breaks.len() - 1];
    // Span a covers [breaks[a], breaks[a + 1]] (closed), unbounded at the ends.
    inner.partition_point(|&b| b < x.inf())..inner.partition_point(|&b| b <= x.sup()) + 1
}

/// One piece's reduced system `F_k = (n₁·(X − W o), n₂·(X − W o))` on its
/// rectangle in knot parameters, with its Jacobian.
struct PieceSystem {
    f: [TensorBezier<Interval>; 2],
    jac: [TensorBezier<Interval>; 4],
}

impl PieceSystem {
    fn of(piece: &BezierPiece, planes: &Planes) -> Option<Self> {
        let (m, n) = piece.hom[3].degree();
        let (du, dv) = piece.hom[3].domain();
        let cols: [&[Interval]; 4] = std::array::from_fn(|c| piece.hom[c].coeffs());
        let f = [0, 1].map(|k| {
            let coeffs = (0..cols[3].len())
                .map(|i| {
                    (0..3).fold(point(0.0), |acc, c| {
                        acc + planes.n[k][c] * (cols[c][i] - cols[3][i] * planes.o[c])
                    })
                })
                .collect();
            TensorBezier::new(m, n, coeffs, *du, *dv).ok()
        });
        let [Some(f0), Some(f1)] = f else { return None };
        let jac = [
            f0.deriv(Direction::U),
            f0.deriv(Direction::V),
            f1.deriv(Direction::U),
            f1.deriv(Direction::V),
        ];
        Some(Self { f: [f0, f1], jac })
    }
}

/// One step of the operator `K` of the module docs: `G(x̃)` enclosed by the
/// hull over the pieces holding `x̃`, `J_k(X)` for every piece meeting `X`
/// (over all of `X`), `Y ≈ (mid hull J_k)⁻¹` — the midpoint of the hull, not
/// one piece's Jacobian, as the pieces' Jacobians may differ by a large
/// factor across a knot line (spans of different lengths).
fn krawczyk_step(surface: &BsplineSurface, planes: &Planes, x: IBox) -> Verdict {
    let mid = [x[0].mid(), x[1].mid()];
    if !(mid[0].is_finite() && mid[1].is_finite()) {
        return Verdict::Undecided(x);
    }
    let xm = mid.map(point);
    let hull2 = |a: [Interval; 2], b: [Interval; 2]| [a[0].convex_hull(b[0]), a[1].convex_hull(b[1])];
    let mut gx = [Interval::EMPTY; 2];
    for piece in meeting(surface, xm) {
        let Some(sys) = PieceSystem::of(piece, planes) else {
            return Verdict::Undecided(x);
        };
        gx = hull2(gx, sys.f.each_ref().map(|f| f.eval(xm[0], xm[1])));
    }
    let mut jacobians = Vec::new();
    for piece in meeting(surface, x) {
        let Some(sys) = PieceSystem::of(piece, planes) else {
            return Verdict::Undecided(x);
        };
        jacobians.push(sys.jac.each_ref().map(|p| p.eval(x[0], x[1])));
    }
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

/// Proves that `G` has exactly one zero in a box containing `x0` and returns
/// a box holding it (epsilon-inflation as in the solver's certification:
/// every box tried contains `x0`), or `None`.
fn certify_piecewise(surface: &BsplineSurface, planes: &Planes, x0: IBox) -> Option<IBox> {
    let mut x = x0.map(|c| inflate(c, 0.1));
    for _ in 0..10 {
        match krawczyk_step(surface, planes, x) {
            Verdict::Unique(mut k) => {
                // Each further K(K) ⊂ int K is proven to hold the same zero.
                for _ in 0..8 {
                    match krawczyk_step(surface, planes, k) {
                        Verdict::Unique(next) if width(next) < width(k) => k = next,
                        _ => break,
                    }
                }
                return Some(k);
            }
            Verdict::NoRoot => return None,
            Verdict::Undecided(k) => x = [0, 1].map(|i| inflate(k[i].convex_hull(x0[i]), 1.0)),
        }
    }
    None
}

fn width(x: IBox) -> f64 {
    x[0].wid().max(x[1].wid())
}

/// `x` widened by `rel` of its width plus a few ulps on each side.
fn inflate(x: Interval, rel: f64) -> Interval {
    let r = rel * x.wid() + 4.0 * f64::EPSILON * x.mag().max(f64::MIN_POSITIVE);
    interval((x.inf() - r).next_down(), (x.sup() + r).next_up())
}
