//! The candidates of each patch kind: interior critical points (bivariate
//! solve), edge critical points (univariate solves), corners; B-spline
//! surfaces piece by piece.

use super::critical::{edge_function, interior_system};
use super::distance::{box_lower, lower_bound, upper_at};
use super::tensor::TensorPrep;
use super::{Candidate, FootKind};
use crate::error::Result;
use crate::poly::{tri_index, TensorBezier, UniBezier};
use crate::ray::bspline::BsplineSurface;
use crate::ray::patch::{Bb as NetBb, Net, TensorPatch, TriPatch};
use crate::ray::Patch;
use crate::scalar::{interval, point};
use crate::solve::{solve_square, solve_triangle, solve_uni, Box2, Solution, SolveOptions, UniOptions};
use inari::Interval;

/// Every candidate of `patch` for the point `p`, in the patch's parameters.
pub(super) fn candidates(patch: &Prepared<'_>, p: [f64; 3], opts: &SolveOptions) -> Result<Vec<Candidate>> {
    match patch {
        Prepared::Triangle(t) => triangle(t, p, opts),
        Prepared::Tensor(t, prep) => tensor(t, prep.as_deref(), p, opts, f64::INFINITY),
        Prepared::Bspline(s, preps) => bspline(s, preps, p, opts),
    }
}

/// A patch with what its points share, computed once ([`TensorPrep`] for
/// each tensor patch or B-spline piece whose system the box solver takes).
pub(crate) enum Prepared<'a> {
    Triangle(&'a TriPatch),
    Tensor(&'a TensorPatch, Option<Box<TensorPrep>>),
    Bspline(&'a BsplineSurface, Vec<Option<TensorPrep>>),
}

impl<'a> Prepared<'a> {
    pub(crate) fn new(patch: &'a Patch) -> Self {
        match patch {
            Patch::Triangle(t) => Prepared::Triangle(t),
            Patch::Tensor(t) => Prepared::Tensor(t, TensorPrep::new(t).map(Box::new)),
            Patch::Bspline(s) => Prepared::Bspline(s, s.pieces().iter().map(|p| TensorPrep::new(p.patch())).collect()),
        }
    }
}

/// A tensor patch: the prepared path, or the general one when it declines.
fn tensor(
    t: &TensorPatch,
    prep: Option<&TensorPrep>,
    p: [f64; 3],
    opts: &SolveOptions,
    outer: f64,
) -> Result<Vec<Candidate>> {
    if let Some(prep) = prep {
        if let Some(c) = super::tensor::candidates(prep, t, p, opts, outer)? {
            return Ok(c);
        }
    }
    tensor_general(t, p, opts, outer)
}

/// Bounds of the squared distance `D` over boxes and at points.
pub(super) trait Dist {
    /// A lower bound of `D` over the box (one evaluation).
    fn lower(&self, b: &Box2) -> f64;
    /// An upper bound of `D` at `(u, v)`.
    fn upper(&self, u: f64, v: f64) -> f64;
}

/// `D` through the interval homogeneous net (inari).
struct NetDist<'a, P> {
    net: &'a Net<P>,
    p: [f64; 3],
}

impl<P: NetBb<Interval>> Dist for NetDist<'_, P> {
    fn lower(&self, b: &Box2) -> f64 {
        box_lower(self.net, self.p, b)
    }
    fn upper(&self, u: f64, v: f64) -> f64 {
        upper_at(self.net, self.p, u, v)
    }
}

/// A candidate region with its bounds; `at` is moved into the closed domain
/// by `clamp`.
pub(super) fn candidate(
    dist: &dyn Dist,
    bx: Box2,
    kind: FootKind,
    certified: bool,
    clamp: impl Fn([f64; 2]) -> [f64; 2],
) -> Candidate {
    let at = clamp(bx.center());
    Candidate {
        bx,
        at,
        kind,
        certified,
        d: [dist.lower(&bx), dist.upper(at[0], at[1])],
    }
}

