//! Surface/surface intersection (seed 002): every branch of the curve where
//! two Bézier patches meet, traced by the seed's continuation and RK4
//! marching, with every traced point certified and every branch proven
//! found.
//!
//! ```
//! use rootclip::glam::DVec3;
//! use rootclip::ray::{Patch, TensorPatch};
//! use rootclip::ssi::{intersect_surfaces, SsiOptions};
//! // The plane z = 1/2 against the paraboloid z = x² + y² over [-1, 1]²:
//! // a circle of radius √½, a closed loop inside both patches.
//! let plane = TensorPatch::new(1, 1, vec![
//!     DVec3::new(-1.0, -1.0, 0.5), DVec3::new(-1.0, 1.0, 0.5),
//!     DVec3::new(1.0, -1.0, 0.5), DVec3::new(1.0, 1.0, 0.5)], None)?;
//! // x² on [−1, 1] has Bézier coefficients 1, −1, 1 (degree 2).
//! let sq = [1.0, -1.0, 1.0];
//! let mut pts = Vec::new();
//! for i in 0..3 {
//!     for j in 0..3 {
//!         pts.push(DVec3::new(i as f64 - 1.0, j as f64 - 1.0, sq[i] + sq[j]));
//!     }
//! }
//! let bowl = TensorPatch::new(2, 2, pts, None)?;
//! let out = intersect_surfaces(&Patch::from(plane), &Patch::from(bowl), &SsiOptions::default())?;
//! assert!(out.complete && out.branches.len() == 1 && out.branches[0].closed);
//! for p in &out.branches[0].points {
//!     let r2 = p.xyz[0] * p.xyz[0] + p.xyz[1] * p.xyz[1];
//!     assert!(p.certified && (r2 - 0.5).abs() < 1e-9);
//! }
//! # Ok::<(), rootclip::Error>(())
//! ```
//!
//! # Contract ([`Intersection`])
//! The curve is `C = {(u, v, s, t) ∈ [0, 1]⁴ : A(u, v) = B(s, t)}` (B-spline
//! surfaces: per pair of Bézier pieces, in knot parameters).
//! * A point flagged `certified` lies within its printed digits' rounding of
//!   a point of `C`: its box (width below `10⁻⁶` relative, usually `10⁻¹²`)
//!   holds exactly one point of `C` on the hyperplane across the marching
//!   direction through it.
//! * Between consecutive points of a branch the curve is proven to be one
//!   arc (a graph over the marching parameter, inside a box the tube test
//!   proved; see `system.rs`), so a branch cannot jump to another branch.
//! * If `complete` is true: the branches are all of `C`, each exactly once
//!   (the start points are complete, see `start.rs`, and every branch ended
//!   at a certified crossing with the boundary or closed on its start), and
//!   `C` has no singular point. Each branch's chord deviates from the curve
//!   by about `tol` at most (a float check at each step's middle).
//! * If `complete` is false, `singular` says where and why: a tangential
//!   contact or other singular point (a start system with an undecided
//!   region), possibly overlapping patches (an equation that may vanish
//!   identically, i.e. a 2-dimensional intersection), or an unfinished
//!   branch (a step proven nowhere, a budget). Branches listed are still
//!   right as far as their certified points go, and each is traced as far
//!   as it can be: from a crossing inward, from a turning point both ways
//!   (an unfinished branch through a turning point has both its ends in
//!   `singular`). A part of a branch that stopped unfinished may then be
//!   listed twice, traced from a crossing and from a turning point.
//!
//! A triangular patch is intersected as the tensor patch
//! `(σ, τ) ↦ T(σ(1 − τ), στ)` (its corner `u = v = 0` the collapsed edge
//! `σ = 0`; reported parameters are the triangle's). If that corner lies on
//! the other patch, the collapsed edge is a curve of zeros of a boundary
//! system and the answer is incomplete there.

mod algebra;
mod exact;
mod start;
mod system;
mod trace;

use crate::error::{Error, Result};
use crate::ray::{Patch, TensorPatch, TriPatch};
use crate::solve::nd::NdOptions;
use glam::DVec3;
use system::{Box4, System};
use trace::{End, Start, Trace, Tracer};

