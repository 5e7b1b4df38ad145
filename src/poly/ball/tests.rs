//! The ball kernels against exact rational arithmetic.

use super::*;
use num_traits::Signed;

fn q(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

use crate::rng::Rng;

/// Every exact coefficient of `exact` lies in the ball.
fn contains(ball: &TriBall, exact: &[BigRational]) -> bool {
    exact.iter().enumerate().all(|(i, e)| {
        let (lo, hi) = ball.bounds(i);
        q(lo) <= *e && *e <= q(hi)
    })
}

fn exact_of(b: &TriBall) -> TriBezier<BigRational> {
    TriBezier::new(b.degree(), b.mid().iter().map(|&m| q(m)).collect()).unwrap()
}

/// Subdivision encloses the exact blossoms of the midpoint polynomial
/// (vertices inside, on the edges of and slightly outside the triangle;
/// the `w` coordinate is not a float), and the radius is a few ulps.
#[test]
fn subdivision_encloses_exact_blossoms() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    for case in 0..300 {
        let n = 1 + case % 7;
        let mid: Vec<f64> = (0..tri_len(n))
            .map(|_| rng.next_signed() * [1.0, 1e-3, 7.0][case % 3])
            .collect();
        let ball = TriBall::new(n, &mid, 0.0).unwrap();
        let mut vert = || {
            let s = 0.5 + 0.55 * rng.next_signed();
            let t = (0.5 + 0.55 * rng.next_signed()) * (1.0 - s).max(0.0);
            [s, t]
        };
        let verts = [vert(), vert(), vert()];
        let sub = ball.subdivide(&verts);
        let exact = exact_of(&ball);
        let bary = verts.map(|[s, t]| {
            let (s, t) = (q(s), q(t));
            let w = q(1.0) - &s - &t;
            [s, t, w]
        });
        let want = exact.subdivide(&bary);
        assert!(contains(&sub, want.coeffs()), "case {case}");
        assert!(
            sub.rad() < 100.0 * n as f64 * U * ball.max_mid() * 4.0,
            "case {case}: {}",
            sub.rad()
        );
    }
}

/// Compensated subdivision encloses the exact blossoms of the exact
/// input, with a radius of a few ulps of the *result's* coefficients
/// (plus ~1e-30 of the input's), on tiny tri-boxes next to a zero of the
/// polynomial, where the float ball's radius is ulps of the input's.
#[test]
fn compensated_subdivision_is_tight_and_rigorous() {
    let mut rng = Rng(0x5eed_0000_1111_2222);
    let third = BigRational::new(1.into(), 3.into());
    for case in 0..200 {
        let n = 1 + case % 6;
        // Exact coefficients that are not floats, around a zero at the centre.
        let exact: Vec<BigRational> = (0..tri_len(n)).map(|_| q(rng.next_signed()) * &third).collect();
        let p0 = TriBezier::new(n, exact).unwrap();
        let centre = [0.3 + 0.1 * rng.next_signed(), 0.2 + 0.1 * rng.next_signed()];
        let bc = [q(centre[0]), q(centre[1]), q(1.0) - q(centre[0]) - q(centre[1])];
        let value = p0.eval_bary(&bc);
        let p = TriBezier::new(n, p0.coeffs().iter().map(|c| c - &value).collect()).unwrap();
        let dd = TriBallDD::from_rationals(n, p.coeffs());
        let h = [1e-3, 1e-9, 1e-14][case % 3];
        let verts = [
            [centre[0] + h, centre[1]],
            [centre[0], centre[1] + h],
            [centre[0] - h, centre[1] - 0.5 * h],
        ];
        let sub = dd.subdivide(&verts);
        let bary = verts.map(|[s, t]| [q(s), q(t), q(1.0) - q(s) - q(t)]);
        let want = p.subdivide(&bary);
        assert!(contains(&sub, want.coeffs()), "case {case}");
        // Tight: a few ulps of the result plus ~u² of the input.
        let local = sub.max_mid();
        assert!(
            sub.rad() <= 4.0 * U * local + 1e-29,
            "case {case}: rad {:e}, local {local:e}",
            sub.rad()
        );
        let float = TriBall::enclose_rationals(n, p.coeffs()).subdivide(&verts);
        assert!(contains(&float, want.coeffs()), "case {case}");
    }
}

