//! Marching along one branch of the curve, from a certified start point,
//! with every step proven.
//!
//! # A step
//! 1. **Predict** by one RK4 step of seed 002's tangent field
//!    `x' = T(x)` (the unit kernel of `F'`, oriented along the march), and
//!    pick the marching axis `p`, the largest component of the tangent at
//!    the step's middle.
//! 2. **Correct** by Newton's method on the hyperplane `x_p = const`
//!    (seed 002's continuation: the curve cut by a plane across the marching
//!    direction), and at the step's middle; the chord's deviation there, in
//!    model space, must be below `tol`, else the step is shortened to bring
//!    it to about `0.8·tol` (it grows as the square of the step). An
//!    accepted step sets the next one's length the same way (at most
//!    doubled, and below the last length the tube test refused); a failed
//!    tube test shortens the step to 0.6 of it, any other rejection halves
//!    it.
//! 3. **Prove** the piece with the tube test of
//!    [`system`](super::system): `K(P, Y) ⊂ int Y` on a box `P × Y` around
//!    the step proves that the curve in it is one arc, a graph over `P`.
//!    The new point is certified on its hyperplane (a box holding exactly
//!    one curve point there; one Krawczyk step from the Newton-converged
//!    point, with the tube's enclosure of `∂_y F`, valid on every box inside
//!    the tube), and both the old and the new point boxes must
//!    lie in the tube: consecutive arcs share a curve point, so the traced
//!    arcs form one connected piece of the curve, and no step can jump to
//!    another branch (the tube holds no other curve point).
//! 4. **Check events** against the certified start points: a crossing with
//!    the box's boundary inside the tube ends the branch there (it is the
//!    only boundary point on the arc, so the arc leaves the domain there);
//!    the start turning point inside a later tube closes a loop; turning
//!    points inside a tube are on this branch. A start point or an
//!    undecided region that only partly overlaps a tube, a tube that leaves
//!    the domain with no crossing in it, or two crossings in one tube halve
//!    the step. Below a step of `10⁻⁹` (or of a quarter of the distance to
//!    the nearest other start point, if that is smaller: a tiny arc between
//!    two crossings `10⁻¹⁰` apart is traced in steps its size) the branch
//!    stops, unfinished.

use super::system::{others, Box4, System};
use crate::scalar::iv::Iv;

/// How a branch ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum End {
    /// At the crossing with this index.
    Crossing(usize),
    /// Back at its start: a closed loop.
    Closed,
    /// The step fell below the floor or the budget ran out near this box.
    Stuck(Box4),
}

/// One traced branch.
pub(crate) struct Trace {
    /// Points in order, each with whether it is certified.
    pub(crate) points: Vec<([f64; 4], bool)>,
    /// The proven tubes, in order.
    pub(crate) tubes: Vec<Box4>,
    /// Indices of the turning points found on this branch.
    pub(crate) turning: Vec<usize>,
    pub(crate) end: End,
}

/// The start of a branch.
#[derive(Clone, Copy)]
pub(crate) enum Start {
    Crossing(usize),
    Turning(usize),
}

pub(crate) struct Tracer<'a> {
    pub(crate) sys: &'a System,
    /// The point of patch A at `(u, v)`, in model space.
    pub(crate) xyz: &'a dyn Fn(f64, f64) -> [f64; 3],
    pub(crate) crossings: &'a [Box4],
    pub(crate) turning: &'a [Box4],
    pub(crate) undecided: &'a [Box4],
    pub(crate) tol: f64,
    pub(crate) max_points: usize,
}

const MIN_STEP: f64 = 1e-9;
const MAX_STEP: f64 = 0.125;

fn center(b: &Box4) -> [f64; 4] {
    b.map(|[lo, hi]| 0.5 * lo + 0.5 * hi)
}

fn overlap(a: &Box4, b: &Box4) -> bool {
    (0..4).all(|d| a[d][0] <= b[d][1] && b[d][0] <= a[d][1])
}

