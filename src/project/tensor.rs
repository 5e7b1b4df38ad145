//! The tensor path: the critical-point system and the distance objective of
//! a tensor patch, prepared once per patch as polynomials affine in the
//! point `P`, so that each point costs one linear combination of
//! coefficient arrays, one box solve and four univariate solves.
//!
//! With `S = X/W` and `T_u = X_u W − X W_u` (`T_u = X_u` for a polynomial
//! patch), the interior system of [`critical`](super::critical) is
//!
//! ```text
//! F = (X − P W)·T_u = X·T_u − Σ_k p_k (W T_{u,k}),     G likewise with v,
//! D·W² = |X − P W|² = X·X − 2 Σ_k p_k (X_k W) + |P|² W²,
//! ```
//! every product built once in interval arithmetic ([`IvPoly`]) at the
//! system's bidegree (`(2m, 2n)`, rational `(3m, 3n)`), then per point
//! `F_ij = A_ij − Σ_k p_k B_k,ij` in [`Iv`] — each coefficient still an
//! enclosure of the exact one, so the solver's certificates speak of the
//! exact system. The restriction of `F` to an edge `v = 0` or `v = 1` is the
//! edge function of that edge (`∂D/∂u` along it has the sign of `F`), so the
//! edges' univariate polynomials are `F`'s first and last rows and `G`'s
//! first and last columns, already in Bernstein form.

use super::distance::lower_bound;
use super::ivpoly::IvPoly;
use super::patches::{candidate, clamp_square, regions, Dist};
use super::{Candidate, FootKind};
use crate::error::Result;
use crate::poly::UniBezier;
use crate::ray::patch::TensorPatch;
use crate::scalar::interval;
use crate::scalar::iv::Iv;
use crate::solve::rect::{eval_box, solve_rect_iv, Query, RectOptions, RectProblem, Squares};
use crate::solve::{solve_uni, Box2, SolveOptions, UniOptions};
use glam::DVec3;

/// The degrees of the box solver's stack-allocated nets.
const RECT_MAX_DEGREE: usize = 23;

/// `a − Σ_k p_k b_k` (or `+`) as an affine family of coefficient arrays.
#[derive(Clone, Debug)]
struct Affine {
    a: Vec<Iv>,
    b: [Vec<Iv>; 3],
}

impl Affine {
    /// `a − Σ p_k b_k`, coefficient by coefficient.
    fn at(&self, p: [Iv; 3]) -> Vec<Iv> {
        let [b0, b1, b2] = &self.b;
        self.a
            .iter()
            .zip(b0.iter().zip(b1.iter().zip(b2)))
            .map(|(&a, (&x, (&y, &z)))| a.sub(p[0].mul(x).add(p[1].mul(y)).add(p[2].mul(z))))
            .collect()
    }
}

/// A tensor patch prepared for many points (module docs).
#[derive(Clone, Debug)]
pub(super) struct TensorPrep {
    rational: bool,
    /// The system's bidegree.
    big: (usize, usize),
    f: Affine,
    g: Affine,
    /// `D·W²` = `num.a − 2 Σ p_k num.b_k + |P|² w2`.
    num: Affine,
    /// `W²` at the system's bidegree (absent: `W = 1`).
    w2: Option<Vec<Iv>>,
    /// The homogeneous net: `X_k` and `W`, at the patch's bidegree.
    x: [IvPoly; 3],
    w: IvPoly,
    /// `(u, v, S(u, v))` on a `GRID × GRID` grid, in `f64`, for the
    /// proposals.
    grid: Vec<(f64, f64, DVec3)>,
}

