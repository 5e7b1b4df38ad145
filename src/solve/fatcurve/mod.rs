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
//! # Why the candidate set is complete
//! `R` is compact; a minimizer `p*` of a linear function `ℓ` (here `u`, `v` or
//! `w`) over `R` lies on the boundary. Either `p*` is on two constraint curves
//! (an intersection: the paper's types 1–3 and the triangle vertices), or on
//! one curve at a smooth point where `∇ℓ ∥ ∇(curve)`. On a line that means the
//! line is a level set of `ℓ`, and then the end points of that boundary piece —
//! intersections again — are minimizers too; on a conic it is a tangency point
//! (type 4) or the conic's centre (a singular point of a degenerate level set).
//! So `min_R ℓ = min` over the *feasible* candidates of these kinds.
//!
//! # Rigor
//! With a rigorous kernel ([`GeoIv`](super::num::GeoIv)) every candidate is an enclosure of the exact
//! candidate of the exact constraint curves, feasibility is tested as
//! "possibly feasible", and the bound is the lower end of the enclosures, so
//! `u_min` is a rigorous lower bound. Where an enclosure cannot be bounded
//! (nearly parallel lines, a nearly degenerate quadratic) it is clamped to
//! `[0, 1]` — always valid, because feasible points have `s, t ∈ [0, 1]` —
//! which only weakens the clip. If no candidate is possibly feasible, `R` is
//! empty: the tri-box holds no root.
//!
//! # Float proposes, intervals verify
//! Enclosing every candidate costs several times the float clip. So the
//! rigorous kernel first takes the float clip's minima, widened by
//! [`VERIFY_MARGIN`] of the kept size, and proves each removed sliver free of
//! `R` (`Verifier::sliver_free`, a few dozen interval operations: the fat
//! line's strip swept along its lines, or across them when it is parallel
//! to the sliver's side); only where such a proof fails are the candidate
//! enclosures computed.

use super::num::Geo;
use crate::poly::{tri_indices, TriBall};
use crate::scalar::iv;
use crate::scalar::Sign;
use smallvec::SmallVec;
use std::cell::{Cell, OnceCell};

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
/// [`GeoIv`](super::num::GeoIv), whose enclosures are as rigorous as inari's
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

/// The data of [`Verifier::sliver_free`] shared by the three slivers of one
/// clip: the fat line `|L| ≤ δ_a`, `L = l0 + l1 s + l2 t`, and the other fat
/// curve `|P| ≤ δ_b` as a quadratic `P` (a line has zero second-order terms),
/// with the products of `∇²P / 2` its proofs use.
struct Verifier<G> {
    l: [G; 3],
    da: f64,
    /// `[−δ_a, δ_a]`.
    lambda: G,
    /// `P` (a line as a quadratic with zero second-order terms).
    q: Quadratic<G>,
    db: f64,
    /// The strip's direction `v = (l2, −l1)`.
    v: (G, G),
    /// `(∇²P / 2) v`.
    hv: (G, G),
    /// `vᵀ (∇²P / 2) v`.
    vhv: G,
    /// `wᵀ (∇²P / 2) w` for the directions `w` along `u = const`
    /// (`(0, 1)`), `v = const` (`(1, 0)`) and `w = const` (`(1, −1)`).
    hw: [G; 3],
    /// What is left of [`CLEAR_BUDGET`] in the current proof.
    budget: Cell<u32>,
}

impl<G: Geo> Verifier<G> {
    /// The verifier of a fat-curve pair whose first curve is a line.
    fn of(fats: &[Fat<G>]) -> Option<Self> {
        match fats {
            [Fat::Line(line, da), other] => Some(Self::new(line, *da, other)),
            _ => None,
        }
    }

    fn new(line: &Linear<G>, da: f64, other: &Fat<G>) -> Self {
        let zero = G::pt(0.0);
        let (q, db) = match other {
            Fat::Line(l, db) => ([l.c[0], l.c[1], l.c[2], zero, zero, zero], *db),
            Fat::Conic(q, db) => (q.c, *db),
        };
        let quadratic = Quadratic { c: q };
        let [_, l1, l2] = line.c;
        let v = (l2, -l1);
        let c4h = q[4] * G::pt(0.5);
        let hv = (q[3] * v.0 + c4h * v.1, c4h * v.0 + q[5] * v.1);
        Verifier {
            l: line.c,
            da,
            lambda: G::pt(-da).hull(G::pt(da)),
            q: quadratic,
            db,
            v,
            hv,
            vhv: v.0 * hv.0 + v.1 * hv.1,
            hw: [q[5], q[3], q[3] - q[4] + q[5]],
            budget: Cell::new(CLEAR_BUDGET),
        }
    }

    /// `P` and `∇P` at `(s, t)`, sharing the products: with `a = c3 s`,
    /// `b = c4 t`, `c = c5 t`, `d = c4 s`, `i = c1 + a + b` and `j = c2 + c`,
    /// `P = c0 + s i + t j`, `∂P/∂s = i + a`, `∂P/∂t = j + c + d` (six
    /// products and eight sums; value and gradient apart take ten products).
    fn jet(&self, (s, t): (G, G)) -> (G, G, G) {
        let c = &self.q.c;
        let (a, b, cc, d) = (c[3] * s, c[4] * t, c[5] * t, c[4] * s);
        let i = c[1] + a + b;
        let j = c[2] + cc;
        (c[0] + s * i + t * j, i + a, j + cc + d)
    }

    /// `aᵀ (∇²P / 2) b`.
    fn half_hessian(&self, a: (G, G), b: (G, G)) -> G {
        let c = &self.q.c;
        c[3] * a.0 * b.0 + c[4] * G::pt(0.5) * (a.0 * b.1 + a.1 * b.0) + c[5] * a.1 * b.1
    }

    /// Proves (`true`) that no point of the tri-box with barycentric
    /// coordinate `σ = (u, v, w)[k] ≤ m` lies both in the fat line and in the
    /// other fat curve; `false` means "not proven".
    ///
    /// # The argument
    /// In coordinates `(σ, τ)` (`τ = v` for `k = 0`, else `u`) the tri-box
    /// is `T = {σ, τ ≥ 0, σ + τ ≤ 1}` and `L = l0' + lσ σ + lτ τ`. Either
    /// `L`'s values at the four corners of the (convex) sliver
    /// `Ω0 = T ∩ {σ ≤ m}` lie beyond `δ_a` on one side, and the strip misses
    /// it; or, with `lτ ≠ 0` proven, the strip is swept by the parallel lines
    /// `L = λ`, `|λ| ≤ δ_a`, which run along `d = ±v / lτ` (`dσ/dh = 1`). From
    /// a point `p` of `Ω = Ω0 ∩ strip` follow `p + h d`, `h ≥ 0`: it stays on
    /// its line, so it leaves `Ω` through an *exit piece*: the end segment
    /// `σ = m` (within `T`), or the part of edge `τ = 0` or `σ + τ = 1` in
    /// the strip with `σ ≤ m` (an exit only if the lines cross it outward).
    /// So `p = x − h d` for an exit point `x` and `0 ≤ h ≤ σ(x)`, and since
    /// `P` has degree ≤ 2, `P(x − h d) = E − D h + C h²` exactly, with
    /// `E = P(x)`, `D = ∇P(x)·d`, `C = dᵀ(∇²P/2)d`. Each piece is a segment
    /// `x0 + μ f`; `E` and `D` are enclosed over it by their (exact) Taylor
    /// expansions at `x0`, and [`bounded_away`] proves `E − D h + C h² > δ_b`
    /// (or `< −δ_b`) on `[0, σ_max]`. Then no point of `Ω` has `|P| ≤ δ_b`.
    /// The sweep is tried first over the *slab* `{0 ≤ σ ≤ m}` of the strip,
    /// a superset of `Ω` that ignores the tri-box's edges: every path then
    /// runs `h ≤ m` from the end line, and one piece is the proof, with no
    /// exit lengths and no edge pieces. Where `L` takes all of
    /// `[−δ_a, δ_a]` on both sides `σ = 0` and `σ = m` of the sliver
    /// ([`Verifier::strip_spans`], the usual case) the slab is `Ω` itself;
    /// elsewhere the sweep with exits follows a failed try. (Together about
    /// 10% of a certified solve of Example 3.)
    /// A strip (nearly) parallel to the end segment, `lτ` not proven
    /// non-zero, is swept across instead ([`Verifier::swept_across`]), and,
    /// where that fails, along its lines with `dτ/dh = 1`
    /// ([`Verifier::swept_along_tau`]); both need `lσ ≠ 0`.
    fn sliver_free(&self, k: usize, m: f64) -> bool {
        let line = self.sliver_line(k, m);
        let da = self.da;
        let corners = [line.l0, line.top, line.base, line.far];
        if corners.iter().all(|x| x.lower() > da) || corners.iter().all(|x| x.upper() < -da) {
            return true;
        }
        self.budget.set(CLEAR_BUDGET);
        if line.lt.nonzero() {
            self.swept_along_sigma(k, m, line)
        } else {
            self.swept_across(k, m, line) || (line.ls.nonzero() && self.swept_along_tau(k, m, line))
        }
    }

