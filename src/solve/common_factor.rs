//! The greatest common divisor of two bivariate polynomials over ℚ, and the
//! quotients: a system with a common factor `h` (a curve of roots) reduced
//! to `f/h = g/h = 0`, whose roots are its isolated ones.
//!
//! # Algorithm
//! Polynomials are taken in `ℚ[u][v]` (polynomials in `v` whose
//! coefficients are polynomials in `u`). By Gauss's lemma
//! `gcd(f, g) = gcd(cont f, cont g) · gcd(pp f, pp g)`, the content being the
//! gcd over `ℚ[u]` of the coefficients and `pp` the primitive part; the
//! primitive gcd is the last non-zero remainder of the primitive
//! pseudo-remainder sequence (`prem`, then `pp`), made primitive (Knuth,
//! TAOCP vol. 2, §4.6.1, Algorithm E; Geddes, Czapor & Labahn 1992, §7.2).
//! Everything is exact; the gcds in `ℚ[u]` are Euclid's
//! ([`gcd`](super::degenerate::gcd), monic). The result is normalized to
//! a leading coefficient of 1 (in the order of the highest power of `v`,
//! then of `u`).

use super::degenerate::gcd as gcd_u;
use crate::poly::Polynomial;
use num_rational::BigRational;
use num_traits::{One, Zero};

type Q = BigRational;
/// A polynomial in `u`, ascending (empty = 0).
type Pu = Vec<Q>;
/// A polynomial in `v` with coefficients in `ℚ[u]`, ascending in `v`.
type Puv = Vec<Pu>;

fn trim_u(p: &mut Pu) {
    while p.last().is_some_and(Zero::is_zero) {
        p.pop();
    }
}

fn trim_uv(p: &mut Puv) {
    for c in p.iter_mut() {
        trim_u(c);
    }
    while p.last().is_some_and(Vec::is_empty) {
        p.pop();
    }
}