/// Options of [`intersect_surfaces`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SsiOptions {
    /// Largest deviation of a chord from the curve, in model units (> 0).
    pub tol: f64,
    /// Box budget of each start-point solve.
    pub max_boxes: usize,
    /// Most points per branch traced one way (a branch traced both ways
    /// from a turning point may hold twice as many).
    pub max_points: usize,
}

impl Default for SsiOptions {
    fn default() -> Self {
        Self {
            tol: 1e-3,
            max_boxes: 200_000,
            max_points: 20_000,
        }
    }
}

impl SsiOptions {
    /// The same options with another chord tolerance.
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }
}

/// A point of a branch.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CurvePoint {
    /// Parameters on patch A.
    pub a: [f64; 2],
    /// Parameters on patch B.
    pub b: [f64; 2],
    /// The point `A(a)` in model space.
    pub xyz: [f64; 3],
    /// Proven within rounding of the curve (module docs).
    pub certified: bool,
}

/// One branch of the curve, points in order along it.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Branch {
    /// A closed loop (the last point joins the first).
    pub closed: bool,
    /// The points.
    pub points: Vec<CurvePoint>,
}

/// Why a region is singular or undecided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize), serde(rename_all = "snake_case"))]
pub enum SingularKind {
    /// The normals are parallel within `10⁻⁶` there: the patches touch.
    TangentialContact,
    /// A coordinate difference may vanish identically: the patches may
    /// overlap (a 2-dimensional intersection).
    Overlap,
    /// A start system left the region undecided (a singular point of the
    /// curve such as two branches crossing, or a budget).
    Undecided,
    /// A branch could not be traced on from here.
    Unfinished,
}

/// A region where the answer is not proven.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Singular {
    /// What kind.
    pub kind: SingularKind,
    /// The region on patch A, `[[u_lo, u_hi], [v_lo, v_hi]]`.
    pub a: [[f64; 2]; 2],
    /// The region on patch B.
    pub b: [[f64; 2]; 2],
    /// In words.
    pub reason: String,
}

/// Counters of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SsiStats {
    /// Boxes processed by the start-point solves.
    pub boxes: usize,
    /// Certified crossings with the patches' boundaries.
    pub crossings: usize,
    /// Certified turning points.
    pub turning_points: usize,
    /// Certified points on the branches.
    pub certified_points: usize,
}

/// The intersection of two patches; see the module docs for the contract.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Intersection {
    /// The branches are the whole intersection (module docs).
    pub complete: bool,
    /// The branches.
    pub branches: Vec<Branch>,
    /// Regions not proven.
    pub singular: Vec<Singular>,
    /// Counters.
    pub stats: SsiStats,
}

/// Every branch of the intersection of patches `a` and `b`, with the
/// contract of the [module docs](self).
///
/// Errors: a `tol` that is not a positive number
/// ([`Error::InvalidOption`]).
pub fn intersect_surfaces(a: &Patch, b: &Patch, opts: &SsiOptions) -> Result<Intersection> {
    if !(opts.tol > 0.0 && opts.tol.is_finite()) {
        return Err(Error::InvalidOption(format!(
            "tol must be a positive number, got {}",
            opts.tol
        )));
    }
    let pa = pieces(a)?;
    let pb = pieces(b)?;
    let mut out = Intersection {
        complete: true,
        branches: Vec::new(),
        singular: Vec::new(),
        stats: SsiStats::default(),
    };
    for (x, mx, ex) in &pa {
        for (y, my, ey) in &pb {
            let exact = match (ex, ey) {
                (Some(a), Some(b)) => Some(exact::ExactPair {
                    a,
                    b,
                    residual: exact::residual(a, b),
                }),
                _ => None,
            };
            let part = intersect_pair(x, y, exact.as_ref(), opts);
            out.complete &= part.complete;
            for mut br in part.branches {
                for p in &mut br.points {
                    p.a = mx.point(p.a);
                    p.b = my.point(p.b);
                }
                out.branches.push(br);
            }
            for mut s in part.singular {
                s.a = mx.region(s.a);
                s.b = my.region(s.b);
                out.singular.push(s);
            }
            out.stats.boxes += part.stats.boxes;
            out.stats.crossings += part.stats.crossings;
            out.stats.turning_points += part.stats.turning_points;
            out.stats.certified_points += part.stats.certified_points;
        }
    }
    Ok(out)
}

