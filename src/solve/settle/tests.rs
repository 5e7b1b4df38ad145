use super::*;

/// `f = v + 2^-1074`, `g = u − ½` on the unit square (bilinear): the
/// root lies 2^-1074 below the edge `v = 0`; `v − 2^-1074` puts it above,
/// `v` on it.
#[test]
fn settles_roots_a_subnormal_away_from_an_edge() {
    let tiny = Q::from_float(f64::from_bits(1)).unwrap();
    let bilinear = |c: [Q; 4]| c.to_vec();
    let half = Q::new(1.into(), 2.into());
    let g = bilinear([-half.clone(), -half.clone(), half.clone(), half.clone()]);
    let bx = Box2 {
        u: [0.5 - 1e-15, 0.5 + 1e-15],
        v: [-1e-28, 1e-28],
    };
    for (shift, want) in [
        (tiny.clone(), Settled::Outside),
        (-tiny.clone(), Settled::Inside),
        (Q::zero(), Settled::Inside),
    ] {
        // v + shift at the corners (0,0), (0,1), (1,0), (1,1).
        let f = bilinear([shift.clone(), &shift + Q::one(), shift.clone(), &shift + Q::one()]);
        let sys = ExactSystem::new(Shape::Tensor(1, 1), f, g.clone(), None).unwrap();
        assert_eq!(sys.settle(bx), want, "shift {shift}");
    }
}

fn q(s: &str) -> Q {
    s.parse().unwrap()
}

/// Bidegree (2, 1): `p(u)` from its degree-2 Bernstein coefficients and
/// `r(v)` from its degree-1 ones, as tensor coefficients (row-major).
fn in_u(b: [&str; 3]) -> Vec<Q> {
    b.iter().flat_map(|x| [q(x), q(x)]).collect()
}
fn in_v(b: [&str; 2]) -> Vec<Q> {
    (0..3).flat_map(|_| b.map(q)).collect()
}

/// A sign condition that holds with equality at the root (`h = 0`: a ray
/// starting on the surface) is decided at once when the root is a
/// rational point, where it used to cost every refinement step with
/// rationals doubling in size each time (minutes).
#[test]
fn an_exact_zero_of_h_at_a_rational_root_is_decided() {
    let bx = Box2 {
        u: [0.5 - 1e-15, 0.5 + 1e-15],
        v: [0.25 - 1e-15, 0.25 + 1e-15],
    };
    // f = u − ½, g = v − ¼; h = u − ½ vanishes at the root: h ≥ 0 holds.
    let (f, g) = (in_u(["-1/2", "0", "1/2"]), in_v(["-1/4", "3/4"]));
    let sys = ExactSystem::new(Shape::Tensor(2, 1), f.clone(), g.clone(), Some(f.clone())).unwrap();
    assert_eq!(sys.settle(bx), Settled::Inside);
    // h = ½ − u + (v − ¼) − 2⁻⁷⁰: negative at the root, zero at nearby
    // points, never at the simplest ones: decided by contraction.
    let h: Vec<Q> = in_u(["1/2", "0", "-1/2"])
        .iter()
        .zip(&g)
        .map(|(a, b)| a + b - Q::new(1.into(), BigInt::one() << 70))
        .collect();
    let sys = ExactSystem::new(Shape::Tensor(2, 1), f, g, Some(h)).unwrap();
    assert_eq!(sys.settle(bx), Settled::Outside);
}

