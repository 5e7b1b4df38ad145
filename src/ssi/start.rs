//! Start points of the tracer, each from a certified solve: the crossings
//! of the intersection curve with the 8 boundary curves of the two patches
//! (square systems in 3 unknowns), and its turning points in one parameter
//! direction (a square system in 4 unknowns).
//!
//! # Why no branch is missed
//! Let `C` be the zero set of `F` in the closed box `[0, 1]⁴`. A component
//! of `C` either meets the boundary of the box, where it holds a zero of
//! one of the 8 face systems `F|_{x_d = 0 or 1} = 0`, or is a closed curve
//! in the open box. On a closed curve the parameter `x_d` (continuous, on a
//! compact set) attains its maximum; there the tangent has no `x_d`
//! component, and the tangent's components are the signed 3×3 minors of
//! `F'`, so the minor without column `d` vanishes — or `F'` has rank below
//! 3 and every minor vanishes. Either way
//! the point is a zero of the square system `(F, D_d)`
//! ([`turning`](super::algebra::turning)). Both solves are complete
//! ([`solve_nd`]): every such zero lies in a certified box or an undecided
//! region. A certified zero of `(F, D_d)` is a smooth point of `C` (its
//! Jacobian, with the rows of `F'`, has full rank), so when the solves
//! leave no undecided region `C` has no singular point at all.

use super::algebra::{turning, Poly};
use super::exact::{ExactPair, TurningExact};
use super::system::{Box4, System};
use crate::error::Error;
use crate::scalar::iv::Iv;
use crate::solve::nd::clip::elevate;
use crate::solve::nd::global::{ExactCoeffs, ExactEq, ExactValues};
use crate::solve::nd::tensor::len_of;
use crate::solve::nd::{solve_nd_exact, BernsteinNd, NdOptions};
use num_rational::BigRational;

type Q = BigRational;

/// What the start-point solves found.
#[derive(Default)]
pub(crate) struct Starts {
    /// Certified crossings with the box's boundary (4-D boxes, the face's
    /// coordinate exact), overlapping ones joined.
    pub(crate) crossings: Vec<Box4>,
    /// Certified turning points.
    pub(crate) turning: Vec<Box4>,
    /// Regions no solve decided, and boxes a budget left.
    pub(crate) undecided: Vec<Box4>,
    /// An equation that may vanish identically (coplanar or overlapping
    /// patches): what the solver said.
    pub(crate) degenerate: Option<String>,
    /// Boxes processed by the solves.
    pub(crate) boxes: usize,
}

/// The face `x_d = end` of a 4-D tensor: the coefficients with `i_d = 0`
/// (or `n_d`), a 3-D tensor in the other axes.
fn face<T: Clone>(c: &[T], deg: &[usize; 4], d: usize, end: usize) -> ([usize; 3], Vec<T>) {
    let rest = super::system::others(d);
    let deg3 = rest.map(|a| deg[a]);
    let idx = if end == 0 { 0 } else { deg[d] };
    let mut out = Vec::with_capacity(len_of(&deg3));
    for (k, x) in c.iter().enumerate() {
        let mut r = k;
        let mut i = [0usize; 4];
        for a in (0..4).rev() {
            i[a] = r % (deg[a] + 1);
            r /= deg[a] + 1;
        }
        if i[d] == idx {
            out.push(x.clone());
        }
    }
    (deg3, out)
}

fn lift(bx3: &[[f64; 2]; 3], d: usize, end: usize) -> Box4 {
    let rest = super::system::others(d);
    let mut out = [[end as f64; 2]; 4];
    for (k, &a) in rest.iter().enumerate() {
        out[a] = bx3[k];
    }
    out
}

fn overlap(a: &Box4, b: &Box4) -> bool {
    (0..4).all(|d| a[d][0] <= b[d][1] && b[d][0] <= a[d][1])
}

