//! The query families of the measurement: random rays, rays grazing a curve
//! at a set distance, exact tangencies, rays aimed at the ends of the
//! parameter range, and (3D) nearly vertical rays. Every family is drawn
//! from a fixed seed, so the tables are reproducible.

use rootclip::glam::{DVec2, DVec3};
use rootclip::internals::Rng;

/// A 2D ray against a quadratic Bézier curve.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    pub o: DVec2,
    pub d: DVec2,
    pub p: [DVec2; 3],
}

/// A 2D ray against the segment `l(t) = t a + (1 − t) b`.
#[derive(Clone, Copy, Debug)]
pub struct Seg {
    pub o: DVec2,
    pub d: DVec2,
    pub a: DVec2,
    pub b: DVec2,
}

/// A 3D ray against the curve `p` swept by `e` along `z`.
#[derive(Clone, Copy, Debug)]
pub struct Swept {
    pub o: DVec3,
    pub d: DVec3,
    pub p: [DVec2; 3],
    pub e: f64,
}

/// A named set of queries.
pub struct Family<C> {
    pub name: String,
    pub cases: Vec<C>,
}

fn point(rng: &mut Rng, r: f64) -> DVec2 {
    DVec2::new(r * rng.next_signed(), r * rng.next_signed())
}

/// `b(t)` in `f64` (de Casteljau).
pub fn bez(p: &[DVec2; 3], t: f64) -> DVec2 {
    let a = p[0].lerp(p[1], t);
    let b = p[1].lerp(p[2], t);
    a.lerp(b, t)
}

/// `b'(t)`.
pub fn bez_d(p: &[DVec2; 3], t: f64) -> DVec2 {
    2.0 * ((1.0 - t) * (p[1] - p[0]) + t * (p[2] - p[1]))
}

fn perp(v: DVec2) -> DVec2 {
    DVec2::new(-v.y, v.x)
}

/// A random curve that bends clearly (no near-straight curves: a grazing
/// ray needs a curvature to graze).
fn bent_curve(rng: &mut Rng) -> [DVec2; 3] {
    loop {
        let p = [point(rng, 1.0), point(rng, 1.0), point(rng, 1.0)];
        let a2 = p[0] - 2.0 * p[1] + p[2];
        let chord = p[2] - p[0];
        if a2.length() > 0.3 && chord.perp_dot(a2).abs() > 0.2 * chord.length() * a2.length() {
            return p;
        }
    }
}

/// A ray at distance `h` from the curve at a random `t*`, parallel to its
/// tangent there, on the concave side (`inside`: two hits) or the convex
/// side (none), starting two units before the tangent point.
fn grazing(rng: &mut Rng, p: &[DVec2; 3], h: f64, inside: bool) -> (DVec2, DVec2) {
    let t = 0.2 + 0.6 * rng.next_f64();
    let tan = bez_d(p, t).normalize();
    let mut nrm = perp(tan);
    if nrm.dot(p[0] - 2.0 * p[1] + p[2]) < 0.0 {
        nrm = -nrm;
    }
    let q = bez(p, t) + if inside { h } else { -h } * nrm;
    (q - 2.0 * tan, tan)
}

pub fn quad_random(rng: &mut Rng, n: usize) -> Family<Quad> {
    let cases = (0..n)
        .map(|_| {
            let p = [point(rng, 1.0), point(rng, 1.0), point(rng, 1.0)];
            let o = point(rng, 3.0);
            let target = bez(&p, rng.next_f64()) + point(rng, 0.1);
            Quad { o, d: target - o, p }
        })
        .collect();
    Family {
        name: "random (aimed near the curve)".into(),
        cases,
    }
}

pub fn quad_grazing(rng: &mut Rng, n: usize, h: f64, inside: bool) -> Family<Quad> {
    let cases = (0..n)
        .map(|_| {
            let p = bent_curve(rng);
            let (o, d) = grazing(rng, &p, h, inside);
            Quad { o, d, p }
        })
        .collect();
    let side = if inside { "inside (2 hits)" } else { "outside (0 hits)" };
    Family {
        name: format!("grazing at {h:.0e}, {side}"),
        cases,
    }
}

/// A dyadic in `[−1, 1]` with `bits` bits after the point.
fn dyadic(rng: &mut Rng, bits: i32) -> f64 {
    let s = 2f64.powi(bits);
    (rng.next_signed() * s).round() / s
}

