//! The univariate solver's search in interval arithmetic: Bernstein
//! subdivision of `[0, 1]` with Descartes' rule as the exclusion and
//! isolation test, the Bézier clip to converge, interval Newton to certify
//! and contract. Works on coefficient enclosures, so every verdict holds
//! for every polynomial in them (and for an exact polynomial, enclosed).

use super::bernstein::{clip_local, derivative_hull, eval, no_signal, restrict, sign_changes, to_global, Sign3};
use super::UniStats;
use crate::scalar::iv::Iv;
use crate::solve::krawczyk::Verdict;

/// Steps of a contraction (each halves the interval or ends it).
const CONTRACT_STEPS: usize = 120;
/// Rounds of [`certify`] (contraction towards `N(X)` or growth).
const CERTIFY_ROUNDS: usize = 24;
/// [`certify`] grows a region by at most this much on each side: a root of
/// condition ~1e9 needs an interval ~1e-7 wide around it before rounding
/// lets Newton's operator land inside, far more than its 1e-12 leaf.
const GROW_CAP: f64 = 1e-6;

pub(crate) fn width(x: [f64; 2]) -> f64 {
    x[1] - x[0]
}

/// At most four floats apart: nothing left to split.
pub(crate) fn narrow(x: [f64; 2]) -> bool {
    let mut t = x[0];
    for _ in 0..4 {
        t = t.next_up();
    }
    t >= x[1]
}

/// `x` widened by `r` on each side (rounded outward: a float is added).
pub(crate) fn widen(x: [f64; 2], r: f64) -> [f64; 2] {
    let ulps = 4.0 * f64::EPSILON * x[0].abs().max(x[1].abs()) + f64::MIN_POSITIVE;
    let r = r + ulps;
    [(x[0] - r).next_down(), (x[1] + r).next_up()]
}

/// Interval Newton on `X = [x0, x1]`: `N(X) = m − p(m)/p'(X)` with `m` the
/// float midpoint, `p(m)` enclosed by de Casteljau on `c` (the coefficients
/// on `[0, 1]`) and `p'(X)` the hull of the derivative's coefficients `cx`
/// on `X`, all rounded outward. `N(X) ⊂ int X` proves exactly one root in
/// `X`, simple, lying in `N(X)` (Moore 1966): [`Verdict::Unique`] with
/// `N(X)`. `N(X) ∩ X = ∅` proves none. Otherwise every root of `X` lies in
/// `N(X) ∩ X` ([`Verdict::Undecided`]; `X` itself when `0 ∈ p'(X)`).
pub(crate) fn newton(c: &[Iv], cx: &[Iv], x: [f64; 2]) -> Verdict<[f64; 2]> {
    let d = derivative_hull(cx, x[0], x[1]);
    if !(d.lo > 0.0 || d.hi < 0.0) {
        return Verdict::Undecided(x);
    }
    let m = 0.5 * x[0] + 0.5 * x[1];
    let n = Iv::point(m).sub(eval(c, m).div(d));
    if !n.is_finite() {
        return Verdict::Undecided(x);
    }
    if n.inside_open(x[0], x[1]) {
        return Verdict::Unique([n.lo, n.hi]);
    }
    match n.meet(Iv::new(x[0], x[1])) {
        None => Verdict::NoRoot,
        Some(k) => Verdict::Undecided([k.lo, k.hi]),
    }
}

/// Contracts `x`, which holds exactly one root, a simple one, by
/// `X ← N(X) ∩ X` while that halves it and by bisection on proven signs
/// otherwise, until neither makes progress (the rounding floor). The root
/// stays inside: every root of `X` lies in `N(X)`; a half is dropped only
/// where `p` has one strict sign at both its ends (an even number of
/// roots, so none of a unique simple one).
pub(crate) fn contract(c: &[Iv], mut x: [f64; 2]) -> [f64; 2] {
    for _ in 0..CONTRACT_STEPS {
        if narrow(x) {
            break;
        }
        let cx = restrict(c, x[0], x[1]);
        let next = match newton(c, &cx, x) {
            Verdict::Unique(k) | Verdict::Undecided(k) => k,
            Verdict::NoRoot => x, // impossible for a certified x; keep it
        };
        if width(next) * 2.0 <= width(x) {
            x = next;
            continue;
        }
        let half = bisect_by_sign(c, next);
        if half == next {
            return next;
        }
        x = half;
    }
    x
}

