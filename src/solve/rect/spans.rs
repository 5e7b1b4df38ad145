//! Clipping a box: the spans of `[0, 1]` in each direction that may hold a
//! root (Bézier hulls, step 4 of the [`rect`](super) docs, and hulls of
//! preconditioned combinations for stalled boxes), the widening that keeps
//! roots off new edges, and the exact sub-boxes they become (clip, split).

use super::net::{at, jacobian_row, one_signed, with_small_degrees, Node, Shape, SMALL_LEN, STACK};
use crate::scalar::iv::{down, up, Iv};
use crate::solve::envelope::zero_span_inline;
use crate::solve::linalg::{inverse2, smallest_singular_left};

/// The smallest ratio of a clipped box's sides ([`keep_aspect`]).
const MIN_ASPECT: f64 = 1e-3;

/// Where boxes are split (exact, and so is `1 − SPLIT`).
const SPLIT: f64 = 63.0 / 128.0;

/// Bézier clipping of the box in both directions: the intersection of the
/// spans of `f` and `g` (`rect` docs, step 4); `None` if it is empty.
pub(super) fn hull_spans(c: &[Iv], sh: Shape) -> Option<[(f64, f64); 2]> {
    match (sh.m, sh.n) {
        (3, 3) => return hull_spans_square::<3, 16>(c),
        (2, 2) => return hull_spans_square::<2, 9>(c),
        _ => {}
    }
    with_small_degrees!(sh, |m, n| hull_spans_in(
        c,
        Shape {
            m,
            n,
            len: (m + 1) * (n + 1),
            ..sh
        }
    ))
}

#[inline(always)]
fn hull_spans_in(c: &[Iv], sh: Shape) -> Option<[(f64, f64); 2]> {
    let mut spans = [(0.0f64, 1.0f64); 2];
    for (d, span) in spans.iter_mut().enumerate() {
        for p in 0..2 {
            let (a, b) = zero_span(&c[p * sh.len..(p + 1) * sh.len], sh, d)?;
            *span = (span.0.max(a), span.1.min(b));
        }
        if span.0 > span.1 {
            return None;
        }
    }
    Some(spans)
}

/// [`hull_spans_in`] for bidegree `(K, K)`, `K ≤ 3` (`L = (K + 1)²`): the
/// row and column ranges of each equation in one pass over fixed arrays,
/// then the same crossings and intersections, so the same floats. The
/// ranges use `<` selections, not `f64::min`: a NaN coefficient gives the
/// whole span either way (it fails `lo ≤ hi`), and where the two could
/// differ, `−0` against `+0`, no crossing depends on it.
#[inline(always)]
fn hull_spans_square<const K: usize, const L: usize>(c: &[Iv]) -> Option<[(f64, f64); 2]> {
    let w = K + 1;
    let mut spans = [(0.0f64, 1.0f64); 2];
    for p in 0..2 {
        let Ok(q) = <&[Iv; L]>::try_from(&c[p * L..(p + 1) * L]) else {
            unreachable!("a polynomial holds (K + 1)² coefficients")
        };
        let (mut rl, mut rh) = ([f64::INFINITY; 4], [f64::NEG_INFINITY; 4]);
        let (mut cl, mut ch) = ([f64::INFINITY; 4], [f64::NEG_INFINITY; 4]);
        let mut ok = true;
        for i in 0..w {
            for j in 0..w {
                let x = q[i * w + j];
                ok &= x.lo <= x.hi;
                rl[i] = if x.lo < rl[i] { x.lo } else { rl[i] };
                rh[i] = if x.hi > rh[i] { x.hi } else { rh[i] };
                cl[j] = if x.lo < cl[j] { x.lo } else { cl[j] };
                ch[j] = if x.hi > ch[j] { x.hi } else { ch[j] };
            }
        }
        for (d, (lo, hi)) in [(&rl, &rh), (&cl, &ch)].into_iter().enumerate() {
            let finite = lo[..w].iter().chain(&hi[..w]).all(|x| x.is_finite());
            let (a, b) = if ok && finite {
                zero_span_inline(&lo[..w], &hi[..w])?
            } else {
                (0.0, 1.0)
            };
            spans[d] = (spans[d].0.max(a), spans[d].1.min(b));
        }
    }
    if spans.iter().any(|s| s.0 > s.1) {
        return None;
    }
    Some(spans)
}

