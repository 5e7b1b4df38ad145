//! Fat curves and the clipping bounds they imply (Liu et al. 2016, §2.3.2–2.3.3).
//!
//! Everything here lives in a tri-box's local Cartesian coordinates `(s, t)`:
//! the tri-box is `{s, t ≥ 0, s + t ≤ 1}` and its barycentric coordinates are
//! `(u, v, w) = (s, t, 1 − s − t)`.
//!
//! A *fat curve* of `f` is `{ |p| ≤ δ }` for a low-degree `p` with
//! `|f − p| ≤ δ` on the tri-box, so it contains `f = 0` there. The feasible
//! region is `R = tri-box ∩ fat curves`, and the clip keeps
//! `{u ≥ u_min, v ≥ v_min, w ≥ w_min}` with `u_min ≤ min_R u`, etc.
//!
//! The stages live in files of their own: `candidates` computes the bounds
//! from enclosures of every candidate minimizer (why that candidate set is
//! complete, and why the bounds are rigorous, is argued there); `verifier`
//! proves a float clip's slivers free of `R` (its soundness argument is on
//! `Verifier::sliver_free`); `hull` holds the Bézier hull bounds
//! ([`bezier_bounds`]).
//!
//! # Float proposes, intervals verify
//! Enclosing every candidate costs several times the float clip. So the
//! rigorous kernel first takes the float clip's minima, widened by
//! [`VERIFY_MARGIN`] of the kept size, and proves each removed sliver free of
//! `R` (`Verifier::sliver_free`, a few dozen interval operations: the fat
//! line's strip swept along its lines, or across them when it is parallel
//! to the sliver's side); only where such a proof fails are the candidate
//! enclosures computed.

mod candidates;
mod curves;
mod hull;
mod verifier;

use crate::scalar::geo::Geo;
use candidates::clip_in;
#[cfg(any(test, feature = "internals"))]
pub use candidates::quadratic_roots_in_unit;
use curves::keep_or_empty;
pub use curves::{ClipBounds, Fat, Linear, Quadratic};
pub use hull::{bezier_bounds, intersect_bounds};
use std::cell::OnceCell;
use verifier::Verifier;

/// The clipping bounds of `R = tri-box ∩ fats` (see the module docs).
///
/// The candidates are computed in the geometry kernel `G`: for the certified
/// solver the branchless outward-rounded
/// [`GeoIv`](crate::scalar::geo::GeoIv), whose enclosures are as rigorous as inari's
/// (a few floats wider) at a fraction of the cost.
pub fn clip_against_fat_curves<G: Geo>(fats: &[Fat<G>]) -> ClipBounds {
    if G::RIGOROUS {
        if let Some(verified) = proposed_and_verified(fats) {
            return verified;
        }
    }
    clip_in(fats)
}

/// The relative margin a verified float clip gives up: the kept tri-box is
/// the float one widened by `VERIFY_MARGIN` of its size on each clipped side.
pub const VERIFY_MARGIN: f64 = 1.0 / (1u64 << 20) as f64;

/// Float proposes, intervals verify: the clip of the float kernel, widened
/// by [`VERIFY_MARGIN`], if [`Verifier::sliver_free`] proves every clipped
/// sliver free of `R`; `Empty` if it proves the whole tri-box free; `None`
/// (no claim) when a proof fails, and the caller computes the
/// enclosure-based bounds of [`clip_in`].
///
/// Both answers are as rigorous as [`clip_in`]'s in a rigorous kernel: a
/// bound `m_k` is returned only with a proof that no point of the tri-box
/// with barycentric coordinate `k` at most `m_k` lies in both fat regions.
/// The float clip only chooses which `m_k` to try. The first fat curve must
/// be a line (it is for every fat-curve method: `f^α` or `f̂`).
fn proposed_and_verified<G: Geo>(fats: &[Fat<G>]) -> Option<ClipBounds> {
    verified(fats, float_claim(fats)?)
}

/// `claim` if [`Verifier::sliver_free`] proves it for `fats` (see
/// [`proposed_and_verified`]).
fn verified<G: Geo>(fats: &[Fat<G>], claim: ClipBounds) -> Option<ClipBounds> {
    let bounds = claim_bounds(claim);
    if bounds.iter().all(|&m| m <= 0.0) {
        return Some(claim);
    }
    let verifier = Verifier::of(fats)?;
    let proven = match claim {
        // One free sliver that is the whole tri-box suffices.
        ClipBounds::Empty => (0..3).any(|k| verifier.sliver_free(k, 1.0)),
        ClipBounds::Keep(_) => (0..3).all(|k| bounds[k] <= 0.0 || verifier.sliver_free(k, bounds[k])),
    };
    proven.then_some(claim)
}

/// The float kernel's clip of `fats` (on their midpoints), widened by
/// [`VERIFY_MARGIN`] of the kept size: the claim a proof is to establish.
/// `None` when the midpoints are not finite, the float clip keeps nothing
/// measurable, or `fats` is not a pair.
fn float_claim<G: Geo>(fats: &[Fat<G>]) -> Option<ClipBounds> {
    let [a, b] = fats else {
        return None;
    };
    match clip_in::<f64>(&[a.midpoints()?, b.midpoints()?]) {
        ClipBounds::Empty => Some(ClipBounds::Empty),
        ClipBounds::Keep(m) => {
            let size = 1.0 - (m[0] + m[1] + m[2]);
            // Also NaN: no proposal.
            if size.is_nan() || size <= 0.0 {
                return None;
            }
            let margin = VERIFY_MARGIN * size + 1e-15;
            Some(ClipBounds::Keep(m.map(|x| (x - margin).max(0.0))))
        }
    }
}

