//! The second-order geometric iteration: the ray against the osculating
//! parabola of the surface's section by the plane through the ray and the
//! current point (Park, Ji & Ko 2013, §4.4 and the Discussion).

use super::first_order::advance_uv;
use super::iteration::{Failure, Outcome, Setup};
use super::jet::{jet, Jet};
use super::linalg::{above, project2, SINGULAR};
use glam::DVec3;

/// Below this `sin θ = |N_A × N_B|` the plane through the ray and the point
/// counts as tangent to the surface (Case 3): the section's curvature
/// vector grows like `1/sin²θ` (Eq. (30)), so below `√ε` it is rounding.
const TANGENT_PLANES: f64 = 1.4901161193847656e-8; // 2⁻²⁶ = √ε

/// The [`Iteration::SecondOrder`](super::Iteration::SecondOrder) iteration (its docs hold the formula).
pub(super) fn run(s: &Setup, start: [f64; 2]) -> Outcome {
    let mut uv = start;
    for k in 1..=s.opts.max_iterations {
        let j = jet(s.patch, uv[0], uv[1]);
        let duv = match step(s, &j) {
            Ok(duv) => duv,
            Err(f) => return Outcome::failed(f, k),
        };
        match advance_uv(s, uv, duv, k) {
            Ok(next) => uv = next,
            Err(done) => return done,
        }
    }
    Outcome::failed(Failure::NoConvergence, s.opts.max_iterations)
}

/// `(Δu, Δv)` of one step at the jet `j` (see [`run`]).
fn step(s: &Setup, j: &Jet) -> Result<[f64; 2], Failure> {
    match osculate(s, j)? {
        Local::OnRay => Ok([0.0, 0.0]),
        Local::TangentPlanes => {
            if !s.opts.zero_tangent_projection {
                return Err(Failure::ZeroTangent);
            }
            let q = s.o + s.d * s.project(j.s);
            project2(j.su, j.sv, q - j.s).ok_or(Failure::SingularJacobian)
        }
        Local::Section(c) => {
            let m = c.na.cross(c.tan);
            let w = s.o - j.s;
            let section = Section {
                k: c.curvature.dot(m),
                dt: s.d.dot(c.tan),
                dm: s.d.dot(m),
                wt: w.dot(c.tan),
                wm: w.dot(m),
            };
            let dl = section.nearest_root()?;
            Ok([c.uv_rate[0] * dl, c.uv_rate[1] * dl])
        }
    }
}

/// The surface's section by plane A at `P`, to second order.
#[derive(Debug)]
struct Curve {
    /// `N_A`.
    na: DVec3,
    /// The unit tangent `T` (Eq. (27)).
    tan: DVec3,
    /// The curvature vector `K = κn` (Eq. (30), re-derived).
    curvature: DVec3,
    /// `(u′, v′)` with `T = S_u u′ + S_v v′` (Eq. (32)).
    uv_rate: [f64; 2],
}

/// What the point `P = S(u, v)` and the ray make of plane A.
#[derive(Debug)]
enum Local {
    /// `P` lies on the ray's line: plane A is undefined, `P` a hit.
    OnRay,
    /// `N_A ∥ N_B` (Case 3): the section has no tangent.
    TangentPlanes,
    /// The section's second-order approximation.
    Section(Curve),
}

/// Plane A and the section it cuts (Eqs. (27)–(32)).
fn osculate(s: &Setup, j: &Jet) -> Result<Local, Failure> {
    let nb = j.su.cross(j.sv);
    if !above(nb.length(), SINGULAR * j.su.length() * j.sv.length()) {
        return Err(Failure::SingularJacobian);
    }
    let nb = nb.normalize();
    let w = j.s - s.o;
    let na = w.cross(s.d);
    if !above(na.length(), SINGULAR * w.length() * s.d.length()) {
        return Ok(Local::OnRay);
    }
    let na = na.normalize();
    let tn = na.cross(nb);
    let sin = tn.length();
    if !above(sin, TANGENT_PLANES) {
        return Ok(Local::TangentPlanes);
    }
    let tan = tn / sin;
    let [up, vp] = project2(j.su, j.sv, tan).ok_or(Failure::SingularJacobian)?;
    let kappa_b = up * up * j.suu.dot(nb) + 2.0 * up * vp * j.suv.dot(nb) + vp * vp * j.svv.dot(nb);
    Ok(Local::Section(Curve {
        na,
        tan,
        curvature: (nb - na.dot(nb) * na) * (kappa_b / (sin * sin)),
        uv_rate: [up, vp],
    }))
}

/// The parabola `P + λT + ½kλ²m` and the ray in plane A's frame `(T, m)`:
/// `d = (dt, dm)`, `o − P = (wt, wm)`.
struct Section {
    k: f64,
    dt: f64,
    dm: f64,
    wt: f64,
    wm: f64,
}

