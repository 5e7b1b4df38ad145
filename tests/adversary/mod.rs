//! The ray adversary: families of *grazing* rays against height-field patches,
//! judged by an independent referee in exact rational arithmetic.
//!
//! Shared by `tests/ray_props.rs` (a few hundred cases under proptest) and the
//! fuzz tool `dev/src/bin/adversary.rs` (many thousands, with reproductions).
//!
//! # The families
//! Every patch is a *height field* whose `x` and `y` are affine in the
//! parameters, exactly: `x = a·u + x0`, `y = b·v + y0` with `a, x0, b, y0`
//! dyadic, heights `z` random `f64` (all 52 mantissa bits, or sometimes few
//! bits so that ties are exact):
//! * [`Family::Tensor`]: bidegree `(m, n)`, `1 ≤ m, n ≤ 4`, control points
//!   `(x0 + a·i/m, y0 + b·j/n, z_ij)` (`a` a multiple of `m`, so they are floats);
//! * [`Family::Rational`]: the same with weights `w_ij = α_i` (positive,
//!   random): `y = b·v + y0` still holds, `x(u)` is rational; rays have `dy = 0`;
//! * [`Family::Triangle`]: degree `1 ≤ n ≤ 4`, points at the domain points
//!   `(x0 + a·i/n, y0 + b·j/n)`;
//! * [`Family::Bspline`]: bidegree `(p, q)`, `2 ≤ p, q ≤ 4`, dyadic knots
//!   (clamped, or unclamped one time in four), often with a crease (an
//!   interior knot of multiplicity `p`), control points at `a·`(Greville
//!   abscissae)`+ x0` (linear precision: `x = a·u + x0` on the domain);
//! * [`Family::Nurbs`]: the same with weights `w_ij = α_i`; rays have `dy = 0`.
//!
//! Heights are full-precision, or multiples of 1/256 (exact ties), or nearly
//! flat (`c + ε·r`, `ε` down to `2^-50`); one patch in five has a *flat edge*
//! (`∂z/∂u = 0` along an edge: its last two control rows equal).
//!
//! Rays are aimed at a *feature*: a corner, an edge (`u + v = 1` on
//! triangles), an interior knot line, a crease, a knot corner, or the
//! interior, and built so that the true hit lies on the feature up to the
//! rounding of one float (and ±1..3 ulps): horizontal or slanted rays through
//! the feature point with `oz` the rounded exact height there ("cross"),
//! vertical rays with `(ox, oy)` the rounded feature point ("vertical"),
//! horizontal rays running exactly along an edge or knot line ("along"), rays
//! whose `oz` is the rounded extremum of the height along their line, across
//! or along a feature ("tangent": two hits a few 1e-8 apart, or none), rays
//! along `u` onto a flat edge ("edge-tangent": a double hit on the edge split
//! by the rounding), and rays starting on the surface at the feature ("start":
//! a hit at `t ≈ 0`). Direction scales are about 1 or `2^±100`. One
//! horizontal case in five is *lowered* (see [`generate`]): the aimed height
//! becomes about 0, so one ulp of `oz` is tiny and the hits lie within
//! 1e-300 of their feature, tangent pairs down to 1e-162 apart.
//!
//! # The referee
//! The ray's line meets the patch where a univariate polynomial vanishes:
//! with the line parameter `s = t` (polynomial patches: `u(t)`, `v(t)` are
//! affine, the hits are the zeros of `z(u(t), v(t)) − oz − dz·t`), or `s = u`
//! (rational patches, `dy = 0`: `v = v*` is fixed and the hits are the zeros of
//! `dx·(N_z − oz·D) − dz·(N_x − ox·D)`, the homogeneous numerators and the
//! weight sum, and `t` a rational function of `u`, per knot span). The
//! polynomial is found exactly (exact evaluation of the Bernstein / B-spline
//! sums at rational points and interpolation; one piece per knot cell for
//! B-splines, a zero on a shared knot counted once) on the closed interval of
//! `s` where the line is in the domain, and its distinct zeros there are
//! isolated by Sturm sequences with exact rational ends. The referee reads the
//! patch's floats from its [`PatchSpec`](rootclip::ray::PatchSpec) (checking
//! the affine claim exactly) and uses nothing of rootclip but its public types.
//!
//! # What is checked ([`judge`])
//! On `intersect(patch, ray, RayOptions::default())`:
//! * **no silent miss**: if the outcome is complete, every true hit with
//!   `t ≥ 0` lies in the `(u, v)` box of a reported hit ([`Fault::Miss`]), and in
//!   the `t` box of one such hit ([`Fault::MissT`]);
//! * **no phantom**: every certified box holds exactly one true hit of the line
//!   ([`Fault::Phantom`]: none, [`Fault::Multiple`]: more), a transversal one
//!   ([`Fault::Tangent`]: a multiple zero, or a touch of a crease where the two
//!   pieces' one-sided slopes differ in sign), whose `t` lies in the `t` box
//!   and in the range `t ≥ 0` ([`Fault::TBox`]); no true hit is claimed by two
//!   certified boxes ([`Fault::Duplicate`]);
//! * every reported `(u, v)` lies in the closed domain ([`Fault::Domain`]);
//! * no error ([`Fault::Error`]); a `ZeroEquation` answer on these non-planar
//!   patches is recorded as suspicious ([`Fault::ZeroEquation`]) but keeps the
//!   contract (no hit list rather than a wrong one).
//!
//! Every membership is decided exactly: a zero is compared with a float (a
//! box end) by the sign of the polynomial there, or, for a non-linear test
//! (the `t` of a rational patch), by refining its isolating interval until the
//! test polynomial has no zero in it. Undecided hits and incomplete or
//! unresolved outcomes are allowed (counted, not faults).
//!
//! # The modules
//! * the case: `case` ([`Case`], [`Family`], replay commands);
//! * the generator: `generate` ([`generate`], the seeded stream [`Mix`]),
//!   `grid` (the patches and their features), `aim` (the rays);
//! * the referee: `exact` (rationals, rounding), `poly` (polynomials over Q
//!   and Z, Sturm sequences), `surface` (the patch in exact arithmetic),
//!   `restrict` (the line's polynomial on each piece), `truth` (the isolated
//!   zeros and exact membership tests);
//! * the judge: `judge` ([`judge`], [`Fault`], [`Verdict`], [`report`]);
//! * `tests`: the referee's own tests.

// Shared by a test binary and a dev tool, each using a part of it.
#![allow(dead_code)]

mod aim;
mod case;
mod exact;
mod generate;
mod grid;
mod judge;
mod poly;
mod restrict;
mod surface;
#[cfg(test)]
mod tests;
mod truth;

// What `tests/ray_props.rs` and `dev/src/bin/adversary.rs` use. Each uses a
// part of it, so the other's names would be unused imports.
#[allow(unused_imports)]
pub use self::{
    case::{Case, Family},
    generate::{generate, Mix},
    judge::{judge, report, Answer, Fault, Verdict},
};
