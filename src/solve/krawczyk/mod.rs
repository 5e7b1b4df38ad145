//! Krawczyk's interval Newton operator: existence, uniqueness and exclusion
//! proofs for a root of `F = (f, g)` in a box.
//!
//! # Definition
//! For a box `X`, `x̃ = mid X`, `Y ≈ F'(x̃)⁻¹` (any real matrix, computed in
//! f64) and an interval enclosure `F'(X)` of the Jacobian over `X`:
//! ```text
//! K(X) = x̃ − Y F(x̃) + (I − Y F'(X)) (X − x̃)
//! ```
//! * `K(X) ⊂ int X` ⟹ `F` has exactly one zero in `X`, it lies in `K(X)`, and
//!   it is simple (`F'` is non-singular there) — Krawczyk 1969, Rump 1983.
//! * `K(X) ∩ X = ∅` ⟹ `F` has no zero in `X` (every zero in `X` lies in `K(X)`).
//!
//! # Variants
//! One operator, four arithmetics; every test answers with one [`Verdict`].
//! * [`System`]: inari intervals on any [`Bivariate`] polynomials (triangular
//!   and tensor BB), with epsilon-inflation and contraction — the solvers'
//!   certificates.
//! * `local`: the box solver's test on `X = [0, 1]²` in a box's own
//!   coordinates, in its branchless `Iv` arithmetic, with `F'(X)` the hull of
//!   the derivative's Bernstein coefficients. Not over [`Bivariate`], whose
//!   enclosures are inari's: the box solver's hot loop avoids inari's
//!   rounding-mode switch per operation, and its Jacobian comes from the
//!   box's coefficients, not from evaluating partial derivatives.
//! * `exact`: rational interval arithmetic on exact systems, for what
//!   rounding left undecided and for settling boundary roots
//!   ([`settle`](crate::solve::settle)). Not over [`Bivariate`] either: its
//!   enclosures round to floats, the noise this variant exists to remove.
//! * `piecewise`: a continuous system that is a different [`Bivariate`]
//!   system on each cell of the plane (a B-spline surface's pieces across
//!   knot lines), with one `I − Y J_k(X)` per piece.

pub(crate) mod exact;
mod interval;
pub(crate) mod local;
pub(crate) mod piecewise;
mod verdict;

pub use interval::{Bivariate, System};
pub use verdict::{IBox, Verdict};
