//! One Bézier patch (triangular or tensor, polynomial or rational) against a
//! ray: the route to the solver, and the triangle route itself.

use super::boxes;
use super::hit::{Degeneracy, Hit, RayHits, RayOutcome};
use super::patch::{eval_interval, Bb, BezierRef, Net};
use super::planes::{reduce, Planes};
use super::query::{Ray, RayOptions};
use super::regions::{finish, region_hit, sort_by_t};
use super::settle;
use crate::error::{Error, Result};
use crate::poly::{TensorBezier, TriBezier};
use crate::scalar::{interval, point};
use crate::solve::{solve_square, solve_triangle, Solution, SquareRoute};
use inari::Interval;

/// Boxes (or tri-boxes) a transversal ray may use before the exact test
/// for a ray along the surface: it needs a few dozen.
const FIRST_BUDGET: usize = 2_000;

/// The hits of `ray` with one Bézier patch ([`super::intersect`]'s contract).
/// First with a budget sized for a transversal ray; a ray that exhausts it
/// is tested exactly for running along the surface ([`settle::runs_along`]:
/// its plane equations share a factor), which is answered at once as
/// [`Degeneracy::AlongSurface`]; otherwise it is solved again with the whole
/// budget (all within the options' deadline).
pub(crate) fn intersect_bezier(b: BezierRef, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    if opts.solve.max_boxes > FIRST_BUDGET {
        let mut short = opts.clone();
        short.solve.max_boxes = FIRST_BUDGET;
        let out = routes(b, ray, &short)?;
        let RayOutcome::Degenerate(Degeneracy::Unresolved(h)) = &out else {
            return Ok(out);
        };
        let late = opts.solve.deadline.is_some_and(|d| std::time::Instant::now() >= d);
        if h.complete || late {
            return Ok(out);
        }
        if settle::runs_along(b, ray) {
            return Ok(RayOutcome::Degenerate(Degeneracy::AlongSurface(RayHits {
                complete: false,
                hits: h.hits.clone(),
            })));
        }
    }
    routes(b, ray, opts)
}

/// A tensor patch on a box route first, retried through the triangles when
/// the box solve runs out of budget; a triangular patch on its route.
fn routes(b: BezierRef, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    if let (BezierRef::Tensor(p), SquareRoute::Rect | SquareRoute::RectFatLine | SquareRoute::RectHybrid) =
        (b, opts.route)
    {
        let out = boxes::intersect_rect(p, ray, opts)?;
        let late = opts.solve.deadline.is_some_and(|d| std::time::Instant::now() >= d);
        if late || !matches!(out, RayOutcome::Degenerate(Degeneracy::Unresolved(ref h)) if !h.complete) {
            return Ok(out);
        }
        // Out of budget: retry through the triangles (fat curves separate
        // nearly parallel curves that axis-aligned boxes cannot).
    }
    let planes = Planes::of(ray);
    let solved = match b {
        BezierRef::Tri(p) => {
            let [f, g] = reduce(p.inet(), &planes);
            let n = p.degree();
            let (f, g) = (TriBezier::new(n, f)?, TriBezier::new(n, g)?);
            run(f.coeffs(), g.coeffs(), || solve_triangle(&f, &g, &opts.solve))?
        }
        BezierRef::Tensor(p) => {
            let [f, g] = reduce(p.inet(), &planes);
            let (m, n) = p.degree();
            let (f, g) = (
                TensorBezier::on_unit_square(m, n, f)?,
                TensorBezier::on_unit_square(m, n, g)?,
            );
            run(f.coeffs(), g.coeffs(), || solve_square(&f, &g, &opts.solve))?
        }
    };
    let sol = match solved {
        Solved::Solution(s) => *s,
        Solved::NoHits => {
            return Ok(RayOutcome::Hits(RayHits {
                complete: true,
                hits: Vec::new(),
            }))
        }
        Solved::ZeroEquation => return Ok(RayOutcome::Degenerate(Degeneracy::ZeroEquation)),
    };
    let mut hits = match b {
        BezierRef::Tri(p) => collect_hits(&sol, p.inet(), b, ray, &planes, opts.t_range),
        BezierRef::Tensor(p) => collect_hits(&sol, p.inet(), b, ray, &planes, opts.t_range),
    };
    Ok(finish(&mut hits, sol.complete, sol.clusters.len(), opts.query))
}

