//! The residual system `F(u, v, s, t) = 0` (3 equations, 4 unknowns; see
//! [`algebra::residual`](super::algebra::residual)) as the tracer uses it:
//! `f64` values, Jacobians and tangents that propose, and the interval
//! test that proves a piece of the curve.
//!
//! # The tube test (parametric Krawczyk)
//! Fix an axis `p` (the marching parameter) and write `x = (x_p, y)`. For a
//! box `P × Y`, `ỹ = mid Y` and any real 3×3 matrix `C`, let
//! ```text
//! K(P, Y) = ỹ − C·F(P, ỹ) + (I − C·∂_y F(P × Y))·(Y − ỹ)
//! ```
//! with outward-rounded enclosures. If `K(P, Y) ⊂ int Y` then for every
//! `x_p ∈ P` the equation `F(x_p, y) = 0` has exactly one solution
//! `y(x_p) ∈ Y`, and `∂_y F` is non-singular on `P × Y` (Krawczyk's theorem
//! for each fixed `x_p`, the enclosures holding for all of them at once).
//! By the implicit function theorem `y(·)` is smooth: the zero set of `F`
//! in `P × Y` is exactly one arc, a graph over `P` that enters and leaves
//! through the faces `x_p = min P` and `x_p = max P`. With `P` a single
//! float this is the certificate of one traced point: exactly one point of
//! the curve on the hyperplane `x_p = const` (the plane across the marching
//! direction) within `Y`.

use super::algebra::Poly;
use crate::scalar::iv::Iv;
use crate::solve::nd::krawczyk::inverse;
use crate::solve::nd::tensor::{derivative, eval_box, eval_mid};

/// A box in `(u, v, s, t)`.
pub(crate) type Box4 = [[f64; 2]; 4];

/// `F` and its partial derivatives on `[0, 1]⁴`.
pub(crate) struct System {
    deg: [usize; 4],
    f: [Vec<Iv>; 3],
    /// `df[e][d]`: degrees and coefficients of `∂F_e/∂x_d`.
    df: Vec<Vec<(Vec<usize>, Vec<Iv>)>>,
}

impl System {
    pub(crate) fn new(f: &[Poly; 3]) -> Self {
        let deg: [usize; 4] = std::array::from_fn(|d| f[0].deg[d]);
        let c: [Vec<Iv>; 3] = std::array::from_fn(|e| {
            if f[e].deg == deg {
                f[e].c.clone()
            } else {
                crate::solve::nd::clip::elevate(&f[e].c, &f[e].deg, &deg)
            }
        });
        let df = (0..3)
            .map(|e| (0..4).map(|d| derivative(&c[e], &deg, d)).collect())
            .collect();
        Self { deg, f: c, df }
    }

    /// The common degrees `(m, n, p, q)`.
    pub(crate) fn degree(&self) -> [usize; 4] {
        self.deg
    }

    /// The coefficients of `F_e` (row-major in `(u, v, s, t)`).
    pub(crate) fn coeffs(&self, e: usize) -> &[Iv] {
        &self.f[e]
    }

    /// `F(x)` in `f64` (a proposal).
    pub(crate) fn value(&self, x: &[f64; 4]) -> [f64; 3] {
        std::array::from_fn(|e| eval_mid(&self.f[e], &self.deg, x))
    }

    /// `F'(x)` in `f64`, 3×4.
    pub(crate) fn jacobian(&self, x: &[f64; 4]) -> [[f64; 4]; 3] {
        std::array::from_fn(|e| {
            std::array::from_fn(|d| {
                let (deg, c) = &self.df[e][d];
                eval_mid(c, deg, x)
            })
        })
    }

    /// The unit tangent of the curve at `x`: the signed 3×3 minors of
    /// `F'(x)` (`T_i = (−1)^i det F'` without column `i`), normalized;
    /// `None` where they all vanish (a singular point).
    pub(crate) fn tangent(&self, x: &[f64; 4]) -> Option<[f64; 4]> {
        let j = self.jacobian(x);
        let t: [f64; 4] = std::array::from_fn(|i| {
            let cols: Vec<usize> = (0..4).filter(|&c| c != i).collect();
            let m = |r: usize, k: usize| j[r][cols[k]];
            let det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
                - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
                + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
            if i % 2 == 0 {
                det
            } else {
                -det
            }
        });
        let n = t.iter().map(|x| x * x).sum::<f64>().sqrt();
        (n > 0.0 && n.is_finite()).then(|| t.map(|x| x / n))
    }

    /// Newton's method on `F(x) = 0` with `x_p` fixed (the curve cut by the
    /// hyperplane `x_p = x[p]`), from `x`; `None` if it does not converge
    /// within 12 steps to `|Δ| ≤ 1e-14`.
    pub(crate) fn correct(&self, mut x: [f64; 4], p: usize) -> Option<[f64; 4]> {
        let q = others(p);
        for _ in 0..12 {
            let f = self.value(&x);
            let j = self.jacobian(&x);
            let y = inverse::<3>(std::array::from_fn(|r| q.map(|c| j[r][c])))?;
            let mut size = 0.0f64;
            for (k, &c) in q.iter().enumerate() {
                let dx: f64 = (0..3).map(|r| y[k][r] * f[r]).sum();
                x[c] -= dx;
                size = size.max(dx.abs());
            }
            if !x.iter().all(|v| v.is_finite()) || x.iter().any(|v| v.abs() > 10.0) {
                return None;
            }
            if size <= 1e-14 {
                return Some(x);
            }
        }
        None
    }

