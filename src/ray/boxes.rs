//! The box route for tensor patches: the reduction in [`Iv`] arithmetic and
//! Bézier (or fat-line, or hybrid) clipping on boxes, with the query's
//! pruning inside the solve.

use super::hit::{Degeneracy, Hit, RayHits, RayOutcome};
use super::patch::{BezierRef, TensorPatch};
use super::query::{Query, Ray, RayOptions};
use super::regions::{finish, region_hit, sort_by_t};
use crate::error::{Error, Result};
use crate::scalar::iv::{down, up, Iv};
use crate::solve::rect::{eval_box, solve_rect_iv, RectClip, RectOptions, RectProblem};
use crate::solve::{Box2, SquareRoute};

/// The objective floor and the query handed to the box solver. Its objective
/// `h/W = t·|d̃|²/2^s` has the sign of `t`, so the floor of `t_min` is
/// `t_min·|d̃|²/2^s`, enclosed (a point for `t_min = 0`); none for
/// `t_min = −∞`. An `Any` query with a finite end asks the solver for the
/// nearest root instead of the first: the first may lie past the end.
fn solver_query(opts: &RayOptions, d2: Iv, scale: f64) -> (Option<[f64; 2]>, Query) {
    let [lo, hi] = opts.t_range;
    let key_min = if lo == 0.0 {
        Some([0.0, 0.0])
    } else if lo.is_finite() {
        let k = Iv::point(lo).mul(d2).scale(1.0 / scale);
        Some([k.lo, k.hi])
    } else {
        None
    };
    let mut query = opts.query;
    if query == Query::Any && hi.is_finite() {
        query = Query::Nearest;
    }
    (key_min, query)
}

/// Four intervals side by side, lane `k` holding the `k`-th: the same
/// [`Iv`] operations per lane (so the same floats), written over arrays so
/// that they compile to vector instructions whatever the inliner decides
/// elsewhere.
#[derive(Clone, Copy)]
struct Lanes {
    lo: [f64; 4],
    hi: [f64; 4],
}

impl Lanes {
    #[inline(always)]
    fn splat(x: Iv) -> Self {
        Self {
            lo: [x.lo; 4],
            hi: [x.hi; 4],
        }
    }

    #[inline(always)]
    fn of(x: [Iv; 4]) -> Self {
        Self {
            lo: [x[0].lo, x[1].lo, x[2].lo, x[3].lo],
            hi: [x[0].hi, x[1].hi, x[2].hi, x[3].hi],
        }
    }

    #[inline(always)]
    fn ivs(self) -> [Iv; 4] {
        let at = |k: usize| Iv::new(self.lo[k], self.hi[k]);
        [at(0), at(1), at(2), at(3)]
    }

    /// [`Iv::add`] per lane.
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        let mut out = self;
        for k in 0..4 {
            out.lo[k] = down(self.lo[k] + b.lo[k]);
            out.hi[k] = up(self.hi[k] + b.hi[k]);
        }
        out
    }

    /// [`Iv::sub`] per lane.
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        let mut out = self;
        for k in 0..4 {
            out.lo[k] = down(self.lo[k] - b.hi[k]);
            out.hi[k] = up(self.hi[k] - b.lo[k]);
        }
        out
    }

    /// [`Iv::mul`] per lane, the extreme products picked by `<` (no NaN
    /// reaches here: the net and the ray are finite; a `±0` picked either way
    /// rounds outward to the same bound), which vectorizes where `f64::min`
    /// may not.
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        let lt = |x: f64, y: f64| if x < y { x } else { y };
        let gt = |x: f64, y: f64| if x > y { x } else { y };
        let mut out = self;
        for k in 0..4 {
            let p = [
                self.lo[k] * b.lo[k],
                self.lo[k] * b.hi[k],
                self.hi[k] * b.lo[k],
                self.hi[k] * b.hi[k],
            ];
            out.lo[k] = down(lt(lt(lt(p[0], p[1]), p[2]), p[3]));
            out.hi[k] = up(gt(gt(gt(p[0], p[1]), p[2]), p[3]));
        }
        out
    }
}

/// `n · q` for four points at once (`q[c]` the lanes of coordinate `c`):
/// per lane the operations of the scalar `dot`, so the same floats.
#[inline(always)]
fn dot4(n: &[Iv; 3], q: &[Lanes; 3]) -> [Iv; 4] {
    let (a, b, c) = (Lanes::splat(n[0]), Lanes::splat(n[1]), Lanes::splat(n[2]));
    a.mul(q[0]).add(b.mul(q[1])).add(c.mul(q[2])).ivs()
}

