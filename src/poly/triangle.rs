//! Bivariate polynomials of total degree `n` in Bernstein–Bézier form on a
//! triangle.
//!
//! # Definition (Liu et al. 2016, Eq. (1)–(2))
//! ```text
//! f(u, v) = Σ_{i+j+k=n} f_ijk B_ijk(u, v, w),   B_ijk = n!/(i! j! k!) u^i v^j w^k,   w = 1 − u − v
//! ```
//! `(u, v, w)` are barycentric coordinates of the polynomial's own triangle: the
//! vertex `u = 1` is `V1`, `v = 1` is `V2`, `w = 1` is `V3`. On the unit
//! triangle `{u, v ≥ 0, u + v ≤ 1}` these are the Cartesian `u`, `v`.
//! Coefficient `f_ij` (k = n − i − j) sits over the abscissa `(i/n, j/n)`.
//!
//! Coefficients are stored `j = 0..=n` outer, `i = 0..=n−j` inner — the order
//! of Eq. (2) and of the CLI's JSON.
//!
//! Where the triangle sits inside a larger domain is not stored here: a
//! sub-triangle is described by its vertices in the parent's barycentric
//! coordinates ([`TriBezier::subdivide`]) and the solver tracks the map.

use super::l2;
use crate::error::{Error, Result};
use crate::scalar::{MatrixKey, Scalar};

/// A triangular Bernstein–Bézier polynomial of total degree `n`.
#[derive(Clone, Debug, PartialEq)]
pub struct TriBezier<S> {
    degree: usize,
    coeffs: Vec<S>,
}

/// Number of coefficients of a triangular polynomial of degree `n`.
pub const fn tri_len(n: usize) -> usize {
    (n + 1) * (n + 2) / 2
}

/// Storage index of `f_ij` (with `k = n − i − j`) in degree `n`.
#[inline]
pub const fn tri_index(n: usize, i: usize, j: usize) -> usize {
    // Rows j = 0, 1, … hold n + 1, n, … coefficients.
    j * (n + 1) - j * (j.saturating_sub(1)) / 2 + i
}

/// Barycentric coordinates `(u, v, w)` of a point with respect to a triangle.
pub type Bary<S> = [S; 3];

/// The multi-indices `(i, j, k)` of degree `n` in storage order.
pub fn tri_indices(n: usize) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..=n).flat_map(move |j| (0..=n - j).map(move |i| (i, j, n - i - j)))
}

/// The result of [`TriBezier::reduce_l2`]: an approximant of lower degree and a
/// bound on the distance to the original.
#[derive(Clone, Debug)]
pub struct TriReduction<S> {
    /// The approximant of degree `k`. With the interval kernel its coefficients
    /// are point intervals (the `f64` midpoints of the L2-best approximant), so
    /// the fat curve it defines is an exact float polynomial.
    pub approx: TriBezier<S>,
    /// `δ = max_i |f_i − ā_i|` with `ā` the approximant elevated to degree
    /// `n`. Then `|f(x) − approx(x)| ≤ δ` on the whole triangle, because the
    /// Bernstein basis is non-negative and sums to one. With the interval
    /// kernel `delta.upper()` is a rigorous upper bound for every polynomial in
    /// the coefficient enclosures.
    pub delta: S,
}

impl<S: Scalar> TriBezier<S> {
    /// A polynomial from its coefficients in storage order (`j` outer, `i`
    /// inner). Errors on the wrong count or a non-finite coefficient.
    pub fn new(degree: usize, coeffs: Vec<S>) -> Result<Self> {
        if coeffs.len() != tri_len(degree) {
            return Err(Error::Shape(format!(
                "degree {degree} triangle needs {} coefficients, got {}",
                tri_len(degree),
                coeffs.len()
            )));
        }
        if let Some(pos) = coeffs.iter().position(|c| !c.is_finite()) {
            return Err(Error::NonFinite(format!("coefficient {pos} is {:?}", coeffs[pos])));
        }
        Ok(Self { degree, coeffs })
    }

    /// A polynomial whose coefficient `f_ijk` is `f(i, j, k)`.
    pub fn from_fn(degree: usize, mut f: impl FnMut(usize, usize, usize) -> S) -> Self {
        let coeffs = tri_indices(degree).map(|(i, j, k)| f(i, j, k)).collect();
        Self { degree, coeffs }
    }

