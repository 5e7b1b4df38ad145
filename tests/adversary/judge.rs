//! The judge ([`judge`]): runs `intersect` on a case and checks the answer
//! against the referee's [`Truth`], every membership decided exactly; each
//! broken promise is a [`Fault`] in the case's [`Verdict`]. And a
//! human-readable [`report`] of a judged case, with the command that
//! replays it.

use super::case::Case;
use super::exact::qf;
use super::surface::Surface;
use super::truth::Truth;
use rootclip::glam::DVec3;
use rootclip::ray::{intersect, Degeneracy, Hit, Patch, Ray, RayOptions, RayOutcome};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

/// A broken promise; see "What is checked" in the adversary's docs (`mod.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Fault {
    Miss,
    MissT,
    Phantom,
    Multiple,
    Tangent,
    TBox,
    Duplicate,
    Domain,
    ZeroEquation,
    Error,
}

impl Fault {
    pub const ALL: [Fault; 10] = [
        Fault::Miss,
        Fault::MissT,
        Fault::Phantom,
        Fault::Multiple,
        Fault::Tangent,
        Fault::TBox,
        Fault::Duplicate,
        Fault::Domain,
        Fault::ZeroEquation,
        Fault::Error,
    ];

    /// A broken promise of the contract: every fault but `ZeroEquation`, an
    /// honest "no hit list" that is only suspicious on these non-planar
    /// patches (the library may call an equation zero when every coefficient
    /// enclosure holds 0, e.g. a B-spline net widened by its knot-insertion
    /// error on a nearly flat patch).
    pub fn breaks_contract(self) -> bool {
        self != Fault::ZeroEquation
    }

    pub fn name(self) -> &'static str {
        match self {
            Fault::Miss => "miss",
            Fault::MissT => "miss-t",
            Fault::Phantom => "phantom",
            Fault::Multiple => "multiple",
            Fault::Tangent => "tangent",
            Fault::TBox => "t-box",
            Fault::Duplicate => "duplicate",
            Fault::Domain => "domain",
            Fault::ZeroEquation => "zero-equation",
            Fault::Error => "error",
        }
    }
}

/// What the library answered, in kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    Complete,
    Incomplete,
    Unresolved,
    ZeroEquation,
    Error,
}

/// The judgement of one case.
#[derive(Clone, Debug)]
pub struct Verdict {
    pub answer: Answer,
    /// True hits with `t ≥ 0`.
    pub roots: usize,
    pub certified: usize,
    pub undecided: usize,
    /// The truth is a curve of hits (not judged).
    pub degenerate: bool,
    /// True hits with `t ≥ 0` within `1e-12` of an edge or knot line (or on it).
    pub near_feature: usize,
    pub faults: Vec<(Fault, String)>,
    pub hits: Vec<Hit>,
    /// The truth, `(u, v, t)` rounded, for reports.
    pub truth: Vec<[f64; 3]>,
    /// Time in `intersect`.
    pub time: Duration,
}

impl Verdict {
    /// Some fault breaks the contract ([`Fault::breaks_contract`]).
    pub fn fails(&self) -> bool {
        self.faults.iter().any(|f| f.0.breaks_contract())
    }
}

/// The case's patch and ray, as rootclip takes them.
pub fn patch_and_ray(case: &Case) -> (Patch, Ray) {
    let patch = Patch::from_spec(&case.spec).expect("adversary: a valid patch");
    let ray = Ray::new(DVec3::from_array(case.origin), DVec3::from_array(case.dir)).expect("a valid ray");
    (patch, ray)
}

/// Runs `intersect` on the case and judges its answer against the referee.
pub fn judge(case: &Case) -> Verdict {
    let truth = Truth::of(case);
    let (patch, ray) = patch_and_ray(case);
    let start = Instant::now();
    let out = intersect(&patch, &ray, &RayOptions::default());
    let time = start.elapsed();
    judge_outcome(case, &truth, out, time)
}

fn describe(h: &Hit) -> String {
    format!(
        "{:?} u {:?} v {:?} t {:?}",
        h.status,
        h.bx.u.map(|x| format!("{x:e}")),
        h.bx.v.map(|x| format!("{x:e}")),
        h.bx.t.map(|x| format!("{x:e}"))
    )
}

