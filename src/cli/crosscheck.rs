//! `rootclip crosscheck`: claimed hits of a fast solver refereed by the
//! certified one ([`crate::ray::classify`]).
//!
//! CLAIMS.txt: one claim per line, `ray_index u v t` (`ray_index` 0-based into
//! RAYS.txt, `t` for the direction as given; any number of claims per ray,
//! none allowed; blank lines and `#` comments skipped). JSON out:
//! `{"schema_version": 1, "rays": [{"claims": [{"u", "v", "t", "verdict"}],
//! "missed": [{"u", "v", "t"}], "nearest_claimed": bool|null, "complete"}],
//! "summary": {"claims", "confirmed", "duplicate", "spurious", "undecided",
//! "missed", "true_hits"}}`, rays in input order, claims in file order.

use super::input::read_input;
use super::output::Answer;
use super::ray::{parse_patch, parse_rays};
use crate::error::{Error, Result};
use crate::ray::{classify_with, Claim, Classification, RayOptions};
use crate::solve::ClaimVerdict;
use rayon::prelude::*;
use serde::Serialize;

/// Arguments of `rootclip crosscheck`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct CrosscheckArgs {
    /// PATCH.json ("-" for stdin), as for "rootclip ray".
    #[arg(long)]
    patch: String,
    /// RAYS.txt ("-" for stdin): one ray per line, "ox oy oz dx dy dz".
    #[arg(long)]
    rays: String,
    /// CLAIMS.txt ("-" for stdin): one claim per line, "ray_index u v t".
    #[arg(long)]
    claims: String,
    /// A claim is confirmed when a certified hit's whole (u, v, t) box lies within this tolerance of it (t relative to max(1, |t|)).
    #[arg(long, default_value_t = 1e-8)]
    tol: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct ClaimJson {
    u: f64,
    v: f64,
    t: f64,
    verdict: ClaimVerdict,
}

#[derive(Serialize)]
struct PointJson {
    u: f64,
    v: f64,
    t: f64,
}

#[derive(Serialize)]
struct RayJson {
    claims: Vec<ClaimJson>,
    missed: Vec<PointJson>,
    nearest_claimed: Option<bool>,
    complete: bool,
}

#[derive(Serialize, Default)]
struct Summary {
    claims: usize,
    confirmed: usize,
    duplicate: usize,
    spurious: usize,
    undecided: usize,
    missed: usize,
    true_hits: usize,
}

#[derive(Serialize)]
struct Report {
    rays: Vec<RayJson>,
    summary: Summary,
}

pub(super) fn run(args: &CrosscheckArgs) -> Result<Answer> {
    let stdin_users = [&args.patch, &args.rays, &args.claims]
        .iter()
        .filter(|p| p.as_str() == "-")
        .count();
    if stdin_users > 1 {
        return Err(Error::InvalidOption(
            "only one of --patch, --rays, --claims can read standard input".into(),
        ));
    }
    let patch = parse_patch(&read_input(&args.patch)?)?;
    let rays = parse_rays(&read_input(&args.rays)?)?;
    let claims = parse_claims(&read_input(&args.claims)?, rays.len())?;
    let opts = RayOptions::default();
    crate::solve::referee::check_tol(args.tol)?;
    let bar = indicatif::ProgressBar::new(rays.len() as u64);
    if rays.len() < 1000 {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let results = rays
        .par_iter()
        .zip(&claims)
        .map(|(ray, c)| {
            let out = classify_with(&patch, ray, c, args.tol, &opts);
            bar.inc(1);
            out
        })
        .collect::<Result<Vec<Classification>>>()?;
    bar.finish_and_clear();
    let mut summary = Summary::default();
    let rays_json: Vec<RayJson> = results
        .iter()
        .zip(&claims)
        .map(|(c, given)| {
            summary.true_hits += c.hits.iter().filter(|h| h.is_certified()).count();
            summary.missed += c.missed.len();
            let claims = given
                .iter()
                .zip(&c.claims)
                .map(|(g, &(verdict, _))| {
                    summary.claims += 1;
                    match verdict {
                        ClaimVerdict::Confirmed => summary.confirmed += 1,
                        ClaimVerdict::Duplicate => summary.duplicate += 1,
                        ClaimVerdict::Spurious => summary.spurious += 1,
                        _ => summary.undecided += 1,
                    }
                    ClaimJson {
                        u: g.u,
                        v: g.v,
                        t: g.t,
                        verdict,
                    }
                })
                .collect();
            let missed = c
                .missed
                .iter()
                .map(|&k| PointJson {
                    u: c.hits[k].u,
                    v: c.hits[k].v,
                    t: c.hits[k].t,
                })
                .collect();
            RayJson {
                claims,
                missed,
                nearest_claimed: c.nearest_claimed,
                complete: c.complete,
            }
        })
        .collect();
    let report = Report {
        rays: rays_json,
        summary,
    };
    Ok(if args.json {
        Answer::json(report)
    } else {
        Answer::text(text(&report))
    })
}

fn text(r: &Report) -> String {
    let mut out = String::new();
    for (k, ray) in r.rays.iter().enumerate() {
        let verdicts: Vec<&str> = ray.claims.iter().map(|c| c.verdict.code()).collect();
        out += &format!(
            "ray {k}: claims [{}], {} missed, nearest {}{}\n",
            verdicts.join(", "),
            ray.missed.len(),
            match ray.nearest_claimed {
                Some(true) => "claimed",
                Some(false) => "NOT claimed",
                None => "not proven",
            },
            if ray.complete { "" } else { ", INCOMPLETE" }
        );
    }
    let s = &r.summary;
    out += &format!(
        "{} claims: {} confirmed, {} duplicate, {} spurious, {} undecided; {} of {} certified hits missed",
        s.claims, s.confirmed, s.duplicate, s.spurious, s.undecided, s.missed, s.true_hits
    );
    out
}

/// Parses CLAIMS.txt into one list per ray (module docs).
fn parse_claims(text: &str, rays: usize) -> Result<Vec<Vec<Claim>>> {
    let mut out = vec![Vec::new(); rays];
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |m: String| Error::Format(format!("CLAIMS line {}: {m}", k + 1));
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != 4 {
            return Err(bad(format!("need 4 fields (ray_index u v t), got {}", fields.len())));
        }
        let index: usize = fields[0]
            .parse()
            .map_err(|_| bad(format!("{:?} is not a ray index", fields[0])))?;
        if index >= rays {
            return Err(bad(format!("ray index {index} is out of range ({rays} rays)")));
        }
        let num = |s: &str| -> Result<f64> {
            let x: f64 = s.parse().map_err(|_| bad(format!("{s:?} is not a number")))?;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(bad(format!("{s:?} is not finite")))
            }
        };
        out[index].push(Claim {
            u: num(fields[1])?,
            v: num(fields[2])?,
            t: num(fields[3])?,
        });
    }
    Ok(out)
}
