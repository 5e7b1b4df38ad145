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
//! or a limit is reached (still undecided): width `2^-1200`, a step that
//! does not halve the box, or 16 steps. A root exactly on an edge never
//! separates from it, which is why the gcd comes first.
//!
//! # Exact zeros: the root as a rational point
//! Where `h = 0` exactly at the root (for a ray: the origin on the surface,
//! `t = 0`) no contraction ever decides the sign, and the rationals double
//! in size with every step. Such a root is usually a rational point (a
//! float origin on a float patch puts it at a dyadic `(u, v)`), so the
//! first three steps try the simplest rational (Stern–Brocot) and the
//! simplest dyadic in each side of the box: a candidate at which `f` and
//! `g` vanish exactly (integer evaluation) is the box's unique root, and
//! the domain and `h ≥ 0` are then decided at that point exactly.
//!
//! Used by [`super::solve`] for exact input, and by the ray front end, whose
//! reduction it repeats in rationals with exact plane normals.

mod poly;
mod power;

use poly::{eval, eval_at, exact_iv, hull, FPoly, FloatDerivs, Poly};

use super::degenerate::gcd;
use super::krawczyk::exact::{self, RationalSystem};
use super::krawczyk::Verdict;
use super::solution::Box2;
use crate::error::{Error, Result};
use crate::poly::{tri_index, tri_len};
use crate::scalar::rational_interval::RI;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

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

/// The width (as `2^-REFINE_BITS`) below which [`ExactSystem::refine`]
/// stops contracting. Each exact Krawczyk step roughly squares the width,
/// and the rationals' sizes double with it, so the last step's cost
/// dominates: from a float box (about 2⁻⁴⁷ wide) the steps reach 2⁻⁷³⁰,
/// then one more about 2⁻¹⁴⁶⁰, then stop (a few ms on a bicubic patch). So
/// a root at least about 2⁻¹⁴⁰⁰ from an edge or a range end is decided,
/// which includes every root a subnormal away from one. A width limit, not
/// a step count: the limit is what stops the hopeless cases (a root
/// exactly on an edge that the gcd test could not see, an irrational root
/// at which `h` vanishes exactly), and their cost must not depend on how
/// slowly they converge.
const REFINE_BITS: u64 = 1200;

/// At most this many steps of [`ExactSystem::refine`], and each must halve
/// the box: with quadratic contraction the width floor comes first (about
/// six steps); the cap only bounds the cost where it does not come.
const REFINE_STEPS: usize = 16;

/// Contraction steps of [`ExactSystem::refine`] in which the simplest
/// rational and dyadic points of the box are tried as the root
/// ([`ExactSystem::rational_root`]): the box is then at most about 2⁻¹⁰⁰
/// wide, which isolates any float and any rational whose denominator is
/// below 2⁵⁰ from every other candidate as simple.
const POINT_STEPS: usize = 3;

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
    /// The polynomials as given.
    input: ([Vec<Q>; 2], Option<Vec<Q>>),
    /// `f`, `g` and `h`, each scaled by a positive integer to integer
    /// coefficients (same roots, same signs), formed on first use: most
    /// solves settle nothing. On dyadic boxes every value is then dyadic,
    /// and the exact kernel never reduces a fraction by a gcd
    /// ([`rational_interval`](crate::scalar::rational_interval)).
    scaled: std::sync::OnceLock<Scaled>,
    /// `∂f_k/∂u`, `∂f_k/∂v` of the scaled system (shapes one degree lower in
    /// that variable), formed on first use.
    df: std::sync::OnceLock<[[Poly; 2]; 2]>,
    /// `∂²f_k/∂x_d∂x_e` (`[k][d][e]`) of the scaled system, formed on first
    /// use: the slopes of the Jacobian's centred form.
    d2f: std::sync::OnceLock<[[[Poly; 2]; 2]; 2]>,
    /// The first and second derivatives enclosed in `f64` intervals
    /// (coefficients rounded outward), formed on first use.
    float: std::sync::OnceLock<FloatDerivs>,
    /// `f` and `g` of the scaled system in power form, formed on first use
    /// (exact values at points; `None` if the conversion failed).
    power: std::sync::OnceLock<Option<[power::PowerForm; 2]>>,
    /// The first derivatives in power form, formed on first use.
    dpower: std::sync::OnceLock<Option<[[power::PowerForm; 2]; 2]>>,
    /// The second derivatives in `f64` intervals, formed on first use.
    float2: std::sync::OnceLock<[[[FPoly; 2]; 2]; 2]>,
}

