//! The four clipping methods of Liu et al. (2016) and the preprocessing of
//! hybrid clipping (§2.3.1, Eqs. (7)–(8)).

use super::fatcurve::{
    bezier_bounds, clip_against_fat_curves, clip_against_fat_curves_swapped, intersect_bounds, ClipBounds, Fat, Linear,
    Quadratic,
};
use super::linalg::solve3;
use crate::poly::{Reduced, TriBall};
use crate::scalar::geo::Geo;
use std::fmt;
use std::str::FromStr;

/// A clipping method on triangles (Liu et al. 2016, §2.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Method {
    /// Triangular Bézier clipping (Roth et al. 2000): convex hulls of both
    /// control nets.
    #[cfg_attr(feature = "serde", serde(rename = "bezier"))]
    Bezier,
    /// Linear fat curves for both equations.
    #[cfg_attr(feature = "serde", serde(rename = "linear"))]
    Linear,
    /// Hybrid clipping without preprocessing: a fat line for `f`, a fat conic
    /// for `g`.
    #[cfg_attr(feature = "serde", serde(rename = "hc-nopre"))]
    HcNoPre,
    /// Hybrid clipping: a fat line for the preprocessed `f̂`, a fat conic for
    /// `g` (a second clip with the roles swapped is added unless
    /// `SolveOptions::swap_roles` is off).
    #[cfg_attr(feature = "serde", serde(rename = "hc"))]
    Hc,
}

impl Method {
    /// All methods, in the paper's table order.
    pub const ALL: [Method; 4] = [Method::Bezier, Method::Linear, Method::HcNoPre, Method::Hc];

    /// The CLI / JSON name.
    pub fn name(self) -> &'static str {
        match self {
            Method::Bezier => "bezier",
            Method::Linear => "linear",
            Method::HcNoPre => "hc-nopre",
            Method::Hc => "hc",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = crate::Error;
    fn from_str(s: &str) -> crate::Result<Self> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| crate::Error::Shape(format!("unknown method '{s}' (bezier, linear, hc-nopre, hc)")))
    }
}

/// The degree-`k` fat curve of `f` on its tri-box (`k` = 1 or 2): the L2-best
/// approximant (Algorithm 2) of the ball's midpoints, a float polynomial, with
/// the rigorous `δ` of [`TriBall::reduce`], lifted into the geometry kernel
/// `G`. `None` when `δ` is not finite (an overflowed ball): no fat curve
/// exists, and the caller must not clip.
pub fn fat_curve<G: Geo>(f: &TriBall, k: usize) -> Option<Fat<G>> {
    to_fat(&f.reduce(k), f)
}

fn to_fat<G: Geo>(red: &Reduced, f: &TriBall) -> Option<Fat<G>> {
    if !red.delta.is_finite() {
        return None;
    }
    // The float kernel's geometry has no enclosures: give its fat curves the
    // slack of a few rounding errors on the coefficient scale, or points on a
    // curve (δ = 0 for an exact low-degree equation) test as outside it.
    let delta = if G::RIGOROUS {
        red.delta
    } else {
        red.delta + 1e-12 * f.max_mid()
    };
    match red.approx.len() {
        3 => Some(Fat::Line(Linear::from_bb(&red.approx), delta)),
        6 => Some(Fat::Conic(Quadratic::from_bb(&red.approx), delta)),
        _ => None,
    }
}