fn inside(a: &Box4, b: &Box4) -> bool {
    (0..4).all(|d| b[d][0] <= a[d][0] && a[d][1] <= b[d][1])
}

/// How the curve meets the domain at a crossing.
enum Entry {
    /// It enters the domain when the tangent `T` (with the signs of its
    /// components over the crossing's box, where proven) is oriented by
    /// this sign (`+1`: along `T`), across every face the crossing lies on.
    Proven(f64, [Option<f64>; 4]),
    /// It enters through one face as it leaves through another: the
    /// crossing is all of the curve in the domain nearby.
    Touches,
    /// The signs are not proven on some face.
    Unproven,
}

/// The faces `(axis, inward sign)` the box lies on: exactly (`exact`: its
/// range there is the point 0 or 1), or touching or past them.
fn faces_of(b: &Box4, exact: bool) -> Vec<(usize, f64)> {
    (0..4)
        .filter_map(|d| {
            let (at0, at1) = if exact {
                (b[d] == [0.0, 0.0], b[d] == [1.0, 1.0])
            } else {
                (b[d][0] <= 0.0, b[d][1] >= 1.0)
            };
            if at0 {
                Some((d, 1.0))
            } else if at1 {
                Some((d, -1.0))
            } else {
                None
            }
        })
        .collect()
}

/// Where a start point's certified box `c` lies on the step's arc.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Place {
    /// Not in the tube: not on this arc.
    Away,
    /// On the arc behind the current point (`xbox`) along axis `p`.
    Behind,
    /// On the arc ahead of the current point.
    Ahead,
    /// Partly in the tube, or level with the current point along `p`.
    Unclear,
}

/// Where the start point in box `c` lies relative to a proven tube (one arc,
/// a graph over axis `p`) and the current point's box `xbox`, for a step
/// towards larger `x_p` if `forward`. A box wholly behind the current point
/// along `p` is behind whether or not it lies in the tube (if its point is in
/// the tube, the arc passed it before the current point).
fn place(c: &Box4, tube: &Box4, xbox: &Box4, p: usize, forward: bool) -> Place {
    let behind = if forward {
        c[p][1] < xbox[p][0]
    } else {
        c[p][0] > xbox[p][1]
    };
    if behind {
        Place::Behind
    } else if !overlap(c, tube) {
        Place::Away
    } else if !inside(c, tube) || (c[p][0] <= xbox[p][1] && xbox[p][0] <= c[p][1]) {
        Place::Unclear
    } else {
        Place::Ahead
    }
}

fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    (0..4).map(|i| a[i] * b[i]).sum()
}

fn in_domain(x: &[f64; 4]) -> bool {
    x.iter().all(|&c| (0.0..=1.0).contains(&c))
}

/// What a proposed step turned out to be.
enum Outcome {
    /// Accepted: the new point, its certified box, the tube, and the
    /// factor for the next step's length.
    Step([f64; 4], Box4, Box4, f64),
    /// Accepted and the branch ends (crossing or loop).
    Last(Box4, End),
    /// Rejected: try again with the step's length times this factor.
    Retry(f64),
    /// Rejected because the tube test failed: try again shorter, and
    /// remember the length.
    Unproven,
}

/// The factor that brings a chord deviation `dev` to about `0.8·tol`: the
/// deviation grows as the square of the step.
fn chord_factor(dev: f64, tol: f64) -> f64 {
    let f = 0.8 * (tol / dev).sqrt();
    if f.is_nan() {
        0.5
    } else {
        f
    }
}

