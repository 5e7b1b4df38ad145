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
mod hull;
mod verifier;

use crate::scalar::geo::Geo;
use candidates::clip_in;
pub use candidates::quadratic_roots_in_unit;
pub use hull::{bezier_bounds, intersect_bounds};
use std::cell::OnceCell;
use verifier::Verifier;

/// `a0 + a1 s + a2 t`.
#[derive(Clone, Copy, Debug)]
pub struct Linear<S> {
    /// `[a0, a1, a2]`.
    pub c: [S; 3],
}

/// `c0 + c1 s + c2 t + c3 s² + c4 s t + c5 t²`.
#[derive(Clone, Copy, Debug)]
pub struct Quadratic<S> {
    /// `[c0, c1, c2, c3, c4, c5]`.
    pub c: [S; 6],
}

impl<G: Geo> Linear<G> {
    /// The monomial form of the degree-1 BB polynomial with float coefficients
    /// `c` (storage order: `f_001, f_100, f_010`) on the tri-box, enclosed in
    /// the geometry kernel.
    pub fn from_bb(c: &[f64]) -> Self {
        debug_assert_eq!(c.len(), 3);
        let [c0, c1, c2] = [c[0], c[1], c[2]].map(G::pt);
        Self {
            c: [c0, c1 - c0, c2 - c0],
        }
    }
}

impl<S: Geo> Linear<S> {
    /// Value at `(s, t)`.
    pub fn eval(&self, s: S, t: S) -> S {
        self.c[0] + self.c[1] * s + self.c[2] * t
    }

    fn shifted(&self, d: f64) -> Self {
        Self {
            c: [self.c[0] - S::pt(d), self.c[1], self.c[2]],
        }
    }
}

impl<G: Geo> Quadratic<G> {
    /// The monomial form of the degree-2 BB polynomial with float coefficients
    /// `c` on the tri-box, enclosed in the geometry kernel: with
    /// `r = 1 − s − t`, `f = f200 s² + f020 t² + f002 r² + 2 f110 st + 2 f101 sr + 2 f011 tr`.
    pub fn from_bb(c: &[f64]) -> Self {
        debug_assert_eq!(c.len(), 6);
        // Storage order: f002, f101, f200, f011, f110, f020.
        let [f002, f101, f200, f011, f110, f020] = [c[0], c[1], c[2], c[3], c[4], c[5]].map(G::pt);
        let two = G::pt(2.0);
        Self {
            c: [
                f002,
                two * (f101 - f002),
                two * (f011 - f002),
                f200 + f002 - two * f101,
                two * (f110 + f002 - f101 - f011),
                f020 + f002 - two * f011,
            ],
        }
    }
}

impl<S: Geo> Quadratic<S> {
    /// Value at `(s, t)`.
    pub fn eval(&self, s: S, t: S) -> S {
        let c = &self.c;
        c[0] + s * (c[1] + c[3] * s + c[4] * t) + t * (c[2] + c[5] * t)
    }

    fn shifted(&self, d: f64) -> Self {
        let mut c = self.c;
        c[0] = c[0] - S::pt(d);
        Self { c }
    }

    /// The lines where the level curves of `Q` are tangent to `s = const`
    /// (`∂Q/∂t = 0`), `t = const` (`∂Q/∂s = 0`) and `w = const`
    /// (`∂Q/∂s = ∂Q/∂t`).
    fn tangency_lines(&self) -> [Linear<S>; 3] {
        let c = &self.c;
        let two = S::pt(2.0);
        [
            Linear {
                c: [c[2], c[4], two * c[5]],
            },
            Linear {
                c: [c[1], two * c[3], c[4]],
            },
            Linear {
                c: [c[1] - c[2], two * c[3] - c[4], c[4] - two * c[5]],
            },
        ]
    }
}

/// `|p| ≤ δ` for a linear or quadratic `p`.
#[derive(Clone, Copy, Debug)]
pub enum Fat<S> {
    /// A fat line: two parallel lines.
    Line(Linear<S>, f64),
    /// A fat conic: two level curves of a quadratic.
    Conic(Quadratic<S>, f64),
}

