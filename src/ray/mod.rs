//! Certified ray–patch intersection: every hit of a ray with a triangular,
//! tensor-product (rational) Bézier or B-spline/NURBS patch, each with a proof.
//!
//! ```
//! use rootclip::glam::DVec3;
//! use rootclip::ray::{intersect, Patch, Ray, RayOptions, TriPatch};
//! // The flat triangle z = 0 with corners (0,0), (1,0), (0,1), degree 1.
//! let tri = TriPatch::new(1, vec![DVec3::ZERO, DVec3::X, DVec3::Y], None)?;
//! let ray = Ray::new(DVec3::new(0.25, 0.5, 2.0), DVec3::new(0.0, 0.0, -1.0))?;
//! let out = intersect(&Patch::from(tri), &ray, &RayOptions::default())?;
//! assert!(out.is_complete() && out.hits().len() == 1);
//! let hit = &out.hits()[0];
//! assert!(hit.is_certified() && (hit.t - 2.0).abs() < 1e-12);
//! # Ok::<(), rootclip::Error>(())
//! ```
//!
//! # Reduction (Liu et al. 2016, §2.2, Eq. (3)–(6); Roth et al. 2000)
//! The ray `o + t·d` is the intersection of two planes through `o` with
//! normals `n₁, n₂ ⊥ d`. Substituting the homogeneous control points gives
//!
//! ```text
//! f_k(u, v) = Σ w_ij n_k·(P_ij − o) B_ij(u, v) = 0,   k = 1, 2,
//! ```
//! whose roots in the domain are exactly the parameters of the hits (weights
//! are positive, so the denominator never vanishes). The normals are
//! `n₁ = e_a × d̃` (`e_a` the axis of `d`'s smallest component) and
//! `n₂ = d̃ × n₁`, `d̃ = 2^s d` scaled to unit size; they are orthogonal to `d`
//! exactly in real arithmetic and not normalized (scaling an equation does not
//! move its roots). Every coefficient is computed in interval arithmetic, so
//! the system handed to the certified solver encloses the exact one and the
//! solver's contract carries over: each certified `(u, v)` box holds exactly
//! one hit of the exact ray with the exact patch.
//!
//! # t
//! `t = (S(u, v) − o)·d / |d|²` (for `d` as given, not normalized), enclosed
//! over the certified box: `S` by interval de Casteljau on each homogeneous
//! coordinate, divided by the weight. Hits with `t` provably outside the
//! range [`RayOptions::t_range`] (default `[0, ∞]`) are dropped; a root whose
//! `t` box reaches over an end of the range is settled in exact arithmetic
//! for Bézier patches, and otherwise reported as
//! [`UndecidedReason::RangeEnd`](crate::solve::UndecidedReason::RangeEnd).
//!
//! # Degenerate cases
//! A ray lying in the plane of a planar patch makes an equation vanish
//! identically: reported as [`RayOutcome::Degenerate`] (never "no hits"), as
//! is a solve that exhausts its budget or ends in many undecided regions (a
//! curve of hits, or a ray grazing along the surface).

mod bezier;
mod boxes;
pub(crate) mod bspline;
mod hit;
#[cfg(feature = "serde")]
mod json;
pub(crate) mod patch;
mod planes;
mod query;
mod referee;
mod regions;
#[cfg(feature = "internals")]
pub(crate) mod sample;
pub(crate) mod settle;
mod spec;
mod surface;

pub use bspline::{BezierPiece, BsplineSurface};
pub use hit::{Degeneracy, Hit, HitBox, HitStatus, RayHits, RayOutcome};
pub use patch::{TensorPatch, TriPatch};
pub use query::{Query, Ray, RayOptions};
pub use referee::{classify, classify_with, Claim, ClaimResult, Classification};
pub use spec::PatchSpec;
pub use surface::Patch;

use crate::error::{Error, Result};
use crate::scalar;
use patch::BezierRef;
use rayon::prelude::*;

/// The hits of `ray` with `patch` that `opts.query` asks for, among those
/// with `t` in `opts.t_range`:
/// * [`Query::All`]: every hit;
/// * [`Query::Nearest`]: the hits that may be the nearest ([`RayHits::nearest`]:
///   a single certified hit is the proven nearest one), found without
///   exploring regions provably farther than a certified hit;
/// * [`Query::Any`]: one certified hit if there is one (the search stops
///   there), else as for `All`.
///
/// `complete` keeps its meaning for the hits the query asks for. Each hit is
/// certified or says why not ([`HitStatus`]); see the module docs for the
/// reduction. Errors: invalid options ([`Error::InvalidOption`]);
/// a hit whose `t` or point overflows `f64` (a direction too short for the patch:
/// [`Error::NonFinite`]).
///
/// ```
/// use rootclip::glam::DVec3;
/// use rootclip::ray::{intersect, Query, Ray, RayOptions, RayOutcome, TensorPatch};
/// // The bilinear saddle z = (x − ½)(y − ½) over [0, 1]², the ray down through its centre.
/// let pts = (0..2).flat_map(|i| (0..2).map(move |j| {
///     DVec3::new(i as f64, j as f64, 0.25 * if i == j { 1.0 } else { -1.0 })
/// })).collect();
/// let saddle = TensorPatch::new(1, 1, pts, None)?;
/// let ray = Ray::new(DVec3::new(0.5, 0.5, 1.0), -DVec3::Z)?;
/// let opts = RayOptions::default().with_query(Query::Nearest);
/// let RayOutcome::Hits(h) = intersect(&saddle.into(), &ray, &opts)? else { panic!("degenerate") };
/// assert!(h.hits[0].is_certified() && (h.hits[0].t - 1.0).abs() < 1e-12);
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn intersect(patch: &Patch, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    opts.validate()?;
    if let Some((s, w)) = scale_for(patch, ray) {
        if let Some((scaled, ray)) = scaled_query(patch, ray, s, w) {
            let out = intersect_unscaled(&scaled, &ray, opts)?;
            return Ok(unscale(out, s));
        }
    }
    intersect_unscaled(patch, ray, opts)
}