impl TensorPrep {
    /// `None` when the system's bidegree exceeds the box solver's nets.
    pub(super) fn new(t: &TensorPatch) -> Option<Self> {
        let (m, n) = t.degree();
        let rational = t.weights().is_some();
        let big = if rational { (3 * m, 3 * n) } else { (2 * m, 2 * n) };
        if big.0 > RECT_MAX_DEGREE || big.1 > RECT_MAX_DEGREE {
            return None;
        }
        let col = |k: usize| IvPoly::new(m, n, t.ivnet().iter().map(|h| h[k]).collect());
        let x = [col(0), col(1), col(2)];
        let w = col(3);
        let lift = |q: &IvPoly| q.elevate(big.0, big.1).c;
        let dot = |a: &[IvPoly; 3], b: &[IvPoly; 3]| a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]));
        let (tu, tv): ([IvPoly; 3], [IvPoly; 3]) = if rational {
            let (wu, wv) = (w.d_u(), w.d_v());
            (
                std::array::from_fn(|k| x[k].d_u().mul(&w).sub(&x[k].mul(&wu))),
                std::array::from_fn(|k| x[k].d_v().mul(&w).sub(&x[k].mul(&wv))),
            )
        } else {
            (std::array::from_fn(|k| x[k].d_u()), std::array::from_fn(|k| x[k].d_v()))
        };
        let times_w = |q: &IvPoly| if rational { q.mul(&w) } else { q.clone() };
        let affine = |t: &[IvPoly; 3]| Affine {
            a: lift(&dot(&x, t)),
            b: std::array::from_fn(|k| lift(&times_w(&t[k]))),
        };
        let num = Affine {
            a: lift(&dot(&x, &x)),
            b: std::array::from_fn(|k| lift(&times_w(&x[k])).iter().map(|c| c.scale(2.0)).collect()),
        };
        Some(Self {
            rational,
            big,
            f: affine(&tu),
            g: affine(&tv),
            num,
            w2: rational.then(|| lift(&w.mul(&w))),
            x,
            w,
            grid: (0..GRID)
                .flat_map(|i| (0..GRID).map(move |j| (i as f64 / (GRID - 1) as f64, j as f64 / (GRID - 1) as f64)))
                .map(|(u, v)| (u, v, t.eval(u, v)))
                .collect(),
        })
    }
}

/// `D = Σ_k ((X_k − p_k W)/W)²`, each coordinate enclosed by [`eval_box`]
/// and squared: tight at points (an expanded `D` would cancel, leaving an
/// on-surface point a distance enclosure near `√ε` instead of `ε`) and cheap
/// over boxes.
struct NetDist<'a> {
    /// `X_k − p_k W`, `k = 0, 1, 2`.
    diff: [IvPoly; 3],
    /// `W`, absent for a polynomial patch.
    w: Option<&'a IvPoly>,
}

/// `x²` as an enclosure (never below 0).
fn iv_sqr(x: Iv) -> Iv {
    let a = if x.lo >= 0.0 {
        x
    } else if x.hi <= 0.0 {
        Iv::new(-x.hi, -x.lo)
    } else {
        Iv::new(0.0, x.hi.max(-x.lo))
    };
    a.mul(a)
}

impl NetDist<'_> {
    fn over(&self, u: [f64; 2], v: [f64; 2]) -> Iv {
        let w = self.w.map(|w| eval_box(&w.c, w.m, w.n, u, v));
        self.diff.iter().fold(Iv::point(0.0), |acc, d| {
            let e = eval_box(&d.c, d.m, d.n, u, v);
            acc.add(iv_sqr(w.map_or(e, |w| e.div(w))))
        })
    }
}

impl Dist for NetDist<'_> {
    fn lower(&self, b: &Box2) -> f64 {
        let d = self.over(b.u, b.v);
        if d.lo.is_nan() {
            0.0
        } else {
            d.lo.max(0.0)
        }
    }
    fn upper(&self, u: f64, v: f64) -> f64 {
        let d = self.over([u, u], [v, v]);
        if d.hi.is_nan() {
            f64::INFINITY
        } else {
            d.hi
        }
    }
}

