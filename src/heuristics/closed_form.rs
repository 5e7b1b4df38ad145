//! The closed forms of Christensen (2008), *Ray intersections*: a 2D ray
//! against a line segment (§1.1) and a quadratic Bézier curve (§1.2), and a
//! 3D ray against the quadratic Bézier curve swept along `z` (§2.1).
//!
//! Each is computed in `f64` exactly as the paper writes it — the same
//! formulas in the same order, the textbook quadratic formula included — so
//! that what rounding does to them can be measured against the certified
//! solver (`papers/ray-intersections-2008/` in the repository). Nothing here
//! is a proof: a returned hit is what the formula gives, and an empty list
//! does not mean "no intersection".
//!
//! Conventions throughout: the ray is `r(s) = o + s d`, `s ≥ 0`; curve
//! parameters are `t ∈ [0, 1]`; a hit is kept, as in the paper, when its
//! computed `t` lies in `[0, 1]`, its `s ≥ 0` (and, on the swept patch, its
//! `u ∈ [0, 1]`). Where a formula divides by zero, or a quotient is not
//! finite (a divisor tiny enough to overflow it), the result is
//! [`ClosedForm::Failed`] with the reason, never a NaN hit.
//!
//! The PDF's text is garbled in four places, re-derived here:
//! * (1) and (7) assume "`d_x ≠ 0 ∧ d_y ≠ 0`", but the text then treats
//!   `d_x = 0`: the condition is `d ≠ 0`, i.e. `d_x ≠ 0 ∨ d_y ≠ 0`;
//! * after (9), "the values of t found then have matching values of t given
//!   by (10)" means matching values of `s`;
//! * §2.1 looks for "`p(u, v) = r(s)`": the patch is `p(t, u)`;
//! * §2.1 applies (9) and (8) to the ray's projection `(o_x, o_y) +
//!   s (d_x, d_y)` on the `xy`-plane (the first two components of
//!   `p(t, u) = r(s)` are exactly the 2D problem, with the same `s`), with
//!   (10) for `s` when `d_x = 0`; when `d_x = d_y = 0` every coefficient of
//!   (9) vanishes, a case the paper does not treat
//!   ([`FormulaFailure::AlongSweep`]).

use crate::error::{Error, Result};
use glam::{DVec2, DVec3};

/// A hit on a segment or curve: its parameter `t` and the ray's `s`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CurveHit {
    /// The segment's or curve's parameter.
    pub t: f64,
    /// The ray parameter: the hit is `o + s d`.
    pub s: f64,
}

/// A hit on the swept quadratic Bézier patch `p(t, u) = (b(t), e u)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PatchHit {
    /// The curve's parameter.
    pub t: f64,
    /// The sweep parameter.
    pub u: f64,
    /// The ray parameter: the hit is `o + s d`.
    pub s: f64,
}

/// Why a closed form gives no answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum FormulaFailure {
    /// The segment formula's denominator `d_x (a_y − b_y) − d_y (a_x − b_x)`
    /// is zero: the ray is parallel to the segment (or on its line).
    Parallel,
    /// The quadratic's leading coefficient `A` is zero (the ray parallel to
    /// the curve's axis direction `p₀ − 2p₁ + p₂`, or a straight curve): the
    /// quadratic formula divides by `2A = 0`.
    LeadingZero,
    /// The 3D ray runs along the sweep (`d_x = d_y = 0`): every coefficient
    /// of (9) is zero and (8), (10) divide by zero.
    AlongSweep,
    /// A computed `t`, `s` or `u` is infinite or NaN: a divisor so small
    /// that the quotient overflowed, or an overflow in the products.
    NotFinite,
}

impl FormulaFailure {
    /// The stable machine-readable code: `"parallel"`, `"leading_zero"`,
    /// `"along_sweep"` or `"not_finite"`.
    pub fn code(self) -> &'static str {
        match self {
            FormulaFailure::Parallel => "parallel",
            FormulaFailure::LeadingZero => "leading_zero",
            FormulaFailure::AlongSweep => "along_sweep",
            FormulaFailure::NotFinite => "not_finite",
        }
    }
}

