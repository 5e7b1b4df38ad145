//! One Bézier patch (triangular or tensor, polynomial or rational) against a
//! ray: the reduction to two equations, the route to the solver, and the
//! solver's regions turned into hits.

use super::patch::{eval_interval, Bb, Net};
use super::{boxes, settle, Degeneracy, Hit, HitBox, HitStatus, Query, Ray, RayHits, RayOptions, RayOutcome};
use super::{TensorPatch, TriPatch, MAX_CLUSTERS};
use crate::error::{Error, Result};
use crate::poly::{TensorBezier, TriBezier};
use crate::scalar::{interval, point};
use crate::solve::settle::Settled;
use crate::solve::{solve_square, solve_triangle, Box2, Solution, SquareRoute, UndecidedReason};
use glam::DVec3;
use inari::Interval;

/// A borrowed Bézier patch of either kind.
#[derive(Clone, Copy, Debug)]
pub(crate) enum BezierRef<'a> {
    Tri(&'a TriPatch),
    Tensor(&'a TensorPatch),
}

impl BezierRef<'_> {
    /// The point and the unit normal at `(u, v)` in `f64`.
    pub(crate) fn point_and_normal(self, u: f64, v: f64) -> (DVec3, DVec3) {
        match self {
            BezierRef::Tri(p) => {
                let (su, sv) = p.partials(u, v);
                (p.eval(u, v), su.cross(sv).normalize_or_zero())
            }
            BezierRef::Tensor(p) => {
                let (x, su, sv) = p.frame(u, v);
                (x, su.cross(sv).normalize_or_zero())
            }
        }
    }

    /// The closed box lies in the patch's closed parameter domain (the unit
    /// square, or the triangle `u, v ≥ 0, u + v ≤ 1` with the sum rounded up).
    fn domain_contains(self, bx: Box2) -> bool {
        let lower = bx.u[0] >= 0.0 && bx.v[0] >= 0.0;
        match self {
            BezierRef::Tri(_) => lower && (point(bx.u[1]) + point(bx.v[1])).sup() <= 1.0,
            BezierRef::Tensor(_) => lower && bx.u[1] <= 1.0 && bx.v[1] <= 1.0,
        }
    }
}

