//! Jets of a patch: the point `S` with its first partials (what Newton and
//! the first-order iteration read) and with its second partials too (what
//! Halley and the second-order iteration read), for every [`Patch`].

use crate::ray::{Patch, TensorPatch, TriPatch};
use crate::TriBezier;
use glam::DVec3;

/// `S` and its partials up to order two at one `(u, v)`, in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Jet {
    /// `S(u, v)`.
    pub s: DVec3,
    /// `∂S/∂u`.
    pub su: DVec3,
    /// `∂S/∂v`.
    pub sv: DVec3,
    /// `∂²S/∂u²`.
    pub suu: DVec3,
    /// `∂²S/∂u∂v`.
    pub suv: DVec3,
    /// `∂²S/∂v²`.
    pub svv: DVec3,
}

/// The second-order jet of `patch` at `(u, v)`: `S, S_u, S_v, S_uu, S_uv,
/// S_vv`.
///
/// * **Formula.** Each homogeneous coordinate `(w·x, w·y, w·z, w)` is
///   evaluated with its partials by de Casteljau stopped two levels early
///   (differencing commutes with the de Casteljau steps); a rational patch
///   then takes the quotient rule on `S = X / W`:
///   `S_a = (X_a − S W_a) / W`,
///   `S_ab = (X_ab − S_a W_b − S_b W_a − S W_ab) / W` (from differentiating
///   `X = S W` twice). A triangular patch's partials treat `w = 1 − u − v`
///   as moving with `u` and `v`. A B-spline/NURBS surface is evaluated on
///   the Bézier piece holding `(u, v)` ([`BsplineSurface::piece_at`](crate::ray::BsplineSurface::piece_at):
///   the later piece on a knot line, so partials there are one-sided), the
///   piece's partials divided by its span lengths (chain rule for
///   `u = u₀ + (u₁ − u₀)s`).
/// * **Rounding.** Plain `f64`; nothing here is enclosed. Outside the
///   domain the polynomial (or the nearest piece's polynomial) is extended.
/// * **Degenerate cases.** None: every patch has positive weights, so `W > 0`
///   on the domain (outside it a rational patch's `W` may vanish and the jet
///   is then not finite).
///
/// ```
/// use rootclip::glam::DVec3;
/// use rootclip::heuristics::jet;
/// use rootclip::ray::{Patch, TensorPatch};
/// // The bilinear saddle z = (x − ½)(y − ½) over [0, 1]², x = u, y = v.
/// let pts = (0..2).flat_map(|i| (0..2).map(move |j| {
///     DVec3::new(i as f64, j as f64, 0.25 * if i == j { 1.0 } else { -1.0 })
/// })).collect();
/// let saddle = Patch::from(TensorPatch::new(1, 1, pts, None)?);
/// let j = jet(&saddle, 0.25, 0.5);
/// assert_eq!(j.s, DVec3::new(0.25, 0.5, 0.0));
/// assert_eq!(j.suv, DVec3::new(0.0, 0.0, 1.0)); // ∂²z/∂x∂y = 1
/// assert_eq!(j.suu, DVec3::ZERO);
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn jet(patch: &Patch, u: f64, v: f64) -> Jet {
    match patch {
        Patch::Triangle(p) => quotient(&tri_hjet(p, u, v)),
        Patch::Tensor(p) => quotient(&tensor_hjet(p, u, v)),
        Patch::Bspline(s) => {
            let piece = s.piece_at(u, v);
            let (a, b) = piece.to_local(u, v);
            let j = quotient(&tensor_hjet(piece.patch(), a, b));
            let (hu, hv) = (
                piece.u_range()[1] - piece.u_range()[0],
                piece.v_range()[1] - piece.v_range()[0],
            );
            Jet {
                s: j.s,
                su: j.su / hu,
                sv: j.sv / hv,
                suu: j.suu / (hu * hu),
                suv: j.suv / (hu * hv),
                svv: j.svv / (hv * hv),
            }
        }
    }
}

/// `(S, S_u, S_v)` at `(u, v)`: the first-order part of [`jet`], computed
/// without the second partials (what Newton and the first-order iteration
/// pay for).
pub(super) fn frame(patch: &Patch, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
    match patch {
        Patch::Tensor(p) => p.frame(u, v),
        Patch::Triangle(p) => {
            let (su, sv) = p.partials(u, v);
            (p.eval(u, v), su, sv)
        }
        Patch::Bspline(s) => {
            let piece = s.piece_at(u, v);
            let (a, b) = piece.to_local(u, v);
            let (x, xa, xb) = piece.patch().frame(a, b);
            let (hu, hv) = (
                piece.u_range()[1] - piece.u_range()[0],
                piece.v_range()[1] - piece.v_range()[0],
            );
            (x, xa / hu, xb / hv)
        }
    }
}

/// Value and partials `[f, f_u, f_v, f_uu, f_uv, f_vv]` of each homogeneous
/// coordinate `(w·x, w·y, w·z, w)`.
type HJet = [[f64; 6]; 4];

