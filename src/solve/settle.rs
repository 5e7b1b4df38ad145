//! Settling, in exact arithmetic, the certified roots that rounding leaves
//! on the domain's boundary: a root whose certified box crosses an edge of
//! the domain may lie in it or within rounding outside it, which interval
//! arithmetic cannot tell. For exact (rational) systems the question has an
//! exact answer; [`ExactSystem::settle`] finds it, optionally together with
//! the sign of a third polynomial `h` at the root (the ray front end's `t`).
//!
//! # On an edge: a gcd
//! The root lies on an edge `E` crossed by the box iff both equations
//! restricted to `E` share a root in the box's range: if `gcd(F, G)`
//! (Euclid over ℚ, power basis) changes sign or vanishes on the part of
//! that range within the edge, `E` holds a root of the system inside the
//! box, and the box holds only one: the root is in the closed domain.
//!
//! # Off an edge: Krawczyk in exact arithmetic
//! Otherwise the box is contracted by `X ← K(X) ∩ X` with rational interval
//! arithmetic (`K(X) = x̃ − Y F(x̃) + (I − Y J(X))(X − x̃)`, endpoints rounded
//! outward to dyadics a little finer than the box, so sizes stay bounded),
//! which converges on the simple root, until the box is provably inside the
//! domain (and `h ≥ 0` on it, if asked), provably outside it (or `h < 0`),
//! or an iteration limit is reached (still undecided). A root exactly on an
//! edge never separates from it, which is why the gcd comes first; `h = 0`
//! exactly at the root (for a ray: the origin on the surface) is settled
//! as `h ≥ 0` only where the box's enclosure of `h` is already `≥ 0`.
//!
//! Used by [`super::solve`] for exact input, and by the ray front end, whose
//! reduction it repeats in rationals with exact plane normals.

use super::degenerate::gcd;
use super::krawczyk::exact::{self, RationalSystem};
use super::krawczyk::Verdict;
use super::solution::Box2;
use crate::error::{Error, Result};
use crate::poly::{tri_index, tri_len, Direction, TensorBezier, TriBezier};
use crate::scalar::rational_interval::RI;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

type Q = BigRational;

/// What exact arithmetic says about a certified root.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Settled {
    /// The root lies in the closed domain (and `h ≥ 0` there, if given).
    Inside,
    /// The root lies outside the domain (or `h < 0` there).
    Outside,
    /// Still undecided (on an edge with an even-multiplicity gcd root, `h`
    /// exactly 0 at the root, or the iteration limit).
    Undecided,
}

/// Contraction steps of [`ExactSystem::refine`]: each roughly squares the
/// box width, so a few decide any root a float's distance from an edge; the
/// limit only stops the hopeless cases (a root exactly on an edge that the
/// gcd test could not see).
const REFINE_STEPS: usize = 12;

/// An edge of the domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edge {
    /// `u = 0`.
    U0,
    /// `u = 1` (square).
    U1,
    /// `v = 0`.
    V0,
    /// `v = 1` (square).
    V1,
    /// `u + v = 1` (triangle).
    Hypotenuse,
}

/// The domain and basis of an [`ExactSystem`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// Degree `n` on the unit triangle (storage order of [`tri_index`]).
    Triangle(usize),
    /// Bidegree `(m, n)` on the unit square (row-major).
    Tensor(usize, usize),
}

impl Shape {
    fn len(self) -> usize {
        match self {
            Shape::Triangle(n) => tri_len(n),
            Shape::Tensor(m, n) => (m + 1) * (n + 1),
        }
    }
}

/// A system `f = g = 0` with exact rational BB coefficients on the unit
/// triangle or square, and optionally a third polynomial `h` whose sign at
/// the root is wanted.
#[derive(Clone, Debug)]
pub struct ExactSystem {
    shape: Shape,
    f: [Vec<Q>; 2],
    h: Option<Vec<Q>>,
    /// `∂f_k/∂u`, `∂f_k/∂v` (shapes one degree lower in that variable),
    /// formed on first use: most solves settle nothing.
    df: std::sync::OnceLock<[[Poly; 2]; 2]>,
}

