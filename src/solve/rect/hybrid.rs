//! Hybrid clipping on boxes: a fat line for `f` and a fat conic for `g`
//! (Liu et al. 2016, §2.3.2–2.3.3, carried over from tri-boxes to boxes).
//!
//! # The clip
//! In a box's local coordinates `(s, t) ∈ [0, 1]²`, `f` gets the strip of
//! [`super::fatline`] and `g` a conic `q = A + B s + C t + D s² + E s t + F t²`:
//! the least-squares fit, in `f64`, of `q`'s own tensor Bernstein coefficients
//! of bidegree `(m, n)` to `g`'s (those of `s²` are `i(i−1)/(m(m−1))`, of `st`
//! `ij/(mn)`, of `t²` `j(j−1)/(n(n−1))`; `s²` is left out when `m < 2`, `t²`
//! when `n < 2`), with `δ = max |g_ij − q_ij|` in [`Iv`] arithmetic, so that
//! `|g − q| ≤ δ` on the box (the basis is a positive partition of unity).
//! Every root lies in `R = {|l| ≤ δ_l} ∩ {|q| ≤ δ_q} ∩ [0, 1]²`.
//!
//! # Why the candidates suffice
//! `R` is compact and bounded by pieces of two lines, two conic level curves
//! `q = ±δ_q` and the box's edges. The extreme `s` (and `t`) over `R` is
//! attained at a point of its boundary that is either where two pieces meet
//! — box corners, a line or a conic level on a box edge, a line on a conic
//! level (a quadratic in one variable after substituting the line) — or an
//! interior point of a conic arc where the arc is tangent to `s = const`,
//! i.e. `∂q/∂t = 0` on `q = ±δ_q` (a quadratic after substituting the linear
//! condition; a conic with `F = 0` has no such point unless a whole vertical
//! line is a level, which is added as a candidate line). Lines and box
//! edges have no interior extremes of `s`. Every candidate is enclosed in
//! [`Iv`] arithmetic (the roots of each quadratic from its interval
//! coefficients, the square root rounded outward); candidates that provably
//! violate a constraint are dropped, and the spans are the hull of the rest.
//! A quadratic whose leading coefficient may vanish is solved as a linear
//! equation with the square term absorbed over `x ∈ [0, 1]` (the only roots
//! that matter lie in the box); one with no usable linear term either, or
//! any non-finite enclosure, gives up the clip ([`FatLineClip::Parallel`]:
//! the caller falls back to Bézier hulls).
//!
//! # Convergence
//! `δ_l = O(h²)` and `δ_q = O(h³)` on a box of size `h`, as for hybrid
//! clipping on tri-boxes (Liu et al. 2016, Lemmas 1–2); the strip meets the
//! conic band transversally at a simple root.

use super::fatline::{FatLineClip, Strip};
use super::net::{at, Shape, STACK};
use crate::scalar::iv::{down, up, Iv};
use crate::solve::linalg::{gauss, Pivoting};

/// A fat conic `|q(s, t)| ≤ δ`, `q = A + B s + C t + D s² + E s t + F t²`.
#[derive(Clone, Copy, Debug)]
struct Conic {
    k: [f64; 6],
    delta: f64,
}

impl Conic {
    /// The least-squares conic through `g`'s coefficients and its rigorous
    /// distance bound (module docs). `None` for non-finite input or a
    /// singular fit.
    fn of(p: &[Iv], sh: Shape) -> Option<Self> {
        let (m, n) = (sh.m, sh.n);
        let basis = |i: usize, j: usize| -> [f64; 6] {
            let (x, y) = (i as f64 / m as f64, j as f64 / n as f64);
            let xx = if m >= 2 {
                (i * i.saturating_sub(1)) as f64 / (m * (m - 1)) as f64
            } else {
                0.0
            };
            let yy = if n >= 2 {
                (j * j.saturating_sub(1)) as f64 / (n * (n - 1)) as f64
            } else {
                0.0
            };
            [1.0, x, y, xx, x * y, yy]
        };
        let used = [true, true, true, m >= 2, true, n >= 2];
        let mut ata = [[0.0f64; 6]; 6];
        let mut atb = [0.0f64; 6];
        for i in 0..=m {
            for j in 0..=n {
                let r = basis(i, j);
                let v = p[at(sh, i, j)].mid();
                for a in 0..6 {
                    atb[a] += r[a] * v;
                    for b in 0..6 {
                        ata[a][b] += r[a] * r[b];
                    }
                }
            }
        }
        // An unused term has basis values 0: its row and column are zero;
        // pin its coefficient to 0.
        for (a, &u) in used.iter().enumerate() {
            if !u {
                ata[a][a] = 1.0;
            }
        }
        let k = gauss(ata, atb, Pivoting::Plain(1e-300))?;
        if !k.iter().all(|x| x.is_finite()) {
            return None;
        }
        // δ over the coefficients, in Iv: q_ij from the exact basis values.
        let kk = k.map(Iv::point);
        let frac = |a: usize, b: usize| Iv::point(a as f64).div(Iv::point(b as f64));
        let mut delta = 0.0f64;
        for i in 0..=m {
            for j in 0..=n {
                let (x, y) = (frac(i, m), frac(j, n));
                let xx = if m >= 2 {
                    frac(i * i.saturating_sub(1), m * (m - 1))
                } else {
                    Iv::point(0.0)
                };
                let yy = if n >= 2 {
                    frac(j * j.saturating_sub(1), n * (n - 1))
                } else {
                    Iv::point(0.0)
                };
                let q = kk[0]
                    .add(kk[1].mul(x))
                    .add(kk[2].mul(y))
                    .add(kk[3].mul(xx))
                    .add(kk[4].mul(x.mul(y)))
                    .add(kk[5].mul(yy));
                let r = p[at(sh, i, j)].sub(q);
                if !r.is_finite() {
                    return None;
                }
                delta = delta.max(r.lo.abs()).max(r.hi.abs());
            }
        }
        Some(Self { k, delta })
    }

