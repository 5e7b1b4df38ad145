//! The univariate solver in exact rational arithmetic, for exact input:
//! restriction to a sub-interval, Descartes' rule on exact coefficients,
//! interval Newton on rational intervals ([`RI`], one [`Verdict`]), the
//! isolation of the small regions that rounding left undecided, and the
//! signs that settle roots at the ends of the domain.
//!
//! Every interval here has `f64` endpoints (exact dyadic rationals), so the
//! regions handed back are exactly the ones the proofs are about, and the
//! rationals stay the size of `n` floats' products.

use crate::scalar::rational_interval::RI;
use crate::scalar::rational_to_interval;
use crate::solve::degenerate::gcd;
use crate::solve::krawczyk::Verdict;
use crate::solve::settle::bernstein_to_power;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

type Q = BigRational;

/// Sub-intervals at most this many float steps wide are not split further.
const FLOAT_STEPS: u32 = 4;

fn q(x: f64) -> Q {
    // Callers pass finite floats (interval ends of a finite solve).
    Q::from_float(x).unwrap_or_else(Q::zero)
}

/// The exact value at `t` (de Casteljau).
pub(crate) fn value(c: &[Q], t: &Q) -> Q {
    crate::poly::eval_coeffs(c, t.clone())
}

/// The sign of the exact value at the float `t`.
pub(crate) fn sign_at(c: &[Q], t: f64) -> Ordering {
    value(c, &q(t)).cmp(&Q::zero())
}

/// The exact BB coefficients on `[t0, t1]` (any `t0 < t1`) of the row `c`
/// on `[0, 1]`: a split at `t1`, then at `t0/t1` (or at `t0`, then at
/// `(t1 − t0)/(1 − t0)` when `t1` is 0).
pub(crate) fn restrict(c: &[Q], t0: &Q, t1: &Q) -> Vec<Q> {
    use crate::poly::split_coeffs;
    if !t1.is_zero() {
        let left = if t1.is_one() {
            c.to_vec()
        } else {
            split_coeffs(c, t1.clone()).0
        };
        if t0.is_zero() {
            left
        } else {
            split_coeffs(&left, t0 / t1).1
        }
    } else {
        let right = split_coeffs(c, t0.clone()).1;
        split_coeffs(&right, (t1 - t0) / (Q::one() - t0)).0
    }
}

/// Sign changes of an exact sequence, zeros skipped (Descartes' count).
pub(crate) fn sign_changes(c: &[Q]) -> usize {
    let mut last = Ordering::Equal;
    let mut n = 0;
    for x in c {
        let s = x.cmp(&Q::zero());
        if s != Ordering::Equal {
            if last != Ordering::Equal && s != last {
                n += 1;
            }
            last = s;
        }
    }
    n
}

/// Interval Newton in exact arithmetic on `X = [α, β]`, from the exact
/// coefficients `cx` on `X` and `c` on `[0, 1]`:
/// `N(X) = m − p(m)/p'(X)`, `m` the float midpoint, `p'(X)` the hull of the
/// derivative's BB coefficients on `X`. `N(X) ⊂ int X`: exactly one root in
/// `X`, simple (Moore 1966; the mean value theorem and the monotonicity
/// that `0 ∉ p'(X)` gives), and it lies in `N(X)`. `N(X) ∩ X = ∅`: no root.
/// Otherwise every root of `X` lies in `N(X) ∩ X` (`None` when `0 ∈ p'(X)`).
pub(crate) fn newton(c: &[Q], cx: &[Q], x: [f64; 2]) -> Verdict<RI, Option<RI>> {
    let n = cx.len() - 1;
    if n == 0 {
        return Verdict::Undecided(None);
    }
    let (a, b) = (q(x[0]), q(x[1]));
    let scale = Q::from_integer(n.into()) / (&b - &a);
    let d: Vec<Q> = cx.windows(2).map(|w| (&w[1] - &w[0]) * &scale).collect();
    let (dlo, dhi) = (d.iter().min().expect("n ≥ 1"), d.iter().max().expect("n ≥ 1"));
    if !dlo.is_positive() && !dhi.is_negative() {
        return Verdict::Undecided(None);
    }
    let m = q(0.5 * x[0] + 0.5 * x[1]);
    let pm = value(c, &m);
    // 1/p'(X) for p'(X) of one strict sign: [1/dhi, 1/dlo].
    let recip = RI::new(Q::one() / dhi, Q::one() / dlo);
    let step = RI::point(pm).mul(&recip);
    let nx = RI::point(m).sub(&step);
    let xr = RI::new(a.clone(), b.clone());
    if nx.lo > a && nx.hi < b {
        return Verdict::Unique(nx);
    }
    match nx.meet(&xr) {
        None => Verdict::NoRoot,
        Some(k) => Verdict::Undecided(Some(k)),
    }
}