/// The map from a Bézier piece's `[0, 1]²` (where the tracer works) to the
/// patch's parameters.
#[derive(Clone, Copy, Debug)]
enum PieceMap {
    /// A tensor patch: the identity.
    Identity,
    /// A B-spline piece on `ur × vr`: `(u, v) = (u₀ + x(u₁ − u₀), v₀ + y(v₁ − v₀))`.
    Span([f64; 2], [f64; 2]),
    /// A triangle as a tensor patch: `(u, v) = (σ(1 − τ), στ)`.
    Triangle,
}

impl PieceMap {
    /// The image of a point, in the patch's closed domain exactly (the
    /// tracer's points may stray by rounding; on a triangle `u + v ≤ 1`
    /// holds in exact arithmetic).
    fn point(self, x: [f64; 2]) -> [f64; 2] {
        let [s, t] = x.map(|c| c.clamp(0.0, 1.0));
        match self {
            PieceMap::Identity => [s, t],
            PieceMap::Span(ur, vr) => [
                (ur[0] + s * (ur[1] - ur[0])).clamp(ur[0], ur[1]),
                (vr[0] + t * (vr[1] - vr[0])).clamp(vr[0], vr[1]),
            ],
            PieceMap::Triangle => {
                let u = (s * (1.0 - t)).clamp(0.0, 1.0);
                let v = (s * t).clamp(0.0, 1.0);
                // u + v ≤ 1 exactly: else v = 1 − u rounded down.
                let one = crate::scalar::point(1.0);
                if (crate::scalar::point(u) + crate::scalar::point(v)).sup() > 1.0 {
                    [u, (one - crate::scalar::point(u)).inf().max(0.0)]
                } else {
                    [u, v]
                }
            }
        }
    }

    /// A box holding the image of the region `r = [[x_lo, x_hi], [y_lo,
    /// y_hi]]` (cut to `[0, 1]²`), rounded outward: on a triangle `u =
    /// σ(1 − τ)` rises with `σ` and falls with `τ`, `v = στ` rises with both.
    fn region(self, r: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
        use crate::scalar::point;
        let [[s0, s1], [t0, t1]] = r.map(|[lo, hi]| [lo.clamp(0.0, 1.0), hi.clamp(0.0, 1.0)]);
        let lin = |x0: f64, x1: f64, a: f64, b: f64| {
            let (lo, hi) = (point(a), point(b));
            [
                (point(x0) + (point(x1) - point(x0)) * lo).inf().max(x0),
                (point(x0) + (point(x1) - point(x0)) * hi).sup().min(x1),
            ]
        };
        match self {
            PieceMap::Identity => [[s0, s1], [t0, t1]],
            PieceMap::Span(ur, vr) => [lin(ur[0], ur[1], s0, s1), lin(vr[0], vr[1], t0, t1)],
            PieceMap::Triangle => {
                let one = point(1.0);
                [
                    [
                        (point(s0) * (one - point(t1))).inf().max(0.0),
                        (point(s1) * (one - point(t0))).sup().min(1.0),
                    ],
                    [
                        (point(s0) * point(t0)).inf().max(0.0),
                        (point(s1) * point(t1)).sup().min(1.0),
                    ],
                ]
            }
        }
    }
}