pub(super) fn judge_outcome(case: &Case, truth: &Truth, out: rootclip::Result<RayOutcome>, time: Duration) -> Verdict {
    let in_range: Vec<bool> = truth
        .roots
        .iter()
        .map(|r| truth.in_t(r, [0.0, f64::INFINITY]))
        .collect();
    let mut v = Verdict {
        answer: Answer::Complete,
        roots: in_range.iter().filter(|x| **x).count(),
        certified: 0,
        undecided: 0,
        degenerate: truth.degenerate,
        near_feature: 0,
        faults: Vec::new(),
        hits: Vec::new(),
        truth: Vec::new(),
        time,
    };
    let (hits, complete) = match out {
        Err(e) => {
            v.answer = Answer::Error;
            v.faults.push((Fault::Error, e.to_string()));
            return v;
        }
        Ok(RayOutcome::Hits(h)) => {
            v.answer = if h.complete {
                Answer::Complete
            } else {
                Answer::Incomplete
            };
            (h.hits, h.complete)
        }
        Ok(RayOutcome::Degenerate(Degeneracy::Unresolved(h))) => {
            v.answer = Answer::Unresolved;
            (h.hits, false)
        }
        Ok(RayOutcome::Degenerate(_)) => {
            v.answer = Answer::ZeroEquation;
            if !truth.degenerate {
                v.faults.push((Fault::ZeroEquation, "on a non-planar patch".into()));
            }
            (Vec::new(), false)
        }
    };
    if truth.degenerate {
        v.hits = hits;
        return v;
    }
    let surf = Surface::of(case);
    v.near_feature = (truth.roots.iter().zip(&in_range))
        .filter(|(r, ok)| **ok && surf.feature_distance(truth.uvt(r, 64)) < 1e-12)
        .count();
    let root_name = |k: usize| format!("true hit {k} (u, v, t) ≈ {:?}", truth.uvt(&truth.roots[k], 120));
    let mut claimed: Vec<Option<usize>> = vec![None; truth.roots.len()];
    for (k, h) in hits.iter().enumerate() {
        if !surf.contains(&qf(h.u), &qf(h.v)) {
            v.faults
                .push((Fault::Domain, format!("hit {k} at ({:e}, {:e})", h.u, h.v)));
        }
        if !h.is_certified() {
            v.undecided += 1;
            continue;
        }
        v.certified += 1;
        let inside: Vec<usize> = (0..truth.roots.len())
            .filter(|&r| truth.in_uv(&truth.roots[r], &h.bx))
            .collect();
        match inside[..] {
            [] => v.faults.push((
                Fault::Phantom,
                format!("certified hit {k}, {}, holds no true hit", describe(h)),
            )),
            [r] => {
                if !truth.transversal[r] {
                    let what = format!(
                        "certified hit {k}, {}, holds {}, a tangency or crease touch",
                        describe(h),
                        root_name(r)
                    );
                    v.faults.push((Fault::Tangent, what));
                }
                if !truth.in_t(&truth.roots[r], h.bx.t) || !in_range[r] {
                    let what = format!(
                        "certified hit {k}, {}: {} not in its t box / t ≥ 0",
                        describe(h),
                        root_name(r)
                    );
                    v.faults.push((Fault::TBox, what));
                }
                if let Some(other) = claimed[r] {
                    let what = format!("certified hits {other} and {k} both hold {}", root_name(r));
                    v.faults.push((Fault::Duplicate, what));
                }
                claimed[r] = Some(k);
            }
            _ => v
                .faults
                .push((Fault::Multiple, format!("certified hit {k} holds true hits {inside:?}"))),
        }
    }
    if complete {
        for (r, root) in truth.roots.iter().enumerate().filter(|(r, _)| in_range[*r]) {
            let uv: Vec<&Hit> = hits.iter().filter(|h| truth.in_uv(root, &h.bx)).collect();
            if uv.is_empty() {
                v.faults.push((Fault::Miss, format!("{} in no hit box", root_name(r))));
            } else if !uv.iter().any(|h| truth.in_t(root, h.bx.t)) {
                v.faults
                    .push((Fault::MissT, format!("{} in no covering hit's t box", root_name(r))));
            }
        }
    }
    v.hits = hits;
    if !v.faults.is_empty() {
        v.truth = truth.roots.iter().map(|r| truth.uvt(r, 120)).collect();
    }
    v
}

/// A human-readable account of a judged case: label, truth, answer, faults,
/// and how to replay it.
pub fn report(case: &Case, v: &Verdict, patch_path: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# {} seed {:#x}: {}", case.family.name(), case.seed, case.label);
    let _ = writeln!(s, "# answer {:?}, {} true hit(s) with t ≥ 0:", v.answer, v.roots);
    for (k, r) in v.truth.iter().enumerate() {
        let _ = writeln!(s, "#   true hit {k}: (u, v, t) ≈ {r:?}");
    }
    for (k, h) in v.hits.iter().enumerate() {
        let _ = writeln!(s, "#   reported {k}: {}", describe(h));
    }
    for (f, what) in &v.faults {
        let _ = writeln!(s, "# FAULT {}: {what}", f.name());
    }
    let _ = writeln!(s, "{}", case.command(patch_path));
    s
}