/// The float interval that encloses `r` (outward), kept within `x`.
fn outward_within(r: &RI, x: [f64; 2]) -> [f64; 2] {
    let lo = rational_to_interval(&r.lo).inf().max(x[0]);
    let hi = rational_to_interval(&r.hi).sup().min(x[1]);
    [lo, hi]
}

/// What exact isolation found in a region.
#[derive(Debug, Default)]
pub(crate) struct Isolated {
    /// Intervals holding exactly one root each, simple.
    pub(crate) roots: Vec<[f64; 2]>,
    /// Pieces still undecided (a multiple root, or the limits).
    pub(crate) undecided: Vec<[f64; 2]>,
    /// Exact tests spent.
    pub(crate) tests: usize,
}

/// Budgets of [`isolate`].
pub(crate) struct Limits {
    /// Bisections along any path.
    pub(crate) depth: usize,
    /// Exact restrictions in all.
    pub(crate) tests: usize,
}

/// Every root of the exact polynomial `c` in `[x0, x1]`: Bernstein
/// bisection with Descartes' rule on exact coefficients (`0` changes: no
/// root in the open piece; `1`: exactly one, simple) and exact interval
/// Newton where Descartes overcounts. The region's ends and every split
/// point are floats where `p ≠ 0` (moved by an ulp or a few where `p`
/// vanishes, outward at the ends), so the open pieces and their ends
/// partition the region and no root is counted twice; a region end moved
/// outward may bring in a root just outside, which the caller settles.
pub(crate) fn isolate(c: &[Q], x: [f64; 2], limits: &Limits) -> Isolated {
    let mut out = Isolated::default();
    let (Some(lo), Some(hi)) = (
        nonzero_near(c, x[0], f64::next_down),
        nonzero_near(c, x[1], f64::next_up),
    ) else {
        out.undecided.push(x);
        return out;
    };
    let mut stack = vec![([lo, hi], limits.depth)];
    while let Some((piece, depth)) = stack.pop() {
        if out.tests >= limits.tests {
            out.undecided.push(piece);
            continue;
        }
        out.tests += 1;
        let cx = restrict(c, &q(piece[0]), &q(piece[1]));
        match sign_changes(&cx) {
            0 => continue,
            1 => {
                out.roots.push(contract(c, piece, &mut out.tests, limits.tests));
                continue;
            }
            _ => {}
        }
        match newton(c, &cx, piece) {
            Verdict::NoRoot => continue,
            Verdict::Unique(_) => {
                out.roots.push(contract(c, piece, &mut out.tests, limits.tests));
                continue;
            }
            Verdict::Undecided(_) => {}
        }
        let mid = 0.5 * piece[0] + 0.5 * piece[1];
        let split = if depth == 0 || narrow(piece) {
            None
        } else {
            nonzero_near(c, mid, f64::next_up).filter(|&m| piece[0] < m && m < piece[1])
        };
        match split {
            Some(m) => {
                stack.push(([m, piece[1]], depth - 1));
                stack.push(([piece[0], m], depth - 1));
            }
            None => out.undecided.push(piece),
        }
    }
    out
}

/// The square-free part `s = p / gcd(p, p')` of an exact polynomial (the
/// same distinct roots, each simple) and the multiple roots' polynomial
/// `g = gcd(p, p')` (`None` when `p` is square-free), both in BB form on
/// `[0, 1]`.
pub(crate) struct SquareFree {
    pub(crate) s: Vec<Q>,
    g: Option<Vec<Q>>,
}

