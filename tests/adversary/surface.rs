//! A case's patch in exact arithmetic ([`Surface`]): its control data read
//! from the `PatchSpec` as rationals, its affine claim checked; its
//! Bernstein, triangle and B-spline sums evaluated exactly at rational
//! points (The NURBS Book A2.2 for the B-spline basis); its closed domain and
//! the knot lines and edges a hit can lie near.

use super::case::Case;
use super::exact::{nearest, qf, qi, sgn, Q};
use super::poly::Poly;
use rootclip::num_bigint::BigInt;
use rootclip::ray::PatchSpec;

pub(super) enum Kind {
    Tensor(usize, usize),
    Triangle(usize),
    Bspline {
        p: usize,
        q: usize,
        ku: Vec<Q>,
        kv: Vec<Q>,
        nu: usize,
        nv: usize,
    },
}

/// A case's patch as exact rationals: `x`, `z`, weights.
pub(super) struct Surface {
    pub(super) kind: Kind,
    x: Vec<Q>,
    z: Vec<Q>,
    pub(super) w: Option<Vec<Q>>,
    /// The parameter domain `[u0, u1] × [v0, v1]` (triangles: `u + v ≤ 1` too).
    pub(super) dom: [Q; 4],
}

fn binom(n: usize, k: usize) -> i64 {
    (0..k).fold(1i64, |acc, i| acc * (n - i) as i64 / (i + 1) as i64)
}

fn powq(x: &Q, k: usize) -> Q {
    (0..k).fold(qi(1), |acc, _| acc * x)
}

fn bernstein(n: usize, x: &Q) -> Vec<Q> {
    let y = qi(1) - x;
    (0..=n)
        .map(|i| qi(binom(n, i)) * powq(x, i) * powq(&y, n - i))
        .collect()
}

/// The `p + 1` B-spline basis functions of span `span` at `x` (the span's
/// polynomials, The NURBS Book A2.2), for `N_{span−p}, …, N_span`.
fn bspline_basis(k: &[Q], p: usize, span: usize, x: &Q) -> Vec<Q> {
    let mut n = vec![qi(0); p + 1];
    n[0] = qi(1);
    let (mut left, mut right) = (vec![qi(0); p + 1], vec![qi(0); p + 1]);
    for j in 1..=p {
        left[j] = x - &k[span + 1 - j];
        right[j] = &k[span + j] - x;
        let mut saved = qi(0);
        for r in 0..j {
            let temp = &n[r] / (&right[r + 1] + &left[j - r]);
            n[r] = &saved + &right[r + 1] * &temp;
            saved = &left[j - r] * &temp;
        }
        n[j] = saved;
    }
    n
}

/// The span `[k_a, k_{a+1})` (of positive length) holding `x`, clamped to the domain.
fn span_of(k: &[Q], p: usize, ncp: usize, x: &Q) -> usize {
    (p..ncp).rfind(|&a| k[a] < k[a + 1] && &k[a] <= x).unwrap_or(p)
}

/// The Greville abscissae `(k_{i+1} + … + k_{i+p}) / p`.
fn greville(k: &[Q], p: usize, ncp: usize) -> Vec<Q> {
    (0..ncp)
        .map(|i| k[i + 1..=i + p].iter().fold(qi(0), |a, x| a + x) / qi(p as i64))
        .collect()
}

