//! Multivariate Halley on the ray–patch system (Park, Ji & Ko 2013, §3.2
//! and §4.2, after Cuyt & Rall 1985).

use super::iteration::{Failure, Outcome, Setup};
use super::linalg::solve3;
use super::jet::jet;
use super::newton::advance;
use glam::DVec3;

/// Halley's method for `G(u, v, t) = S(u, v) − (o + t·d) = 0`.
///
/// * **Formula** (Eqs. (9)–(12), (21)): with `J = [S_u, S_v, −d]`, the
///   Newton step `Q = −J⁻¹G` (Eq. (10)) and
///   `b = J⁻¹ [Qᵀ H(G_x) Q, Qᵀ H(G_y) Q, Qᵀ H(G_z) Q]` (Eqs. (11)–(12)),
///   the step is, component by component, `ΔX_k = Q_k² / (Q_k + b_k / 2)`
///   (Eq. (9), whose fraction the PDF text loses: "Δ X = Q 2 Q + 1 2 b";
///   read so because it is the only reading that gives the scalar Halley
///   step `−2ff'/(2f'² − ff'')` for one unknown). `G` is linear in `t`, so
///   each Hessian (Eq. (21)) has only its `(u, v)` block, and
///   `Qᵀ H(G) Q = Q_u² S_uu + 2 Q_u Q_v S_uv + Q_v² S_vv`.
/// * **Rounding.** `f64`; the end point is a claim.
/// * **Degenerate cases.** As Newton ([`Failure::SingularJacobian`]); a
///   component with `Q_k = 0` takes `ΔX_k = 0` (the limit), one with
///   `Q_k + b_k/2 = 0 ≠ Q_k` has no step ([`Failure::NonFinite`]).
///
/// Runnable example: [`iterate`](super::iterate) with [`Iteration::Halley`](super::Iteration::Halley).
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