/// The span of `[0, 1]` in direction `d` (0: `s`, index `i`; 1: `t`, index
/// `j`) where the convex hull of the coefficient ranges meets zero (module
/// docs, step 4); `None` if it provably does not.
#[inline(always)]
fn zero_span(p: &[Iv], sh: Shape, d: usize) -> Option<(f64, f64)> {
    let k = if d == 0 { sh.m } else { sh.n };
    if k < 4 {
        zero_span_with(p, sh, d, &mut [0.0; 4], &mut [0.0; 4])
    } else if k < STACK {
        zero_span_with(p, sh, d, &mut [0.0; STACK], &mut [0.0; STACK])
    } else {
        zero_span_with(p, sh, d, &mut vec![0.0; k + 1], &mut vec![0.0; k + 1])
    }
}

/// [`zero_span`] with scratch for the ranges (at least `k + 1` long). A
/// coefficient that is not finite gives the whole span: a NaN fails
/// `lo ≤ hi`, an infinite endpoint makes its row's range infinite.
#[inline(always)]
fn zero_span_with(p: &[Iv], sh: Shape, d: usize, lo: &mut [f64], hi: &mut [f64]) -> Option<(f64, f64)> {
    let (k, other) = if d == 0 { (sh.m, sh.n) } else { (sh.n, sh.m) };
    let mut ok = true;
    for a in 0..=k {
        let (mut l, mut h) = (f64::INFINITY, f64::NEG_INFINITY);
        for b in 0..=other {
            let c = if d == 0 { p[at(sh, a, b)] } else { p[at(sh, b, a)] };
            ok &= c.lo <= c.hi;
            l = l.min(c.lo);
            h = h.max(c.hi);
        }
        ok &= l.is_finite() & h.is_finite();
        lo[a] = l;
        hi[a] = h;
    }
    if !ok {
        return Some((0.0, 1.0));
    }
    zero_span_inline(&lo[..=k], &hi[..=k])
}

/// Spans from equations that are combinations of `f` and `g` (every root of
/// the system is a root of each): the rows of `Y·F` with `Y ≈ J(centre)⁻¹`,
/// which makes the system nearly the identity so the hulls are tight, and
/// `h = a f + b g` with `(a, b)` the left singular vector of `J` for its
/// smallest singular value, which is nearly constant where `f = 0` and
/// `g = 0` run (nearly) parallel — there it proves no root at once, where
/// axis-aligned hulls of `f` and `g` would need boxes as thin as the gap.
/// `None` when some combination proves there is no root.
pub(super) fn preconditioned_spans(c: &[Iv], sh: Shape) -> Option<[(f64, f64); 2]> {
    with_small_degrees!(sh, |m, n| preconditioned_spans_in(
        c,
        Shape {
            m,
            n,
            len: (m + 1) * (n + 1),
            ..sh
        }
    ))
}

#[inline(always)]
fn preconditioned_spans_in(c: &[Iv], sh: Shape) -> Option<[(f64, f64); 2]> {
    let (f, g) = (&c[..sh.len], &c[sh.len..2 * sh.len]);
    let [a, b] = jacobian_row(f, sh);
    let [cc, d] = jacobian_row(g, sh);
    let j = [a, b, cc, d].map(Iv::mid);
    if !j.iter().all(|x| x.is_finite()) {
        return Some([(0.0, 1.0); 2]);
    }
    let mut combos = [[0.0f64; 2]; 3];
    let mut count = 0;
    if let Some(y) = inverse2(j, 0.0) {
        combos[..2].copy_from_slice(&[[y[0], y[1]], [y[2], y[3]]]);
        count = 2;
    }
    if let Some(v) = smallest_singular_left(j) {
        combos[count] = v;
        count += 1;
    }
    let mut spans = [(0.0f64, 1.0f64); 2];
    let mut small = [Iv::point(0.0); SMALL_LEN];
    let mut large: Vec<Iv>;
    let h: &mut [Iv] = if sh.len <= SMALL_LEN {
        &mut small[..sh.len]
    } else {
        large = vec![Iv::point(0.0); sh.len];
        &mut large
    };
    for &[wa, wb] in &combos[..count] {
        for (k, x) in h.iter_mut().enumerate() {
            *x = times(wa, f[k]).add(times(wb, g[k]));
        }
        if one_signed(h) {
            return None;
        }
        for (dir, span) in spans.iter_mut().enumerate() {
            let (lo, hi) = zero_span(h, sh, dir)?;
            *span = (span.0.max(lo), span.1.min(hi));
            if span.0 > span.1 {
                return None;
            }
        }
    }
    Some(spans)
}

