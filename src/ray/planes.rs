//! The reduction of a ray to two plane equations (module docs of
//! [`crate::ray`]) in interval arithmetic, and `t` over a box.

use super::patch::Net;
use super::query::Ray;
use crate::poly::{TensorBezier, TriBezier};
use crate::scalar::point;
use inari::Interval;

/// The two planes through the ray, in interval arithmetic (also used by the
/// B-spline knot-line merging).
pub(crate) struct Planes {
    pub(crate) o: [Interval; 3],
    pub(crate) n: [[Interval; 3]; 2],
    /// `d̃ = 2^s d` (enclosed) and `2^s`.
    pub(crate) d: [Interval; 3],
    pub(crate) scale: Interval,
}

impl Planes {
    pub(crate) fn of(ray: &Ray) -> Self {
        let d = ray.dir();
        let big = d.abs().max_element();
        // A power of two, clamped so that it stays finite.
        let e = big.log2().floor().clamp(-1022.0, 1023.0) as i32;
        let scale = point(2f64.powi(-e));
        let dt = [point(d.x) * scale, point(d.y) * scale, point(d.z) * scale];
        let a = d.abs();
        let axis = if a.x <= a.y && a.x <= a.z {
            0
        } else if a.y <= a.z {
            1
        } else {
            2
        };
        let mut e_a = [point(0.0); 3];
        e_a[axis] = point(1.0);
        let n1 = cross(e_a, dt);
        let n2 = cross(dt, n1);
        Self {
            o: ray.origin().to_array().map(point),
            n: [n1, n2],
            d: dt,
            scale,
        }
    }

    /// `t = (S − o)·d / |d|² = 2^s (S − o)·d̃ / |d̃|²`.
    pub(crate) fn t_of(&self, s: [Interval; 3]) -> Interval {
        let num = (0..3).fold(point(0.0), |acc, c| acc + (s[c] - self.o[c]) * self.d[c]);
        let den = (0..3).fold(point(0.0), |acc, c| acc + self.d[c].sqr());
        self.scale * num / den
    }
}

fn cross(a: [Interval; 3], b: [Interval; 3]) -> [Interval; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `f_k` coefficients `n_k·(wP − w o)` in storage order, for `k = 1, 2`.
pub(super) fn reduce<P: HasCoeffs>(net: &Net<P>, planes: &Planes) -> [Vec<Interval>; 2] {
    let cols: [&[Interval]; 4] = std::array::from_fn(|c| net.c[c].coeff_slice());
    let len = cols[3].len();
    [0, 1].map(|k| {
        let n = planes.n[k];
        (0..len)
            .map(|i| {
                (0..3).fold(point(0.0), |acc, c| {
                    acc + n[c] * (cols[c][i] - cols[3][i] * planes.o[c])
                })
            })
            .collect()
    })
}

pub(super) trait HasCoeffs {
    fn coeff_slice(&self) -> &[Interval];
}

impl HasCoeffs for TriBezier<Interval> {
    fn coeff_slice(&self) -> &[Interval] {
        self.coeffs()
    }
}

impl HasCoeffs for TensorBezier<Interval> {
    fn coeff_slice(&self) -> &[Interval] {
        self.coeffs()
    }
}
