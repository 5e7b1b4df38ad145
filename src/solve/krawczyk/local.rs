//! Krawczyk's operator on `X = [0, 1]²` in a box's own (local) coordinates,
//! in the branchless [`Iv`] arithmetic of the box solver's hot loop
//! ([`rect`](crate::solve::rect), module docs, step 3).
//!
//! The caller gives `F'(X)` once, enclosed over the whole box (the box
//! solver: the hull of the derivative's Bernstein coefficients), and `F` at
//! local points; since `F'(X)` stays valid for every sub-box, a proof on
//! `X` is followed by contraction with the same `Y` and `I − Y F'(X)`.
//!
//! Not over [`Bivariate`](super::Bivariate): that trait encloses in inari,
//! whose rounding-mode switch per operation is what the box solver's `Iv`
//! avoids, and its Jacobian comes from the box's coefficients rather than
//! from evaluating partial derivatives over a sub-box. Such a system
//! implements [`LocalSystem`].

use super::verdict::Verdict;
use crate::scalar::iv::Iv;
use crate::solve::linalg::inverse2;

/// A system `F = (f, g)` in local coordinates `(s, t) ∈ [0, 1]²`.
pub(crate) trait LocalSystem {
    /// `F(s, t)` enclosed, at a point given in floats.
    fn value(&self, s: f64, t: f64) -> [Iv; 2];
    /// `F(s, t)` and its Jacobian `[f_s, f_t, g_s, g_t]` at `(s, t)`, of the
    /// midpoint system in `f64` (a proposal, never a proof).
    fn jet_mid(&self, s: f64, t: f64) -> ([f64; 2], [f64; 4]);
}

/// Krawczyk on the unit box `X = [0, 1]²`, with `j = [f_s, f_t, g_s, g_t]`
/// enclosed over `X`: `Unique` with a contracted enclosure of the only root
/// when `K(X) ⊂ (0, 1)²` (the root is simple and in the interior, so no
/// neighbouring box can claim it), `NoRoot` when `K(X) ∩ X = ∅`.
pub(crate) fn certify_unit_box<S: LocalSystem>(sys: &S, j: [Iv; 4]) -> Verdict<[Iv; 2], ()> {
    if j.iter().any(|x| !x.is_finite()) {
        return Verdict::Undecided(());
    }
    let Some(y) = inverse2(j.map(Iv::mid), 1e-12) else {
        return Verdict::Undecided(());
    };
    let y = y.map(Iv::point);
    // M = I − Y J
    let one = Iv::point(1.0);
    let mm = [
        one.sub(y[0].mul(j[0]).add(y[1].mul(j[2]))),
        Iv::point(0.0).sub(y[0].mul(j[1]).add(y[1].mul(j[3]))),
        Iv::point(0.0).sub(y[2].mul(j[0]).add(y[3].mul(j[2]))),
        one.sub(y[2].mul(j[1]).add(y[3].mul(j[3]))),
    ];
    let unit = [Iv::new(0.0, 1.0); 2];
    let Some(k) = step(sys, &y, &mm, unit) else {
        return Verdict::Undecided(());
    };
    if !(k[0].inside_open(0.0, 1.0) && k[1].inside_open(0.0, 1.0)) {
        if k[0].meet(unit[0]).is_none() || k[1].meet(unit[1]).is_none() {
            return Verdict::NoRoot;
        }
        return Verdict::Undecided(());
    }
    Verdict::Unique(contract(sys, &y, &mm, k))
}

/// `K(x)` with the fixed `Y` and `M = I − Y F'(X)`; `None` if not finite.
fn step<S: LocalSystem>(sys: &S, y: &[Iv; 4], mm: &[Iv; 4], x: [Iv; 2]) -> Option<[Iv; 2]> {
    let p = [x[0].mid(), x[1].mid()];
    let [fx, gx] = sys.value(p[0], p[1]);
    let d = [x[0].sub(Iv::point(p[0])), x[1].sub(Iv::point(p[1]))];
    let k0 = Iv::point(p[0])
        .sub(y[0].mul(fx).add(y[1].mul(gx)))
        .add(mm[0].mul(d[0]).add(mm[1].mul(d[1])));
    let k1 = Iv::point(p[1])
        .sub(y[2].mul(fx).add(y[3].mul(gx)))
        .add(mm[2].mul(d[0]).add(mm[3].mul(d[1])));
    (k0.is_finite() && k1.is_finite()).then_some([k0, k1])
}

