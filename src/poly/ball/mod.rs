//! Ball polynomials: triangular BB polynomials with `f64` coefficients and one
//! rigorous radius — the certified solver's working form.
//!
//! # Definition
//! A [`TriBall`] of degree `n` with midpoints `m_ijk` and radius `r ≥ 0`
//! stands for the set of polynomials
//! ```text
//! { Σ_{i+j+k=n} c_ijk B_ijk(u, v, w) : |c_ijk − m_ijk| ≤ r for all ijk }
//! ```
//! (Liu et al. 2016, Eq. (1)–(2); storage order as [`TriBezier`]). Every
//! operation returns a ball that contains the exact result of the operation
//! applied to *every* member of its inputs — the same promise as interval
//! coefficients, with one radius per polynomial instead of two endpoints per
//! coefficient (the idea of Arb's balls, at the level of a polynomial).
//!
//! # Why one radius
//! The midpoints are computed in plain `f64` — exactly the floating-point work
//! of a solver without proofs — and the radius grows by an *a priori* bound of
//! that work's rounding, derived once per operation below. Rigor then costs
//! `O(1)` per operation instead of a multiple of every arithmetic operation.
//! The bounds are of the same size as the widths interval arithmetic would
//! carry: the rounding of a de Casteljau step is a few units in the last place
//! of the net's largest value, for every coefficient alike.
//!
//! # Rounding model
//! `u = 2⁻⁵³`. For round-to-nearest, `|fl(x) − x| ≤ u·|fl(x)|` and
//! `≤ u·|x|` when no underflow occurs; an underflowing operation errs by at
//! most `2⁻¹⁰⁷⁵` absolutely. Each bound below is computed in `f64` from
//! non-negative terms and then multiplied by `1 + 32u` and increased by a
//! small absolute term ([`inflate`]), which covers the rounding of the few
//! operations that compute the bound itself and every underflow of the
//! operation (at most `2⁻¹⁰⁷⁵` each, far below the absolute term for the
//! operation counts here).
//!
//! Midpoints that overflow make the ball unbounded (`r = ∞`, or a NaN
//! midpoint): its queries then prove nothing, which is sound. The solver
//! scales its input by a power of two first ([`TriBall::normalized`]), so
//! this only happens for absurd dynamic ranges.

use super::index::{tri_index, tri_len, Bary};
use super::l2;
use super::triangle::TriBezier;
use crate::error::{Error, Result};
use crate::scalar::eft::{two_prod, two_sum, Dd, DdPoint};
use crate::scalar::{iv, MatrixCache, MatrixKey, Scalar, Sign};
use inari::Interval;
use num_rational::BigRational;
use smallvec::SmallVec;
use std::sync::Arc;

/// Coefficients stored inline up to degree 4 (15 values, the preprocessed
/// line of a cubic system included); larger degrees spill to the heap.
pub type Coeffs = SmallVec<[f64; 16]>;

/// The unit roundoff `2⁻⁵³`.
pub const U: f64 = f64::EPSILON / 2.0;

/// `x` increased so that it bounds the exact value of a bound that was
/// computed as `x` by at most 30 roundings of non-negative terms (each a
/// relative `u`), plus underflow: `x·(1 + 32u) + 2⁻¹⁰⁶⁰`.
#[inline]
fn inflate(x: f64) -> f64 {
    x * (1.0 + 32.0 * U) + 1e-319
}

/// `γ_k = k u / (1 − k u)`, Higham's bound for `k` roundings (an upper bound,
/// computed with margin).
#[inline]
fn gamma(k: usize) -> f64 {
    let ku = k as f64 * U;
    ku / (1.0 - ku) * (1.0 + 4.0 * U)
}

/// A triangular BB polynomial with `f64` midpoints and one radius (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TriBall {
    degree: usize,
    mid: Coeffs,
    rad: f64,
    /// A strict sign of the enclosed polynomial proven coefficient by
    /// coefficient when the ball was built from per-coefficient enclosures
    /// ([`TriBall::enclose`]): the one radius, sized for the largest
    /// coefficient, can hide the sign of tiny ones that a per-coefficient
    /// enclosure still proves (a sparse polynomial far from its zeros).
    sign: Option<Sign>,
}

