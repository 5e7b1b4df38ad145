//! Tensor-product polynomials of bidegree `(m, n)` in Bernstein–Bézier form on
//! a rectangle `[a, b] × [c, d]`.
//!
//! ```text
//! f(u, v) = Σ_{i=0}^{m} Σ_{j=0}^{n} f_ij B^m_i(s) B^n_j(t),   s = (u − a)/(b − a),   t = (v − c)/(d − c)
//! ```
//! Coefficients are stored row-major: `f_ij` at index `i·(n+1) + j`.

use super::index::{tri_index, tri_len};
use super::l2::{self, binomial, multinomial};
use super::triangle::{mat_vec, max_abs_diff, TriBezier};
use super::univariate::{deriv_coeffs, eval_coeffs, split_coeffs, UniBezier};
use crate::error::{Error, Result};
use crate::scalar::{MatrixKey, Scalar, Sign};
use num_rational::BigRational;
use num_traits::Zero;

/// A tensor-product Bernstein–Bézier polynomial of bidegree `(m, n)`.
#[derive(Clone, Debug, PartialEq)]
pub struct TensorBezier<S> {
    m: usize,
    n: usize,
    coeffs: Vec<S>,
    u_domain: [S; 2],
    v_domain: [S; 2],
}

/// The result of [`TensorBezier::reduce_l2`]; see
/// [`TriReduction`](super::TriReduction) for the meaning of the fields.
#[derive(Clone, Debug)]
pub struct TensorReduction<S> {
    /// The approximant of bidegree `(k, l)` on the same rectangle.
    pub approx: TensorBezier<S>,
    /// `max_ij |f_ij − ā_ij|`, a bound on `|f − approx|` over the rectangle.
    pub delta: S,
}

/// Which parameter a split or derivative acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// The first parameter, `u` (index `i`).
    U,
    /// The second parameter, `v` (index `j`).
    V,
}

impl<S: Scalar> TensorBezier<S> {
    /// A polynomial from `(m+1)(n+1)` row-major coefficients on a rectangle.
    /// Errors on a wrong count, a non-finite value or an empty side.
    pub fn new(m: usize, n: usize, coeffs: Vec<S>, u_domain: [S; 2], v_domain: [S; 2]) -> Result<Self> {
        if coeffs.len() != (m + 1) * (n + 1) {
            return Err(Error::Shape(format!(
                "bidegree ({m}, {n}) needs {} coefficients, got {}",
                (m + 1) * (n + 1),
                coeffs.len()
            )));
        }
        let sides = [&u_domain, &v_domain];
        for d in sides {
            UniBezier::new(vec![S::zero()], d.clone())?;
        }
        if let Some(pos) = coeffs.iter().position(|c| !c.is_finite()) {
            let c = &coeffs[pos];
            return Err(Error::NonFinite(format!(
                "coefficient {pos} is not finite (it lies in [{:e}, {:e}]; an input or an intermediate value overflowed)",
                c.lower(),
                c.upper()
            )));
        }
        Ok(Self {
            m,
            n,
            coeffs,
            u_domain,
            v_domain,
        })
    }