#[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
/// `f̂ = ℓ f^α + (1 − ℓ) f^β` with `ℓ = ℓ0 + ℓ1 u + ℓ2 v` chosen (in f64) so
/// that the Hessian of `f̂` vanishes at the point `c` (local barycentric):
/// `A(c) ℓ = −∇²f^β(c)` with `A` of Eq. (8), written with `Δ = f^α − f^β`:
/// ```text
/// A = [ Δuu   u Δuu + 2Δu   v Δuu        ]
///     [ Δuv   u Δuv + Δv    v Δuv + Δu   ]
///     [ Δvv   u Δvv         v Δvv + 2Δv  ]
/// ```
/// (Eq. (8) as printed checks out: it is the Hessian of `ℓ Δ` collected by
/// `ℓ0, ℓ1, ℓ2`.) `None` when `A` is numerically singular — the caller then
/// uses `f^α` (the paper's fallback).
///
/// Any `ℓ` keeps the method rigorous: every root of `{f^α, f^β}` is a root of
/// `{f̂, f^β}`, and `f̂ = ℓΔ + f^β` is enclosed by ball arithmetic
/// ([`TriBall::linear_combination`]).
pub fn preprocess(fa: &TriBall, fb: &TriBall, c: [f64; 3]) -> Option<TriBall> {
    let delta = TriBall::combine(1.0, fa, -1.0, fb);
    paper_multiplier(&jet(&delta, c), jet_noise(&delta), &jet(fb, c), c).map(|l| apply_paper(&delta, fb, l))
}

/// Gradient and Hessian at `c`, in `f64` (the multipliers only need to be
/// good, not exact: any choice is rigorous).
type Jet = ([f64; 2], [f64; 3]);

fn jet(p: &TriBall, c: [f64; 3]) -> Jet {
    let (_, g, h) = p.jet2(&c);
    (g, h)
}

/// An estimate `(e₁, e₂)` of how far [`TriBall::jet2`]'s first and second
/// partials (at a point of the triangle) can be from those of a member of
/// the ball: the partials' coefficients are differences of 2 and 4
/// coefficients times `n` and `n(n − 1)`, each within `r` plus the
/// evaluation's rounding (`~2n u M`).
fn jet_noise(p: &TriBall) -> (f64, f64) {
    let n = p.degree() as f64;
    let base = p.rad() + 2.0 * n * f64::EPSILON * p.max_mid();
    (2.0 * n * base, 4.0 * n * (n - 1.0).max(0.0) * base)
}

/// `ℓ = (ℓ0, ℓ1, ℓ2)` of Eq. (7) from the jets of `Δ = f^α − f^β` (formed as
/// a polynomial first, so that partials which vanish exactly stay 0 and a
/// singular `A` is seen as such) and of `f^β`; `None` when `A` is
/// numerically singular.
///
/// A row of `A` whose entries are all within a few times the rounding noise
/// of `Δ`'s jet (`noise = (e₁, e₂)` for first and second partials,
/// [`jet_noise`]) is zero: `A` is singular. (In Example 2 `Δ` depends on `u`
/// alone and the third row vanishes exactly; its computed entries are
/// rounding noise, which a pivot test relative to the row itself would
/// accept, and `ℓ` would be meaningless.)
fn paper_multiplier(jd: &Jet, noise: (f64, f64), jb: &Jet, c: [f64; 3]) -> Option<[f64; 3]> {
    let [du, dv] = jd.0;
    let [duu, duv, dvv] = jd.1;
    let rhs = [-jb.1[0], -jb.1[1], -jb.1[2]];
    let (u, v) = (c[0], c[1]);
    let a = [
        [duu, u * duu + 2.0 * du, v * duu],
        [duv, u * duv + dv, v * duv + du],
        [dvv, u * dvv, v * dvv + 2.0 * dv],
    ];
    let (e1, e2) = noise;
    let (ua, va) = (u.abs(), v.abs());
    let row_noise = [
        [e2, ua * e2 + 2.0 * e1, va * e2],
        [e2, ua * e2 + e1, va * e2 + e1],
        [e2, ua * e2, va * e2 + 2.0 * e1],
    ];
    let zero_row = a
        .iter()
        .zip(&row_noise)
        .any(|(row, noise)| row.iter().zip(noise).all(|(x, e)| x.abs() <= 8.0 * e));
    if zero_row {
        return None;
    }
    let l = solve3(a, rhs)?;
    (!l.iter().any(|x| !x.is_finite() || x.abs() > 1e8)).then_some(l)
}

/// `f̂ = ℓ Δ + f^β` in ball arithmetic.
fn apply_paper(delta: &TriBall, fb: &TriBall, l: [f64; 3]) -> TriBall {
    // ℓ as a degree-1 BB polynomial: values at V3 (0,0), V1 (1,0), V2 (0,1).
    let ell = [l[0], l[0] + l[1], l[0] + l[2]];
    TriBall::linear_combination(ell, delta, [1.0; 3], fb)
}