    /// The total degree `n`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// All coefficients in storage order.
    pub fn coeffs(&self) -> &[S] {
        &self.coeffs
    }

    /// Coefficient `f_ij` (`k = n − i − j`). Panics if `i + j > n` (a caller bug,
    /// not user data).
    pub fn coeff(&self, i: usize, j: usize) -> &S {
        assert!(i + j <= self.degree, "index ({i}, {j}) outside degree {}", self.degree);
        &self.coeffs[tri_index(self.degree, i, j)]
    }

    /// The same polynomial in another kernel, coefficient by coefficient.
    pub fn map<T: Scalar>(&self, f: impl Fn(&S) -> T) -> TriBezier<T> {
        TriBezier {
            degree: self.degree,
            coeffs: self.coeffs.iter().map(f).collect(),
        }
    }

    /// Value at barycentric point `b = (u, v, w)` by de Casteljau.
    ///
    /// Rounding: each step is a convex combination when `b` is inside the
    /// triangle, so the f64 kernel is backward stable there; the interval
    /// kernel encloses the exact value for every member of `b`.
    pub fn eval_bary(&self, b: &Bary<S>) -> S {
        let mut net = self.coeffs.clone();
        for m in (1..=self.degree).rev() {
            de_casteljau_step(&mut net, m, b);
        }
        net.swap_remove(0)
    }

    /// Value at `(u, v)` with `w = 1 − u − v` (points outside the triangle are
    /// allowed: the polynomial extends).
    ///
    /// ```
    /// use rootclip::TriBezier;
    /// // f = u on the unit triangle: coefficients i/n.
    /// let f = TriBezier::from_fn(2, |i, _, _| i as f64 / 2.0);
    /// assert!((f.eval(0.3, 0.5) - 0.3).abs() < 1e-15);
    /// ```
    pub fn eval(&self, u: S, v: S) -> S {
        let w = S::one() - u.clone() - v.clone();
        self.eval_bary(&[u, v, w])
    }

    /// The same polynomial on the sub-triangle with vertices `verts[0]`,
    /// `verts[1]`, `verts[2]` (each in this triangle's barycentric
    /// coordinates). The new coefficient `g_ijk` is the blossom
    /// `f[V1^i, V2^j, V3^k]`, computed by repeated de Casteljau steps.
    ///
    /// Exact in the rational kernel; with intervals, an enclosure of the exact
    /// coefficients for every member of the inputs. The vertices may lie
    /// outside the triangle (extrapolation) and the sub-triangle may be
    /// degenerate (then the result is constant along the collapsed direction).
    pub fn subdivide(&self, verts: &[Bary<S>; 3]) -> Self {
        let n = self.degree;
        let mut out = vec![S::zero(); tri_len(n)];
        let mut a = self.coeffs.clone(); // A_r = r steps at V1, degree n − r
        for r in 0..=n {
            if r > 0 {
                de_casteljau_step(&mut a, n - r + 1, &verts[0]);
            }
            let mut b = a.clone(); // B_s = s steps at V2 of A_r
            for s in 0..=n - r {
                if s > 0 {
                    de_casteljau_step(&mut b, n - r - s + 1, &verts[1]);
                }
                let mut c = b.clone();
                for m in (1..=n - r - s).rev() {
                    de_casteljau_step(&mut c, m, &verts[2]);
                }
                out[tri_index(n, r, s)] = c.swap_remove(0);
            }
        }
        Self { degree: n, coeffs: out }
    }

    /// The four sub-triangles of the 1-to-4 midpoint split (Liu et al. 2016,
    /// §2.3.5), in the order: corner at `V1`, corner at `V2`, corner at `V3`,
    /// middle. Their vertices are [`split4_vertices`]; all four keep the
    /// parent's orientation.
    pub fn split4(&self) -> [Self; 4] {
        split4_vertices::<S>().map(|v| self.subdivide(&v))
    }

    /// Degree elevation to `m ≥ n` (the same polynomial, more coefficients):
    /// `f^{n+1}_ijk = (i f_{i−1,j,k} + j f_{i,j−1,k} + k f_{i,j,k−1}) / (n + 1)`.
    /// Errors if `m < n`.
    pub fn elevate(&self, m: usize) -> Result<Self> {
        if m < self.degree {
            return Err(Error::Shape(format!("cannot elevate degree {} to {m}", self.degree)));
        }
        let mut cur = self.clone();
        while cur.degree < m {
            cur = cur.elevate_once();
        }
        Ok(cur)
    }

