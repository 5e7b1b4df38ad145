//! `rootclip ray`: PATCH.json in, certified hits (text or JSON) out.
//!
//! PATCH.json is a [`PatchSpec`] (unknown keys are errors); B-spline hits are
//! reported in knot parameters. RAYS.txt: one ray per line,
//! `ox oy oz dx dy dz` (blank lines and `#` comments are skipped). JSON out:
//! `{"schema_version": 1, "rays": [RayOutcome, …]}`, one entry per ray in
//! input order, each the library's serialization of [`RayOutcome`]; a ray
//! line that cannot be read, or a ray that fails, is `{"error": {"code",
//! "message", "line"}}` in its place, and the exit code is then 1.

use super::input::read_input;
use super::json::{write_document, Item, ItemError, LazySeq};
use super::output::Answer;
use super::values::SquareRouteArg;
use crate::error::{Error, Result};
use crate::ray::{intersect, Patch, PatchSpec, Query, Ray, RayOptions, RayOutcome};
use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;
use std::io::{self, Write};

/// Arguments of `rootclip ray`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct RayArgs {
    /// PATCH.json ("-" for stdin): {"type": "triangle" | "tensor" | "bspline", "degree": ..., "points": [[x, y, z], ...], "weights": [...]}; B-splines also "knots_u", "knots_v".
    #[arg(long)]
    patch: String,
    /// Origin x,y,z of a single ray (with --dir).
    #[arg(long, allow_hyphen_values = true)]
    origin: Option<String>,
    /// Direction x,y,z of a single ray (with --origin; not normalized).
    #[arg(long, allow_hyphen_values = true)]
    dir: Option<String>,
    /// RAYS.txt ("-" for stdin): one ray per line, "ox oy oz dx dy dz".
    #[arg(long)]
    rays: Option<String>,
    /// Only the hits that may be the nearest (a single certified hit is the
    /// proven nearest); regions provably farther are never explored.
    #[arg(long, conflicts_with = "any")]
    nearest: bool,
    /// Any one certified hit (shadow rays): the search stops at the first.
    #[arg(long)]
    any: bool,
    /// Only hits with t >= T_MIN (may be negative: the line behind the origin).
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.0)]
    t_min: f64,
    /// Only hits with t <= T_MAX (default: no limit).
    #[arg(long, allow_negative_numbers = true)]
    t_max: Option<f64>,
    /// How tensor patches are solved: natively on boxes, or as two triangles.
    #[arg(long, value_enum, default_value = "rect")]
    route: SquareRouteArg,
    /// Wall-clock budget per ray in seconds (e.g. 0.01): past it the ray ends incomplete with the hits found.
    #[arg(long)]
    timeout: Option<f64>,
    /// Box budget per solve (default 20000; a transversal ray needs a few dozen).
    #[arg(long)]
    max_boxes: Option<usize>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Runs the command and returns its output. Batches run in parallel (rayon),
/// with a progress bar on a terminal; the output is in input order, written
/// ray by ray (text or JSON) once every ray is solved.
pub(super) fn run(args: &RayArgs) -> Result<Answer> {
    if args.patch == "-" && args.rays.as_deref() == Some("-") {
        return Err(Error::InvalidOption(
            "--patch and --rays cannot both read standard input".into(),
        ));
    }
    let patch = parse_patch(&read_input(&args.patch)?)?;
    let rays: Vec<Line<Ray>> = match (&args.origin, &args.dir, &args.rays) {
        (Some(o), Some(d), None) => vec![(1, Ok(Ray::new(parse_vec3("--origin", o)?, parse_vec3("--dir", d)?)?))],
        (None, None, Some(path)) => parse_rays(&read_input(path)?),
        _ => {
            return Err(Error::InvalidOption(
                "give either --origin and --dir, or --rays (not both)".into(),
            ))
        }
    };
    let query = if args.nearest {
        Query::Nearest
    } else if args.any {
        Query::Any
    } else {
        Query::All
    };
    let mut opts = RayOptions::default()
        .with_query(query)
        .with_route(args.route.into())
        .with_t_range(args.t_min, args.t_max.unwrap_or(f64::INFINITY));
    if let Some(t) = args.timeout {
        opts = opts.with_timeout(super::input::duration("--timeout", t)?);
    }
    if let Some(n) = args.max_boxes {
        opts = opts.with_max_boxes(n);
    }
    opts.validate()?;
    let bar = indicatif::ProgressBar::new(rays.len() as u64);
    if rays.len() < 1000 {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let outcomes: Vec<std::result::Result<RayOutcome, ItemError>> = rays
        .par_iter()
        .map(|(line, r)| {
            let out = r
                .as_ref()
                .map_err(|e| e.clone())
                .and_then(|r| intersect(&patch, r, &opts))
                .map_err(|e| ItemError::new(&e, *line));
            bar.inc(1);
            out
        })
        .collect();
    bar.finish_and_clear();
    let failed = outcomes.iter().filter(|o| o.is_err()).count();
    let items = outcomes.len();
    Ok(if args.json {
        Answer::new(move |out| write_json(out, &outcomes))
    } else {
        Answer::new(move |out| write_text(out, &outcomes))
    }
    .with_failed(failed, items))
}

/// An input line's number (1-based) and what was read from it.
pub(super) type Line<T> = (usize, Result<T>);

/// `{"schema_version": 1, "rays": [...]}`, each ray's JSON made as it is
/// written.
fn write_json(out: &mut impl Write, outcomes: &[std::result::Result<RayOutcome, ItemError>]) -> io::Result<()> {
    #[derive(Serialize)]
    struct Rays<'a> {
        rays: LazySeq<'a, std::result::Result<RayOutcome, ItemError>, Item<&'a RayOutcome>>,
    }
    fn view(o: &std::result::Result<RayOutcome, ItemError>) -> Item<&RayOutcome> {
        match o {
            Ok(o) => Item::Ok(o),
            Err(e) => Item::Err { error: e.clone() },
        }
    }
    let rays = LazySeq {
        items: outcomes,
        view: &view,
    };
    write_document(out, &Rays { rays })
}

