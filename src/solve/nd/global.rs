//! Krawczyk on a box in domain coordinates, for the leaves of the iteration
//! and for merging: the operator of [`krawczyk`](super::krawczyk) with
//! sharper ingredients, since a leaf is where rounding hurts most.
//!
//! * `F(x̃)` is evaluated **exactly** at the float point `x̃` from the
//!   coefficients' midpoints (rational de Casteljau), then widened by a
//!   float bound `r` of the largest coefficient radius (the Bernstein basis
//!   is a non-negative partition of unity, so a coefficient error of at
//!   most `r` moves the value by at most `r`), then enclosed in floats
//!   outward. Where the caller knows the exact system the enclosures stand
//!   for ([`ExactValues`]), `F(x̃)` is its exact value, with no radius: then a
//!   zero is proven in a leaf however close its neighbours or its
//!   conditioning make it.
//! * `F'(X)` is the enclosure over `X` of the derivatives computed once on
//!   the whole domain (interval de Casteljau with parameter ranges), not the
//!   hull of a restricted polynomial's differences, whose rounding is
//!   divided by the box's width.
//!
//! Near two zeros `10⁻⁷` apart both matter: the values there are `~10⁻¹⁵`
//! and the derivatives `~10⁻⁷`, below what the subdivided coefficients
//! resolve.

use super::tensor::{derivative, eval_box};
use crate::scalar::iv::{up, Iv};
use crate::scalar::rational_to_interval;
use crate::solve::krawczyk::Verdict;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// A square system on the domain with its derivatives.
///
/// The derivatives and radii are built on first use: most solves certify
/// every zero by the local test and never reach a leaf.
pub(crate) struct GlobalSystem<'a, const N: usize> {
    deg: [[usize; N]; N],
    c: &'a [Vec<Iv>],
    /// The exact system the enclosures `c` hold, when known: its values are
    /// then exact, with no radius.
    exact: Option<&'a dyn ExactValues<N>>,
    parts: std::cell::OnceCell<Parts>,
}

/// What [`GlobalSystem`] derives from the coefficients.
struct Parts {
    /// `d[e][k]`: degrees and coefficients of `∂f_e/∂x_k`.
    d: Vec<Vec<(Vec<usize>, Vec<Iv>)>>,
    /// An upper bound of each equation's largest coefficient radius
    /// (exact rational of a float).
    radius: Vec<BigRational>,
}

/// An upper bound of `max(hi − mid, mid − lo)` over the coefficients, in
/// `f64`: each difference rounded to nearest, then moved up by [`up`] (so
/// it is at least the exact one).
fn radius_bound(eq: &[Iv]) -> f64 {
    eq.iter()
        .filter(|x| x.lo != x.hi)
        .map(|x| {
            let m = x.mid();
            up((x.hi - m).max(m - x.lo))
        })
        .fold(0.0f64, f64::max)
}

impl<'a, const N: usize> GlobalSystem<'a, N> {
    pub(crate) fn new(deg: [[usize; N]; N], c: &'a [Vec<Iv>], exact: Option<&'a dyn ExactValues<N>>) -> Self {
        Self {
            deg,
            c,
            exact,
            parts: std::cell::OnceCell::new(),
        }
    }

    fn parts(&self) -> &Parts {
        self.parts.get_or_init(|| Parts {
            d: (0..N)
                .map(|e| (0..N).map(|k| derivative(&self.c[e], &self.deg[e], k)).collect())
                .collect(),
            radius: self.c.iter().map(|eq| q(radius_bound(eq))).collect(),
        })
    }

    /// `f_e(x)` enclosed (module docs: exact, plus the radius; exact alone
    /// for an exact system).
    fn value(&self, e: usize, x: &[f64; N]) -> Iv {
        if let Some(ex) = self.exact {
            let v = rational_to_interval(&ex.value(e, x));
            return Iv::new(v.inf(), v.sup());
        }
        let v = eval_exact(&self.c[e], &self.deg[e], x);
        let r = &self.parts().radius[e];
        let lo = rational_to_interval(&(&v - r)).inf();
        let hi = rational_to_interval(&(&v + r)).sup();
        Iv::new(lo, hi)
    }

    fn jacobian(&self, x: &[[f64; 2]; N]) -> [[Iv; N]; N] {
        std::array::from_fn(|e| {
            std::array::from_fn(|k| {
                let (deg, c) = &self.parts().d[e][k];
                eval_box(c, deg, &x[..])
            })
        })
    }

