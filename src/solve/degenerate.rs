//! Exact detection of degenerate systems: an identically zero equation, or a
//! common factor of `f` and `g` (a curve of roots).
//!
//! # Common factor test
//! If `f` and `g` share a factor `h` that involves `v`, then for all but
//! finitely many `u₀` the univariate `f(u₀, ·)` and `g(u₀, ·)` share the
//! factor `h(u₀, ·)`, so their gcd over ℚ is non-trivial. Conversely, without
//! a common factor the gcd is non-trivial only where `f(u₀,·)` and `g(u₀,·)`
//! have a common complex root (at most `deg f · deg g` values of `u₀`, by
//! Bézout) or one of them vanishes identically (at most `deg_u f + deg_u g`
//! values). So `D + 1` distinct `u₀` with non-trivial gcd, `D` that bound, prove
//! a common factor; the same in the other variable catches factors in `u` only.
//! Two quick samples decide the usual case; the full count runs only when both
//! are non-trivial.

use crate::poly::Polynomial;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// `true` iff `f` and `g` share a non-constant factor (exact).
pub fn has_common_factor(f: &Polynomial, g: &Polynomial) -> bool {
    if f.is_zero() || g.is_zero() {
        return true;
    }
    [false, true].into_iter().any(|swap| common_factor_in(f, g, swap))
}

fn common_factor_in(f: &Polynomial, g: &Polynomial, swap: bool) -> bool {
    let (fd, gd) = (f.degrees(), g.degrees());
    let sampled = |d: (u32, u32)| if swap { d.1 } else { d.0 } as usize;
    let other = |d: (u32, u32)| if swap { d.0 } else { d.1 } as usize;
    if other(fd) == 0 || other(gd) == 0 {
        // One equation does not involve the free variable: a shared factor
        // would have to be in the sampled variable only; the other pass checks it.
        return false;
    }
    let bound = (f.total_degree() as usize) * (g.total_degree() as usize) + sampled(fd) + sampled(gd);
    (0..=bound).all(|k| {
        let x0 = sample(k);
        let (a, b) = (restrict(f, &x0, swap), restrict(g, &x0, swap));
        degree(&gcd(a, b)).is_some_and(|d| d >= 1)
    })
}

/// Distinct sample values with small odd denominators.
fn sample(k: usize) -> BigRational {
    BigRational::new(BigInt::from(3 * k as i64 + 1), BigInt::from(7))
        + BigRational::new(BigInt::one(), BigInt::from(1009))
}

/// `f(x0, ·)` (or `f(·, x0)` when `swap`) as coefficients by power.
fn restrict(f: &Polynomial, x0: &BigRational, swap: bool) -> Vec<BigRational> {
    let mut out: Vec<BigRational> = Vec::new();
    for (&(a, b), c) in f.terms() {
        let (fixed, free) = if swap { (b, a) } else { (a, b) };
        let free = free as usize;
        if out.len() <= free {
            out.resize(free + 1, BigRational::zero());
        }
        out[free] += c * num_traits::pow(x0.clone(), fixed as usize);
    }
    out
}

fn degree(p: &[BigRational]) -> Option<usize> {
    p.iter().rposition(|c| !c.is_zero())
}

/// Monic gcd over ℚ by Euclid (zero polynomial = empty).
pub(crate) fn gcd(mut a: Vec<BigRational>, mut b: Vec<BigRational>) -> Vec<BigRational> {
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        let r = rem(&a, &b);
        a = b;
        b = r;
    }
    if let Some(lead) = a.last().cloned() {
        for c in &mut a {
            *c /= lead.clone();
        }
    }
    a
}

fn trim(p: &mut Vec<BigRational>) {
    while p.last().is_some_and(|c| c.is_zero()) {
        p.pop();
    }
}

fn rem(a: &[BigRational], b: &[BigRational]) -> Vec<BigRational> {
    let mut r = a.to_vec();
    let db = b.len() - 1;
    let lead = b[db].clone();
    while r.len() > db {
        let top = r.len() - 1;
        let q = r[top].clone() / lead.clone();
        for (i, c) in b.iter().enumerate() {
            let idx = top - db + i;
            r[idx] = r[idx].clone() - q.clone() * c;
        }
        r.pop();
        trim(&mut r);
    }
    trim(&mut r);
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_polynomial;

    fn p(s: &str) -> Polynomial {
        parse_polynomial(s).unwrap()
    }

    #[test]
    fn detects_shared_factors() {
        assert!(has_common_factor(&p("(u-v)*(u+1)"), &p("(u-v)*(v-3)")));
        assert!(has_common_factor(&p("(u-1/3)*v"), &p("(u-1/3)*(v^2+1)")));
        assert!(has_common_factor(&p("(u^2+v^2-1/4)*(u+2)"), &p("(u^2+v^2-1/4)^2")));
        assert!(!has_common_factor(&p("u^2+v^2-1/4"), &p("u*v-1/8")));
        assert!(!has_common_factor(&p("u^3-v"), &p("u^3+v-1/4")));
        assert!(!has_common_factor(&p("u-1/3"), &p("v-1/5")));
        assert!(has_common_factor(&p("0"), &p("u")));
    }
}
