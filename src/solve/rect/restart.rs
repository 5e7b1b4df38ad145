//! Restarts from the exact input: a box whose coefficients rounding has
//! swamped is recomputed from the exact system in double-double, so that
//! its coefficients are again a few ulps of *its own* magnitudes.
//!
//! # Why
//! Every box's coefficients descend from the domain's, rounded to `f64`:
//! each carries an error of a few ulps of the domain's largest coefficient
//! `M₀`. Where the system is tiny compared with `M₀` — between the middle
//! roots of a product of 30 lines the values are about `10⁻¹⁸ M₀` — that
//! error is wider than the coefficients themselves, every clip stalls, and
//! only exact arithmetic (milliseconds per box) decides anything. Recomputed
//! from the exact input in double-double, the error is `~100 (m + n) u² M₀`
//! (`u = 2⁻⁵³`), about `10⁻²⁹ M₀`: the float steps work again down to
//! boxes whose values are `10⁻¹³` of the domain's.
//!
//! # The restriction
//! The box `[α_u, α_u + (1 − α_u) γ_u] × [α_v, α_v + (1 − α_v) γ_v]` of the
//! unit square (floats `α`, `γ`: the same exact sub-boxes as a clip, see
//! `rect` docs) is reached by two de Casteljau subdivisions per direction
//! (keep `[α, 1]`, then its first `γ`), each step `c' = x + τ (y − x)` with
//! the float `τ ∈ [0, 1]` in double-double arithmetic ([`lerp_dd`]).
//!
//! # Error bound
//! Let every value (exact or stored) be at most `M` in magnitude; the steps
//! are convex combinations, so `M = M₀ + R` serves throughout. One step
//! errs by at most `34 u² M` ([`lerp_dd`]), and errors already in `x`, `y`
//! pass through the convex combination `(1 − τ) x + τ y` without growing.
//! A coefficient of the box is the result of at most `2 (m + n)` steps, so
//! ```text
//! R = R₀ + 2 (m + n) (34 u² M + 10⁻³⁰⁰)
//! ```
//! bounds its error, where `R₀` bounds the input's rounding to double-double
//! and `10⁻³⁰⁰` every underflow of a step (at most ten roundings of at most
//! `2⁻¹⁰⁷⁴` each). The box's `f64` intervals are `h ± (|l| + R)` rounded
//! outward.

use super::net::Shape;
use crate::scalar::eft::{two_prod, two_sum, Dd};
use crate::scalar::iv::{self, Iv};
use crate::scalar::{rational_to_f64, rational_to_interval};
use num_rational::BigRational;
use num_traits::Zero;

/// The unit roundoff `2⁻⁵³`.
const U: f64 = f64::EPSILON / 2.0;

/// A polynomial of bidegree `(m, n)` on the unit square in double-double,
/// scaled by a power of two to largest coefficient about 1, with a bound
/// `rad` of every coefficient's error and `mag` of every magnitude.
#[derive(Clone, Debug)]
struct DdNet {
    c: Vec<Dd>,
    rad: f64,
    mag: f64,
}

/// `f` and `g` of an exact system on the unit square in double-double: the
/// source of restarts ([`DdSystem::restrict`]).
#[derive(Clone, Debug)]
pub(super) struct DdSystem {
    m: usize,
    n: usize,
    polys: [DdNet; 2],
}

impl DdNet {
    /// `c · 2^−e` (`e` from the largest coefficient) in double-double: `h`
    /// the nearest float, `l` the nearest to the rest, `rad` the largest
    /// width of the rest's tightest enclosure. `None` if every coefficient
    /// is 0 or a part is not finite.
    fn new(c: &[BigRational]) -> Option<Self> {
        let bits = |q: &BigRational| q.numer().bits() as i64 - q.denom().bits() as i64;
        let e = c.iter().filter(|q| !q.is_zero()).map(bits).max()?;
        let scale = |q: &BigRational| {
            if e >= 0 {
                BigRational::new_raw(q.numer().clone(), q.denom() << e as usize)
            } else {
                BigRational::new_raw(q.numer() << (-e) as usize, q.denom().clone())
            }
        };
        let (mut out, mut rad, mut mag) = (Vec::with_capacity(c.len()), 0.0f64, 0.0f64);
        for q in c {
            let q = scale(q);
            let h = rational_to_f64(&q);
            let rest = rational_to_interval(&(&q - BigRational::from_float(h)?));
            let (h, l) = two_sum(h, rest.inf());
            rad = rad.max(iv::up(rest.sup() - rest.inf()));
            mag = mag.max(iv::up(h.abs() + l.abs()));
            out.push(Dd { h, l });
        }
        (rad.is_finite() && mag.is_finite()).then_some(Self { c: out, rad, mag })
    }
}

