//! The referee's own tests: Sturm counts and exact signs at isolated zeros,
//! rounding to the nearest float, hand-built grazing, tangent, triangle,
//! rational and crease cases whose hits are known by hand, a judge that
//! catches mutated answers, and generated cases of every family that are
//! valid and refereed.

use super::case::{Case, Family};
use super::exact::{nearest, qf, qi, sgn, Q};
use super::generate::generate;
use super::judge::{judge, judge_outcome, patch_and_ray, report, Fault};
use super::poly::Poly;
use super::restrict::{Line, TOfS};
use super::truth::{Piece, Root, Truth};
use rootclip::glam::DVec3;
use rootclip::num_bigint::BigInt;
use rootclip::ray::{intersect, Hit, HitBox, PatchSpec, RayOptions, RayOutcome, TensorPatch, TriPatch};
use std::time::Duration;

fn q(n: i64, d: i64) -> Q {
    Q::new(BigInt::from(n), BigInt::from(d))
}

fn count(p: &Poly, lo: Q, hi: Q) -> usize {
    Piece::new(lo.clone(), hi, p, TOfS::identity()).roots(0).len()
}

#[test]
fn sturm_counts_distinct_roots_in_closed_intervals() {
    let p = Poly::from_roots(&[qi(1), qi(2), qi(3)]);
    assert_eq!(count(&p, qi(0), qi(4)), 3);
    assert_eq!(count(&p, qi(1), qi(2)), 2);
    assert_eq!(count(&p, q(3, 2), q(5, 2)), 1);
    assert_eq!(count(&p, q(7, 2), qi(9)), 0);
    // Multiple roots count once.
    let p = Poly::from_roots(&[qi(1), qi(1), q(1, 3), q(1, 3), q(1, 3)]);
    assert_eq!(count(&p, qi(0), qi(1)), 2);
    // s² + 1 has no real root; s² − 2 two irrational ones.
    assert_eq!(count(&Poly::new(vec![qi(1), qi(0), qi(1)]), qi(-10), qi(10)), 0);
    let p = Poly::new(vec![qi(-2), qi(0), qi(1)]);
    assert_eq!(count(&p, qi(-2), qi(2)), 2);
    assert_eq!(count(&p, q(141, 100), q(142, 100)), 1);
    assert_eq!(count(&p, q(142, 100), qi(2)), 0);
    // Two roots 1e-30 apart are separated.
    let e = Q::new(BigInt::from(1), BigInt::from(10).pow(30));
    let p = Poly::from_roots(&[q(1, 2), q(1, 2) + e]);
    assert_eq!(count(&p, qi(0), qi(1)), 2);
}

#[test]
fn signs_at_isolated_roots_are_exact() {
    // √2 against floats just below and above it, and t = s² at √2 is 2.
    let p = Poly::new(vec![qi(-2), qi(0), qi(1)]);
    let t = Truth {
        line: Line {
            u: Poly::linear(qi(0), qi(1)),
            v: Poly::constant(qi(0)),
        },
        pieces: vec![Piece::new(
            qi(0),
            qi(2),
            &p,
            TOfS {
                num: Poly::new(vec![qi(0), qi(0), qi(1)]),
                den: Poly::constant(qi(1)),
            },
        )],
        roots: vec![],
        transversal: vec![],
        degenerate: false,
    };
    let r = &t.pieces[0].roots(0)[0];
    let s2 = std::f64::consts::SQRT_2;
    assert!(qf(s2) * qf(s2) > qi(2) && qf(s2.next_down()) * qf(s2.next_down()) < qi(2));
    let bx = |lo: f64, hi: f64| HitBox {
        u: [lo, hi],
        v: [0.0, 0.0],
        t: [0.0, 0.0],
    };
    assert!(!t.in_uv(r, &bx(s2, 2.0)));
    assert!(t.in_uv(r, &bx(s2.next_down(), 2.0)));
    assert!(t.in_uv(r, &bx(0.0, s2)));
    assert!(!t.in_uv(r, &bx(0.0, s2.next_down())));
    assert!(t.in_t(r, [2.0, 2.0]));
    assert!(!t.in_t(r, [2.0f64.next_up(), 3.0]));
}

