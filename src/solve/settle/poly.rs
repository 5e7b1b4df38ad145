//! The exact system's polynomials as the evaluations need them: exact BB
//! polynomials and their derivatives ([`Poly`]), enclosed over rational
//! boxes ([`eval`]) and valued exactly at rational points ([`eval_at`]), and
//! their `f64` interval copies ([`FPoly`]) for the Jacobian's enclosures.

use super::{Shape, Q};
use crate::poly::{tri_index, Direction, TensorBezier, TriBezier};
use crate::scalar::iv::Iv;
use crate::scalar::rational_interval::RI;
use crate::scalar::rational_to_interval;
use crate::solve::krawczyk::Bivariate;
use crate::solve::nd::tensor::eval_box;
use inari::{interval, Interval};
use num_bigint::BigInt;
use num_traits::{One, ToPrimitive};

/// `[[f_u, f_v], [g_u, g_v]]` with interval coefficients that enclose the
/// exact ones.
#[derive(Clone, Debug)]
pub(super) struct FloatDerivs {
    pub(super) d1: [[FPoly; 2]; 2],
}

/// A [`Poly`] with `f64` interval coefficients enclosing its own.
#[derive(Clone, Debug)]
pub(super) enum FPoly {
    Triangle(TriBezier<Interval>),
    Tensor(Box<TensorBezier<Interval>>),
}

impl FPoly {
    pub(super) fn of(p: &Poly) -> Self {
        match p {
            Poly::Triangle(t) => FPoly::Triangle(t.map(rational_to_interval)),
            Poly::Tensor(t) => FPoly::Tensor(Box::new(t.map(rational_to_interval))),
        }
    }

    /// An enclosure of the range over `u × v` (inari, outward rounding).
    pub(super) fn over(&self, u: Interval, v: Interval) -> Interval {
        match self {
            FPoly::Triangle(t) => t.value(u, v),
            FPoly::Tensor(t) => {
                // De Casteljau with interval parameters (each step encloses
                // its values for every parameter in the range), in [`Iv`].
                let (m, n) = t.degree();
                let c: Vec<Iv> = t.coeffs().iter().map(|x| Iv::new(x.inf(), x.sup())).collect();
                let x = eval_box(&c, &[m, n], &[[u.inf(), u.sup()], [v.inf(), v.sup()]]);
                interval!(x.lo, x.hi).unwrap_or(Interval::ENTIRE)
            }
        }
    }

    /// An enclosure of the range over the box `u × v` (float endpoints, any
    /// position) by the convex hull property: the coefficients on a piece
    /// holding the box — the box itself on the square, the right triangle
    /// with legs `Δu + Δv` at its lower-left corner on the triangle — by de
    /// Casteljau at point parameters, their hull. Unlike interval de
    /// Casteljau over `u × v` (whose excess is about the coefficients'
    /// size times the width, hopeless where they cancel heavily), the excess
    /// is of the order of the range's own variation plus rounding.
    pub(super) fn hull_over(&self, u: [f64; 2], v: [f64; 2]) -> Interval {
        let pt = |x: f64| interval!(x, x).unwrap_or(Interval::ENTIRE);
        let coeffs: Vec<Interval> = match self {
            FPoly::Tensor(t) => {
                let (m, n) = t.degree();
                // Rows (lines in v) restricted in place, then columns.
                let mut c: Vec<Iv> = t.coeffs().iter().map(|x| Iv::new(x.inf(), x.sup())).collect();
                for row in c.chunks_exact_mut(n + 1) {
                    restrict_line(row, v);
                }
                let mut col = vec![Iv::point(0.0); m + 1];
                let mut hull = Iv::new(f64::INFINITY, f64::NEG_INFINITY);
                for j in 0..=n {
                    for (i, x) in col.iter_mut().enumerate() {
                        *x = c[i * (n + 1) + j];
                    }
                    restrict_line(&mut col, u);
                    hull = col.iter().fold(hull, |h, x| h.hull(*x));
                }
                return interval!(hull.lo, hull.hi).unwrap_or(Interval::ENTIRE);
            }
            FPoly::Triangle(t) => {
                let side = (pt(u[1]) - pt(u[0])) + (pt(v[1]) - pt(v[0]));
                let bary = |a: Interval, b: Interval| [a, b, pt(1.0) - a - b];
                let (u0, v0) = (pt(u[0]), pt(v[0]));
                let verts = [bary(u0, v0), bary(u0 + side, v0), bary(u0, v0 + side)];
                t.subdivide(&verts).coeffs().to_vec()
            }
        };
        coeffs.iter().fold(Interval::EMPTY, |acc, c| acc.convex_hull(*c))
    }
}