/// What a closed form gives: its hits (possibly none), or why it gives
/// nothing.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ClosedForm<H> {
    /// The hits the formula keeps, in the order it computes them.
    Hits(Vec<H>),
    /// The formula divides by zero or overflows.
    Failed(FormulaFailure),
}

impl<H> ClosedForm<H> {
    /// The hits (none for a failure).
    pub fn hits(&self) -> &[H] {
        match self {
            ClosedForm::Hits(h) => h,
            ClosedForm::Failed(_) => &[],
        }
    }

    /// Why the formula failed (`None` if it gave hits, or none).
    pub fn failure(&self) -> Option<FormulaFailure> {
        match self {
            ClosedForm::Hits(_) => None,
            ClosedForm::Failed(f) => Some(*f),
        }
    }
}

fn finite2(what: &str, v: &[DVec2]) -> Result<()> {
    if v.iter().all(|p| p.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite(format!(
            "a point or direction of the {what} is NaN or infinite"
        )))
    }
}

fn nonzero_dir(d: DVec2) -> Result<()> {
    if d == DVec2::ZERO {
        Err(Error::Degenerate("the ray direction is zero".into()))
    } else {
        Ok(())
    }
}

/// Ray `o + s d` against the segment `l(t) = t a + (1 − t) b`, `t ∈ [0, 1]`
/// (Christensen 2008, §1.1, Eqs. (1)–(2)):
///
/// ```text
/// t = (d_x (o_y − b_y) − d_y (o_x − b_x)) / (d_x (a_y − b_y) − d_y (a_x − b_x))
/// s = (l_x(t) − o_x) / d_x          (Eq. (2); (l_y(t) − o_y) / d_y when d_x = 0)
/// ```
/// and the hit is kept when `t ∈ [0, 1]` and `s ≥ 0`. Note the paper's
/// orientation: `t = 1` at `a`, `t = 0` at `b`.
///
/// Rounded: plain `f64` in the paper's order; no error bound. The
/// denominator is `|d| |a − b| sin α` for a ray at angle `α` to the segment
/// and cancels: `t` carries a relative error of order `ε/α` (a hit found but
/// misplaced from `α ≈ 1e-12` on), and a hit within rounding of `t = 0`,
/// `t = 1` or `s = 0` may be dropped or kept wrongly. Degenerate:
/// a zero denominator ([`FormulaFailure::Parallel`]), a non-finite quotient
/// ([`FormulaFailure::NotFinite`]). Errors: NaN or infinite input
/// ([`Error::NonFinite`]), `d = 0` or `a = b` ([`Error::Degenerate`]).
///
/// ```
/// use rootclip::glam::DVec2;
/// use rootclip::heuristics::ray_segment_2d;
/// // The ray from (0, −1) upwards meets the segment from (1, 1) to (−1, 1)
/// // at its midpoint, s = 2.
/// let h = ray_segment_2d(DVec2::new(0.0, -1.0), DVec2::Y, DVec2::new(1.0, 1.0), DVec2::new(-1.0, 1.0))?;
/// assert_eq!(h.hits()[0].t, 0.5);
/// assert_eq!(h.hits()[0].s, 2.0);
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn ray_segment_2d(o: DVec2, d: DVec2, a: DVec2, b: DVec2) -> Result<ClosedForm<CurveHit>> {
    finite2("ray or segment", &[o, d, a, b])?;
    nonzero_dir(d)?;
    if a == b {
        return Err(Error::Degenerate("the segment's ends coincide".into()));
    }
    let den = d.x * (a.y - b.y) - d.y * (a.x - b.x);
    if den == 0.0 {
        return Ok(ClosedForm::Failed(FormulaFailure::Parallel));
    }
    let t = (d.x * (o.y - b.y) - d.y * (o.x - b.x)) / den;
    let (lx, ly) = (t * a.x + (1.0 - t) * b.x, t * a.y + (1.0 - t) * b.y);
    let s = if d.x != 0.0 { (lx - o.x) / d.x } else { (ly - o.y) / d.y };
    if !(t.is_finite() && s.is_finite()) {
        return Ok(ClosedForm::Failed(FormulaFailure::NotFinite));
    }
    let keep = (0.0..=1.0).contains(&t) && s >= 0.0;
    Ok(ClosedForm::Hits(if keep {
        vec![CurveHit { t, s }]
    } else {
        Vec::new()
    }))
}

