//! The generator's rays ([`aim_ray`]): for a patch and a feature on it, a
//! ray built so that its true hit lies on the feature up to the rounding of
//! one float (and ±1..3 ulps): across the feature ("cross"), vertical onto
//! it, along an edge or knot line, at the rounded extremum of the height
//! along its line ("tangent"), along `u` onto a flat edge ("edge-tangent"),
//! or starting on the surface ("start").

use super::case::{Case, Family};
use super::exact::{nearest, pow2, qf, qi, ulps, Q};
use super::generate::Mix;
use super::grid::{dyadic01, target, Along, Grid, Target};
use super::restrict::{restrict, RPiece, TOfS};
use super::surface::Surface;
use super::truth::{Piece, Root};

/// `0` (often), or `±1..3`.
fn wiggle(rng: &mut Mix) -> i32 {
    rng.pick(&[0, 0, 0, 0, 1, -1, 1, -1, 2, -2, 3, -3])
}

fn tag(k: i32) -> String {
    if k == 0 {
        String::new()
    } else {
        format!("{k:+}ulp")
    }
}

/// A horizontal direction `(dx, dy)`, exact dyadic (or, one time in eight, a
/// full-precision slope), of size about `2^e`.
fn direction(rng: &mut Mix, dy_zero: bool) -> (f64, f64) {
    let sx = rng.pick(&[1.0, -1.0]);
    let sy = rng.pick(&[1.0, -1.0]);
    let e = scale(rng);
    if dy_zero {
        return (sx * e, 0.0);
    }
    let k = rng.range(1, 16) as f64 / 16.0;
    let (dx, dy) = match rng.range(0, 7) {
        0 => (1.0, 0.0),
        1 => (0.0, 1.0),
        2 | 3 => (1.0, k),
        4 | 5 => (k, 1.0),
        _ => (1.0, rng.signed()),
    };
    (sx * dx * e, sy * dy * e)
}

/// A power of two about 1, or (one time in twenty) `2^±100`: `t` scales
/// inversely.
fn scale(rng: &mut Mix) -> f64 {
    if rng.chance(0.05) {
        pow2(rng.pick(&[-100, 100]))
    } else {
        pow2(rng.range(-2, 2))
    }
}

/// The builder of rays for one patch.
struct Aim<'a> {
    g: &'a Grid,
    surf: Surface,
    rational: bool,
}