/// One polynomial of an [`ExactSystem`] as the BB type of its shape.
#[derive(Clone, Debug)]
enum Poly {
    Triangle(TriBezier<Q>),
    Tensor(Box<TensorBezier<Q>>),
}

impl Poly {
    /// `c` in `shape`'s storage order (its length checked by the caller).
    fn new(shape: Shape, c: Vec<Q>) -> Self {
        match shape {
            Shape::Triangle(n) => Poly::Triangle(TriBezier::new(n, c).expect("length checked")),
            Shape::Tensor(m, n) => {
                Poly::Tensor(Box::new(TensorBezier::on_unit_square(m, n, c).expect("length checked")))
            }
        }
    }

    /// `∂/∂u`, `∂/∂v`, exactly.
    fn derivs(&self) -> [Poly; 2] {
        match self {
            Poly::Triangle(p) => [Poly::Triangle(p.deriv_u()), Poly::Triangle(p.deriv_v())],
            Poly::Tensor(p) => [Direction::U, Direction::V].map(|d| Poly::Tensor(Box::new(p.deriv(d)))),
        }
    }

    fn shape(&self) -> Shape {
        match self {
            Poly::Triangle(p) => Shape::Triangle(p.degree()),
            Poly::Tensor(p) => {
                let (m, n) = p.degree();
                Shape::Tensor(m, n)
            }
        }
    }

    fn coeffs(&self) -> &[Q] {
        match self {
            Poly::Triangle(p) => p.coeffs(),
            Poly::Tensor(p) => p.coeffs(),
        }
    }

    /// An enclosure over the box `x`.
    fn enclose(&self, x: &[RI; 2]) -> RI {
        eval(self.shape(), self.coeffs(), x)
    }

    /// The value at `(u, v)` in `f64` (an estimate).
    fn eval_f64(&self, u: f64, v: f64) -> f64 {
        let to_f64 = |x: &Q| x.to_f64().unwrap_or(f64::NAN);
        match self {
            Poly::Triangle(p) => p.map(to_f64).eval(u, v),
            Poly::Tensor(p) => p.map(to_f64).eval(u, v),
        }
    }
}

impl ExactSystem {
    /// The system `f = g = 0` (coefficients in `shape`'s storage order) and
    /// the optional `h`, all of the same shape. Errors on a length mismatch.
    pub fn new(shape: Shape, f: Vec<Q>, g: Vec<Q>, h: Option<Vec<Q>>) -> Result<Self> {
        let len = shape.len();
        if f.len() != len || g.len() != len || h.as_ref().is_some_and(|h| h.len() != len) {
            return Err(Error::Shape(format!(
                "{shape:?} needs {len} coefficients per polynomial"
            )));
        }
        Ok(Self {
            shape,
            f: [f, g],
            h,
            df: std::sync::OnceLock::new(),
        })
    }

    /// `[[f_u, f_v], [g_u, g_v]]` as exact polynomials.
    fn df(&self) -> &[[Poly; 2]; 2] {
        self.df
            .get_or_init(|| self.f.clone().map(|p| Poly::new(self.shape, p).derivs()))
    }

    /// The Jacobian `[f_u, f_v, g_u, g_v]` at `(u, v)`, in `f64` (an
    /// estimate, for deciding whether an exact test is worth its cost).
    pub fn jacobian_f64(&self, u: f64, v: f64) -> [f64; 4] {
        let d = |k: usize, dir: usize| self.df()[k][dir].eval_f64(u, v);
        [d(0, 0), d(0, 1), d(1, 0), d(1, 1)]
    }

    /// The domain: the unit triangle or the unit square.
    pub fn domain(&self) -> super::Domain {
        match self.shape {
            Shape::Triangle(_) => super::Domain::Triangle,
            Shape::Tensor(..) => super::Domain::Square,
        }
    }

