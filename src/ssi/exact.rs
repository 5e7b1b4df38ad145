//! The exact residual of a patch pair: the rational coefficients of
//! `F = w_B·(w x)_A − w_A·(w x)_B` ([`algebra::residual`](super::algebra::residual))
//! whose interval enclosures the solvers work on, for the start-point
//! solves' leaf tests (exact values, so a zero is proven however closely its
//! neighbours or an edge crowd it) and the exact settling of crossings on
//! the boundary.
//!
//! A piece's homogeneous Bézier net is exact when its patch is given by
//! floats (a tensor patch), and computed in rationals otherwise: a
//! B-spline piece by blossoming (`ray::bspline::exact`), a triangle as the
//! tensor patch `(σ, τ) ↦ T(σ(1 − τ), στ)` by the convex combinations of
//! `triangle_as_tensor`, here in exact arithmetic.

use crate::solve::nd::global::{ExactEq, ExactValues};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

type Q = BigRational;

/// A homogeneous control net `(w x, w y, w z, w)` of bidegree `deg`,
/// row-major, with whether the patch is rational (`w` not identically 1).
#[derive(Clone, Debug)]
pub(crate) struct ExactNet {
    pub(crate) deg: (usize, usize),
    pub(crate) hom: Vec<[Q; 4]>,
    pub(crate) rational: bool,
}

/// The exact nets of a patch pair and their residual ([`residual`]).
pub(crate) struct ExactPair<'a> {
    pub(crate) a: &'a ExactNet,
    pub(crate) b: &'a ExactNet,
    pub(crate) residual: [Vec<Q>; 3],
}

/// `C(n, k)` exactly.
fn binom(n: usize, k: usize) -> BigInt {
    (0..k).fold(BigInt::one(), |acc, i| acc * (n - i) / (i + 1))
}

/// The exact tensor net of bidegree `(n, n)` of the triangular net `tri`
/// (degree `n`, control points `j` outer, `i` inner) through
/// `(u, v) = (σ(1 − τ), στ)`: `c_{a,l} = Σ_j b_{a−j, j} C(a, j) C(n − a, l − j) / C(n, l)`.
pub(crate) fn triangle_net(n: usize, tri: &[[Q; 4]], rational: bool) -> ExactNet {
    let index = |i: usize, j: usize| (0..j).map(|r| n + 1 - r).sum::<usize>() + i;
    let mut hom = Vec::with_capacity((n + 1) * (n + 1));
    for a in 0..=n {
        for l in 0..=n {
            let mut c: [Q; 4] = std::array::from_fn(|_| Q::zero());
            for j in l.saturating_sub(n - a)..=a.min(l) {
                let wt = Q::new(binom(a, j) * binom(n - a, l - j), binom(n, l));
                for (x, y) in c.iter_mut().zip(&tri[index(a - j, j)]) {
                    *x += &wt * y;
                }
            }
            hom.push(c);
        }
    }
    ExactNet {
        deg: (n, n),
        hom,
        rational,
    }
}

/// The exact residual of nets `a` (in `(u, v)`) and `b` (in `(s, t)`): three
/// polynomials of degree `(m, n, p, q)`, row-major in `(u, v, s, t)`, the
/// coefficient of `(i, j, k, l)` being `H_A[ij]·W_B[kl] − W_A[ij]·H_B[kl]`
/// (`W ≡ 1` for a polynomial patch: its degree-0 weight raised to the full
/// degree is 1 at every coefficient).
pub(crate) fn residual(a: &ExactNet, b: &ExactNet) -> [Vec<Q>; 3] {
    let one = Q::one();
    let w = |net: &ExactNet, k: usize| {
        if net.rational {
            net.hom[k][3].clone()
        } else {
            one.clone()
        }
    };
    std::array::from_fn(|e| {
        let mut out = Vec::with_capacity(a.hom.len() * b.hom.len());
        for (ia, ha) in a.hom.iter().enumerate() {
            let wa = w(a, ia);
            for (ib, hb) in b.hom.iter().enumerate() {
                out.push(&ha[e] * w(b, ib) - &wa * &hb[e]);
            }
        }
        out
    })
}

