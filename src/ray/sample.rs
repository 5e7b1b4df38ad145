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

/// `n` rays aimed at uniform random points of the patch (issue 20's hard
/// rays): `P = S(a, b)` for uniform `(a, b)` in the unit square, origin
/// `o = P + (U(2, 6), U(−3, 3), U(−3, 3))`, direction `P − o` (so `t = 1`
/// hits, up to rounding; many rays nearly graze a fold of the surface).
/// For tensor and B-spline patches (`(a, b)` over the unit square).
pub fn surface_aimed_rays(patch: &Patch, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed.max(1));
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let p = patch.eval(rng.next_f64(), rng.next_f64());
        let off = DVec3::new(
            2.0 + 4.0 * rng.next_f64(),
            3.0 * rng.next_signed(),
            3.0 * rng.next_signed(),
        );
        let origin = p + off;
        if let Ok(ray) = Ray::new(origin, p - origin) {
            out.push(ray);
        }
    }
    out
}

/// `n` secondary rays: origins on the patch, `o = S(a, b)` evaluated in
/// `f64` (every other one at a dyadic `(a, b)` on a 1/64 grid, where the
/// evaluation is often exact, so the origin lies exactly on the surface:
/// a `t = 0` hit), directions uniform on the unit sphere.
pub fn secondary_rays(patch: &Patch, n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed.max(1));
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let (mut a, mut b) = (rng.next_f64(), rng.next_f64());
        if out.len() % 2 == 0 {
            (a, b) = ((a * 64.0).round() / 64.0, (b * 64.0).round() / 64.0);
        }
        let z = rng.next_signed();
        let phi = std::f64::consts::TAU * rng.next_f64();
        let r = (1.0 - z * z).sqrt();
        if let Ok(ray) = Ray::new(patch.eval(a, b), DVec3::new(r * phi.cos(), r * phi.sin(), z)) {
            out.push(ray);
        }
    }
    out
}