    /// `L` in the frame of sliver `k` ([`Verifier::frame_line`]) with its
    /// values at the corners of the sliver `{σ ≤ m}`, computed once for
    /// the corner test and the sweeps.
    fn sliver_line(&self, k: usize, m: f64) -> SliverLine<G> {
        let (l0, ls, lt) = self.frame_line(k);
        let sig_m = G::pt(m);
        let base = l0 + ls * sig_m;
        SliverLine {
            l0,
            ls,
            lt,
            top: l0 + lt,
            base,
            far: base + lt * (G::pt(1.0) - sig_m),
        }
    }

    /// `L = l0' + lσ σ + lτ τ` in the frame of sliver `k` (see
    /// [`frame_point`]): `(l0', lσ, lτ)`.
    fn frame_line(&self, k: usize) -> (G, G, G) {
        let [a0, a1, a2] = self.l;
        match k {
            0 => (a0, a1, a2),
            1 => (a0, a2, a1),
            _ => (a0 + a2, -a2, a1 - a2),
        }
    }

    /// [`Verifier::sliver_free`] with `lτ ≠ 0`: the strip's lines run along
    /// `d` with `dσ/dh = 1`, so `h ≤ σ(x)`.
    fn swept_along_sigma(&self, k: usize, m: f64, line: SliverLine<G>) -> bool {
        let SliverLine {
            l0,
            ls,
            lt,
            top,
            base,
            far,
        } = line;
        let (zero, one) = (G::pt(0.0), G::pt(1.0));
        let sig_m = G::pt(m);
        let r = one / lt;
        let r2 = square(r);
        // d = v / σ(v) with σ(v) = lτ, except −lτ for k = 1.
        let sign = |x: G| if k == 1 { -x } else { x };
        let c = self.vhv * r2;
        let slope = -ls * r;
        // The end line σ = m, where L = λ at τ = (λ − base) / lτ; along it
        // x = x0 + μ w r, w = (0, 1), (1, 0) or (1, −1), expanded at λc
        // (τ0 = (λc − base) / lτ).
        let end_piece = |lc: G| {
            let tau0 = (lc - base) * r;
            let (p, gs, gt) = self.jet(frame_point(k, sig_m, tau0));
            let (gw, hwv) = match k {
                0 => (gt, self.hv.1),
                1 => (gs, self.hv.0),
                _ => (gs - gt, self.hv.0 - self.hv.1),
            };
            let gv = gs * self.v.0 + gt * self.v.1;
            let piece = Piece {
                p,
                b: gw * r,
                a: self.hw[k] * r2,
                d0: sign(gv * r),
                d1: sign(G::pt(2.0) * hwv * r2),
                c,
                db: self.db,
            };
            (piece, tau0)
        };
        // The slab: a point x of `Ω` lies on the level line `L = L(x)`,
        // which meets the end line after `h = m − σ(x) ∈ [0, m]`, and
        // `L(x)` lies in the hull Λ' of `L` at the sliver's four corners
        // (the sliver is convex, `L` linear), within `[−δ_a, δ_a]`: one piece
        // over Λ' with `h ≤ m`, exits ignored, covers `Ω` (with the slab of
        // the strip beyond the tri-box's edges, where the lines leave it).
        // Where `L` spans `[−δ_a, δ_a]` on both sides `σ = 0` and `σ = m`
        // within the tri-box ([`Verifier::strip_spans`], the usual case), the
        // strip crosses the slab inside the tri-box (convex, so the level
        // lines between stay in it): Λ' is all of `[−δ_a, δ_a]`, the slab is
        // `Ω` itself, no edge is an exit and this piece is the whole proof.
        // Elsewhere the slab may reach beyond an edge, where `P` may vanish:
        // it gets [`SLAB_TRY_BUDGET`] halvings, then the sweep with exits.
        let both = self.strip_spans((l0, top)) && self.strip_spans((base, far));
        let lam = if both {
            Some(self.lambda)
        } else {
            clamp_hull(l0.hull(top).hull(base).hull(far), self.lambda)
        };
        let Some(lam) = lam else { return true };
        let lc = if both {
            zero
        } else {
            G::pt(0.5 * (lam.lower() + lam.upper()))
        };
        let (piece, _) = end_piece(lc);
        if !both {
            self.budget.set(SLAB_TRY_BUDGET);
        }
        if piece.clear(lam - lc, &|_: G| sig_m, SPLITS, &self.budget) {
            return true;
        }
        if both {
            return false;
        }
        self.budget.set(CLEAR_BUDGET);
        // The end segment: σ = m, L = λ between `base` and `far` (τ from 0
        // to 1 − m), |λ| ≤ δ_a, expanded at the middle λc of that range.
        if let Some(lam) = clamp_hull(base.hull(far), self.lambda) {
            let lc = G::pt(0.5 * (lam.lower() + lam.upper()));
            let (piece, tau0) = end_piece(lc);
            // Back along d from x, σ falls by h and τ by slope·h: the path
            // leaves the tri-box (and never returns) at τ = 0 or σ + τ = 1.
            let h_max = |mu: G| {
                let tau = tau0 + mu * r;
                let mut h = m;
                if slope.lower() > 0.0 {
                    h = h.min((G::pt(tau.upper()) / G::pt(slope.lower())).upper());
                }
                let grow = -(one + slope);
                if grow.lower() > 0.0 {
                    h = h.min(((one - sig_m - G::pt(tau.lower())) / G::pt(grow.lower())).upper());
                }
                path_bound(h, m)
            };
            if !piece.clear(lam - lc, &h_max, SPLITS, &self.budget) {
                return false;
            }
        }
        // The edges τ = 0 (an exit where τ falls along d: lσ/lτ > 0) and
        // σ + τ = 1 (where σ + τ grows: 1 − lσ/lτ > 0), parametrized by σ
        // ∈ [0, m], which bounds h.
        let dir = (sign(self.v.0 * r), sign(self.v.1 * r));
        let by_sigma = |sig: G| path_bound(sig.upper(), m);
        let range = zero.hull(sig_m);
        (slope.lower() >= 0.0 || self.edge_clear(k, ((zero, zero), (one, zero)), (l0, ls), range, dir, c, &by_sigma))
            && ((one + slope).upper() <= 0.0
                || self.edge_clear(k, ((zero, one), (one, -one)), (top, ls - lt), range, dir, c, &by_sigma))
    }

    /// Whether `L` takes every value of `[−δ_a, δ_a]` on a side of the slab
    /// `0 ≤ σ ≤ m` within the tri-box, given `L` at the side's ends: `l0'`
    /// and `l0' + lτ` (`σ = 0`, `τ ∈ [0, 1]`) or `base` and `far` (`σ = m`,
    /// `τ ∈ [0, 1 − m]`), for every member of the enclosures.
    fn strip_spans(&self, (a, b): (G, G)) -> bool {
        let da = self.da;
        a.upper().min(b.upper()) <= -da && a.lower().max(b.lower()) >= da
    }

    /// [`Verifier::sliver_free`] with `lσ ≠ 0` (for a strip parallel, or
    /// nearly, to the end segment, where `lτ` is not proven non-zero): the
    /// strip's lines run along `d = (e, 1)` in `(σ, τ)`, `e = −lτ/lσ`, so
    /// `h ≤ τ(x)`. The exits are the edge `σ + τ = 1` (where `1 + e > 0`),
    /// `σ = 0` (where `e < 0`) and the end segment `σ = m` (where `e > 0`);
    /// `τ` grows along `d`, so `τ = 0` is never one.
    fn swept_along_tau(&self, k: usize, m: f64, line: SliverLine<G>) -> bool {
        let SliverLine {
            lt, ls, top, base, l0, ..
        } = line;
        let (zero, one) = (G::pt(0.0), G::pt(1.0));
        let sig_m = G::pt(m);
        let e = -lt / ls;
        let dir = frame_dir(k, e, one);
        let c = self.half_hessian(dir, dir);
        let by_tau = |tau: G| path_bound(tau.upper(), 1.0);
        let by_sigma = |sig: G| path_bound((one - sig).upper(), 1.0);
        let up = (zero, one);
        ((one + e).upper() <= 0.0
            || self.edge_clear(
                k,
                ((zero, one), (one, -one)),
                (top, ls - lt),
                zero.hull(sig_m),
                dir,
                c,
                &by_sigma,
            ))
            && (e.lower() >= 0.0 || self.edge_clear(k, ((zero, zero), up), (l0, lt), zero.hull(one), dir, c, &by_tau))
            && (e.upper() <= 0.0
                || self.edge_clear(
                    k,
                    ((sig_m, zero), up),
                    (base, lt),
                    zero.hull(one - sig_m),
                    dir,
                    c,
                    &by_tau,
                ))
    }

