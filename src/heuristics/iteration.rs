//! What every iteration shares: the method names, the options, the outcome
//! with its failure reasons, the parameter domain and its rules, and the
//! entry point [`iterate`].

use super::{first_order, halley, newton, second_order};
use crate::ray::{Patch, Ray};
use glam::DVec3;

/// The four iterations of Park, Ji & Ko (2013) for a ray and a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Iteration {
    /// Newton–Raphson for `G(u, v, t) = S(u, v) − (o + t·d) = 0`.
    ///
    /// * **Formula** (Eqs. (6)–(8), (19)–(20)): `X = (u, v, t)`,
    ///   `J = [S_u, S_v, −d]`, `ΔX = −J⁻¹ G(X)`, `X ← X + ΔX` until
    ///   `|ΔX|₂ < δ`. The start's `t₀` (the paper does not give one) is the
    ///   projection of `S(u₀, v₀)` on the ray.
    /// * **Rounding.** `f64`, Cramer's rule; the end point is a claim.
    /// * **Degenerate cases.** `J` singular within rounding (the ray parallel
    ///   to the tangent plane, Case 1 of the Discussion, or `S_u ∥ S_v`):
    ///   [`Failure::SingularJacobian`]. A tangential hit (Case 2) makes `J`
    ///   singular at the root: the iteration slows to linear convergence and
    ///   may stop on the step limit or a singular `J`.
    ///
    /// ```
    /// use rootclip::heuristics::experiment::example;
    /// use rootclip::heuristics::{iterate, IterOptions, Iteration};
    /// let ex = example(1)?; // the paper's Example 1: one hit, at (0.788660789, 0.895380221)
    /// let out = iterate(Iteration::Newton, &ex.patch, &ex.ray, [0.6, 0.9], &IterOptions::default());
    /// let end = out.end.expect("converges from here");
    /// assert!((end.u - 0.788660789).abs() < 1e-9 && (end.v - 0.895380221).abs() < 1e-9);
    /// // From (0, 0) it leaves the patch.
    /// let out = iterate(Iteration::Newton, &ex.patch, &ex.ray, [0.0, 0.0], &IterOptions::default());
    /// assert_eq!(out.failure.map(|f| f.code()), Some("left_domain"));
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    Newton,
    /// Halley's method for `G(u, v, t) = S(u, v) − (o + t·d) = 0`.
    ///
    /// * **Formula** (Eqs. (9)–(12), (21)): with `J = [S_u, S_v, −d]`, the
    ///   Newton step `Q = −J⁻¹G` (Eq. (10)) and
    ///   `b = J⁻¹ [Qᵀ H(G_x) Q, Qᵀ H(G_y) Q, Qᵀ H(G_z) Q]` (Eqs. (11)–(12)),
    ///   the step is, component by component, `ΔX_k = Q_k² / (Q_k + b_k / 2)`
    ///   (Eq. (9), whose fraction the PDF text loses: "Δ X = Q 2 Q + 1 2 b";
    ///   read so because it is the only reading that gives the scalar Halley
    ///   step `−2ff'/(2f'² − ff'')` for one unknown). `G` is linear in `t`, so
    ///   each Hessian (Eq. (21)) has only its `(u, v)` block, and
    ///   `Qᵀ H(G) Q = Q_u² S_uu + 2 Q_u Q_v S_uv + Q_v² S_vv`.
    /// * **Rounding.** `f64`; the end point is a claim.
    /// * **Degenerate cases.** As Newton ([`Failure::SingularJacobian`]); a
    ///   component with `Q_k = 0` takes `ΔX_k = 0` (the limit), one with
    ///   `Q_k + b_k/2 = 0 ≠ Q_k` has no step ([`Failure::NonFinite`]).
    ///
    /// ```
    /// use rootclip::heuristics::experiment::example;
    /// use rootclip::heuristics::{iterate, IterOptions, Iteration};
    /// let ex = example(1)?;
    /// let opts = IterOptions::default();
    /// let halley = iterate(Iteration::Halley, &ex.patch, &ex.ray, [0.6, 0.9], &opts);
    /// let newton = iterate(Iteration::Newton, &ex.patch, &ex.ray, [0.6, 0.9], &opts);
    /// assert!(halley.end.is_some() && halley.iterations <= newton.iterations);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    Halley,
    /// The first-order geometric iteration for the hit of the ray `o + t·d`
    /// with `S(u, v)`.
    ///
    /// * **Formula** (Eqs. (22)–(24)): at `P = S(u, v)` the unit normal
    ///   `N = S_u × S_v / |S_u × S_v|` (Eq. (22)); the ray meets the tangent
    ///   plane at `t = (P − o)·N / (d·N)` (Eq. (23)), the point `q = o + t·d`;
    ///   `(Δu, Δv)` solves the normal equations
    ///   `(q − P)·S_u = (S_u·S_u)Δu + (S_v·S_u)Δv`,
    ///   `(q − P)·S_v = (S_u·S_v)Δu + (S_v·S_v)Δv` (Eq. (24)), i.e. moves along
    ///   the projection of `q − P` on the tangent plane; until
    ///   `(Δu² + Δv²)^{1/2} < δ`. As the Discussion shows (Eqs. (36)–(37)) this
    ///   is Newton's step without a `t` unknown.
    /// * **Domain.** The paper states no rule here; [`IterOptions::domain_rule`](IterOptions::domain_rule)
    ///   applies (default §4.4's, [`DomainRule::Clip`](DomainRule::Clip)).
    /// * **Rounding.** `f64`; the end point is a claim, its `t` the projection
    ///   of `S(u, v)` on the ray.
    /// * **Degenerate cases.** `d·N = 0` within rounding (Case 1):
    ///   [`Failure::ParallelTangentPlane`]; `S_u ∥ S_v`:
    ///   [`Failure::SingularJacobian`].
    ///
    /// ```
    /// use rootclip::heuristics::experiment::example;
    /// use rootclip::heuristics::{iterate, Failure, IterOptions, Iteration};
    /// // Example 3: at (0.6, 0.5) the tangent plane contains the ray (Case 1).
    /// let ex = example(3)?;
    /// let out = iterate(Iteration::FirstOrder, &ex.patch, &ex.ray, [0.6, 0.5], &IterOptions::default());
    /// assert_eq!(out.failure, Some(Failure::ParallelTangentPlane));
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    FirstOrder,
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
    ///   paper's rule, [`DomainRule::Clip`](DomainRule::Clip)).
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
    ///   [`IterOptions::zero_tangent_projection`](IterOptions::zero_tangent_projection)
    ///   is off).
    /// * **Rounding.** `f64`; the end point is a claim, its `t` the projection
    ///   of `S(u, v)` on the ray. `S_u ∥ S_v` within rounding:
    ///   [`Failure::SingularJacobian`].
    ///
    /// ```
    /// use rootclip::heuristics::experiment::example;
    /// use rootclip::heuristics::{iterate, IterOptions, Iteration};
    /// // Example 3, the tangential ray, from the paper's start (Cases 1 and 3 at once).
    /// let ex = example(3)?;
    /// let out = iterate(Iteration::SecondOrder, &ex.patch, &ex.ray, [0.6, 0.5], &IterOptions::default());
    /// let end = out.end.expect("the projection of Case 3 converges");
    /// assert!((end.u - 0.5).abs() < 1e-12 && (end.v - 0.5).abs() < 1e-12 && out.iterations <= 5);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    SecondOrder,
}

