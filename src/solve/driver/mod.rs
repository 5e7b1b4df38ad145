//! Algorithm 1 of Liu et al. (2016) as a work-list loop over tri-boxes, generic
//! over the kernel: `Interval` for the certified solver, `f64` for the same
//! iteration without proofs (to measure the cost of rigor).
//!
//! One *step* (one call of Algorithm 1) clips a tri-box and, when the clip did
//! not halve its diameter, splits the clipped tri-box 1-to-4. The tri-boxes it
//! produces are one level deeper. Check-sign (§2.3.4) discards a tri-box when
//! every coefficient of `f` or of `g` on it has one strict sign.

use super::fatcurve::ClipBounds;
use super::method::{clip_bounds, clip_bounds_swapped, Method};
use super::num::Geo;
use super::tribox::TriBox;
use crate::poly::dyadic::subdivide_dyadic;
use crate::poly::{tri_index, TriBall, TriBallDD, TriBezier};
use crate::scalar::Sign;
use num_rational::BigRational;

/// Budgets and tolerances of one run.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// The clipping method.
    pub method: Method,
    /// Stop refining a tri-box once its diameter is below this.
    pub eps: f64,
    /// At most this many tri-boxes are processed.
    pub max_boxes: usize,
    /// No tri-box deeper than this level is processed.
    pub max_depth: usize,
    /// At most this many tri-boxes are computed from the exact rational
    /// input ([`EXACT_BELOW`]); later ones use compensated balls (sound,
    /// only noisier). Rational coefficients grow with the input's and the
    /// vertices' sizes, so near a degenerate (triple) root an unbounded
    /// exact phase can take minutes.
    pub max_exact: usize,
    /// Probe stalled tri-boxes (clip did not halve) smaller than this with
    /// the `probe` callback of [`run`] (and converging ones below
    /// [`EARLY_CERTIFY`], or below ½ with a predicted contraction under
    /// [`KAPPA_PROBE`]); `0` disables probing (as the tables do).
    pub probe_below: f64,
    /// The split test.
    pub split: SplitRule,
    /// For [`Method::Hc`] and [`Method::HcNoPre`]: where the clip would not
    /// halve the tri-box, clip once more with the equations' roles swapped
    /// (`g` linear, preprocessed for `hc`; `f` quadratic) and keep what both
    /// clips keep, before the split test. Not in the paper's Algorithm 1
    /// (`false` runs it as printed). Each clip is rigorous, so their
    /// intersection is; it separates two close roots without the split the
    /// one-role clip needs (Example 3, k = 2 and 5).
    pub swap_roles: bool,
}

/// When a step splits the clipped tri-box 1-to-4 (Algorithm 1, line 7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SplitRule {
    /// Split when the clip did not halve the diameter (default; the reading
    /// of §2.3.5's prose, "larger than half of the size of D").
    #[default]
    Halving,
    /// Split when `u_min + v_min + w_min ≤ 0.5·diam(D)`, Algorithm 1 line 7 as
    /// printed. It mixes a barycentric sum with a length, so on small
    /// tri-boxes it almost never splits; it reproduces the paper's Bézier and
    /// linear counts closely (see papers/hybrid-clipping-2016).
    PaperLiteral,
}

/// What a probe (Krawczyk on a stalled tri-box) proved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Probe {
    /// Exactly one root in (a box containing) the tri-box: stop refining it.
    Unique,
    /// No root in the tri-box: discard it.
    NoRoot,
    /// Nothing proven.
    Undecided,
}

/// Below this diameter a stalled, undecided tri-box is not split further:
/// it sits at the precision floor of a multiple or near-multiple root, where
/// tangency amplifies the ~1e-16 rounding of the coefficients into a lens
/// ~1e-8 long that no subdivision can resolve.
pub const SINGULAR_FLOOR: f64 = 1e-9;

/// One node of the recursion tree: the tri-box at some level.
#[derive(Clone, Copy, Debug)]
pub struct Node {
    /// The node of the step that produced this one (`None` for the root).
    pub parent: Option<usize>,
    /// Steps from the root tri-box.
    pub level: usize,
    /// Longest edge.
    pub diam: f64,
}

