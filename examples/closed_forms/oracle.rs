//! The certified referees of Christensen's (2008) closed forms (harness code, shared by
//! the `closed_forms` example, `tests/closed_forms.rs` and the bench).
//!
//! * 2D, ray against a segment or a quadratic Bézier curve: the hits are the
//!   roots in `[0, 1]` of `f(t) = n·(b(t) − o)`, `n = (−d_y, d_x)` (the ray's
//!   line through `o` in implicit form), whose BB coefficients
//!   `n·(p_i − o)` are computed exactly in rationals from the float inputs
//!   and solved by [`solve_uni`]; the ray parameter's sign is that of
//!   `g(t) = d·(b(t) − o)` at the root, decided exactly (its BB coefficients
//!   on the root's interval all of one strict sign, after exact bisection of
//!   the interval if needed).
//! * 3D, ray against the swept patch: [`intersect`] on the tensor patch of
//!   bidegree `(2, 1)` with control points `(p_i, 0)` and `(p_i, e)`, whose
//!   `(u, v)` are the paper's `(t, u)` and whose ray parameter is the paper's
//!   `s`. Where that leaves a region undecided (grazing rays, rays nearly
//!   along the sweep), [`swept_reduced`] decides it by the exact reduction
//!   to 2D: the first two components of `p(t, u) = o + s d` are the 2D
//!   problem of the projected ray, and `u = (o_z + d_z s)/e ∈ [0, 1]` is
//!   one more exact sign at the root.

use num_rational::BigRational;
use num_traits::{Signed, Zero};
use rootclip::glam::{DVec2, DVec3};
use rootclip::inari::Interval;
use rootclip::ray::{intersect, HitStatus, Patch, Ray, RayOptions, RayOutcome, TensorPatch};
use rootclip::scalar::rational_to_interval;
use rootclip::solve::{solve_uni, UniOptions};
use rootclip::UniBezier;

type Q = BigRational;

/// A hit the referee proves: the intervals hold exactly one intersection of
/// the exact ray with the exact curve or patch, transversal, with `s ≥ 0`.
#[derive(Clone, Debug)]
pub struct Proven {
    /// The curve parameter `t`.
    pub t: [f64; 2],
    /// The sweep parameter `u` (3D only).
    pub u: Option<[f64; 2]>,
}

/// A region the referee leaves undecided: a tangency (double root), or a
/// hit whose `s ≥ 0` or position on the patch is not proven.
#[derive(Clone, Debug)]
pub struct Open {
    /// The curve parameter's range.
    pub t: [f64; 2],
    /// The sweep parameter's range (3D only).
    pub u: Option<[f64; 2]>,
}

/// What the referee says about one ray.
#[derive(Clone, Debug, Default)]
pub struct Referee {
    /// Certified hits with `s ≥ 0`.
    pub hits: Vec<Proven>,
    /// Undecided regions (none when every hit is decided).
    pub open: Vec<Open>,
    /// Every hit lies in `hits` or `open` (no budget ran out).
    pub complete: bool,
    /// The ray runs along the curve (2D: `f ≡ 0`) or along the patch (3D: a
    /// curve of hits): no finite list exists.
    pub degenerate: bool,
    /// 3D: the tensor-patch referee left something undecided and the exact
    /// reduction to 2D decided every hit instead.
    pub reduced: bool,
}

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite input")
}

/// The exact BB coefficients of `t ↦ w·(p(t) − o)` for the control points
/// `p` (`w`, `o` exact from floats).
fn dot_coeffs(w: [Q; 2], o: DVec2, p: &[DVec2]) -> Vec<Q> {
    p.iter()
        .map(|pi| &w[0] * (q(pi.x) - q(o.x)) + &w[1] * (q(pi.y) - q(o.y)))
        .collect()
}

fn eval(c: &[Q], t: &Q) -> Q {
    let mut w = c.to_vec();
    let s = Q::from_integer(1.into()) - t;
    for m in (1..w.len()).rev() {
        for i in 0..m {
            w[i] = &s * &w[i] + t * &w[i + 1];
        }
    }
    w.swap_remove(0)
}