/// `Iv::point(a).mul(x)` with its two distinct products only (the same
/// floats: the minimum and maximum of `a·lo`, `a·hi`, moved outward).
#[inline(always)]
fn times(a: f64, x: Iv) -> Iv {
    let (p, q) = (a * x.lo, a * x.hi);
    Iv::new(down(p.min(q)), up(p.max(q)))
}

/// Widens the kept spans so that neither side of the new box is narrower
/// than [`MIN_ASPECT`] times the other (widths relative to the domain).
///
/// Why: a ray nearly along an iso-line clips one direction to ~1e-14 while
/// the other is still ~1e-2; the collapsed side is then at the rounding
/// floor, local Krawczyk cannot succeed, and the box ends as a leaf for the
/// (slower) global certificate. Keeping more of a span is always sound.
pub(super) fn keep_aspect(spans: &mut [(f64, f64); 2], w: [f64; 2]) {
    let new = [0, 1].map(|d| (spans[d].1 - spans[d].0) * w[d]);
    for d in 0..2 {
        let want = MIN_ASPECT * new[1 - d];
        if new[d] < want && w[d] > 0.0 {
            let r = 0.5 * (want / w[d] - (spans[d].1 - spans[d].0));
            spans[d] = ((spans[d].0 - r).max(0.0), (spans[d].1 + r).min(1.0));
        }
    }
}

/// Restricts the node to `[α, β]` in direction `d` (`rect` docs: exact
/// sub-box through float split parameters).
pub(super) fn clip(node: &mut Node, sh: Shape, d: usize, alpha: f64, beta: f64) {
    let gamma = clip_gamma(alpha, beta);
    restrict_all(&mut node.c, sh, d, alpha, gamma);
    let [lo, hi] = node.bx[d];
    // Convex combinations: the endpoint enclosures never grow wider than
    // their parents' (plus rounding), however many clips follow.
    let new_lo = if alpha > 0.0 { Iv::lerp(lo, hi, alpha) } else { lo };
    let new_hi = if gamma < 1.0 { Iv::lerp(new_lo, hi, gamma) } else { hi };
    node.bx[d] = [new_lo, new_hi];
    node.key = None;
}

/// The float `γ ≥ (β − α)/(1 − α)` (1 if `β ≥ 1`), so that the part
/// `[α, α + (1 − α)γ]` a clip keeps holds `[α, β]`.
pub(super) fn clip_gamma(alpha: f64, beta: f64) -> f64 {
    if beta >= 1.0 {
        1.0
    } else {
        ((beta - alpha).next_up() / (1.0 - alpha).next_down())
            .next_up()
            .min(1.0)
    }
}

/// Every polynomial of the node restricted in direction `d` to `[α, 1]`
/// (if `α > 0`) and then to the first `γ` of that (if `γ < 1`): two
/// [`subdivide_all`]s, with the `(K, K)` nets transposed once for both.
fn restrict_all(c: &mut [Iv], sh: Shape, d: usize, alpha: f64, gamma: f64) {
    let square = |c: &mut [Iv], f: fn(&mut [Iv], usize, f64, f64)| {
        for block in c.chunks_exact_mut(sh.len).take(sh.polys) {
            f(block, d, alpha, gamma);
        }
    };
    match (sh.m, sh.n) {
        (3, 3) => square(c, restrict_square::<3, 16>),
        (2, 2) => square(c, restrict_square::<2, 9>),
        (1, 1) => square(c, restrict_square::<1, 4>),
        _ => {
            if alpha > 0.0 {
                subdivide_all(c, sh, d, alpha, true);
            }
            if gamma < 1.0 {
                subdivide_all(c, sh, d, gamma, false);
            }
        }
    }
}

