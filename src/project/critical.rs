//! The critical points of the squared distance `D(u, v) = |S(u, v) − P|²`:
//! the polynomial systems whose roots they are, built in interval
//! arithmetic from a patch's homogeneous net.
//!
//! For `S = X/W` (`W = 1` for a polynomial patch) and `W > 0`,
//!
//! ```text
//! ∂D/∂u = 2 (X − P W)·(X_u W − X W_u) / W³,
//! ```
//! so the interior critical points are the roots of
//! `F = (X − P W)·(X_u W − X W_u)` and `G` (the same with `v`), and on an edge
//! `C(s) = X(s)/W(s)` those of `(X − P W)·(X' W − X W')`; for a polynomial
//! patch `F = (X − P)·X_u`. Every coefficient is an interval enclosure of the
//! exact one, so the solver's certificates speak of the exact system.

use crate::poly::{Direction, TensorBezier, TriBezier};
use crate::scalar::point;
use inari::Interval;

/// What the construction needs from a BB polynomial type.
pub(super) trait Bb: Clone {
    fn mul(&self, other: &Self) -> Self;
    fn add(&self, other: &Self) -> Self;
    fn sub(&self, other: &Self) -> Self;
    fn scale(&self, c: Interval) -> Self;
    /// Every coefficient minus `c`: the polynomial minus the constant `c`.
    fn sub_const(&self, c: Interval) -> Self;
    fn d_u(&self) -> Self;
    fn d_v(&self) -> Self;
}

impl Bb for TensorBezier<Interval> {
    fn mul(&self, other: &Self) -> Self {
        TensorBezier::mul(self, other)
    }
    fn add(&self, other: &Self) -> Self {
        TensorBezier::add(self, other)
    }
    fn sub(&self, other: &Self) -> Self {
        TensorBezier::sub(self, other)
    }
    fn scale(&self, c: Interval) -> Self {
        self.map_coeffs(|x| *x * c)
    }
    fn sub_const(&self, c: Interval) -> Self {
        self.map_coeffs(|x| *x - c)
    }
    fn d_u(&self) -> Self {
        self.deriv(Direction::U)
    }
    fn d_v(&self) -> Self {
        self.deriv(Direction::V)
    }
}

impl Bb for TriBezier<Interval> {
    fn mul(&self, other: &Self) -> Self {
        TriBezier::mul(self, other)
    }
    fn add(&self, other: &Self) -> Self {
        TriBezier::add(self, other)
    }
    fn sub(&self, other: &Self) -> Self {
        TriBezier::sub(self, other)
    }
    fn scale(&self, c: Interval) -> Self {
        self.map(|x| *x * c)
    }
    fn sub_const(&self, c: Interval) -> Self {
        self.map(|x| *x - c)
    }
    fn d_u(&self) -> Self {
        self.deriv_u()
    }
    fn d_v(&self) -> Self {
        self.deriv_v()
    }
}

/// `Σ_k a_k · b_k`.
fn dot<P: Bb>(a: &[P; 3], b: &[P; 3]) -> P {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

/// `(F, G)` for the homogeneous net `[wx, wy, wz, w]` and the point `p`;
/// `rational` is false when `w ≡ 1`.
pub(super) fn interior_system<P: Bb>(net: &[P; 4], p: [f64; 3], rational: bool) -> (P, P) {
    let x: [P; 3] = [net[0].clone(), net[1].clone(), net[2].clone()];
    if !rational {
        // X − P: the Bernstein basis sums to 1, so p comes off every coefficient.
        let diff: [P; 3] = std::array::from_fn(|k| x[k].sub_const(point(p[k])));
        let xu: [P; 3] = std::array::from_fn(|k| x[k].d_u());
        let xv: [P; 3] = std::array::from_fn(|k| x[k].d_v());
        return (dot(&diff, &xu), dot(&diff, &xv));
    }
    let w = &net[3];
    let diff: [P; 3] = std::array::from_fn(|k| x[k].sub(&w.scale(point(p[k]))));
    let (wu, wv) = (w.d_u(), w.d_v());
    let tu: [P; 3] = std::array::from_fn(|k| x[k].d_u().mul(w).sub(&x[k].mul(&wu)));
    let tv: [P; 3] = std::array::from_fn(|k| x[k].d_v().mul(w).sub(&x[k].mul(&wv)));
    (dot(&diff, &tu), dot(&diff, &tv))
}

/// The edge function `(X − P W)·(X' W − X W')` (or `(X − P)·X'`) of a
/// homogeneous net of curves on `[0, 1]`, each stored as a tensor polynomial
/// of bidegree `(m, 0)` (the curve's parameter is `u`).
pub(super) fn edge_function(net: &[TensorBezier<Interval>; 4], p: [f64; 3], rational: bool) -> TensorBezier<Interval> {
    interior_system(net, p, rational).0
}