impl Aim<'_> {
    /// `(x, y)` of the parameter point, exactly.
    fn xy(&self, u: f64, v: f64) -> (Q, Q) {
        let [a, x0, b, y0] = self.g.affine.map(qf);
        let (u, v) = (qf(u), qf(v));
        let x = if self.rational {
            let [nx, _, w] = self.surf.hom(&u, &v, self.surf.cell_of(&u, &v));
            nx / w
        } else {
            x0 + a * &u
        };
        (x, y0 + b * v)
    }

    /// A time `t0` (a power of two) after which a ray with horizontal speed
    /// `m` has crossed the whole footprint.
    fn lead_time(&self, m: f64) -> f64 {
        let [a, _, b, _] = self.g.affine;
        let span = (self.g.dom[1] - self.g.dom[0]) * a.abs() + (self.g.dom[3] - self.g.dom[2]) * b.abs() + 2.0;
        pow2((span / m).log2().ceil() as i64)
    }

    /// Horizontal (or slightly slanted) through the target, `oz` its rounded height.
    fn cross(&self, rng: &mut Mix, t: &Target) -> ([f64; 3], [f64; 3], String) {
        let (dx, dy) = direction(rng, self.rational);
        let slant = rng.chance(0.25);
        let dz = if slant {
            rng.pick(&[0.0625, -0.25, 1.0, -4.0]) * dx.abs().max(dy.abs())
        } else {
            0.0
        };
        self.cross_with(rng, t, [dx, dy, dz])
    }

    fn cross_with(&self, rng: &mut Mix, t: &Target, [dx, dy, dz]: [f64; 3]) -> ([f64; 3], [f64; 3], String) {
        let t0 = self.lead_time(dx.abs().max(dy.abs()));
        let (x, y) = self.xy(t.u, t.v);
        let z = self.surf.height(&qf(t.u), &qf(t.v));
        let k = wiggle(rng);
        let o = [
            nearest(&(x - qf(t0 * dx))),
            nearest(&(y - qf(t0 * dy))),
            ulps(nearest(&(z - qf(t0 * dz))), k),
        ];
        (o, [dx, dy, dz], format!("cross dz={dz} oz{}", tag(k)))
    }

    /// Vertical through the rounded target, `(ox, oy)` moved by a few ulps.
    fn vertical(&self, rng: &mut Mix, t: &Target) -> ([f64; 3], [f64; 3], String) {
        let (x, y) = self.xy(t.u, t.v);
        let (kx, ky) = (wiggle(rng), wiggle(rng));
        let e = scale(rng);
        let down = rng.chance(0.5);
        let o = [
            ulps(nearest(&x), kx),
            ulps(nearest(&y), ky),
            if down { 2.0 } else { -2.0 },
        ];
        let d = [0.0, 0.0, if down { -e } else { e }];
        (o, d, format!("vertical ox{} oy{}", tag(kx), tag(ky)))
    }

    /// Horizontal, in the vertical plane over the line `along` (moved by a
    /// few ulps), at the rounded height of the target.
    fn along(&self, rng: &mut Mix, t: &Target, along: Along) -> ([f64; 3], [f64; 3], String) {
        let [a, x0, b, y0] = self.g.affine;
        let e = pow2(rng.range(-2, 2));
        let sign = rng.pick(&[1.0, -1.0]);
        let k = wiggle(rng);
        let z = nearest(&self.surf.height(&qf(t.u), &qf(t.v)));
        let (o, d) = match along {
            Along::U(c) => {
                let t0 = self.lead_time(e);
                let y = y0 + b * t.v;
                ([ulps(x0 + a * c, k), y - t0 * sign * e, z], [0.0, sign * e, 0.0])
            }
            Along::V(c) => {
                let t0 = self.lead_time(e);
                let x = nearest(&self.xy(t.u, t.v).0);
                ([x - t0 * sign * e, ulps(y0 + b * c, k), z], [sign * e, 0.0, 0.0])
            }
            Along::Hyp => {
                // Points (x0 + a·u, y0 + b·(1 − u)), from u = −1 up or u = 2 down.
                let d = [sign * a * e, -sign * b * e, 0.0];
                let u = if sign > 0.0 { -1.0 } else { 2.0 };
                ([ulps(x0 + a * u, k), y0 + b * (1.0 - u), z], d)
            }
        };
        (o, d, format!("along {along:?} ({}){}", t.name, tag(k)))
    }

    /// From the rounded target point on the surface itself, leaving it
    /// slanted: a hit at `t ≈ 0`, just inside or outside the range `t ≥ 0`.
    fn start(&self, rng: &mut Mix, t: &Target) -> ([f64; 3], [f64; 3], String) {
        let (dx, dy) = direction(rng, self.rational);
        let dz = rng.pick(&[0.25, -0.25, 1.0, -1.0, 4.0]) * dx.abs().max(dy.abs());
        let (x, y) = self.xy(t.u, t.v);
        let z = self.surf.height(&qf(t.u), &qf(t.v));
        let (kx, kz) = (wiggle(rng), wiggle(rng));
        let o = [ulps(nearest(&x), kx), nearest(&y), ulps(nearest(&z), kz)];
        (o, [dx, dy, dz], format!("start dz={dz} ox{} oz{}", tag(kx), tag(kz)))
    }

    /// Horizontal through the target, across in a random direction or along
    /// its feature line, `oz` the rounded value of an extremum of the height
    /// along the line: two hits a few 1e-8 apart, or none.
    fn tangent(&self, rng: &mut Mix, t: &Target) -> Option<([f64; 3], [f64; 3], String)> {
        let along = t.along.filter(|_| rng.chance(0.5));
        let (mut o, d, _) = match along {
            Some(a) => self.along(rng, t, a),
            None => self.cross(rng, t),
        };
        let d = [d[0], d[1], 0.0];
        o[2] = 0.0;
        let probe = Case {
            family: Family::Tensor,
            seed: 0,
            label: String::new(),
            spec: self.g.spec.clone(),
            affine: self.g.affine,
            origin: o,
            dir: d,
        };
        let r = restrict(&probe);
        // (lo, hi, height along the line, its derivative's numerator).
        let mut cands = Vec::new();
        for RPiece { lo, hi, p: h, t } in r.pieces.into_iter().filter(|rp| rp.lo < rp.hi) {
            if self.rational {
                // h = dx·N_z here; the height is N_z / D with D = t.den / |dx|.
                let crit = h.deriv().mul(&t.den).sub(&h.mul(&t.den.deriv()));
                cands.push((lo, hi, h, Some(t.den), crit));
            } else {
                let crit = h.deriv();
                cands.push((lo, hi, h, None, crit));
            }
        }
        let mut zeros = Vec::new();
        for (lo, hi, h, den, crit) in &cands {
            if crit.is_zero() || crit.degree() == 0 {
                continue;
            }
            let piece = Piece::new(lo.clone(), hi.clone(), crit, TOfS::identity());
            for root in piece.roots(0) {
                let s = match root {
                    Root::Exact(x) => x,
                    Root::Iso { lo, hi, .. } => {
                        let (mut lo, mut hi) = (lo, hi);
                        let mut exact = None;
                        for _ in 0..100 {
                            exact = piece.bisect(&mut lo, &mut hi);
                            if exact.is_some() {
                                break;
                            }
                        }
                        exact.unwrap_or((lo + hi) / qi(2))
                    }
                };
                let z = match den {
                    Some(den) => h.eval(&s) / den.eval(&s) * qf(d[0].abs()) / qf(d[0]),
                    None => h.eval(&s),
                };
                zeros.push(z);
            }
        }
        if zeros.is_empty() {
            return None;
        }
        let z = &zeros[rng.range(0, zeros.len() as i64 - 1) as usize];
        let k = wiggle(rng);
        o[2] = ulps(nearest(z), k);
        let how = if along.is_some() { "tangent-along" } else { "tangent" };
        Some((o, d, format!("{how} oz{}", tag(k))))
    }
}