/// The input radius is carried through subdivision.
#[test]
fn subdivision_carries_the_radius() {
    let ball = TriBall::new(2, &[0.5, -0.25, 1.0, 0.125, 0.0, -1.0], 1e-6).unwrap();
    let sub = ball.subdivide(&[[0.5, 0.25], [0.25, 0.5], [0.25, 0.25]]);
    assert!(sub.rad() >= 1e-6 && sub.rad() < 1e-6 + 1e-14);
    // The ball's extreme members subdivide into the result.
    for sign in [-1.0, 1.0] {
        let shifted: Vec<BigRational> = ball.mid().iter().map(|&m| q(m) + q(sign * 1e-6)).collect();
        let p = TriBezier::new(2, shifted).unwrap();
        let bary = [[0.5, 0.25], [0.25, 0.5], [0.25, 0.25]].map(|[s, t]| {
            let (s, t) = (q(s), q(t));
            let w = q(1.0) - &s - &t;
            [s, t, w]
        });
        assert!(contains(&sub, p.subdivide(&bary).coeffs()));
    }
}

/// `δ` bounds the exact distance between each coefficient of the ball's
/// extreme members and the approximant elevated exactly.
#[test]
fn reduction_bound_is_rigorous() {
    let mut rng = Rng(0xdead_beef_1234_5678);
    for case in 0..200 {
        let n = 1 + case % 6;
        let k = 1 + case % 2;
        let mid: Vec<f64> = (0..tri_len(n)).map(|_| rng.next_signed()).collect();
        let rad = if case % 3 == 0 {
            0.0
        } else {
            1e-9 * (rng.next_signed() + 1.0)
        };
        let ball = TriBall::new(n, &mid, rad).unwrap();
        let red = ball.reduce(k);
        assert_eq!(red.approx.len(), tri_len(k));
        let a = TriBezier::new(k, red.approx.iter().map(|&x| q(x)).collect()).unwrap();
        let top = n.max(k);
        let a_up = a.elevate(top).unwrap();
        let f_up = exact_of(&ball).elevate(top).unwrap();
        let worst = f_up
            .coeffs()
            .iter()
            .zip(a_up.coeffs())
            .map(|(f, e)| Signed::abs(&(f - e)) + q(rad))
            .fold(q(0.0), |m, x| if x > m { x } else { m });
        assert!(worst <= q(red.delta), "case {case}: {} > {}", worst, red.delta);
        if n > k && rad == 0.0 {
            // Not much more than the true distance.
            let w: f64 = num_traits::ToPrimitive::to_f64(&worst).unwrap();
            assert!(red.delta <= w * (1.0 + 1e-9) + 1e-13, "case {case}");
        }
    }
}

