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
//! The usual case is decided by one sample per variable whose gcd is trivial
//! modulo the prime `2⁶¹ − 1` (which proves it trivial over ℚ, see
//! `coprime_mod_p`): a few microseconds, against tens for Euclid over ℚ.
//! The full count over ℚ runs only when that is not proven.

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
    // The usual case in microseconds: one sample whose gcd is trivial modulo
    // a prime is a sample whose gcd is trivial over ℚ.
    if coprime_mod_p(f, g, &sample(0), swap, (other(fd), other(gd))) {
        return false;
    }
    let bound = (f.total_degree() as usize) * (g.total_degree() as usize) + sampled(fd) + sampled(gd);
    (0..=bound).all(|k| {
        let x0 = sample(k);
        let (a, b) = (restrict(f, &x0, swap), restrict(g, &x0, swap));
        degree(&gcd(a, b)).is_some_and(|d| d >= 1)
    })
}

/// The prime of [`coprime_mod_p`]: `2⁶¹ − 1`.
const P: u64 = (1 << 61) - 1;

/// `a·b mod P` for `a, b < P`, by the Mersenne folding `2⁶¹ ≡ 1`.
fn mul_mod(a: u64, b: u64) -> u64 {
    let x = a as u128 * b as u128;
    let s = (x as u64 & P) + (x >> 61) as u64;
    let s = (s & P) + (s >> 61);
    if s >= P {
        s - P
    } else {
        s
    }
}

fn pow_mod(mut a: u64, mut e: u64) -> u64 {
    let mut r = 1;
    while e > 0 {
        if e & 1 == 1 {
            r = mul_mod(r, a);
        }
        a = mul_mod(a, a);
        e >>= 1;
    }
    r
}

/// `x mod P` for a rational whose denominator `P` does not divide; `None`
/// otherwise.
fn rational_mod_p(x: &BigRational) -> Option<u64> {
    let residue = |n: &BigInt| -> u64 {
        if let Some(small) = num_traits::ToPrimitive::to_i64(n) {
            return small.rem_euclid(P as i64) as u64;
        }
        let r = n % BigInt::from(P);
        let r = if r.sign() == num_bigint::Sign::Minus {
            r + BigInt::from(P)
        } else {
            r
        };
        r.iter_u64_digits().next().unwrap_or(0)
    };
    let d = residue(x.denom());
    let n = residue(x.numer());
    match d {
        0 => None,
        1 => Some(n),
        _ => Some(mul_mod(n, pow_mod(d, P - 2))),
    }
}