    fn elevate_once(&self) -> Self {
        let n = self.degree;
        let denom = S::from_i64(n as i64 + 1);
        Self::from_fn(n + 1, |i, j, k| {
            let mut acc = S::zero();
            if i > 0 {
                acc = acc + S::from_i64(i as i64) * self.coeff(i - 1, j).clone();
            }
            if j > 0 {
                acc = acc + S::from_i64(j as i64) * self.coeff(i, j - 1).clone();
            }
            if k > 0 {
                acc = acc + S::from_i64(k as i64) * self.coeff(i, j).clone();
            }
            acc / denom.clone()
        })
    }

    /// `∂f/∂u` (with `v` held fixed, so `w = 1 − u − v` moves), degree `n − 1`:
    /// `n (f_{i+1,j,k} − f_{i,j,k+1})`. The derivative of a constant is the
    /// zero polynomial of degree 0.
    pub fn deriv_u(&self) -> Self {
        self.directional(|s, i, j| s.coeff(i + 1, j).clone())
    }

    /// `∂f/∂v`, degree `n − 1`: `n (f_{i,j+1,k} − f_{i,j,k+1})`.
    pub fn deriv_v(&self) -> Self {
        self.directional(|s, i, j| s.coeff(i, j + 1).clone())
    }

    fn directional(&self, plus: impl Fn(&Self, usize, usize) -> S) -> Self {
        let n = self.degree;
        if n == 0 {
            return Self {
                degree: 0,
                coeffs: vec![S::zero()],
            };
        }
        let scale = S::from_i64(n as i64);
        Self::from_fn(n - 1, |i, j, _| {
            scale.clone() * (plus(self, i, j) - self.coeff(i, j).clone())
        })
    }

    /// The second partials `(f_uu, f_uv, f_vv)`, each of degree `n − 2` (or the
    /// zero constant when `n < 2`).
    pub fn hessian(&self) -> [Self; 3] {
        let fu = self.deriv_u();
        let fv = self.deriv_v();
        [fu.deriv_u(), fu.deriv_v(), fv.deriv_v()]
    }

    /// The L2-best approximation of degree `k < n` over the triangle, and the
    /// bound `δ` (Liu et al. 2016, §2.3.2, Algorithm 2).
    ///
    /// The normalized L2 norm (Eq. (10)) is invariant under affine maps, so the
    /// projection is one matrix per `(n, k)` — `G_kk⁻¹ G_kn` from exact Gram
    /// matrices of the Bernstein bases (see [`l2`](super::l2)) — computed once in
    /// rationals and cached per kernel.
    ///
    /// Exact in the rational kernel (and then `δ = 0` iff `f` has degree ≤ `k`).
    /// With intervals the approximant is rounded to a float polynomial and `δ`
    /// bounds the distance from it rigorously. Errors if `k >= n`.
    pub fn reduce_l2(&self, k: usize) -> Result<TriReduction<S>> {
        let n = self.degree;
        if k >= n {
            return Err(Error::Shape(format!("L2 reduction needs k < n, got k = {k}, n = {n}")));
        }
        let mat = S::cached_matrix(MatrixKey::TriReduce(n, k), || l2::tri_reduction_exact(n, k));
        let approx = Self {
            degree: k,
            coeffs: mat_vec(&mat, &self.coeffs, tri_len(k)),
        };
        let approx = approx.map(S::to_point);
        let delta = max_abs_diff(&self.coeffs, &approx.elevate_cached(n).coeffs);
        Ok(TriReduction { approx, delta })
    }

    /// Elevation to degree `m` through a cached matrix (faster for hot loops
    /// than repeated single steps).
    pub fn elevate_cached(&self, m: usize) -> Self {
        let n = self.degree;
        if m <= n {
            return self.clone();
        }
        let mat = S::cached_matrix(MatrixKey::TriElevate(n, m), || l2::tri_elevation_exact(n, m));
        Self {
            degree: m,
            coeffs: mat_vec(&mat, &self.coeffs, tri_len(m)),
        }
    }

