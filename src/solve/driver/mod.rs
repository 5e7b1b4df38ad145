//! Algorithm 1 of Liu et al. (2016) as a work-list loop over tri-boxes, generic
//! over the kernel: `Interval` for the certified solver, `f64` for the same
//! iteration without proofs (to measure the cost of rigor).
//!
//! One *step* (one call of Algorithm 1) clips a tri-box and, when the clip did
//! not halve its diameter, splits the clipped tri-box 1-to-4. The tri-boxes it
//! produces are one level deeper. Check-sign (§2.3.4) discards a tri-box when
//! every coefficient of `f` or of `g` on it has one strict sign.
//!
//! One step's phases are in `step`; the precision a tri-box's polynomials
//! are computed in (float balls, compensated, exact) is managed in
//! `precision`.

mod precision;
mod step;

use super::krawczyk::Verdict;
use super::method::Method;
use super::tribox::TriBox;
use crate::poly::{tri_index, TriBall, TriBallDD};
use crate::scalar::geo::Geo;
use crate::scalar::Sign;
pub use precision::{Exact, ExactPair, Precision, EXACT_BELOW, MAX_EXACT_BOXES};
use step::step;

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
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum SplitRule {
    /// Split when the clip did not halve the diameter (default; the reading
    /// of §2.3.5's prose, "larger than half of the size of D").
    #[default]
    #[cfg_attr(
        feature = "cli",
        value(help = "split when a clip does not halve the diameter (default)")
    )]
    Halving,
    /// Split when `u_min + v_min + w_min ≤ 0.5·diam(D)`, Algorithm 1 line 7 as
    /// printed. It mixes a barycentric sum with a length, so on small
    /// tri-boxes it almost never splits; it reproduces the paper's Bézier and
    /// linear counts closely (see papers/hybrid-clipping-2016).
    #[cfg_attr(
        feature = "cli",
        value(name = "paper", help = "split when u_min + v_min + w_min <= 0.5 diam(D), as printed")
    )]
    PaperLiteral,
}

/// What a probe (Krawczyk on a stalled tri-box) proved: a unique root in (a
/// box containing) the tri-box stops refining it, no root discards it. The
/// caller keeps the certificate; the driver needs only the verdict.
pub type Probe = Verdict<()>;

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

/// After this many undecided probes in a row, only every 16th eligible
/// tri-box is probed.
pub const FUTILE_PROBES: usize = 64;

/// With probing on, a tri-box that a clip brought below this diameter is
/// offered to Krawczyk right away.
pub const EARLY_CERTIFY: f64 = 1e-2;

/// A converging tri-box below diameter ½ whose predicted Krawczyk
/// contraction `newton_kappa` (private; see its comment) is below this is
/// probed too.
pub const KAPPA_PROBE: f64 = 0.3;

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
/// coordinates ([`newton_kappa`] and `clip_floor` read the same jets).
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
    let Some(w) = super::linalg::smallest_singular_left([a[0], a[1], b[0], b[1]]) else {
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

    pub(super) fn ball(expr: &str) -> TriBall {
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
}
