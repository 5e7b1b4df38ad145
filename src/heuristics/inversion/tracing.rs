//! Tracing the projection of a segment onto the surface (Pei et al. 2019,
//! §2.1, §2.3): the paper's single trace and Wang et al.'s multisegment
//! tracing.
//!
//! For `L(t) = tP + (1 − t)P₀` and the fixed direction
//! `V = [N₀ × (P − P₀)] × (P − P₀)` (`N₀` the normal at `P₀`), the curve
//! `S(u(t), v(t))` with `[S − L] × V = 0` (Eq. (2)) satisfies
//!
//! ```text
//! u_t = S_v·[V × (P − P₀)] / V·(S_u × S_v),
//! v_t = S_u·[(P − P₀) × V] / V·(S_u × S_v)          (Eq. (5))
//! ```
//! (re-derived: dot `S_u u_t + S_v v_t − (P − P₀) = λV` with `S_v × V` and
//! with `S_u × V`; the printed equation agrees). It is integrated by the
//! classic fixed-step RK4 (Eq. (17)) from `t₀ = 0` to `t_n = 1`.

use super::{clamp, Failure, InvOptions, Outcome};
use crate::heuristics::jet;
use crate::heuristics::linalg::above;
use crate::ray::Patch;
use glam::DVec3;

/// The right-hand side of Eq. (5) at `(u, v)`, or `None` where
/// `V·(S_u × S_v)` vanishes (the projection direction is tangent).
fn field(patch: &Patch, uv: [f64; 2], d: DVec3, v: DVec3) -> Option<[f64; 2]> {
    let j = jet(patch, uv[0], uv[1]);
    let den = v.dot(j.su.cross(j.sv));
    let scale = v.length() * j.su.length() * j.sv.length();
    if !above(den.abs(), 1e-12 * scale) {
        return None;
    }
    Some([j.sv.dot(v.cross(d)) / den, j.su.dot(d.cross(v)) / den])
}

/// One RK4 step of Eq. (17) (the field does not depend on `t`).
fn rk4_step(patch: &Patch, uv: [f64; 2], h: f64, d: DVec3, v: DVec3) -> Option<[f64; 2]> {
    let add = |a: [f64; 2], k: [f64; 2], s: f64| [a[0] + s * k[0], a[1] + s * k[1]];
    let k1 = field(patch, uv, d, v)?;
    let k2 = field(patch, add(uv, k1, h / 2.0), d, v)?;
    let k3 = field(patch, add(uv, k2, h / 2.0), d, v)?;
    let k4 = field(patch, add(uv, k3, h), d, v)?;
    let k = [
        k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0],
        k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1],
    ];
    Some(add(uv, k, h / 6.0))
}

/// Traces one segment from `S(start)` to `P` with `n = ⌈1/dt⌉` equal steps
/// (Eqs. (18)–(19)), stopping early once `|S − P| < eps1` (Eq. (6); the
/// loop of Algorithm 1, lines 11–16). Each step is clamped to the square.
pub(super) fn trace(patch: &Patch, p: DVec3, start: [f64; 2], dt: f64, eps1: f64) -> Outcome {
    let j = jet(patch, start[0], start[1]);
    let d = p - j.s;
    if d.length() < eps1 {
        return Outcome {
            end: Ok(start),
            iterations: 0,
        };
    }
    let n0 = j.su.cross(j.sv).normalize_or_zero();
    let mut v = n0.cross(d).cross(d);
    if v.length_squared() == 0.0 {
        // P₀P along the normal: any direction across the segment in the
        // tangent plane's normal section serves; the normal itself is the
        // limit of V as P₀P tilts.
        v = n0;
    }
    let steps = (1.0 / dt).ceil().max(1.0) as usize;
    let h = 1.0 / steps as f64;
    let mut uv = start;
    for k in 0..steps {
        uv = match rk4_step(patch, uv, h, d, v) {
            Some(x) if x[0].is_finite() && x[1].is_finite() => clamp(x),
            Some(_) => {
                return Outcome {
                    end: Err(Failure::NonFinite),
                    iterations: k + 1,
                }
            }
            None => {
                return Outcome {
                    end: Err(Failure::Singular),
                    iterations: k + 1,
                }
            }
        };
        if (patch.eval(uv[0], uv[1]) - p).length() < eps1 {
            return Outcome {
                end: Ok(uv),
                iterations: k + 1,
            };
        }
    }
    Outcome {
        end: Ok(uv),
        iterations: steps,
    }
}

/// Wang et al.'s multisegment tracing (§5.1, Eq. (38)): trace from the
/// start to `P`, then from the end point to `P` again along a new segment
/// with a new direction `V`, each segment with the same step, until
/// `|S − P| ≤ ε₂` (Eq. (29)) — checked after every RK4 step — or the cap on
/// segments. A segment that makes no progress ends the run.
pub(super) fn multisegment(patch: &Patch, p: DVec3, opts: &InvOptions) -> Outcome {
    let mut uv = opts.start;
    let mut iterations = 0;
    let mut dist = (patch.eval(uv[0], uv[1]) - p).length();
    for _ in 0..opts.max_iterations {
        if dist <= opts.eps2 {
            return Outcome {
                end: Ok(uv),
                iterations,
            };
        }
        let seg = trace(patch, p, uv, opts.dt, opts.eps2);
        iterations += seg.iterations;
        let next = match seg.end {
            Ok(x) => x,
            Err(f) => {
                return Outcome {
                    end: Err(f),
                    iterations,
                }
            }
        };
        let d = (patch.eval(next[0], next[1]) - p).length();
        if !above(dist, d) {
            // A stationary point of the tracing (off-surface P: the
            // projection of the segment ends where S − P ∥ V).
            return Outcome {
                end: if d <= opts.eps2 {
                    Ok(next)
                } else {
                    Err(Failure::NoConvergence)
                },
                iterations,
            };
        }
        (uv, dist) = (next, d);
    }
    Outcome {
        end: if dist <= opts.eps2 {
            Ok(uv)
        } else {
            Err(Failure::NoConvergence)
        },
        iterations,
    }
}
