//! Heuristic (uncertified) solvers from the seed papers, run against the
//! certified solver as an oracle. Nothing here is a proof: a returned point
//! is where an iteration stopped, and "nothing" does not mean "no root".
//!
//! * [`newton_ray_patch`]: Newton–Raphson on `G(u, v, t) = S(u, v) − (o + t d)`
//!   (Park, Ji & Ko 2013, §3 Eqs. (6)–(8) and (19)), the baseline every ray
//!   tracer starts from.

mod closed_form;
pub use closed_form::{
    ray_quadratic_bezier_2d, ray_segment_2d, ray_swept_quadratic_patch_3d, ClosedForm, CurveHit, FormulaFailure,
    PatchHit,
};

use crate::ray::{Patch, Ray};
use glam::{DMat3, DVec3};

/// Where a heuristic iteration stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeuristicHit {
    /// Ray parameter (for the direction as given).
    pub t: f64,
    /// Patch parameters.
    pub u: f64,
    /// Patch parameters.
    pub v: f64,
    /// Iterations used.
    pub iterations: usize,
}

/// Newton–Raphson for the ray–patch system from `(u0, v0)` (Park et al. 2013,
/// Eq. (8): `ΔX = −J⁻¹ G(X)`, `X = (u, v, t)`, `J = [S_u, S_v, −d]`), with
/// `t0` the projection of `S(u0, v0)` on the ray.
///
/// Stops when `|ΔX|∞ < tol` (returns the point if it lies in the closed
/// domain up to `1e-9` and `t ≥ 0`), when `J` is singular or the iterate
/// leaves `[−1, 2]²` (returns `None`), or after `max_iter` steps (`None`).
///
/// ```
/// use glam::DVec3;
/// use rootclip::heuristics::newton_ray_patch;
/// use rootclip::ray::{Ray, TriPatch};
/// let p = TriPatch::new(1, vec![DVec3::ZERO, DVec3::X, DVec3::Y], None).unwrap();
/// let ray = Ray::new(DVec3::new(0.25, 0.5, 2.0), DVec3::new(0.0, 0.0, -1.0)).unwrap();
/// let h = newton_ray_patch(&p.into(), &ray, (1.0 / 3.0, 1.0 / 3.0), 1e-13, 30).unwrap();
/// assert!((h.t - 2.0).abs() < 1e-12 && (h.u - 0.25).abs() < 1e-12);
/// ```
pub fn newton_ray_patch(
    patch: &Patch,
    ray: &Ray,
    start: (f64, f64),
    tol: f64,
    max_iter: usize,
) -> Option<HeuristicHit> {
    let (o, d) = (ray.origin(), ray.dir());
    let (mut u, mut v) = start;
    let mut t = (patch.eval(u, v) - o).dot(d) / d.length_squared();
    for k in 1..=max_iter {
        let g = patch.eval(u, v) - (o + d * t);
        let (su, sv) = patch.partials(u, v);
        let j = DMat3::from_cols(su, sv, -d);
        if j.determinant().abs() < 1e-300 {
            return None;
        }
        let dx: DVec3 = -(j.inverse() * g);
        if !dx.is_finite() {
            return None;
        }
        u += dx.x;
        v += dx.y;
        t += dx.z;
        if !(-1.0..=2.0).contains(&u) || !(-1.0..=2.0).contains(&v) {
            return None;
        }
        if dx.abs().max_element() < tol {
            let inside = match patch {
                Patch::Triangle(_) => u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9,
                _ => (-1e-9..=1.0 + 1e-9).contains(&u) && (-1e-9..=1.0 + 1e-9).contains(&v),
            };
            return (inside && t >= 0.0).then_some(HeuristicHit { t, u, v, iterations: k });
        }
    }
    None
}
