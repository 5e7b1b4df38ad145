//! The number trait behind the Bernstein–Bézier algebra, and its three kernels.
//!
//! Every polynomial type in [`crate::poly`] is generic over [`Scalar`]. The
//! three kernels play three roles:
//!
//! | kernel | role | rounding |
//! |---|---|---|
//! | `f64` | fast *proposals* (approximants, Newton midpoints) | round-to-nearest, no guarantee |
//! | [`Interval`](inari::Interval) (inari) | rigorous *enclosures*: every operation rounds outward, so the exact result of the same computation on any members of the inputs lies in the output | outward |
//! | [`BigRational`](num_rational::BigRational) | exact reference arithmetic (oracles, tests, parsing) | exact |
//!
//! inari implements no `num-traits`, so the trait is ours (the same choice the
//! `geo`/`robust` crates make for their kernels).
//!
//! # Conversions
//! * [`rational_to_interval`]: the *tightest* interval with `f64` endpoints
//!   containing a rational. A rational that is not a float (such as 1/10) becomes
//!   an interval of width one ulp, never a point.
//! * [`rational_to_f64`] rounds to nearest.
//!
//! # Speed of the interval kernel
//! The hot loops of [`crate::poly`] run interval arithmetic on bare endpoint
//! pairs (the crate-private `endpoints` module): the same operations in the
//! same order, each endpoint the same float inari's operators produce, but
//! without inari's switch of the FPU rounding mode per operation, which made
//! interval code 10–25 times slower than `f64`.

mod cache;
mod convert;
pub(crate) mod eft;
mod endpoints;
pub(crate) mod geo;
pub(crate) mod iv;
mod kernel;
pub(crate) mod rational_interval;

pub use convert::{rational_to_f64, rational_to_interval};
pub use kernel::{Kernel, Scalar, Sign};

pub(crate) use cache::{MatrixCache, MatrixKey};
#[cfg(any(test, feature = "internals"))]
pub(crate) use convert::interval_contains_rational;
pub(crate) use convert::{interval, point};
pub(crate) use endpoints::{
    cached_endpoints, endpoint_net, endpoint_of, endpoints_of, from_endpoint, from_endpoints, store_endpoints, Arith,
    Endpoints,
};