    /// [`Verifier::sliver_free`] across the strip, for one (nearly) parallel
    /// to the end segment (`lτ` not proven non-zero), where the strip's own
    /// lines run along the end segment and `P`'s extremum on them lies
    /// inside the sliver: `d = (1, 0)` in `(σ, τ)`, so `h ≤ σ(x)`. The path
    /// now leaves the strip too: the exits are the end segment, the edge
    /// `σ + τ = 1` and the strip's side `L = ±δ_a` where `±lσ > 0`, taken
    /// (for `lσ ≠ 0`) as `σ = (±δ_a − l0' − lτ τ) / lσ`, `τ ∈ [0, 1 − σ]`
    /// (a superset: points beyond the sliver only add checks); with `lσ`
    /// not proven non-zero, no proof.
    fn swept_across(&self, k: usize, m: f64, line: SliverLine<G>) -> bool {
        let SliverLine {
            lt, ls, top, base, l0, ..
        } = line;
        let (zero, one) = (G::pt(0.0), G::pt(1.0));
        let sig_m = G::pt(m);
        let dir = frame_dir(k, one, zero);
        let c = self.half_hessian(dir, dir);
        let by_sigma = |sig: G| path_bound(sig.upper(), m);
        let by_m = |_: G| sig_m;
        let up = (zero, one);
        if !ls.nonzero()
            || !self.edge_clear(
                k,
                ((sig_m, zero), up),
                (base, lt),
                zero.hull(one - sig_m),
                dir,
                c,
                &by_m,
            )
            || !self.edge_clear(
                k,
                ((zero, one), (one, -one)),
                (top, ls - lt),
                zero.hull(sig_m),
                dir,
                c,
                &by_sigma,
            )
        {
            return false;
        }
        let r = one / ls;
        let f = (-lt * r, one);
        for lam in [self.da, -self.da] {
            // The side's outward normal is ±∇L: an exit where ±lσ > 0.
            let exit = if lam > 0.0 { ls.upper() > 0.0 } else { ls.lower() < 0.0 };
            if !exit {
                continue;
            }
            // σ at τ = 0, and its range over τ ∈ [0, 1].
            let s0 = (G::pt(lam) - l0) * r;
            let sig = s0.hull(s0 + f.0);
            if sig.lower() > m || sig.upper() < 0.0 {
                continue;
            }
            let tau = zero.hull(G::pt((one - G::pt(sig.lower().max(0.0))).upper()));
            let h_of = |t: G| path_bound((s0 + f.0 * t).upper(), m);
            if !self.edge_clear(k, ((s0, zero), f), (G::pt(lam), zero), tau, dir, c, &h_of) {
                return false;
            }
        }
        true
    }

    /// Proves `|P(x − h d)| > δ_b` (one sign) for the points `x = o + x f` of
    /// an edge (`(o, f)` in the frame, the parameter `x` in `range`) where
    /// `|L| ≤ δ_a`, `L = c0 + c1 x` along it, and `0 ≤ h ≤ h_of(x)`; `d` is
    /// `dir` in `(s, t)`, `c = dᵀ(∇²P/2)d`. The piece is expanded at the
    /// middle of its parameter range (see [`Piece`]).
    #[allow(clippy::too_many_arguments)]
    fn edge_clear(
        &self,
        k: usize,
        ((o_s, o_t), f): ((G, G), (G, G)),
        (c0, c1): (G, G),
        range: G,
        dir: (G, G),
        c: G,
        h_of: &impl Fn(G) -> G,
    ) -> bool {
        let da = self.da;
        let range = if c1.nonzero() {
            let (x, y) = ((G::pt(-da) - c0) / c1, (G::pt(da) - c0) / c1);
            clamp_hull(x.hull(y), range)
        } else {
            let l = c0 + c1 * range;
            (l.lower() <= da && l.upper() >= -da).then_some(range)
        };
        let Some(range) = range else { return true };
        let mid = G::pt(0.5 * (range.lower() + range.upper()));
        let f_st = frame_dir(k, f.0, f.1);
        let (p, gs, gt) = self.jet(frame_point(k, o_s + mid * f.0, o_t + mid * f.1));
        let piece = Piece {
            p,
            b: gs * f_st.0 + gt * f_st.1,
            a: self.half_hessian(f_st, f_st),
            d0: gs * dir.0 + gt * dir.1,
            d1: G::pt(2.0) * self.half_hessian(f_st, dir),
            c,
            db: self.db,
        };
        piece.clear(range - mid, &|mu: G| h_of(mid + mu), SPLITS, &self.budget)
    }
}

/// `L = l0' + lσ σ + lτ τ` in the frame of a sliver `{σ ≤ m}`, with its
/// values at the sliver's corners `(0, 1)` (`top`), `(m, 0)` (`base`) and
/// `(m, 1 − m)` (`far`); `l0'` is the value at `(0, 0)`.
#[derive(Clone, Copy)]
struct SliverLine<G> {
    l0: G,
    ls: G,
    lt: G,
    top: G,
    base: G,
    far: G,
}

/// The sliver frame's point `(σ, τ)` in `(s, t)`: `σ` is the barycentric
/// coordinate `k` of the tri-box and `τ` the next one, `v` for `k = 0`, else
/// `u`: `k = 0`: `(σ, τ)`; `k = 1`: `(τ, σ)`; `k = 2`: `(τ, 1 − σ − τ)`.
fn frame_point<G: Geo>(k: usize, sig: G, tau: G) -> (G, G) {
    let (s, t) = frame_dir(k, sig, tau);
    if k == 2 {
        (s, G::pt(1.0) + t)
    } else {
        (s, t)
    }
}

/// The linear part of [`frame_point`]: a direction `(σ, τ)` in `(s, t)`.
fn frame_dir<G: Geo>(k: usize, a: G, b: G) -> (G, G) {
    match k {
        0 => (a, b),
        1 => (b, a),
        _ => (b, -a - b),
    }
}

/// `G::pt` of an upper bound `h` on the length of a backward path, within
/// `[0, cap]` for a `cap` every path obeys (`m` where `h ≤ σ(x) ≤ m`, 1 where
/// `h ≤ τ(x) ≤ 1`), and `cap` itself for a NaN bound: never a bound that
/// would cover less of the path.
fn path_bound<G: Geo>(h: f64, cap: f64) -> G {
    G::pt(if h.is_nan() { cap } else { h.clamp(0.0, cap) })
}

/// How often [`Piece::clear`] may halve a piece that fails as a whole.
const SPLITS: u32 = 12;

/// How many halvings [`Piece::clear`] may make in one
/// [`Verifier::sliver_free`]: they go deep only next to the point that makes
/// a proof tight (the minimum of a conic touching the sliver's side, found
/// by the float clip to ~2⁻²⁰ of the tri-box), so a failing proof stays
/// cheaper than the enclosure clip it falls back to.
const CLEAR_BUDGET: u32 = 48;

/// How many halvings the slab try of [`Verifier::swept_along_sigma`] may make
/// where the strip leaves the tri-box within the slab, before the sweep with
/// exits: there the try usually succeeds (the slab beyond the edge is small)
/// or needs the halvings the sweep's end piece would make anyway (a bound
/// `m` set by `P = 0` where the strip meets an edge). Measured on the
/// paper's examples (certified `hc`, no probes): 0 halvings is slower than
/// the sweep alone on Example 3, 8 takes 5–7% off it, 16 no more.
const SLAB_TRY_BUDGET: u32 = 8;

/// `P(x0 + μ f − h d) = E(μ) − D(μ) h + C h²` on an exit piece of
/// [`Verifier::sliver_free`]: exactly `E = p + b μ + a μ²`, `D = d0 + d1 μ`.
struct Piece<G> {
    p: G,
    b: G,
    a: G,
    d0: G,
    d1: G,
    c: G,
    db: f64,
}

impl<G: Geo> Piece<G> {
    /// Proves `|P| > δ_b` (one sign) for `μ ∈ mu`, `0 ≤ h ≤ h_max(μ-range)`;
    /// where the whole piece fails, its halves are tried (`splits` levels,
    /// each halving taken from `budget`):
    /// [`bounded_away`] bounds `E` and `D` separately, which loses the
    /// coupling through `μ` on a long piece.
    fn clear(&self, mu: G, h_max: &impl Fn(G) -> G, splits: u32, budget: &Cell<u32>) -> bool {
        let d = self.d0 + self.d1 * mu;
        let h = h_max(mu);
        let e = self.p + mu * self.b + square(mu) * self.a;
        if bounded_away(e, d, self.c, h, self.db)
            || bounded_away(quadratic_range(self.p, self.b, self.a, mu), d, self.c, h, self.db)
        {
            return true;
        }
        if splits == 0 || budget.get() == 0 {
            return false;
        }
        budget.set(budget.get() - 1);
        let (lo, hi) = (mu.lower(), mu.upper());
        let mid = 0.5 * (lo + hi);
        if !(lo < mid && mid < hi) {
            return false;
        }
        self.clear(G::pt(lo).hull(G::pt(mid)), h_max, splits - 1, budget)
            && self.clear(G::pt(mid).hull(G::pt(hi)), h_max, splits - 1, budget)
    }
}

