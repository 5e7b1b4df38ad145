//! Krawczyk's operator in inari interval arithmetic on a system `(f, g)` of
//! any [`Bivariate`] polynomials (triangular and tensor BB): the
//! certification of the solvers' leaves, the probes of the triangle
//! iteration, and the merging of certified boxes.
//!
//! Everything is evaluated with outward rounding (inari), on the system's
//! interval coefficients, so the verdicts hold for every polynomial system in
//! the coefficient enclosures.

use super::verdict::{IBox, Verdict};
use crate::poly::{Direction, TensorBezier, TriBezier};
use crate::scalar::geo::{Geo, GeoIv};
use crate::scalar::point;
use crate::solve::linalg::inverse2;
use inari::Interval;

/// A bivariate polynomial the Krawczyk operator can work on: evaluated in
/// interval arithmetic anywhere in the plane (it extends beyond its domain),
/// with its partial derivatives as polynomials of the same kind.
pub trait Bivariate: Clone {
    /// An enclosure of the range over the box `u × v`.
    fn value(&self, u: Interval, v: Interval) -> Interval;
    /// `[∂/∂u, ∂/∂v]`.
    fn partials(&self) -> [Self; 2];
    /// The same polynomial with its coefficients' midpoints, in `f64`.
    type Mid: Clone + std::fmt::Debug;
    /// [`Bivariate::Mid`] of `self`.
    fn mid(&self) -> Self::Mid;
    /// The midpoint polynomial's value at `(u, v)`, in `f64` (no bound).
    fn mid_value(p: &Self::Mid, u: f64, v: f64) -> f64;
}

impl Bivariate for TriBezier<Interval> {
    fn value(&self, u: Interval, v: Interval) -> Interval {
        self.eval(u, v)
    }
    fn partials(&self) -> [Self; 2] {
        [self.deriv_u(), self.deriv_v()]
    }
    type Mid = TriBezier<f64>;
    fn mid(&self) -> TriBezier<f64> {
        self.map(|c| c.mid())
    }
    fn mid_value(p: &TriBezier<f64>, u: f64, v: f64) -> f64 {
        p.eval(u, v)
    }
}

impl Bivariate for TensorBezier<Interval> {
    fn value(&self, u: Interval, v: Interval) -> Interval {
        self.eval(u, v)
    }
    fn partials(&self) -> [Self; 2] {
        [self.deriv(Direction::U), self.deriv(Direction::V)]
    }
    type Mid = TensorBezier<f64>;
    fn mid(&self) -> TensorBezier<f64> {
        self.map(|c| c.mid())
    }
    fn mid_value(p: &TensorBezier<f64>, u: f64, v: f64) -> f64 {
        p.eval(u, v)
    }
}

/// One Krawczyk step: the verdict, `K(X)` itself when it could be computed,
/// the Jacobian enclosure it used, and its rounding floor (the widest side
/// of the enclosure of `Y·F(x̃)`, which every `K` around the root includes).
struct Step {
    verdict: Verdict,
    raw: Option<IBox>,
    jac: Option<[GeoIv; 4]>,
    floor: f64,
}

/// The system `F = (f, g)` with its Jacobian, as BB polynomials in the
/// coordinates the boxes are given in (triangular polynomials are evaluated by
/// de Casteljau at barycentric `(u, v, 1 − u − v)`, tensor ones row by row;
/// both extend beyond their domain).
#[derive(Clone, Debug)]
pub struct System<P: Bivariate = TriBezier<Interval>> {
    f: P,
    g: P,
    jac: [P; 4],
    /// The Jacobian's entries with midpoint coefficients: the
    /// preconditioner `Y` only has to be some real matrix near `F'(x̃)⁻¹`.
    jac_mid: [P::Mid; 4],
    /// `f` and `g` with midpoint coefficients, for the `f64` Newton steps of
    /// [`System::contract`].
    value_mid: [P::Mid; 2],
}

impl<P: Bivariate> System<P> {
    /// The system `(f, g)`.
    pub fn new(f: P, g: P) -> Self {
        let [fu, fv] = f.partials();
        let [gu, gv] = g.partials();
        let jac = [fu, fv, gu, gv];
        Self {
            value_mid: [f.mid(), g.mid()],
            f,
            g,
            jac_mid: jac.each_ref().map(P::mid),
            jac,
        }
    }

    fn eval(p: &P, x: IBox) -> Interval {
        p.value(x[0], x[1])
    }

    /// `F(x)` enclosed.
    pub fn value(&self, x: IBox) -> [Interval; 2] {
        [Self::eval(&self.f, x), Self::eval(&self.g, x)]
    }

    /// One Krawczyk step on `x`.
    pub fn krawczyk(&self, x: IBox) -> Verdict {
        self.step(x, None).0
    }

