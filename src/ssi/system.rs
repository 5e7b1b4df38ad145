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
    /// The midpoints of `f`, for the `f64` proposals.
    fm: [Vec<f64>; 3],
}

/// Degrees up to this per axis get the stack-buffer evaluation of
/// [`System::value_jacobian`].
const BASIS_MAX: usize = 40;

/// The Bernstein basis `B^n_i(x)` and its derivative `n (B^{n−1}_{i−1} −
/// B^{n−1}_i)` at `x` (any float), by the recurrence
/// `B^r_i = (1 − x) B^{r−1}_i + x B^{r−1}_{i−1}`.
fn basis(n: usize, x: f64, b: &mut [f64; BASIS_MAX + 1], db: &mut [f64; BASIS_MAX + 1]) {
    b[0] = 1.0;
    let s = 1.0 - x;
    for r in 1..=n {
        if r == n {
            for i in 0..=n {
                let lo = if i > 0 { b[i - 1] } else { 0.0 };
                let hi = if i < n { b[i] } else { 0.0 };
                db[i] = n as f64 * (lo - hi);
            }
        }
        b[r] = x * b[r - 1];
        for i in (1..r).rev() {
            b[i] = s * b[i] + x * b[i - 1];
        }
        b[0] *= s;
    }
    if n == 0 {
        db[0] = 0.0;
    }
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
        let fm = std::array::from_fn(|e| c[e].iter().map(|v| v.mid()).collect());
        Self { deg, f: c, df, fm }
    }

    /// The common degrees `(m, n, p, q)`.
    pub(crate) fn degree(&self) -> [usize; 4] {
        self.deg
    }

    /// The coefficients of `F_e` (row-major in `(u, v, s, t)`).
    pub(crate) fn coeffs(&self, e: usize) -> &[Iv] {
        &self.f[e]
    }

    /// `F(x)` and `F'(x)` (3×4) in `f64`, proposals: the coefficients'
    /// midpoints contracted with the Bernstein basis of each axis and its
    /// derivative, axis by axis (forward mode), on the stack.
    pub(crate) fn value_jacobian(&self, x: &[f64; 4]) -> ([f64; 3], [[f64; 4]; 3]) {
        if self.deg.iter().any(|&n| n > BASIS_MAX) {
            let v = std::array::from_fn(|e| eval_mid(&self.f[e], &self.deg, x));
            let j = std::array::from_fn(|e| {
                std::array::from_fn(|d| {
                    let (deg, c) = &self.df[e][d];
                    eval_mid(c, deg, x)
                })
            });
            return (v, j);
        }
        let [n0, n1, n2, n3] = self.deg;
        let mut b = [[0.0f64; BASIS_MAX + 1]; 4];
        let mut db = [[0.0f64; BASIS_MAX + 1]; 4];
        for d in 0..4 {
            basis(self.deg[d], x[d], &mut b[d], &mut db[d]);
        }
        let mut val = [0.0f64; 3];
        let mut jac = [[0.0f64; 4]; 3];
        for e in 0..3 {
            let c = &self.fm[e];
            // (value, ∂0, ∂1, ∂2, ∂3) of the partial contractions.
            let mut a0 = [0.0f64; 5];
            for i in 0..=n0 {
                let mut a1 = [0.0f64; 4];
                for j in 0..=n1 {
                    let mut a2 = [0.0f64; 3];
                    for k in 0..=n2 {
                        let base = ((i * (n1 + 1) + j) * (n2 + 1) + k) * (n3 + 1);
                        let line = &c[base..base + n3 + 1];
                        let (mut v, mut g3) = (0.0, 0.0);
                        for (l, &cl) in line.iter().enumerate() {
                            v += b[3][l] * cl;
                            g3 += db[3][l] * cl;
                        }
                        a2[0] += b[2][k] * v;
                        a2[1] += db[2][k] * v;
                        a2[2] += b[2][k] * g3;
                    }
                    a1[0] += b[1][j] * a2[0];
                    a1[1] += db[1][j] * a2[0];
                    a1[2] += b[1][j] * a2[1];
                    a1[3] += b[1][j] * a2[2];
                }
                a0[0] += b[0][i] * a1[0];
                a0[1] += db[0][i] * a1[0];
                a0[2] += b[0][i] * a1[1];
                a0[3] += b[0][i] * a1[2];
                a0[4] += b[0][i] * a1[3];
            }
            val[e] = a0[0];
            jac[e] = [a0[1], a0[2], a0[3], a0[4]];
        }
        (val, jac)
    }

    /// The unit tangent of the curve at `x`: the signed 3×3 minors of
    /// `F'(x)` (`T_i = (−1)^i det F'` without column `i`), normalized;
    /// `None` where they all vanish (a singular point).
    pub(crate) fn tangent(&self, x: &[f64; 4]) -> Option<[f64; 4]> {
        let (_, j) = self.value_jacobian(x);
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
    /// within 12 steps.
    ///
    /// Converged means a step below `1e-14`, or a step below `1e-8` that is
    /// no longer than half the one before: the iteration has reached the
    /// rounding floor of `F`. Where the curve's derivative across the
    /// hyperplane is small (a loop of radius `1e-4` has `∂_y F ≈ 1e-4`),
    /// that floor, the rounding of `F` divided by `∂_y F`, lies above
    /// `1e-14`, and the steps wander at `1e-14 … 1e-13` for ever. This only
    /// proposes: the point is accepted or refused by the Krawczyk
    /// certificate.
    pub(crate) fn correct(&self, mut x: [f64; 4], p: usize) -> Option<[f64; 4]> {
        let q = others(p);
        let mut last = f64::INFINITY;
        for _ in 0..12 {
            let (f, j) = self.value_jacobian(&x);
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
            if size <= 1e-14 || (size <= 1e-8 && size > 0.5 * last) {
                return Some(x);
            }
            last = size;
        }
        None
    }

    /// The tube test of the module docs on `P × Y` (`y` the three axes
    /// other than `p`, in order): `Some(K)` when `K(P, Y) ⊂ int Y`.
    pub(crate) fn tube(&self, p: usize, pr: [f64; 2], y: [[f64; 2]; 3]) -> Option<[[f64; 2]; 3]> {
        let jac = self.jacobian_box(p, pr, &y)?;
        inside_k(&self.krawczyk(p, pr, y, &jac)?, &y)
    }

    /// An enclosure of `∂_y F` (columns: the axes other than `p`) over
    /// `P × Y`; `None` if not finite.
    pub(crate) fn jacobian_box(&self, p: usize, pr: [f64; 2], y: &[[f64; 2]; 3]) -> Option<[[Iv; 3]; 3]> {
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
        jac.iter().flatten().all(|x| x.is_finite()).then_some(jac)
    }

    /// The signs of the tangent's components over the box `b`, where proven:
    /// `T_k = (−1)^k det(F' without column k)` (the kernel of `F'`, the
    /// curve's tangent up to orientation), each determinant enclosed from
    /// the interval Jacobian over `b`; `Some(±1)` where the enclosure
    /// excludes 0.
    pub(crate) fn tangent_signs(&self, b: &Box4) -> [Option<f64>; 4] {
        let jac: [[Iv; 4]; 3] = std::array::from_fn(|e| {
            std::array::from_fn(|k| {
                let (deg, c) = &self.df[e][k];
                eval_box(c, deg, b)
            })
        });
        std::array::from_fn(|k| {
            let q = others(k);
            let m = |r: usize, c: usize| jac[r][q[c]];
            let det = m(0, 0)
                .mul(m(1, 1).mul(m(2, 2)).sub(m(1, 2).mul(m(2, 1))))
                .sub(m(0, 1).mul(m(1, 0).mul(m(2, 2)).sub(m(1, 2).mul(m(2, 0)))))
                .add(m(0, 2).mul(m(1, 0).mul(m(2, 1)).sub(m(1, 1).mul(m(2, 0)))));
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            if det.lo > 0.0 {
                Some(sign)
            } else if det.hi < 0.0 {
                Some(-sign)
            } else {
                None
            }
        })
    }

    /// `K(P, Y)` of the module docs, with `jac` an enclosure of `∂_y F`
    /// over `P × Y` (or over any box holding it); `None` when the midpoint
    /// Jacobian is singular or a bound is not finite. Outside a tube test
    /// it only proposes (a box to try next).
    pub(crate) fn krawczyk(&self, p: usize, pr: [f64; 2], y: [[f64; 2]; 3], jac: &[[Iv; 3]; 3]) -> Option<[Iv; 3]> {
        let q = others(p);
        let mut full: Box4 = [[0.0; 2]; 4];
        full[p] = pr;
        for (k, &c) in q.iter().enumerate() {
            full[c] = y[k];
        }
        let cm = inverse::<3>(jac.map(|r| r.map(Iv::mid)))?;
        let ym: [f64; 3] = std::array::from_fn(|k| 0.5 * y[k][0] + 0.5 * y[k][1]);
        let mut at = full;
        for (k, &c) in q.iter().enumerate() {
            at[c] = [ym[k], ym[k]];
        }
        // C·F(P, ỹ), enclosed by the mean-value form
        // C·F(p̃, ỹ) + (C·∂_p F(P, ỹ))·(P − p̃), second order in |P| and
        // free of the wrapping of a box by C (C·∂_p F ≈ −dy/dp). (Meeting
        // it with the direct enclosure C·F(P, ỹ) cost three evaluations
        // in 18 and saved no step.)
        let row = |r: usize, v: &[Iv; 3]| (0..3).fold(Iv::point(0.0), |s, c| s.add(Iv::point(cm[r][c]).mul(v[c])));
        let cfs: [Iv; 3] = if pr[0] == pr[1] {
            // A hyperplane: `F(p, ỹ)` at a point, nothing to expand.
            let f0: [Iv; 3] = std::array::from_fn(|e| eval_box(&self.f[e], &self.deg, &at));
            std::array::from_fn(|r| row(r, &f0))
        } else {
            let pm = 0.5 * pr[0] + 0.5 * pr[1];
            let mut centre = at;
            centre[p] = [pm, pm];
            let dp = Iv::new(pr[0], pr[1]).sub(Iv::point(pm));
            let f0: [Iv; 3] = std::array::from_fn(|e| eval_box(&self.f[e], &self.deg, &centre));
            let fp: [Iv; 3] = std::array::from_fn(|e| {
                let (deg, c) = &self.df[e][p];
                eval_box(c, deg, &at)
            });
            std::array::from_fn(|r| row(r, &f0).add(row(r, &fp).mul(dp)))
        };
        let mut out = [Iv::point(0.0); 3];
        for r in 0..3 {
            let cf = cfs[r];
            let mut s = Iv::point(ym[r]).sub(cf);
            for c in 0..3 {
                let mut m = Iv::point(if r == c { 1.0 } else { 0.0 });
                for k in 0..3 {
                    m = m.sub(Iv::point(cm[r][k]).mul(jac[k][c]));
                }
                s = s.add(m.mul(Iv::new(y[c][0], y[c][1]).sub(Iv::point(ym[c]))));
            }
            if !s.is_finite() {
                return None;
            }
            out[r] = s;
        }
        Some(out)
    }

    /// As [`System::certify_point`], inside a proven tube: `jac` encloses
    /// `∂_y F` over `tube`, so over every box `Y ⊂ tube` on the hyperplane,
    /// and only `F(x_p, ỹ)` is evaluated. `None` if no box of radius
    /// `1e-12`…`1e-8` (relative) inside the tube proves it.
    pub(crate) fn certify_in(&self, x: &[f64; 4], p: usize, tube: &Box4, jac: &[[Iv; 3]; 3]) -> Option<Box4> {
        self.certify_in_radii(x, p, tube, jac, &[1e-12, 1e-10, 1e-8])
    }

    /// [`System::certify_in`] with the radii `radii` (relative to
    /// `1 + |x|`, tried in order): smaller ones place a point within
    /// `10⁻¹⁴` of a face on its side.
    pub(crate) fn certify_in_radii(
        &self,
        x: &[f64; 4],
        p: usize,
        tube: &Box4,
        jac: &[[Iv; 3]; 3],
        radii: &[f64],
    ) -> Option<Box4> {
        let q = others(p);
        let pr = [x[p], x[p]];
        if !(tube[p][0] <= pr[0] && pr[1] <= tube[p][1]) {
            return None;
        }
        for &r in radii {
            let y: [[f64; 2]; 3] = std::array::from_fn(|k| {
                let c = x[q[k]];
                let rad = r * (1.0 + c.abs());
                [c - rad, c + rad]
            });
            if !(0..3).all(|k| tube[q[k]][0] <= y[k][0] && y[k][1] <= tube[q[k]][1]) {
                return None;
            }
            if let Some(k) = self.krawczyk(p, pr, y, jac).and_then(|k| inside_k(&k, &y)) {
                let mut out: Box4 = [[x[p], x[p]]; 4];
                for (i, &c) in q.iter().enumerate() {
                    out[c] = k[i];
                }
                return Some(out);
            }
        }
        None
    }

    /// Certifies the curve point near `x` on the hyperplane `x_p = x[p]`:
    /// a box `Y` around it with `K ⊂ int Y`, returning `K`; `None` if no box
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
            // One Krawczyk step from the Newton-converged point: `K` is
            // already about as narrow as the rounding of `F` there, so
            // iterating it would buy nothing.
            if let Some(k) = self.tube(p, pr, y) {
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

/// `K` as float bounds when it lies in the interior of `y`.
fn inside_k(k: &[Iv; 3], y: &[[f64; 2]; 3]) -> Option<[[f64; 2]; 3]> {
    let mut out = [[0.0; 2]; 3];
    for r in 0..3 {
        if !k[r].inside_open(y[r][0], y[r][1]) {
            return None;
        }
        out[r] = [k[r].lo, k[r].hi];
    }
    Some(out)
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
