//! Exact polynomials in `u`, `v` in the monomial basis, and their exact
//! conversion to Bernstein–Bézier form on the unit triangle and unit square.
//!
//! # Conversions
//! ```text
//! triangle, degree n:  u^a v^b = Σ_{i≥a, j≥b} C(i,a) C(j,b) / C(n; a, b, n−a−b) · B^n_ijk
//! interval, degree m:  t^a     = Σ_{i≥a} C(i,a) / C(m,a) · B^m_i(t)
//! ```
//! (the first from `u^a v^b = u^a v^b (u + v + w)^{n−a−b}`).

use super::index::{tri_index, tri_indices, tri_len};
use super::l2::{binomial, multinomial};
use super::tensor::TensorBezier;
use super::triangle::TriBezier;
use crate::error::{Error, Result};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;
use std::fmt;

/// Highest total degree a [`Polynomial`] may reach; larger products are
/// rejected with [`Error::TooLarge`] instead of running away.
pub const MAX_DEGREE: u32 = 200;

/// Most term-by-term products one multiplication may take (a bivariate
/// polynomial of total degree 60 has 1891 terms; `1891²` fits): bounds the
/// parser's work on inputs such as `(u+v+1)^100*(u+v+1)^100`.
pub const MAX_PRODUCT_TERMS: usize = 4_000_000;

/// Most rational products an exact BB conversion may take (about a second).
pub const MAX_CONVERSION_WORK: usize = 4_000_000;

/// Terms `((a, b), numerator)` over a common denominator.
type IntegerTerms = Vec<((u32, u32), BigInt)>;

/// An exact polynomial `Σ c_ab u^a v^b` with rational coefficients. Zero
/// coefficients are never stored, so equality is equality of polynomials.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Polynomial {
    terms: BTreeMap<(u32, u32), BigRational>,
}

