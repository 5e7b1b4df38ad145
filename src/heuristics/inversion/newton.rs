//! Newton–Raphson for point inversion and projection (Pei et al. 2019,
//! §2.4, Eqs. (22)–(29), after Piegl & Tiller): with `r = S − P`,
//! `f = r·S_u`, `g = r·S_v` (Eqs. (23)–(24)), solve
//!
//! ```text
//! [ |S_u|² + r·S_uu    S_u·S_v + r·S_uv ] [Δu]     [f]
//! [ S_u·S_v + r·S_vu   |S_v|² + r·S_vv  ] [Δv] = − [g]      (Eqs. (25)–(28))
//! ```
//! and step, until `|P − S| ≤ ε₂` (Eq. (29)) or the step is below `10⁻¹⁴`
//! (a critical point of the distance: the projection case).

use super::{step_in_square, Failure, InvOptions, Outcome};
use crate::heuristics::jet;
use crate::heuristics::linalg::above;
use crate::ray::Patch;
use glam::DVec3;

/// Newton from `start`.
pub(super) fn newton(patch: &Patch, p: DVec3, start: [f64; 2], opts: &InvOptions) -> Outcome {
    let mut uv = start;
    for k in 0..opts.max_iterations {
        let j = jet(patch, uv[0], uv[1]);
        let r = j.s - p;
        if !r.is_finite() {
            return Outcome {
                end: Err(Failure::NonFinite),
                iterations: k,
            };
        }
        if r.length() <= opts.eps2 {
            return Outcome {
                end: Ok(uv),
                iterations: k,
            };
        }
        let (f, g) = (r.dot(j.su), r.dot(j.sv));
        let a = j.su.dot(j.su) + r.dot(j.suu);
        let b = j.su.dot(j.sv) + r.dot(j.suv);
        let c = j.sv.dot(j.sv) + r.dot(j.svv);
        let det = a * c - b * b;
        let scale = (a.abs() + b.abs()) * (b.abs() + c.abs());
        if !above(det.abs(), 1e-14 * scale) {
            return Outcome {
                end: Err(Failure::Singular),
                iterations: k + 1,
            };
        }
        let du = (-f * c + g * b) / det;
        let dv = (-g * a + f * b) / det;
        if let Some(out) = step_in_square(&mut uv, [du, dv], opts, k) {
            return out;
        }
    }
    let r = patch.eval(uv[0], uv[1]) - p;
    Outcome {
        end: if r.length() <= opts.eps2 {
            Ok(uv)
        } else {
            Err(Failure::NoConvergence)
        },
        iterations: opts.max_iterations,
    }
}
