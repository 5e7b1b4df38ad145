//! Certified ray–patch intersection: every hit of a ray with a triangular or
//! tensor-product (rational) Bézier patch, each with a proof.
//!
//! # Reduction (Liu et al. 2016, §2.2, Eq. (3)–(6); Roth et al. 2000)
//! The ray `o + t·d` is the intersection of two planes through `o` with
//! normals `n₁, n₂ ⊥ d`. Substituting the homogeneous control points gives
//!
//! ```text
//! f_k(u, v) = Σ w_ij n_k·(P_ij − o) B_ij(u, v) = 0,   k = 1, 2,
//! ```
//! whose roots in the domain are exactly the parameters of the hits (weights
//! are positive, so the denominator never vanishes). The normals are
//! `n₁ = e_a × d̃` (`e_a` the axis of `d`'s smallest component) and
//! `n₂ = d̃ × n₁`, `d̃ = 2^s d` scaled to unit size; they are orthogonal to `d`
//! exactly in real arithmetic and not normalized (scaling an equation does not
//! move its roots). Every coefficient is computed in interval arithmetic, so
//! the system handed to [`solve_triangle`]/[`solve_square`] encloses the exact
//! one and the solver's contract carries over: each certified `(u, v)` box
//! holds exactly one hit of the exact ray with the exact patch.
//!
//! # t
//! `t = (S(u, v) − o)·d / |d|²` (for `d` as given, not normalized), enclosed
//! over the certified box: `S` by interval de Casteljau on each homogeneous
//! coordinate, divided by the weight. Hits with `t` provably negative are
//! dropped; a `t` box that straddles 0 is kept and flagged
//! ([`Hit::t_straddles_zero`]).
//!
//! # Degenerate cases
//! A ray lying in the plane of a planar patch makes an equation vanish
//! identically: reported as [`RayOutcome::Degenerate`] (never "no hits"), as
//! is a solve that exhausts its budget or ends in many undecided regions (a
//! curve of hits, or a ray grazing along the surface).

pub mod bspline;
pub mod cli;
mod settle;
use crate::solve::settle::Settled;
pub mod patch;
pub mod sample;

pub use bspline::{intersect_bspline, BezierPiece, BsplineSurface};
pub use patch::{Patch, TensorPatch, TriPatch, MAX_DEGREE};

use crate::error::{Error, Result};
use crate::poly::{TensorBezier, TriBezier};
use crate::scalar::iv::Iv;
use crate::scalar::{interval, point};
pub use crate::solve::rect::Query;
use crate::solve::rect::{eval_box, solve_rect_iv, RectClip, RectOptions, RectProblem};
use crate::solve::{solve_square, solve_triangle, Box2, Solution, SolveOptions};
use glam::DVec3;
use inari::Interval;
use patch::{eval_interval, Bb, Net};

/// A ray `o + t·d`, `t ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    origin: DVec3,
    dir: DVec3,
}

impl Ray {
    /// A ray from `origin` along `dir` (not normalized; `t` is measured in
    /// units of `dir`). Errors: NaN/∞ ([`Error::NonFinite`]), zero direction
    /// ([`Error::Degenerate`]).
    pub fn new(origin: DVec3, dir: DVec3) -> Result<Self> {
        if !origin.is_finite() || !dir.is_finite() {
            return Err(Error::NonFinite(format!(
                "ray origin {:?} / direction {:?}",
                origin.to_array(),
                dir.to_array()
            )));
        }
        if dir == DVec3::ZERO {
            return Err(Error::Degenerate("the ray direction is zero".into()));
        }
        Ok(Self { origin, dir })
    }

    /// The origin `o`.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The direction `d`.
    pub fn dir(&self) -> DVec3 {
        self.dir
    }

    /// `o + t·d` in `f64`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// Closed boxes of a hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitBox {
    /// `[lo, hi]` in `u`.
    pub u: [f64; 2],
    /// `[lo, hi]` in `v`.
    pub v: [f64; 2],
    /// `[lo, hi]` in `t`.
    pub t: [f64; 2],
}