/// The slivers a claim removes: `{σ_k ≤ m_k}`, the whole tri-box (`m = 1`)
/// for `Empty`.
fn claim_bounds(claim: ClipBounds) -> [f64; 3] {
    match claim {
        ClipBounds::Empty => [1.0; 3],
        ClipBounds::Keep(m) => m,
    }
}

/// The kept tri-box is more than half as wide as the clipped one (it is
/// similar to it with ratio `1 − Σ m`).
fn keeps_over_half(bounds: ClipBounds) -> bool {
    matches!(bounds, ClipBounds::Keep(m) if 1.0 - m.iter().sum::<f64>() > 0.5)
}

/// [`clip_against_fat_curves`] of `first`, and where it keeps more than half
/// of the tri-box ([`keeps_over_half`]) also of `second()` (the same system
/// with the roles of `f` and `g` swapped), intersected; the flag says whether
/// `second` was used.
///
/// In a rigorous kernel the two float claims are combined first and each
/// side is proven once, by the fat-curve pair whose claim sets it (the other
/// pair's smaller bound is the second try): a root lies in both pairs' fat
/// regions, so a sliver free of either pair's region holds no root. Where
/// both proofs of a side fail, each pair's clip is computed on its own from
/// its float claim (proven, else by enclosures) and the two are intersected,
/// as in the float kernel.
pub fn clip_against_fat_curves_swapped<G: Geo>(
    first: &[Fat<G>],
    second: impl FnOnce() -> Option<[Fat<G>; 2]>,
) -> (ClipBounds, bool) {
    let unclipped = ClipBounds::Keep([0.0; 3]);
    let both = |a: ClipBounds, b: ClipBounds| (intersect_bounds(a, b, G::RIGOROUS), true);
    // The float kernel, or no float claim: the (enclosure) clip of `first`.
    let claim_a = if G::RIGOROUS { float_claim(first) } else { None };
    let Some(claim_a) = claim_a else {
        let a = clip_in(first);
        return if keeps_over_half(a) {
            both(a, second().map_or(unclipped, |p| clip_against_fat_curves(&p)))
        } else {
            (a, false)
        };
    };
    // A pair's own clip from its float claim: proven, else the enclosures.
    let own = |fats: &[Fat<G>], claim| verified(fats, claim).unwrap_or_else(|| clip_in(fats));
    if !keeps_over_half(claim_a) {
        return (own(first, claim_a), false);
    }
    let Some(pair_b) = second() else {
        return (own(first, claim_a), true);
    };
    let Some(claim_b) = float_claim(&pair_b) else {
        return both(own(first, claim_a), clip_in(&pair_b));
    };
    let (ma, mb) = (claim_bounds(claim_a), claim_bounds(claim_b));
    // Each pair's verifier is built when a side first needs it.
    type Lazy<'a, G> = (&'a OnceCell<Option<Verifier<G>>>, &'a [Fat<G>]);
    let (cell_a, cell_b) = (OnceCell::new(), OnceCell::new());
    let (va, vb): (Lazy<G>, Lazy<G>) = ((&cell_a, first), (&cell_b, &pair_b));
    let free = |(v, fats): Lazy<G>, k: usize, m: f64| {
        v.get_or_init(|| Verifier::of(fats))
            .as_ref()
            .is_some_and(|v| v.sliver_free(k, m))
    };
    if claim_a == ClipBounds::Empty || claim_b == ClipBounds::Empty {
        let empty = (0..3).any(|k| {
            (claim_a == ClipBounds::Empty && free(va, k, 1.0)) || (claim_b == ClipBounds::Empty && free(vb, k, 1.0))
        });
        return if empty {
            (ClipBounds::Empty, true)
        } else {
            both(own(first, claim_a), own(&pair_b, claim_b))
        };
    }
    let mut m = [0.0; 3];
    for k in 0..3 {
        // The larger bound first, by its own pair; then the smaller.
        let (hi, lo) = if ma[k] >= mb[k] {
            ((va, ma[k]), (vb, mb[k]))
        } else {
            ((vb, mb[k]), (va, ma[k]))
        };
        m[k] = if hi.1 <= 0.0 || free(hi.0, k, hi.1) {
            hi.1
        } else if lo.1 <= 0.0 || free(lo.0, k, lo.1) {
            lo.1
        } else {
            return both(own(first, claim_a), own(&pair_b, claim_b));
        };
    }
    (keep_or_empty(m, true), true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::point;

    #[test]
    fn strip_clip_is_rigorous() {
        // f = s − 0.3 (exact line), δ = 0: all roots have u = 0.3.
        let l = Linear {
            c: [point(-0.3), point(1.0), point(0.0)],
        };
        let ClipBounds::Keep(m) = clip_against_fat_curves(&[Fat::Line(l, 0.0)]) else {
            panic!()
        };
        assert!(m[0] <= 0.3 && m[0] > 0.29);
        assert_eq!(m[1], 0.0);
        assert!(m[2] <= 0.0 + 1e-15);
    }
}
