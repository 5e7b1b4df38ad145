//! The float-interval Bernstein kernels of the univariate solver, on bare
//! [`Iv`] endpoint pairs (rounded to nearest and moved outward: no rounding
//! mode switches in the hot loop): restriction to a sub-interval, value at a
//! point, the derivative's hull, Descartes' sign counts and the Bézier clip.
//!
//! Every function returns enclosures: the exact result of the same
//! computation for every polynomial whose coefficients lie in the input
//! enclosures lies in the output.

use crate::scalar::iv::Iv;

/// The whole line: what a computation that proves nothing returns.
const ENTIRE: Iv = Iv {
    lo: f64::NEG_INFINITY,
    hi: f64::INFINITY,
};

/// One de Casteljau step `(1 − t)·a + t·b`, for any float `t`.
fn lerp(a: Iv, b: Iv, t: f64) -> Iv {
    if (0.0..=1.0).contains(&t) {
        Iv::lerp(a, b, t)
    } else {
        Iv::lerp_any(a, b, t)
    }
}

/// In place: the coefficients on `[0, t]` of the row `w` on `[0, 1]` (local
/// parameter; `t` any float, or a range `[t, t_hi]` enclosing the exact
/// parameter). After step `k`, `w[i]` for `i ≥ k` holds the level-`k`
/// combination of `w[i−k..=i]`, so `w[i]` ends as the left piece's `i`-th
/// coefficient.
fn left_part(w: &mut [Iv], t: [f64; 2]) {
    let n = w.len() - 1;
    for k in 1..=n {
        for i in (k..=n).rev() {
            w[i] = step(w[i - 1], w[i], t);
        }
    }
}

/// In place: the coefficients on `[t, 1]` (as [`left_part`], mirrored).
fn right_part(w: &mut [Iv], t: [f64; 2]) {
    let n = w.len() - 1;
    for k in 1..=n {
        for i in 0..=n - k {
            w[i] = step(w[i], w[i + 1], t);
        }
    }
}

/// A de Casteljau step at a parameter known to lie in `[t[0], t[1]]`.
fn step(a: Iv, b: Iv, t: [f64; 2]) -> Iv {
    if t[0] == t[1] {
        lerp(a, b, t[0])
    } else {
        Iv::lerp_range(a, b, t[0], t[1])
    }
}

/// An enclosure `[lo, hi]` of a quotient of floats (`b ≠ 0`).
fn quotient(a: f64, b: f64) -> [f64; 2] {
    let q = Iv::point(a).div(Iv::point(b));
    [q.lo, q.hi]
}

/// Enclosures of the BB coefficients on `[t0, t1]` (any floats `t0 < t1`)
/// of the polynomial whose coefficients on `[0, 1]` are `c`: an exact split
/// at one end (a float), then a split at the enclosed local parameter of the
/// other. Two de Casteljau passes whatever the depth of a subdivision, so
/// rounding does not accumulate along its paths.
pub(crate) fn restrict(c: &[Iv], t0: f64, t1: f64) -> Vec<Iv> {
    let mut w = c.to_vec();
    if !(t0 < t1 && t0.is_finite() && t1.is_finite()) {
        return vec![ENTIRE; c.len()];
    }
    if t1 > 0.0 && (t1 <= 1.0 || t0 >= 1.0) {
        // [0, t1] first, then [t0/t1, 1] of it.
        if t1 != 1.0 {
            left_part(&mut w, [t1, t1]);
        }
        if t0 != 0.0 {
            right_part(&mut w, quotient(t0, t1));
        }
    } else {
        // t0 < 1 here: [t0, 1] first, then [0, (t1 − t0)/(1 − t0)] of it.
        if t0 != 0.0 {
            right_part(&mut w, [t0, t0]);
        }
        let num = Iv::point(t1).sub(Iv::point(t0));
        let den = Iv::point(1.0).sub(Iv::point(t0));
        let r = num.div(den);
        left_part(&mut w, [r.lo, r.hi]);
    }
    w
}

/// An enclosure of the value at the float `t` (de Casteljau).
pub(crate) fn eval(c: &[Iv], t: f64) -> Iv {
    let mut w = c.to_vec();
    let n = w.len() - 1;
    for k in 1..=n {
        for i in 0..=n - k {
            w[i] = lerp(w[i], w[i + 1], t);
        }
    }
    w[0]
}

/// An enclosure of `p'` over `[t0, t1]` from the coefficients `c` on it:
/// the hull of `n (c_{i+1} − c_i) / (t1 − t0)` (the derivative's BB
/// coefficients; a polynomial lies in the hull of its coefficients). The
/// zero polynomial for degree 0.
pub(crate) fn derivative_hull(c: &[Iv], t0: f64, t1: f64) -> Iv {
    let n = c.len() - 1;
    if n == 0 {
        return Iv::point(0.0);
    }
    let mut h: Option<Iv> = None;
    for w in c.windows(2) {
        let d = w[1].sub(w[0]);
        h = Some(h.map_or(d, |h| h.hull(d)));
    }
    let width = Iv::point(t1).sub(Iv::point(t0));
    let scaled = h.expect("n ≥ 1").mul(Iv::point(n as f64));
    scaled.div(width)
}

