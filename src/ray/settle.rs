//! The ray reduction in exact arithmetic, for [`crate::solve::settle`]: a
//! certified root within rounding of the patch's edge, or at `t` within
//! rounding of an end of the `t` range, is settled exactly.
//!
//! For a patch whose control points and weights are the given floats (not a
//! B-spline piece, whose net carries knot-insertion error), the ray's planes
//! are taken with exactly representable normals `n_a = e_a × d`,
//! `n_b = e_b × d` (`a`, `b` the two axes other than `d`'s largest component
//! `c`, so `n_a × n_b = d_c d ≠ 0`: the planes meet in the ray's line, and the
//! system has the same roots as the one solved in floating point). Then
//! `f_k = Σ w_ij n_k·(P_ij − o) B_ij` and the numerator of `t`,
//! `h = Σ w_ij d·(P_ij − o) B_ij` (`t = h / (W |d|²)`, `W > 0`), have exact
//! rational coefficients; so do `h − t₀|d|²W` and `t₁|d|²W − h`, whose signs
//! say `t ≥ t₀` and `t ≤ t₁` for the ends of a range.

use super::patch::BezierRef;
use super::query::Ray;
use crate::solve::settle::{ExactSystem, Settled, Shape};
use crate::solve::Box2;
use glam::DVec3;
use num_rational::BigRational;
use num_traits::{One, Zero};

type Q = BigRational;

/// Settles the root certified in `bx` for the `t` range `[lo, hi]`:
/// [`Settled::Inside`] is a hit (on the closed patch, `t` in the range),
/// [`Settled::Outside`] a miss; undecided for patches that are not exactly
/// their floats. `check_hi`: the upper end needs a proof too (the lower end,
/// when finite, is always settled, with the domain).
pub(super) fn settle(b: BezierRef, ray: &Ray, bx: Box2, range: [f64; 2], check_hi: bool) -> Settled {
    match exact_net(b).and_then(|(shape, hom)| systems_of_net(shape, &hom, ray, range, check_hi)) {
        Some(systems) => settle_all(&systems, bx),
        None => Settled::Undecided,
    }
}

/// Every system must place the root inside: a miss if one proves it
/// outside, a hit if all prove it inside.
pub(super) fn settle_all(systems: &[ExactSystem], bx: Box2) -> Settled {
    let mut all_inside = true;
    for sys in systems {
        match sys.settle(bx) {
            Settled::Outside => return Settled::Outside,
            Settled::Undecided => all_inside = false,
            Settled::Inside => {}
        }
    }
    if all_inside {
        Settled::Inside
    } else {
        Settled::Undecided
    }
}

/// The exact systems whose settling decides a root for the range `[lo, hi]`:
/// one with `t ≥ lo` as its sign condition (none when `lo = −∞`), one with
/// `t ≤ hi` when `check_hi` and `hi` is finite, and one with the domain alone
/// if neither applies. `None` if a value is not finite.
pub(super) fn systems_of_net(
    shape: Shape,
    hom: &[[Q; 4]],
    ray: &Ray,
    [lo, hi]: [f64; 2],
    check_hi: bool,
) -> Option<Vec<ExactSystem>> {
    let mut out = Vec::with_capacity(2);
    if lo.is_finite() {
        out.push(system_of_net(shape, hom, ray, Bound::Min(lo))?);
    }
    if check_hi && hi.is_finite() {
        out.push(system_of_net(shape, hom, ray, Bound::Max(hi))?);
    }
    if out.is_empty() {
        out.push(system_of_net(shape, hom, ray, Bound::None)?);
    }
    Some(out)
}

/// The sign condition on `t` an exact system carries.
#[derive(Clone, Copy)]
enum Bound {
    /// None: the domain alone.
    None,
    /// `t ≥ lo`: `h − lo·|d|²·W ≥ 0`.
    Min(f64),
    /// `t ≤ hi`: `hi·|d|²·W − h ≥ 0`.
    Max(f64),
}

/// The homogeneous control point `(w x, w y, w z, w)` exactly (`w = 1`
/// without a weight); `None` if a value is not finite.
pub(crate) fn exact_hom(p: DVec3, weight: Option<f64>) -> Option<[Q; 4]> {
    let q = |x: f64| Q::from_float(x);
    let w = match weight {
        Some(w) => q(w)?,
        None => Q::one(),
    };
    Some([&w * q(p.x)?, &w * q(p.y)?, &w * q(p.z)?, w])
}

