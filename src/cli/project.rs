//! `rootclip project`: the certified closest point of a patch to each of many
//! points ([`crate::project::project`]).
//!
//! PTS.txt: one point `x y z` per line (blank lines and `#` comments
//! skipped). JSON out: `{"schema_version": 1, "points": [{"u", "v", "point",
//! "distance": [lo, hi], "certified", "status", "ties": [...], "box": {"u",
//! "v"}}]}`, in input order.

use super::input::read_input;
use super::json::{write_document, LazySeq};
use super::output::Answer;
use super::ray::parse_patch;
use crate::error::{Error, Result};
use crate::project::{project_batch, Foot, ProjectOptions, Projection, ProjectionStatus};
use crate::solve::Box2;
use glam::DVec3;
use serde::Serialize;
use std::io::{self, Write};

/// Arguments of `rootclip project`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct ProjectArgs {
    /// PATCH.json ("-" for stdin), as for "rootclip ray".
    #[arg(long)]
    patch: String,
    /// PTS.txt ("-" for stdin): one point "x y z" per line.
    #[arg(long)]
    points: String,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct TieJson {
    u: f64,
    v: f64,
    point: [f64; 3],
    distance: [f64; 2],
    certified: bool,
    #[serde(rename = "box")]
    bx: Box2,
}

#[derive(Serialize)]
struct PointJson {
    u: f64,
    v: f64,
    point: [f64; 3],
    distance: [f64; 2],
    certified: bool,
    status: ProjectionStatus,
    ties: Vec<TieJson>,
    #[serde(rename = "box")]
    bx: Option<Box2>,
}

fn tie(f: &Foot) -> TieJson {
    TieJson {
        u: f.u,
        v: f.v,
        point: f.point.to_array(),
        distance: f.distance,
        certified: f.certified,
        bx: f.bx,
    }
}

fn point_json(p: &Projection) -> PointJson {
    PointJson {
        u: p.u,
        v: p.v,
        point: p.point.to_array(),
        distance: p.distance,
        certified: p.status != ProjectionStatus::Undecided,
        status: p.status,
        ties: p.feet.iter().skip(1).map(tie).collect(),
        bx: p.feet.first().map(|f| f.bx),
    }
}

pub(super) fn run(args: &ProjectArgs) -> Result<Answer> {
    if args.patch == "-" && args.points == "-" {
        return Err(Error::InvalidOption(
            "--patch and --points cannot both read standard input".into(),
        ));
    }
    let patch = parse_patch(&read_input(&args.patch)?)?;
    let points = parse_points(&read_input(&args.points)?)?;
    let results = project_batch(&patch, &points, &ProjectOptions::default())
        .into_iter()
        .collect::<Result<Vec<_>>>()?;
    Ok(if args.json {
        Answer::new(move |out| {
            #[derive(Serialize)]
            struct Report<'a> {
                points: LazySeq<'a, Projection, PointJson>,
            }
            let points = LazySeq {
                items: &results,
                view: &point_json,
            };
            write_document(out, &Report { points })
        })
    } else {
        Answer::new(move |out| write_text(out, &results))
    })
}

/// `point k: …` for each point, joined by newlines, and a final newline.
fn write_text(out: &mut impl Write, results: &[Projection]) -> io::Result<()> {
    for (k, p) in results.iter().enumerate() {
        if k > 0 {
            out.write_all(b"\n")?;
        }
        write!(
            out,
            "point {k}: u = {:.17} v = {:.17} distance [{:e}, {:e}] {}",
            p.u,
            p.v,
            p.distance[0],
            p.distance[1],
            match p.status {
                ProjectionStatus::Unique => "certified",
                ProjectionStatus::Ties => "certified, tied feet",
                _ => "UNDECIDED",
            }
        )?;
        if p.feet.len() > 1 {
            write!(out, " ({} feet)", p.feet.len())?;
        }
    }
    out.write_all(b"\n")
}

/// Parses PTS.txt: `x y z` per line.
fn parse_points(text: &str) -> Result<Vec<DVec3>> {
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |m: String| Error::Format(format!("POINTS line {}: {m}", k + 1));
        let c: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse::<f64>().map_err(|_| bad(format!("{x:?} is not a number"))))
            .collect::<Result<_>>()?;
        if c.len() != 3 {
            return Err(bad(format!("need 3 numbers (x y z), got {}", c.len())));
        }
        if c.iter().any(|x| !x.is_finite()) {
            return Err(bad("coordinates must be finite".into()));
        }
        out.push(DVec3::new(c[0], c[1], c[2]));
    }
    Ok(out)
}