/// The interior candidates of a solve: certified roots, undecided regions,
/// leftovers.
pub(super) fn regions(sol: &Solution) -> impl Iterator<Item = (Box2, bool)> + '_ {
    sol.roots
        .iter()
        .map(|r| (r.bx, true))
        .chain(sol.clusters.iter().map(|c| (c.bx, false)))
        .chain(sol.leftovers.iter().map(|l| (l.bx, false)))
}

pub(super) fn clamp_square([u, v]: [f64; 2]) -> [f64; 2] {
    [u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)]
}

/// The point moved into the closed triangle, `u + v ≤ 1` in exact
/// arithmetic (checked as an interval sum's upper bound: a float sum that
/// rounds to 1 may be above it).
fn clamp_triangle([u, v]: [f64; 2]) -> [f64; 2] {
    let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
    if (point(u) + point(v)).sup() <= 1.0 {
        return [u, v];
    }
    // Onto the hypotenuse: u scaled down, then v = 1 − u rounded down.
    let s = u + v;
    let u2 = if s > 1.0 { (u / s).min(1.0) } else { u };
    [u2, (point(1.0) - point(u2)).inf().max(0.0)]
}

/// Tightens the lower bounds of the candidates that might hold the minimum
/// (their cheap bound is below the best upper bound, `outer` included) by
/// refining them against that bound.
fn refine(dist: &dyn Dist, cands: &mut [Candidate], outer: f64) {
    let best = cands.iter().map(|c| c.d[1]).fold(outer, f64::min);
    for c in cands.iter_mut().filter(|c| c.d[0] < best) {
        c.d[0] = c.d[0].max(lower_bound(&|b: &Box2| dist.lower(b), c.bx, best));
    }
}

/// The four edges and corners of a tensor patch, as candidates.
fn tensor_edges(
    net: &Net<TensorBezier<Interval>>,
    p: [f64; 3],
    rational: bool,
    opts: &SolveOptions,
    dist: &dyn Dist,
    out: &mut Vec<Candidate>,
) -> Result<()> {
    let (m, n) = net.c[0].degree();
    // The four edges as curves on [0, 1]: (fixed direction, at), each a net
    // of bidegree (k, 0).
    for (along_u, fixed) in [(true, 0.0), (true, 1.0), (false, 0.0), (false, 1.0)] {
        let curve: [TensorBezier<Interval>; 4] = std::array::from_fn(|k| {
            let c = net.c[k].coeffs();
            let coeffs: Vec<Interval> = if along_u {
                let j = if fixed == 0.0 { 0 } else { n };
                (0..=m).map(|i| c[i * (n + 1) + j]).collect()
            } else {
                let i = if fixed == 0.0 { 0 } else { m };
                (0..=n).map(|j| c[i * (n + 1) + j]).collect()
            };
            let deg = coeffs.len() - 1;
            TensorBezier::on_unit_square(deg, 0, coeffs).expect("finite net")
        });
        let place = |s: [f64; 2]| {
            if along_u {
                Box2::new(s, [fixed, fixed])
            } else {
                Box2::new([fixed, fixed], s)
            }
        };
        edge(&curve, p, rational, opts, &mut |s, certified| {
            out.push(candidate(dist, place(s), FootKind::Edge, certified, clamp_square))
        })?;
    }
    for (u, v) in [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)] {
        out.push(candidate(
            dist,
            Box2::new([u, u], [v, v]),
            FootKind::Corner,
            true,
            clamp_square,
        ));
    }
    Ok(())
}

/// Tensor patches of high degree: the critical-point system in inari
/// intervals, solved through the triangles.
fn tensor_general(t: &TensorPatch, p: [f64; 3], opts: &SolveOptions, outer: f64) -> Result<Vec<Candidate>> {
    let net = t.inet();
    let rational = t.weights().is_some();
    let dist = NetDist { net, p };
    let mut out = Vec::new();
    let (f, g) = interior_system(&net.c, p, rational);
    match solve_square(&f, &g, opts) {
        Ok(sol) => out.extend(regions(&sol).map(|(bx, c)| candidate(&dist, bx, FootKind::Interior, c, clamp_square))),
        // An identically zero equation: every interior point may be critical.
        Err(_) => out.push(candidate(
            &dist,
            Box2::new([0.0, 1.0], [0.0, 1.0]),
            FootKind::Interior,
            false,
            clamp_square,
        )),
    }
    tensor_edges(net, p, rational, opts, &dist, &mut out)?;
    refine(&dist, &mut out, outer);
    Ok(out)
}

