//! Hu & Wallner's second-order iteration for orthogonal projection (2005,
//! as described in Pei et al. 2019, §2.4), started from the pieces of a
//! subdivided patch (§5.1.2: 64 pieces by three midpoint subdivisions, a
//! piece tried when its control net's box, expanded, holds `P`; the start
//! is the piece's centre).
//!
//! The PDF describes the step in words only, so it is re-derived here. At
//! `S = S(u, v)` with unit normal `n`:
//! 1. the first-order step: `(Δu, Δv)` with `S_u Δu + S_v Δv` the projection
//!    of `P − S` on the tangent plane; `T = S_u Δu + S_v Δv`, `t = T/|T|`;
//! 2. the normal curvature along it, `κ = n·S₂ / |T|²` with
//!    `S₂ = S_uu Δu² + 2 S_uv Δu Δv + S_vv Δv²`, and the curvature circle
//!    in the normal plane of `t`: centre `Q = S + n/κ`, radius `1/|κ|`;
//! 3. `X`: where the line from `Q` through `P` (projected into that plane)
//!    meets the circle (for `κ ≈ 0`, the foot of `P` on the tangent line);
//! 4. the parameter step `λ(Δu, Δv)` whose second-order Taylor image has
//!    the tangential component of `X`: `λ|T| + ½λ² t·S₂ = t·(X − S)`, the
//!    root nearest the first-order `λ = t·(X − S)/|T|`.

use super::{step_in_square, Failure, InvOptions, Outcome};
use crate::heuristics::jet;
use crate::heuristics::linalg::above;
use crate::ray::Patch;
use glam::{DVec3, DVec4};

/// Subdivisions per side (three midpoint subdivisions: 8 × 8 = 64 pieces).
const SIDE: usize = 8;

/// How much a piece's control-net box is expanded, relative to its
/// diagonal (the paper expands "the convex hull scope" without a number).
const EXPAND: f64 = 0.1;

/// The pieces of a tensor patch: each piece's parameter box and its
/// control net's expanded bounding box.
#[derive(Clone, Debug, Default)]
pub struct Pieces {
    pieces: Vec<([f64; 2], [f64; 2], DVec3, DVec3)>,
    diagonal: f64,
}

impl Pieces {
    /// The 64 pieces of a tensor patch (none for other kinds).
    pub fn new(patch: &Patch) -> Self {
        let Patch::Tensor(t) = patch else {
            let (lo, hi) = sample_box(patch);
            return Self {
                pieces: Vec::new(),
                diagonal: (hi - lo).length(),
            };
        };
        let (m, n) = t.degree();
        let w = |k: usize| t.weights().map_or(1.0, |w| w[k]);
        let net: Vec<DVec4> = t
            .points()
            .iter()
            .enumerate()
            .map(|(k, p)| (*p * w(k)).extend(w(k)))
            .collect();
        let (lo, hi) = bounds(&net);
        let mut pieces = Vec::with_capacity(SIDE * SIDE);
        for a in 0..SIDE {
            let ur = [a as f64 / SIDE as f64, (a + 1) as f64 / SIDE as f64];
            // Rows (fixed j) restricted in u, then each row in v.
            let cols: Vec<Vec<DVec4>> = (0..=n)
                .map(|j| sub_curve(&(0..=m).map(|i| net[i * (n + 1) + j]).collect::<Vec<_>>(), ur))
                .collect();
            for b in 0..SIDE {
                let vr = [b as f64 / SIDE as f64, (b + 1) as f64 / SIDE as f64];
                let sub: Vec<DVec4> = (0..=m)
                    .flat_map(|i| sub_curve(&cols.iter().map(|c| c[i]).collect::<Vec<_>>(), vr))
                    .collect();
                let (l, h) = bounds(&sub);
                let pad = DVec3::splat(EXPAND * (h - l).length());
                pieces.push((ur, vr, l - pad, h + pad));
            }
        }
        Self {
            pieces,
            diagonal: (hi - lo).length(),
        }
    }

    /// The diagonal of the whole control net's box.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }
}

/// A box around a patch from a 9 × 9 sample (kinds without pieces: only
/// the scale of the tolerances comes from it).
fn sample_box(patch: &Patch) -> (DVec3, DVec3) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = -lo;
    for i in 0..9 {
        for j in 0..9 {
            let (u, v) = (i as f64 / 8.0, j as f64 / 8.0);
            if matches!(patch, Patch::Triangle(_)) && u + v > 1.0 {
                continue;
            }
            let s = patch.eval(u, v);
            (lo, hi) = (lo.min(s), hi.max(s));
        }
    }
    (lo, hi)
}

/// The box of the points of a homogeneous net.
fn bounds(net: &[DVec4]) -> (DVec3, DVec3) {
    net.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(l, h), c| {
            let p = c.truncate() / c.w;
            (l.min(p), h.max(p))
        },
    )
}

