//! Tensor BB polynomials on `[0, 1]²` in the branchless interval type
//! [`Iv`] (outward rounding without switching the FPU's mode): the
//! projection's hot path builds its critical-point systems and its distance
//! objective here, in the layout of the box solver.
//!
//! Products go through the scaled Bernstein basis: with
//! `â_ij = C(m, i) C(n, j) a_ij`, the product's scaled coefficients are the
//! plain convolution `ĉ_kl = Σ â_ij b̂_{k−i, l−j}`, and `c_kl = ĉ_kl / (C(M, k)
//! C(N, l))`. Binomials are exact integers enclosed as intervals.

use crate::scalar::iv::{down, up, Iv};

/// A polynomial of bidegree `(m, n)`, coefficients row-major (`c_ij` at
/// `i·(n + 1) + j`), every coefficient an enclosure.
#[derive(Clone, Debug)]
pub(super) struct IvPoly {
    pub(super) m: usize,
    pub(super) n: usize,
    pub(super) c: Vec<Iv>,
}

/// `C(n, k)` as an enclosing interval (exact below 2⁵³).
fn binomial(n: usize, k: usize) -> Iv {
    let mut b: u128 = 1;
    for i in 0..k.min(n - k) {
        b = b * (n - i) as u128 / (i + 1) as u128;
    }
    let x = b as f64;
    if b < (1u128 << 53) {
        Iv::point(x)
    } else {
        Iv::new(down(x), up(x))
    }
}

impl IvPoly {
    pub(super) fn new(m: usize, n: usize, c: Vec<Iv>) -> Self {
        debug_assert_eq!(c.len(), (m + 1) * (n + 1));
        Self { m, n, c }
    }

    fn at(&self, i: usize, j: usize) -> Iv {
        self.c[i * (self.n + 1) + j]
    }

    /// `C(m, i) C(n, j) c_ij`.
    fn scaled(&self) -> Vec<Iv> {
        let bu: Vec<Iv> = (0..=self.m).map(|i| binomial(self.m, i)).collect();
        let bv: Vec<Iv> = (0..=self.n).map(|j| binomial(self.n, j)).collect();
        (0..=self.m)
            .flat_map(|i| (0..=self.n).map(move |j| (i, j)))
            .map(|(i, j)| self.at(i, j).mul(bu[i].mul(bv[j])))
            .collect()
    }

    /// `f·g`, bidegree `(m₁ + m₂, n₁ + n₂)`.
    pub(super) fn mul(&self, o: &Self) -> Self {
        let (m, n) = (self.m + o.m, self.n + o.n);
        let (a, b) = (self.scaled(), o.scaled());
        let mut c = vec![Iv::point(0.0); (m + 1) * (n + 1)];
        for i in 0..=self.m {
            for j in 0..=self.n {
                let x = a[i * (self.n + 1) + j];
                for i2 in 0..=o.m {
                    for j2 in 0..=o.n {
                        let k = (i + i2) * (n + 1) + j + j2;
                        c[k] = c[k].add(x.mul(b[i2 * (o.n + 1) + j2]));
                    }
                }
            }
        }
        let bu: Vec<Iv> = (0..=m).map(|k| binomial(m, k)).collect();
        let bv: Vec<Iv> = (0..=n).map(|l| binomial(n, l)).collect();
        for (row, bk) in c.chunks_mut(n + 1).zip(&bu) {
            for (x, bl) in row.iter_mut().zip(&bv) {
                *x = x.div(bk.mul(*bl));
            }
        }
        Self { m, n, c }
    }

    /// The same polynomial at bidegree `(m2, n2) ≥ (m, n)`, one degree at a
    /// time: `c'_i = (i/(k+1)) c_{i−1} + (1 − i/(k+1)) c_i`.
    pub(super) fn elevate(&self, m2: usize, n2: usize) -> Self {
        let mut p = self.clone();
        while p.m < m2 {
            p = p.elevate_once(true);
        }
        while p.n < n2 {
            p = p.elevate_once(false);
        }
        p
    }

    fn elevate_once(&self, in_u: bool) -> Self {
        let (m, n) = if in_u {
            (self.m + 1, self.n)
        } else {
            (self.m, self.n + 1)
        };
        let k = if in_u { m } else { n };
        let weight = |i: usize| Iv::point(i as f64).div(Iv::point(k as f64));
        let get = |i: isize, j: isize| -> Iv {
            if i < 0 || j < 0 || i as usize > self.m || j as usize > self.n {
                Iv::point(0.0)
            } else {
                self.at(i as usize, j as usize)
            }
        };
        let mut c = Vec::with_capacity((m + 1) * (n + 1));
        for i in 0..=m {
            for j in 0..=n {
                let (r, prev, cur) = if in_u {
                    (i, get(i as isize - 1, j as isize), get(i as isize, j as isize))
                } else {
                    (j, get(i as isize, j as isize - 1), get(i as isize, j as isize))
                };
                let t = weight(r);
                c.push(prev.mul(t).add(cur.mul(Iv::point(1.0).sub(t))));
            }
        }
        Self { m, n, c }
    }