/// A tri-box the loop stopped at, with its polynomials and tree node.
#[derive(Clone, Debug)]
pub struct Leaf {
    /// The tri-box (root-local coordinates).
    pub tb: TriBox,
    /// Its node in the trace.
    pub node: usize,
    /// `f` on the tri-box (scaled by the run's power of two).
    pub fa: TriBall,
    /// `g` on the tri-box (scaled likewise).
    pub fb: TriBall,
    /// How `fa`, `fb` were computed; tri-boxes below this one are computed
    /// at least as precisely (within the exact budget).
    pub precision: Precision,
}

/// How a tri-box's polynomials were computed from the root triangle's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Precision {
    /// Float subdivision ([`TriBall::subdivide`]): radius a few ulps of the
    /// root polynomial's largest coefficient.
    Float,
    /// Compensated subdivision ([`TriBallDD::subdivide`]): radius a few ulps
    /// of the tri-box's own coefficients.
    Compensated,
    /// Exact subdivision of the rational input, then enclosed.
    Exact,
}

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
pub const FLOOR_MARGIN: f64 = 1.0 / 16.0;

/// Whether a tri-box with noisy float balls can do without the compensated
/// recomputation: its [`clip_floor`] is below [`FLOOR_MARGIN`] of `ε` (the
/// clips still reach `ε`) *and* the system is nearly linear on it
/// ([`newton_kappa`] below [`KAPPA_PROBE`]: at most one root, simple, where
/// Krawczyk contracts). The second condition keeps the precise coefficients
/// wherever the run works on more than a clip's convergence — near-parallel
/// curves, clusters, close pairs of roots — where the sign tests, the
/// separating combination and the singular floor ([`singular_floor`]) need
/// them (the referee found runs to `ε = 1e-6` on curves 1e-9 apart that
/// certified fewer roots without it). The estimates only decide when to pay
/// for precision, never what is proven; a tri-box that stalls after all is
/// recomputed then (the stalled branch of [`step`]).
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
pub const NOISE_RATIO: f64 = 1e-9;

/// After this many undecided probes in a row, only every 16th eligible
/// tri-box is probed.
pub const FUTILE_PROBES: usize = 64;

/// The default [`Limits::max_exact`].
pub const MAX_EXACT_BOXES: usize = 64;

/// With probing on, a tri-box that a clip brought below this diameter is
/// offered to Krawczyk right away.
pub const EARLY_CERTIFY: f64 = 1e-2;

/// A converging tri-box below diameter ½ whose predicted Krawczyk
/// contraction `newton_kappa` (private; see its comment) is below this is
/// probed too.
pub const KAPPA_PROBE: f64 = 0.3;

/// The exact input, when there is one (rational coefficients).
pub type ExactPair = [TriBezier<BigRational>; 2];

/// What a run knows exactly about its input system.
#[derive(Clone, Copy, Debug)]
pub enum Exact<'a> {
    /// Nothing beyond the input balls.
    None,
    /// The system is these rational polynomials (on the root triangle,
    /// unscaled).
    Rational(&'a ExactPair),
    /// The input balls have radius 0: their float coefficients are the
    /// system (its rationals are built only if an exact restart needs them).
    Floats,
}

/// Counters of one run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Tri-boxes processed (clipped).
    pub boxes: usize,
    /// Clips that shrank a tri-box.
    pub clips: usize,
    /// 1-to-4 splits.
    pub splits: usize,
    /// Tri-boxes discarded by check-sign.
    pub sign_exclusions: usize,
    /// Tri-boxes discarded because the fat regions (or hulls) do not meet.
    pub clip_exclusions: usize,
    /// Krawczyk probes of stalled tri-boxes.
    pub probes: usize,
    /// Tri-boxes discarded by a probe.
    pub probe_exclusions: usize,
    /// Tri-boxes recomputed in compensated arithmetic (noisy or stalled).
    pub compensated_restarts: usize,
    /// Tri-boxes whose polynomials were computed in compensated arithmetic.
    pub compensated_boxes: usize,
    /// Stalled tri-boxes recomputed from the exact input.
    pub exact_restarts: usize,
    /// Tri-boxes whose polynomials were computed from the exact input.
    pub exact_boxes: usize,
    /// Second hybrid clips with the equations' roles swapped
    /// ([`Limits::swap_roles`]).
    pub role_swaps: usize,
}

