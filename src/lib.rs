//! # rootclip
//!
//! Certified roots of bivariate polynomial systems in Bernstein–Bézier form.
//!
//! The crate is layered, and data flows one way down this list:
//! 1. [`scalar`] — the number trait and its three kernels (`f64` proposes,
//!    [`inari::Interval`] encloses, [`num_rational::BigRational`] is exact);
//! 2. [`poly`] — univariate, triangular and tensor BB polynomials written once
//!    over any kernel: de Casteljau, subdivision onto any sub-triangle,
//!    elevation, derivatives, L2-best degree reduction with a rigorous bound,
//!    tensor → two triangles; exact parsing of expressions in `u`, `v`.
//!
//! Reference: Liu, Cao, Chen, Zeng (2016), *Ray-triangular Bézier patch
//! intersection using hybrid clipping algorithm*, FITEE 17(10),
//! doi:10.1631/FITEE.1500390.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod error;
pub mod heuristics;
pub mod poly;
pub mod ray;
pub mod repro;
pub mod rng;
pub mod scalar;
pub mod solve;

pub use error::{Error, Result};
pub use poly::{parse_polynomial, Polynomial, TensorBezier, TriBezier, UniBezier};
pub use scalar::{Kernel, Scalar, Sign};
pub use solve::{solve, Domain, Method, Solution, SolveOptions};