    /// A polynomial on the unit square, `(m+1)(n+1)` coefficients row-major
    /// (`c_ij` of `B^m_i(u) B^n_j(v)` at `i·(n+1) + j`).
    ///
    /// ```
    /// use rootclip::TensorBezier;
    /// let f = TensorBezier::on_unit_square(1, 1, vec![0.0, 1.0, 2.0, 3.0])?; // f = 2u + v
    /// assert_eq!(f.eval(0.5, 0.25), 1.25);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn on_unit_square(m: usize, n: usize, coeffs: Vec<S>) -> Result<Self> {
        Self::new(m, n, coeffs, [S::zero(), S::one()], [S::zero(), S::one()])
    }

    /// The bidegree `(m, n)`.
    pub fn degree(&self) -> (usize, usize) {
        (self.m, self.n)
    }

    /// The coefficients, row-major.
    pub fn coeffs(&self) -> &[S] {
        &self.coeffs
    }

    /// Coefficient `f_ij`. Panics if out of range (a caller bug).
    pub fn coeff(&self, i: usize, j: usize) -> &S {
        assert!(
            i <= self.m && j <= self.n,
            "index ({i}, {j}) outside bidegree ({}, {})",
            self.m,
            self.n
        );
        &self.coeffs[i * (self.n + 1) + j]
    }

    /// The rectangle `([a, b], [c, d])`.
    pub fn domain(&self) -> (&[S; 2], &[S; 2]) {
        (&self.u_domain, &self.v_domain)
    }

    /// The same rectangle with every coefficient replaced by `f` of it (for
    /// scaling an equation; [`TensorBezier::map`] converts the domain too).
    pub fn map_coeffs(&self, f: impl Fn(&S) -> S) -> Self {
        TensorBezier {
            coeffs: self.coeffs.iter().map(f).collect(),
            ..self.clone()
        }
    }

    /// The same polynomial in another kernel.
    pub fn map<T: Scalar>(&self, f: impl Fn(&S) -> T) -> TensorBezier<T> {
        TensorBezier {
            m: self.m,
            n: self.n,
            coeffs: self.coeffs.iter().map(&f).collect(),
            u_domain: [f(&self.u_domain[0]), f(&self.u_domain[1])],
            v_domain: [f(&self.v_domain[0]), f(&self.v_domain[1])],
        }
    }

    /// Value at `(u, v)` by de Casteljau in `v` along each row, then in `u`.
    ///
    /// ```
    /// use rootclip::TensorBezier;
    /// // f = u·v on the unit square: coefficients (i/1)(j/1).
    /// let f = TensorBezier::on_unit_square(1, 1, vec![0.0, 0.0, 0.0, 1.0]).unwrap();
    /// assert!((f.eval(0.5, 0.25) - 0.125).abs() < 1e-15);
    /// ```
    pub fn eval(&self, u: S, v: S) -> S {
        // Straight on the coefficient rows: a tensor made by `map` may carry a
        // domain that no longer passes `UniBezier::new` (e.g. collapsed by
        // rounding), and evaluation must not panic on it.
        let local = |x: S, [a, b]: &[S; 2]| (x - a.clone()) / (b.clone() - a.clone());
        let t = local(v, &self.v_domain);
        let column: Vec<S> = self
            .coeffs
            .chunks(self.n + 1)
            .map(|row| eval_coeffs(row, t.clone()))
            .collect();
        eval_coeffs(&column, local(u, &self.u_domain))
    }

    /// The two pieces either side of `at` (a domain coordinate in `direction`).
    /// Errors unless `at` is provably inside the open side.
    pub fn subdivide(&self, direction: Direction, at: S) -> Result<(Self, Self)> {
        let side = match direction {
            Direction::U => &self.u_domain,
            Direction::V => &self.v_domain,
        };
        let probe = UniBezier::new(vec![S::zero()], side.clone())?;
        probe.subdivide(at.clone())?; // validates a < at < b
        let t = probe.local(at.clone());
        let (mut lo, mut hi) = (self.clone(), self.clone());
        let lines = self.lines(direction);
        for (idx, line) in lines.iter().enumerate() {
            let (l, r) = split_coeffs(line, t.clone());
            lo.set_line(direction, idx, l);
            hi.set_line(direction, idx, r);
        }
        match direction {
            Direction::U => {
                lo.u_domain[1] = at.clone();
                hi.u_domain[0] = at;
            }
            Direction::V => {
                lo.v_domain[1] = at.clone();
                hi.v_domain[0] = at;
            }
        }
        Ok((lo, hi))
    }

    /// The coefficient lines along `direction`: for `U`, the `n + 1` columns
    /// (fixed `j`, `i = 0..=m`); for `V`, the `m + 1` rows.
    fn lines(&self, direction: Direction) -> Vec<Vec<S>> {
        match direction {
            Direction::U => (0..=self.n)
                .map(|j| (0..=self.m).map(|i| self.coeff(i, j).clone()).collect())
                .collect(),
            Direction::V => (0..=self.m)
                .map(|i| (0..=self.n).map(|j| self.coeff(i, j).clone()).collect())
                .collect(),
        }
    }

    fn set_line(&mut self, direction: Direction, idx: usize, line: Vec<S>) {
        let n1 = self.n + 1;
        for (t, c) in line.into_iter().enumerate() {
            let pos = match direction {
                Direction::U => t * n1 + idx,
                Direction::V => idx * n1 + t,
            };
            self.coeffs[pos] = c;
        }
    }

    /// Applies a linear map (row-major, `rows × len`) to every line along
    /// `direction`, giving a polynomial of degree `rows − 1` in that direction.
    fn map_lines(&self, direction: Direction, mat: &[S], rows: usize) -> Self {
        let lines: Vec<Vec<S>> = self.lines(direction).iter().map(|l| mat_vec(mat, l, rows)).collect();
        let (m, n) = match direction {
            Direction::U => (rows - 1, self.n),
            Direction::V => (self.m, rows - 1),
        };
        let mut out = Self {
            m,
            n,
            coeffs: vec![S::zero(); (m + 1) * (n + 1)],
            ..self.clone()
        };
        for (idx, line) in lines.into_iter().enumerate() {
            out.set_line(direction, idx, line);
        }
        out
    }

    /// Degree elevation to `(m2, n2) ≥ (m, n)`.
    pub fn elevate(&self, m2: usize, n2: usize) -> Result<Self> {
        if m2 < self.m || n2 < self.n {
            return Err(Error::Shape(format!(
                "cannot elevate ({}, {}) to ({m2}, {n2})",
                self.m, self.n
            )));
        }
        let (m, n) = (self.m, self.n);
        // A direction whose degree stays is left alone (the identity's
        // products would cost O(m²n) for nothing, and in rationals a gcd each).
        let mut out = self.clone();
        if m2 > m {
            let eu = S::cached_matrix(MatrixKey::UniElevate(m, m2), || l2::uni_elevation_exact(m, m2));
            out = out.map_lines(Direction::U, &eu, m2 + 1);
        }
        if n2 > n {
            let ev = S::cached_matrix(MatrixKey::UniElevate(n, n2), || l2::uni_elevation_exact(n, n2));
            out = out.map_lines(Direction::V, &ev, n2 + 1);
        }
        Ok(out)
    }

    /// The product `f·g` of bidegree `(m₁ + m₂, n₁ + n₂)` on `f`'s rectangle
    /// (`g` must live on the same one):
    /// `(fg)_kl = Σ_{i+i'=k, j+j'=l} w^{m₁m₂}_{ii'} w^{n₁n₂}_{jj'} f_ij g_i'j'`,
    /// `w^{mn}_{ii'} = C(m, i) C(n, i') / C(m + n, i + i')`. Exact in
    /// rationals; an enclosure with intervals.
    ///
    /// ```
    /// use rootclip::TensorBezier;
    /// let u = TensorBezier::on_unit_square(1, 0, vec![0.0, 1.0])?; // f = u
    /// let v = TensorBezier::on_unit_square(0, 1, vec![0.0, 1.0])?; // g = v
    /// let uv = u.mul(&v);
    /// assert_eq!(uv.degree(), (1, 1));
    /// assert_eq!(uv.eval(0.5, 0.25), 0.125);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn mul(&self, other: &Self) -> Self {
        let ((m1, n1), (m2, n2)) = (self.degree(), other.degree());
        let (m, n) = (m1 + m2, n1 + n2);
        let wu = S::cached_matrix(MatrixKey::UniProduct(m1, m2), || l2::uni_product_weights(m1, m2));
        let wv = S::cached_matrix(MatrixKey::UniProduct(n1, n2), || l2::uni_product_weights(n1, n2));
        let mut coeffs = vec![S::zero(); (m + 1) * (n + 1)];
        for i in 0..=m1 {
            for j in 0..=n1 {
                let a = &self.coeffs[i * (n1 + 1) + j];
                for i2 in 0..=m2 {
                    let au = wu[i * (m2 + 1) + i2].clone() * a.clone();
                    for j2 in 0..=n2 {
                        let k = (i + i2) * (n + 1) + j + j2;
                        let term =
                            au.clone() * wv[j * (n2 + 1) + j2].clone() * other.coeffs[i2 * (n2 + 1) + j2].clone();
                        coeffs[k] = coeffs[k].clone() + term;
                    }
                }
            }
        }
        Self {
            m,
            n,
            coeffs,
            ..self.clone()
        }
    }

    /// `f + g` on `f`'s rectangle, elevating to the larger bidegree first.
    pub fn add(&self, other: &Self) -> Self {
        let ((m1, n1), (m2, n2)) = (self.degree(), other.degree());
        let (m, n) = (m1.max(m2), n1.max(n2));
        let lift = |p: &Self| {
            if p.degree() == (m, n) {
                p.clone()
            } else {
                p.elevate(m, n).unwrap_or_else(|_| p.clone())
            }
        };
        let (a, b) = (lift(self), lift(other));
        Self {
            coeffs: a
                .coeffs
                .iter()
                .zip(&b.coeffs)
                .map(|(x, y)| x.clone() + y.clone())
                .collect(),
            ..a
        }
    }

    /// `f − g` on `f`'s rectangle, elevating to the larger bidegree first.
    pub fn sub(&self, other: &Self) -> Self {
        self.add(&other.map_coeffs(|c| -c.clone()))
    }

    /// The partial derivative in `direction`, in domain coordinates: bidegree
    /// drops by one in that direction (the zero polynomial if it was 0).
    pub fn deriv(&self, direction: Direction) -> Self {
        let lines = self.lines(direction);
        let side = match direction {
            Direction::U => &self.u_domain,
            Direction::V => &self.v_domain,
        };
        let derived: Vec<Vec<S>> = lines.iter().map(|l| deriv_coeffs(l, side)).collect();
        let len = derived[0].len();
        let (m, n) = match direction {
            Direction::U => (len - 1, self.n),
            Direction::V => (self.m, len - 1),
        };
        let mut out = Self {
            m,
            n,
            coeffs: vec![S::zero(); (m + 1) * (n + 1)],
            ..self.clone()
        };
        for (idx, line) in derived.into_iter().enumerate() {
            out.set_line(direction, idx, line);
        }
        out
    }

    /// The L2-best approximation of bidegree `(k, l)` over the rectangle
    /// (`k < m` or `l < n`; a direction with equal degree is kept) and the
    /// bound `δ`. The L2 projection onto a tensor space is the tensor product of
    /// the univariate projections, so rows and columns are reduced in turn.
    pub fn reduce_l2(&self, k: usize, l: usize) -> Result<TensorReduction<S>> {
        let (m, n) = (self.m, self.n);
        if k > m || l > n || (k == m && l == n) {
            return Err(Error::Shape(format!(
                "L2 reduction of ({m}, {n}) to ({k}, {l}) is not a reduction"
            )));
        }
        let ru = S::cached_matrix(MatrixKey::UniReduce(m, k), || reduction_or_identity(m, k));
        let rv = S::cached_matrix(MatrixKey::UniReduce(n, l), || reduction_or_identity(n, l));
        let mut approx = self
            .map_lines(Direction::U, &ru, k + 1)
            .map_lines(Direction::V, &rv, l + 1);
        approx.coeffs = approx.coeffs.iter().map(S::to_point).collect();
        let delta = max_abs_diff(&self.coeffs, approx.elevate(m, n)?.coeffs());
        Ok(TensorReduction { approx, delta })
    }

    /// Exact conversion into two triangular polynomials of degree `m + n`
    /// covering the rectangle: in local coordinates `(s, t) ∈ [0, 1]²`,
    /// * the first is `{s, t ≥ 0, s + t ≤ 1}` with barycentric `(s, t, 1 − s − t)`;
    /// * the second is `{s + t ≥ 1}` with barycentric `(1 − s, 1 − t, s + t − 1)`
    ///   (the point reflection through the centre, so `V1 = (0, 1)`,
    ///   `V2 = (1, 0)`, `V3 = (1, 1)`).
    ///
    /// Formula: `B^m_i(s) B^n_j(t)` with `1 − s = t + w`, `1 − t = s + w`
    /// expands to `Σ_{a,b} C(m,i)C(n,j)C(m−i,a)C(n−j,b)/C(m+n; i+b, j+a, ·) B^{m+n}_{i+b, j+a}`.
    /// Exact in rationals; an enclosure with intervals. Errors
    /// ([`Error::NonFinite`]) when a float or interval coefficient overflows
    /// (coefficients near the `f64` range).
    pub fn to_triangles(&self) -> Result<[TriBezier<S>; 2]> {
        let (m, n) = (self.m, self.n);
        let mat = S::cached_matrix(MatrixKey::TensorToTri(m, n), || tensor_to_tri_exact(m, n));
        let reflected: Vec<S> = self.coeffs.iter().rev().cloned().collect();
        let first = mat_vec(&mat, &self.coeffs, tri_len(m + n));
        let second = mat_vec(&mat, &reflected, tri_len(m + n));
        Ok([TriBezier::new(m + n, first)?, TriBezier::new(m + n, second)?])
    }

    /// `true` if the (local) point `(s, t)` lies where [`Self::to_triangles`]
    /// puts it in the first triangle (`s + t ≤ 1`).
    pub fn in_first_triangle(s: f64, t: f64) -> bool {
        s + t <= 1.0
    }

    /// Sign summary of the coefficients: `Some(sign)` when every coefficient has
    /// that strict sign (then `f` has it on the whole rectangle).
    pub fn uniform_sign(&self) -> Option<Sign> {
        let first = self.coeffs[0].sign_class();
        let strict = matches!(first, Sign::Positive | Sign::Negative);
        (strict && self.coeffs.iter().all(|c| c.sign_class() == first)).then_some(first)
    }
}

fn reduction_or_identity(n: usize, k: usize) -> Vec<BigRational> {
    if k == n {
        l2::uni_elevation_exact(n, n)
    } else {
        l2::uni_reduction_exact(n, k)
    }
}

/// The exact matrix of [`TensorBezier::to_triangles`], `tri_len(m+n) × (m+1)(n+1)`.
pub fn tensor_to_tri_exact(m: usize, n: usize) -> Vec<BigRational> {
    let big = m + n;
    let cols = (m + 1) * (n + 1);
    let mut out = vec![<BigRational as Zero>::zero(); tri_len(big) * cols];
    for i in 0..=m {
        for j in 0..=n {
            let base = binomial(m, i) * binomial(n, j);
            for a in 0..=m - i {
                for b in 0..=n - j {
                    let (p, q) = (i + b, j + a);
                    let num = &base * binomial(m - i, a) * binomial(n - j, b);
                    let den = multinomial(p, q, big - p - q);
                    out[tri_index(big, p, q) * cols + i * (n + 1) + j] += BigRational::new(num, den);
                }
            }
        }
    }
    out
}
