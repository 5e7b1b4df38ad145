//! The referee: claimed roots (from a heuristic solver, say) checked against
//! a certified solve, each with one verdict.
//!
//! # How a claim is decided
//! A claim is a point `c = (u, v)`; `tol` is a distance in the max-norm
//! (`|Δu|, |Δv| ≤ tol`). Against the regions of a certified solve — root
//! boxes, each holding exactly one root, and undecided regions — in the order
//! the claims are given:
//! * **confirmed** by a root box `B` when every point of `B` lies within `tol`
//!   of `c` (so the root in `B` does, whichever point of `B` it is), and no
//!   earlier claim confirmed `B`; among several such boxes the one nearest
//!   `c` is taken;
//! * **duplicate** when root boxes lie within `tol` of `c` that way but each
//!   was confirmed by an earlier claim;
//! * **spurious** when the solve is complete and no region at all (root box
//!   or undecided region) comes within `tol` of `c`: proven, there is no root
//!   within `tol`;
//! * **undecided** otherwise: `c` is within `tol` of an undecided region, of
//!   a root box only partly within `tol`, or the solve was incomplete.
//!
//! Every comparison is exact (the floats are compared as rationals), so a
//! verdict never depends on rounding.

use super::solution::{Box2, Solution};
use super::{solve, Domain, SolveOptions};
use crate::error::{Error, Result};
use crate::poly::Polynomial;
use num_rational::BigRational;
use std::cmp::Ordering;

/// What the referee says of one claim (module docs for the rules).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum ClaimVerdict {
    /// A certified root (hit) lies within `tol`, and no earlier claim took it.
    Confirmed,
    /// Only certified roots that earlier claims confirmed lie within `tol`.
    Duplicate,
    /// Proven: there is no root (hit) within `tol`.
    Spurious,
    /// Near an undecided region, or the solve was incomplete.
    Undecided,
}

impl ClaimVerdict {
    /// The stable machine-readable code: `"confirmed"`, `"duplicate"`,
    /// `"spurious"` or `"undecided"`.
    pub fn code(self) -> &'static str {
        match self {
            ClaimVerdict::Confirmed => "confirmed",
            ClaimVerdict::Duplicate => "duplicate",
            ClaimVerdict::Spurious => "spurious",
            ClaimVerdict::Undecided => "undecided",
        }
    }
}

/// A region of a certified answer: a box, and whether it is a certified root.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Region {
    pub(crate) bx: Box2,
    pub(crate) certified: bool,
}

/// The verdict of each claim (and the region that confirmed it or that it
/// duplicates), in the order given; `complete` is the solve's.
pub(crate) fn referee(
    claims: &[[f64; 2]],
    regions: &[Region],
    complete: bool,
    tol: f64,
) -> Vec<(ClaimVerdict, Option<usize>)> {
    let q = |x: f64| BigRational::from_float(x);
    let tol_q = q(tol);
    let mut taken = vec![false; regions.len()];
    claims
        .iter()
        .map(|&c| {
            let Some(tol_q) = &tol_q else {
                return (ClaimVerdict::Undecided, None);
            };
            // (far, near) distances of each region from c, exactly.
            let dist: Vec<Option<(BigRational, BigRational)>> = regions.iter().map(|r| distances(c, &r.bx)).collect();
            let within = |k: usize| regions[k].certified && dist[k].as_ref().is_some_and(|(far, _)| far <= tol_q);
            let near_key = |k: &usize| dist[*k].as_ref().map(|(_, near)| near.clone());
            let pick = |free: bool| {
                (0..regions.len())
                    .filter(|&k| within(k) && taken[k] != free)
                    .min_by(|a, b| near_key(a).cmp(&near_key(b)).then(a.cmp(b)))
            };
            if let Some(k) = pick(true) {
                taken[k] = true;
                return (ClaimVerdict::Confirmed, Some(k));
            }
            if let Some(k) = pick(false) {
                return (ClaimVerdict::Duplicate, Some(k));
            }
            let clear = dist
                .iter()
                .all(|d| d.as_ref().is_some_and(|(_, near)| near.cmp(tol_q) == Ordering::Greater));
            if complete && clear {
                (ClaimVerdict::Spurious, None)
            } else {
                (ClaimVerdict::Undecided, None)
            }
        })
        .collect()
}

/// The largest and the smallest max-norm distance from `c` to a point of the
/// closed box, exactly; `None` if something is not finite.
fn distances(c: [f64; 2], bx: &Box2) -> Option<(BigRational, BigRational)> {
    let q = |x: f64| BigRational::from_float(x);
    let zero = BigRational::from_integer(0.into());
    let mut far = zero.clone();
    let mut near = zero.clone();
    for (x, [lo, hi]) in [(c[0], bx.u), (c[1], bx.v)] {
        let (x, lo, hi) = (q(x)?, q(lo)?, q(hi)?);
        let below = &lo - &x;
        let above = &x - &hi;
        far = far.max((&x - &lo).max(&hi - &x));
        near = near.max(below.max(above).max(zero.clone()));
    }
    Some((far, near))
}

