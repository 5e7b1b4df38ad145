//! The methods raced: rootclip's certified all-hits query and each peer's
//! ray–surface call, on the same bicubic converted to the peer's NURBS type.
//! Every method maps a ray `o + t·d` to the `t` of its hits in `[0, 3]`
//! (in units of `d`, as rootclip reports them).

use brepkit_math::nurbs::curve::NurbsCurve as BkCurve;
use brepkit_math::nurbs::intersection::{intersect_curve_surface, intersect_line_nurbs, RaySurface};
use brepkit_math::nurbs::surface::NurbsSurface as BkSurface;
use brepkit_math::vec::{Point3 as BkPoint, Vec3 as BkVec};
use curvo::prelude::{HasIntersection, Intersects, NurbsCurve3D, NurbsSurface3D};
use nalgebra::{Point3 as NaPoint3, Point4};
use rootclip::glam::DVec3;
use rootclip::heuristics::{iterate, IterOptions, Iteration};
use rootclip::ray::{intersect, Patch, Ray, RayOptions, RayOutcome};

/// The ray's `t` range: every method's hits are kept in `[0, T_MAX]`.
pub const T_MAX: f64 = 3.0;

/// rootclip's answer for one ray: the `t` boxes of its certified hits and
/// of the others (undecided hits, or the hits of a degenerate ray).
#[derive(Default)]
pub struct Certified {
    pub certified: Vec<[f64; 2]>,
    pub uncertified: Vec<[f64; 2]>,
    pub degenerate: bool,
}

/// The bicubic in each library's form, prepared once (as rootclip's
/// [`Patch`] is).
pub struct Surfaces {
    pub patch: Patch,
    brepkit: BkSurface,
    brepkit_ray: RaySurface,
    curvo: NurbsSurface3D<f64>,
    opts: RayOptions,
    iter_opts: IterOptions,
}

/// A bicubic Bézier patch as a clamped B-spline: knots `0⁴ 1⁴`.
const KNOTS: [f64; 8] = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];

/// brepkit's `RaySurface::hits` reach: how far from the ray a patch's hull
/// may lie and still be searched, and the radius within which two hits are
/// one (the bicubic is about 11 units across).
const BREPKIT_REACH: f64 = 1e-8;

/// brepkit's `intersect_curve_surface` tolerance (its documentation's
/// example value).
const BREPKIT_CURVE_TOL: f64 = 1e-7;

/// brepkit's `intersect_line_nurbs` seed grid (the 10 × 10).
const BREPKIT_SAMPLES: usize = 10;

impl Surfaces {
    /// `grid[i][j]` is the control point `P_ij`, `i` along `u`.
    pub fn new(patch: Patch, grid: &[Vec<DVec3>]) -> Result<Self, String> {
        let brepkit = BkSurface::new(
            3,
            3,
            KNOTS.to_vec(),
            KNOTS.to_vec(),
            grid.iter()
                .map(|row| row.iter().map(|p| bk_point(*p)).collect())
                .collect(),
            vec![vec![1.0; 4]; 4],
        )
        .map_err(|e| format!("brepkit-math NurbsSurface: {e:?}"))?;
        let brepkit_ray = RaySurface::new(&brepkit).ok_or("brepkit-math RaySurface::new refused the bicubic")?;
        let curvo = NurbsSurface3D::new(
            3,
            3,
            KNOTS.to_vec(),
            KNOTS.to_vec(),
            grid.iter()
                .map(|row| row.iter().map(|p| Point4::new(p.x, p.y, p.z, 1.0)).collect())
                .collect(),
        );
        let s = Self {
            patch,
            brepkit,
            brepkit_ray,
            curvo,
            opts: RayOptions::default().with_t_range(0.0, T_MAX),
            iter_opts: IterOptions::default(),
        };
        s.check_conversions()?;
        Ok(s)
    }

    /// The three surfaces agree at a few parameters (the conversions keep
    /// `u` and `v` the same way round).
    fn check_conversions(&self) -> Result<(), String> {
        for (u, v) in [(0.1, 0.7), (0.5, 0.5), (0.9, 0.2), (0.0, 1.0)] {
            let p = self.patch.eval(u, v);
            let b = self.brepkit.evaluate(u, v);
            let c = self.curvo.point_at(u, v);
            let eb = (p - DVec3::new(b.x(), b.y(), b.z())).length();
            let ec = (p - DVec3::new(c.x, c.y, c.z)).length();
            if eb > 1e-12 || ec > 1e-12 {
                return Err(format!(
                    "conversions disagree at ({u}, {v}): brepkit {eb:e}, curvo {ec:e}"
                ));
            }
        }
        Ok(())
    }