/// What the enclosure of a coefficient says about its sign, for every member.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sign3 {
    /// Every member is `> 0`.
    Pos,
    /// Every member is `< 0`.
    Neg,
    /// Exactly zero (a point interval `[0, 0]`).
    Zero,
    /// Either sign, or zero (or NaN: nothing is known).
    Unknown,
}

impl Sign3 {
    pub(crate) fn of(x: Iv) -> Self {
        if x.lo > 0.0 {
            Sign3::Pos
        } else if x.hi < 0.0 {
            Sign3::Neg
        } else if x.lo == 0.0 && x.hi == 0.0 {
            Sign3::Zero
        } else {
            Sign3::Unknown
        }
    }

    /// Strictly positive or strictly negative.
    pub(crate) fn strict(self) -> bool {
        matches!(self, Sign3::Pos | Sign3::Neg)
    }

    /// Both strict and opposite.
    pub(crate) fn opposite(self, o: Self) -> bool {
        matches!((self, o), (Sign3::Pos, Sign3::Neg) | (Sign3::Neg, Sign3::Pos))
    }
}

/// The fewest and the most sign changes (zeros skipped) of the coefficient
/// sequence over every member of the enclosures, an unknown sign counting
/// as `+`, `−` or `0`, whichever gives the extreme. By Descartes' rule of
/// signs on the Bernstein coefficients (the substitution `t = x/(1 + x)`
/// maps `(0, 1)` to `(0, ∞)` and `Σ c_i B_i` to `(1 + x)⁻ⁿ Σ c_i C(n, i) xⁱ`),
/// a member with `V` changes has at most `V` roots in the open interval,
/// counted with multiplicity, and `V` minus that count is even.
pub(crate) fn sign_changes(c: &[Iv]) -> (usize, usize) {
    // Per last non-zero sign (none, +, −): the fewest and most changes.
    let mut lo: [Option<usize>; 3] = [Some(0), None, None];
    let mut hi: [Option<usize>; 3] = [Some(0), None, None];
    for &x in c {
        let options: &[usize] = match Sign3::of(x) {
            Sign3::Pos => &[1],
            Sign3::Neg => &[2],
            Sign3::Zero => &[0],
            Sign3::Unknown => &[0, 1, 2],
        };
        let (mut nlo, mut nhi) = ([None; 3], [None; 3]);
        for state in 0..3 {
            for &o in options {
                let to = if o == 0 { state } else { o };
                let change = usize::from(state != 0 && o != 0 && o != state);
                if let Some(v) = lo[state] {
                    nlo[to] = Some(nlo[to].map_or(v + change, |w: usize| w.min(v + change)));
                }
                if let Some(v) = hi[state] {
                    nhi[to] = Some(nhi[to].map_or(v + change, |w: usize| w.max(v + change)));
                }
            }
        }
        (lo, hi) = (nlo, nhi);
    }
    let min = lo.iter().flatten().copied().min().unwrap_or(0);
    let max = hi.iter().flatten().copied().max().unwrap_or(0);
    (min, max)
}

/// Every coefficient's sign is unknown: the enclosures say nothing here
/// (rounding noise has swamped the polynomial's values), and no subdivision
/// of the same enclosures will say more.
pub(crate) fn no_signal(c: &[Iv]) -> bool {
    c.iter().all(|&x| Sign3::of(x) == Sign3::Unknown)
}

/// A lower bound on the first local parameter in `[0, 1]` where the convex
/// hull of the control polygon of some member meets zero; `None` when no
/// member's hull does (then no member has a root in `[0, 1]`).
///
/// When `c₀` is strictly positive for every member, the hull's first
/// crossing lies on the lower chain, which for every member lies above the
/// lower chain of the points `(i/n, lo_i)`; the first crossing of that chain
/// is the least crossing `x_i + (x_j − x_i)·lo_i/(lo_i − lo_j)` over the
/// pairs `i < j` with `lo_i > 0 ≥ lo_j` (every such segment lies in the
/// hull, and the chain's crossing edge is one of them). Each crossing is
/// bounded below in interval arithmetic. Negative `c₀`: the same with `−hi`.
pub(crate) fn hull_first_crossing(c: &[Iv]) -> Option<f64> {
    let n = c.len() - 1;
    if c.iter().any(|x| !x.is_finite()) {
        return Some(0.0); // an unbounded coefficient: no clip
    }
    let y: Vec<f64> = match Sign3::of(c[0]) {
        Sign3::Pos => c.iter().map(|x| x.lo).collect(),
        Sign3::Neg => c.iter().map(|x| -x.hi).collect(),
        _ => return Some(0.0),
    };
    if n == 0 {
        return None;
    }
    let mut best: Option<f64> = None;
    for i in (0..n).filter(|&i| y[i] > 0.0) {
        for j in (i + 1..=n).filter(|&j| y[j] <= 0.0) {
            // frac = y_i/(y_i − y_j) ∈ (0, 1], bounded below.
            let frac = Iv::point(y[i]).div(Iv::point(y[i]).sub(Iv::point(y[j])));
            let x = Iv::point(i as f64)
                .add(Iv::point((j - i) as f64).scale(frac.lo.max(0.0)))
                .div(Iv::point(n as f64));
            let x = x.lo.max(0.0);
            best = Some(best.map_or(x, |b| b.min(x)));
        }
    }
    best
}