impl SquareFree {
    pub(crate) fn new(c: &[Q]) -> Self {
        let p = bernstein_to_power(c);
        let dp: Vec<Q> = p
            .iter()
            .enumerate()
            .skip(1)
            .map(|(i, a)| a * Q::from_integer(i.into()))
            .collect();
        let g = gcd(p.clone(), dp);
        if g.len() <= 1 {
            return Self { s: c.to_vec(), g: None };
        }
        let s = quotient(&p, &g);
        Self {
            s: power_to_bb(&s),
            g: Some(power_to_bb(&g)),
        }
    }

    /// For an interval `x` holding exactly one root `r` of `s` (one distinct
    /// root of `p`): an interval holding `r` as a simple root of `p` — `g`
    /// proven root-free on it (Descartes, non-zero ends), after contracting
    /// `x` if needed — or `None` when `r` stays possibly multiple (it is
    /// multiple when `g(r) = 0`, and then no interval proves otherwise).
    pub(crate) fn simple(&self, x: [f64; 2], tests: &mut usize, budget: usize) -> Option<[f64; 2]> {
        let Some(g) = &self.g else {
            return Some(x);
        };
        let free = |y: [f64; 2]| {
            let cy = restrict(g, &q(y[0]), &q(y[1]));
            sign_changes(&cy) == 0 && !cy[0].is_zero() && !cy[cy.len() - 1].is_zero()
        };
        if free(x) {
            return Some(x);
        }
        let y = contract(&self.s, x, tests, budget);
        free(y).then_some(y)
    }
}

/// The quotient of `a` by `b` in the power basis (ascending; exact when
/// `b` divides `a`, `b` trimmed).
fn quotient(a: &[Q], b: &[Q]) -> Vec<Q> {
    let mut r = a.to_vec();
    let lead = b.last().expect("non-zero divisor").clone();
    let mut out = vec![Q::zero(); a.len().saturating_sub(b.len()) + 1];
    for k in (0..out.len()).rev() {
        let f = &r[k + b.len() - 1] / &lead;
        for (i, c) in b.iter().enumerate() {
            r[k + i] -= &f * c;
        }
        out[k] = f;
    }
    out
}

/// The BB coefficients on `[0, 1]` of a power-basis polynomial of degree
/// `n = a.len() − 1`: `c_j = Σ_{i ≤ j} C(j, i)/C(n, i) a_i`.
fn power_to_bb(a: &[Q]) -> Vec<Q> {
    let n = a.len() - 1;
    let binom = |n: usize, k: usize| -> BigInt { (0..k).fold(BigInt::one(), |acc, i| acc * (n - i) / (i + 1)) };
    (0..=n)
        .map(|j| {
            (0..=j)
                .map(|i| &a[i] * Q::new(binom(j, i), binom(n, i)))
                .fold(Q::zero(), |s, x| s + x)
        })
        .collect()
}

/// At most [`FLOAT_STEPS`] floats apart.
fn narrow(x: [f64; 2]) -> bool {
    let mut t = x[0];
    for _ in 0..FLOAT_STEPS {
        t = t.next_up();
    }
    t >= x[1]
}

/// `x`, or the first of a few floats stepped from it by `next` where the
/// exact value is not zero.
fn nonzero_near(c: &[Q], x: f64, next: fn(f64) -> f64) -> Option<f64> {
    let mut t = x;
    for _ in 0..8 {
        if sign_at(c, t) != Ordering::Equal {
            return Some(t);
        }
        t = next(t);
    }
    None
}

