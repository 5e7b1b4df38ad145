//! Rigorous enclosures of the squared distance `D = |S(u, v) − P|²` over a
//! parameter box (a lower bound) and at a point (an upper bound of the
//! minimum: any point of the closed domain bounds it from above).

use crate::ray::patch::{eval_interval, Bb, Net};
use crate::scalar::{interval, point};
use crate::solve::Box2;
use inari::Interval;

/// Pieces a lower bound may evaluate: the refinement stops there, its bound
/// still rigorous (the smallest over the pieces left).
const MAX_PIECES: usize = 512;

/// `|s − p|²` for an enclosure `s` of a point.
fn squared(s: [Interval; 3], p: [f64; 3]) -> Interval {
    (0..3).fold(point(0.0), |acc, k| acc + (s[k] - point(p[k])).sqr())
}

/// A lower bound of `D` over one box by interval evaluation of the net.
pub(crate) fn box_lower<P: Bb<Interval>>(net: &Net<P>, p: [f64; 3], b: &Box2) -> f64 {
    let d = squared(
        eval_interval(net, interval(b.u[0], b.u[1]), interval(b.v[0], b.v[1])),
        p,
    );
    // An empty or NaN enclosure bounds nothing: 0 is always a lower bound.
    if d.is_empty() || d.inf().is_nan() {
        0.0
    } else {
        d.inf().max(0.0)
    }
}

/// A lower bound of `D` over the closed box (in the patch's parameters; the
/// box may reach outside the domain, where the patch's polynomials are
/// continued: still a lower bound over the part inside), refined best first
/// from the one-box bound `eval`: the piece with the smallest bound is
/// bisected across its longer side until that bound reaches `target` (no
/// need to know more: the region cannot hold the minimum below it) or the
/// pieces run out.
pub(crate) fn lower_bound(eval: &dyn Fn(&Box2) -> f64, bx: Box2, target: f64) -> f64 {
    let first = eval(&bx);
    let mut heap = std::collections::BinaryHeap::new();
    heap.push(Piece { lo: first, bx });
    let mut pieces = 1;
    while let Some(top) = heap.peek() {
        let (lo, b) = (top.lo, top.bx);
        let w = (b.u[1] - b.u[0]).max(b.v[1] - b.v[0]);
        if lo >= target || pieces + 2 > MAX_PIECES || w <= 1e-12 {
            return lo;
        }
        heap.pop();
        let [um, vm] = b.center();
        let (x, y) = if b.u[1] - b.u[0] >= b.v[1] - b.v[0] {
            (Box2::new([b.u[0], um], b.v), Box2::new([um, b.u[1]], b.v))
        } else {
            (Box2::new(b.u, [b.v[0], vm]), Box2::new(b.u, [vm, b.v[1]]))
        };
        for c in [x, y] {
            // A child's bound never drops below its parent's: the parent's
            // enclosure holds the child's values.
            heap.push(Piece {
                lo: eval(&c).max(lo),
                bx: c,
            });
        }
        pieces += 2;
    }
    first
}

/// A box in the refinement, ordered so that the heap's top has the smallest
/// bound.
struct Piece {
    lo: f64,
    bx: Box2,
}

impl PartialEq for Piece {
    fn eq(&self, o: &Self) -> bool {
        self.lo.total_cmp(&o.lo).is_eq()
    }
}
impl Eq for Piece {}
impl PartialOrd for Piece {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Piece {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        o.lo.total_cmp(&self.lo)
    }
}

/// An upper bound of `D` at the point `(u, v)` (which must lie in the closed
/// domain for the bound to bound the minimum).
pub(crate) fn upper_at<P: Bb<Interval>>(net: &Net<P>, p: [f64; 3], u: f64, v: f64) -> f64 {
    let d = squared(eval_interval(net, point(u), point(v)), p);
    if d.is_empty() || d.sup().is_nan() {
        f64::INFINITY
    } else {
        d.sup()
    }
}

/// `[√lo, √hi]` rounded outward.
pub(crate) fn sqrt_range(lo: f64, hi: f64) -> [f64; 2] {
    let d = interval(lo.max(0.0), hi).sqrt();
    if d.is_empty() {
        [0.0, f64::INFINITY]
    } else {
        // (+ 0.0 turns a −0 into +0.)
        [d.inf() + 0.0, d.sup()]
    }
}