/// [`ExactSystem`]'s polynomials with integer coefficients.
#[derive(Clone, Debug)]
struct Scaled {
    f: [Vec<Q>; 2],
    h: Option<Vec<Q>>,
}

/// `c` times the least common multiple of its denominators: integers.
fn integral(c: &[Q]) -> Vec<Q> {
    use num_integer::Integer;
    let mut l = BigInt::one();
    for q in c {
        if !(&l % q.denom()).is_zero() {
            l = l.lcm(q.denom());
        }
    }
    c.iter()
        .map(|q| Q::from_integer(q.numer() * (&l / q.denom())))
        .collect()
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
            input: ([f, g], h),
            scaled: std::sync::OnceLock::new(),
            df: std::sync::OnceLock::new(),
            d2f: std::sync::OnceLock::new(),
            float: std::sync::OnceLock::new(),
            power: std::sync::OnceLock::new(),
            dpower: std::sync::OnceLock::new(),
            float2: std::sync::OnceLock::new(),
        })
    }

    /// `f` and `g` as given, with their bidegree, if the system is on the
    /// square (for restarts of the box solver).
    pub(crate) fn tensor_input(&self) -> Option<(usize, usize, [&[Q]; 2])> {
        match self.shape {
            Shape::Tensor(m, n) => Some((m, n, [&self.input.0[0], &self.input.0[1]])),
            Shape::Triangle(_) => None,
        }
    }

    /// The system with integer coefficients.
    fn scaled(&self) -> &Scaled {
        self.scaled.get_or_init(|| Scaled {
            f: [integral(&self.input.0[0]), integral(&self.input.0[1])],
            h: self.input.1.as_deref().map(integral),
        })
    }

    /// `[[f_u, f_v], [g_u, g_v]]` as exact polynomials.
    fn df(&self) -> &[[Poly; 2]; 2] {
        self.df
            .get_or_init(|| self.scaled().f.clone().map(|p| Poly::new(self.shape, p).derivs()))
    }

    /// The second derivatives `[k][d][e]` as exact polynomials.
    fn d2f(&self) -> &[[[Poly; 2]; 2]; 2] {
        self.d2f
            .get_or_init(|| self.df().clone().map(|row| row.map(|p| p.derivs())))
    }

    /// The derivatives in `f64` intervals.
    fn float(&self) -> &FloatDerivs {
        self.float.get_or_init(|| FloatDerivs {
            d1: self.df().clone().map(|row| row.map(|p| FPoly::of(&p))),
        })
    }

    /// The Jacobian over `x` enclosed in `f64` interval arithmetic: at a
    /// point by interval de Casteljau, over a box by the hull of the
    /// coefficients on a piece holding it ([`FPoly::hull_over`]). Only
    /// `F(x̃)` must be exact for Krawczyk's operator to contract to a simple
    /// root; `F'(X)` needs to be tight relative to `|F'|`, which
    /// `f64` gives unless the Jacobian itself is lost to rounding (then
    /// [`ExactSystem::certify`] falls back to the exact enclosure).
    fn jacobian_float(&self, x: &[RI; 2]) -> Option<[[RI; 2]; 2]> {
        let fl = self.float();
        let xf = [hull(&x[0]), hull(&x[1])];
        let is_point = x.iter().all(|c| c.lo == c.hi);
        let entry = |p: &FPoly| -> Option<RI> {
            let j = if is_point {
                p.over(xf[0], xf[1])
            } else {
                p.hull_over([xf[0].inf(), xf[0].sup()], [xf[1].inf(), xf[1].sup()])
            };
            if !(j.inf().is_finite() && j.sup().is_finite()) {
                return None;
            }
            exact_iv(j)
        };
        let [[a, b], [c, d]] = &fl.d1;
        let [[a, b], [c, d]] = [[entry(a), entry(b)], [entry(c), entry(d)]];
        Some([[a?, b?], [c?, d?]])
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
                let [f, g] = [0, 1].map(|k| bernstein_to_power(&self.edge(&self.scaled().f[k], *edge)));
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
        let Some(h) = &self.scaled().h else {
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
    ///
    /// A root where a sign condition holds with equality — `h = 0` exactly
    /// (a ray starting on the surface: `t = 0`) — never separates from the
    /// condition's boundary however far the box contracts. Such a root is
    /// usually a rational point (a dyadic, when the ray's origin is a float
    /// point of the patch): in the first [`POINT_STEPS`] steps the simplest
    /// points of the box are tried as the root in exact arithmetic, which
    /// decides it at once. Otherwise the contraction stops at width
    /// `2^-REFINE_BITS`, at a step that does not halve the box, or after
    /// [`REFINE_STEPS`] steps (undecided), so the cost stays bounded.
    fn refine(&self, mut x: [RI; 2], in_domain: bool) -> Settled {
        let floor = Q::new(BigInt::one(), BigInt::one() << REFINE_BITS);
        for step in 0..REFINE_STEPS {
            if step < POINT_STEPS {
                if let Some(root) = self.rational_root(&x) {
                    return self.settle_point(&root);
                }
            }
            let before = x[0].width().max(x[1].width());
            if before < floor {
                return Settled::Undecided;
            }
            let Some(k) = exact::krawczyk(self, &x) else {
                return Settled::Undecided;
            };
            let (Some(a), Some(b)) = (k[0].meet(&x[0]), k[1].meet(&x[1])) else {
                // K(X) ∩ X = ∅ would prove no root: impossible for a
                // certified box; distrust and give up.
                return Settled::Undecided;
            };
            // A step that does not halve the box will not converge (the
            // contraction is quadratic where it works): stop.
            if a.width().max(b.width()) * Q::from_integer(2.into()) > before {
                return Settled::Undecided;
            }
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

    /// The root in `x` (the only one, as in [`ExactSystem::settle`]) when
    /// it is one of the simplest points of `x`: per coordinate the rational
    /// with the smallest denominator in the interval, or the dyadic with
    /// the fewest bits; a candidate is the root iff `f` and `g` vanish
    /// there exactly. `None` when neither candidate is a root (nothing is
    /// claimed then).
    fn rational_root(&self, x: &[RI; 2]) -> Option<[Q; 2]> {
        let candidates = |r: &RI| [simplest_rational(&r.lo, &r.hi), Some(simplest_dyadic(&r.lo, &r.hi))];
        let (cu, cv) = (candidates(&x[0]), candidates(&x[1]));
        let f = &self.scaled().f;
        let mut tried: Vec<[Q; 2]> = Vec::with_capacity(4);
        for u in cu.iter().flatten() {
            for v in cv.iter().flatten() {
                let p = [u.clone(), v.clone()];
                if tried.contains(&p) {
                    continue;
                }
                if f.iter().all(|c| eval_at(self.shape, c, &p).is_zero()) {
                    return Some(p);
                }
                tried.push(p);
            }
        }
        None
    }

    /// The verdict for a root known exactly: in the closed domain and
    /// `h ≥ 0` there (exact evaluations), or not.
    fn settle_point(&self, p: &[Q; 2]) -> Settled {
        let at = [RI::point(p[0].clone()), RI::point(p[1].clone())];
        let h_ok = self
            .scaled()
            .h
            .as_ref()
            .is_none_or(|h| !eval_at(self.shape, h, p).is_negative());
        match self.domain_contains(&at) {
            Some(true) if h_ok => Settled::Inside,
            _ => Settled::Outside,
        }
    }

    /// Krawczyk in exact arithmetic on the closed box `bx` widened by an
    /// eighth of its size on each side (a root on its edge should not defeat
    /// the test): [`Verdict::Unique`] with a box holding the only root of
    /// the widened box, a simple one, once `K(X) ⊂ int X` for a contraction
    /// `X` of it (every root of the widened box stays in each `X`, so the
    /// uniqueness extends to it); [`Verdict::NoRoot`] when `K(X) ∩ X` is
    /// empty. Used on the small undecided regions that rounding left: with
    /// exact coefficients the noise that defeated the interval Krawczyk test
    /// is gone (two roots 1e-8 apart, say).
    ///
    /// First with the Jacobian enclosed in `f64` intervals ([`Fast`]: `F` at
    /// the centre is still exact), then, if that is undecided, with every
    /// enclosure exact.
    ///
    /// The exact retry is skipped where the Jacobian at the box's centre is
    /// nearly singular ([`ExactSystem::nearly_singular`]): no Krawczyk test
    /// proves a multiple root, and near one the exact enclosures (whose
    /// rationals grow with every product) are the whole cost.
    pub fn certify(&self, bx: Box2) -> Verdict<Box2, ()> {
        match self.certify_floats(bx) {
            (Verdict::Undecided(()), true) if !self.nearly_singular(bx) => exact::certify(self, bx),
            (v, _) => v,
        }
    }

    /// Exact Krawczyk with the Jacobian in `f64` intervals ([`Fast`]), and
    /// whether rounding visibly limited that Jacobian.
    fn certify_floats(&self, bx: Box2) -> (Verdict<Box2, ()>, bool) {
        let fast = Fast {
            sys: self,
            lossy: std::cell::Cell::new(false),
        };
        let v = exact::certify(&fast, bx);
        (v, fast.lossy.get())
    }

    /// Whether one of the simplest points of `bx` ([`ExactSystem::rational_root`]'s
    /// candidates) is a root at which the Jacobian's determinant vanishes
    /// too, all exactly: a multiple root, which no Krawczyk test certifies.
    /// `false` claims nothing (an irrational multiple root is not found).
    pub(crate) fn holds_exact_multiple_root(&self, bx: Box2) -> bool {
        let iv = |[lo, hi]: [f64; 2]| Some(RI::new(Q::from_float(lo)?, Q::from_float(hi)?));
        let (Some(u), Some(v)) = (iv(bx.u), iv(bx.v)) else {
            return false;
        };
        let Some(p) = self.rational_root(&[u, v]) else {
            return false;
        };
        let d = |k: usize, e: usize| self.deriv_at(k, e, &p);
        match (d(0, 0), d(0, 1), d(1, 0), d(1, 1)) {
            (Some(a), Some(b), Some(c), Some(e)) => (a * e - b * c).is_zero(),
            _ => false,
        }
    }

    /// [`ExactSystem::certify`] without the exact retry: `F` at the centre
    /// exact, the Jacobian in `f64` intervals (exact only where those are
    /// unbounded). For callers whose own float work is clean, where a
    /// failure means several roots or a multiple one, not rounding.
    pub(crate) fn certify_fast(&self, bx: Box2) -> Verdict<Box2, ()> {
        self.certify_floats(bx).0
    }

    /// Whether the Jacobian at the centre of `bx`, estimated in `f64`, is
    /// singular within `10⁻¹¹` of its rows' norms (or not finite): a
    /// multiple root, or roots closer than the exact tests separate. An
    /// estimate: it decides where exact work is spent, never what is proven.
    pub fn nearly_singular(&self, bx: Box2) -> bool {
        let j = self.jacobian_f64(0.5 * (bx.u[0] + bx.u[1]), 0.5 * (bx.v[0] + bx.v[1]));
        let det = j[0] * j[3] - j[1] * j[2];
        let scale = (j[0] * j[0] + j[1] * j[1]).sqrt() * (j[2] * j[2] + j[3] * j[3]).sqrt();
        // (NaN counts as singular.)
        det.abs().partial_cmp(&(1e-11 * scale)) != Some(std::cmp::Ordering::Greater)
    }

    /// `p(x)` exactly at the point `x` (integer coefficients `c`).
    fn value_at(&self, k: usize, x: &[Q; 2]) -> Q {
        let power = self.power.get_or_init(|| {
            let f = &self.scaled().f;
            Some([
                power::PowerForm::new(self.shape, &f[0])?,
                power::PowerForm::new(self.shape, &f[1])?,
            ])
        });
        let num = match power {
            Some(p) => p[k].eval_at(x),
            None => eval_at(self.shape, &self.scaled().f[k], x),
        };
        Q::new(num, power_den(self.shape, x))
    }

    /// `∂f_k/∂x_d` exactly at the point `x` (power form; `None` if that
    /// failed).
    fn deriv_at(&self, k: usize, d: usize, x: &[Q; 2]) -> Option<Q> {
        let dp = self.dpower.get_or_init(|| {
            let df = self.df();
            let one = |p: &Poly| power::PowerForm::new(p.shape(), p.coeffs());
            Some([[one(&df[0][0])?, one(&df[0][1])?], [one(&df[1][0])?, one(&df[1][1])?]])
        });
        Some(power_value(&dp.as_ref()?[k][d], self.df()[k][d].shape(), x))
    }

    /// The Jacobian over the box `x` by the centred form `F'(m) +
    /// F''(X)·(X − m)` about its centre `m`: `F'(m)` exact (power form),
    /// `F''(X)` the hull of its coefficients on a piece holding `X` in `f64`
    /// intervals rounded outward ([`FPoly::hull_over`]). `O(mn)` big-integer
    /// and `O(mn(m + n))` float operations, where the exact enclosure takes
    /// `O(mn(m + n))` rational ones; its excess is `F''`'s rounding times
    /// the width, far below `|F'|` on the small boxes this is for. `None`
    /// where a bound is not finite.
    fn jacobian_centred(&self, x: &[RI; 2]) -> Option<[[RI; 2]; 2]> {
        let two = Q::from_integer(2.into());
        let m = [0, 1].map(|e| (&x[e].lo + &x[e].hi) / &two);
        let dx = [x[0].sub_point(&m[0]), x[1].sub_point(&m[1])];
        let xf = [hull(&x[0]), hull(&x[1])];
        let f2 = self
            .float2
            .get_or_init(|| self.d2f().clone().map(|r| r.map(|e| e.map(|p| FPoly::of(&p)))));
        let entry = |k: usize, d: usize| -> Option<RI> {
            let mut acc = RI::point(self.deriv_at(k, d, &m)?);
            for (e, dxe) in dx.iter().enumerate() {
                let h = f2[k][d][e].hull_over([xf[0].inf(), xf[0].sup()], [xf[1].inf(), xf[1].sup()]);
                if !(h.inf().is_finite() && h.sup().is_finite()) {
                    return None;
                }
                acc = acc.add(&exact_iv(h)?.mul(dxe));
            }
            Some(acc)
        };
        Some([[entry(0, 0)?, entry(0, 1)?], [entry(1, 0)?, entry(1, 1)?]])
    }
}

/// [`ExactSystem`] with its Jacobian enclosed in `f64` intervals
/// ([`ExactSystem::jacobian_float`]; exactly where that is unbounded).
struct Fast<'a> {
    sys: &'a ExactSystem,
    /// Set when rounding visibly limited the Jacobian: its enclosure at the
    /// centre is not tight (or not finite), so an exact retry may succeed
    /// where this one failed.
    lossy: std::cell::Cell<bool>,
}

impl RationalSystem for Fast<'_> {
    fn value(&self, x: &[RI; 2]) -> [RI; 2] {
        self.sys.value(x)
    }

    fn jacobian(&self, x: &[RI; 2]) -> [[RI; 2]; 2] {
        match self.sys.jacobian_float(x) {
            Some(j) => {
                if x.iter().all(|c| c.lo == c.hi) && !tight(&j) {
                    self.lossy.set(true);
                }
                j
            }
            None => {
                self.lossy.set(true);
                self.sys.jacobian(x)
            }
        }
    }
}

/// `p(x)` exactly from its power form (`shape` is `p`'s).
fn power_value(p: &power::PowerForm, shape: Shape, x: &[Q; 2]) -> Q {
    Q::new(p.eval_at(x), power_den(shape, x))
}

/// The denominator of the homogeneous evaluations at `x` (`eval_at`,
/// [`power::PowerForm::eval_at`]): `b^m d^n` on the square, `(bd)^n` on the
/// triangle, for `x = (a/b, c/d)`.
fn power_den(shape: Shape, x: &[Q; 2]) -> num_bigint::BigInt {
    let (b, d) = (x[0].denom(), x[1].denom());
    match shape {
        Shape::Tensor(m, n) => num_traits::pow(b.clone(), m) * num_traits::pow(d.clone(), n),
        Shape::Triangle(n) => num_traits::pow(b * d, n),
    }
}

/// Every entry's width is below a thousandth of its row's largest magnitude
/// (then rounding costs Krawczyk's contraction little, and the exact retry
/// would not do better).
fn tight(j: &[[RI; 2]; 2]) -> bool {
    j.iter().all(|row| {
        let mag = |r: &RI| r.lo.abs().max(r.hi.abs());
        let scale = mag(&row[0]).max(mag(&row[1]));
        let limit = &scale / Q::from_integer(1000.into());
        row.iter().all(|r| r.width() <= limit)
    })
}

impl RationalSystem for ExactSystem {
    /// Exact at a point (by integer de Casteljau), an enclosure otherwise.
    fn value(&self, x: &[RI; 2]) -> [RI; 2] {
        let f = &self.scaled().f;
        if x.iter().all(|c| c.lo == c.hi) {
            let p = [x[0].lo.clone(), x[1].lo.clone()];
            return [0, 1].map(|k| RI::point(self.value_at(k, &p)));
        }
        [0, 1].map(|k| eval(self.shape, &f[k], x))
    }

    /// Each entry `j = ∂f_k/∂x_d` enclosed twice, kept where both agree:
    /// by de Casteljau over `X`, and by the centred (mean-value) form
    /// `j(m) + Σ_e ∂j/∂x_e(X)·(X_e − m)` about the box's centre `m`. Near a
    /// root where the coefficients cancel heavily (`|∇f|` far below their
    /// size: roots of a product of many lines, a few hundredths apart) the
    /// direct enclosure is about `n·max|c|·w` wide, which swamps `|∇f|`
    /// unless `w` is tiny; the centred form's excess is of order `w²`.
    ///
    /// First, cheaply, the centred form with `F''` in `f64`
    /// ([`ExactSystem::jacobian_centred`]), kept if tight; at a point, the
    /// exact value by power form.
    fn jacobian(&self, x: &[RI; 2]) -> [[RI; 2]; 2] {
        let is_point = x.iter().all(|c| c.lo == c.hi);
        if is_point {
            let p = [x[0].lo.clone(), x[1].lo.clone()];
            return [0, 1].map(|k| {
                [0, 1].map(|d| match self.deriv_at(k, d, &p) {
                    Some(v) => RI::point(v),
                    None => self.df()[k][d].enclose(x),
                })
            });
        }
        if let Some(j) = self.jacobian_centred(x).filter(tight) {
            return j;
        }
        let two = Q::from_integer(2.into());
        let m = [0, 1].map(|e| (&x[e].lo + &x[e].hi) / &two);
        let pm = [RI::point(m[0].clone()), RI::point(m[1].clone())];
        let dx = [x[0].sub_point(&m[0]), x[1].sub_point(&m[1])];
        [0, 1].map(|k| {
            [0, 1].map(|d| {
                let direct = self.df()[k][d].enclose(x);
                let mut centred = self.df()[k][d].enclose(&pm);
                for (e, dxe) in dx.iter().enumerate() {
                    centred = centred.add(&self.d2f()[k][d][e].enclose(x).mul(dxe));
                }
                // Both contain every value over X, so they meet.
                direct.meet(&centred).unwrap_or(direct)
            })
        })
    }
}

/// Continued-fraction terms [`simplest_rational`] follows before it gives
/// up (the candidate is only an offer; the box's width bounds the
/// denominators worth trying anyway).
const SIMPLEST_TERMS: usize = 128;

/// The rational with the smallest denominator in `[lo, hi]` (`lo ≤ hi`;
/// among integers the one nearest 0): the Stern–Brocot descent, by the
/// continued fraction both ends share, in integer arithmetic (convergents
/// are in lowest terms). `None` after [`SIMPLEST_TERMS`] terms.
fn simplest_rational(lo: &Q, hi: &Q) -> Option<Q> {
    use num_integer::Integer;
    if lo.is_negative() && !hi.is_negative() {
        return Some(Q::zero());
    }
    if hi.is_negative() {
        return simplest_rational(&-hi, &-lo).map(|q| -q);
    }
    // 0 ≤ lo = p1/q1 ≤ hi = p2/q2; convergents h/k of the terms so far.
    let (mut p1, mut q1) = (lo.numer().clone(), lo.denom().clone());
    let (mut p2, mut q2) = (hi.numer().clone(), hi.denom().clone());
    let (mut h1, mut h2, mut k1, mut k2) = (BigInt::one(), BigInt::zero(), BigInt::zero(), BigInt::one());
    for _ in 0..SIMPLEST_TERMS {
        // The last term is the smallest integer in the interval, if any.
        let c = p1.div_ceil(&q1);
        let last = &c * &q2 <= p2;
        let a = if last { c } else { p1.div_floor(&q1) };
        let (h, k) = (&a * &h1 + &h2, &a * &k1 + &k2);
        if last {
            return Some(Q::new_raw(h, k));
        }
        (h2, h1, k2, k1) = (h1, h, k1, k);
        // lo, hi in (a, a + 1): go on with 1/(hi − a) ≤ 1/(lo − a).
        let (np1, nq1) = (q2.clone(), &p2 - &a * &q2);
        let (np2, nq2) = (q1.clone(), &p1 - &a * &q1);
        (p1, q1, p2, q2) = (np1, nq1, np2, nq2);
    }
    None
}

/// The dyadic `c/2^k` with the smallest `k ≥ 0` in `[lo, hi]` (`lo ≤ hi`):
/// a multiple of `2^-k` lies in the interval for every `k` past the first
/// that has one, so `k` is found by bisection (integer arithmetic).
fn simplest_dyadic(lo: &Q, hi: &Q) -> Q {
    use num_integer::Integer;
    let at = |k: u64| -> Option<Q> {
        let c = (lo.numer() << k).div_ceil(lo.denom());
        (&c * hi.denom() <= hi.numer() << k).then(|| Q::new(c, BigInt::one() << k))
    };
    // 2^-k ≤ hi − lo guarantees a multiple; a point interval needs the
    // exact binary expansion of lo (a dyadic or none).
    let w = hi - lo;
    let mut top = if w.is_zero() {
        // A dyadic point's denominator is 2^k; a non-dyadic point has no
        // dyadic in it: return it as is (it is its own simplest point).
        let d = lo.denom();
        if d.magnitude().count_ones() == 1 {
            d.bits() - 1
        } else {
            return lo.clone();
        }
    } else {
        (w.denom().bits() as i64 - w.numer().bits() as i64 + 1).max(0) as u64
    };
    let mut bottom = 0;
    if let Some(q) = at(0) {
        return q;
    }
    // at(bottom) is None, at(top) is Some.
    while top - bottom > 1 {
        let mid = bottom + (top - bottom) / 2;
        if at(mid).is_some() {
            top = mid;
        } else {
            bottom = mid;
        }
    }
    at(top).expect("a multiple of 2^-top lies in the interval")
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
mod tests;
