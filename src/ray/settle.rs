//! Settling, in exact arithmetic, the certified roots that rounding leaves
//! undecided: within rounding of a patch edge, or at `t` within rounding
//! of 0.
//!
//! A certified root (exactly one simple root of the patch polynomial in its
//! `(u, v)` box) whose box crosses an edge of the parameter domain may lie
//! on the patch (a hit) or on the polynomial's continuation just past the
//! edge (a miss); one whose `t` box holds 0 may be just behind the origin.
//! For a patch whose control points and weights are the given floats (not a
//! B-spline piece, whose net carries knot-insertion error) both questions
//! have exact answers.
//!
//! # The exact system
//! The ray's planes are taken with exactly representable normals
//! `n_a = e_a × d`, `n_b = e_b × d` (`a`, `b` the two axes other than `d`'s
//! largest component `c`, so `n_a × n_b = d_c d ≠ 0`: the planes meet in the
//! ray's line, and the system has the same roots as the solver's). Then
//! `f_k = Σ w_ij n_k·(P_ij − o) B_ij` and the numerator of `t`,
//! `h = Σ w_ij d·(P_ij − o) B_ij` (`t = h / (W |d|²)`, `W > 0`), have exact
//! rational coefficients.
//!
//! # On an edge: a gcd
//! The root lies on an edge `E` crossed by the box iff both equations
//! restricted to `E` share a root in the box's range: if `gcd(F, G)`
//! (Euclid over ℚ, power basis) changes sign or vanishes on the part of
//! that range within the edge, `E` holds a root of the system inside the
//! box, and the box holds only one: the root is on the closed patch.
//!
//! # Off an edge: Krawczyk in exact arithmetic
//! Otherwise the box is contracted by `X ← K(X) ∩ X` with rational interval
//! arithmetic (`K(X) = x̃ − Y F(x̃) + (I − Y J(X))(X − x̃)`, endpoints rounded
//! outward to dyadics a little finer than the box, so sizes stay bounded),
//! which converges quadratically on the simple root, until the box is
//! provably inside the domain (a hit, if `t ≥ 0` is also proven on it),
//! provably outside it or at `t < 0` (a miss: the hit is dropped), or an
//! iteration limit is reached (still undecided). A root exactly on an edge
//! never separates from it, which is why the gcd comes first; an origin
//! exactly on the surface leaves `t = 0` undecided.

use super::{Patch, Ray};
use crate::poly::tri_index;
use crate::solve::degenerate::gcd;
use crate::solve::Box2;
use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

type Q = BigRational;

/// What exact arithmetic says about a certified root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Settled {
    /// A hit: on the closed patch, with `t ≥ 0`.
    Hit,
    /// Not a hit: off the patch, or behind the origin.
    Miss,
    /// Still undecided (on an edge with an even-multiplicity gcd root, an
    /// origin exactly on the surface, or the iteration limit).
    Undecided,
}

/// Settles the root certified in `bx` (module docs); [`Settled::Undecided`]
/// for patches that are not exactly their floats.
pub(super) fn settle(patch: &Patch, ray: &Ray, bx: Box2) -> Settled {
    let Some(sys) = ExactSystem::of(patch, ray) else {
        return Settled::Undecided;
    };
    let q = |x: f64| BigRational::from_float(x);
    let (Some(u0), Some(u1), Some(v0), Some(v1)) = (q(bx.u[0]), q(bx.u[1]), q(bx.v[0]), q(bx.v[1])) else {
        return Settled::Undecided;
    };
    let x = [RI::new(u0, u1), RI::new(v0, v1)];
    if sys.domain_contains(&x) != Some(true) && sys.on_crossed_edge(&x) {
        // On the closed patch; then only t can be in doubt.
        return match sys.t_sign(&x) {
            Some(true) => Settled::Hit,
            _ => sys.refine(x, true),
        };
    }
    sys.refine(x, false)
}

/// Contraction steps of [`ExactSystem::refine`]: each roughly squares the
/// box width (or, on a nearly linear system, multiplies it by ~1e-16), so
/// 24 take 1e-16 below the smallest float either way.
const REFINE_STEPS: usize = 24;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Edge {
    U0,
    U1,
    V0,
    V1,
    /// `u + v = 1` of a triangle.
    Hypotenuse,
}

#[derive(Clone, Copy, Debug)]
enum Shape {
    Triangle(usize),
    Tensor(usize, usize),
}

