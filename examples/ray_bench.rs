//! Whole-process timing of certified all-hits queries: 10,000 random rays
//! aimed at the bicubic patch of seed 000's Example 1
//! (tests/data/seed000_example1.json), one thread.
//!
//! Rays: origins uniform on a sphere of radius 12 around the centre of the
//! control net's bounding box, each aimed at a uniform point of that box
//! (fixed seed). Prints time per ray and counts of certified hits,
//! undecided regions and degenerate rays.
//!
//! `cargo run --release --example ray_bench [N]`

use glam::DVec3;
use rootclip::ray::{cli, default_options, intersect, RayOutcome};
use std::time::Instant;

/// xorshift64*: a fixed, dependency-free stream of uniform floats.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(10_000), |s| s.parse())?;
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/seed000_example1.json"))?;
    let v: serde_json::Value = serde_json::from_str(&text)?;
    let patch = cli::parse_patch(&v["patch"].to_string())?;
    let (lo, hi) = patch
        .points()
        .iter()
        .fold((DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)), |(l, h), p| {
            (l.min(*p), h.max(*p))
        });
    let centre = (lo + hi) / 2.0;
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let rays: Vec<rootclip::ray::Ray> = (0..n)
        .map(|_| {
            let z = 2.0 * rng.next() - 1.0;
            let phi = std::f64::consts::TAU * rng.next();
            let r = (1.0 - z * z).sqrt();
            let origin = centre + 12.0 * DVec3::new(r * phi.cos(), r * phi.sin(), z);
            let target = lo + (hi - lo) * DVec3::new(rng.next(), rng.next(), rng.next());
            rootclip::ray::Ray::new(origin, target - origin).expect("finite, non-zero")
        })
        .collect();
    let opts = default_options();
    let (mut certified, mut undecided, mut degenerate, mut max_hits) = (0, 0, 0, 0);
    let t0 = Instant::now();
    for ray in &rays {
        match intersect(&patch, ray, &opts)? {
            RayOutcome::Hits(h) => {
                certified += h.hits.iter().filter(|x| x.certified).count();
                undecided += h.hits.iter().filter(|x| !x.certified).count();
                max_hits = max_hits.max(h.hits.len());
            }
            RayOutcome::Degenerate(_) => degenerate += 1,
        }
    }
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "{n} rays: {:.2} µs/ray; {certified} certified hits, {undecided} undecided regions, {degenerate} degenerate rays, at most {max_hits} hits on a ray",
        secs * 1e6 / n as f64
    );
    Ok(())
}