    /// [`System::krawczyk`], with `K(X)` itself (not intersected with `X`)
    /// when it could be computed.
    ///
    /// `jac`, when given, is an enclosure of the Jacobian over a box that
    /// contains `x` (the box a proof started from): any enclosure over `x`
    /// makes `K` valid, a wider one only widens it, and for the tiny boxes
    /// of the contraction the difference is far below their width.
    fn step(&self, x: IBox, jac: Option<[GeoIv; 4]>) -> (Verdict, Option<IBox>) {
        let s = self.step_jac(x, jac);
        (s.verdict, s.raw)
    }

    /// [`System::step`], with the Jacobian enclosure it used and its
    /// rounding floor.
    fn step_jac(&self, x: IBox, jac: Option<[GeoIv; 4]>) -> Step {
        let mid = [x[0].mid(), x[1].mid()];
        let undecided = |jac| Step {
            verdict: Verdict::Undecided(x),
            raw: None,
            jac,
            floor: f64::INFINITY,
        };
        if !(mid[0].is_finite() && mid[1].is_finite()) {
            return undecided(None);
        }
        let xm = [point(mid[0]), point(mid[1])];
        // The arithmetic of K in GeoIv: inari's endpoints without its
        // rounding-mode switch per operation.
        let fx = self.value(xm).map(GeoIv::of);
        let j = jac.unwrap_or_else(|| self.jac.each_ref().map(|p| GeoIv::of(Self::eval(p, x))));
        let jm = self.jac_mid.each_ref().map(|p| P::mid_value(p, mid[0], mid[1]));
        let Some(y) = inverse2(jm, 1e-14) else {
            return undecided(Some(j));
        };
        let y = y.map(GeoIv::pt);
        // K = x̃ − Y F(x̃) + (I − Y J) (X − x̃)
        let yf = [y[0] * fx[0] + y[1] * fx[1], y[2] * fx[0] + y[3] * fx[1]];
        let one = GeoIv::pt(1.0);
        let m = [
            one - (y[0] * j[0] + y[1] * j[2]),
            -(y[0] * j[1] + y[1] * j[3]),
            -(y[2] * j[0] + y[3] * j[2]),
            one - (y[2] * j[1] + y[3] * j[3]),
        ];
        let xg = [GeoIv::of(x[0]), GeoIv::of(x[1])];
        let mg = [GeoIv::pt(mid[0]), GeoIv::pt(mid[1])];
        let d = [xg[0] - mg[0], xg[1] - mg[1]];
        let k = [
            mg[0] - yf[0] + m[0] * d[0] + m[1] * d[1],
            mg[1] - yf[1] + m[2] * d[0] + m[3] * d[1],
        ]
        .map(|c| crate::scalar::interval(c.lower(), c.upper()));
        if k.iter().any(|c| c.is_empty()) {
            return undecided(Some(j));
        }
        let verdict = if k[0].interior(x[0]) && k[1].interior(x[1]) {
            Verdict::Unique(k)
        } else {
            let meet = [k[0].intersection(x[0]), k[1].intersection(x[1])];
            if meet[0].is_empty() || meet[1].is_empty() {
                Verdict::NoRoot
            } else {
                Verdict::Undecided(meet)
            }
        };
        Step {
            verdict,
            raw: Some(k),
            jac: Some(j),
            floor: yf.iter().map(|c| c.upper() - c.lower()).fold(0.0, f64::max),
        }
    }

    /// Tries to prove that the box `x0` holds exactly one root, by Krawczyk
    /// with epsilon-inflation: every box tried contains `x0`, so on success all
    /// roots in `x0` are the one root. On success returns the contracted box
    /// (iterated `K` until it stops shrinking), which holds that root.
    pub fn certify(&self, x0: IBox) -> Verdict {
        self.certify_within(x0, 10)
    }

