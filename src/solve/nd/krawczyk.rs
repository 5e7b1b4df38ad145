//! Krawczyk's operator for `N` equations in `N` unknowns on a box in its
//! own (local) coordinates `X = [0, 1]^N`, in the branchless [`Iv`]
//! arithmetic.
//!
//! ```text
//! K(X) = x̃ − Y F(x̃) + (I − Y F'(X)) (X − x̃),   x̃ = mid X,   Y ≈ F'(x̃)⁻¹
//! ```
//! `F'(X)` is the hull of the derivatives' Bernstein coefficients (valid on
//! every sub-box too), `F(x̃)` interval de Casteljau at a float point, `Y`
//! any real matrix (the `f64` inverse of the midpoint Jacobian).
//! * `K(X) ⊂ int X`: exactly one zero in `X`, simple (Krawczyk 1969; Rump
//!   1983: every matrix in `F'(X)` is then non-singular);
//! * `K(X) ∩ X = ∅`: no zero in `X`.

use super::tensor::{derivative_hull, eval_mid, eval_point};
use crate::scalar::iv::Iv;
use crate::solve::krawczyk::Verdict;

/// A square system on one box: equation `e` has degrees `deg[e]` and
/// coefficients `c[e]` (local coordinates).
pub(crate) struct LocalBox<'a, const N: usize> {
    pub(crate) deg: &'a [[usize; N]],
    pub(crate) c: Vec<&'a [Iv]>,
}

impl<const N: usize> LocalBox<'_, N> {
    fn value(&self, x: &[f64; N]) -> [Iv; N] {
        std::array::from_fn(|e| eval_point(self.c[e], &self.deg[e], x))
    }

    fn value_mid(&self, x: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|e| eval_mid(self.c[e], &self.deg[e], x))
    }

    /// `F'(X)` over the whole box, row `e`, column `d`.
    pub(crate) fn jacobian(&self) -> [[Iv; N]; N] {
        std::array::from_fn(|e| std::array::from_fn(|d| derivative_hull(self.c[e], &self.deg[e], d)))
    }
}

/// The inverse of `a` in `f64` by Gauss–Jordan elimination with partial
/// pivoting; `None` when a pivot is below `1e-14` of its column's scale or a
/// value is not finite. A proposal: any `Y` keeps Krawczyk rigorous.
// Row operations read one row while writing another: index loops are clearer.
#[allow(clippy::needless_range_loop)]
pub(crate) fn inverse<const N: usize>(a: [[f64; N]; N]) -> Option<[[f64; N]; N]> {
    let scale = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let mut m = a;
    let mut inv = [[0.0; N]; N];
    for (i, row) in inv.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for col in 0..N {
        let piv = (col..N).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        // NaN fails the test too.
        if m[piv][col].abs().partial_cmp(&(1e-14 * scale)) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        m.swap(col, piv);
        inv.swap(col, piv);
        let p = m[col][col];
        for k in 0..N {
            m[col][k] /= p;
            inv[col][k] /= p;
        }
        for r in 0..N {
            if r != col {
                let f = m[r][col];
                if f != 0.0 {
                    for k in 0..N {
                        m[r][k] -= f * m[col][k];
                        inv[r][k] -= f * inv[col][k];
                    }
                }
            }
        }
    }
    inv.iter().flatten().all(|x| x.is_finite()).then_some(inv)
}

/// `Y` (floats) and `M = I − Y J` (enclosed).
pub(crate) type Preconditioner<const N: usize> = ([[f64; N]; N], [[Iv; N]; N]);

/// `Y` and `M = I − Y J` for a Jacobian enclosure `j`; `None` when the
/// midpoint Jacobian is numerically singular or `j` is not finite.
pub(crate) fn preconditioner<const N: usize>(j: &[[Iv; N]; N]) -> Option<Preconditioner<N>> {
    if j.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let y = inverse(j.map(|r| r.map(Iv::mid)))?;
    let mm = std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            let mut s = Iv::point(if r == c { 1.0 } else { 0.0 });
            for k in 0..N {
                s = s.sub(Iv::point(y[r][k]).mul(j[k][c]));
            }
            s
        })
    });
    Some((y, mm))
}

