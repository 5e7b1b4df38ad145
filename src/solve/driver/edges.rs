//! Vanishing domain edges: the strip cut off an edge along which both
//! equations may vanish (a curve of roots), and the size floor of a tri-box.

use crate::poly::{tri_index, TriBall};
use crate::solve::tribox::TriBox;

/// The relative width of the strip cut along an edge where both equations
/// may vanish: `2⁻³⁰` (exact).
pub const EDGE_STRIP: f64 = 1.0 / (1u64 << 30) as f64;

/// Edge coefficients at most this fraction of the largest coefficient count
/// as vanishing ([`vanishing_edges`]): `2⁻³⁶ ≈ 1.5e-11`.
pub const VANISHING: f64 = 1.0 / (1u64 << 36) as f64;

/// Which of the edges `u = 0` (coefficients `i = 0`) and `v = 0` (`j = 0`) of
/// the root triangle carry only coefficients that may be zero or are below
/// [`VANISHING`] of the polynomial's largest, in both `f` and `g`: then both
/// equations (nearly) vanish along that edge, a curve of roots or of near
/// roots (a ray through, or within rounding of, a patch's collapsed edge),
/// which no subdivision resolves quickly.
pub fn vanishing_edges(f: &TriBall, g: &TriBall) -> [bool; 2] {
    let edge = |p: &TriBall, along_v: bool| {
        let n = p.degree();
        let scale = p.mag();
        let r = p.rad();
        let tiny =
            |m: f64| m.abs().partial_cmp(&r) != Some(std::cmp::Ordering::Greater) || m.abs() + r <= VANISHING * scale;
        (0..=n).all(|k| {
            let idx = if along_v {
                tri_index(n, 0, k)
            } else {
                tri_index(n, k, 0)
            };
            tiny(p.mid()[idx])
        })
    };
    [edge(f, true) && edge(g, true), edge(f, false) && edge(g, false)]
}

/// The root tri-box and the system on it: the unit triangle, or, where both
/// equations may vanish along the edge `u = 0` or `v = 0`, the verified
/// triangle `{u ≥ η, v ≥ η'}` ([`EDGE_STRIP`]) with the cut strips pushed to
/// `strips` as undecided regions.
///
/// Why: along such an edge the iteration would cover a curve of roots with
/// ever smaller tri-boxes until the budget ends the run. Cutting is sound:
/// the strips are reported, not discarded. (The edge `w = 0` is not cut: its
/// strip has no thin bounding box; a curve of roots there still ends in a
/// budget, reported as incomplete.)
pub(super) fn cut_vanishing_edges(
    f: &TriBall,
    g: &TriBall,
    strips: &mut Vec<[[f64; 2]; 2]>,
) -> (TriBox, TriBall, TriBall) {
    let unit = TriBox::unit();
    let cut = vanishing_edges(f, g);
    let mins = [0, 1].map(|k| if cut[k] { EDGE_STRIP } else { 0.0 });
    if !cut.contains(&true) {
        return (unit, f.clone(), g.clone());
    }
    let Some(tb) = unit.clip([mins[0], mins[1], 0.0]) else {
        return (unit, f.clone(), g.clone());
    };
    if cut[0] {
        strips.push([[0.0, EDGE_STRIP], [0.0, 1.0]]);
    }
    if cut[1] {
        strips.push([[0.0, 1.0], [0.0, EDGE_STRIP]]);
    }
    let (fa, fb) = TriBall::subdivide_pair(f, g, &tb.verts);
    (tb, fa, fb)
}

/// A tri-box whose vertices are a few ulps apart cannot be clipped or split
/// reliably any more.
pub(super) fn too_small(tb: &TriBox) -> bool {
    let scale = tb.verts.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
    tb.diam() < 8.0 * f64::EPSILON * scale
}