/// The roots `t ∈ [0, 1]` of (9) with their `s ≥ 0` from (8) or (10): the
/// shared core of the 2D curve and the swept patch.
fn quadratic_hits(o: DVec2, d: DVec2, p: [DVec2; 3]) -> std::result::Result<Vec<CurveHit>, FormulaFailure> {
    let [p0, p1, p2] = p;
    // Eq. (6): b(t) = (p0 − 2p1 + p2) t² + (2p1 − 2p0) t + p0.
    let a2 = p0 - 2.0 * p1 + p2;
    let a1 = 2.0 * p1 - 2.0 * p0;
    // Eq. (9).
    let qa = d.x * a2.y - d.y * a2.x;
    let qb = d.x * a1.y - d.y * a1.x;
    let qc = d.x * (p0.y - o.y) - d.y * (p0.x - o.x);
    if qa == 0.0 {
        return Err(FormulaFailure::LeadingZero);
    }
    let disc = qb * qb - 4.0 * qa * qc;
    let ts: Vec<f64> = if disc > 0.0 {
        let r = disc.sqrt();
        vec![(-qb + r) / (2.0 * qa), (-qb - r) / (2.0 * qa)]
    } else if disc == 0.0 {
        vec![-qb / (2.0 * qa)]
    } else if disc < 0.0 {
        Vec::new()
    } else {
        return Err(FormulaFailure::NotFinite); // NaN: ∞ − ∞ in the products
    };
    let mut hits = Vec::with_capacity(ts.len());
    for t in ts {
        if !t.is_finite() {
            return Err(FormulaFailure::NotFinite);
        }
        if !(0.0..=1.0).contains(&t) {
            continue;
        }
        // Eq. (8), or (10) when d_x = 0.
        let s = if d.x != 0.0 {
            (a2.x * t * t + a1.x * t + p0.x - o.x) / d.x
        } else {
            (a2.y * t * t + a1.y * t + p0.y - o.y) / d.y
        };
        if !s.is_finite() {
            return Err(FormulaFailure::NotFinite);
        }
        if s >= 0.0 {
            hits.push(CurveHit { t, s });
        }
    }
    Ok(hits)
}