/// One Krawczyk step on the sub-box `x` of the unit box, with the fixed `Y`
/// and `M`; `None` if not finite.
fn step<const N: usize>(sys: &LocalBox<'_, N>, y: &[[f64; N]; N], mm: &[[Iv; N]; N], x: &[Iv; N]) -> Option<[Iv; N]> {
    let p: [f64; N] = std::array::from_fn(|d| x[d].mid());
    let fx = sys.value(&p);
    let dx: [Iv; N] = std::array::from_fn(|d| x[d].sub(Iv::point(p[d])));
    let k: [Iv; N] = std::array::from_fn(|r| {
        let mut s = Iv::point(p[r]);
        for c in 0..N {
            s = s.sub(Iv::point(y[r][c]).mul(fx[c]));
            s = s.add(mm[r][c].mul(dx[c]));
        }
        s
    });
    k.iter().all(|v| v.is_finite()).then_some(k)
}

/// Krawczyk on the unit box: `Unique` with a contracted enclosure of the only
/// zero (local coordinates) when `K(X) ⊂ (0, 1)^N` — the zero is simple and
/// interior, so no neighbouring box can claim it; `NoRoot` when
/// `K(X) ∩ X = ∅`.
pub(crate) fn certify_unit<const N: usize>(sys: &LocalBox<'_, N>) -> Verdict<[Iv; N], ()> {
    let j = sys.jacobian();
    let Some((y, mm)) = preconditioner(&j) else {
        return Verdict::Undecided(());
    };
    let unit = [Iv::new(0.0, 1.0); N];
    let Some(k) = step(sys, &y, &mm, &unit) else {
        return Verdict::Undecided(());
    };
    if !k.iter().all(|c| c.inside_open(0.0, 1.0)) {
        if k.iter().any(|c| c.meet(Iv::new(0.0, 1.0)).is_none()) {
            return Verdict::NoRoot;
        }
        return Verdict::Undecided(());
    }
    Verdict::Unique(contract(sys, &y, &mm, k))
}

/// Narrows `k = K(X) ⊂ int X`, which holds the only zero of `X` (the same
/// scheme as the bivariate box solver's): Newton with `Y` fixed proposes the
/// zero, one step on a tiny box around it proves it; failing that, plain
/// iteration of `K`.
fn contract<const N: usize>(sys: &LocalBox<'_, N>, y: &[[f64; N]; N], mm: &[[Iv; N]; N], k: [Iv; N]) -> [Iv; N] {
    let mut p: [f64; N] = std::array::from_fn(|d| k[d].mid());
    let mut last = f64::INFINITY;
    for _ in 0..8 {
        let fv = sys.value_mid(&p);
        let dx: [f64; N] = std::array::from_fn(|r| (0..N).map(|c| y[r][c] * fv[c]).sum());
        for d in 0..N {
            p[d] = (p[d] - dx[d]).clamp(k[d].lo, k[d].hi);
        }
        let size = dx.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if !(size >= 1e-15 && size <= 0.5 * last) {
            break;
        }
        last = size;
    }
    let mag = |c: Iv| c.lo.abs().max(c.hi.abs());
    let q = mm
        .iter()
        .map(|row| row.iter().map(|&c| mag(c)).sum::<f64>())
        .fold(0.0f64, f64::max);
    if q < 0.75 {
        let fv = sys.value(&p);
        let r: [f64; N] = std::array::from_fn(|a| {
            let d: f64 = (0..N).map(|c| y[a][c].abs() * mag(fv[c])).sum();
            4.0 * d / (1.0 - q) + 1e-16
        });
        let tiny: [Iv; N] = std::array::from_fn(|a| Iv::new((p[a] - r[a]).max(k[a].lo), (p[a] + r[a]).min(k[a].hi)));
        if let Some(kk) = step(sys, y, mm, &tiny) {
            if (0..N).all(|a| kk[a].inside_open(tiny[a].lo, tiny[a].hi)) {
                return kk;
            }
        }
    }
    let mut x = k;
    for _ in 0..12 {
        let Some(kx) = step(sys, y, mm, &x) else { break };
        let mut met = [Iv::point(0.0); N];
        for d in 0..N {
            match kx[d].meet(x[d]) {
                Some(m) => met[d] = m,
                None => return x,
            }
        }
        let w = |b: &[Iv; N]| b.iter().fold(0.0f64, |m, c| m.max(c.wid()));
        let shrunk = w(&met) < 0.5 * w(&x);
        x = met;
        if !shrunk {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_of_a_permutation_and_a_singular_matrix() {
        let a = [[0.0, 2.0, 0.0], [0.0, 0.0, 4.0], [1.0, 0.0, 0.0]];
        let y = inverse(a).unwrap();
        assert_eq!(y, [[0.0, 0.0, 1.0], [0.5, 0.0, 0.0], [0.0, 0.25, 0.0]]);
        assert!(inverse([[1.0, 2.0], [2.0, 4.0]]).is_none());
    }
}