impl DdSystem {
    /// `f` and `g` (bidegree `(m, n)`, row-major, on the unit square) in
    /// double-double; `None` if either vanishes identically or does not fit
    /// the float range after scaling, or on a length mismatch.
    pub(super) fn new(m: usize, n: usize, f: &[BigRational], g: &[BigRational]) -> Option<Self> {
        let len = (m + 1) * (n + 1);
        if f.len() != len || g.len() != len {
            return None;
        }
        Some(Self {
            m,
            n,
            polys: [DdNet::new(f)?, DdNet::new(g)?],
        })
    }

    /// The coefficients of `f` and `g` (each scaled by a power of two) on a
    /// box of the unit square holding `outer` (float endpoints), as `f64`
    /// intervals in the layout of [`Shape::pair`], and that box's endpoints
    /// (enclosures of the exact ones). `None` if `outer` does not meet the
    /// square or the shape differs.
    pub(super) fn restrict(&self, sh: Shape, outer: [[f64; 2]; 2]) -> Option<(Vec<Iv>, [[Iv; 2]; 2])> {
        if (sh.m, sh.n) != (self.m, self.n) || sh.polys < 2 {
            return None;
        }
        let mut params = [(0.0, 1.0); 2];
        let mut bx = [[Iv::point(0.0), Iv::point(1.0)]; 2];
        for d in 0..2 {
            let (lo, hi) = (outer[d][0].max(0.0), outer[d][1].min(1.0));
            if !(lo < hi) {
                return None;
            }
            // As `spans::clip`: [α, α + (1 − α)γ] ⊇ [lo, hi].
            let gamma = if hi >= 1.0 {
                1.0
            } else {
                ((hi - lo).next_up() / (1.0 - lo).next_down()).next_up().min(1.0)
            };
            params[d] = (lo, gamma);
            let a = Iv::point(lo);
            bx[d] = [a, if gamma < 1.0 { Iv::lerp(a, Iv::point(1.0), gamma) } else { Iv::point(1.0) }];
        }
        let steps = (2 * (self.m + self.n)) as f64;
        let mut out = Vec::with_capacity(sh.polys * sh.len);
        for p in &self.polys {
            let mut c = p.c.clone();
            for (d, &(alpha, gamma)) in params.iter().enumerate() {
                restrict(&mut c, self.m, self.n, d, alpha, gamma);
            }
            let m = iv::up(p.mag + p.rad) * (1.0 + 1e-10);
            let rad = iv::up(p.rad + steps * (34.0 * U * U * m + 1e-300));
            out.extend(c.iter().map(|x| {
                let r = iv::up(x.l.abs() + rad);
                Iv::new(iv::down(x.h - r), iv::up(x.h + r))
            }));
        }
        out.resize(sh.polys * sh.len, Iv::point(0.0));
        out.iter().all(|x| x.is_finite()).then_some((out, bx))
    }
}

/// One de Casteljau step `x + τ (y − x)` in double-double (`τ ∈ [0, 1]` a
/// float, `|x.l| ≤ u|x.h|` and the same for `y`), renormalized.
///
/// # Error
/// With `|x|, |y| ≤ M`: TwoSum gives `y.h − x.h = d_h + e₁` exactly, and
/// `d_l = fl(e₁ + fl(y.l − x.l))` errs by `≤ 6.01 u² M`; TwoProd gives
/// `τ d_h = p_h + e₂` exactly, and `p_l = fl(e₂ + fl(τ d_l))` by
/// `≤ 10.1 u² M`; TwoSum gives `x.h + p_h = s_h + e₃` exactly, and
/// `s_l = fl(e₃ + fl(x.l + p_l))` by `≤ 17.5 u² M`; the last TwoSum is
/// exact. So the result is `x + τ (y − x)` within `33.7 u² M` (and an
/// underflow of the products, `≤ 10·2⁻¹⁰⁷⁴`).
#[inline(always)]
fn lerp_dd(x: Dd, y: Dd, tau: f64) -> Dd {
    let (dh, e1) = two_sum(y.h, -x.h);
    let dl = e1 + (y.l - x.l);
    let (ph, e2) = two_prod(tau, dh);
    let pl = e2 + tau * dl;
    let (sh, e3) = two_sum(x.h, ph);
    let sl = e3 + (x.l + pl);
    let (h, l) = two_sum(sh, sl);
    Dd { h, l }
}