    /// rootclip, certified, all hits in `[0, 3]` (`Query::All`, box route).
    pub fn rootclip(&self, ray: &Ray) -> Certified {
        let out = intersect(&self.patch, ray, &self.opts).expect("a valid ray");
        let mut c = Certified {
            degenerate: matches!(out, RayOutcome::Degenerate(_)),
            ..Certified::default()
        };
        for h in out.hits() {
            if h.is_certified() && !c.degenerate {
                c.certified.push(h.bx.t);
            } else {
                c.uncertified.push(h.bx.t);
            }
        }
        c
    }

    /// brepkit-math `intersect_line_nurbs`: Newton from the points of a
    /// 10 × 10 parameter grid near the line; hits on the whole line.
    pub fn brepkit_line(&self, ray: &Ray) -> Vec<f64> {
        let (o, d) = (ray.origin(), ray.dir());
        intersect_line_nurbs(&self.brepkit, bk_point(o), bk_vec(d), BREPKIT_SAMPLES)
            .map(|hits| in_range(hits.iter().map(|h| h.param2.0)))
            .unwrap_or_default()
    }

    /// brepkit-math `intersect_curve_surface`: the segment `o + t·d`,
    /// `t ∈ [0, 3]`, as a degree-1 NURBS curve; Newton on `C(s) = S(u, v)`
    /// from 9 samples per Bézier segment against each Bézier patch.
    pub fn brepkit_curve(&self, ray: &Ray) -> Vec<f64> {
        let (o, d) = (ray.origin(), ray.dir());
        let Ok(curve) = BkCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![bk_point(o), bk_point(o + T_MAX * d)],
            vec![1.0, 1.0],
        ) else {
            return Vec::new();
        };
        intersect_curve_surface(&curve, &self.brepkit, BREPKIT_CURVE_TOL)
            .map(|hits| in_range(hits.iter().map(|h| T_MAX * h.t)))
            .unwrap_or_default()
    }

    /// brepkit-math `RaySurface::hits`: Bézier subdivision of the prepared
    /// surface down to leaves of 1e-3 of its size, Newton in each leaf.
    /// Also whether brepkit flags the ray as grazing (its count in doubt).
    pub fn brepkit_ray(&self, ray: &Ray) -> (Vec<f64>, bool) {
        let (o, d) = (ray.origin(), ray.dir());
        let len = d.length();
        let hits = self.brepkit_ray.hits(bk_point(o), bk_vec(d / len), BREPKIT_REACH);
        (in_range(hits.hits.iter().map(|h| h.t / len)), hits.grazed)
    }

    /// curvo `find_intersection` of the surface with the segment
    /// `o + t·d`, `t ∈ [0, 3]`, as a degree-1 NURBS curve (normalized
    /// knots), default solver options.
    pub fn curvo(&self, ray: &Ray) -> Vec<f64> {
        let (o, d) = (ray.origin(), ray.dir());
        let e = o + T_MAX * d;
        let line = NurbsCurve3D::polyline(&[NaPoint3::new(o.x, o.y, o.z), NaPoint3::new(e.x, e.y, e.z)], true);
        self.curvo
            .find_intersection(&line, None)
            .map(|hits| in_range(hits.iter().map(|h| T_MAX * h.b().1)))
            .unwrap_or_default()
    }

    /// Plain Newton–Raphson from `(½, ½)` on `S(u, v) = o + t·d`
    /// (rootclip's heuristic: its `(u, v)` iterates are those of Newton on
    /// the ray's two-plane system), at most one hit.
    pub fn newton(&self, ray: &Ray) -> Vec<f64> {
        let out = iterate(Iteration::Newton, &self.patch, ray, [0.5, 0.5], &self.iter_opts);
        in_range(out.end.map(|e| e.t))
    }
}

fn in_range(ts: impl IntoIterator<Item = f64>) -> Vec<f64> {
    ts.into_iter().filter(|t| (0.0..=T_MAX).contains(t)).collect()
}

fn bk_point(p: DVec3) -> BkPoint {
    BkPoint::new(p.x, p.y, p.z)
}

fn bk_vec(p: DVec3) -> BkVec {
    BkVec::new(p.x, p.y, p.z)
}
