//! Error-free transformations: the exact rounding errors of a sum and a
//! product, the directed rounding built on them (the interval kernels'
//! endpoints rounded up without switching the FPU's rounding mode), and the
//! double-double values of the ball polynomials' compensated subdivision.
//!
//! `two_sum(a, b) = (s, e)` with `a + b = s + e` exactly (Knuth); `two_prod(a,
//! b) = (p, e)` with `a·b = p + e` exactly (one FMA; away from underflow).

/// `a + b = s + e` exactly (Knuth's TwoSum).
#[inline(always)]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a·b = p + e` exactly (one FMA), away from underflow.
#[inline(always)]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// A vertex in double-double barycentrics: `s`, `t` exact, and
/// `w = 1 − s − t = wh + wl + ew` with
/// ```text
/// |ew| ≤ 2u²(1 + u)⁴ (|t| + |wh| + |wl|)        (u = 2⁻⁵³)
/// ```
/// Derivation ([`DdPoint::new`]): TwoSum gives `1 − s = a + e1` and
/// `a − t = b + e2` exactly, `|e1| ≤ u|a|`, `|e2| ≤ u|b|`; `c = fl(e1 + e2)`
/// rounds once, so `ew = e1 + e2 − c`, `|ew| ≤ u(|e1| + |e2|) ≤ u²(|a| + |b|)`;
/// the last TwoSum `b + c = wh + wl` is exact. With `1 − s = t + w` and
/// `a − t = w − e1`: `|a| ≤ (1 + u)(|t| + |w|)`, `|b| ≤ (1 + u)(|w| + u|a|)`,
/// so `|a| + |b| ≤ (1 + u)³(|t| + 2|w|)`, and `|w| ≤ |wh| + |wl| + |ew|`
/// gives the bound (the `|ew|` on the right costs one more `1 + u`).
/// It is *not* `u|wl|`: that holds only while the last TwoSum does not
/// carry (`wh = b`, `wl = c`); when `c` moves `wh` off `b`, `wl` can be far
/// below `c` (the carry case, tested below).
#[derive(Clone, Copy)]
pub(crate) struct DdPoint {
    pub(crate) s: f64,
    pub(crate) t: f64,
    pub(crate) wh: f64,
    pub(crate) wl: f64,
}

impl DdPoint {
    pub(crate) fn new([s, t]: [f64; 2]) -> Self {
        // 1 − s = a + e1, a − t = b + e2 (both exact), e1 + e2 = c + e3.
        let (a, e1) = two_sum(1.0, -s);
        let (b, e2) = two_sum(a, -t);
        let (wh, wl) = two_sum(b, e1 + e2);
        Self { s, t, wh, wl }
    }
}

/// A double-double value `h + l` (`|l| ≤ u|h|` after renormalization).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Dd {
    pub(crate) h: f64,
    pub(crate) l: f64,
}

/// `r` moved one float towards `+∞` if `err > 0`: the rounded-up value of
/// `r + err` for a nearest `r` with exact error `err`. Only for finite
/// non-zero `r`, or `err = 0` (a non-zero error implies a non-zero result
/// in the checked ranges).
#[inline(always)]
pub(crate) fn round_up(r: f64, err: f64) -> f64 {
    // The sign bit of `0 − err` is set exactly when err > 0 (both zeros give +0).
    let nudge = (0.0 - err).to_bits() >> 63;
    // For r > 0 the next float up has bits + 1; for r < 0, bits − 1.
    let step = 1u64.wrapping_sub((r.to_bits() >> 63) << 1);
    f64::from_bits(r.to_bits().wrapping_add(step & nudge.wrapping_neg()))
}
/// `a + b` rounded up, lane by lane: TwoSum gives the rounding error exactly.
#[inline(always)]
pub(crate) fn add_up(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let s = [a[0] + b[0], a[1] + b[1]];
    let bb = [s[0] - a[0], s[1] - a[1]];
    let e = [
        (a[0] - (s[0] - bb[0])) + (b[0] - bb[0]),
        (a[1] - (s[1] - bb[1])) + (b[1] - bb[1]),
    ];
    [round_up(s[0], e[0]), round_up(s[1], e[1])]
}
/// `a · b` rounded up, lane by lane: one FMA gives the rounding error exactly.
#[inline(always)]
pub(crate) fn mul_up(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let p = [a[0] * b[0], a[1] * b[1]];
    let e = [a[0].mul_add(b[0], -p[0]), a[1].mul_add(b[1], -p[1])];
    [round_up(p[0], e[0]), round_up(p[1], e[1])]
}
/// `if take { x } else { y }` as a bit blend (coefficient signs are
/// effectively random: a branch would mispredict).
#[inline(always)]
pub(crate) fn select(take: bool, x: f64, y: f64) -> f64 {
    let mask = (take as u64).wrapping_neg();
    f64::from_bits((x.to_bits() & mask) | (y.to_bits() & !mask))
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;
    use num_traits::Signed;

    /// The bound of [`DdPoint`] on vertices where the last TwoSum carries
    /// (`wh ≠ fl(1 − s − t)`'s first part) and `|ew| > u|wl|` — the case
    /// the earlier `|ew| ≤ u|wl|` missed — and on a grid of ordinary ones;
    /// `ew` computed exactly.
    #[test]
    fn dd_point_error_bound_holds_in_the_carry_case() {
        let q = |x: f64| BigRational::from_float(x).unwrap();
        let u = f64::EPSILON / 2.0;
        let check = |s: f64, t: f64| -> bool {
            let p = DdPoint::new([s, t]);
            let ew = BigRational::from_integer(1.into()) - q(s) - q(t) - q(p.wh) - q(p.wl);
            let bound = 2.0 * u * u * (1.0 + u).powi(4) * (t.abs() + p.wh.abs() + p.wl.abs());
            assert!(ew.abs() <= q(bound), "s = {s:e}, t = {t:e}: ew = {ew}");
            ew.abs() > q(u * p.wl.abs())
        };
        let carry = [
            (0x3c83980ad596aec6u64, 0xbcd607ade1e8331bu64),
            (0xbfc3eece750ae966, 0x3c9da5252c9c80cb),
            (0xbfd4f6c4b41b4909, 0xbc944ef593ba2e77),
        ];
        for (s, t) in carry {
            let (s, t) = (f64::from_bits(s), f64::from_bits(t));
            let (a, _) = two_sum(1.0, -s);
            let (b, _) = two_sum(a, -t);
            assert_ne!(DdPoint::new([s, t]).wh, b, "not a carry case");
            assert!(check(s, t), "|ew| ≤ u|wl| holds here: not the case tested");
        }
        for i in 0..64 {
            for j in 0..64 {
                let s = (i as f64 / 63.0) * (1.0 + 1e-3 * (j as f64).sin());
                let t = (1.0 - s) * (j as f64 / 63.0) + 1e-18 * i as f64;
                check(s, t);
            }
        }
    }
}
