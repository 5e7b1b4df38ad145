//! Not part of the API (feature `internals`, hidden from the docs): the
//! crate's internals for its benches, tests and dev tools. Anything here may
//! change or vanish in any release.

/// The triangle solver's iteration (Algorithm 1 on ball polynomials).
pub mod driver {
    pub use crate::solve::driver::edges::*;
    pub use crate::solve::driver::estimates::*;
    pub use crate::solve::driver::precision::*;
    pub use crate::solve::driver::run;
    pub use crate::solve::driver::state::*;
}
/// Fat curves, verified clips, candidate enumeration, hull bounds.
pub mod fatcurve {
    pub use crate::solve::fatcurve::*;
}
/// The clipping methods and preprocessing.
pub mod method {
    pub use crate::solve::method::*;
}
/// The geometry kernels (`f64`, `GeoIv`).
pub mod geo {
    pub use crate::scalar::geo::*;
}
/// Tri-boxes: verified clip and split.
pub mod tribox {
    pub use crate::solve::tribox::*;
}
/// The box solver for tensor systems.
pub mod rect {
    pub use crate::solve::rect::*;
}
/// The paper's systems and tables.
pub mod repro {
    pub use crate::repro::*;
}
/// Ball polynomials.
pub mod ball {
    pub use crate::poly::ball::*;
}
/// Exact L2 machinery.
pub mod l2 {
    pub use crate::poly::l2::*;
}
/// Triangular BB internals.
pub mod triangle {
    pub use crate::poly::triangle::*;
}

pub use crate::heuristics::experiment::at_scale_rays;
pub use crate::ray::sample::{aimed_rays, secondary_rays, surface_aimed_rays};
pub use crate::rng::Rng;

use crate::poly::{TensorBezier, TriBezier};
use crate::solve::{Box2, Root, Solution, SolveOptions};
use inari::Interval;
use num_rational::BigRational;

/// The point interval `[x, x]`.
pub fn point(x: f64) -> Interval {
    crate::scalar::point(x)
}

/// The interval `[lo, hi]` (entire if NaN or reversed).
pub fn interval(lo: f64, hi: f64) -> Interval {
    crate::scalar::interval(lo, hi)
}

/// `q ∈ x`, exactly.
pub fn interval_contains_rational(x: Interval, q: &BigRational) -> bool {
    crate::scalar::interval_contains_rational(x, q)
}

/// The triangle solver on interval BB input (what `solve_bb` runs for it).
pub fn solve_triangle(
    f: &TriBezier<Interval>,
    g: &TriBezier<Interval>,
    opts: &SolveOptions,
) -> crate::Result<Solution> {
    crate::solve::solve_triangle(f, g, opts)
}

/// The square solver on interval BB input.
pub fn solve_square(
    f: &TensorBezier<Interval>,
    g: &TensorBezier<Interval>,
    opts: &SolveOptions,
) -> crate::Result<Solution> {
    crate::solve::solve_square(f, g, opts)
}

/// The same clipping iteration in plain `f64`, without proofs: the centres
/// of its final tri-boxes (the baseline of the cost of rigor).
pub fn solve_triangle_f64(f: &TriBezier<f64>, g: &TriBezier<f64>, opts: &SolveOptions) -> Vec<[f64; 2]> {
    crate::solve::solve_triangle_f64(f, g, opts)
}

/// A root entry as a solver would report it (for tests of result checkers).
pub fn root(u: f64, v: f64, bx: Box2, on_boundary: bool) -> Root {
    Root {
        u,
        v,
        bx,
        on_boundary,
        diameters: Vec::new(),
    }
}