    /// Krawczyk on the box `x` (float bounds, domain coordinates): `Unique`
    /// with an enclosure of the only zero when `K(X) ⊂ int X` (contracted by
    /// a few more steps), `NoRoot` when `K(X) ∩ X = ∅`.
    pub(crate) fn certify(&self, x: [[f64; 2]; N]) -> Verdict<[[f64; 2]; N], ()> {
        let Some(k) = self.step(&x) else {
            return Verdict::Undecided(());
        };
        let inside = (0..N).all(|a| k[a].lo > x[a][0] && k[a].hi < x[a][1]);
        if !inside {
            if (0..N).any(|a| k[a].hi < x[a][0] || k[a].lo > x[a][1]) {
                return Verdict::NoRoot;
            }
            return Verdict::Undecided(());
        }
        let mut cur: [[f64; 2]; N] = std::array::from_fn(|a| [k[a].lo, k[a].hi]);
        for _ in 0..4 {
            let Some(k) = self.step(&cur) else { break };
            let next: [[f64; 2]; N] = std::array::from_fn(|a| [k[a].lo.max(cur[a][0]), k[a].hi.min(cur[a][1])]);
            let w = |b: &[[f64; 2]; N]| b.iter().fold(0.0f64, |m, s| m.max(s[1] - s[0]));
            let shrunk = w(&next) < 0.5 * w(&cur);
            cur = next;
            if !shrunk {
                break;
            }
        }
        Verdict::Unique(cur)
    }

    /// `K(X)`; `None` when the midpoint Jacobian is singular or a value is
    /// not finite.
    fn step(&self, x: &[[f64; 2]; N]) -> Option<[Iv; N]> {
        let j = self.jacobian(x);
        let (y, mm) = super::krawczyk::preconditioner(&j)?;
        let p: [f64; N] = std::array::from_fn(|a| 0.5 * x[a][0] + 0.5 * x[a][1]);
        let f: [Iv; N] = std::array::from_fn(|e| self.value(e, &p));
        let dx: [Iv; N] = std::array::from_fn(|a| Iv::new(x[a][0], x[a][1]).sub(Iv::point(p[a])));
        let k: [Iv; N] = std::array::from_fn(|r| {
            let mut s = Iv::point(p[r]);
            for c in 0..N {
                s = s.sub(Iv::point(y[r][c]).mul(f[c]));
                s = s.add(mm[r][c].mul(dx[c]));
            }
            s
        });
        k.iter().all(|v| v.is_finite()).then_some(k)
    }
}

fn q(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap_or_else(BigRational::zero)
}

/// `x = m / 2^k` with `m` an integer and `k ≥ 0` (every finite float is
/// one).
fn dyadic(x: f64) -> (BigInt, u32) {
    if x == 0.0 || !x.is_finite() {
        return (BigInt::zero(), 0);
    }
    let (mant, exp, sign) = num_traits::Float::integer_decode(x);
    let tz = mant.trailing_zeros() as i32;
    let (mant, exp) = (mant >> tz, i32::from(exp) + tz);
    let m = BigInt::from(mant) * i64::from(sign);
    if exp >= 0 {
        (m << exp as u32, 0)
    } else {
        (m, exp.unsigned_abs())
    }
}

/// The exact value at the float point `x` of the polynomial whose
/// coefficients are the midpoints of `c` (de Casteljau in exact dyadic
/// arithmetic: every float is an integer over a power of two, and so is
/// every de Casteljau value at float parameters, so the values are kept as
/// integer numerators over one common power of two and reduced once, at the
/// end).
pub(crate) fn eval_exact(c: &[Iv], deg: &[usize], x: &[f64]) -> BigRational {
    let parts: Vec<(BigInt, u32)> = c.iter().map(|v| dyadic(v.mid())).collect();
    let shift = parts.iter().map(|p| p.1).max().unwrap_or(0);
    let work: Vec<BigInt> = parts.into_iter().map(|(m, k)| m << (shift - k)).collect();
    let (num, shift) = casteljau_int(work, shift, deg, x);
    BigRational::new(num, BigInt::one() << shift)
}

