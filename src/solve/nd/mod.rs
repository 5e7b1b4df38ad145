//! The certified solver for square systems in `N` unknowns (`N = 3, 4` in
//! rootclip's uses; any `N ≥ 1` works): every zero of
//! `F = (f_1, …, f_N) = 0` in the closed unit box `[0, 1]^N`, each `f_e` a
//! tensor-product Bernstein polynomial ([`BernsteinNd`]).
//!
//! ```
//! use rootclip::solve::nd::{solve_nd, BernsteinNd, NdOptions};
//! // x − 1/4, y − 1/2, z − 3/4 on the unit cube, degree 1 in each variable.
//! let lin = |axis: usize, r: f64| {
//!     let c = (0..8).map(|k| ((k >> (2 - axis)) & 1) as f64 - r).collect();
//!     BernsteinNd::<3>::new([1, 1, 1], c)
//! };
//! let sys = [lin(0, 0.25)?, lin(1, 0.5)?, lin(2, 0.75)?];
//! let sol = solve_nd(&sys, &NdOptions::default())?;
//! assert!(sol.complete && sol.undecided.is_empty() && sol.roots.len() == 1);
//! let b = sol.roots[0].bx;
//! assert!(b[0][0] <= 0.25 && 0.25 <= b[0][1] && b[2][0] <= 0.75 && 0.75 <= b[2][1]);
//! # Ok::<(), rootclip::Error>(())
//! ```
//!
//! # Contract ([`NdSolution`])
//! For every system whose coefficients lie in the input enclosures (for
//! `f64` input: for that system):
//! * if `complete` is true, every zero of `F` in the closed box `[0, 1]^N`
//!   lies in a `roots` box or an `undecided` box;
//! * whatever `complete` says, a zero in none of them lies in a `leftovers`
//!   box (the budget `max_boxes` stopped there); `complete` is true iff
//!   `leftovers` is empty;
//! * each `roots[k].bx` holds exactly one zero of `F` in `ℝ^N`, a simple one
//!   (`F'` non-singular there), and distinct entries hold distinct zeros.
//!   A box that reaches outside the unit box (`on_boundary`) may hold a zero
//!   of the polynomials' continuation within its width outside it; boxes
//!   wholly outside are dropped;
//! * `undecided` boxes promise nothing (a multiple zero, zeros closer than
//!   `eps`, a curve of zeros).
//!
//! # The iteration
//! Depth first over boxes, each box carrying enclosures of the Bernstein
//! coefficients of every `f_e` restricted to it (local coordinates
//! `[0, 1]^N`). One step:
//! 1. **sign exclusion**: an `f_e` whose coefficients are all strictly
//!    positive, or all strictly negative, has no zero on the box (the tensor
//!    Bernstein basis is a positive partition of unity);
//! 2. **Krawczyk** once the box's widest side is at most ¼: `X = [0, 1]^N`,
//!    `F'(X)` the hull of the derivatives' Bernstein coefficients, `F(x̃)`
//!    by interval de Casteljau, `Y` the `f64` inverse of the midpoint
//!    Jacobian. `K(X) ⊂ (0, 1)^N` proves exactly one zero, simple and
//!    interior (so no neighbouring box can claim it), which is contracted
//!    (Newton with `Y` fixed, checked by one more step) and reported;
//!    `K(X) ∩ X = ∅` proves none;
//! 3. **clip** every axis by the projected polyhedron of every equation
//!    (Sherbrooke & Patrikalakis 1993; see `clip.rs`), the kept span the
//!    intersection over the equations, widened by a quarter of its width on
//!    each side (a simple zero never ends within rounding of a new face)
//!    with no side below `10⁻³` of the widest — the rules of the bivariate
//!    box solver ([`rect`](crate::solve)). A clip is two de Casteljau
//!    splits at floats, so each box is an exact sub-box of its parent;
//! 4. a clip that kept more than half the volume is followed by a clip with
//!    the rows of `Y·F` (each a combination of the equations, so it keeps
//!    every zero; near a simple zero nearly `x_d − x*_d`), equations raised
//!    to common degrees first;
//! 5. still stalled: **split** the widest side at `63/128`.
//!
//! A box narrower than `eps` that step 2 did not settle (a zero on a face,
//! a multiple zero, two zeros closer than the subdivided coefficients
//! resolve) is a *leaf*: Krawczyk in domain coordinates on the leaf inflated
//! by a tenth of its width, then by its width, with `F(x̃)` evaluated
//! exactly (rational de Casteljau on the coefficients' midpoints, plus the
//! largest radius) and `F'(X)` enclosed from the derivatives of the whole
//! system (see `global.rs`). A unique zero
//! touching the leaf is a root (overlapping roots are merged only when
//! Krawczyk proves one zero in their hull, and kept apart when it proves
//! none in their intersection); no zero excludes it; otherwise the leaf is
//! undecided, and touching undecided leaves are joined. Stalled boxes below
//! `10⁻⁹` are leaves at once (near a multiple zero rounding hides the signs
//! over a region about the square root of the rounding wide).
//!
//! All arithmetic on coefficients is the branchless interval kernel of the
//! box solver (each endpoint rounded to nearest, moved one float outward).

