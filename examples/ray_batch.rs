//! A batch of rays against a patch read from JSON, in parallel: how many hit,
//! how many hits are certified, and what the undecided ones are.
//!
//! `cargo run --release --example ray_batch [PATCH.json] [RAYS]`
//!
//! Reading `PATCH.json` uses the `serde` feature (`rootclip = { ...,
//! features = ["serde"] }` in a crate of your own).

use rootclip::glam::DVec3;
use rootclip::ray::{intersect_batch, Patch, PatchSpec, Query, Ray, RayOptions, RayOutcome};
use std::collections::BTreeMap;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("examples/data/seed000_bicubic.json", String::as_str);
    let n: usize = args.get(2).map_or(Ok(100_000), |s| s.parse())?;
    let spec: PatchSpec = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let patch = Patch::from_spec(&spec)?;

    // Rays from a ring of origins around the control net, aimed at points of
    // the patch itself (a deterministic spread of parameters).
    let (lo, hi) = spec_bounds(patch.points());
    let centre = 0.5 * (lo + hi);
    let radius = 2.0 * (hi - lo).length().max(1.0);
    let rays: Vec<Ray> = (0..n)
        .map(|k| {
            let (a, b) = (frac(k as f64 * 0.618_033_988_75), frac(k as f64 * 0.754_877_666_25));
            let target = patch.eval(a, b);
            let phi = std::f64::consts::TAU * frac(k as f64 * 0.569_840_290_99);
            let origin = centre + radius * DVec3::new(phi.cos(), phi.sin(), 0.3 * (2.0 * b - 1.0));
            Ray::new(origin, target - origin)
        })
        .collect::<Result<_, _>>()?;

    for (name, query) in [("all hits", Query::All), ("nearest hit", Query::Nearest)] {
        let opts = RayOptions::default().with_query(query);
        let start = Instant::now();
        let outcomes = intersect_batch(&patch, &rays, &opts);
        let secs = start.elapsed().as_secs_f64();
        let mut certified = 0;
        let mut undecided: BTreeMap<&str, usize> = BTreeMap::new();
        let (mut degenerate, mut errors, mut with_hit) = (0, 0, 0);
        for out in &outcomes {
            match out {
                Ok(o @ RayOutcome::Hits(h)) => {
                    with_hit += usize::from(!h.hits.is_empty());
                    for hit in o.hits() {
                        match hit.undecided_reason() {
                            None => certified += 1,
                            Some(r) => *undecided.entry(r.code()).or_default() += 1,
                        }
                    }
                }
                Ok(RayOutcome::Degenerate(_)) => degenerate += 1,
                Err(_) => errors += 1,
            }
        }
        println!(
            "{name}: {n} rays in {secs:.3} s ({:.2} µs/ray on {} threads): {with_hit} rays hit, \
             {certified} certified hits, undecided {undecided:?}, {degenerate} degenerate rays, {errors} errors",
            secs * 1e6 / n as f64,
            rayon_threads()
        );
    }
    Ok(())
}

fn frac(x: f64) -> f64 {
    x - x.floor()
}

fn spec_bounds(points: &[DVec3]) -> (DVec3, DVec3) {
    let lo = points.iter().copied().fold(DVec3::INFINITY, DVec3::min);
    let hi = points.iter().copied().fold(DVec3::NEG_INFINITY, DVec3::max);
    (lo, hi)
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
