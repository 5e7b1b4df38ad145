//! The referee for rays: hits claimed by a fast solver (a heuristic, a
//! renderer, a CAD kernel) checked against the certified hits.
//!
//! A claim `(u, v, t)` is decided on all three coordinates, by the rules of
//! [`classify_roots`](crate::solve::classify_roots) against the certified
//! all-hits answer of the ray, "within tolerance" meaning `|Δu| ≤ tol`,
//! `|Δv| ≤ tol` and `|Δt| ≤ tol·max(1, |t|)` (`t` relative to its size, in
//! units of the direction as given): **confirmed** when a certified hit's
//! whole `(u, v, t)` box lies within tolerance of the claim and no earlier
//! claim of the same ray took it; **duplicate** when only hits earlier
//! claims took lie within tolerance that way; **spurious** when the answer
//! is complete and no hit region at all (certified or not) has a point
//! within tolerance — so a claim with the right `(u, v)` and a wrong `t` is
//! spurious; **undecided** otherwise. The comparisons are exact.

use super::hit::{Hit, RayHits, RayOutcome};
use super::query::{Query, Ray, RayOptions};
use super::surface::Patch;
use crate::error::Result;
use crate::scalar::point;
use crate::solve::referee::{check_tol, missed, referee_n, Region};
use crate::solve::ClaimVerdict;

/// A claimed hit: parameters `(u, v)` on the patch and the ray parameter `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Claim {
    /// Claimed `u`.
    pub u: f64,
    /// Claimed `v`.
    pub v: f64,
    /// Claimed `t` (judged like `u` and `v`, relative to `max(1, |t|)`).
    pub t: f64,
}

/// The verdict on one claim.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ClaimResult {
    /// The claim as given.
    #[cfg_attr(feature = "serde", serde(flatten))]
    pub claim: Claim,
    /// What the referee says of it.
    pub verdict: ClaimVerdict,
    /// The index (into [`Classification::hits`]) of the hit that confirmed
    /// it or that it duplicates.
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
    pub hit: Option<usize>,
}

/// The referee's answer for one ray.
///
/// JSON (feature `serde`; what `rootclip crosscheck --json` prints per ray):
/// the fields; `missed` as indices into `hits`; `nearest_claimed` `null`
/// when the nearest hit is not proven.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Classification {
    /// One result per claim, in the order given.
    pub claims: Vec<ClaimResult>,
    /// The indices (into `hits`) of certified hits no claim confirmed.
    pub missed: Vec<usize>,
    /// Whether the nearest hit was claimed: `Some(true)` when it is proven
    /// (one certified hit no other region can undercut) and a claim
    /// confirmed it, `Some(false)` when it is proven and none did, `None`
    /// when there is no hit or the nearest is not proven.
    pub nearest_claimed: Option<bool>,
    /// The certified answer was complete (not a degenerate ray).
    pub complete: bool,
    /// Every hit of the ray in the range, certified or not, sorted by `t`.
    pub hits: Vec<Hit>,
}

/// Checks `claims` of hits of `ray` with `patch` against the certified
/// all-hits answer (module docs for the rules), with the default options and
/// the tolerance `tol` (`1e-8` is a good default).
///
/// Errors: a `tol` that is negative or not finite
/// ([`Error::InvalidOption`](crate::Error::InvalidOption)).
///
/// ```
/// use rootclip::glam::DVec3;
/// use rootclip::ray::{classify, Claim, Ray, TriPatch};
/// use rootclip::solve::ClaimVerdict;
/// let tri = TriPatch::new(1, vec![DVec3::ZERO, DVec3::X, DVec3::Y], None)?;
/// let ray = Ray::new(DVec3::new(0.25, 0.5, 1.0), -DVec3::Z)?; // hits (0.25, 0.5) at t = 1
/// let claims = [
///     Claim { u: 0.25, v: 0.5, t: 1.0 },
///     Claim { u: 0.9, v: 0.05, t: 1.0 },
///     Claim { u: 0.25, v: 0.5, t: 1.001 }, // the right point, the wrong t
/// ];
/// let c = classify(&tri.into(), &ray, &claims, 1e-8)?;
/// assert_eq!(c.claims[0].verdict, ClaimVerdict::Confirmed);
/// assert_eq!(c.claims[1].verdict, ClaimVerdict::Spurious);
/// assert_eq!(c.claims[2].verdict, ClaimVerdict::Spurious);
/// assert_eq!(c.nearest_claimed, Some(true));
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn classify(patch: &Patch, ray: &Ray, claims: &[Claim], tol: f64) -> Result<Classification> {
    classify_with(patch, ray, claims, tol, &RayOptions::default())
}

/// [`classify`] with options: the `t` range and the solver options apply;
/// the query is always all hits.
pub fn classify_with(
    patch: &Patch,
    ray: &Ray,
    claims: &[Claim],
    tol: f64,
    opts: &RayOptions,
) -> Result<Classification> {
    check_tol(tol)?;
    let opts = opts.clone().with_query(Query::All);
    let outcome = super::intersect(patch, ray, &opts)?;
    let complete = outcome.is_complete();
    let hits = outcome.hits().to_vec();
    let regions: Vec<Region<3>> = hits
        .iter()
        .map(|h| Region {
            bx: [h.bx.u, h.bx.v, h.bx.t],
            certified: h.is_certified(),
        })
        .collect();
    let points: Vec<[f64; 3]> = claims.iter().map(|c| [c.u, c.v, c.t]).collect();
    // tol·max(1, |t|) rounded up (NaN stays NaN: never confirmed).
    let tols: Vec<[f64; 3]> = claims
        .iter()
        .map(|c| [tol, tol, (point(tol) * point(c.t.abs().max(1.0))).sup()])
        .collect();
    let verdicts = referee_n(&points, &tols, &regions, complete);
    // Hits are sorted by t, certified or not: map the certified ones.
    let certified: Vec<usize> = (0..hits.len()).filter(|&k| hits[k].is_certified()).collect();
    let confirmed_of = |k: usize| {
        verdicts
            .iter()
            .any(|&(v, i)| v == ClaimVerdict::Confirmed && i == Some(k))
    };
    let missed_hits: Vec<usize> = missed(&verdicts, hits.len())
        .into_iter()
        .filter(|&k| hits[k].is_certified())
        .collect();
    let nearest_claimed = match (&outcome, complete) {
        (RayOutcome::Hits(h), true) => proven_nearest(h).map(confirmed_of),
        _ => None,
    };
    debug_assert!(certified.iter().all(|&k| confirmed_of(k) != missed_hits.contains(&k)));
    Ok(Classification {
        claims: claims
            .iter()
            .zip(verdicts)
            .map(|(&claim, (verdict, hit))| ClaimResult { claim, verdict, hit })
            .collect(),
        missed: missed_hits,
        nearest_claimed,
        complete,
        hits,
    })
}

/// The index of the proven nearest hit: the only candidate of
/// [`RayHits::nearest`], certified.
fn proven_nearest(h: &RayHits) -> Option<usize> {
    let near = h.nearest();
    match near.as_slice() {
        [one] if one.is_certified() => h.hits.iter().position(|x| std::ptr::eq(x, *one)),
        _ => None,
    }
}
