//! Exact subdivision onto a triangle with `f64` vertices in integer
//! arithmetic: the solver's exact phase recomputes a tri-box's polynomials
//! from the rational input, and doing that with `BigRational` spends nearly
//! all its time in the gcds of normalization.
//!
//! # Method
//! Every float is a dyadic rational, so the nine barycentric coordinates of
//! the three vertices (`w = 1 − s − t` included) share one denominator
//! `2^E`, and the coefficients share one denominator `D` (their lcm). With
//! integer numerators `P = 2^E b` and `C = D c`, each de Casteljau step
//! `c' = b_u c_{i+1,j} + b_v c_{i,j+1} + b_w c_{i,j}` of the blossom
//! ([`TriBezier::subdivide`]) becomes an integer step that scales the net by
//! `2^E`; after the `n` steps of every blossom value the result is
//! `G / (D 2^{nE})` exactly, returned unnormalized (no gcd).

use super::index::{tri_index, tri_len};
use super::triangle::{blossom_net, TriBezier};
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// The polynomial on the sub-triangle with vertices `verts` (`(s, t)` in
/// this triangle's coordinates, finite floats), exactly: the same values as
/// `subdivide` with the vertices' exact barycentric coordinates, as
/// unnormalized rationals. `None` for a non-finite vertex.
pub fn subdivide_dyadic(p: &TriBezier<BigRational>, verts: &[[f64; 2]; 3]) -> Option<Vec<BigRational>> {
    let n = p.degree();
    // Common denominator of the coefficients.
    let mut d = BigInt::one();
    for c in p.coeffs() {
        d = d.lcm(c.denom());
    }
    let coeffs: Vec<BigInt> = p.coeffs().iter().map(|c| c.numer() * (&d / c.denom())).collect();
    // Vertices as integers over 2^E.
    let mut parts: Vec<(BigInt, i64)> = Vec::with_capacity(6);
    for v in verts {
        for &x in v {
            parts.push(dyadic(x)?);
        }
    }
    let e = parts.iter().map(|&(_, k)| k).max().unwrap_or(0).max(0);
    let scale = |(m, k): &(BigInt, i64)| m << (e - k) as usize;
    let one = BigInt::one() << e as usize;
    let bary: Vec<[BigInt; 3]> = (0..3)
        .map(|k| {
            let (s, t) = (scale(&parts[2 * k]), scale(&parts[2 * k + 1]));
            let w = &one - &s - &t;
            [s, t, w]
        })
        .collect();
    let out = blossom_net(coeffs, n, BigInt::zero(), |net, m, k| step(net, m, &bary[k]));
    let den = d << (n as u64 * e as u64) as usize;
    Some(out.into_iter().map(|g| BigRational::new_raw(g, den.clone())).collect())
}

/// `x = m / 2^k` with integer `m` (`k` may be negative).
pub(crate) fn dyadic(x: f64) -> Option<(BigInt, i64)> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some((BigInt::zero(), 0));
    }
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { -1 } else { 1 };
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let (mant, k) = if exp == 0 {
        (frac, 1074)
    } else {
        (frac | (1u64 << 52), 1075 - exp)
    };
    Some((BigInt::from(mant) * sign, k))
}

/// One integer de Casteljau step of the net of degree `m` at `p` (storage
/// order of [`tri_index`]): `c'_ij = p_u c_{i+1,j} + p_v c_{i,j+1} + p_w c_ij`.
fn step(net: &mut Vec<BigInt>, m: usize, p: &[BigInt; 3]) {
    let mut next = Vec::with_capacity(tri_len(m - 1));
    for j in 0..m {
        for i in 0..m - j {
            next.push(
                &p[0] * &net[tri_index(m, i + 1, j)]
                    + &p[1] * &net[tri_index(m, i, j + 1)]
                    + &p[2] * &net[tri_index(m, i, j)],
            );
        }
    }
    *net = next;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_rational_subdivision() {
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        let coeffs = vec![
            q(1, 3),
            q(-2, 7),
            q(5, 11),
            q(1, 2),
            q(-3, 5),
            q(7, 13),
            q(2, 9),
            q(-1, 17),
            q(4, 3),
            q(1, 1),
        ];
        let p = TriBezier::new(3, coeffs).unwrap();
        let verts = [[0.1, 0.2], [0.7, 1e-300], [0.25, 0.5]];
        let exact = |x: f64| BigRational::from_float(x).unwrap();
        let bary = verts.map(|[s, t]| {
            let (s, t) = (exact(s), exact(t));
            let w = BigRational::one() - &s - &t;
            [s, t, w]
        });
        let want = p.subdivide(&bary);
        let got = subdivide_dyadic(&p, &verts).unwrap();
        for (g, w) in got.iter().zip(want.coeffs()) {
            assert_eq!(g, w);
        }
        assert_eq!(dyadic(-0.75), Some((BigInt::from(-3i64 << 51), 53)));
    }
}
