//! The state of a run: its limits, the tri-boxes in flight (leaves), the
//! recursion tree (nodes), the counters, and the stopping constants.

use crate::poly::TriBezier;
use crate::poly::{TriBall, TriBallDD};
use crate::solve::krawczyk::Verdict;
use crate::solve::method::Method;
use crate::solve::tribox::TriBox;
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
    /// No tri-box is processed after this instant.
    pub deadline: Option<std::time::Instant>,
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

/// Everything a step needs besides the tri-box: the root system (scaled), the
/// exact input, the limits and the output under construction.
pub(super) struct Ctx<'a> {
    pub(super) f: TriBall,
    pub(super) g: TriBall,
    pub(super) exact: Exact<'a>,
    /// The exact pair of [`Exact::Floats`], built on first use.
    pub(super) exact_floats: Option<ExactPair>,
    /// The root pair in double-double, built on first use.
    pub(super) dd: Option<[TriBallDD; 2]>,
    pub(super) limits: &'a Limits,
    pub(super) out: Run,
}

/// Below this diameter a stalled, undecided tri-box is not split further
/// ([`SINGULAR_FLOOR`] for float coefficients; compensated and exact
/// coefficients resolve far closer to a multiple root, and two simple roots
/// 1e-10 apart must still be separated by splitting). The finer floor holds
/// for at most [`FINE_BUDGET`] tri-boxes below [`SINGULAR_FLOOR`] per run:
/// it pays for separating a local pair of roots in a handful of splits, but
/// along a long, nearly tangential stretch of the curves it would spend the
/// whole budget on ever finer leaves.
pub(super) fn singular_floor(cx: &Ctx, precision: Precision) -> f64 {
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
pub(super) fn at_level(out: &mut Run, mut leaf: Leaf, level: usize, diam: f64) -> Leaf {
    leaf.node = push_node(out, leaf.node, level, diam);
    leaf
}

pub(super) fn push_node(out: &mut Run, parent: usize, level: usize, diam: f64) -> usize {
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

/// The default [`Limits::max_exact`](super::Limits::max_exact).
pub const MAX_EXACT_BOXES: usize = 64;

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