/// [`restrict_all`] on one `(K, K)` block: the lerps of
/// [`subdivide_square`] at `α`, then at `γ`, so the same floats.
#[inline(always)]
fn restrict_square<const K: usize, const L: usize>(block: &mut [Iv], d: usize, alpha: f64, gamma: f64) {
    let Ok(c) = <&mut [Iv; L]>::try_from(block) else {
        unreachable!("a block holds (K + 1)² coefficients")
    };
    let cut = |c: &mut [Iv; L]| {
        if alpha > 0.0 {
            lerp_rows::<K, L>(c, alpha, true);
        }
        if gamma < 1.0 {
            lerp_rows::<K, L>(c, gamma, false);
        }
    };
    if d == 0 {
        cut(c);
    } else {
        let mut tr = transpose::<K, L>(c);
        cut(&mut tr);
        *c = transpose::<K, L>(&tr);
    }
}

/// Splits the node at [`SPLIT`] in direction `d`.
pub(super) fn split(node: &Node, sh: Shape, d: usize) -> (Node, Node) {
    let mut left = node.clone();
    let mut right = node.clone();
    subdivide_all(&mut left.c, sh, d, SPLIT, false);
    subdivide_all(&mut right.c, sh, d, SPLIT, true);
    let [lo, hi] = node.bx[d];
    let mid = Iv::lerp(lo, hi, SPLIT);
    left.bx[d] = [lo, mid];
    right.bx[d] = [mid, hi];
    (left.key, right.key) = (None, None);
    (left, right)
}

/// One de Casteljau subdivision of every polynomial of the node in
/// direction `d` at `t`, keeping `[t, 1]` (`right`) or `[0, t]`.
///
/// In `s` (`d = 0`) whole rows are combined at once (`row_i ← lerp(row_i,
/// row_{i+1})`), a contiguous loop the compiler vectorizes; in `t` each row
/// is one contiguous line.
fn subdivide_all(c: &mut [Iv], sh: Shape, d: usize, t: f64, right: bool) {
    let square = |c: &mut [Iv], f: fn(&mut [Iv], usize, f64, bool)| {
        for block in c.chunks_exact_mut(sh.len).take(sh.polys) {
            f(block, d, t, right);
        }
    };
    match (sh.m, sh.n) {
        (3, 3) => return square(c, subdivide_square::<3, 16>),
        (2, 2) => return square(c, subdivide_square::<2, 9>),
        (1, 1) => return square(c, subdivide_square::<1, 4>),
        _ => {}
    }
    with_small_degrees!(sh, |m, n| subdivide_all_in(
        c,
        Shape {
            m,
            n,
            len: (m + 1) * (n + 1),
            ..sh
        },
        d,
        t,
        right
    ))
}

/// [`subdivide_all`] on one block of bidegree `(K, K)` (`L = (K + 1)²`
/// coefficients) in fixed arrays: whole rows combined at once in `s`, and in
/// `t` the same on the transposed block, so both directions run as
/// contiguous lanes the compiler vectorizes. The same `Iv::lerp`s on the same
/// operands as [`subdivide_all_in`], so the same floats.
#[inline(always)]
fn subdivide_square<const K: usize, const L: usize>(block: &mut [Iv], d: usize, t: f64, right: bool) {
    let Ok(c) = <&mut [Iv; L]>::try_from(block) else {
        unreachable!("a block holds (K + 1)² coefficients")
    };
    if d == 0 {
        lerp_rows::<K, L>(c, t, right);
    } else {
        let mut tr = transpose::<K, L>(c);
        lerp_rows::<K, L>(&mut tr, t, right);
        *c = transpose::<K, L>(&tr);
    }
}

/// The `(K + 1) × (K + 1)` array transposed.
#[inline(always)]
pub(super) fn transpose<const K: usize, const L: usize>(c: &[Iv; L]) -> [Iv; L] {
    let w = K + 1;
    let mut tr = [Iv::point(0.0); L];
    for i in 0..w {
        for j in 0..w {
            tr[j * w + i] = c[i * w + j];
        }
    }
    tr
}

/// De Casteljau across the rows of a `(K + 1) × (K + 1)` array at `t`:
/// `row_i ← lerp(row_i, row_{i+1})` keeps `[t, 1]` (`right`), `row_i ←
/// lerp(row_{i−1}, row_i)` from the last row down keeps `[0, t]`.
#[inline(always)]
pub(super) fn lerp_rows<const K: usize, const L: usize>(c: &mut [Iv; L], t: f64, right: bool) {
    let w = K + 1;
    for r in 1..w {
        if right {
            for i in 0..w - r {
                for j in 0..w {
                    c[i * w + j] = Iv::lerp(c[i * w + j], c[(i + 1) * w + j], t);
                }
            }
        } else {
            for i in (r..w).rev() {
                for j in 0..w {
                    c[i * w + j] = Iv::lerp(c[(i - 1) * w + j], c[i * w + j], t);
                }
            }
        }
    }
}