/// `linear_combination` and `combine` enclose the exact products.
#[test]
fn combinations_enclose_exact_results() {
    let mut rng = Rng(0x0bad_cafe_f00d_0001);
    for case in 0..200 {
        let n = 1 + case % 5;
        let p = TriBall::new(
            n,
            &(0..tri_len(n)).map(|_| rng.next_signed()).collect::<Vec<_>>(),
            1e-12,
        )
        .unwrap();
        let qb = TriBall::new(
            n,
            &(0..tri_len(n)).map(|_| rng.next_signed() * 3.0).collect::<Vec<_>>(),
            0.0,
        )
        .unwrap();
        let l = [rng.next_signed() * 5.0, rng.next_signed(), rng.next_signed() * 0.1];
        let m = [1.0 / 3.0, rng.next_signed(), 1.0];
        let out = TriBall::linear_combination(l, &p, m, &qb);
        let lin = |c: [f64; 3]| TriBezier::new(1, c.iter().map(|&x| q(x)).collect()).unwrap();
        for sign in [-1.0, 1.0] {
            let pe = TriBezier::new(n, p.mid().iter().map(|&x| q(x) + q(sign * 1e-12)).collect()).unwrap();
            let want = lin(l).mul(&pe).add(&lin(m).mul(&exact_of(&qb)));
            assert!(contains(&out, want.coeffs()), "case {case}");
        }
        let (a, b) = (rng.next_signed(), rng.next_signed() * 1e3);
        let c = TriBall::combine(a, &p, b, &qb);
        let want: Vec<BigRational> = exact_of(&p)
            .coeffs()
            .iter()
            .zip(exact_of(&qb).coeffs())
            .map(|(x, y)| q(a) * x + q(b) * y)
            .collect();
        // Members of p reach 1e-12 away from its midpoints.
        assert!(c.rad() >= a.abs() * 1e-12);
        assert!(contains(&c, &want), "case {case}");
    }
}

#[test]
fn signs_and_bounds() {
    let b = TriBall::new(1, &[1.0, 2.0, 0.5], 0.25).unwrap();
    assert_eq!(b.strict_sign(), Some(Sign::Positive));
    let b = TriBall::new(1, &[1.0, 2.0, 0.25], 0.25).unwrap();
    assert_eq!(b.strict_sign(), None);
    assert!(!b.sign_lost());
    let b = TriBall::new(1, &[1e-17, -1e-17, 0.0], 1e-16).unwrap();
    assert!(b.sign_lost());
    let (lo, hi) = TriBall::new(0, &[0.1], 0.1).unwrap().bounds(0);
    assert!(lo <= 0.0 && hi >= 0.2);
}

#[test]
fn enclosures_from_intervals_and_rationals() {
    let third = BigRational::new(1.into(), 3.into());
    let b = TriBall::enclose_rationals(0, std::slice::from_ref(&third));
    assert!(b.rad() > 0.0 && contains(&b, &[third]));
    let b = TriBall::enclose_rationals(0, &[q(0.5)]);
    assert_eq!(b.rad(), 0.0);
    let i = TriBezier::new(0, vec![crate::scalar::interval(0.1, 0.30000000000000004)]).unwrap();
    let b = TriBall::enclose(&i).unwrap();
    assert!(contains(&b, &[q(0.1)]) && contains(&b, &[q(0.30000000000000004)]));
}

#[test]
fn normalization_is_exact_and_keeps_signs() {
    let b = TriBall::new(1, &[3e200, -1e200, 5e-100], 1e190).unwrap();
    let e = TriBall::normalizing_exponent(&[&b]);
    let s = b.scaled_pow2(e);
    assert!(s.mag() >= 1.0 && s.mag() < 2.0 + 1e-15);
    assert_eq!(s.scaled_pow2(-e).mid(), b.mid());
    let tiny = TriBall::new(0, &[f64::from_bits(3)], 0.0).unwrap().scaled_pow2(-1);
    assert!(tiny.rad() > 0.0, "the underflow went into the radius");
    assert!(q(tiny.mid()[0]) - q(tiny.rad()) <= q(f64::from_bits(3)) / BigRational::from_integer(2.into()));
}

#[test]
fn jets_match_the_generic_kernel() {
    let p = TriBezier::from_fn(4, |i, j, k| (i as f64 - 0.3 * j as f64 + 0.1 * (k * k) as f64).sin());
    let b = TriBall::from_points(&p);
    let c = [0.2, 0.3, 0.5];
    let (v0, g0, h0) = p.jet2(&c);
    let (v1, g1, h1) = b.jet2(&c);
    assert!((v0 - v1).abs() < 1e-14);
    for i in 0..2 {
        assert!((g0[i] - g1[i]).abs() < 1e-12);
    }
    for i in 0..3 {
        assert!((h0[i] - h1[i]).abs() < 1e-11);
    }
}