/// The coefficients of the BB line `c` (parameter range `[0, 1]`) on a
/// superset of `[a, b]`, in place, by two de Casteljau splits (enclosures
/// throughout, [`Iv`]). Normally the right part at `a`, then the left part
/// of that at `γ ≥ (b − a)/(1 − a)` (rounded up). When `b > 1 ≥ a ≥ 0`
/// (a box widened past the domain's edge), the left part at `b` first,
/// then the right part of that at `α ≤ a/b` (rounded down): extrapolating
/// a degree-`n` line to `t` widens its intervals by `(|1 − t| + |t|)ⁿ`,
/// which is `(1 + 2(b − 1))ⁿ` from the whole line but `(1 + 2(b − 1)/(1 −
/// a))ⁿ` from the short piece `[a, 1]` (`1.25¹⁰⁰ ≈ 10¹⁰` for a box an eighth
/// beyond the edge, at degree 100).
fn restrict_line(c: &mut [Iv], [a, b]: [f64; 2]) {
    let n = c.len() - 1;
    if n == 0 {
        return;
    }
    let (pa, pb) = (Iv::point(a), Iv::point(b));
    if b > 1.0 && a >= 0.0 {
        left_part(c, b);
        let alpha = pa.div(pb).lo;
        if alpha.is_nan() {
            c.fill(Iv::new(f64::NEG_INFINITY, f64::INFINITY));
        } else if alpha > 0.0 {
            right_part(c, alpha);
        }
        return;
    }
    if a != 0.0 {
        right_part(c, a);
    }
    let gamma = pb.sub(pa).div(Iv::point(1.0).sub(pa)).hi;
    if gamma.is_nan() {
        c.fill(Iv::new(f64::NEG_INFINITY, f64::INFINITY));
    } else if !(gamma >= 1.0 && b <= 1.0) {
        // (Else the whole right part `[a, 1]`: a superset of `[a, b]`.)
        left_part(c, gamma);
    }
}

/// One step of de Casteljau at `t` (extrapolation by general products).
fn lerp(x: Iv, y: Iv, t: f64) -> Iv {
    if (0.0..=1.0).contains(&t) {
        Iv::lerp(x, y, t)
    } else {
        Iv::lerp_any(x, y, t)
    }
}

/// The line's coefficients on `[t, 1]`, in place: after level `k`,
/// `c[n − k]` holds the level-`k` value at index `n − k`, which later levels
/// leave alone.
fn right_part(c: &mut [Iv], t: f64) {
    let n = c.len() - 1;
    for k in 1..=n {
        for i in 0..=n - k {
            c[i] = lerp(c[i], c[i + 1], t);
        }
    }
}

/// The line's coefficients on `[0, t]`, in place: after level `k`, `c[k]`
/// holds the level-`k` value at index 0, which later levels leave alone.
fn left_part(c: &mut [Iv], t: f64) {
    let n = c.len() - 1;
    for k in 1..=n {
        for i in (k..=n).rev() {
            c[i] = lerp(c[i - 1], c[i], t);
        }
    }
}

/// The `f64` interval hull of a rational interval.
pub(super) fn hull(x: &RI) -> Interval {
    let (lo, hi) = (rational_to_interval(&x.lo), rational_to_interval(&x.hi));
    interval!(lo.inf(), hi.sup()).unwrap_or(Interval::ENTIRE)
}

/// A rational interval holding the `f64` interval `x` (its endpoints are
/// dyadic and exact); `None` where `x` is unbounded or empty.
pub(super) fn exact_iv(x: Interval) -> Option<RI> {
    if x.is_empty() {
        return None;
    }
    Some(RI::new(Q::from_float(x.inf())?, Q::from_float(x.sup())?))
}

/// One polynomial of an [`ExactSystem`] as the BB type of its shape.
#[derive(Clone, Debug)]
pub(super) enum Poly {
    Triangle(TriBezier<Q>),
    Tensor(Box<TensorBezier<Q>>),
}

impl Poly {
    /// `c` in `shape`'s storage order (its length checked by the caller).
    pub(super) fn new(shape: Shape, c: Vec<Q>) -> Self {
        match shape {
            Shape::Triangle(n) => Poly::Triangle(TriBezier::new(n, c).expect("length checked")),
            Shape::Tensor(m, n) => {
                Poly::Tensor(Box::new(TensorBezier::on_unit_square(m, n, c).expect("length checked")))
            }
        }
    }

    /// `∂/∂u`, `∂/∂v`, exactly.
    pub(super) fn derivs(&self) -> [Poly; 2] {
        match self {
            Poly::Triangle(p) => [Poly::Triangle(p.deriv_u()), Poly::Triangle(p.deriv_v())],
            Poly::Tensor(p) => [Direction::U, Direction::V].map(|d| Poly::Tensor(Box::new(p.deriv(d)))),
        }
    }

    pub(super) fn shape(&self) -> Shape {
        match self {
            Poly::Triangle(p) => Shape::Triangle(p.degree()),
            Poly::Tensor(p) => {
                let (m, n) = p.degree();
                Shape::Tensor(m, n)
            }
        }
    }

