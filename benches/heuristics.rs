//! Park, Ji & Ko's (2013) four iterations (`rootclip::heuristics::iterate`) on a fixed
//! batch of 256 rays aimed at random points of Example 1's bicubic patch
//! (`internals::at_scale_rays`: from `P + (U(2, 6), U(−3, 3), U(−3, 3))`,
//! so `t = 1` is a hit), each from (½, ½) with the default options, one
//! thread: `heuristics/newton`, `heuristics/halley`,
//! `heuristics/first-order`, `heuristics/second-order`. Divide by 256 for µs
//! per ray; `ray/rect-all` in `benches/ray.rs` is the certified baseline
//! (on other rays), and the write-up `papers/second-order-geometric-2013`
//! has both on the same 10,000 rays, refereed.
//!
//! `cargo bench --bench heuristics` takes about half a minute.

use criterion::{criterion_group, criterion_main, Criterion};
use rootclip::heuristics::experiment::example;
use rootclip::heuristics::{iterate, IterOptions, Iteration};
use rootclip::internals::at_scale_rays;
use std::hint::black_box;
use std::time::Duration;

const RAYS: usize = 256;

fn bench(c: &mut Criterion) {
    let ex = example(1).expect("Example 1");
    let rays = at_scale_rays(&ex.patch, RAYS, 0x5eed_0000_2013);
    let opts = IterOptions::default();
    let mut g = c.benchmark_group("heuristics");
    for m in Iteration::ALL {
        g.bench_function(m.code(), |b| {
            b.iter(|| {
                for r in &rays {
                    black_box(iterate(m, &ex.patch, r, [0.5, 0.5], &opts));
                }
            })
        });
    }
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
