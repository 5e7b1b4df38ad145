//! The precision a tri-box's polynomials are computed in ([`Precision`]:
//! float balls, compensated, exact), and when a step recomputes them more
//! precisely.

use super::estimates::{kappa_of, CentreJets};
use super::state::{Ctx, Exact, ExactPair, Leaf, Precision, KAPPA_PROBE};
use crate::poly::dyadic::subdivide_dyadic;
use crate::poly::{TriBall, TriBallDD, TriBezier};
use crate::scalar::geo::Geo;
use crate::solve::tribox::TriBox;
use num_rational::BigRational;

/// Below this diameter a stalled tri-box is recomputed more precisely
/// ([`Precision`]: float, then compensated, then exact): float balls carry
/// ~1e-16 absolute rounding from the root triangle's scale, which near a
/// tangential intersection (small angle θ) limits clipping to ~1e-16/θ;
/// compensated balls carry a few ulps of their own (tiny) coefficients plus
/// ~1e-30 of the root's, exact ones only their final rounding.
pub const EXACT_BELOW: f64 = 1e-6;

/// Rounding noise (the ball's diameter) above [`NOISE_RATIO`] of the largest
/// coefficient: the rounding inherited from the root triangle's scale (a few
/// ulps of the *root's* coefficients, while a small tri-box's coefficients
/// are small) starts to limit clipping.
fn noisy(p: &TriBall) -> bool {
    2.0 * p.rad() > NOISE_RATIO * p.mag()
}

/// The smallest tri-box a clip of `item` can keep around a transversal root
/// with its coefficients' noise, estimated: each fat curve is at least the
/// ball's diameter `2r` wide, a strip `2r / |∇p|` wide in the tri-box's
/// coordinates (gradient of the midpoint polynomial at the centre), and two
/// strips at angle `θ` meet in a region about `(w_f + w_g) / sin θ` across;
/// times the tri-box's diameter. `∞` where the gradients vanish or are
/// parallel (a double root, a tangency: always worth recomputing).
///
/// Near the end of a run to `ε = 1e-12` this is 2e-15 … 5e-14 on the
/// paper's examples with float balls, but 9e-13 at Example 3 (k = 5)'s
/// nearly tangential root (sin θ ≈ 4e-3): there the compensated
/// coefficients save two tri-boxes, elsewhere they bought nothing the clips
/// needed.
fn clip_floor(item: &Leaf, jets: &CentreJets) -> f64 {
    let (a, b) = (jets.a, jets.b);
    let (na, nb) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
    let sin = (a[0] * b[1] - a[1] * b[0]).abs() / (na * nb);
    let floor = item.tb.diam() * (2.0 * item.fa.rad() / na + 2.0 * item.fb.rad() / nb) / sin;
    if floor.is_nan() {
        f64::INFINITY
    } else {
        floor
    }
}

/// A noisy float ball ([`noisy`]) is kept while its [`clip_floor`] is below
/// this fraction of the run's `ε` (see [`float_suffices`]).
const FLOOR_MARGIN: f64 = 1.0 / 16.0;

/// Whether a tri-box with noisy float balls can do without the compensated
/// recomputation: its [`clip_floor`] is below [`FLOOR_MARGIN`] of `ε` (the
/// clips still reach `ε`) *and* the system is nearly linear on it
/// ([`newton_kappa`](super::newton_kappa) below [`KAPPA_PROBE`]: at most one
/// root, simple, where Krawczyk contracts). The second condition keeps the
/// precise coefficients wherever the run works on more than a clip's
/// convergence — near-parallel curves, clusters, close pairs of roots —
/// where the sign tests, the separating combination and the singular floor
/// ([`singular_floor`](super::singular_floor)) need them (the referee found
/// runs to `ε = 1e-6` on curves 1e-9 apart that certified fewer roots
/// without it). The estimates only decide when to pay for precision, never
/// what is proven; a tri-box that stalls after all is recomputed then (the
/// stalled branch of [`step`](super::step::step)).
fn float_suffices(item: &Leaf, eps: f64) -> bool {
    let jets = CentreJets::of(&item.fa, &item.fb);
    clip_floor(item, &jets) < FLOOR_MARGIN * eps && kappa_of(&jets) < KAPPA_PROBE
}

/// A clip of a tri-box of diameter `h` across a transversal root can shrink it
/// to about `ρ·h`, where `ρ` is the relative noise of the coefficients
/// (the fat curves are at least that wide). Recomputing from the exact input
/// when `ρ > 1e-9` below [`EXACT_BELOW`] keeps that floor under
/// `1e-9 · 1e-6 = 1e-15`, below every `ε` the paper's tables use, and where
/// the curves meet at a small angle the exact coefficients are what lets
/// clipping continue at all.
const NOISE_RATIO: f64 = 1e-9;

