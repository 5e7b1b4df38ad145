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

use super::index::{tri_index, tri_indices, tri_len, Bary};
use super::l2;
use crate::error::{Error, Result};
use crate::scalar::{
    cached_endpoints, endpoint_net, endpoint_of, endpoints_of, from_endpoint, from_endpoints, store_endpoints, Arith,
    Endpoints, MatrixKey, Scalar,
};
use smallvec::SmallVec;

/// A triangular Bernstein–Bézier polynomial of total degree `n`.
#[derive(Clone, Debug, PartialEq)]
pub struct TriBezier<S> {
    degree: usize,
    coeffs: Vec<S>,
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
    /// inner: [`tri_indices`](crate::poly::tri_indices)). Errors on the wrong
    /// count or a non-finite coefficient.
    ///
    /// ```
    /// use rootclip::TriBezier;
    /// // Degree 1: the coefficients at the vertices w = 1, u = 1, v = 1.
    /// let f = TriBezier::new(1, vec![1.0, 3.0, 5.0])?; // f = 1 + 2u + 4v
    /// assert_eq!(f.eval(0.25, 0.5), 3.5);
    /// assert!(TriBezier::new(2, vec![1.0, 2.0]).is_err());
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn new(degree: usize, coeffs: Vec<S>) -> Result<Self> {
        if coeffs.len() != tri_len(degree) {
            return Err(Error::Shape(format!(
                "degree {degree} triangle needs {} coefficients, got {}",
                tri_len(degree),
                coeffs.len()
            )));
        }
        if let Some(pos) = coeffs.iter().position(|c| !c.is_finite()) {
            let c = &coeffs[pos];
            return Err(Error::NonFinite(format!(
                "coefficient {pos} is not finite (it lies in [{:e}, {:e}]; an input or an intermediate value overflowed)",
                c.lower(),
                c.upper()
            )));
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
        // Scratch on the stack for the usual degrees (this is the hot loop of
        // Krawczyk's operator).
        if let Some(p) = bary_endpoints(b) {
            if let Some(mut net) = endpoint_net(&self.coeffs) {
                for m in (1..=self.degree).rev() {
                    step(&mut net, m, &p);
                }
                return from_endpoint(net[0]);
            }
        }
        let mut net: SmallVec<[S; 36]> = self.coeffs.iter().cloned().collect();
        for m in (1..=self.degree).rev() {
            step(&mut net, m, b);
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
        let coeffs = match endpoints_of(&self.coeffs).zip(endpoints_of(verts.as_flattened())) {
            Some((f, v)) => {
                let verts = [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]];
                from_endpoints(&subdivide_net(&f, n, &verts))
            }
            None => subdivide_net(&self.coeffs, n, verts),
        };
        Self { degree: n, coeffs }
    }

    /// The four sub-triangles of the 1-to-4 midpoint split (Liu et al. 2016,
    /// §2.3.5), in the order: corner at `V1`, corner at `V2`, corner at `V3`,
    /// middle (vertices at the edge midpoints); all four keep the
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

    /// The value, the gradient `(f_u, f_v)` and the Hessian
    /// `(f_uu, f_uv, f_vv)` at the barycentric point `b` (`w = 1 − u − v`
    /// moves with `u` and `v`), without forming derivative polynomials:
    /// de Casteljau down to the quadratic net `q` at `b` gives
    /// `f_uu = n(n−1)(q_200 − 2q_101 + q_002)`,
    /// `f_uv = n(n−1)(q_110 − q_101 − q_011 + q_002)`,
    /// `f_vv = n(n−1)(q_020 − 2q_011 + q_002)` (differencing commutes with
    /// the de Casteljau steps); one step more, the linear net `r`, gives
    /// `f_u = n(r_100 − r_001)`, `f_v = n(r_010 − r_001)`. Partials of order
    /// above `n` are zero. Rounding as [`eval_bary`](Self::eval_bary).
    ///
    /// ```
    /// use rootclip::TriBezier;
    /// // f = u² + 3uv on the unit triangle (degree 2).
    /// let f = TriBezier::from_fn(2, |i, j, _| match (i, j) { (2, 0) => 1.0, (1, 1) => 1.5, _ => 0.0 });
    /// let (val, grad, hess) = f.jet2(&[0.25, 0.5, 0.25]);
    /// assert!((val - 0.4375).abs() < 1e-15 && (grad[0] - 2.0).abs() < 1e-15 && (grad[1] - 0.75).abs() < 1e-15);
    /// assert_eq!(hess, [2.0, 3.0, 0.0]);
    /// ```
    pub fn jet2(&self, b: &Bary<S>) -> (S, [S; 2], [S; 3]) {
        let n = self.degree;
        let mut net = self.coeffs.clone();
        for m in (3..=n).rev() {
            de_casteljau_step(&mut net, m, b);
        }
        let at = |net: &[S], m: usize, i: usize, j: usize| net[tri_index(m, i, j)].clone();
        let hess = if n >= 2 {
            let k = S::from_i64((n * (n - 1)) as i64);
            let q = |i, j| at(&net, 2, i, j);
            let two = S::from_i64(2);
            [
                k.clone() * (q(2, 0) - two.clone() * q(1, 0) + q(0, 0)),
                k.clone() * (q(1, 1) - q(1, 0) - q(0, 1) + q(0, 0)),
                k * (q(0, 2) - two * q(0, 1) + q(0, 0)),
            ]
        } else {
            [S::zero(), S::zero(), S::zero()]
        };
        if n >= 2 {
            de_casteljau_step(&mut net, 2, b);
        }
        let grad = if n >= 1 {
            let k = S::from_i64(n as i64);
            let r = |i, j| at(&net, 1, i, j);
            let g = [k.clone() * (r(1, 0) - r(0, 0)), k * (r(0, 1) - r(0, 0))];
            de_casteljau_step(&mut net, 1, b);
            g
        } else {
            [S::zero(), S::zero()]
        };
        (net.swap_remove(0), grad, hess)
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
    /// matrices of the Bernstein bases — computed once in
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
        let (reduce, elevate) = (MatrixKey::TriReduce(n, k), MatrixKey::TriElevate(k, n));
        let build_reduce = || l2::tri_reduction_exact(n, k);
        let build_elevate = || l2::tri_elevation_exact(k, n);
        let (approx, delta) = match endpoints_of(&self.coeffs) {
            Some(f) => {
                let red = cached_endpoints(reduce, build_reduce);
                let elev = cached_endpoints(elevate, build_elevate);
                let (approx, delta) = reduce_net(&f, &red, &elev, k);
                (from_endpoints(&approx), from_endpoints(&[delta]).swap_remove(0))
            }
            None => {
                let red = S::cached_matrix(reduce, build_reduce);
                let elev = S::cached_matrix(elevate, build_elevate);
                reduce_net(&self.coeffs, &red, &elev, k)
            }
        };
        let approx = Self {
            degree: k,
            coeffs: approx,
        };
        Ok(TriReduction { approx, delta })
    }

    /// Elevation to degree `m` through a cached matrix (faster for hot loops
    /// than repeated single steps).
    pub fn elevate_cached(&self, m: usize) -> Self {
        let n = self.degree;
        if m <= n {
            return self.clone();
        }
        let key = MatrixKey::TriElevate(n, m);
        let build = || l2::tri_elevation_exact(n, m);
        let coeffs = match endpoints_of(&self.coeffs) {
            Some(f) => from_endpoints(&mat_vec(&cached_endpoints(key, build), &f, tri_len(m))),
            None => mat_vec(&S::cached_matrix(key, build), &self.coeffs, tri_len(m)),
        };
        Self { degree: m, coeffs }
    }

    /// The product `f·g` of degree `m + n`:
    /// `(fg)_γ = Σ_{α+β=γ} C(m;α) C(n;β) / C(m+n;γ) · f_α g_β`.
    /// Exact in rationals; an enclosure with intervals.
    pub fn mul(&self, other: &Self) -> Self {
        let (m, n) = (self.degree, other.degree);
        let key = MatrixKey::TriProduct(m, n);
        let build = || l2::tri_product_weights(m, n);
        let coeffs = match endpoints_of(&self.coeffs).zip(endpoints_of(&other.coeffs)) {
            Some((f, g)) => from_endpoints(&mul_net(m, n, &cached_endpoints(key, build), &f, &g)),
            None => mul_net(m, n, &S::cached_matrix(key, build), &self.coeffs, &other.coeffs),
        };
        Self { degree: m + n, coeffs }
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
/// Afterwards `net.len() == tri_len(m − 1)`.
pub fn de_casteljau_step<S: Scalar>(net: &mut Vec<S>, m: usize, p: &Bary<S>) {
    debug_assert!(m >= 1 && net.len() >= tri_len(m));
    if let Some((mut e, p)) = endpoints_of(&net[..tri_len(m)]).zip(bary_endpoints(p)) {
        step(&mut e, m, &p);
        e.truncate(tri_len(m - 1));
        net.truncate(e.len());
        store_endpoints(net, &e);
    } else {
        step(net, m, p);
        net.truncate(tri_len(m - 1));
    }
}

// The kernels below are written once over `Arith`: a kernel's own values, or
// bare interval endpoints (`Endpoints`) when the kernel is `Interval` — same
// operations in the same order, same results, without inari's per-operation
// rounding-mode switches (see `crate::scalar`, "Speed of the interval kernel").
// The public methods above pick the representation.

fn bary_endpoints<S: Scalar>(p: &Bary<S>) -> Option<Bary<Endpoints>> {
    Some([endpoint_of(&p[0])?, endpoint_of(&p[1])?, endpoint_of(&p[2])?])
}

/// [`de_casteljau_step`] on any working representation, in place: the first
/// `tri_len(m − 1)` entries become the new net (the rest is stale).
fn step<W: Arith>(net: &mut [W], m: usize, p: &[W; 3]) {
    // Range checks once per step instead of once per operation (products of
    // two vetted values, sums of three products).
    if W::in_fast_range(p, 480) && W::in_fast_range(&net[..tri_len(m)], 480) {
        step_with(net, m, p, W::product_unchecked, W::add_product_unchecked);
    } else {
        step_with(net, m, p, W::product, W::add_product);
    }
}

fn step_with<W: Arith>(
    net: &mut [W],
    m: usize,
    p: &[W; 3],
    product: impl Fn(&W, &W) -> W,
    add_product: impl Fn(W, &W, &W) -> W,
) {
    let [pu, pv, pw] = p;
    // The new coefficient (i, j) goes to tri_index(m − 1, i, j) =
    // tri_index(m, i, j) − j: at or before the three old entries it reads, and
    // before everything later coefficients read. So the old net can be
    // overwritten in storage order, and no allocation is needed.
    let mut out = 0;
    let mut row = 0; // tri_index(m, 0, j)
    for j in 0..m {
        let next_row = row + m + 1 - j; // tri_index(m, 0, j + 1)
        for i in 0..m - j {
            let c = product(pu, &net[row + i + 1]);
            let c = add_product(c, pv, &net[next_row + i]);
            net[out] = add_product(c, pw, &net[row + i]);
            out += 1;
        }
        row = next_row;
    }
}

/// [`TriBezier::subdivide`]: `g_rs = f[V1^r, V2^s, V3^(n−r−s)]`.
fn subdivide_net<W: Arith>(coeffs: &[W], n: usize, verts: &[[W; 3]; 3]) -> Vec<W> {
    blossom_net(coeffs.to_vec(), n, W::zero_value(), |net, m, k| {
        step(net, m, &verts[k]);
        net.truncate(tri_len(m - 1));
    })
}

/// The blossoms `g_rs = f[V1^r, V2^s, V3^(n−r−s)]` of the degree-`n` net
/// `coeffs`, in storage order, given a de Casteljau step `step(net, m, k)`
/// that takes a net of degree `m` one step towards vertex `V(k+1)`: `r` steps
/// at `V1`, then `s` at `V2`, then the rest at `V3`. Written once for every
/// kernel ([`TriBezier::subdivide`], and the integer steps of the exact
/// phase in `poly::dyadic`).
pub(crate) fn blossom_net<T: Clone>(
    coeffs: Vec<T>,
    n: usize,
    zero: T,
    mut step: impl FnMut(&mut Vec<T>, usize, usize),
) -> Vec<T> {
    let mut out = vec![zero; tri_len(n)];
    // Three nets, allocated once: A_r = r steps at V1 (degree n − r),
    // B_s = s steps at V2 of A_r, and the scratch copy of B_s that is
    // evaluated at V3.
    let mut a = coeffs;
    let mut b = Vec::with_capacity(tri_len(n));
    let mut c = Vec::with_capacity(tri_len(n));
    for r in 0..=n {
        if r > 0 {
            step(&mut a, n - r + 1, 0);
        }
        b.clone_from(&a);
        for s in 0..=n - r {
            if s > 0 {
                step(&mut b, n - r - s + 1, 1);
            }
            let g = if s == n - r {
                b[0].clone()
            } else {
                c.clone_from(&b);
                for m in (1..=n - r - s).rev() {
                    step(&mut c, m, 2);
                }
                c[0].clone()
            };
            out[tri_index(n, r, s)] = g;
        }
    }
    out
}

/// [`TriBezier::reduce_l2`]: the approximant (rounded to points) and `δ`.
fn reduce_net<W: Arith>(f: &[W], reduce: &[W], elevate: &[W], k: usize) -> (Vec<W>, W) {
    let approx: Vec<W> = mat_vec(reduce, f, tri_len(k)).iter().map(W::point_of).collect();
    let delta = max_abs_diff(f, &mat_vec(elevate, &approx, f.len()));
    (approx, delta)
}

/// [`TriBezier::mul`] with product weights `w` (`tri_len(m) × tri_len(n)`).
fn mul_net<W: Arith>(m: usize, n: usize, w: &[W], f: &[W], g: &[W]) -> Vec<W> {
    // Each term multiplies three values, hence the narrower range.
    let vetted = |v: &[W]| W::in_fast_range(v, 320);
    if vetted(f) && vetted(g) && vetted(w) {
        mul_net_with((m, n), (w, f, g), W::product_unchecked, W::add_product_unchecked)
    } else {
        mul_net_with((m, n), (w, f, g), W::product, W::add_product)
    }
}

fn mul_net_with<W: Arith>(
    (m, n): (usize, usize),
    (w, f, g): (&[W], &[W], &[W]),
    product: impl Fn(&W, &W) -> W,
    add_product: impl Fn(W, &W, &W) -> W,
) -> Vec<W> {
    let mut out = vec![W::zero_value(); tri_len(m + n)];
    // α runs over f's coefficients and β over g's, both in storage order; each
    // term is (w_αβ · f_α) · g_β, added into (fg)_{α+β}.
    let mut alpha = 0;
    for ja in 0..=m {
        for ia in 0..=m - ja {
            let weights = &w[alpha * g.len()..(alpha + 1) * g.len()];
            let mut beta = 0;
            for jb in 0..=n {
                let target_row = tri_index(m + n, 0, ja + jb) + ia;
                for ib in 0..=n - jb {
                    let wf = product(&weights[beta], &f[alpha]);
                    let t = target_row + ib;
                    out[t] = add_product(out[t].clone(), &wf, &g[beta]);
                    beta += 1;
                }
            }
            alpha += 1;
        }
    }
    out
}

/// Row-major matrix (`rows × v.len()`) times vector; each entry is the sum
/// `0 + m_r0 v_0 + m_r1 v_1 + …` accumulated left to right.
pub(crate) fn mat_vec<W: Arith>(mat: &[W], v: &[W], rows: usize) -> Vec<W> {
    debug_assert_eq!(mat.len(), rows * v.len());
    // Range checks once per call instead of once per operation.
    if W::in_fast_range(v, 480) && W::in_fast_range(mat, 480) {
        mat_vec_with(mat, v, rows, W::add_product_unchecked)
    } else {
        mat_vec_with(mat, v, rows, W::add_product)
    }
}

fn mat_vec_with<W: Arith>(mat: &[W], v: &[W], rows: usize, add_product: impl Fn(W, &W, &W) -> W) -> Vec<W> {
    let cols = v.len();
    let mut out = Vec::with_capacity(rows);
    // Four rows at a time: each row is still summed in order (same result),
    // but four independent sums keep the FPU busy while each one waits for its
    // previous term (a long wait with rigorous rounding).
    let mut blocks = mat.chunks_exact(4 * cols.max(1));
    for block in blocks.by_ref() {
        let (r0, rest) = block.split_at(cols);
        let (r1, rest) = rest.split_at(cols);
        let (r2, r3) = rest.split_at(cols);
        let mut acc = [W::zero_value(), W::zero_value(), W::zero_value(), W::zero_value()];
        for (c, x) in v.iter().enumerate() {
            acc[0] = add_product(acc[0].clone(), &r0[c], x);
            acc[1] = add_product(acc[1].clone(), &r1[c], x);
            acc[2] = add_product(acc[2].clone(), &r2[c], x);
            acc[3] = add_product(acc[3].clone(), &r3[c], x);
        }
        out.extend(acc);
    }
    for row in blocks.remainder().chunks_exact(cols.max(1)) {
        out.push(
            row.iter()
                .zip(v)
                .fold(W::zero_value(), |acc, (a, b)| add_product(acc, a, b)),
        );
    }
    out.resize(rows, W::zero_value()); // cols == 0: every entry is the empty sum
    out
}

/// `max_i |a_i − b_i|` in the kernel's arithmetic (an upper bound for
/// intervals: take `.upper()`).
pub(crate) fn max_abs_diff<W: Arith>(a: &[W], b: &[W]) -> W {
    a.iter()
        .zip(b)
        .fold(W::zero_value(), |acc, (x, y)| W::max_abs_diff_step(acc, x, y))
}

#[cfg(test)]
mod tests {
    //! The hot kernels are tuned (in place, scratch buffers, kernel hooks);
    //! these tests hold them to the straightforward versions, bit for bit.
    use super::*;
    use crate::scalar::point;
    use inari::Interval;
    use num_rational::BigRational;

    fn reference_step<S: Scalar>(net: &mut Vec<S>, m: usize, p: &Bary<S>) {
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

    fn reference_subdivide<S: Scalar>(f: &TriBezier<S>, verts: &[Bary<S>; 3]) -> Vec<S> {
        let n = f.degree();
        let mut out = vec![S::zero(); tri_len(n)];
        let mut a = f.coeffs().to_vec();
        for r in 0..=n {
            if r > 0 {
                reference_step(&mut a, n - r + 1, &verts[0]);
            }
            let mut b = a.clone();
            for s in 0..=n - r {
                if s > 0 {
                    reference_step(&mut b, n - r - s + 1, &verts[1]);
                }
                let mut c = b.clone();
                for m in (1..=n - r - s).rev() {
                    reference_step(&mut c, m, &verts[2]);
                }
                out[tri_index(n, r, s)] = c.swap_remove(0);
            }
        }
        out
    }

    fn reference_mul<S: Scalar>(f: &TriBezier<S>, g: &TriBezier<S>) -> Vec<S> {
        let (m, n) = (f.degree(), g.degree());
        let w = l2::tri_product_weights(m, n);
        let w: Vec<S> = w.iter().map(S::from_rational).collect();
        let mut out = vec![S::zero(); tri_len(m + n)];
        for (a, (a0, a1, _)) in tri_indices(m).enumerate() {
            for (b, (b0, b1, _)) in tri_indices(n).enumerate() {
                let term = w[a * tri_len(n) + b].clone() * f.coeffs()[a].clone() * g.coeffs()[b].clone();
                let t = tri_index(m + n, a0 + b0, a1 + b1);
                out[t] = out[t].clone() + term;
            }
        }
        out
    }

    fn reference_reduce<S: Scalar>(f: &TriBezier<S>, k: usize) -> (Vec<S>, S) {
        let n = f.degree();
        let conv = |m: Vec<BigRational>| m.iter().map(S::from_rational).collect::<Vec<S>>();
        let dot = |mat: &[S], v: &[S], rows: usize| -> Vec<S> {
            (0..rows)
                .map(|r| {
                    let row = &mat[r * v.len()..(r + 1) * v.len()];
                    row.iter()
                        .zip(v)
                        .fold(S::zero(), |acc, (a, b)| acc + a.clone() * b.clone())
                })
                .collect()
        };
        let red = conv(l2::tri_reduction_exact(n, k));
        let approx: Vec<S> = dot(&red, f.coeffs(), tri_len(k)).iter().map(S::to_point).collect();
        let up = dot(&conv(l2::tri_elevation_exact(k, n)), &approx, tri_len(n));
        let delta = f
            .coeffs()
            .iter()
            .zip(&up)
            .fold(S::zero(), |acc, (x, y)| S::max(acc, (x.clone() - y.clone()).abs()));
        (approx, delta)
    }

    /// Bitwise equality: `f64` bits, interval endpoint bits.
    trait Bits {
        fn bits(&self) -> Vec<u64>;
    }
    impl Bits for f64 {
        fn bits(&self) -> Vec<u64> {
            vec![self.to_bits()]
        }
    }
    impl Bits for Interval {
        fn bits(&self) -> Vec<u64> {
            vec![self.inf().to_bits(), self.sup().to_bits()]
        }
    }
    fn bits<S: Bits>(v: &[S]) -> Vec<u64> {
        v.iter().flat_map(Bits::bits).collect()
    }

    fn pseudo_random(n: usize, seed: u64) -> TriBezier<f64> {
        let mut x = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        TriBezier::from_fn(n, |_, _, _| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 3.0
        })
    }

    /// Interior, extrapolating, degenerate and split-4 sub-triangles.
    fn vertex_sets() -> Vec<[Bary<f64>; 3]> {
        let mut v = vec![
            [[0.6, 0.3, 0.1], [0.2, 0.7, 0.1], [0.25, 0.25, 0.5]],
            [[1.3, -0.2, -0.1], [-0.4, 1.1, 0.3], [0.1, 0.1, 0.8]],
            [[0.5, 0.5, 0.0], [0.5, 0.5, 0.0], [0.0, 0.0, 1.0]],
        ];
        v.extend(split4_vertices::<f64>());
        v
    }

    fn widen(x: f64) -> Interval {
        // Half the intervals are points, half have width (the solver's case).
        if x.to_bits() % 2 == 0 {
            point(x)
        } else {
            crate::scalar::interval(x.next_down(), x.next_up().next_up())
        }
    }

    #[test]
    fn subdivide_matches_reference_bitwise() {
        for n in 0..=7 {
            let f = pseudo_random(n, n as u64 + 1);
            let fi = f.map(|&c| widen(c));
            for verts in vertex_sets() {
                assert_eq!(
                    bits(f.subdivide(&verts).coeffs()),
                    bits(&reference_subdivide(&f, &verts))
                );
                let vi = verts.map(|v| v.map(widen));
                assert_eq!(bits(fi.subdivide(&vi).coeffs()), bits(&reference_subdivide(&fi, &vi)));
            }
        }
        let q = |x: f64| BigRational::from_float(x).unwrap();
        let f = pseudo_random(4, 9).map(|&c| q(c));
        let verts = vertex_sets()[1].map(|v| v.map(q));
        assert_eq!(f.subdivide(&verts).coeffs(), &reference_subdivide(&f, &verts)[..]);
    }

    #[test]
    fn step_truncates_like_the_allocating_version() {
        let f = pseudo_random(5, 3);
        let mut net = f.coeffs().to_vec();
        net.extend([7.0, 8.0]); // a longer buffer than tri_len(5)
        let mut net_i: Vec<Interval> = net.iter().map(|&c| widen(c)).collect();
        let (mut reference, mut reference_i) = (net.clone(), net_i.clone());
        let p = [0.2, 0.3, 0.5];
        let p_i = p.map(widen);
        for m in (1..=5).rev() {
            de_casteljau_step(&mut net, m, &p);
            reference_step(&mut reference, m, &p);
            assert_eq!(bits(&net), bits(&reference));
            de_casteljau_step(&mut net_i, m, &p_i);
            reference_step(&mut reference_i, m, &p_i);
            assert_eq!(bits(&net_i), bits(&reference_i));
        }
        assert_eq!((net.len(), net_i.len()), (1, 1));
    }

    #[test]
    fn elevate_and_eval_match_reference_bitwise() {
        for n in 0..=6 {
            let f = pseudo_random(n, 41 + n as u64).map(|&c| widen(c));
            let conv: Vec<Interval> = l2::tri_elevation_exact(n, n + 3)
                .iter()
                .map(Scalar::from_rational)
                .collect();
            let reference: Vec<Interval> = (0..tri_len(n + 3))
                .map(|r| {
                    let row = &conv[r * tri_len(n)..(r + 1) * tri_len(n)];
                    row.iter()
                        .zip(f.coeffs())
                        .fold(Interval::zero(), |acc, (a, b)| acc + *a * *b)
                })
                .collect();
            assert_eq!(bits(f.elevate_cached(n + 3).coeffs()), bits(&reference));
            let p = [0.3, 0.9, -0.2].map(widen);
            let mut net = f.coeffs().to_vec();
            for m in (1..=n).rev() {
                reference_step(&mut net, m, &p);
            }
            assert_eq!(bits(&[f.eval_bary(&p)]), bits(&net));
        }
    }

    #[test]
    fn huge_tiny_and_unbounded_coefficients_fall_back_to_inari() {
        // Outside the range where the error-free transformations are exact,
        // operations go to inari; the results must still match bit for bit.
        // 1e-110 passes the per-step and per-matrix vetting of two-factor
        // products but not that of three-factor ones (`mul`).
        let scales = [1.0e-200, 1.0e-110, 1.0e200, 1.0e305];
        for (t, &scale) in scales.iter().enumerate() {
            let f = pseudo_random(4, 51 + t as u64).map(|&c| widen(c * scale));
            let verts = vertex_sets()[0].map(|v| v.map(widen));
            assert_eq!(
                bits(f.subdivide(&verts).coeffs()),
                bits(&reference_subdivide(&f, &verts))
            );
            let (r, (ra, rd)) = (f.reduce_l2(2).unwrap(), reference_reduce(&f, 2));
            assert_eq!(bits(r.approx.coeffs()), bits(&ra));
            assert_eq!(bits(&[r.delta]), bits(&[rd]));
            assert_eq!(bits(f.mul(&f).coeffs()), bits(&reference_mul(&f, &f)));
        }
        let mut coeffs = pseudo_random(2, 61).map(|&c| widen(c)).coeffs().to_vec();
        coeffs[1] = Interval::ENTIRE;
        let f = TriBezier::from_fn(2, |i, j, _| coeffs[tri_index(2, i, j)]);
        let verts = vertex_sets()[1].map(|v| v.map(widen));
        assert_eq!(
            bits(f.subdivide(&verts).coeffs()),
            bits(&reference_subdivide(&f, &verts))
        );
    }

    #[test]
    fn mul_and_reduce_match_reference_bitwise() {
        for (m, n) in [(0, 2), (1, 1), (2, 3), (3, 3), (4, 2), (5, 4)] {
            let (f, g) = (pseudo_random(m, 11 + m as u64), pseudo_random(n, 21 + n as u64));
            assert_eq!(bits(f.mul(&g).coeffs()), bits(&reference_mul(&f, &g)));
            let (fi, gi) = (f.map(|&c| widen(c)), g.map(|&c| widen(c)));
            assert_eq!(bits(fi.mul(&gi).coeffs()), bits(&reference_mul(&fi, &gi)));
        }
        for n in 2..=7 {
            let f = pseudo_random(n, 31 + n as u64);
            let fi = f.map(|&c| widen(c));
            for k in 1..n.min(4) {
                let (r, ri) = (f.reduce_l2(k).unwrap(), fi.reduce_l2(k).unwrap());
                let (ra, rd) = reference_reduce(&f, k);
                let (ria, rid) = reference_reduce(&fi, k);
                assert_eq!(bits(r.approx.coeffs()), bits(&ra));
                assert_eq!(bits(&[r.delta]), bits(&[rd]));
                assert_eq!(bits(ri.approx.coeffs()), bits(&ria));
                assert_eq!(bits(&[ri.delta]), bits(&[rid]));
            }
        }
    }
}