#[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
/// The generalised preprocessing used when Eq. (8)'s `A` is singular:
/// `f̂ = ℓ f^α + m f^β` with two linear multipliers `ℓ = 1 + ℓ1 (u − u_c) + ℓ2 (v − v_c)`
/// and `m = m0 + m1 (u − u_c) + m2 (v − v_c)` whose Hessian vanishes at `c`:
/// ```text
/// f_uu + m0 g_uu + 2ℓ1 f_u + 2m1 g_u                 = 0
/// f_uv + m0 g_uv + ℓ1 f_v + ℓ2 f_u + m1 g_v + m2 g_u = 0
/// f_vv + m0 g_vv + 2ℓ2 f_v + 2m2 g_v                 = 0
/// ```
/// solved for the minimum-norm `(m0, ℓ1, ℓ2, m1, m2)`. Three equations, five
/// unknowns: solvable whenever `∇f` and `∇g` are transversal at `c` — exactly
/// the simple-root case. The paper's form is the special case `m = 1 − ℓ`,
/// which is singular for all of Examples 1 and 2 (there `f − g` is linear,
/// respectively a function of `u` alone). Rigor is as for [`preprocess`]:
/// every root of `{f^α, f^β}` is a root of `{f̂, f^β}`.
pub fn preprocess_general(fa: &TriBall, fb: &TriBall, c: [f64; 3]) -> Option<TriBall> {
    general_multipliers(&jet(fa, c), &jet(fb, c)).map(|x| apply_general(fa, fb, x, c))
}

/// The minimum-norm `(m0, ℓ1, ℓ2, m1, m2)` of [`preprocess_general`].
fn general_multipliers(ja: &Jet, jb: &Jet) -> Option<[f64; 5]> {
    let ((fg, fh), (gg, gh)) = (ja, jb);
    // Columns of M for x = (m0, ℓ1, ℓ2, m1, m2).
    let cols = [
        [gh[0], gh[1], gh[2]],
        [2.0 * fg[0], fg[1], 0.0],
        [0.0, fg[0], 2.0 * fg[1]],
        [2.0 * gg[0], gg[1], 0.0],
        [0.0, gg[0], 2.0 * gg[1]],
    ];
    let mut mmt = [[0.0; 3]; 3];
    for (r, row) in mmt.iter_mut().enumerate() {
        for (k, x) in row.iter_mut().enumerate() {
            *x = cols.iter().map(|col| col[r] * col[k]).sum();
        }
    }
    let y = solve3(mmt, [-fh[0], -fh[1], -fh[2]])?;
    let x = cols.map(|col| col[0] * y[0] + col[1] * y[1] + col[2] * y[2]);
    (!x.iter().any(|v| !v.is_finite() || v.abs() > 1e8)).then_some(x)
}

/// `f̂ = ℓ f^α + m f^β` in ball arithmetic.
fn apply_general(fa: &TriBall, fb: &TriBall, x: [f64; 5], c: [f64; 3]) -> TriBall {
    let (cs, ct) = (c[0], c[1]);
    // A linear polynomial a + b1 (s − cs) + b2 (t − ct) in BB form: values at V3, V1, V2.
    let linear = |a: f64, b1: f64, b2: f64| {
        let at = |s: f64, t: f64| a + b1 * (s - cs) + b2 * (t - ct);
        [at(0.0, 0.0), at(1.0, 0.0), at(0.0, 1.0)]
    };
    TriBall::linear_combination(linear(1.0, x[1], x[2]), fa, linear(x[0], x[3], x[4]), fb)
}

/// The width `2δ / |∇l|` of a fat line's strip in local coordinates (∞ for
/// a constant approximant), from the float approximant.
fn strip_width(red: &Reduced) -> f64 {
    let a = &red.approx;
    // The approximant of a normalized ball: no overflow, so no `hypot`.
    let (gs, gt) = (a[1] - a[0], a[2] - a[0]);
    let g = (gs * gs + gt * gt).sqrt();
    if g > 0.0 {
        2.0 * red.delta / g
    } else {
        f64::INFINITY
    }
}