/// Ray `o + s d` against the quadratic Bézier curve
/// `b(t) = (1 − t)² p₀ + 2t(1 − t) p₁ + t² p₂`, `t ∈ [0, 1]` (Christensen
/// 2008, §1.2, Eqs. (3)–(10)). Substituting `s` from the first component
/// into the second, `d_y (b_x(t) − o_x) = d_x (b_y(t) − o_y)`, gives
///
/// ```text
/// A t² + B t + C = 0,   A = d_x (p0y − 2 p1y + p2y) − d_y (p0x − 2 p1x + p2x)
///                       B = d_x (2 p1y − 2 p0y) − d_y (2 p1x − 2 p0x)
///                       C = d_x (p0y − o_y) − d_y (p0x − o_x)
/// t = (−B ± √(B² − 4AC)) / (2A)            (the textbook formula)
/// s = (b_x(t) − o_x) / d_x                  (Eq. (8); (10) with y when d_x = 0)
/// ```
/// with `b_x(t)` evaluated in the power form (6). Roots with `t ∉ [0, 1]`
/// or `s < 0` are dropped; a zero discriminant gives one hit.
///
/// Rounded: plain `f64`; `B² − 4AC` cancels for a grazing ray (at distance
/// `h`, the roots move by about `ε/√h`, and at `h ≲ ε` two hits become none
/// or none two) and `−B ± √…` for a small root (a hit within `ε` of `t = 0`
/// comes out as exactly `t = 0` and is kept even when it lies outside); the
/// range tests on rounded `t` and `s` decide hits within rounding of an end
/// either way — which is what `papers/ray-intersections-2008/` measures. Degenerate: `A = 0`
/// ([`FormulaFailure::LeadingZero`]: the paper has no linear case), a
/// non-finite root or `s` ([`FormulaFailure::NotFinite`]). Errors: NaN or
/// infinite input ([`Error::NonFinite`]), `d = 0` ([`Error::Degenerate`]).
///
/// ```
/// use rootclip::glam::DVec2;
/// use rootclip::heuristics::ray_quadratic_bezier_2d;
/// // The parabola through (−1, 1), (0, −1), (1, 1) is y = x² (in b(t):
/// // x = 2t − 1); the ray y = 1/4 from the left meets it at x = ∓1/2.
/// let p = [DVec2::new(-1.0, 1.0), DVec2::new(0.0, -1.0), DVec2::new(1.0, 1.0)];
/// let hits = ray_quadratic_bezier_2d(DVec2::new(-2.0, 0.25), DVec2::X, p)?;
/// let mut t: Vec<f64> = hits.hits().iter().map(|h| h.t).collect();
/// t.sort_by(f64::total_cmp);
/// assert_eq!(t, [0.25, 0.75]);
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn ray_quadratic_bezier_2d(o: DVec2, d: DVec2, p: [DVec2; 3]) -> Result<ClosedForm<CurveHit>> {
    finite2("ray or curve", &[o, d, p[0], p[1], p[2]])?;
    nonzero_dir(d)?;
    Ok(match quadratic_hits(o, d, p) {
        Ok(h) => ClosedForm::Hits(h),
        Err(f) => ClosedForm::Failed(f),
    })
}

