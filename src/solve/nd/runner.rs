//! The loop over boxes of [`solve_nd`](super::solve_nd): one step per box as
//! the [`nd`](super) docs list them, leaves certified on the whole system,
//! overlapping roots merged, undecided boxes grouped.

use super::clip::{elevate, hull_spans, widen};
use super::global::{ExactValues, GlobalSystem};
use super::krawczyk::{certify_unit, preconditioner, LocalBox};
use super::tensor::{len_of, one_signed, subdivide};
use super::{NdOptions, NdRoot, NdSolution, NdUndecided};
use crate::scalar::iv::Iv;
use crate::solve::krawczyk::Verdict;
use crate::solve::solution::Stats;

/// Boxes at most this wide (the widest side) get a local Krawczyk test.
const KRAWCZYK_BELOW: f64 = 0.25;

/// A certified box narrower than this (relative to the box it was proven in)
/// is reported; a wider one is clipped to it and certified again.
const REPORT_BELOW: f64 = 1e-12;

/// Stalled boxes narrower than this are leaves (near a multiple zero the
/// region where rounding hides the sign is about the square root of the
/// rounding wide; splitting it further costs boxes for nothing).
const SINGULAR_FLOOR: f64 = 1e-9;

/// The least fraction of a side a clip must remove to be done.
const MIN_CUT: f64 = 0.1;

/// Where boxes are split (exact, and so is `1 − SPLIT`).
const SPLIT: f64 = 63.0 / 128.0;

/// A box: the coefficients of every equation on it (concatenated), its
/// endpoints (each an enclosure of the exact one).
#[derive(Clone)]
struct Node<const N: usize> {
    c: Vec<Iv>,
    bx: [[Iv; 2]; N],
}

impl<const N: usize> Node<N> {
    fn outer(&self) -> [[f64; 2]; N] {
        self.bx.map(|[lo, hi]| [lo.lo, hi.hi])
    }
}

enum Step<const N: usize> {
    Done,
    Continue(Node<N>),
    Split(Node<N>, Node<N>),
}

pub(super) struct Runner<'a, const N: usize> {
    deg: [[usize; N]; N],
    offsets: [usize; N],
    root: &'a [Vec<Iv>],
    global: GlobalSystem<'a, N>,
    opts: NdOptions,
    stats: Stats,
    roots: Vec<[[f64; 2]; N]>,
    undecided: Vec<[[f64; 2]; N]>,
}

impl<'a, const N: usize> Runner<'a, N> {
    pub(super) fn new(
        deg: [[usize; N]; N],
        root: &'a [Vec<Iv>],
        exact: Option<&'a dyn ExactValues<N>>,
        opts: NdOptions,
    ) -> Self {
        let mut offsets = [0usize; N];
        for e in 1..N {
            offsets[e] = offsets[e - 1] + len_of(&deg[e - 1]);
        }
        Self {
            deg,
            offsets,
            root,
            global: GlobalSystem::new(deg, root, exact),
            opts,
            stats: Stats::default(),
            roots: Vec::new(),
            undecided: Vec::new(),
        }
    }