impl Iteration {
    /// All four, in the paper's order.
    pub const ALL: [Iteration; 4] = [
        Iteration::Newton,
        Iteration::Halley,
        Iteration::FirstOrder,
        Iteration::SecondOrder,
    ];

    /// The stable machine-readable name: `"newton"`, `"halley"`,
    /// `"first-order"` or `"second-order"`.
    pub fn code(self) -> &'static str {
        match self {
            Iteration::Newton => "newton",
            Iteration::Halley => "halley",
            Iteration::FirstOrder => "first-order",
            Iteration::SecondOrder => "second-order",
        }
    }
}

/// What an iteration does with a step that leaves the patch's parameter
/// domain (the unit square or triangle, or a B-spline's knot rectangle).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum DomainRule {
    /// The rule of §4.4 (its last paragraph), the only one the paper
    /// states: the new point is replaced by the point where the segment
    /// from the old one leaves the domain. An iterate on the edge whose
    /// step points out (the cut step is zero) stops with
    /// [`Failure::LeftDomain`].
    #[default]
    Clip,
    /// The new point is replaced by the nearest point of the domain
    /// (coordinate-wise clamping on a rectangle), so an iterate can slide
    /// along an edge; one that cannot move stops with
    /// [`Failure::LeftDomain`].
    Clamp,
    /// Stop with [`Failure::LeftDomain`] at the first iterate outside the
    /// closed domain.
    Stop,
}