    /// The tube test of the module docs on `P × Y` (`y` the three axes
    /// other than `p`, in order): `Some(K)` when `K(P, Y) ⊂ int Y`.
    pub(crate) fn tube(&self, p: usize, pr: [f64; 2], y: [[f64; 2]; 3]) -> Option<[[f64; 2]; 3]> {
        let q = others(p);
        let mut full: Box4 = [[0.0; 2]; 4];
        full[p] = pr;
        for (k, &c) in q.iter().enumerate() {
            full[c] = y[k];
        }
        let jac: [[Iv; 3]; 3] = std::array::from_fn(|e| {
            std::array::from_fn(|k| {
                let (deg, c) = &self.df[e][q[k]];
                eval_box(c, deg, &full)
            })
        });
        if jac.iter().flatten().any(|x| !x.is_finite()) {
            return None;
        }
        let cm = inverse::<3>(jac.map(|r| r.map(Iv::mid)))?;
        let ym: [f64; 3] = std::array::from_fn(|k| 0.5 * y[k][0] + 0.5 * y[k][1]);
        let mut at = full;
        for (k, &c) in q.iter().enumerate() {
            at[c] = [ym[k], ym[k]];
        }
        // C·F(P, ỹ), enclosed twice: directly, and by the mean-value form
        // C·F(p̃, ỹ) + (C·∂_p F(P, ỹ))·(P − p̃), second order in |P| and
        // free of the wrapping of a box by C (C·∂_p F ≈ −dy/dp); both hold.
        let pm = 0.5 * pr[0] + 0.5 * pr[1];
        let mut centre = at;
        centre[p] = [pm, pm];
        let dp = Iv::new(pr[0], pr[1]).sub(Iv::point(pm));
        let direct: [Iv; 3] = std::array::from_fn(|e| eval_box(&self.f[e], &self.deg, &at));
        let f0: [Iv; 3] = std::array::from_fn(|e| eval_box(&self.f[e], &self.deg, &centre));
        let fp: [Iv; 3] = std::array::from_fn(|e| {
            let (deg, c) = &self.df[e][p];
            eval_box(c, deg, &at)
        });
        let row = |r: usize, v: &[Iv; 3]| (0..3).fold(Iv::point(0.0), |s, c| s.add(Iv::point(cm[r][c]).mul(v[c])));
        let mut out = [[0.0; 2]; 3];
        for r in 0..3 {
            let mv = row(r, &f0).add(row(r, &fp).mul(dp));
            let cf = row(r, &direct).meet(mv).unwrap_or(mv);
            let mut s = Iv::point(ym[r]).sub(cf);
            for c in 0..3 {
                let mut m = Iv::point(if r == c { 1.0 } else { 0.0 });
                for k in 0..3 {
                    m = m.sub(Iv::point(cm[r][k]).mul(jac[k][c]));
                }
                s = s.add(m.mul(Iv::new(y[c][0], y[c][1]).sub(Iv::point(ym[c]))));
            }
            if !(s.is_finite() && s.inside_open(y[r][0], y[r][1])) {
                return None;
            }
            out[r] = [s.lo, s.hi];
        }
        Some(out)
    }

    /// Certifies the curve point near `x` on the hyperplane `x_p = x[p]`:
    /// a box `Y` around it with `K ⊂ int Y`, contracted; `None` if no box
    /// of radius `1e-12`…`1e-6` (relative) proves it.
    pub(crate) fn certify_point(&self, x: &[f64; 4], p: usize) -> Option<Box4> {
        let q = others(p);
        let pr = [x[p], x[p]];
        for r in [1e-12, 1e-10, 1e-8, 1e-6] {
            let y: [[f64; 2]; 3] = std::array::from_fn(|k| {
                let c = x[q[k]];
                let rad = r * (1.0 + c.abs());
                [c - rad, c + rad]
            });
            if let Some(mut k) = self.tube(p, pr, y) {
                for _ in 0..3 {
                    match self.tube(p, pr, k) {
                        Some(kk) => k = kk,
                        None => break,
                    }
                }
                let mut out: Box4 = [[x[p], x[p]]; 4];
                for (i, &c) in q.iter().enumerate() {
                    out[c] = k[i];
                }
                return Some(out);
            }
        }
        None
    }
}

/// The three axes other than `p`, in order.
pub(crate) fn others(p: usize) -> [usize; 3] {
    let mut out = [0; 3];
    let mut k = 0;
    for d in 0..4 {
        if d != p {
            out[k] = d;
            k += 1;
        }
    }
    out
}
