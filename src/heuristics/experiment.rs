//! Park, Ji & Ko's (2013) experiment, refereed: Examples 1–3 (
//! §6) — a bicubic patch, a ray, 121 starts — with every method's end
//! point judged by the certified solver ([`crate::ray::classify_with`]),
//! never by its distance to a printed root.
//!
//! # The examples
//! Each surface is a B-spline of order 4 on the knots `{0,0,0,0,1,1,1,1}`
//! in `u` and `v`, i.e. a bicubic Bézier patch, built here as a
//! [`TensorPatch`] with the control points in the paper's order, row-major
//! (`P_ij` at `4i + j`, `i` along `u`; this is the reading that puts the
//! printed roots of Examples 1 and 2 at the printed `(u, v)` rather than at
//! `(v, u)`).
//! 1. Rows `z = −5, −1, 1, 5`, each `(0, 0), (1, 3), (2, 3), (3, 0)` in
//!    `(x, y)`; the ray `o = (5, 2, 2)`, `d = (−1, −0.5, 0.3)`: one hit.
//! 2. The same, but the rows `z = ±5` flat: `(0, 0), (1, 0), (2, 0), (3, 0)`;
//!    the ray `o = (5, 2, 0)`, `d = (−10, −3, 1)`: two hits, the nearer at
//!    the printed `(0.529890614, 0.769592159)`.
//! 3. Example 1's surface and the ray `o = (5, 2.25, 0)`, `d = (−1, 0, 0)`,
//!    tangent to it at `(½, ½)`: there `y = 9v(1 − v)` peaks at 2.25 and
//!    `z(½) = 0`, so the ray touches the ridge at `t = 3.5`, a double root
//!    the certified solver reports as undecided.
//!
//! # Verdicts
//! Every end point of one ray is a claim `(u, v, t)` for
//! [`classify_with`] (tolerance [`REFEREE_TOL`] in `(u, v)`, relative in `t`), all claims of
//! a ray in one call: a claim `confirmed` or `duplicate` (a later start
//! finding the same hit) has a certified hit within the tolerance. Then:
//! * [`Verdict::Correct`]: that hit is the proven nearest one (the only
//!   candidate of [`RayHits::nearest`](crate::ray::RayHits::nearest));
//! * [`Verdict::WrongHit`]: a certified hit that is provably not the
//!   nearest (another certified hit ends before it begins);
//! * [`Verdict::NotAHit`]: `spurious` — proven, no hit in the `t` range
//!   within the tolerance (a point off the surface, or behind the origin);
//! * [`Verdict::Undecided`]: the referee cannot tell — the claim lies near
//!   an undecided region (reason `"near_undecided_region"`, e.g. Example
//!   3's tangential hit), or at a certified hit that may or may not be the
//!   nearest because an undecided region may lie in front of it
//!   (`"nearest_not_proven"`);
//! * [`Verdict::Failed`]: the iteration returned no point (reason: the
//!   [`Failure`] code).

use super::iteration::{iterate, End, Failure, IterOptions, Iteration, Outcome};
use crate::error::{Error, Result};
use crate::ray::{classify_with, Claim, Hit, Patch, Ray, RayHits, RayOptions, TensorPatch};
use crate::solve::ClaimVerdict;
use glam::DVec3;

/// The claim tolerance in `(u, v)` (max-norm) handed to the referee.
pub const REFEREE_TOL: f64 = 1e-8;

/// One of the paper's examples: its patch and its ray.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Example {
    /// 1, 2 or 3.
    pub number: u8,
    /// The bicubic patch (module docs).
    pub patch: Patch,
    /// The ray.
    pub ray: Ray,
}