    /// Settles the root certified in `bx` (exactly one simple root of the
    /// system in the closed box): is it in the closed domain, and is `h ≥ 0`
    /// there? See the module docs.
    pub fn settle(&self, bx: Box2) -> Settled {
        let q = |x: f64| Q::from_float(x);
        let (Some(u0), Some(u1), Some(v0), Some(v1)) = (q(bx.u[0]), q(bx.u[1]), q(bx.v[0]), q(bx.v[1])) else {
            return Settled::Undecided;
        };
        let x = [RI::new(u0, u1), RI::new(v0, v1)];
        let inside = self.domain_contains(&x);
        if inside == Some(false) {
            return Settled::Outside;
        }
        if inside == Some(true) || self.on_crossed_edge(&x) {
            // In the closed domain; then only h can be in doubt.
            return match self.h_sign(&x) {
                Some(true) => Settled::Inside,
                Some(false) => Settled::Outside,
                None => self.refine(x, true),
            };
        }
        self.refine(x, false)
    }

    /// `Some(true)`: the box lies in the closed domain; `Some(false)`: it
    /// lies outside it; `None`: neither is proven.
    fn domain_contains(&self, x: &[RI; 2]) -> Option<bool> {
        let (zero, one) = (Q::zero(), Q::one());
        let lower_in = x[0].lo >= zero && x[1].lo >= zero;
        let lower_out = x[0].hi < zero || x[1].hi < zero;
        match self.shape {
            Shape::Tensor(..) => {
                if lower_out || x[0].lo > one || x[1].lo > one {
                    Some(false)
                } else if lower_in && x[0].hi <= one && x[1].hi <= one {
                    Some(true)
                } else {
                    None
                }
            }
            Shape::Triangle(_) => {
                if lower_out || &x[0].lo + &x[1].lo > one {
                    Some(false)
                } else if lower_in && &x[0].hi + &x[1].hi <= one {
                    Some(true)
                } else {
                    None
                }
            }
        }
    }

    /// The edges of the domain on which the root certified in `bx` is
    /// proven to lie (exactly; among the edges the box crosses).
    pub fn root_edges(&self, bx: Box2) -> Vec<Edge> {
        let q = |x: f64| Q::from_float(x);
        let (Some(u0), Some(u1), Some(v0), Some(v1)) = (q(bx.u[0]), q(bx.u[1]), q(bx.v[0]), q(bx.v[1])) else {
            return Vec::new();
        };
        self.edges_with_root(&[RI::new(u0, u1), RI::new(v0, v1)])
    }

    /// The root in `x` (unique) lies on an edge the box crosses (the gcd
    /// test of the module docs).
    fn on_crossed_edge(&self, x: &[RI; 2]) -> bool {
        !self.edges_with_root(x).is_empty()
    }

    fn edges_with_root(&self, x: &[RI; 2]) -> Vec<Edge> {
        let (zero, one) = (Q::zero(), Q::one());
        let clip = |lo: &Q, hi: &Q| (lo.clone().max(zero.clone()), hi.clone().min(one.clone()));
        let [u, v] = x;
        let mut edges: Vec<(Edge, (Q, Q))> = Vec::new();
        if u.lo < zero {
            edges.push((Edge::U0, clip(&v.lo, &v.hi)));
        }
        if v.lo < zero {
            edges.push((Edge::V0, clip(&u.lo, &u.hi)));
        }
        match self.shape {
            Shape::Tensor(..) => {
                if u.hi > one {
                    edges.push((Edge::U1, clip(&v.lo, &v.hi)));
                }
                if v.hi > one {
                    edges.push((Edge::V1, clip(&u.lo, &u.hi)));
                }
            }
            Shape::Triangle(_) => {
                if &u.hi + &v.hi > one {
                    // Along u + v = 1, parametrized by u: u ∈ U and 1 − u ∈ V.
                    let lo = u.lo.clone().max(&one - &v.hi);
                    let hi = u.hi.clone().min(&one - &v.lo);
                    edges.push((Edge::Hypotenuse, clip(&lo, &hi)));
                }
            }
        }
        edges
            .into_iter()
            .filter(|(edge, (lo, hi))| {
                if lo > hi {
                    return false;
                }
                let [f, g] = [0, 1].map(|k| bernstein_to_power(&self.edge(&self.f[k], *edge)));
                let h = gcd(f, g);
                if h.len() < 2 {
                    return false;
                }
                let (a, b) = (horner(&h, lo), horner(&h, hi));
                !(a.is_positive() && b.is_positive() || a.is_negative() && b.is_negative())
            })
            .map(|(edge, _)| edge)
            .collect()
    }