/// Outside `[2⁻⁴⁰⁰, 2⁴⁰⁰]` the reduction's products (coordinates times the
/// normals, weights times coordinates) may overflow or lose their digits to
/// underflow: such a query is solved scaled.
const SAFE_EXP: i32 = 400;

/// The powers of two `(s, w)` that bring the patch's coordinates with the
/// ray's origin (`s`), and its weights (`w`), to about 1, where either is
/// outside the safe range; `None` if both are inside it.
fn scale_for(patch: &Patch, ray: &Ray) -> Option<(f64, f64)> {
    let m = patch.magnitude();
    let outside = |x: f64| x != 0.0 && !(2f64.powi(-SAFE_EXP)..=2f64.powi(SAFE_EXP)).contains(&x);
    let size = m.coords.max(ray.origin().abs().max_element());
    let (lo, hi) = (m.weights[0], m.weights[1]);
    if !outside(size) && !outside(lo) && !outside(hi) {
        return None;
    }
    let to_one = |x: f64| {
        if x > 0.0 && x.is_finite() {
            2f64.powi(-(x.log2().floor() as i32).clamp(-1000, 1000))
        } else {
            1.0
        }
    };
    Some((to_one(size), to_one(hi)))
}

/// The patch with its coordinates times `s` and weights times `w`, and the
/// ray with origin and direction times `s` (the same hits, the same `t`,
/// the same parameters): `None` unless every product is exact (a
/// coordinate that would lose bits to underflow keeps the query unscaled).
fn scaled_query(patch: &Patch, ray: &Ray, s: f64, w: f64) -> Option<(Patch, Ray)> {
    let exact = |x: f64, k: f64| x * k / k == x && (x * k).is_finite();
    let mut spec = patch.to_spec();
    let (points, weights) = match &mut spec {
        PatchSpec::Triangle { points, weights, .. }
        | PatchSpec::Tensor { points, weights, .. }
        | PatchSpec::Bspline { points, weights, .. } => (points, weights),
    };
    for p in points.iter_mut() {
        for c in p.iter_mut() {
            if !exact(*c, s) {
                return None;
            }
            *c *= s;
        }
    }
    for x in weights.iter_mut().flatten() {
        if !exact(*x, w) {
            return None;
        }
        *x *= w;
    }
    let (o, d) = (ray.origin(), ray.dir());
    if !(o.to_array().iter().chain(&d.to_array()).all(|&x| exact(x, s))) {
        return None;
    }
    let ray = Ray::new(o * s, d * s).ok()?;
    Some((Patch::from_spec(&spec).ok()?, ray))
}

/// The hits of a query solved scaled by `s`, in the original's units: only
/// the points move (parameters, `t` and normals are the same).
fn unscale(out: RayOutcome, s: f64) -> RayOutcome {
    let back = |mut h: RayHits| {
        for hit in &mut h.hits {
            hit.point /= s;
        }
        h
    };
    match out {
        RayOutcome::Hits(h) => RayOutcome::Hits(back(h)),
        RayOutcome::Degenerate(Degeneracy::Unresolved(h)) => RayOutcome::Degenerate(Degeneracy::Unresolved(back(h))),
        RayOutcome::Degenerate(Degeneracy::AlongSurface(h)) => {
            RayOutcome::Degenerate(Degeneracy::AlongSurface(back(h)))
        }
        d => d,
    }
}

fn intersect_unscaled(patch: &Patch, ray: &Ray, opts: &RayOptions) -> Result<RayOutcome> {
    // One deadline for every solve this ray starts (routes, retries, pieces).
    let opts = &RayOptions {
        solve: opts.solve.started(),
        ..opts.clone()
    };
    let out = match patch {
        Patch::Triangle(p) => bezier::intersect_bezier(BezierRef::Tri(p), ray, opts),
        Patch::Tensor(p) => bezier::intersect_bezier(BezierRef::Tensor(p), ray, opts),
        Patch::Bspline(s) => bspline::intersect_bspline(s, ray, opts),
    }?;
    let out = into_domain(patch, out);
    // A hit's numbers overflow only where `t ~ |S − o| / |d|` exceeds the
    // largest float (a very short direction): an error, never a NaN or ∞
    // in a hit (JSON would print `null`).
    if let Some(h) = out.hits().iter().find(|h| !hit_is_finite(h)) {
        return Err(Error::NonFinite(format!(
            "a hit's t or point overflows f64 (t box {:?}): the direction is too short for this patch",
            h.bx.t
        )));
    }
    Ok(out)
}