/// Example `n` of the paper (module docs). Errors: `n` not 1, 2 or 3
/// ([`Error::InvalidOption`]).
///
/// ```
/// use rootclip::heuristics::experiment::example;
/// let ex = example(2)?;
/// assert_eq!(ex.patch.points().len(), 16);
/// assert!(example(4).is_err());
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn example(n: u8) -> Result<Example> {
    let full = [(0.0, 0.0), (1.0, 3.0), (2.0, 3.0), (3.0, 0.0)];
    let flat = [(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)];
    let (rows, origin, dir) = match n {
        1 => ([full; 4], DVec3::new(5.0, 2.0, 2.0), DVec3::new(-1.0, -0.5, 0.3)),
        2 => (
            [flat, full, full, flat],
            DVec3::new(5.0, 2.0, 0.0),
            DVec3::new(-10.0, -3.0, 1.0),
        ),
        3 => ([full; 4], DVec3::new(5.0, 2.25, 0.0), DVec3::new(-1.0, 0.0, 0.0)),
        _ => {
            return Err(Error::InvalidOption(format!(
                "Park, Ji & Ko (2013) has Examples 1, 2 and 3, not {n}"
            )))
        }
    };
    let points = rows
        .iter()
        .zip([-5.0, -1.0, 1.0, 5.0])
        .flat_map(|(row, z)| row.iter().map(move |&(x, y)| DVec3::new(x, y, z)))
        .collect();
    Ok(Example {
        number: n,
        patch: TensorPatch::new(3, 3, points, None)?.into(),
        ray: Ray::new(origin, dir)?,
    })
}

/// The `k × k` grid of starts `(i/(k−1), j/(k−1))` on `[0, 1]²`, `u` outer
/// (`k ≥ 2`); `grid_starts(11)` is the paper's 121 starts `0, 0.1, …, 1`.
pub fn grid_starts(k: usize) -> Vec<[f64; 2]> {
    let k = k.max(2);
    let at = |i: usize| i as f64 / (k - 1) as f64;
    (0..k).flat_map(|i| (0..k).map(move |j| [at(i), at(j)])).collect()
}

/// What the referee says about one end point (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum Verdict {
    /// The proven nearest certified hit.
    Correct,
    /// A certified hit, provably not the nearest.
    WrongHit,
    /// Proven: no hit within the tolerance.
    NotAHit,
    /// The referee cannot decide.
    Undecided,
    /// The iteration returned no point.
    Failed,
}

impl Verdict {
    /// The stable machine-readable code: `"correct"`, `"wrong_hit"`,
    /// `"not_a_hit"`, `"undecided"` or `"failed"`.
    pub fn code(self) -> &'static str {
        match self {
            Verdict::Correct => "correct",
            Verdict::WrongHit => "wrong_hit",
            Verdict::NotAHit => "not_a_hit",
            Verdict::Undecided => "undecided",
            Verdict::Failed => "failed",
        }
    }
}

/// The referee's answer for the end points of several iterations on one
/// ray.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Judgement {
    /// Per outcome: the verdict and its reason code (a [`Failure`] code, or
    /// why it is undecided; `None` otherwise).
    pub verdicts: Vec<(Verdict, Option<&'static str>)>,
    /// Per outcome: the index into `hits` of the certified hit it found.
    pub found: Vec<Option<usize>>,
    /// Every hit of the ray in the range, certified or not, sorted by `t`.
    pub hits: Vec<Hit>,
    /// The index of the proven nearest hit, if proven.
    pub nearest: Option<usize>,
}