/// One intersection of the ray with the patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit {
    /// Midpoint of the `t` box.
    pub t: f64,
    /// Midpoint of the `u` box.
    pub u: f64,
    /// Midpoint of the `v` box.
    pub v: f64,
    /// `S(u, v)` in `f64`.
    pub point: DVec3,
    /// Unit normal `S_u × S_v` at `(u, v)` in `f64` (zero where undefined).
    pub normal: DVec3,
    /// `true`: the `(u, v)` box holds exactly one hit, a simple (transversal)
    /// one. `false`: an undecided region (grazing ray, close hits) that may
    /// hold any number of hits, including none.
    pub certified: bool,
    /// The `t` box contains 0: the hit may lie at or just behind the origin
    /// (then it is not certified: a hit needs `t ≥ 0`).
    pub t_straddles_zero: bool,
    /// The `(u, v)` box reaches outside the patch's parameter domain: the
    /// patch polynomial, continued past the edge, has exactly one simple root
    /// in the box, but it lies within rounding of the edge, and whether it is
    /// on the patch (a hit) or just past its edge (a miss) is not proven, so
    /// `certified` is false. (B-spline pieces settle this across interior
    /// knot lines, where the neighbouring piece continues the surface.)
    pub on_edge: bool,
    /// The boxes; the hit's exact `(u, v, t)` lies in them.
    pub bx: HitBox,
}

/// The hits of one ray, sorted by `t`.
#[derive(Clone, Debug, PartialEq)]
pub struct RayHits {
    /// `true`: every hit with `t ≥ 0` lies in one of `hits` (certified or
    /// not). `false`: a budget stopped the solve (never happens without also
    /// being reported as [`RayOutcome::Degenerate`] by [`intersect`]).
    pub complete: bool,
    /// The hits, sorted by `t` (midpoint), then `u`, `v`.
    pub hits: Vec<Hit>,
}

impl RayHits {
    /// The hits that may be the nearest one: every hit whose `t` lower bound
    /// is at most the smallest `t` upper bound of a certified hit (all hits
    /// when none is certified). A single certified entry is a proven nearest
    /// hit.
    pub fn nearest(&self) -> Vec<&Hit> {
        let best = self
            .hits
            .iter()
            .filter(|h| h.certified)
            .map(|h| h.bx.t[1])
            .fold(f64::INFINITY, f64::min);
        self.hits.iter().filter(|h| h.bx.t[0] <= best).collect()
    }
}

/// Why a ray could not be answered with a list of hits.
#[derive(Clone, Debug, PartialEq)]
pub enum Degeneracy {
    /// An equation may vanish identically (every coefficient enclosure
    /// contains 0): the ray lies in the plane of the patch, or in a plane
    /// holding the whole control net.
    ZeroEquation,
    /// The solve exhausted its budget or ended in more than
    /// [`MAX_CLUSTERS`] undecided regions: most likely a curve of hits (the ray
    /// runs along the surface). The hits found so far are kept.
    Unresolved(RayHits),
}

/// The answer for one ray.
#[derive(Clone, Debug, PartialEq)]
pub enum RayOutcome {
    /// Every hit with `t ≥ 0`; see [`RayHits`].
    Hits(RayHits),
    /// No hit list can be given; see [`Degeneracy`].
    Degenerate(Degeneracy),
}

impl RayOutcome {
    /// A short description of a degenerate outcome (`None` for hits).
    pub fn degenerate_reason(&self) -> Option<&'static str> {
        match self {
            RayOutcome::Hits(_) => None,
            RayOutcome::Degenerate(Degeneracy::ZeroEquation) => {
                Some("the ray lies in a plane containing the whole control net (a planar patch): an equation vanishes identically")
            }
            RayOutcome::Degenerate(Degeneracy::Unresolved(_)) => Some(
                "solver budget exhausted or too many undecided regions: the ray probably runs along the surface",
            ),
        }
    }
}

/// More undecided regions than this make a ray [`Degeneracy::Unresolved`].
pub const MAX_CLUSTERS: usize = 16;

/// The solver options used by [`intersect`] callers that have no opinion: the
/// default, with a budget of 20,000 tri-boxes per triangle (a transversal
/// ray needs a few dozen; more means a curve of hits).
pub fn default_options() -> SolveOptions {
    SolveOptions {
        max_boxes: 20_000,
        ..SolveOptions::default()
    }
}