/// The approximant of [`TriBall::reduce`] and its rigorous distance bound.
#[derive(Clone, Debug)]
pub struct Reduced {
    /// The approximant's BB coefficients, degree `k`: any float polynomial
    /// (the L2-best one of the midpoints, rounded).
    pub approx: Coeffs,
    /// `δ` with `|f − approx| ≤ δ` on the whole triangle for every member `f`
    /// of the ball (an upper bound, rigorous).
    pub delta: f64,
}

impl TriBall {
    #[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
    /// The ball with midpoints `mid` (storage order) and radius `rad`. Errors on
    /// the wrong count, a non-finite midpoint or a negative or NaN radius.
    pub fn new(degree: usize, mid: &[f64], rad: f64) -> Result<Self> {
        if mid.len() != tri_len(degree) {
            return Err(Error::Shape(format!(
                "degree {degree} triangle needs {} coefficients, got {}",
                tri_len(degree),
                mid.len()
            )));
        }
        if mid.iter().any(|x| !x.is_finite()) || rad.is_nan() || rad < 0.0 {
            return Err(Error::NonFinite(
                "ball polynomial with a non-finite coefficient or radius".into(),
            ));
        }
        Ok(Self {
            degree,
            mid: mid.iter().copied().collect(),
            rad,
            sign: None,
        })
    }

    /// A ball from parts already checked by the caller.
    fn new_raw(degree: usize, mid: Coeffs, rad: f64) -> Self {
        Self {
            degree,
            mid,
            rad,
            sign: None,
        }
    }

    #[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
    /// The float polynomial `p` itself (radius 0).
    pub fn from_points(p: &TriBezier<f64>) -> Self {
        Self::new_raw(p.degree(), p.coeffs().iter().copied().collect(), 0.0)
    }