/// Every hit's box cut to the patch's closed parameter domain, and its
/// `(u, v)` moved into the cut box, so that every reported parameter lies in
/// the domain exactly (on a triangle `u + v ≤ 1` in exact arithmetic, not
/// only after rounding). The hits a box stands for lie in the domain, so
/// they lie in the cut box; a box that misses the domain altogether stands
/// for no hit of the patch and is dropped. Point and normal are re-evaluated
/// where `(u, v)` moved.
fn into_domain(patch: &Patch, out: RayOutcome) -> RayOutcome {
    let (ud, vd) = match patch {
        Patch::Bspline(s) => s.domain(),
        Patch::Triangle(_) | Patch::Tensor(_) => ([0.0, 1.0], [0.0, 1.0]),
    };
    let triangle = matches!(patch, Patch::Triangle(_));
    let cut = |h: Hit| -> Option<Hit> {
        let mut bx = h.bx;
        bx.u = [bx.u[0].max(ud[0]), bx.u[1].min(ud[1])];
        bx.v = [bx.v[0].max(vd[0]), bx.v[1].min(vd[1])];
        if triangle {
            // u ≤ 1 − v_lo and v ≤ 1 − u_lo on the triangle, rounded up.
            bx.u[1] = bx.u[1].min((scalar::point(1.0) - scalar::point(bx.v[0])).sup());
            bx.v[1] = bx.v[1].min((scalar::point(1.0) - scalar::point(bx.u[0])).sup());
        }
        if !(bx.u[0] <= bx.u[1] && bx.v[0] <= bx.v[1]) {
            return None;
        }
        let mut u = h.u.clamp(bx.u[0], bx.u[1]);
        let mut v = h.v.clamp(bx.v[0], bx.v[1]);
        if triangle && (scalar::point(u) + scalar::point(v)).sup() > 1.0 {
            // 1 − u rounded down: then u + v ≤ 1 exactly.
            v = (scalar::point(1.0) - scalar::point(u)).inf().max(0.0);
            if v < bx.v[0] {
                u = (scalar::point(1.0) - scalar::point(bx.v[0])).inf().max(bx.u[0]);
                v = bx.v[0];
            }
        }
        let moved = u != h.u || v != h.v;
        let (point, normal) = if moved {
            patch.point_and_normal(u, v)
        } else {
            (h.point, h.normal)
        };
        Some(Hit {
            u,
            v,
            point,
            normal,
            bx,
            ..h
        })
    };
    let keep = |h: RayHits| RayHits {
        complete: h.complete,
        hits: h.hits.into_iter().filter_map(cut).collect(),
    };
    match out {
        RayOutcome::Hits(h) => RayOutcome::Hits(keep(h)),
        RayOutcome::Degenerate(Degeneracy::Unresolved(h)) => RayOutcome::Degenerate(Degeneracy::Unresolved(keep(h))),
        RayOutcome::Degenerate(Degeneracy::AlongSurface(h)) => {
            RayOutcome::Degenerate(Degeneracy::AlongSurface(keep(h)))
        }
        d @ RayOutcome::Degenerate(Degeneracy::ZeroEquation) => d,
    }
}

/// Every number of `h` is finite.
fn hit_is_finite(h: &Hit) -> bool {
    let b = &h.bx;
    [h.t, h.u, h.v, b.u[0], b.u[1], b.v[0], b.v[1], b.t[0], b.t[1]]
        .iter()
        .all(|x| x.is_finite())
        && h.point.is_finite()
        && h.normal.is_finite()
}

/// [`intersect`] for many rays, in parallel (rayon's global pool), the
/// outcomes in the order of `rays`; an error is returned per ray.
///
/// ```
/// use rootclip::glam::DVec3;
/// use rootclip::ray::{intersect_batch, Ray, RayOptions, TriPatch};
/// let tri = TriPatch::new(1, vec![DVec3::ZERO, DVec3::X, DVec3::Y], None)?;
/// let rays: Vec<Ray> = (0..100)
///     .map(|k| Ray::new(DVec3::new(0.004 * k as f64, 0.2, 1.0), -DVec3::Z))
///     .collect::<Result<_, _>>()?;
/// let out = intersect_batch(&tri.into(), &rays, &RayOptions::default());
/// let hits: usize = out.iter().map(|o| o.as_ref().map_or(0, |o| o.hits().len())).sum();
/// assert_eq!(hits, 100);
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn intersect_batch(patch: &Patch, rays: &[Ray], opts: &RayOptions) -> Vec<Result<RayOutcome>> {
    if let Err(e) = opts.validate() {
        return rays.iter().map(|_| Err(e.clone())).collect();
    }
    rays.par_iter().map(|r| intersect(patch, r, opts)).collect()
}
