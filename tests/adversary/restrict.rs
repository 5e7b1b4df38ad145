//! The ray's line restricted to the patch, exactly ([`restrict`]): the
//! closed interval of the line parameter `s` on which the line is in the
//! domain, cut where it crosses interior knot lines, and on each piece the
//! polynomial whose zeros are the hits, found by exact evaluation at rational
//! points and interpolation. `s = t` on polynomial patches; on rational ones
//! (rays with `dy = 0`) `s = u`, and `t` is a rational function of `u` per
//! knot span ([`TOfS`]).

use super::case::Case;
use super::exact::{qf, qi, sgn, Q};
use super::poly::Poly;
use super::surface::{Kind, Surface};
use rootclip::num_bigint::BigInt;

/// The line `s ↦ (u(s), v(s))` in the parameter domain.
#[derive(Clone, Debug)]
pub struct Line {
    pub u: Poly,
    pub v: Poly,
}

/// `t(s) = num(s) / den(s)` on a piece, `den > 0` there.
#[derive(Clone, Debug)]
pub struct TOfS {
    pub num: Poly,
    pub den: Poly,
}

impl TOfS {
    /// `t = s`.
    pub(super) fn identity() -> TOfS {
        TOfS {
            num: Poly::linear(qi(0), qi(1)),
            den: Poly::constant(qi(1)),
        }
    }
}

/// One piece of a [`Restriction`]: `[lo, hi]`, the polynomial whose zeros
/// there are the hits, and `t` there.
#[derive(Clone, Debug)]
pub struct RPiece {
    pub lo: Q,
    pub hi: Q,
    pub p: Poly,
    pub t: TOfS,
}

/// The closed interval of `s` on which every form is `≥ 0` (`None`: empty;
/// an end `None`: unbounded).
fn clip(forms: &[Poly]) -> Option<(Option<Q>, Option<Q>)> {
    let (mut lo, mut hi): (Option<Q>, Option<Q>) = (None, None);
    for f in forms {
        match f.degree() {
            0 => {
                if f.0.first().map_or(0, sgn) < 0 {
                    return None;
                }
            }
            _ => {
                let r = -&f.0[0] / &f.0[1];
                if sgn(&f.0[1]) > 0 {
                    lo = Some(lo.map_or(r.clone(), |l| l.max(r)));
                } else {
                    hi = Some(hi.map_or(r.clone(), |h| h.min(r)));
                }
            }
        }
    }
    match (&lo, &hi) {
        (Some(l), Some(h)) if l > h => None,
        _ => Some((lo, hi)),
    }
}

/// The polynomial through `(xs[i], ys[i])` (Newton's divided differences).
fn interpolate(xs: &[Q], ys: &[Q]) -> Poly {
    let n = xs.len();
    let mut c = ys.to_vec();
    for j in 1..n {
        for i in (j..n).rev() {
            c[i] = (&c[i] - &c[i - 1]) / (&xs[i] - &xs[i - j]);
        }
    }
    let mut p = Poly::constant(c[n - 1].clone());
    for i in (0..n - 1).rev() {
        p = p.mul(&Poly::linear(-&xs[i], qi(1))).add(&Poly::constant(c[i].clone()));
    }
    p
}

/// `deg + 1` points strictly inside `[lo, hi]` (`lo < hi`).
fn samples(lo: &Q, hi: &Q, deg: usize) -> Vec<Q> {
    (0..=deg)
        .map(|i| lo + (hi - lo) * Q::new(BigInt::from(i + 1), BigInt::from(deg + 2)))
        .collect()
}

/// The ray's line restricted to the patch: consecutive closed pieces of the
/// line parameter, on each the exact polynomial whose zeros are the hits
/// (the B-spline's cells, a single piece for Bézier patches).
pub struct Restriction {
    pub line: Line,
    pub pieces: Vec<RPiece>,
}