/// The Bézier pieces of a patch with the map from a piece's `[0, 1]²` to
/// the patch's parameters, and the piece's exact homogeneous net (`None` if
/// a number is not finite).
fn pieces(p: &Patch) -> Result<Vec<(TensorPatch, PieceMap, Option<exact::ExactNet>)>> {
    use crate::ray::settle::exact_hom;
    let hom_of = |points: &[DVec3], weights: Option<&[f64]>| -> Option<Vec<[num_rational::BigRational; 4]>> {
        points
            .iter()
            .enumerate()
            .map(|(k, &q)| exact_hom(q, weights.map(|w| w[k])))
            .collect()
    };
    match p {
        Patch::Tensor(t) => {
            let net = hom_of(t.points(), t.weights()).map(|hom| exact::ExactNet {
                deg: t.degree(),
                hom,
                rational: t.weights().is_some(),
            });
            Ok(vec![(t.clone(), PieceMap::Identity, net)])
        }
        Patch::Bspline(s) => Ok(s
            .pieces()
            .iter()
            .map(|piece| {
                let net = crate::ray::bspline::exact::exact_piece_net(s, piece).map(|hom| exact::ExactNet {
                    deg: piece.patch().degree(),
                    hom,
                    rational: s.weights().is_some(),
                });
                (
                    piece.patch().clone(),
                    PieceMap::Span(piece.u_range(), piece.v_range()),
                    net,
                )
            })
            .collect()),
        Patch::Triangle(t) => {
            let net =
                hom_of(t.points(), t.weights()).map(|hom| exact::triangle_net(t.degree(), &hom, t.weights().is_some()));
            Ok(vec![(triangle_as_tensor(t)?, PieceMap::Triangle, net)])
        }
    }
}

/// A triangular patch as a tensor patch of bidegree `(n, n)` on `[0, 1]²`
/// through `(u, v) = (σ(1 − τ), στ)`, which maps the square onto the
/// triangle (the edge `σ = 0` collapses to the corner `u = v = 0`):
/// `B^n_{ijk}(u, v) = B^n_{i+j}(σ) B^{i+j}_j(τ)`, the second factor raised
/// to degree `n`, so `c_{a,l} = Σ_j b_{a−j, j} C(a, j) C(n − a, l − j) / C(n, l)`
/// for each homogeneous coordinate, a convex combination. Computed in `f64`;
/// the patch's enclosures are widened by a bound of that rounding, so it
/// stands for the exact triangle.
fn triangle_as_tensor(p: &TriPatch) -> Result<TensorPatch> {
    let n = p.degree();
    let pts = p.points();
    let w = p.weights();
    // Control point (i, j): j outer, i inner.
    let index = |i: usize, j: usize| (0..j).map(|r| n + 1 - r).sum::<usize>() + i;
    let hom = |i: usize, j: usize| -> [f64; 4] {
        let k = index(i, j);
        let wk = w.map_or(1.0, |w| w[k]);
        [pts[k].x * wk, pts[k].y * wk, pts[k].z * wk, wk]
    };
    let binom = |n: usize, k: usize| -> f64 { (0..k).fold(1.0f64, |r, i| r * (n - i) as f64 / (i + 1) as f64) };
    let mut points = Vec::with_capacity((n + 1) * (n + 1));
    let mut weights = Vec::with_capacity((n + 1) * (n + 1));
    let mut big = 0.0f64;
    for a in 0..=n {
        for l in 0..=n {
            let mut c = [0.0f64; 4];
            for j in l.saturating_sub(n - a)..=a.min(l) {
                let wt = binom(a, j) * binom(n - a, l - j) / binom(n, l);
                let h = hom(a - j, j);
                for (x, y) in c.iter_mut().zip(h) {
                    *x += wt * y;
                    big = big.max(y.abs());
                }
            }
            if w.is_some() {
                points.push(DVec3::new(c[0] / c[3], c[1] / c[3], c[2] / c[3]));
                weights.push(c[3]);
            } else {
                points.push(DVec3::new(c[0], c[1], c[2]));
            }
        }
    }
    let mut t = TensorPatch::new(n, n, points, w.map(|_| weights))?;
    // Binomials below 2⁵³ are exact; each weight carries ≤ 4 roundings, each
    // term 1 more, the sum n + 1, the division and the patch's own products
    // 3: (2n + 16)·2⁻⁵³ of the largest coordinate bounds it all.
    t.widen([(2 * n + 16) as f64 * f64::EPSILON * 0.5 * big * 2.0; 4])?;
    Ok(t)
}