fn triangle(t: &TriPatch, p: [f64; 3], opts: &SolveOptions) -> Result<Vec<Candidate>> {
    let net = t.inet();
    let dist = NetDist { net, p };
    let rational = t.weights().is_some();
    let n = t.degree();
    let mut out = Vec::new();
    let (f, g) = interior_system(&net.c, p, rational);
    match solve_triangle(&f, &g, opts) {
        Ok(sol) => out.extend(regions(&sol).map(|(bx, c)| candidate(&dist, bx, FootKind::Interior, c, clamp_triangle))),
        Err(_) => out.push(candidate(
            &dist,
            Box2::new([0.0, 1.0], [0.0, 1.0]),
            FootKind::Interior,
            false,
            clamp_triangle,
        )),
    }
    // Edges: v = 0 (u from 0 to 1: f_{i,0,n−i}), u = 0 (v from 0 to 1:
    // f_{0,j,n−j}), u + v = 1 (u from 0 to 1, v = 1 − u: f_{i,n−i,0}). On each,
    // B^n_{ijk} restricts to the univariate Bernstein polynomial.
    type Place = fn(Interval) -> Box2;
    type Index = fn(usize, usize) -> (usize, usize);
    let edges: [(Index, Place); 3] = [
        (|_n, i| (i, 0), |s| Box2::new([s.inf(), s.sup()], [0.0, 0.0])),
        (|_n, j| (0, j), |s| Box2::new([0.0, 0.0], [s.inf(), s.sup()])),
        (
            |n, i| (i, n - i),
            |s| {
                let v = point(1.0) - s;
                Box2::new([s.inf(), s.sup()], [v.inf().max(0.0), v.sup()])
            },
        ),
    ];
    for (index, place) in edges {
        let curve: [TensorBezier<Interval>; 4] = std::array::from_fn(|k| {
            let c = net.c[k].coeffs();
            let coeffs: Vec<Interval> = (0..=n)
                .map(|r| {
                    let (i, j) = index(n, r);
                    c[tri_index(n, i, j)]
                })
                .collect();
            TensorBezier::on_unit_square(n, 0, coeffs).expect("finite net")
        });
        edge(&curve, p, rational, opts, &mut |s, certified| {
            out.push(candidate(
                &dist,
                place(interval(s[0], s[1])),
                FootKind::Edge,
                certified,
                clamp_triangle,
            ))
        })?;
    }
    for (u, v) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)] {
        out.push(candidate(
            &dist,
            Box2::new([u, u], [v, v]),
            FootKind::Corner,
            true,
            clamp_triangle,
        ));
    }
    refine(&dist, &mut out, f64::INFINITY);
    Ok(out)
}

/// The critical points of `D` along one edge curve (a net of bidegree
/// `(k, 0)` on `[0, 1]`): each region of the univariate solve, as `[s₀, s₁]`
/// with whether it is certified.
fn edge(
    curve: &[TensorBezier<Interval>; 4],
    p: [f64; 3],
    rational: bool,
    opts: &SolveOptions,
    push: &mut dyn FnMut([f64; 2], bool),
) -> Result<()> {
    let h = edge_function(curve, p, rational);
    let (k, _) = h.degree();
    let coeffs: Vec<Interval> = (0..=k).map(|i| *h.coeff(i, 0)).collect();
    let uni = UniBezier::on_unit(coeffs)?;
    let uopts = UniOptions::default().with_eps(opts.eps).with_max_boxes(opts.max_boxes);
    match solve_uni(&uni, &uopts) {
        Ok(sol) => {
            for r in &sol.roots {
                push(r.interval, true);
            }
            for c in sol
                .clusters
                .iter()
                .map(|c| c.interval)
                .chain(sol.leftovers.iter().copied())
            {
                push(c, false);
            }
        }
        // Identically zero: the whole edge may be critical.
        Err(_) => push([0.0, 1.0], false),
    }
    Ok(())
}