/// What the loop produced.
#[derive(Clone, Debug)]
pub struct Run {
    /// Tri-boxes with diameter below `eps` (or too small to split further).
    pub leaves: Vec<Leaf>,
    /// Tri-boxes left unprocessed by a budget.
    pub leftovers: Vec<Leaf>,
    /// The recursion tree.
    pub nodes: Vec<Node>,
    /// Counters.
    pub counters: Counters,
    /// Probes in a row that proved nothing (see [`FUTILE_PROBES`]).
    pub futile_probes: usize,
    /// Stalled undecided tri-boxes met below [`SINGULAR_FLOOR`] (see
    /// [`singular_floor`]).
    pub fine_boxes: usize,
    /// Strips `[[u_lo, u_hi], [v_lo, v_hi]]` cut off the root triangle along
    /// edges where both equations may vanish ([`vanishing_edges`]); they are
    /// undecided regions, never explored.
    pub strips: Vec<[[f64; 2]; 2]>,
    /// The power of two `e` the system was scaled by (`2^e f`, `2^e g`:
    /// the same roots; see [`TriBall::normalizing_exponent`]).
    pub scale_exp: i32,
}

/// A strict sign shared by every coefficient of every member (check-sign):
/// the polynomial has that sign on the whole tri-box. A proof for balls; for
/// the plain iteration, the radius is its noise estimate.
pub fn uniform_sign(f: &TriBall) -> Option<Sign> {
    f.strict_sign()
}

/// Everything a step needs besides the tri-box: the root system (scaled), the
/// exact input, the limits and the output under construction.
struct Ctx<'a> {
    f: TriBall,
    g: TriBall,
    exact: Exact<'a>,
    /// The exact pair of [`Exact::Floats`], built on first use.
    exact_floats: Option<ExactPair>,
    /// The root pair in double-double, built on first use.
    dd: Option<[TriBallDD; 2]>,
    limits: &'a Limits,
    out: Run,
}

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

/// Runs Algorithm 1 on the root triangle, on which `f` and `g` are given
/// (same degree). `probe` is asked about stalled small tri-boxes (see
/// [`Limits::probe_below`]). `G` is the geometry kernel (module docs).
pub fn run<G: Geo>(
    f: &TriBall,
    g: &TriBall,
    exact: Exact,
    limits: &Limits,
    probe: &mut dyn FnMut(&TriBox) -> Probe,
) -> Run {
    let scale_exp = TriBall::normalizing_exponent(&[f, g]);
    let (fs, gs) = (f.scaled_pow2(scale_exp), g.scaled_pow2(scale_exp));
    let exact = match exact {
        _ if !G::RIGOROUS => Exact::None,
        // The balls are the system only while they are points.
        Exact::Floats if fs.rad() > 0.0 || gs.rad() > 0.0 => Exact::None,
        e => e,
    };
    let mut cx = Ctx {
        f: fs,
        g: gs,
        exact,
        exact_floats: None,
        dd: None,
        limits,
        out: Run {
            leaves: Vec::new(),
            leftovers: Vec::new(),
            nodes: Vec::new(),
            counters: Counters::default(),
            futile_probes: 0,
            fine_boxes: 0,
            strips: Vec::new(),
            scale_exp,
        },
    };
    if uniform_sign(&cx.f).is_some() || uniform_sign(&cx.g).is_some() {
        cx.out.counters.sign_exclusions += 1;
        return cx.out;
    }
    let (root, fa, fb) = cut_vanishing_edges(&cx.f, &cx.g, &mut cx.out.strips);
    cx.out.nodes.push(Node {
        parent: None,
        level: 0,
        diam: root.diam(),
    });
    let mut stack = vec![Leaf {
        tb: root,
        node: 0,
        fa,
        fb,
        precision: Precision::Float,
    }];
    while let Some(item) = stack.pop() {
        let node = cx.out.nodes[item.node];
        if item.tb.diam() < limits.eps || too_small(&item.tb) {
            cx.out.leaves.push(item);
            continue;
        }
        if cx.out.counters.boxes >= limits.max_boxes || node.level >= limits.max_depth {
            cx.out.leftovers.push(item);
            continue;
        }
        cx.out.counters.boxes += 1;
        step::<G>(&mut cx, item, &mut stack, probe);
    }
    cx.out
}