/// Every hit of `ray` with `patch` for `t ≥ 0`, each certified or flagged as
/// undecided; see the module docs for the reduction and the guarantees.
///
/// ```
/// use glam::DVec3;
/// use rootclip::ray::{intersect, default_options, Ray, RayOutcome, TriPatch};
/// // The flat triangle z = 0 with corners (0,0), (1,0), (0,1), degree 1.
/// let p = TriPatch::new(1, vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0)], None).unwrap();
/// let ray = Ray::new(DVec3::new(0.25, 0.5, 2.0), DVec3::new(0.0, 0.0, -1.0)).unwrap();
/// let RayOutcome::Hits(h) = intersect(&p.into(), &ray, &default_options()).unwrap() else { panic!() };
/// assert!(h.complete && h.hits.len() == 1 && h.hits[0].certified);
/// assert!((h.hits[0].t - 2.0).abs() < 1e-12);
/// ```
pub fn intersect(patch: &Patch, ray: &Ray, opts: &SolveOptions) -> Result<RayOutcome> {
    intersect_with(
        patch,
        ray,
        &RayOptions {
            solve: *opts,
            ..RayOptions::default()
        },
    )
}

/// How a tensor-product patch is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TensorRoute {
    /// Native Bézier clipping on boxes ([`solve_rect`](crate::solve::rect::solve_rect)), with the query's
    /// pruning inside the solve (boxes farther than a certified hit dropped,
    /// the nearer child first); a ray that exhausts its budget is retried through
    /// [`TensorRoute::Triangles`]. The default: measured over 20 times
    /// faster (README).
    #[default]
    Rect,
    /// As [`TensorRoute::Rect`], with fat-line clipping on boxes
    /// ([`RectClip::FatLine`]) instead of Bézier hulls.
    RectFatLine,
    /// As [`TensorRoute::Rect`], with hybrid clipping on boxes (a fat line
    /// and a fat conic, [`RectClip::Hybrid`]).
    RectHybrid,
    /// The square as two triangles of degree `m + n`, solved by hybrid
    /// clipping ([`solve_square`]); queries filter the full hit list.
    Triangles,
}

/// Options of [`intersect_with`].
#[derive(Clone, Debug)]
pub struct RayOptions {
    /// Solver options (`eps`, `max_boxes`; `method` and `split` apply to
    /// triangles).
    pub solve: SolveOptions,
    /// How tensor patches are solved.
    pub route: TensorRoute,
    /// All hits, the nearest, or any (shadow rays).
    pub query: Query,
}

impl Default for RayOptions {
    fn default() -> Self {
        Self {
            solve: default_options(),
            route: TensorRoute::default(),
            query: Query::All,
        }
    }
}

