//! Certified surface/surface intersection (`rootclip::ssi::intersect_surfaces`)
//! with the default options: Alsaïdi's Example 5.1 (two paraboloids of
//! bidegree (2, 2), one closed loop), `ssi/ex5.1`; a bicubic pair with two
//! branches, `ssi/bicubic`; and a bicubic pair that does not meet,
//! `ssi/bicubic-apart` (the start-point solves alone). The same pairs, the
//! time per certified point and the growth with degree are printed by
//! `cargo run --release --example ssi_timing`; the numbers are in
//! `docs/performance.md`.
//!
//! `cargo bench --bench ssi` takes about half a minute.

use criterion::{criterion_group, criterion_main, Criterion};
use rootclip::glam::DVec3;
use rootclip::ray::{Patch, TensorPatch};
use rootclip::ssi::{intersect_surfaces, SsiOptions};
use std::hint::black_box;
use std::time::Duration;

/// A height field over `[x0, x0 + w] × [y0, y0 + w]` rotated by `angle`,
/// bidegree `(n, n)` (as in `examples/ssi_timing.rs`).
fn field(n: usize, x0: f64, y0: f64, w: f64, angle: f64, z: impl Fn(usize, usize) -> f64) -> Patch {
    let (c, s) = (angle.cos(), angle.sin());
    let mut pts = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (x0 + w * i as f64 / n as f64, y0 + w * j as f64 / n as f64);
            pts.push(DVec3::new(c * x - s * y, s * x + c * y, z(i, j)));
        }
    }
    Patch::from(TensorPatch::new(n, n, pts, None).expect("patch"))
}

/// Deterministic pseudo-random numbers in `[−1, 1]` (as in the example).
fn noise(seed: u64) -> impl Fn(usize, usize) -> f64 {
    move |i, j| {
        let mut x = seed ^ ((i as u64) << 32 | j as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        x ^= x >> 33;
        x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
        x ^= x >> 33;
        (x % 2_000_001) as f64 / 1_000_000.0 - 1.0
    }
}

fn bicubic(seed: u64) -> (Patch, Patch) {
    let (za, zb) = (noise(seed), noise(seed + 100));
    let a = field(3, 0.0, 0.0, 1.0, 0.0, move |i, j| 0.3 * za(i, j));
    let b = field(3, -0.1, -0.2, 1.2, 0.4, move |i, j| {
        0.25 * zb(i, j) + 0.1 * i as f64 - 0.05
    });
    (a, b)
}

fn bench(c: &mut Criterion) {
    let opts = SsiOptions::default();
    let sq = [9.0, -9.0, 9.0];
    let p1 = field(2, -3.0, -3.0, 6.0, 0.0, |i, j| sq[i] + sq[j]);
    let p2 = field(2, -3.0, -3.0, 6.0, 0.0, |i, j| 9.0 - (sq[i] + sq[j]) / 5.0);
    let mut g = c.benchmark_group("ssi");
    g.measurement_time(Duration::from_secs(4)).sample_size(20);
    g.bench_function("ex5.1", |b| {
        b.iter(|| intersect_surfaces(black_box(&p1), black_box(&p2), &opts).expect("ssi"))
    });
    for (name, seed) in [("bicubic", 1u64), ("bicubic-apart", 4)] {
        let (pa, pb) = bicubic(seed);
        g.bench_function(name, |b| {
            b.iter(|| intersect_surfaces(black_box(&pa), black_box(&pb), &opts).expect("ssi"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