impl Tracer<'_> {
    fn oriented(&self, x: &[f64; 4], dir: &[f64; 4]) -> Option<[f64; 4]> {
        let t = self.sys.tangent(x)?;
        Some(if dot(&t, dir) < 0.0 { t.map(|c| -c) } else { t })
    }

    /// One RK4 step of `x' = T(x)`; Euler where a tangent is missing.
    fn predict(&self, x: &[f64; 4], dir: &[f64; 4], h: f64) -> [f64; 4] {
        let at = |y: [f64; 4], k: &[f64; 4], s: f64| -> [f64; 4] { std::array::from_fn(|i| y[i] + s * k[i]) };
        let k1 = *dir;
        let Some(k2) = self.oriented(&at(*x, &k1, 0.5 * h), dir) else {
            return at(*x, &k1, h);
        };
        let Some(k3) = self.oriented(&at(*x, &k2, 0.5 * h), dir) else {
            return at(*x, &k1, h);
        };
        let Some(k4) = self.oriented(&at(*x, &k3, h), dir) else {
            return at(*x, &k1, h);
        };
        std::array::from_fn(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }

    /// Traces from `start` (whose certified box is `sbox`) until an end.
    /// From a turning point, along the tangent at its centre, or against it
    /// when `backward` (a crossing has one way in; `backward` is ignored).
    pub(crate) fn trace(&self, start: Start, sbox: Box4, backward: bool) -> Trace {
        let x0 = center(&sbox);
        let mut tr = Trace {
            points: vec![(x0, true)],
            tubes: Vec::new(),
            turning: Vec::new(),
            end: End::Stuck(sbox),
        };
        if let Start::Turning(k) = start {
            tr.turning.push(k);
        }
        let Some(t0) = self.sys.tangent(&x0) else {
            return tr;
        };
        let mut dir = if backward { t0.map(|c| -c) } else { t0 };
        // From a crossing: the orientation of the tangent that enters the
        // domain, proven where the signs of the tangent's components over
        // the crossing's box are (`entry`), else proposed by the float
        // tangent.
        let mut entry = None;
        if let Start::Crossing(k) = start {
            match self.entry(&sbox) {
                Entry::Proven(orient, signs) => {
                    // Orient the float tangent by its largest component whose
                    // sign is proven.
                    let axis = (0..4)
                        .filter(|&a| signs[a].is_some())
                        .max_by(|&a, &b| t0[a].abs().total_cmp(&t0[b].abs()));
                    match axis {
                        Some(a) if t0[a] != 0.0 => {
                            let want = orient * signs[a].unwrap_or(0.0);
                            dir = if t0[a] * want > 0.0 { t0 } else { t0.map(|c| -c) };
                            entry = Some((orient, signs));
                        }
                        _ => return tr,
                    }
                }
                Entry::Touches => {
                    // The curve only touches the domain here (enters through
                    // one face as it leaves through another: a corner).
                    tr.end = End::Crossing(k);
                    return tr;
                }
                Entry::Unproven => {
                    dir = t0;
                    let faces = faces_of(&sbox, false);
                    let Some(&(d, s)) = faces.iter().max_by(|a, b| t0[a.0].abs().total_cmp(&t0[b.0].abs())) else {
                        return tr;
                    };
                    if t0[d] * s < 0.0 {
                        dir = t0.map(|c| -c);
                    }
                    if faces.iter().any(|&(e, s)| dir[e] * s <= 0.0) {
                        tr.end = End::Crossing(k);
                        return tr;
                    }
                }
            }
        }
        let mut x = x0;
        let mut xbox = sbox;
        let mut h = 0.02f64;
        // Below the last length the tube test refused, raised by a tenth
        // at each accepted step: chord control alone would double the step
        // into the same refusal over and over.
        let mut ceiling = MAX_STEP;
        loop {
            if tr.points.len() >= self.max_points {
                tr.end = End::Stuck(xbox);
                return tr;
            }
            let outcome = self.step(&x, &xbox, &dir, h, start, entry, &mut tr);
            match outcome {
                Outcome::Retry(_) | Outcome::Unproven => {
                    (h, ceiling) = match outcome {
                        Outcome::Retry(f) => (h * f, ceiling),
                        _ => (0.6 * h, 0.9 * h),
                    };
                    if h < MIN_STEP && h < 0.25 * self.gap(&xbox, start) {
                        tr.end = End::Stuck(xbox);
                        return tr;
                    }
                }
                Outcome::Last(tube, end) => {
                    tr.tubes.push(tube);
                    match end {
                        End::Crossing(k) => tr.points.push((center(&self.crossings[k]), true)),
                        End::Closed | End::Stuck(_) => {}
                    }
                    tr.end = end;
                    return tr;
                }
                Outcome::Step(xn, nbox, tube, grow) => {
                    tr.tubes.push(tube);
                    tr.points.push((xn, true));
                    let Some(t) = self.oriented(&xn, &dir) else {
                        tr.end = End::Stuck(tube);
                        return tr;
                    };
                    dir = t;
                    x = xn;
                    xbox = nbox;
                    h = (h * grow).min(ceiling);
                    ceiling = (1.1 * ceiling).min(MAX_STEP);
                }
            }
        }
    }

    /// Proposes, checks and proves one step of length `h` (module docs).
    #[allow(clippy::too_many_arguments)]
    fn step(
        &self,
        x: &[f64; 4],
        xbox: &Box4,
        dir: &[f64; 4],
        h: f64,
        start: Start,
        entry: Option<(f64, [Option<f64>; 4])>,
        tr: &mut Trace,
    ) -> Outcome {
        let pred = self.predict(x, dir, h);
        let mid: [f64; 4] = std::array::from_fn(|i| 0.5 * (x[i] + pred[i]));
        let Some(tm) = self.oriented(&mid, dir) else {
            return Outcome::Retry(0.5);
        };
        let p = (0..4).max_by(|&a, &b| tm[a].abs().total_cmp(&tm[b].abs())).unwrap_or(0);
        let Some(xn) = self.sys.correct(pred, p) else {
            return Outcome::Retry(0.5);
        };
        if (xn[p] - x[p]) * tm[p] <= 0.0 {
            return Outcome::Retry(0.5);
        }
        let Some(xm) = self.sys.correct(std::array::from_fn(|i| 0.5 * (x[i] + xn[i])), p) else {
            return Outcome::Retry(0.5);
        };
        let (a, b, m) = (
            (self.xyz)(x[0], x[1]),
            (self.xyz)(xn[0], xn[1]),
            (self.xyz)(xm[0], xm[1]),
        );
        let dev = (0..3).map(|i| (m[i] - 0.5 * (a[i] + b[i])).powi(2)).sum::<f64>().sqrt();
        // NaN counts as too far.
        if dev.partial_cmp(&self.tol) != Some(std::cmp::Ordering::Less) && h > 1e-6 {
            return Outcome::Retry(chord_factor(dev, self.tol).clamp(0.1, 0.5));
        }
        let Some((tube, jac)) = self.prove(x, &xm, &xn, p, xbox) else {
            return Outcome::Unproven;
        };
        let first = tr.tubes.is_empty();
        // Start points in the tube: on the arc, which is a graph over axis p,
        // so each lies behind the current point, ahead of it, or level with
        // it along p; only those ahead are on this step's walk.
        let forward = xn[p] > x[p];
        let mut hits = Vec::new();
        for (k, c) in self.crossings.iter().enumerate() {
            if first && matches!(start, Start::Crossing(s) if s == k) {
                continue;
            }
            match place(c, &tube, xbox, p, forward) {
                Place::Away | Place::Behind => {}
                Place::Unclear => return Outcome::Retry(0.5),
                Place::Ahead => hits.push(k),
            }
        }
        if self.undecided.iter().any(|u| overlap(u, &tube)) {
            return Outcome::Retry(0.5);
        }
        if hits.len() > 1 {
            return Outcome::Retry(0.5);
        }
        if hits.is_empty() && !in_domain(&xn) {
            // The arc leaves the domain, so a crossing lies in the tube;
            // none was found whole in it: a smaller step.
            return Outcome::Retry(0.5);
        }
        if let (true, Start::Crossing(_)) = (first, start) {
            // The first step from a crossing must enter the domain. Going on
            // to another crossing it is the whole open arc between them,
            // which meets no boundary, so it lies wholly inside the domain or
            // wholly outside it (a bit of the curve poking out of an edge):
            // proven inside by the orientation of the walk (the tangent's
            // proven signs at the start: `T_p` says which way along `p` the
            // entering orientation goes), or else by a certified point of
            // the arc inside.
            let walk = if xn[p] > x[p] { 1.0 } else { -1.0 };
            let inward = entry.and_then(|(orient, signs)| signs[p].map(|sp| walk * sp == orient));
            match (inward, hits.first()) {
                (Some(false), _) => return Outcome::Retry(0.5),
                (None, Some(&k)) if !self.inside_between(&xm, p, &tube, &jac, &self.crossings[k], xbox) => {
                    return Outcome::Retry(0.5)
                }
                _ => {}
            }
        }
        let mut found = Vec::new();
        for (k, t) in self.turning.iter().enumerate() {
            let own = matches!(start, Start::Turning(s) if s == k);
            if own && first {
                continue;
            }
            match place(t, &tube, xbox, p, forward) {
                Place::Away | Place::Behind => {}
                Place::Unclear => return Outcome::Retry(0.5),
                Place::Ahead => found.push(k),
            }
        }
        let closed = found.iter().any(|&k| matches!(start, Start::Turning(s) if s == k));
        if closed || !hits.is_empty() {
            for k in found {
                if !tr.turning.contains(&k) {
                    tr.turning.push(k);
                }
            }
            let end = if closed { End::Closed } else { End::Crossing(hits[0]) };
            return Outcome::Last(tube, end);
        }
        let nbox = self
            .sys
            .certify_in(&xn, p, &tube, &jac)
            .or_else(|| self.sys.certify_point(&xn, p))
            .filter(|b| inside(b, &tube));
        let Some(nb) = nbox else {
            return Outcome::Retry(0.5);
        };
        for k in found {
            if !tr.turning.contains(&k) {
                tr.turning.push(k);
            }
        }
        Outcome::Step(xn, nb, tube, chord_factor(dev, self.tol).clamp(0.5, 2.0))
    }

    /// How the curve meets the domain at the crossing `sbox` ([`Entry`]): a
    /// certified crossing is a simple zero of its face system, so the
    /// tangent's component across the face is not 0 there; its sign over
    /// the box, proven in interval arithmetic, says which orientation
    /// enters. A box that lies on no face exactly (or past one) is
    /// unproven.
    fn entry(&self, sbox: &Box4) -> Entry {
        let faces = faces_of(sbox, true);
        if faces.is_empty() || faces_of(sbox, false).len() != faces.len() {
            return Entry::Unproven;
        }
        let signs = self.sys.tangent_signs(sbox);
        let mut orient = None;
        for &(d, s) in &faces {
            let Some(t) = signs[d] else {
                return Entry::Unproven;
            };
            match orient {
                None => orient = Some(t * s),
                Some(o) if o != t * s => return Entry::Touches,
                Some(_) => {}
            }
        }
        match orient {
            Some(o) => Entry::Proven(o, signs),
            None => Entry::Unproven,
        }
    }

    /// The max-norm distance from the box `xbox` to the nearest start point
    /// other than `start` (`∞` if none): where start points crowd together
    /// (a tiny arc cutting a corner, two crossings 10⁻¹⁰ apart) steps go
    /// below [`MIN_STEP`], down to a quarter of this gap.
    fn gap(&self, xbox: &Box4, start: Start) -> f64 {
        let dist = |b: &Box4| {
            (0..4)
                .map(|d| (b[d][0] - xbox[d][1]).max(xbox[d][0] - b[d][1]).max(0.0))
                .fold(0.0f64, f64::max)
        };
        let crossings = self
            .crossings
            .iter()
            .enumerate()
            .filter(|&(k, _)| !matches!(start, Start::Crossing(s) if s == k))
            .map(|(_, b)| dist(b));
        let turning = self
            .turning
            .iter()
            .enumerate()
            .filter(|&(k, _)| !matches!(start, Start::Turning(s) if s == k))
            .map(|(_, b)| dist(b));
        crossings.chain(turning).fold(f64::INFINITY, f64::min)
    }

    /// The arc of the tube between the start crossing `xbox` and the
    /// crossing `end` has a point inside the closed domain: the curve point
    /// on the hyperplane `x_p = xm_p`, certified in the tube, lies in
    /// `[0, 1]⁴`, and that hyperplane passes strictly between the two
    /// crossings' boxes (so the point is neither of them).
    fn inside_between(
        &self,
        xm: &[f64; 4],
        p: usize,
        tube: &Box4,
        jac: &[[Iv; 3]; 3],
        end: &Box4,
        xbox: &Box4,
    ) -> bool {
        let (lo, hi) = if xbox[p][1] < end[p][0] {
            (xbox[p][1], end[p][0])
        } else {
            (end[p][1], xbox[p][0])
        };
        if !(lo < xm[p] && xm[p] < hi) {
            return false;
        }
        self.sys
            .certify_in_radii(xm, p, tube, jac, &[1e-15, 1e-13, 1e-12, 1e-10, 1e-8])
            .is_some_and(|b| inside(&b, tube) && b.iter().all(|&[l, h]| 0.0 <= l && h <= 1.0))
    }

    /// The tube around the step `x → xn` (midpoint `xm`) along axis `p`,
    /// holding the previous point's box; `None` if not proven.
    ///
    /// The first `Y` is the hull of the three points and the previous box,
    /// padded by a quarter of its extent and a fifth of the step on each
    /// axis: an axis the arc barely moves along must still absorb the
    /// wrapping `(I − C·∂_y F)·(Y − ỹ)` of the wide ones, which grows with
    /// the step, not with its own extent. The second is that `Y` joined
    /// with `K(P, Y)` widened by a quarter of its width (ε-inflation).
    fn prove(&self, x: &[f64; 4], xm: &[f64; 4], xn: &[f64; 4], p: usize, xbox: &Box4) -> Option<(Box4, [[Iv; 3]; 3])> {
        let q = others(p);
        let len = (xn[p] - x[p]).abs();
        let pad = 1e-3 * len + (xbox[p][1] - xbox[p][0]) + 1e-13;
        let pr = [x[p].min(xn[p]) - pad, x[p].max(xn[p]) + pad];
        let mut y: [[f64; 2]; 3] = std::array::from_fn(|k| {
            let c = q[k];
            let lo = x[c].min(xm[c]).min(xn[c]).min(xbox[c][0]);
            let hi = x[c].max(xm[c]).max(xn[c]).max(xbox[c][1]);
            let r = 0.25 * (hi - lo) + 0.2 * len + 1e-12;
            [lo - r, hi + r]
        });
        for _ in 0..2 {
            let jac = self.sys.jacobian_box(p, pr, &y)?;
            let k = self.sys.krawczyk(p, pr, y, &jac)?;
            if (0..3).all(|r| k[r].inside_open(y[r][0], y[r][1])) {
                let mut tube: Box4 = [pr; 4];
                for (i, &c) in q.iter().enumerate() {
                    tube[c] = y[i];
                }
                return inside(xbox, &tube).then_some((tube, jac));
            }
            y = std::array::from_fn(|r| {
                let w = 0.25 * (k[r].hi - k[r].lo) + 1e-12;
                [y[r][0].min(k[r].lo - w), y[r][1].max(k[r].hi + w)]
            });
        }
        None
    }
}
