//! A box of the box solver and its Bernstein net: the layout of the
//! coefficients of every polynomial on the box, and what is read off them
//! directly (signs, derivative hulls, enclosures over sub-boxes).

use crate::scalar::interval;
use crate::scalar::iv::{down, up, Iv};
use crate::solve::krawczyk::IBox;

/// Scratch arrays on the stack hold this many coefficients per line; higher
/// degrees use heap buffers for the same steps.
pub(super) const STACK: usize = 24;

/// Coefficients per polynomial up to which scratch copies live in fixed
/// arrays (bicubic: 16).
pub(super) const SMALL_LEN: usize = 16;

/// Calls `$body` with `m` and `n` as constants for the
/// small bidegrees (the bicubic of a typical patch is `(3, 3)`), so that the
/// inlined kernel's loops are unrolled and free of bounds checks; the same
/// operations in the same order as the general call, so the same floats.
macro_rules! with_small_degrees {
    ($sh:expr, |$m:ident, $n:ident| $body:expr) => {
        match ($sh.m, $sh.n) {
            (1, 1) => {
                let ($m, $n) = (1, 1);
                $body
            }
            (2, 2) => {
                let ($m, $n) = (2, 2);
                $body
            }
            (3, 3) => {
                let ($m, $n) = (3, 3);
                $body
            }
            ($m, $n) => $body,
        }
    };
}
pub(super) use with_small_degrees;

/// The layout of a box's coefficients: `polys` polynomials of bidegree
/// `(m, n)`, `len` coefficients each, row-major, one after the other.
#[derive(Clone, Copy, Debug)]
pub(super) struct Shape {
    pub(super) m: usize,
    pub(super) n: usize,
    pub(super) len: usize,
    pub(super) polys: usize,
}

impl Shape {
    /// The system `f, g` of bidegree `(m, n)`.
    pub(super) fn pair(m: usize, n: usize) -> Self {
        Shape {
            m,
            n,
            len: (m + 1) * (n + 1),
            polys: 2,
        }
    }
}

/// Index of coefficient `(i, j)`.
#[inline]
pub(super) fn at(sh: Shape, i: usize, j: usize) -> usize {
    i * (sh.n + 1) + j
}

/// The indices of the coefficients on one edge: `d = 0` the rows `i = 0`
/// (`high = false`) or `i = m`, `d = 1` the columns `j = 0` or `j = n`.
pub(super) fn edge_indices(sh: Shape, d: usize, high: bool) -> impl Iterator<Item = usize> {
    let (count, fixed) = if d == 0 {
        (sh.n + 1, if high { sh.m } else { 0 })
    } else {
        (sh.m + 1, if high { sh.n } else { 0 })
    };
    (0..count).map(move |k| if d == 0 { at(sh, fixed, k) } else { at(sh, k, fixed) })
}

/// Every coefficient is strictly positive, or every one strictly negative:
/// no zero on the box (the Bernstein basis is a positive partition of unity).
pub(super) fn one_signed(c: &[Iv]) -> bool {
    c.iter().all(|x| x.lo > 0.0) || c.iter().all(|x| x.hi < 0.0)
}

/// A box: the coefficients of every polynomial on it, its endpoints (each an
/// enclosure), its trace index.
#[derive(Clone, Debug)]
pub(super) struct Node {
    pub(super) c: Vec<Iv>,
    pub(super) bx: [[Iv; 2]; 2],
    pub(super) id: u32,
    /// A lower bound of the objective over this box computed for exactly
    /// this box ([`Query::Nearest`](super::Query::Nearest) orders children
    /// by it and then prunes with it, so it is computed once), or `None`.
    pub(super) key: Option<f64>,
    /// The box's larger relative width when exact Krawczyk last failed on it
    /// or an ancestor (`∞` if never tried): tried again only on boxes a
    /// quarter as wide.
    pub(super) exact_w: f64,
    /// The box's larger relative width when it or an ancestor was last
    /// restarted from the exact input (`∞` if never): restarted again only
    /// once a quarter as wide.
    pub(super) restart_w: f64,
    /// Whether the last restart of this box (or an ancestor) found no
    /// precision that clears the rounding.
    pub(super) restart_failed: bool,
}

impl Node {
    pub(super) fn outer(&self) -> [[f64; 2]; 2] {
        self.bx.map(|[lo, hi]| [lo.lo, hi.hi])
    }

    pub(super) fn ibox(&self) -> IBox {
        self.outer().map(|[lo, hi]| interval(lo, hi))
    }
}