/// The control points of a curve restricted to `[a, b] ⊂ [0, 1]` (de
/// Casteljau at `b`, keep the left part, then at `a/b`, keep the right).
fn sub_curve(c: &[DVec4], [a, b]: [f64; 2]) -> Vec<DVec4> {
    let split = |c: &[DVec4], t: f64, left: bool| -> Vec<DVec4> {
        let k = c.len();
        let mut work = c.to_vec();
        let mut out = vec![DVec4::ZERO; k];
        for r in 0..k {
            if left {
                out[r] = work[0];
            } else {
                out[k - 1 - r] = work[k - 1 - r];
            }
            for i in 0..k - 1 - r {
                work[i] = work[i] * (1.0 - t) + work[i + 1] * t;
            }
        }
        out
    };
    let left = split(c, b, true);
    if a == 0.0 {
        left
    } else {
        split(&left, a / b, false)
    }
}

/// Hu's method: the pieces whose expanded box holds `p`, in order, each
/// iterated from its centre; the first that converges wins.
pub(super) fn from_pieces(patch: &Patch, pieces: &Pieces, p: DVec3, opts: &InvOptions) -> Outcome {
    let mut iterations = 0;
    let mut last = Failure::NotInAnyPiece;
    for (ur, vr, lo, hi) in &pieces.pieces {
        if p.cmplt(*lo).any() || p.cmpgt(*hi).any() {
            continue;
        }
        let start = [0.5 * (ur[0] + ur[1]), 0.5 * (vr[0] + vr[1])];
        let out = second_order(patch, p, start, opts);
        iterations += out.iterations;
        match out.end {
            Ok(uv) => {
                return Outcome {
                    end: Ok(uv),
                    iterations,
                }
            }
            Err(f) => last = f,
        }
    }
    Outcome {
        end: Err(last),
        iterations,
    }
}

/// The second-order iteration from `start` (module docs), until
/// `|S − P| ≤ ε₂` or a step below `10⁻¹⁴`.
pub(super) fn second_order(patch: &Patch, p: DVec3, start: [f64; 2], opts: &InvOptions) -> Outcome {
    let mut uv = start;
    for k in 0..opts.max_iterations {
        let j = jet(patch, uv[0], uv[1]);
        let q = p - j.s;
        if !q.is_finite() {
            return Outcome {
                end: Err(Failure::NonFinite),
                iterations: k,
            };
        }
        if q.length() <= opts.eps2 {
            return Outcome {
                end: Ok(uv),
                iterations: k,
            };
        }
        let Some(step) = hu_step(j, q) else {
            return Outcome {
                end: Err(Failure::Singular),
                iterations: k + 1,
            };
        };
        if let Some(out) = step_in_square(&mut uv, step, opts, k) {
            return out;
        }
    }
    let d = (patch.eval(uv[0], uv[1]) - p).length();
    Outcome {
        end: if d <= opts.eps2 {
            Ok(uv)
        } else {
            Err(Failure::NoConvergence)
        },
        iterations: opts.max_iterations,
    }
}

/// One step (module docs); `q = P − S`. `None` where the tangent plane is
/// degenerate.
fn hu_step(j: crate::heuristics::Jet, q: DVec3) -> Option<[f64; 2]> {
    let (e, f, g) = (j.su.dot(j.su), j.su.dot(j.sv), j.sv.dot(j.sv));
    let det = j.su.cross(j.sv).length_squared();
    if !above(det, 1e-24 * e * g) {
        return None;
    }
    let (qu, qv) = (q.dot(j.su), q.dot(j.sv));
    let (du, dv) = ((g * qu - f * qv) / det, (e * qv - f * qu) / det);
    let t_vec = j.su * du + j.sv * dv;
    let tl = t_vec.length();
    if !above(tl, 0.0) {
        return Some([0.0, 0.0]);
    }
    let t = t_vec / tl;
    let n = j.su.cross(j.sv).normalize();
    let s2 = j.suu * (du * du) + j.suv * (2.0 * du * dv) + j.svv * (dv * dv);
    let kappa = n.dot(s2) / (tl * tl);
    // P in the normal plane of t: (a, b) in the frame (t, n) at S.
    let (a, b) = (q.dot(t), q.dot(n));
    let x_t = if kappa.abs() * (a.abs() + b.abs()) < 1e-12 {
        a
    } else {
        let r = 1.0 / kappa; // signed: the centre is at (0, r)
        let (da, db) = (a, b - r);
        let len = (da * da + db * db).sqrt();
        if !above(len, 0.0) {
            return None; // P at the centre: every circle point is as near
        }
        da / len * r.abs()
    };
    let c2 = 0.5 * t.dot(s2);
    let lambda = if c2 == 0.0 {
        x_t / tl
    } else {
        let disc = tl * tl + 4.0 * c2 * x_t;
        if disc >= 0.0 {
            2.0 * x_t / (tl + disc.sqrt())
        } else {
            x_t / tl
        }
    };
    Some([lambda * du, lambda * dv])
}
