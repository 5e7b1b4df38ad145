//! [`Patch`]: the surfaces a ray can be intersected with.

use super::bspline::BsplineSurface;
use super::patch::{TensorPatch, TriPatch};
use glam::DVec3;

/// A Bézier patch of either kind, or a B-spline/NURBS surface (intersected
/// piece by piece). Degrees are at most 40 in each direction.
// Patches are built once and borrowed by every ray: the size difference of
// the variants costs nothing, boxing would cost an indirection per ray.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum Patch {
    /// A triangular patch on the unit triangle.
    Triangle(TriPatch),
    /// A tensor-product patch on the unit square.
    Tensor(TensorPatch),
    /// A B-spline or NURBS surface on its knot domain (boxed: it owns its
    /// Bézier pieces).
    Bspline(Box<BsplineSurface>),
}

impl From<TriPatch> for Patch {
    fn from(p: TriPatch) -> Self {
        Patch::Triangle(p)
    }
}

impl From<TensorPatch> for Patch {
    fn from(p: TensorPatch) -> Self {
        Patch::Tensor(p)
    }
}

impl From<BsplineSurface> for Patch {
    fn from(s: BsplineSurface) -> Self {
        Patch::Bspline(Box::new(s))
    }
}

impl Patch {
    /// The magnitudes of the control points and weights (cached).
    pub(crate) fn magnitude(&self) -> super::patch::Magnitude {
        match self {
            Patch::Triangle(p) => p.magnitude(),
            Patch::Tensor(p) => p.magnitude(),
            Patch::Bspline(s) => s.magnitude,
        }
    }

    /// `S(u, v)` in `f64`.
    pub fn eval(&self, u: f64, v: f64) -> DVec3 {
        match self {
            Patch::Triangle(p) => p.eval(u, v),
            Patch::Tensor(p) => p.eval(u, v),
            Patch::Bspline(s) => s.eval(u, v),
        }
    }

    /// `(∂S/∂u, ∂S/∂v)` in `f64`.
    pub fn partials(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        match self {
            Patch::Triangle(p) => p.partials(u, v),
            Patch::Tensor(p) => p.partials(u, v),
            Patch::Bspline(s) => s.partials(u, v),
        }
    }

    /// The unit normal `S_u × S_v / |S_u × S_v|` in `f64`; the zero vector
    /// where the partials are parallel (a collapsed corner or edge).
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let (su, sv) = self.partials(u, v);
        su.cross(sv).normalize_or_zero()
    }

    /// The point and the unit normal at `(u, v)` (one pass for tensors).
    pub fn point_and_normal(&self, u: f64, v: f64) -> (DVec3, DVec3) {
        match self {
            Patch::Tensor(p) => {
                let (x, su, sv) = p.frame(u, v);
                (x, su.cross(sv).normalize_or_zero())
            }
            _ => (self.eval(u, v), self.normal(u, v)),
        }
    }

    /// The control points.
    pub fn points(&self) -> &[DVec3] {
        match self {
            Patch::Triangle(p) => p.points(),
            Patch::Tensor(p) => p.points(),
            Patch::Bspline(s) => s.points(),
        }
    }
}