/// `{x² : x ∈ a}` (not `a · a`, which is negative where `a` straddles 0).
fn square<G: Geo>(a: G) -> G {
    if a.lower() >= 0.0 || a.upper() <= 0.0 {
        a * a
    } else {
        let m = G::pt(a.mag());
        G::pt(0.0).hull(m * m)
    }
}

/// An enclosure of `{p + b μ + a μ² : μ ∈ mu}` that is tight for a wide
/// `mu` (the sum of the terms' enclosures is not: it treats `μ` and `μ²` as
/// independent): the values at the ends of `mu`, and at the vertex
/// `−b / (2a)` if it may lie in `mu`.
fn quadratic_range<G: Geo>(p: G, b: G, a: G, mu: G) -> G {
    let at = |x: f64| {
        let x = G::pt(x);
        p + x * (b + a * x)
    };
    let ends = at(mu.lower()).hull(at(mu.upper()));
    if !a.nonzero() {
        // The vertex is anywhere (or absent): keep the term-wise enclosure.
        return ends.hull(p + mu * b + square(mu) * a);
    }
    let two = G::pt(2.0);
    let vertex = -b / (two * a);
    if vertex.upper() < mu.lower() || vertex.lower() > mu.upper() {
        ends
    } else {
        ends.hull(p - square(b) / (two * two * a))
    }
}

/// `a ∩ b` as an enclosure, `None` when provably empty.
fn clamp_hull<G: Geo>(a: G, b: G) -> Option<G> {
    let (lo, hi) = (a.lower().max(b.lower()), a.upper().min(b.upper()));
    (lo <= hi).then(|| G::pt(lo).hull(G::pt(hi)))
}

/// Proves `E − D h + C h² > δ` for all `h ∈ [0, h_max]` and all members of
/// the enclosures `e`, `d`, `c`, or `< −δ` for all of them. For `h ≥ 0` the
/// expression is at least `g(h) = E_lo − D_hi h + C_lo h²`, whose minimum on
/// the interval is at an end, or at the vertex `h* = D_hi / (2 C_lo)` when
/// `g` is convex and falls at 0; the mirror image bounds it from above.
fn bounded_away<G: Geo>(e: G, d: G, c: G, h_max: G, delta: f64) -> bool {
    let above = |e_lo: f64, d_hi: f64, c_lo: f64| {
        // NaN anywhere proves nothing.
        if e_lo.is_nan() || d_hi.is_nan() || c_lo.is_nan() || e_lo <= delta {
            return false;
        }
        let (e, d, c) = (G::pt(e_lo), G::pt(d_hi), G::pt(c_lo));
        let at_end = (e - d * h_max + c * h_max * h_max).lower();
        if at_end.is_nan() || at_end <= delta {
            return false;
        }
        if d_hi > 0.0 && c_lo > 0.0 {
            let two = G::pt(2.0);
            let vertex = d / (two * c);
            // h* beyond h_max: g falls on the whole interval, minimum at h_max.
            return vertex.lower() >= h_max.upper() || (e - d * vertex / two).lower() > delta;
        }
        true
    };
    above(e.lower(), d.upper(), c.lower()) || above(-e.upper(), -d.lower(), -c.upper())
}

/// A boundary line with what its candidates need, computed once per line:
/// `src` tags the two sides of one strip (parallel by construction, never
/// intersected with each other).
struct BoundaryLine<G> {
    src: usize,
    l: Linear<G>,
    /// Not proven to miss the unit square.
    meets: bool,
    cut: Cut<G>,
}

/// How a line meets a conic's level curve (see [`line_conic`]).
enum Cut<G> {
    /// The line misses `[0, 1]²`, or is `a0 = 0` (no line or every point).
    Nothing,
    /// Neither coefficient provably non-zero: the whole segment.
    Whole,
    /// `other = m · x + k`, with `x = s` when `by_s`, else `x = t`.
    Param { by_s: bool, m: G, k: G },
}

impl<G: Geo> BoundaryLine<G> {
    fn new(src: usize, l: Linear<G>) -> Self {
        let meets = meets_unit_square(&l);
        Self {
            src,
            l,
            meets,
            cut: if meets { cut_of(&l) } else { Cut::Nothing },
        }
    }
}

fn clip_in<G: Geo>(fats: &[Fat<G>]) -> ClipBounds {
    let (zero, one) = (G::pt(0.0), G::pt(1.0));
    // The tri-box's edges s = 0, t = 0, w = 0 as graphs (see `cut_of`):
    // s = 0·t + 0, t = 0·s + 0, t = −s + 1 (exact).
    let edge = |src: usize, c: [G; 3], by_s: bool, m: G, k: G| BoundaryLine {
        src,
        l: Linear { c },
        meets: true,
        cut: Cut::Param { by_s, m, k },
    };
    let edges = [
        edge(EDGE_S, [zero, one, zero], false, zero, zero),
        edge(EDGE_T, [zero, zero, one], true, zero, zero),
        edge(EDGE_W, [-one, one, one], true, -one, one),
    ];
    let mut lines: SmallVec<[BoundaryLine<G>; 4]> = SmallVec::new();
    let mut conics: SmallVec<[(Quadratic<G>, f64, usize); 1]> = SmallVec::new();
    let mut tangents: SmallVec<[BoundaryLine<G>; 3]> = SmallVec::new();
    let mut centres: SmallVec<[[Linear<G>; 2]; 1]> = SmallVec::new();
    for (idx, fat) in fats.iter().enumerate() {
        match fat {
            Fat::Line(l, d) => {
                lines.push(BoundaryLine::new(idx, l.shifted(*d)));
                lines.push(BoundaryLine::new(idx, l.shifted(-*d)));
            }
            Fat::Conic(q, d) => {
                conics.push((*q, *d, idx));
                let tl = q.tangency_lines();
                tangents.extend(tl.iter().map(|l| BoundaryLine::new(usize::MAX, *l)));
                centres.push([tl[0], tl[1]]);
            }
        }
    }
    // Float candidates on an edge of the tri-box (s, t or w = 0) land a few
    // ulps of 1 to either side of it: accept them, or a root on the edge is
    // clipped away. Rigorous kernels need no slack.
    let slack = if G::RIGOROUS { 0.0 } else { -1e-12 };
    // A candidate's exact point satisfies the constraints it is constructed
    // on (a strip side, a level curve, a tri-box edge): `on` marks them
    // ([`On`]), and only the others are tested. (Their tests would answer
    // "possibly" anyway, so the result is the same.)
    let feasible = |s: G, t: G, on: On| {
        (on.has(On::S) || s.possibly_ge(slack))
            && (on.has(On::T) || t.possibly_ge(slack))
            && (on.has(On::W) || (G::pt(1.0) - s - t).possibly_ge(slack))
            && fats
                .iter()
                .enumerate()
                .all(|(i, f)| on.has(On::fat(i)) || f.possibly_contains(s, t))
    };
    let mut bounds = Bounds::new();
    let mut push = |[s, t]: [G; 2], on: On| {
        if bounds.could_lower(s, t) && feasible(s, t, on) {
            bounds.add(s, t);
        }
        bounds.settled()
    };
    // Each loop stops as soon as the result is settled (`push` says so).
    'pairs: {
        // Edges meet edges at the vertices (exact).
        let corners = On(On::S.0 | On::T.0 | On::W.0);
        for v in [[zero, zero], [zero, one], [one, zero]] {
            if push(v, corners) {
                break 'pairs;
            }
        }
        for e in 0..edges.len() {
            for line in lines.iter().filter(|l| l.meets) {
                let on = On::edge(e).and(On::fat(line.src));
                if edge_line(e, &line.l, &mut |p| push(p, on)) {
                    break 'pairs;
                }
            }
        }
        for (a, la) in lines.iter().enumerate() {
            for lb in &lines[a + 1..] {
                let on = On::fat(la.src).and(On::fat(lb.src));
                if la.src != lb.src && la.meets && lb.meets && line_line(&la.l, &lb.l, &mut |p| push(p, on)) {
                    break 'pairs;
                }
            }
        }
        for (q, d, qi) in &conics {
            // The two level curves `Q = ±δ` differ in the constant term only.
            let levels = [q.shifted(*d).c[0], q.shifted(-*d).c[0]];
            for line in edges.iter().chain(&lines).chain(&tangents) {
                // Only the piece of the line inside every other strip can hold
                // a feasible candidate.
                let range = fats.iter().enumerate().fold([0.0, 1.0], |r, (idx, fat)| match fat {
                    Fat::Line(l, d) if line.src != idx => inside_strip(&line.cut, l, *d, r),
                    _ => r,
                });
                let on = On::fat(*qi).and(match line.src {
                    EDGE_S => On::S,
                    EDGE_T => On::T,
                    EDGE_W => On::W,
                    src => On::fat(src),
                });
                if line_conic(&line.cut, q, levels, range, &mut |p| push(p, on)) {
                    break 'pairs;
                }
            }
        }
        for [a, b] in &centres {
            if meets_unit_square(a) && meets_unit_square(b) && line_line(a, b, &mut |p| push(p, On(0))) {
                break 'pairs;
            }
        }
    }
    bounds.finish(G::RIGOROUS)
}