    /// [`System::certify`] with at most `rounds` Krawczyk steps of
    /// epsilon-inflation before it gives up (`Undecided`): a quick probe of a
    /// box during the iteration, where giving up only costs further clips,
    /// while the final certification of a leaf tries hard.
    pub fn certify_within(&self, x0: IBox, rounds: usize) -> Verdict {
        // A leaf at the iteration's end can be a few ulps wide, below
        // Krawczyk's rounding floor; start from at least `FLOOR_ULPS` ulps
        // (any box containing `x0` proves the same), not from rounds of
        // inflation that each cost a step.
        let mut x = x0.map(|c| {
            let x = inflate(c, 0.1);
            let min = FLOOR_ULPS * f64::EPSILON * c.mag().max(1.0);
            if x.wid() >= min {
                x
            } else {
                let m = c.mid();
                crate::scalar::interval((m - 0.5 * min).min(c.inf()), (m + 0.5 * min).max(c.sup()))
            }
        });
        for _ in 0..rounds {
            let Step {
                verdict,
                raw,
                jac,
                floor,
            } = self.step_jac(x, None);
            match verdict {
                // Within twice the width of `Y·F(x̃)`'s enclosure (the
                // rounding of `F` at the midpoint, amplified by the inverse
                // Jacobian, which every `K` near the root contains), a
                // narrower proven box would win a factor 2 at most: an
                // ill-conditioned root, whose floor is far above the jump's
                // 32 ulps; the jump and further steps are skipped.
                Verdict::Unique(k) if width(k) <= 2.0 * floor => return Verdict::Unique(k),
                Verdict::Unique(k) => return Verdict::Unique(self.contract(k, jac)),
                Verdict::NoRoot => return Verdict::NoRoot,
                Verdict::Undecided(meet) => {
                    // Grow around the hull of K(X) and the original box,
                    // doubling it: an ill-conditioned root (condition c) needs
                    // a box about c times the rounding of F before K(X) fits
                    // inside. K(X) itself, not K(X) ∩ X: the intersection never
                    // leaves X, so the box could only triple per step and a
                    // leaf at eps (1e-15 wide) never reached the 1e-9 that a
                    // root of condition 1e7 needs. K(X) is capped at `x0`
                    // ± 1e-6 (relative beyond 1), which keeps a wild K(X) from
                    // swallowing other roots.
                    let raw = raw.unwrap_or(meet);
                    x = [0, 1].map(|i| {
                        let cap = 1e-6 * x0[i].mag().max(1.0);
                        let reach = crate::scalar::interval(x0[i].inf() - cap, x0[i].sup() + cap);
                        let grown = raw[i].intersection(reach);
                        let grown = if grown.is_empty() { meet[i] } else { grown };
                        inflate(grown.convex_hull(x0[i]), 1.0)
                    });
                }
            }
        }
        Verdict::Undecided(x)
    }

    /// Narrows the enclosure `k` of the one root of a box `x ⊃ k`: first by
    /// [`System::newton_jump`], else by Krawczyk steps until they stop
    /// halving the width.
    ///
    /// `jac` encloses the Jacobian over a box containing `k` (see
    /// [`System::step`]).
    fn contract(&self, mut k: IBox, jac: Option<[GeoIv; 4]>) -> IBox {
        // Already at the rounding floor (the usual final certification of a
        // leaf at eps, from a box ~1024 ulps wide: K(X) is a few ulps): the
        // jump's 32-ulp box cannot fit inside, and a further step wins an
        // ulp at most.
        if at_rounding_floor(k) {
            return k;
        }
        if let Some(b) = self.newton_jump(k, jac) {
            return b;
        }
        // The fallback iterates with fresh Jacobians: its quadratic
        // convergence needs them.
        for _ in 0..8 {
            match self.step(k, None).0 {
                Verdict::Unique(next) if width(next) < width(k) => {
                    // Quadratic convergence halves the width many times over
                    // per step; a step that does not halve it has reached
                    // the rounding floor, and further steps win ulps.
                    let halved = width(next) <= 0.5 * width(k);
                    k = next;
                    // A box a few ulps wide is at the floor already: the next
                    // step could not halve it (saves that step's evaluations).
                    if !halved || at_rounding_floor(k) {
                        break;
                    }
                }
                _ => break,
            }
        }
        k
    }

    /// The root in `k`, where `k` lies in a box proven to hold exactly one
    /// root: `f64` Newton steps on the midpoint system from `mid k`, then one
    /// Krawczyk step on a box `B ⊂ k` a few ulps wide around the result.
    /// `K(B) ⊂ int B` proves a root in `B`, which is then *the* root, and
    /// `K(B)` encloses it. Quadratic convergence in `f64` costs a few cheap
    /// evaluations where the interval iteration from `k` (about `1e-4` wide
    /// after a probe) needs three Krawczyk steps. `None` (the caller iterates
    /// Krawczyk instead) when Newton leaves `k` or `B` is not proven.
    fn newton_jump(&self, k: IBox, jac: Option<[GeoIv; 4]>) -> Option<IBox> {
        let mut x = [k[0].mid(), k[1].mid()];
        for _ in 0..4 {
            let f = self.value_mid.each_ref().map(|p| P::mid_value(p, x[0], x[1]));
            let j = self.jac_mid.each_ref().map(|p| P::mid_value(p, x[0], x[1]));
            let y = inverse2(j, 1e-14)?;
            let dx = [y[0] * f[0] + y[1] * f[1], y[2] * f[0] + y[3] * f[1]];
            x = [x[0] - dx[0], x[1] - dx[1]];
            if !(x[0].is_finite() && x[1].is_finite()) {
                return None;
            }
            // Converged to rounding: a further step moves by ulps at most.
            if dx
                .iter()
                .zip(&x)
                .all(|(d, c)| d.abs() <= 4.0 * f64::EPSILON * c.abs().max(1.0))
            {
                break;
            }
        }
        // 32 ulps of the coordinate (of 1 near 0), then 10⁴ times that for a
        // root whose rounding is amplified by a poor condition.
        for ulps in [32.0, 3.2e5] {
            let b = x.map(|c| {
                let r = ulps * f64::EPSILON * c.abs().max(1.0);
                crate::scalar::interval((c - r).next_down(), (c + r).next_up())
            });
            if !(b[0].subset(k[0]) && b[1].subset(k[1])) {
                return None;
            }
            if let Verdict::Unique(kb) = self.step(b, jac).0 {
                return Some(kb);
            }
        }
        None
    }
}