/// Parses PATCH.json (a [`PatchSpec`]) and validates the patch.
pub(super) fn parse_patch(text: &str) -> Result<Patch> {
    let spec: PatchSpec = serde_json::from_str(text).map_err(|e| Error::Format(format!("PATCH.json: {e}")))?;
    Patch::from_spec(&spec)
}

fn parse_vec3(what: &str, s: &str) -> Result<DVec3> {
    let c: Vec<f64> = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .map_err(|_| Error::InvalidOption(format!("{what}: {x:?} is not a number")))
        })
        .collect::<Result<_>>()?;
    if c.len() != 3 {
        return Err(Error::InvalidOption(format!("{what} needs x,y,z, got {s:?}")));
    }
    Ok(DVec3::new(c[0], c[1], c[2]))
}

/// Parses RAYS.txt: `ox oy oz dx dy dz` per line, each line's ray or its
/// error (blank lines and `#` comments skipped).
pub(super) fn parse_rays(text: &str) -> Vec<Line<Ray>> {
    let mut rays = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let parse = || -> Result<Ray> {
            let c: Vec<f64> = line
                .split_whitespace()
                .map(|x| {
                    x.parse::<f64>()
                        .map_err(|_| Error::Format(format!("RAYS line {}: {x:?} is not a number", k + 1)))
                })
                .collect::<Result<_>>()?;
            if c.len() != 6 {
                return Err(Error::Format(format!(
                    "RAYS line {}: need 6 numbers, got {}",
                    k + 1,
                    c.len()
                )));
            }
            Ray::new(DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5]))
        };
        rays.push((k + 1, parse()));
    }
    rays
}

/// `ray k: …` and a line per hit for each ray (a failed ray: its error),
/// the rays' texts joined by newlines, and a final newline.
fn write_text(out: &mut impl Write, outcomes: &[std::result::Result<RayOutcome, ItemError>]) -> io::Result<()> {
    for (k, o) in outcomes.iter().enumerate() {
        if k > 0 {
            out.write_all(b"\n")?;
        }
        match o {
            Ok(o) => write_outcome(out, k, o)?,
            Err(e) => write!(out, "{}", e.text("ray", k))?,
        }
    }
    out.write_all(b"\n")
}

/// `x` with 17 decimals, or in scientific notation when that would print
/// hundreds of digits or only zeros (`|x| ≥ 10¹⁶` or `|x| < 10⁻⁴`).
fn fixed_or_exp(x: f64) -> String {
    if x == 0.0 || (1e-4..1e16).contains(&x.abs()) {
        format!("{x:.17}")
    } else {
        format!("{x:.17e}")
    }
}

fn write_outcome(out: &mut impl Write, k: usize, o: &RayOutcome) -> io::Result<()> {
    let hits = o.hits();
    write!(
        out,
        "ray {k}: {} hit(s){}",
        hits.len(),
        if o.is_complete() { ", complete" } else { "" }
    )?;
    if let Some(reason) = o.degenerate_reason() {
        write!(out, ", DEGENERATE: {reason}")?;
    }
    for h in hits {
        write!(
            out,
            "\n  t = {} u = {:.17} v = {:.17} point [{:e}, {:e}, {:e}] normal [{:.6}, {:.6}, {:.6}]  t box [{:e}, {:e}]",
            fixed_or_exp(h.t),
            h.u,
            h.v, h.point.x, h.point.y, h.point.z, h.normal.x, h.normal.y, h.normal.z, h.bx.t[0], h.bx.t[1]
        )?;
        if let Some(r) = h.undecided_reason() {
            write!(out, "  (undecided: {})", r.describe())?;
        }
    }
    Ok(())
}