/// Ray `o + s d` in 3D against the patch swept by the quadratic Bézier
/// curve `b(t)` (control points `p` in the `xy`-plane) a distance `e` along
/// `+z`: `p(t, u) = (b_x(t), b_y(t), e u)`, `t, u ∈ [0, 1]` (Christensen
/// 2008, §2.1, Eq. (11)). The first two components of `p(t, u) = r(s)` are
/// the 2D problem of [`ray_quadratic_bezier_2d`] for the projected ray
/// `(o_x, o_y) + s (d_x, d_y)` (same `A`, `B`, `C`, same `s`); the third
/// gives
///
/// ```text
/// u = (o_z + d_z s) / e                                       (Eq. (11))
/// ```
/// Hits with `t ∉ [0, 1]`, `s < 0` or `u ∉ [0, 1]` are dropped (the paper's
/// order: `t`, then `s`, then `u`). The patch is the tensor patch of bidegree
/// `(2, 1)` with control points `(p_i, 0)` and `(p_i, e)`.
///
/// Rounded as [`ray_quadratic_bezier_2d`], plus one rounding in `u`; for a
/// ray nearly along the sweep, direction `(ε_d w, d_z)`, Eq. (8) or (10)
/// divides by a component of size `ε_d`, so `s` and `u` carry errors of
/// order `ε/ε_d` (right `t`, wrong `u`).
/// Degenerate: `d_x = d_y = 0` ([`FormulaFailure::AlongSweep`]: the ray
/// lies on a vertical line, which meets the patch in a segment or not at
/// all), `A = 0`, non-finite results. Errors: NaN or infinite input
/// ([`Error::NonFinite`]), `d = 0` or `e = 0` ([`Error::Degenerate`]).
///
/// ```
/// use rootclip::glam::{DVec2, DVec3};
/// use rootclip::heuristics::ray_swept_quadratic_patch_3d;
/// let p = [DVec2::new(-1.0, 1.0), DVec2::new(0.0, -1.0), DVec2::new(1.0, 1.0)];
/// // Along x at height y = 1/4, rising in z: hits at x = −1/2 (z = 0.75)
/// // and x = 1/2 (z = 1.25) on the patch of height e = 2.
/// let o = DVec3::new(-2.0, 0.25, 0.0);
/// let d = DVec3::new(1.0, 0.0, 0.5);
/// let hits = ray_swept_quadratic_patch_3d(o, d, p, 2.0)?;
/// assert_eq!(hits.hits().len(), 2);
/// assert!(hits.hits().iter().any(|h| h.t == 0.25 && h.u == 0.375 && h.s == 1.5));
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn ray_swept_quadratic_patch_3d(o: DVec3, d: DVec3, p: [DVec2; 3], e: f64) -> Result<ClosedForm<PatchHit>> {
    if !(o.is_finite() && d.is_finite() && e.is_finite()) {
        return Err(Error::NonFinite("the ray or the sweep is NaN or infinite".into()));
    }
    finite2("curve", &p)?;
    if d == DVec3::ZERO {
        return Err(Error::Degenerate("the ray direction is zero".into()));
    }
    if e == 0.0 {
        return Err(Error::Degenerate("the sweep distance e is zero".into()));
    }
    if d.x == 0.0 && d.y == 0.0 {
        return Ok(ClosedForm::Failed(FormulaFailure::AlongSweep));
    }
    let hits = match quadratic_hits(o.truncate(), d.truncate(), p) {
        Ok(h) => h,
        Err(f) => return Ok(ClosedForm::Failed(f)),
    };
    let mut out = Vec::with_capacity(hits.len());
    for CurveHit { t, s } in hits {
        let u = (o.z + d.z * s) / e;
        if !u.is_finite() {
            return Ok(ClosedForm::Failed(FormulaFailure::NotFinite));
        }
        if (0.0..=1.0).contains(&u) {
            out.push(PatchHit { t, u, s });
        }
    }
    Ok(ClosedForm::Hits(out))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failures_and_errors() {
        let (o, d) = (DVec2::ZERO, DVec2::X);
        let seg = |a, b| ray_segment_2d(o, d, a, b).unwrap().failure();
        assert_eq!(
            seg(DVec2::new(0.0, 1.0), DVec2::new(1.0, 1.0)),
            Some(FormulaFailure::Parallel)
        );
        assert!(ray_segment_2d(o, DVec2::ZERO, DVec2::X, DVec2::Y).is_err());
        assert!(ray_segment_2d(o, d, DVec2::X, DVec2::X).is_err());
        assert!(ray_segment_2d(DVec2::NAN, d, DVec2::X, DVec2::Y).is_err());
        // A straight "curve": A = 0 for every ray.
        let line = [DVec2::ZERO, DVec2::new(1.0, 1.0), DVec2::new(2.0, 2.0)];
        let r = ray_quadratic_bezier_2d(DVec2::new(0.0, 1.0), DVec2::X, line).unwrap();
        assert_eq!(r.failure(), Some(FormulaFailure::LeadingZero));
        let p = [DVec2::new(-1.0, 1.0), DVec2::new(0.0, -1.0), DVec2::new(1.0, 1.0)];
        let up = ray_swept_quadratic_patch_3d(DVec3::ZERO, DVec3::Z, p, 1.0).unwrap();
        assert_eq!(up.failure(), Some(FormulaFailure::AlongSweep));
        assert!(ray_swept_quadratic_patch_3d(DVec3::ZERO, DVec3::X, p, 0.0).is_err());
        // A divisor so small that t overflows.
        let tiny = ray_quadratic_bezier_2d(DVec2::new(0.0, 0.25), DVec2::new(1e-311, 1.0), p).unwrap();
        assert_eq!(tiny.failure(), Some(FormulaFailure::NotFinite));
        assert_eq!(FormulaFailure::NotFinite.code(), "not_finite");
    }

    #[test]
    fn tangent_ray_gives_one_hit_from_a_zero_discriminant() {
        // y = x² and the ray y = 0 touch at t = 1/2.
        let p = [DVec2::new(-1.0, 1.0), DVec2::new(0.0, -1.0), DVec2::new(1.0, 1.0)];
        let h = ray_quadratic_bezier_2d(DVec2::new(-2.0, 0.0), DVec2::X, p).unwrap();
        assert_eq!(h.hits(), &[CurveHit { t: 0.5, s: 2.0 }]);
    }
}