/// The local sub-interval `[λ₀, λ₁] ⊂ [0, 1]` outside which no member has a
/// root (the Bézier clip: the control polygon's convex hull meets zero only
/// there); `None` when no member has a root in `[0, 1]`.
pub(crate) fn clip_local(c: &[Iv]) -> Option<[f64; 2]> {
    let l0 = hull_first_crossing(c)?;
    let rev: Vec<Iv> = c.iter().rev().copied().collect();
    let m = hull_first_crossing(&rev)?;
    let l1 = Iv::point(1.0).sub(Iv::point(m)).hi.min(1.0);
    (l0 <= l1).then_some([l0, l1])
}

/// The global sub-interval of `[t0, t1]` that the local `[λ₀, λ₁]` covers,
/// rounded outward (and kept within `[t0, t1]`).
pub(crate) fn to_global(t: [f64; 2], l: [f64; 2]) -> [f64; 2] {
    let w = Iv::point(t[1]).sub(Iv::point(t[0]));
    let a = Iv::point(t[0]).add(Iv::point(l[0]).mul(w)).lo;
    let b = Iv::point(t[0]).add(Iv::point(l[1]).mul(w)).hi;
    [a.max(t[0]).min(t[1]), b.min(t[1]).max(t[0])]
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;
    use num_traits::{One, Zero};

    type Q = BigRational;

    fn q(x: f64) -> Q {
        Q::from_float(x).unwrap()
    }

    fn contains(i: Iv, x: &Q) -> bool {
        q(i.lo) <= *x && *x <= q(i.hi)
    }

    /// The exact coefficients on [t0, t1] by blossoming in rationals.
    fn exact_restrict(c: &[Q], t0: &Q, t1: &Q) -> Vec<Q> {
        let n = c.len() - 1;
        (0..=n)
            .map(|i| {
                let mut w = c.to_vec();
                for k in 0..n {
                    let t = if k < i { t1 } else { t0 };
                    for j in 0..n - k {
                        w[j] = (Q::one() - t) * &w[j] + t * &w[j + 1];
                    }
                }
                w[0].clone()
            })
            .collect()
    }

    #[test]
    fn restriction_encloses_the_exact_coefficients() {
        let c = [0.3, -1.25, 2.0, 0.7, -0.1];
        let iv: Vec<Iv> = c.iter().map(|&x| Iv::point(x)).collect();
        let qc: Vec<Q> = c.iter().map(|&x| q(x)).collect();
        for (t0, t1) in [
            (0.1, 0.35),
            (0.0, 0.3),
            (0.7, 1.0),
            (-0.01, 0.02),
            (0.99, 1.01),
            (1e-300, 3e-300),
            (-0.2, -0.1),
            (1.1, 1.3),
            (-0.5, 1.5),
        ] {
            let r = restrict(&iv, t0, t1);
            let e = exact_restrict(&qc, &q(t0), &q(t1));
            for (a, b) in r.iter().zip(&e) {
                assert!(contains(*a, b), "[{t0}, {t1}]");
            }
        }
    }

    #[test]
    fn sign_changes_count_unknowns_both_ways() {
        let p = Iv::point(1.0);
        let m = Iv::point(-1.0);
        let u = Iv::new(-1.0, 1.0);
        let z = Iv::point(0.0);
        assert_eq!(sign_changes(&[p, p, p]), (0, 0));
        assert_eq!(sign_changes(&[p, z, m]), (1, 1));
        assert_eq!(sign_changes(&[p, u, m]), (1, 1));
        assert_eq!(sign_changes(&[p, u, p]), (0, 2));
        assert_eq!(sign_changes(&[u, p, m]), (1, 2));
        assert_eq!(sign_changes(&[p, m, p, m]), (3, 3));
        assert_eq!(sign_changes(&[u, u]), (0, 1));
    }

    #[test]
    fn clip_keeps_the_roots() {
        // (t − 0.3)(t − 0.6) on [0, 1]: BB coefficients 0.18, −0.27·½ + …
        let pw = [0.18, -0.9, 1.0]; // a0 + a1 t + a2 t²
        let bb = [pw[0], pw[0] + pw[1] / 2.0, pw[0] + pw[1] + pw[2]];
        let iv: Vec<Iv> = bb.iter().map(|&x| Iv::point(x)).collect();
        let [l0, l1] = clip_local(&iv).unwrap();
        assert!(l0 > 0.0 && l0 <= 0.3 && (0.6..1.0).contains(&l1), "{l0} {l1}");
        assert!(clip_local(&[Iv::point(1.0), Iv::point(0.5), Iv::point(2.0)]).is_none());
        let _ = Q::zero();
    }
}
