//! Multivariate Halley on the ray–patch system (Park, Ji & Ko 2013, §3.2
//! and §4.2, after Cuyt & Rall 1985).

use super::iteration::{Failure, Outcome, Setup};
use super::jet::jet;
use super::linalg::solve3;
use super::newton::advance;
use glam::DVec3;

/// The [`Iteration::Halley`](super::Iteration::Halley) iteration (its docs hold the formula).
pub(super) fn run(s: &Setup, start: [f64; 2]) -> Outcome {
    let [mut u, mut v] = start;
    let mut t = s.project(jet(s.patch, u, v).s);
    for k in 1..=s.opts.max_iterations {
        let j = jet(s.patch, u, v);
        let cols = [j.su, j.sv, -s.d];
        let g = j.s - (s.o + s.d * t);
        let Some(q) = solve3(cols, -g) else {
            return Outcome::failed(Failure::SingularJacobian, k);
        };
        let h = q.x * q.x * j.suu + 2.0 * q.x * q.y * j.suv + q.y * q.y * j.svv;
        let Some(b) = solve3(cols, h) else {
            return Outcome::failed(Failure::SingularJacobian, k);
        };
        let dx = DVec3::from_array(std::array::from_fn(|c| {
            let (qc, bc) = (q[c], b[c]);
            if qc == 0.0 {
                0.0
            } else {
                qc * qc / (qc + 0.5 * bc)
            }
        }));
        match advance(s, [u, v], t, dx, k) {
            Ok((uv, next_t)) => ([u, v], t) = (uv, next_t),
            Err(done) => return done,
        }
    }
    Outcome::failed(Failure::NoConvergence, s.opts.max_iterations)
}
