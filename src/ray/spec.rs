//! [`PatchSpec`]: a patch as plain data, the shape of `PATCH.json`.

use super::bspline::BsplineSurface;
use super::patch::{TensorPatch, TriPatch};
use super::surface::Patch;
use crate::error::Result;
use glam::DVec3;

/// A patch as plain data: what `PATCH.json` holds, and what
/// [`Patch::from_spec`] validates. With the `serde` feature it reads and
/// writes the JSON, tagged by `"type"`; unknown keys are errors.
///
/// ```json
/// {"type": "triangle", "degree": 2, "points": [[x, y, z], ...], "weights": [...]}
/// {"type": "tensor", "degree": [m, n], "points": [...], "weights": [...]}
/// {"type": "bspline", "degree": [p, q], "knots_u": [...], "knots_v": [...], "points": [...]}
/// ```
///
/// Triangle points run `j = 0..=n` outer, `i = 0..=n−j` inner (Liu et al.
/// 2016, Eq. (2)); tensor and B-spline points row-major, `P_ij` at
/// `i·(n+1) + j` (B-splines: `i·n_v + j`); `weights` is optional, in the
/// same order, and positive.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)
)]
pub enum PatchSpec {
    /// A triangular Bézier patch of degree `degree` ([`TriPatch::new`]).
    Triangle {
        /// The degree `n ≥ 1`.
        degree: usize,
        /// `(n+1)(n+2)/2` control points.
        points: Vec<[f64; 3]>,
        /// Optional positive weights.
        #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
        weights: Option<Vec<f64>>,
    },
    /// A tensor-product Bézier patch ([`TensorPatch::new`]).
    Tensor {
        /// The bidegree `[m, n]`.
        degree: [usize; 2],
        /// `(m+1)(n+1)` control points, row-major.
        points: Vec<[f64; 3]>,
        /// Optional positive weights.
        #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
        weights: Option<Vec<f64>>,
    },
    /// A B-spline or NURBS surface ([`BsplineSurface::new`]).
    Bspline {
        /// The bidegree `[p, q]`.
        degree: [usize; 2],
        /// The knot vector in `u`.
        knots_u: Vec<f64>,
        /// The knot vector in `v`.
        knots_v: Vec<f64>,
        /// `n_u·n_v` control points, row-major.
        points: Vec<[f64; 3]>,
        /// Optional positive weights.
        #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "Option::is_none"))]
        weights: Option<Vec<f64>>,
    },
}

fn points(p: &[[f64; 3]]) -> Vec<DVec3> {
    p.iter().map(|&c| DVec3::from_array(c)).collect()
}

impl Patch {
    /// The patch a [`PatchSpec`] describes, validated as its constructor
    /// validates ([`TriPatch::new`], [`TensorPatch::new`],
    /// [`BsplineSurface::new`]).
    ///
    /// ```
    /// use rootclip::ray::{Patch, PatchSpec};
    /// let spec = PatchSpec::Triangle {
    ///     degree: 1,
    ///     points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    ///     weights: None,
    /// };
    /// let patch = Patch::from_spec(&spec)?;
    /// assert_eq!(patch.to_spec(), spec);
    /// # Ok::<(), rootclip::Error>(())
    /// ```
    pub fn from_spec(spec: &PatchSpec) -> Result<Patch> {
        Ok(match spec {
            PatchSpec::Triangle {
                degree,
                points: p,
                weights,
            } => TriPatch::new(*degree, points(p), weights.clone())?.into(),
            PatchSpec::Tensor {
                degree,
                points: p,
                weights,
            } => TensorPatch::new(degree[0], degree[1], points(p), weights.clone())?.into(),
            PatchSpec::Bspline {
                degree,
                knots_u,
                knots_v,
                points: p,
                weights,
            } => BsplineSurface::new(
                (degree[0], degree[1]),
                knots_u.clone(),
                knots_v.clone(),
                points(p),
                weights.clone(),
            )?
            .into(),
        })
    }

    /// The patch as plain data (the inverse of [`Patch::from_spec`]).
    pub fn to_spec(&self) -> PatchSpec {
        let pts = |p: &[DVec3]| p.iter().map(|x| x.to_array()).collect();
        match self {
            Patch::Triangle(p) => PatchSpec::Triangle {
                degree: p.degree(),
                points: pts(p.points()),
                weights: p.weights().map(<[f64]>::to_vec),
            },
            Patch::Tensor(p) => {
                let (m, n) = p.degree();
                PatchSpec::Tensor {
                    degree: [m, n],
                    points: pts(p.points()),
                    weights: p.weights().map(<[f64]>::to_vec),
                }
            }
            Patch::Bspline(s) => {
                let (p, q) = s.degree();
                PatchSpec::Bspline {
                    degree: [p, q],
                    knots_u: s.knots_u().to_vec(),
                    knots_v: s.knots_v().to_vec(),
                    points: pts(s.points()),
                    weights: s.weights().map(<[f64]>::to_vec),
                }
            }
        }
    }
}

impl TryFrom<PatchSpec> for Patch {
    type Error = crate::Error;
    fn try_from(spec: PatchSpec) -> Result<Patch> {
        Patch::from_spec(&spec)
    }
}

impl From<&Patch> for PatchSpec {
    fn from(p: &Patch) -> PatchSpec {
        p.to_spec()
    }
}
