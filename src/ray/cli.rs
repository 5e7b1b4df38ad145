//! The `rootclip ray` command: patch JSON in, hits (text or JSON) out.
//!
//! PATCH.json: `{"type":"triangle","degree":n,"points":[[x,y,z],…]}` (order of
//! Eq. (2): `j` outer, `i` inner), `{"type":"tensor","degree":[m,n],"points":[…]}`
//! (row-major) or a B-spline/NURBS surface
//! `{"type":"bspline","degree":[p,q],"knots_u":[…],"knots_v":[…],"points":[…]}`
//! (`n_u·n_v` points row-major, `P_ij` at `i·n_v + j`, with
//! `n_u = len(knots_u) − p − 1`; clamped or unclamped knots, see
//! [`BsplineSurface::new`]), each with optional `"weights"` in the same order;
//! B-spline hits are reported in knot parameters. RAYS.txt:
//! one ray per line, `ox oy oz dx dy dz` (blank lines and `#` comments are
//! skipped). JSON out: `{"rays":[{"complete":…,"hits":[…]}]}`, one entry per
//! ray in input order; a degenerate ray has `"complete": false` and a
//! `"degenerate"` reason.

use super::{
    intersect_with, BsplineSurface, Hit, Patch, Query, Ray, RayOptions, RayOutcome, TensorPatch, TensorRoute, TriPatch,
};
use crate::error::{Error, Result};
use glam::DVec3;
use rayon::prelude::*;
use serde_json::{json, Value};

/// Arguments of `rootclip ray`.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct RayArgs {
    /// PATCH.json: {"type":"triangle"|"tensor"|"bspline","degree":..,"points":\[\[x,y,z\],..\],"weights":\[..\]}
    /// (B-splines also "knots_u", "knots_v").
    #[arg(long)]
    pub patch: String,
    /// Origin x,y,z of a single ray (with --dir).
    #[arg(long, allow_hyphen_values = true)]
    pub origin: Option<String>,
    /// Direction x,y,z of a single ray (with --origin; not normalized).
    #[arg(long, allow_hyphen_values = true)]
    pub dir: Option<String>,
    /// RAYS.txt: one ray per line, "ox oy oz dx dy dz".
    #[arg(long)]
    pub rays: Option<String>,
    /// Only the hits that may be the nearest (a single certified hit is the
    /// proven nearest); regions provably farther are never explored.
    #[arg(long, conflicts_with = "any")]
    pub nearest: bool,
    /// Any one certified hit (shadow rays): the search stops at the first.
    #[arg(long)]
    pub any: bool,
    /// How tensor patches are solved: natively on boxes, or as two triangles.
    #[arg(long, value_enum, default_value = "rect")]
    pub route: RouteArg,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// `--route` values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum RouteArg {
    /// Bézier clipping on boxes (default; faster).
    #[default]
    Rect,
    /// Fat-line clipping on boxes.
    RectFatLine,
    /// Hybrid clipping (fat line + fat conic) on boxes.
    RectHybrid,
    /// Two triangles of degree m + n, hybrid clipping.
    Triangles,
}