/// A ray aimed at a random feature of `g` by a random construction, and
/// how (`"… @ feature"`).
pub(super) fn aim_ray(g: &Grid, family: Family, rng: &mut Mix) -> ([f64; 3], [f64; 3], String) {
    let probe = Case {
        family,
        seed: 0,
        label: String::new(),
        spec: g.spec.clone(),
        affine: g.affine,
        origin: [0.0; 3],
        dir: [0.0; 3],
    };
    let aim = Aim {
        surf: Surface::of(&probe),
        g,
        rational: family.rational(),
    };
    let mut t = g.targets[rng.range(0, g.targets.len() as i64 - 1) as usize].clone();
    let (o, d, how) = match rng.range(0, if g.flat_edge.is_some() { 6 } else { 4 }) {
        5 => {
            // Along u at the rounded height of the flat edge: a double hit
            // on the edge, split by the rounding into two hits straddling
            // it (or none).
            let c = g.flat_edge.unwrap();
            let r = dyadic01(rng);
            let v = g.dom[2] + (g.dom[3] - g.dom[2]) * rng.pick(&[0.0, r, r, 1.0]);
            t = target(format!("flat edge u={c} v={v}"), c, v, None);
            let dx = rng.pick(&[1.0, -1.0]) * scale(rng);
            let (o, d, how) = aim.cross_with(rng, &t, [dx, 0.0, 0.0]);
            (o, d, how.replace("cross", "edge-tangent"))
        }
        0 => aim.cross(rng, &t),
        1 => aim.vertical(rng, &t),
        2 => match t.along {
            Some(along) => aim.along(rng, &t, along),
            None => aim.cross(rng, &t),
        },
        3 => aim.tangent(rng, &t).unwrap_or_else(|| aim.cross(rng, &t)),
        _ => aim.start(rng, &t),
    };
    (o, d, format!("{how} @ {}", t.name))
}