impl DomainRule {
    /// The stable machine-readable name: `"clip"`, `"clamp"` or `"stop"`.
    pub fn code(self) -> &'static str {
        match self {
            DomainRule::Clip => "clip",
            DomainRule::Clamp => "clamp",
            DomainRule::Stop => "stop",
        }
    }
}

/// Options of [`iterate`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct IterOptions {
    /// At most this many steps (default 50; the paper states none).
    pub max_iterations: usize,
    /// The paper's `δ`: the iteration has converged when a step is shorter
    /// than this (default `1e-6`: the paper states none, and this one
    /// reproduces its mean iteration counts for Newton and Halley; see the
    /// write-up). Newton and Halley measure the whole step `|ΔX|₂`,
    /// `X = (u, v, t)`; the geometric iterations `(Δu² + Δv²)^{1/2}`, as
    /// the paper does.
    pub tol: f64,
    /// What a step out of the domain does, for every method (default
    /// [`DomainRule::Clip`], §4.4's rule).
    pub domain_rule: DomainRule,
    /// Case 3 of the paper's Discussion: where the plane through the ray and
    /// the current point is tangent to the surface (`N_A ∥ N_B`, no curve
    /// tangent), the second-order iteration projects the point on the ray
    /// and steps towards it (default `true`); `false` stops there with
    /// [`Failure::ZeroTangent`] instead.
    pub zero_tangent_projection: bool,
}

impl Default for IterOptions {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            tol: 1e-6,
            domain_rule: DomainRule::Clip,
            zero_tangent_projection: true,
        }
    }
}

impl IterOptions {
    /// The same options with at most `n` steps.
    pub fn with_max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }

    /// The same options with the step tolerance `δ = tol`.
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }

    /// The same options with the domain rule `rule`.
    pub fn with_domain_rule(mut self, rule: DomainRule) -> Self {
        self.domain_rule = rule;
        self
    }

    /// The same options with Case 3's projection on or off.
    pub fn with_zero_tangent_projection(mut self, on: bool) -> Self {
        self.zero_tangent_projection = on;
        self
    }

    /// Checks the options: `tol` finite and positive, `max_iterations ≥ 1`
    /// ([`Error::InvalidOption`](crate::Error::InvalidOption)). [`iterate`]
    /// does not call it: with a NaN `tol` nothing converges.
    pub fn validate(&self) -> crate::Result<()> {
        if !(self.tol.is_finite() && self.tol > 0.0) {
            return Err(crate::Error::InvalidOption(format!(
                "the step tolerance must be finite and positive, got {}",
                self.tol
            )));
        }
        if self.max_iterations == 0 {
            return Err(crate::Error::InvalidOption("max_iterations must be at least 1".into()));
        }
        Ok(())
    }
}

/// Where a converged iteration ended: patch parameters and ray parameter
/// (`o + t·d` for the direction as given).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct End {
    /// Patch parameter `u`.
    pub u: f64,
    /// Patch parameter `v`.
    pub v: f64,
    /// Ray parameter `t`.
    pub t: f64,
}