    /// The smallest ball around the interval midpoints that contains every
    /// coefficient interval of `p`. Errors on an unbounded coefficient.
    pub fn enclose(p: &TriBezier<Interval>) -> Result<Self> {
        let mut mid = Coeffs::with_capacity(p.coeffs().len());
        let mut rad = 0.0f64;
        for c in p.coeffs() {
            let (lo, hi) = (c.inf(), c.sup());
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(Error::NonFinite(format!("coefficient [{lo:e}, {hi:e}] is not bounded")));
            }
            let m = c.mid();
            if lo != hi {
                // The differences are rounded: `up` makes them upper bounds.
                rad = rad.max(iv::up(hi - m)).max(iv::up(m - lo));
            }
            mid.push(m);
        }
        let coeffs = p.coeffs();
        let sign = if coeffs.iter().all(|c| c.inf() > 0.0) {
            Some(Sign::Positive)
        } else if coeffs.iter().all(|c| c.sup() < 0.0) {
            Some(Sign::Negative)
        } else {
            None
        };
        Ok(Self {
            degree: p.degree(),
            mid,
            rad,
            sign,
        })
    }

    /// The ball around the nearest floats of exact coefficients (storage order,
    /// degree `n`): each is enclosed in its tightest float interval
    /// ([`Scalar::from_rational`]), so exact floats give radius 0.
    pub fn enclose_rationals(n: usize, coeffs: &[BigRational]) -> Self {
        let p = TriBezier::from_fn(n, |i, j, _| Interval::from_rational(&coeffs[tri_index(n, i, j)]));
        // Tight enclosures of finite rationals are bounded unless they overflow.
        Self::enclose(&p).unwrap_or_else(|_| Self::unbounded(n))
    }

    /// The ball that contains every polynomial of degree `n` (radius `∞`).
    pub fn unbounded(n: usize) -> Self {
        Self::new_raw(n, std::iter::repeat_n(0.0, tri_len(n)).collect(), f64::INFINITY)
    }

    /// The total degree `n`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The midpoints in storage order.
    pub fn mid(&self) -> &[f64] {
        &self.mid
    }

    /// The radius.
    pub fn rad(&self) -> f64 {
        self.rad
    }

    /// `max |m_ijk|` (0 for no coefficients; NaN-free midpoints assumed).
    pub fn max_mid(&self) -> f64 {
        max_abs(&self.mid)
    }

    /// An upper bound of every member's largest coefficient magnitude:
    /// `max |m| + r`, rounded up.
    pub fn mag(&self) -> f64 {
        iv::up(self.max_mid() + self.rad)
    }

    /// Rigorous bounds `[lo, hi]` of coefficient `idx` over the ball.
    pub fn bounds(&self, idx: usize) -> (f64, f64) {
        let m = self.mid[idx];
        if self.rad == 0.0 {
            (m, m)
        } else {
            (iv::down(m - self.rad), iv::up(m + self.rad))
        }
    }

    #[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
    /// The coefficients as intervals (for interoperation and tests).
    pub fn to_intervals(&self) -> TriBezier<Interval> {
        TriBezier::from_fn(self.degree, |i, j, _| {
            let (lo, hi) = self.bounds(tri_index(self.degree, i, j));
            crate::scalar::interval(lo, hi)
        })
    }

    /// A strict sign shared by every coefficient of every member (check-sign,
    /// Liu et al. 2016, §2.3.4): every `m > r`, or every `m < −r`. The float
    /// comparisons are exact, so the answer is a proof: the polynomial has
    /// that sign on the whole triangle.
    pub fn strict_sign(&self) -> Option<Sign> {
        if self.sign.is_some() {
            return self.sign;
        }
        let r = self.rad;
        if self.mid.iter().all(|&m| m > r) {
            Some(Sign::Positive)
        } else if self.mid.iter().all(|&m| m < -r) {
            Some(Sign::Negative)
        } else {
            None
        }
    }

    /// The midpoints share a strict sign that the radius hides (some
    /// `|m| ≤ r`): a more precise computation of the same polynomial may
    /// prove it ([`TriBall::strict_sign`] is `None` here).
    pub fn sign_hidden(&self) -> bool {
        self.strict_sign().is_none() && (self.mid.iter().all(|&m| m > 0.0) || self.mid.iter().all(|&m| m < 0.0))
    }

    /// Every coefficient's range contains 0 (`|m| ≤ r` for all, or a NaN):
    /// the sign is lost to rounding on the whole triangle, and no sub-triangle
    /// (whose coefficients are convex combinations) can recover it.
    pub fn sign_lost(&self) -> bool {
        let r = self.rad;
        self.mid
            .iter()
            .all(|&m| m.abs().partial_cmp(&r) != Some(std::cmp::Ordering::Greater))
    }

    /// The same ball scaled by `2^e`: exact for the midpoints unless one
    /// underflows, in which case the radius takes the (subnormal) loss.
    pub fn scaled_pow2(&self, e: i32) -> Self {
        let s = pow2(e);
        let mut lossy = false;
        let mid: Coeffs = self
            .mid
            .iter()
            .map(|&m| {
                let x = m * s;
                lossy |= x * pow2(-e) != m;
                x
            })
            .collect();
        let rad = iv::up(self.rad * s) + if lossy { 2.0 * f64::from_bits(1) } else { 0.0 };
        Self {
            degree: self.degree,
            mid,
            rad,
            // A positive factor keeps every sign.
            sign: self.sign,
        }
    }

    /// The exponent `e` that brings `max(|m| + r)` of `balls` into `[1, 2)`,
    /// so that products with the solver's bounded multipliers cannot overflow
    /// (0 for all-zero balls). Scaling an equation by a positive constant does
    /// not move its roots; one common factor keeps `f − g` (Liu et al.'s
    /// preprocessing, Eq. (7)) the same polynomial up to that factor.
    pub fn normalizing_exponent(balls: &[&TriBall]) -> i32 {
        let m = balls.iter().map(|b| b.mag()).fold(0.0, f64::max);
        if m > 0.0 && m.is_finite() {
            -(m.log2().floor() as i32).clamp(-1000, 1000)
        } else {
            0
        }
    }

    #[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
    /// The polynomial on the sub-triangle with vertices `verts` (`(s, t)` in
    /// this triangle's Cartesian coordinates, barycentric `(s, t, 1 − s − t)`):
    /// coefficient `g_ijk` is the blossom `f[P1^i, P2^j, P3^k]`, computed by
    /// `n` de Casteljau steps per coefficient (as [`TriBezier::subdivide`]).
    ///
    /// # Radius
    /// With `w̃ = fl(fl(1 − s) − t)` per vertex, `e_w = u(|fl(1 − s)| + |w̃|)`
    /// bounds `|w̃ − w|`. A step `x̃ = fl(s·a + fl(t·b + fl(w̃·c)))` (two FMAs
    /// and a product) errs from the exact `s a + t b + w c` by at most
    /// `3u·S·M + e_w·M`, where `M` bounds the magnitudes entering the step and
    /// `S = |s| + |t| + |w̃|`; the exact map of the input radius is at most
    /// `Ŝ·r` with `Ŝ = S + e_w`, and the computed values grow by at most
    /// `S(1 + u)³` per step. Over the `n` steps of a coefficient (vertices of
    /// the three kinds, so `S`, `e_w` are maxima over the vertices):
    /// ```text
    /// r' = Ŝⁿ r + n Ŝⁿ⁻¹ (3u Ŝ + e_w) M₀ (1 + u)³ⁿ,   M₀ = max |m|
    /// ```
    /// For a sub-triangle of the triangle (`S = 1`) this is
    /// `r + n(3u + e_w) M₀`: a few ulps of the largest coefficient per step.
    ///
    /// Vertices outside the triangle extrapolate (`S > 1`); a non-finite
    /// vertex gives the unbounded ball.
    pub fn subdivide(&self, verts: &[[f64; 2]; 3]) -> Self {
        let Some(sub) = Subdivision::new(self.degree, verts) else {
            return Self::unbounded(self.degree);
        };
        let net: SmallVec<[[f64; 1]; 16]> = self.mid.iter().map(|&x| [x]).collect();
        let mut out: SmallVec<[[f64; 1]; 16]> = SmallVec::from_elem([0.0; 1], net.len());
        blossom(&net, self.degree, &sub.bary, &mut out);
        sub.ball(self, out.iter().map(|v| v[0]).collect())
    }

    /// [`TriBall::subdivide`] of two balls of the same degree onto the same
    /// sub-triangle in one pass (each de Casteljau step of the blossom then
    /// works on pairs of values: one loop for both, two-lane arithmetic).
    /// Panics on different degrees (a caller bug).
    pub fn subdivide_pair(f: &TriBall, g: &TriBall, verts: &[[f64; 2]; 3]) -> (TriBall, TriBall) {
        let n = f.degree;
        assert_eq!(n, g.degree, "subdivide_pair needs equal degrees");
        let Some(sub) = Subdivision::new(n, verts) else {
            return (Self::unbounded(n), Self::unbounded(n));
        };
        let net: SmallVec<[[f64; 2]; 16]> = f.mid.iter().zip(&g.mid).map(|(&a, &b)| [a, b]).collect();
        let mut out: SmallVec<[[f64; 2]; 16]> = SmallVec::from_elem([0.0; 2], net.len());
        blossom(&net, n, &sub.bary, &mut out);
        (
            sub.ball(f, out.iter().map(|v| v[0]).collect()),
            sub.ball(g, out.iter().map(|v| v[1]).collect()),
        )
    }

    /// The L2-best approximation of degree `k` (Liu et al. 2016, §2.3.2,
    /// Algorithm 2; projection matrices as [`TriBezier::reduce_l2`]) and a
    /// rigorous `δ`. For `k ≥ n` the approximant is the ball's midpoint
    /// polynomial (elevated to `k`).
    ///
    /// # The bound
    /// With `a` the approximant (any floats), `ẽ = fl(Ẽ a)` its elevation to
    /// degree `n` by the rounded elevation matrix (`|Ẽ − E| ≤ u E`
    /// entrywise, `E ≥ 0` with unit row sums) in `K = tri_len(k)` fused steps:
    /// ```text
    /// |f_i − (E a)_i| ≤ r + |m_i − ẽ_i| + (γ_2K (1 + u) + u) max |a|
    /// ```
    /// and since the Bernstein basis is a non-negative partition of unity,
    /// `|f − a| ≤ max_i |f_i − (E a)_i|` on the triangle.
    pub fn reduce(&self, k: usize) -> Reduced {
        let n = self.degree;
        if k >= n {
            let approx = if k == n {
                self.mid.clone()
            } else {
                let e = elevation_matrix(n, k);
                mat_vec(&e, &self.mid, tri_len(k))
            };
            // Elevation is a convex map: |E f − fl(Ẽ m)| ≤ r + (γ(1+u) + u)·max|m|.
            let err = if k == n {
                0.0
            } else {
                (gamma(2 * tri_len(n)) * (1.0 + U) + U) * self.max_mid()
            };
            let delta = if k == n && self.rad == 0.0 {
                0.0
            } else {
                inflate(self.rad + err)
            };
            return Reduced { approx, delta };
        }
        let (red, elev) = reduction_matrices(n, k);
        let approx = mat_vec(&red, &self.mid, tri_len(k));
        let back = mat_vec(&elev, &approx, tri_len(n));
        let mut dist = 0.0f64;
        for (m, e) in self.mid.iter().zip(&back) {
            dist = dist.max((m - e).abs());
        }
        let slack = (gamma(2 * tri_len(k)) * (1.0 + U) + U) * max_abs(&approx);
        let delta = inflate(dist * (1.0 + 2.0 * U) + self.rad + slack);
        Reduced {
            approx,
            delta: if delta.is_nan() { f64::INFINITY } else { delta },
        }
    }

    /// `a·p + b·q` for float weights `a`, `b` (same degree; panics otherwise,
    /// a caller bug). Each midpoint is `fl(a p_i + fl(b q_i))`, within
    /// `2u(|a|P + |b|Q)` of the exact combination (`P`, `Q` the largest
    /// midpoints).
    pub fn combine(a: f64, p: &TriBall, b: f64, q: &TriBall) -> TriBall {
        assert_eq!(p.degree, q.degree, "combine needs equal degrees");
        let mid: Coeffs = p.mid.iter().zip(&q.mid).map(|(&x, &y)| a.mul_add(x, b * y)).collect();
        let scale = a.abs() * p.max_mid() + b.abs() * q.max_mid();
        let rad = inflate(a.abs() * p.rad + b.abs() * q.rad + 2.0 * U * scale);
        finish(p.degree, mid, rad)
    }

    /// `ℓ·p + μ·q` for linear polynomials `ℓ`, `μ` given by their degree-1
    /// BB coefficients (storage order: at `V3`, `V1`, `V2`), degree `n + 1`
    /// (`p`, `q` of the same degree `n`; panics otherwise).
    ///
    /// # Formula
    /// The product of a linear and a degree-`n` polynomial has
    /// `(ℓ p)_γ = Σ_a (γ_a / (n + 1)) ℓ_a p_{γ − e_a}` (`a` over the three
    /// vertices), so with `h_a = ℓ_a p + μ_a q`:
    /// `(ℓ p + μ q)_γ = (γ_1 h_1[γ−e_1] + γ_2 h_2[γ−e_2] + γ_3 h_3[γ−e_3]) / (n + 1)`.
    ///
    /// # Radius
    /// `max_a (|ℓ_a| r_p + |μ_a| r_q)` for the inputs' radii (the weights are
    /// non-negative with unit sum), plus `2u H` for forming the `h_a` and
    /// `5u H` for the three products, two sums and the division, where
    /// `H = max_a (|ℓ_a| P + |μ_a| Q)(1 + 2u)`.
    pub fn linear_combination(l: [f64; 3], p: &TriBall, m: [f64; 3], q: &TriBall) -> TriBall {
        assert_eq!(p.degree, q.degree, "linear_combination needs equal degrees");
        let n = p.degree;
        let len = tri_len(n);
        // h_a for a = V1, V2, V3 (BB storage order of ℓ: V3, V1, V2).
        let weights = [(l[1], m[1]), (l[2], m[2]), (l[0], m[0])];
        let mut h: SmallVec<[f64; 108]> = SmallVec::with_capacity(3 * len);
        for &(la, ma) in &weights {
            h.extend(p.mid.iter().zip(&q.mid).map(|(&x, &y)| la.mul_add(x, ma * y)));
        }
        let (h1, rest) = h.split_at(len);
        let (h2, h3) = rest.split_at(len);
        let n1 = n + 1;
        let denom = n1 as f64;
        let mut mid = Coeffs::with_capacity(tri_len(n1));
        for j in 0..=n1 {
            for i in 0..=n1 - j {
                let k = n1 - i - j;
                let mut acc = 0.0;
                if i > 0 {
                    acc += i as f64 * h1[tri_index(n, i - 1, j)];
                }
                if j > 0 {
                    acc += j as f64 * h2[tri_index(n, i, j - 1)];
                }
                if k > 0 {
                    acc += k as f64 * h3[tri_index(n, i, j)];
                }
                mid.push(acc / denom);
            }
        }
        let (pm, qm) = (p.max_mid(), q.max_mid());
        let mut carried = 0.0f64;
        let mut size = 0.0f64;
        for &(la, ma) in &weights {
            carried = carried.max(la.abs() * p.rad + ma.abs() * q.rad);
            size = size.max(la.abs() * pm + ma.abs() * qm);
        }
        let rad = inflate(carried + 7.0 * U * size * (1.0 + 2.0 * U));
        finish(n1, mid, rad)
    }

    /// The value, gradient `(f_u, f_v)` and Hessian `(f_uu, f_uv, f_vv)` of the
    /// midpoint polynomial at the barycentric point `b`, in `f64` (no bound:
    /// for choosing multipliers and directions). As [`TriBezier::jet2`].
    pub fn jet2(&self, b: &Bary<f64>) -> (f64, [f64; 2], [f64; 3]) {
        let n = self.degree;
        let mut net: SmallVec<[[f64; 1]; 16]> = self.mid.iter().map(|&x| [x]).collect();
        for m in (3..=n).rev() {
            step(&mut net, m, b);
        }
        let q = |net: &[[f64; 1]], i, j| net[tri_index(2, i, j)][0];
        let hess = if n >= 2 {
            let k = (n * (n - 1)) as f64;
            [
                k * (q(&net, 2, 0) - 2.0 * q(&net, 1, 0) + q(&net, 0, 0)),
                k * (q(&net, 1, 1) - q(&net, 1, 0) - q(&net, 0, 1) + q(&net, 0, 0)),
                k * (q(&net, 0, 2) - 2.0 * q(&net, 0, 1) + q(&net, 0, 0)),
            ]
        } else {
            [0.0; 3]
        };
        if n >= 2 {
            step(&mut net, 2, b);
        }
        let (value, grad) = if n >= 1 {
            let k = n as f64;
            let g = [k * (net[1][0] - net[0][0]), k * (net[2][0] - net[0][0])];
            let [pu, pv, pw] = *b;
            (pu.mul_add(net[1][0], pv.mul_add(net[2][0], pw * net[0][0])), g)
        } else {
            (net[0][0], [0.0; 2])
        };
        (value, grad, hess)
    }
}

