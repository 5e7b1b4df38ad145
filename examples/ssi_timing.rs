//! Surface/surface intersection timings: time per pair, per certified point,
//! and how it grows with degree.
//!
//! `cargo run --release --example ssi_timing` (`SSI_REPS=n` sets the
//! repetitions of every case, `SSI_ONLY=text` picks cases by name).

use rootclip::glam::DVec3;
use rootclip::ray::{Patch, TensorPatch};
use rootclip::ssi::{intersect_surfaces, SsiOptions};
use std::time::Instant;

/// A height field over the square `[x0, x0 + w] × [y0, y0 + w]` rotated by
/// `angle`, bidegree `(n, n)`, heights `z(i, j)`.
fn field(n: usize, x0: f64, y0: f64, w: f64, angle: f64, z: impl Fn(usize, usize) -> f64) -> Patch {
    let (c, s) = (angle.cos(), angle.sin());
    let mut pts = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (x0 + w * i as f64 / n as f64, y0 + w * j as f64 / n as f64);
            pts.push(DVec3::new(c * x - s * y, s * x + c * y, z(i, j)));
        }
    }
    Patch::from(TensorPatch::new(n, n, pts, None).unwrap())
}

/// Deterministic pseudo-random numbers in `[−1, 1]`.
fn noise(seed: u64) -> impl Fn(usize, usize) -> f64 {
    move |i, j| {
        let mut x = seed ^ ((i as u64) << 32 | j as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        x ^= x >> 33;
        x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
        x ^= x >> 33;
        (x % 2_000_001) as f64 / 1_000_000.0 - 1.0
    }
}

fn run(name: &str, a: &Patch, b: &Patch, reps: usize) {
    // `SSI_REPS=1` for profiling runs (callgrind, perf); `SSI_ONLY=text`
    // runs only the cases whose name holds it.
    let reps = std::env::var("SSI_REPS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(reps);
    let opts = SsiOptions::default();
    if std::env::var("SSI_ONLY").is_ok_and(|only| !name.contains(&only)) {
        return;
    }
    let mut out = intersect_surfaces(a, b, &opts).unwrap();
    let t = Instant::now();
    for _ in 0..reps {
        out = intersect_surfaces(a, b, &opts).unwrap();
    }
    let ms = t.elapsed().as_secs_f64() * 1e3 / reps as f64;
    let pts = out.stats.certified_points.max(1);
    println!(
        "{name:<34} {:>3} branches ({} closed) {:>5} pts  complete={:<5} {:>9.2} ms  {:>7.1} µs/pt  crossings {} turning {} boxes {}",
        out.branches.len(),
        out.branches.iter().filter(|b| b.closed).count(),
        out.stats.certified_points,
        out.complete,
        ms,
        ms * 1e3 / pts as f64,
        out.stats.crossings,
        out.stats.turning_points,
        out.stats.boxes
    );
    for s in &out.singular {
        println!("    singular {:?} a {:?} b {:?}", s.kind, s.a, s.b);
    }
}

fn main() {
    // Alsaïdi's Example 5.1 on [−3, 3]²: z = x² + y² and z = 9 − (x² + y²)/5.
    let sq = [9.0, -9.0, 9.0];
    let p1 = field(2, -3.0, -3.0, 6.0, 0.0, |i, j| sq[i] + sq[j]);
    let p2 = field(2, -3.0, -3.0, 6.0, 0.0, |i, j| 9.0 - (sq[i] + sq[j]) / 5.0);
    run("Alsaïdi Ex. 5.1 (paraboloids)", &p1, &p2, 5);
    // Bicubic pairs: a wavy field and a rotated, tilted one.
    for seed in 1..=6u64 {
        let za = noise(seed);
        let zb = noise(seed + 100);
        let a = field(3, 0.0, 0.0, 1.0, 0.0, move |i, j| 0.3 * za(i, j));
        let b = field(3, -0.1, -0.2, 1.2, 0.4, move |i, j| {
            0.25 * zb(i, j) + 0.1 * i as f64 - 0.05
        });
        run(&format!("bicubic/bicubic seed {seed}"), &a, &b, 5);
    }
    // Degree growth.
    for n in [2usize, 3, 4, 5, 6] {
        let za = noise(7);
        let zb = noise(8);
        let a = field(n, 0.0, 0.0, 1.0, 0.0, move |i, j| 0.3 * za(i, j));
        let b = field(n, -0.1, -0.2, 1.2, 0.4, move |i, j| {
            0.25 * zb(i, j) + 0.1 * i as f64 / n as f64 * 3.0 - 0.05
        });
        run(&format!("degree ({n}, {n}) pair"), &a, &b, 2);
    }
}
