//! Reproducible ray sets for benchmarks, examples and tests.

use super::query::Ray;
use super::surface::Patch;
use glam::DVec3;

pub use crate::rng::Rng;

/// `n` rays with origins uniform on the sphere of radius `radius` around the
/// centre of the control net's bounding box, each aimed at a uniform point
/// of that box: about half hit the patch (the benchmark rays).
pub fn aimed_rays(patch: &Patch, n: usize, radius: f64, seed: u64) -> Vec<Ray> {
    let (lo, hi) = patch
        .points()
        .iter()
        .fold((DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)), |(l, h), p| {
            (l.min(*p), h.max(*p))
        });
    let centre = (lo + hi) / 2.0;
    let mut rng = Rng(seed.max(1));
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let z = 2.0 * rng.next_f64() - 1.0;
        let phi = std::f64::consts::TAU * rng.next_f64();
        let r = (1.0 - z * z).sqrt();
        let origin = centre + radius * DVec3::new(r * phi.cos(), r * phi.sin(), z);
        let target = lo + (hi - lo) * DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64());
        if let Ok(ray) = Ray::new(origin, target - origin) {
            out.push(ray);
        }
    }
    out
}
