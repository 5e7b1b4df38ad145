//! The polynomials of a surface/surface intersection, in tensor Bernstein
//! form with interval coefficients: the homogeneous residual
//! `F = w_B·P_A − w_A·P_B` in `(u, v, s, t)` and the turning-point
//! polynomial of one parameter direction.
//!
//! A patch is its homogeneous net `H = (w·x, w·y, w·z, w)`; a polynomial
//! patch has `w = 1`, a polynomial of degree 0, so that its derivatives are
//! the zero polynomial and drop out of sums and products (degrees stay those
//! of the Euclidean formulas). Every operation encloses the exact result for
//! every net within the coefficient enclosures.

use crate::ray::TensorPatch;
use crate::scalar::iv::{down, up, Iv};
use crate::solve::nd::clip::elevate;
use crate::solve::nd::tensor::{derivative, len_of};

/// A tensor Bernstein polynomial on `[0, 1]^k` (`deg.len() = k`), row-major.
#[derive(Clone, Debug)]
pub(crate) struct Poly {
    pub(crate) deg: Vec<usize>,
    pub(crate) c: Vec<Iv>,
}

impl Poly {
    fn zero(vars: usize) -> Self {
        Self {
            deg: vec![0; vars],
            c: vec![Iv::point(0.0)],
        }
    }

    /// Every coefficient is exactly 0.
    pub(crate) fn is_zero(&self) -> bool {
        self.c.iter().all(|x| x.lo == 0.0 && x.hi == 0.0)
    }

    /// `∂p/∂x_axis` (zero when the degree there is 0).
    pub(crate) fn d(&self, axis: usize) -> Self {
        if self.deg[axis] == 0 {
            return Self::zero(self.deg.len());
        }
        let (deg, c) = derivative(&self.c, &self.deg, axis);
        Self { deg, c }
    }

    fn lifted(&self, to: &[usize]) -> Vec<Iv> {
        if self.deg == to {
            self.c.clone()
        } else {
            elevate(&self.c, &self.deg, to)
        }
    }

    /// `self + other` (`negate`: `self − other`), both raised to common
    /// degrees.
    fn combine(&self, other: &Self, negate: bool) -> Self {
        let op = |x: Iv, y: Iv| if negate { x.sub(y) } else { x.add(y) };
        if other.is_zero() {
            return self.clone();
        }
        if self.is_zero() {
            return Self {
                deg: other.deg.clone(),
                c: other.c.iter().map(|y| op(Iv::point(0.0), *y)).collect(),
            };
        }
        let deg: Vec<usize> = self.deg.iter().zip(&other.deg).map(|(a, b)| *a.max(b)).collect();
        let (a, b) = (self.lifted(&deg), other.lifted(&deg));
        let c = a.iter().zip(&b).map(|(x, y)| op(*x, *y)).collect();
        Self { deg, c }
    }

    pub(crate) fn add(&self, other: &Self) -> Self {
        self.combine(other, false)
    }

    pub(crate) fn sub(&self, other: &Self) -> Self {
        self.combine(other, true)
    }

    /// The product, of degree `deg_a + deg_b`:
    /// `c_k = Σ_{i+j=k} a_i b_j Π_d C(m_d, i_d) C(n_d, j_d) / C(m_d + n_d, k_d)`.
    pub(crate) fn mul(&self, other: &Self) -> Self {
        let vars = self.deg.len();
        if self.is_zero() || other.is_zero() {
            return Self::zero(vars);
        }
        let deg: Vec<usize> = self.deg.iter().zip(&other.deg).map(|(a, b)| a + b).collect();
        let scaled = |p: &Self| -> Vec<(Vec<usize>, Iv)> {
            (0..p.c.len())
                .map(|k| {
                    let i = unflatten(k, &p.deg);
                    let w = (0..vars).fold(Iv::point(1.0), |w, d| w.mul(int(binom(p.deg[d], i[d]))));
                    let x = p.c[k].mul(w);
                    (i, x)
                })
                .collect()
        };
        let (a, b) = (scaled(self), scaled(other));
        let mut c = vec![Iv::point(0.0); len_of(&deg)];
        for (i, x) in &a {
            for (j, y) in &b {
                let k: Vec<usize> = i.iter().zip(j).map(|(p, q)| p + q).collect();
                let slot = &mut c[flatten(&k, &deg)];
                *slot = slot.add(x.mul(*y));
            }
        }
        for (k, x) in c.iter_mut().enumerate() {
            let idx = unflatten(k, &deg);
            let w = (0..vars).fold(Iv::point(1.0), |w, d| w.mul(int(binom(deg[d], idx[d]))));
            *x = x.div(w);
        }
        Self { deg, c }
    }

    /// The product `p(x)·q(y)` in the variables `(x, y)`: coefficients
    /// `a_i b_j` (the tensor basis is the product of the bases).
    pub(crate) fn outer(&self, other: &Self) -> Self {
        let mut deg = self.deg.clone();
        deg.extend_from_slice(&other.deg);
        if self.is_zero() || other.is_zero() {
            return Self::zero(deg.len());
        }
        let mut c = Vec::with_capacity(self.c.len() * other.c.len());
        for x in &self.c {
            for y in &other.c {
                c.push(x.mul(*y));
            }
        }
        Self { deg, c }
    }
}

