//! The box solver's runner: the entry points and the depth-first loop over
//! boxes that applies the steps of the [`rect`](super) docs to each box.

use super::fatline::{fat_line_spans, FatLineClip};
use super::hybrid::hybrid_spans;
use super::net::{edge_indices, eval_box, one_signed, Node, Shape};
use super::options::{Objective, Query, RectClip, RectOptions, RectSolution};
use super::proof::{local_krawczyk, sign_lost};
use super::restart::{swamped, Restarts};
use super::spans::{clip, hull_spans, keep_aspect, preconditioned_spans, split};
use crate::error::{Error, Result};
use crate::poly::TensorBezier;
use crate::scalar::interval;
use crate::scalar::iv::Iv;
use crate::solve::driver::VANISHING;
use crate::solve::krawczyk::{IBox, System, Verdict};
use crate::solve::regions::{merge_roots, overlaps, undecided_clusters, Found};
use crate::solve::settle::ExactSystem;
use crate::solve::solution::{Box2, Cluster, Leftover, Root, Solution, Stats, UndecidedReason};
use inari::Interval;
use std::sync::Arc;

mod stalled;

/// Boxes at most this wide (relative) get a local Krawczyk test.
const KRAWCZYK_BELOW: f64 = 0.125;

/// A certified box narrower than this (relative to the box it was proven
/// in) is reported; a wider one is clipped to it and certified again.
const REPORT_BELOW: f64 = 1e-12;

/// Stalled boxes narrower than this (relative) are not split but handed to
/// the leaf test (see [`Runner::step`]).
const SINGULAR_FLOOR: f64 = 1e-9;

/// Stalled boxes narrower than this (relative) are tried by exact Krawczyk
/// when the system is exact ([`RectProblem::exact`]) and the box's
/// coefficients are [`NOISY`](super::restart::NOISY).
const EXACT_BELOW: f64 = 1e-2;

/// Stalled boxes narrower than this (relative) whose coefficients are not
/// [`NOISY`](super::restart::NOISY) are tried by exact Krawczyk.
const EXACT_CLEAN_BELOW: f64 = 1e-4;

/// The relative width of the strip cut along an edge where both equations
/// may vanish ([`Runner::cut_vanishing_edges`]): `2⁻³⁰`, so that `1 − EDGE_STRIP`
/// is exact.
const EDGE_STRIP: f64 = 1.0 / (1u64 << 30) as f64;

/// Stalled boxes below this (relative) size whose separating sign is lost
/// to rounding are leaves ([`sign_lost`]).
const LOST_BELOW: f64 = 1e-3;

/// Coefficients beyond this magnitude are rejected (keeps every difference
/// of two coefficients finite, which the hull crossings rely on).
const MAX_MAGNITUDE: f64 = 1e300;

/// Solves `f = g = 0` on the domain of `f` (a rectangle) by Bézier clipping on
/// boxes; see the [`rect`](super) docs for the method and [`RectSolution`] for what
/// the result guarantees.
///
/// Errors: different domains, an equation whose coefficients all contain 0
/// (it may be identically zero: [`Error::Degenerate`]), non-finite or huge
/// coefficients ([`Error::NonFinite`]), a bad `eps`.
///
/// ```
/// use rootclip::poly::TensorBezier;
/// use rootclip::internals::rect::{solve_rect, RectOptions};
/// use rootclip::internals::point;
/// // f = s − ¼, g = t − ¾ on the unit square (bidegree (1, 1)).
/// let f = TensorBezier::on_unit_square(1, 1, [-0.25, -0.25, 0.75, 0.75].map(point).to_vec()).unwrap();
/// let g = TensorBezier::on_unit_square(1, 1, [-0.75, 0.25, -0.75, 0.25].map(point).to_vec()).unwrap();
/// let r = solve_rect(&f, &g, None, &RectOptions::default()).unwrap().solution;
/// assert!(r.complete && r.roots.len() == 1 && r.roots[0].bx.contains(0.25, 0.75));
/// ```
pub fn solve_rect(
    f: &TensorBezier<Interval>,
    g: &TensorBezier<Interval>,
    objective: Option<Objective<'_>>,
    opts: &RectOptions,
) -> Result<RectSolution> {
    solve_rect_iv(rect_problem(f, g, objective)?, opts)
}