pub(crate) mod clip;
pub(crate) mod global;
pub(crate) mod krawczyk;
mod runner;
pub(crate) mod tensor;

pub use tensor::BernsteinNd;

use crate::error::{Error, Result};
use crate::solve::solution::Stats;

/// Options of [`solve_nd`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct NdOptions {
    /// Boxes narrower than this (in every axis) are leaves; in `(0, 1)`.
    pub eps: f64,
    /// Boxes processed before the run stops with `complete = false`.
    pub max_boxes: usize,
}

impl Default for NdOptions {
    fn default() -> Self {
        Self {
            eps: 1e-12,
            max_boxes: 200_000,
        }
    }
}

impl NdOptions {
    /// The same options with another `eps`.
    pub fn with_eps(mut self, eps: f64) -> Self {
        self.eps = eps;
        self
    }

    /// The same options with another box budget.
    pub fn with_max_boxes(mut self, max_boxes: usize) -> Self {
        self.max_boxes = max_boxes;
        self
    }
}

/// A certified zero: its box holds exactly one zero of the system, simple.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct NdRoot<const N: usize> {
    /// The midpoint of the box.
    pub x: [f64; N],
    /// The closed box `[lo, hi]` per axis.
    pub bx: [[f64; 2]; N],
    /// The box is not strictly inside the open unit box.
    pub on_boundary: bool,
}

/// An undecided region: it may hold any number of zeros.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct NdUndecided<const N: usize> {
    /// The closed box `[lo, hi]` per axis.
    pub bx: [[f64; 2]; N],
}

/// The result of [`solve_nd`]; see the module docs for the contract.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct NdSolution<const N: usize> {
    /// Every zero is in `roots` or `undecided` (see the contract).
    pub complete: bool,
    /// Certified zeros, sorted by their midpoints.
    pub roots: Vec<NdRoot<N>>,
    /// Regions where nothing was proven.
    pub undecided: Vec<NdUndecided<N>>,
    /// Boxes a budget left unexplored.
    pub leftovers: Vec<[[f64; 2]; N]>,
    /// Counters (`boxes` counts boxes processed).
    pub stats: Stats,
}

/// Every zero of the square system `system` in the closed unit box
/// `[0, 1]^N`, with the contract of the [module docs](self).
///
/// Errors: an equation whose coefficients all contain 0 (it may vanish
/// identically: [`Error::Degenerate`]), an `eps` outside `(0, 1)`
/// ([`Error::InvalidOption`]), coefficients beyond `10³⁰⁰`
/// ([`Error::NonFinite`]).
pub fn solve_nd<const N: usize>(system: &[BernsteinNd<N>; N], opts: &NdOptions) -> Result<NdSolution<N>> {
    solve_nd_exact(system, None, opts)
}

/// [`solve_nd`] for a system whose exact values are known (`exact`: the
/// polynomials whose coefficients lie in `system`'s enclosures): the
/// leaves' Krawczyk tests then evaluate `F` exactly.
pub(crate) fn solve_nd_exact<const N: usize>(
    system: &[BernsteinNd<N>; N],
    exact: Option<&dyn global::ExactValues<N>>,
    opts: &NdOptions,
) -> Result<NdSolution<N>> {
    if !(opts.eps > 0.0 && opts.eps < 1.0) {
        return Err(Error::InvalidOption(format!(
            "eps must lie in (0, 1), got {}",
            opts.eps
        )));
    }
    for (e, p) in system.iter().enumerate() {
        if p.c.iter().all(|x| x.lo <= 0.0 && x.hi >= 0.0) {
            return Err(Error::Degenerate(format!(
                "equation {e}: every coefficient may be zero (it may vanish identically)"
            )));
        }
        if p.c.iter().any(|x| !(x.lo.abs() <= 1e300 && x.hi.abs() <= 1e300)) {
            return Err(Error::NonFinite(format!("equation {e}: a coefficient is beyond 1e300")));
        }
    }
    let deg: [[usize; N]; N] = std::array::from_fn(|e| system[e].deg);
    let root: Vec<_> = system.iter().map(|p| p.c.clone()).collect();
    Ok(runner::Runner::new(deg, &root, exact, *opts).run())
}