    fn eval(&self, s: Iv, t: Iv) -> Iv {
        let k = self.k.map(Iv::point);
        k[0].add(k[1].mul(s))
            .add(k[2].mul(t))
            .add(k[3].mul(s.mul(s)))
            .add(k[4].mul(s.mul(t)))
            .add(k[5].mul(t.mul(t)))
    }

    /// Provably outside the band at the candidate point.
    fn excludes(&self, p: [Iv; 2]) -> bool {
        let v = self.eval(p[0], p[1]);
        v.lo > self.delta || v.hi < -self.delta
    }

    /// `q(x, α + β x)` as `[c0, c1, c2]` (`c0 + c1 x + c2 x²`), the conic on
    /// the line `t = α + β s` (or, `swap`, on `s = α + β t`, in `t`).
    fn on_line(&self, alpha: Iv, beta: Iv, swap: bool) -> [Iv; 3] {
        let k = self.k.map(Iv::point);
        // In the swapped frame the roles of (B, D) and (C, F) exchange.
        let (a, b, c, d, e, f) = if swap {
            (k[0], k[2], k[1], k[5], k[4], k[3])
        } else {
            (k[0], k[1], k[2], k[3], k[4], k[5])
        };
        [
            a.add(c.mul(alpha)).add(f.mul(alpha.mul(alpha))),
            b.add(c.mul(beta))
                .add(e.mul(alpha))
                .add(f.mul(alpha.mul(beta)).scale(2.0)),
            d.add(e.mul(beta)).add(f.mul(beta.mul(beta))),
        ]
    }
}

/// The real roots in `[0, 1]` of `c0 + c1 x + c2 x² = 0`, for every member
/// of the interval coefficients, enclosed (the enclosures may reach outside
/// `[0, 1]`; the callers drop what lies outside the box); `Err(())` when no
/// enclosure is possible (the equation may be degenerate, a value is not
/// finite).
///
/// A leading coefficient that may vanish (interval arithmetic rarely gives
/// an exact 0, even for a conic with no square term) is absorbed: for
/// `x ∈ [0, 1]`, `c2 x² ∈ c2·[0, 1]`, so the roots there solve the linear
/// `(c0 + c2·[0, 1]) + c1 x = 0`.
fn quadratic_roots(c: [Iv; 3]) -> Result<Vec<Iv>, ()> {
    let [c0, c1, c2] = c;
    if !(c0.is_finite() && c1.is_finite() && c2.is_finite()) {
        return Err(());
    }
    if !(c2.lo > 0.0 || c2.hi < 0.0) {
        let c0 = c0.add(c2.mul(Iv::new(0.0, 1.0)));
        if !(c1.lo > 0.0 || c1.hi < 0.0) {
            // No linear term either: roots only if the constant may vanish,
            // and then anywhere.
            return if c0.lo > 0.0 || c0.hi < 0.0 {
                Ok(Vec::new())
            } else {
                Err(())
            };
        }
        return Ok(vec![Iv::point(0.0).sub(c0).div(c1)]);
    }
    let disc = c1.mul(c1).sub(c2.mul(c0).scale(4.0));
    if disc.hi < 0.0 {
        return Ok(Vec::new());
    }
    let root = Iv::new(down(disc.lo.max(0.0).sqrt()).max(0.0), up(disc.hi.sqrt()));
    let two_a = c2.scale(2.0);
    let minus_b = Iv::point(0.0).sub(c1);
    let out = vec![minus_b.add(root).div(two_a), minus_b.sub(root).div(two_a)];
    if out.iter().all(|x| x.is_finite()) {
        Ok(out)
    } else {
        Err(())
    }
}

