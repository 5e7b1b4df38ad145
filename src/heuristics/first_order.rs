//! The first-order geometric iteration: the ray against the tangent plane
//! (Park, Ji & Ko 2013, §4.3).

use super::iteration::{Failure, Outcome, Setup};
use super::jet::frame;
use super::linalg::{above, project2, SINGULAR};

/// The [`Iteration::FirstOrder`](super::Iteration::FirstOrder) iteration (its docs hold the formula).
pub(super) fn run(s: &Setup, start: [f64; 2]) -> Outcome {
    let mut uv = start;
    for k in 1..=s.opts.max_iterations {
        let (p, su, sv) = frame(s.patch, uv[0], uv[1]);
        let n = su.cross(sv);
        if !above(n.length(), SINGULAR * su.length() * sv.length()) {
            return Outcome::failed(Failure::SingularJacobian, k);
        }
        let n = n.normalize();
        let dn = s.d.dot(n);
        if !above(dn.abs(), SINGULAR * s.d.length()) {
            return Outcome::failed(Failure::ParallelTangentPlane, k);
        }
        let q = s.o + s.d * ((p - s.o).dot(n) / dn);
        let Some(duv) = project2(su, sv, q - p) else {
            return Outcome::failed(Failure::SingularJacobian, k);
        };
        match advance_uv(s, uv, duv, k) {
            Ok(next) => uv = next,
            Err(done) => return done,
        }
    }
    Outcome::failed(Failure::NoConvergence, s.opts.max_iterations)
}

/// One update `(u, v) ← (u, v) + (Δu, Δv)` of a geometric iteration: `Err`
/// with the outcome when the step is not finite, converged
/// (`(Δu² + Δv²)^{1/2} < δ`; `t` is then the end point's projection on the
/// ray) or stopped by the domain rule, else the next `(u, v)`.
pub(super) fn advance_uv(s: &Setup, uv: [f64; 2], duv: [f64; 2], k: usize) -> Result<[f64; 2], Outcome> {
    if !(duv[0].is_finite() && duv[1].is_finite()) {
        return Err(Outcome::failed(Failure::NonFinite, k));
    }
    let to = [uv[0] + duv[0], uv[1] + duv[1]];
    if duv[0].hypot(duv[1]) < s.opts.tol {
        let t = s.project(frame(s.patch, to[0], to[1]).0);
        return Err(s.finish(to, t, k));
    }
    s.step(uv, to).map_err(|f| Outcome::failed(f, k))
}