impl Polynomial {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Self::default()
    }

    /// A constant.
    pub fn constant(c: BigRational) -> Self {
        Self::monomial(c, 0, 0)
    }

    /// `c u^a v^b`.
    pub fn monomial(c: BigRational, a: u32, b: u32) -> Self {
        let mut terms = BTreeMap::new();
        if !c.is_zero() {
            terms.insert((a, b), c);
        }
        Self { terms }
    }

    /// The variable `u`.
    pub fn u() -> Self {
        Self::monomial(BigRational::one(), 1, 0)
    }

    /// The variable `v`.
    pub fn v() -> Self {
        Self::monomial(BigRational::one(), 0, 1)
    }

    /// The non-zero terms, keyed by `(exponent of u, exponent of v)`.
    pub fn terms(&self) -> &BTreeMap<(u32, u32), BigRational> {
        &self.terms
    }

    /// `true` for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The constant value, if the polynomial is constant.
    pub fn as_constant(&self) -> Option<BigRational> {
        match self.terms.len() {
            0 => Some(BigRational::zero()),
            1 => self.terms.get(&(0, 0)).cloned(),
            _ => None,
        }
    }

    /// Total degree (0 for constants and for the zero polynomial).
    pub fn total_degree(&self) -> u32 {
        self.terms.keys().map(|&(a, b)| a + b).max().unwrap_or(0)
    }

    /// Degrees in `u` and in `v` separately.
    pub fn degrees(&self) -> (u32, u32) {
        let du = self.terms.keys().map(|k| k.0).max().unwrap_or(0);
        let dv = self.terms.keys().map(|k| k.1).max().unwrap_or(0);
        (du, dv)
    }

    fn add_term(&mut self, key: (u32, u32), c: BigRational) {
        let entry = self.terms.entry(key).or_insert_with(BigRational::zero);
        *entry += c;
        if entry.is_zero() {
            self.terms.remove(&key);
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Self) -> Self {
        let mut out = self.clone();
        for (k, c) in &other.terms {
            out.add_term(*k, c.clone());
        }
        out
    }

    /// `−self`.
    pub fn neg(&self) -> Self {
        Self {
            terms: self.terms.iter().map(|(k, c)| (*k, -c)).collect(),
        }
    }

    /// `self − other`.
    pub fn sub(&self, other: &Self) -> Self {
        self.add(&other.neg())
    }

    /// `c · self`.
    pub fn scale(&self, c: &BigRational) -> Self {
        if c.is_zero() {
            return Self::zero();
        }
        Self {
            terms: self.terms.iter().map(|(k, x)| (*k, x * c)).collect(),
        }
    }

    /// `self · other`; errors if the total degree would exceed 200.
    pub fn mul(&self, other: &Self) -> Result<Self> {
        let deg = self.total_degree() + other.total_degree();
        if deg > MAX_DEGREE && !self.is_zero() && !other.is_zero() {
            return Err(Error::TooLarge(format!(
                "total degree {deg} exceeds the limit {MAX_DEGREE}"
            )));
        }
        let products = self.terms.len().saturating_mul(other.terms.len());
        if products > MAX_PRODUCT_TERMS {
            return Err(Error::TooLarge(format!(
                "a product of {} by {} terms ({products} rational products) exceeds the limit {MAX_PRODUCT_TERMS}",
                self.terms.len(),
                other.terms.len()
            )));
        }
        // Over one integer denominator per factor: the products and sums are
        // integer ones, and each coefficient is reduced once at the end (a
        // gcd per rational product made a product of 25 lines take 0.5 s).
        let (d1, n1) = self.integer_terms();
        let (d2, n2) = other.integer_terms();
        let mut sums: BTreeMap<(u32, u32), BigInt> = BTreeMap::new();
        for ((a1, b1), c1) in &n1 {
            for ((a2, b2), c2) in &n2 {
                *sums.entry((a1 + a2, b1 + b2)).or_insert_with(BigInt::zero) += c1 * c2;
            }
        }
        let den = d1 * d2;
        let terms = sums
            .into_iter()
            .filter(|(_, c)| !c.is_zero())
            .map(|(k, c)| (k, BigRational::new(c, den.clone())))
            .collect();
        Ok(Self { terms })
    }

    /// `(D, [(key, D·c)])`: the terms over the lcm `D` of their denominators.
    fn integer_terms(&self) -> (BigInt, IntegerTerms) {
        let d = self
            .terms
            .values()
            .fold(BigInt::one(), |d, c| num_integer::Integer::lcm(&d, c.denom()));
        let terms = self
            .terms
            .iter()
            .map(|(k, c)| (*k, c.numer() * (&d / c.denom())))
            .collect();
        (d, terms)
    }

    /// `self^e` by repeated squaring; errors past total degree 200.
    pub fn pow(&self, e: u32) -> Result<Self> {
        let deg = u64::from(self.total_degree()) * u64::from(e);
        if deg > u64::from(MAX_DEGREE) {
            return Err(Error::TooLarge(format!(
                "total degree {deg} exceeds the limit {MAX_DEGREE}"
            )));
        }
        let mut result = Self::constant(BigRational::one());
        let mut base = self.clone();
        let mut e = e;
        while e > 0 {
            if e & 1 == 1 {
                result = result.mul(&base)?;
            }
            e >>= 1;
            if e > 0 {
                base = base.mul(&base)?;
            }
        }
        Ok(result)
    }

    /// Exact value at `(u, v)`.
    pub fn eval(&self, u: &BigRational, v: &BigRational) -> BigRational {
        self.terms.iter().fold(BigRational::zero(), |acc, ((a, b), c)| {
            acc + c * num_traits::pow(u.clone(), *a as usize) * num_traits::pow(v.clone(), *b as usize)
        })
    }

    /// Rational products the exact conversion to the unit triangle costs
    /// (`terms × coefficients`).
    pub fn triangle_cost(&self) -> usize {
        let n = self.total_degree() as usize;
        self.terms.len().saturating_mul((n + 1) * (n + 2) / 2)
    }

    /// Rational products the exact conversion to the unit square costs.
    pub fn square_cost(&self) -> usize {
        let (m, n) = self.degrees();
        self.terms.len().saturating_mul((m as usize + 1) * (n as usize + 1))
    }

    /// Errors with [`Error::TooLarge`] when an exact conversion would take more
    /// than 4,000,000 rational products (seconds of work), so
    /// that callers fail fast on inputs like `(u+v+1)^100`.
    pub fn check_conversion_cost(&self, square: bool) -> Result<()> {
        let cost = if square {
            self.square_cost()
        } else {
            self.triangle_cost()
        };
        if cost > MAX_CONVERSION_WORK {
            return Err(Error::TooLarge(format!(
                "exact conversion of a polynomial with {} terms of degree {} needs {cost} rational products (limit {MAX_CONVERSION_WORK})",
                self.terms.len(),
                self.total_degree()
            )));
        }
        Ok(())
    }

    /// Exact BB form on the unit triangle of degree `max(total degree, min_degree)`.
    pub fn to_triangle(&self, min_degree: usize) -> TriBezier<BigRational> {
        let n = (self.total_degree() as usize).max(min_degree);
        // Term (a, b) adds c·C(i,a)C(j,b)/C(n; a,b,n−a−b) to f_ij. Summed over
        // one common denominator L (the lcm of every term's), the sums are of
        // integers, and each coefficient is reduced once at the end instead
        // of after every addition.
        let dens: Vec<BigInt> = self
            .terms
            .iter()
            .map(|((a, b), c)| {
                let (a, b) = (*a as usize, *b as usize);
                c.denom() * multinomial(a, b, n - a - b)
            })
            .collect();
        let common = dens.iter().fold(BigInt::one(), |l, d| num_integer::Integer::lcm(&l, d));
        let mut sums = vec![BigInt::zero(); tri_len(n)];
        for (((a, b), c), den) in self.terms.iter().zip(&dens) {
            let (a, b) = (*a as usize, *b as usize);
            let scale = c.numer() * (&common / den);
            for j in b..=n - a {
                for i in a..=n - j {
                    sums[tri_index(n, i, j)] += &scale * (binomial(i, a) * binomial(j, b));
                }
            }
        }
        let coeffs = sums.into_iter().map(|s| BigRational::new(s, common.clone())).collect();
        TriBezier::new(n, coeffs).expect("exact coefficients are finite")
    }

    /// Exact BB form on the unit square of bidegree (degree in `u`, degree in `v`).
    ///
    /// `u^a v^b = Σ_{i ≥ a, j ≥ b} C(i,a)/C(m,a) · C(j,b)/C(n,b) · B_i(u) B_j(v)`,
    /// summed one direction at a time (`O(mn(m + n))` operations, not
    /// `O(m²n²)`) in integers over one common denominator, reduced once per
    /// coefficient at the end.
    pub fn to_square(&self) -> TensorBezier<BigRational> {
        use num_integer::Integer;
        let (m, n) = self.degrees();
        let (m, n) = (m as usize, n as usize);
        let top = m.max(n);
        let pascal = super::l2::pascal(top);
        let lcm_row = |k: usize| pascal[k].iter().fold(BigInt::one(), |acc, c| acc.lcm(c));
        let (cm, cn) = (lcm_row(m), lcm_row(n));
        let den_l = self.terms.values().fold(BigInt::one(), |acc, c| acc.lcm(c.denom()));
        // w[a][b] = c_ab · L · (Cm / C(m,a)) · (Cn / C(n,b)), an integer.
        let mut w = vec![vec![BigInt::zero(); n + 1]; m + 1];
        for ((a, b), c) in &self.terms {
            let (a, b) = (*a as usize, *b as usize);
            let num = c.numer() * (&den_l / c.denom());
            w[a][b] = num * (&cm / &pascal[m][a]) * (&cn / &pascal[n][b]);
        }
        // t[i][b] = Σ_{a ≤ i} w[a][b] C(i,a); s[i][j] = Σ_{b ≤ j} t[i][b] C(j,b).
        let mut coeffs = Vec::with_capacity((m + 1) * (n + 1));
        let den = den_l * cm * cn;
        for i in 0..=m {
            let t: Vec<BigInt> = (0..=n)
                .map(|b| (0..=i).fold(BigInt::zero(), |acc, a| acc + &w[a][b] * &pascal[i][a]))
                .collect();
            for row in &pascal[..=n] {
                // row = C(j, ·) for j = 0..=n
                let s = row.iter().zip(&t).fold(BigInt::zero(), |acc, (c, tb)| acc + tb * c);
                coeffs.push(BigRational::new(s, den.clone()));
            }
        }
        TensorBezier::on_unit_square(m, n, coeffs).expect("exact coefficients are finite")
    }
    /// The monomial form of a tensor BB polynomial on the unit square:
    /// `Σ_ij c_ij C(m,i) u^i (1−u)^(m−i) C(n,j) v^j (1−v)^(n−j)`, exactly.
    pub fn from_square(f: &TensorBezier<BigRational>) -> Self {
        let (m, n) = f.degree();
        // B^k_i(x) = C(k,i) x^i (1 − x)^(k−i) = Σ_p C(k,i) C(k−i,p) (−1)^p x^(i+p).
        let basis = |k: usize, i: usize| -> Vec<(u32, BigRational)> {
            (0..=k - i)
                .map(|p| {
                    let c = BigRational::from_integer(binomial(k, i) * binomial(k - i, p));
                    ((i + p) as u32, if p % 2 == 1 { -c } else { c })
                })
                .collect()
        };
        let mut out = Self::zero();
        for i in 0..=m {
            let bu = basis(m, i);
            for j in 0..=n {
                let c = f.coeff(i, j);
                if c.is_zero() {
                    continue;
                }
                for (a, cu) in &bu {
                    for (b, cv) in basis(n, j) {
                        out.add_term((*a, b), c * cu * cv);
                    }
                }
            }
        }
        out
    }

    /// The monomial form of a BB polynomial on the unit triangle (the inverse
    /// of [`Self::to_triangle`]), for any degree.
    ///
    /// Expands `C(n; i,j,k) u^i v^j w^k` with
    /// `w^k = Σ_{p+q≤k} (−1)^{p+q} C(k; p,q,k−p−q) u^p v^q` term by term. The
    /// work is bounded by the input's size, so the degree limit of 200 (a guard against
    /// runaway *parsing*) does not apply: going through [`Self::pow`] here used
    /// to panic for degrees above it.
    ///
    /// In integers over the coefficients' common denominator, each sum
    /// reduced once at the end.
    pub fn from_triangle(f: &TriBezier<BigRational>) -> Self {
        let n = f.degree();
        let den = f
            .coeffs()
            .iter()
            .fold(BigInt::one(), |d, c| num_integer::Integer::lcm(&d, c.denom()));
        // sums[tri_index(n, a, b)]: the numerator of the coefficient of u^a v^b.
        let mut sums = vec![BigInt::zero(); tri_len(n)];
        // C(k; p, q, k − p − q) = C(k, p)·C(k − p, q).
        let c = super::l2::pascal(n);
        for ((i, j, k), coeff) in tri_indices(n).zip(f.coeffs()) {
            if coeff.is_zero() {
                continue;
            }
            let scaled = coeff.numer() * (&den / coeff.denom()) * &c[n][i] * &c[n - i][j];
            for p in 0..=k {
                let sp = &scaled * &c[k][p];
                for q in 0..=k - p {
                    let t = &sp * &c[k - p][q];
                    let sum = &mut sums[tri_index(n, i + p, j + q)];
                    if (p + q) % 2 == 1 {
                        *sum -= t;
                    } else {
                        *sum += t;
                    }
                }
            }
        }
        let terms = tri_indices(n)
            .zip(sums)
            .filter(|(_, c)| !c.is_zero())
            .map(|((a, b, _), c)| ((a as u32, b as u32), BigRational::new(c, den.clone())))
            .collect();
        Self { terms }
    }
}

