//! The ray reduction in exact arithmetic, for [`crate::solve::settle`]: a
//! certified root within rounding of the patch's edge, or at `t` within
//! rounding of 0, is settled exactly.
//!
//! For a patch whose control points and weights are the given floats (not a
//! B-spline piece, whose net carries knot-insertion error), the ray's planes
//! are taken with exactly representable normals `n_a = e_a × d`,
//! `n_b = e_b × d` (`a`, `b` the two axes other than `d`'s largest component
//! `c`, so `n_a × n_b = d_c d ≠ 0`: the planes meet in the ray's line, and the
//! system has the same roots as the one solved in floating point). Then
//! `f_k = Σ w_ij n_k·(P_ij − o) B_ij` and the numerator of `t`,
//! `h = Σ w_ij d·(P_ij − o) B_ij` (`t = h / (W |d|²)`, `W > 0`), have exact
//! rational coefficients.

use super::{Patch, Ray};
use crate::solve::settle::{ExactSystem, Settled, Shape};
use crate::solve::Box2;
use glam::DVec3;
use num_rational::BigRational;
use num_traits::{One, Zero};

type Q = BigRational;

/// Settles the root certified in `bx`: [`Settled::Inside`] is a hit (on the
/// closed patch, `t ≥ 0`), [`Settled::Outside`] a miss; undecided for
/// patches that are not exactly their floats.
pub(super) fn settle(patch: &Patch, ray: &Ray, bx: Box2) -> Settled {
    match exact_system(patch, ray) {
        Some(sys) => sys.settle(bx),
        None => Settled::Undecided,
    }
}

fn exact_system(patch: &Patch, ray: &Ray) -> Option<ExactSystem> {
    let (shape, points, weights) = match patch {
        Patch::Triangle(p) => (Shape::Triangle(p.degree()), p.points(), p.weights()),
        Patch::Tensor(p) if p.net_is_exact() => {
            let (m, n) = p.degree();
            (Shape::Tensor(m, n), p.points(), p.weights())
        }
        _ => return None,
    };
    let hom = points
        .iter()
        .enumerate()
        .map(|(idx, &p)| exact_hom(p, weights.map(|w| w[idx])))
        .collect::<Option<Vec<_>>>()?;
    system_of_net(shape, &hom, ray)
}

/// The homogeneous control point `(w x, w y, w z, w)` exactly (`w = 1`
/// without a weight); `None` if a value is not finite.
pub(super) fn exact_hom(p: DVec3, weight: Option<f64>) -> Option<[Q; 4]> {
    let q = |x: f64| Q::from_float(x);
    let w = match weight {
        Some(w) => q(w)?,
        None => Q::one(),
    };
    Some([&w * q(p.x)?, &w * q(p.y)?, &w * q(p.z)?, w])
}

/// The exact system of a homogeneous net `(w x, w y, w z, w)` (in `shape`'s
/// storage order) and the ray (module docs).
pub(super) fn system_of_net(shape: Shape, hom: &[[Q; 4]], ray: &Ray) -> Option<ExactSystem> {
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
    // e_k × d, for the two axes k ≠ c; then d itself for t.
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
    // n·(wP − w o) for each row.
    let rows: Vec<Vec<Q>> = normals
        .iter()
        .map(|n| {
            hom.iter()
                .map(|h| (0..3).fold(Q::zero(), |acc, c| acc + &n[c] * (&h[c] - &h[3] * &o[c])))
                .collect()
        })
        .collect();
    let [f, g, h]: [Vec<Q>; 3] = rows.try_into().ok()?;
    ExactSystem::new(shape, f, g, Some(h)).ok()
}