/// The half of `x` where the sign change is proven to be, or `x`.
fn bisect_by_sign(c: &[Iv], x: [f64; 2]) -> [f64; 2] {
    let m = 0.5 * x[0] + 0.5 * x[1];
    if !(x[0] < m && m < x[1]) {
        return x;
    }
    let sm = Sign3::of(eval(c, m));
    if !sm.strict() {
        return x;
    }
    if sm == Sign3::of(eval(c, x[0])) {
        [m, x[1]]
    } else if sm == Sign3::of(eval(c, x[1])) {
        [x[0], m]
    } else {
        x
    }
}

/// What Descartes' rule proves on `[t0, t1]` from the coefficients there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Descartes {
    /// No member has a root in the closed interval (no sign change, and
    /// both end values strictly signed).
    NoRoot,
    /// Every member has exactly one root in the open interval, simple
    /// (exactly one sign change for every member), and strictly opposite
    /// signs at the ends.
    One,
    /// Neither.
    Unknown,
}

pub(crate) fn descartes(cx: &[Iv]) -> Descartes {
    let (vmin, vmax) = sign_changes(cx);
    let (s0, sn) = (Sign3::of(cx[0]), Sign3::of(cx[cx.len() - 1]));
    if vmax == 0 && s0.strict() && sn.strict() {
        Descartes::NoRoot
    } else if vmin == 1 && vmax == 1 && s0.opposite(sn) {
        Descartes::One
    } else {
        Descartes::Unknown
    }
}

/// What the search found in `[0, 1]` (local parameter).
#[derive(Debug, Default)]
pub(crate) struct Search {
    /// Intervals holding exactly one root each, simple.
    pub(crate) roots: Vec<[f64; 2]>,
    /// Intervals neither excluded nor isolated when the search stopped
    /// there (narrower than `eps`, or with no signal left).
    pub(crate) leaves: Vec<[f64; 2]>,
    /// Intervals the budget left unexplored.
    pub(crate) leftovers: Vec<[f64; 2]>,
}

/// The subdivision search on the coefficient enclosures `c` on `[0, 1]`.
/// Every root in `[0, 1]` of every member ends in a root interval, a leaf
/// or a leftover: an interval is dropped only when Descartes or Newton
/// proves it root-free, and a clip keeps every point the control polygon's
/// hull does not exclude.
pub(crate) fn search(c: &[Iv], eps: f64, max_boxes: usize, stats: &mut UniStats) -> Search {
    let mut out = Search::default();
    let mut stack = vec![[0.0, 1.0]];
    while let Some(x) = stack.pop() {
        if stats.intervals >= max_boxes {
            out.leftovers.push(x);
            continue;
        }
        stats.intervals += 1;
        let cx = restrict(c, x[0], x[1]);
        match descartes(&cx) {
            Descartes::NoRoot => {
                stats.exclusions += 1;
                continue;
            }
            Descartes::One => {
                stats.isolations += 1;
                out.roots.push(contract(c, x));
                continue;
            }
            Descartes::Unknown => {}
        }
        let mut kept = x;
        if derivative_hull(&cx, x[0], x[1]).lo.is_finite() {
            stats.newton_tests += 1;
            match newton(c, &cx, x) {
                Verdict::Unique(k) => {
                    out.roots.push(contract(c, k));
                    continue;
                }
                Verdict::NoRoot => {
                    stats.newton_exclusions += 1;
                    continue;
                }
                Verdict::Undecided(k) => kept = k,
            }
        }
        if width(x) < eps || no_signal(&cx) || narrow(x) {
            out.leaves.push(x);
            continue;
        }
        if width(kept) * 2.0 > width(x) {
            match clip_local(&cx) {
                None => {
                    stats.exclusions += 1;
                    continue;
                }
                Some(l) => kept = to_global(x, l),
            }
        }
        if width(kept) * 2.0 <= width(x) {
            stats.clips += 1;
            stack.push(kept);
            continue;
        }
        let m = 0.5 * kept[0] + 0.5 * kept[1];
        if !(kept[0] < m && m < kept[1]) {
            out.leaves.push(kept);
            continue;
        }
        stats.bisections += 1;
        stack.push([m, kept[1]]);
        stack.push([kept[0], m]);
    }
    out
}