/// The [`RectProblem`] of [`solve_rect`]'s arguments (errors as there).
fn rect_problem(
    f: &TensorBezier<Interval>,
    g: &TensorBezier<Interval>,
    objective: Option<Objective<'_>>,
) -> Result<RectProblem> {
    let (du, dv) = f.domain();
    let same = |p: &TensorBezier<Interval>| {
        let (a, b) = p.domain();
        a == du && b == dv
    };
    if !same(g) || objective.is_some_and(|o| !same(o.num) || o.den.is_some_and(|d| !same(d))) {
        return Err(Error::Shape(
            "the system and the objective must share one rectangle".into(),
        ));
    }
    let (mf, nf) = f.degree();
    let (mg, ng) = g.degree();
    let mut m = mf.max(mg).max(1);
    let mut n = nf.max(ng).max(1);
    if let Some(o) = objective {
        m = m.max(o.num.degree().0);
        n = n.max(o.num.degree().1);
        if let Some(d) = o.den {
            m = m.max(d.degree().0);
            n = n.max(d.degree().1);
        }
    }
    let lift = |p: &TensorBezier<Interval>| -> Result<Vec<Iv>> {
        let e = if p.degree() == (m, n) {
            p.clone()
        } else {
            p.elevate(m, n)?
        };
        Ok(e.coeffs().iter().map(|c| Iv::new(c.inf(), c.sup())).collect())
    };
    let iv = |x: &Interval| Iv::new(x.inf(), x.sup());
    let problem = RectProblem {
        m,
        n,
        domain: [[iv(&du[0]), iv(&du[1])], [iv(&dv[0]), iv(&dv[1])]],
        f: lift(f)?,
        g: lift(g)?,
        num: objective.map(|o| lift(o.num)).transpose()?,
        den: objective.and_then(|o| o.den).map(lift).transpose()?,
        squares: None,
        exact: None,
        triangle: false,
    };
    Ok(problem)
}

/// [`solve_rect`] (no objective) for a system also known exactly: `exact`
/// is `f = g = 0` in rationals on the same (unit) square. With `triangle`,
/// the roots sought are those of the unit triangle `u + v ≤ 1` (see
/// [`RectProblem::triangle`]).
pub(crate) fn solve_rect_exact(
    f: &TensorBezier<Interval>,
    g: &TensorBezier<Interval>,
    exact: Arc<ExactSystem>,
    triangle: bool,
    opts: &RectOptions,
) -> Result<RectSolution> {
    let (du, dv) = f.domain();
    let unit = |d: &[Interval; 2]| d[0] == interval(0.0, 0.0) && d[1] == interval(1.0, 1.0);
    if !(unit(du) && unit(dv)) {
        return Err(Error::Shape("an exact system is solved on the unit square".into()));
    }
    // The exact system is used only through boxes in domain coordinates.
    let mut problem = rect_problem(f, g, None)?;
    problem.exact = Some(exact);
    problem.triangle = triangle;
    solve_rect_iv(problem, opts)
}

/// The input of [`solve_rect_iv`]: the system (and objective) as [`Iv`]
/// coefficient enclosures of one bidegree `(m, n)`, row-major, on `domain`
/// (each endpoint an enclosure of the exact one).
#[derive(Clone, Debug)]
pub(crate) struct RectProblem {
    pub(crate) m: usize,
    pub(crate) n: usize,
    pub(crate) domain: [[Iv; 2]; 2],
    pub(crate) f: Vec<Iv>,
    pub(crate) g: Vec<Iv>,
    pub(crate) num: Option<Vec<Iv>>,
    pub(crate) den: Option<Vec<Iv>>,
    /// The objective as a sum of squares, `Σ_k (c_k / w)²`, each `c_k` (and
    /// `w > 0`) of its own bidegree `(m', n')` on the domain: when present,
    /// the objective is bounded over a box coordinate by coordinate (tight
    /// where the expanded `num/den` would cancel); `num`/`den` must still be
    /// the same objective.
    pub(crate) squares: Option<Squares>,
    /// The same system in exact rational arithmetic, on the same domain, if
    /// the input is exact: boxes that rounding stalls are then tried by
    /// exact Krawczyk ([`ExactSystem::certify`]) instead of being split
    /// down to the rounding floor.
    pub(crate) exact: Option<Arc<ExactSystem>>,
    /// The roots sought are those of the unit triangle `u + v ≤ 1` in the
    /// (unit) square: a box whose lower-left corner is beyond the
    /// hypotenuse is dropped, a root whose box reaches it is reported
    /// `on_boundary` (for the caller to settle exactly), and one whose box
    /// lies beyond it is dropped.
    pub(crate) triangle: bool,
}

