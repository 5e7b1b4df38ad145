//! Tri-boxes: triangular sub-domains with exact `f64` vertices, and the two
//! ways the driver replaces one — a clip and a 1-to-4 split — each *verified*
//! to cover what it replaces.
//!
//! Vertices are points in the root triangle's local Cartesian coordinates
//! `(s, t)` (barycentric `(s, t, 1 − s − t)`). A vertex is an exact `f64`, and
//! the polynomial on a tri-box is an enclosure for exactly that triangle, so the
//! reported regions are the ones the proofs are about.
//!
//! Rounding: a clip is computed in the parent's barycentric coordinates and
//! its corners are enclosed in intervals; the proposed `f64` triangle is pushed
//! outward a few ulps and accepted only once interval orientation tests prove it
//! contains all three enclosed corners. A split's midpoints are nudged outward
//! until each is proven on or outside its edge, so the four children cover the
//! parent.

use crate::scalar::geo::{Geo, GeoIv};
use crate::scalar::{interval, point};
use inari::Interval;

/// A point `(s, t)`.
pub type Pt = [f64; 2];

/// A tri-box: vertices `V1, V2, V3` (counter-clockwise) and its recursion level.
#[derive(Clone, Debug, PartialEq)]
pub struct TriBox {
    /// `V1` (local `u = 1`), `V2` (`v = 1`), `V3` (`w = 1`).
    pub verts: [Pt; 3],
}

fn sub(a: Pt, b: Pt) -> Pt {
    [a[0] - b[0], a[1] - b[1]]
}

/// The Euclidean length (for step sizes and diameters, not proofs). Tri-box
/// coordinates are near `[0, 1]`, so `√(x² + y²)` cannot overflow and
/// libm's slower `hypot` buys nothing; a non-finite result still propagates.
fn norm(a: Pt) -> f64 {
    (a[0] * a[0] + a[1] * a[1]).sqrt()
}

