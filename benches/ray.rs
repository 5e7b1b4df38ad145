//! Certified ray queries against Park, Ji & Ko's (2013) Example 1 bicubic patch
//! (tests/data/seed000_example1.json), per batch of 256 fixed rays
//! ([`aimed_rays`]: about three quarters hit, some twice), one thread:
//!
//! * `ray/rect-all`, `ray/rect-nearest`, `ray/rect-any`: the default
//!   rectangle route with each query;
//! * `ray/rect-fat-line-all`, `ray/rect-hybrid-all`: the rectangle route with
//!   fat-line or hybrid (fat line + fat conic) clipping instead of Bézier
//!   hulls;
//! * `ray/triangles-all`: the same patch as two degree-6 triangles (hybrid
//!   clipping), the route the rectangle one is measured against;
//! * `ray/newton`: plain Newton–Raphson from the patch centre on the same
//!   rays (`heuristics::iterate` with the default options; no proof, it
//!   misses hits — `dev`'s `ray_bench` counts them; `benches/heuristics.rs`
//!   has all four iterations).
//!
//! Divide the reported time by 256 for µs per ray. Whole-process batch
//! timings (10,000 rays, rayon): `cargo run --release -p rootclip-dev --bin ray_bench`.
//!
//! `cargo bench --bench ray` takes about a minute.

use criterion::{criterion_group, criterion_main, Criterion};
use rootclip::heuristics::{iterate, IterOptions, Iteration};
use rootclip::internals::aimed_rays;
use rootclip::ray::{intersect, Patch, PatchSpec, Query, Ray, RayOptions};
use rootclip::solve::SquareRoute;
use std::hint::black_box;
use std::time::Duration;

const RAYS: usize = 256;

fn setup() -> (Patch, Vec<Ray>) {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/seed000_example1.json"))
        .expect("fixture");
    let v: serde_json::Value = serde_json::from_str(&text).expect("json");
    let spec: PatchSpec = serde_json::from_value(v["patch"].clone()).expect("patch");
    let patch = Patch::from_spec(&spec).expect("patch");
    let rays = aimed_rays(&patch, RAYS, 12.0, 0x9e37_79b9_7f4a_7c15);
    (patch, rays)
}

fn bench(c: &mut Criterion) {
    let (patch, rays) = setup();
    let mut g = c.benchmark_group("ray");
    let cases = [
        ("rect-all", SquareRoute::Rect, Query::All),
        ("rect-nearest", SquareRoute::Rect, Query::Nearest),
        ("rect-any", SquareRoute::Rect, Query::Any),
        ("rect-fat-line-all", SquareRoute::RectFatLine, Query::All),
        ("rect-hybrid-all", SquareRoute::RectHybrid, Query::All),
        ("triangles-all", SquareRoute::Triangles, Query::All),
    ];
    for (name, route, query) in cases {
        let opts = RayOptions::default().with_route(route).with_query(query);
        g.bench_function(name, |b| {
            b.iter(|| {
                for r in &rays {
                    black_box(intersect(&patch, r, &opts).expect("valid input"));
                }
            })
        });
    }
    let iter_opts = IterOptions::default();
    g.bench_function("newton", |b| {
        b.iter(|| {
            for r in &rays {
                black_box(iterate(Iteration::Newton, &patch, r, [0.5, 0.5], &iter_opts));
            }
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
