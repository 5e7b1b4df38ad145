//! Polynomials in Bernstein–Bézier form: univariate on an interval, triangular
//! of total degree `n`, tensor-product of bidegree `(m, n)`; exact monomial
//! input, its parser and its conversion to BB form.
//!
//! All BB types are generic over [`Scalar`](crate::scalar::Scalar), so the
//! same code runs in `f64`, in rigorous intervals and in exact rationals:
//!
//! ```
//! use rootclip::{num_rational::BigRational, TriBezier};
//! // u² on the unit triangle, degree 2, coefficients in the order of tri_indices.
//! let p = rootclip::parse_polynomial("u^2")?;
//! let bb: TriBezier<BigRational> = p.to_triangle(2);
//! let x: TriBezier<f64> = bb.map(|q| rootclip::scalar::rational_to_f64(q));
//! assert!((x.eval(0.5, 0.25) - 0.25).abs() < 1e-15);
//! # Ok::<(), rootclip::Error>(())
//! ```

pub(crate) mod ball;
pub(crate) mod dyadic;
mod index;
pub(crate) mod l2;
mod monomial;
mod parse;
pub(crate) mod tensor;
pub(crate) mod triangle;
mod univariate;

pub use index::{tri_index, tri_indices, tri_len, Bary};
pub use monomial::Polynomial;
pub use parse::parse_polynomial;
pub use tensor::{Direction, TensorBezier, TensorReduction};
pub use triangle::{TriBezier, TriReduction};
pub use univariate::{UniBezier, UniReduction};

pub(crate) use ball::{Reduced, TriBall, TriBallDD};
pub(crate) use l2::pascal;
pub(crate) use univariate::{eval_coeffs, split_coeffs};
