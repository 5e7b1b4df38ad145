//! Univariate polynomials in Bernstein–Bézier form on an interval `[a, b]`.
//!
//! ```text
//! p(x) = Σ_{i=0}^{n} c_i B^n_i(t),   B^n_i(t) = C(n,i) t^i (1 − t)^{n−i},   t = (x − a)/(b − a)
//! ```

use super::l2;
use super::triangle::{mat_vec, max_abs_diff};
use crate::error::{Error, Result};
use crate::scalar::{MatrixKey, Scalar, Sign};

/// A univariate Bernstein–Bézier polynomial of degree `n` on `[a, b]`.
#[derive(Clone, Debug, PartialEq)]
pub struct UniBezier<S> {
    coeffs: Vec<S>,
    domain: [S; 2],
}

/// The result of [`UniBezier::reduce_l2`]; see
/// [`TriReduction`](super::TriReduction) for the meaning of the fields.
#[derive(Clone, Debug)]
pub struct UniReduction<S> {
    /// The approximant of degree `k` on the same interval.
    pub approx: UniBezier<S>,
    /// `max_i |c_i − ā_i|`, a bound on `|p − approx|` over `[a, b]`.
    pub delta: S,
}

impl<S: Scalar> UniBezier<S> {
    /// A polynomial from its `n + 1` coefficients on `[a, b]`. Errors on no
    /// coefficients, a non-finite value, or `a >= b` (not provably `a < b`).
    pub fn new(coeffs: Vec<S>, domain: [S; 2]) -> Result<Self> {
        if coeffs.is_empty() {
            return Err(Error::Shape(
                "a univariate polynomial needs at least one coefficient".into(),
            ));
        }
        if let Some(pos) = coeffs.iter().chain(domain.iter()).position(|c| !c.is_finite()) {
            return Err(Error::NonFinite(format!(
                "coefficient or domain end {pos} is not finite"
            )));
        }
        if (domain[1].clone() - domain[0].clone()).sign_class() != Sign::Positive {
            return Err(Error::Degenerate(format!(
                "interval [{:?}, {:?}] is empty or a point",
                domain[0], domain[1]
            )));
        }
        Ok(Self { coeffs, domain })
    }