/// The exact BB coefficients of `c` on `[a, b]` (blossoms `a^{n−i} b^i`).
fn restrict(c: &[Q], a: &Q, b: &Q) -> Vec<Q> {
    let n = c.len() - 1;
    (0..=n)
        .map(|i| {
            let mut w = c.to_vec();
            for k in 0..n {
                let t = if k < i { b } else { a };
                let s = Q::from_integer(1.into()) - t;
                for j in 0..n - k {
                    w[j] = &s * &w[j] + t * &w[j + 1];
                }
            }
            w.swap_remove(0)
        })
        .collect()
}

/// An enclosure of `g` over `t` (interval de Casteljau, outward rounding):
/// a cheap rigorous filter before the exact computation.
fn enclose(g: &[Q], t: [f64; 2]) -> Interval {
    enclose_iv(&g.iter().map(rational_to_interval).collect::<Vec<_>>(), t)
}

/// An enclosure over `t` of the polynomial whose coefficients lie in `g`.
fn enclose_iv(g: &[Interval], t: [f64; 2]) -> Interval {
    let t = Interval::try_from((t[0], t[1])).expect("ordered");
    let one = Interval::try_from((1.0, 1.0)).expect("point");
    let mut w = g.to_vec();
    for m in (1..w.len()).rev() {
        for i in 0..m {
            w[i] = (one - t) * w[i] + t * w[i + 1];
        }
    }
    w[0]
}