/// See [`RectProblem::squares`].
#[derive(Clone, Debug)]
pub(crate) struct Squares {
    pub(crate) m: usize,
    pub(crate) n: usize,
    pub(crate) c: [Vec<Iv>; 3],
    pub(crate) w: Option<Vec<Iv>>,
}

impl Squares {
    fn over(&self, s: [f64; 2], t: [f64; 2]) -> Iv {
        let w = self.w.as_ref().map(|w| eval_box(w, self.m, self.n, s, t));
        self.c.iter().fold(Iv::point(0.0), |acc, c| {
            let e = eval_box(c, self.m, self.n, s, t);
            let e = w.map_or(e, |w| e.div(w));
            let a = if e.lo >= 0.0 {
                e
            } else if e.hi <= 0.0 {
                Iv::new(-e.hi, -e.lo)
            } else {
                Iv::new(0.0, e.hi.max(-e.lo))
            };
            acc.add(a.mul(a))
        })
    }
}

/// [`solve_rect`] on [`Iv`] coefficients (the ray front end's fast path).
pub(crate) fn solve_rect_iv(p: RectProblem, opts: &RectOptions) -> Result<RectSolution> {
    // The rule of `SolveOptions::validate`, on every route: an `eps` of 1
    // or more is valid and stops at the first box (a cluster, or a root
    // Krawczyk certifies there).
    if !(opts.eps.is_finite() && opts.eps > 0.0) {
        return Err(Error::InvalidOption(format!(
            "eps must be a positive finite number, got {}",
            opts.eps
        )));
    }
    let (m, n) = (p.m, p.n);
    let len = (m + 1) * (n + 1);
    if m == 0 || n == 0 {
        return Err(Error::Shape("the rectangle solver needs bidegree ≥ (1, 1)".into()));
    }
    let parts = [Some(&p.f), Some(&p.g), p.num.as_ref(), p.den.as_ref()];
    for c in parts.into_iter().flatten() {
        if c.len() != len {
            return Err(Error::Shape(format!(
                "bidegree ({m}, {n}) needs {len} coefficients, got {}",
                c.len()
            )));
        }
        if let Some(x) = c
            .iter()
            .find(|x| !(x.lo.abs() <= MAX_MAGNITUDE && x.hi.abs() <= MAX_MAGNITUDE && x.lo <= x.hi))
        {
            return Err(Error::NonFinite(format!(
                "coefficient [{}, {}] is not finite or beyond 1e300",
                x.lo, x.hi
            )));
        }
    }
    if !p.domain.iter().flatten().all(|x| x.is_finite()) || !(0..2).all(|a| p.domain[a][0].hi < p.domain[a][1].lo) {
        return Err(Error::Shape("the rectangle must be finite and non-empty".into()));
    }
    for (name, c) in [("f", &p.f), ("g", &p.g)] {
        if c.iter().all(|x| x.lo <= 0.0 && x.hi >= 0.0) {
            return Err(Error::Degenerate(format!(
                "every coefficient of {name} contains 0: it may vanish identically"
            )));
        }
    }
    if p.den
        .as_ref()
        .is_some_and(|d| d.iter().any(|x| x.lo.is_nan() || x.lo <= 0.0))
    {
        return Err(Error::Degenerate("the objective's denominator must be positive".into()));
    }
    // The objective is not carried through the subdivision: it is bounded
    // over a box only where a query needs it (a certified root; a box that
    // Nearest might prune), from the domain's coefficients.
    let shape = Shape::pair(m, n);
    let mut buf = Vec::with_capacity(shape.polys * len);
    buf.extend_from_slice(&p.f);
    buf.extend_from_slice(&p.g);
    if let (Some(num), Some([k_min, _])) = (&p.num, opts.key_min) {
        // k = num/den with den > 0: k < k_min everywhere if every ratio is.
        let below = match &p.den {
            Some(den) => num.iter().zip(den).all(|(a, d)| a.div(*d).hi < k_min),
            None => num.iter().all(|a| a.hi < k_min),
        };
        if below {
            return Ok(RectSolution {
                solution: Solution {
                    complete: true,
                    roots: Vec::new(),
                    clusters: Vec::new(),
                    leftovers: Vec::new(),
                    stats: Stats::default(),
                },
                stopped_early: false,
            });
        }
    }
    let domain = p.domain;
    let mut run = Runner {
        shape,
        opts: *opts,
        scale: domain.map(|[lo, hi]| (hi.hi - lo.lo).next_up()),
        stats: Stats::default(),
        trace: Vec::with_capacity(64),
        found: Vec::new(),
        undecided: Vec::new(),
        problem: p,
        global: None,
        best: match opts.query {
            Query::Nearest => opts.key_max.filter(|k| !k.is_nan()).unwrap_or(f64::INFINITY),
            _ => f64::INFINITY,
        },
        stopped_early: false,
        edge_strips: Vec::new(),
        restarts: None,
    };
    let mut first = Node {
        key: None,
        exact_w: f64::INFINITY,
        restart_w: f64::INFINITY,
        restart_failed: false,
        c: buf,
        bx: domain,
        id: run.push_trace(u32::MAX, domain.map(|[lo, hi]| [lo.lo, hi.hi])),
    };
    run.cut_vanishing_edges(&mut first);
    let leftovers = run.drive(first);
    Ok(run.finish(leftovers))
}

