//! Exact values of an integer BB polynomial at rational points through its
//! power (monomial) form: homogeneous Horner in big integers, `O(mn)`
//! multiplications (tensor, bidegree `(m, n)`) or `O(n²)` (triangle, degree
//! `n`), where de Casteljau takes `O(mn(m + n))` or `O(n³)`.

use super::Shape;
use crate::poly::tri_index;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// Power-form coefficients `a[i][j]` of `u^i v^j` (integers: the BB
/// coefficients are integers and the basis change has integer entries);
/// row `i` has `n + 1` entries on the square, `n − i + 1` on the triangle.
#[derive(Clone, Debug)]
pub(super) struct PowerForm {
    shape: Shape,
    a: Vec<Vec<BigInt>>,
}

impl PowerForm {
    /// The power form of the BB polynomial `c` (integer coefficients in
    /// `shape`'s storage order); `None` if a coefficient is not an integer.
    ///
    /// `a_ij = ∂_u^i ∂_v^j p(0, 0) / (i! j!)`, and the derivatives at the
    /// corner are forward differences of the coefficients: on the square
    /// `a_ij = C(m,i) C(n,j) Δ_u^i Δ_v^j c_00`, on the triangle
    /// `a_ij = C(n,i) C(n−i,j) Δ_u^i Δ_v^j c_00` (with `c_pq` the
    /// coefficient of `u^p v^q w^(n−p−q)`); the differences in `u` first,
    /// then in `v`: `O(mn(m + n))` or `O(n³)` integer operations.
    #[allow(clippy::needless_range_loop)] // the formula's indices read best
    pub(super) fn new(shape: Shape, c: &[BigRational]) -> Option<Self> {
        let int = |q: &BigRational| q.denom().is_one().then(|| q.numer().clone());
        let (m, n, tri) = match shape {
            Shape::Tensor(m, n) => (m, n, false),
            Shape::Triangle(n) => (n, n, true),
        };
        let top = m.max(n);
        let binom = crate::poly::pascal(top);
        // c_pq, or None outside the triangle.
        let at = |p: usize, q: usize| -> Option<BigInt> {
            if tri {
                (p + q <= n).then(|| int(&c[tri_index(n, p, q)])).flatten()
            } else {
                int(&c[p * (n + 1) + q])
            }
        };
        let cols = |i: usize| if tri { n - i } else { n };
        // d[i][q] = Σ_p (−1)^(i−p) C(i,p) c_pq.
        let mut d: Vec<Vec<BigInt>> = Vec::with_capacity(m + 1);
        for i in 0..=m {
            let mut row = Vec::with_capacity(cols(i) + 1);
            for q in 0..=cols(i) {
                let mut acc = BigInt::zero();
                for p in 0..=i {
                    let t = &binom[i][p] * at(p, q)?;
                    if (i - p) % 2 == 1 {
                        acc -= t;
                    } else {
                        acc += t;
                    }
                }
                row.push(acc);
            }
            d.push(row);
        }
        let mut a: Vec<Vec<BigInt>> = Vec::with_capacity(m + 1);
        for (i, di) in d.iter().enumerate() {
            let mut row = Vec::with_capacity(cols(i) + 1);
            for j in 0..=cols(i) {
                let mut acc = BigInt::zero();
                for (q, dq) in di.iter().enumerate().take(j + 1) {
                    let t = &binom[j][q] * dq;
                    if (j - q) % 2 == 1 {
                        acc -= t;
                    } else {
                        acc += t;
                    }
                }
                let scale = if tri {
                    &binom[n][i] * &binom[n - i][j]
                } else {
                    &binom[m][i] * &binom[n][j]
                };
                row.push(acc * scale);
            }
            a.push(row);
        }
        Some(Self { shape, a })
    }

    /// `b^m d^n · p(a/b, c/d)` (tensor) or `(bd)^n · p(a/b, c/d)` (triangle)
    /// at the point `(a/b, c/d)` with `b, d > 0`: the same integer as
    /// `settle::eval_at`, by homogeneous Horner.
    pub(super) fn eval_at(&self, p: &[BigRational; 2]) -> BigInt {
        let (a, b) = (p[0].numer(), p[0].denom());
        let (c, d) = (p[1].numer(), p[1].denom());
        let powers = |x: &BigInt, k: usize| {
            let mut out = Vec::with_capacity(k + 1);
            out.push(BigInt::one());
            for i in 0..k {
                out.push(&out[i] * x);
            }
            out
        };
        // Σ_j row[j] y^j z^(k−j) for k = row.len() − 1, with zpow = z^0..
        let horner = |row: &[BigInt], y: &BigInt, zpow: &[BigInt]| {
            let k = row.len() - 1;
            let mut h = row[k].clone();
            for j in (0..k).rev() {
                h = h * y + &row[j] * &zpow[k - j];
            }
            h
        };
        match self.shape {
            Shape::Tensor(m, n) => {
                let (bpow, dpow) = (powers(b, m), powers(d, n));
                let mut h = horner(&self.a[m], c, &dpow);
                for i in (0..m).rev() {
                    h = h * a + horner(&self.a[i], c, &dpow) * &bpow[m - i];
                }
                h
            }
            Shape::Triangle(n) => {
                // u = (ad)/(bd), v = (cb)/(bd): Σ a_ij A^i C^j D^(n−i−j).
                let (aa, cc, dd) = (a * d, c * b, b * d);
                let dpow = powers(&dd, n);
                let mut h = horner(&self.a[n], &cc, &dpow);
                for i in (0..n).rev() {
                    h = h * &aa + horner(&self.a[i], &cc, &dpow);
                }
                h
            }
        }
    }
}