/// One clipping computation on a tri-box (local coordinates): the bounds
/// `u_min, v_min, w_min` for `method`, or `Empty` when the fat regions (or
/// hulls) prove the tri-box root-free. `incenter` is the tri-box incenter in
/// its own barycentric coordinates (for `Hc`). The geometry runs in `G`:
/// [`GeoIv`](crate::scalar::geo::GeoIv) for proofs, `f64` for the plain iteration.
pub fn clip_bounds<G: Geo>(method: Method, fa: &TriBall, fb: &TriBall, incenter: [f64; 3]) -> ClipBounds {
    match method {
        Method::Bezier => intersect_bounds(
            bezier_bounds(fa, G::RIGOROUS),
            bezier_bounds(fb, G::RIGOROUS),
            G::RIGOROUS,
        ),
        _ => {
            fat_pair::<G>(method, fa, fb, incenter).map_or(ClipBounds::Keep([0.0; 3]), |p| clip_against_fat_curves(&p))
        }
    }
}

/// [`clip_bounds`], and for the fat-curve methods, where the kept tri-box is
/// more than half of this one, also with the roles of `f` and `g` swapped,
/// intersected (see [`clip_against_fat_curves_swapped`], which proves each
/// side of the two clips once); the flag says whether the swapped clip ran.
pub fn clip_bounds_swapped<G: Geo>(
    method: Method,
    fa: &TriBall,
    fb: &TriBall,
    incenter: [f64; 3],
) -> (ClipBounds, bool) {
    if method == Method::Bezier {
        return (clip_bounds::<G>(method, fa, fb, incenter), false);
    }
    let Some(first) = fat_pair::<G>(method, fa, fb, incenter) else {
        return (ClipBounds::Keep([0.0; 3]), false);
    };
    clip_against_fat_curves_swapped(&first, || fat_pair::<G>(method, fb, fa, incenter))
}

/// The two fat curves `method` clips with (a fat line of `f` first), `None`
/// where one has no finite width; not for Bézier clipping.
fn fat_pair<G: Geo>(method: Method, fa: &TriBall, fb: &TriBall, incenter: [f64; 3]) -> Option<[Fat<G>; 2]> {
    let fat = |p: &TriBall, k: usize| fat_curve::<G>(p, k);
    match method {
        Method::Bezier => None,
        Method::Linear => Some([fat(fa, 1)?, fat(fb, 1)?]),
        Method::HcNoPre => Some([fat(fa, 1)?, fat(fb, 2)?]),
        Method::Hc => {
            let plain = fa.reduce(1);
            let fhat = preprocessed(fa, fb, incenter).map(|p| {
                let red = p.reduce(1);
                (p, red)
            });
            // The preprocessed line wins asymptotically (δ = O(h³)), but on large
            // tri-boxes, or at the rounding floor where the local Hessians are
            // noise, f̂ can be worse than f^α: keep the narrower strip. Both are
            // rigorous, so the choice affects speed only.
            let line = match &fhat {
                Some((p, red)) if strip_width(red) < strip_width(&plain) => to_fat::<G>(red, p),
                _ => to_fat::<G>(&plain, fa),
            };
            Some([line?, fat(fb, 2)?])
        }
    }
}

/// `f̂` of [`preprocess`], or of [`preprocess_general`] where Eq. (8)'s `A`
/// is singular; `None` if neither exists.
fn preprocessed(fa: &TriBall, fb: &TriBall, c: [f64; 3]) -> Option<TriBall> {
    let delta = TriBall::combine(1.0, fa, -1.0, fb);
    let jb = jet(fb, c);
    match paper_multiplier(&jet(&delta, c), jet_noise(&delta), &jb, c) {
        Some(l) => Some(apply_paper(&delta, fb, l)),
        None => general_multipliers(&jet(fa, c), &jb).map(|x| apply_general(fa, fb, x, c)),
    }
}
