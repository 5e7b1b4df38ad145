//! Polynomials in power form: [`Poly`] over Q, in which the referee builds
//! the polynomial whose zeros are the hits, and [`IPoly`], a positive
//! primitive multiple over Z, on which gcds, square-free parts and Sturm
//! sequences ([`Sturm`]: the number of distinct zeros in an interval, by
//! Sturm's theorem) run without rational arithmetic.

use super::exact::{qi, sgn, Q};
use rootclip::num_bigint::{BigInt, Sign};

/// A polynomial over Q, coefficients from the constant term up, no trailing
/// zeros (the zero polynomial is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct Poly(pub(super) Vec<Q>);

impl Poly {
    pub fn new(mut c: Vec<Q>) -> Poly {
        while c.last().is_some_and(|x| sgn(x) == 0) {
            c.pop();
        }
        Poly(c)
    }
    pub fn constant(c: Q) -> Poly {
        Poly::new(vec![c])
    }
    /// `c0 + c1·s`.
    pub fn linear(c0: Q, c1: Q) -> Poly {
        Poly::new(vec![c0, c1])
    }
    /// `Π (s − r)` over `roots`.
    pub fn from_roots(roots: &[Q]) -> Poly {
        roots
            .iter()
            .fold(Poly::constant(qi(1)), |p, r| p.mul(&Poly::linear(-r, qi(1))))
    }
    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }
    /// The degree (0 for constants and for zero).
    pub fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }
    pub fn eval(&self, x: &Q) -> Q {
        self.0.iter().rev().fold(qi(0), |acc, c| acc * x + c)
    }
    pub(super) fn deriv(&self) -> Poly {
        Poly::new(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * qi(k as i64))
                .collect(),
        )
    }
    pub(super) fn add(&self, o: &Poly) -> Poly {
        let n = self.0.len().max(o.0.len());
        let at = |p: &Poly, k: usize| p.0.get(k).cloned().unwrap_or_else(|| qi(0));
        Poly::new((0..n).map(|k| at(self, k) + at(o, k)).collect())
    }
    pub(super) fn scale(&self, c: &Q) -> Poly {
        Poly::new(self.0.iter().map(|x| x * c).collect())
    }
    pub(super) fn sub(&self, o: &Poly) -> Poly {
        self.add(&o.scale(&qi(-1)))
    }
    pub(super) fn mul(&self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly(Vec::new());
        }
        let mut c = vec![qi(0); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in o.0.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly::new(c)
    }
    /// `1 + max |c_k / c_n|`: every zero has a smaller modulus.
    pub(super) fn cauchy_bound(&self) -> Q {
        let l = self.0.last().expect("a non-zero polynomial");
        let m = self.0[..self.0.len() - 1]
            .iter()
            .map(|c| {
                let r = c / l;
                if sgn(&r) < 0 {
                    -r
                } else {
                    r
                }
            })
            .max()
            .unwrap_or_else(|| qi(0));
        m + qi(1)
    }
}