/// The hybrid clip of the box whose polynomials (`f` then `g`) are the first
/// two blocks of `c`; see the module docs.
pub(super) fn hybrid_spans(c: &[Iv], sh: Shape) -> FatLineClip {
    if sh.m >= STACK || sh.n >= STACK {
        return FatLineClip::Parallel;
    }
    let (Some(strip), Some(conic)) = (Strip::of(&c[..sh.len], sh), Conic::of(&c[sh.len..2 * sh.len], sh)) else {
        return FatLineClip::Parallel;
    };
    match candidates(strip, conic) {
        Ok(cands) => spans_of(&cands, strip, conic),
        Err(()) => FatLineClip::Parallel,
    }
}

fn candidates(strip: Strip, conic: Conic) -> Result<Vec<[Iv; 2]>, ()> {
    let (la, lb, lc, ld) = strip.uncentred();
    let (zero, one) = (Iv::point(0.0), Iv::point(1.0));
    let mut out: Vec<[Iv; 2]> = Vec::with_capacity(48);
    for s in [zero, one] {
        for t in [zero, one] {
            out.push([s, t]);
        }
    }
    let line_rhs = [ld, -ld].map(|d| Iv::point(0.0).sub(la).add(Iv::point(d)));
    let levels = [conic.delta, -conic.delta];
    // Lines on box edges.
    for e in line_rhs {
        for side in [zero, one] {
            if lb.lo != 0.0 || lb.hi != 0.0 {
                out.push([e.sub(lc.mul(side)).div(lb), side]);
            }
            if lc.lo != 0.0 || lc.hi != 0.0 {
                out.push([side, e.sub(lb.mul(side)).div(lc)]);
            }
        }
    }
    // Conic levels on box edges, on the lines, and their tangencies.
    for level in levels {
        let lv = Iv::point(level);
        for side in [zero, one] {
            // t = side: q(s, side) = level (the line t = 0 + 0·s).
            let [c0, c1, c2] = conic.on_line(side, zero, false);
            for s in quadratic_roots([c0.sub(lv), c1, c2])? {
                out.push([s, side]);
            }
            let [c0, c1, c2] = conic.on_line(side, zero, true);
            for t in quadratic_roots([c0.sub(lv), c1, c2])? {
                out.push([side, t]);
            }
        }
        for e in line_rhs {
            // b s + c t = e: solve for the variable with the larger coefficient.
            let (alpha, beta, swap) = if lc.lo.abs() >= lb.lo.abs() && lc.lo != 0.0 {
                (e.div(lc), Iv::point(0.0).sub(lb).div(lc), false)
            } else if lb.lo != 0.0 {
                (e.div(lb), Iv::point(0.0).sub(lc).div(lb), true)
            } else {
                continue;
            };
            let [c0, c1, c2] = conic.on_line(alpha, beta, swap);
            for x in quadratic_roots([c0.sub(lv), c1, c2])? {
                let y = alpha.add(beta.mul(x));
                out.push(if swap { [y, x] } else { [x, y] });
            }
        }
        // Tangency to s = const: ∂q/∂t = C + E s + 2F t = 0.
        let [_, kb, kc, kd, ke, kf] = conic.k;
        for (lin, quad, cross, swap) in [(kc, kf, ke, false), (kb, kd, ke, true)] {
            if quad != 0.0 {
                // t = −(lin + cross·s)/(2 quad) (or s in terms of t).
                let two_q = Iv::point(quad).scale(2.0);
                let alpha = Iv::point(-lin).div(two_q);
                let beta = Iv::point(-cross).div(two_q);
                let [c0, c1, c2] = conic.on_line(alpha, beta, swap);
                for x in quadratic_roots([c0.sub(lv), c1, c2])? {
                    let y = alpha.add(beta.mul(x));
                    out.push(if swap { [y, x] } else { [x, y] });
                }
            } else if cross != 0.0 {
                // The levels may hold a whole line s = −lin/cross: add it.
                let x = Iv::point(-lin).div(Iv::point(cross));
                out.push(if swap {
                    [Iv::new(0.0, 1.0), x]
                } else {
                    [x, Iv::new(0.0, 1.0)]
                });
            } else if lin == 0.0 {
                // q does not depend on this variable: its levels are whole
                // lines x = root of the rest.
                let [c0, c1, c2] = conic.on_line(zero, zero, swap);
                for x in quadratic_roots([c0.sub(lv), c1, c2])? {
                    out.push(if swap {
                        [Iv::new(0.0, 1.0), x]
                    } else {
                        [x, Iv::new(0.0, 1.0)]
                    });
                }
            }
        }
    }
    Ok(out)
}