/// The crossings of `C` with the 8 faces (each face system with its exact
/// coefficients when the residual's are known).
fn crossings(sys: &System, exact: Option<&[Vec<Q>; 3]>, opts: &NdOptions, out: &mut Starts) {
    let deg = sys.degree();
    for d in 0..4 {
        for end in [0, 1] {
            let eqs: [BernsteinNd<3>; 3] = std::array::from_fn(|e| {
                let (deg3, c) = face(sys.coeffs(e), &deg, d, end);
                BernsteinNd { deg: deg3, c }
            });
            let exact_q: Option<Vec<Vec<Q>>> = exact.map(|ex| ex.iter().map(|c| face(c, &deg, d, end).1).collect());
            let exact_face: Option<Vec<ExactEq>> =
                exact_q.as_ref().map(|ex| ex.iter().map(|c| ExactEq::new(c)).collect());
            let exact_sys = exact_face.as_ref().map(|e| ExactCoeffs {
                deg: [eqs[0].deg; 3],
                eqs: e,
            });
            let res = solve_nd_exact(&eqs, exact_sys.as_ref().map(|e| e as &dyn ExactValues<3>), opts);
            let face_sys = match (&exact_q, &exact_face) {
                (Some(q), Some(e)) => Some(FaceSystem {
                    deg3: eqs[0].deg,
                    iv: eqs.iter().map(|p| p.c.clone()).collect(),
                    exact: q,
                    eqs: e,
                }),
                _ => None,
            };
            match res {
                Ok(sol) => {
                    out.boxes += sol.stats.boxes;
                    for r in &sol.roots {
                        let bx3 = match settle_on_boundary(r.bx, face_sys.as_ref()) {
                            OnBoundary::Inside(b) => b,
                            OnBoundary::Outside => continue,
                            OnBoundary::Unknown => {
                                out.undecided.push(lift(&r.bx, d, end));
                                continue;
                            }
                        };
                        let b = lift(&bx3, d, end);
                        match out.crossings.iter_mut().find(|c| overlap(c, &b)) {
                            Some(c) => {
                                for a in 0..4 {
                                    c[a] = [c[a][0].min(b[a][0]), c[a][1].max(b[a][1])];
                                }
                            }
                            None => out.crossings.push(b),
                        }
                    }
                    out.undecided.extend(sol.undecided.iter().map(|u| lift(&u.bx, d, end)));
                    out.undecided.extend(sol.leftovers.iter().map(|b| lift(b, d, end)));
                }
                Err(e) => {
                    out.degenerate.get_or_insert_with(|| format!("face x{d} = {end}: {e}"));
                    out.undecided.push(lift(&[[0.0, 1.0]; 3], d, end));
                }
            }
        }
    }
}

/// Where a face system's certified zero lies relative to the face's own
/// boundary (the other faces of `[0, 1]⁴`).
enum OnBoundary {
    /// In the closed face, within this box (`bx3`, or the point proven on
    /// a boundary face).
    Inside([[f64; 2]; 3]),
    /// Outside it: not a point of the curve in the domain.
    Outside,
    /// Not decided: the box reaches past the boundary and no proof placed
    /// the zero.
    Unknown,
}

/// The face system `x_d = end` with its exact coefficients, for settling
/// its zeros on the boundary.
struct FaceSystem<'a> {
    deg3: [usize; 3],
    /// The enclosures, per equation.
    iv: Vec<Vec<Iv>>,
    /// The exact coefficients, per equation (as rationals and for exact
    /// evaluation).
    exact: &'a [Vec<Q>],
    eqs: &'a [ExactEq],
}