/// Hulls of `∂p/∂s` and `∂p/∂t` over the box, from the derivative's
/// Bernstein coefficients.
pub(super) fn jacobian_row(p: &[Iv], sh: Shape) -> [Iv; 2] {
    match (sh.m, sh.n) {
        (3, 3) => jacobian_row_square::<3, 16>(p),
        (2, 2) => jacobian_row_square::<2, 9>(p),
        _ => with_small_degrees!(sh, |m, n| jacobian_row_in(p, m, n)),
    }
}

/// [`jacobian_row_in`] for bidegree `(K, K)` (`L = (K + 1)²`) in a fixed
/// array. The hulls take `<` selections instead of `f64::min`: with no NaN
/// difference they pick the same float but for the sign of a zero, and
/// `down(±0) = −ABS`, `up(±0) = ABS` either way; with one, the hull is NaN
/// as before.
#[inline(always)]
fn jacobian_row_square<const K: usize, const L: usize>(p: &[Iv]) -> [Iv; 2] {
    let Ok(c) = <&[Iv; L]>::try_from(p) else {
        unreachable!("a polynomial holds (K + 1)² coefficients")
    };
    let w = K + 1;
    let (mut s_lo, mut s_hi, mut t_lo, mut t_hi) = (
        [f64::INFINITY; 4],
        [f64::NEG_INFINITY; 4],
        [f64::INFINITY; 4],
        [f64::NEG_INFINITY; 4],
    );
    let mut nan = [false; 2];
    for i in 0..w {
        for j in 0..w {
            let x = c[i * w + j];
            if i < K {
                let y = c[(i + 1) * w + j];
                let (lo, hi) = (y.lo - x.hi, y.hi - x.lo);
                nan[0] |= lo.is_nan() | hi.is_nan();
                s_lo[j] = if lo < s_lo[j] { lo } else { s_lo[j] };
                s_hi[j] = if hi > s_hi[j] { hi } else { s_hi[j] };
            }
            if j < K {
                let y = c[i * w + j + 1];
                let (lo, hi) = (y.lo - x.hi, y.hi - x.lo);
                nan[1] |= lo.is_nan() | hi.is_nan();
                t_lo[i] = if lo < t_lo[i] { lo } else { t_lo[i] };
                t_hi[i] = if hi > t_hi[i] { hi } else { t_hi[i] };
            }
        }
    }
    let hull = |lo: [f64; 4], hi: [f64; 4], nan: bool| {
        if nan {
            return Iv::new(f64::NAN, f64::NAN);
        }
        let l = lo[..w].iter().fold(f64::INFINITY, |a, &b| if b < a { b } else { a });
        let h = hi[..w]
            .iter()
            .fold(f64::NEG_INFINITY, |a, &b| if b > a { b } else { a });
        Iv::new(down(l), up(h)).scale(K as f64)
    };
    [hull(s_lo, s_hi, nan[0]), hull(t_lo, t_hi, nan[1])]
}

#[inline(always)]
fn jacobian_row_in(p: &[Iv], m: usize, n: usize) -> [Iv; 2] {
    // The hull of the differences `c' − c` (each `[c'.lo − c.hi, c'.hi − c.lo]`
    // moved outward by `down`/`up`, as `Iv::sub` does) taken before the
    // outward move: `down` and `up` are nondecreasing in `r` (for `r < 0`
    // both `r` and `−e(r)`, `e = fl(|r|·2⁻⁵¹ + ABS)`, grow with `r`; for
    // `r ≥ 0` two floats `r₁ < r₂` are at least an ulp of `r₁` apart, more
    // than `e` can grow between them, ~2⁻⁵¹ of that gap plus an ulp of `e`;
    // and rounding is monotone), so `min down(r_k) = down(min r_k)` and
    // `max up(r_k) = up(max r_k)`: the same floats as the hull of the
    // `Iv::sub`s, with one move per hull instead of two per difference. A
    // NaN difference makes the hull NaN, as `Iv::hull` does.
    let w = n + 1;
    let mut ds = [f64::INFINITY, f64::NEG_INFINITY];
    let mut dt = [f64::INFINITY, f64::NEG_INFINITY];
    let mut nan = [false; 2];
    let put = |h: &mut [f64; 2], nan: &mut bool, a: Iv, c: Iv| {
        let (lo, hi) = (a.lo - c.hi, a.hi - c.lo);
        *nan |= lo.is_nan() || hi.is_nan();
        h[0] = h[0].min(lo);
        h[1] = h[1].max(hi);
    };
    for i in 0..=m {
        for j in 0..=n {
            let c = p[i * w + j];
            if i < m {
                put(&mut ds, &mut nan[0], p[(i + 1) * w + j], c);
            }
            if j < n {
                put(&mut dt, &mut nan[1], p[i * w + j + 1], c);
            }
        }
    }
    let hull = |h: [f64; 2], nan: bool, k: usize| {
        if k == 0 {
            Iv::point(0.0)
        } else if nan {
            Iv::new(f64::NAN, f64::NAN)
        } else {
            Iv::new(down(h[0]), up(h[1]))
        }
    };
    [hull(ds, nan[0], m).scale(m as f64), hull(dt, nan[1], n).scale(n as f64)]
}