impl Surface {
    /// The patch of `case`, its affine claim checked exactly.
    pub(super) fn of(case: &Case) -> Surface {
        let [a, x0, b, y0] = case.affine.map(qf);
        let check = |pt: &[f64; 3], u: &Q, v: &Q| {
            assert!(
                qf(pt[0]) == &x0 + &a * u && qf(pt[1]) == &y0 + &b * v,
                "adversary: the patch breaks its affine map at {pt:?}"
            );
        };
        let zs = |pts: &[[f64; 3]]| pts.iter().map(|p| qf(p[2])).collect::<Vec<_>>();
        let xs = |pts: &[[f64; 3]]| pts.iter().map(|p| qf(p[0])).collect::<Vec<_>>();
        let unit = [qi(0), qi(1), qi(0), qi(1)];
        match &case.spec {
            PatchSpec::Tensor {
                degree: [m, n],
                points,
                weights,
            } => {
                for i in 0..=*m {
                    for j in 0..=*n {
                        let ui = Q::new(BigInt::from(i), BigInt::from(*m));
                        let vj = Q::new(BigInt::from(j), BigInt::from(*n));
                        check(&points[i * (n + 1) + j], &ui, &vj);
                        if let Some(w) = weights {
                            assert!(w[i * (n + 1) + j] == w[i * (n + 1)], "adversary: weights must be α_i");
                        }
                    }
                }
                let w = weights.as_ref().map(|w| w.iter().map(|&x| qf(x)).collect());
                Surface {
                    kind: Kind::Tensor(*m, *n),
                    x: xs(points),
                    z: zs(points),
                    w,
                    dom: unit,
                }
            }
            PatchSpec::Triangle {
                degree,
                points,
                weights,
            } => {
                assert!(weights.is_none(), "adversary: rational triangles are not refereed");
                let n = *degree;
                let mut k = 0;
                for j in 0..=n {
                    for i in 0..=n - j {
                        let ui = Q::new(BigInt::from(i), BigInt::from(n));
                        let vj = Q::new(BigInt::from(j), BigInt::from(n));
                        check(&points[k], &ui, &vj);
                        k += 1;
                    }
                }
                Surface {
                    kind: Kind::Triangle(n),
                    x: xs(points),
                    z: zs(points),
                    w: None,
                    dom: unit,
                }
            }
            PatchSpec::Bspline {
                degree: [p, q],
                knots_u,
                knots_v,
                points,
                weights,
            } => {
                let ku: Vec<Q> = knots_u.iter().map(|&x| qf(x)).collect();
                let kv: Vec<Q> = knots_v.iter().map(|&x| qf(x)).collect();
                let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
                let (gu, gv) = (greville(&ku, *p, nu), greville(&kv, *q, nv));
                for i in 0..nu {
                    for j in 0..nv {
                        check(&points[i * nv + j], &gu[i], &gv[j]);
                        if let Some(w) = weights {
                            assert!(w[i * nv + j] == w[i * nv], "adversary: weights must be α_i");
                        }
                    }
                }
                let dom = [ku[*p].clone(), ku[nu].clone(), kv[*q].clone(), kv[nv].clone()];
                Surface {
                    kind: Kind::Bspline {
                        p: *p,
                        q: *q,
                        ku,
                        kv,
                        nu,
                        nv,
                    },
                    x: xs(points),
                    z: zs(points),
                    w: weights.as_ref().map(|w| w.iter().map(|&x| qf(x)).collect()),
                    dom,
                }
            }
            other => panic!("adversary: unknown patch {other:?}"),
        }
    }

    /// The degree of the height along a line, a bound.
    pub(super) fn line_degree(&self) -> usize {
        match &self.kind {
            Kind::Tensor(m, n) => m + n,
            Kind::Triangle(n) => *n,
            Kind::Bspline { p, q, .. } => p + q,
        }
    }

    /// The cell (B-spline spans) holding `(u, v)`.
    pub(super) fn cell_of(&self, u: &Q, v: &Q) -> (usize, usize) {
        match &self.kind {
            Kind::Bspline { p, q, ku, kv, nu, nv } => (span_of(ku, *p, *nu, u), span_of(kv, *q, *nv, v)),
            _ => (0, 0),
        }
    }

