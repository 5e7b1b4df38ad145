//! The local proof on a box: Krawczyk on `[0, 1]²` in the box's own
//! coordinates (step 3 of the [`rect`](super) docs; the operator is
//! `krawczyk::local`, this module hands it the box's system), and the test
//! for a box whose separating sign is lost to rounding.

use super::net::{jacobian_row, with_small_degrees, Shape, SMALL_LEN, STACK};
use super::spans::{lerp_rows, transpose};
use crate::scalar::iv::Iv;
use crate::solve::krawczyk::local::{self, LocalSystem};
use crate::solve::krawczyk::Verdict;
use crate::solve::linalg::smallest_singular_left;

/// The polynomial's value at the local point `(s, t)` (floats in `[0, 1]`).
#[inline(always)]
fn eval_local_in(p: &[Iv], m: usize, n: usize, s: f64, t: f64) -> Iv {
    if m < 4 && n < 4 {
        let mut col = [Iv::point(0.0); 4];
        let mut row = [Iv::point(0.0); 4];
        eval_local_with(p, m, n, s, t, &mut col, &mut row)
    } else if m < STACK && n < STACK {
        let mut col = [Iv::point(0.0); STACK];
        let mut row = [Iv::point(0.0); STACK];
        eval_local_with(p, m, n, s, t, &mut col, &mut row)
    } else {
        eval_local_with(
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

/// [`eval_local_in`] for bidegree `(K, K)` (`L = (K + 1)²`) in fixed
/// arrays: every row in `t` at once, as de Casteljau across the rows of the
/// transposed net, then the column in `s`. The same `Iv::lerp`s on the same
/// operands, so the same floats.
#[inline(always)]
fn eval_square<const K: usize, const L: usize>(p: &[Iv], s: f64, t: f64) -> Iv {
    let Ok(c) = <&[Iv; L]>::try_from(p) else {
        unreachable!("a polynomial holds (K + 1)² coefficients")
    };
    let mut tr = transpose::<K, L>(c);
    lerp_rows::<K, L>(&mut tr, t, true);
    let col = &mut tr[..=K];
    for r in 1..=K {
        for i in 0..=K - r {
            col[i] = Iv::lerp(col[i], col[i + 1], s);
        }
    }
    col[0]
}

#[inline(always)]
fn eval_local_with(p: &[Iv], m: usize, n: usize, s: f64, t: f64, col: &mut [Iv], row: &mut [Iv]) -> Iv {
    for i in 0..=m {
        row[..=n].copy_from_slice(&p[i * (n + 1)..=i * (n + 1) + n]);
        for r in 1..=n {
            for j in 0..=n - r {
                row[j] = Iv::lerp(row[j], row[j + 1], t);
            }
        }
        col[i] = row[0];
    }
    for r in 1..=m {
        for i in 0..=m - r {
            col[i] = Iv::lerp(col[i], col[i + 1], s);
        }
    }
    col[0]
}

/// Krawczyk on `X = [0, 1]²` in the box's local coordinates (`rect` docs,
/// step 3), then contraction ([`local::certify_unit_box`]).
pub(super) fn local_krawczyk(c: &[Iv], sh: Shape) -> Verdict<[Iv; 2], ()> {
    let (f, g) = (&c[..sh.len], &c[sh.len..2 * sh.len]);
    let [a, b] = jacobian_row(f, sh);
    let [cc, d] = jacobian_row(g, sh);
    // The midpoint system, once per box (Newton in `contract` evaluates it
    // up to eight times).
    let mut small = [0.0f64; 2 * SMALL_LEN];
    let large: Vec<f64>;
    let mid: &[f64] = if sh.len <= SMALL_LEN {
        for (x, c) in small.iter_mut().zip(&c[..2 * sh.len]) {
            *x = c.mid();
        }
        &small[..2 * sh.len]
    } else {
        large = c[..2 * sh.len].iter().map(|x| x.mid()).collect();
        &large
    };
    local::certify_unit_box(&BoxSystem { f, g, mid, sh }, [a, b, cc, d])
}

/// The system on a box, as [`local`] evaluates it (degrees below [`STACK`]).
struct BoxSystem<'a> {
    f: &'a [Iv],
    g: &'a [Iv],
    /// The midpoints of `f`'s coefficients, then of `g`'s.
    mid: &'a [f64],
    sh: Shape,
}

/// The value and both partial derivatives at the local point `(s, t)` of
/// the polynomial with coefficients `mid`, in `f64` (a proposal, never a
/// proof): de Casteljau stopped one level short in each direction gives the
/// two points whose difference is the derivative (times the degree).
#[inline(always)]
fn jet_mid_in(mid: &[f64], m: usize, n: usize, s: f64, t: f64) -> [f64; 3] {
    if m < 4 && n < 4 {
        let (mut col, mut dcol, mut row) = ([0.0f64; 4], [0.0f64; 4], [0.0f64; 4]);
        jet_mid_with(mid, (m, n), (s, t), [&mut col, &mut dcol, &mut row])
    } else if m < STACK && n < STACK {
        let mut col = [0.0f64; STACK];
        let mut dcol = [0.0f64; STACK];
        let mut row = [0.0f64; STACK];
        jet_mid_with(mid, (m, n), (s, t), [&mut col, &mut dcol, &mut row])
    } else {
        let (mut col, mut dcol, mut row) = (vec![0.0; m + 1], vec![0.0; m + 1], vec![0.0; n + 1]);
        jet_mid_with(mid, (m, n), (s, t), [&mut col, &mut dcol, &mut row])
    }
}

/// [`jet_mid_in`] with scratch `[col, dcol, row]` (at least `m + 1`,
/// `m + 1`, `n + 1` long).
#[inline(always)]
fn jet_mid_with(
    mid: &[f64],
    (m, n): (usize, usize),
    (s, t): (f64, f64),
    [col, dcol, row]: [&mut [f64]; 3],
) -> [f64; 3] {
    for i in 0..=m {
        row[..=n].copy_from_slice(&mid[i * (n + 1)..=i * (n + 1) + n]);
        for r in 1..n {
            for j in 0..=n - r {
                row[j] += t * (row[j + 1] - row[j]);
            }
        }
        col[i] = row[0] + t * (row[1] - row[0]);
        dcol[i] = n as f64 * (row[1] - row[0]);
    }
    for r in 1..m {
        for i in 0..=m - r {
            col[i] += s * (col[i + 1] - col[i]);
        }
    }
    for r in 1..=m {
        for i in 0..=m - r {
            dcol[i] += s * (dcol[i + 1] - dcol[i]);
        }
    }
    [col[0] + s * (col[1] - col[0]), m as f64 * (col[1] - col[0]), dcol[0]]
}

/// [`jet_mid_in`] for bidegree `(K, K)`, `K ≤ 3` (`L = (K + 1)²`): every
/// row in `t` at once on the transposed net, then the columns in `s`; the
/// same operations, so the same floats.
#[inline(always)]
fn jet_square<const K: usize, const L: usize>(mid: &[f64], s: f64, t: f64) -> [f64; 3] {
    let Ok(c) = <&[f64; L]>::try_from(mid) else {
        unreachable!("a polynomial holds (K + 1)² coefficients")
    };
    let w = K + 1;
    let mut tr = [0.0f64; L];
    for i in 0..w {
        for j in 0..w {
            tr[j * w + i] = c[i * w + j];
        }
    }
    for r in 1..K {
        for j in 0..w - r {
            for i in 0..w {
                tr[j * w + i] += t * (tr[(j + 1) * w + i] - tr[j * w + i]);
            }
        }
    }
    let (mut col, mut dcol) = ([0.0f64; 4], [0.0f64; 4]);
    for i in 0..w {
        col[i] = tr[i] + t * (tr[w + i] - tr[i]);
        dcol[i] = K as f64 * (tr[w + i] - tr[i]);
    }
    for r in 1..K {
        for i in 0..w - r {
            col[i] += s * (col[i + 1] - col[i]);
        }
    }
    for r in 1..w {
        for i in 0..w - r {
            dcol[i] += s * (dcol[i + 1] - dcol[i]);
        }
    }
    [col[0] + s * (col[1] - col[0]), K as f64 * (col[1] - col[0]), dcol[0]]
}

impl LocalSystem for BoxSystem<'_> {
    fn value(&self, s: f64, t: f64) -> [Iv; 2] {
        match (self.sh.m, self.sh.n) {
            (3, 3) => return [eval_square::<3, 16>(self.f, s, t), eval_square::<3, 16>(self.g, s, t)],
            (2, 2) => return [eval_square::<2, 9>(self.f, s, t), eval_square::<2, 9>(self.g, s, t)],
            _ => {}
        }
        with_small_degrees!(self.sh, |m, n| [
            eval_local_in(self.f, m, n, s, t),
            eval_local_in(self.g, m, n, s, t)
        ])
    }

    fn jet_mid(&self, s: f64, t: f64) -> ([f64; 2], [f64; 4]) {
        let (f, g) = self.mid.split_at(self.sh.len);
        let [[fv, fs, ft], [gv, gs, gt]] = match (self.sh.m, self.sh.n) {
            (3, 3) => [jet_square::<3, 16>(f, s, t), jet_square::<3, 16>(g, s, t)],
            (2, 2) => [jet_square::<2, 9>(f, s, t), jet_square::<2, 9>(g, s, t)],
            _ => with_small_degrees!(self.sh, |m, n| [jet_mid_in(f, m, n, s, t), jet_mid_in(g, m, n, s, t)]),
        };
        ([fv, gv], [fs, ft, gs, gt])
    }
}

/// The combination of `f` and `g` closest to vanishing (by the Jacobian at
/// the box's centre, in domain coordinates: `w` are the box's relative
/// widths) has every coefficient possibly zero: the sign that would separate
/// the curves is lost to rounding on the whole box, and no subdivision
/// restores it (a child's coefficients are convex combinations of these).
/// Near a triple root that region is ~1e-5 wide.
///
/// Domain coordinates matter: on a long thin box an equation varying only
/// across it is lost on the box, while splitting along the box still
/// separates roots; its Jacobian row is then not small, so it is not the
/// combination tested.
pub(super) fn sign_lost(c: &[Iv], sh: Shape, w: [f64; 2]) -> bool {
    let (f, g) = (&c[..sh.len], &c[sh.len..2 * sh.len]);
    let [a, b] = jacobian_row(f, sh);
    let [cc, d] = jacobian_row(g, sh);
    let j = [a.mid() / w[0], b.mid() / w[1], cc.mid() / w[0], d.mid() / w[1]];
    let Some(v) = smallest_singular_left(j) else {
        return false;
    };
    let (va, vb) = (Iv::point(v[0]), Iv::point(v[1]));
    f.iter().zip(g).all(|(x, y)| {
        let h = va.mul(*x).add(vb.mul(*y));
        !(h.lo > 0.0 || h.hi < 0.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn square_evaluation_gives_the_general_floats() {
        let mut rng = Rng(5);
        for k in 1..=3usize {
            let len = (k + 1) * (k + 1);
            for _ in 0..200 {
                let p: Vec<Iv> = (0..len)
                    .map(|_| {
                        let x = rng.next_signed();
                        Iv::new(x, x + 1e-3 * rng.next_f64())
                    })
                    .collect();
                let (s, t) = (rng.next_f64(), rng.next_f64());
                let want = eval_local_with(&p, k, k, s, t, &mut [Iv::point(0.0); 4], &mut [Iv::point(0.0); 4]);
                let got = match k {
                    1 => eval_square::<1, 4>(&p, s, t),
                    2 => eval_square::<2, 9>(&p, s, t),
                    _ => eval_square::<3, 16>(&p, s, t),
                };
                assert_eq!(got, want);
                if k >= 2 {
                    let mid: Vec<f64> = p.iter().map(|x| x.mid()).collect();
                    let got = match k {
                        2 => jet_square::<2, 9>(&mid, s, t),
                        _ => jet_square::<3, 16>(&mid, s, t),
                    };
                    assert_eq!(got, jet_mid_in(&mid, k, k, s, t));
                }
            }
        }
    }
}