/// Why an iteration stopped without an end point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum Failure {
    /// The linear system of the step is singular within rounding: Newton's
    /// and Halley's Jacobian `[S_u, S_v, −d]` (the ray parallel to the
    /// tangent plane, or `S_u ∥ S_v`), or the first fundamental form of the
    /// geometric iterations (`S_u ∥ S_v`: a collapsed edge or corner).
    SingularJacobian,
    /// An iterate left the domain ([`DomainRule::Stop`]), or could not move
    /// because its step points out of the domain ([`DomainRule::Clip`],
    /// [`DomainRule::Clamp`]), or the converged point lies outside the
    /// closed domain (by more than `tol`).
    LeftDomain,
    /// No step shorter than `tol` within `max_iterations`.
    NoConvergence,
    /// The first-order iteration: the ray is parallel to the tangent plane
    /// (Eq. (23)'s denominator `d·N` vanishes); the second-order iteration:
    /// the ray is parallel to a straight section (no curvature to meet it).
    ParallelTangentPlane,
    /// The second-order iteration with Case 3's projection switched off: the
    /// plane through the ray and the point is tangent to the surface, so the
    /// section has no tangent (Eq. (27): `N_A × N_B = 0`).
    ZeroTangent,
    /// A step or a point was not finite (an overflow, a Halley denominator
    /// `Q + b/2` that vanished, a rational patch evaluated where its weight
    /// vanishes, a non-finite start).
    NonFinite,
    /// Converged, but behind the ray's origin (`t < 0`), where the paper
    /// considers no intersection.
    BehindOrigin,
}

impl Failure {
    /// The stable machine-readable code: `"singular_jacobian"`,
    /// `"left_domain"`, `"no_convergence"`, `"parallel_tangent_plane"`,
    /// `"zero_tangent"`, `"non_finite"` or `"behind_origin"`.
    pub fn code(self) -> &'static str {
        match self {
            Failure::SingularJacobian => "singular_jacobian",
            Failure::LeftDomain => "left_domain",
            Failure::NoConvergence => "no_convergence",
            Failure::ParallelTangentPlane => "parallel_tangent_plane",
            Failure::ZeroTangent => "zero_tangent",
            Failure::NonFinite => "non_finite",
            Failure::BehindOrigin => "behind_origin",
        }
    }

    /// A one-line English description for output.
    pub fn describe(self) -> &'static str {
        match self {
            Failure::SingularJacobian => {
                "the step's linear system is singular (ray parallel to the tangent plane, or S_u ∥ S_v)"
            }
            Failure::LeftDomain => "the iteration left the parameter domain",
            Failure::NoConvergence => "no convergence within the iteration limit",
            Failure::ParallelTangentPlane => "the ray is parallel to the tangent plane (or to a straight section)",
            Failure::ZeroTangent => {
                "the plane through the ray and the point is tangent to the surface: the section has no tangent"
            }
            Failure::NonFinite => "a step or a point was not finite",
            Failure::BehindOrigin => "converged behind the ray's origin (t < 0)",
        }
    }
}

/// What an iteration returned: exactly one of `end` and `failure` is set.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Outcome {
    /// The converged point (a claim, not a proof), if any.
    pub end: Option<End>,
    /// Steps taken (including the last, short one).
    pub iterations: usize,
    /// Why there is no end point.
    pub failure: Option<Failure>,
}

impl Outcome {
    pub(super) fn converged(end: End, iterations: usize) -> Self {
        Self {
            end: Some(end),
            iterations,
            failure: None,
        }
    }

    pub(super) fn failed(failure: Failure, iterations: usize) -> Self {
        Self {
            end: None,
            iterations,
            failure: Some(failure),
        }
    }
}