/// The exact plane equations `f`, `g` and the numerator of `t`, `h`, of a
/// homogeneous net `(w x, w y, w z, w)` and the ray (module docs): the
/// coefficients `n·(wP − w o)` with `n = e_k × d` for the two axes `k` other
/// than `d`'s largest component, and `n = d`. `None` if a value is not
/// finite.
pub(crate) fn exact_rows(hom: &[[Q; 4]], ray: &Ray) -> Option<[Vec<Q>; 3]> {
    let q = |x: f64| Q::from_float(x);
    let vec = |p: DVec3| -> Option<[Q; 3]> { Some([q(p.x)?, q(p.y)?, q(p.z)?]) };
    let (o, d) = (vec(ray.origin())?, vec(ray.dir())?);
    let a = ray.dir().abs();
    let c = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    // e_k × d, for the two axes k ≠ c; then d itself for t.
    let normal = |k: usize| {
        let mut e = [Q::zero(), Q::zero(), Q::zero()];
        e[k] = Q::one();
        [
            &e[1] * &d[2] - &e[2] * &d[1],
            &e[2] * &d[0] - &e[0] * &d[2],
            &e[0] * &d[1] - &e[1] * &d[0],
        ]
    };
    let normals = [normal((c + 1) % 3), normal((c + 2) % 3), d];
    // n·(wP − w o) for each row.
    let rows: Vec<Vec<Q>> = normals
        .iter()
        .map(|n| {
            hom.iter()
                .map(|h| (0..3).fold(Q::zero(), |acc, c| acc + &n[c] * (&h[c] - &h[3] * &o[c])))
                .collect()
        })
        .collect();
    rows.try_into().ok()
}

/// The exact system of a homogeneous net `(w x, w y, w z, w)` (in `shape`'s
/// storage order) and the ray (module docs), with the sign condition `bound`.
fn system_of_net(shape: Shape, hom: &[[Q; 4]], ray: &Ray, bound: Bound) -> Option<ExactSystem> {
    let q = |x: f64| Q::from_float(x);
    let [f, g, h] = exact_rows(hom, ray)?;
    let d = ray.dir();
    // t = h / (W |d|²) with W > 0: t ≥ lo ⟺ h − lo |d|² W ≥ 0.
    let d2 = [d.x, d.y, d.z]
        .iter()
        .map(|&x| q(x))
        .try_fold(Q::zero(), |acc, x| Some(acc + x.as_ref()? * x.as_ref()?))?;
    let shifted = |end: f64, sign: i32| -> Option<Vec<Q>> {
        let k = q(end)? * &d2;
        Some(
            h.iter()
                .zip(hom)
                .map(|(h, w)| if sign > 0 { h - &k * &w[3] } else { &k * &w[3] - h })
                .collect(),
        )
    };
    let cond = match bound {
        Bound::None => None,
        Bound::Min(0.0) => Some(h.clone()),
        Bound::Min(lo) => Some(shifted(lo, 1)?),
        Bound::Max(hi) => Some(shifted(hi, -1)?),
    };
    ExactSystem::new(shape, f, g, cond).ok()
}

/// The exact homogeneous net of a Bézier patch that is exactly its floats,
/// with its shape; `None` for a B-spline piece (its net carries knot
/// insertion error) or a value that is not finite.
pub(crate) fn exact_net(b: BezierRef) -> Option<(Shape, Vec<[Q; 4]>)> {
    let (shape, points, weights) = match b {
        BezierRef::Tri(p) => (Shape::Triangle(p.degree()), p.points(), p.weights()),
        BezierRef::Tensor(p) if p.net_is_exact() => {
            let (m, n) = p.degree();
            (Shape::Tensor(m, n), p.points(), p.weights())
        }
        _ => return None,
    };
    let hom = points
        .iter()
        .enumerate()
        .map(|(idx, &p)| exact_hom(p, weights.map(|w| w[idx])))
        .collect::<Option<Vec<_>>>()?;
    Some((shape, hom))
}

/// Proven: the ray runs along the patch — its two exact plane equations
/// share a non-constant factor (a curve of common zeros; exact test of
/// [`has_common_factor`](crate::solve::degenerate::has_common_factor) on
/// the exact reduction). `false` claims nothing (a B-spline piece, or no
/// common factor).
pub(crate) fn runs_along(b: BezierRef, ray: &Ray) -> bool {
    use crate::poly::{Polynomial, TensorBezier, TriBezier};
    let Some((shape, hom)) = exact_net(b) else {
        return false;
    };
    let Some([f, g, _]) = exact_rows(&hom, ray) else {
        return false;
    };
    let poly = |c: Vec<Q>| -> Option<Polynomial> {
        match shape {
            Shape::Tensor(m, n) => Some(Polynomial::from_square(&TensorBezier::on_unit_square(m, n, c).ok()?)),
            Shape::Triangle(n) => Some(Polynomial::from_triangle(&TriBezier::new(n, c).ok()?)),
        }
    };
    match (poly(f), poly(g)) {
        (Some(f), Some(g)) => !f.is_zero() && !g.is_zero() && crate::solve::degenerate::has_common_factor(&f, &g),
        _ => false,
    }
}