/// The hits of `ray` with one Bézier patch ([`super::intersect`]'s contract):
/// a tensor patch on a box route first, retried through the triangles when
/// the box solve runs out of budget.
pub(crate) fn intersect_bezier(b: BezierRef, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    if let (BezierRef::Tensor(p), SquareRoute::Rect | SquareRoute::RectFatLine | SquareRoute::RectHybrid) =
        (b, opts.route)
    {
        let out = boxes::intersect_rect(p, ray, opts)?;
        if !matches!(out, RayOutcome::Degenerate(Degeneracy::Unresolved(ref h)) if !h.complete) {
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

/// The outcome of a solve's hits: unresolved if the solve was incomplete or
/// ended in too many undecided regions, else the hits the query asks for.
pub(super) fn finish(hits: &mut Vec<Hit>, complete: bool, clusters: usize, query: Query) -> RayOutcome {
    let hits_taken = std::mem::take(hits);
    if !complete || clusters > MAX_CLUSTERS {
        return RayOutcome::Degenerate(Degeneracy::Unresolved(RayHits {
            complete,
            hits: hits_taken,
        }));
    }
    let mut hits = hits_taken;
    select(&mut hits, query);
    RayOutcome::Hits(RayHits { complete: true, hits })
}

/// Keeps the hits a query asks for (the list is sorted by `t`).
pub(super) fn select(hits: &mut Vec<Hit>, query: Query) {
    match query {
        Query::All => {}
        Query::Nearest => {
            let all = RayHits {
                complete: true,
                hits: std::mem::take(hits),
            };
            *hits = all.nearest().into_iter().cloned().collect();
        }
        Query::Any => {
            if let Some(h) = hits.iter().find(|h| h.is_certified()) {
                *hits = vec![h.clone()];
            }
        }
    }
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
        Err(Error::Degenerate(_)) => Ok(Solved::ZeroEquation),
        Err(e) => Err(e),
    }
}

/// The two planes through the ray, in interval arithmetic (also used by the
/// B-spline knot-line merging).
pub(crate) struct Planes {
    pub(crate) o: [Interval; 3],
    pub(crate) n: [[Interval; 3]; 2],
    /// `d̃ = 2^s d` (enclosed) and `2^s`.
    pub(crate) d: [Interval; 3],
    pub(crate) scale: Interval,
}

impl Planes {
    pub(crate) fn of(ray: &Ray) -> Self {
        let d = ray.dir();
        let big = d.abs().max_element();
        // A power of two, clamped so that it stays finite.
        let e = big.log2().floor().clamp(-1022.0, 1023.0) as i32;
        let scale = point(2f64.powi(-e));
        let dt = [point(d.x) * scale, point(d.y) * scale, point(d.z) * scale];
        let a = d.abs();
        let axis = if a.x <= a.y && a.x <= a.z {
            0
        } else if a.y <= a.z {
            1
        } else {
            2
        };
        let mut e_a = [point(0.0); 3];
        e_a[axis] = point(1.0);
        let n1 = cross(e_a, dt);
        let n2 = cross(dt, n1);
        Self {
            o: ray.origin().to_array().map(point),
            n: [n1, n2],
            d: dt,
            scale,
        }
    }

    /// `t = (S − o)·d / |d|² = 2^s (S − o)·d̃ / |d̃|²`.
    pub(crate) fn t_of(&self, s: [Interval; 3]) -> Interval {
        let num = (0..3).fold(point(0.0), |acc, c| acc + (s[c] - self.o[c]) * self.d[c]);
        let den = (0..3).fold(point(0.0), |acc, c| acc + self.d[c].sqr());
        self.scale * num / den
    }
}

fn cross(a: [Interval; 3], b: [Interval; 3]) -> [Interval; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `f_k` coefficients `n_k·(wP − w o)` in storage order, for `k = 1, 2`.
fn reduce<P: HasCoeffs>(net: &Net<P>, planes: &Planes) -> [Vec<Interval>; 2] {
    let cols: [&[Interval]; 4] = std::array::from_fn(|c| net.c[c].coeff_slice());
    let len = cols[3].len();
    [0, 1].map(|k| {
        let n = planes.n[k];
        (0..len)
            .map(|i| {
                (0..3).fold(point(0.0), |acc, c| {
                    acc + n[c] * (cols[c][i] - cols[3][i] * planes.o[c])
                })
            })
            .collect()
    })
}

trait HasCoeffs {
    fn coeff_slice(&self) -> &[Interval];
}

impl HasCoeffs for TriBezier<Interval> {
    fn coeff_slice(&self) -> &[Interval] {
        self.coeffs()
    }
}

impl HasCoeffs for TensorBezier<Interval> {
    fn coeff_slice(&self) -> &[Interval] {
        self.coeffs()
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

/// Sorts hits by `t` (midpoint), then `u`, `v`.
pub(super) fn sort_by_t(hits: &mut [Hit]) {
    hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.u.total_cmp(&b.u)).then(a.v.total_cmp(&b.v)));
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

/// The hit of a solver region — a certified root (`cluster = None`) or an
/// undecided cluster — with its `t` enclosure; `None` if `t` is provably
/// outside `range`. A root is certified only if it is also proven to lie in
/// the patch's closed domain (else [`UndecidedReason::Boundary`]) and its `t`
/// in the range (else [`UndecidedReason::RangeEnd`]): by the boxes, or, where
/// rounding leaves either in doubt, in exact arithmetic (`settle.rs`), which
/// may also prove a miss (`None`).
pub(super) fn region_hit(
    b: BezierRef,
    ray: &Ray,
    bx: Box2,
    cluster: Option<UndecidedReason>,
    t: [f64; 2],
    range: [f64; 2],
) -> Option<Hit> {
    let [lo, hi] = range;
    if t[1] < lo || t[0] > hi {
        return None;
    }
    let mut inside = b.domain_contains(bx);
    let finite = t[0].is_finite() && t[1].is_finite();
    let (mut above, mut below) = (t[0] >= lo && finite, t[1] <= hi && finite);
    let mut t = t;
    if cluster.is_none() && !(inside && above && below) {
        match settle::settle(b, ray, bx, range, !below) {
            Settled::Inside => {
                (inside, above, below) = (true, true, true);
                t = [t[0].max(lo), t[1].min(hi)];
            }
            Settled::Outside => return None,
            Settled::Undecided => {}
        }
    }
    let status = match cluster {
        Some(reason) => HitStatus::Undecided(reason),
        None if !inside => HitStatus::Undecided(UndecidedReason::Boundary),
        None if !(above && below) => HitStatus::Undecided(UndecidedReason::RangeEnd),
        None => HitStatus::Certified,
    };
    let (u, v) = (0.5 * (bx.u[0] + bx.u[1]), 0.5 * (bx.v[0] + bx.v[1]));
    let (point, normal) = b.point_and_normal(u, v);
    Some(Hit {
        t: 0.5 * (t[0] + t[1]),
        u,
        v,
        point,
        normal,
        status,
        bx: HitBox { u: bx.u, v: bx.v, t },
    })
}
