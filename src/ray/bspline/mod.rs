//! B-spline and NURBS surfaces for the ray front end: validated input, Bézier
//! extraction by knot insertion, and certified hits with the duplicates at
//! knot lines merged only when a proof says they are one hit.
//!
//! # Surface
//! ```text
//! S(u, v) = Σ_i Σ_j w_ij P_ij N_i,p(u) N_j,q(v) / Σ_i Σ_j w_ij N_i,p(u) N_j,q(v),
//!           (u, v) ∈ [u_p, u_{n_u}] × [v_q, v_{n_v}],
//! ```
//! with `N_i,p` the B-spline basis of degree `p` on the knot vector
//! `u_0 ≤ … ≤ u_{n_u+p}` (Cox–de Boor), `n_u × n_v` control points stored
//! row-major (`P_ij` at index `i·n_v + j`) and all `w_ij = 1` without weights.
//! Clamped and unclamped knot vectors are both accepted; the domain is always
//! `[knots[p], knots[n]]`.
//!
//! # Decomposition (Boehm 1980, doi:10.1016/0010-4485(80)90154-2; Piegl &
//! Tiller, *The NURBS Book*, §5.2 and Algorithm A5.6)
//! Every distinct knot value in the domain, both ends included, is inserted
//! until it has multiplicity `p` (in `u`; `q` in `v`), on the homogeneous
//! coordinates `(w·x, w·y, w·z, w)` (on `(x, y, z)` alone for a polynomial
//! surface, so that its pieces stay polynomial). On each span `[ξ_a, ξ_{a+1}]`
//! of positive length the `p + 1` control points whose basis functions live
//! there are then the Bézier net of the piece; zero-length spans give no piece.
//! The insertions are convex combinations in `f64`: a piece's control points
//! are the exact ones up to a few ulps of the net's magnitude per inserted
//! knot, a bound computed alongside, and each piece's interval net is
//! widened by it. Certificates (below) therefore speak about the exact
//! surface of the given knots, points and weights, as a [`TensorPatch`]'s
//! speak about its `f64` input.
//!
//! Neighbouring pieces take their common boundary row (or column) from the
//! same entries of the refined net, bit for bit, so the stored pieces join
//! exactly: along a knot line both pieces are the same rational curve.
//!
//! # Hits
//! [`intersect_bspline`] culls every piece whose control-net bounding box
//! (enlarged by `1e-9` of its size; the convex hull property makes this
//! conservative) the ray provably misses for `t` in the range, intersects the others
//! with [`intersect`](super::intersect), and maps each `(u, v)` box from the
//! piece's `[0, 1]²` to knot parameters by `u = u₀ + (u₁ − u₀)·s` in interval
//! arithmetic (outward). A certified box then holds exactly one root of its
//! piece's system; when it reaches across a knot line, that root may be one
//! of the piece's polynomial *extension* lying within the box's width of the
//! line (the [`Root::on_boundary`](crate::solve::Root::on_boundary) contract
//! of the solver, now at interior lines too).
//!
//! # Duplicates at knot lines
//! A hit on a knot line is found by both neighbouring pieces (four at a
//! corner). Overlapping boxes alone do not prove that two reports are one hit
//! (a crease can be crossed twice within a box width), so a group of
//! overlapping certified reports is merged only when Krawczyk's operator on
//! the piecewise system proves a single zero; otherwise all are kept. See
//! [`merge`].
//!
//! # Degenerate cases
//! A ray in the plane of a planar piece makes the whole ray
//! [`RayOutcome::Degenerate`] with [`Degeneracy::ZeroEquation`]; an unresolved
//! piece makes it [`Degeneracy::Unresolved`] with every hit found (all pieces),
//! `complete` only if every piece finished within its budget.

pub(crate) mod exact;
mod merge;
mod surface;

pub use surface::{BezierPiece, BsplineSurface};

use super::bezier::intersect_bezier;
use super::hit::{Degeneracy, Hit, HitBox, HitStatus, RayHits, RayOutcome};
use super::patch::BezierRef;
use super::query::{Query, Ray, RayOptions};
use super::regions::{select, sort_by_t};
use crate::error::Result;
use crate::scalar::{interval, point};
use glam::DVec3;
use inari::Interval;

