//! Exact Gram, elevation and L2-reduction matrices of Bernstein bases.
//!
//! All matrices are row-major `Vec<BigRational>`, built exactly and cached per
//! kernel by [`Scalar::cached_matrix`](crate::scalar::Scalar::cached_matrix).
//!
//! # Formulas
//! With the normalized measure (area or length 1), for multi-indices `α`
//! (degree `m`) and `β` (degree `n`):
//! ```text
//! triangle:  ∫ B^m_α B^n_β = C(m;α) C(n;β) / C(m+n;α+β) · 2 / ((m+n+1)(m+n+2))
//! interval:  ∫ B^m_i B^n_j = C(m,i) C(n,j) / C(m+n,i+j) · 1 / (m+n+1)
//! ```
//! (`C(n;α)` multinomial). The L2-best approximation of degree `k` has
//! coefficients `a = G_kk⁻¹ G_kn f` — the normal equations of the projection
//! (Lu and Wang 2006, without boundary constraints; Liu et al. 2016 §2.3.2).

use super::index::{tri_indices, tri_len};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// `n choose k` exactly (0 when `k > n`).
pub fn binomial(n: usize, k: usize) -> BigInt {
    if k > n {
        return BigInt::zero();
    }
    let k = k.min(n - k);
    let mut acc = BigInt::one();
    for t in 0..k {
        acc = acc * BigInt::from(n - t) / BigInt::from(t + 1);
    }
    acc
}

/// Pascal's triangle: row `k` holds `C(k, 0..=k)`, for `k ≤ top`.
pub(crate) fn pascal(top: usize) -> Vec<Vec<BigInt>> {
    let mut rows: Vec<Vec<BigInt>> = vec![vec![BigInt::one()]];
    for k in 1..=top {
        let prev = &rows[k - 1];
        let mut row = vec![BigInt::one(); k + 1];
        for i in 1..k {
            row[i] = &prev[i - 1] + &prev[i];
        }
        rows.push(row);
    }
    rows
}

/// The multinomial `n! / (i! j! k!)` with `n = i + j + k`.
pub fn multinomial(i: usize, j: usize, k: usize) -> BigInt {
    binomial(i + j + k, i) * binomial(j + k, j)
}

fn ratio(num: BigInt, den: BigInt) -> BigRational {
    BigRational::new(num, den)
}

/// Normalized Gram matrix `∫_T B^m_α B^n_β / Area(T)`, `tri_len(m) × tri_len(n)`.
pub fn tri_gram(m: usize, n: usize) -> Vec<BigRational> {
    let s = m + n;
    let scale = ratio(BigInt::from(2), BigInt::from((s + 1) * (s + 2)));
    let mut out = Vec::with_capacity(tri_len(m) * tri_len(n));
    for (a0, a1, a2) in tri_indices(m) {
        for (b0, b1, b2) in tri_indices(n) {
            let num = multinomial(a0, a1, a2) * multinomial(b0, b1, b2);
            let den = multinomial(a0 + b0, a1 + b1, a2 + b2);
            out.push(ratio(num, den) * &scale);
        }
    }
    out
}

/// Normalized Gram matrix `∫_0^1 B^m_i B^n_j`, `(m+1) × (n+1)`.
pub fn uni_gram(m: usize, n: usize) -> Vec<BigRational> {
    let scale = ratio(BigInt::one(), BigInt::from(m + n + 1));
    let mut out = Vec::with_capacity((m + 1) * (n + 1));
    for i in 0..=m {
        for j in 0..=n {
            let num = binomial(m, i) * binomial(n, j);
            out.push(ratio(num, binomial(m + n, i + j)) * &scale);
        }
    }
    out
}

/// Triangular elevation matrix from degree `n` to `m ≥ n`:
/// `E[β][α] = C(n;α) C(m−n;β−α) / C(m;β)` for `α ≤ β`.
pub fn tri_elevation_exact(n: usize, m: usize) -> Vec<BigRational> {
    let d = m - n;
    let mut out = Vec::with_capacity(tri_len(m) * tri_len(n));
    for (b0, b1, b2) in tri_indices(m) {
        for (a0, a1, a2) in tri_indices(n) {
            let entry = if a0 <= b0 && a1 <= b1 && a2 <= b2 && (b0 - a0) + (b1 - a1) <= d {
                let num = multinomial(a0, a1, a2) * multinomial(b0 - a0, b1 - a1, b2 - a2);
                ratio(num, multinomial(b0, b1, b2))
            } else {
                BigRational::zero()
            };
            out.push(entry);
        }
    }
    out
}