    pub(super) fn coeffs(&self) -> &[Q] {
        match self {
            Poly::Triangle(p) => p.coeffs(),
            Poly::Tensor(p) => p.coeffs(),
        }
    }

    /// An enclosure over the box `x`.
    pub(super) fn enclose(&self, x: &[RI; 2]) -> RI {
        eval(self.shape(), self.coeffs(), x)
    }

    /// The value at `(u, v)` in `f64` (an estimate).
    pub(super) fn eval_f64(&self, u: f64, v: f64) -> f64 {
        let to_f64 = |x: &Q| x.to_f64().unwrap_or(f64::NAN);
        match self {
            Poly::Triangle(p) => p.map(to_f64).eval(u, v),
            Poly::Tensor(p) => p.map(to_f64).eval(u, v),
        }
    }
}

/// An enclosure of the polynomial over the box `x`, by de Casteljau in
/// rational interval arithmetic.
pub(super) fn eval(shape: Shape, c: &[Q], x: &[RI; 2]) -> RI {
    let one = RI::point(Q::one());
    let lerp = |a: &RI, b: &RI, t: &RI, s: &RI| a.mul(s).add(&b.mul(t));
    match shape {
        Shape::Tensor(m, n) => {
            let (su, sv) = (one.sub(&x[0]), one.sub(&x[1]));
            let mut col: Vec<RI> = (0..=m)
                .map(|i| {
                    let mut row: Vec<RI> = (0..=n).map(|j| RI::point(c[i * (n + 1) + j].clone())).collect();
                    for r in (1..=n).rev() {
                        for j in 0..r {
                            row[j] = lerp(&row[j], &row[j + 1], &x[1], &sv);
                        }
                    }
                    row.swap_remove(0)
                })
                .collect();
            for r in (1..=m).rev() {
                for i in 0..r {
                    col[i] = lerp(&col[i], &col[i + 1], &x[0], &su);
                }
            }
            col.swap_remove(0)
        }
        Shape::Triangle(n) => {
            let w = one.sub(&x[0]).sub(&x[1]);
            let mut net: Vec<RI> = c.iter().cloned().map(RI::point).collect();
            for m in (1..=n).rev() {
                let mut next = Vec::with_capacity(m * (m + 1) / 2);
                for j in 0..m {
                    for i in 0..m - j {
                        let a = net[tri_index(m, i + 1, j)].mul(&x[0]);
                        let b = net[tri_index(m, i, j + 1)].mul(&x[1]);
                        let cc = net[tri_index(m, i, j)].mul(&w);
                        next.push(a.add(&b).add(&cc));
                    }
                }
                net = next;
            }
            net.swap_remove(0)
        }
    }
}

/// `b^m d^n · p(a/b, c/d)` (tensor, bidegree `(m, n)`) or `(bd)^n · p(a/b,
/// c/d)` (triangle, degree `n`) for integer coefficients `c` (in `shape`'s
/// storage order) and the point `(a/b, c/d)`, `b, d > 0`: by homogeneous de
/// Casteljau in integers, so no fraction is ever reduced. It has the sign
/// of `p` there, and is zero exactly where `p` is.
pub(super) fn eval_at(shape: Shape, c: &[Q], p: &[Q; 2]) -> BigInt {
    let (a, b) = (p[0].numer(), p[0].denom());
    let (cc, d) = (p[1].numer(), p[1].denom());
    let int = |q: &Q| q.numer().clone();
    match shape {
        Shape::Tensor(m, n) => {
            let (sa, sc) = (b - a, d - cc);
            let mut col: Vec<BigInt> = (0..=m)
                .map(|i| {
                    let mut row: Vec<BigInt> = (0..=n).map(|j| int(&c[i * (n + 1) + j])).collect();
                    for r in (1..=n).rev() {
                        for j in 0..r {
                            row[j] = &row[j] * &sc + &row[j + 1] * cc;
                        }
                    }
                    row.swap_remove(0)
                })
                .collect();
            for r in (1..=m).rev() {
                for i in 0..r {
                    col[i] = &col[i] * &sa + &col[i + 1] * a;
                }
            }
            col.swap_remove(0)
        }
        Shape::Triangle(n) => {
            let (u, v) = (a * d, cc * b);
            let w = b * d - &u - &v;
            let mut net: Vec<BigInt> = c.iter().map(int).collect();
            for m in (1..=n).rev() {
                let mut next = Vec::with_capacity(m * (m + 1) / 2);
                for j in 0..m {
                    for i in 0..m - j {
                        next.push(
                            &net[tri_index(m, i + 1, j)] * &u
                                + &net[tri_index(m, i, j + 1)] * &v
                                + &net[tri_index(m, i, j)] * &w,
                        );
                    }
                }
                net = next;
            }
            net.swap_remove(0)
        }
    }
}