/// The hits of `ray` with `patch` that `opts.query` asks for:
/// * [`Query::All`]: every hit with `t ≥ 0` ([`intersect`]);
/// * [`Query::Nearest`]: the hits that may be the nearest ([`RayHits::nearest`]:
///   a single certified hit is the proven nearest one), found without
///   exploring regions provably farther than a certified hit;
/// * [`Query::Any`]: one certified hit with `t` provably `≥ 0` if there is one
///   (the search stops there), else as for `All`.
///
/// `complete` keeps its meaning for the hits the query asks for.
pub fn intersect_with(patch: &Patch, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    if let (Patch::Tensor(p), TensorRoute::Rect | TensorRoute::RectFatLine | TensorRoute::RectHybrid) =
        (patch, opts.route)
    {
        let out = intersect_rect(p, patch, ray, opts)?;
        if !matches!(out, RayOutcome::Degenerate(Degeneracy::Unresolved(ref h)) if !h.complete) {
            return Ok(out);
        }
        // Out of budget: retry through the triangles (fat curves separate
        // nearly parallel curves that axis-aligned boxes cannot).
        let tri = RayOptions {
            route: TensorRoute::Triangles,
            ..opts.clone()
        };
        return intersect_with(patch, ray, &tri);
    }
    let planes = Planes::of(ray);
    let solved = match patch {
        Patch::Bspline(s) => return bspline::intersect_bspline(s, ray, opts),
        Patch::Triangle(p) => {
            let [f, g] = reduce(p.inet(), &planes);
            let n = p.degree();
            let (f, g) = (TriBezier::new(n, f)?, TriBezier::new(n, g)?);
            run(f.coeffs(), g.coeffs(), || solve_triangle(&f, &g, &opts.solve))?
        }
        Patch::Tensor(p) => {
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
    let mut hits = match patch {
        Patch::Triangle(p) => collect_hits(&sol, p.inet(), patch, ray, &planes),
        Patch::Tensor(p) => collect_hits(&sol, p.inet(), patch, ray, &planes),
        // Returned by the first match; delegating again keeps this one total.
        Patch::Bspline(s) => return bspline::intersect_bspline(s, ray, opts),
    };
    if !sol.complete || sol.clusters.len() > MAX_CLUSTERS {
        return Ok(RayOutcome::Degenerate(Degeneracy::Unresolved(RayHits {
            complete: sol.complete,
            hits,
        })));
    }
    select(&mut hits, opts.query);
    Ok(RayOutcome::Hits(RayHits { complete: true, hits }))
}

/// The tensor route through [`solve_rect`], in [`Iv`] arithmetic throughout:
/// the reduction, the objective `h = (wP − w o)·d̃` (so `t = 2^s h / (w |d̃|²)`),
/// and the `t` enclosures of the hits.
fn intersect_rect(p: &TensorPatch, patch: &Patch, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    let (m, n) = p.degree();
    let d = ray.dir;
    let e = d.abs().max_element().log2().floor().clamp(-1022.0, 1023.0) as i32;
    let scale = 2f64.powi(-e);
    let dt = d.to_array().map(|x| Iv::point(x).scale(scale));
    let a = d.abs();
    let axis = if a.x <= a.y && a.x <= a.z {
        0
    } else if a.y <= a.z {
        1
    } else {
        2
    };
    let mut e_a = [Iv::point(0.0); 3];
    e_a[axis] = Iv::point(1.0);
    let cross = |a: [Iv; 3], b: [Iv; 3]| {
        [
            a[1].mul(b[2]).sub(a[2].mul(b[1])),
            a[2].mul(b[0]).sub(a[0].mul(b[2])),
            a[0].mul(b[1]).sub(a[1].mul(b[0])),
        ]
    };
    let n1 = cross(e_a, dt);
    let n2 = cross(dt, n1);
    let dot = |a: &[Iv; 3], b: &[Iv; 3]| a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]));
    let o = ray.origin.to_array();
    let len = (m + 1) * (n + 1);
    let (mut f, mut g, mut h) = (
        Vec::with_capacity(len),
        Vec::with_capacity(len),
        Vec::with_capacity(len),
    );
    let weights = p.weights();
    for hom in p.ivnet() {
        // (wP − w o), from the homogeneous enclosures (w = 1 exactly for a
        // polynomial patch).
        let q: [Iv; 3] = match weights {
            None => std::array::from_fn(|c| hom[c].sub(Iv::point(o[c]))),
            Some(_) => std::array::from_fn(|c| hom[c].sub(hom[3].mul(Iv::point(o[c])))),
        };
        f.push(dot(&n1, &q));
        g.push(dot(&n2, &q));
        h.push(dot(&dt, &q));
    }
    let one_signed = |c: &[Iv]| c.iter().all(|x| x.lo > 0.0) || c.iter().all(|x| x.hi < 0.0);
    if one_signed(&f) || one_signed(&g) || h.iter().all(|x| x.hi < 0.0) {
        return Ok(RayOutcome::Hits(RayHits {
            complete: true,
            hits: Vec::new(),
        }));
    }
    let maybe_zero = |c: &[Iv]| c.iter().all(|x| x.lo <= 0.0 && x.hi >= 0.0);
    if maybe_zero(&f) || maybe_zero(&g) {
        return Ok(RayOutcome::Degenerate(Degeneracy::ZeroEquation));
    }
    let den: Option<Vec<Iv>> = weights.map(|_| p.ivnet().iter().map(|h| h[3]).collect());
    let unit = [[Iv::point(0.0), Iv::point(1.0)]; 2];
    let problem = RectProblem {
        m,
        n,
        domain: unit,
        f,
        g,
        num: Some(h.clone()),
        den: den.clone(),
    };
    let ropts = RectOptions {
        eps: opts.solve.eps,
        max_boxes: opts.solve.max_boxes,
        query: opts.query,
        key_min: Some(0.0),
        clip: match opts.route {
            TensorRoute::RectFatLine => RectClip::FatLine,
            TensorRoute::RectHybrid => RectClip::Hybrid,
            _ => RectClip::Bezier,
        },
    };
    let sol = match solve_rect_iv(problem, &ropts) {
        Ok(r) => r.solution,
        Err(Error::Degenerate(_)) => return Ok(RayOutcome::Degenerate(Degeneracy::ZeroEquation)),
        Err(e) => return Err(e),
    };
    let d2 = dot(&dt, &dt);
    let t_of = |bx: Box2| {
        let num = eval_box(&h, m, n, bx.u, bx.v);
        let w = den.as_ref().map_or(Iv::point(1.0), |w| eval_box(w, m, n, bx.u, bx.v));
        num.div(w.mul(d2)).scale(scale)
    };
    let regions = sol
        .roots
        .iter()
        .map(|r| (r.bx, true))
        .chain(sol.clusters.iter().map(|c| (c.bx, false)));
    let mut hits: Vec<Hit> = regions
        .filter_map(|(bx, root)| {
            let t = t_of(bx);
            Hit::of_region(patch, ray, bx, root, [t.lo, t.hi])
        })
        .collect();
    hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.u.total_cmp(&b.u)).then(a.v.total_cmp(&b.v)));
    if !sol.complete || sol.clusters.len() > MAX_CLUSTERS {
        return Ok(RayOutcome::Degenerate(Degeneracy::Unresolved(RayHits {
            complete: sol.complete,
            hits,
        })));
    }
    select(&mut hits, opts.query);
    Ok(RayOutcome::Hits(RayHits { complete: true, hits }))
}