#[test]
fn nearest_rounds_to_nearest_even() {
    assert_eq!(nearest(&q(1, 10)), 0.1);
    assert_eq!(nearest(&q(-1, 3)), -1.0 / 3.0);
    assert_eq!(nearest(&qf(5e-324)), 5e-324);
    assert_eq!(nearest(&(qf(5e-324) / qi(2))), 0.0);
    assert_eq!(nearest(&(qf(5e-324) * q(3, 2))), 1e-323);
    let half_ulp = qf(1.0) + qf(f64::EPSILON) / qi(2);
    assert_eq!(nearest(&half_ulp), 1.0);
    assert_eq!(
        nearest(&(qf(1.0) + qf(f64::EPSILON) * q(3, 2))),
        1.0 + 2.0 * f64::EPSILON
    );
    assert_eq!(nearest(&qf(1e300)), 1e300);
}

/// The hand-checked grazing case: the bilinear `z = c·u` over the unit
/// square (`c` the float 0.1) and horizontal rays along `x` at height
/// `oz`: a hit iff `0 ≤ oz ≤ c`, at `u = oz / c`. At `oz = c` the hit is
/// the edge `u = 1` exactly; one ulp above, none; one below, just inside.
#[test]
fn hand_built_grazing_tensor() {
    let c = 0.1;
    let pts = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, c], [1.0, 1.0, c]];
    let mk = |oz: f64, dir: [f64; 3], origin: [f64; 3]| Case {
        family: Family::Tensor,
        seed: 0,
        label: "hand".into(),
        spec: PatchSpec::Tensor {
            degree: [1, 1],
            points: pts.to_vec(),
            weights: None,
        },
        affine: [1.0, 0.0, 1.0, 0.0],
        origin: [origin[0], origin[1], if dir[2] == 0.0 { oz } else { origin[2] }],
        dir,
    };
    let horizontal = |oz: f64| mk(oz, [1.0, 0.0, 0.0], [-1.0, 0.5, 0.0]);
    let on_edge = Truth::of(&horizontal(c));
    assert_eq!(on_edge.roots.len(), 1);
    assert!(
        matches!(&on_edge.roots[0], Root::Exact(t) if *t == qi(2)),
        "{:?}",
        on_edge.roots
    );
    assert!(Truth::of(&horizontal(c.next_up())).roots.is_empty());
    let inside = Truth::of(&horizontal(c.next_down()));
    assert_eq!(inside.roots.len(), 1);
    let [u, v, t] = inside.uvt(&inside.roots[0], 120);
    assert!(u < 1.0 && (u - 1.0).abs() < 1e-15 && v == 0.5 && (t - 2.0).abs() < 1e-15);
    assert_eq!(Truth::of(&horizontal(0.0)).roots.len(), 1);
    assert!(Truth::of(&horizontal(-5e-324)).roots.is_empty());
    // Vertical rays on and just off the edge x = 1.
    let vertical = |x: f64| mk(0.0, [0.0, 0.0, -1.0], [x, 0.5, 1.0]);
    assert_eq!(Truth::of(&vertical(1.0)).roots.len(), 1);
    assert!(Truth::of(&vertical(1.0f64.next_up())).roots.is_empty());
    // And the library on all of them.
    for case in [
        horizontal(c),
        horizontal(c.next_up()),
        horizontal(c.next_down()),
        vertical(1.0),
    ] {
        let v = judge(&case);
        assert!(!v.fails(), "{}", report(&case, &v, "PATCH.json"));
    }
    assert!(TensorPatch::new(1, 1, pts.iter().map(|p| DVec3::from_array(*p)).collect(), None).is_ok());
}

/// `z = (u − ½)²` (bidegree (2, 1), heights ¼, −¼, ¼) and horizontal
/// rays along `x`: at `oz = 0` one double hit at `u = ½` (not
/// transversal); at `oz = 5e-324` two simple hits `±2^-537` from it; at
/// `oz = −5e-324` none. The library must certify neither side of the double
/// hit as a simple one.
#[test]
fn hand_built_tangency() {
    let mut points = Vec::new();
    for (i, z) in [0.25, -0.25, 0.25].into_iter().enumerate() {
        for j in 0..2 {
            points.push([i as f64 / 2.0, j as f64, z]);
        }
    }
    let case = |oz: f64| Case {
        family: Family::Tensor,
        seed: 0,
        label: "hand tangency".into(),
        spec: PatchSpec::Tensor {
            degree: [2, 1],
            points: points.clone(),
            weights: None,
        },
        affine: [1.0, 0.0, 1.0, 0.0],
        origin: [-1.0, 0.5, oz],
        dir: [1.0, 0.0, 0.0],
    };
    let double = Truth::of(&case(0.0));
    assert_eq!(double.roots.len(), 1);
    assert_eq!(double.approx(&double.roots[0], 60), q(3, 2));
    assert!(!double.transversal[0]);
    let split = Truth::of(&case(5e-324));
    assert_eq!(split.roots.len(), 2);
    assert!(split.transversal.iter().all(|x| *x));
    let gap = split.approx(&split.roots[0], 1200) - split.approx(&split.roots[1], 1200);
    let gap = nearest(&if sgn(&gap) < 0 { -gap } else { gap });
    assert!((gap / 2f64.powi(-536) - 1.0).abs() < 1e-9, "{gap:e}");
    assert!(Truth::of(&case(-5e-324)).roots.is_empty());
    for oz in [0.0, 5e-324, -5e-324] {
        let v = judge(&case(oz));
        assert!(!v.fails(), "{}", report(&case(oz), &v, "PATCH.json"));
    }
}