/// What the combination `w_f f + w_g g` that is closest to vanishing says
/// about a stalled tri-box (`w` the left singular vector of the smallest
/// singular value of the Jacobian at its centre; or `f`, `g` themselves).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Combination {
    /// Its coefficients share a strict sign: every root of the system is a
    /// root of it, so the tri-box holds none. Near a multiple root `f` and
    /// `g` keep mixed signs over a wide neighbourhood while their difference
    /// is already one-signed; without this test Bézier clipping split that
    /// neighbourhood into tens of thousands of tri-boxes.
    NoRoot,
    /// Every coefficient (of `f`, `g` or the combination) may be zero: the
    /// sign that would separate the curves is lost to rounding on the whole
    /// tri-box, and subdivision cannot restore it (a child's coefficients are
    /// convex combinations of these, so they contain 0 too); only exact
    /// coefficients could. Such a tri-box is a leaf whatever its size: near
    /// a root of multiplicity `k` the region is about the `k`-th root of the
    /// rounding wide (~1e-8 for a double root, ~1e-5 for a triple one).
    Lost,
    /// Neither.
    Open,
}

/// A Kantorovich-style prediction (float, no proof: it only decides whether
/// a probe is worth its cost) of how far Krawczyk's operator is from
/// contracting on a tri-box:
/// ```text
/// κ = ‖J⁻¹‖∞-weighted curvature = max_i Σ_k |(J⁻¹)_ik| (|h_uu| + 2|h_uv| + |h_vv|)_k
/// ```
/// with the Jacobian `J` and the Hessians `h` of `(f, g)` at the centroid,
/// in the tri-box's own (unit-triangle) coordinates, where the box has size
/// ~1. `‖I − J⁻¹ J(X)‖ ≲ κ · size`, so Krawczyk contracts when κ is well
/// below 1. Measured on 600 random dense systems (degrees 2–6, half of them
/// with a planted root; converging tri-boxes between 1e-2 and 0.5 in
/// diameter): a 2-round probe certified all 28 tri-boxes with κ < 0.1, 80%
/// of those with κ in [0.1, 0.32), 20% in [0.32, 1), none of ~380 above 1. A failed probe
/// costs about a third of a clip, so probing pays above ~25% success:
/// [`KAPPA_PROBE`] = 0.3. `∞` for a singular `J` (or non-finite jets).
fn newton_kappa(f: &TriBall, g: &TriBall) -> f64 {
    kappa_of(&CentreJets::of(f, g))
}

/// The gradients `a`, `b` and Hessians `ha`, `hb` of the midpoint
/// polynomials of `f` and `g` at the tri-box's centroid, in its own
/// coordinates ([`newton_kappa`] and [`clip_floor`] read the same jets).
struct CentreJets {
    a: [f64; 2],
    ha: [f64; 3],
    b: [f64; 2],
    hb: [f64; 3],
}

impl CentreJets {
    fn of(f: &TriBall, g: &TriBall) -> Self {
        let centre = [1.0 / 3.0; 3];
        let (_, a, ha) = f.jet2(&centre);
        let (_, b, hb) = g.jet2(&centre);
        Self { a, ha, b, hb }
    }
}

/// [`newton_kappa`] from the jets.
fn kappa_of(&CentreJets { a, ha, b, hb }: &CentreJets) -> f64 {
    let det = a[0] * b[1] - a[1] * b[0];
    let y = [[b[1] / det, -a[1] / det], [-b[0] / det, a[0] / det]];
    let hn = |h: [f64; 3]| h[0].abs() + 2.0 * h[1].abs() + h[2].abs();
    let (na, nb) = (hn(ha), hn(hb));
    let k = (y[0][0].abs() * na + y[0][1].abs() * nb).max(y[1][0].abs() * na + y[1][1].abs() * nb);
    if k.is_finite() {
        k
    } else {
        f64::INFINITY
    }
}