/// A B-spline surface piece by piece, each a closed tensor patch (a knot line
/// may be a crease); pieces are visited nearest first (by a lower bound of `D`
/// over the whole piece) and skipped once that bound exceeds the best upper
/// bound found. Boxes are mapped to knot parameters outward; each
/// representative point is chosen in knot parameters and `D` bounded over
/// the interval enclosure of its local coordinates, so the bound holds at the
/// reported point itself.
fn bspline(
    s: &BsplineSurface,
    preps: &[Option<TensorPrep>],
    p: [f64; 3],
    opts: &SolveOptions,
) -> Result<Vec<Candidate>> {
    let unit = Box2::new([0.0, 1.0], [0.0, 1.0]);
    let mut order: Vec<(f64, usize)> = s
        .pieces()
        .iter()
        .enumerate()
        .map(|(k, piece)| (box_lower(piece.patch().inet(), p, &unit), k))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<Candidate> = Vec::new();
    let mut best = f64::INFINITY;
    for (lo, k) in order {
        if lo > best {
            break;
        }
        let piece = &s.pieces()[k];
        let local = tensor(piece.patch(), preps[k].as_ref(), p, opts, best)?;
        let net = piece.patch().inet();
        let (ur, vr) = (piece.u_range(), piece.v_range());
        let to_knots = |range: [f64; 2], b: [f64; 2]| {
            let x0 = point(range[0]);
            let x = x0 + (point(range[1]) - x0) * interval(b[0], b[1]);
            [x.inf(), x.sup()]
        };
        for c in local {
            let bx = Box2::new(to_knots(ur, c.bx.u), to_knots(vr, c.bx.v));
            // A point of the piece in knot parameters, and the enclosure of
            // its local coordinates.
            let at = [bx.center()[0].clamp(ur[0], ur[1]), bx.center()[1].clamp(vr[0], vr[1])];
            let local_of = |x: f64, r: [f64; 2]| {
                let l = (point(x) - point(r[0])) / (point(r[1]) - point(r[0]));
                [l.inf().max(0.0), l.sup().min(1.0)]
            };
            let (lu, lv) = (local_of(at[0], ur), local_of(at[1], vr));
            let hi = upper_over(net, p, Box2::new(lu, lv));
            best = best.min(hi);
            out.push(Candidate {
                bx,
                at,
                kind: c.kind,
                certified: c.certified,
                d: [c.d[0], hi],
            });
        }
    }
    Ok(out)
}

/// An upper bound of `D` over a (tiny) box of local coordinates.
fn upper_over<P: NetBb<Interval>>(net: &Net<P>, p: [f64; 3], bx: Box2) -> f64 {
    let s = crate::ray::patch::eval_interval(net, interval(bx.u[0], bx.u[1]), interval(bx.v[0], bx.v[1]));
    let d = (0..3).fold(point(0.0), |acc, k| acc + (s[k] - point(p[k])).sqr());
    if d.is_empty() || d.sup().is_nan() {
        f64::INFINITY
    } else {
        d.sup()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;

    /// `0.1 + 0.9` rounds to 1 in floats but exceeds it exactly: moved onto
    /// the hypotenuse so that `u + v ≤ 1` holds exactly.
    #[test]
    fn triangle_points_are_inside_exactly() {
        let q = |x: f64| BigRational::from_float(x).unwrap();
        let one = BigRational::from_integer(1.into());
        assert_eq!(0.1 + 0.9, 1.0);
        assert!(q(0.1) + q(0.9) > one);
        for p in [[0.1, 0.9], [0.7, 0.3], [1.5, 0.25], [-0.5, 2.0], [1e-300, 1.0]] {
            let [u, v] = clamp_triangle(p);
            assert!(u >= 0.0 && v >= 0.0 && q(u) + q(v) <= one, "{p:?} -> ({u}, {v})");
        }
        assert_eq!(clamp_triangle([0.25, 0.5]), [0.25, 0.5]);
    }
}