/// The sign of `g` at the one root of `f` in `t` (a simple root, `f` with
/// exact coefficients): `Some(true)` if `g > 0` there, `Some(false)` if
/// `g < 0`, `Some(true)` too if `g = 0` (the ray's origin on the curve:
/// `s = 0`), `None` if exact bisection does not tell within its budget.
fn sign_at_root(f: &[Q], g: &[Q], t: [f64; 2]) -> Option<bool> {
    let e = enclose(g, t);
    if e.inf() > 0.0 {
        return Some(true);
    }
    if e.sup() < 0.0 {
        return Some(false);
    }
    let (mut lo, mut hi) = (q(t[0]), q(t[1]));
    for _ in 0..200 {
        let cg = restrict(g, &lo, &hi);
        if cg.iter().all(Signed::is_positive) {
            return Some(true);
        }
        if cg.iter().all(Signed::is_negative) {
            return Some(false);
        }
        let (flo, fhi) = (eval(f, &lo), eval(f, &hi));
        for (fx, x) in [(&flo, &lo), (&fhi, &hi)] {
            if fx.is_zero() {
                return Some(!eval(g, x).is_negative());
            }
        }
        let mid = (&lo + &hi) / Q::from_integer(2.into());
        let fm = eval(f, &mid);
        if fm.is_zero() {
            return Some(!eval(g, &mid).is_negative());
        }
        if fm.is_positive() == flo.is_positive() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    None
}

/// The referee for a ray against the curve with control points `p` (a
/// segment `l(t) = t a + (1 − t) b` is `[b, a]`; a quadratic is
/// `[p₀, p₁, p₂]`). First on enclosures of the coefficients (cheap, and its
/// certificates hold for the exact coefficients, which lie in them); where
/// that leaves anything undecided, on the exact rational coefficients.
pub fn curve_2d(o: DVec2, d: DVec2, p: &[DVec2]) -> Referee {
    curve_2d_enclosed(o, d, p).unwrap_or_else(|| curve_2d_exact(o, d, p))
}

/// Root intervals wider than this from the enclosures are recomputed from
/// the exact coefficients, so that the closed forms' errors are measured
/// against tight intervals (rounding in the coefficients widens the
/// enclosed intervals by about `1e-16 / |f'|`).
const TIGHT: f64 = 1e-13;

/// `w·(p_i − o)` enclosed, for each control point.
fn dot_enclosed(w: DVec2, o: DVec2, p: &[DVec2]) -> Vec<Interval> {
    let iv = |x: f64| Interval::try_from((x, x)).expect("finite");
    p.iter()
        .map(|pi| iv(w.x) * (iv(pi.x) - iv(o.x)) + iv(w.y) * (iv(pi.y) - iv(o.y)))
        .collect()
}

/// The referee on enclosures; `None` unless every hit is decided.
fn curve_2d_enclosed(o: DVec2, d: DVec2, p: &[DVec2]) -> Option<Referee> {
    let f = dot_enclosed(DVec2::new(-d.y, d.x), o, p);
    let g = dot_enclosed(d, o, p);
    let sol = solve_uni(&UniBezier::on_unit(f).ok()?, &UniOptions::default()).ok()?;
    if !sol.complete || !sol.clusters.is_empty() {
        return None;
    }
    let mut out = Referee {
        complete: true,
        ..Referee::default()
    };
    for r in &sol.roots {
        if r.interval[1] - r.interval[0] > TIGHT {
            return None; // ill-conditioned: exact coefficients give a tighter interval
        }
        let e = enclose_iv(&g, r.interval);
        if e.inf() > 0.0 {
            out.hits.push(Proven { t: r.interval, u: None });
        } else if e.sup() >= 0.0 {
            return None; // s ≥ 0 not decided (or NaN): exactly, then
        }
    }
    Some(out)
}

/// The referee on the exact rational coefficients.
fn curve_2d_exact(o: DVec2, d: DVec2, p: &[DVec2]) -> Referee {
    let (dx, dy) = (q(d.x), q(d.y));
    let f = dot_coeffs([-dy.clone(), dx.clone()], o, p);
    let g = dot_coeffs([dx, dy], o, p);
    if f.iter().all(Zero::is_zero) {
        return Referee {
            complete: true,
            degenerate: true,
            ..Referee::default()
        };
    }
    let sol = solve_uni(&UniBezier::on_unit(f.clone()).expect("finite"), &UniOptions::default()).expect("not zero");
    let mut out = Referee {
        complete: sol.complete,
        ..Referee::default()
    };
    for r in &sol.roots {
        match sign_at_root(&f, &g, r.interval) {
            Some(true) => out.hits.push(Proven { t: r.interval, u: None }),
            Some(false) => {}
            None => out.open.push(Open { t: r.interval, u: None }),
        }
    }
    for c in &sol.clusters {
        // A region entirely behind the origin holds no hit.
        if enclose(&g, c.interval).sup() >= 0.0 {
            out.open.push(Open { t: c.interval, u: None });
        }
    }
    for l in &sol.leftovers {
        out.open.push(Open { t: *l, u: None });
    }
    out
}

/// The swept patch of [`ray_swept_quadratic_patch_3d`](rootclip::heuristics::ray_swept_quadratic_patch_3d)
/// as a tensor patch: `(u, v) = (t, u)` of the paper.
pub fn swept_patch(p: [DVec2; 3], e: f64) -> Patch {
    let pts = p
        .iter()
        .flat_map(|pi| [DVec3::new(pi.x, pi.y, 0.0), DVec3::new(pi.x, pi.y, e)])
        .collect();
    Patch::from(TensorPatch::new(2, 1, pts, None).expect("a finite net"))
}

/// The referee for a 3D ray against the swept patch `p`, `e` (see the module
/// docs): [`swept_3d`], and where it leaves anything undecided,
/// [`swept_reduced`] if that decides every hit.
pub fn swept(o: DVec3, d: DVec3, p: [DVec2; 3], e: f64) -> Referee {
    let r = swept_3d(o, d, &swept_patch(p, e));
    if r.complete && r.open.is_empty() && !r.degenerate {
        return r;
    }
    swept_reduced(o, d, &p, e).unwrap_or(r)
}

/// The swept-patch referee by the exact reduction to 2D, for `e > 0`:
/// the roots `t` of `f(t) = n·(b(t) − o_xy)` (`n ⟂ d_xy`) isolated by
/// [`solve_uni`] on exact coefficients, and at each simple root three exact
/// signs, with `g(t) = d_xy·(b(t) − o_xy) = s |d_xy|²` there:
/// `s ≥ 0 ⇔ g ≥ 0`, `u ≥ 0 ⇔ o_z |d_xy|² + d_z g ≥ 0` and
/// `u ≤ 1 ⇔ (e − o_z) |d_xy|² − d_z g ≥ 0`. `None` unless every root is
/// simple and every sign decided (a tangency in plan, `d_xy = 0`, `e ≤ 0`).
pub fn swept_reduced(o: DVec3, d: DVec3, p: &[DVec2; 3], e: f64) -> Option<Referee> {
    let (o2, d2) = (o.truncate(), d.truncate());
    if d2 == DVec2::ZERO || e <= 0.0 {
        return None;
    }
    let (dx, dy) = (q(d2.x), q(d2.y));
    let f = dot_coeffs([-dy.clone(), dx.clone()], o2, p);
    if f.iter().all(Zero::is_zero) {
        return None;
    }
    let g = dot_coeffs([dx.clone(), dy.clone()], o2, p);
    let sol = solve_uni(&UniBezier::on_unit(f.clone()).ok()?, &UniOptions::default()).ok()?;
    if !sol.complete || !sol.clusters.is_empty() || !sol.leftovers.is_empty() {
        return None;
    }
    let dd = &dx * &dx + &dy * &dy;
    let (oz, dz, eq) = (q(o.z), q(d.z), q(e));
    let above: Vec<Q> = g.iter().map(|gi| &oz * &dd + &dz * gi).collect();
    let below: Vec<Q> = g.iter().map(|gi| (&eq - &oz) * &dd - &dz * gi).collect();
    let mut out = Referee {
        complete: true,
        reduced: true,
        ..Referee::default()
    };
    for r in &sol.roots {
        let on = sign_at_root(&f, &g, r.interval)?
            && sign_at_root(&f, &above, r.interval)?
            && sign_at_root(&f, &below, r.interval)?;
        if on {
            let (t, u) = narrow_t_and_u(&f, &above, &dd, &eq, r.interval);
            out.hits.push(Proven { t, u: Some(u) });
        }
    }
    Some(out)
}

/// Bisects the simple root of `f` in `t` exactly (rational midpoints,
/// below the float resolution if need be) until
/// `u = (o_z |d|² + d_z g) / (|d|² e)` — `above / (dd e)` — is enclosed to
/// `1e-13` (by the hull of its exact BB coefficients on the piece), and
/// returns both ranges. A nearly vertical ray makes `u` far more sensitive
/// to `t` than `t` itself (`du/dt ≈ 1/ε`).
fn narrow_t_and_u(f: &[Q], above: &[Q], dd: &Q, e: &Q, t: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    let scale = dd * e;
    let u_of = |lo: &Q, hi: &Q| {
        let c = restrict(above, lo, hi);
        let min = c.iter().min().expect("three coefficients") / &scale;
        let max = c.iter().max().expect("three coefficients") / &scale;
        [rational_to_interval(&min).inf(), rational_to_interval(&max).sup()]
    };
    let t_of = |lo: &Q, hi: &Q| [rational_to_interval(lo).inf(), rational_to_interval(hi).sup()];
    let (mut lo, mut hi) = (q(t[0]), q(t[1]));
    let f_lo = eval(f, &lo);
    for x in [&lo, &hi] {
        if eval(f, x).is_zero() {
            return (t_of(x, x), u_of(x, x));
        }
    }
    for _ in 0..200 {
        let u = u_of(&lo, &hi);
        if u[1] - u[0] <= 1e-13 {
            return (t_of(&lo, &hi), u);
        }
        let mid = (&lo + &hi) / Q::from_integer(2.into());
        let fm = eval(f, &mid);
        if fm.is_zero() {
            return (t_of(&mid, &mid), u_of(&mid, &mid));
        }
        if fm.is_positive() == f_lo.is_positive() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (t_of(&lo, &hi), u_of(&lo, &hi))
}

/// The referee for a 3D ray against the swept patch as a tensor patch, by
/// [`intersect`] alone.
pub fn swept_3d(o: DVec3, d: DVec3, patch: &Patch) -> Referee {
    let ray = Ray::new(o, d).expect("non-zero direction");
    let outcome = intersect(patch, &ray, &RayOptions::default()).expect("valid options");
    let hits = match &outcome {
        RayOutcome::Hits(h) => h,
        RayOutcome::Degenerate(_) => {
            return Referee {
                complete: true,
                degenerate: true,
                ..Referee::default()
            }
        }
    };
    let mut out = Referee {
        complete: hits.complete,
        ..Referee::default()
    };
    for h in &hits.hits {
        match h.status {
            HitStatus::Certified => out.hits.push(Proven {
                t: h.bx.u,
                u: Some(h.bx.v),
            }),
            HitStatus::Undecided(_) => out.open.push(Open {
                t: h.bx.u,
                u: Some(h.bx.v),
            }),
        }
    }
    out
}
