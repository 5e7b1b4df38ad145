//! The enclosure-based clip ([`clip_in`]): the bounds of `R` (see the
//! parent module) as minima over enclosures of every candidate minimizer.
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
//! With a rigorous kernel ([`GeoIv`](crate::scalar::geo::GeoIv)) every candidate is an enclosure of the exact
//! candidate of the exact constraint curves, feasibility is tested as
//! "possibly feasible", and the bound is the lower end of the enclosures, so
//! `u_min` is a rigorous lower bound. Where an enclosure cannot be bounded
//! (nearly parallel lines, a nearly degenerate quadratic) it is clamped to
//! `[0, 1]` — always valid, because feasible points have `s, t ∈ [0, 1]` —
//! which only weakens the clip. If no candidate is possibly feasible, `R` is
//! empty: the tri-box holds no root.

use super::curves::{keep_or_empty, ClipBounds, Fat, Linear, Quadratic};
use crate::scalar::geo::Geo;
use crate::scalar::iv;
use crate::scalar::Sign;
use smallvec::SmallVec;

pub(super) struct Bounds {
    mins: [f64; 3],
    any: bool,
}

impl Bounds {
    pub(super) fn new() -> Self {
        Self {
            mins: [f64::INFINITY; 3],
            any: false,
        }
    }

    /// Whether [`Bounds::add`] of this candidate could change anything: it is
    /// the first one, or it lowers one of the minima. Deciding this before
    /// the (costlier) feasibility test changes no result.
    pub(super) fn could_lower<S: Geo>(&self, s: S, t: S) -> bool {
        let w = S::pt(1.0) - s - t;
        !self.any || s.lower() < self.mins[0] || t.lower() < self.mins[1] || w.lower() < self.mins[2]
    }

    pub(super) fn add<S: Geo>(&mut self, s: S, t: S) {
        let w = S::pt(1.0) - s - t;
        self.any = true;
        self.mins[0] = self.mins[0].min(s.lower());
        self.mins[1] = self.mins[1].min(t.lower());
        self.mins[2] = self.mins[2].min(w.lower());
    }

    /// No candidate can change the result any more: it is `Keep([0, 0, 0])`
    /// (`finish` clamps the minima to `[0, 1]`).
    pub(super) fn settled(&self) -> bool {
        self.any && self.mins.iter().all(|&m| m <= 0.0)
    }

    pub(super) fn finish(self, rigorous: bool) -> ClipBounds {
        if !self.any {
            return ClipBounds::Empty;
        }
        let m = self.mins.map(|x| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) });
        keep_or_empty(m, rigorous)
    }
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

/// The clipping bounds of `R = tri-box ∩ fats` from enclosures of every
/// candidate (see the module docs).
pub(super) fn clip_in<G: Geo>(fats: &[Fat<G>]) -> ClipBounds {
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

#[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
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

#[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::geo::GeoIv;
    use crate::scalar::{interval, point};
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
}
