//! The second-order geometric iteration: the ray against the osculating
//! parabola of the surface's section by the plane through the ray and the
//! current point (Park, Ji & Ko 2013, §4.4 and the Discussion).

use super::first_order::advance_uv;
use super::iteration::{Failure, Outcome, Setup};
use super::linalg::{project2, SINGULAR};
use super::jet::{jet, Jet};

/// Below this `sin θ = |N_A × N_B|` the plane through the ray and the point
/// counts as tangent to the surface (Case 3): the section's curvature
/// vector grows like `1/sin²θ` (Eq. (30)), so below `√ε` it is rounding.
const TANGENT_PLANES: f64 = 1.4901161193847656e-8; // 2⁻²⁶ = √ε

/// The second-order geometric iteration for the hit of the ray `o + t·d`
/// with `S(u, v)`.
///
/// * **Formula** (Eqs. (25)–(35)). At `P = S(u, v)` let plane A hold the ray
///   and `P`, with unit normal `N_A = (P − o) × d / |(P − o) × d|`, and
///   `N_B = S_u × S_v / |S_u × S_v|` (Eq. (28)). Their section `c` has the
///   unit tangent `T = N_A × N_B / |N_A × N_B|` (Eq. (27)) and, to second
///   order, `c(λ) ≈ P + λT + ½λ²K` (Eq. (26)) with the curvature vector
///   `K = κ n = κ_B (N_B − cos θ N_A) / (1 − cos²θ)`, `cos θ = N_A·N_B`
///   (Eq. (30); the PDF text reads "κ_B(1 − cos²θ)", a lost fraction: `K`
///   lies in plane A, so `K·N_A = 0`, and Meusnier's theorem gives
///   `K·N_B = κ_B`, which fixes the division). `κ_B = L u′² + 2M u′v′ + N v′²`
///   (Eq. (31), `L = S_uu·N_B`, `M = S_uv·N_B`, `N = S_vv·N_B`) with
///   `(u′, v′)` from `T = S_u u′ + S_v v′` by the normal equations
///   (Eq. (32)). Writing `m = N_A × T` (the unit normal of `c` in plane A:
///   this keeps a straight section, `K = 0`, well defined) and `k = K·m`,
///   the dot products of `P + ΔλT + ½Δλ²K = o + d t` (Eq. (33)) with `T`
///   and `m` (Eqs. (34)–(35)) are
///   `Δλ − (d·T) t = (o − P)·T` and `½kΔλ² − (d·m) t = (o − P)·m`;
///   eliminating `t` (multiplied through by `d·T`, so `d·T = 0` needs no
///   division) leaves
///   `½k(d·T) Δλ² − (d·m) Δλ + (d·m)(o − P)·T − (d·T)(o − P)·m = 0`.
///   Of its roots `Δλ₁, Δλ₂`, with points `q₁, q₂` on the ray, the one on
///   the origin's side of the plane through `q_mid = (q₁ + q₂)/2`
///   perpendicular to `d` is taken (the paper's selection: the nearer
///   one). Then `(Δu, Δv) = (u′, v′)Δλ`, until `(Δu² + Δv²)^{1/2} < δ`; a
///   step out of the domain is cut where the segment leaves it (the
///   paper's rule, [`DomainRule::Clip`](super::DomainRule::Clip)).
/// * **Choices where the paper is silent.** A negative discriminant (the
///   parabola misses the ray) takes the vertex `Δλ = −b/2a`, the point of
///   the parabola nearest the ray's line; a ray through `P` takes no step.
/// * **Special cases** (the Discussion). Case 1, the ray parallel to the
///   tangent plane: `d·m = 0`, the equation is `½k(d·T)Δλ² = …`, solved as
///   any other (if also `k = 0`: [`Failure::ParallelTangentPlane`]). Case
///   2, a tangential hit: `d·m` and `(o − P)·m` tend to 0 together and the
///   steps to 0. Case 3, `N_A ∥ N_B` (`sin θ ≤ 2⁻²⁶`, no tangent): `P` is
///   projected on the ray, `q = o + ((P − o)·d/|d|²) d`, and `(Δu, Δv)`
///   moves towards it as in Eq. (24) (or [`Failure::ZeroTangent`] when
///   [`IterOptions::zero_tangent_projection`](super::IterOptions::zero_tangent_projection)
///   is off).
/// * **Rounding.** `f64`; the end point is a claim, its `t` the projection
///   of `S(u, v)` on the ray. `S_u ∥ S_v` within rounding:
///   [`Failure::SingularJacobian`].
///
/// Runnable example: [`iterate`](super::iterate) with [`Iteration::SecondOrder`](super::Iteration::SecondOrder).
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
    let nb = j.su.cross(j.sv);
    if !(nb.length() > SINGULAR * j.su.length() * j.sv.length()) {
        return Err(Failure::SingularJacobian);
    }
    let nb = nb.normalize();
    let w = j.s - s.o;
    let na = w.cross(s.d);
    if !(na.length() > SINGULAR * w.length() * s.d.length()) {
        // P lies on the ray's line: it is a hit already.
        return Ok([0.0, 0.0]);
    }
    let na = na.normalize();
    let tn = na.cross(nb);
    let sin = tn.length();
    if !(sin > TANGENT_PLANES) {
        if !s.opts.zero_tangent_projection {
            return Err(Failure::ZeroTangent);
        }
        let q = s.o + s.d * s.project(j.s);
        return project2(j.su, j.sv, q - j.s).ok_or(Failure::SingularJacobian);
    }
    let tan = tn / sin;
    let [up, vp] = project2(j.su, j.sv, tan).ok_or(Failure::SingularJacobian)?;
    let kappa_b = up * up * j.suu.dot(nb) + 2.0 * up * vp * j.suv.dot(nb) + vp * vp * j.svv.dot(nb);
    let curvature = (nb - na.dot(nb) * na) * (kappa_b / (sin * sin));
    let m = na.cross(tan);
    let k = curvature.dot(m);
    let (dt, dm) = (s.d.dot(tan), s.d.dot(m));
    let (wt, wm) = (-w.dot(tan), -w.dot(m));
    let section = Section { k, dt, dm, wt, wm };
    let dl = section.nearest_root()?;
    Ok([up * dl, vp * dl])
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