/// Exact tangencies: dyadic control points (24 bits) and `t*` (10 bits),
/// so `b(t*)`, `d = b'(t*)` and `o = b(t*) − d` are exact floats and
/// `n·(b(t) − o)` has an exact double root at `t*`.
pub fn quad_tangent(rng: &mut Rng, n: usize) -> Family<Quad> {
    let mut cases = Vec::with_capacity(n);
    while cases.len() < n {
        let p = [0, 1, 2].map(|_| DVec2::new(dyadic(rng, 24), dyadic(rng, 24)));
        let t = (100.0 + (rng.next_f64() * 824.0).floor()) / 1024.0;
        let d = bez_d(&p, t);
        let bent = d.perp_dot(p[0] - 2.0 * p[1] + p[2]).abs() > 0.05 * d.length();
        if d.length() > 0.1 && bent {
            cases.push(Quad {
                o: bez(&p, t) - d,
                d,
                p,
            });
        }
    }
    Family {
        name: "exact tangency (double root)".into(),
        cases,
    }
}

/// Rays aimed at an end point (`end` 0: `p₀`, 2: `p₂`) from a random
/// origin, `d = p_end − o` rounded: the hit lies within rounding of the end
/// of the parameter range, inside or outside.
pub fn quad_aimed_end(rng: &mut Rng, n: usize, end: usize) -> Family<Quad> {
    let cases = (0..n)
        .map(|_| {
            let p = bent_curve(rng);
            let o = point(rng, 3.0);
            Quad { o, d: p[end] - o, p }
        })
        .collect();
    Family {
        name: format!("aimed at p{end} (t = {})", end / 2),
        cases,
    }
}

/// `p₀ = (0, 0)` and a horizontal ray at height `±1e-300`: the hit lies
/// `~1e-300` inside (`+`) or outside (`−`) the end `t = 0`.
pub fn quad_tiny_off_end(rng: &mut Rng, n: usize, above: bool) -> Family<Quad> {
    let cases = (0..n)
        .map(|_| {
            let p1 = DVec2::new(rng.next_signed(), 0.2 + 0.8 * rng.next_f64());
            let p2 = DVec2::new(rng.next_signed(), 0.2 + 0.8 * rng.next_f64());
            let y = if above { 1e-300 } else { -1e-300 };
            Quad {
                o: DVec2::new(-2.0, y),
                d: DVec2::X,
                p: [DVec2::ZERO, p1, p2],
            }
        })
        .collect();
    let side = if above { "inside" } else { "outside" };
    Family {
        name: format!("1e-300 {side} the end t = 0"),
        cases,
    }
}

pub fn seg_random(rng: &mut Rng, n: usize) -> Family<Seg> {
    let cases = (0..n)
        .map(|_| {
            let (a, b) = (point(rng, 1.0), point(rng, 1.0));
            let o = point(rng, 3.0);
            let target = b.lerp(a, rng.next_f64()) + point(rng, 0.1);
            Seg { o, d: target - o, a, b }
        })
        .collect();
    Family {
        name: "random (aimed near the segment)".into(),
        cases,
    }
}

/// Rays at angle `angle` to the segment, aimed at its midpoint.
pub fn seg_near_parallel(rng: &mut Rng, n: usize, angle: f64) -> Family<Seg> {
    let cases = (0..n)
        .map(|_| {
            let (a, b) = (point(rng, 1.0), point(rng, 1.0));
            let u = (a - b).normalize();
            let d = u + angle * perp(u);
            let m = 0.5 * (a + b);
            Seg {
                o: m - 2.0 * d,
                d,
                a,
                b,
            }
        })
        .collect();
    Family {
        name: format!("at angle {angle:.0e} to the segment"),
        cases,
    }
}

/// Rays aimed at an end (`a`: `t = 1`), `d = a − o` rounded.
pub fn seg_aimed_end(rng: &mut Rng, n: usize) -> Family<Seg> {
    let cases = (0..n)
        .map(|_| {
            let (a, b) = (point(rng, 1.0), point(rng, 1.0));
            let o = point(rng, 3.0);
            Seg { o, d: a - o, a, b }
        })
        .collect();
    Family {
        name: "aimed at a (t = 1)".into(),
        cases,
    }
}

