//! Algorithm 1 of Liu et al. (2016) as a work-list loop over tri-boxes, generic
//! over the kernel: `Interval` for the certified solver, `f64` for the same
//! iteration without proofs (to measure the cost of rigor).
//!
//! One *step* (one call of Algorithm 1) clips a tri-box and, when the clip did
//! not halve its diameter, splits the clipped tri-box 1-to-4. The tri-boxes it
//! produces are one level deeper. Check-sign (§2.3.4) discards a tri-box when
//! every coefficient of `f` or of `g` on it has one strict sign.

use super::fatcurve::{intersect_bounds, ClipBounds};
use super::method::{clip_bounds_with, Method};
use super::num::Num;
use super::tribox::TriBox;
use crate::poly::dyadic::subdivide_dyadic;
use crate::poly::TriBezier;
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
    /// input ([`EXACT_BELOW`]); later ones use the interval kernel (sound,
    /// only noisier). Rational coefficients grow with the input's and the
    /// vertices' sizes, so near a degenerate (triple) root an unbounded
    /// exact phase can take minutes.
    pub max_exact: usize,
    /// Probe stalled tri-boxes (clip did not halve) smaller than this with
    /// the `probe` callback of [`run`]; `0` disables probing (as the tables
    /// do).
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
pub struct Leaf<S> {
    /// The tri-box (root-local coordinates).
    pub tb: TriBox,
    /// Its node in the trace.
    pub node: usize,
    /// `f` on the tri-box.
    pub fa: TriBezier<S>,
    /// `g` on the tri-box.
    pub fb: TriBezier<S>,
    /// `fa`, `fb` were computed exactly (rationals, then enclosed), as are the
    /// polynomials of every tri-box below this one.
    pub exact: bool,
}

/// Below this diameter a stalled tri-box is recomputed from the exact input:
/// the interval coefficients carry ~1e-16 absolute rounding from the root
/// triangle's scale, which near a tangential intersection (small angle θ)
/// limits clipping to ~1e-16/θ; exact coefficients enclosed afresh carry
/// rounding relative to their own (tiny) size.
pub const EXACT_BELOW: f64 = 1e-6;

/// Coefficient enclosures wider than `1e-4` of the largest coefficient: the
/// rounding inherited from the root triangle's scale starts to dominate.
fn noisy<S: Num>(p: &TriBezier<S>) -> bool {
    if !S::KERNEL.is_rigorous() {
        return false;
    }
    let (mut width, mut size) = (0.0f64, 0.0f64);
    for c in p.coeffs() {
        width = width.max(c.upper() - c.lower());
        size = size.max(c.mag());
    }
    width > 1e-4 * size
}

/// After this many undecided probes in a row, only every 16th eligible
/// tri-box is probed.
pub const FUTILE_PROBES: usize = 64;

/// The default [`Limits::max_exact`].
pub const MAX_EXACT_BOXES: usize = 64;

/// With probing on, a tri-box that a clip brought below this diameter is
/// offered to Krawczyk right away.
pub const EARLY_CERTIFY: f64 = 1e-2;

/// The exact input, when there is one (rational coefficients).
pub type ExactPair = [TriBezier<BigRational>; 2];

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
pub struct Run<S> {
    /// Tri-boxes with diameter below `eps` (or too small to split further).
    pub leaves: Vec<Leaf<S>>,
    /// Tri-boxes left unprocessed by a budget.
    pub leftovers: Vec<Leaf<S>>,
    /// The recursion tree.
    pub nodes: Vec<Node>,
    /// Counters.
    pub counters: Counters,
    /// Probes in a row that proved nothing (see [`FUTILE_PROBES`]).
    pub futile_probes: usize,
    /// Strips `[[u_lo, u_hi], [v_lo, v_hi]]` cut off the root triangle along
    /// edges where both equations may vanish ([`vanishing_edges`]); they are
    /// undecided regions, never explored.
    pub strips: Vec<[[f64; 2]; 2]>,
    /// The float kernel's absolute coefficient noise (0 for the rigorous
    /// kernels): added to fat-curve widths and check-sign thresholds.
    pub noise: f64,
}

/// Check-sign with untracked noise (plain `f64`): every coefficient of one
/// strict sign and, in the float kernel, larger than `noise` in magnitude.
fn signed_beyond<S: Num>(f: &TriBezier<S>, noise: f64) -> bool {
    uniform_sign(f).is_some() && (S::KERNEL.is_rigorous() || f.coeffs().iter().all(|c| c.mag() > noise))
}