impl<S: Geo> Fat<S> {
    /// The same fat curve with its coefficients' midpoints (the input of
    /// the float proposal); `None` if one is not finite.
    fn midpoints(&self) -> Option<Fat<f64>> {
        fn mids<S: Geo, const N: usize>(c: [S; N]) -> Option<[f64; N]> {
            let mut out = [0.0; N];
            for (m, x) in out.iter_mut().zip(c) {
                *m = 0.5 * (x.lower() + x.upper());
                if !m.is_finite() {
                    return None;
                }
            }
            Some(out)
        }
        Some(match self {
            Fat::Line(l, d) => Fat::Line(Linear { c: mids(l.c)? }, *d),
            Fat::Conic(q, d) => Fat::Conic(Quadratic { c: mids(q.c)? }, *d),
        })
    }

    fn possibly_contains(&self, s: S, t: S) -> bool {
        let (val, d) = match self {
            Fat::Line(l, d) => (l.eval(s, t), *d),
            Fat::Conic(q, d) => (q.eval(s, t), *d),
        };
        // The float kernel's candidates lie on the boundary curves only up to
        // the rounding of their computation (root solving loses digits near
        // tangency): allow that much on the scale of the curve's terms
        // (`s, t ∈ [0, 1]`), or boundary points are lost. Rigorous kernels
        // carry it in their enclosures.
        let d = if S::RIGOROUS {
            d
        } else {
            let scale = match self {
                Fat::Line(l, _) => l.c.iter().map(|c| c.mag()).sum::<f64>(),
                Fat::Conic(q, _) => q.c.iter().map(|c| c.mag()).sum::<f64>(),
            };
            d + 1e-9 * scale
        };
        val.possibly_le(d) && val.possibly_ge(-d)
    }
}

/// The outcome of a clipping computation in local barycentric coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClipBounds {
    /// Proven: no root in the tri-box.
    Empty,
    /// Every root has `u ≥ mins[0]`, `v ≥ mins[1]`, `w ≥ mins[2]` (each in `[0, 1]`).
    Keep([f64; 3]),
}

struct Bounds {
    mins: [f64; 3],
    any: bool,
}

impl Bounds {
    fn new() -> Self {
        Self {
            mins: [f64::INFINITY; 3],
            any: false,
        }
    }

    /// Whether [`Bounds::add`] of this candidate could change anything: it is
    /// the first one, or it lowers one of the minima. Deciding this before
    /// the (costlier) feasibility test changes no result.
    fn could_lower<S: Geo>(&self, s: S, t: S) -> bool {
        let w = S::pt(1.0) - s - t;
        !self.any || s.lower() < self.mins[0] || t.lower() < self.mins[1] || w.lower() < self.mins[2]
    }

    fn add<S: Geo>(&mut self, s: S, t: S) {
        let w = S::pt(1.0) - s - t;
        self.any = true;
        self.mins[0] = self.mins[0].min(s.lower());
        self.mins[1] = self.mins[1].min(t.lower());
        self.mins[2] = self.mins[2].min(w.lower());
    }

    /// No candidate can change the result any more: it is `Keep([0, 0, 0])`
    /// (`finish` clamps the minima to `[0, 1]`).
    fn settled(&self) -> bool {
        self.any && self.mins.iter().all(|&m| m <= 0.0)
    }

    fn finish(self, rigorous: bool) -> ClipBounds {
        if !self.any {
            return ClipBounds::Empty;
        }
        let m = self.mins.map(|x| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) });
        keep_or_empty(m, rigorous)
    }
}

/// `Keep(m)`, or `Empty` when the bounds are inconsistent (`Σ m > 1`: no point
/// satisfies all three). Rigorous minima are lower bounds, so `Σ m > 1` is a
/// proof; float minima of a converged region can exceed 1 by rounding, so the
/// float kernel needs a margin before it calls the region empty.
fn keep_or_empty(m: [f64; 3], rigorous: bool) -> ClipBounds {
    let margin = if rigorous { 0.0 } else { 1e-9 };
    // Float minima are estimates, not lower bounds: back them off a little so
    // the float iteration does not cut an ulp past the root it converges to.
    let m = m.map(|x| (x - margin).max(0.0));
    let sum = m[0] + m[1] + m[2];
    if sum > 1.0 + margin {
        ClipBounds::Empty
    } else if sum > 1.0 {
        let scale = 1.0 / sum;
        ClipBounds::Keep(m.map(|x| x * scale))
    } else {
        ClipBounds::Keep(m)
    }
}

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