/// The candidates of a prepared tensor patch for the point `p`; `None` when
/// the box solver gives up (a budget, an equation that may vanish
/// identically): the general route decides then. `outer` is an upper bound
/// of `D` known from elsewhere (other B-spline pieces).
pub(super) fn candidates(
    prep: &TensorPrep,
    t: &TensorPatch,
    p: [f64; 3],
    opts: &SolveOptions,
    outer: f64,
) -> Result<Option<Vec<Candidate>>> {
    let pi = p.map(Iv::point);
    let (bm, bn) = prep.big;
    let f = prep.f.at(pi);
    let g = prep.g.at(pi);
    let num = {
        let p2 = pi.iter().fold(Iv::point(0.0), |acc, &c| acc.add(c.mul(c)));
        let lin = prep.num.at(pi);
        match &prep.w2 {
            Some(w2) => lin.iter().zip(w2).map(|(a, w)| a.add(p2.mul(*w))).collect(),
            None => lin.iter().map(|a| a.add(p2)).collect::<Vec<_>>(),
        }
    };
    let diff: [IvPoly; 3] = std::array::from_fn(|k| {
        let x = &prep.x[k];
        if prep.rational {
            IvPoly::new(
                x.m,
                x.n,
                x.c.iter().zip(&prep.w.c).map(|(a, w)| a.sub(pi[k].mul(*w))).collect(),
            )
        } else {
            x.map(|c| c.sub(pi[k]))
        }
    });
    let dist = NetDist {
        diff,
        w: prep.rational.then_some(&prep.w),
    };
    let edges = EdgeRows::of(&f, &g, bm, bn);
    let problem = RectProblem {
        m: bm,
        n: bn,
        domain: [[Iv::point(0.0), Iv::point(1.0)]; 2],
        f,
        g,
        num: Some(num),
        den: prep.w2.clone(),
        squares: Some(Squares {
            m: dist.diff[0].m,
            n: dist.diff[0].n,
            c: [dist.diff[0].c.clone(), dist.diff[1].c.clone(), dist.diff[2].c.clone()],
            w: dist.w.map(|w| w.c.clone()),
        }),
        exact: None,
        triangle: false,
    };
    // Floating point proposes a near point; its enclosed distance bounds the
    // minimum from above, so every region provably farther is pruned from
    // the start (the corners, being candidates anyway, join the proposal).
    let guess = propose(t, &prep.grid, p);
    let mut out = Vec::new();
    out.push(candidate(
        &dist,
        Box2::new([guess[0]; 2], [guess[1]; 2]),
        FootKind::Interior,
        false,
        clamp_square,
    ));
    for (u, v) in [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)] {
        out.push(candidate(
            &dist,
            Box2::new([u, u], [v, v]),
            FootKind::Corner,
            true,
            clamp_square,
        ));
    }
    let best = |out: &[Candidate]| out.iter().map(|c| c.d[1]).fold(outer, f64::min);
    let ropts = RectOptions {
        eps: opts.eps.min(0.5),
        max_boxes: opts.max_boxes,
        query: Query::Nearest,
        key_max: Some(best(&out)),
        ..RectOptions::default()
    };
    match solve_rect_iv(problem, &ropts) {
        Ok(r) if r.solution.complete => {
            out.extend(regions(&r.solution).map(|(bx, c)| candidate(&dist, bx, FootKind::Interior, c, clamp_square)))
        }
        _ => return Ok(None),
    }
    let curves = edge_curves(&dist.diff, dist.w);
    edges.candidates(curves, opts, &dist, best(&out), &mut out)?;
    // The proposal was only a bound: the minimum lies in one of the other
    // regions (every region farther than the bound was pruned, none nearer),
    // whose own upper bounds then bound it too.
    out.remove(0);
    refine(&dist, &mut out, outer);
    Ok(Some(out))
}

/// Halvings of an edge curve tried before its solve (to skip far edges).
const EDGE_DEPTH: u32 = 3;

/// An edge of the patch as the curves `X_k − p_k W` and `W` (Bernstein
/// coefficients, the patch's boundary rows).
type EdgeCurve = ([Vec<Iv>; 3], Option<Vec<Iv>>);

