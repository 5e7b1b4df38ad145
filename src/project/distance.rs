//! Rigorous enclosures of the squared distance `D = |S(u, v) − P|²` over a
//! parameter box (a lower bound) and at a point (an upper bound of the
//! minimum: any point of the closed domain bounds it from above).

use crate::ray::patch::{eval_interval, Bb, Net};
use crate::scalar::{interval, point};
use crate::solve::Box2;
use inari::Interval;

/// Boxes wider than this are bisected (up to [`MAX_PIECES`] pieces) before
/// their lower bound is taken: interval evaluation overestimates in
/// proportion to the width.
const SPLIT_ABOVE: f64 = 1.0 / 64.0;
/// The most pieces one box is cut into.
const MAX_PIECES: usize = 256;

/// `|s − p|²` for an enclosure `s` of a point.
fn squared(s: [Interval; 3], p: [f64; 3]) -> Interval {
    (0..3).fold(point(0.0), |acc, k| acc + (s[k] - point(p[k])).sqr())
}

/// A lower bound of `D` over the closed box (in the patch's parameters;
/// the box may reach outside the domain, where the patch's polynomials are
/// continued: still a lower bound over the part inside).
pub(crate) fn lower_bound<P: Bb<Interval>>(net: &Net<P>, p: [f64; 3], bx: Box2) -> f64 {
    let mut stack = vec![bx];
    let mut lo = f64::INFINITY;
    let mut pieces = 1;
    while let Some(b) = stack.pop() {
        let wide = (b.u[1] - b.u[0]).max(b.v[1] - b.v[0]) > SPLIT_ABOVE;
        if wide && pieces + 1 <= MAX_PIECES {
            pieces += 1;
            let [um, vm] = b.center();
            let (x, y) = if b.u[1] - b.u[0] >= b.v[1] - b.v[0] {
                (Box2::new([b.u[0], um], b.v), Box2::new([um, b.u[1]], b.v))
            } else {
                (Box2::new(b.u, [b.v[0], vm]), Box2::new(b.u, [vm, b.v[1]]))
            };
            stack.push(x);
            stack.push(y);
            continue;
        }
        let s = eval_interval(net, interval(b.u[0], b.u[1]), interval(b.v[0], b.v[1]));
        let d = squared(s, p);
        // An empty or NaN enclosure bounds nothing: 0 is always a lower bound.
        let l = if d.is_empty() || d.inf().is_nan() { 0.0 } else { d.inf().max(0.0) };
        lo = lo.min(l);
    }
    lo
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
        [d.inf(), d.sup()]
    }
}