/// Judges the end points of `outcomes` (of iterations on `ray` and `patch`)
/// against the certified all-hits answer with `opts`' `t` range and solver
/// options (module docs for the rules).
///
/// Errors: as [`classify_with`].
pub fn judge(patch: &Patch, ray: &Ray, outcomes: &[Outcome], opts: &RayOptions) -> Result<Judgement> {
    let claims: Vec<Claim> = outcomes
        .iter()
        .filter_map(|o| o.end.map(|e| Claim { u: e.u, v: e.v, t: e.t }))
        .collect();
    let c = classify_with(patch, ray, &claims, REFEREE_TOL, opts)?;
    let ray_hits = RayHits {
        complete: c.complete,
        hits: c.hits,
    };
    let candidates: Vec<usize> = ray_hits
        .nearest()
        .into_iter()
        .filter_map(|h| ray_hits.hits.iter().position(|x| std::ptr::eq(x, h)))
        .collect();
    let nearest = match candidates.as_slice() {
        [k] if c.complete && ray_hits.hits[*k].is_certified() => Some(*k),
        _ => None,
    };
    let mut verdicts = Vec::with_capacity(outcomes.len());
    let mut found = Vec::with_capacity(outcomes.len());
    let mut claim = c.claims.iter();
    for o in outcomes {
        let Some(_) = o.end else {
            found.push(None);
            let failure = o.failure.unwrap_or(Failure::NoConvergence);
            verdicts.push((Verdict::Failed, Some(failure.code())));
            continue;
        };
        let r = claim.next().expect("one verdict per claim");
        let (cv, hit) = (r.verdict, r.hit);
        found.push(match cv {
            ClaimVerdict::Confirmed | ClaimVerdict::Duplicate => hit,
            _ => None,
        });
        verdicts.push(match (cv, hit) {
            (ClaimVerdict::Confirmed | ClaimVerdict::Duplicate, Some(k)) => {
                if nearest == Some(k) {
                    (Verdict::Correct, None)
                } else if nearest.is_some() || !candidates.contains(&k) {
                    (Verdict::WrongHit, None)
                } else {
                    (Verdict::Undecided, Some("nearest_not_proven"))
                }
            }
            (ClaimVerdict::Spurious, _) => (Verdict::NotAHit, None),
            _ => (Verdict::Undecided, Some("near_undecided_region")),
        });
    }
    Ok(Judgement {
        verdicts,
        found,
        hits: ray_hits.hits,
        nearest,
    })
}

/// One run of the experiment: a method from a start, where it ended, and
/// the verdict. JSON (feature `serde`): `{"method", "start", "end":
/// {"u", "v", "t"} | null, "iterations", "verdict", "reason"}`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Run {
    /// The iteration.
    pub method: Iteration,
    /// `(u₀, v₀)`.
    pub start: [f64; 2],
    /// The converged point, if any.
    pub end: Option<End>,
    /// Steps taken.
    pub iterations: usize,
    /// The referee's verdict.
    pub verdict: Verdict,
    /// The failure code for [`Verdict::Failed`], why for
    /// [`Verdict::Undecided`], else `None`.
    pub reason: Option<&'static str>,
}

/// Every method of `methods` from every start of `starts` on `ray` and
/// `patch`, judged ([`judge`], one certified solve per call): the runs
/// method by method, starts in order.
///
/// Errors: as [`judge`].
pub fn run_starts(
    patch: &Patch,
    ray: &Ray,
    methods: &[Iteration],
    starts: &[[f64; 2]],
    opts: &IterOptions,
    ray_opts: &RayOptions,
) -> Result<Vec<Run>> {
    let mut plan = Vec::with_capacity(methods.len() * starts.len());
    for &m in methods {
        for &s in starts {
            plan.push((m, s, iterate(m, patch, ray, s, opts)));
        }
    }
    let outcomes: Vec<Outcome> = plan.iter().map(|p| p.2).collect();
    let j = judge(patch, ray, &outcomes, ray_opts)?;
    Ok(plan
        .into_iter()
        .zip(j.verdicts)
        .map(|((method, start, o), (verdict, reason))| Run {
            method,
            start,
            end: o.end,
            iterations: o.iterations,
            verdict,
            reason,
        })
        .collect())
}

/// Example `n`'s experiment as the paper ran it: the 121 starts
/// ([`grid_starts`]`(11)`) with all four methods, judged on the ray
/// (`t ≥ 0`).
///
/// Errors: an unknown example ([`Error::InvalidOption`]), options that do
/// not validate ([`IterOptions::validate`]).
///
/// ```
/// use rootclip::heuristics::experiment::{run_example, Verdict};
/// use rootclip::heuristics::{IterOptions, Iteration};
/// let runs = run_example(1, &IterOptions::default())?;
/// assert_eq!(runs.len(), 4 * 121);
/// let correct = |m| runs.iter().filter(|r| r.method == m && r.verdict == Verdict::Correct).count();
/// assert!(correct(Iteration::SecondOrder) > correct(Iteration::Newton));
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn run_example(n: u8, opts: &IterOptions) -> Result<Vec<Run>> {
    opts.validate()?;
    let ex = example(n)?;
    run_starts(
        &ex.patch,
        &ex.ray,
        &Iteration::ALL,
        &grid_starts(11),
        opts,
        &RayOptions::default(),
    )
}