/// See [`Restriction`] and the module docs.
pub fn restrict(case: &Case) -> Restriction {
    let surf = Surface::of(case);
    let [ox, oy, oz] = case.origin.map(qf);
    let [dx, dy, dz] = case.dir.map(qf);
    let [a, x0, b, y0] = case.affine.map(qf);
    if surf.w.is_some() {
        return restrict_rational(&surf, case);
    }
    // s = t: u(t), v(t) affine.
    let line = Line {
        u: Poly::linear((&ox - &x0) / &a, &dx / &a),
        v: Poly::linear((&oy - &y0) / &b, &dy / &b),
    };
    let piece = |lo: Q, hi: Q, p: Poly| RPiece {
        lo,
        hi,
        p,
        t: TOfS::identity(),
    };
    let deg = surf.line_degree() + 1;
    let on_cell = |s: &Q, cell: (usize, usize)| {
        let [_, z, w] = surf.hom(&line.u.eval(s), &line.v.eval(s), cell);
        z / w - &oz - &dz * s
    };
    let cell_at = |s: &Q| surf.cell_of(&line.u.eval(s), &line.v.eval(s));
    let fit = |lo: &Q, hi: &Q| {
        let cell = cell_at(&((lo + hi) / qi(2)));
        let xs = samples(lo, hi, deg);
        let ys: Vec<Q> = xs.iter().map(|s| on_cell(s, cell)).collect();
        interpolate(&xs, &ys)
    };
    let mut pieces = Vec::new();
    match clip(&surf.constraints(&line.u, &line.v)) {
        None => {}
        Some((Some(lo), Some(hi))) => {
            let mut cuts: Vec<Q> = surf
                .breaks(&line.u, &line.v)
                .into_iter()
                .filter(|s| *s > lo && *s < hi)
                .collect();
            cuts.push(lo.clone());
            cuts.push(hi.clone());
            cuts.sort();
            cuts.dedup();
            if lo == hi {
                // The line touches the domain at one point: the piece is
                // that point, its polynomial the cell's there.
                let cell = cell_at(&lo);
                let xs = samples(&lo, &(&lo + qi(1)), deg);
                let ys: Vec<Q> = xs.iter().map(|s| on_cell(s, cell)).collect();
                pieces.push(piece(lo.clone(), lo, interpolate(&xs, &ys)));
            }
            for w in cuts.windows(2) {
                pieces.push(piece(w[0].clone(), w[1].clone(), fit(&w[0], &w[1])));
            }
        }
        Some(_) => {
            // A vertical ray: u, v constant, the line meets the patch at one
            // point for every t; its zero is bounded by Cauchy's bound.
            assert!(line.u.degree() == 0 && line.v.degree() == 0, "a bounded domain");
            let p = fit(&qi(-1), &qi(1));
            let bound = if p.is_zero() { qi(1) } else { p.cauchy_bound() };
            pieces.push(piece(-&bound, bound, p));
        }
    }
    Restriction { line, pieces }
}

/// A rational tensor or NURBS patch (`w_ij = α_i`) and a ray with `dy = 0`:
/// `s = u`, `v = v*`, hits the zeros of `dx·(N_z − oz·D) − dz·(N_x − ox·D)`
/// (per knot span in `u`), `t = (x − ox)/dx` (or `(z − oz)/dz` for `dx = 0`).
fn restrict_rational(surf: &Surface, case: &Case) -> Restriction {
    let [ox, oy, oz] = case.origin.map(qf);
    let [dx, dy, dz] = case.dir.map(qf);
    let [_, _, b, y0] = case.affine.map(qf);
    assert!(sgn(&dy) == 0, "adversary: rays on rational patches need dy = 0");
    let vstar = (&oy - &y0) / &b;
    let line = Line {
        u: Poly::linear(qi(0), qi(1)),
        v: Poly::constant(vstar.clone()),
    };
    let [u0, u1, v0, v1] = &surf.dom;
    if vstar < *v0 || vstar > *v1 {
        return Restriction {
            line,
            pieces: Vec::new(),
        };
    }
    let (deg, knots) = match &surf.kind {
        Kind::Tensor(m, _) => (*m, Vec::new()),
        Kind::Bspline { p, ku, .. } => (*p, ku.iter().filter(|k| *k > u0 && *k < u1).cloned().collect()),
        Kind::Triangle(_) => panic!("adversary: rational triangles are not refereed"),
    };
    let mut cuts = knots;
    cuts.push(u0.clone());
    cuts.push(u1.clone());
    cuts.sort();
    cuts.dedup();
    // t = num / den, den > 0 (flip both for a negative dx, or dz when dx = 0).
    let flip = if sgn(&dx) < 0 || (sgn(&dx) == 0 && sgn(&dz) < 0) {
        qi(-1)
    } else {
        qi(1)
    };
    let pieces = cuts
        .windows(2)
        .map(|w| {
            let cell = surf.cell_of(&((&w[0] + &w[1]) / qi(2)), &vstar);
            let xs = samples(&w[0], &w[1], deg);
            let rows: Vec<[Q; 3]> = xs.iter().map(|u| surf.hom(u, &vstar, cell)).collect();
            let fit = |f: &dyn Fn(&[Q; 3]) -> Q| interpolate(&xs, &rows.iter().map(f).collect::<Vec<_>>());
            let p = fit(&|[nx, nz, d]| &dx * (nz - &oz * d) - &dz * (nx - &ox * d));
            let t = if sgn(&dx) != 0 {
                TOfS {
                    num: fit(&|[nx, _, d]| &flip * (nx - &ox * d)),
                    den: fit(&|[_, _, d]| &flip * &dx * d),
                }
            } else {
                TOfS {
                    num: fit(&|[_, nz, d]| &flip * (nz - &oz * d)),
                    den: fit(&|[_, _, d]| &flip * &dz * d),
                }
            };
            RPiece {
                lo: w[0].clone(),
                hi: w[1].clone(),
                p,
                t,
            }
        })
        .collect();
    Restriction { line, pieces }
}
