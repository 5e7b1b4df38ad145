//! The local proof on a box: Krawczyk on `[0, 1]²` in the box's own
//! coordinates (step 3 of the [`rect`](super) docs; the operator is
//! `krawczyk::local`, this module hands it the box's system), and the test
//! for a box whose separating sign is lost to rounding.

use super::net::{at, jacobian_row, Shape, STACK};
use crate::scalar::iv::Iv;
use crate::solve::krawczyk::local::{self, LocalSystem};
use crate::solve::krawczyk::Verdict;
use crate::solve::linalg::smallest_singular_left;
use smallvec::{smallvec, SmallVec};

/// The polynomial's value at the local point `(s, t)` (floats in `[0, 1]`).
fn eval_local(p: &[Iv], sh: Shape, s: f64, t: f64) -> Iv {
    let mut col: SmallVec<[Iv; STACK]> = smallvec![Iv::point(0.0); sh.m + 1];
    let mut row: SmallVec<[Iv; STACK]> = smallvec![Iv::point(0.0); sh.n + 1];
    for i in 0..=sh.m {
        row[..=sh.n].copy_from_slice(&p[at(sh, i, 0)..=at(sh, i, sh.n)]);
        for r in 1..=sh.n {
            for j in 0..=sh.n - r {
                row[j] = Iv::lerp(row[j], row[j + 1], t);
            }
        }
        col[i] = row[0];
    }
    for r in 1..=sh.m {
        for i in 0..=sh.m - r {
            col[i] = Iv::lerp(col[i], col[i + 1], s);
        }
    }
    col[0]
}

/// The value at the local point `(s, t)` of the polynomial with the
/// midpoints of `p` as coefficients, in `f64` (a proposal, never a proof).
fn eval_mid(p: &[Iv], sh: Shape, s: f64, t: f64) -> f64 {
    let mut col: SmallVec<[f64; STACK]> = smallvec![0.0; sh.m + 1];
    let mut row: SmallVec<[f64; STACK]> = smallvec![0.0; sh.n + 1];
    for i in 0..=sh.m {
        for (r, c) in row.iter_mut().zip(&p[at(sh, i, 0)..=at(sh, i, sh.n)]) {
            *r = c.mid();
        }
        for r in 1..=sh.n {
            for j in 0..=sh.n - r {
                row[j] += t * (row[j + 1] - row[j]);
            }
        }
        col[i] = row[0];
    }
    for r in 1..=sh.m {
        for i in 0..=sh.m - r {
            col[i] += s * (col[i + 1] - col[i]);
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
    local::certify_unit_box(&BoxSystem { f, g, sh }, [a, b, cc, d])
}

/// The system on a box, as [`local`] evaluates it.
struct BoxSystem<'a> {
    f: &'a [Iv],
    g: &'a [Iv],
    sh: Shape,
}

impl LocalSystem for BoxSystem<'_> {
    fn value(&self, s: f64, t: f64) -> [Iv; 2] {
        [eval_local(self.f, self.sh, s, t), eval_local(self.g, self.sh, s, t)]
    }

    fn value_mid(&self, s: f64, t: f64) -> [f64; 2] {
        [eval_mid(self.f, self.sh, s, t), eval_mid(self.g, self.sh, s, t)]
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