/// The simplest point of the box is tried as the root only where `f`
/// and `g` vanish there exactly: the root `½ + 2⁻⁶⁰` with `h = ½ − u`
/// (negative at the root, zero at ½, the box's simplest point) is
/// outside. A variant that takes the simplest point for the root without
/// that test says inside.
#[test]
fn the_simplest_point_is_the_root_only_if_it_is_a_root() {
    let eps = Q::new(1.into(), BigInt::one() << 60);
    let half = q("1/2");
    let f: Vec<Q> = in_u(["-1/2", "0", "1/2"]).iter().map(|c| c - &eps).collect();
    let g = in_v(["-1/4", "3/4"]);
    let h = in_u(["1/2", "0", "-1/2"]);
    let sys = ExactSystem::new(Shape::Tensor(2, 1), f, g, Some(h)).unwrap();
    let bx = Box2 {
        u: [0.5 - 1e-15, 0.5 + 1e-15],
        v: [0.25 - 1e-15, 0.25 + 1e-15],
    };
    assert_eq!(sys.settle(bx), Settled::Outside);
    assert!(sys
        .rational_root(&[RI::new(q("49/100"), q("51/100")), RI::point(q("1/4"))])
        .is_none());
    // eval_at against the rational evaluation, at points in and out.
    let (f, g) = (&sys.scaled().f[0], &sys.scaled().f[1]);
    for p in [[q("1/3"), q("-2/7")], [&half + &eps, q("1/4")], [q("5/4"), q("3")]] {
        let at = [RI::point(p[0].clone()), RI::point(p[1].clone())];
        let want = sys.value(&at);
        for (c, w) in [f, g].into_iter().zip(&want) {
            let got = eval_at(Shape::Tensor(2, 1), c, &p);
            let scale = Q::from_integer(p[0].denom().pow(2u32) * p[1].denom());
            assert_eq!(Q::from_integer(got), &w.lo * scale);
        }
    }
    assert_eq!(
        sys.rational_root(&[RI::new(&half + &eps, &half + &eps), RI::point(q("1/4"))]),
        Some([&half + &eps, q("1/4")])
    );
}

/// [`eval_at`] on a triangle: the scaled homogeneous value equals the
/// rational evaluation times `(bd)^n`.
#[test]
fn eval_at_on_a_triangle_matches_the_rational_evaluation() {
    let c: Vec<Q> = ["3", "-2", "5", "7", "-11", "1"].iter().map(|x| q(x)).collect();
    for p in [
        [q("1/3"), q("2/7")],
        [q("-1/2"), q("5/4")],
        [q("0"), q("1")],
        [q("3/8"), q("0")],
    ] {
        let at = [RI::point(p[0].clone()), RI::point(p[1].clone())];
        let want = eval(Shape::Triangle(2), &c, &at).lo;
        let scale = Q::from_integer((p[0].denom() * p[1].denom()).pow(2u32));
        assert_eq!(
            Q::from_integer(eval_at(Shape::Triangle(2), &c, &p)),
            want * scale,
            "{p:?}"
        );
    }
}

/// An irrational root at which `h` vanishes exactly (`u = 1/√2`,
/// `h = 2u² − 1`) cannot be decided by contraction: the refinement stops
/// at its width limit, undecided, instead of running on.
#[test]
fn an_exact_zero_at_an_irrational_root_ends_undecided() {
    let (f, g) = (in_u(["-1", "-1", "1"]), in_v(["-1/4", "3/4"]));
    let sys = ExactSystem::new(Shape::Tensor(2, 1), f.clone(), g, Some(f)).unwrap();
    let bx = Box2 {
        u: [
            std::f64::consts::FRAC_1_SQRT_2 - 4e-16,
            std::f64::consts::FRAC_1_SQRT_2 + 4e-16,
        ],
        v: [0.25 - 1e-15, 0.25 + 1e-15],
    };
    assert_eq!(sys.settle(bx), Settled::Undecided);
}

