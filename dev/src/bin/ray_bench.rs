//! Whole-process timing of certified ray queries against Park, Ji & Ko's (2013) Example 1
//! bicubic patch (tests/data/seed000_example1.json), with plain Newton from
//! the patch centre on the same rays as the baseline.
//!
//! Rays: origins uniform on a sphere of radius 12 around the centre of the
//! control net's bounding box, each aimed at a uniform point of that box
//! (fixed seed; [`rootclip::internals::aimed_rays`]). One thread per
//! query, then the all-hits batch on every core (rayon). Checks, in the same
//! run: the rectangle and triangle routes agree hit for hit (every certified
//! hit of one overlaps a hit box of the other); the nearest and any-hit
//! queries return hits of the all-hits list; Newton's misses are counted
//! against the certified hits.
//!
//! `cargo run --release -p rootclip-dev --bin ray_bench [N]` (default 10,000; the
//! triangle route runs on the first N/10 rays only: it is ~25× slower).

use rootclip::heuristics::{iterate, IterOptions, Iteration};
use rootclip::internals::aimed_rays;
use rootclip::ray::{
    intersect, intersect_batch, Degeneracy, Hit, Patch, PatchSpec, Query, Ray, RayOptions, RayOutcome,
};
use rootclip::solve::SquareRoute;
use std::time::Instant;

fn hits(o: &RayOutcome) -> &[Hit] {
    match o {
        RayOutcome::Hits(h) | RayOutcome::Degenerate(Degeneracy::Unresolved(h)) => &h.hits,
        RayOutcome::Degenerate(_) => &[],
    }
}

fn overlap(a: &Hit, b: &Hit) -> bool {
    a.bx.u[0] <= b.bx.u[1] && b.bx.u[0] <= a.bx.u[1] && a.bx.v[0] <= b.bx.v[1] && b.bx.v[0] <= a.bx.v[1]
}