fn mul_u(a: &Pu, b: &Pu) -> Pu {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![Q::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    trim_u(&mut out);
    out
}

fn sub_u(a: &Pu, b: &Pu) -> Pu {
    let mut out = vec![Q::zero(); a.len().max(b.len())];
    for (i, x) in a.iter().enumerate() {
        out[i] += x;
    }
    for (i, x) in b.iter().enumerate() {
        out[i] -= x;
    }
    trim_u(&mut out);
    out
}

/// `a / b` in `ℚ[u]`, `b ≠ 0`, `None` unless the division is exact.
fn div_u(a: &Pu, b: &Pu) -> Option<Pu> {
    let mut r = a.clone();
    trim_u(&mut r);
    let db = b.len() - 1;
    if r.len() < b.len() {
        return r.is_empty().then(Vec::new);
    }
    let mut q = vec![Q::zero(); r.len() - db];
    while r.len() > db {
        let top = r.len() - 1;
        let c = &r[top] / &b[db];
        for (i, x) in b.iter().enumerate() {
            let t = &c * x;
            r[top - db + i] -= t;
        }
        q[top - db] = c;
        r.pop();
        trim_u(&mut r);
    }
    r.is_empty().then_some(q)
}

/// The content: the monic gcd in `ℚ[u]` of the coefficients.
fn content(p: &Puv) -> Pu {
    p.iter().fold(Vec::new(), |g, c| {
        if g.is_empty() {
            gcd_u(c.clone(), Vec::new())
        } else {
            gcd_u(g, c.clone())
        }
    })
}

/// `p` divided by `c ∈ ℚ[u]` coefficient by coefficient (exact).
fn div_uv_by_u(p: &Puv, c: &Pu) -> Option<Puv> {
    p.iter().map(|x| div_u(x, c)).collect()
}

fn primitive(p: &Puv) -> Puv {
    let c = content(p);
    if c.is_empty() {
        return p.clone();
    }
    div_uv_by_u(p, &c).unwrap_or_else(|| p.clone())
}

/// The pseudo-remainder of `a` by `b` in `v` (`deg_v a ≥ deg_v b`):
/// `lc(b)^(deg a − deg b + 1)·a` reduced by `b`.
fn prem(a: &Puv, b: &Puv) -> Puv {
    let mut r = a.clone();
    let db = b.len() - 1;
    let lead = &b[db];
    while r.len() > db && !r.is_empty() {
        let top = r.len() - 1;
        let t = r[top].clone();
        for x in r.iter_mut() {
            *x = mul_u(x, lead);
        }
        for (i, y) in b.iter().enumerate() {
            let idx = top - db + i;
            r[idx] = sub_u(&r[idx], &mul_u(&t, y));
        }
        trim_uv(&mut r);
    }
    r
}

/// `a / b` in `ℚ[u][v]` (`b ≠ 0`), `None` unless exact.
fn div_uv(a: &Puv, b: &Puv) -> Option<Puv> {
    let mut r = a.clone();
    trim_uv(&mut r);
    let db = b.len() - 1;
    if r.len() < b.len() {
        return r.is_empty().then(Vec::new);
    }
    let mut q: Puv = vec![Vec::new(); r.len() - db];
    while r.len() > db && !r.is_empty() {
        let top = r.len() - 1;
        let c = div_u(&r[top], &b[db])?;
        for (i, y) in b.iter().enumerate() {
            let idx = top - db + i;
            r[idx] = sub_u(&r[idx], &mul_u(&c, y));
        }
        q[top - db] = c;
        trim_uv(&mut r);
    }
    r.is_empty().then_some(q)
}

fn to_uv(p: &Polynomial) -> Puv {
    let mut out: Puv = Vec::new();
    for (&(a, b), c) in p.terms() {
        let (a, b) = (a as usize, b as usize);
        if out.len() <= b {
            out.resize(b + 1, Vec::new());
        }
        if out[b].len() <= a {
            out[b].resize(a + 1, Q::zero());
        }
        out[b][a] = c.clone();
    }
    trim_uv(&mut out);
    out
}

fn from_uv(p: &Puv) -> Polynomial {
    let mut out = Polynomial::zero();
    for (b, c) in p.iter().enumerate() {
        for (a, x) in c.iter().enumerate() {
            out = out.add(&Polynomial::monomial(x.clone(), a as u32, b as u32));
        }
    }
    out
}

/// The gcd of `f` and `g` over `ℚ` (module docs), normalized to leading
/// coefficient 1; `1` when they are coprime. For two zero polynomials, 0.
pub(crate) fn gcd(f: &Polynomial, g: &Polynomial) -> Polynomial {
    let (mut a, mut b) = (to_uv(f), to_uv(g));
    if a.is_empty() {
        return normalized(from_uv(&b));
    }
    if b.is_empty() {
        return normalized(from_uv(&a));
    }
    let c = gcd_u(content(&a), content(&b));
    (a, b) = (primitive(&a), primitive(&b));
    if a.len() < b.len() {
        std::mem::swap(&mut a, &mut b);
    }
    while b.len() > 1 {
        let r = prem(&a, &b);
        a = b;
        b = if r.is_empty() { Vec::new() } else { primitive(&r) };
        if b.is_empty() {
            break;
        }
    }
    // b is 0 (a is the primitive gcd) or of degree 0 in v (coprime in v).
    let g_v: Puv = if b.is_empty() {
        primitive(&a)
    } else {
        vec![vec![Q::one()]]
    };
    normalized(from_uv(&g_v.iter().map(|x| mul_u(x, &c)).collect()))
}

/// `p` scaled to leading coefficient 1 (the term with the highest power of
/// `v`, then of `u`).
fn normalized(p: Polynomial) -> Polynomial {
    let lead = p
        .terms()
        .iter()
        .max_by_key(|(&(a, b), _)| (b, a))
        .map(|(_, c)| c.clone());
    match lead {
        Some(l) => p.scale(&(Q::one() / l)),
        None => p,
    }
}

/// `f / h` exactly (`h` divides `f`); `None` if it does not.
pub(crate) fn quotient(f: &Polynomial, h: &Polynomial) -> Option<Polynomial> {
    let hb = to_uv(h);
    if hb.is_empty() {
        return None;
    }
    div_uv(&to_uv(f), &hb).map(|q| from_uv(&q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_polynomial;

    fn p(s: &str) -> Polynomial {
        parse_polynomial(s).unwrap()
    }

    #[test]
    fn common_factors_and_quotients() {
        for (f, g, h) in [
            ("(u-v)*(u+v-1)", "(u-v)*(2*u-1/3)", "v - u"),
            ("(u^2+v^2-1/4)*(u+2)", "(u^2+v^2-1/4)^2*(v-3)", "v^2 + u^2 - 1/4"),
            ("(u-1/3)*v", "(u-1/3)*(v^2+1)", "u - 1/3"),
            ("u*v", "u + v", "1"),
            ("(u*v - 1)^2*(u - 2)", "(u*v-1)*(u-2)*(v+5)", "(u*v-1)*(u-2)"),
            ("3*(u+1)*(v-u)", "6*(v-u)*(u+1)^2", "(u+1)*(v-u)"),
        ] {
            let (f, g) = (p(f), p(g));
            let got = gcd(&f, &g);
            assert_eq!(got, normalized(p(h)), "gcd({f}, {g})");
            let (qf, qg) = (quotient(&f, &got).unwrap(), quotient(&g, &got).unwrap());
            assert_eq!(qf.mul(&got).unwrap(), f);
            assert_eq!(qg.mul(&got).unwrap(), g);
            assert_eq!(gcd(&qf, &qg), Polynomial::constant(Q::one()));
        }
        assert!(quotient(&p("u + 1"), &p("v")).is_none());
    }
}
