//! The double-double ball ([`TriBallDD`]): the root polynomial of a solve
//! in compensated arithmetic, for tri-boxes where the float ball's rounding
//! floor stops clipping.

use super::*;

/// A triangular BB polynomial in double-double: coefficient `c = hi + lo`
/// (`|lo| ≤ u|hi|`) up to a radius `r` — the root polynomial from which
/// [`TriBallDD::subdivide`] computes tri-box polynomials whose radius is a few
/// units in the last place of the *tri-box's own* coefficients.
///
/// # Why
/// A float subdivision ([`TriBall::subdivide`]) errs by a few ulps of the
/// root polynomial's largest coefficient, for every tri-box: on a tiny tri-box
/// next to a root, whose coefficients are tiny, that rounding dominates and
/// stops clipping and check-sign (the "rounding floor", amplified by `1/θ`
/// where the curves cross at a small angle `θ`). Computing the same blossoms
/// with compensated arithmetic (error-free products and sums, the errors
/// carried in the low parts) moves that floor to `~100 n u² M₀`, about
/// `1e-30` of the root's scale, and rounding the result to `f64` costs one
/// ulp of each result coefficient — at about ten times the float cost, so the
/// solver uses it only where the float ball is noisy.
#[derive(Clone, Debug)]
pub struct TriBallDD {
    degree: usize,
    hi: Coeffs,
    lo: Coeffs,
    rad: f64,
}

impl TriBallDD {
    /// The float ball `b` as a double-double one (low parts 0).
    pub fn from_ball(b: &TriBall) -> Self {
        Self {
            degree: b.degree,
            hi: b.mid.clone(),
            lo: std::iter::repeat_n(0.0, b.mid.len()).collect(),
            rad: b.rad,
        }
    }

    /// Exact coefficients (storage order, degree `n`) to double-double: `hi`
    /// the nearest float, `lo` an end of the tightest interval around
    /// `c − hi`, the radius that interval's width (so about `u²|c|`).
    pub fn from_rationals(n: usize, coeffs: &[BigRational]) -> Self {
        let (mut hi, mut lo) = (Coeffs::new(), Coeffs::new());
        let mut rad = 0.0f64;
        for c in coeffs {
            let h = crate::scalar::rational_to_f64(c);
            let rest = crate::scalar::rational_to_interval(&(c - BigRational::from_float(h).unwrap_or_default()));
            hi.push(h);
            lo.push(rest.inf());
            rad = rad.max(iv::up(rest.sup() - rest.inf()));
        }
        if !(rad.is_finite() && hi.iter().all(|x| x.is_finite())) {
            return Self::from_ball(&TriBall::unbounded(n));
        }
        Self { degree: n, hi, lo, rad }
    }

    /// The same polynomial scaled by `2^e` (exact unless a part underflows,
    /// which the radius then takes).
    pub fn scaled_pow2(&self, e: i32) -> Self {
        let (h, l) = (
            TriBall::new_raw(self.degree, self.hi.clone(), self.rad),
            TriBall::new_raw(self.degree, self.lo.clone(), 0.0),
        );
        let (h, l) = (h.scaled_pow2(e), l.scaled_pow2(e));
        Self {
            degree: self.degree,
            hi: h.mid,
            lo: l.mid,
            rad: iv::up(h.rad + l.rad),
        }
    }