/// Runs one query over the rays on one thread; prints a line; returns the outcomes.
fn run(
    patch: &rootclip::ray::Patch,
    rays: &[Ray],
    route: SquareRoute,
    query: Query,
) -> Result<(Vec<RayOutcome>, f64), rootclip::Error> {
    let opts = {
        let mut o = RayOptions::default();
        o.route = route;
        o.query = query;
        o
    };
    let t0 = Instant::now();
    let outs = rays
        .iter()
        .map(|r| intersect(patch, r, &opts))
        .collect::<Result<Vec<_>, _>>()?;
    let us = t0.elapsed().as_secs_f64() * 1e6 / rays.len() as f64;
    let certified: usize = outs
        .iter()
        .map(|o| hits(o).iter().filter(|h| h.is_certified()).count())
        .sum();
    let undecided: usize = outs
        .iter()
        .map(|o| hits(o).iter().filter(|h| !h.is_certified()).count())
        .sum();
    let degenerate = outs.iter().filter(|o| matches!(o, RayOutcome::Degenerate(_))).count();
    let widest = outs
        .iter()
        .flat_map(|o| hits(o).iter().filter(|h| h.is_certified()))
        .map(|h| (h.bx.u[1] - h.bx.u[0]).max(h.bx.v[1] - h.bx.v[0]))
        .fold(0.0f64, f64::max);
    println!(
        "{route:?} {query:?}: {} rays, {us:.2} µs/ray; {certified} certified hits (widest (u, v) box side {widest:.1e}), {undecided} undecided, {degenerate} degenerate",
        rays.len()
    );
    Ok((outs, us))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(10_000), |s| s.parse())?;
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/seed000_example1.json"
    ))?;
    let v: serde_json::Value = serde_json::from_str(&text)?;
    let spec: PatchSpec =
        serde_json::from_value(v["patch"].clone()).map_err(|e| rootclip::Error::Format(e.to_string()))?;
    let patch = Patch::from_spec(&spec)?;
    let rays = aimed_rays(&patch, n, 12.0, 0x9e37_79b9_7f4a_7c15);
    println!(
        "machine: {} threads available",
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );

    let (all, us_all) = run(&patch, &rays, SquareRoute::Rect, Query::All)?;
    let (near, us_near) = run(&patch, &rays, SquareRoute::Rect, Query::Nearest)?;
    let (any, us_any) = run(&patch, &rays, SquareRoute::Rect, Query::Any)?;
    let sub = &rays[..n.div_ceil(10)];
    let (tri, us_tri) = run(&patch, sub, SquareRoute::Triangles, Query::All)?;

    // Agreement: routes, and queries against all hits.
    let disagree = all
        .iter()
        .zip(&tri)
        .filter(|(a, b)| {
            let (ha, hb) = (hits(a), hits(b));
            ha.iter().any(|x| !hb.iter().any(|y| overlap(x, y))) || hb.iter().any(|x| !ha.iter().any(|y| overlap(x, y)))
        })
        .count();
    let first_certified = |o: &RayOutcome| hits(o).iter().find(|h| h.is_certified()).cloned();
    let near_wrong = all
        .iter()
        .zip(&near)
        .filter(|(a, b)| match (first_certified(a), first_certified(b)) {
            (Some(x), Some(y)) => !overlap(&x, &y),
            (x, y) => x.is_some() != y.is_some(),
        })
        .count();
    let any_wrong = all
        .iter()
        .zip(&any)
        .filter(|(a, b)| {
            let ha = hits(a);
            let hb = hits(b);
            hb.iter().any(|y| !ha.iter().any(|x| overlap(x, y))) || (hb.is_empty() != ha.is_empty())
        })
        .count();
    println!(
        "routes disagree on {disagree} of {} rays; nearest differs from the first of all hits on {near_wrong} rays; any-hit not among all hits on {any_wrong} rays",
        sub.len()
    );

    // Newton from the patch centre, same rays.
    let t0 = Instant::now();
    let newton: Vec<_> = rays
        .iter()
        .map(|r| iterate(Iteration::Newton, &patch, r, [0.5, 0.5], &IterOptions::default()).end)
        .collect();
    let us_newton = t0.elapsed().as_secs_f64() * 1e6 / n as f64;
    let true_hits: usize = all
        .iter()
        .map(|o| hits(o).iter().filter(|h| h.is_certified()).count())
        .sum();
    let rays_with_hits = all.iter().filter(|o| hits(o).iter().any(|h| h.is_certified())).count();
    let mut found = 0;
    let mut spurious = 0;
    for (o, nh) in all.iter().zip(&newton) {
        if let Some(h) = nh {
            let close = hits(o)
                .iter()
                .any(|x| (x.u - h.u).abs() < 1e-8 && (x.v - h.v).abs() < 1e-8);
            if close {
                found += 1;
            } else {
                spurious += 1;
            }
        }
    }
    println!(
        "Newton from (½, ½): {us_newton:.2} µs/ray; found {found} of {true_hits} certified hits (rays with a hit: {rays_with_hits}; missed hits: {}), {spurious} points not at a certified hit",
        true_hits - found
    );

    // The all-hits batch on every core.
    let opts = RayOptions::default();
    let t0 = Instant::now();
    let par = intersect_batch(&patch, &rays, &opts);
    let wall = t0.elapsed().as_secs_f64();
    let par_same = par.iter().zip(&all).all(|(p, a)| p.as_ref().ok() == Some(a));
    println!(
        "Rect All on {} threads: {:.3} s wall for {n} rays ({:.2} µs/ray), identical to the 1-thread run: {par_same}",
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        wall,
        wall * 1e6 / n as f64
    );
    println!(
        "ratios: triangles/rect {:.1}, rect all/nearest {:.2}, rect all/any {:.2}, rect all/Newton {:.2}",
        us_tri / us_all,
        us_all / us_near,
        us_all / us_any,
        us_all / us_newton
    );
    Ok(())
}