/// Whether the region `ra` of `a` and `rb` of `b` may be a tangential
/// contact: the normals at the regions' centres are parallel within `10⁻⁶`
/// (in `f64`, the evidence), and the enclosure of `N_a × N_b` over the
/// regions contains zero (no proof that the normals differ anywhere in them:
/// a region proven transversal is never called tangential).
fn may_touch(a: &TensorPatch, ra: [[f64; 2]; 2], b: &TensorPatch, rb: [[f64; 2]; 2]) -> bool {
    let mid = |r: [f64; 2]| (0.5 * r[0] + 0.5 * r[1]).clamp(0.0, 1.0);
    let (na, nb) = (a.normal(mid(ra[0]), mid(ra[1])), b.normal(mid(rb[0]), mid(rb[1])));
    if na.cross(nb).length() > 1e-6 || na == DVec3::ZERO || nb == DVec3::ZERO {
        return false;
    }
    let iv = |r: [f64; 2]| crate::scalar::interval(r[0].max(0.0), r[1].min(1.0));
    let ea = a.normal_enclosure(iv(ra[0]), iv(ra[1]));
    let eb = b.normal_enclosure(iv(rb[0]), iv(rb[1]));
    let cross = [
        ea[1] * eb[2] - ea[2] * eb[1],
        ea[2] * eb[0] - ea[0] * eb[2],
        ea[0] * eb[1] - ea[1] * eb[0],
    ];
    cross.iter().all(|c| c.contains(0.0))
}

fn split(b: &Box4) -> ([[f64; 2]; 2], [[f64; 2]; 2]) {
    ([b[0], b[1]], [b[2], b[3]])
}

/// The intersection of two Bézier patches.
fn intersect_pair(
    a: &TensorPatch,
    b: &TensorPatch,
    exact: Option<&exact::ExactPair>,
    opts: &SsiOptions,
) -> Intersection {
    let ha = algebra::homogeneous(a);
    let hb = algebra::homogeneous(b);
    let f = algebra::residual(&ha, &hb);
    let sys = System::new(&f);
    let nd = NdOptions::default().with_max_boxes(opts.max_boxes);
    // The exact residual matches the enclosures' storage when the degrees
    // agree (they always do: both are (m, n, p, q)).
    let exact = exact.filter(|e| {
        e.residual
            .iter()
            .enumerate()
            .all(|(k, c)| c.len() == sys.coeffs(k).len())
    });
    let starts = start::find(&sys, exact, &ha, &hb, &nd);
    let mut out = Intersection {
        complete: true,
        branches: Vec::new(),
        singular: Vec::new(),
        stats: SsiStats {
            boxes: starts.boxes,
            crossings: starts.crossings.len(),
            turning_points: starts.turning.len(),
            certified_points: 0,
        },
    };
    if let Some(reason) = &starts.degenerate {
        out.complete = false;
        out.singular.push(Singular {
            kind: SingularKind::Overlap,
            a: [[0.0, 1.0]; 2],
            b: [[0.0, 1.0]; 2],
            reason: format!("an equation may vanish identically ({reason})"),
        });
        return out;
    }
    for u in group(&starts.undecided) {
        out.complete = false;
        let (ra, rb) = split(&u);
        let tangential = may_touch(a, ra, b, rb);
        out.singular.push(Singular {
            kind: if tangential {
                SingularKind::TangentialContact
            } else {
                SingularKind::Undecided
            },
            a: ra,
            b: rb,
            reason: if tangential {
                "the patches may touch here (normals parallel at its centre, and not proven apart over it): a tangential contact".into()
            } else {
                "a start-point solve left this region undecided (a singular point of the curve, or a budget)".into()
            },
        });
    }
    let xyz = |u: f64, v: f64| a.eval(u, v).to_array();
    let tracer = Tracer {
        sys: &sys,
        xyz: &xyz,
        crossings: &starts.crossings,
        turning: &starts.turning,
        undecided: &starts.undecided,
        tol: opts.tol,
        max_points: opts.max_points,
    };
    let mut used_cross = vec![false; starts.crossings.len()];
    let mut used_turn = vec![false; starts.turning.len()];
    // Each trace with the end of its other half (traces from a turning point).
    let mut traces: Vec<(Trace, Option<End>)> = Vec::new();
    for k in 0..starts.crossings.len() {
        if used_cross[k] {
            continue;
        }
        used_cross[k] = true;
        let tr = tracer.trace(Start::Crossing(k), starts.crossings[k], false);
        if let End::Crossing(e) = tr.end {
            used_cross[e] = true;
        }
        tr.turning.iter().for_each(|&t| used_turn[t] = true);
        traces.push((tr, None));
    }
    for k in 0..starts.turning.len() {
        let t = &starts.turning[k];
        let on_traced = traces.iter().any(|(tr, _)| tr.tubes.iter().any(|tb| inside(t, tb)));
        if used_turn[k] || on_traced {
            continue;
        }
        used_turn[k] = true;
        let (tr, other) = trace_both_ways(&tracer, k, t);
        tr.turning.iter().for_each(|&t| used_turn[t] = true);
        traces.push((tr, other));
    }
    for (tr, other) in traces {
        let closed = tr.end == End::Closed;
        let ends = match other {
            Some(o) if o != tr.end => vec![tr.end, o],
            _ => vec![tr.end],
        };
        for end in ends {
            if let End::Stuck(bx) = end {
                out.complete = false;
                let (ra, rb) = split(&bx);
                out.singular.push(Singular {
                    kind: SingularKind::Unfinished,
                    a: ra,
                    b: rb,
                    reason: "a branch could not be traced on from here (no step proven, or the point budget)".into(),
                });
            }
        }
        let points: Vec<CurvePoint> = tr
            .points
            .iter()
            .map(|&(x, certified)| CurvePoint {
                a: [x[0], x[1]],
                b: [x[2], x[3]],
                xyz: xyz(x[0], x[1]),
                certified,
            })
            .collect();
        out.complete &= points.iter().all(|p| p.certified);
        out.stats.certified_points += points.iter().filter(|p| p.certified).count();
        out.branches.push(Branch { closed, points });
    }
    out
}