/// Runs `method` for the hit of `ray` with `patch` from the start `(u₀, v₀)`
/// (in the patch's parameters: the unit square or triangle, a B-spline's
/// knot rectangle). Each [`Iteration`] variant's docs give its formula.
///
/// * **Convergence.** A step shorter than `opts.tol` ends the iteration;
///   the point after it is the end if it lies in the closed domain (within
///   `opts.tol`) and in front of the origin (`t ≥ 0`), else the failure says
///   why. The end's `t` is Newton's and Halley's own third unknown, and for
///   the geometric iterations the projection `(S(u, v) − o)·d / |d|²` of the
///   end point on the ray.
/// * **Rounding.** Plain `f64`: an end point is where a float iteration
///   stopped, not a proven hit; it may be a non-hit, or not the nearest.
///   [`crate::ray::classify`] referees it.
/// * **Degenerate cases** end with a [`Failure`], never a panic: a start
///   outside the domain ([`Failure::LeftDomain`] after 0 steps), a
///   non-finite start ([`Failure::NonFinite`]).
///
/// ```
/// use rootclip::glam::DVec3;
/// use rootclip::heuristics::{iterate, IterOptions, Iteration};
/// use rootclip::ray::{Ray, TriPatch};
/// let tri = TriPatch::new(1, vec![DVec3::ZERO, DVec3::X, DVec3::Y], None)?;
/// let ray = Ray::new(DVec3::new(0.25, 0.5, 2.0), -DVec3::Z)?;
/// for method in Iteration::ALL {
///     let out = iterate(method, &tri.clone().into(), &ray, [0.3, 0.3], &IterOptions::default());
///     let end = out.end.expect("a flat triangle: every method converges");
///     assert!((end.u - 0.25).abs() < 1e-12 && (end.v - 0.5).abs() < 1e-12 && (end.t - 2.0).abs() < 1e-12);
/// }
/// # Ok::<(), rootclip::Error>(())
/// ```
pub fn iterate(method: Iteration, patch: &Patch, ray: &Ray, start: [f64; 2], opts: &IterOptions) -> Outcome {
    let setup = Setup::new(patch, ray, opts);
    if !(start[0].is_finite() && start[1].is_finite()) {
        return Outcome::failed(Failure::NonFinite, 0);
    }
    if !setup.domain.contains(start, 0.0) {
        return Outcome::failed(Failure::LeftDomain, 0);
    }
    match method {
        Iteration::Newton => newton::run(&setup, start),
        Iteration::Halley => halley::run(&setup, start),
        Iteration::FirstOrder => first_order::run(&setup, start),
        Iteration::SecondOrder => second_order::run(&setup, start),
    }
}

/// Everything a method reads: the patch, the ray, the domain and the
/// options.
pub(super) struct Setup<'a> {
    pub(super) patch: &'a Patch,
    pub(super) o: DVec3,
    pub(super) d: DVec3,
    pub(super) domain: Domain,
    pub(super) opts: &'a IterOptions,
}

impl<'a> Setup<'a> {
    pub(super) fn new(patch: &'a Patch, ray: &Ray, opts: &'a IterOptions) -> Self {
        Self {
            patch,
            o: ray.origin(),
            d: ray.dir(),
            domain: Domain::of(patch),
            opts,
        }
    }

    /// `t` of the point of the ray's line nearest `p`: `(p − o)·d / |d|²`.
    pub(super) fn project(&self, p: DVec3) -> f64 {
        (p - self.o).dot(self.d) / self.d.length_squared()
    }

    /// The step from `from` to `to` under the domain rule: `Ok(point)` to
    /// go on from, `Err(LeftDomain)` to stop.
    pub(super) fn step(&self, from: [f64; 2], to: [f64; 2]) -> Result<[f64; 2], Failure> {
        if !(to[0].is_finite() && to[1].is_finite()) {
            return Err(Failure::NonFinite);
        }
        if self.domain.contains(to, 0.0) {
            return Ok(to);
        }
        let next = match self.opts.domain_rule {
            DomainRule::Stop => return Err(Failure::LeftDomain),
            DomainRule::Clip => self.domain.clip(from, to),
            DomainRule::Clamp => self.domain.nearest(to),
        };
        if next == from {
            Err(Failure::LeftDomain)
        } else {
            Ok(next)
        }
    }

    /// The outcome of a converged iteration at `(u, v)` with ray parameter
    /// `t` after `k` steps: checked against the domain and the origin.
    pub(super) fn finish(&self, uv: [f64; 2], t: f64, k: usize) -> Outcome {
        if !(uv[0].is_finite() && uv[1].is_finite() && t.is_finite()) {
            Outcome::failed(Failure::NonFinite, k)
        } else if !self.domain.contains(uv, self.opts.tol) {
            Outcome::failed(Failure::LeftDomain, k)
        } else if t < 0.0 {
            Outcome::failed(Failure::BehindOrigin, k)
        } else {
            Outcome::converged(End { u: uv[0], v: uv[1], t }, k)
        }
    }
}