    fn eq<'n>(&self, c: &'n [Iv], e: usize) -> &'n [Iv] {
        &c[self.offsets[e]..self.offsets[e] + len_of(&self.deg[e])]
    }

    fn local<'n>(&'n self, c: &'n [Iv]) -> LocalBox<'n, N> {
        LocalBox {
            deg: &self.deg,
            c: (0..N).map(|e| self.eq(c, e)).collect(),
        }
    }

    pub(super) fn run(mut self) -> NdSolution<N> {
        let first = Node {
            c: self.root.concat(),
            bx: [[Iv::point(0.0), Iv::point(1.0)]; N],
        };
        let mut queue = vec![first];
        let mut left = Vec::new();
        while let Some(node) = queue.pop() {
            if self.stats.boxes >= self.opts.max_boxes {
                left.push(node.outer());
                left.extend(queue.drain(..).map(|n| n.outer()));
                break;
            }
            self.stats.boxes += 1;
            match self.step(node) {
                Step::Done => {}
                Step::Continue(n) => queue.push(n),
                Step::Split(a, b) => {
                    queue.push(b);
                    queue.push(a);
                }
            }
        }
        self.finish(left)
    }

    fn widths(node: &Node<N>) -> [f64; N] {
        node.outer().map(|[lo, hi]| hi - lo)
    }

    fn step(&mut self, mut node: Node<N>) -> Step<N> {
        if (0..N).any(|e| one_signed(self.eq(&node.c, e))) {
            self.stats.sign_exclusions += 1;
            return Step::Done;
        }
        let w = Self::widths(&node);
        let widest = w.iter().fold(0.0f64, |m, &x| m.max(x));
        if widest <= KRAWCZYK_BELOW {
            self.stats.krawczyk_calls += 1;
            match certify_unit(&self.local(&node.c)) {
                Verdict::Unique(k) => {
                    let bx = to_global(&node.bx, &k);
                    let narrow = bx.iter().all(|[lo, hi]| hi - lo <= self.opts.eps);
                    if narrow || k.iter().all(|c| c.wid() <= REPORT_BELOW) {
                        self.roots.push(bx);
                        return Step::Done;
                    }
                    // The box's only zero lies in K ⊂ int box: go on with K
                    // widened by half its width on each side, where the
                    // Jacobian is tighter, if that at least halves the box.
                    let spans: [(f64, f64); N] = std::array::from_fn(|d| {
                        let r = 0.5 * (k[d].hi - k[d].lo);
                        ((k[d].lo - r).max(0.0), (k[d].hi + r).min(1.0))
                    });
                    if spans.iter().map(|s| s.1 - s.0).product::<f64>() <= 0.5 {
                        self.clip_to(&mut node, &spans);
                        return Step::Continue(node);
                    }
                }
                Verdict::NoRoot => {
                    self.stats.probe_exclusions += 1;
                    return Step::Done;
                }
                Verdict::Undecided(()) => {}
            }
        }
        if widest < self.opts.eps {
            self.leaf(&node);
            return Step::Done;
        }
        let eqs: Vec<(&[usize; N], &[Iv])> = (0..N).map(|e| (&self.deg[e], self.eq(&node.c, e))).collect();
        let Some(mut spans) = hull_spans(&eqs) else {
            self.stats.clip_exclusions += 1;
            return Step::Done;
        };
        widen(&mut spans, w);
        let kept = self.clip_to(&mut node, &spans);
        if kept <= 0.5 {
            return Step::Continue(node);
        }
        // Stalled: clip again with preconditioned combinations.
        match self.preconditioned_spans(&node) {
            None => {
                self.stats.clip_exclusions += 1;
                return Step::Done;
            }
            Some(mut spans) => {
                widen(&mut spans, Self::widths(&node));
                if kept * self.clip_to(&mut node, &spans) <= 0.5 {
                    return Step::Continue(node);
                }
            }
        }
        let w = Self::widths(&node);
        let widest = w.iter().fold(0.0f64, |m, &x| m.max(x));
        if widest < self.opts.eps.max(SINGULAR_FLOOR) {
            self.leaf(&node);
            return Step::Done;
        }
        self.stats.splits += 1;
        let d = (0..N).max_by(|&a, &b| w[a].total_cmp(&w[b])).unwrap_or(0);
        let (a, b) = self.split(&node, d);
        Step::Split(a, b)
    }

    /// Spans from the rows of `Y·F`, `Y ≈ F'(mid)⁻¹`: every zero of the
    /// system is a zero of each row, and near a simple zero the rows are
    /// nearly `x_d − x*_d`, so their hulls are tight where those of the
    /// equations are not. `None` when a row proves there is no zero.
    fn preconditioned_spans(&self, node: &Node<N>) -> Option<[(f64, f64); N]> {
        let sys = self.local(&node.c);
        let Some((y, _)) = preconditioner(&sys.jacobian()) else {
            return Some([(0.0, 1.0); N]);
        };
        let top: [usize; N] = std::array::from_fn(|d| (0..N).map(|e| self.deg[e][d]).max().unwrap_or(0));
        let lifted: Vec<Vec<Iv>> = (0..N)
            .map(|e| {
                let c = self.eq(&node.c, e);
                if self.deg[e] == top {
                    c.to_vec()
                } else {
                    elevate(c, &self.deg[e], &top)
                }
            })
            .collect();
        let len = len_of(&top);
        let mut spans = [(0.0f64, 1.0f64); N];
        let mut h = vec![Iv::point(0.0); len];
        for row in y.iter() {
            for (k, x) in h.iter_mut().enumerate() {
                let mut s = Iv::point(0.0);
                for (e, l) in lifted.iter().enumerate() {
                    s = s.add(Iv::point(row[e]).mul(l[k]));
                }
                *x = s;
            }
            if one_signed(&h) {
                return None;
            }
            let part = hull_spans::<N>(&[(&top, &h)])?;
            for d in 0..N {
                spans[d] = (spans[d].0.max(part[d].0), spans[d].1.min(part[d].1));
                if spans[d].0 > spans[d].1 {
                    return None;
                }
            }
        }
        Some(spans)
    }

    /// Restricts the node to `spans` (local coordinates; only where they
    /// cut at least [`MIN_CUT`] of the side: a cut costs two de Casteljau
    /// passes over every equation, whatever it removes); returns the kept
    /// fraction of its volume.
    fn clip_to(&mut self, node: &mut Node<N>, spans: &[(f64, f64); N]) -> f64 {
        let mut kept = 1.0;
        for (d, &(a, b)) in spans.iter().enumerate() {
            if b - a <= 1.0 - MIN_CUT {
                self.clip_axis(node, d, a, b);
                kept *= b - a;
            }
        }
        if kept < 1.0 {
            self.stats.clips += 1;
        }
        kept
    }

    /// Restricts the node to `[α, β]` of axis `d`: two de Casteljau splits at
    /// floats, keep `[α, 1]`, then its first `γ ≥ (β − α)/(1 − α)` (rounded
    /// up), so the node stays an exact sub-box of its parent, a superset of
    /// the requested one.
    fn clip_axis(&self, node: &mut Node<N>, d: usize, alpha: f64, beta: f64) {
        let gamma = if beta >= 1.0 {
            1.0
        } else {
            ((beta - alpha).next_up() / (1.0 - alpha).next_down())
                .next_up()
                .min(1.0)
        };
        for e in 0..N {
            let (o, l) = (self.offsets[e], len_of(&self.deg[e]));
            let c = &mut node.c[o..o + l];
            if alpha > 0.0 {
                subdivide(c, &self.deg[e], d, alpha, true);
            }
            if gamma < 1.0 {
                subdivide(c, &self.deg[e], d, gamma, false);
            }
        }
        let [lo, hi] = node.bx[d];
        let new_lo = if alpha > 0.0 { Iv::lerp(lo, hi, alpha) } else { lo };
        let new_hi = if gamma < 1.0 { Iv::lerp(new_lo, hi, gamma) } else { hi };
        node.bx[d] = [new_lo, new_hi];
    }

    fn split(&self, node: &Node<N>, d: usize) -> (Node<N>, Node<N>) {
        let mut a = node.clone();
        let mut b = node.clone();
        for e in 0..N {
            let (o, l) = (self.offsets[e], len_of(&self.deg[e]));
            subdivide(&mut a.c[o..o + l], &self.deg[e], d, SPLIT, false);
            subdivide(&mut b.c[o..o + l], &self.deg[e], d, SPLIT, true);
        }
        let [lo, hi] = node.bx[d];
        let mid = Iv::lerp(lo, hi, SPLIT);
        a.bx[d] = [lo, mid];
        b.bx[d] = [mid, hi];
        (a, b)
    }

    /// Krawczyk on the whole system over the box `x` (domain
    /// coordinates) inflated by a tenth of its width, then by its width
    /// (`ε`-inflation: a zero within rounding of the box's faces is proven
    /// in the larger box): the verdict in domain coordinates.
    fn certify_global(&mut self, x: [[f64; 2]; N]) -> Verdict<[[f64; 2]; N], ()> {
        for factor in [0.1, 1.0] {
            let infl: [[f64; 2]; N] = std::array::from_fn(|d| {
                let r = factor * (x[d][1] - x[d][0]) + 1e-15 * (1.0 + x[d][0].abs().max(x[d][1].abs()));
                [x[d][0] - r, x[d][1] + r]
            });
            self.stats.krawczyk_calls += 1;
            match self.global.certify(infl) {
                Verdict::Undecided(()) => {}
                v => return v,
            }
        }
        Verdict::Undecided(())
    }

    /// A box below `eps` that local Krawczyk did not settle.
    fn leaf(&mut self, node: &Node<N>) {
        self.stats.leaves += 1;
        let x = node.outer();
        match self.certify_global(x) {
            Verdict::Unique(k) => {
                if (0..N).any(|d| k[d][1] < x[d][0] || k[d][0] > x[d][1]) {
                    self.stats.krawczyk_exclusions += 1;
                } else {
                    self.roots.push(k);
                }
            }
            Verdict::NoRoot => self.stats.krawczyk_exclusions += 1,
            Verdict::Undecided(()) => self.undecided.push(x),
        }
    }

    /// A joined undecided region, settled by global Krawczyk on it whole,
    /// else on its halves (the widest side bisected) down to `depth` more
    /// levels: two simple zeros closer than the subdivided coefficients
    /// resolve (their leaves all undecided, then joined into one region)
    /// are each proven in a half wider than the rounding of their values.
    /// Halves neither proven nor excluded at the last level stay undecided.
    /// First, the whole region inflated by up to 512 times its widest side:
    /// one zero there proves the region holds at most that zero.
    fn settle_region(&mut self, bx: [[f64; 2]; N], depth: usize) {
        match self.certify_global(bx) {
            Verdict::Unique(k) => self.roots.push(k),
            Verdict::NoRoot => self.stats.krawczyk_exclusions += 1,
            Verdict::Undecided(()) => {
                if depth == REGION_SPLITS {
                    // A lone simple zero whose values are lost to rounding
                    // over the region (a zero within 10⁻¹⁴ of a face, its
                    // system's coefficients rounded): proven in a box some
                    // powers of two wider than the region.
                    let w = bx.iter().fold(1e-15f64, |m, [lo, hi]| m.max(hi - lo));
                    for f in [8.0, 64.0, 512.0] {
                        let infl: [[f64; 2]; N] = bx.map(|[lo, hi]| [lo - f * w, hi + f * w]);
                        self.stats.krawczyk_calls += 1;
                        if let Verdict::Unique(k) = self.global.certify(infl) {
                            self.roots.push(k);
                            return;
                        }
                    }
                }
                let d = (0..N)
                    .max_by(|&a, &b| (bx[a][1] - bx[a][0]).total_cmp(&(bx[b][1] - bx[b][0])))
                    .unwrap_or(0);
                let mid = 0.5 * bx[d][0] + 0.5 * bx[d][1];
                if depth == 0 || !(bx[d][0] < mid && mid < bx[d][1]) {
                    self.undecided.push(bx);
                    return;
                }
                let (mut lo, mut hi) = (bx, bx);
                lo[d][1] = mid;
                hi[d][0] = mid;
                self.settle_region(lo, depth - 1);
                self.settle_region(hi, depth - 1);
            }
        }
    }

    fn finish(mut self, left: Vec<[[f64; 2]; N]>) -> NdSolution<N> {
        // Joined undecided leaves are tried once more as a whole: two zeros
        // closer than a leaf's inflation are separated by the join, and a
        // group wider than the rounding of its values can be proven where no
        // single leaf could.
        for bx in group(std::mem::take(&mut self.undecided)) {
            self.settle_region(bx, REGION_SPLITS);
        }
        let roots = std::mem::take(&mut self.roots);
        let roots = self.merge(roots);
        let inside = |b: &[[f64; 2]; N]| b.iter().all(|[lo, hi]| *lo > 0.0 && *hi < 1.0);
        let outside = |b: &[[f64; 2]; N]| b.iter().any(|[lo, hi]| *hi < 0.0 || *lo > 1.0);
        let mut out = Vec::new();
        for bx in roots {
            if outside(&bx) {
                self.stats.outside_domain += 1;
                continue;
            }
            out.push(NdRoot {
                x: bx.map(|[lo, hi]| 0.5 * lo + 0.5 * hi),
                bx,
                on_boundary: !inside(&bx),
            });
        }
        out.sort_by(|a, b| a.x.partial_cmp(&b.x).unwrap_or(std::cmp::Ordering::Equal));
        let undecided = group(std::mem::take(&mut self.undecided))
            .into_iter()
            .map(|bx| NdUndecided { bx })
            .collect();
        NdSolution {
            complete: left.is_empty(),
            roots: out,
            undecided,
            leftovers: left,
            stats: self.stats,
        }
    }

    /// Certified boxes that overlap may hold the same zero (a leaf's
    /// inflated proof reaching into a neighbour): one zero if Krawczyk proves
    /// a unique zero in their hull; distinct if it proves none in their
    /// intersection; otherwise both become undecided.
    fn merge(&mut self, mut roots: Vec<[[f64; 2]; N]>) -> Vec<[[f64; 2]; N]> {
        let mut out: Vec<[[f64; 2]; N]> = Vec::new();
        'next: while let Some(r) = roots.pop() {
            for i in 0..out.len() {
                if !overlap(&out[i], &r) {
                    continue;
                }
                let hull: [[f64; 2]; N] =
                    std::array::from_fn(|d| [out[i][d][0].min(r[d][0]), out[i][d][1].max(r[d][1])]);
                if let Verdict::Unique(k) = self.certify_global(hull) {
                    out[i] = k;
                    continue 'next;
                }
                let meet: [[f64; 2]; N] =
                    std::array::from_fn(|d| [out[i][d][0].max(r[d][0]), out[i][d][1].min(r[d][1])]);
                if matches!(self.certify_global(meet), Verdict::NoRoot) {
                    continue;
                }
                let o = out.swap_remove(i);
                self.undecided.push(o);
                self.undecided.push(r);
                continue 'next;
            }
            out.push(r);
        }
        out
    }
}