/// `src` of the tri-box's edges `s = 0`, `t = 0`, `w = 0` (fat curves use
/// their index, tangency lines `usize::MAX`).
const EDGE_S: usize = usize::MAX - 3;
const EDGE_T: usize = usize::MAX - 2;
const EDGE_W: usize = usize::MAX - 1;

/// The constraints a candidate satisfies by construction: bit 0–2 the
/// tri-box's `s ≥ 0`, `t ≥ 0`, `w ≥ 0`, bit `3 + i` fat curve `i`.
#[derive(Clone, Copy)]
struct On(u32);

impl On {
    const S: On = On(1);
    const T: On = On(2);
    const W: On = On(4);

    /// Fat curve `i` (nothing for a `src` that is no fat curve).
    fn fat(i: usize) -> On {
        On(if i < 29 { 8 << i } else { 0 })
    }

    fn edge(e: usize) -> On {
        [On::S, On::T, On::W][e]
    }

    fn and(self, o: On) -> On {
        On(self.0 | o.0)
    }

    fn has(self, o: On) -> bool {
        self.0 & o.0 == o.0
    }
}

/// Whether `a0 + a1 s + a2 t = 0` can meet the unit square `[0, 1]²` (the
/// tri-box lies inside it): `false` only when proven not to.
fn meets_unit_square<G: Geo>(l: &Linear<G>) -> bool {
    if G::RIGOROUS {
        let unit = G::pt(0.0).hull(G::pt(1.0));
        let range = l.eval(unit, unit);
        range.possibly_le(0.0) && range.possibly_ge(0.0)
    } else {
        // For f64 `hull` is the midpoint: use the corner values.
        let v = [
            l.eval(G::pt(0.0), G::pt(0.0)),
            l.eval(G::pt(1.0), G::pt(0.0)),
            l.eval(G::pt(0.0), G::pt(1.0)),
            l.eval(G::pt(1.0), G::pt(1.0)),
        ];
        let lo = v.iter().map(|x| x.lower()).fold(f64::INFINITY, f64::min);
        let hi = v.iter().map(|x| x.upper()).fold(f64::NEG_INFINITY, f64::max);
        lo <= 0.0 && hi >= 0.0
    }
}

/// Enclosures of the intersection of two lines that may meet the unit square
/// ([`meets_unit_square`]), restricted to `[0, 1]²`, handed to `push`; `true`
/// as soon as `push` returns `true`. Exactly parallel lines (determinant
/// provably zero) give nothing: they never meet in a single point, and where
/// they coincide the minimizers are end points found through other pairs.
fn line_line<G: Geo>(a: &Linear<G>, b: &Linear<G>, push: &mut impl FnMut([G; 2]) -> bool) -> bool {
    let det = a.c[1] * b.c[2] - a.c[2] * b.c[1];
    // a1 s + a2 t = −a0, b1 s + b2 t = −b0 (Cramer).
    let ns = a.c[2] * b.c[0] - a.c[0] * b.c[2];
    let nt = a.c[0] * b.c[1] - a.c[1] * b.c[0];
    cramer(det, ns, nt, push)
}

/// [`line_line`] of edge `e` of the tri-box (`s = 0`, `t = 0`, `w = 0`, i.e.
/// `[0, 1, 0]`, `[0, 0, 1]`, `[−1, 1, 1]`) and `b`: Cramer's terms without
/// the products with the edge's exact zeros and ones (which are exact, so
/// the enclosures are the same).
fn edge_line<G: Geo>(e: usize, b: &Linear<G>, push: &mut impl FnMut([G; 2]) -> bool) -> bool {
    let [b0, b1, b2] = b.c;
    let zero = G::pt(0.0);
    let (det, ns, nt) = match e {
        0 => (b2, zero, -b0),
        1 => (-b1, b0, zero),
        _ => (b2 - b1, b0 + b2, -b1 - b0),
    };
    cramer(det, ns, nt, push)
}

/// The point `(ns, nt) / det` of [`line_line`], in `[0, 1]²`, to `push`.
fn cramer<G: Geo>(det: G, ns: G, nt: G, push: &mut impl FnMut([G; 2]) -> bool) -> bool {
    if det.sign_class() == Sign::Zero {
        return false;
    }
    let ts = G::div_pieces(nt, det);
    for s in G::div_pieces(ns, det).into_iter().flatten() {
        for t in ts.into_iter().flatten() {
            if let (Some(s), Some(t)) = (s.clamp_to(0.0, 1.0), t.clamp_to(0.0, 1.0)) {
                if push([s, t]) {
                    return true;
                }
            }
        }
    }
    false
}

/// The line `l` (which may meet the unit square) as a graph over the
/// coordinate with the larger coefficient on the other one.
fn cut_of<G: Geo>(l: &Linear<G>) -> Cut<G> {
    let [a0, a1, a2] = l.c;
    if a1.sign_class() == Sign::Zero && a2.sign_class() == Sign::Zero {
        return Cut::Nothing; // "a0 = 0": no line, or every point (see module docs).
    }
    let by_s = a2.mag() >= a1.mag() || G::RIGOROUS && a2.nonzero() && !a1.nonzero();
    let (num_a, den, num_k) = if by_s { (a1, a2, a0) } else { (a2, a1, a0) };
    if !den.nonzero() {
        return Cut::Whole;
    }
    Cut::Param {
        by_s,
        m: -num_a / den,
        k: -num_k / den,
    }
}

/// `range` (a sub-interval of `[0, 1]` for the line's parameter `x`, see
/// [`cut_of`]) narrowed to an outer bound of the parameters whose points lie
/// in the strip `|l| ≤ δ`; `[1, 0]` (empty) when none do. Along the line
/// `l = λ0 + λ1 x`, so the strip is `x ∈ [(−δ − λ0)/λ1, (δ − λ0)/λ1]` when
/// `λ1 ≠ 0` is proven, and no narrowing is attempted otherwise. The float
/// kernel widens the bounds by a relative `1e-9` (its candidates are not
/// enclosures).
fn inside_strip<G: Geo>(cut: &Cut<G>, l: &Linear<G>, delta: f64, range: [f64; 2]) -> [f64; 2] {
    let Cut::Param { by_s, m, k } = *cut else {
        return range;
    };
    let [l0, l1, l2] = l.c;
    // (s, t) = (x, m x + k) or (m x + k, x).
    let (lam0, lam1) = if by_s {
        (l0 + l2 * k, l1 + l2 * m)
    } else {
        (l0 + l1 * k, l2 + l1 * m)
    };
    if !lam1.nonzero() {
        return range;
    }
    let d = G::pt(delta);
    let (a, b) = ((-d - lam0) / lam1, (d - lam0) / lam1);
    let (mut lo, mut hi) = (a.lower().min(b.lower()), a.upper().max(b.upper()));
    if !G::RIGOROUS {
        let slack = 1e-9 * (1.0 + lo.abs() + hi.abs());
        (lo, hi) = (lo - slack, hi + slack);
    }
    if lo.is_nan() || hi.is_nan() {
        return range;
    }
    [range[0].max(lo), range[1].min(hi)]
}

/// Enclosures of the intersections of a line (as [`cut_of`] parametrizes it)
/// with the level curves `Q − Q(0, 0) + c0 = 0` for both `c0` in `levels`,
/// restricted to `[0, 1]²` and to the parameters in `range` (outside it no
/// point is feasible: see [`inside_strip`]), handed to `push`; `true` as soon
/// as `push` returns `true`. What does not depend on the level is computed
/// once, and a level whose quadratic provably has no zero on `range` is
/// skipped without solving.
fn line_conic<G: Geo>(
    cut: &Cut<G>,
    q: &Quadratic<G>,
    levels: [G; 2],
    range: [f64; 2],
    push: &mut impl FnMut([G; 2]) -> bool,
) -> bool {
    // NaN bounds fail both comparisons and keep the whole segment.
    if range[0] > range[1] {
        return false;
    }
    let (by_s, m, k) = match *cut {
        Cut::Nothing => return false,
        Cut::Whole => {
            // The same candidate for both levels.
            let unit = G::pt(0.0).hull(G::pt(1.0));
            return push([unit, unit]);
        }
        Cut::Param { by_s, m, k } => (by_s, m, k),
    };
    let c = &q.c;
    let two = G::pt(2.0);
    // α x² + β x + γ with γ = c0 + γ1 + γ2.
    let (alpha, beta, gamma1, gamma2) = if by_s {
        // Q(s, m s + k)
        (
            c[3] + c[4] * m + c[5] * m * m,
            c[1] + c[2] * m + c[4] * k + two * c[5] * m * k,
            c[2] * k,
            c[5] * k * k,
        )
    } else {
        // Q(m t + k, t)
        (
            c[5] + c[4] * m + c[3] * m * m,
            c[2] + c[1] * m + c[4] * k + two * c[3] * m * k,
            c[1] * k,
            c[3] * k * k,
        )
    };
    let mut eq = Quad {
        alpha,
        beta,
        gamma: G::pt(0.0), // set per level
        beta_sq: beta * beta,
        four_alpha: G::pt(4.0) * alpha,
    };
    let segment = G::pt(range[0]).hull(G::pt(range[1]));
    for c0 in levels {
        eq.gamma = c0 + gamma1 + gamma2;
        if [alpha, beta, eq.gamma].iter().all(|c| c.sign_class() == Sign::Zero) {
            // The line lies in the level curve: minimizers on it are the end
            // points of that boundary piece, found through the other pairs.
            continue;
        }
        if G::RIGOROUS && [0.0, 1.0] != range {
            // The quadratic's range over the segment (x ≥ 0, so α x·x is
            // an enclosure of α x²) misses 0: no crossing there.
            let value = (alpha * segment + beta) * segment + eq.gamma;
            if value.lower() > 0.0 || value.upper() < 0.0 {
                continue;
            }
        }
        let mut settled = false;
        roots_in(&eq, range, &mut |x| {
            if let Some(y) = (m * x + k).clamp_to(0.0, 1.0) {
                settled = push(if by_s { [x, y] } else { [y, x] });
            }
            settled
        });
        if settled {
            return true;
        }
    }
    false
}

