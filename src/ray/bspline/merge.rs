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
//! hit in `X` is a zero of `G`. The operator is Krawczyk's for piecewise
//! systems (`solve::krawczyk::piecewise`: `G(x̃)` enclosed over the pieces
//! holding `x̃`, and one `I − Y J_k(X)` per piece meeting `X`, which keeps
//! the proof valid across a crease, where the pieces' `∂G/∂u` differ while
//! `∂G/∂v` (along the line) agree). On success the group becomes one
//! certified hit with the contracted box and `t` enclosed over it.
//!
//! # Degenerate cases
//! Where the pieces meeting at the hit do not all face the same way as seen
//! along the ray (a fold, or a pyramid apex seen partly from behind), `G` is
//! not one-to-one near the hit and no proof exists: the group's reports are
//! all kept. A hit is never dropped; at worst each piece reports it.

use super::surface::{BezierPiece, BsplineSurface};
use crate::poly::TensorBezier;
use crate::ray::hit::{Hit, HitBox, HitStatus};
use crate::ray::planes::Planes;
use crate::ray::query::Ray;
use crate::scalar::{interval, point};
use crate::solve::krawczyk::piecewise::{self, Piece, Piecewise};
use crate::solve::krawczyk::{IBox, Verdict};
use crate::solve::UndecidedReason;
use inari::Interval;
use std::collections::BTreeMap;

fn overlaps(a: [f64; 2], b: [f64; 2]) -> bool {
    a[0] <= b[1] && b[0] <= a[1]
}

/// Groups certified hits of different pieces whose `(u, v)` boxes overlap
/// (transitively) and replaces a group by one hit where
/// [`piecewise::certify`] proves a single zero; everything else is kept.
pub(super) fn merge_knot_line_duplicates(
    surface: &BsplineSurface,
    ray: &Ray,
    found: Vec<(Hit, usize)>,
    range: [f64; 2],
) -> Vec<Hit> {
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
            if a.is_proven_root()
                && b.is_proven_root()
                && pa != pb
                && overlaps(a.bx.u, b.bx.u)
                && overlaps(a.bx.v, b.bx.v)
            {
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
        if group.len() == 1 && !group[0].on_edge() {
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
        match piecewise::certify(&KnotLineSystem { surface, planes }, x0) {
            Verdict::Unique(k) => out.extend(merged_hit(surface, planes, k, range)),
            Verdict::NoRoot | Verdict::Undecided(_) => out.extend(group),
        }
    }
    out
}

/// The merged hit of a proven box `k`: `t` enclosed over `k` on every piece
/// meeting it; `None` if `t` is provably outside `range`.
fn merged_hit(surface: &BsplineSurface, planes: &Planes, k: IBox, [lo, hi]: [f64; 2]) -> Option<Hit> {
    let t = meeting(surface, k)
        .map(|piece| {
            let h: [Interval; 4] = std::array::from_fn(|c| piece.hom[c].eval(k[0], k[1]));
            planes.t_of([h[0] / h[3], h[1] / h[3], h[2] / h[3]])
        })
        .fold(Interval::EMPTY, |a, b| a.convex_hull(b));
    if t.sup() < lo || t.inf() > hi {
        return None;
    }
    let (u, v) = (k[0].mid(), k[1].mid());
    let (su, sv) = surface.partials(u, v);
    // The zero of the piecewise system is a hit if it lies on the surface's
    // closed parameter domain (the outer pieces' extensions are not) and
    // its t is proven to lie in the range.
    let (bu, bv) = (&surface.breaks_u, &surface.breaks_v);
    let inside =
        k[0].inf() >= bu[0] && k[0].sup() <= bu[bu.len() - 1] && k[1].inf() >= bv[0] && k[1].sup() <= bv[bv.len() - 1];
    Some(Hit {
        t: t.mid(),
        u,
        v,
        point: surface.eval(u, v),
        normal: su.cross(sv).normalize_or_zero(),
        status: if !inside {
            HitStatus::Undecided(UndecidedReason::Boundary)
        } else if !(t.inf() >= lo && t.sup() <= hi && t.inf().is_finite() && t.sup().is_finite()) {
            HitStatus::Undecided(UndecidedReason::RangeEnd)
        } else {
            HitStatus::Certified
        },
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

/// The piecewise system `G` of the module docs for one ray: on each piece's
/// extended rectangle, the piece's reduced system.
struct KnotLineSystem<'a> {
    surface: &'a BsplineSurface,
    planes: &'a Planes,
}

impl Piecewise for KnotLineSystem<'_> {
    type P = TensorBezier<Interval>;

    fn pieces(&self, x: IBox) -> Option<Vec<Piece<Self::P>>> {
        meeting(self.surface, x)
            .map(|piece| reduced(piece, self.planes))
            .collect()
    }
}

/// One piece's reduced system `F_k = (n₁·(X − W o), n₂·(X − W o))` on its
/// rectangle in knot parameters, with its Jacobian.
fn reduced(piece: &BezierPiece, planes: &Planes) -> Option<Piece<TensorBezier<Interval>>> {
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
    Some(Piece::new(f0, f1))
}