/// Settles the zero certified in `bx3` (exactly one zero of the face system
/// in `ℝ³`, a simple one) on the closed face. A box within `[0, 1]³` is
/// inside. One that reaches past the boundary is contracted by Krawczyk
/// steps with exact values (a zero `10⁻¹⁸` from the boundary is placed on
/// its side: floats are fine near 0 and 1). One still reaching past it
/// along exactly one axis `k` — a zero on the boundary within the last
/// float — is settled where the boundary is shared: on the 2-face
/// `x_k = e` the three equations restricted are tested, exactly, for
/// vanishing identically (two patches sharing an edge: one coordinate
/// difference is zero all along it); if exactly one does, Krawczyk with
/// exact values on the other two (2 unknowns) over the box's projection
/// proves a zero of the 2-face system in it, which is then a zero of the
/// face system in `bx3` — the only one — on the boundary, so in the closed
/// domain. Anything else is [`OnBoundary::Unknown`].
fn settle_on_boundary(bx3: [[f64; 2]; 3], face: Option<&FaceSystem>) -> OnBoundary {
    use crate::solve::krawczyk::Verdict;
    use crate::solve::nd::global::GlobalSystem;
    let out = |b: &[[f64; 2]; 3]| b.iter().any(|&[lo, hi]| hi < 0.0 || lo > 1.0);
    let past = |b: &[[f64; 2]; 3]| -> Vec<usize> { (0..3).filter(|&k| b[k][0] < 0.0 || b[k][1] > 1.0).collect() };
    if out(&bx3) {
        return OnBoundary::Outside;
    }
    if past(&bx3).is_empty() {
        return OnBoundary::Inside(bx3);
    }
    let Some(face) = face else {
        return OnBoundary::Unknown;
    };
    let coeffs3 = ExactCoeffs {
        deg: [face.deg3; 3],
        eqs: face.eqs,
    };
    let sys3 = GlobalSystem::<3>::new([face.deg3; 3], &face.iv, Some(&coeffs3));
    let mut bx3 = bx3;
    for _ in 0..3 {
        match sys3.certify(bx3) {
            Verdict::Unique(k) => bx3 = k,
            _ => break,
        }
        if out(&bx3) {
            return OnBoundary::Outside;
        }
        if past(&bx3).is_empty() {
            return OnBoundary::Inside(bx3);
        }
    }
    let k = match past(&bx3).as_slice() {
        [k] => *k,
        _ => return OnBoundary::Unknown,
    };
    let e = usize::from(bx3[k][0] >= 0.0);
    let two: Vec<(Vec<usize>, Vec<Q>)> = face.exact.iter().map(|c| face_nd(c, &face.deg3, k, e)).collect();
    let zero: Vec<bool> = two
        .iter()
        .map(|(_, c)| c.iter().all(num_traits::Zero::is_zero))
        .collect();
    if zero.iter().filter(|&&z| z).count() != 1 {
        return OnBoundary::Unknown;
    }
    let keep: Vec<&(Vec<usize>, Vec<Q>)> = two.iter().zip(&zero).filter(|(_, &z)| !z).map(|(t, _)| t).collect();
    let deg2: [usize; 2] = [keep[0].0[0], keep[0].0[1]];
    let iv: Vec<Vec<Iv>> = keep
        .iter()
        .map(|(_, c)| {
            c.iter()
                .map(|q| {
                    let x = crate::scalar::rational_to_interval(q);
                    Iv::new(x.inf(), x.sup())
                })
                .collect()
        })
        .collect();
    let exact2: Vec<ExactEq> = keep.iter().map(|(_, c)| ExactEq::new(c)).collect();
    let coeffs2 = ExactCoeffs {
        deg: [deg2, deg2],
        eqs: &exact2,
    };
    let sys = GlobalSystem::<2>::new([deg2, deg2], &iv, Some(&coeffs2));
    let axes: Vec<usize> = (0..3).filter(|&a| a != k).collect();
    let proj: [[f64; 2]; 2] = [bx3[axes[0]], bx3[axes[1]]];
    let infl: [[f64; 2]; 2] = proj.map(|[lo, hi]| {
        let r = (hi - lo) + 1e-15 * (1.0 + lo.abs().max(hi.abs()));
        [lo - r, hi + r]
    });
    match sys.certify(infl) {
        Verdict::Unique(k2) if (0..2).all(|a| proj[a][0] <= k2[a][0] && k2[a][1] <= proj[a][1]) => {
            let mut out = bx3;
            out[k] = [e as f64; 2];
            out[axes[0]] = k2[0];
            out[axes[1]] = k2[1];
            OnBoundary::Inside(out)
        }
        _ => OnBoundary::Unknown,
    }
}

/// The face `x_d = end` of a tensor of any dimension (degrees `deg`): the
/// coefficients with `i_d = 0` (or `deg[d]`), with the remaining degrees.
fn face_nd<T: Clone>(c: &[T], deg: &[usize], d: usize, end: usize) -> (Vec<usize>, Vec<T>) {
    let idx = if end == 0 { 0 } else { deg[d] };
    let rest: Vec<usize> = (0..deg.len()).filter(|&a| a != d).map(|a| deg[a]).collect();
    let mut out = Vec::with_capacity(len_of(&rest));
    for (k, x) in c.iter().enumerate() {
        let (mut r, mut i_d) = (k, 0);
        for a in (0..deg.len()).rev() {
            if a == d {
                i_d = r % (deg[a] + 1);
            }
            r /= deg[a] + 1;
        }
        if i_d == idx {
            out.push(x.clone());
        }
    }
    (rest, out)
}