#[inline(always)]
fn subdivide_all_in(c: &mut [Iv], sh: Shape, d: usize, t: f64, right: bool) {
    let w = sh.n + 1;
    for block in c.chunks_exact_mut(sh.len).take(sh.polys) {
        if d == 0 {
            let k = sh.m;
            for r in 1..=k {
                if right {
                    for i in 0..=k - r {
                        let (head, tail) = block.split_at_mut((i + 1) * w);
                        for (x, y) in head[i * w..].iter_mut().zip(&tail[..w]) {
                            *x = Iv::lerp(*x, *y, t);
                        }
                    }
                } else {
                    for i in (r..=k).rev() {
                        let (head, tail) = block.split_at_mut(i * w);
                        for (y, x) in tail[..w].iter_mut().zip(&head[(i - 1) * w..]) {
                            *y = Iv::lerp(*x, *y, t);
                        }
                    }
                }
            }
        } else {
            let k = sh.n;
            for line in block.chunks_exact_mut(w) {
                for r in 1..=k {
                    if right {
                        for i in 0..=k - r {
                            line[i] = Iv::lerp(line[i], line[i + 1], t);
                        }
                    } else {
                        for i in (r..=k).rev() {
                            line[i] = Iv::lerp(line[i - 1], line[i], t);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    fn random_net(rng: &mut Rng, len: usize) -> Vec<Iv> {
        (0..len)
            .map(|_| {
                let x = rng.next_signed();
                Iv::new(x, x + 1e-3 * rng.next_f64())
            })
            .collect()
    }

    #[test]
    fn square_subdivision_gives_the_general_floats() {
        let mut rng = Rng(7);
        for k in 1..=3 {
            let sh = Shape::pair(k, k);
            for _ in 0..50 {
                let net = random_net(&mut rng, 2 * sh.len);
                let t = rng.next_f64();
                for (d, right) in [(0, false), (0, true), (1, false), (1, true)] {
                    let (mut a, mut b) = (net.clone(), net.clone());
                    subdivide_all(&mut a, sh, d, t, right);
                    subdivide_all_in(&mut b, sh, d, t, right);
                    assert_eq!(a, b, "k {k} d {d} right {right}");
                }
            }
        }
    }

    #[test]
    fn square_hull_spans_give_the_general_floats() {
        let mut rng = Rng(3);
        for k in 2..=3 {
            let sh = Shape::pair(k, k);
            for _ in 0..2000 {
                let mut net = random_net(&mut rng, 2 * sh.len);
                // Shift the equations so that their zero sets cross the box.
                for p in 0..2 {
                    let off = 0.8 * rng.next_signed();
                    for x in &mut net[p * sh.len..(p + 1) * sh.len] {
                        *x = Iv::new(x.lo + off, x.hi + off);
                    }
                }
                let want = with_small_degrees!(sh, |m, n| hull_spans_in(&net, Shape { m, n, ..sh }));
                assert_eq!(hull_spans(&net, sh), want);
            }
        }
    }

    #[test]
    fn square_restriction_gives_two_subdivisions() {
        let mut rng = Rng(13);
        for k in 1..=3 {
            let sh = Shape::pair(k, k);
            for _ in 0..50 {
                let net = random_net(&mut rng, 2 * sh.len);
                let (alpha, gamma) = (0.5 * rng.next_f64(), 0.5 + 0.5 * rng.next_f64());
                for d in 0..2 {
                    for (a, g) in [(alpha, gamma), (0.0, gamma), (alpha, 1.0)] {
                        let (mut x, mut y) = (net.clone(), net.clone());
                        restrict_all(&mut x, sh, d, a, g);
                        if a > 0.0 {
                            subdivide_all_in(&mut y, sh, d, a, true);
                        }
                        if g < 1.0 {
                            subdivide_all_in(&mut y, sh, d, g, false);
                        }
                        assert_eq!(x, y, "k {k} d {d}");
                    }
                }
            }
        }
    }
}