impl Section {
    /// The ray parameter of the parabola's point at `Δλ` (from Eq. (34) or
    /// (35), whichever has the larger coefficient of `t`: `d` lies in
    /// plane A, so `dt² + dm² = |d|²` and one of them is at least `|d|/√2`).
    fn t_at(&self, dl: f64) -> f64 {
        if self.dt.abs() >= self.dm.abs() {
            (dl - self.wt) / self.dt
        } else {
            (0.5 * self.k * dl * dl - self.wm) / self.dm
        }
    }

    /// The root `Δλ` of `aΔλ² + bΔλ + c = 0` (see [`run`]) whose point on
    /// the ray lies on the origin's side of the plane through `q_mid`
    /// perpendicular to `d`; the vertex when there is no real root.
    fn nearest_root(&self) -> Result<f64, Failure> {
        let a = 0.5 * self.k * self.dt;
        let b = -self.dm;
        let c = self.dm * self.wt - self.dt * self.wm;
        if a == 0.0 {
            return if b != 0.0 {
                Ok(-c / b)
            } else if c == 0.0 {
                Ok(0.0)
            } else {
                Err(Failure::ParallelTangentPlane)
            };
        }
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            return Ok(-b / (2.0 * a));
        }
        // The stable pair: q = −(b + sgn(b)√disc)/2, roots q/a and c/q.
        let q = -0.5 * (b + disc.sqrt().copysign(b));
        if q == 0.0 {
            return Ok(0.0);
        }
        let roots = [q / a, c / q];
        let ts = roots.map(|r| self.t_at(r));
        // (q_i − q_mid)·d has the sign of t_i − t_mid, (o − q_mid)·d that of −t_mid.
        let mid = 0.5 * (ts[0] + ts[1]);
        let pick = if mid > 0.0 {
            usize::from(ts[1] < ts[0])
        } else if mid < 0.0 {
            usize::from(ts[1] > ts[0])
        } else {
            usize::from(ts[0] < 0.0)
        };
        Ok(roots[pick])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::heuristics::experiment::example;
    use crate::heuristics::iteration::Setup;
    use crate::heuristics::IterOptions;
    use crate::ray::Ray;

    /// The point of plane A on the surface whose projection on `T` is `λ`:
    /// Newton on `(N_A·(S − P), T·(S − P) − λ)` from `(u, v) + λ(u′, v′)`.
    fn section_point(s: &Setup, p: DVec3, c: &Curve, uv: [f64; 2], lambda: f64) -> DVec3 {
        let [mut u, mut v] = [uv[0] + lambda * c.uv_rate[0], uv[1] + lambda * c.uv_rate[1]];
        for _ in 0..30 {
            let j = jet(s.patch, u, v);
            let f = [c.na.dot(j.s - p), c.tan.dot(j.s - p) - lambda];
            let (a, b, cc, d) = (c.na.dot(j.su), c.na.dot(j.sv), c.tan.dot(j.su), c.tan.dot(j.sv));
            let det = a * d - b * cc;
            u -= (d * f[0] - b * f[1]) / det;
            v -= (a * f[1] - cc * f[0]) / det;
        }
        jet(s.patch, u, v).s
    }

    /// `P + λT + ½λ²K` follows the true section to third order (the error
    /// drops 8-fold when λ halves), on planes A far from perpendicular to
    /// the surface (sin θ = 0.2 … 0.5), where a wrong `1/sin²θ` in Eq. (30)
    /// would leave a second-order error (a 4-fold drop).
    #[test]
    fn the_osculating_parabola_is_second_order_accurate() {
        let ex = example(1).unwrap();
        let ray = Ray::new(glam::DVec3::new(5.0, 1.0, 1.5), glam::DVec3::new(-1.0, 0.2, -0.4)).unwrap();
        let opts = IterOptions::default();
        let s = Setup::new(&ex.patch, &ray, &opts);
        for uv in [[0.3, 0.6], [0.1, 0.5], [0.9, 0.5]] {
            let j = jet(&ex.patch, uv[0], uv[1]);
            let Ok(Local::Section(c)) = osculate(&s, &j) else {
                panic!("a transversal section at {uv:?}")
            };
            let sin = c.na.cross(j.su.cross(j.sv).normalize()).length();
            assert!(sin < 0.5, "θ should be oblique at {uv:?}: sin θ = {sin}");
            let err =
                |l: f64| (section_point(&s, j.s, &c, uv, l) - (j.s + l * c.tan + 0.5 * l * l * c.curvature)).length();
            for l in [0.02, -0.02] {
                let (e1, e2) = (err(l), err(l / 2.0));
                assert!(
                    e1 < 1e-3 && e1 / e2 > 6.0,
                    "at {uv:?}, λ = {l}: errors {e1:e}, {e2:e} (third order halves to 1/8)"
                );
            }
        }
    }
}
