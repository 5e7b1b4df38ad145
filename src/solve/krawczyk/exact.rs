//! Krawczyk's operator in exact arithmetic: rational interval enclosures
//! ([`RI`]) of an exactly given system, for the small regions that rounding
//! left undecided and for settling roots on the domain's boundary
//! ([`settle`](crate::solve::settle)).
//!
//! `K(X) = x̃ − Y F(x̃) + (I − Y J(X))(X − x̃)` as in the parent module, with
//! `x̃` and `Y` rounded to dyadics a little finer than the box and `K(X)`'s
//! endpoints rounded outward to them (so the rationals' sizes stay bounded
//! while the contraction stays quadratic).
//!
//! Not over [`Bivariate`](super::Bivariate): that trait encloses in inari's
//! `f64` intervals, whose rounding is exactly the noise this variant exists
//! to remove (two roots 1e-8 apart, a root a subnormal away from an edge).
//! Its systems implement [`RationalSystem`] instead.

use super::verdict::Verdict;
use crate::scalar::rational_interval::{cmp, q_add, q_mul, q_sub, RI};
use crate::solve::linalg::inverse2_dyadic;
use crate::solve::solution::Box2;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;

type Q = BigRational;

/// Steps of [`certify`].
const CERTIFY_STEPS: usize = 4;

/// A certified box at most this wide is not contracted further.
const TIGHT: f64 = 1e-15;

/// A system `F = (f, g)` enclosed in exact rational interval arithmetic:
/// the exact counterpart of [`Bivariate`](super::Bivariate) for a pair.
pub(crate) trait RationalSystem {
    /// `F` enclosed over the box `x` (exactly, at a point box).
    fn value(&self, x: &[RI; 2]) -> [RI; 2];
    /// `[[f_u, f_v], [g_u, g_v]]` enclosed over the box `x`.
    fn jacobian(&self, x: &[RI; 2]) -> [[RI; 2]; 2];
}

/// Krawczyk in exact arithmetic on `bx` widened by an eighth of its size on
/// each side, contracted by `X ← K(X) ∩ X` for at most [`CERTIFY_STEPS`]
/// steps; the contract of
/// [`ExactSystem::certify`](crate::solve::settle::ExactSystem::certify).
pub(crate) fn certify<S: RationalSystem>(sys: &S, bx: Box2) -> Verdict<Box2, ()> {
    let q = |x: f64| Q::from_float(x);
    // In rationals: a float widening of a box a few ulps wide would round
    // away (a root exactly on its edge, e.g. a corner of the domain, would
    // stay on the widened box's edge, where K(X) ⊂ int X cannot hold).
    let widen = |b: [f64; 2]| {
        let (lo, hi) = (q(b[0])?, q(b[1])?);
        // (An eighth: the float endpoints are dyadic, and so stays every
        // value of the test, whose products then need no gcd.)
        let r = (&hi - &lo) / Q::from_integer(8.into());
        Some((&lo - &r, &hi + &r))
    };
    let (Some((u0, u1)), Some((v0, v1))) = (widen(bx.u), widen(bx.v)) else {
        return Verdict::Undecided(());
    };
    let mut x = [RI::new(u0, u1), RI::new(v0, v1)];
    // K(X) ⊂ int X comes within a few steps when it comes at all; a step
    // that does not halve the box means it will not (and the rationals'
    // sizes double with every step that does).
    for _ in 0..CERTIFY_STEPS {
        let Some((k, jx)) = krawczyk_with(sys, &x, None) else {
            return Verdict::Undecided(());
        };
        let inside =
            (0..2).all(|d| cmp(&k[d].lo, &x[d].lo) == Ordering::Greater && cmp(&k[d].hi, &x[d].hi) == Ordering::Less);
        if inside {
            // The unique root lies in K, and K(X) ∩ X keeps it: a few more
            // steps bring the box down to rounding, while each at least
            // halves it. They reuse X's Jacobian enclosure (it encloses F'
            // over every K ⊂ X; the contraction per step is then about
            // |I − Y J(X)| ≈ width(X)·|F''|/|F'| instead of quadratic, still
            // far below ½ on the small boxes handed here), which saves the
            // enclosure, the costly part of a step.
            let mut k = k;
            for _ in 0..CERTIFY_STEPS {
                let w = k[0].width().max(k[1].width());
                if w.to_f64().is_some_and(|w| w <= TIGHT) {
                    break;
                }
                let Some((next, _)) = krawczyk_with(sys, &k, Some(&jx)) else {
                    break;
                };
                let (Some(a), Some(b)) = (next[0].meet(&k[0]), next[1].meet(&k[1])) else {
                    break;
                };
                if a.width().max(b.width()) * Q::from_integer(2.into()) > w {
                    break;
                }
                k = [a, b];
            }
            let out = |r: &RI| {
                let (lo, hi) = (r.lo.to_f64().unwrap_or(f64::NAN), r.hi.to_f64().unwrap_or(f64::NAN));
                // Outward by an ulp: `to_f64` rounds to nearest.
                [lo.next_down(), hi.next_up()]
            };
            return Verdict::Unique(Box2 {
                u: out(&k[0]),
                v: out(&k[1]),
            });
        }
        let (Some(a), Some(b)) = (k[0].meet(&x[0]), k[1].meet(&x[1])) else {
            return Verdict::NoRoot;
        };
        let before = x[0].width().max(x[1].width());
        let after = a.width().max(b.width());
        if after * Q::from_integer(2.into()) > before {
            return Verdict::Undecided(());
        }
        x = [a, b];
    }
    Verdict::Undecided(())
}