/// `true` only if `f(x0, ·)` and `g(x0, ·)` (`f(·, x0)`, `g(·, x0)` when
/// `swap`) are coprime over ℚ — proven through their images modulo the prime
/// `P`. If `h = gcd_ℚ(a, b)` has degree ≥ 1, then (Gauss's lemma) its
/// primitive integer form divides the integer forms of `a` and `b`, and when
/// `P` divides neither leading coefficient, `h mod P` keeps its degree and
/// divides `a mod P` and `b mod P`. So a gcd of degree 0 modulo `P`, with
/// `a mod P` and `b mod P` of the full degrees `degs` in the free variable
/// (upper bounds of the rational degrees, hence equal to them), proves
/// `gcd_ℚ = 1`. `false` means "not proven" (a denominator divisible by `P`,
/// a leading coefficient vanishing mod `P`, or a non-trivial gcd): the exact
/// test decides.
fn coprime_mod_p(f: &Polynomial, g: &Polynomial, x0: &BigRational, swap: bool, degs: (usize, usize)) -> bool {
    let Some(x) = rational_mod_p(x0) else {
        return false;
    };
    let top = (f.total_degree().max(g.total_degree())) as usize;
    let powers: Vec<u64> = std::iter::successors(Some(1u64), |&p| Some(mul_mod(p, x)))
        .take(top + 1)
        .collect();
    let restrict = |p: &Polynomial, deg: usize| -> Option<Vec<u64>> {
        let mut out = vec![0u64; deg + 1];
        for (&(a, b), c) in p.terms() {
            let (fixed, free) = if swap { (b, a) } else { (a, b) };
            let term = mul_mod(rational_mod_p(c)?, *powers.get(fixed as usize)?);
            let slot = out.get_mut(free as usize)?;
            *slot = (*slot + term) % P;
        }
        (out[deg] != 0).then_some(out)
    };
    let (Some(mut a), Some(mut b)) = (restrict(f, degs.0), restrict(g, degs.1)) else {
        return false;
    };
    // Euclid over F_P; the gcd's degree is that of the last non-zero remainder.
    let trim = |p: &mut Vec<u64>| {
        while p.last() == Some(&0) {
            p.pop();
        }
    };
    trim(&mut a);
    trim(&mut b);
    while !b.is_empty() {
        let inv = pow_mod(*b.last().expect("non-empty"), P - 2);
        while a.len() >= b.len() {
            let q = mul_mod(*a.last().expect("non-empty"), inv);
            let shift = a.len() - b.len();
            for (i, &c) in b.iter().enumerate() {
                a[shift + i] = (a[shift + i] + P - mul_mod(q, c)) % P;
            }
            trim(&mut a);
            if a.is_empty() {
                break;
            }
        }
        std::mem::swap(&mut a, &mut b);
    }
    a.len() == 1
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

    #[test]
    fn mersenne_product_is_the_remainder() {
        let mut rng = crate::rng::Rng(0x243f6a8885a308d3);
        let mut next = || rng.next_u64() % P;
        let mut pairs = vec![(0, 0), (P - 1, P - 1), (P - 1, 1), (1 << 60, 2), (P - 1, 2)];
        pairs.extend((0..10_000).map(|_| (next(), next())));
        for (a, b) in pairs {
            assert_eq!(mul_mod(a, b) as u128, (a as u128 * b as u128) % P as u128, "{a} * {b}");
        }
    }

    /// The modular shortcut agrees with the exact gcd of the same sample: it
    /// never claims coprime where the rational gcd is not, and it does prove
    /// the usual coprime case.
    #[test]
    fn modular_sample_agrees_with_the_exact_gcd() {
        let cases = [
            ("u^3-v", "u^3+v-1/4"),
            ("u^2+v^2-1/4", "u*v-1/8"),
            ("(u-v)*(u+1)", "(u-v)*(v-3)"),
            ("(u^2+v^2-1/4)*(u+2)", "(u^2+v^2-1/4)^2"),
            ("(v - 2/7 - 1/1009)*(u+v)", "(v - 2/7 - 1/1009)*(u-v)"),
            ("v^2 - (1/7 + 1/1009)^2", "v - 1/7 - 1/1009"),
            ("(u*v - 1)*(v+3)", "u^2*v^2 - 2*u*v + 1"),
            ("7/3*u^4*v^3 - v + 1/9", "u*v^2 - 11/13*v + 1"),
            ("u - 1/3", "v - 1/5"),
        ];
        for (f, g) in cases {
            let (f, g) = (p(f), p(g));
            for swap in [false, true] {
                let x0 = sample(0);
                let (fd, gd) = (f.degrees(), g.degrees());
                let other = |d: (u32, u32)| if swap { d.0 } else { d.1 } as usize;
                let exact = degree(&gcd(restrict(&f, &x0, swap), restrict(&g, &x0, swap)));
                let modular = coprime_mod_p(&f, &g, &x0, swap, (other(fd), other(gd)));
                if modular {
                    assert_eq!(exact, Some(0), "{f} / {g}, swap {swap}");
                }
                if exact == Some(0) && other(fd) > 0 && other(gd) > 0 {
                    assert!(modular, "{f} / {g}, swap {swap}: the usual case is not proven");
                }
            }
        }
    }
}
