//! Newton–Raphson on the ray–patch system (Park, Ji & Ko 2013, §3.1 and §4.1).

use super::iteration::{Failure, Outcome, Setup};
use super::jet::frame;
use super::linalg::solve3;
use glam::DVec3;

/// The [`Iteration::Newton`](super::Iteration::Newton) iteration (its docs hold the formula).
pub(super) fn run(s: &Setup, start: [f64; 2]) -> Outcome {
    let [mut u, mut v] = start;
    let mut t = s.project(frame(s.patch, u, v).0);
    for k in 1..=s.opts.max_iterations {
        let (p, su, sv) = frame(s.patch, u, v);
        let g = p - (s.o + s.d * t);
        let Some(dx) = solve3([su, sv, -s.d], -g) else {
            return Outcome::failed(Failure::SingularJacobian, k);
        };
        match advance(s, [u, v], t, dx, k) {
            Ok((uv, next_t)) => ([u, v], t) = (uv, next_t),
            Err(done) => return done,
        }
    }
    Outcome::failed(Failure::NoConvergence, s.opts.max_iterations)
}

/// One update `X ← X + ΔX` of Newton or Halley: `Err` with the outcome when
/// the step is not finite, converged (`|ΔX|₂ < δ`) or stopped by the domain
/// rule, else the next `(u, v)` and `t`.
pub(super) fn advance(s: &Setup, uv: [f64; 2], t: f64, dx: DVec3, k: usize) -> Result<([f64; 2], f64), Outcome> {
    if !dx.is_finite() {
        return Err(Outcome::failed(Failure::NonFinite, k));
    }
    let to = [uv[0] + dx.x, uv[1] + dx.y];
    if dx.length() < s.opts.tol {
        return Err(s.finish(to, t + dx.z, k));
    }
    match s.step(uv, to) {
        Ok(next) => Ok((next, t + dx.z)),
        Err(f) => Err(Outcome::failed(f, k)),
    }
}