fn fmt_rational(q: &BigRational) -> String {
    if q.denom() == &BigInt::one() {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}

/// Prints a form the parser reads back to the same polynomial, highest total
/// degree first: `3/4*u^2*v - u + 1/2`. The zero polynomial prints as `0`.
impl fmt::Display for Polynomial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.terms.is_empty() {
            return write!(f, "0");
        }
        let mut keys: Vec<_> = self.terms.keys().copied().collect();
        keys.sort_by_key(|k| std::cmp::Reverse((k.0 + k.1, k.0)));
        for (pos, key) in keys.iter().enumerate() {
            let c = &self.terms[key];
            let sign = if c.is_negative() { "-" } else { "+" };
            match (pos, sign) {
                (0, "-") => write!(f, "-")?,
                (0, _) => {}
                _ => write!(f, " {sign} ")?,
            }
            let mag = c.abs();
            let mut factors = Vec::new();
            if !mag.is_one() || *key == (0, 0) {
                factors.push(fmt_rational(&mag));
            }
            for (var, e) in [("u", key.0), ("v", key.1)] {
                match e {
                    0 => {}
                    1 => factors.push(var.to_string()),
                    _ => factors.push(format!("{var}^{e}")),
                }
            }
            write!(f, "{}", factors.join("*"))?;
        }
        Ok(())
    }
}