/// Contracts `x`, which holds exactly one root (simple) and has non-zero
/// exact values at its ends, by exact Newton steps `X ← N(X) ∩ X` with
/// float endpoints (rounded outward, kept within `X`), until a step no
/// longer halves it. The root stays inside at every step: every root of
/// `X` lies in `N(X)`.
fn contract(c: &[Q], mut x: [f64; 2], tests: &mut usize, budget: usize) -> [f64; 2] {
    while *tests < budget && !narrow(x) {
        *tests += 1;
        let cx = restrict(c, &q(x[0]), &q(x[1]));
        let next = match newton(c, &cx, x) {
            Verdict::Unique(n) | Verdict::Undecided(Some(n)) => outward_within(&n, x),
            _ => bisect_by_sign(c, x),
        };
        if (next[1] - next[0]) * 2.0 > x[1] - x[0] {
            // Newton stalls only where p' nearly vanishes: halve instead.
            let half = bisect_by_sign(c, next);
            if half == next {
                return next;
            }
            x = half;
        } else {
            x = next;
        }
    }
    x
}

/// The half of `x` where `p` changes sign (exact signs; `x` holds one simple
/// root and `p ≠ 0` at its ends), or `x` when the midpoint is a root or
/// not a new float.
fn bisect_by_sign(c: &[Q], x: [f64; 2]) -> [f64; 2] {
    let m = 0.5 * x[0] + 0.5 * x[1];
    if !(x[0] < m && m < x[1]) {
        return x;
    }
    let sm = sign_at(c, m);
    if sm == Ordering::Equal {
        return x;
    }
    if sm == sign_at(c, x[0]) {
        [m, x[1]]
    } else {
        [x[0], m]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ints(v: &[i64]) -> Vec<Q> {
        v.iter().map(|&x| Q::from_integer(x.into())).collect()
    }

    #[test]
    fn restriction_is_exact() {
        // 1 − 2t + … : p(t) = (1 − t)² − 2·2t(1 − t)·… check by values.
        let c = ints(&[3, -5, 2, 7]);
        let (t0, t1) = (Q::new(1.into(), 3.into()), Q::new(3.into(), 4.into()));
        let r = restrict(&c, &t0, &t1);
        for k in 0..=4 {
            let s = Q::new(k.into(), 4.into());
            let t = &t0 + (&t1 - &t0) * &s;
            assert_eq!(value(&r, &s), value(&c, &t));
        }
        let r = restrict(&c, &Q::new((-1).into(), 2.into()), &Q::zero());
        let s = Q::new(1.into(), 3.into());
        assert_eq!(value(&r, &s), value(&c, &Q::new((-1).into(), 3.into())));
    }

    #[test]
    fn square_free_part_and_simple_roots() {
        // (t − 1/4)² (t − 1/2): s = (t − 1/4)(t − 1/2), g = t − 1/4.
        let quarter = Q::new(1.into(), 4.into());
        let half = Q::new(1.into(), 2.into());
        let p = [
            -(&quarter * &quarter * &half),
            &quarter * &quarter + &quarter * &half * Q::from_integer(2.into()),
            -(&half + &quarter * Q::from_integer(2.into())),
            Q::one(),
        ];
        let c = power_to_bb(&p);
        let sf = SquareFree::new(&c);
        assert_eq!(sf.s.len(), 3);
        for t in [&quarter, &half] {
            assert!(value(&sf.s, t).is_zero());
        }
        let mut tests = 0;
        assert!(sf.simple([0.4, 0.6], &mut tests, 100).is_some());
        assert!(sf.simple([0.2, 0.3], &mut tests, 100).is_none());
    }

    #[test]
    fn separates_roots_1e_minus_12_apart() {
        // (t − r)(t − r − δ) in BB form on [0, 1] from the power form.
        let r = q(0.3);
        let s = &r + q(1e-12);
        let (a0, a1) = (&r * &s, -(&r + &s));
        let c = vec![a0.clone(), &a0 + &a1 / Q::from_integer(2.into()), &a0 + &a1 + Q::one()];
        let out = isolate(&c, [0.3 - 1e-9, 0.3 + 1e-9], &Limits { depth: 64, tests: 400 });
        assert_eq!(out.roots.len(), 2, "{out:?}");
        assert!(out.undecided.is_empty());
        for (x, root) in out.roots.iter().zip([&r, &s]) {
            assert!(q(x[0]) <= *root && *root <= q(x[1]));
        }
    }
}