/// `S = X / W` and its partials by the quotient rule (see [`jet`]).
fn quotient(h: &HJet) -> Jet {
    let at = |k: usize| DVec3::new(h[0][k], h[1][k], h[2][k]);
    let w = h[3];
    let s = at(0) / w[0];
    let su = (at(1) - s * w[1]) / w[0];
    let sv = (at(2) - s * w[2]) / w[0];
    let suu = (at(3) - 2.0 * su * w[1] - s * w[3]) / w[0];
    let suv = (at(4) - su * w[2] - sv * w[1] - s * w[4]) / w[0];
    let svv = (at(5) - 2.0 * sv * w[2] - s * w[5]) / w[0];
    Jet {
        s,
        su,
        sv,
        suu,
        suv,
        svv,
    }
}

/// Degrees are at most 40 (the patch constructors refuse more).
const MAX_DEGREE: usize = 40;

type H4 = [f64; 4];

fn lerp4(a: H4, b: H4, s: f64, t: f64) -> H4 {
    std::array::from_fn(|c| s * a[c] + t * b[c])
}

/// Value, first and second derivative of a univariate BB polynomial of
/// degree `k = c.len() − 1` on `[0, 1]` at `t`, four coordinates at once:
/// de Casteljau down to three points `c₀, c₁, c₂` gives
/// `p = (1−t)²c₀ + 2t(1−t)c₁ + t²c₂`, `p' = k((1−t)(c₁ − c₀) + t(c₂ − c₁))`,
/// `p'' = k(k−1)(c₂ − 2c₁ + c₀)`. Overwrites `c`.
fn uni_jet2(c: &mut [H4], t: f64) -> (H4, H4, H4) {
    let k = c.len() - 1;
    let s = 1.0 - t;
    if k == 0 {
        return (c[0], [0.0; 4], [0.0; 4]);
    }
    for r in 1..k.saturating_sub(1) {
        for i in 0..=k - r {
            c[i] = lerp4(c[i], c[i + 1], s, t);
        }
    }
    let kf = k as f64;
    if k == 1 {
        let d = std::array::from_fn(|j| kf * (c[1][j] - c[0][j]));
        return (lerp4(c[0], c[1], s, t), d, [0.0; 4]);
    }
    let (c0, c1, c2) = (c[0], c[1], c[2]);
    let l0 = lerp4(c0, c1, s, t);
    let l1 = lerp4(c1, c2, s, t);
    let p = lerp4(l0, l1, s, t);
    let d = std::array::from_fn(|j| kf * (l1[j] - l0[j]));
    let dd = std::array::from_fn(|j| kf * (kf - 1.0) * (c2[j] - 2.0 * c1[j] + c0[j]));
    (p, d, dd)
}

/// The homogeneous control point `(w·x, w·y, w·z, w)` number `k`.
fn homogeneous(points: &[DVec3], weights: Option<&[f64]>, k: usize) -> H4 {
    let w = weights.map_or(1.0, |w| w[k]);
    let p = points[k];
    [w * p.x, w * p.y, w * p.z, w]
}

/// [`HJet`] of a tensor patch: each row (fixed `i`) in `v` with two
/// derivatives, then those three columns in `u`; on the stack.
fn tensor_hjet(p: &TensorPatch, u: f64, v: f64) -> HJet {
    let (m, n) = p.degree();
    let (pts, wts) = (p.points(), p.weights());
    let (mut r0, mut r1, mut r2) = (
        [[0.0; 4]; MAX_DEGREE + 1],
        [[0.0; 4]; MAX_DEGREE + 1],
        [[0.0; 4]; MAX_DEGREE + 1],
    );
    let mut line = [[0.0; 4]; MAX_DEGREE + 1];
    for (i, ((a, b), c)) in r0.iter_mut().zip(&mut r1).zip(&mut r2).take(m + 1).enumerate() {
        for (j, slot) in line[..=n].iter_mut().enumerate() {
            *slot = homogeneous(pts, wts, i * (n + 1) + j);
        }
        (*a, *b, *c) = uni_jet2(&mut line[..=n], v);
    }
    let (f, fu, fuu) = uni_jet2(&mut r0[..=m], u);
    let (fv, fuv, _) = uni_jet2(&mut r1[..=m], u);
    let (fvv, _, _) = uni_jet2(&mut r2[..=m], u);
    std::array::from_fn(|c| [f[c], fu[c], fv[c], fuu[c], fuv[c], fvv[c]])
}

/// [`HJet`] of a triangular patch through [`TriBezier::jet2`] on each
/// homogeneous coordinate (allocates; triangles are not on a hot path here).
fn tri_hjet(p: &TriPatch, u: f64, v: f64) -> HJet {
    let n = p.degree();
    let (pts, wts) = (p.points(), p.weights());
    let hom: Vec<H4> = (0..pts.len()).map(|k| homogeneous(pts, wts, k)).collect();
    let bary = [u, v, 1.0 - u - v];
    std::array::from_fn(|c| {
        let poly = TriBezier::new(n, hom.iter().map(|h| h[c]).collect())
            .expect("a TriPatch's net has the length of its degree");
        let (f, g, h) = poly.jet2(&bary);
        [f, g[0], g[1], h[0], h[1], h[2]]
    })
}