/// The net `c` (bidegree `(m, n)`, row-major) restricted in direction `d`
/// to `[α, 1]` and then to the first `γ` of that.
fn restrict(c: &mut [Dd], m: usize, n: usize, d: usize, alpha: f64, gamma: f64) {
    let w = n + 1;
    let k = if d == 0 { m } else { n };
    // Lines: whole rows at once in u (index i·w + j over j), one row in v.
    let (count, stride, step) = if d == 0 { (w, w, 1) } else { (m + 1, 1, w) };
    let at = |line: usize, i: usize| line * step + i * stride;
    if alpha > 0.0 {
        for r in 1..=k {
            for i in 0..=k - r {
                for line in 0..count {
                    let (a, b) = (at(line, i), at(line, i + 1));
                    c[a] = lerp_dd(c[a], c[b], alpha);
                }
            }
        }
    }
    if gamma < 1.0 {
        for r in 1..=k {
            for i in (r..=k).rev() {
                for line in 0..count {
                    let (a, b) = (at(line, i - 1), at(line, i));
                    c[b] = lerp_dd(c[a], c[b], gamma);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    /// The exact restriction of a tensor net to `[α, α + (1 − α)γ]` per
    /// direction, by rational de Casteljau.
    fn exact_restrict(c: &[BigRational], m: usize, n: usize, params: [(f64, f64); 2]) -> Vec<BigRational> {
        let mut c = c.to_vec();
        let w = n + 1;
        for (d, &(alpha, gamma)) in params.iter().enumerate() {
            let (a, g) = (BigRational::from_float(alpha).unwrap(), BigRational::from_float(gamma).unwrap());
            let k = if d == 0 { m } else { n };
            let lines = if d == 0 { w } else { m + 1 };
            for line in 0..lines {
                let idx = |i: usize| if d == 0 { i * w + line } else { line * w + i };
                let mut v: Vec<BigRational> = (0..=k).map(|i| c[idx(i)].clone()).collect();
                for r in 1..=k {
                    for i in 0..=k - r {
                        v[i] = &v[i] + &a * (&v[i + 1] - &v[i]);
                    }
                }
                for r in 1..=k {
                    for i in (r..=k).rev() {
                        v[i] = &v[i - 1] + &g * (&v[i] - &v[i - 1]);
                    }
                }
                for i in 0..=k {
                    c[idx(i)] = v[i].clone();
                }
            }
        }
        c
    }

    #[test]
    fn restriction_encloses_the_exact_one_tightly() {
        // A product of lines in u times one in v, bidegree (6, 3): tiny
        // between its roots, where f64 from the domain's coefficients is lost.
        let (m, n) = (6, 3);
        let mut f = vec![BigRational::zero(); (m + 1) * (n + 1)];
        let mut g = vec![BigRational::zero(); (m + 1) * (n + 1)];
        for i in 0..=m {
            for j in 0..=n {
                f[i * (n + 1) + j] = q((i as i64 * 7 - 20) * (j as i64 + 1), 13) + q(1, 3 + i as i64);
                g[i * (n + 1) + j] = q(j as i64 * 5 - 8, 11) - q(i as i64, 17);
            }
        }
        let sys = DdSystem::new(m, n, &f, &g).unwrap();
        let sh = Shape::pair(m, n);
        for outer in [
            [[0.0, 1.0], [0.0, 1.0]],
            [[0.3, 0.3000001], [0.71, 0.7100002]],
            [[0.1, 0.6], [0.9, 1.0]],
            [[0.0, 1e-9], [0.5, 0.5 + 1e-12]],
        ] {
            let (c, bx) = sys.restrict(sh, outer).unwrap();
            for d in 0..2 {
                assert!(bx[d][0].lo <= outer[d][0] && bx[d][1].hi >= outer[d][1]);
            }
            let params = [0, 1].map(|d| {
                let lo = outer[d][0];
                let gamma = if outer[d][1] >= 1.0 {
                    1.0
                } else {
                    ((outer[d][1] - lo).next_up() / (1.0 - lo).next_down()).next_up().min(1.0)
                };
                (lo, gamma)
            });
            for (k, poly) in [&f, &g].iter().enumerate() {
                let exact = exact_restrict(poly, m, n, params);
                let scale = {
                    let bits = |q: &BigRational| q.numer().bits() as i64 - q.denom().bits() as i64;
                    poly.iter().filter(|q| !q.is_zero()).map(bits).max().unwrap()
                };
                let mag = exact.iter().map(|x| rational_to_f64(x).abs()).fold(0.0, f64::max);
                for (i, e) in exact.iter().enumerate() {
                    let x: Iv = c[k * sh.len + i];
                    let e = e * BigRational::from_float(2f64.powi(-scale as i32)).unwrap();
                    let (lo, hi) = (BigRational::from_float(x.lo).unwrap(), BigRational::from_float(x.hi).unwrap());
                    assert!(lo <= e && e <= hi, "coefficient {i} of poly {k} on {outer:?}");
                    // Tight: within 1e-25 of the domain's scale plus a few ulps of the box's.
                    let w = x.hi - x.lo;
                    assert!(w <= 1e-25 + 1e-14 * mag * 2f64.powi(-scale as i32), "width {w} on {outer:?}");
                }
            }
        }
    }

    #[test]
    fn degenerate_input_gives_none() {
        let z = vec![BigRational::zero(); 4];
        let one = vec![q(1, 1); 4];
        assert!(DdSystem::new(1, 1, &z, &one).is_none());
        assert!(DdSystem::new(1, 1, &one, &one[..3]).is_none());
        let sys = DdSystem::new(1, 1, &one, &one).unwrap();
        assert!(sys.restrict(Shape::pair(1, 1), [[1.5, 2.0], [0.0, 1.0]]).is_none());
        assert!(sys.restrict(Shape::pair(2, 1), [[0.0, 1.0], [0.0, 1.0]]).is_none());
    }
}