/// The vertices of a sub-triangle in barycentric coordinates, with what the
/// radius of [`TriBall::subdivide`] needs.
struct Subdivision {
    degree: usize,
    bary: [[f64; 3]; 3],
    /// `Ŝ = max (|s| + |t| + |w̃|) + e_w`, rounded up.
    s_hat: f64,
    ew_max: f64,
}

impl Subdivision {
    /// `None` for a non-finite vertex.
    fn new(degree: usize, verts: &[[f64; 2]; 3]) -> Option<Self> {
        let mut s_max = 0.0f64;
        let mut ew_max = 0.0f64;
        let bary: [[f64; 3]; 3] = verts.map(|[s, t]| {
            let one_minus_s = 1.0 - s;
            let w = one_minus_s - t;
            s_max = s_max.max(s.abs() + t.abs() + w.abs());
            ew_max = ew_max.max(U * (one_minus_s.abs() + w.abs()));
            [s, t, w]
        });
        (s_max.is_finite() && ew_max.is_finite()).then(|| Self {
            degree,
            bary,
            s_hat: iv::up(s_max + ew_max),
            ew_max,
        })
    }

    /// The ball with the blossoms `mid` of `from`'s midpoints and the radius
    /// of [`TriBall::subdivide`].
    fn ball(&self, from: &TriBall, mid: Coeffs) -> TriBall {
        let n = self.degree;
        let rad = if n == 0 {
            from.rad
        } else {
            let p = self.s_hat.powi(n as i32 - 1);
            let growth = 1.0 + gamma(3 * n);
            inflate(
                p * self.s_hat * from.rad
                    + n as f64 * p * (3.0 * U * self.s_hat + self.ew_max) * from.max_mid() * growth,
            )
        };
        finish(n, mid, rad)
    }
}