    /// The Bernstein coefficients of `c` restricted to `edge`, in its
    /// parameter (`v` on `u = 0, 1`; `u` on the others).
    fn edge(&self, c: &[Q], edge: Edge) -> Vec<Q> {
        match (self.shape, edge) {
            (Shape::Tensor(_, n), Edge::U0) => (0..=n).map(|j| c[j].clone()).collect(),
            (Shape::Tensor(m, n), Edge::U1) => (0..=n).map(|j| c[m * (n + 1) + j].clone()).collect(),
            (Shape::Tensor(m, n), Edge::V0) => (0..=m).map(|i| c[i * (n + 1)].clone()).collect(),
            (Shape::Tensor(m, n), Edge::V1) => (0..=m).map(|i| c[i * (n + 1) + n].clone()).collect(),
            (Shape::Triangle(n), Edge::U0) => (0..=n).map(|j| c[tri_index(n, 0, j)].clone()).collect(),
            (Shape::Triangle(n), Edge::V0) => (0..=n).map(|i| c[tri_index(n, i, 0)].clone()).collect(),
            // B_{i, n−i, 0}(u, 1 − u) = C(n, i) u^i (1 − u)^(n−i).
            (Shape::Triangle(n), Edge::Hypotenuse) => (0..=n).map(|i| c[tri_index(n, i, n - i)].clone()).collect(),
            _ => Vec::new(),
        }
    }

    /// `Some(true)`: `h ≥ 0` on the box (or no `h`); `Some(false)`: `h < 0`.
    fn h_sign(&self, x: &[RI; 2]) -> Option<bool> {
        let Some(h) = &self.h else {
            return Some(true);
        };
        let h = eval(self.shape, h, x);
        if !h.lo.is_negative() {
            Some(true)
        } else if h.hi.is_negative() {
            Some(false)
        } else {
            None
        }
    }

    /// Contracts `x` on its root by exact Krawczyk steps until the root is
    /// settled (module docs). `in_domain`: the root is already known to be
    /// in the closed domain.
    fn refine(&self, mut x: [RI; 2], in_domain: bool) -> Settled {
        for _ in 0..REFINE_STEPS {
            let Some(k) = exact::krawczyk(self, &x) else {
                return Settled::Undecided;
            };
            let (Some(a), Some(b)) = (k[0].meet(&x[0]), k[1].meet(&x[1])) else {
                // K(X) ∩ X = ∅ would prove no root: impossible for a
                // certified box; distrust and give up.
                return Settled::Undecided;
            };
            x = [a, b];
            let inside = if in_domain {
                Some(true)
            } else {
                self.domain_contains(&x)
            };
            match (inside, self.h_sign(&x)) {
                (Some(false), _) | (_, Some(false)) => return Settled::Outside,
                (Some(true), Some(true)) => return Settled::Inside,
                _ => {}
            }
        }
        Settled::Undecided
    }