struct Runner {
    shape: Shape,
    opts: RectOptions,
    /// The domain's side lengths (widths are compared relative to them).
    scale: [f64; 2],
    stats: Stats,
    /// `(parent, diameter)` per box, for [`Root::diameters`].
    trace: Vec<(u32, f64)>,
    found: Vec<Found>,
    undecided: Vec<Found>,
    problem: RectProblem,
    /// The whole system in domain coordinates, built on first use.
    global: Option<System<TensorBezier<Interval>>>,
    /// Smallest certified upper bound of the objective (for Nearest).
    best: f64,
    stopped_early: bool,
    /// Strips cut along edges where both equations may vanish.
    edge_strips: Vec<IBox>,
    /// The exact system in higher precisions, built on the first restart
    /// (`Some(None)` without one).
    restarts: Option<Option<Restarts>>,
}

enum Step {
    Done,
    Continue(Node),
    Split(Node, Node),
}

impl Runner {
    fn push_trace(&mut self, parent: u32, outer: [[f64; 2]; 2]) -> u32 {
        let diam = (outer[0][1] - outer[0][0]).hypot(outer[1][1] - outer[1][0]);
        self.trace.push((parent, diam));
        (self.trace.len() - 1) as u32
    }

    fn diameters(&self, mut id: u32) -> Vec<f64> {
        let mut depth = 0;
        let mut k = id;
        while k != u32::MAX {
            (depth, k) = (depth + 1, self.trace[k as usize].0);
        }
        let mut out = Vec::with_capacity(depth);
        while id != u32::MAX {
            let (parent, d) = self.trace[id as usize];
            out.push(d);
            id = parent;
        }
        out.reverse();
        out
    }

    fn rel_width(&self, node: &Node) -> [f64; 2] {
        let o = node.outer();
        [(o[0][1] - o[0][0]) / self.scale[0], (o[1][1] - o[1][0]) / self.scale[1]]
    }