/// Certifies a region the search left (a group of touching leaves): tests
/// the region widened a little (a root on its edge), then contracts towards
/// `N(X)` or grows (at most [`GROW_CAP`] on each side) until Descartes or
/// Newton decides. Invariant: every root of the region lies in the current
/// `X` (contraction keeps `N(X) ∩ X`, growth only adds), so
/// [`Verdict::NoRoot`] proves the region root-free and
/// [`Verdict::Unique`]'s interval holds the region's only possible root
/// (it may lie outside the region, or outside `[0, 1]`).
pub(crate) fn certify(c: &[Iv], region: [f64; 2], stats: &mut UniStats) -> Verdict<[f64; 2], ()> {
    let cap = [region[0] - GROW_CAP, region[1] + GROW_CAP];
    let mut x = widen(region, 0.1 * width(region));
    for _ in 0..CERTIFY_ROUNDS {
        let cx = restrict(c, x[0], x[1]);
        match descartes(&cx) {
            Descartes::NoRoot => return Verdict::NoRoot,
            Descartes::One => return Verdict::Unique(contract(c, x)),
            Descartes::Unknown => {}
        }
        stats.newton_tests += 1;
        let next = match newton(c, &cx, x) {
            Verdict::Unique(k) => return Verdict::Unique(contract(c, k)),
            Verdict::NoRoot => return Verdict::NoRoot,
            Verdict::Undecided(k) if width(k) * 2.0 <= width(x) => widen(k, 0.1 * width(k)),
            Verdict::Undecided(_) => {
                let grown = widen(x, 0.5 * width(x));
                [grown[0].max(cap[0]).min(x[0]), grown[1].min(cap[1]).max(x[1])]
            }
        };
        if next == x {
            break;
        }
        x = next;
    }
    Verdict::Undecided(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(c: &[f64]) -> Vec<Iv> {
        c.iter().map(|&x| Iv::point(x)).collect()
    }

    #[test]
    fn newton_certifies_a_simple_root_and_contracts() {
        // t − 1/3 on [0, 1]: BB coefficients −1/3, 2/3.
        let c = iv(&[-1.0 / 3.0, 2.0 / 3.0]);
        let x = [0.25, 0.5];
        let v = newton(&c, &restrict(&c, x[0], x[1]), x);
        let Verdict::Unique(k) = v else { panic!("{v:?}") };
        let k = contract(&c, k);
        assert!(k[0] <= 1.0 / 3.0 && 1.0 / 3.0 <= k[1] && width(k) < 4e-15, "{k:?}");
    }

    #[test]
    fn search_isolates_and_excludes() {
        // (t − 0.25)(t − 0.75) = t² − t + 3/16: BB 3/16, 3/16 − 1/2, 3/16.
        let c = iv(&[0.1875, 0.1875 - 0.5, 0.1875]);
        let mut stats = UniStats::default();
        let s = search(&c, 1e-12, 1000, &mut stats);
        assert_eq!(s.roots.len(), 2, "{s:?}");
        assert!(s.leaves.is_empty() && s.leftovers.is_empty());
        assert!(s.roots[0][0] <= 0.25 && 0.25 <= s.roots[0][1] || s.roots[1][0] <= 0.25 && 0.25 <= s.roots[1][1]);
    }
}