    /// Krawczyk in exact arithmetic on the closed box `bx` widened by a
    /// tenth of its size on each side (a root on its edge should not defeat
    /// the test): [`Verdict::Unique`] with a box holding the only root of
    /// the widened box, a simple one, once `K(X) ⊂ int X` for a contraction
    /// `X` of it (every root of the widened box stays in each `X`, so the
    /// uniqueness extends to it); [`Verdict::NoRoot`] when `K(X) ∩ X` is
    /// empty. Used on the small undecided regions that rounding left: with
    /// exact coefficients the noise that defeated the interval Krawczyk test
    /// is gone (two roots 1e-8 apart, say).
    pub fn certify(&self, bx: Box2) -> Verdict<Box2, ()> {
        exact::certify(self, bx)
    }
}

impl RationalSystem for ExactSystem {
    fn value(&self, x: &[RI; 2]) -> [RI; 2] {
        [0, 1].map(|k| eval(self.shape, &self.f[k], x))
    }

    fn jacobian(&self, x: &[RI; 2]) -> [[RI; 2]; 2] {
        [0, 1].map(|k| [0, 1].map(|d| self.df()[k][d].enclose(x)))
    }
}

/// An enclosure of the polynomial over the box `x`, by de Casteljau in
/// rational interval arithmetic.
fn eval(shape: Shape, c: &[Q], x: &[RI; 2]) -> RI {
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

/// `Σ b_i C(m, i) s^i (1 − s)^(m−i)` in the power basis (ascending).
pub(crate) fn bernstein_to_power(b: &[Q]) -> Vec<Q> {
    let m = b.len().saturating_sub(1);
    let binom = |n: usize, k: usize| -> BigInt { (0..k).fold(BigInt::one(), |acc, i| acc * (n - i) / (i + 1)) };
    let mut out = vec![Q::zero(); m + 1];
    for (i, bi) in b.iter().enumerate() {
        let ci = Q::from_integer(binom(m, i));
        for k in 0..=m - i {
            let mut term = bi * &ci * Q::from_integer(binom(m - i, k));
            if k % 2 == 1 {
                term = -term;
            }
            out[i + k] += term;
        }
    }
    out
}

fn horner(p: &[Q], x: &Q) -> Q {
    p.iter().rev().fold(Q::zero(), |acc, c| acc * x + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f = v + 2^-1074`, `g = u − ½` on the unit square (bilinear): the
    /// root lies 2^-1074 below the edge `v = 0`; `v − 2^-1074` puts it above,
    /// `v` on it.
    #[test]
    fn settles_roots_a_subnormal_away_from_an_edge() {
        let tiny = Q::from_float(f64::from_bits(1)).unwrap();
        let bilinear = |c: [Q; 4]| c.to_vec();
        let half = Q::new(1.into(), 2.into());
        let g = bilinear([-half.clone(), -half.clone(), half.clone(), half.clone()]);
        let bx = Box2 {
            u: [0.5 - 1e-15, 0.5 + 1e-15],
            v: [-1e-28, 1e-28],
        };
        for (shift, want) in [
            (tiny.clone(), Settled::Outside),
            (-tiny.clone(), Settled::Inside),
            (Q::zero(), Settled::Inside),
        ] {
            // v + shift at the corners (0,0), (0,1), (1,0), (1,1).
            let f = bilinear([shift.clone(), &shift + Q::one(), shift.clone(), &shift + Q::one()]);
            let sys = ExactSystem::new(Shape::Tensor(1, 1), f, g.clone(), None).unwrap();
            assert_eq!(sys.settle(bx), want, "shift {shift}");
        }
    }

    #[test]
    fn bernstein_to_power_matches_the_definition() {
        // 1·B0 + 3·B1 + 2·B2 = (1−s)² + 6 s (1−s) + 2 s² = 1 + 4 s − 3 s².
        let b: Vec<Q> = [1, 3, 2].iter().map(|&x| Q::from_integer(x.into())).collect();
        let p = bernstein_to_power(&b);
        let want: Vec<Q> = [1, 4, -3].iter().map(|&x| Q::from_integer(x.into())).collect();
        assert_eq!(p, want);
    }
}