/// A degree-1 triangle `z = c·v` and a vertical ray onto its hypotenuse,
/// one ulp in and out; and a rational row whose hits are known.
#[test]
fn hand_built_triangle_and_rational() {
    let c = 0.3;
    let pts = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, c]];
    let tri = |x: f64, y: f64| Case {
        family: Family::Triangle,
        seed: 0,
        label: "hand".into(),
        spec: PatchSpec::Triangle {
            degree: 1,
            points: pts.clone(),
            weights: None,
        },
        affine: [1.0, 0.0, 1.0, 0.0],
        origin: [x, y, 1.0],
        dir: [0.0, 0.0, -1.0],
    };
    assert_eq!(Truth::of(&tri(0.25, 0.75)).roots.len(), 1);
    assert!(Truth::of(&tri(0.25f64.next_up(), 0.75)).roots.is_empty());
    assert_eq!(Truth::of(&tri(0.25f64.next_down(), 0.75)).roots.len(), 1);
    assert!(TriPatch::new(1, pts.iter().map(|p| DVec3::from_array(*p)).collect(), None).is_ok());
    // Rational (1, 1) with α = (1, 3): z = 3u / (1 + 2u) at the row
    // z = (0, 1); at oz = 1/2, u = 1/4 exactly (t from x = u: t = 1 + 1/4).
    let rat = Case {
        family: Family::Rational,
        seed: 0,
        label: "hand".into(),
        spec: PatchSpec::Tensor {
            degree: [1, 1],
            points: vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0]],
            weights: Some(vec![1.0, 1.0, 3.0, 3.0]),
        },
        affine: [1.0, 0.0, 1.0, 0.0],
        origin: [-1.0, 0.5, 0.5],
        dir: [1.0, 0.0, 0.0],
    };
    let truth = Truth::of(&rat);
    assert_eq!(truth.roots.len(), 1);
    let r = &truth.roots[0];
    assert_eq!(truth.approx(r, 200), q(1, 4));
    // x(u) = 3u / (1 + 2u) too: x(1/4) = 1/2, t = x − ox = 3/2.
    assert!(truth.in_t(r, [1.5, 1.5]) && !truth.in_t(r, [1.5f64.next_up(), 2.0]));
}

/// A biquadratic B-spline with a crease at u = 1 (knot of multiplicity 2):
/// the exact pieces meet on the crease, a zero there counts once.
#[test]
fn bspline_crease_zero_counts_once() {
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let (nu, nv) = (5, 3);
    let zu = [0.0, 0.5, 0.25, 0.5, 0.0];
    let mut points = Vec::new();
    for (i, z) in zu.iter().enumerate() {
        for j in 0..nv {
            let gx = (ku[i + 1] + ku[i + 2]) / 2.0;
            let gy = (kv[j + 1] + kv[j + 2]) / 2.0;
            points.push([gx, gy, *z]);
        }
    }
    assert_eq!(points.len(), nu * nv);
    // z on the crease u = 1 is the control value 0.25 (interpolated).
    let case = Case {
        family: Family::Bspline,
        seed: 0,
        label: "hand".into(),
        spec: PatchSpec::Bspline {
            degree: [2, 2],
            knots_u: ku,
            knots_v: kv,
            points,
            weights: None,
        },
        affine: [1.0, 0.0, 1.0, 0.0],
        origin: [1.0, 0.5, 1.0],
        dir: [0.0, 0.0, -1.0],
    };
    let t = Truth::of(&case);
    assert_eq!(t.roots.len(), 1);
    assert!(t.in_t(&t.roots[0], [0.75, 0.75]));
    // Horizontal along x at the crease height: z = u − 3u²/4 on [0, 1]
    // (and its mirror image on [1, 2]), a valley at the crease (z = 1/4,
    // rising to 1/3 on both sides): the ray touches the crease (t = 2)
    // and crosses at u = 1/3 and 5/3.
    let along = Case {
        origin: [-1.0, 0.5, 0.25],
        dir: [1.0, 0.0, 0.0],
        ..case
    };
    let t = Truth::of(&along);
    let crease = t.roots.iter().position(|r| matches!(r, Root::Exact(x) if *x == qi(2)));
    assert_eq!(t.roots.len(), 3, "{:?}", t.roots);
    // The touch is not a crossing; the other two are.
    assert_eq!(t.transversal.iter().filter(|x| **x).count(), 2);
    assert!(!t.transversal[crease.expect("a zero on the crease")]);
}