    /// `f + g` at the larger bidegree.
    pub(super) fn add(&self, o: &Self) -> Self {
        let (m, n) = (self.m.max(o.m), self.n.max(o.n));
        let (a, b) = (self.elevate(m, n), o.elevate(m, n));
        Self {
            m,
            n,
            c: a.c.iter().zip(&b.c).map(|(x, y)| x.add(*y)).collect(),
        }
    }

    /// `f − g` at the larger bidegree.
    pub(super) fn sub(&self, o: &Self) -> Self {
        self.add(&o.map(|x| Iv::point(0.0).sub(x)))
    }

    /// Each coefficient through `f`.
    pub(super) fn map(&self, f: impl Fn(Iv) -> Iv) -> Self {
        Self {
            m: self.m,
            n: self.n,
            c: self.c.iter().map(|&x| f(x)).collect(),
        }
    }

    /// `∂/∂u` (bidegree `(m − 1, n)`; the zero polynomial of bidegree
    /// `(0, n)` when `m = 0`).
    pub(super) fn d_u(&self) -> Self {
        if self.m == 0 {
            return Self::new(0, self.n, vec![Iv::point(0.0); self.n + 1]);
        }
        let k = Iv::point(self.m as f64);
        let mut c = Vec::with_capacity(self.m * (self.n + 1));
        for i in 0..self.m {
            for j in 0..=self.n {
                c.push(self.at(i + 1, j).sub(self.at(i, j)).mul(k));
            }
        }
        Self::new(self.m - 1, self.n, c)
    }

    /// `∂/∂v`.
    pub(super) fn d_v(&self) -> Self {
        if self.n == 0 {
            return Self::new(self.m, 0, vec![Iv::point(0.0); self.m + 1]);
        }
        let k = Iv::point(self.n as f64);
        let mut c = Vec::with_capacity((self.m + 1) * self.n);
        for i in 0..=self.m {
            for j in 0..self.n {
                c.push(self.at(i, j + 1).sub(self.at(i, j)).mul(k));
            }
        }
        Self::new(self.m, self.n - 1, c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(p: &IvPoly, u: f64, v: f64) -> f64 {
        let b = |n: usize, k: usize, t: f64| binomial(n, k).mid() * t.powi(k as i32) * (1.0 - t).powi((n - k) as i32);
        let mut s = 0.0;
        for i in 0..=p.m {
            for j in 0..=p.n {
                s += p.at(i, j).mid() * b(p.m, i, u) * b(p.n, j, v);
            }
        }
        s
    }

    #[test]
    fn algebra_by_values() {
        let f = IvPoly::new(2, 1, [1.0, -2.0, 0.5, 3.0, -1.0, 2.0].map(Iv::point).to_vec());
        let g = IvPoly::new(1, 2, [0.25, 1.0, -3.0, 2.0, 0.0, 1.5].map(Iv::point).to_vec());
        for (u, v) in [(0.1, 0.7), (0.5, 0.5), (0.9, 0.2)] {
            let (fu, gu) = (eval(&f, u, v), eval(&g, u, v));
            assert!((eval(&f.mul(&g), u, v) - fu * gu).abs() < 1e-13);
            assert!((eval(&f.add(&g), u, v) - (fu + gu)).abs() < 1e-13);
            assert!((eval(&f.sub(&g), u, v) - (fu - gu)).abs() < 1e-13);
            assert!((eval(&f.elevate(4, 3), u, v) - fu).abs() < 1e-13);
            let h = 1e-6;
            let du = (eval(&f, u + h, v) - eval(&f, u - h, v)) / (2.0 * h);
            let dv = (eval(&f, u, v + h) - eval(&f, u, v - h)) / (2.0 * h);
            assert!((eval(&f.d_u(), u, v) - du).abs() < 1e-6);
            assert!((eval(&f.d_v(), u, v) - dv).abs() < 1e-6);
        }
        // Every coefficient an enclosure: the product of point polynomials
        // holds the exact rational coefficients (checked on one with 1/3).
        let third = IvPoly::new(1, 0, vec![Iv::point(1.0), Iv::point(0.0)]).mul(&IvPoly::new(
            2,
            0,
            [1.0, 1.0, 1.0].map(Iv::point).to_vec(),
        ));
        // (1 − u)·1 in degree 3: coefficients 1, 2/3, 1/3, 0.
        for (c, want) in third.c.iter().zip([1.0, 2.0 / 3.0, 1.0 / 3.0, 0.0]) {
            assert!(c.lo <= want && want <= c.hi, "{c:?} vs {want}");
        }
    }
}
