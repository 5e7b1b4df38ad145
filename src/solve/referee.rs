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
use num_traits::Signed;

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

/// A region of a certified answer: a box in `N` coordinates, and whether
/// it is a certified root.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Region<const N: usize = 2> {
    pub(crate) bx: [[f64; 2]; N],
    pub(crate) certified: bool,
}

impl Region {
    /// A region of a bivariate solve.
    pub(crate) fn of_box(bx: Box2, certified: bool) -> Self {
        Region {
            bx: [bx.u, bx.v],
            certified,
        }
    }
}

/// The verdict of each claim (and the region that confirmed it or that it
/// duplicates), in the order given; `complete` is the solve's. Each claim
/// carries its own tolerances per coordinate (`tol[k][c]` for claim `k`,
/// coordinate `c`): "within tolerance" means `|Δx_c| ≤ tol_c` in every
/// coordinate, decided exactly.
pub(crate) fn referee_n<const N: usize>(
    claims: &[[f64; N]],
    tols: &[[f64; N]],
    regions: &[Region<N>],
    complete: bool,
) -> Vec<(ClaimVerdict, Option<usize>)> {
    let mut taken = vec![false; regions.len()];
    claims
        .iter()
        .zip(tols)
        .map(|(c, tol)| {
            let Some(tol_q) = tol
                .iter()
                .map(|&t| BigRational::from_float(t))
                .collect::<Option<Vec<_>>>()
            else {
                return (ClaimVerdict::Undecided, None);
            };
            // Per region: (every point within tol, some point within tol,
            // scaled distance of the nearest point), exactly.
            let dist: Vec<Option<Distances>> = regions.iter().map(|r| distances(c, &r.bx, &tol_q)).collect();
            let within = |k: usize| regions[k].certified && dist[k].as_ref().is_some_and(|d| d.all_within);
            let near_key = |k: &usize| dist[*k].as_ref().map(|d| d.near.clone());
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
            let clear = dist.iter().all(|d| d.as_ref().is_some_and(|d| !d.some_within));
            if complete && clear {
                (ClaimVerdict::Spurious, None)
            } else {
                (ClaimVerdict::Undecided, None)
            }
        })
        .collect()
}

/// [`referee_n`] for points `(u, v)` with one tolerance `tol` (max-norm).
pub(crate) fn referee(
    claims: &[[f64; 2]],
    regions: &[Region],
    complete: bool,
    tol: f64,
) -> Vec<(ClaimVerdict, Option<usize>)> {
    referee_n(claims, &vec![[tol; 2]; claims.len()], regions, complete)
}

/// How a closed box lies around a claim, exactly.
struct Distances {
    /// Every point of the box is within tolerance of the claim.
    all_within: bool,
    /// Some point of the box is.
    some_within: bool,
    /// The largest of the per-coordinate gaps from the claim to the box,
    /// each divided by its tolerance (`0` inside; ranks the boxes within
    /// tolerance).
    near: BigRational,
}

/// How the closed box `bx` lies around the claim `c` with tolerances `tol`;
/// `None` if a number is not finite.
fn distances<const N: usize>(c: &[f64; N], bx: &[[f64; 2]; N], tol: &[BigRational]) -> Option<Distances> {
    let q = |x: f64| BigRational::from_float(x);
    let zero = BigRational::from_integer(0.into());
    let mut out = Distances {
        all_within: true,
        some_within: true,
        near: zero.clone(),
    };
    for ((&x, &[lo, hi]), tol) in c.iter().zip(bx).zip(tol) {
        let (x, lo, hi) = (q(x)?, q(lo)?, q(hi)?);
        let far = (&x - &lo).max(&hi - &x);
        let near = (&lo - &x).max(&x - &hi).max(zero.clone());
        out.all_within &= far <= *tol;
        out.some_within &= near <= *tol;
        // (At tolerance 0 a box with a gap is never picked: no ranking.)
        let scaled = if tol.is_positive() { &near / tol } else { near };
        out.near = out.near.max(scaled);
    }
    Some(out)
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
        .map(|r| Region::of_box(r.bx, true))
        .chain(solution.clusters.iter().map(|c| Region::of_box(c.bx, false)))
        .chain(solution.leftovers.iter().map(|l| Region::of_box(l.bx, false)))
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
        Region::of_box(Box2::new(u, v), certified)
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