/// `p` in `(s, t, u, v)` rewritten in `(u, v, s, t)`.
pub(super) fn swap_pairs(p: &Poly) -> Poly {
    let deg = vec![p.deg[2], p.deg[3], p.deg[0], p.deg[1]];
    let mut c = vec![Iv::point(0.0); p.c.len()];
    let (a0, a1, a2, a3) = (p.deg[0] + 1, p.deg[1] + 1, p.deg[2] + 1, p.deg[3] + 1);
    for i in 0..a0 {
        for j in 0..a1 {
            for k in 0..a2 {
                for l in 0..a3 {
                    c[((k * a3 + l) * a0 + i) * a1 + j] = p.c[((i * a1 + j) * a2 + k) * a3 + l];
                }
            }
        }
    }
    Poly { deg, c }
}

/// The turning points: the first direction (`u`, `v`, `s`, `t`) whose
/// system is not degenerate.
fn turning_points(
    sys: &System,
    exact: Option<&ExactPair>,
    a: &[Poly; 4],
    b: &[Poly; 4],
    opts: &NdOptions,
    out: &mut Starts,
) {
    let residual: Option<Vec<ExactEq>> = exact.map(|e| e.residual.iter().map(|c| ExactEq::new(c)).collect());
    let f: [BernsteinNd<4>; 3] = std::array::from_fn(|e| BernsteinNd {
        deg: sys.degree(),
        c: sys.coeffs(e).to_vec(),
    });
    // u-turning points: the minor without column v, and so on.
    let candidates: [(bool, usize); 4] = [(true, 1), (true, 0), (false, 1), (false, 0)];
    let mut last = None;
    for (on_a, axis) in candidates {
        let d = if on_a {
            turning(a, b, axis)
        } else {
            swap_pairs(&turning(b, a, axis))
        };
        if d.is_zero() {
            continue;
        }
        // All four at common degrees, once: the solver's preconditioned
        // clips combine the equations, and would raise `F` to the degrees
        // of `D` on every box that stalls.
        let top: [usize; 4] = std::array::from_fn(|k| d.deg[k].max(sys.degree()[k]));
        let raise = |deg: &[usize], c: &[Iv]| BernsteinNd {
            deg: top,
            c: if deg == top { c.to_vec() } else { elevate(c, deg, &top) },
        };
        let eqs = [
            raise(&f[0].deg, &f[0].c),
            raise(&f[1].deg, &f[1].c),
            raise(&f[2].deg, &f[2].c),
            raise(&d.deg, &d.c),
        ];
        let values = match (exact, &residual) {
            (Some(e), Some(r)) => Some(TurningExact {
                residual: r,
                deg: sys.degree(),
                a: e.a,
                b: e.b,
                on_a,
                axis,
            }),
            _ => None,
        };
        match solve_nd_exact(&eqs, values.as_ref().map(|v| v as &dyn ExactValues<4>), opts) {
            Ok(sol) => {
                out.boxes += sol.stats.boxes;
                // A zero whose box reaches past the domain may lie outside
                // it: not a start point the tracer may use.
                for r in &sol.roots {
                    if r.bx.iter().all(|&[lo, hi]| 0.0 <= lo && hi <= 1.0) {
                        out.turning.push(r.bx);
                    } else {
                        out.undecided.push(r.bx);
                    }
                }
                out.undecided.extend(sol.undecided.iter().map(|u| u.bx));
                out.undecided.extend(sol.leftovers.iter().copied());
                return;
            }
            Err(e @ Error::Degenerate(_)) => last = Some(e),
            Err(e) => {
                last = Some(e);
                break;
            }
        }
    }
    out.degenerate.get_or_insert_with(|| {
        format!(
            "turning points: {}",
            last.map_or("every direction vanishes".into(), |e| e.to_string())
        )
    });
    out.undecided.push([[0.0, 1.0]; 4]);
}

/// Every start point (module docs).
pub(crate) fn find(sys: &System, exact: Option<&ExactPair>, a: &[Poly; 4], b: &[Poly; 4], opts: &NdOptions) -> Starts {
    let mut out = Starts::default();
    crossings(sys, exact.map(|e| &e.residual), opts, &mut out);
    if out.degenerate.is_none() {
        turning_points(sys, exact, a, b, opts, &mut out);
    }
    out
}
