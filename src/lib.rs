//! # rootclip
//!
//! Every root of a polynomial system in Bernstein–Bézier form, with a proof:
//! each root in a small box certified to hold exactly one root, the rest of
//! the domain proven root-free, and honest *undecided* regions where a proof
//! is out of reach. On top of the solver: certified ray–patch intersection
//! for triangular, tensor, rational and B-spline/NURBS patches.
//!
//! ```
//! use rootclip::solve::{solve, Domain, SolveOptions};
//! let f = rootclip::parse_polynomial("u^3 - v")?;
//! let g = rootclip::parse_polynomial("u^3 + v - 1/4")?;
//! let sol = solve(&f, &g, Domain::Triangle, &SolveOptions::default())?;
//! assert!(sol.complete && sol.roots.len() == 1 && sol.clusters.is_empty());
//! assert!(sol.roots[0].bx.contains(0.5, 0.125)); // the root (1/2, 1/8), proven
//! # Ok::<(), rootclip::Error>(())
//! ```
//!
//! # Layers
//! Data flows one way, down this list; nothing lower knows about anything
//! higher.
//! 1. [`scalar`] — the number tower: `f64` proposes, [`inari::Interval`]
//!    encloses, [`num_rational::BigRational`] decides; the [`Scalar`] trait
//!    over all three (inside: branchless intervals, error-free
//!    transformations, double-double).
//! 2. [`poly`] — Bernstein–Bézier algebra written once over any kernel:
//!    [`UniBezier`], [`TriBezier`], [`TensorBezier`], exact [`Polynomial`]s
//!    and the expression parser (inside: ball polynomials, L2 reduction).
//! 3. [`solve`](mod@solve) — the certified solver: [`solve::solve`],
//!    [`solve::solve_bb`] and the [`Solution`] contract (inside:
//!    triangle clipping — Bézier, linear, hybrid — with verified clips, box
//!    clipping for tensor systems, Krawczyk certificates, exact settling on
//!    the boundary).
//! 4. Front ends: [`ray`] (certified ray–patch hits), [`project`] (certified
//!    closest points and inversion), [`heuristics`] (uncertified solvers from
//!    the papers, refereed by the certified ones).
//! 5. The `rootclip` binary (feature `cli`).
//!
//! # Features
//! * `cli` (default): the `rootclip` binary; pulls in clap, indicatif and
//!   serde_json. A library user can turn it off (`default-features = false`).
//! * `serde`: `Serialize`/`Deserialize` on options, results and
//!   [`ray::PatchSpec`]; the CLI's JSON comes from these derives.
//!
//! # Building
//! inari needs the FMA/AVX instructions of x86-64-v3: a crate that depends
//! on rootclip sets `rustflags = ["-C", "target-cpu=haswell"]` (or `native`)
//! for `x86_64` targets in its `.cargo/config.toml` (see the README).
//!
//! Reference: Liu, Cao, Chen, Zeng (2016), *Ray-triangular Bézier patch
//! intersection using hybrid clipping algorithm*, FITEE 17(10),
//! doi:10.1631/FITEE.1500390.
#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod error;
pub mod heuristics;
pub mod poly;
pub mod project;
pub mod ray;
pub mod scalar;
pub mod solve;

// The paper reproductions: the `tables` command, and the report example
// through `internals` (which uses more of it than the command does).
#[cfg(any(feature = "cli", feature = "internals"))]
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub(crate) mod repro;
#[cfg(any(test, feature = "internals"))]
pub(crate) mod rng;
#[cfg(feature = "serde")]
mod serde_util;

#[cfg(feature = "cli")]
#[doc(hidden)]
pub mod cli;
#[cfg(feature = "internals")]
#[doc(hidden)]
pub mod internals;

pub use error::{Error, Result};
pub use poly::{parse_polynomial, Polynomial, TensorBezier, TriBezier, UniBezier};
pub use scalar::{Scalar, Sign};
pub use solve::{solve, solve_bb, Domain, Method, Solution, SolveOptions};

// The README's Rust examples run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The crates whose types appear in rootclip's signatures, re-exported so
/// that a user's versions always match.
pub use {glam, inari, num_bigint, num_rational};