    /// The product `f·g` of degree `m + n`:
    /// `(fg)_γ = Σ_{α+β=γ} C(m;α) C(n;β) / C(m+n;γ) · f_α g_β`.
    /// Exact in rationals; an enclosure with intervals.
    pub fn mul(&self, other: &Self) -> Self {
        let (m, n) = (self.degree, other.degree);
        let w = S::cached_matrix(MatrixKey::TriProduct(m, n), || l2::tri_product_weights(m, n));
        let mut out = vec![S::zero(); tri_len(m + n)];
        let cols = tri_len(n);
        for (a, (a0, a1, _)) in tri_indices(m).enumerate() {
            for (b, (b0, b1, _)) in tri_indices(n).enumerate() {
                let term = w[a * cols + b].clone() * self.coeffs[a].clone() * other.coeffs[b].clone();
                let g = tri_index(m + n, a0 + b0, a1 + b1);
                out[g] = out[g].clone() + term;
            }
        }
        Self {
            degree: m + n,
            coeffs: out,
        }
    }

    /// `f + g`, elevating the lower degree first.
    pub fn add(&self, other: &Self) -> Self {
        let d = self.degree.max(other.degree);
        let (a, b) = (self.elevate_cached(d), other.elevate_cached(d));
        Self {
            degree: d,
            coeffs: a.coeffs.into_iter().zip(b.coeffs).map(|(x, y)| x + y).collect(),
        }
    }

    /// `f − g`, elevating the lower degree first.
    pub fn sub(&self, other: &Self) -> Self {
        self.add(&other.map(|c| -c.clone()))
    }

    /// `true` when every coefficient is exactly zero (an identically zero
    /// polynomial). With intervals: every coefficient is the point `[0, 0]`.
    pub fn is_zero(&self) -> bool {
        self.coeffs.iter().all(|c| c.sign_class() == crate::scalar::Sign::Zero)
    }
}

/// The vertices of the four sub-triangles of the 1-to-4 split, in the order of
/// [`TriBezier::split4`]. `M_ab` is the midpoint of edge `V_a V_b`; the middle
/// triangle is `(M23, M13, M12)`, a half-scale point reflection of the parent
/// (so it keeps the orientation).
pub fn split4_vertices<S: Scalar>() -> [[Bary<S>; 3]; 4] {
    let z = S::zero;
    let o = S::one;
    let h = || S::one() / S::from_i64(2);
    let v1 = [o(), z(), z()];
    let v2 = [z(), o(), z()];
    let v3 = [z(), z(), o()];
    let m12 = [h(), h(), z()];
    let m13 = [h(), z(), h()];
    let m23 = [z(), h(), h()];
    [
        [v1, m12.clone(), m13.clone()],
        [m12.clone(), v2, m23.clone()],
        [m13.clone(), m23.clone(), v3],
        [m23, m13, m12],
    ]
}

/// One de Casteljau step in place: the net of degree `m` (first `tri_len(m)`
/// entries) becomes the net of degree `m − 1` at barycentric point `p`:
/// `c'_ijk = p_u c_{i+1,j,k} + p_v c_{i,j+1,k} + p_w c_{i,j,k+1}`.
pub fn de_casteljau_step<S: Scalar>(net: &mut Vec<S>, m: usize, p: &Bary<S>) {
    debug_assert!(m >= 1 && net.len() >= tri_len(m));
    let mut next = Vec::with_capacity(tri_len(m - 1));
    for j in 0..m {
        for i in 0..m - j {
            let c = p[0].clone() * net[tri_index(m, i + 1, j)].clone()
                + p[1].clone() * net[tri_index(m, i, j + 1)].clone()
                + p[2].clone() * net[tri_index(m, i, j)].clone();
            next.push(c);
        }
    }
    *net = next;
}

/// Row-major matrix (`rows × v.len()`) times vector.
pub(crate) fn mat_vec<S: Scalar>(mat: &[S], v: &[S], rows: usize) -> Vec<S> {
    let cols = v.len();
    debug_assert_eq!(mat.len(), rows * cols);
    (0..rows)
        .map(|r| {
            let row = &mat[r * cols..(r + 1) * cols];
            row.iter()
                .zip(v)
                .fold(S::zero(), |acc, (a, b)| acc + a.clone() * b.clone())
        })
        .collect()
}

/// `max_i |a_i − b_i|` in the kernel's arithmetic (an upper bound for
/// intervals: take `.upper()`).
pub(crate) fn max_abs_diff<S: Scalar>(a: &[S], b: &[S]) -> S {
    a.iter()
        .zip(b)
        .fold(S::zero(), |acc, (x, y)| S::max(acc, (x.clone() - y.clone()).abs()))
}