/// The four edges in [`EdgeRows`]' order: `v = 0`, `v = 1`, `u = 0`, `u = 1`.
fn edge_curves(diff: &[IvPoly; 3], w: Option<&IvPoly>) -> [EdgeCurve; 4] {
    let pick = |q: &IvPoly, e: usize| -> Vec<Iv> {
        let (m, n) = (q.m, q.n);
        match e {
            0 => (0..=m).map(|i| q.c[i * (n + 1)]).collect(),
            1 => (0..=m).map(|i| q.c[i * (n + 1) + n]).collect(),
            2 => q.c[..=n].to_vec(),
            _ => q.c[m * (n + 1)..].to_vec(),
        }
    };
    std::array::from_fn(|e| (std::array::from_fn(|k| pick(&diff[k], e)), w.map(|w| pick(w, e))))
}

/// `D > best` on the whole edge, proven from the convex hull of the
/// coefficients (each coordinate of `(X − P W)/W` lies between its
/// coefficients' extremes divided by `W`'s), the curve halved by de
/// Casteljau up to `depth` times where that does not suffice.
fn edge_far((diff, w): EdgeCurve, best: f64, depth: u32) -> bool {
    let hull = |c: &[Iv]| {
        c.iter()
            .fold(Iv::new(f64::INFINITY, f64::NEG_INFINITY), |a, x| a.hull(*x))
    };
    let w_max = w.as_ref().map_or(1.0, |w| hull(w).hi);
    let lower = diff.iter().fold(Iv::point(0.0), |acc, c| {
        let h = hull(c);
        let gap = if h.lo > 0.0 {
            h.lo
        } else if h.hi < 0.0 {
            -h.hi
        } else {
            0.0
        };
        acc.add(Iv::point(gap).mul(Iv::point(gap)))
    });
    // lower / w_max², rounded down (w_max ≥ W > 0 on the edge).
    let d = lower.div(Iv::point(w_max).mul(Iv::point(w_max)));
    if d.lo > best {
        return true;
    }
    if depth == 0 || d.lo.is_nan() {
        return false;
    }
    let halves = |c: &[Iv]| -> (Vec<Iv>, Vec<Iv>) {
        let k = c.len();
        let mut work = c.to_vec();
        let (mut left, mut right) = (vec![Iv::point(0.0); k], vec![Iv::point(0.0); k]);
        for r in 0..k {
            left[r] = work[0];
            right[k - 1 - r] = work[k - 1 - r];
            for i in 0..k - 1 - r {
                work[i] = Iv::lerp(work[i], work[i + 1], 0.5);
            }
        }
        (left, right)
    };
    let split = |c: &[Vec<Iv>; 3]| {
        let h = [halves(&c[0]), halves(&c[1]), halves(&c[2])];
        (
            [h[0].0.clone(), h[1].0.clone(), h[2].0.clone()],
            [h[0].1.clone(), h[1].1.clone(), h[2].1.clone()],
        )
    };
    let (dl, dr) = split(&diff);
    let (wl, wr) = match &w {
        Some(w) => {
            let (a, b) = halves(w);
            (Some(a), Some(b))
        }
        None => (None, None),
    };
    edge_far((dl, wl), best, depth - 1) && edge_far((dr, wr), best, depth - 1)
}

/// The edge functions: `F` on `v = 0`, `v = 1` (curves in `u`), `G` on
/// `u = 0`, `u = 1` (curves in `v`).
struct EdgeRows {
    rows: [(Vec<Iv>, bool, f64); 4],
}

impl EdgeRows {
    fn of(f: &[Iv], g: &[Iv], bm: usize, bn: usize) -> Self {
        let row = |c: &[Iv], j: usize| (0..=bm).map(|i| c[i * (bn + 1) + j]).collect::<Vec<_>>();
        let column = |c: &[Iv], i: usize| c[i * (bn + 1)..(i + 1) * (bn + 1)].to_vec();
        Self {
            rows: [
                (row(f, 0), true, 0.0),
                (row(f, bn), true, 1.0),
                (column(g, 0), false, 0.0),
                (column(g, bm), false, 1.0),
            ],
        }
    }