/// An enclosure of the polynomial with row-major coefficients `p` of
/// bidegree `(m, n)` over the local box `s × t` (any floats, extrapolation
/// included), by de Casteljau with [`Iv::lerp_range`].
pub(crate) fn eval_box(p: &[Iv], m: usize, n: usize, s: [f64; 2], t: [f64; 2]) -> Iv {
    match (m, n) {
        (3, 3) => eval_box_square::<3, 16>(p, s, t),
        (2, 2) => eval_box_square::<2, 9>(p, s, t),
        _ => with_small_degrees!(Shape::pair(m, n), |m, n| eval_box_in(p, m, n, s, t)),
    }
}

/// [`eval_box_in`] for bidegree `(K, K)` (`L = (K + 1)²`) in a fixed array:
/// every row in `t` at once, as de Casteljau across the rows of the
/// transposed net, then the column in `s`; the same operations, so the same
/// floats.
#[inline(always)]
fn eval_box_square<const K: usize, const L: usize>(p: &[Iv], s: [f64; 2], t: [f64; 2]) -> Iv {
    let Ok(c) = <&[Iv; L]>::try_from(p) else {
        return eval_box_in(p, K, K, s, t);
    };
    let w = K + 1;
    let mut tr = super::spans::transpose::<K, L>(c);
    for r in 1..w {
        for j in 0..w - r {
            for i in 0..w {
                tr[j * w + i] = Iv::lerp_range(tr[j * w + i], tr[(j + 1) * w + i], t[0], t[1]);
            }
        }
    }
    let col = &mut tr[..w];
    for r in 1..w {
        for i in 0..w - r {
            col[i] = Iv::lerp_range(col[i], col[i + 1], s[0], s[1]);
        }
    }
    col[0]
}

#[inline(always)]
fn eval_box_in(p: &[Iv], m: usize, n: usize, s: [f64; 2], t: [f64; 2]) -> Iv {
    if m < 4 && n < 4 {
        let mut col = [Iv::point(0.0); 4];
        let mut row = [Iv::point(0.0); 4];
        eval_box_with(p, m, n, s, t, &mut col, &mut row)
    } else if m < STACK && n < STACK {
        let mut col = [Iv::point(0.0); STACK];
        let mut row = [Iv::point(0.0); STACK];
        eval_box_with(p, m, n, s, t, &mut col, &mut row)
    } else {
        eval_box_with(
            p,
            m,
            n,
            s,
            t,
            &mut vec![Iv::point(0.0); m + 1],
            &mut vec![Iv::point(0.0); n + 1],
        )
    }
}

#[inline(always)]
fn eval_box_with(p: &[Iv], m: usize, n: usize, s: [f64; 2], t: [f64; 2], col: &mut [Iv], row: &mut [Iv]) -> Iv {
    for (i, line) in p.chunks(n + 1).enumerate() {
        row[..=n].copy_from_slice(line);
        for k in 1..=n {
            for j in 0..=n - k {
                row[j] = Iv::lerp_range(row[j], row[j + 1], t[0], t[1]);
            }
        }
        col[i] = row[0];
    }
    for k in 1..=m {
        for i in 0..=m - k {
            col[i] = Iv::lerp_range(col[i], col[i + 1], s[0], s[1]);
        }
    }
    col[0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn square_jacobian_rows_and_box_values_give_the_general_floats() {
        let mut rng = Rng(9);
        for k in 2..=3usize {
            for _ in 0..500 {
                let p: Vec<Iv> = (0..(k + 1) * (k + 1))
                    .map(|_| {
                        let x = rng.next_signed();
                        Iv::new(x, x + 1e-3 * rng.next_f64())
                    })
                    .collect();
                assert_eq!(jacobian_row(&p, Shape::pair(k, k)), jacobian_row_in(&p, k, k));
                for (s, t) in [
                    ([0.25, 0.25], [0.5, 0.75]),
                    ([0.1, 0.3], [0.6, 0.6]),
                    ([-0.5, 0.5], [0.9, 1.5]),
                ] {
                    assert_eq!(eval_box(&p, k, k, s, t), eval_box_in(&p, k, k, s, t));
                }
            }
        }
    }
}