/// Every hit of `ray` with the B-spline/NURBS `surface` for `t` in the range, in knot
/// parameters, sorted by `t`; see the module docs for the culling, the
/// mapping, the merge of duplicates at knot lines and the degenerate cases.
/// Each piece is solved with `opts` (budgets are per piece).
///
/// ```
/// use glam::DVec3;
/// use rootclip::ray::{intersect, BsplineSurface, Patch, Ray, RayOptions, RayOutcome};
/// // A biquadratic bump over [0, 3] × [0, 1], clamped, three pieces in u.
/// let ku = vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0];
/// let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// let pts = (0..5).flat_map(|i| (0..3).map(move |j| DVec3::new(i as f64, j as f64, ((i + j) % 2) as f64))).collect();
/// let s = BsplineSurface::new((2, 2), ku, kv, pts, None).unwrap();
/// let ray = Ray::new(s.eval(1.3, 0.6) + DVec3::Z, -DVec3::Z).unwrap();
/// let RayOutcome::Hits(h) = intersect(&Patch::from(s), &ray, &RayOptions::default()).unwrap() else { panic!() };
/// assert!(h.complete && h.hits.len() == 1 && h.hits[0].is_certified());
/// assert!(h.hits[0].bx.u[0] <= 1.3 + 1e-12 && 1.3 - 1e-12 <= h.hits[0].bx.u[1]);
/// ```
pub(crate) fn intersect_bspline(surface: &BsplineSurface, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    // Each piece answers `All` (or `Any`, which may stop the loop); the
    // query is applied to the merged list.
    let piece_opts = RayOptions {
        query: if opts.query == Query::Any {
            Query::Any
        } else {
            Query::All
        },
        ..opts.clone()
    };
    let mut found = Vec::new();
    let (mut complete, mut unresolved) = (true, false);
    for (k, piece) in surface.pieces.iter().enumerate() {
        if !box_may_meet(piece.lo, piece.hi, ray, opts.t_range) {
            continue;
        }
        let hits = match intersect_bezier(BezierRef::Tensor(&piece.patch), ray, &piece_opts)? {
            RayOutcome::Hits(h) => h.hits,
            RayOutcome::Degenerate(Degeneracy::ZeroEquation) => {
                return Ok(RayOutcome::Degenerate(Degeneracy::ZeroEquation))
            }
            RayOutcome::Degenerate(Degeneracy::Unresolved(h) | Degeneracy::AlongSurface(h)) => {
                unresolved = true;
                complete &= h.complete;
                h.hits
            }
        };
        // A root the piece could not place on its side of an edge (its net
        // carries knot-insertion error) is settled on the exact net.
        let hits: Vec<Hit> = hits
            .into_iter()
            .filter_map(|h| settle_on_edge(surface, piece, ray, h, opts.t_range))
            .collect();
        let done = opts.query == Query::Any && hits.iter().any(Hit::is_certified);
        found.extend(hits.into_iter().map(|h| (to_knot_hit(piece, h), k)));
        if done {
            break;
        }
    }
    let mut hits = merge::merge_knot_line_duplicates(surface, ray, found, opts.t_range);
    sort_by_t(&mut hits);
    Ok(if unresolved {
        RayOutcome::Degenerate(Degeneracy::Unresolved(RayHits { complete, hits }))
    } else {
        select(&mut hits, opts.query);
        RayOutcome::Hits(RayHits { complete: true, hits })
    })
}