enum Solved {
    Solution(Box<Solution>),
    /// An equation's coefficients all have one strict sign.
    NoHits,
    ZeroEquation,
}

/// Screens the reduced system before solving: a one-signed equation proves
/// there is no hit (this also settles a ray in the plane of a planar patch
/// that misses it); an equation that may be identically zero is degenerate.
fn run(f: &[Interval], g: &[Interval], solve: impl FnOnce() -> Result<Solution>) -> Result<Solved> {
    let one_signed = |c: &[Interval]| c.iter().all(|x| x.inf() > 0.0) || c.iter().all(|x| x.sup() < 0.0);
    if one_signed(f) || one_signed(g) {
        return Ok(Solved::NoHits);
    }
    let maybe_zero = |c: &[Interval]| c.iter().all(|x| x.contains(0.0));
    if maybe_zero(f) || maybe_zero(g) {
        return Ok(Solved::ZeroEquation);
    }
    match solve() {
        Ok(s) => Ok(Solved::Solution(Box::new(s))),
        // Unreachable after the screen above (kept as the solver's own word).
        Err(Error::Degenerate(_) | Error::ZeroEquation(_)) => Ok(Solved::ZeroEquation),
        Err(e) => Err(e),
    }
}

/// Roots and clusters become hits (clusters undecided, with their reason);
/// hits with `t` provably outside the range are dropped; sorted by `t`.
fn collect_hits<P: Bb<Interval>>(
    sol: &Solution,
    net: &Net<P>,
    b: BezierRef,
    ray: &Ray,
    planes: &Planes,
    range: [f64; 2],
) -> Vec<Hit> {
    let regions = sol
        .roots
        .iter()
        .map(|r| (r.bx, None))
        .chain(sol.clusters.iter().map(|c| (c.bx, Some(c.reason))));
    let mut hits: Vec<Hit> = regions
        .filter_map(|(bx, cluster)| {
            let t = t_over(net, planes, interval(bx.u[0], bx.u[1]), interval(bx.v[0], bx.v[1]));
            region_hit(b, ray, bx, cluster, [t.inf(), t.sup()], range)
        })
        .collect();
    sort_by_t(&mut hits);
    hits
}

/// Pieces per side of the box over which [`t_over`] evaluates.
const T_PIECES: f64 = 64.0;

/// An enclosure of `t` over the box `uu × vv`: interval de Casteljau on each
/// of up to 64 × 64 sub-boxes no wider than 1/64 (they overlap, so they cover
/// the box), joined. Interval evaluation overestimates in proportion to the
/// box's width, so a wide undecided region (a strip along a whole edge)
/// would otherwise get no useful bound; a certified box is one piece.
fn t_over<P: Bb<Interval>>(net: &Net<P>, planes: &Planes, uu: Interval, vv: Interval) -> Interval {
    let pieces = |x: Interval| (x.wid() * T_PIECES).ceil().clamp(1.0, T_PIECES) as u32;
    let piece = |x: Interval, k: u32, a: u32| {
        if k == 1 {
            return x;
        }
        let at = |j: u32| point(x.inf()) + (point(x.sup()) - point(x.inf())) * point(j as f64) / point(k as f64);
        interval(at(a).inf(), at(a + 1).sup())
    };
    let (ku, kv) = (pieces(uu), pieces(vv));
    let mut t = Interval::EMPTY;
    for a in 0..ku {
        for b in 0..kv {
            t = t.convex_hull(planes.t_of(eval_interval(net, piece(uu, ku, a), piece(vv, kv, b))));
        }
    }
    t
}