fn spans_of(cands: &[[Iv; 2]], strip: Strip, conic: Conic) -> FatLineClip {
    let (la, lb, lc, ld) = strip.uncentred();
    let strip_excludes = |p: [Iv; 2]| {
        let v = la.add(lb.mul(p[0])).add(lc.mul(p[1]));
        v.lo > ld || v.hi < -ld
    };
    let mut span = [(f64::INFINITY, f64::NEG_INFINITY); 2];
    for &p in cands {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return FatLineClip::Parallel;
        }
        let outside_box = p.iter().any(|x| x.lo > 1.0 || x.hi < 0.0);
        if outside_box || strip_excludes(p) || conic.excludes(p) {
            continue;
        }
        for d in 0..2 {
            span[d] = (span[d].0.min(p[d].lo), span[d].1.max(p[d].hi));
        }
    }
    if span[0].0 > span[0].1 {
        return FatLineClip::Empty;
    }
    FatLineClip::Spans(span.map(|(lo, hi)| (lo.max(0.0), hi.min(1.0))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_conic_is_fitted_exactly() {
        // g = s² + st − t (bidegree (2, 2)): its own coefficients, so δ ≈ 0.
        let (m, n) = (2, 2);
        let sh = Shape::pair(m, n);
        let g: Vec<Iv> = (0..=m)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| {
                let xx = (i * i.saturating_sub(1)) as f64 / 2.0;
                Iv::point(xx + (i * j) as f64 / 4.0 - j as f64 / 2.0)
            })
            .collect();
        let q = Conic::of(&g, sh).unwrap();
        assert!(q.delta < 1e-14, "{q:?}");
        for (got, want) in q.k.iter().zip([0.0, 0.0, -1.0, 1.0, 1.0, 0.0]) {
            assert!((got - want).abs() < 1e-12, "{:?}", q.k);
        }
    }

    #[test]
    fn quadratic_roots_enclose_both() {
        // (x − 0.25)(x − 0.75) = x² − x + 0.1875.
        let r = quadratic_roots([Iv::point(0.1875), Iv::point(-1.0), Iv::point(1.0)]).unwrap();
        assert!(r.iter().any(|x| x.lo <= 0.25 && 0.25 <= x.hi));
        assert!(r.iter().any(|x| x.lo <= 0.75 && 0.75 <= x.hi));
        assert!(quadratic_roots([Iv::point(1.0), Iv::point(0.0), Iv::point(1.0)])
            .unwrap()
            .is_empty());
        // A leading term that may vanish is absorbed over x ∈ [0, 1]:
        // 1e-20 x² + x − 0.5 has its root near 0.5.
        let r = quadratic_roots([Iv::point(-0.5), Iv::point(1.0), Iv::new(-1e-20, 1e-20)]).unwrap();
        assert!(
            r.len() == 1 && r[0].lo <= 0.5 && 0.5 <= r[0].hi && r[0].wid() < 1e-14,
            "{r:?}"
        );
        assert!(quadratic_roots([Iv::new(-1.0, 1.0), Iv::new(-1e-20, 1e-20), Iv::new(-1e-20, 1e-20)]).is_err());
    }

    #[test]
    fn line_and_circle_clip_around_their_crossing() {
        // f = s − t (bilinear), g = (s − ½)² + (t − ½)² − 1/8 at bidegree (2, 2):
        // they cross at s = t = ½ ± ¼.
        let (m, n) = (2, 2);
        let sh = Shape::pair(m, n);
        let f: Vec<Iv> = (0..=m)
            .flat_map(|i| (0..=n).map(move |j| Iv::point(i as f64 / 2.0 - j as f64 / 2.0)))
            .collect();
        // s² − s + t² − t + 3/8 in Bernstein: s² → i(i−1)/2, s → i/2.
        let g: Vec<Iv> = (0..=m)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| {
                let sq = |k: usize| (k * k.saturating_sub(1)) as f64 / 2.0 - k as f64 / 2.0;
                Iv::point(sq(i) + sq(j) + 0.375)
            })
            .collect();
        let mut c = f;
        c.extend(g);
        let FatLineClip::Spans(sp) = hybrid_spans(&c, sh) else {
            panic!()
        };
        for d in 0..2 {
            assert!(sp[d].0 <= 0.25 && 0.75 <= sp[d].1, "{sp:?}");
            assert!(sp[d].1 - sp[d].0 < 0.6, "{sp:?}");
        }
    }
}