/// `orient(a, b, c)`: twice the signed area, enclosed (inari's endpoints,
/// through [`GeoIv`]).
pub fn orient(a: [GeoIv; 2], b: [GeoIv; 2], c: [GeoIv; 2]) -> GeoIv {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// A fast proof that every point of the box `k` lies strictly left of the
/// line from `a` to `b` (`orient(a, b, x) > 0`); `false` means "not proven"
/// (the caller then evaluates [`orient`] in `GeoIv`).
///
/// The orientation at the box's centre `m` is evaluated in `f64` and
/// accepted beyond Shewchuk's error bound for `orient2d` on float inputs,
/// `(3 + 16ε)ε · (|ex·dy| + |ey·dx|)` with `ε = 2⁻⁵³`, `e = b − a`,
/// `d = m − a` (Shewchuk 1997, `ccwerrboundA`; valid without underflow,
/// which the `1e-300` slack and the `1e-250` floor keep away); the box
/// moves it by at most `|ex|·r_t + |ey|·r_s` for radii `r` bounding the
/// distance of the box's ends from `m` (any float of the box). Every bound is enlarged by a
/// relative `2⁻⁴⁰`, far above the few roundings of its own evaluation.
fn left_of_filtered(a: Pt, b: Pt, k: [GeoIv; 2]) -> bool {
    const EPS: f64 = f64::EPSILON / 2.0;
    const GROW: f64 = 1.0 + 1.0 / (1u64 << 40) as f64;
    // Any float m in the box serves as centre; the differences to the ends
    // are rounded by at most one relative ε (and are exact when zero).
    let centre_radius = |x: GeoIv| {
        let (lo, hi) = (x.lower(), x.upper());
        let m = 0.5 * lo + 0.5 * hi;
        // (Inside already without underflow; no `clamp`, which panics on NaN.)
        let m = if m < lo {
            lo
        } else if m > hi {
            hi
        } else {
            m
        };
        (m, (hi - m).max(m - lo) * GROW + 1e-300)
    };
    let ((ms, rs), (mt, rt)) = (centre_radius(k[0]), centre_radius(k[1]));
    let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
    let (dx, dy) = (ms - a[0], mt - a[1]);
    let (left, right) = (ex * dy, ey * dx);
    let det = left - right;
    let detsum = left.abs() + right.abs();
    // NaN anywhere fails the comparison.
    if detsum.is_nan() || detsum <= 1e-250 {
        return false;
    }
    let errbound = (3.0 + 16.0 * EPS) * EPS * detsum;
    let shift = ex.abs() * rt + ey.abs() * rs;
    det > (errbound + shift + 1e-300) * GROW * GROW
}

/// An enclosure of `X = o + x (v − o) + y (w − o)` (exact `f64` inputs),
/// coordinate by coordinate, from error-free transformations: `v − o =
/// d + e_d` (TwoSum), `x·d = p + e_p` (FMA remainder), `p_v + p_w = s + e_s`
/// and `o + s = r + e_r` (TwoSum) are exact, so
/// `X = r + (e_r + e_s + e_pv + e_pw + x·e_dv + y·e_dw)`. The bracket is a
/// few ulps of `r` and of the products; it is summed in `f64` as `c`, whose
/// error (five sums and two products of terms bounded by `T = Σ|terms|`) is
/// below `8u·T + 1e-300` with `u = 2⁻⁵³` (the absolute term covers
/// underflowed products and remainders). Then `X ∈ [r + c − ε, r + c + ε]`:
/// an end is `r` itself where the correction points inward, else `r + c ± ε`
/// rounded and moved one float outward. About two ulps of the corner wide,
/// against the few ulps of `Σ wᵢ Vᵢ` evaluated in intervals, with no interval
/// operation.
fn corner_enclosure(o: Pt, (x, v): (f64, Pt), (y, w): (f64, Pt)) -> [GeoIv; 2] {
    use crate::scalar::eft::{two_prod, two_sum};
    const U: f64 = f64::EPSILON / 2.0;
    [0, 1].map(|i| {
        let (dv, edv) = two_sum(v[i], -o[i]);
        let (dw, edw) = two_sum(w[i], -o[i]);
        // (The FMA remainder is exact away from underflow; there the
        // absolute term below covers it.)
        let ((pv, epv), (pw, epw)) = (two_prod(x, dv), two_prod(y, dw));
        let (s, es) = two_sum(pv, pw);
        let (r, er) = two_sum(o[i], s);
        let terms = [er, es, epv, epw, x * edv, y * edw];
        let c = terms.iter().sum::<f64>();
        let eps = 8.0 * U * terms.iter().map(|t| t.abs()).sum::<f64>() + 1e-300;
        let (lo, hi) = (c - eps, c + eps);
        let lo = if lo >= 0.0 { r } else { (r + lo).next_down() };
        let hi = if hi <= 0.0 { r } else { (r + hi).next_up() };
        // NaN (non-finite input) stays NaN: no containment is then proven.
        GeoIv::new(lo, hi)
    })
}

fn ipt(p: Pt) -> [GeoIv; 2] {
    [GeoIv::pt(p[0]), GeoIv::pt(p[1])]
}

/// The midpoint of an enclosure, rounded to nearest.
fn mid(x: GeoIv) -> f64 {
    0.5 * x.lower() + 0.5 * x.upper()
}

impl TriBox {
    /// The root triangle `(1, 0), (0, 1), (0, 0)`.
    pub fn unit() -> Self {
        Self {
            verts: [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]],
        }
    }

    /// The longest edge.
    pub fn diam(&self) -> f64 {
        let [a, b, c] = self.verts;
        norm(sub(a, b)).max(norm(sub(b, c))).max(norm(sub(c, a)))
    }

    /// The inradius `2·area / perimeter` (f64, for step sizes only).
    pub fn inradius(&self) -> f64 {
        let [a, b, c] = self.verts;
        let area2 = ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs();
        let per = norm(sub(a, b)) + norm(sub(b, c)) + norm(sub(c, a));
        if per > 0.0 {
            area2 / per
        } else {
            0.0
        }
    }

    #[cfg_attr(not(feature = "internals"), allow(dead_code))] // Used by tests and dev tools.
    /// Barycentric coordinates of the vertices w.r.t. the root triangle, as
    /// intervals (exact `s`, `t`; `1 − s − t` enclosed).
    pub fn bary_intervals(&self) -> [[Interval; 3]; 3] {
        self.verts.map(|[s, t]| {
            let (si, ti) = (point(s), point(t));
            [si, ti, point(1.0) - si - ti]
        })
    }

    /// The incenter, in the tri-box's own barycentric coordinates: side
    /// lengths opposite each vertex, normalized. Falls back to the centroid for
    /// a collapsed triangle.
    pub fn incenter_bary(&self) -> [f64; 3] {
        let [a, b, c] = self.verts;
        let (la, lb, lc) = (norm(sub(b, c)), norm(sub(c, a)), norm(sub(a, b)));
        let sum = la + lb + lc;
        if sum > 0.0 && sum.is_finite() {
            [la / sum, lb / sum, lc / sum]
        } else {
            [1.0 / 3.0; 3]
        }
    }

    /// The point with barycentric coordinates `b` (f64, not rigorous).
    pub fn point_at(&self, b: [f64; 3]) -> Pt {
        let [p, q, r] = self.verts;
        [
            b[0] * p[0] + b[1] * q[0] + b[2] * r[0],
            b[0] * p[1] + b[1] * q[1] + b[2] * r[1],
        ]
    }

    /// The axis-aligned bounding box `([s_lo, s_hi], [t_lo, t_hi])` (exact).
    pub fn bbox(&self) -> [[f64; 2]; 2] {
        let s = self.verts.map(|p| p[0]);
        let t = self.verts.map(|p| p[1]);
        let lo_hi = |x: [f64; 3]| [x[0].min(x[1]).min(x[2]), x[0].max(x[1]).max(x[2])];
        [lo_hi(s), lo_hi(t)]
    }

    /// Provably counter-clockwise with positive area.
    pub fn is_proper(&self) -> bool {
        let [a, b, c] = self.verts;
        left_of_filtered(a, b, ipt(c)) || orient(ipt(a), ipt(b), ipt(c)).lower() > 0.0
    }

    /// The triangle `{u ≥ mins[0], v ≥ mins[1], w ≥ mins[2]}` (local
    /// barycentric; `mins ≥ 0`, `Σ mins < 1`), as a new tri-box with `f64`
    /// vertices proven to contain it. `None` if no such triangle could be
    /// verified (the caller then keeps `self`).
    pub fn clip(&self, mins: [f64; 3]) -> Option<TriBox> {
        // Corner i of K is V_i moved towards the two other vertices by the
        // other two minima (e.g. (1 − b − c) V1 + b V2 + c V3 = V1 + b (V2 −
        // V1) + c (V3 − V1)), enclosed by `corner_enclosure`.
        let [p, q, r] = self.verts;
        let [a, b, c] = mins;
        let corners = [
            corner_enclosure(p, (b, q), (c, r)),
            corner_enclosure(q, (a, p), (c, r)),
            corner_enclosure(r, (a, p), (b, q)),
        ];
        // K is homothetic to this tri-box with ratio ρ = 1 − Σ mins. Propose
        // c_K + λ (V_i − c_T) with λ a little above ρ: each edge then moves out by
        // (λ − ρ)·r (r the inradius), which must cover the corners' uncertainty.
        // Unlike pushing K's own corners apart, this works even when K is below
        // float resolution (its corners round to one point).
        let rho = (1.0 - (mins[0] + mins[1] + mins[2])).max(0.0);
        let centre = |pts: &[[f64; 2]]| {
            let n = pts.len() as f64;
            [
                pts.iter().map(|p| p[0]).sum::<f64>() / n,
                pts.iter().map(|p| p[1]).sum::<f64>() / n,
            ]
        };
        let ck = centre(&corners.map(|k| [mid(k[0]), mid(k[1])]));
        let ct = centre(&self.verts);
        let r = self.inradius();
        if r.is_nan() || r <= 0.0 {
            return None;
        }
        let spread = corners
            .iter()
            .flatten()
            .map(|c| crate::scalar::iv::up(c.upper() - c.lower()))
            .fold(0.0, f64::max);
        // Rounding scale: coordinates near the tri-box, never below the
        // tri-box's own size (a clip to a point at the origin still needs a
        // triangle of representable, provable size around it).
        let scale = ck[0]
            .abs()
            .max(ck[1].abs())
            .max(ct[0].abs())
            .max(ct[1].abs())
            .max(self.diam());
        let ulp = f64::EPSILON * scale;
        let mut extra = 2.0 * (spread + 2.0 * ulp) / r + rho * f64::powi(2.0, -40);
        for _ in 0..60 {
            let lambda = rho + extra;
            if lambda >= 1.0 {
                return None;
            }
            let verts = self
                .verts
                .map(|v| [ck[0] + lambda * (v[0] - ct[0]), ck[1] + lambda * (v[1] - ct[1])]);
            let cand = TriBox { verts };
            if cand.is_proper() && corners.iter().all(|k| cand.contains_enclosure(*k)) {
                return Some(cand);
            }
            extra *= 2.0;
        }
        None
    }

    /// Every point of the box `k` lies in the closed triangle (proven).
    fn contains_enclosure(&self, k: [GeoIv; 2]) -> bool {
        let [a, b, c] = self.verts;
        let left_of = |p: Pt, q: Pt| left_of_filtered(p, q, k) || orient(ipt(p), ipt(q), k).lower() >= 0.0;
        left_of(a, b) && left_of(b, c) && left_of(c, a)
    }

    /// [`TriBox::clip`] without the proof, for the plain `f64` iteration: the
    /// triangle `{u ≥ mins[0], v ≥ mins[1], w ≥ mins[2]}` as the homothetic
    /// image of this one (ratio `1 − Σ mins`), rounded to nearest. `None` if
    /// it has no area.
    pub fn clip_unverified(&self, mins: [f64; 3]) -> Option<TriBox> {
        let rho = 1.0 - (mins[0] + mins[1] + mins[2]);
        if rho.is_nan() || rho <= 0.0 {
            return None;
        }
        let [p, q, r] = self.verts;
        let corner = |w: [f64; 3]| {
            [
                w[0] * p[0] + w[1] * q[0] + w[2] * r[0],
                w[0] * p[1] + w[1] * q[1] + w[2] * r[1],
            ]
        };
        let [a, b, c] = mins;
        let verts = [
            corner([1.0 - b - c, b, c]),
            corner([a, 1.0 - a - c, c]),
            corner([a, b, 1.0 - a - b]),
        ];
        let cand = TriBox { verts };
        (cand.diam() > 0.0).then_some(cand)
    }

    /// The four children of the 1-to-4 split, in the order corner `V1`, corner
    /// `V2`, corner `V3`, middle `(M23, M13, M12)` — the same order and
    /// orientation as [`TriBezier::split4`](crate::poly::TriBezier::split4).
    /// Midpoints are nudged outward until proven on or outside their edge, so
    /// the children cover `self`. `None` if that fails (a collapsed tri-box).
    pub fn split4(&self) -> Option<[TriBox; 4]> {
        let [p1, p2, p3] = self.verts;
        let m12 = outward_midpoint(p1, p2)?;
        let m23 = outward_midpoint(p2, p3)?;
        let m13 = outward_midpoint(p3, p1)?;
        let kids = [
            TriBox { verts: [p1, m12, m13] },
            TriBox { verts: [m12, p2, m23] },
            TriBox { verts: [m13, m23, p3] },
            TriBox { verts: [m23, m13, m12] },
        ];
        kids.iter().all(TriBox::is_proper).then_some(kids)
    }
}