pub(super) fn int_sgn(x: &BigInt) -> i32 {
    match x.sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

fn int_abs(x: &BigInt) -> BigInt {
    if int_sgn(x) < 0 {
        -x
    } else {
        x.clone()
    }
}

fn int_gcd(a: &BigInt, b: &BigInt) -> BigInt {
    let (mut a, mut b) = (int_abs(a), int_abs(b));
    while int_sgn(&b) != 0 {
        let r = &a % &b;
        a = b;
        b = r;
    }
    a
}

/// A primitive polynomial over Z: a positive multiple of the polynomial it
/// was made from (the same signs everywhere), so that Sturm sequences and
/// gcds run without rational arithmetic.
#[derive(Clone, Debug)]
pub(super) struct IPoly(pub(super) Vec<BigInt>);

impl IPoly {
    /// Trailing zeros dropped, divided by the content.
    fn primitive(mut c: Vec<BigInt>) -> IPoly {
        while c.last().is_some_and(|x| int_sgn(x) == 0) {
            c.pop();
        }
        let g = c.iter().fold(BigInt::from(0), |g, x| int_gcd(&g, x));
        if int_sgn(&g) > 0 {
            for x in &mut c {
                *x = &*x / &g;
            }
        }
        IPoly(c)
    }

    /// `p` times the (positive) lcm of its denominators, made primitive.
    pub(super) fn of(p: &Poly) -> IPoly {
        let lcm = p.0.iter().fold(BigInt::from(1), |l, c| {
            let d = c.denom();
            &l / int_gcd(&l, d) * d
        });
        IPoly::primitive(p.0.iter().map(|c| c.numer() * (&lcm / c.denom())).collect())
    }

    fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    pub(super) fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }

    /// The sign at `x = n/d` (`d > 0`): of `Σ c_k n^k d^(deg − k)`.
    pub(super) fn sign_at(&self, x: &Q) -> i32 {
        let Some(lead) = self.0.last() else { return 0 };
        let (n, d) = (x.numer(), x.denom());
        let (mut acc, mut dk) = (lead.clone(), BigInt::from(1));
        for c in self.0.iter().rev().skip(1) {
            dk *= d;
            acc = acc * n + c * &dk;
        }
        int_sgn(&acc)
    }

    pub(super) fn deriv(&self) -> IPoly {
        IPoly::primitive(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * BigInt::from(k))
                .collect(),
        )
    }

    /// A positive multiple of the remainder of `self` by `b` (pseudo-division
    /// with the multiplier `|lead(b)|`), made primitive.
    fn rem(&self, b: &IPoly) -> IPoly {
        let mut r = self.0.clone();
        let lb = b.0.last().expect("a non-zero divisor");
        let (mul, flip) = (int_abs(lb), int_sgn(lb));
        while r.len() >= b.0.len() {
            let k = r.len() - b.0.len();
            let lr = r.last().unwrap() * BigInt::from(flip);
            for x in &mut r {
                *x *= &mul;
            }
            for (j, bj) in b.0.iter().enumerate() {
                r[k + j] -= &lr * bj;
            }
            r.pop();
            while r.last().is_some_and(|x| int_sgn(x) == 0) {
                r.pop();
            }
        }
        IPoly::primitive(r)
    }

    /// `self / g` for a primitive `g` dividing it (Gauss: the quotient is
    /// integral).
    fn div_exact(&self, g: &IPoly) -> IPoly {
        let mut r = self.0.clone();
        let dn = g.0.len();
        let mut q = vec![BigInt::from(0); r.len() + 1 - dn];
        for k in (0..q.len()).rev() {
            let c = &r[k + dn - 1] / g.0.last().unwrap();
            for (j, gj) in g.0.iter().enumerate() {
                r[k + j] -= &c * gj;
            }
            q[k] = c;
        }
        assert!(r.iter().all(|x| int_sgn(x) == 0), "an exact division");
        IPoly::primitive(q)
    }

    pub(super) fn gcd(&self, o: &IPoly) -> IPoly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let r = a.rem(&b);
            a = b;
            b = r;
        }
        a
    }

    /// The square-free part: the same distinct zeros, all simple.
    pub(super) fn squarefree(&self) -> IPoly {
        if self.degree() == 0 {
            return self.clone();
        }
        self.div_exact(&self.gcd(&self.deriv()))
    }

    fn neg(&self) -> IPoly {
        IPoly(self.0.iter().map(|x| -x).collect())
    }
}

/// The Sturm sequence of a square-free polynomial, each member scaled by a
/// positive number.
pub(super) struct Sturm(Vec<IPoly>);

impl Sturm {
    pub(super) fn new(p: &IPoly) -> Sturm {
        let mut chain = vec![p.clone()];
        if p.degree() >= 1 {
            chain.push(p.deriv());
            loop {
                let n = chain.len();
                let r = chain[n - 2].rem(&chain[n - 1]);
                if r.is_zero() {
                    break;
                }
                chain.push(r.neg());
            }
        }
        Sturm(chain)
    }
    /// Sign changes at `x`, zeros skipped.
    fn changes(&self, x: &Q) -> usize {
        let (mut last, mut n) = (0, 0);
        for p in &self.0 {
            let s = p.sign_at(x);
            if s != 0 {
                if last != 0 && s != last {
                    n += 1;
                }
                last = s;
            }
        }
        n
    }
    /// Distinct zeros in `(a, b]` (Sturm's theorem, `a < b`).
    pub(super) fn count(&self, a: &Q, b: &Q) -> usize {
        self.changes(a)
            .checked_sub(self.changes(b))
            .expect("Sturm counts decrease")
    }
    /// Distinct zeros in the open `(a, b)`.
    pub(super) fn count_open(&self, a: &Q, b: &Q) -> usize {
        self.count(a, b) - usize::from(self.0[0].sign_at(b) == 0)
    }
}