    /// The main loop, depth first; returns the boxes a budget left.
    fn drive(&mut self, first: Node) -> Vec<Node> {
        let mut queue = Vec::with_capacity(16);
        queue.push(first);
        while let Some(node) = queue.pop() {
            if self.stopped_early {
                break;
            }
            if self.stats.boxes >= self.opts.max_boxes
                || self.opts.deadline.is_some_and(|d| std::time::Instant::now() >= d)
            {
                queue.push(node);
                return queue;
            }
            self.stats.boxes += 1;
            match self.step(node) {
                Step::Done => {}
                Step::Continue(n) => queue.push(n),
                Step::Split(a, b) => {
                    // Nearest: the child nearer in the objective first, so
                    // that a near root is certified early and prunes the rest.
                    let (mut a, mut b) = (a, b);
                    if self.opts.query == Query::Nearest {
                        a.key = Some(self.key_over(a.ibox()).0);
                        b.key = Some(self.key_over(b.ibox()).0);
                    }
                    let swap = self.opts.query == Query::Nearest && b.key < a.key;
                    let (a, b) = if swap { (b, a) } else { (a, b) };
                    queue.push(b);
                    queue.push(a);
                }
            }
        }
        Vec::new()
    }

    fn step(&mut self, mut node: Node) -> Step {
        // Beyond the hypotenuse: `fl(a + b) > 1` implies `a + b > 1`
        // (rounding is monotone), and every point of the box has `u ≥ a`,
        // `v ≥ b` (lower ends of the edges' enclosures).
        if self.problem.triangle && node.bx[0][0].lo + node.bx[1][0].lo > 1.0 {
            self.stats.outside_domain += 1;
            return Step::Done;
        }
        let sh = self.shape;
        let (f, rest) = node.c.split_at(sh.len);
        let g = &rest[..sh.len];
        if one_signed(f) || one_signed(g) {
            self.stats.sign_exclusions += 1;
            return Step::Done;
        }
        // Nearest: once a root is certified, a box whose objective is
        // provably above it cannot hold a nearer root.
        if self.opts.query == Query::Nearest
            && self.best < f64::INFINITY
            && node.key.unwrap_or_else(|| self.key_over(node.ibox()).0) > self.best
        {
            self.stats.sign_exclusions += 1;
            return Step::Done;
        }
        let w = self.rel_width(&node);
        if w[0].max(w[1]) <= KRAWCZYK_BELOW {
            self.stats.krawczyk_calls += 1;
            let kv = local_krawczyk(&node.c, sh);
            match kv {
                Verdict::Unique(k) => {
                    // The box holds exactly one root, in K ⊂ int box. Go on
                    // with K widened by half its width on each side (so the
                    // root stays inside, away from the new edges), where J
                    // is tighter, while that at least halves the box and the
                    // test still succeeds there; when it no longer does
                    // (rounding of the coefficients catches up with |F'|·w
                    // on an ill-conditioned system), the last proven K is
                    // the root's box. A wide K (J still loose) is left to
                    // the clips below instead.
                    let mut k = k;
                    loop {
                        let bx = [0, 1].map(|a| {
                            let [lo, hi] = node.bx[a];
                            let x = Iv::lerp_range(lo, hi, k[a].lo, k[a].hi);
                            interval(x.lo, x.hi)
                        });
                        let narrow = (0..2).all(|a| bx[a].wid() <= self.opts.eps * self.scale[a]);
                        if narrow || k[0].wid().max(k[1].wid()) <= REPORT_BELOW {
                            self.add_root(bx, node.id);
                            return Step::Done;
                        }
                        let mut spans = k.map(|c| {
                            let r = 0.5 * (c.hi - c.lo);
                            ((c.lo - r).max(0.0), (c.hi + r).min(1.0))
                        });
                        // Not thinner than `MIN_ASPECT` of the other side: a
                        // needle box (one equation clips its variable to
                        // rounding while the other lags) ruins the next tests.
                        keep_aspect(&mut spans, self.rel_width(&node));
                        if spans.iter().map(|s| s.1 - s.0).product::<f64>() > 0.5 {
                            break;
                        }
                        let mut child = node.clone();
                        for (d, &(a, b)) in spans.iter().enumerate() {
                            clip(&mut child, sh, d, a, b);
                        }
                        self.stats.clips += 1;
                        self.stats.krawczyk_calls += 1;
                        match local_krawczyk(&child.c, sh) {
                            Verdict::Unique(next) => {
                                child.id = self.push_trace(node.id, child.outer());
                                node = child;
                                k = next;
                            }
                            // The child holds the root (it holds K): "none"
                            // cannot be proven, and undecided keeps `bx`.
                            _ => {
                                self.add_root(bx, node.id);
                                return Step::Done;
                            }
                        }
                    }
                }
                Verdict::NoRoot => {
                    self.stats.probe_exclusions += 1;
                    return Step::Done;
                }
                Verdict::Undecided(()) => {}
            }
        }
        if w[0].max(w[1]) < self.opts.eps {
            // A box that clipped down to `eps` while rounding swamped it
            // is recomputed first: its Krawczyk test may then succeed.
            let noisy = self.swamped(&node);
            if let Some(fresh) = self.try_restart(&mut node, noisy) {
                return Step::Continue(fresh);
            }
            self.leaf(&node);
            return Step::Done;
        }
        // Clip in both directions.
        let fat = match self.opts.clip {
            RectClip::FatLine => fat_line_spans(&node.c, sh),
            RectClip::Hybrid => hybrid_spans(&node.c, sh),
            RectClip::Bezier => FatLineClip::Parallel,
        };
        let mut spans = match fat {
            FatLineClip::Empty => {
                self.stats.clip_exclusions += 1;
                return Step::Done;
            }
            FatLineClip::Spans(s) => s,
            FatLineClip::Parallel => match hull_spans(&node.c, sh) {
                Some(s) => s,
                None => {
                    self.stats.clip_exclusions += 1;
                    return Step::Done;
                }
            },
        };
        // Near a simple root the hulls close in on it from both sides, and
        // one clip can leave it within rounding of an edge, where K(X) ⊂ int X
        // can never hold again (sub-boxes never grow back). Keep a quarter of
        // the span's width as margin on each side, at every size, so that the
        // Krawczyk tests below can succeed.
        for span in spans.iter_mut() {
            let r = 0.25 * (span.1 - span.0);
            *span = ((span.0 - r).max(0.0), (span.1 + r).min(1.0));
        }
        keep_aspect(&mut spans, w);
        let area = self.clip_to(&mut node, &spans);
        if area <= 0.5 {
            return Step::Continue(node);
        }
        // Stalled: clip again with preconditioned equations (`rect` docs),
        // once the box is in Krawczyk's range. Above it, where a stall is
        // mostly two roots in one box, split at once.
        let wc = self.rel_width(&node);
        let pre = if wc[0].max(wc[1]) > KRAWCZYK_BELOW {
            Some([(0.0, 1.0); 2])
        } else {
            preconditioned_spans(&node.c, sh)
        };
        match pre {
            None => {
                self.stats.clip_exclusions += 1;
                return Step::Done;
            }
            Some(mut spans) => {
                // The same margin as above: a root the preconditioned hulls
                // close in on must not end up within rounding of an edge.
                for span in spans.iter_mut() {
                    let r = 0.25 * (span.1 - span.0);
                    *span = ((span.0 - r).max(0.0), (span.1 + r).min(1.0));
                }
                keep_aspect(&mut spans, self.rel_width(&node));
                if area * self.clip_to(&mut node, &spans) <= 0.5 {
                    return Step::Continue(node);
                }
            }
        }
        let w = self.rel_width(&node);
        let noisy = self.swamped(&node);
        if let Some(fresh) = self.try_restart(&mut node, noisy) {
            return Step::Continue(fresh);
        }
        // Rounding stalls a box at any size, two close roots only a wide
        // one: a clean box is tried exactly only once it is small.
        let below = if noisy { EXACT_BELOW } else { EXACT_CLEAN_BELOW };
        if w[0].max(w[1]) < below && 4.0 * w[0].max(w[1]) <= node.exact_w {
            if let Some(done) = self.try_exact(&node, noisy) {
                return done;
            }
            node.exact_w = w[0].max(w[1]);
        }
        // A stalled box below the floor is a leaf: near a multiple root the
        // region where the coefficients' rounding hides the sign is
        // ~√(rounding) wide, and splitting it down to `eps` would cost
        // millions of boxes for nothing. So is one whose separating sign is
        // lost to rounding, at any size.
        if w[0].max(w[1]) < self.opts.eps.max(SINGULAR_FLOOR)
            || (w[0].max(w[1]) < LOST_BELOW && sign_lost(&node.c, sh, w))
        {
            self.leaf(&node);
            return Step::Done;
        }
        self.stats.splits += 1;
        let d = usize::from(w[1] > w[0]);
        let (mut a, mut b) = split(&node, sh, d);
        a.id = self.push_trace(node.id, a.outer());
        b.id = self.push_trace(node.id, b.outer());
        Step::Split(a, b)
    }