/// The midpoint of edge `a → b` of a counter-clockwise triangle, nudged along
/// the outward normal until `orient(a, b, m) ≤ 0` is proven (on or outside
/// the edge).
fn outward_midpoint(a: Pt, b: Pt) -> Option<Pt> {
    let mut m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let d = sub(b, a);
    let len = norm(d);
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let outward = [d[1] / len, -d[0] / len];
    let mut step = f64::EPSILON * (m[0].abs().max(m[1].abs()).max(f64::MIN_POSITIVE));
    for _ in 0..8 {
        if orient(ipt(a), ipt(b), ipt(m)).upper() <= 0.0 {
            return Some(m);
        }
        m = [m[0] + outward[0] * step, m[1] + outward[1] * step];
        step *= 4.0;
    }
    None
}

/// The box `[lo, hi]²` enclosing a tri-box, for Krawczyk.
pub fn box_of(tb: &TriBox) -> [Interval; 2] {
    let [s, t] = tb.bbox();
    [interval(s[0], s[1]), interval(t[0], t[1])]
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;
    use num_traits::{Signed, Zero};

    /// The float filter of the orientation test claims `orient(a, b, x) > 0`
    /// on a box only where the exact orientation (rationals) is positive at
    /// all four corners of the box (it is affine in `x`), on random and on
    /// nearly collinear configurations at scales from 1 down to 1e-15, with
    /// boxes from points to wide; and it decides most clear cases.
    #[test]
    fn filtered_orientation_is_exact_where_it_claims() {
        let mut rng = crate::rng::Rng(0x0f11_7e55);
        let q = |x: f64| BigRational::from_float(x).expect("finite");
        let (mut claimed, mut clear, mut clear_claimed) = (0, 0, 0);
        for case in 0..20000 {
            let scale = [1.0, 1e-3, 1e-8, 1e-15][case % 4];
            let base = [rng.next_f64(), rng.next_f64()];
            let a = [base[0] + scale * rng.next_signed(), base[1] + scale * rng.next_signed()];
            let b = [base[0] + scale * rng.next_signed(), base[1] + scale * rng.next_signed()];
            // A point near the line through a and b (or anywhere), pushed off
            // it by a relative offset from 0 to 1.
            let t = 2.0 * rng.next_signed();
            let off = [0.0, 1e-17, 1e-15, 1e-12, 1e-6, 1.0][(case / 4) % 6] * rng.next_signed();
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            let m = [a[0] + t * ex - off * ey, a[1] + t * ey + off * ex];
            let rad = [0.0, 1e-18, 1e-16, 1e-13][(case / 24) % 4] * scale;
            let k = [m[0] - rad, m[0] + rad, m[1] - rad, m[1] + rad];
            let boxed = [
                GeoIv::pt(k[0]).hull(GeoIv::pt(k[1])),
                GeoIv::pt(k[2]).hull(GeoIv::pt(k[3])),
            ];
            let exact =
                |x: f64, y: f64| (q(b[0]) - q(a[0])) * (q(y) - q(a[1])) - (q(b[1]) - q(a[1])) * (q(x) - q(a[0]));
            let corners = [
                exact(k[0], k[2]),
                exact(k[0], k[3]),
                exact(k[1], k[2]),
                exact(k[1], k[3]),
            ];
            let positive = corners.iter().all(|c| c.is_positive());
            let claim = left_of_filtered(a, b, boxed);
            if claim {
                claimed += 1;
                assert!(positive, "case {case}: claimed left of {a:?} -> {b:?}, box {k:?}");
            }
            // Clearly positive: the smallest corner is above 1e-9 of the scale².
            let min = corners.iter().min().expect("four").clone();
            if !min.is_zero() && min > q(1e-9 * scale * scale) {
                clear += 1;
                clear_claimed += usize::from(claim);
            }
        }
        assert!(
            claimed > 3000 && clear > 1000 && clear_claimed == clear,
            "{claimed} {clear} {clear_claimed}"
        );
    }

    /// `corner_enclosure` holds the exact corner (rationals) and is at most
    /// a few ulps wide, for triangles from the unit one down to 1e-15 wide
    /// around points from 1e-300 to 1, corners at the origin, minima from 0
    /// and subnormals to 1; and a clip built on it contains the exact
    /// corners of `{u ≥ a, v ≥ b, w ≥ c}` (orientation in rationals).
    #[test]
    fn corner_enclosures_hold_the_exact_corners() {
        let mut rng = crate::rng::Rng(0xc0_4e55);
        let q = |x: f64| BigRational::from_float(x).expect("finite");
        let (mut tried, mut clips, mut widest) = (0, 0, 0.0f64);
        for case in 0..6000 {
            let scale = [1.0, 1e-3, 1e-8, 1e-15][case % 4];
            let base = [0.0, 1e-300, 1e-6, 0.3, 1.0][(case / 4) % 5];
            let pt = |rng: &mut crate::rng::Rng| [base + scale * rng.next_f64(), base + scale * rng.next_f64()];
            let tb = if case % 97 == 0 {
                TriBox::unit()
            } else {
                // Counter-clockwise, as every tri-box.
                let [p0, p1, p2] = [pt(&mut rng), pt(&mut rng), pt(&mut rng)];
                let ccw = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]) > 0.0;
                TriBox {
                    verts: if ccw { [p0, p1, p2] } else { [p0, p2, p1] },
                }
            };
            let min = |rng: &mut crate::rng::Rng| match rng.next_f64() {
                p if p < 0.1 => 0.0,
                p if p < 0.15 => 5e-324 * (1.0 + (rng.next_f64() * 1e6).floor()),
                p if p < 0.3 => 1e-12 * rng.next_f64(),
                _ => rng.next_f64() / 3.0,
            };
            let mins = [min(&mut rng), min(&mut rng), min(&mut rng)];
            let [p, qv, r] = tb.verts;
            let (a, b, c) = (mins[0], mins[1], mins[2]);
            let corners = [
                (p, (b, qv), (c, r), corner_enclosure(p, (b, qv), (c, r))),
                (qv, (a, p), (c, r), corner_enclosure(qv, (a, p), (c, r))),
                (r, (a, p), (b, qv), corner_enclosure(r, (a, p), (b, qv))),
            ];
            let mut exact = Vec::new();
            for (o, (x, v), (y, w), e) in corners {
                let xy = [0, 1].map(|i| q(o[i]) + q(x) * (q(v[i]) - q(o[i])) + q(y) * (q(w[i]) - q(o[i])));
                for i in 0..2 {
                    let (lo, hi) = (e[i].lower(), e[i].upper());
                    assert!(q(lo) <= xy[i] && xy[i] <= q(hi), "case {case}: {lo} {hi} vs {}", xy[i]);
                    let m = lo.abs().max(hi.abs());
                    widest = widest.max((hi - lo) / (f64::EPSILON * m).max(1e-300));
                }
                exact.push(xy);
            }
            let removed = mins.iter().sum::<f64>();
            if removed < 0.9 && tb.is_proper() {
                // A clip that removes a measurable part of a tri-box far above
                // the float grid must verify; below it (or removing ~nothing)
                // it may fail, and the caller keeps the tri-box.
                let representable = scale >= 1e-8 && removed >= 1e-6;
                tried += usize::from(representable);
                if let Some(k) = tb.clip(mins) {
                    clips += usize::from(representable);
                    let [ka, kb, kc] = k.verts.map(|v| [q(v[0]), q(v[1])]);
                    let left = |s: &[BigRational; 2], t: &[BigRational; 2], x: &[BigRational; 2]| {
                        !((&t[0] - &s[0]) * (&x[1] - &s[1]) - (&t[1] - &s[1]) * (&x[0] - &s[0])).is_negative()
                    };
                    for x in &exact {
                        assert!(
                            left(&ka, &kb, x) && left(&kb, &kc, x) && left(&kc, &ka, x),
                            "case {case}: clip misses a corner"
                        );
                    }
                }
            }
        }
        // Two ulps of the corner plus the rounding of its correction; and
        // most clips verify.
        assert!(widest <= 4.0, "{widest}");
        assert!(tried > 2400 && clips == tried, "{clips} of {tried}");
    }

    #[test]
    fn clip_contains_corners_and_shrinks() {
        let tb = TriBox::unit();
        let c = tb.clip([0.1, 0.2, 0.3]).unwrap();
        assert!(c.diam() < tb.diam() * 0.41 && c.diam() > tb.diam() * 0.39);
    }

    #[test]
    fn split_children_cover() {
        let tb = TriBox {
            verts: [[0.7, 0.1], [0.1, 0.7], [0.1, 0.1]],
        };
        let kids = tb.split4().unwrap();
        let area = |t: &TriBox| {
            let [a, b, c] = t.verts;
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        };
        let total: f64 = kids.iter().map(area).sum();
        assert!((total - area(&tb)).abs() < 1e-15);
    }

    #[test]
    fn tiny_clip_still_verifies() {
        let tb = TriBox {
            verts: [[0.5 + 1e-14, 0.125], [0.5, 0.125 + 1e-14], [0.5, 0.125]],
        };
        let c = tb.clip([0.3, 0.3, 0.3]).unwrap();
        assert!(c.diam() < 1e-14);
    }
}