impl Ctx<'_> {
    /// The root pair in double-double: from the exact input when there is
    /// one, else the float balls themselves; scaled like `f`, `g`.
    fn dd(&mut self) -> &[TriBallDD; 2] {
        if self.dd.is_none() {
            let e = self.out.scale_exp;
            let pair = match self.exact {
                Exact::Rational([fe, ge]) => {
                    [fe, ge].map(|p| TriBallDD::from_rationals(p.degree(), p.coeffs()).scaled_pow2(e))
                }
                Exact::Floats | Exact::None => [&self.f, &self.g].map(TriBallDD::from_ball),
            };
            self.dd = Some(pair);
        }
        self.dd.as_ref().expect("just built")
    }

    /// The exact input, if there is one and its budget is not spent.
    fn exact_left(&self) -> bool {
        !matches!(self.exact, Exact::None) && self.out.counters.exact_boxes < self.limits.max_exact
    }

    /// The exact input pair (unscaled), built on first use for
    /// [`Exact::Floats`] from the balls' midpoints scaled back (exactly: the
    /// run checked that the scaling lost nothing).
    fn exact_pair(&mut self) -> Option<&ExactPair> {
        match self.exact {
            Exact::Rational(p) => Some(p),
            Exact::None => None,
            Exact::Floats => {
                if self.exact_floats.is_none() {
                    let e = self.out.scale_exp;
                    let back = |b: &TriBall| {
                        let b = b.scaled_pow2(-e);
                        let c = b
                            .mid()
                            .iter()
                            .map(|&m| BigRational::from_float(m).unwrap_or_default())
                            .collect();
                        TriBezier::new(b.degree(), c).expect("same length")
                    };
                    self.exact_floats = Some([back(&self.f), back(&self.g)]);
                }
                self.exact_floats.as_ref()
            }
        }
    }
}

/// The pair on `tb` at `precision` (counted): by float or compensated ball
/// subdivision of the root pair, or from the exact input (enclosed, then
/// scaled like the run's system). Exact falls back to compensated when the
/// exact input or its budget is gone.
pub(super) fn restrict_pair(cx: &mut Ctx, precision: Precision, tb: &TriBox) -> (TriBall, TriBall, Precision) {
    match precision {
        Precision::Exact if cx.exact_left() => {
            cx.out.counters.exact_boxes += 1;
            let e = cx.out.scale_exp;
            let [fe, ge] = cx.exact_pair().expect("exact_left");
            // Integer arithmetic over common denominators (no gcds).
            let enclose = |p: &TriBezier<BigRational>| match subdivide_dyadic(p, &tb.verts) {
                Some(c) => TriBall::enclose_rationals(p.degree(), &c).scaled_pow2(e),
                None => TriBall::unbounded(p.degree()),
            };
            (enclose(fe), enclose(ge), Precision::Exact)
        }
        Precision::Exact | Precision::Compensated => {
            cx.out.counters.compensated_boxes += 1;
            let [f, g] = cx.dd();
            let (fa, fb) = TriBallDD::subdivide_pair(f, g, &tb.verts);
            (fa, fb, Precision::Compensated)
        }
        Precision::Float => {
            let (fa, fb) = TriBall::subdivide_pair(&cx.f, &cx.g, &tb.verts);
            (fa, fb, Precision::Float)
        }
    }
}

/// The next precision for a tri-box whose polynomials are too noisy: always
/// compensated after float; exact after compensated when the exact input is
/// there with budget left and the tri-box is below [`EXACT_BELOW`]. `None`
/// if there is nothing better.
pub(super) fn finer(cx: &Ctx, precision: Precision, diam: f64) -> Option<Precision> {
    match precision {
        Precision::Float => Some(Precision::Compensated),
        Precision::Compensated if cx.exact_left() && diam < EXACT_BELOW => Some(Precision::Exact),
        _ => None,
    }
}

