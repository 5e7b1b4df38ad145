//! `rootclip ssi`: two patches in, every branch of their intersection curve
//! out (text or JSON).
//!
//! A.json and B.json are [`PatchSpec`](crate::ray::PatchSpec)s as for
//! `ray`. JSON out: `{"schema_version": 1, "complete": …, "branches":
//! [{"closed": …, "points": [{"a": [u, v], "b": [s, t], "xyz": [x, y, z],
//! "certified": …}]}], "singular": [{"kind": …, "a": …, "b": …, "reason":
//! …}], "stats": {…, "seconds": …}}`.

use super::input::read_input;
use super::json::document;
use super::ray::parse_patch;
use crate::error::{Error, Result};
use crate::ssi::{intersect_surfaces, Intersection, SsiOptions, SsiStats};
use serde::Serialize;

/// Arguments of `rootclip ssi`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct SsiArgs {
    /// A.json ("-" for stdin): a patch as for `ray --patch` (tensor or bspline).
    #[arg(long)]
    a: String,
    /// B.json ("-" for stdin): the other patch.
    #[arg(long)]
    b: String,
    /// Largest deviation of a chord from the curve, in model units.
    #[arg(long, default_value_t = 1e-3)]
    tol: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Runs the command and returns its output.
pub(super) fn run(args: &SsiArgs) -> Result<String> {
    if args.a == "-" && args.b == "-" {
        return Err(Error::InvalidOption(
            "--a and --b cannot both read standard input".into(),
        ));
    }
    let a = parse_patch(&read_input(&args.a)?).map_err(|e| Error::Format(format!("--a: {e}")))?;
    let b = parse_patch(&read_input(&args.b)?).map_err(|e| Error::Format(format!("--b: {e}")))?;
    let opts = SsiOptions::default().with_tol(args.tol);
    let clock = std::time::Instant::now();
    let out = intersect_surfaces(&a, &b, &opts)?;
    let seconds = clock.elapsed().as_secs_f64();
    Ok(if args.json {
        json(&out, seconds)
    } else {
        text(&out, seconds)
    })
}

fn json(out: &Intersection, seconds: f64) -> String {
    #[derive(Serialize)]
    struct Stats<'a> {
        #[serde(flatten)]
        stats: &'a SsiStats,
        seconds: f64,
    }
    #[derive(Serialize)]
    struct Body<'a> {
        complete: bool,
        branches: &'a [crate::ssi::Branch],
        singular: &'a [crate::ssi::Singular],
        stats: Stats<'a>,
    }
    document(&Body {
        complete: out.complete,
        branches: &out.branches,
        singular: &out.singular,
        stats: Stats {
            stats: &out.stats,
            seconds,
        },
    })
}

fn text(out: &Intersection, seconds: f64) -> String {
    let mut s = format!(
        "{} branch(es), {}; {} certified points, {} crossings, {} turning points, {:.3} ms\n",
        out.branches.len(),
        if out.complete {
            "complete"
        } else {
            "NOT complete (see the singular regions)"
        },
        out.stats.certified_points,
        out.stats.crossings,
        out.stats.turning_points,
        seconds * 1e3
    );
    for (k, br) in out.branches.iter().enumerate() {
        let (first, last) = (br.points.first(), br.points.last());
        s.push_str(&format!(
            "branch {k}: {} points, {}",
            br.points.len(),
            if br.closed { "closed" } else { "open" }
        ));
        if let (Some(f), Some(l)) = (first, last) {
            s.push_str(&format!(
                ", from a = ({:.9}, {:.9}) to a = ({:.9}, {:.9})",
                f.a[0], f.a[1], l.a[0], l.a[1]
            ));
        }
        s.push('\n');
    }
    for r in &out.singular {
        s.push_str(&format!(
            "singular ({:?}): a in {:?}, b in {:?}: {}\n",
            r.kind, r.a, r.b, r.reason
        ));
    }
    s.pop();
    s
}
