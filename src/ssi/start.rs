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
use super::system::{Box4, System};
use crate::error::Error;
use crate::scalar::iv::Iv;
use crate::solve::nd::clip::elevate;
use crate::solve::nd::tensor::len_of;
use crate::solve::nd::{solve_nd, BernsteinNd, NdOptions};

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
fn face(c: &[Iv], deg: &[usize; 4], d: usize, end: usize) -> ([usize; 3], Vec<Iv>) {
    let rest = super::system::others(d);
    let deg3 = rest.map(|a| deg[a]);
    let idx = if end == 0 { 0 } else { deg[d] };
    let mut out = Vec::with_capacity(len_of(&deg3));
    for (k, &x) in c.iter().enumerate() {
        let mut r = k;
        let mut i = [0usize; 4];
        for a in (0..4).rev() {
            i[a] = r % (deg[a] + 1);
            r /= deg[a] + 1;
        }
        if i[d] == idx {
            out.push(x);
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

/// The crossings of `C` with the 8 faces.
fn crossings(sys: &System, opts: &NdOptions, out: &mut Starts) {
    let deg = sys.degree();
    for d in 0..4 {
        for end in [0, 1] {
            let eqs: [BernsteinNd<3>; 3] = std::array::from_fn(|e| {
                let (deg3, c) = face(sys.coeffs(e), &deg, d, end);
                BernsteinNd { deg: deg3, c }
            });
            let res = solve_nd(&eqs, opts);
            match res {
                Ok(sol) => {
                    out.boxes += sol.stats.boxes;
                    for r in &sol.roots {
                        let b = lift(&r.bx, d, end);
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

/// `p` in `(s, t, u, v)` rewritten in `(u, v, s, t)`.
fn swap_pairs(p: &Poly) -> Poly {
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
fn turning_points(sys: &System, a: &[Poly; 4], b: &[Poly; 4], opts: &NdOptions, out: &mut Starts) {
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
        match solve_nd(&eqs, opts) {
            Ok(sol) => {
                out.boxes += sol.stats.boxes;
                out.turning.extend(sol.roots.iter().map(|r| r.bx));
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
pub(crate) fn find(sys: &System, a: &[Poly; 4], b: &[Poly; 4], opts: &NdOptions) -> Starts {
    let mut out = Starts::default();
    crossings(sys, opts, &mut out);
    if out.degenerate.is_none() {
        turning_points(sys, a, b, opts, &mut out);
    }
    out
}