fn unflatten(mut k: usize, deg: &[usize]) -> Vec<usize> {
    let mut out = vec![0; deg.len()];
    for d in (0..deg.len()).rev() {
        out[d] = k % (deg[d] + 1);
        k /= deg[d] + 1;
    }
    out
}

fn flatten(i: &[usize], deg: &[usize]) -> usize {
    i.iter().zip(deg).fold(0, |a, (&k, &n)| a * (n + 1) + k)
}

/// `C(n, k)` (`n ≤ 120` here; exact below `2¹²⁸`).
fn binom(n: usize, k: usize) -> u128 {
    let mut r: u128 = 1;
    for i in 0..k {
        r = r * (n - i) as u128 / (i + 1) as u128;
    }
    r
}

/// An enclosure of an integer.
fn int(x: u128) -> Iv {
    let f = x as f64;
    if x < (1u128 << 53) {
        Iv::point(f)
    } else {
        Iv::new(down(f), up(f))
    }
}

/// The homogeneous coordinate polynomials `(w·x, w·y, w·z, w)` of a patch
/// in its `(u, v)`; `w` of degree 0 for a polynomial patch.
pub(crate) fn homogeneous(p: &TensorPatch) -> [Poly; 4] {
    let (m, n) = p.degree();
    let net = p.ivnet();
    std::array::from_fn(|k| {
        if k == 3 && p.weights().is_none() {
            return Poly {
                deg: vec![0, 0],
                c: vec![Iv::point(1.0)],
            };
        }
        Poly {
            deg: vec![m, n],
            c: net.iter().map(|r| r[k]).collect(),
        }
    })
}

/// The residual `F_k = w_B(s, t)·(w x)_A(u, v) − w_A(u, v)·(w x)_B(s, t)`,
/// `k = x, y, z`, in `(u, v, s, t)`: on `[0, 1]⁴` its zeros are exactly the
/// pairs of parameters where the patches meet (`F = w_A w_B (A − B)` and
/// weights are positive).
pub(crate) fn residual(a: &[Poly; 4], b: &[Poly; 4]) -> [Poly; 3] {
    std::array::from_fn(|k| a[k].outer(&b[3]).sub(&a[3].outer(&b[k])))
}

/// The 3×3 determinant of polynomials (rows `r`, columns `c`).
fn det3(m: [[&Poly; 3]; 3]) -> Poly {
    let minor = |r1: usize, r2: usize, c1: usize, c2: usize| m[r1][c1].mul(m[r2][c2]).sub(&m[r1][c2].mul(m[r2][c1]));
    let t0 = m[0][0].mul(&minor(1, 2, 1, 2));
    let t1 = m[0][1].mul(&minor(1, 2, 0, 2));
    let t2 = m[0][2].mul(&minor(1, 2, 0, 1));
    t0.sub(&t1).add(&t2)
}

/// The turning-point polynomial of the direction `axis` of patch `p` (0: its
/// first parameter, 1: its second) against patch `q`:
/// `det[(V, 0), H_q, ∂₁H_q, ∂₂H_q]` with `V = w ∂P − ∂w P` the homogeneous
/// form of `p`'s partial derivative. It equals `w_p² w_q³` times
/// `det(∂p/∂axis, ∂q/∂s, ∂q/∂t)`, the 3×3 minor of the Jacobian of
/// `p − q` without the other parameter of `p`; so on the intersection curve
/// it vanishes exactly where the curve's tangent has no component along the
/// other parameter of `p`, or the curve is singular. Variables `(p's, q's)`.
pub(crate) fn turning(p: &[Poly; 4], q: &[Poly; 4], axis: usize) -> Poly {
    let v: Vec<Poly> = (0..3)
        .map(|k| p[3].mul(&p[k].d(axis)).sub(&p[3].d(axis).mul(&p[k])))
        .collect();
    let hs: Vec<Poly> = q.iter().map(|h| h.d(0)).collect();
    let ht: Vec<Poly> = q.iter().map(|h| h.d(1)).collect();
    let mut total: Option<Poly> = None;
    for (a, va) in v.iter().enumerate() {
        let rows: Vec<usize> = (0..4).filter(|&r| r != a).collect();
        let m = [0, 1, 2].map(|i| [&q[rows[i]], &hs[rows[i]], &ht[rows[i]]]);
        let term = va.outer(&det3(m));
        total = Some(match total {
            None => term,
            Some(t) if a == 1 => t.sub(&term),
            Some(t) => t.add(&term),
        });
    }
    total.unwrap_or_else(|| Poly::zero(4))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn product_of_linear_forms() {
        // (x)(1 − x) on degree 1 each: x(1 − x) has coefficients 0, 1/2, 0.
        let a = Poly {
            deg: vec![1],
            c: vec![Iv::point(0.0), Iv::point(1.0)],
        };
        let b = Poly {
            deg: vec![1],
            c: vec![Iv::point(1.0), Iv::point(0.0)],
        };
        let p = a.mul(&b);
        assert_eq!(p.deg, vec![2]);
        // Outward rounding moves an exact 0 by one subnormal.
        assert!(p.c[1].lo <= 0.5 && 0.5 <= p.c[1].hi && p.c[0].lo <= 0.0 && p.c[0].hi < 1e-300);
        let s = a.add(&b);
        assert!(s.c.iter().all(|x| x.lo <= 1.0 && 1.0 <= x.hi));
    }
}
