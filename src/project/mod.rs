//! Certified point projection and inversion: the closest point of a patch to
//! any point `P`, with a rigorous enclosure of the distance and a certified
//! parameter box where it is attained.
//!
//! ```
//! use rootclip::glam::DVec3;
//! use rootclip::project::{project, ProjectOptions, ProjectionStatus};
//! use rootclip::ray::TensorPatch;
//! // The plane z = 0 over [0, 1]² (bilinear), and a point above (0.25, 0.5).
//! let pts = vec![DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
//! let plane = TensorPatch::new(1, 1, pts, None)?;
//! let pr = project(&plane.into(), DVec3::new(0.25, 0.5, 2.0), &ProjectOptions::default())?;
//! assert_eq!(pr.status, ProjectionStatus::Unique);
//! assert!(pr.distance[0] <= 2.0 && 2.0 <= pr.distance[1] && pr.distance[1] - pr.distance[0] < 1e-9);
//! assert!((pr.u - 0.25).abs() < 1e-12 && (pr.v - 0.5).abs() < 1e-12);
//! # Ok::<(), rootclip::Error>(())
//! ```
//!
//! # How the minimum is proven
//! The squared distance `D(u, v) = |S(u, v) − P|²` attains its minimum over
//! the closed domain at a critical point of the interior, of an edge, or at a
//! corner. The interior critical points are the roots of the system
//! `(X − P W)·(X_u W − X W_u) = (X − P W)·(X_v W − X W_v) = 0` (`S = X/W`;
//! `(S − P)·S_u = (S − P)·S_v = 0` for a polynomial patch), isolated by the
//! certified bivariate solver; an edge's are the roots of the same
//! expression along the edge curve, isolated by the certified univariate
//! solver; the corners are points. Every region the solvers return (certified
//! root boxes, undecided regions, leftovers of a budget) is a candidate; over
//! each, `D` is enclosed in interval arithmetic. Then
//! * the minimum is at least the smallest lower bound over all candidates
//!   (the solves are complete, or their leftovers are candidates too);
//! * it is at most `D` at any point of the closed domain, in particular at a
//!   point of each candidate (its centre, moved into the domain);
//! * the **feet** are the candidates whose lower bound does not exceed that
//!   upper bound: the minimum is attained in one of them.
//!
//! A single certified foot is a proven closest point ([`ProjectionStatus::Unique`]);
//! several certified ones that intervals cannot tell apart (a point on the
//! medial axis, equidistant from two feet) are [`ProjectionStatus::Ties`];
//! any undecided foot (a focal point, where the critical points form a curve)
//! makes it [`ProjectionStatus::Undecided`] — the distance enclosure holds in
//! every case. B-spline surfaces are projected piece by piece, each piece a
//! closed patch (a knot line may be a crease), pieces whose control-net box
//! is farther than the best candidate skipped.

mod critical;
mod distance;
mod ivpoly;
mod patches;
mod tensor;

use crate::error::{Error, Result};
use crate::ray::Patch;
use crate::solve::{Box2, SolveOptions};
use glam::DVec3;
use rayon::prelude::*;

/// Options of [`project`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct ProjectOptions {
    /// The certified solves' options (`eps`, budgets; `max_boxes` applies
    /// to each solve).
    pub solve: SolveOptions,
}

impl Default for ProjectOptions {
    fn default() -> Self {
        Self {
            solve: SolveOptions {
                max_boxes: 20_000,
                square_route: crate::solve::SquareRoute::Rect,
                ..SolveOptions::default()
            },
        }
    }
}

/// Where a foot lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum FootKind {
    /// A critical point of `D` inside the patch.
    Interior,
    /// A critical point of `D` on an edge.
    Edge,
    /// A corner of the patch.
    Corner,
}

/// A region where the minimum of the distance may be attained.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Foot {
    /// A point of the closed domain in the region (its centre, moved into
    /// the domain).
    pub u: f64,
    /// See `u`.
    pub v: f64,
    /// The region, a closed box in the patch's parameters.
    #[cfg_attr(feature = "serde", serde(rename = "box"))]
    pub bx: Box2,
    /// `S(u, v)` in `f64`.
    pub point: DVec3,
    /// An enclosure of the distance over the region's closest point and
    /// `|S(u, v) − P|`: `[lower bound over the region, upper bound at (u, v)]`.
    pub distance: [f64; 2],
    /// Interior, edge or corner.
    pub kind: FootKind,
    /// The region holds exactly one critical point of its kind (a corner is
    /// one point): a certified foot.
    pub certified: bool,
}

/// What is proven about the closest point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum ProjectionStatus {
    /// One certified foot: the closest point lies in its box.
    Unique,
    /// Several certified feet whose distances intervals cannot tell apart
    /// (equidistant feet): the closest point lies in one of their boxes.
    Ties,
    /// An undecided region may hold the closest point (a curve of critical
    /// points, a budget): only the distance enclosure is proven.
    Undecided,
}