/// `α x² + β x + γ`, with `β²` and `4α` (shared by the two levels of a fat conic).
struct Quad<G> {
    alpha: G,
    beta: G,
    gamma: G,
    beta_sq: G,
    four_alpha: G,
}

/// Enclosures of every root of `α x² + β x + γ` in `[0, 1]` (for all members
/// of the coefficient enclosures). When both `α` and `β` may vanish, the
/// whole of `[0, 1]` is returned.
pub fn quadratic_roots_in_unit<G: Geo>(alpha: G, beta: G, gamma: G) -> Vec<G> {
    let mut out = Vec::new();
    let eq = Quad {
        alpha,
        beta,
        gamma,
        beta_sq: beta * beta,
        four_alpha: G::pt(4.0) * alpha,
    };
    roots_in_unit(&eq, &mut |x| {
        out.push(x);
        false
    });
    out
}

/// [`quadratic_roots_in_unit`], each root handed to `keep`; stops once `keep`
/// returns `true`.
fn roots_in_unit<G: Geo>(eq: &Quad<G>, keep: &mut impl FnMut(G) -> bool) {
    roots_in(eq, [0.0, 1.0], keep)
}

/// The roots in `range ⊂ [0, 1]` of [`roots_in_unit`] (clamped to it).
fn roots_in<G: Geo>(eq: &Quad<G>, range: [f64; 2], keep: &mut impl FnMut(G) -> bool) {
    let Quad {
        alpha,
        beta,
        gamma,
        beta_sq,
        four_alpha,
    } = *eq;
    // On [0, 1], |α x² + β x| ≤ |α| + |β|: a constant term beyond that has no
    // root there. (Decides the nearly-constant case below without giving up.)
    // With enclosures the sum is rounded up, so the test is a proof.
    let bound = alpha.mag() + beta.mag();
    if gamma.mig() > if G::RIGOROUS { iv::up(bound) } else { bound } {
        return;
    }
    let disc = beta_sq - four_alpha * gamma;
    let Some(sq) = disc.sqrt_nonneg() else {
        return;
    };
    let mut keep_in_unit = |x: G| x.clamp_to(range[0], range[1]).is_some_and(&mut *keep);
    if beta.nonzero() {
        // q = −(β + sign(β)·√D)/2 has |q| ≥ |β|/2 > 0: roots q/α and γ/q.
        let q = (if beta.lower() > 0.0 { -(beta + sq) } else { sq - beta }) / G::pt(2.0);
        if keep_in_unit(gamma / q) {
            return;
        }
        for piece in G::div_pieces(q, alpha).into_iter().flatten() {
            if keep_in_unit(piece) {
                return;
            }
        }
    } else if alpha.nonzero() {
        let two_a = G::pt(2.0) * alpha;
        if !keep_in_unit((-beta + sq) / two_a) {
            keep_in_unit((-beta - sq) / two_a);
        }
    } else if G::RIGOROUS {
        keep(G::pt(range[0]).hull(G::pt(range[1])));
    } else if gamma.sign_class() == Sign::Zero {
        keep(G::pt(0.0));
    }
}

/// Bézier clipping bounds of one equation (Roth et al. 2000, as used in Liu et
/// al. 2016 §4): the control net `(i/n, j/n, f_ijk)` bounds the graph, so the
/// zero set projects into the hull of the points `(i/n, f_ijk)` cut by
/// `f = 0`, and likewise for `j` and `k`. The hull meets the axis in the
/// convex hull of the zero-valued points and the crossings of segments between
/// a positive and a negative point; the minimum of those is the bound.
///
/// Each coefficient enters as the two ends of its range over the ball: the
/// surface of every member lies in the convex hull of all of them. `rigorous`
/// subtracts the proven rounding margin from each crossing (the certified
/// solver); without it the crossings are plain `f64` proposals.
pub fn bezier_bounds(f: &TriBall, rigorous: bool) -> ClipBounds {
    let n = f.degree().max(1);
    // The control points (i/n, j/n, k/n; f_ijk) with each coefficient's
    // enclosure as its two endpoints: the surface lies in the convex hull of
    // all of them (whatever the exact coefficients are), and the hull meets
    // z = 0 in the hull of the endpoints that are 0, of the points whose
    // enclosure holds 0, and of the crossings of segments joining a positive
    // and a negative endpoint. (An enclosure that straddles 0 is not a point
    // at 0: its negative end pairs with positive neighbours, and the crossing
    // can lie away from it.)
    let mut pos: SmallVec<[([usize; 3], f64); 72]> = SmallVec::new();
    let mut neg: SmallVec<[([usize; 3], f64); 72]> = SmallVec::new();
    let mut mins = [f64::INFINITY; 3];
    for (idx, (i, j, k)) in tri_indices(f.degree()).enumerate() {
        let (lo, hi) = f.bounds(idx);
        if lo.is_nan() || hi.is_nan() {
            return ClipBounds::Keep([0.0; 3]);
        }
        if lo <= 0.0 && hi >= 0.0 {
            for (m, x) in mins.iter_mut().zip([i, j, k]) {
                *m = m.min(x as f64 / n as f64);
            }
        }
        for y in if hi != lo {
            [Some(lo), Some(hi)]
        } else {
            [Some(lo), None]
        }
        .into_iter()
        .flatten()
        {
            if y > 0.0 {
                pos.push(([i, j, k], y));
            } else if y < 0.0 {
                neg.push(([i, j, k], y));
            }
        }
    }
    if mins[0].is_infinite() && (pos.is_empty() || neg.is_empty()) {
        return ClipBounds::Empty;
    }
    // The crossing of the segment from (a, yp) to (b, yq), yp > 0 > yq, with
    // the axis is x = a + (b − a)·t, t = yp / (yp − yq) ∈ (0, 1), with
    // a = i/n, b = j/n. Evaluated in `f64`, every quantity (a, b, b − a, t, x)
    // lies in [−1, 1], and each of the six roundings (i/n, j/n, b − a,
    // yp − yq, the quotient, the product, the sum) errs by at most one ulp
    // of 1 relative to its operands: the computed x is within 7·2⁻⁵² of the
    // exact crossing (plus 2⁻¹⁰⁷⁴ for a subnormal quotient), so subtracting
    // 16·2⁻⁵² gives a lower bound. This is 20–40× cheaper than interval
    // operations, and this loop is most of a Bézier clip.
    let margin = if rigorous { 16.0 * f64::EPSILON } else { 0.0 };
    let nn = n as f64;
    for (coord, m) in mins.iter_mut().enumerate() {
        for p in &pos {
            for q in &neg {
                let (yp, yq) = (p.1, q.1);
                let span = yp - yq;
                let (a, b) = (p.0[coord] as f64 / nn, q.0[coord] as f64 / nn);
                let x = if span.is_finite() {
                    a + (b - a) * (yp / span) - margin
                } else {
                    // Overflow of yp − yq: enclose with outward rounding.
                    let (xp, xq) = (iv::Iv::point(p.0[coord] as f64), iv::Iv::point(q.0[coord] as f64));
                    let (xp, xq) = (xp.div(iv::Iv::point(nn)), xq.div(iv::Iv::point(nn)));
                    let (yp, yq) = (iv::Iv::point(yp), iv::Iv::point(yq));
                    xp.add(xq.sub(xp).mul(yp.div(yp.sub(yq)))).lo
                };
                *m = m.min(x);
            }
        }
    }
    let m = mins.map(|x| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) });
    keep_or_empty(m, rigorous)
}