    /// Each edge's critical points (univariate certified solve) as
    /// candidates; an edge function that may vanish identically makes the
    /// whole edge one undecided candidate.
    /// Edges whose distance is provably above `best` (an upper bound of the
    /// minimum) are skipped.
    fn candidates(
        &self,
        curves: [EdgeCurve; 4],
        opts: &SolveOptions,
        dist: &dyn Dist,
        best: f64,
        out: &mut Vec<Candidate>,
    ) -> Result<()> {
        let uopts = UniOptions::default().with_eps(opts.eps).with_max_boxes(opts.max_boxes);
        for ((coeffs, along_u, fixed), curve) in self.rows.iter().zip(curves) {
            let place = |s: [f64; 2]| {
                if *along_u {
                    Box2::new(s, [*fixed, *fixed])
                } else {
                    Box2::new([*fixed, *fixed], s)
                }
            };
            if edge_far(curve, best, EDGE_DEPTH) {
                continue;
            }
            let mut push = |s: [f64; 2], certified: bool| {
                out.push(candidate(dist, place(s), FootKind::Edge, certified, clamp_square))
            };
            let uni = UniBezier::on_unit(coeffs.iter().map(|c| interval(c.lo, c.hi)).collect())?;
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
                Err(_) => push([0.0, 1.0], false),
            }
        }
        Ok(())
    }
}

/// Tightens the lower bounds of the candidates that might hold the minimum
/// (see [`super::patches`]'s `refine`).
fn refine(dist: &dyn Dist, cands: &mut [Candidate], outer: f64) {
    let best = cands.iter().map(|c| c.d[1]).fold(outer, f64::min);
    for c in cands.iter_mut().filter(|c| c.d[0] < best) {
        c.d[0] = c.d[0].max(lower_bound(&|b: &Box2| dist.lower(b), c.bx, best));
    }
}

/// Grid samples per side for the floating-point proposal.
const GRID: usize = 8;

/// A point of the closed square near the closest one, in `f64`: the best of
/// a `GRID × GRID` sample, then a few Gauss–Newton steps on `|S − P|²`
/// clamped to the square. Only a proposal: its distance is enclosed before
/// it is used.
fn propose(t: &TensorPatch, grid: &[(f64, f64, DVec3)], p: [f64; 3]) -> [f64; 2] {
    let p = DVec3::from_array(p);
    let (mut u, mut v, mut d0) = grid
        .iter()
        .map(|&(u, v, s)| (u, v, (s - p).length_squared()))
        .fold((0.0, 0.0, f64::INFINITY), |a, b| if b.2 < a.2 { b } else { a });
    let (mut s, mut su, mut sv) = t.frame(u, v);
    for _ in 0..12 {
        let r = s - p;
        let (a, b, c) = (su.dot(su), su.dot(sv), sv.dot(sv));
        let (gu, gv) = (su.dot(r), sv.dot(r));
        let det = a * c - b * b;
        if det.is_nan() || det.abs() <= 1e-300 {
            break;
        }
        let (mut du, mut dv) = ((-c * gu + b * gv) / det, (b * gu - a * gv) / det);
        // Backtracking: halve the step until the distance decreases.
        let mut tries = 0;
        let (u1, v1, f1, d1) = loop {
            let (u1, v1) = ((u + du).clamp(0.0, 1.0), (v + dv).clamp(0.0, 1.0));
            let f1 = t.frame(u1, v1);
            let d1 = (f1.0 - p).length_squared();
            tries += 1;
            if d1 <= d0 || tries == 12 {
                break (u1, v1, f1, d1);
            }
            (du, dv) = (0.5 * du, 0.5 * dv);
        };
        if d1.is_nan() || d1 > d0 {
            break;
        }
        let small = (u1 - u).abs() + (v1 - v).abs() < 1e-15;
        (d0, u, v) = (d1, u1, v1);
        (s, su, sv) = f1;
        if small {
            break;
        }
    }
    [u, v]
}