/// Whether a rigorous run should recompute a tri-box's coefficients more
/// precisely: `Some(true)` when a sign is hidden by the radius
/// ([`TriBall::sign_hidden`]: exact coefficients prove their signs one by one
/// at any size, within the exact budget — a sparse system whose small terms
/// are far below the rounding of its large ones), `Some(false)` when the
/// coefficients are noisy relative to their values ([`noisy`], which
/// matters on small tri-boxes) and the float balls do not suffice
/// ([`float_suffices`]), `None` otherwise and always for the float kernel.
fn needs_finer<G: Geo>(item: &Leaf, eps: f64) -> Option<bool> {
    if !G::RIGOROUS {
        return None;
    }
    if item.fa.sign_hidden() || item.fb.sign_hidden() {
        return Some(true);
    }
    ((noisy(&item.fa) || noisy(&item.fb)) && !float_suffices(item, eps)).then_some(false)
}

/// `item` recomputed more precisely (same tri-box, same level) before the
/// clip is spoiled by rounding, as long as a finer precision helps
/// ([`needs_finer`], [`finer`]); `diam` is the tri-box's diameter.
pub(super) fn at_working_precision<G: Geo>(cx: &mut Ctx, mut item: Leaf, diam: f64) -> Leaf {
    while let Some(hidden) = needs_finer::<G>(&item, cx.limits.eps) {
        let Some(next) = finer(cx, item.precision, if hidden { 0.0 } else { diam }) else {
            break;
        };
        let (fa, fb, precision) = restart_pair(cx, next, &item.tb);
        if precision <= item.precision {
            break;
        }
        item = Leaf {
            fa,
            fb,
            precision,
            ..item
        };
    }
    item
}

/// [`restrict_pair`] at `next`, a finer precision than the tri-box had,
/// counted as a restart.
pub(super) fn restart_pair(cx: &mut Ctx, next: Precision, tb: &TriBox) -> (TriBall, TriBall, Precision) {
    if next == Precision::Exact {
        cx.out.counters.exact_restarts += 1;
    } else {
        cx.out.counters.compensated_restarts += 1;
    }
    restrict_pair(cx, next, tb)
}

#[cfg(test)]
mod tests {
    use super::super::tests::ball;
    use super::*;
    use crate::scalar::geo::GeoIv;

    /// The clip floor against values worked by hand on the unit triangle
    /// (diameter √2) with radius `r` on both balls: `√2 · (2r/|∇f| +
    /// 2r/|∇g|) / sin θ` — `√2 · 4r` for `u`, `v` (θ = 90°), `√2 · (2r + 2r/√2)
    /// / sin 45°` for `u`, `u + v`; ∞ for parallel gradients and for a
    /// vanishing one. And the gate: a noisy ball is recomputed for an `ε`
    /// near its floor, not for one far above it unless the system is far
    /// from linear on the tri-box.
    #[test]
    fn clip_floor_by_hand() {
        let r = 1e-9;
        let leaf = |f: &str, g: &str| {
            let noisy = |e: &str| TriBall::new(2, ball(e).mid(), r).unwrap();
            Leaf {
                tb: TriBox::unit(),
                node: 0,
                fa: noisy(f),
                fb: noisy(g),
                precision: Precision::Float,
            }
        };
        let clip_floor = |item: &Leaf| clip_floor(item, &CentreJets::of(&item.fa, &item.fb));
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y;
        let s2 = 2f64.sqrt();
        let right = clip_floor(&leaf("u - 1/3", "v - 1/4"));
        assert!(close(right, s2 * 4.0 * r), "{right}");
        let slanted = clip_floor(&leaf("u - 1/3", "u + v - 1/2"));
        assert!(close(slanted, s2 * (2.0 * r + 2.0 * r / s2) * s2), "{slanted}");
        assert_eq!(clip_floor(&leaf("u - 1/3", "2*u - 1/2")), f64::INFINITY);
        assert_eq!(clip_floor(&leaf("1/3", "v - 1/4")), f64::INFINITY);
        // Coefficients up to 2/3 with noise 2e-9 > 1e-9 · 2/3: noisy; the
        // floor 5.7e-9 matters for ε = 1e-8, not for ε = 1e-6.
        let item = leaf("u - 1/3", "v - 1/4");
        assert!(noisy(&item.fa));
        assert_eq!(needs_finer::<GeoIv>(&item, 1e-8), Some(false));
        assert_eq!(needs_finer::<GeoIv>(&item, 1e-6), None);
        assert_eq!(needs_finer::<f64>(&item, 1e-8), None);
        // Far from linear (κ = 3, see `newton_kappa_by_hand`), the precise
        // coefficients are kept whatever the floor.
        let curved = leaf("u^2 + v^2 - 1/4", "u - v");
        assert!(noisy(&curved.fa) && clip_floor(&curved) < 1e-7);
        assert_eq!(needs_finer::<GeoIv>(&curved, 1e-6), Some(false));
    }
}