/// The values one de Casteljau step combines, `L` nets at once: the blossom
/// ([`blossom`]) is written once for float lanes and for double-double lanes.
trait Lanes: Copy + Default {
    /// A vertex in barycentric coordinates, as the point operation wants it.
    type Point;
    /// `p_u a + p_v b + p_w c`.
    fn combine(p: &Self::Point, a: Self, b: Self, c: Self) -> Self;
}

impl<const L: usize> Lanes for [f64; L]
where
    [f64; L]: Default,
{
    type Point = [f64; 3];
    /// Two FMAs over a product (see [`TriBall::subdivide`] for the bound).
    #[inline(always)]
    fn combine(p: &[f64; 3], a: Self, b: Self, c: Self) -> Self {
        let [pu, pv, pw] = *p;
        let mut y = [0.0; L];
        for l in 0..L {
            y[l] = pu.mul_add(a[l], pv.mul_add(b[l], pw * c[l]));
        }
        y
    }
}

impl<const L: usize> Lanes for [Dd; L]
where
    [Dd; L]: Default,
{
    type Point = DdPoint;
    /// The compensated step of [`TriBallDD::subdivide`].
    #[inline(always)]
    fn combine(p: &DdPoint, a: Self, b: Self, c: Self) -> Self {
        let mut y = [Dd::default(); L];
        for l in 0..L {
            let (a, b, c) = (a[l], b[l], c[l]);
            let (s1, e1) = two_prod(p.s, a.h);
            let (s2, e2) = two_prod(p.t, b.h);
            let (s3, e3) = two_prod(p.wh, c.h);
            let (h1, r1) = two_sum(s1, s2);
            let (h, r2) = two_sum(h1, s3);
            let low = p.s.mul_add(a.l, p.t.mul_add(b.l, p.wh.mul_add(c.l, p.wl * c.h)));
            let low = low + ((r1 + r2) + (e1 + e2 + e3));
            let (yh, yl) = two_sum(h, low);
            y[l] = Dd { h: yh, l: yl };
        }
        y
    }
}