/// Value and derivative of the univariate BB polynomial `c` on `[0, 1]` at
/// `t`: de Casteljau stopped one level early leaves `p₀, p₁`; then
/// `p = (1 − t)p₀ + t p₁` and `p' = k(p₁ − p₀)`.
fn uni_jet(c: &[Q], t: &Q) -> (Q, Q) {
    let k = c.len() - 1;
    if k == 0 {
        return (c[0].clone(), Q::zero());
    }
    let s = Q::one() - t;
    let mut w = c.to_vec();
    for r in 1..k {
        for i in 0..=k - r {
            w[i] = &s * &w[i] + t * &w[i + 1];
        }
    }
    (&s * &w[0] + t * &w[1], Q::from_integer(k.into()) * (&w[1] - &w[0]))
}

/// `[H, ∂H/∂u, ∂H/∂v]` of the homogeneous net at `(u, v)`, exactly.
#[allow(clippy::needless_range_loop)] // the coordinate index reads best
fn jet(net: &ExactNet, u: &Q, v: &Q) -> [[Q; 4]; 3] {
    let (m, n) = net.deg;
    let mut out: [[Q; 4]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| Q::zero()));
    for k in 0..4 {
        let (mut vals, mut dvs) = (Vec::with_capacity(m + 1), Vec::with_capacity(m + 1));
        for i in 0..=m {
            let row: Vec<Q> = (0..=n).map(|j| net.hom[i * (n + 1) + j][k].clone()).collect();
            let (p, dp) = uni_jet(&row, v);
            vals.push(p);
            dvs.push(dp);
        }
        let (p, pu) = uni_jet(&vals, u);
        let (pv, _) = uni_jet(&dvs, u);
        out[0][k] = p;
        out[1][k] = pu;
        out[2][k] = pv;
    }
    out
}

/// Exact values of the turning-point system `(F, D)` of
/// [`start`](super::start): `F` the residual (exact coefficients), `D`
/// the determinant [`algebra::turning`](super::algebra::turning) encloses,
/// `det[(V, 0), H_q, ∂₁H_q, ∂₂H_q]` with `V = w_p ∂P − ∂w_p P` the
/// homogeneous partial of patch `p` along `axis`, evaluated from the exact
/// nets at the point (the same function as the enclosed polynomial).
pub(crate) struct TurningExact<'a> {
    pub(crate) residual: &'a [ExactEq],
    pub(crate) deg: [usize; 4],
    pub(crate) a: &'a ExactNet,
    pub(crate) b: &'a ExactNet,
    /// `p` is patch A (else B, with the variables of A first as always).
    pub(crate) on_a: bool,
    pub(crate) axis: usize,
}