/// Combines bounds that must hold together (both equations vanish at a root).
pub fn intersect_bounds(a: ClipBounds, b: ClipBounds, rigorous: bool) -> ClipBounds {
    match (a, b) {
        (ClipBounds::Keep(x), ClipBounds::Keep(y)) => {
            keep_or_empty([x[0].max(y[0]), x[1].max(y[1]), x[2].max(y[2])], rigorous)
        }
        _ => ClipBounds::Empty,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{interval, point};
    use crate::solve::num::GeoIv;
    use inari::Interval;

    #[test]
    fn quadratic_roots_enclosed() {
        let r: Vec<Interval> = quadratic_roots_in_unit(point(1.0), point(-0.75), point(0.125));
        // roots 0.25 and 0.5
        assert_eq!(r.len(), 2);
        assert!(r.iter().any(|x| x.contains(0.25)) && r.iter().any(|x| x.contains(0.5)));
        // nearly linear: α = 0 exactly, root at 0.4
        let r: Vec<Interval> = quadratic_roots_in_unit(point(0.0), point(1.0), point(-0.4));
        assert!(r.iter().any(|x| x.contains(0.4)));
    }

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

    /// The fast geometry kernel gives inari's clip bounds: its operations
    /// have inari's endpoints, except for the outer ends of two-piece
    /// quotients (rounded a float wider), which can only lower a bound.
    #[test]
    fn fast_kernel_matches_inari() {
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut compared = 0;
        for case in 0..400 {
            let mut coeff = |scale: f64| {
                let x = (next() - 0.5) * scale;
                // Exact zeros and exact points, as in the paper's examples.
                match case % 4 {
                    0 => point((x * 8.0).round() / 8.0),
                    1 => point(x),
                    _ => interval(x, x + 1e-9 * next()),
                }
            };
            let line = Linear {
                c: [coeff(1.0), coeff(2.0), coeff(2.0)],
            };
            let conic = Quadratic {
                c: [coeff(1.0), coeff(2.0), coeff(2.0), coeff(2.0), coeff(2.0), coeff(2.0)],
            };
            let fats = [Fat::Line(line, 0.05 * next()), Fat::Conic(conic, 0.05 * next())];
            let fast_fats = fats.map(|f| match f {
                Fat::Line(l, d) => Fat::Line(Linear { c: l.c.map(GeoIv::of) }, d),
                Fat::Conic(q, d) => Fat::Conic(Quadratic { c: q.c.map(GeoIv::of) }, d),
            });
            // The enclosure-based bounds in both kernels (the verified float
            // clip that `clip_against_fat_curves` tries first is tested below).
            let fast = clip_in(&fast_fats);
            let reference = clip_in(&fats);
            match (fast, reference) {
                (ClipBounds::Keep(f), ClipBounds::Keep(r)) => {
                    compared += 1;
                    for i in 0..3 {
                        assert!(f[i] <= r[i] && r[i] - f[i] < 1e-12, "case {case}: {f:?} vs {r:?}");
                    }
                }
                (f, r) => assert_eq!(f, r, "case {case}"),
            }
        }
        assert!(compared > 50, "{compared}");
    }

    /// The verified float clip never claims too much, checked independently
    /// with inari: on random fat lines and fat conics (and pairs of fat
    /// lines) through a random point, every point proven (by direct interval
    /// evaluation) to lie in the tri-box and in both fat regions satisfies the
    /// returned bounds, and an `Empty` claim has no such point. The points
    /// are where the minima sit: crossings of the strip's lines
    /// (`L = λ`, 41 values of `λ`) with `P = 0` and `P = ±δ_b`, crossings of
    /// the tri-box edges with `L = ±δ_a` and with `P = ±δ_b`, and a grid.
    #[test]
    fn verified_clips_hold_every_feasible_point() {
        let mut rng = crate::rng::Rng(0x5eed_c11b);
        let (mut kept, mut empty, mut declined, mut checked) = (0, 0, 0, 0);
        let (mut proofs, mut refuted, mut slab) = ([0; 4], 0, [0; 2]);
        for case in 0..500 {
            let mut r = || rng.next_f64();
            let (s0, t0) = (1.4 * r() - 0.2, 1.4 * r() - 0.2);
            let log_uniform = |x: f64, lo: f64, hi: f64| (lo.ln() + x * (hi.ln() - lo.ln())).exp();
            let (da, db) = (log_uniform(r(), 1e-9, 0.3), log_uniform(r(), 1e-9, 0.3));
            let (mut g1, mut g2) = (2.0 * r() - 1.0, 2.0 * r() - 1.0);
            // Strips parallel to a side of the tri-box (lτ = 0 in frame k = 0,
            // 1 or 2), which symmetric systems produce.
            match case % 7 {
                1 => g2 = 0.0,
                2 => g1 = 0.0,
                3 => g2 = g1,
                _ => {}
            }
            let l = [-(g1 * s0 + g2 * t0) + 0.1 * da * (2.0 * r() - 1.0), g1, g2];
            let (h1, h2) = (2.0 * r() - 1.0, 2.0 * r() - 1.0);
            let curv = [0.0, 0.3, 1.0, 4.0][case % 4];
            let (q3, q4, q5) = (
                curv * (2.0 * r() - 1.0),
                curv * (2.0 * r() - 1.0),
                curv * (2.0 * r() - 1.0),
            );
            // Q(s, t) = h1 (s − s0) + h2 (t − t0) + the quadratic terms in (s − s0, t − t0).
            let q = [
                -(h1 * s0 + h2 * t0) + q3 * s0 * s0 + q4 * s0 * t0 + q5 * t0 * t0,
                h1 - 2.0 * q3 * s0 - q4 * t0,
                h2 - q4 * s0 - 2.0 * q5 * t0,
                q3,
                q4,
                q5,
            ];
            let conic = case % 5 != 0;
            // Two lines in three with coefficient enclosures 2e-12 wide (as
            // the solver's are, so a zero coefficient is not proven non-zero)
            // or 0.06 wide (so strips with slopes of both signs use every
            // exit piece); the strip is then the union over the members, and
            // the points below are taken for the corner members too.
            let lw = [0.0, 1e-12, 0.03][case % 3];
            let line = Linear {
                c: l.map(|x| GeoIv::pt(x - lw).hull(GeoIv::pt(x + lw))),
            };
            let fat_line = Fat::Line(line, da);
            let other = if conic {
                Fat::Conic(Quadratic { c: q.map(GeoIv::pt) }, db)
            } else {
                Fat::Line(
                    Linear {
                        c: [q[0], q[1], q[2]].map(GeoIv::pt),
                    },
                    db,
                )
            };
            let claim = proposed_and_verified(&[fat_line, other]);
            let verifier = Verifier::new(&line, da, &other);
            let qs = if conic { q } else { [q[0], q[1], q[2], 0.0, 0.0, 0.0] };
            let members: Vec<[f64; 3]> = if lw > 0.0 {
                (0..8)
                    .map(|b| [0, 1, 2].map(|i| l[i] + if b >> i & 1 == 1 { lw } else { -lw }))
                    .chain([l])
                    .collect()
            } else {
                vec![l]
            };
            let qv = |s: f64, t: f64| qs[0] + qs[1] * s + qs[2] * t + qs[3] * s * s + qs[4] * s * t + qs[5] * t * t;
            // Proven feasible, and the proven barycentric coordinates.
            let proven = |s: f64, t: f64| -> Option<[Interval; 3]> {
                let (si, ti) = (point(s), point(t));
                let c = |x: f64| point(x);
                let in_strip = members.iter().any(|l| {
                    let lx = c(l[0]) + c(l[1]) * si + c(l[2]) * ti;
                    lx.inf() >= -da && lx.sup() <= da
                });
                let qx = c(qs[0])
                    + c(qs[1]) * si
                    + c(qs[2]) * ti
                    + c(qs[3]) * si * si
                    + c(qs[4]) * si * ti
                    + c(qs[5]) * ti * ti;
                let w = c(1.0) - si - ti;
                let inside = |x: Interval, d: f64| x.inf() >= -d && x.sup() <= d;
                (s >= 0.0 && t >= 0.0 && w.inf() >= 0.0 && in_strip && inside(qx, db)).then_some([si, ti, w])
            };
            let mut pts: Vec<(f64, f64)> = Vec::new();
            // Zeros of `f` along `x ↦ point(x)`, x ∈ [0, 1], by scanning and bisection.
            let mut zeros = |point_at: &dyn Fn(f64) -> Option<(f64, f64)>, f: &dyn Fn(f64, f64) -> f64| {
                let n = 400;
                let val = |x: f64| point_at(x).map(|(s, t)| f(s, t));
                for i in 0..n {
                    let (mut a, mut b) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                    let (Some(fa), Some(fb)) = (val(a), val(b)) else {
                        continue;
                    };
                    if fa == 0.0 {
                        pts.extend(point_at(a));
                    }
                    if fa.signum() * fb.signum() >= 0.0 {
                        continue;
                    }
                    let sa = fa.signum();
                    for _ in 0..60 {
                        let m = 0.5 * (a + b);
                        match val(m) {
                            Some(v) if v.signum() == sa => a = m,
                            Some(_) => b = m,
                            None => break,
                        }
                    }
                    pts.extend(point_at(a));
                    pts.extend(point_at(b));
                }
            };
            for &l in &members {
                for i in 0..=40 {
                    let lam = da * (i as f64 / 20.0 - 1.0) * 0.999;
                    // The line L = λ as a graph over the coordinate with the larger slope.
                    let on_line = move |x: f64| {
                        if l[2].abs() >= l[1].abs() {
                            Some((x, (lam - l[0] - l[1] * x) / l[2]))
                        } else {
                            Some(((lam - l[0] - l[2] * x) / l[1], x))
                        }
                    };
                    for level in [0.0, 0.999 * db, -0.999 * db] {
                        zeros(&on_line, &|s, t| qv(s, t) - level);
                    }
                }
            }
            let edges: [&dyn Fn(f64) -> Option<(f64, f64)>; 3] =
                [&|x| Some((0.0, x)), &|x| Some((x, 0.0)), &|x| Some((x, 1.0 - x))];
            for edge in edges {
                for l in &members {
                    for level in [0.999 * da, -0.999 * da] {
                        zeros(edge, &|s, t| l[0] + l[1] * s + l[2] * t - level);
                    }
                }
                for level in [0.0, 0.999 * db, -0.999 * db] {
                    zeros(edge, &|s, t| qv(s, t) - level);
                }
            }
            for i in 0..=60 {
                for j in 0..=60 - i {
                    pts.push((i as f64 / 60.0, j as f64 / 60.0));
                }
            }
            match claim {
                None => declined += 1,
                Some(ClipBounds::Empty) => empty += 1,
                Some(ClipBounds::Keep(_)) => kept += 1,
            }
            let feasible: Vec<[Interval; 3]> = pts.iter().filter_map(|&(s, t)| proven(s, t)).collect();
            checked += feasible.len();
            for bary in &feasible {
                match claim {
                    None => {}
                    Some(ClipBounds::Empty) => panic!("case {case}: Empty, but {bary:?} is feasible"),
                    Some(ClipBounds::Keep(m)) => {
                        for k in 0..3 {
                            assert!(bary[k].sup() >= m[k], "case {case}: {bary:?} is feasible, below {m:?}");
                        }
                    }
                }
            }
            // The proofs themselves, on claims that are false as often as
            // true: just below and above the smallest feasible coordinate
            // found, and at random.
            for k in 0..3 {
                let low = feasible.iter().map(|b| b[k].inf()).fold(f64::INFINITY, f64::min);
                let mut tries: Vec<f64> = (0..8).map(|_| r()).collect();
                if low.is_finite() {
                    tries.extend([1e-3, 1e-6, -1e-6, -1e-3, -0.1].map(|x| low * (1.0 + x)));
                }
                for m in tries.into_iter().filter(|m| *m > 0.0 && *m <= 1.0) {
                    // The proof, and each sweep on its own (either is valid
                    // wherever its coefficient is non-zero).
                    let frame = verifier.sliver_line(k, m);
                    let fresh = || verifier.budget.set(CLEAR_BUDGET);
                    // Proofs (and failures) by the slab shortcut of the sweep along σ.
                    let SliverLine {
                        l0,
                        ls,
                        lt,
                        top,
                        base,
                        far,
                    } = frame;
                    let by_slab = lt.nonzero() && verifier.strip_spans((l0, top)) && verifier.strip_spans((base, far));
                    let sweeps = [
                        Some(verifier.sliver_free(k, m)),
                        lt.nonzero().then(|| {
                            fresh();
                            verifier.swept_along_sigma(k, m, frame)
                        }),
                        ls.nonzero().then(|| {
                            fresh();
                            verifier.swept_along_tau(k, m, frame)
                        }),
                        ls.nonzero().then(|| {
                            fresh();
                            verifier.swept_across(k, m, frame)
                        }),
                    ];
                    if by_slab {
                        slab[usize::from(sweeps[1] == Some(true))] += 1;
                    }
                    for (how, proven) in sweeps.into_iter().enumerate() {
                        match proven {
                            Some(true) => {
                                proofs[how] += 1;
                                for bary in &feasible {
                                    assert!(
                                        bary[k].sup() > m,
                                        "case {case}: sliver {k} ≤ {m} proven free ({how}), but {bary:?}"
                                    );
                                }
                            }
                            Some(false) if how == 0 && feasible.iter().any(|b| b[k].sup() <= m) => refuted += 1,
                            _ => {}
                        }
                    }
                }
            }
        }
        assert!(
            kept > 100
                && empty > 100
                && checked > 20000
                && proofs.iter().all(|&p| p > 1000)
                && refuted > 1000
                && slab.iter().all(|&n| n > 1000),
            "{kept} {empty} {declined} {checked} {proofs:?} {refuted} {slab:?}"
        );
    }

    /// A NaN anywhere in the Taylor form or the path length proves nothing,
    /// and a NaN path length becomes the cap, not 0.
    #[test]
    fn nan_proves_nothing() {
        let (p, nan) = (GeoIv::pt, GeoIv::pt(f64::NAN));
        assert!(bounded_away(p(1.0), p(0.1), p(1.0), p(0.5), 0.5));
        assert!(!bounded_away(p(1.0), nan, p(1.0), p(0.5), 0.5));
        assert!(!bounded_away(p(1.0), p(0.1), nan, p(0.5), 0.5));
        assert!(!bounded_away(nan, p(0.1), p(1.0), p(0.5), 0.5));
        assert!(!bounded_away(p(1.0), p(0.1), p(1.0), nan, 0.5));
        assert_eq!(path_bound::<f64>(f64::NAN, 0.3), 0.3);
        assert_eq!(path_bound::<f64>(-1.0, 0.3), 0.0);
        assert_eq!(path_bound::<f64>(0.7, 0.3), 0.3);
    }

    /// The float evaluation of the hull crossings in `bezier_bounds` stays a
    /// lower bound of the exact crossings (rationals), on random nets with
    /// coefficients of mixed magnitudes, including subnormal and huge ones.
    #[test]
    fn bezier_bounds_are_below_the_exact_hull_crossings() {
        use num_rational::BigRational;
        use num_traits::{Signed, Zero};
        let mut rng = crate::rng::Rng(0x9e3779b97f4a7c15);
        let mut rnd = move || rng.next_u64();
        for case in 0..600 {
            let n = 1 + case % 6;
            let len = (n + 1) * (n + 2) / 2;
            let scale = [1.0, 1e-300, 1e300, 1e-310, 3.0][case % 5];
            let mids: Vec<f64> = (0..len)
                .map(|_| ((rnd() % 2001) as f64 - 1000.0) / 997.0 * scale)
                .collect();
            let rad = if rnd() % 3 == 0 { 0.0 } else { scale * 1e-3 };
            let f = TriBall::new(n, &mids, rad).unwrap();
            let q = |x: f64| BigRational::from_float(x).unwrap();
            // The exact coefficient ranges [m − r, m + r].
            let ends: Vec<[BigRational; 2]> = mids.iter().map(|&m| [q(m) - q(rad), q(m) + q(rad)]).collect();
            let ClipBounds::Keep(mins) = bezier_bounds(&f, true) else {
                // Empty: every endpoint strictly of one sign.
                assert!(
                    ends.iter().all(|e| e[0].is_positive()) || ends.iter().all(|e| e[1].is_negative()),
                    "case {case}"
                );
                continue;
            };
            // Exact: the smallest abscissa of the hull's crossings, per coordinate.
            let nq = BigRational::from_integer(n.into());
            let pts: Vec<([usize; 3], BigRational)> = crate::poly::tri_indices(n)
                .zip(&ends)
                .flat_map(|((i, j, k), e)| [([i, j, k], e[0].clone()), ([i, j, k], e[1].clone())])
                .collect();
            for (coord, &m) in mins.iter().enumerate() {
                let mut exact: Option<BigRational> = None;
                let mut take = |x: BigRational| {
                    if exact.as_ref().is_none_or(|e| x < *e) {
                        exact = Some(x);
                    }
                };
                for (a, ya) in &pts {
                    if ya.is_zero() {
                        take(BigRational::from_integer(a[coord].into()) / &nq);
                    }
                    for (b, yb) in &pts {
                        if ya.is_positive() && yb.is_negative() {
                            let (xa, xb) = (
                                BigRational::from_integer(a[coord].into()) / &nq,
                                BigRational::from_integer(b[coord].into()) / &nq,
                            );
                            take(&xa + (&xb - &xa) * (ya / (ya - yb)));
                        }
                    }
                }
                if let Some(e) = exact {
                    let e = e.max(BigRational::zero()).min(BigRational::from_integer(1.into()));
                    assert!(
                        q(m) <= e,
                        "case {case} coord {coord}: bound {m} above the exact crossing {e}"
                    );
                }
            }
        }
    }
}