/// The referee's answer for a bivariate system.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct RootClassification {
    /// One verdict per claim, in the order given, with the index (into
    /// `solution.roots`) of the root that confirmed it or that it duplicates.
    pub claims: Vec<(ClaimVerdict, Option<usize>)>,
    /// The indices (into `solution.roots`) of certified roots no claim
    /// confirmed.
    pub missed: Vec<usize>,
    /// The certified solve the claims were judged against.
    pub solution: Solution,
}

/// Checks claimed roots `(u, v)` of `f = g = 0` on `domain` against a
/// certified solve (see the module docs for the rules; `tol` in the
/// max-norm, `1e-8` is a good default). Errors: those of [`solve`], and a
/// `tol` that is negative or not finite ([`Error::InvalidOption`]).
///
/// ```
/// use rootclip::solve::{classify_roots, ClaimVerdict, Domain, SolveOptions};
/// let f = rootclip::parse_polynomial("u - v")?;
/// let g = rootclip::parse_polynomial("u + v - 1/2")?; // one root, (1/4, 1/4)
/// let claims = [[0.25, 0.25 + 1e-10], [0.25, 0.25], [0.6, 0.1]];
/// let c = classify_roots(&f, &g, Domain::Triangle, &claims, 1e-8, &SolveOptions::default())?;
/// let verdicts: Vec<_> = c.claims.iter().map(|x| x.0).collect();
/// assert_eq!(verdicts, [ClaimVerdict::Confirmed, ClaimVerdict::Duplicate, ClaimVerdict::Spurious]);
/// assert!(c.missed.is_empty());
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn classify_roots(
    f: &Polynomial,
    g: &Polynomial,
    domain: Domain,
    claims: &[[f64; 2]],
    tol: f64,
    opts: &SolveOptions,
) -> Result<RootClassification> {
    check_tol(tol)?;
    let solution = solve(f, g, domain, opts)?;
    let regions: Vec<Region> = solution
        .roots
        .iter()
        .map(|r| Region {
            bx: r.bx,
            certified: true,
        })
        .chain(solution.clusters.iter().map(|c| Region {
            bx: c.bx,
            certified: false,
        }))
        .chain(solution.leftovers.iter().map(|l| Region {
            bx: l.bx,
            certified: false,
        }))
        .collect();
    let claims = referee(claims, &regions, solution.complete, tol);
    let missed = missed(&claims, solution.roots.len());
    Ok(RootClassification {
        claims,
        missed,
        solution,
    })
}

/// The certified regions `0..certified` no claim confirmed.
pub(crate) fn missed(claims: &[(ClaimVerdict, Option<usize>)], certified: usize) -> Vec<usize> {
    let mut hit = vec![false; certified];
    for (v, k) in claims {
        if let (ClaimVerdict::Confirmed, Some(k)) = (v, k) {
            if *k < certified {
                hit[*k] = true;
            }
        }
    }
    (0..certified).filter(|&k| !hit[k]).collect()
}

/// `tol` must be a non-negative finite number.
pub(crate) fn check_tol(tol: f64) -> Result<()> {
    if tol.is_finite() && tol >= 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidOption(format!(
            "tol must be a non-negative finite number, got {tol}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region(u: [f64; 2], v: [f64; 2], certified: bool) -> Region {
        Region {
            bx: Box2::new(u, v),
            certified,
        }
    }

    #[test]
    fn rules_by_hand() {
        let t = 2f64.powi(-27);
        let regions = [
            region([0.5, 0.5], [0.5, 0.5], true),
            region([0.25, 0.25 + 4.0 * t], [0.25, 0.25], true),
            region([0.75, 0.75 + 1e-4], [0.125, 0.125 + 1e-4], false),
        ];
        let v = |claims: &[[f64; 2]], complete| -> Vec<ClaimVerdict> {
            referee(claims, &regions, complete, t)
                .into_iter()
                .map(|x| x.0)
                .collect()
        };
        use ClaimVerdict::*;
        // Within tol (exactly tol away counts), again (duplicate), a hair
        // beyond (spurious), near the undecided region, and a box only partly
        // within tol (undecided).
        assert_eq!(
            v(
                &[
                    [0.5 + t, 0.5 - t],
                    [0.5, 0.5],
                    [0.5 + 2.0 * t, 0.5],
                    [0.75 + 1e-4 + 0.5 * t, 0.125],
                    [0.25, 0.25]
                ],
                true
            ),
            [Confirmed, Duplicate, Spurious, Undecided, Undecided]
        );
        // The nearer of two boxes within tol is taken first, the other next.
        let pair = [
            region([0.5, 0.5], [0.5, 0.5], true),
            region([0.5 + t, 0.5 + t], [0.5, 0.5], true),
        ];
        let r = referee(&[[0.5 + t, 0.5], [0.5, 0.5], [0.5, 0.5]], &pair, true, t);
        assert_eq!(r, [(Confirmed, Some(1)), (Confirmed, Some(0)), (Duplicate, Some(0))]);
        // An incomplete solve proves nothing spurious; NaN is never confirmed.
        assert_eq!(v(&[[0.1, 0.1]], false), [Undecided]);
        assert_eq!(v(&[[f64::NAN, 0.5]], true), [Undecided]);
    }
}