/// Univariate elevation matrix from degree `n` to `m ≥ n`:
/// `E[j][i] = C(n,i) C(m−n,j−i) / C(m,j)`.
pub fn uni_elevation_exact(n: usize, m: usize) -> Vec<BigRational> {
    let mut out = Vec::with_capacity((m + 1) * (n + 1));
    for j in 0..=m {
        for i in 0..=n {
            let entry = if i <= j && j - i <= m - n {
                ratio(binomial(n, i) * binomial(m - n, j - i), binomial(m, j))
            } else {
                BigRational::zero()
            };
            out.push(entry);
        }
    }
    out
}

/// Weights `C(m;α) C(n;β) / C(m+n;α+β)` of the triangular BB product,
/// `tri_len(m) × tri_len(n)` (the target index is `α + β`).
pub fn tri_product_weights(m: usize, n: usize) -> Vec<BigRational> {
    let mut out = Vec::with_capacity(tri_len(m) * tri_len(n));
    for (a0, a1, a2) in tri_indices(m) {
        for (b0, b1, b2) in tri_indices(n) {
            let num = multinomial(a0, a1, a2) * multinomial(b0, b1, b2);
            out.push(ratio(num, multinomial(a0 + b0, a1 + b1, a2 + b2)));
        }
    }
    out
}

/// The weights of the univariate BB product of degrees `m` and `n`:
/// `C(m, i) C(n, j) / C(m + n, i + j)` at `i·(n + 1) + j`.
pub fn uni_product_weights(m: usize, n: usize) -> Vec<BigRational> {
    let mut out = Vec::with_capacity((m + 1) * (n + 1));
    for i in 0..=m {
        for j in 0..=n {
            out.push(ratio(binomial(m, i) * binomial(n, j), binomial(m + n, i + j)));
        }
    }
    out
}

/// The triangular L2 projection from degree `n` to `k`: `G_kk⁻¹ G_kn`,
/// `tri_len(k) × tri_len(n)`.
pub fn tri_reduction_exact(n: usize, k: usize) -> Vec<BigRational> {
    solve_exact(tri_gram(k, k), tri_gram(k, n), tri_len(k), tri_len(n))
}

/// The univariate L2 projection from degree `n` to `k`: `G_kk⁻¹ G_kn`,
/// `(k+1) × (n+1)`.
pub fn uni_reduction_exact(n: usize, k: usize) -> Vec<BigRational> {
    solve_exact(uni_gram(k, k), uni_gram(k, n), k + 1, n + 1)
}

/// Solves `A X = B` exactly by Gauss–Jordan elimination; `A` is `d × d`
/// (symmetric positive definite here, so pivots never vanish — a zero pivot is
/// still searched past for safety), `B` is `d × c`.
fn solve_exact(mut a: Vec<BigRational>, mut b: Vec<BigRational>, d: usize, c: usize) -> Vec<BigRational> {
    for col in 0..d {
        let piv = (col..d)
            .find(|&r| !a[r * d + col].is_zero())
            .expect("Gram matrices are nonsingular");
        if piv != col {
            for t in 0..d {
                a.swap(piv * d + t, col * d + t);
            }
            for t in 0..c {
                b.swap(piv * c + t, col * c + t);
            }
        }
        let inv = a[col * d + col].recip();
        for t in 0..d {
            a[col * d + t] *= &inv;
        }
        for t in 0..c {
            b[col * c + t] *= &inv;
        }
        for r in 0..d {
            if r == col || a[r * d + col].is_zero() {
                continue;
            }
            let factor = a[r * d + col].clone();
            for t in 0..d {
                let sub = &factor * &a[col * d + t];
                a[r * d + t] -= sub;
            }
            for t in 0..c {
                let sub = &factor * &b[col * c + t];
                b[r * c + t] -= sub;
            }
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gram_rows_sum_to_basis_integrals() {
        // Σ_β ∫ B^m_α B^n_β = ∫ B^m_α = 1 / tri_len(m) (normalized).
        let g = tri_gram(2, 3);
        for r in 0..tri_len(2) {
            let s: BigRational = g[r * tri_len(3)..(r + 1) * tri_len(3)].iter().sum();
            assert_eq!(s, ratio(1.into(), BigInt::from(tri_len(2))));
        }
    }

    #[test]
    fn reduction_of_elevated_is_identity() {
        let red = tri_reduction_exact(4, 2);
        let elev = tri_elevation_exact(2, 4);
        let (k, n) = (tri_len(2), tri_len(4));
        for r in 0..k {
            for c in 0..k {
                let v: BigRational = (0..n).map(|t| &red[r * n + t] * &elev[t * k + c]).sum();
                assert_eq!(
                    v,
                    if r == c {
                        BigRational::one()
                    } else {
                        BigRational::zero()
                    }
                );
            }
        }
    }
}