impl ExactValues<4> for TurningExact<'_> {
    fn value(&self, e: usize, x: &[f64; 4]) -> Q {
        if e < 3 {
            return self.residual[e].eval(&self.deg, x);
        }
        let q = |c: f64| Q::from_float(c).unwrap_or_else(Q::zero);
        let (ja, jb) = (jet(self.a, &q(x[0]), &q(x[1])), jet(self.b, &q(x[2]), &q(x[3])));
        let (jp, jq) = if self.on_a { (&ja, &jb) } else { (&jb, &ja) };
        let (h, dh) = (&jp[0], &jp[1 + self.axis]);
        let v: [Q; 3] = std::array::from_fn(|k| &h[3] * &dh[k] - &dh[3] * &h[k]);
        // Cofactor expansion along the first column (V, 0).
        let det3 = |r: [usize; 3]| -> Q {
            let m = |i: usize, c: usize| &jq[c][r[i]];
            m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
                + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
        };
        &v[0] * det3([1, 2, 3]) - &v[1] * det3([0, 2, 3]) + &v[2] * det3([0, 1, 3])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(x: f64) -> Q {
        Q::from_float(x).unwrap()
    }

    #[test]
    fn triangle_net_reproduces_the_triangle() {
        // The linear triangle x = u, y = v, z = 1 − u − v as a tensor patch:
        // at (σ, τ) the point (σ(1 − τ), στ, 1 − σ).
        let tri: Vec<[Q; 4]> = [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
            .iter()
            .map(|p| [q(p[0]), q(p[1]), q(p[2]), Q::one()])
            .collect();
        let net = triangle_net(1, &tri, false);
        // Bilinear corners: (σ, τ) = (0, 0), (0, 1), (1, 0), (1, 1).
        let want = [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        for (got, w) in net.hom.iter().zip(want) {
            assert_eq!([got[0].clone(), got[1].clone(), got[2].clone()], w.map(q));
        }
    }

    /// The exact residual lies in the enclosures the solvers work on, for a
    /// polynomial and a rational patch (the same storage order), and the
    /// exact turning value at a point lies in the enclosing polynomial's.
    #[test]
    fn exact_residual_lies_in_the_enclosures() {
        use crate::ray::TensorPatch;
        use crate::ssi::algebra;
        use glam::DVec3;
        let pts_a: Vec<DVec3> = (0..9)
            .map(|k| {
                DVec3::new(
                    0.5 * (k / 3) as f64,
                    0.5 * (k % 3) as f64,
                    0.1 * ((k * 7) % 5) as f64 - 0.2,
                )
            })
            .collect();
        let pts_b: Vec<DVec3> = (0..6)
            .map(|k| DVec3::new(0.3 * (k / 2) as f64 + 0.1, 0.9 * (k % 2) as f64, 0.05 * k as f64))
            .collect();
        let wb = vec![1.0, 0.7, 1.3, 0.9, 1.1, 0.6];
        let a = TensorPatch::new(2, 2, pts_a.clone(), None).unwrap();
        let b = TensorPatch::new(2, 1, pts_b.clone(), Some(wb.clone())).unwrap();
        let hom = |pts: &[DVec3], w: Option<&[f64]>| -> Vec<[Q; 4]> {
            pts.iter()
                .enumerate()
                .map(|(k, p)| crate::ray::settle::exact_hom(*p, w.map(|w| w[k])).unwrap())
                .collect()
        };
        let ea = ExactNet {
            deg: (2, 2),
            hom: hom(&pts_a, None),
            rational: false,
        };
        let eb = ExactNet {
            deg: (2, 1),
            hom: hom(&pts_b, Some(&wb)),
            rational: true,
        };
        let (ha, hb) = (algebra::homogeneous(&a), algebra::homogeneous(&b));
        let f = algebra::residual(&ha, &hb);
        let r = residual(&ea, &eb);
        for e in 0..3 {
            assert_eq!(f[e].deg, vec![2, 2, 2, 1]);
            assert_eq!(f[e].c.len(), r[e].len());
            for (iv, q) in f[e].c.iter().zip(&r[e]) {
                let (lo, hi) = (Q::from_float(iv.lo).unwrap(), Q::from_float(iv.hi).unwrap());
                assert!(&lo <= q && q <= &hi, "{q} not in [{}, {}]", iv.lo, iv.hi);
            }
        }
        let eqs: Vec<ExactEq> = r.iter().map(|c| ExactEq::new(c)).collect();
        for (on_a, axis) in [(true, 0), (true, 1), (false, 0), (false, 1)] {
            let d = if on_a {
                algebra::turning(&ha, &hb, axis)
            } else {
                super::super::start::swap_pairs(&algebra::turning(&hb, &ha, axis))
            };
            let t = TurningExact {
                residual: &eqs,
                deg: [2, 2, 2, 1],
                a: &ea,
                b: &eb,
                on_a,
                axis,
            };
            let x = [0.3, 0.65, 0.2, 0.8];
            let enclosed = crate::solve::nd::tensor::eval_point(&d.c, &d.deg, &x);
            let exact = t.value(3, &x);
            let (lo, hi) = (Q::from_float(enclosed.lo).unwrap(), Q::from_float(enclosed.hi).unwrap());
            assert!(
                lo <= exact && exact <= hi,
                "({on_a}, {axis}): {exact} not in {enclosed:?}"
            );
        }
    }
}