    /// `(Σ w x B, Σ w z B, Σ w B)` at `(u, v)`, with the polynomials of `cell`.
    pub(super) fn hom(&self, u: &Q, v: &Q, cell: (usize, usize)) -> [Q; 3] {
        let mut acc = [qi(0), qi(0), qi(0)];
        let mut add = |idx: usize, basis: Q| {
            let wb = match &self.w {
                Some(w) => &w[idx] * basis,
                None => basis,
            };
            acc[0] += &self.x[idx] * &wb;
            acc[1] += &self.z[idx] * &wb;
            acc[2] += wb;
        };
        match &self.kind {
            Kind::Tensor(m, n) => {
                let (bu, bv) = (bernstein(*m, u), bernstein(*n, v));
                for (i, bi) in bu.iter().enumerate() {
                    for (j, bj) in bv.iter().enumerate() {
                        add(i * (n + 1) + j, bi * bj);
                    }
                }
            }
            Kind::Triangle(n) => {
                let w = qi(1) - u - v;
                let mut k = 0;
                for j in 0..=*n {
                    for i in 0..=n - j {
                        let c = qi(binom(*n, i) * binom(n - i, j));
                        add(k, c * powq(u, i) * powq(v, j) * powq(&w, n - i - j));
                        k += 1;
                    }
                }
            }
            Kind::Bspline { p, q, ku, kv, nv, .. } => {
                let (bu, bv) = (bspline_basis(ku, *p, cell.0, u), bspline_basis(kv, *q, cell.1, v));
                for (r, nu_r) in bu.iter().enumerate() {
                    for (c, nv_c) in bv.iter().enumerate() {
                        add((cell.0 - p + r) * nv + (cell.1 - q + c), nu_r * nv_c);
                    }
                }
            }
        }
        acc
    }

    /// The height `z(u, v)`, exactly.
    pub(super) fn height(&self, u: &Q, v: &Q) -> Q {
        let [_, z, w] = self.hom(u, v, self.cell_of(u, v));
        z / w
    }

    /// Linear forms in `(u, v)` that are `≥ 0` exactly on the domain.
    pub(super) fn constraints(&self, u: &Poly, v: &Poly) -> Vec<Poly> {
        let [u0, u1, v0, v1] = &self.dom;
        let c = |x: &Q| Poly::constant(x.clone());
        let mut out = vec![u.sub(&c(u0)), c(u1).sub(u), v.sub(&c(v0)), c(v1).sub(v)];
        if matches!(self.kind, Kind::Triangle(_)) {
            out.push(c(&qi(1)).sub(u).sub(v));
        }
        out
    }

    /// `(u, v)` lies in the closed domain.
    pub(super) fn contains(&self, u: &Q, v: &Q) -> bool {
        self.constraints(&Poly::constant(u.clone()), &Poly::constant(v.clone()))
            .iter()
            .all(|c| c.0.first().map_or(0, sgn) >= 0)
    }

    /// The distance (in parameters, rounded) from `(u, v)` to the nearest
    /// edge or interior knot line.
    pub(super) fn feature_distance(&self, [u, v, _]: [f64; 3]) -> f64 {
        let (mut us, mut vs): (Vec<f64>, Vec<f64>) = (vec![0.0, 1.0], vec![0.0, 1.0]);
        if let Kind::Bspline { ku, kv, .. } = &self.kind {
            us = ku.iter().map(nearest).collect();
            vs = kv.iter().map(nearest).collect();
        }
        let d = |x: f64, cs: &[f64]| cs.iter().map(|c| (x - c).abs()).fold(f64::INFINITY, f64::min);
        let hyp = if matches!(self.kind, Kind::Triangle(_)) {
            (1.0 - u - v).abs()
        } else {
            f64::INFINITY
        };
        d(u, &us).min(d(v, &vs)).min(hyp)
    }

    /// The values of `s` at which the line crosses an interior knot line.
    pub(super) fn breaks(&self, u: &Poly, v: &Poly) -> Vec<Q> {
        let Kind::Bspline { ku, kv, .. } = &self.kind else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (line, knots, lo, hi) in [(u, ku, &self.dom[0], &self.dom[1]), (v, kv, &self.dom[2], &self.dom[3])] {
            if line.degree() == 1 {
                for k in knots.iter().filter(|k| *k > lo && *k < hi) {
                    out.push((k - &line.0[0]) / &line.0[1]);
                }
            }
        }
        out
    }
}