/// De Casteljau on integer coefficients `work` (over `2^shift`) at the float
/// point `x`: the value as an integer over `2^shift'`, returned with `shift'`.
fn casteljau_int(mut work: Vec<BigInt>, mut shift: u32, deg: &[usize], x: &[f64]) -> (BigInt, u32) {
    let mut len = work.len();
    for d in (0..deg.len()).rev() {
        let n = deg[d];
        // (1 − t)·a + t·b = ((2^k − m)·a + m·b) / 2^k for t = m / 2^k.
        let (t, k) = dyadic(x[d]);
        let s = (BigInt::one() << k) - &t;
        let lines = len / (n + 1);
        for l in 0..lines {
            let base = l * (n + 1);
            for r in 1..=n {
                for i in 0..=n - r {
                    let v = &s * &work[base + i] + &t * &work[base + i + 1];
                    work[base + i] = v;
                }
            }
            work.swap(l, base);
        }
        len = lines;
        shift += n as u32 * k;
    }
    (work.swap_remove(0), shift)
}

/// Exact values at float points of the system a [`GlobalSystem`]'s
/// enclosures stand for.
pub(crate) trait ExactValues<const N: usize> {
    /// `f_e(x)`, exactly.
    fn value(&self, e: usize, x: &[f64; N]) -> BigRational;
}

/// A system by its exact coefficients: equation `e` of degrees `deg[e]`.
pub(crate) struct ExactCoeffs<'a, const N: usize> {
    pub(crate) deg: [[usize; N]; N],
    pub(crate) eqs: &'a [ExactEq],
}

impl<const N: usize> ExactValues<N> for ExactCoeffs<'_, N> {
    fn value(&self, e: usize, x: &[f64; N]) -> BigRational {
        self.eqs[e].eval(&self.deg[e], x)
    }
}

/// A polynomial with exact rational coefficients, stored as integers over
/// one common denominator, for exact values at float points.
#[derive(Clone, Debug)]
pub(crate) struct ExactEq {
    num: Vec<BigInt>,
    den: BigInt,
}

impl ExactEq {
    /// The coefficients `c` (any rationals).
    pub(crate) fn new(c: &[BigRational]) -> Self {
        use num_integer::Integer;
        let den = c.iter().fold(BigInt::one(), |l, q| l.lcm(q.denom()));
        let num = c.iter().map(|q| q.numer() * (&den / q.denom())).collect();
        Self { num, den }
    }

    /// The exact value at the float point `x`.
    pub(crate) fn eval(&self, deg: &[usize], x: &[f64]) -> BigRational {
        let (num, shift) = casteljau_int(self.num.clone(), 0, deg, x);
        BigRational::new(num, &self.den << shift)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rational de Casteljau, one reduced fraction per value: the reference.
    fn eval_rational(c: &[f64], deg: &[usize], x: &[f64]) -> BigRational {
        let mut work: Vec<BigRational> = c.iter().map(|&v| q(v)).collect();
        let mut len = work.len();
        for d in (0..deg.len()).rev() {
            let n = deg[d];
            let t = q(x[d]);
            let s = BigRational::one() - &t;
            let lines = len / (n + 1);
            for l in 0..lines {
                let base = l * (n + 1);
                for r in 1..=n {
                    for i in 0..=n - r {
                        work[base + i] = &s * &work[base + i] + &t * &work[base + i + 1];
                    }
                }
                work.swap(l, base);
            }
            len = lines;
        }
        work.swap_remove(0)
    }

    #[test]
    fn dyadic_evaluation_is_exact() {
        // Coefficients of mixed magnitudes and signs, parameters inside,
        // on the faces and outside the unit box (an inflated leaf).
        let deg = [2usize, 3, 1];
        let c: Vec<f64> = (0..24)
            .map(|k| {
                let v = ((k * 7919) % 23) as f64 - 11.3;
                v * [1.0, 1e-9, 3.0e5, 0.1][k % 4]
            })
            .collect();
        let iv: Vec<Iv> = c.iter().map(|&v| Iv::point(v)).collect();
        for x in [
            [0.3, 0.7, 0.1],
            [0.0, 1.0, 0.5],
            [-1e-3, 1.000001, 0.123456789],
            [1e-300, 0.5, 2.0],
        ] {
            assert_eq!(eval_exact(&iv, &deg, &x), eval_rational(&c, &deg, &x));
        }
        let (m, k) = dyadic(0.75);
        assert_eq!((m, k), (BigInt::from(3), 2));
        assert_eq!(dyadic(-40.0), (BigInt::from(-40), 0));
    }
}