    /// Bounds of the objective `num/den` over the box `x` (domain
    /// coordinates), by interval de Casteljau on the domain's coefficients;
    /// the whole line without an objective (or where the bound is not finite).
    fn key_over(&self, x: IBox) -> (f64, f64) {
        let p = &self.problem;
        let Some(num) = &p.num else {
            return (f64::NEG_INFINITY, f64::INFINITY);
        };
        // Local coordinates of the box, enclosed outward.
        let local = |a: usize| {
            let [lo, hi] = p.domain[a];
            let w = hi.sub(lo);
            let l = Iv::point(x[a].inf()).sub(lo).div(w);
            let h = Iv::point(x[a].sup()).sub(lo).div(w);
            [l.lo, h.hi]
        };
        let (s, t) = (local(0), local(1));
        if let Some(sq) = &p.squares {
            let k = sq.over(s, t);
            if !(k.lo.is_nan() || k.hi.is_nan()) {
                return (k.lo, k.hi);
            }
        }
        let k = eval_box(num, p.m, p.n, s, t);
        let k = match &p.den {
            Some(den) => k.div(eval_box(den, p.m, p.n, s, t)),
            None => k,
        };
        if k.lo.is_nan() || k.hi.is_nan() {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        (k.lo, k.hi)
    }

    /// Clips `node` to `spans` (local coordinates; only where they cut) and
    /// records the clip in the trace; returns the kept fraction of the area.
    fn clip_to(&mut self, node: &mut Node, spans: &[(f64, f64); 2]) -> f64 {
        let mut area = 1.0;
        for (d, &(a, b)) in spans.iter().enumerate() {
            if a > 0.0 || b < 1.0 {
                clip(node, self.shape, d, a, b);
                area *= b - a;
            }
        }
        if area < 1.0 {
            self.stats.clips += 1;
            node.id = self.push_trace(node.id, node.outer());
        }
        area
    }

    /// Records a certified root (and, for the queries, bounds the objective
    /// over its box).
    fn add_root(&mut self, bx: IBox, id: u32) {
        // Only a root proven to lie in the closed domain may end or prune a
        // query: one within rounding of an edge may be a root of the
        // polynomial's continuation past it (for a ray, a miss).
        let d = self.problem.domain;
        let inside = (0..2).all(|a| bx[a].inf() >= d[a][0].hi && bx[a].sup() <= d[a][1].lo);
        if inside && self.opts.query != Query::All {
            // (Without an objective every root counts as above the floor.)
            let key = self.key_over(bx);
            if self.opts.key_min.is_none_or(|[_, m]| key.0 >= m) {
                self.best = self.best.min(key.1);
                if self.opts.query == Query::Any {
                    self.stopped_early = true;
                }
            }
        }
        self.found.push(Found {
            bx,
            diameters: self.diameters(id),
        });
    }

    /// Cuts a strip of relative width [`EDGE_STRIP`] off every edge of the
    /// domain along which both equations may vanish identically or nearly
    /// (all their coefficients on that edge contain 0 or are below
    /// [`VANISHING`] of their largest) and keeps it as an undecided
    /// region ([`UndecidedReason::VanishingEdge`]).
    ///
    /// Why: if `f(0, t) ≡ g(0, t) ≡ 0` the edge is a curve of roots, and
    /// without the cut the iteration covers it with ever smaller boxes until
    /// the budget ends the run (a ray through the apex of a patch with a
    /// collapsed edge does exactly this). Cutting is always sound: the strip
    /// is reported, not discarded, and the rest is an exact sub-box solved as
    /// usual, where `f ≈ s·∂f/∂s` is far from rounding noise.
    fn cut_vanishing_edges(&mut self, node: &mut Node) {
        let sh = self.shape;
        for d in 0..2 {
            for high in [false, true] {
                let vanishes = (0..2).all(|p| {
                    let c = &node.c[p * sh.len..(p + 1) * sh.len];
                    let mag = |x: &Iv| x.lo.abs().max(x.hi.abs());
                    let scale = c.iter().map(mag).fold(0.0, f64::max);
                    edge_indices(sh, d, high)
                        .all(|k| (c[k].lo <= 0.0 && c[k].hi >= 0.0) || mag(&c[k]) <= VANISHING * scale)
                });
                if !vanishes {
                    continue;
                }
                let [lo, hi] = node.bx[d];
                let mut strip = node.ibox();
                if high {
                    clip(node, sh, d, 0.0, 1.0 - EDGE_STRIP);
                    strip[d] = interval(node.bx[d][1].lo, hi.hi);
                } else {
                    clip(node, sh, d, EDGE_STRIP, 1.0);
                    strip[d] = interval(lo.lo, node.bx[d][0].hi);
                }
                self.edge_strips.push(strip);
            }
        }
    }

    /// The whole system in domain coordinates (for leaves and merging).
    fn system(&mut self) -> &System<TensorBezier<Interval>> {
        let p = &self.problem;
        self.global.get_or_insert_with(|| {
            let tb = |c: &[Iv]| {
                let iv = |x: &Iv| interval(x.lo, x.hi);
                let d = p.domain.map(|[lo, hi]| [iv(&lo), iv(&hi)]);
                TensorBezier::new(p.m, p.n, c.iter().map(iv).collect(), d[0], d[1]).expect("checked in solve_rect_iv")
            };
            System::new(tb(&p.f), tb(&p.g))
        })
    }

    fn finish(mut self, left: Vec<Node>) -> RectSolution {
        let found = std::mem::take(&mut self.found);
        // Certified boxes that do not overlap hold distinct roots: the global
        // system (built with inari, slow) is needed only when some do.
        let overlapping = found
            .iter()
            .enumerate()
            .any(|(i, a)| found[i + 1..].iter().any(|b| overlaps(a.bx, b.bx)));
        let roots = if overlapping {
            let mut stats = self.stats;
            let (roots, undecided) = merge_roots(found, self.system(), &mut stats);
            self.stats = stats;
            self.undecided.extend(undecided);
            roots
        } else {
            found
        };
        let domain = self.problem.domain;
        let triangle = self.problem.triangle;
        // (As in `step`: a rounded sum beyond 1 proves the exact one is, and
        // one below 1 that it is below.)
        let beyond = |x: &IBox| triangle && x[0].inf() + x[1].inf() > 1.0;
        let mut out = Vec::new();
        for r in roots {
            let x = r.bx;
            let outside = (0..2).any(|a| x[a].sup() < domain[a][0].lo || x[a].inf() > domain[a][1].hi);
            if outside || beyond(&x) {
                self.stats.outside_domain += 1;
                continue;
            }
            let inside = (0..2).all(|a| x[a].inf() > domain[a][0].hi && x[a].sup() < domain[a][1].lo)
                && !(triangle && x[0].sup() + x[1].sup() >= 1.0);
            out.push(Root {
                u: x[0].mid(),
                v: x[1].mid(),
                bx: Box2::of(x),
                on_boundary: !inside,
                diameters: r.diameters,
            });
        }
        out.sort_by(|a, b| a.u.total_cmp(&b.u).then(a.v.total_cmp(&b.v)));
        let clusters = undecided_clusters(std::mem::take(&mut self.undecided))
            .into_iter()
            .filter(|c| !beyond(&c.bx.ibox()))
            .chain(self.edge_strips.iter().map(|&s| Cluster {
                bx: Box2::of(s),
                reason: UndecidedReason::VanishingEdge,
                diameters: Vec::new(),
            }))
            .collect();
        self.stats.max_level = out
            .iter()
            .map(|r| r.diameters.len().saturating_sub(1))
            .max()
            .unwrap_or(0);
        let leftovers: Vec<Leftover> = left
            .iter()
            .filter(|n| !beyond(&n.ibox()))
            .map(|n| Leftover {
                bx: Box2::of(n.ibox()),
                triangle: None,
            })
            .collect();
        RectSolution {
            solution: Solution {
                complete: leftovers.is_empty(),
                roots: out,
                clusters,
                leftovers,
                stats: self.stats,
            },
            stopped_early: self.stopped_early,
        }
    }
}