/// The two plane equations and the numerator of `t`, exactly, in the
/// patch's storage order.
struct ExactSystem {
    shape: Shape,
    f: [Vec<Q>; 2],
    /// `Σ w d·(P − o) B`: the sign of `t`.
    h: Vec<Q>,
    /// `∂f_k/∂u`, `∂f_k/∂v` (shapes one degree lower in that variable).
    df: [[Vec<Q>; 2]; 2],
}

impl ExactSystem {
    fn of(patch: &Patch, ray: &Ray) -> Option<Self> {
        let (shape, points, weights) = match patch {
            Patch::Triangle(p) => (Shape::Triangle(p.degree()), p.points(), p.weights()),
            Patch::Tensor(p) if p.net_is_exact() => {
                let (m, n) = p.degree();
                (Shape::Tensor(m, n), p.points(), p.weights())
            }
            _ => return None,
        };
        let q = |x: f64| Q::from_float(x);
        let vec = |p: DVec3| -> Option<[Q; 3]> { Some([q(p.x)?, q(p.y)?, q(p.z)?]) };
        let (o, d) = (vec(ray.origin())?, vec(ray.dir())?);
        let a = ray.dir().abs();
        let c = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        // e_k × d, for the two axes k ≠ c.
        let normal = |k: usize| {
            let mut e = [Q::zero(), Q::zero(), Q::zero()];
            e[k] = Q::one();
            [
                &e[1] * &d[2] - &e[2] * &d[1],
                &e[2] * &d[0] - &e[0] * &d[2],
                &e[0] * &d[1] - &e[1] * &d[0],
            ]
        };
        let normals = [normal((c + 1) % 3), normal((c + 2) % 3), d.clone()];
        let mut rows: [Vec<Q>; 3] = [Vec::new(), Vec::new(), Vec::new()];
        for (idx, &p) in points.iter().enumerate() {
            let p = vec(p)?;
            let w = match weights {
                Some(w) => q(w[idx])?,
                None => Q::one(),
            };
            for (k, n) in normals.iter().enumerate() {
                let dot = (0..3).fold(Q::zero(), |acc, c| acc + &n[c] * (&p[c] - &o[c]));
                rows[k].push(&w * dot);
            }
        }
        let [f0, f1, h] = rows;
        let df = [derivs(shape, &f0), derivs(shape, &f1)];
        Some(Self {
            shape,
            f: [f0, f1],
            h,
            df,
        })
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

    /// The root in `x` (unique) lies on an edge the box crosses (the gcd
    /// test of the module docs).
    fn on_crossed_edge(&self, x: &[RI; 2]) -> bool {
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
        edges.into_iter().any(|(edge, (lo, hi))| {
            if lo > hi {
                return false;
            }
            let [f, g] = [0, 1].map(|k| bernstein_to_power(&self.edge(&self.f[k], edge)));
            let h = gcd(f, g);
            if h.len() < 2 {
                return false;
            }
            let (a, b) = (horner(&h, &lo), horner(&h, &hi));
            !(a.is_positive() && b.is_positive() || a.is_negative() && b.is_negative())
        })
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

    /// `Some(true)`: `t ≥ 0` on the box; `Some(false)`: `t < 0` on it.
    fn t_sign(&self, x: &[RI; 2]) -> Option<bool> {
        let h = eval(self.shape, &self.h, x);
        if !h.lo.is_negative() {
            Some(true)
        } else if h.hi.is_negative() {
            Some(false)
        } else {
            None
        }
    }

    /// Contracts `x` on its root by exact Krawczyk steps until the root is
    /// settled (module docs). `on_patch`: the root is already known to be
    /// on the closed patch.
    fn refine(&self, mut x: [RI; 2], on_patch: bool) -> Settled {
        for _ in 0..REFINE_STEPS {
            let Some(k) = self.krawczyk(&x) else {
                return Settled::Undecided;
            };
            let (Some(a), Some(b)) = (k[0].meet(&x[0]), k[1].meet(&x[1])) else {
                // K(X) ∩ X = ∅ would prove no root: impossible for a
                // certified box; distrust and give up.
                return Settled::Undecided;
            };
            x = [a, b];
            let inside = if on_patch { Some(true) } else { self.domain_contains(&x) };
            match (inside, self.t_sign(&x)) {
                (Some(false), _) | (_, Some(false)) => return Settled::Miss,
                (Some(true), Some(true)) => return Settled::Hit,
                _ => {}
            }
        }
        Settled::Undecided
    }

    /// `K(X) = x̃ − Y F(x̃) + (I − Y J(X))(X − x̃)`, endpoints rounded outward.
    fn krawczyk(&self, x: &[RI; 2]) -> Option<[RI; 2]> {
        let width = x[0].width().max(x[1].width());
        let bits = precision_bits(&width)?;
        let mid = [x[0].mid_rounded(bits), x[1].mid_rounded(bits)];
        let pt = [RI::point(mid[0].clone()), RI::point(mid[1].clone())];
        let fm = [0, 1].map(|k| eval(self.shape, &self.f[k], &pt).lo);
        let jm: [[Q; 2]; 2] = [0, 1].map(|k| [0, 1].map(|d| eval_deriv(self.shape, &self.df[k][d], d, &pt).lo));
        let y = inverse_f64(&jm)?;
        let jx: [[RI; 2]; 2] = [0, 1].map(|k| [0, 1].map(|d| eval_deriv(self.shape, &self.df[k][d], d, x)));
        let dx = [x[0].sub_point(&mid[0]), x[1].sub_point(&mid[1])];
        let mut out: [RI; 2] = [RI::point(Q::zero()), RI::point(Q::zero())];
        for (i, o) in out.iter_mut().enumerate() {
            let yf = &y[i][0] * &fm[0] + &y[i][1] * &fm[1];
            let mut acc = RI::point(&mid[i] - yf);
            for (j, dxj) in dx.iter().enumerate() {
                // (I − Y J)_ij = δ_ij − Σ_l Y_il J_lj
                let yj = jx[0][j].scale(&y[i][0]).add(&jx[1][j].scale(&y[i][1]));
                let delta = if i == j { Q::one() } else { Q::zero() };
                let m = RI::point(delta).sub(&yj);
                acc = acc.add(&m.mul(dxj));
            }
            *o = acc.round_out(bits);
        }
        Some(out)
    }
}

/// Bits after the binary point that keep rounding far below `width`.
fn precision_bits(width: &Q) -> Option<u64> {
    if !width.is_positive() {
        return Some(64);
    }
    // log2(width) ≈ bits(numer) − bits(denom).
    let e = width.numer().bits() as i64 - width.denom().bits() as i64;
    let bits = (40 - e).max(64);
    (bits < 1 << 20).then_some(bits as u64)
}

/// `Y ≈ J⁻¹` in `f64`, converted exactly (any `Y` keeps Krawczyk rigorous).
fn inverse_f64(j: &[[Q; 2]; 2]) -> Option<[[Q; 2]; 2]> {
    let a = j
        .each_ref()
        .map(|r| r.each_ref().map(|x| x.to_f64().unwrap_or(f64::NAN)));
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let inv = [[a[1][1] / det, -a[0][1] / det], [-a[1][0] / det, a[0][0] / det]];
    let q = |x: f64| Q::from_float(x);
    Some([[q(inv[0][0])?, q(inv[0][1])?], [q(inv[1][0])?, q(inv[1][1])?]])
}

/// A closed interval with exact rational endpoints.
#[derive(Clone, Debug, PartialEq)]
struct RI {
    lo: Q,
    hi: Q,
}

impl RI {
    fn new(lo: Q, hi: Q) -> Self {
        Self { lo, hi }
    }
    fn point(x: Q) -> Self {
        Self { lo: x.clone(), hi: x }
    }
    fn add(&self, b: &Self) -> Self {
        Self::new(&self.lo + &b.lo, &self.hi + &b.hi)
    }
    fn sub(&self, b: &Self) -> Self {
        Self::new(&self.lo - &b.hi, &self.hi - &b.lo)
    }
    fn sub_point(&self, b: &Q) -> Self {
        Self::new(&self.lo - b, &self.hi - b)
    }
    fn scale(&self, s: &Q) -> Self {
        let (a, b) = (&self.lo * s, &self.hi * s);
        if s.is_negative() {
            Self::new(b, a)
        } else {
            Self::new(a, b)
        }
    }
    fn mul(&self, b: &Self) -> Self {
        let p = [&self.lo * &b.lo, &self.lo * &b.hi, &self.hi * &b.lo, &self.hi * &b.hi];
        let lo = p.iter().min().expect("four").clone();
        let hi = p.iter().max().expect("four").clone();
        Self::new(lo, hi)
    }
    fn width(&self) -> Q {
        &self.hi - &self.lo
    }
    fn meet(&self, b: &Self) -> Option<Self> {
        let lo = (&self.lo).max(&b.lo).clone();
        let hi = (&self.hi).min(&b.hi).clone();
        (lo <= hi).then(|| Self::new(lo, hi))
    }
    /// The midpoint rounded to a multiple of `2^-bits`.
    fn mid_rounded(&self, bits: u64) -> Q {
        let m = (&self.lo + &self.hi) / Q::from_integer(2.into());
        let s = Q::from_integer(BigInt::one() << bits);
        (m * &s).round() / s
    }
    /// Endpoints moved outward to multiples of `2^-bits`.
    fn round_out(&self, bits: u64) -> Self {
        let s = Q::from_integer(BigInt::one() << bits);
        Self::new((&self.lo * &s).floor() / &s, (&self.hi * &s).ceil() / &s)
    }
}

/// `∂c/∂u` (`d = 0`) or `∂c/∂v` (`d = 1`) coefficients, exactly.
fn derivs(shape: Shape, c: &[Q]) -> [Vec<Q>; 2] {
    match shape {
        Shape::Tensor(m, n) => {
            let at = |i: usize, j: usize| &c[i * (n + 1) + j];
            let (qm, qn) = (Q::from_integer(m.into()), Q::from_integer(n.into()));
            let du = (0..m)
                .flat_map(|i| (0..=n).map(move |j| (i, j)))
                .map(|(i, j)| &qm * (at(i + 1, j) - at(i, j)))
                .collect();
            let dv = (0..=m)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .map(|(i, j)| &qn * (at(i, j + 1) - at(i, j)))
                .collect();
            [du, dv]
        }
        Shape::Triangle(n) => {
            let qn = Q::from_integer(n.into());
            let at = |i: usize, j: usize| &c[tri_index(n, i, j)];
            let mut du = Vec::new();
            let mut dv = Vec::new();
            for j in 0..n {
                for i in 0..n - j {
                    du.push(&qn * (at(i + 1, j) - at(i, j)));
                    dv.push(&qn * (at(i, j + 1) - at(i, j)));
                }
            }
            [du, dv]
        }
    }
}

/// A derivative's enclosure over `x` (its shape is one degree lower in `d`).
fn eval_deriv(shape: Shape, c: &[Q], d: usize, x: &[RI; 2]) -> RI {
    let lower = match shape {
        Shape::Tensor(m, n) if d == 0 => Shape::Tensor(m.saturating_sub(1), n),
        Shape::Tensor(m, n) => Shape::Tensor(m, n.saturating_sub(1)),
        Shape::Triangle(n) => Shape::Triangle(n.saturating_sub(1)),
    };
    if c.is_empty() {
        return RI::point(Q::zero());
    }
    eval(lower, c, x)
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
fn bernstein_to_power(b: &[BigRational]) -> Vec<BigRational> {
    let m = b.len().saturating_sub(1);
    let binom = |n: usize, k: usize| -> BigInt { (0..k).fold(BigInt::one(), |acc, i| acc * (n - i) / (i + 1)) };
    let mut out = vec![BigRational::zero(); m + 1];
    for (i, bi) in b.iter().enumerate() {
        let ci = BigRational::from_integer(binom(m, i));
        for k in 0..=m - i {
            let mut term = bi * &ci * BigRational::from_integer(binom(m - i, k));
            if k % 2 == 1 {
                term = -term;
            }
            out[i + k] += term;
        }
    }
    out
}

fn horner(p: &[BigRational], x: &BigRational) -> BigRational {
    p.iter().rev().fold(BigRational::zero(), |acc, c| acc * x + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bernstein_to_power_matches_the_definition() {
        // 1·B0 + 3·B1 + 2·B2 = (1−s)² + 6 s (1−s) + 2 s² = 1 + 4 s − 3 s².
        let b: Vec<BigRational> = [1, 3, 2].iter().map(|&x| BigRational::from_integer(x.into())).collect();
        let p = bernstein_to_power(&b);
        let want: Vec<BigRational> = [1, 4, -3]
            .iter()
            .map(|&x| BigRational::from_integer(x.into()))
            .collect();
        assert_eq!(p, want);
    }
}