/// Keeps the hits a query asks for (the list is sorted by `t`).
fn select(hits: &mut Vec<Hit>, query: Query) {
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
            if let Some(h) = hits.iter().find(|h| h.certified && !h.t_straddles_zero) {
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
        let d = ray.dir;
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
            o: ray.origin.to_array().map(point),
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

/// Roots and clusters become hits (clusters with `certified = false`); hits
/// with `t` provably negative are dropped; sorted by `t`.
fn collect_hits<P: Bb<Interval>>(sol: &Solution, net: &Net<P>, patch: &Patch, ray: &Ray, planes: &Planes) -> Vec<Hit> {
    let regions = sol
        .roots
        .iter()
        .map(|r| (r.bx, true))
        .chain(sol.clusters.iter().map(|c| (c.bx, false)));
    let mut hits: Vec<Hit> = regions
        .filter_map(|(bx, certified)| hit_of(bx, certified, net, patch, ray, planes))
        .collect();
    hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.u.total_cmp(&b.u)).then(a.v.total_cmp(&b.v)));
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

fn hit_of<P: Bb<Interval>>(
    bx: Box2,
    certified: bool,
    net: &Net<P>,
    patch: &Patch,
    ray: &Ray,
    planes: &Planes,
) -> Option<Hit> {
    let (uu, vv) = (interval(bx.u[0], bx.u[1]), interval(bx.v[0], bx.v[1]));
    let t = t_over(net, planes, uu, vv);
    Hit::of_region(patch, ray, bx, certified, [t.inf(), t.sup()])
}

impl Hit {
    /// The hit of a solver region: a certified root (`root`) or an undecided
    /// cluster, with its `t` enclosure; `None` if `t` is provably negative.
    /// Certified only if, beyond the root's certificate, the root is proven
    /// to lie in the patch's closed domain (else [`Hit::on_edge`]) and at
    /// `t ≥ 0`: by the boxes, or, where rounding leaves either in doubt, in
    /// exact arithmetic (`settle.rs`), which may also prove a miss (`None`).
    fn of_region(patch: &Patch, ray: &Ray, bx: Box2, root: bool, t: [f64; 2]) -> Option<Self> {
        if t[1] < 0.0 {
            return None;
        }
        let mut inside = patch_domain_contains(patch, bx);
        let mut t_proven = t[0] >= 0.0 && t[1].is_finite();
        let mut t = t;
        if root && !(inside && t_proven) {
            match settle::settle(patch, ray, bx) {
                Settled::Inside => {
                    (inside, t_proven) = (true, true);
                    t[0] = t[0].max(0.0);
                }
                Settled::Outside => return None,
                Settled::Undecided => {}
            }
        }
        let (u, v) = (0.5 * (bx.u[0] + bx.u[1]), 0.5 * (bx.v[0] + bx.v[1]));
        let (point, normal) = patch.point_and_normal(u, v);
        Some(Hit {
            t: 0.5 * (t[0] + t[1]),
            u,
            v,
            point,
            normal,
            certified: root && inside && t_proven,
            t_straddles_zero: t[0] <= 0.0,
            on_edge: root && !inside,
            bx: HitBox { u: bx.u, v: bx.v, t },
        })
    }
}

/// The closed box lies in the patch's closed parameter domain (the unit
/// square, or the triangle `u, v ≥ 0, u + v ≤ 1` with the sum rounded up).
fn patch_domain_contains(patch: &Patch, bx: Box2) -> bool {
    let lower = bx.u[0] >= 0.0 && bx.v[0] >= 0.0;
    match patch {
        Patch::Triangle(_) => lower && (point(bx.u[1]) + point(bx.v[1])).sup() <= 1.0,
        _ => lower && bx.u[1] <= 1.0 && bx.v[1] <= 1.0,
    }
}