/// A patch's closed parameter domain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Domain {
    /// `[u₀, u₁] × [v₀, v₁]`.
    Rect([f64; 2], [f64; 2]),
    /// `u, v ≥ 0`, `u + v ≤ 1`.
    Triangle,
}

impl Domain {
    fn of(patch: &Patch) -> Self {
        match patch {
            Patch::Triangle(_) => Domain::Triangle,
            Patch::Tensor(_) => Domain::Rect([0.0, 1.0], [0.0, 1.0]),
            Patch::Bspline(s) => {
                let (u, v) = s.domain();
                Domain::Rect(u, v)
            }
        }
    }

    /// `p` lies in the domain enlarged by `slack` (in each constraint).
    pub(super) fn contains(&self, p: [f64; 2], slack: f64) -> bool {
        match *self {
            Domain::Rect(u, v) => {
                u[0] - slack <= p[0] && p[0] <= u[1] + slack && v[0] - slack <= p[1] && p[1] <= v[1] + slack
            }
            Domain::Triangle => p[0] >= -slack && p[1] >= -slack && p[0] + p[1] <= 1.0 + slack,
        }
    }

    /// The point where the segment from `from` (inside) to `to` leaves the
    /// domain: `from + s(to − from)` with the largest `s ∈ [0, 1]` that
    /// satisfies every constraint (and snapped onto the edge it meets).
    fn clip(&self, from: [f64; 2], to: [f64; 2]) -> [f64; 2] {
        let d = [to[0] - from[0], to[1] - from[1]];
        // Each constraint a·p ≤ b: the largest s with a·(from + s d) ≤ b.
        let limit = |a: [f64; 2], b: f64| {
            let slope = a[0] * d[0] + a[1] * d[1];
            let room = b - (a[0] * from[0] + a[1] * from[1]);
            if slope > 0.0 {
                (room / slope).clamp(0.0, 1.0)
            } else {
                1.0
            }
        };
        let s = match *self {
            Domain::Rect(u, v) => limit([1.0, 0.0], u[1])
                .min(limit([-1.0, 0.0], -u[0]))
                .min(limit([0.0, 1.0], v[1]))
                .min(limit([0.0, -1.0], -v[0])),
            Domain::Triangle => limit([-1.0, 0.0], 0.0)
                .min(limit([0.0, -1.0], 0.0))
                .min(limit([1.0, 1.0], 1.0)),
        };
        let p = [from[0] + s * d[0], from[1] + s * d[1]];
        self.snap(p)
    }

    /// `p` moved onto the domain where rounding left it a hair outside.
    fn snap(&self, p: [f64; 2]) -> [f64; 2] {
        match *self {
            Domain::Rect(u, v) => [p[0].clamp(u[0], u[1]), p[1].clamp(v[0], v[1])],
            // fl(a + fl(1 − a)) ≤ 1 for a ∈ [0, 1], so the snapped point passes `contains`.
            Domain::Triangle => {
                let a = p[0].clamp(0.0, 1.0);
                [a, p[1].clamp(0.0, 1.0 - a)]
            }
        }
    }

    /// The point of the domain nearest `p` (Euclidean).
    fn nearest(&self, p: [f64; 2]) -> [f64; 2] {
        match *self {
            Domain::Rect(..) => self.snap(p),
            Domain::Triangle => {
                let [u, v] = [p[0].clamp(0.0, 1.0), p[1].clamp(0.0, 1.0)];
                if u + v <= 1.0 {
                    return [u, v];
                }
                // Onto the edge u + v = 1, within its ends.
                let a = (p[0] - 0.5 * (p[0] + p[1] - 1.0)).clamp(0.0, 1.0);
                self.snap([a, 1.0 - a])
            }
        }
    }
}