/// The tensor route through [`solve_rect`], in [`Iv`] arithmetic throughout:
/// the reduction, the objective `h = (wP − w o)·d̃` (so `t = 2^s h / (w |d̃|²)`),
/// and the `t` enclosures of the hits.
pub(super) fn intersect_rect(p: &TensorPatch, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    let (m, n) = p.degree();
    let d = ray.dir();
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
    let o = ray.origin().to_array();
    let len = (m + 1) * (n + 1);
    let (mut f, mut g, mut h) = (
        vec![Iv::point(0.0); len],
        vec![Iv::point(0.0); len],
        vec![Iv::point(0.0); len],
    );
    let weights = p.weights();
    // (wP − w o), from the homogeneous enclosures (w = 1 exactly for a
    // polynomial patch), four control points at a time.
    let net = p.ivnet();
    let quads = len / 4;
    let origin = [0, 1, 2].map(|c| Lanes::splat(Iv::point(o[c])));
    for i in 0..quads {
        let quad = &net[4 * i..4 * i + 4];
        let lanes = |c: usize| Lanes::of([quad[0][c], quad[1][c], quad[2][c], quad[3][c]]);
        let q: [Lanes; 3] = if weights.is_none() {
            [
                lanes(0).sub(origin[0]),
                lanes(1).sub(origin[1]),
                lanes(2).sub(origin[2]),
            ]
        } else {
            let w = lanes(3);
            [
                lanes(0).sub(w.mul(origin[0])),
                lanes(1).sub(w.mul(origin[1])),
                lanes(2).sub(w.mul(origin[2])),
            ]
        };
        f[4 * i..4 * i + 4].copy_from_slice(&dot4(&n1, &q));
        g[4 * i..4 * i + 4].copy_from_slice(&dot4(&n2, &q));
        h[4 * i..4 * i + 4].copy_from_slice(&dot4(&dt, &q));
    }
    for k in 4 * quads..len {
        let hom = &net[k];
        let q: [Iv; 3] = [0, 1, 2].map(|c| match weights {
            None => hom[c].sub(Iv::point(o[c])),
            Some(_) => hom[c].sub(hom[3].mul(Iv::point(o[c]))),
        });
        f[k] = dot(&n1, &q);
        g[k] = dot(&n2, &q);
        h[k] = dot(&dt, &q);
    }
    let one_signed = |c: &[Iv]| c.iter().all(|x| x.lo > 0.0) || c.iter().all(|x| x.hi < 0.0);
    // (Every h_ij < 0: t < 0 on the whole patch.)
    if one_signed(&f) || one_signed(&g) || (opts.t_range[0] >= 0.0 && h.iter().all(|x| x.hi < 0.0)) {
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
    let d2 = dot(&dt, &dt);
    let (key_min, query) = solver_query(opts, d2, scale);
    let problem = RectProblem {
        m,
        n,
        domain: unit,
        f,
        g,
        num: Some(h.clone()),
        den: den.clone(),
        squares: None,
        exact: None,
        triangle: false,
    };
    let ropts = RectOptions {
        eps: opts.solve.eps,
        max_boxes: opts.solve.max_boxes,
        query,
        key_min,
        clip: match opts.route {
            SquareRoute::RectFatLine => RectClip::FatLine,
            SquareRoute::RectHybrid => RectClip::Hybrid,
            _ => RectClip::Bezier,
        },
        deadline: opts.solve.deadline,
        key_max: None,
    };
    let sol = match solve_rect_iv(problem, &ropts) {
        Ok(r) => r.solution,
        Err(Error::Degenerate(_)) => return Ok(RayOutcome::Degenerate(Degeneracy::ZeroEquation)),
        Err(e) => return Err(e),
    };
    let t_of = |bx: Box2| {
        let num = eval_box(&h, m, n, bx.u, bx.v);
        let w = den.as_ref().map_or(Iv::point(1.0), |w| eval_box(w, m, n, bx.u, bx.v));
        num.div(w.mul(d2)).scale(scale)
    };
    let b = BezierRef::Tensor(p);
    let regions = sol
        .roots
        .iter()
        .map(|r| (r.bx, None))
        .chain(sol.clusters.iter().map(|c| (c.bx, Some(c.reason))));
    let mut hits: Vec<Hit> = regions
        .filter_map(|(bx, cluster)| {
            let t = t_of(bx);
            region_hit(b, ray, bx, cluster, [t.lo, t.hi], opts.t_range)
        })
        .collect();
    sort_by_t(&mut hits);
    Ok(finish(&mut hits, sol.complete, sol.clusters.len(), opts.query))
}