/// Success counts of one method over a set of runs.
///
/// JSON (feature `serde`): `{"method", "runs", "correct", "wrong_hit",
/// "not_a_hit", "undecided", "failed", "mean_iterations"}`, the last
/// `null` when no run is correct.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(into = "TallyRepr", from = "TallyRepr")
)]
pub struct Tally {
    /// The method.
    pub method: Iteration,
    /// Runs of this method.
    pub runs: usize,
    /// Runs per verdict, in the order of [`Verdict`]'s variants:
    /// correct, wrong hit, not a hit, undecided, failed.
    pub counts: [usize; 5],
    /// Mean iterations of the correct runs (`NaN` if none).
    pub mean_iterations: f64,
}

/// [`Tally`] as written and read.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
struct TallyRepr {
    method: Iteration,
    runs: usize,
    correct: usize,
    wrong_hit: usize,
    not_a_hit: usize,
    undecided: usize,
    failed: usize,
    mean_iterations: Option<f64>,
}

#[cfg(feature = "serde")]
impl From<Tally> for TallyRepr {
    fn from(t: Tally) -> Self {
        let [correct, wrong_hit, not_a_hit, undecided, failed] = t.counts;
        TallyRepr {
            method: t.method,
            runs: t.runs,
            correct,
            wrong_hit,
            not_a_hit,
            undecided,
            failed,
            mean_iterations: t.mean_iterations.is_finite().then_some(t.mean_iterations),
        }
    }
}

#[cfg(feature = "serde")]
impl From<TallyRepr> for Tally {
    fn from(t: TallyRepr) -> Self {
        Tally {
            method: t.method,
            runs: t.runs,
            counts: [t.correct, t.wrong_hit, t.not_a_hit, t.undecided, t.failed],
            mean_iterations: t.mean_iterations.unwrap_or(f64::NAN),
        }
    }
}

/// The [`Tally`] of each method of `methods` over `runs`.
pub fn tally(runs: &[Run], methods: &[Iteration]) -> Vec<Tally> {
    methods
        .iter()
        .map(|&m| {
            let mine: Vec<&Run> = runs.iter().filter(|r| r.method == m).collect();
            let mut counts = [0; 5];
            for r in &mine {
                counts[verdict_index(r.verdict)] += 1;
            }
            let correct: Vec<&&Run> = mine.iter().filter(|r| r.verdict == Verdict::Correct).collect();
            let mean = correct.iter().map(|r| r.iterations as f64).sum::<f64>() / correct.len() as f64;
            Tally {
                method: m,
                runs: mine.len(),
                counts,
                mean_iterations: mean,
            }
        })
        .collect()
}

fn verdict_index(v: Verdict) -> usize {
    match v {
        Verdict::Correct => 0,
        Verdict::WrongHit => 1,
        Verdict::NotAHit => 2,
        Verdict::Undecided => 3,
        Verdict::Failed => 4,
    }
}

/// `n` rays for the at-scale run on `patch` with parameters on `[0, 1]²`:
/// each aimed at `P = S(a, b)`, `a, b` uniform on `[0, 1]`, from
/// `o = P + (U(2, 6), U(−3, 3), U(−3, 3))`, direction `P − o` (so `t = 1`
/// is a hit, up to rounding), drawn from the crate's xorshift stream
/// (`internals::Rng`) with `seed` (non-zero) in the order `a, b, Δx, Δy,
/// Δz` per ray.
/// Not part of the API: re-exported from `internals` for the example and
/// the bench.
#[cfg(feature = "internals")]
#[doc(hidden)]
pub fn at_scale_rays(patch: &Patch, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = crate::rng::Rng(seed.max(1));
    let mut rays = Vec::with_capacity(n);
    while rays.len() < n {
        let (a, b) = (rng.next_f64(), rng.next_f64());
        let p = patch.eval(a, b);
        let off = DVec3::new(
            2.0 + 4.0 * rng.next_f64(),
            3.0 * rng.next_signed(),
            3.0 * rng.next_signed(),
        );
        let o = p + off;
        // |P − o| ≥ 2 up to rounding: never zero; skipped all the same if it were.
        if let Ok(r) = Ray::new(o, p - o) {
            rays.push(r);
        }
    }
    rays
}
