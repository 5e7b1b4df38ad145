//! `rootclip crosscheck`: claimed hits of a fast solver refereed by the
//! certified one ([`crate::ray::classify`]).
//!
//! CLAIMS.txt: one claim per line, `ray_index u v t` (`ray_index` 0-based into
//! RAYS.txt, `t` for the direction as given; any number of claims per ray,
//! none allowed; blank lines and `#` comments skipped). JSON out:
//! `{"schema_version": 1, "rays": [Classification, …], "summary": {"claims",
//! "confirmed", "duplicate", "spurious", "undecided", "missed",
//! "true_hits"}}`, rays in input order (each the library's serialization of
//! [`Classification`]: `claims` `[{"u", "v", "t", "verdict", "hit"}]` in
//! file order, `missed` as indices into `hits`, `nearest_claimed`,
//! `complete`, `hits`). A ray or claim line that cannot be read, or a ray
//! that fails, is an `{"error": {"code", "message", "line"}}` (rays: in the
//! ray's place; claims: in `"claim_errors"`), and the exit code is then 1.

use super::input::read_input;
use super::json::{Item, ItemError};
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
    rays: Vec<Item<Classification>>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    claim_errors: Vec<ItemError>,
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
    let rays = parse_rays(&read_input(&args.rays)?);
    let (claims, claim_errors) = parse_claims(&read_input(&args.claims)?, rays.len());
    let opts = RayOptions::default();
    crate::solve::referee::check_tol(args.tol)?;
    let bar = indicatif::ProgressBar::new(rays.len() as u64);
    if rays.len() < 1000 {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let results: Vec<std::result::Result<Classification, ItemError>> = rays
        .par_iter()
        .zip(&claims)
        .map(|((line, ray), c)| {
            let out = ray
                .as_ref()
                .map_err(Clone::clone)
                .and_then(|ray| classify_with(&patch, ray, c, args.tol, &opts))
                .map_err(|e| ItemError::new(&e, *line));
            bar.inc(1);
            out
        })
        .collect();
    bar.finish_and_clear();
    let mut summary = Summary::default();
    for c in results.iter().flatten() {
        summary.true_hits += c.hits.iter().filter(|h| h.is_certified()).count();
        summary.missed += c.missed.len();
        for r in &c.claims {
            summary.claims += 1;
            match r.verdict {
                ClaimVerdict::Confirmed => summary.confirmed += 1,
                ClaimVerdict::Duplicate => summary.duplicate += 1,
                ClaimVerdict::Spurious => summary.spurious += 1,
                _ => summary.undecided += 1,
            }
        }
    }
    let failed = results.iter().filter(|r| r.is_err()).count() + claim_errors.len();
    let items = results.len() + claim_errors.len();
    let report = Report {
        rays: results
            .into_iter()
            .map(|r| match r {
                Ok(c) => Item::Ok(c),
                Err(error) => Item::Err { error },
            })
            .collect(),
        claim_errors,
        summary,
    };
    Ok(if args.json {
        Answer::json(report)
    } else {
        Answer::text(text(&report))
    }
    .with_failed(failed, items))
}

fn text(r: &Report) -> String {
    let mut out = String::new();
    for (k, ray) in r.rays.iter().enumerate() {
        let ray = match ray {
            Item::Ok(c) => c,
            Item::Err { error } => {
                out += &error.text("ray", k);
                out += "\n";
                continue;
            }
        };
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
    for e in &r.claim_errors {
        out += &format!("claim (line {}): error: {}\n", e.line, e.message);
    }
    let s = &r.summary;
    out += &format!(
        "{} claims: {} confirmed, {} duplicate, {} spurious, {} undecided; {} of {} certified hits missed",
        s.claims, s.confirmed, s.duplicate, s.spurious, s.undecided, s.missed, s.true_hits
    );
    out
}

/// Parses CLAIMS.txt into one list per ray (module docs), and the lines
/// that could not be read (each its own error).
fn parse_claims(text: &str, rays: usize) -> (Vec<Vec<Claim>>, Vec<ItemError>) {
    let mut out = vec![Vec::new(); rays];
    let mut errors = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let parse = || -> Result<(usize, Claim)> {
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
            Ok((
                index,
                Claim {
                    u: num(fields[1])?,
                    v: num(fields[2])?,
                    t: num(fields[3])?,
                },
            ))
        };
        match parse() {
            Ok((index, claim)) => out[index].push(claim),
            Err(e) => errors.push(ItemError::new(&e, k + 1)),
        }
    }
    (out, errors)
}
