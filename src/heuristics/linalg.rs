//! The small linear systems of the iterations, with one notion of
//! "singular within rounding" for all of them.

use glam::DVec3;

/// A system counts as singular when the sine of the angle between its
/// columns (for three columns: the volume they span relative to the
/// product of their lengths) is at most this: singular within rounding,
/// whatever the scale of the patch.
pub(super) const SINGULAR: f64 = 64.0 * f64::EPSILON;

/// `x > floor`: a size clearly above its degenerate floor. NaN is never
/// above, so a NaN size counts as degenerate (the callers test
/// `!above(..)` on purpose rather than `≤`).
pub(super) fn above(x: f64, floor: f64) -> bool {
    x > floor
}

/// `x` with `x₀c₀ + x₁c₁ + x₂c₂ = b` (Cramer's rule), or `None` when the
/// columns are singular within [`SINGULAR`].
pub(super) fn solve3(c: [DVec3; 3], b: DVec3) -> Option<DVec3> {
    let cross = c[1].cross(c[2]);
    let det = c[0].dot(cross);
    let scale = c[0].length() * c[1].length() * c[2].length();
    if !above(det.abs(), SINGULAR * scale) {
        return None;
    }
    Some(DVec3::new(b.dot(cross), c[0].dot(b.cross(c[2])), c[0].dot(c[1].cross(b))) / det)
}

/// `(x₀, x₁)` with `x₀a + x₁b` the projection of `r` on the plane of `a, b`:
/// the normal equations `[a·a a·b; a·b b·b] x = [r·a, r·b]` (the form of
/// Eqs. (24) and (32)), or `None` when `a ∥ b` within [`SINGULAR`].
pub(super) fn project2(a: DVec3, b: DVec3, r: DVec3) -> Option<[f64; 2]> {
    let (e, f, g) = (a.dot(a), a.dot(b), b.dot(b));
    // e·g − f² = |a × b|², computed as such to avoid the cancellation.
    let det = a.cross(b).length_squared();
    if !above(det, SINGULAR * SINGULAR * e * g) {
        return None;
    }
    let (ra, rb) = (r.dot(a), r.dot(b));
    Some([(g * ra - f * rb) / det, (e * rb - f * ra) / det])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_and_refuses_singular_systems() {
        let c = [DVec3::X, DVec3::new(1.0, 2.0, 0.0), DVec3::new(0.0, 1.0, 4.0)];
        let x = DVec3::new(0.5, -1.0, 2.0);
        let b = c[0] * x.x + c[1] * x.y + c[2] * x.z;
        assert!((solve3(c, b).unwrap() - x).length() < 1e-15);
        assert_eq!(solve3([DVec3::X, DVec3::Y, DVec3::X + DVec3::Y], b), None);
        let p = project2(DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::new(3.0, 2.0, 7.0)).unwrap();
        assert!((p[0] - 1.0).abs() < 1e-15 && (p[1] - 2.0).abs() < 1e-15);
        assert_eq!(project2(DVec3::X, 2.0 * DVec3::X, DVec3::Y), None);
    }
}