/// `K(X) = x̃ − Y F(x̃) + (I − Y J(X))(X − x̃)`, endpoints rounded outward.
pub(crate) fn krawczyk<S: RationalSystem>(sys: &S, x: &[RI; 2]) -> Option<[RI; 2]> {
    krawczyk_with(sys, x, None).map(|(k, _)| k)
}

/// [`krawczyk`] with `J(X)` replaced by `j` when given (any enclosure of
/// `F'` over a box holding `x`); returns `K` and the enclosure used.
fn krawczyk_with<S: RationalSystem>(sys: &S, x: &[RI; 2], j: Option<&Jacobian>) -> Option<([RI; 2], Jacobian)> {
    let width = x[0].width().max(x[1].width());
    let bits = precision_bits(&width)?;
    let mid = [x[0].mid_rounded(bits), x[1].mid_rounded(bits)];
    let pt = [RI::point(mid[0].clone()), RI::point(mid[1].clone())];
    let fm = sys.value(&pt).map(|v| v.lo);
    let jm: [[Q; 2]; 2] = sys.jacobian(&pt).map(|row| row.map(|v| v.lo));
    let y = inverse2_dyadic(&jm, bits)?;
    let jx: Jacobian = match j {
        Some(j) => j.clone(),
        None => sys.jacobian(x),
    };
    let dx = [x[0].sub_point(&mid[0]), x[1].sub_point(&mid[1])];
    let mut out: [RI; 2] = [RI::point(Q::zero()), RI::point(Q::zero())];
    for (i, o) in out.iter_mut().enumerate() {
        let yf = q_add(&q_mul(&y[i][0], &fm[0]), &q_mul(&y[i][1], &fm[1]));
        let mut acc = RI::point(q_sub(&mid[i], &yf));
        for (j, dxj) in dx.iter().enumerate() {
            // (I − Y J)_ij = δ_ij − Σ_l Y_il J_lj
            let yj = jx[0][j].scale(&y[i][0]).add(&jx[1][j].scale(&y[i][1]));
            let delta = if i == j { Q::one() } else { Q::zero() };
            let m = RI::point(delta).sub(&yj);
            acc = acc.add(&m.mul(dxj));
        }
        *o = acc.round_out(bits);
    }
    Some((out, jx))
}

/// `[[f_u, f_v], [g_u, g_v]]` enclosed.
type Jacobian = [[RI; 2]; 2];

/// Bits after the binary point that keep rounding far below `width²`.
fn precision_bits(width: &Q) -> Option<u64> {
    if !width.is_positive() {
        return Some(64);
    }
    // log2(width) ≈ bits(numer) − bits(denom). Rounding to about the square
    // of the width keeps it from limiting the (quadratic) contraction.
    let e = width.numer().bits() as i64 - width.denom().bits() as i64;
    let bits = (64 - 2 * e).max(64);
    (bits < 1 << 20).then_some(bits as u64)
}