fn separating_combination(f: &TriBall, g: &TriBall) -> Combination {
    if f.degree() != g.degree() {
        return Combination::Open;
    }
    if f.sign_lost() || g.sign_lost() {
        return Combination::Lost;
    }
    let centre = [1.0 / 3.0; 3];
    let (_, a, _) = f.jet2(&centre);
    let (_, b, _) = g.jet2(&centre);
    let Some(w) = super::method::smallest_singular_left([a[0], a[1], b[0], b[1]]) else {
        return Combination::Open;
    };
    let norm = w[0].abs().max(w[1].abs());
    if !(norm > 0.0 && norm.is_finite()) {
        return Combination::Open;
    }
    let h = TriBall::combine(w[0] / norm, f, w[1] / norm, g);
    if h.strict_sign().is_some() {
        Combination::NoRoot
    } else if h.sign_lost() {
        Combination::Lost
    } else {
        Combination::Open
    }
}

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
fn cut_vanishing_edges(f: &TriBall, g: &TriBall, strips: &mut Vec<[[f64; 2]; 2]>) -> (TriBox, TriBall, TriBall) {
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
fn too_small(tb: &TriBox) -> bool {
    let scale = tb.verts.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
    tb.diam() < 8.0 * f64::EPSILON * scale
}

/// The pair on `tb` at `precision` (counted): by float or compensated ball
/// subdivision of the root pair, or from the exact input (enclosed, then
/// scaled like the run's system). Exact falls back to compensated when the
/// exact input or its budget is gone.
fn restrict_pair(cx: &mut Ctx, precision: Precision, tb: &TriBox) -> (TriBall, TriBall, Precision) {
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
fn finer(cx: &Ctx, precision: Precision, diam: f64) -> Option<Precision> {
    match precision {
        Precision::Float => Some(Precision::Compensated),
        Precision::Compensated if cx.exact_left() && diam < EXACT_BELOW => Some(Precision::Exact),
        _ => None,
    }
}

/// Below this diameter a stalled, undecided tri-box is not split further
/// ([`SINGULAR_FLOOR`] for float coefficients; compensated and exact
/// coefficients resolve far closer to a multiple root, and two simple roots
/// 1e-10 apart must still be separated by splitting). The finer floor holds
/// for at most [`FINE_BUDGET`] tri-boxes below [`SINGULAR_FLOOR`] per run:
/// it pays for separating a local pair of roots in a handful of splits, but
/// along a long, nearly tangential stretch of the curves it would spend the
/// whole budget on ever finer leaves.
fn singular_floor(cx: &Ctx, precision: Precision) -> f64 {
    match precision {
        Precision::Compensated | Precision::Exact if cx.out.fine_boxes < FINE_BUDGET => SINGULAR_FLOOR_PRECISE,
        _ => SINGULAR_FLOOR,
    }
}

/// See [`singular_floor`].
pub const FINE_BUDGET: usize = 256;

/// [`singular_floor`] for compensated and exact coefficients: their noise is
/// a few ulps of the tri-box's own coefficients (plus ~1e-30 of the root's),
/// so near a double root (coefficients ~h² at diameter h) the sign of the
/// separating combination is resolvable to h ~ 1e-15; this stays clear of
/// the float grid of the vertices.
pub const SINGULAR_FLOOR_PRECISE: f64 = 1e-13;

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

/// One step of Algorithm 1 on `item` (see the module docs), phase by phase:
/// the pair at the working precision, the separating-combination test, the
/// clip, check-sign on the kept tri-box, a more precise restart where it
/// stalled at the rounding floor, the probe, and the decision — a leaf, clip
/// again, or split 1-to-4. Every exclusion is counted where it happens.
fn step<G: Geo>(cx: &mut Ctx, item: Leaf, stack: &mut Vec<Leaf>, probe: &mut dyn FnMut(&TriBox) -> Probe) {
    let level = cx.out.nodes[item.node].level + 1;
    let diam = item.tb.diam();
    let item = at_working_precision::<G>(cx, item, diam);
    if combination_excludes(cx, &item) {
        return;
    }
    let Some(mins) = clip_mins::<G>(cx, &item) else {
        return;
    };
    let leaf = clip_to::<G>(cx, item, mins, diam);
    if sign_excludes(cx, &leaf.fa, &leaf.fb) {
        return;
    }
    let new_diam = leaf.tb.diam();
    let kept = Clipped {
        progressed: cx.limits.split.progressed(mins, diam, new_diam),
        leaf,
        level,
        diam: new_diam,
    };
    if let Some(next) = stalled_finer::<G>(cx, &kept) {
        return restart_finer(cx, kept, next, stack);
    }
    let (probed, verdict) = probe_clipped(cx, &kept, probe);
    match decide::<G>(cx, &kept, probed, verdict) {
        Decision::Excluded => {}
        Decision::Leaf => {
            let leaf = kept.into_child(&mut cx.out);
            cx.out.leaves.push(leaf);
        }
        Decision::Continue => stack.push(kept.into_child(&mut cx.out)),
        Decision::Split => split_and_push(cx, kept, stack),
    }
}

/// A tri-box after the clip of a [`step`] and its check-sign: what the later
/// phases read.
struct Clipped {
    /// The kept tri-box and its pair; `node` is still the parent's.
    leaf: Leaf,
    /// The level of the tri-boxes this step produces.
    level: usize,
    /// The kept tri-box's diameter.
    diam: f64,
    /// Whether the clip made enough progress to skip the split
    /// ([`SplitRule::progressed`]).
    progressed: bool,
}

impl Clipped {
    /// The kept tri-box recorded in the trace as a child at its level.
    fn into_child(self, out: &mut Run) -> Leaf {
        at_level(out, self.leaf, self.level, self.diam)
    }
}

/// What a [`step`] does with a clipped tri-box after its probe.
enum Decision {
    /// Proven free of roots (already counted): dropped.
    Excluded,
    /// Refined no further: certified unique by the probe, its separating sign
    /// lost to rounding, or stalled below the singular floor.
    Leaf,
    /// The clip progressed: clip it again.
    Continue,
    /// Stalled: split it 1-to-4.
    Split,
}

impl SplitRule {
    /// Whether a clip from diameter `diam` to `new_diam` with bounds `mins`
    /// made progress: no split then (Algorithm 1, line 7).
    fn progressed(self, mins: [f64; 3], diam: f64, new_diam: f64) -> bool {
        match self {
            SplitRule::Halving => new_diam <= 0.5 * diam,
            SplitRule::PaperLiteral => mins.iter().sum::<f64>() > 0.5 * diam && new_diam < diam,
        }
    }
}

/// `item` recomputed more precisely (same tri-box, same level) before the
/// clip is spoiled by rounding, as long as a finer precision helps
/// ([`needs_finer`], [`finer`]); `diam` is the tri-box's diameter.
fn at_working_precision<G: Geo>(cx: &mut Ctx, mut item: Leaf, diam: f64) -> Leaf {
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
fn restart_pair(cx: &mut Ctx, next: Precision, tb: &TriBox) -> (TriBall, TriBall, Precision) {
    if next == Precision::Exact {
        cx.out.counters.exact_restarts += 1;
    } else {
        cx.out.counters.compensated_restarts += 1;
    }
    restrict_pair(cx, next, tb)
}

/// Whether the separating combination of `item`'s pair is one-signed
/// (counted as a sign exclusion).
///
/// Every root is a root of any combination w_f f + w_g g: one that is
/// one-signed on the tri-box excludes it for the price of two jets and a
/// combination, before the (far costlier) clip. The combination closest to
/// vanishing at the centre varies least over the tri-box, so it is the
/// likeliest to keep one sign where the curves pass without meeting.
fn combination_excludes(cx: &mut Ctx, item: &Leaf) -> bool {
    let excluded = separating_combination(&item.fa, &item.fb) == Combination::NoRoot;
    if excluded {
        cx.out.counters.sign_exclusions += 1;
    }
    excluded
}

/// Check-sign: whether `fa` or `fb` has one strict sign on its tri-box
/// (counted as a sign exclusion).
fn sign_excludes(cx: &mut Ctx, fa: &TriBall, fb: &TriBall) -> bool {
    let excluded = uniform_sign(fa).is_some() || uniform_sign(fb).is_some();
    if excluded {
        cx.out.counters.sign_exclusions += 1;
    }
    excluded
}

/// The clip bounds of `item` by the run's method (with the roles swapped as
/// well where [`Limits::swap_roles`] asks), `None` when they prove it empty
/// (counted as a clip exclusion).
fn clip_mins<G: Geo>(cx: &mut Ctx, item: &Leaf) -> Option<[f64; 3]> {
    let limits = cx.limits;
    let incenter = item.tb.incenter_bary();
    let bounds = if limits.swap_roles && matches!(limits.method, Method::Hc | Method::HcNoPre) {
        // Where the clip keeps more than half, the clip with f and g swapped
        // as well (its fat line is g's), intersected.
        let (bounds, swapped) = clip_bounds_swapped::<G>(limits.method, &item.fa, &item.fb, incenter);
        cx.out.counters.role_swaps += usize::from(swapped);
        bounds
    } else {
        clip_bounds::<G>(limits.method, &item.fa, &item.fb, incenter)
    };
    match bounds {
        ClipBounds::Empty => {
            cx.out.counters.clip_exclusions += 1;
            None
        }
        ClipBounds::Keep(m) => Some(m),
    }
}

/// `item` clipped to `mins` (verified in a rigorous kernel) and its pair
/// restricted to the kept tri-box, where that is smaller than `diam`
/// (counted); else `item` itself.
fn clip_to<G: Geo>(cx: &mut Ctx, item: Leaf, mins: [f64; 3], diam: f64) -> Leaf {
    let clipped = if mins.iter().sum::<f64>() > 0.0 {
        if G::RIGOROUS {
            item.tb.clip(mins)
        } else {
            item.tb.clip_unverified(mins)
        }
    } else {
        None
    };
    match clipped {
        Some(tb) if tb.diam() < diam => {
            cx.out.counters.clips += 1;
            let (fa, fb, precision) = restrict_pair(cx, item.precision, &tb);
            Leaf {
                tb,
                fa,
                fb,
                precision,
                ..item
            }
        }
        _ => item,
    }
}

/// The finer precision a rigorous run recomputes a stalled tri-box in, when
/// it is below [`EXACT_BELOW`] (the rounding floor) and there is one.
fn stalled_finer<G: Geo>(cx: &Ctx, kept: &Clipped) -> Option<Precision> {
    if G::RIGOROUS && !kept.progressed && kept.diam < EXACT_BELOW {
        finer(cx, kept.leaf.precision, kept.diam)
    } else {
        None
    }
}

/// Stalled at the rounding floor: the kept tri-box at precision `next`,
/// pushed as a child to redo.
fn restart_finer(cx: &mut Ctx, kept: Clipped, next: Precision, stack: &mut Vec<Leaf>) {
    let (fa, fb, precision) = restart_pair(cx, next, &kept.leaf.tb);
    let node = push_node(&mut cx.out, kept.leaf.node, kept.level, kept.diam);
    stack.push(Leaf {
        node,
        fa,
        fb,
        precision,
        ..kept.leaf
    });
}

/// Whether the kept tri-box is to be probed, and the probe's verdict
/// (`Undecided` when not probed, or throttled).
///
/// Probes: a converging clip below EARLY_CERTIFY, or below ½ where
/// newton_kappa predicts contraction, may already be certified
/// (Krawczyk's contraction then converges quadratically without further
/// clips); a stalled one below `probe_below` may be certified or excluded,
/// and below SINGULAR_FLOOR it is not split further.
fn probe_clipped(cx: &mut Ctx, kept: &Clipped, probe: &mut dyn FnMut(&TriBox) -> Probe) -> (bool, Probe) {
    let (new_diam, next) = (kept.diam, &kept.leaf);
    let probe_here = cx.limits.probe_below > 0.0
        && if kept.progressed {
            new_diam < EARLY_CERTIFY || (new_diam < 0.5 && newton_kappa(&next.fa, &next.fb) < KAPPA_PROBE)
        } else {
            new_diam < cx.limits.probe_below
        };
    // After a long run of futile probes (all undecided: curves running
    // within a hair of each other over a long stretch, where every tri-box
    // stalls), probe only every 16th tri-box; a probe only saves work.
    let throttled = cx.out.futile_probes >= FUTILE_PROBES && cx.out.counters.boxes % 16 != 0;
    let verdict = if probe_here && !throttled {
        cx.out.counters.probes += 1;
        let v = probe(&next.tb);
        cx.out.futile_probes = if v == Probe::Undecided {
            cx.out.futile_probes + 1
        } else {
            0
        };
        v
    } else {
        Probe::Undecided
    };
    (probe_here, verdict)
}

/// What becomes of the kept tri-box after its probe (`probed`: it was to be
/// probed; exclusions counted): a stalled, probed, undecided tri-box of a
/// rigorous run gets the separating-combination test on its new pair, and
/// stops at the singular floor ([`singular_floor`]).
fn decide<G: Geo>(cx: &mut Ctx, kept: &Clipped, probed: bool, verdict: Probe) -> Decision {
    let (new_diam, progressed) = (kept.diam, kept.progressed);
    let stop_here = match verdict {
        Probe::NoRoot => {
            cx.out.counters.probe_exclusions += 1;
            return Decision::Excluded;
        }
        Probe::Unique => true,
        Probe::Undecided if !progressed && probed && G::RIGOROUS => {
            match separating_combination(&kept.leaf.fa, &kept.leaf.fb) {
                Combination::NoRoot => {
                    cx.out.counters.sign_exclusions += 1;
                    return Decision::Excluded;
                }
                Combination::Lost => true,
                Combination::Open => {
                    if new_diam < SINGULAR_FLOOR {
                        cx.out.fine_boxes += 1;
                    }
                    new_diam < singular_floor(cx, kept.leaf.precision)
                }
            }
        }
        Probe::Undecided => false,
    };
    if stop_here {
        Decision::Leaf
    } else if progressed {
        Decision::Continue
    } else {
        Decision::Split
    }
}

/// The kept tri-box split 1-to-4, each child's pair restricted at the kept
/// tri-box's precision and pushed unless check-sign excludes it; a tri-box
/// too small to split is a leaf.
fn split_and_push(cx: &mut Ctx, kept: Clipped, stack: &mut Vec<Leaf>) {
    let Some(kids) = kept.leaf.tb.split4() else {
        // Collapsed at the rounding floor: hand it to the certification phase.
        let leaf = kept.into_child(&mut cx.out);
        return cx.out.leaves.push(leaf);
    };
    cx.out.counters.splits += 1;
    let (precision, parent) = (kept.leaf.precision, kept.leaf.node);
    // Push in reverse so the corner at V1 is processed first.
    for kid in kids.into_iter().rev() {
        let (ka, kb, precision) = restrict_pair(cx, precision, &kid);
        if sign_excludes(cx, &ka, &kb) {
            continue;
        }
        let node = push_node(&mut cx.out, parent, kept.level, kid.diam());
        stack.push(Leaf {
            tb: kid,
            node,
            fa: ka,
            fb: kb,
            precision,
        });
    }
}

/// `leaf` (whose `node` is its parent's) recorded in the trace as a child at `level`.
fn at_level(out: &mut Run, mut leaf: Leaf, level: usize, diam: f64) -> Leaf {
    leaf.node = push_node(out, leaf.node, level, diam);
    leaf
}

fn push_node(out: &mut Run, parent: usize, level: usize, diam: f64) -> usize {
    out.nodes.push(Node {
        parent: Some(parent),
        level,
        diam,
    });
    out.nodes.len() - 1
}

/// The diameters along the path from the root to `node`, indexed by level.
pub fn path_diameters(nodes: &[Node], node: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let mut cur = Some(node);
    while let Some(i) = cur {
        out.push(nodes[i].diam);
        cur = nodes[i].parent;
    }
    out.reverse();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::rational_to_f64;
    use crate::solve::num::GeoIv;

    fn ball(expr: &str) -> TriBall {
        let p = crate::parse_polynomial(expr).unwrap().to_triangle(2);
        TriBall::from_points(&p.map(rational_to_f64))
    }

    /// κ on the unit triangle against values worked by hand: 0 for a linear
    /// system (Newton is exact), `max_i Σ_k |(J⁻¹)_ik| ‖h_k‖` for a circle
    /// and a line at the centroid (J = [[2/3, 2/3], [1, −1]], J⁻¹ =
    /// [[3/4, 1/2], [3/4, −1/2]], ‖h_f‖ = 2 + 0 + 2 = 4, h_g = 0: κ = 3), ∞ for
    /// parallel gradients.
    #[test]
    fn newton_kappa_by_hand() {
        assert_eq!(newton_kappa(&ball("u - 1/3"), &ball("v - 1/4")), 0.0);
        let k = newton_kappa(&ball("u^2 + v^2 - 1/4"), &ball("u - v"));
        assert!((k - 3.0).abs() < 1e-12, "{k}");
        assert_eq!(newton_kappa(&ball("u - v"), &ball("2*u - 2*v + 1")), f64::INFINITY);
    }

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