/// Runs the command and returns its output. Batches run in parallel (rayon),
/// with a progress bar on a terminal; the output is in input order.
pub fn run(args: &RayArgs) -> Result<String> {
    let text = read(&args.patch)?;
    let patch = parse_patch(&text)?;
    let rays = match (&args.origin, &args.dir, &args.rays) {
        (Some(o), Some(d), None) => vec![Ray::new(parse_vec3("--origin", o)?, parse_vec3("--dir", d)?)?],
        (None, None, Some(path)) => parse_rays(&read(path)?)?,
        _ => {
            return Err(Error::Shape(
                "give either --origin and --dir, or --rays (not both)".into(),
            ))
        }
    };
    let opts = RayOptions {
        route: match args.route {
            RouteArg::Rect => TensorRoute::Rect,
            RouteArg::RectFatLine => TensorRoute::RectFatLine,
            RouteArg::RectHybrid => TensorRoute::RectHybrid,
            RouteArg::Triangles => TensorRoute::Triangles,
        },
        query: if args.nearest {
            Query::Nearest
        } else if args.any {
            Query::Any
        } else {
            Query::All
        },
        ..RayOptions::default()
    };
    let bar = indicatif::ProgressBar::new(rays.len() as u64);
    if rays.len() < 1000 {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let outcomes = rays
        .par_iter()
        .map(|r| {
            let out = intersect_with(&patch, r, &opts);
            bar.inc(1);
            out
        })
        .collect::<Result<Vec<_>>>()?;
    bar.finish_and_clear();
    let nearest = args.nearest;
    Ok(if args.json {
        json!({"rays": outcomes.iter().map(|o| outcome_json(o, nearest)).collect::<Vec<_>>()}).to_string()
    } else {
        outcomes
            .iter()
            .enumerate()
            .map(|(k, o)| outcome_text(k, o, nearest))
            .collect::<Vec<_>>()
            .join("\n")
    })
}

fn read(path: &str) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| Error::Shape(format!("cannot read {path}: {e}")))
}

/// Parses PATCH.json (see the module docs).
pub fn parse_patch(text: &str) -> Result<Patch> {
    let v: Value = serde_json::from_str(text).map_err(|e| Error::Shape(format!("PATCH.json: {e}")))?;
    let kind = v
        .get("type")
        .and_then(Value::as_str)
        .ok_or_else(|| shape("\"type\" must be a string"))?;
    let points = parse_points(v.get("points").ok_or_else(|| shape("missing \"points\""))?)?;
    let weights = match v.get("weights") {
        None | Some(Value::Null) => None,
        Some(w) => Some(numbers(w, "weights")?),
    };
    let degree = v.get("degree").ok_or_else(|| shape("missing \"degree\""))?;
    match kind {
        "triangle" => {
            let n = degree
                .as_u64()
                .ok_or_else(|| shape("triangle \"degree\" must be a non-negative integer"))?;
            Ok(TriPatch::new(n as usize, points, weights)?.into())
        }
        "tensor" => {
            let (m, n) = bidegree(degree, "tensor", "[m, n]")?;
            Ok(TensorPatch::new(m, n, points, weights)?.into())
        }
        "bspline" => {
            let (p, q) = bidegree(degree, "bspline", "[p, q]")?;
            let knots = |key: &str| -> Result<Vec<f64>> {
                let k = v
                    .get(key)
                    .ok_or_else(|| shape(&format!("bspline needs \"{key}\", an array of non-decreasing numbers")))?;
                numbers(k, key)
            };
            Ok(BsplineSurface::new((p, q), knots("knots_u")?, knots("knots_v")?, points, weights)?.into())
        }
        other => Err(shape(&format!(
            "unknown patch type {other:?} (triangle, tensor, bspline)"
        ))),
    }
}

/// `[m, n]` with non-negative integers.
fn bidegree(degree: &Value, kind: &str, form: &str) -> Result<(usize, usize)> {
    let d = numbers(degree, "degree")?;
    let ok = d.len() == 2 && d.iter().all(|x| *x >= 0.0 && x.fract() == 0.0);
    if !ok {
        return Err(shape(&format!(
            "{kind} \"degree\" must be {form} with non-negative integers"
        )));
    }
    Ok((d[0] as usize, d[1] as usize))
}

fn shape(msg: &str) -> Error {
    Error::Shape(format!("PATCH.json: {msg}"))
}

fn numbers(v: &Value, what: &str) -> Result<Vec<f64>> {
    let arr = v
        .as_array()
        .ok_or_else(|| shape(&format!("\"{what}\" must be an array")))?;
    arr.iter()
        .map(|x| {
            x.as_f64()
                .ok_or_else(|| shape(&format!("\"{what}\" must hold numbers, found {x}")))
        })
        .collect()
}