#[test]
fn simplest_points_by_hand() {
    let r = |a: &str, b: &str| simplest_rational(&q(a), &q(b)).unwrap();
    assert_eq!(r("33/100", "34/100"), q("1/3"));
    assert_eq!(r("1/2", "1/2"), q("1/2"));
    assert_eq!(r("-1/10", "1/5"), q("0"));
    assert_eq!(r("-34/100", "-33/100"), q("-1/3"));
    assert_eq!(r("22/10", "23/10"), q("9/4"));
    assert_eq!(r("7/5", "7/5"), q("7/5"));
    let d = |a: &str, b: &str| simplest_dyadic(&q(a), &q(b));
    assert_eq!(d("3/10", "4/10"), q("3/8"));
    assert_eq!(d("1/3", "1/3"), q("1/3"));
    assert_eq!(d("5/8", "5/8"), q("5/8"));
    assert_eq!(d("-3/10", "-1/10"), q("-1/4"));
    assert_eq!(d("2", "3"), q("2"));
    // Every answer lies in its interval and nothing simpler does, over
    // a grid of small intervals (checked by brute force).
    for a in 0..40i64 {
        for w in 0..12i64 {
            let (lo, hi) = (Q::new(a.into(), 37.into()), Q::new((a + w).into(), 37.into()));
            let s = simplest_rational(&lo, &hi).unwrap();
            assert!(lo <= s && s <= hi);
            let within = |x: Q| lo <= x && x <= hi;
            let best = (1..=37i64)
                .find(|&den| (0..=2 * den).any(|num| within(Q::new(num.into(), den.into()))))
                .unwrap();
            assert_eq!(s.denom(), &BigInt::from(best), "[{lo}, {hi}]");
            let s = simplest_dyadic(&lo, &hi);
            assert!(lo <= s && s <= hi);
            if w == 0 {
                continue; // a/37: not a dyadic, its own simplest point
            }
            let k = (0..12u32)
                .find(|&k| (0..=2i64 << k).any(|num| within(Q::new(num.into(), (1i64 << k).into()))))
                .unwrap();
            assert_eq!(s.denom(), &BigInt::from(1i64 << k), "[{lo}, {hi}]");
        }
    }
}

#[test]
fn bernstein_to_power_matches_the_definition() {
    // 1·B0 + 3·B1 + 2·B2 = (1−s)² + 6 s (1−s) + 2 s² = 1 + 4 s − 3 s².
    let b: Vec<Q> = [1, 3, 2].iter().map(|&x| Q::from_integer(x.into())).collect();
    let p = bernstein_to_power(&b);
    let want: Vec<Q> = [1, 4, -3].iter().map(|&x| Q::from_integer(x.into())).collect();
    assert_eq!(p, want);
}

/// A double root at a rational point is found exactly (`f = (u − ½)²`,
/// `g = v − ¼`); a simple one (`f = u − ½`) and a double root at an
/// irrational point are not claimed.
#[test]
fn exact_multiple_roots_are_found_only_where_they_are() {
    let bx = Box2 {
        u: [0.5 - 1e-9, 0.5 + 1e-9],
        v: [0.25 - 1e-9, 0.25 + 1e-9],
    };
    let g = in_v(["-1/4", "3/4"]);
    // (u − ½)² in Bernstein form of degree 2: ¼, −¼, ¼.
    let double = ExactSystem::new(Shape::Tensor(2, 1), in_u(["1/4", "-1/4", "1/4"]), g.clone(), None).unwrap();
    assert!(double.holds_exact_multiple_root(bx));
    let simple = ExactSystem::new(Shape::Tensor(2, 1), in_u(["-1/2", "0", "1/2"]), g.clone(), None).unwrap();
    assert!(!simple.holds_exact_multiple_root(bx));
    // (u − ½)² − 2⁻⁸⁰ has two simple roots ½ ± 2⁻⁴⁰, none at the box's simplest points.
    let e = Q::new(1.into(), BigInt::one() << 80);
    let close: Vec<Q> = in_u(["1/4", "-1/4", "1/4"]).iter().map(|c| c - &e).collect();
    let close = ExactSystem::new(Shape::Tensor(2, 1), close, g, None).unwrap();
    assert!(!close.holds_exact_multiple_root(bx));
}