/// Narrows `k = K(X) ⊂ int X`, which holds the only root of `X`.
///
/// Every root in X lies in K(X), and J over the whole box stays valid for
/// any X inside it. First Newton in f64 from the centre of K proposes the
/// root; then one Krawczyk step on a tiny box around it, sized from
/// |Y F(x*)| and q = ‖I − Y J‖, proves it. If that fails, plain iteration
/// of K.
///
/// The proposal uses the midpoint system's Jacobian at the iterate
/// (quadratic convergence), not the fixed `Y`: with `Y` (the chord method)
/// the error shrinks only by `‖I − Y J(x)‖` per step, a few tenths on a
/// box an eighth wide, so eight steps left the point ~10⁻⁶ off and the
/// proven box too wide to report; the box was then clipped and proven
/// again. Where that Jacobian is singular the step falls back to `Y`. The
/// proposal is never trusted: only `K(tiny) ⊂ int tiny` proves.
fn contract<S: LocalSystem>(sys: &S, y: &[Iv; 4], mm: &[Iv; 4], k: [Iv; 2]) -> [Iv; 2] {
    let mut x = k;
    let ym = y.map(|c| c.lo);
    let mut p = [k[0].mid(), k[1].mid()];
    let mut last = f64::INFINITY;
    for _ in 0..8 {
        let ([fv, gv], jp) = sys.jet_mid(p[0], p[1]);
        let yp = inverse2(jp, 1e-12).unwrap_or(ym);
        let dx = [yp[0] * fv + yp[1] * gv, yp[2] * fv + yp[3] * gv];
        if !(dx[0].is_finite() && dx[1].is_finite()) {
            break;
        }
        p = [
            (p[0] - dx[0]).clamp(k[0].lo, k[0].hi),
            (p[1] - dx[1]).clamp(k[1].lo, k[1].hi),
        ];
        // Local coordinates are in [0, 1]: a step below a few ulps of 1 is
        // rounding, and a step that stops shrinking will not improve.
        let size = dx[0].abs().max(dx[1].abs());
        if size < 1e-15 || size > 0.5 * last {
            break;
        }
        last = size;
    }
    let q = (mm[0].lo.abs().max(mm[0].hi.abs()) + mm[1].lo.abs().max(mm[1].hi.abs()))
        .max(mm[2].lo.abs().max(mm[2].hi.abs()) + mm[3].lo.abs().max(mm[3].hi.abs()));
    if q < 0.75 {
        let [fv, gv] = sys.value(p[0], p[1]);
        let mag = |c: Iv| c.lo.abs().max(c.hi.abs());
        let d = [
            ym[0].abs() * mag(fv) + ym[1].abs() * mag(gv),
            ym[2].abs() * mag(fv) + ym[3].abs() * mag(gv),
        ];
        let r = d.map(|d| 4.0 * d / (1.0 - q) + 1e-16);
        let tiny = [0, 1].map(|a| Iv::new((p[a] - r[a]).max(k[a].lo), (p[a] + r[a]).min(k[a].hi)));
        if let Some(kk) = step(sys, y, mm, tiny) {
            if kk[0].inside_open(tiny[0].lo, tiny[0].hi) && kk[1].inside_open(tiny[1].lo, tiny[1].hi) {
                // K(tiny) ⊂ int tiny: the root (the only one in the box) is in it.
                return kk;
            }
        }
    }
    for _ in 0..12 {
        let Some(k) = step(sys, y, mm, x) else { break };
        let (Some(a), Some(b)) = (k[0].meet(x[0]), k[1].meet(x[1])) else {
            break;
        };
        let shrunk = a.wid().max(b.wid()) < 0.5 * x[0].wid().max(x[1].wid());
        x = [a, b];
        if !shrunk {
            break;
        }
    }
    x
}