/// The narrowest box side, in ulps of its coordinate (and of 1), that
/// [`System::certify_within`] starts from: well above the rounding floor of
/// a well-conditioned root (16 ulps), and still ~2e-13 wide.
const FLOOR_ULPS: f64 = 1024.0;

/// Each side of `x` is at most 16 ulps of its largest coordinate (and of 1)
/// wide: Krawczyk's rounding floor for a well-conditioned root.
fn at_rounding_floor(x: IBox) -> bool {
    x.iter().all(|c| c.wid() <= 16.0 * f64::EPSILON * c.mag().max(1.0))
}

/// The larger side of a box.
pub fn width(x: IBox) -> f64 {
    x[0].wid().max(x[1].wid())
}

/// `x` widened by `rel` of its width plus a few ulps on each side.
pub(super) fn inflate(x: Interval, rel: f64) -> Interval {
    let r = rel * x.wid() + 4.0 * f64::EPSILON * x.mag().max(f64::MIN_POSITIVE);
    crate::scalar::interval((x.inf() - r).next_down(), (x.sup() + r).next_up())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_polynomial;
    use crate::scalar::{interval, Scalar};
    use num_rational::BigRational;

    fn system(f: &str, g: &str) -> System {
        let conv = |s: &str| parse_polynomial(s).unwrap().to_triangle(3).map(Interval::from_rational);
        System::new(conv(f), conv(g))
    }

    fn holds(x: Interval, q: &BigRational) -> bool {
        let r = |v: f64| BigRational::from_float(v).unwrap();
        r(x.inf()) <= *q && *q <= r(x.sup())
    }

    /// The root (1/3, 1/7) is not a float: the certified box must still hold
    /// it exactly, be a few ulps wide (the Newton jump), and lie in the box
    /// the first Krawczyk step proved.
    #[test]
    fn certified_box_holds_the_exact_root_and_is_tight() {
        let sys = system("(3*u - 1)*(u + 1) + (7*v - 1)^3", "7*v - 1 + (3*u - 1)*v^2");
        let (u, v) = (
            BigRational::new(1.into(), 3.into()),
            BigRational::new(1.into(), 7.into()),
        );
        // A box of a probe's size (interval de Casteljau overestimates the
        // Jacobian on wide boxes: the cube's coefficients reach 343).
        let x0 = [interval(0.330, 0.337), interval(0.140, 0.146)];
        let verdict = sys.certify(x0);
        let Verdict::Unique(k) = verdict else {
            panic!("simple root not certified: {verdict:?}")
        };
        assert!(holds(k[0], &u) && holds(k[1], &v), "{k:?}");
        assert!(width(k) < 1e-14, "{k:?}");
        let Verdict::Unique(first) = sys.krawczyk(x0.map(|c| inflate(c, 0.1))) else {
            panic!("first step")
        };
        assert!(k[0].subset(first[0]) && k[1].subset(first[1]));
    }

    /// A jump is refused when Newton leaves the enclosure: here `k` holds
    /// the root 0.5 of the first equation's factor but Newton is started
    /// from a box around the other root's basin.
    #[test]
    fn newton_jump_stays_inside_the_enclosure() {
        let sys = system("(2*u - 1)*(4*u - 3)", "v - 1/4");
        // k around u = 0.75 … 0.8: Newton from 0.775 goes to 0.75, inside.
        let k = [interval(0.74, 0.81), interval(0.2, 0.3)];
        let b = sys.newton_jump(k, None).expect("root 0.75 inside k");
        assert!(b[0].contains(0.75) && b[1].contains(0.25));
        // k = [0.6, 0.7] holds no root; the jump must not report one outside.
        assert!(sys
            .newton_jump([interval(0.6, 0.7), interval(0.2, 0.3)], None)
            .is_none());
    }
}