/// Bisection levels of `settle_region` (at most `2^6` Krawczyk
/// tests per joined region).
const REGION_SPLITS: usize = 6;

/// The closed boxes share a point.
fn overlap<const N: usize>(a: &[[f64; 2]; N], b: &[[f64; 2]; N]) -> bool {
    (0..N).all(|d| a[d][0] <= b[d][1] && b[d][0] <= a[d][1])
}

/// Undecided boxes that touch, joined into their hulls (repeated until no
/// two hulls touch).
fn group<const N: usize>(mut boxes: Vec<[[f64; 2]; N]>) -> Vec<[[f64; 2]; N]> {
    let mut changed = true;
    while changed {
        changed = false;
        let mut out: Vec<[[f64; 2]; N]> = Vec::new();
        for b in boxes {
            if let Some(o) = out.iter_mut().find(|o| overlap(o, &b)) {
                for d in 0..N {
                    o[d] = [o[d][0].min(b[d][0]), o[d][1].max(b[d][1])];
                }
                changed = true;
            } else {
                out.push(b);
            }
        }
        boxes = out;
    }
    boxes
}

/// Local coordinates `k` of a box with endpoints `bx` to domain coordinates,
/// rounded outward.
fn to_global<const N: usize>(bx: &[[Iv; 2]; N], k: &[Iv; N]) -> [[f64; 2]; N] {
    std::array::from_fn(|d| {
        let [lo, hi] = bx[d];
        let x = Iv::lerp_range(lo, hi, k[d].lo, k[d].hi);
        [x.lo, x.hi]
    })
}