/// The branch through turning point `k` (box `t`), traced along its
/// tangent and, unless that closes a loop, against it, the halves joined at
/// the turning point; with the end of the second half.
///
/// A half may end at a crossing already traced from: the trace from there
/// then stopped unfinished on the way here (the arc through a crossing is
/// unique, and a finished trace would hold this turning point in a tube),
/// and the part between its stop and this point is traced only from here.
fn trace_both_ways(tracer: &Tracer, k: usize, t: &Box4) -> (Trace, Option<End>) {
    let fwd = tracer.trace(Start::Turning(k), *t, false);
    if fwd.end == End::Closed {
        return (fwd, None);
    }
    let bwd = tracer.trace(Start::Turning(k), *t, true);
    if bwd.end == End::Closed {
        // The loop, whole, the other way round: `fwd` was part of it.
        return (bwd, None);
    }
    let mut tr = Trace {
        points: bwd.points.into_iter().rev().collect(),
        tubes: bwd.tubes,
        turning: bwd.turning,
        end: fwd.end,
    };
    tr.points.extend(fwd.points.into_iter().skip(1));
    tr.tubes.extend(fwd.tubes);
    for j in fwd.turning {
        if !tr.turning.contains(&j) {
            tr.turning.push(j);
        }
    }
    (tr, Some(bwd.end))
}

fn inside(a: &Box4, b: &Box4) -> bool {
    (0..4).all(|d| b[d][0] <= a[d][0] && a[d][1] <= b[d][1])
}

/// Boxes that touch, joined into their hulls.
fn group(boxes: &[Box4]) -> Vec<Box4> {
    let mut out: Vec<Box4> = Vec::new();
    for b in boxes {
        let mut cur = *b;
        while let Some(i) = out
            .iter()
            .position(|o| (0..4).all(|d| o[d][0] <= cur[d][1] && cur[d][0] <= o[d][1]))
        {
            let o = out.swap_remove(i);
            for d in 0..4 {
                cur[d] = [cur[d][0].min(o[d][0]), cur[d][1].max(o[d][1])];
            }
        }
        out.push(cur);
    }
    out
}