    /// A polynomial on `[0, 1]`.
    ///
    /// ```
    /// use rootclip::UniBezier;
    /// let f = UniBezier::on_unit(vec![1.0, -1.0, 1.0])?; // (1 − x)² − 2x(1 − x) + x²
    /// assert_eq!(f.eval(0.5), 0.0);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn on_unit(coeffs: Vec<S>) -> Result<Self> {
        Self::new(coeffs, [S::zero(), S::one()])
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.coeffs.len() - 1
    }

    /// The coefficients `c_0 … c_n`.
    pub fn coeffs(&self) -> &[S] {
        &self.coeffs
    }

    /// The interval `[a, b]`.
    pub fn domain(&self) -> &[S; 2] {
        &self.domain
    }

    /// The local parameter `t = (x − a)/(b − a)` of a point `x`.
    pub fn local(&self, x: S) -> S {
        let [a, b] = self.domain.clone();
        (x - a.clone()) / (b - a)
    }

    /// Value at `x` (any real; outside `[a, b]` the polynomial extends), by de
    /// Casteljau at `t = (x − a)/(b − a)`.
    ///
    /// ```
    /// use rootclip::UniBezier;
    /// let p = UniBezier::new(vec![1.0, -1.0, 1.0], [2.0, 4.0]).unwrap();
    /// assert_eq!(p.eval(3.0), 0.0); // (1 − 2 + 1)/4 · … at t = 1/2
    /// ```
    pub fn eval(&self, x: S) -> S {
        self.eval_local(self.local(x))
    }

    /// Value at local parameter `t`.
    pub fn eval_local(&self, t: S) -> S {
        eval_coeffs(&self.coeffs, t)
    }

    /// The two pieces on `[a, x]` and `[x, b]`. Errors unless `a < x < b`
    /// provably.
    pub fn subdivide(&self, x: S) -> Result<(Self, Self)> {
        let [a, b] = self.domain.clone();
        let inside = (x.clone() - a.clone()).sign_class() == Sign::Positive
            && (b.clone() - x.clone()).sign_class() == Sign::Positive;
        if !inside {
            return Err(Error::Degenerate(format!(
                "split point {x:?} is not inside ({a:?}, {b:?})"
            )));
        }
        let (left, right) = split_coeffs(&self.coeffs, self.local(x.clone()));
        Ok((
            Self {
                coeffs: left,
                domain: [a, x.clone()],
            },
            Self {
                coeffs: right,
                domain: [x, b],
            },
        ))
    }

    /// Degree elevation to `m ≥ n`: `c'_j = Σ_i C(n,i) C(m−n,j−i)/C(m,j) c_i`.
    pub fn elevate(&self, m: usize) -> Result<Self> {
        let n = self.degree();
        if m < n {
            return Err(Error::Shape(format!("cannot elevate degree {n} to {m}")));
        }
        let mat = S::cached_matrix(MatrixKey::UniElevate(n, m), || l2::uni_elevation_exact(n, m));
        Ok(Self {
            coeffs: mat_vec(&mat, &self.coeffs, m + 1),
            domain: self.domain.clone(),
        })
    }

    /// `dp/dx`, degree `n − 1`: `n (c_{i+1} − c_i) / (b − a)` (the zero constant
    /// for `n = 0`).
    pub fn deriv(&self) -> Self {
        Self {
            coeffs: deriv_coeffs(&self.coeffs, &self.domain),
            domain: self.domain.clone(),
        }
    }

    /// The L2-best approximation of degree `k < n` over `[a, b]` and the bound
    /// `δ`; same contract as [`TriBezier::reduce_l2`](super::TriBezier::reduce_l2).
    pub fn reduce_l2(&self, k: usize) -> Result<UniReduction<S>> {
        let n = self.degree();
        if k >= n {
            return Err(Error::Shape(format!("L2 reduction needs k < n, got k = {k}, n = {n}")));
        }
        let mat = S::cached_matrix(MatrixKey::UniReduce(n, k), || l2::uni_reduction_exact(n, k));
        let coeffs: Vec<S> = mat_vec(&mat, &self.coeffs, k + 1).iter().map(S::to_point).collect();
        let approx = Self {
            coeffs,
            domain: self.domain.clone(),
        };
        let delta = max_abs_diff(&self.coeffs, approx.elevate(n)?.coeffs());
        Ok(UniReduction { approx, delta })
    }
}

/// de Casteljau value of a non-empty coefficient row at local `t`. No domain
/// is involved, so callers holding unvalidated rows (tensor lines after a
/// `map`) cannot trip [`UniBezier::new`]'s checks.
pub(crate) fn eval_coeffs<S: Scalar>(c: &[S], t: S) -> S {
    let mut c = c.to_vec();
    let s = S::one() - t.clone();
    for m in (1..c.len()).rev() {
        for i in 0..m {
            c[i] = s.clone() * c[i].clone() + t.clone() * c[i + 1].clone();
        }
    }
    c.swap_remove(0)
}

/// Coefficients of `dp/dx` for the row `c` on `[a, b]`: `n (c_{i+1} − c_i) / (b − a)`,
/// or the zero constant when `n = 0`.
pub(crate) fn deriv_coeffs<S: Scalar>(c: &[S], domain: &[S; 2]) -> Vec<S> {
    let n = c.len() - 1;
    if n == 0 {
        return vec![S::zero()];
    }
    let [a, b] = domain.clone();
    let scale = S::from_i64(n as i64) / (b - a);
    c.windows(2)
        .map(|w| scale.clone() * (w[1].clone() - w[0].clone()))
        .collect()
}

/// de Casteljau split of a coefficient row at local `t`: the coefficients on
/// `[0, t]` and on `[t, 1]`.
pub(crate) fn split_coeffs<S: Scalar>(c: &[S], t: S) -> (Vec<S>, Vec<S>) {
    let n = c.len() - 1;
    let s = S::one() - t.clone();
    let mut work = c.to_vec();
    let mut left = Vec::with_capacity(n + 1);
    let mut right = vec![S::zero(); n + 1];
    left.push(work[0].clone());
    right[n] = work[n].clone();
    for m in (1..=n).rev() {
        for i in 0..m {
            work[i] = s.clone() * work[i].clone() + t.clone() * work[i + 1].clone();
        }
        left.push(work[0].clone());
        right[m - 1] = work[m - 1].clone();
    }
    (left, right)
}