/// A piece's hit, settled in exact arithmetic if it is undecided only at the
/// piece's edge ([`UndecidedReason::Boundary`](crate::solve::UndecidedReason::Boundary)):
/// certified if its root is on the piece with `t` in the range, `None` if it
/// is off it or out of range, unchanged if undecided.
///
/// A settled hit's box is cut to the piece (past its edge the surface is
/// another piece, which may hold a hit of its own within the box). A root
/// exactly on an interior knot line is a root of both neighbouring pieces;
/// it is kept by the piece below the line only, and left to the piecewise
/// proof of [`merge`] (at a C⁰ crease a ray may touch the surface there
/// without crossing it, which no single piece can tell).
fn settle_on_edge(surface: &BsplineSurface, piece: &BezierPiece, ray: &Ray, h: Hit, range: [f64; 2]) -> Option<Hit> {
    use crate::solve::settle::{Edge, Settled, Shape};
    use crate::solve::Box2;
    if !h.on_edge() {
        return Some(h);
    }
    let (p, q) = surface.degree;
    let check_hi = h.bx.t[1] > range[1] || h.bx.t[1].is_nan();
    let Some(systems) = exact::exact_piece_net(surface, piece)
        .and_then(|net| super::settle::systems_of_net(Shape::Tensor(p, q), &net, ray, range, check_hi))
    else {
        return Some(h);
    };
    let bx = Box2 { u: h.bx.u, v: h.bx.v };
    match super::settle::settle_all(&systems, bx) {
        Settled::Inside => {
            let on = systems[0].root_edges(bx);
            let (bu, bv) = (&surface.breaks_u, &surface.breaks_v);
            let below_line =
                (on.contains(&Edge::U0) && piece.u[0] > bu[0]) || (on.contains(&Edge::V0) && piece.v[0] > bv[0]);
            if below_line {
                return None;
            }
            // Exactly on an interior knot line (or corner) the root is a zero
            // of this piece's polynomial, a simple one, but the surface there
            // is two pieces: at a crease the ray may touch it without crossing.
            // Only the piecewise proof of the merge step certifies it.
            let on_line = (on.contains(&Edge::U1) && piece.u[1] < bu[bu.len() - 1])
                || (on.contains(&Edge::V1) && piece.v[1] < bv[bv.len() - 1]);
            let clamp = |x: [f64; 2]| [x[0].max(0.0), x[1].min(1.0)];
            Some(Hit {
                status: if on_line {
                    HitStatus::Undecided(crate::solve::UndecidedReason::Boundary)
                } else {
                    HitStatus::Certified
                },
                bx: HitBox {
                    u: clamp(h.bx.u),
                    v: clamp(h.bx.v),
                    t: [h.bx.t[0].max(range[0]), h.bx.t[1].min(range[1])],
                },
                ..h
            })
        }
        Settled::Outside => None,
        Settled::Undecided => Some(h),
    }
}

/// `false` only if the ray provably misses, for `t` in `range`, the box
/// `[lo, hi]` enlarged by `1e-9` of its size (slab test in interval
/// arithmetic).
fn box_may_meet(lo: DVec3, hi: DVec3, ray: &Ray, range: [f64; 2]) -> bool {
    let scale = (hi - lo)
        .max_element()
        .max(lo.abs().max_element())
        .max(hi.abs().max_element());
    let pad = 1e-9 * scale + f64::MIN_POSITIVE;
    let (o, d) = (ray.origin(), ray.dir());
    let (mut enter, mut exit) = (range[0], range[1]);
    for c in 0..3 {
        let (l, h) = (lo[c] - pad, hi[c] + pad);
        if d[c] == 0.0 {
            if o[c] < l || o[c] > h {
                return false;
            }
            continue;
        }
        let a = (point(l) - point(o[c])) / point(d[c]);
        let b = (point(h) - point(o[c])) / point(d[c]);
        if a.is_empty() || b.is_empty() {
            return true;
        }
        let (near, far) = if d[c] > 0.0 { (a, b) } else { (b, a) };
        enter = enter.max(near.inf());
        exit = exit.min(far.sup());
    }
    enter <= exit
}

/// `[x₀ + (x₁ − x₀)·lo, x₀ + (x₁ − x₀)·hi]`, rounded outward.
fn to_knot_interval(range: [f64; 2], b: [f64; 2]) -> Interval {
    let x0 = point(range[0]);
    x0 + (point(range[1]) - x0) * interval(b[0], b[1])
}

/// A piece's hit with its `(u, v)` box mapped outward to knot parameters
/// (`point` and `normal` are the piece's: the same surface point, and the
/// spans' positive lengths do not turn the normal).
fn to_knot_hit(piece: &BezierPiece, h: Hit) -> Hit {
    let (u, v) = (to_knot_interval(piece.u, h.bx.u), to_knot_interval(piece.v, h.bx.v));
    Hit {
        u: u.mid(),
        v: v.mid(),
        bx: HitBox {
            u: [u.inf(), u.sup()],
            v: [v.inf(), v.sup()],
            t: h.bx.t,
        },
        ..h
    }
}