/// `b = (0, 0)` and a horizontal ray at height `±1e-300`.
pub fn seg_tiny_off_end(rng: &mut Rng, n: usize, above: bool) -> Family<Seg> {
    let cases = (0..n)
        .map(|_| {
            let a = DVec2::new(rng.next_signed(), 0.2 + 0.8 * rng.next_f64());
            let y = if above { 1e-300 } else { -1e-300 };
            Seg {
                o: DVec2::new(-2.0, y),
                d: DVec2::X,
                a,
                b: DVec2::ZERO,
            }
        })
        .collect();
    let side = if above { "inside" } else { "outside" };
    Family {
        name: format!("1e-300 {side} the end t = 0"),
        cases,
    }
}

fn lift(v: DVec2, z: f64) -> DVec3 {
    DVec3::new(v.x, v.y, z)
}

pub fn swept_random(rng: &mut Rng, n: usize) -> Family<Swept> {
    let cases = (0..n)
        .map(|_| {
            let p = [point(rng, 1.0), point(rng, 1.0), point(rng, 1.0)];
            let e = 0.5 + 1.5 * rng.next_f64();
            let o = lift(point(rng, 3.0), e * (2.0 * rng.next_f64() - 0.5));
            let target = lift(bez(&p, rng.next_f64()) + point(rng, 0.1), e * rng.next_f64());
            Swept { o, d: target - o, p, e }
        })
        .collect();
    Family {
        name: "random (aimed near the patch)".into(),
        cases,
    }
}

/// The 2D grazing rays, rising or falling so that the hits lie at
/// `u ∈ [0.3, 0.7]`.
pub fn swept_grazing(rng: &mut Rng, n: usize, h: f64, inside: bool) -> Family<Swept> {
    let cases = (0..n)
        .map(|_| {
            let p = bent_curve(rng);
            let (o, d) = grazing(rng, &p, h, inside);
            let e = 0.5 + 1.5 * rng.next_f64();
            let dz = 0.2 * rng.next_signed();
            let u = 0.3 + 0.4 * rng.next_f64();
            Swept {
                o: lift(o, e * u - 2.0 * dz),
                d: lift(d, dz),
                p,
                e,
            }
        })
        .collect();
    let side = if inside { "inside" } else { "outside" };
    Family {
        name: format!("grazing at {h:.0e} in plan, {side}"),
        cases,
    }
}

/// Rays through a random point of the patch, direction `(ε w, 1)`: nearly
/// parallel to the sweep.
pub fn swept_near_vertical(rng: &mut Rng, n: usize, eps: f64) -> Family<Swept> {
    let cases = (0..n)
        .map(|_| {
            let p = bent_curve(rng);
            let e = 0.5 + 1.5 * rng.next_f64();
            let t = 0.1 + 0.8 * rng.next_f64();
            let u = 0.2 + 0.6 * rng.next_f64();
            let angle = std::f64::consts::TAU * rng.next_f64();
            let w = DVec2::new(angle.cos(), angle.sin());
            let d = lift(eps * w, 1.0);
            let hit = lift(bez(&p, t), e * u);
            Swept {
                o: hit - 0.5 * d,
                d,
                p,
                e,
            }
        })
        .collect();
    Family {
        name: format!("direction (ε w, 1), ε = {eps:.0e}"),
        cases,
    }
}

/// Horizontal rays at height `z = ±1e-300` (the patch's bottom edge is
/// `z = 0`): hits `1e-300` inside or outside `u = 0`.
pub fn swept_tiny_off_edge(rng: &mut Rng, n: usize, above: bool) -> Family<Swept> {
    let cases = (0..n)
        .map(|_| {
            let p = [point(rng, 1.0), point(rng, 1.0), point(rng, 1.0)];
            let e = 0.5 + 1.5 * rng.next_f64();
            let o = point(rng, 3.0);
            let target = bez(&p, rng.next_f64());
            let z = if above { 1e-300 } else { -1e-300 };
            Swept {
                o: lift(o, z),
                d: lift(target - o, 0.0),
                p,
                e,
            }
        })
        .collect();
    let side = if above { "inside" } else { "outside" };
    Family {
        name: format!("horizontal, 1e-300 {side} the edge u = 0"),
        cases,
    }
}