/// The absolute rounding noise of coefficients computed in plain `f64` from
/// `f` and `g` by subdivision: `64·n·2⁻⁵³·max|coefficient|` (de Casteljau
/// errs by a few units in the last place of the largest coefficient per
/// step). 0 for the rigorous kernels, whose enclosures carry their errors.
fn float_noise<S: Num>(f: &TriBezier<S>, g: &TriBezier<S>) -> f64 {
    if S::KERNEL.is_rigorous() {
        return 0.0;
    }
    let m = f.coeffs().iter().chain(g.coeffs()).map(|c| c.mag()).fold(0.0, f64::max);
    64.0 * f.degree().max(g.degree()).max(1) as f64 * f64::EPSILON * 0.5 * m
}

/// A strict sign shared by every coefficient (the polynomial has that sign on
/// the whole tri-box), rigorous for the interval kernel.
pub fn uniform_sign<S: Num>(f: &TriBezier<S>) -> Option<Sign> {
    let first = f.coeffs()[0].sign_class();
    let strict = matches!(first, Sign::Positive | Sign::Negative);
    (strict && f.coeffs().iter().all(|c| c.sign_class() == first)).then_some(first)
}

/// Runs Algorithm 1 on the root triangle, on which `f` and `g` are given.
/// `probe` is asked about stalled small tri-boxes (see [`Limits::probe_below`]).
pub fn run<S: Num>(
    f: &TriBezier<S>,
    g: &TriBezier<S>,
    exact: Option<&ExactPair>,
    limits: &Limits,
    probe: &mut dyn FnMut(&TriBox) -> Probe,
) -> Run<S> {
    let mut out = Run {
        leaves: Vec::new(),
        leftovers: Vec::new(),
        nodes: Vec::new(),
        counters: Counters::default(),
        futile_probes: 0,
        strips: Vec::new(),
        noise: float_noise(f, g),
    };
    if uniform_sign(f).is_some() || uniform_sign(g).is_some() {
        out.counters.sign_exclusions += 1;
        return out;
    }
    let (root, fa, fb) = cut_vanishing_edges(f, g, &mut out.strips);
    out.nodes.push(Node {
        parent: None,
        level: 0,
        diam: root.diam(),
    });
    let mut stack = vec![Leaf {
        tb: root,
        node: 0,
        fa,
        fb,
        exact: false,
    }];
    while let Some(item) = stack.pop() {
        let node = out.nodes[item.node];
        if item.tb.diam() < limits.eps || too_small(&item.tb) {
            out.leaves.push(item);
            continue;
        }
        if out.counters.boxes >= limits.max_boxes || node.level >= limits.max_depth {
            out.leftovers.push(item);
            continue;
        }
        out.counters.boxes += 1;
        step(f, g, exact, item, limits, &mut out, &mut stack, probe);
    }
    out
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

fn separating_combination<S: Num>(f: &TriBezier<S>, g: &TriBezier<S>) -> Combination {
    if !S::KERNEL.is_rigorous() || f.degree() != g.degree() {
        return Combination::Open;
    }
    fn lost<S: Num>(mut c: impl Iterator<Item = S>) -> bool {
        c.all(|c| matches!(c.sign_class(), Sign::Zero | Sign::Straddles))
    }
    if lost(f.coeffs().iter().copied()) || lost(g.coeffs().iter().copied()) {
        return Combination::Lost;
    }
    let centre = [1.0 / 3.0; 3];
    let (_, a, _) = f.map(|x| x.to_f64()).jet2(&centre);
    let (_, b, _) = g.map(|x| x.to_f64()).jet2(&centre);
    let Some(w) = super::method::smallest_singular_left([a[0], a[1], b[0], b[1]]) else {
        return Combination::Open;
    };
    let norm = w[0].abs().max(w[1].abs());
    if !(norm > 0.0 && norm.is_finite()) {
        return Combination::Open;
    }
    let (wf, wg) = (S::pt(w[0] / norm), S::pt(w[1] / norm));
    let h = TriBezier::new(
        f.degree(),
        f.coeffs()
            .iter()
            .zip(g.coeffs())
            .map(|(x, y)| wf * *x + wg * *y)
            .collect(),
    )
    .expect("same degree");
    if uniform_sign(&h).is_some() {
        Combination::NoRoot
    } else if lost(h.coeffs().iter().copied()) {
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
pub fn vanishing_edges<S: Num>(f: &TriBezier<S>, g: &TriBezier<S>) -> [bool; 2] {
    let edge = |p: &TriBezier<S>, along_v: bool| {
        let n = p.degree();
        let scale = p.coeffs().iter().map(|c| c.mag()).fold(0.0, f64::max);
        let tiny = |c: &S| matches!(c.sign_class(), Sign::Zero | Sign::Straddles) || c.mag() <= VANISHING * scale;
        (0..=n).all(|k| tiny(if along_v { p.coeff(0, k) } else { p.coeff(k, 0) }))
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
fn cut_vanishing_edges<S: Num>(
    f: &TriBezier<S>,
    g: &TriBezier<S>,
    strips: &mut Vec<[[f64; 2]; 2]>,
) -> (TriBox, TriBezier<S>, TriBezier<S>) {
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
    let (fa, fb) = (restrict(f, &tb), restrict(g, &tb));
    (tb, fa, fb)
}

/// A tri-box whose vertices are a few ulps apart cannot be clipped or split
/// reliably any more.
fn too_small(tb: &TriBox) -> bool {
    let scale = tb.verts.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
    tb.diam() < 8.0 * f64::EPSILON * scale
}

fn restrict<S: Num>(f: &TriBezier<S>, tb: &TriBox) -> TriBezier<S> {
    let verts = tb
        .verts
        .map(|[s, t]| [S::pt(s), S::pt(t), S::pt(1.0) - S::pt(s) - S::pt(t)]);
    f.subdivide(&verts)
}

/// The pair on `tb`: from the exact input (then enclosed) when `use_exact`,
/// otherwise in the kernel's arithmetic.
fn restrict_pair<S: Num>(
    f: &TriBezier<S>,
    g: &TriBezier<S>,
    exact: Option<&ExactPair>,
    use_exact: bool,
    tb: &TriBox,
) -> (TriBezier<S>, TriBezier<S>) {
    match exact {
        Some([fe, ge]) if use_exact => {
            // Integer arithmetic over common denominators (no gcds).
            let enclose = |p: &TriBezier<BigRational>| {
                let c = subdivide_dyadic(p, &tb.verts).expect("tri-box vertices are finite");
                TriBezier::new(p.degree(), c.iter().map(S::from_rational).collect()).expect("same degree")
            };
            (enclose(fe), enclose(ge))
        }
        _ => (restrict(f, tb), restrict(g, tb)),
    }
}

#[allow(clippy::too_many_arguments)]
fn step<S: Num>(
    f: &TriBezier<S>,
    g: &TriBezier<S>,
    exact: Option<&ExactPair>,
    mut item: Leaf<S>,
    limits: &Limits,
    out: &mut Run<S>,
    stack: &mut Vec<Leaf<S>>,
    probe: &mut dyn FnMut(&TriBox) -> Probe,
) {
    let level = out.nodes[item.node].level + 1;
    let diam = item.tb.diam();
    // Past the exact budget the interval kernel takes over, also below
    // tri-boxes that were exact so far.
    let exact = exact.filter(|_| out.counters.exact_boxes < limits.max_exact);
    item.exact &= exact.is_some();
    // Counts the exact computations that `restrict_pair` is about to do.
    let count_exact = |out: &mut Run<S>, use_exact: bool| {
        if use_exact && exact.is_some() {
            out.counters.exact_boxes += 1;
        }
    };
    if exact.is_some() && !item.exact && diam < EXACT_BELOW && (noisy(&item.fa) || noisy(&item.fb)) {
        // The enclosures are wide relative to the values: recompute exactly
        // before the clip is spoiled by rounding (same tri-box, same level).
        out.counters.exact_restarts += 1;
        count_exact(out, true);
        let (fa, fb) = restrict_pair(f, g, exact, true, &item.tb);
        item = Leaf {
            fa,
            fb,
            exact: true,
            ..item
        };
    }
    let incenter = item.tb.incenter_bary();
    let noise = out.noise;
    let mut bounds = clip_bounds_with(limits.method, &item.fa, &item.fb, incenter, noise);
    if limits.swap_roles && matches!(limits.method, Method::Hc | Method::HcNoPre) {
        if let ClipBounds::Keep(m) = bounds {
            // The kept tri-box is similar to this one with ratio 1 − Σ mins.
            if 1.0 - m.iter().sum::<f64>() > 0.5 {
                out.counters.role_swaps += 1;
                let swapped = clip_bounds_with(limits.method, &item.fb, &item.fa, incenter, noise);
                bounds = intersect_bounds(bounds, swapped, S::KERNEL);
            }
        }
    }
    let mins = match bounds {
        ClipBounds::Empty => {
            out.counters.clip_exclusions += 1;
            return;
        }
        ClipBounds::Keep(m) => m,
    };
    let clipped = if mins.iter().sum::<f64>() > 0.0 {
        item.tb.clip(mins)
    } else {
        None
    };
    let (tb, fa, fb) = match clipped {
        Some(tb) if tb.diam() < diam => {
            out.counters.clips += 1;
            count_exact(out, item.exact);
            let (fa, fb) = restrict_pair(f, g, exact, item.exact, &tb);
            (tb, fa, fb)
        }
        _ => (item.tb, item.fa, item.fb),
    };
    if signed_beyond(&fa, noise) || signed_beyond(&fb, noise) {
        out.counters.sign_exclusions += 1;
        return;
    }
    let new_diam = tb.diam();
    let progressed = match limits.split {
        SplitRule::Halving => new_diam <= 0.5 * diam,
        SplitRule::PaperLiteral => mins.iter().sum::<f64>() > 0.5 * diam && new_diam < diam,
    };
    if !progressed && exact.is_some() && !item.exact && new_diam < EXACT_BELOW && S::KERNEL.is_rigorous() {
        // Stalled at the rounding floor: redo this tri-box from the exact input.
        out.counters.exact_restarts += 1;
        count_exact(out, true);
        let (fa, fb) = restrict_pair(f, g, exact, true, &tb);
        let node = push_node(out, item.node, level, new_diam);
        stack.push(Leaf {
            tb,
            node,
            fa,
            fb,
            exact: true,
        });
        return;
    }
    // Probes: a converging clip below EARLY_CERTIFY may already be certified
    // (Krawczyk's contraction then converges quadratically without further
    // clips); a stalled one below `probe_below` may be certified or excluded,
    // and below SINGULAR_FLOOR it is not split further.
    let probe_here = limits.probe_below > 0.0
        && if progressed {
            new_diam < EARLY_CERTIFY
        } else {
            new_diam < limits.probe_below
        };
    // After a long run of futile probes (all undecided: curves running
    // within a hair of each other over a long stretch, where every tri-box
    // stalls), probe only every 16th tri-box; a probe only saves work.
    let throttled = out.futile_probes >= FUTILE_PROBES && out.counters.boxes % 16 != 0;
    let verdict = if probe_here && !throttled {
        out.counters.probes += 1;
        let v = probe(&tb);
        out.futile_probes = if v == Probe::Undecided {
            out.futile_probes + 1
        } else {
            0
        };
        v
    } else {
        Probe::Undecided
    };
    let next = Leaf {
        tb,
        node: item.node,
        fa,
        fb,
        exact: item.exact,
    };
    let stop_here = match verdict {
        Probe::NoRoot => {
            out.counters.probe_exclusions += 1;
            return;
        }
        Probe::Unique => true,
        Probe::Undecided if !progressed && probe_here => match separating_combination(&next.fa, &next.fb) {
            Combination::NoRoot => {
                out.counters.sign_exclusions += 1;
                return;
            }
            Combination::Lost => true,
            Combination::Open => new_diam < SINGULAR_FLOOR,
        },
        Probe::Undecided => false,
    };
    if stop_here || progressed {
        let leaf = at_level(out, next, level, new_diam);
        if stop_here {
            out.leaves.push(leaf);
        } else {
            stack.push(leaf);
        }
        return;
    }
    let Some(kids) = next.tb.split4() else {
        // Collapsed at the rounding floor: hand it to the certification phase.
        let leaf = at_level(out, next, level, new_diam);
        return out.leaves.push(leaf);
    };
    out.counters.splits += 1;
    // Push in reverse so the corner at V1 is processed first.
    for kid in kids.into_iter().rev() {
        count_exact(out, item.exact);
        let (ka, kb) = restrict_pair(f, g, exact, item.exact, &kid);
        if signed_beyond(&ka, out.noise) || signed_beyond(&kb, out.noise) {
            out.counters.sign_exclusions += 1;
            continue;
        }
        let node = push_node(out, item.node, level, kid.diam());
        stack.push(Leaf {
            tb: kid,
            node,
            fa: ka,
            fb: kb,
            exact: item.exact,
        });
    }
}

/// `leaf` (whose `node` is its parent's) recorded in the trace as a child at `level`.
fn at_level<S>(out: &mut Run<S>, mut leaf: Leaf<S>, level: usize, diam: f64) -> Leaf<S> {
    leaf.node = push_node(out, leaf.node, level, diam);
    leaf
}

fn push_node<S>(out: &mut Run<S>, parent: usize, level: usize, diam: f64) -> usize {
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
