//! The small dense linear algebra of the solvers, all proposals in `f64`
//! (or exact rationals), never proofs: 2×2 inverses for Krawczyk's
//! preconditioner `Y ≈ J⁻¹` (any `Y` keeps Krawczyk rigorous; a good one
//! makes it succeed), the combination of two equations closest to
//! vanishing, and Gaussian elimination for the 3×3 systems of the
//! preprocessing multipliers and the least-squares fits.

use crate::scalar::rational_interval::{div_round, q_mul, q_sub, Round};
use num_rational::BigRational;
use num_traits::{Signed, Zero};

type Q = BigRational;

/// The inverse of the 2×2 matrix `m` (row-major) in `f64`; `None` when it is
/// numerically singular: `det = m₀m₃ − m₁m₂` is 0 or not finite, or
/// `|det| < tiny·(|m₀| + |m₁|)(|m₂| + |m₃|)` (`tiny = 0` rejects only those).
pub(crate) fn inverse2(m: [f64; 4], tiny: f64) -> Option<[f64; 4]> {
    let det = m[0] * m[3] - m[1] * m[2];
    let scale = (m[0].abs() + m[1].abs()) * (m[2].abs() + m[3].abs());
    if det == 0.0 || !det.is_finite() || det.abs() < tiny * scale {
        return None;
    }
    Some([m[3] / det, -m[1] / det, -m[2] / det, m[0] / det])
}

/// `Y ≈ J⁻¹`: the exact inverse of the midpoint Jacobian, each entry
/// rounded to nearest with `bits` significant bits (relative to itself, so
/// scaling an equation or a variable scales `Y` exactly and loses nothing;
/// zero entries stay zero). Any `Y` keeps Krawczyk rigorous; a sharp one
/// makes `I − Y J(X)` of the order of the box, so the contraction is
/// quadratic, and on a linear system it is one step. `None` if `J` is
/// singular.
pub(crate) fn inverse2_dyadic(j: &[[Q; 2]; 2], bits: u64) -> Option<[[Q; 2]; 2]> {
    let det = q_sub(&q_mul(&j[0][0], &j[1][1]), &q_mul(&j[0][1], &j[1][0]));
    if det.is_zero() {
        return None;
    }
    let adj = [[j[1][1].clone(), -&j[0][1]], [-&j[1][0], j[0][0].clone()]];
    // An entry x = a/det ≈ 2^e is rounded to a multiple of 2^(e − bits).
    // (Divided only as it is rounded: a reduced quotient costs a gcd.)
    let round = |x: &Q| {
        if x.is_zero() {
            return Q::zero();
        }
        let e = (x.numer().bits() + det.denom().bits()) as i64 - (x.denom().bits() + det.numer().bits()) as i64;
        let shift = (bits as i64 - e).clamp(0, 1 << 20) as u64;
        div_round(x, &det, shift, Round::Nearest)
    };
    Some(adj.map(|r| r.map(|x| round(&x))))
}

/// The left singular vector of the smallest singular value of the 2×2
/// matrix `j` (row-major): the combination of the rows that is closest to
/// vanishing. `None` when it is not finite or zero.
pub(crate) fn smallest_singular_left(j: [f64; 4]) -> Option<[f64; 2]> {
    // J Jᵀ = [[p, q], [q, r]]; eigenvector of its smallest eigenvalue.
    let (p, q, r) = (
        j[0] * j[0] + j[1] * j[1],
        j[0] * j[2] + j[1] * j[3],
        j[2] * j[2] + j[3] * j[3],
    );
    let lam = 0.5 * (p + r) - (0.25 * (p - r) * (p - r) + q * q).sqrt();
    let (v1, v2) = ([q, lam - p], [lam - r, q]);
    let v = if v1[0].abs() + v1[1].abs() >= v2[0].abs() + v2[1].abs() {
        v1
    } else {
        v2
    };
    (v.iter().all(|x| x.is_finite()) && v != [0.0, 0.0]).then_some(v)
}

/// Gaussian elimination with partial pivoting; `None` when a pivot is tiny
/// relative to its row (numerically singular).
pub(crate) fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    gauss(a, b, Pivoting::Scaled(1e-10))
}

/// How [`gauss`] picks pivots and when it gives up.
#[derive(Clone, Copy)]
pub(crate) enum Pivoting {
    /// Largest `|a_ic|` relative to the largest entry of row `i`; singular
    /// when that ratio is below the threshold (or a row is 0 or not finite).
    Scaled(f64),
    /// Largest `|a_ic|`; singular when it is below the threshold.
    Plain(f64),
}

/// Solves `a x = b` by Gaussian elimination with partial pivoting, in `f64`
/// (the multipliers and fits that use it need good values, not proofs);
/// `None` when numerically singular by `pivoting`'s test.
// Row operations read one row while writing another: index loops are clearer.
#[allow(clippy::needless_range_loop)]
pub(crate) fn gauss<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N], pivoting: Pivoting) -> Option<[f64; N]> {
    let (scale, tiny) = match pivoting {
        Pivoting::Scaled(tiny) => {
            let scale = a.map(|r| r.iter().fold(0.0f64, |m, x| m.max(x.abs())));
            if scale.iter().any(|&s| s == 0.0 || !s.is_finite()) {
                return None;
            }
            (scale, tiny)
        }
        Pivoting::Plain(tiny) => ([1.0; N], tiny),
    };
    for col in 0..N {
        let piv = (col..N).max_by(|&i, &j| (a[i][col] / scale[i]).abs().total_cmp(&(a[j][col] / scale[j]).abs()))?;
        if (a[piv][col] / scale[piv]).abs() < tiny {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..N {
            let f = a[r][col] / a[col][col];
            for k in col..N {
                a[r][k] -= f * a[col][k];
            }
            b[r] -= f * b[col];
        }
    }
    let mut x = [0.0; N];
    for r in (0..N).rev() {
        let s: f64 = (r + 1..N).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}