/// The judge can fail: the library's answers, mutated, draw each fault.
#[test]
fn judge_catches_mutated_answers() {
    let (mut multiple, mut phantom) = (false, false);
    for seed in 0..300 {
        let case = generate(Family::Tensor, seed);
        let truth = Truth::of(&case);
        let (patch, ray) = patch_and_ray(&case);
        let out = intersect(&patch, &ray, &RayOptions::default()).unwrap();
        let RayOutcome::Hits(h) = &out else { continue };
        let in_range = truth.roots.iter().any(|r| truth.in_t(r, [0.0, f64::INFINITY]));
        let Some(c) = h.hits.iter().position(Hit::is_certified) else {
            continue;
        };
        if !h.complete || !in_range {
            continue;
        }
        let faults = |f: &dyn Fn(&mut Vec<Hit>)| -> Vec<Fault> {
            let mut o = out.clone();
            if let RayOutcome::Hits(h) = &mut o {
                f(&mut h.hits);
            }
            let v = judge_outcome(&case, &truth, Ok(o), Duration::ZERO);
            v.faults.into_iter().map(|x| x.0).collect()
        };
        assert!(faults(&|_| {}).is_empty(), "{}", case.label);
        assert!(faults(&|h| h.clear()).contains(&Fault::Miss));
        assert!(faults(&|h| h.push(h[c].clone())).contains(&Fault::Duplicate));
        assert!(faults(&|h| h[c].bx.t = [h[c].bx.t[1] + 1.0, h[c].bx.t[1] + 2.0]).contains(&Fault::TBox));
        assert!(faults(&|h| h[c].u = -1e-300).contains(&Fault::Domain));
        let off = HitBox {
            u: [0.5, 0.5],
            v: [0.375, 0.375],
            t: h.hits[c].bx.t,
        };
        if truth.roots.iter().all(|r| !truth.in_uv(r, &off)) {
            assert!(faults(&|h| h[c].bx = off).contains(&Fault::Phantom));
            phantom = true;
        }
        if truth.roots.len() >= 2 {
            let all = HitBox {
                u: [0.0, 1.0],
                v: [0.0, 1.0],
                t: [0.0, 1e300],
            };
            assert!(faults(&|h| h[c].bx = all).contains(&Fault::Multiple));
            multiple = true;
        }
    }
    assert!(multiple && phantom);
}

/// The smallest certified crease touch: a biquadratic B-spline whose
/// height is `u − 3u²/4` on `[0, 1]`, mirrored on `[1, 2]` (a valley
/// crease at `u = 1`, `z = 1/4` there), and the horizontal ray at `z = 1/4`
/// along `x`: hits at `u = 1/3` and `5/3` cross the surface, the one at the
/// crease only touches it and must not be certified (a transversal hit
/// is promised). main at 87ca309 certified all three.
#[test]
fn crease_touch_is_not_certified() {
    let zs = [0.0, 0.5, 0.25, 0.5, 0.0];
    let points = (0..5)
        .flat_map(|i| (0..3).map(move |j| [i as f64 / 2.0, j as f64 / 2.0, zs[i]]))
        .collect();
    let case = Case {
        family: Family::Bspline,
        seed: 0,
        label: "hand crease touch".into(),
        spec: PatchSpec::Bspline {
            degree: [2, 2],
            knots_u: vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
            knots_v: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            points,
            weights: None,
        },
        affine: [1.0, 0.0, 1.0, 0.0],
        origin: [-1.0, 0.5, 0.25],
        dir: [1.0, 0.0, 0.0],
    };
    let truth = Truth::of(&case);
    assert_eq!(truth.roots.len(), 3);
    assert_eq!(truth.transversal.iter().filter(|x| !**x).count(), 1);
    let v = judge(&case);
    assert!(!v.fails(), "{}", report(&case, &v, "PATCH.json"));
}

/// Every family generates valid, refereed cases.
#[test]
fn generated_cases_are_valid() {
    for family in Family::ALL {
        for seed in 0..20 {
            let case = generate(family, seed);
            let _ = patch_and_ray(&case);
            let t = Truth::of(&case);
            assert!(!t.degenerate, "{}", case.label);
        }
    }
}