    #[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
    /// The polynomial on the sub-triangle with vertices `verts`, as
    /// [`TriBall::subdivide`], computed in compensated arithmetic and rounded
    /// to a float ball.
    ///
    /// # One step
    /// With `A = Ah + Al` etc. (`|Al| ≤ u|Ah|`), TwoProd gives
    /// `s·Ah = s1 + e1`, `t·Bh = s2 + e2`, `wh·Ch = s3 + e3` and TwoSum
    /// `s1 + s2 + s3 = h + r1 + r2` exactly; then
    /// ```text
    /// y = s A + t B + w C = h + L + (wl Cl + ew C),
    /// L = r1 + r2 + e1 + e2 + e3 + s Al + t Bl + wh Cl + wl Ch
    /// ```
    /// and `L` is summed in `f64` (ten roundings). Every term of `L` is at
    /// most `u·S·M` (`S = |s| + |t| + |wh| + |wl|`, `M` the input magnitude)
    /// or `|wl|M`, four `u S M` in all. The two terms left out of `L`:
    /// `|wl Cl| ≤ u|wl|M`, and `|ew C| ≤ 2u²(1 + u)⁵ S M` by the bound of
    /// `DdPoint` in `scalar::eft` (not `u|wl|M`: `wl` may be far below `ew/u` when the
    /// last TwoSum of `w` carries). So, with `γ₁₀ ≤ 10u(1 + 11u)`, the step
    /// errs by at most
    /// `γ₁₀(4u S M + |wl| M) + u|wl| M + 2u²(1 + u)⁵ S M ≤ (42.01u² S + 11.01u |wl|) M`
    /// `≤ (44u² S + 13u |wl|) M`, and
    /// `(h, L)` is renormalized exactly by TwoSum. Over the `n` steps of a
    /// coefficient, as for the float ball:
    /// ```text
    /// r' = max |yl| + Ŝⁿ r + n Ŝⁿ⁻¹ (44u² Ŝ + 13u w_l) M₀ (1 + u)³ⁿ
    /// ```
    /// where `yl` are the low parts of the results (their exact distance to
    /// the float midpoints `yh`) and `w_l = max |wl|`.
    pub fn subdivide(&self, verts: &[[f64; 2]; 3]) -> TriBall {
        let [one] = Self::subdivide_all([self], verts);
        one
    }

    /// [`TriBallDD::subdivide`] of two polynomials of the same degree onto
    /// the same sub-triangle in one two-lane pass. Panics on different
    /// degrees (a caller bug).
    pub fn subdivide_pair(f: &TriBallDD, g: &TriBallDD, verts: &[[f64; 2]; 3]) -> (TriBall, TriBall) {
        let [a, b] = Self::subdivide_all([f, g], verts);
        (a, b)
    }

    fn subdivide_all<const L: usize>(polys: [&TriBallDD; L], verts: &[[f64; 2]; 3]) -> [TriBall; L]
    where
        [Dd; L]: Default,
    {
        let n = polys[0].degree;
        assert!(polys.iter().all(|p| p.degree == n), "subdivide_all needs equal degrees");
        let pts = verts.map(DdPoint::new);
        let mut s_max = 0.0f64;
        let mut wl_max = 0.0f64;
        for p in &pts {
            s_max = s_max.max(p.s.abs() + p.t.abs() + p.wh.abs() + p.wl.abs());
            wl_max = wl_max.max(p.wl.abs());
        }
        if !s_max.is_finite() {
            return polys.map(|_| TriBall::unbounded(n));
        }
        let len = tri_len(n);
        let net: SmallVec<[[Dd; L]; 16]> = (0..len).map(|i| polys.map(|p| Dd { h: p.hi[i], l: p.lo[i] })).collect();
        let mut out: SmallVec<[[Dd; L]; 16]> = SmallVec::from_elem([Dd::default(); L], len);
        blossom(&net, n, &pts, &mut out);
        let s_hat = iv::up(s_max);
        let p = if n == 0 { 1.0 } else { s_hat.powi(n as i32 - 1) };
        let growth = 1.0 + gamma(3 * n);
        let mut lane = 0;
        polys.map(|poly| {
            let mid: Coeffs = out.iter().map(|v| v[lane].h).collect();
            let low = out.iter().fold(0.0f64, |m, v| m.max(v[lane].l.abs()));
            lane += 1;
            let rad = if n == 0 {
                poly.rad + low
            } else {
                let m0 = max_abs(&poly.hi) * (1.0 + U);
                let floor = n as f64 * p * (44.0 * U * U * s_hat + 13.0 * U * wl_max) * m0 * growth;
                inflate(low + p * s_hat * poly.rad + floor)
            };
            finish(n, mid, rad)
        })
    }
}