fn parse_points(v: &Value) -> Result<Vec<DVec3>> {
    let arr = v
        .as_array()
        .ok_or_else(|| shape("\"points\" must be an array of [x, y, z]"))?;
    arr.iter()
        .map(|p| {
            let c = numbers(p, "points")?;
            if c.len() != 3 {
                return Err(shape(&format!("a point needs 3 coordinates, got {p}")));
            }
            Ok(DVec3::new(c[0], c[1], c[2]))
        })
        .collect()
}

fn parse_vec3(what: &str, s: &str) -> Result<DVec3> {
    let c: Vec<f64> = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .map_err(|_| Error::Shape(format!("{what}: {x:?} is not a number")))
        })
        .collect::<Result<_>>()?;
    if c.len() != 3 {
        return Err(Error::Shape(format!("{what} needs x,y,z, got {s:?}")));
    }
    Ok(DVec3::new(c[0], c[1], c[2]))
}

/// Parses RAYS.txt: `ox oy oz dx dy dz` per line.
pub fn parse_rays(text: &str) -> Result<Vec<Ray>> {
    let mut rays = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let c: Vec<f64> = line
            .split_whitespace()
            .map(|x| {
                x.parse::<f64>()
                    .map_err(|_| Error::Shape(format!("RAYS line {}: {x:?} is not a number", k + 1)))
            })
            .collect::<Result<_>>()?;
        if c.len() != 6 {
            return Err(Error::Shape(format!(
                "RAYS line {}: need 6 numbers, got {}",
                k + 1,
                c.len()
            )));
        }
        let ray = Ray::new(DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5]))
            .map_err(|e| Error::Shape(format!("RAYS line {}: {e}", k + 1)))?;
        rays.push(ray);
    }
    Ok(rays)
}

fn selected(o: &RayOutcome, nearest: bool) -> (bool, Vec<&Hit>) {
    match o {
        RayOutcome::Hits(h) if nearest => (h.complete, h.nearest()),
        RayOutcome::Hits(h) => (h.complete, h.hits.iter().collect()),
        RayOutcome::Degenerate(super::Degeneracy::Unresolved(h)) => (false, h.hits.iter().collect()),
        RayOutcome::Degenerate(_) => (false, Vec::new()),
    }
}

fn hit_json(h: &Hit) -> Value {
    json!({
        "t": h.t, "u": h.u, "v": h.v,
        "point": h.point.to_array(), "normal": h.normal.to_array(),
        "certified": h.certified, "on_edge": h.on_edge, "t_straddles_zero": h.t_straddles_zero,
        "box": {"u": h.bx.u, "v": h.bx.v, "t": h.bx.t}
    })
}

fn outcome_json(o: &RayOutcome, nearest: bool) -> Value {
    let (complete, hits) = selected(o, nearest);
    let mut v = json!({"complete": complete, "hits": hits.into_iter().map(hit_json).collect::<Vec<_>>()});
    if let Some(reason) = o.degenerate_reason() {
        v["degenerate"] = json!(reason);
    }
    v
}

fn outcome_text(k: usize, o: &RayOutcome, nearest: bool) -> String {
    let (complete, hits) = selected(o, nearest);
    let mut out = format!(
        "ray {k}: {} hit(s){}",
        hits.len(),
        if complete { ", complete" } else { "" }
    );
    if let Some(reason) = o.degenerate_reason() {
        out += &format!(", DEGENERATE: {reason}");
    }
    for h in hits {
        out += &format!(
            "\n  t = {:.17} u = {:.17} v = {:.17} point [{:e}, {:e}, {:e}]{}  t box [{:e}, {:e}]",
            h.t,
            h.u,
            h.v,
            h.point.x,
            h.point.y,
            h.point.z,
            if h.certified {
                ""
            } else if h.on_edge {
                "  (within rounding of the patch's edge: hit or just a miss, undecided)"
            } else if h.t_straddles_zero {
                "  (t may be below 0: undecided)"
            } else {
                "  (undecided region)"
            },
            h.bx.t[0],
            h.bx.t[1]
        );
    }
    out
}
