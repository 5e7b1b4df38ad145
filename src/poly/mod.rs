//! Polynomials in Bernstein–Bézier form: univariate on an interval, triangular
//! of total degree `n`, tensor-product of bidegree `(m, n)`; exact monomial
//! input and its conversion; exact L2 machinery.
//!
//! All BB types are generic over [`Scalar`](crate::scalar::Scalar), so the same
//! code runs in `f64`, in rigorous intervals and in exact rationals.

pub mod ball;
pub mod dyadic;
pub mod l2;
pub mod monomial;
pub mod parse;
pub mod tensor;
pub mod triangle;
pub mod univariate;

pub use ball::{Reduced, TriBall, TriBallDD};
pub use monomial::Polynomial;
pub use parse::parse_polynomial;
pub use tensor::{Direction, TensorBezier, TensorReduction};
pub use triangle::{split4_vertices, tri_index, tri_indices, tri_len, Bary, TriBezier, TriReduction};
pub use univariate::{UniBezier, UniReduction};