/// A ball from computed midpoints and radius: unbounded if anything overflowed.
fn finish(degree: usize, mid: Coeffs, rad: f64) -> TriBall {
    if rad.is_finite() && mid.iter().all(|m| m.is_finite()) {
        TriBall::new_raw(degree, mid, rad)
    } else {
        TriBall::unbounded(degree)
    }
}

fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |acc, v| acc.max(v.abs()))
}

/// `2^e` for `|e| ≤ 1000`, exactly.
fn pow2(e: i32) -> f64 {
    let e = e.clamp(-1000, 1000);
    if e >= -1022 {
        f64::from_bits(((1023 + e) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

/// One de Casteljau step on `L` float nets at once: each net of degree `m`
/// in `src` becomes the net of degree `m − 1` at `p` in `dst`
/// (`c' = p_u c_{i+1,j} + p_v c_{i,j+1} + p_w c_ij`, evaluated as two FMAs
/// over a product).
#[inline(always)]
fn step_from<N: Lanes>(src: &[N], dst: &mut [N], m: usize, p: &N::Point) {
    let mut out = 0;
    let mut row = 0;
    for j in 0..m {
        let next = row + m + 1 - j;
        for i in 0..m - j {
            dst[out] = N::combine(p, src[row + i + 1], src[next + i], src[row + i]);
            out += 1;
        }
        row = next;
    }
}

/// [`step_from`] in place: writing in storage order never overwrites an
/// entry a later output reads (see `triangle::step_with`).
#[inline(always)]
fn step<N: Lanes>(net: &mut [N], m: usize, p: &N::Point) {
    let mut out = 0;
    let mut row = 0;
    for j in 0..m {
        let next = row + m + 1 - j;
        for i in 0..m - j {
            net[out] = N::combine(p, net[row + i + 1], net[next + i], net[row + i]);
            out += 1;
        }
        row = next;
    }
}

/// The value at `p` of the `L` nets of degree `d` in `src` (a full pyramid:
/// the first step out of place into `scratch`, the rest in place).
#[inline(always)]
fn pyramid<N: Lanes>(src: &[N], scratch: &mut [N], d: usize, p: &N::Point) -> N {
    if d == 0 {
        return src[0];
    }
    step_from(src, scratch, d, p);
    for m in (1..d).rev() {
        step(scratch, m, p);
    }
    scratch[0]
}

/// The blossoms `out[ij] = f[P1^i, P2^j, P3^(n−i−j)]` of `L` float nets
/// `c` (as `triangle::blossom_net`: `i` steps at `P1`, then `j` at `P2`,
/// then the rest at `P3`). Every first step reads its source out of place,
/// so no net is ever copied; scratch lives on the stack for small degrees.
fn blossom<N: Lanes>(c: &[N], n: usize, p: &[N::Point; 3], out: &mut [N]) {
    // A constant degree lets the compiler unroll the short loops of the
    // common low degrees completely.
    match n {
        1 => blossom_n(c, 1, p, out),
        2 => blossom_n(c, 2, p, out),
        3 => blossom_n(c, 3, p, out),
        4 => blossom_n(c, 4, p, out),
        _ => blossom_n(c, n, p, out),
    }
}

#[inline(always)]
fn blossom_n<N: Lanes>(c: &[N], n: usize, p: &[N::Point; 3], out: &mut [N]) {
    let len = tri_len(n);
    let mut buf: SmallVec<[N; 48]> = SmallVec::from_elem(N::default(), 3 * len);
    let (a, rest) = buf.split_at_mut(len);
    let (b, cc) = rest.split_at_mut(len);
    for r in 0..=n {
        // A_r: r steps at P1 (A_0 is the input itself).
        let ar: &[N] = if r == 0 {
            c
        } else {
            if r == 1 {
                step_from(c, a, n, &p[0]);
            } else {
                step(a, n - r + 1, &p[0]);
            }
            a
        };
        let top = n - r;
        for s in 0..=top {
            // B_s: s steps at P2 of A_r (B_0 = A_r).
            if s == 1 {
                step_from(ar, b, top, &p[1]);
            } else if s > 1 {
                step(b, top - s + 1, &p[1]);
            }
            let src: &[N] = if s == 0 { ar } else { b };
            out[tri_index(n, r, s)] = pyramid(src, cc, top - s, &p[2]);
        }
    }
}

/// Row-major `rows × v.len()` matrix times `v`, each row a chain of FMAs.
fn mat_vec(mat: &[f64], v: &[f64], rows: usize) -> Coeffs {
    let cols = v.len();
    mat.chunks_exact(cols.max(1))
        .take(rows)
        .map(|row| row.iter().zip(v).fold(0.0, |acc: f64, (a, x)| a.mul_add(*x, acc)))
        .collect()
}

/// The rounded L2 projection (`n → k`) and elevation (`k → n`) matrices, from
/// the crate's cache of exact matrices converted to `f64` (nearest).
fn reduction_matrices(n: usize, k: usize) -> (Arc<[f64]>, Arc<[f64]>) {
    // The reductions of the clipping methods (k = 1, 2) of moderate degrees
    // are looked up in a small per-thread table indexed by (n, k): no hashing
    // and no reference count traffic on a shared cache line per clip.
    const TOP: usize = 24;
    type Pair = (Arc<[f64]>, Arc<[f64]>);
    thread_local! {
        static TABLE: std::cell::RefCell<Vec<Option<Pair>>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    let build = || {
        (
            f64::cached_matrix(MatrixKey::TriReduce(n, k), || l2::tri_reduction_exact(n, k)),
            elevation_matrix(k, n),
        )
    };
    if n > TOP || k > 2 {
        return build();
    }
    let slot = n * 3 + k;
    TABLE
        .try_with(|t| {
            let mut t = t.borrow_mut();
            if t.len() <= slot {
                t.resize(3 * (TOP + 1), None);
            }
            t[slot].get_or_insert_with(build).clone()
        })
        .unwrap_or_else(|_| build())
}

fn elevation_matrix(from: usize, to: usize) -> Arc<[f64]> {
    f64::cached_matrix(MatrixKey::TriElevate(from, to), || l2::tri_elevation_exact(from, to))
}

mod dd;
#[cfg(test)]
mod tests;

pub use dd::TriBallDD;