/// The closest point of a patch to a point.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Projection {
    /// Parameters of a point of the patch whose distance lies in `distance`
    /// (the best foot's).
    pub u: f64,
    /// See `u`.
    pub v: f64,
    /// `S(u, v)` in `f64`.
    pub point: DVec3,
    /// A rigorous enclosure `[lo, hi]` of the minimum of `|S − P|` over the
    /// closed patch; `|S(u, v) − P| ≤ hi`.
    pub distance: [f64; 2],
    /// What is proven; see [`ProjectionStatus`].
    pub status: ProjectionStatus,
    /// The feet, best first: the minimum is attained in one of their boxes.
    pub feet: Vec<Foot>,
}

/// The closest point of `patch` to `point` (module docs for the proof).
///
/// Errors: a non-finite point ([`Error::NonFinite`]), invalid options.
pub fn project(patch: &Patch, point: DVec3, opts: &ProjectOptions) -> Result<Projection> {
    opts.solve.validate()?;
    if !point.is_finite() {
        return Err(Error::NonFinite(format!("point {:?}", point.to_array())));
    }
    project_prepared(patch, &patches::Prepared::new(patch), point, opts)
}

fn project_prepared(
    patch: &Patch,
    prep: &patches::Prepared<'_>,
    point: DVec3,
    opts: &ProjectOptions,
) -> Result<Projection> {
    if !point.is_finite() {
        return Err(Error::NonFinite(format!("point {:?}", point.to_array())));
    }
    let candidates = patches::candidates(prep, point.to_array(), &opts.solve)?;
    Ok(decide(patch, candidates))
}

/// [`project`] for many points, in parallel (rayon), results in input order.
/// What the points share (the critical-point system and the distance as
/// polynomials affine in the point, see `src/project/tensor.rs`) is built
/// once.
pub fn project_batch(patch: &Patch, points: &[DVec3], opts: &ProjectOptions) -> Vec<Result<Projection>> {
    if let Err(e) = opts.solve.validate() {
        return points.iter().map(|_| Err(e.clone())).collect();
    }
    let prep = patches::Prepared::new(patch);
    points
        .par_iter()
        .map(|&p| project_prepared(patch, &prep, p, opts))
        .collect()
}

/// A candidate region with its squared-distance bounds.
#[derive(Clone, Debug)]
pub(crate) struct Candidate {
    pub(crate) bx: Box2,
    /// A point of the closed domain in the region.
    pub(crate) at: [f64; 2],
    pub(crate) kind: FootKind,
    pub(crate) certified: bool,
    /// Lower bound of `D` over the region, upper bound of `D` at `at`.
    pub(crate) d: [f64; 2],
}

/// The feet and the verdict from the candidates (module docs). Feet whose
/// boxes touch are one foot (the hull; certified if all were): the same
/// point found by two strata — a corner and an edge's end, two pieces of a
/// B-spline along their common knot line.
fn decide(patch: &Patch, mut cands: Vec<Candidate>) -> Projection {
    let hi = cands.iter().map(|c| c.d[1]).fold(f64::INFINITY, f64::min);
    let lo = cands.iter().map(|c| c.d[0]).fold(f64::INFINITY, f64::min);
    cands.retain(|c| c.d[0] <= hi);
    let mut cands = merge_touching(cands);
    cands.sort_by(|a, b| a.d[1].total_cmp(&b.d[1]).then(a.d[0].total_cmp(&b.d[0])));
    let feet: Vec<Foot> = cands
        .iter()
        .map(|c| Foot {
            u: c.at[0],
            v: c.at[1],
            bx: c.bx,
            point: patch.eval(c.at[0], c.at[1]),
            distance: distance::sqrt_range(c.d[0], c.d[1]),
            kind: c.kind,
            certified: c.certified,
        })
        .collect();
    let status = match feet.as_slice() {
        [one] if one.certified => ProjectionStatus::Unique,
        many if !many.is_empty() && many.iter().all(|f| f.certified) => ProjectionStatus::Ties,
        _ => ProjectionStatus::Undecided,
    };
    let (u, v, point) = feet
        .first()
        .map_or((f64::NAN, f64::NAN, DVec3::NAN), |f| (f.u, f.v, f.point));
    Projection {
        u,
        v,
        point,
        distance: distance::sqrt_range(lo, hi),
        status,
        feet,
    }
}

/// Joins candidates whose boxes touch (transitively) into their hull; the
/// representative point and the upper bound of the best member are kept.
fn merge_touching(cands: Vec<Candidate>) -> Vec<Candidate> {
    let mut out: Vec<Candidate> = Vec::with_capacity(cands.len());
    for c in cands {
        let mut merged = c;
        while let Some(k) = out.iter().position(|o| o.bx.overlaps(&merged.bx)) {
            let o = out.swap_remove(k);
            let best = if o.d[1] <= merged.d[1] { &o } else { &merged };
            merged = Candidate {
                bx: Box2::new(
                    [o.bx.u[0].min(merged.bx.u[0]), o.bx.u[1].max(merged.bx.u[1])],
                    [o.bx.v[0].min(merged.bx.v[0]), o.bx.v[1].max(merged.bx.v[1])],
                ),
                at: best.at,
                kind: best.kind,
                certified: o.certified && merged.certified,
                d: [o.d[0].min(merged.d[0]), best.d[1]],
            };
        }
        out.push(merged);
    }
    out
}
