//! Property tests of the Bernstein–Bézier algebra across its three kernels.
//!
//! Every property is checked against an independent exact computation written
//! in this file: the explicit Bernstein sums `Σ c_α C(n;α) u^i v^j w^k` (never
//! de Casteljau), factorial-based binomials, Dirichlet/Beta integrals for the
//! Gram matrices, hand differentiation of monomials. Rationals are small
//! (`n/d`, `|n| < 50`, `d < 20`) and points include many outside the unit
//! triangle, where the polynomials extend.
//!
//! Kernel contracts checked:
//! * `BigRational`: equal to the exact reference;
//! * `inari::Interval`: contains the exact value, and is not uselessly wide
//!   (containment alone would be met by the entire line);
//! * `f64`: within `1e-9 · max|c| · L^n` of the exact value, where `L` bounds
//!   the growth of a de Casteljau step at the point (`|u| + |v| + |w|`).

use inari::Interval;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::Config;
use rootclip::internals::interval_contains_rational;
use rootclip::internals::l2::{tri_gram, uni_gram};
use rootclip::poly::{tri_len, Direction, TensorBezier, TriBezier, UniBezier};
use rootclip::scalar::{rational_to_f64, rational_to_interval};
// `rootclip::Scalar` is named by path only: in scope, its `zero`/`one`/`abs`
// would clash with num-traits' on `BigRational`.
use rootclip::Polynomial;

type Q = BigRational;

// ---------------------------------------------------------------------------
// Independent exact reference
// ---------------------------------------------------------------------------

fn q(n: i64, d: i64) -> Q {
    Q::new(n.into(), d.into())
}

fn qi(n: usize) -> Q {
    Q::from_integer(BigInt::from(n))
}

fn fact(n: usize) -> BigInt {
    (1..=n).fold(BigInt::one(), |acc, t| acc * BigInt::from(t))
}

fn binom(n: usize, k: usize) -> BigInt {
    if k > n {
        BigInt::zero()
    } else {
        fact(n) / (fact(k) * fact(n - k))
    }
}

fn multinom(i: usize, j: usize, k: usize) -> BigInt {
    fact(i + j + k) / (fact(i) * fact(j) * fact(k))
}

fn pw(x: &Q, e: usize) -> Q {
    num_traits::pow(x.clone(), e)
}

/// `(i, j, k)` of degree `n` in the documented storage order: `j` outer, `i` inner.
fn indices(n: usize) -> Vec<(usize, usize, usize)> {
    (0..=n)
        .flat_map(|j| (0..=n - j).map(move |i| (i, j, n - i - j)))
        .collect()
}

/// `Σ f_ijk · n!/(i! j! k!) · u^i v^j w^k` — the definition, no de Casteljau.
fn tri_direct(coeffs: &[Q], n: usize, b: &[Q; 3]) -> Q {
    indices(n)
        .into_iter()
        .zip(coeffs)
        .map(|((i, j, k), c)| c * Q::from_integer(multinom(i, j, k)) * pw(&b[0], i) * pw(&b[1], j) * pw(&b[2], k))
        .sum()
}

fn tri_at(f: &TriBezier<Q>, b: &[Q; 3]) -> Q {
    tri_direct(f.coeffs(), f.degree(), b)
}

fn bern(n: usize, i: usize, t: &Q) -> Q {
    Q::from_integer(binom(n, i)) * pw(t, i) * pw(&(Q::one() - t), n - i)
}

fn uni_direct(c: &[Q], t: &Q) -> Q {
    let n = c.len() - 1;
    c.iter().enumerate().map(|(i, ci)| ci * bern(n, i, t)).sum()
}

fn local(x: &Q, dom: &[Q; 2]) -> Q {
    (x - &dom[0]) / (&dom[1] - &dom[0])
}

/// `Σ f_ij B^m_i(s) B^n_j(t)` at domain point `(u, v)`.
fn tensor_at(f: &TensorBezier<Q>, u: &Q, v: &Q) -> Q {
    let (m, n) = f.degree();
    let (du, dv) = f.domain();
    let (s, t) = (local(u, du), local(v, dv));
    let mut acc = Q::zero();
    for i in 0..=m {
        for j in 0..=n {
            acc += &f.coeffs()[i * (n + 1) + j] * bern(m, i, &s) * bern(n, j, &t);
        }
    }
    acc
}

fn bary(u: &Q, v: &Q) -> [Q; 3] {
    [u.clone(), v.clone(), Q::one() - u - v]
}

/// `b0·V1 + b1·V2 + b2·V3`, componentwise.
fn map_bary(b: &[Q; 3], verts: &[[Q; 3]; 3]) -> [Q; 3] {
    std::array::from_fn(|c| &b[0] * &verts[0][c] + &b[1] * &verts[1][c] + &b[2] * &verts[2][c])
}

fn max_abs(c: &[Q]) -> f64 {
    c.iter().map(|x| rational_to_f64(&x.abs())).fold(0.0, f64::max)
}

fn l1(b: &[Q; 3]) -> f64 {
    b.iter().map(|x| rational_to_f64(&x.abs())).sum()
}

fn exact(x: f64) -> Q {
    Q::from_float(x).expect("finite float")
}

fn iv(x: &Q) -> Interval {
    rational_to_interval(x)
}

fn fl(x: &Q) -> f64 {
    rational_to_f64(x)
}

fn tri_iv(f: &TriBezier<Q>) -> TriBezier<Interval> {
    f.map(<Interval as rootclip::Scalar>::from_rational)
}

fn tri_fl(f: &TriBezier<Q>) -> TriBezier<f64> {
    f.map(<f64 as rootclip::Scalar>::from_rational)
}

fn uni_in<S: rootclip::Scalar>(f: &UniBezier<Q>) -> UniBezier<S> {
    let c = f.coeffs().iter().map(S::from_rational).collect();
    let d = f.domain();
    UniBezier::new(c, [S::from_rational(&d[0]), S::from_rational(&d[1])]).expect("valid domain")
}

/// The interval contains `exact` and is at most `tol` wide.
fn encloses(x: Interval, exact: &Q, tol: f64) -> std::result::Result<(), TestCaseError> {
    prop_assert!(
        interval_contains_rational(x, exact),
        "[{:e}, {:e}] misses {exact}",
        x.inf(),
        x.sup()
    );
    prop_assert!(
        x.sup() - x.inf() <= tol,
        "[{:e}, {:e}] wider than {tol:e}",
        x.inf(),
        x.sup()
    );
    Ok(())
}

fn encloses_all(x: &[Interval], exact: &[Q], tol: f64) -> std::result::Result<(), TestCaseError> {
    prop_assert_eq!(x.len(), exact.len());
    for (a, b) in x.iter().zip(exact) {
        encloses(*a, b, tol)?;
    }
    Ok(())
}

fn close(x: f64, want: &Q, tol: f64) -> std::result::Result<(), TestCaseError> {
    prop_assert!(x.is_finite());
    let err = fl(&(exact(x) - want).abs());
    prop_assert!(err <= tol, "{x:e} vs {want}: error {err:e} > {tol:e}");
    Ok(())
}

// ---------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------

fn cfg(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

fn rat() -> impl Strategy<Value = Q> {
    (-50i64..50, 1i64..20).prop_map(|(n, d)| q(n, d))
}

/// A point `(u, v)`: half inside the unit triangle, half anywhere in `[-4, 6]²`.
fn point() -> impl Strategy<Value = (Q, Q)> {
    prop_oneof![
        (0i64..20, 0i64..20, 1i64..20).prop_map(|(a, b, c)| (q(a, a + b + c), q(b, a + b + c))),
        (-40i64..=60, 10i64..=20, -40i64..=60, 10i64..=20).prop_map(|(a, b, c, d)| (q(a, b), q(c, d))),
    ]
}

/// A point inside the closed unit triangle.
fn inside() -> impl Strategy<Value = (Q, Q)> {
    (0i64..20, 0i64..20, 0i64..20).prop_map(|(a, b, c)| {
        let s = (a + b + c).max(1);
        (q(a, s), q(b, s))
    })
}

fn tri_of(n: usize) -> impl Strategy<Value = TriBezier<Q>> {
    vec(rat(), tri_len(n)).prop_map(move |c| TriBezier::new(n, c).expect("right count"))
}

fn tri_poly(lo: usize, hi: usize) -> impl Strategy<Value = TriBezier<Q>> {
    (lo..=hi).prop_flat_map(tri_of)
}

/// `[a, a + len]` with `a ∈ [-8, 8]`, `len ∈ [1/4, 8]`.
fn domain() -> impl Strategy<Value = [Q; 2]> {
    (-8i64..=8, 1i64..=4, 1i64..=8, 1i64..=4).prop_map(|(a, da, l, dl)| {
        let a = q(a, da);
        let b = &a + q(l, dl);
        [a, b]
    })
}

fn uni_poly(lo: usize, hi: usize) -> impl Strategy<Value = UniBezier<Q>> {
    (lo..=hi)
        .prop_flat_map(|n| (vec(rat(), n + 1), domain()))
        .prop_map(|(c, d)| UniBezier::new(c, d).expect("valid"))
}

fn tensor_poly(hi: usize, unit: bool) -> impl Strategy<Value = TensorBezier<Q>> {
    (0..=hi, 0..=hi)
        .prop_flat_map(|(m, n)| (Just(m), Just(n), vec(rat(), (m + 1) * (n + 1)), domain(), domain()))
        .prop_map(move |(m, n, c, du, dv)| {
            if unit {
                TensorBezier::on_unit_square(m, n, c).expect("valid")
            } else {
                TensorBezier::new(m, n, c, du, dv).expect("valid")
            }
        })
}

/// A coordinate for points on a line of the domain: `[-6, 6]`.
fn coord() -> impl Strategy<Value = Q> {
    (-60i64..=60, 10i64..=20).prop_map(|(n, d)| q(n, d))
}

/// Sub-triangle vertices in barycentric coordinates: generic, with a repeated
/// vertex, or collinear.
fn sub_triangle() -> impl Strategy<Value = [[Q; 3]; 3]> {
    let vert = || (-20i64..=40, 1i64..=20, -20i64..=40, 1i64..=20).prop_map(|(a, b, c, d)| bary(&q(a, b), &q(c, d)));
    (vert(), vert(), vert(), 0..4u8).prop_map(|(a, b, c, kind)| match kind {
        0 => [a.clone(), a, c],
        1 => {
            let two = qi(2);
            let col = std::array::from_fn(|t| &two * &b[t] - &a[t]);
            [a, b, col]
        }
        _ => [a, b, c],
    })
}

fn polynomial(max_deg: u32) -> impl Strategy<Value = Polynomial> {
    vec((0..=max_deg, 0..=max_deg, rat()), 0..8).prop_map(move |terms| {
        terms
            .into_iter()
            .filter(|(a, b, _)| a + b <= max_deg)
            .fold(Polynomial::zero(), |p, (a, b, c)| p.add(&Polynomial::monomial(c, a, b)))
    })
}

// ---------------------------------------------------------------------------
// 1. Cross-kernel evaluation and operations
// ---------------------------------------------------------------------------

proptest! {
    #![proptest_config(cfg(192))]

    #[test]
    fn tri_eval_agrees_across_kernels(f in tri_poly(0, 8), (u, v) in point()) {
        let n = f.degree();
        let b = bary(&u, &v);
        let want = tri_at(&f, &b);
        prop_assert_eq!(f.eval_bary(&b), want.clone());
        prop_assert_eq!(f.eval(u.clone(), v.clone()), want.clone());
        let scale = max_abs(f.coeffs()) * l1(&b).powi(n as i32);
        encloses(tri_iv(&f).eval(iv(&u), iv(&v)), &want, 1e-9 * scale)?;
        close(tri_fl(&f).eval(fl(&u), fl(&v)), &want, 1e-9 * scale)?;
    }

    /// `jet2` (de Casteljau down to the quadratic net) equals the value,
    /// gradient and Hessian from the derivative polynomials, exactly.
    #[test]
    fn tri_jet2_is_the_exact_taylor_data(f in tri_poly(0, 7), (u, v) in point()) {
        let b = bary(&u, &v);
        let (val, grad, hess) = f.jet2(&b);
        prop_assert_eq!(val, tri_at(&f, &b));
        prop_assert_eq!(&grad[0], &tri_at(&f.deriv_u(), &b));
        prop_assert_eq!(&grad[1], &tri_at(&f.deriv_v(), &b));
        let h = f.hessian();
        for (got, want) in hess.iter().zip(&h) {
            prop_assert_eq!(got, &tri_at(want, &b));
        }
    }

    #[test]
    fn uni_eval_agrees_across_kernels(f in uni_poly(0, 8), x in coord()) {
        let t = local(&x, f.domain());
        let want = uni_direct(f.coeffs(), &t);
        prop_assert_eq!(f.eval(x.clone()), want.clone());
        let growth = fl(&t.abs()) + fl(&(Q::one() - &t).abs());
        let scale = max_abs(f.coeffs()) * growth.powi(f.degree() as i32);
        encloses(uni_in::<Interval>(&f).eval(iv(&x)), &want, 1e-9 * scale)?;
        close(uni_in::<f64>(&f).eval(fl(&x)), &want, 1e-9 * scale)?;
    }

    #[test]
    fn tensor_eval_agrees_across_kernels(f in tensor_poly(4, false), u in coord(), v in coord()) {
        let want = tensor_at(&f, &u, &v);
        prop_assert_eq!(f.eval(u.clone(), v.clone()), want.clone());
        let (du, dv) = f.domain();
        let (s, t) = (local(&u, du), local(&v, dv));
        let g = |x: &Q| fl(&x.abs()) + fl(&(Q::one() - x).abs());
        let (m, n) = f.degree();
        let scale = max_abs(f.coeffs()) * g(&s).powi(m as i32) * g(&t).powi(n as i32);
        encloses(f.map(<Interval as rootclip::Scalar>::from_rational).eval(iv(&u), iv(&v)), &want, 1e-9 * scale)?;
        close(f.map(<f64 as rootclip::Scalar>::from_rational).eval(fl(&u), fl(&v)), &want, 1e-9 * scale)?;
    }
}

proptest! {
    #![proptest_config(cfg(64))]

    #[test]
    fn tri_interval_ops_enclose_exact(
        f in tri_poly(0, 8),
        g in tri_poly(0, 4),
        verts in sub_triangle(),
        up in 0usize..3,
    ) {
        let n = f.degree();
        let fi = tri_iv(&f);
        let big = max_abs(f.coeffs());

        let growth = verts.iter().map(l1).fold(1.0, f64::max);
        let vi = verts.clone().map(|v| v.map(|x| iv(&x)));
        let tol = 1e-9 * big * growth.powi(n as i32);
        encloses_all(fi.subdivide(&vi).coeffs(), f.subdivide(&verts).coeffs(), tol)?;

        for (pi, pq) in fi.split4().iter().zip(f.split4().iter()) {
            encloses_all(pi.coeffs(), pq.coeffs(), 1e-12 * big)?;
        }
        let e = f.elevate(n + up).unwrap();
        encloses_all(fi.elevate(n + up).unwrap().coeffs(), e.coeffs(), 1e-12 * big)?;
        encloses_all(fi.elevate_cached(n + up).coeffs(), e.coeffs(), 1e-12 * big)?;
        encloses_all(fi.deriv_u().coeffs(), f.deriv_u().coeffs(), 1e-12 * big * n as f64)?;
        encloses_all(fi.deriv_v().coeffs(), f.deriv_v().coeffs(), 1e-12 * big * n as f64)?;
        let prod_tol = 1e-12 * big * max_abs(g.coeffs());
        encloses_all(fi.mul(&tri_iv(&g)).coeffs(), f.mul(&g).coeffs(), prod_tol)?;
        // f64 agrees with the same scale of error.
        let ff = tri_fl(&f);
        for (x, want) in ff.elevate(n + up).unwrap().coeffs().iter().zip(e.coeffs()) {
            close(*x, want, 1e-12 * big)?;
        }
        for (x, want) in ff.deriv_u().coeffs().iter().zip(f.deriv_u().coeffs()) {
            close(*x, want, 1e-12 * big * n as f64)?;
        }
    }

    #[test]
    fn tri_reduce_l2_bounds_are_rigorous(f in tri_poly(1, 8), k_seed in 0usize..8, pts in vec(inside(), 4)) {
        let n = f.degree();
        let k = k_seed % n;
        let exact_red = f.reduce_l2(k).unwrap();
        let big = max_abs(f.coeffs()).max(1e-300);

        let red = tri_iv(&f).reduce_l2(k).unwrap();
        prop_assert_eq!(red.approx.degree(), k);
        // The approximant is a float polynomial: point intervals.
        let approx: Vec<Q> = red.approx.coeffs().iter().map(|c| {
            assert_eq!(c.inf(), c.sup(), "approximant coefficient is not a point");
            exact(c.inf())
        }).collect();
        let approx = TriBezier::new(k, approx).unwrap();
        let bound = exact(red.delta.sup());
        // Rigorous on the whole triangle: the exact coefficient distance …
        let elevated = approx.elevate(n).unwrap();
        let coeff_dist = f.coeffs().iter().zip(elevated.coeffs()).map(|(a, b)| (a - b).abs()).max().unwrap();
        prop_assert!(coeff_dist <= bound);
        // … hence at every sample point (vertices, centroid and random ones).
        let mut samples = pts;
        samples.extend([(q(0, 1), q(0, 1)), (q(1, 1), q(0, 1)), (q(0, 1), q(1, 1)), (q(1, 3), q(1, 3))]);
        for (u, v) in &samples {
            let b = bary(u, v);
            prop_assert!((tri_at(&f, &b) - tri_at(&approx, &b)).abs() <= bound);
        }
        // And not uselessly loose, in both float kernels.
        prop_assert!(fl(&(&bound - &exact_red.delta)) <= 1e-6 * big);
        for (a, b) in approx.coeffs().iter().zip(exact_red.approx.coeffs()) {
            prop_assert!(fl(&(a - b).abs()) <= 1e-6 * big);
        }
        let fred = tri_fl(&f).reduce_l2(k).unwrap();
        close(fred.delta, &exact_red.delta, 1e-6 * big)?;
        for (a, b) in fred.approx.coeffs().iter().zip(exact_red.approx.coeffs()) {
            close(*a, b, 1e-6 * big)?;
        }
    }

    #[test]
    fn uni_interval_ops_enclose_exact(f in uni_poly(0, 8), x_seed in 1i64..64, up in 0usize..3, k_seed in 0usize..8) {
        let n = f.degree();
        let fi = uni_in::<Interval>(&f);
        let big = max_abs(f.coeffs()).max(1e-300);
        let d = f.domain().clone();
        let x = &d[0] + (&d[1] - &d[0]) * q(x_seed, 64);
        let (lq, rq) = f.subdivide(x.clone()).unwrap();
        let (li, ri) = fi.subdivide(iv(&x)).unwrap();
        encloses_all(li.coeffs(), lq.coeffs(), 1e-12 * big)?;
        encloses_all(ri.coeffs(), rq.coeffs(), 1e-12 * big)?;
        prop_assert!(interval_contains_rational(li.domain()[1], &x));
        let e = f.elevate(n + up).unwrap();
        encloses_all(fi.elevate(n + up).unwrap().coeffs(), e.coeffs(), 1e-12 * big)?;
        let len = fl(&(&d[1] - &d[0]));
        encloses_all(fi.deriv().coeffs(), f.deriv().coeffs(), 1e-12 * big * (n as f64 + 1.0) / len)?;
        if n > 0 {
            let k = k_seed % n;
            let exact_red = f.reduce_l2(k).unwrap();
            let red = fi.reduce_l2(k).unwrap();
            let approx: Vec<Q> = red.approx.coeffs().iter().map(|c| exact(c.mid())).collect();
            prop_assert!(red.approx.coeffs().iter().all(|c| c.inf() == c.sup()));
            let elevated = UniBezier::new(approx.clone(), d.clone()).unwrap().elevate(n).unwrap();
            let bound = exact(red.delta.sup());
            for (a, b) in f.coeffs().iter().zip(elevated.coeffs()) {
                prop_assert!((a - b).abs() <= bound);
            }
            for t in [q(0, 1), q(1, 3), q(1, 2), q(7, 9), q(1, 1)] {
                prop_assert!((uni_direct(f.coeffs(), &t) - uni_direct(&approx, &t)).abs() <= bound);
            }
            prop_assert!(fl(&(&bound - &exact_red.delta)) <= 1e-6 * big);
        }
    }

    #[test]
    fn tensor_interval_ops_enclose_exact(
        f in tensor_poly(4, false),
        at in 1i64..64,
        up in (0usize..2, 0usize..2),
        kl in (0usize..5, 0usize..5),
    ) {
        let (m, n) = f.degree();
        let fi = f.map(<Interval as rootclip::Scalar>::from_rational);
        let big = max_abs(f.coeffs()).max(1e-300);
        for dir in [Direction::U, Direction::V] {
            let side = match dir { Direction::U => f.domain().0.clone(), Direction::V => f.domain().1.clone() };
            let x = &side[0] + (&side[1] - &side[0]) * q(at, 64);
            let (lq, hq) = f.subdivide(dir, x.clone()).unwrap();
            let (li, hi) = fi.subdivide(dir, iv(&x)).unwrap();
            encloses_all(li.coeffs(), lq.coeffs(), 1e-12 * big)?;
            encloses_all(hi.coeffs(), hq.coeffs(), 1e-12 * big)?;
            let len = fl(&(&side[1] - &side[0]));
            encloses_all(fi.deriv(dir).coeffs(), f.deriv(dir).coeffs(), 1e-12 * big * 5.0 / len)?;
        }
        let e = f.elevate(m + up.0, n + up.1).unwrap();
        encloses_all(fi.elevate(m + up.0, n + up.1).unwrap().coeffs(), e.coeffs(), 1e-12 * big)?;
        for (ti, tq) in fi.to_triangles().unwrap().iter().zip(f.to_triangles().unwrap().iter()) {
            encloses_all(ti.coeffs(), tq.coeffs(), 1e-12 * big)?;
        }
        let (k, l) = (kl.0.min(m), kl.1.min(n));
        if (k, l) != (m, n) {
            let exact_red = f.reduce_l2(k, l).unwrap();
            let red = fi.reduce_l2(k, l).unwrap();
            prop_assert!(red.approx.coeffs().iter().all(|c| c.inf() == c.sup()));
            let approx: Vec<Q> = red.approx.coeffs().iter().map(|c| exact(c.inf())).collect();
            let (du, dv) = f.domain();
            let approx = TensorBezier::new(k, l, approx, du.clone(), dv.clone()).unwrap();
            let bound = exact(red.delta.sup());
            for (a, b) in f.coeffs().iter().zip(approx.elevate(m, n).unwrap().coeffs()) {
                prop_assert!((a - b).abs() <= bound);
            }
            prop_assert!(fl(&(&bound - &exact_red.delta)) <= 1e-6 * big);
        }
    }
}

/// A wide interval around `c` (radius `c·r`-ish) and a rational member of it.
fn widened(c: &Q, r: &Q, t: &Q) -> (Interval, Q) {
    let x = iv(&(c - r)).convex_hull(iv(&(c + r)));
    (x, c + r * t)
}

/// `(centre, radius, position in [-1, 1])`: radius 0 (a point) a quarter of the time.
fn wide() -> impl Strategy<Value = (Q, Q, Q)> {
    (rat(), prop_oneof![Just(0i64), 1i64..40], -16i64..=16).prop_map(|(c, r, t)| (c, q(r, 64), q(t, 16)))
}

fn wide_tri(n: usize) -> impl Strategy<Value = (TriBezier<Interval>, TriBezier<Q>)> {
    vec(wide(), tri_len(n)).prop_map(move |v| {
        let (iv, member): (Vec<_>, Vec<_>) = v.iter().map(|(c, r, t)| widened(c, r, t)).unzip();
        (TriBezier::new(n, iv).unwrap(), TriBezier::new(n, member).unwrap())
    })
}

fn wide_bary() -> impl Strategy<Value = ([Interval; 3], [Q; 3])> {
    (point(), wide(), wide()).prop_map(|((u, v), (_, ru, tu), (_, rv, tv))| {
        let (ru, rv) = (ru * q(1, 8), rv * q(1, 8));
        let (iu, mu) = widened(&u, &ru, &tu);
        let (iv_, mv) = widened(&v, &rv, &tv);
        // w is enclosed on its own (as the solver's vertices are): an interval
        // around 1 − u − v wide enough for every member of iu and iv_.
        let (iw, _) = widened(&(Q::one() - &u - &v), &(ru + rv), &Q::zero());
        let mw = Q::one() - &mu - &mv;
        ([iu, iv_, iw], [mu, mv, mw])
    })
}

proptest! {
    #![proptest_config(cfg(64))]

    /// The rigorous-kernel contract for inputs with width: every result encloses
    /// the exact result for *every* member of the inputs (here, a random one).
    #[test]
    fn interval_kernel_encloses_every_member(
        (fi, fq) in (0usize..=7).prop_flat_map(wide_tri),
        (gi, gq) in (0usize..=3).prop_flat_map(wide_tri),
        verts in vec(wide_bary(), 3),
        (pi, pq) in wide_bary(),
    ) {
        let n = fq.degree();
        encloses(fi.eval_bary(&pi), &tri_at(&fq, &pq), f64::INFINITY)?;
        let vi: [[Interval; 3]; 3] = std::array::from_fn(|t| verts[t].0);
        let vq: [[Q; 3]; 3] = std::array::from_fn(|t| verts[t].1.clone());
        let inf = f64::INFINITY;
        encloses_all(fi.subdivide(&vi).coeffs(), fq.subdivide(&vq).coeffs(), inf)?;
        for (a, b) in fi.split4().iter().zip(fq.split4().iter()) {
            encloses_all(a.coeffs(), b.coeffs(), inf)?;
        }
        encloses_all(fi.mul(&gi).coeffs(), fq.mul(&gq).coeffs(), inf)?;
        encloses_all(fi.add(&gi).coeffs(), fq.add(&gq).coeffs(), inf)?;
        encloses_all(fi.sub(&gi).coeffs(), fq.sub(&gq).coeffs(), inf)?;
        encloses_all(fi.deriv_u().coeffs(), fq.deriv_u().coeffs(), inf)?;
        encloses_all(fi.deriv_v().coeffs(), fq.deriv_v().coeffs(), inf)?;
        encloses_all(fi.elevate(n + 2).unwrap().coeffs(), fq.elevate(n + 2).unwrap().coeffs(), inf)?;
        encloses_all(fi.elevate_cached(n + 1).coeffs(), fq.elevate(n + 1).unwrap().coeffs(), inf)?;
        if n > 0 {
            // δ bounds |member − approx| for the point approximant, coefficientwise.
            let red = fi.reduce_l2(n - 1).unwrap();
            let approx: Vec<Q> = red.approx.coeffs().iter().map(|c| exact(c.inf())).collect();
            let up = TriBezier::new(n - 1, approx).unwrap().elevate(n).unwrap();
            let bound = exact(red.delta.sup());
            for (a, b) in fq.coeffs().iter().zip(up.coeffs()) {
                prop_assert!((a - b).abs() <= bound);
            }
        }
    }
}

// ---------------------------------------------------------------------------
// 2. rational_to_interval is the tightest enclosure
// ---------------------------------------------------------------------------

/// A rational whose reduced denominator has an odd factor (so not a float),
/// over the whole float range including subnormals and overflow.
fn non_dyadic() -> impl Strategy<Value = Q> {
    (any::<i64>(), 1u64..u64::MAX, -1100i32..1100).prop_filter_map("dyadic", |(n, d, e)| {
        let r = Q::new(BigInt::from(n), BigInt::from(d)) * pow2(e);
        let mut den = r.denom().clone();
        while (&den % 2u32).is_zero() {
            den /= 2u32;
        }
        (!den.is_one()).then_some(r)
    })
}

fn pow2(e: i32) -> Q {
    let p = Q::from_integer(BigInt::one() << e.unsigned_abs());
    if e >= 0 {
        p
    } else {
        p.recip()
    }
}

fn check_tight(x: &Q) -> std::result::Result<Interval, TestCaseError> {
    let r = rational_to_interval(x);
    prop_assert!(interval_contains_rational(r, x));
    if r.sup() == f64::INFINITY {
        prop_assert_eq!(r.inf(), f64::MAX);
        prop_assert!(x > &exact(f64::MAX));
    } else if r.inf() == f64::NEG_INFINITY {
        prop_assert_eq!(r.sup(), -f64::MAX);
        prop_assert!(x < &exact(-f64::MAX));
    } else if r.inf() == r.sup() {
        prop_assert_eq!(&exact(r.inf()), x);
    } else {
        prop_assert_eq!(r.inf().next_up(), r.sup(), "endpoints not adjacent");
        prop_assert!(&exact(r.inf()) < x && x < &exact(r.sup()));
        let near = rational_to_f64(x);
        prop_assert!(near == r.inf() || near == r.sup());
    }
    Ok(r)
}

proptest! {
    #![proptest_config(cfg(256))]

    #[test]
    fn float_becomes_point(x in any::<f64>().prop_filter("finite", |x| x.is_finite()), e in -60i32..60) {
        let y = x * 2f64.powi(e);
        prop_assume!(y.is_finite());
        let r = check_tight(&exact(y))?;
        prop_assert_eq!((r.inf(), r.sup()), (y, y));
    }

    #[test]
    fn non_float_is_one_ulp_wide(x in non_dyadic()) {
        let r = check_tight(&x)?;
        prop_assert!(r.inf() < r.sup());
    }

    #[test]
    fn dyadic_non_float_is_one_ulp_wide(
        m in prop_oneof![(1u64 << 53)..u64::MAX, ((1u64 << 52)..(1u64 << 53)).prop_map(|k| 2 * k)],
        e in -1140i32..1000,
        neg in any::<bool>(),
    ) {
        // An odd mantissa of 54 to 64 bits is not a float; `2k + 1` with
        // `k` of 53 bits is exactly halfway between two floats (a tie).
        let x = Q::from_integer(BigInt::from(m | 1)) * pow2(e);
        let x = if neg { -x } else { x };
        let r = check_tight(&x)?;
        prop_assert!(r.inf() < r.sup());
    }

    #[test]
    fn small_rationals_are_tight(n in -1000i64..1000, d in 1i64..1000) {
        check_tight(&q(n, d))?;
    }
}

// ---------------------------------------------------------------------------
// 3–5. Exact identities: subdivision, split4, elevation, product
// ---------------------------------------------------------------------------

proptest! {
    #![proptest_config(cfg(48))]

    #[test]
    fn subdivide_is_composition_with_affine_map(f in tri_poly(0, 8), verts in sub_triangle(), (u, v) in point()) {
        let g = f.subdivide(&verts);
        prop_assert_eq!(g.degree(), f.degree());
        let b = bary(&u, &v);
        prop_assert_eq!(tri_at(&g, &b), tri_at(&f, &map_bary(&b, &verts)));
        // Vertices of the sub-triangle are interpolated.
        let n = f.degree();
        let corner = |c: usize| g.coeff(usize::from(c == 0) * n, usize::from(c == 1) * n).clone();
        for (c, vert) in verts.iter().enumerate() {
            prop_assert_eq!(corner(c), tri_at(&f, vert));
        }
    }
}

proptest! {
    #![proptest_config(cfg(96))]

    #[test]
    fn split4_pieces_in_documented_order(f in tri_poly(0, 8), (u, v) in point()) {
        let h = q(1, 2);
        let z = Q::zero;
        let o = Q::one;
        let (v1, v2, v3) = ([o(), z(), z()], [z(), o(), z()], [z(), z(), o()]);
        let m12 = [h.clone(), h.clone(), z()];
        let m13 = [h.clone(), z(), h.clone()];
        let m23 = [z(), h.clone(), h.clone()];
        let expected = [
            [v1, m12.clone(), m13.clone()],
            [m12.clone(), v2, m23.clone()],
            [m13.clone(), m23.clone(), v3],
            [m23, m13, m12],
        ];
        let pieces = f.split4();
        let b = bary(&u, &v);
        for (piece, verts) in pieces.iter().zip(&expected) {
            prop_assert_eq!(tri_at(piece, &b), tri_at(&f, &map_bary(&b, verts)));
            prop_assert_eq!(piece, &f.subdivide(verts));
        }
    }

    #[test]
    fn elevation_preserves_the_polynomial(
        f in tri_poly(0, 8),
        g in uni_poly(0, 8),
        h in tensor_poly(4, false),
        up in 0usize..3,
        (u, v) in point(),
        x in coord(),
    ) {
        let n = f.degree();
        let e = f.elevate(n + up).unwrap();
        prop_assert_eq!(e.degree(), n + up);
        prop_assert_eq!(&e, &f.elevate_cached(n + up));
        let b = bary(&u, &v);
        prop_assert_eq!(tri_at(&e, &b), tri_at(&f, &b));
        prop_assert!(f.elevate(n + 1).unwrap().elevate(n).is_err());
        if n > 0 {
            prop_assert!(f.elevate(n - 1).is_err());
        }

        let ge = g.elevate(g.degree() + up).unwrap();
        prop_assert_eq!(ge.degree(), g.degree() + up);
        prop_assert_eq!(ge.domain(), g.domain());
        let t = local(&x, g.domain());
        prop_assert_eq!(uni_direct(ge.coeffs(), &t), uni_direct(g.coeffs(), &t));

        let (m1, n1) = h.degree();
        let he = h.elevate(m1 + up, n1 + 2 - up).unwrap();
        prop_assert_eq!(he.degree(), (m1 + up, n1 + 2 - up));
        prop_assert_eq!(tensor_at(&he, &x, &u), tensor_at(&h, &x, &u));
    }

    #[test]
    fn product_sum_difference_evaluate_pointwise(f in tri_poly(0, 4), g in tri_poly(0, 4), (u, v) in point()) {
        let b = bary(&u, &v);
        let (fb, gb) = (tri_at(&f, &b), tri_at(&g, &b));
        let p = f.mul(&g);
        prop_assert_eq!(p.degree(), f.degree() + g.degree());
        prop_assert_eq!(tri_at(&p, &b), &fb * &gb);
        let s = f.add(&g);
        prop_assert_eq!(s.degree(), f.degree().max(g.degree()));
        prop_assert_eq!(tri_at(&s, &b), &fb + &gb);
        prop_assert_eq!(tri_at(&f.sub(&g), &b), &fb - &gb);
        prop_assert!(f.sub(&f).is_zero());
    }
}

// ---------------------------------------------------------------------------
// 6. L2 reduction: exact on low degree, residual orthogonal to the subspace
// ---------------------------------------------------------------------------

/// `∫_T B^m_α B^n_β / Area(T)` from the Dirichlet integral
/// `∫_T u^p v^q w^r = p! q! r! / (p+q+r+2)!` (area 1/2).
fn my_tri_gram(m: usize, n: usize) -> Vec<Vec<Q>> {
    indices(m)
        .into_iter()
        .map(|(a0, a1, a2)| {
            indices(n)
                .into_iter()
                .map(|(b0, b1, b2)| {
                    let (p, r, s) = (a0 + b0, a1 + b1, a2 + b2);
                    let num = multinom(a0, a1, a2) * multinom(b0, b1, b2) * fact(p) * fact(r) * fact(s) * 2;
                    Q::new(num, fact(p + r + s + 2))
                })
                .collect()
        })
        .collect()
}

/// `∫_0^1 B^m_i B^n_j` from the Beta integral.
fn my_uni_gram(m: usize, n: usize) -> Vec<Vec<Q>> {
    (0..=m)
        .map(|i| {
            (0..=n)
                .map(|j| {
                    let num = binom(m, i) * binom(n, j) * fact(i + j) * fact(m + n - i - j);
                    Q::new(num, fact(m + n + 1))
                })
                .collect()
        })
        .collect()
}

fn flat(g: Vec<Vec<Q>>) -> Vec<Q> {
    g.into_iter().flatten().collect()
}

#[test]
fn gram_matrices_match_integrals() {
    for m in 0..=4 {
        for n in 0..=4 {
            assert_eq!(tri_gram(m, n), flat(my_tri_gram(m, n)), "tri ({m}, {n})");
            assert_eq!(uni_gram(m, n), flat(my_uni_gram(m, n)), "uni ({m}, {n})");
        }
    }
}

proptest! {
    #![proptest_config(cfg(32))]

    #[test]
    fn tri_reduce_l2_is_exact_on_low_degree(f in tri_poly(0, 5), up in 1usize..4) {
        let k = f.degree();
        let r = f.elevate(k + up).unwrap().reduce_l2(k).unwrap();
        prop_assert_eq!(&r.approx, &f);
        prop_assert!(r.delta.is_zero());
    }

    #[test]
    fn tri_reduce_l2_residual_is_orthogonal(f in tri_poly(1, 8), k_seed in 0usize..8) {
        let n = f.degree();
        let k = k_seed % n;
        let r = f.reduce_l2(k).unwrap();
        prop_assert_eq!(r.approx.degree(), k);
        let residual: Vec<Q> = f.coeffs().iter().zip(r.approx.elevate(n).unwrap().coeffs()).map(|(a, b)| a - b).collect();
        for row in my_tri_gram(k, n) {
            let dot: Q = row.iter().zip(&residual).map(|(g, r)| g * r).sum();
            prop_assert!(dot.is_zero());
        }
        // δ is exactly the coefficient distance of the residual.
        let dist = residual.iter().map(|x| x.abs()).max().unwrap();
        prop_assert_eq!(r.delta, dist);
    }

    #[test]
    fn uni_reduce_l2_exact_and_orthogonal(f in uni_poly(1, 8), k_seed in 0usize..8, up in 1usize..4) {
        let n = f.degree();
        let k = k_seed % n;
        let r = f.reduce_l2(k).unwrap();
        prop_assert_eq!(r.approx.domain(), f.domain());
        let residual: Vec<Q> = f.coeffs().iter().zip(r.approx.elevate(n).unwrap().coeffs()).map(|(a, b)| a - b).collect();
        for row in my_uni_gram(k, n) {
            let dot: Q = row.iter().zip(&residual).map(|(g, r)| g * r).sum();
            prop_assert!(dot.is_zero());
        }
        let same = f.elevate(n + up).unwrap().reduce_l2(n).unwrap();
        prop_assert_eq!(same.approx.coeffs(), f.coeffs());
        prop_assert!(same.delta.is_zero());
        prop_assert!(f.reduce_l2(n).is_err());
    }

    #[test]
    fn tensor_reduce_l2_exact_and_orthogonal(f in tensor_poly(4, false), kl in (0usize..5, 0usize..5), up in (0usize..3, 1usize..3)) {
        let (m, n) = f.degree();
        let (k, l) = (kl.0.min(m), kl.1.min(n));
        prop_assert!(f.reduce_l2(m, n).is_err());
        prop_assert!(f.reduce_l2(m + 1, n).is_err());
        if (k, l) != (m, n) {
            let r = f.reduce_l2(k, l).unwrap();
            prop_assert_eq!(r.approx.degree(), (k, l));
            let el = r.approx.elevate(m, n).unwrap();
            let res: Vec<Q> = f.coeffs().iter().zip(el.coeffs()).map(|(a, b)| a - b).collect();
            let (gu, gv) = (my_uni_gram(k, m), my_uni_gram(l, n));
            for (a, row_u) in gu.iter().enumerate() {
                for (b, row_v) in gv.iter().enumerate() {
                    let mut dot = Q::zero();
                    for (i, gui) in row_u.iter().enumerate() {
                        for (j, gvj) in row_v.iter().enumerate() {
                            dot += gui * gvj * &res[i * (n + 1) + j];
                        }
                    }
                    prop_assert!(dot.is_zero(), "not orthogonal to B_{a} B_{b}");
                }
            }
        }
        let e = f.elevate(m + up.0, n + up.1).unwrap();
        let back = e.reduce_l2(m, n).unwrap();
        prop_assert_eq!(back.approx.coeffs(), f.coeffs());
        prop_assert!(back.delta.is_zero());
    }
}

// ---------------------------------------------------------------------------
// 7. Derivatives against hand-differentiated monomials
// ---------------------------------------------------------------------------

/// `∂^(du+dv) p / ∂u^du ∂v^dv` at `(u, v)`, straight from the terms.
fn monomial_deriv(p: &Polynomial, du: u32, dv: u32, u: &Q, v: &Q) -> Q {
    let falling = |a: u32, d: u32| (0..d).fold(Q::one(), |acc, t| acc * Q::from_integer(BigInt::from(a) - t));
    p.terms()
        .iter()
        .filter(|((a, b), _)| *a >= du && *b >= dv)
        .map(|((a, b), c)| c * falling(*a, du) * falling(*b, dv) * pw(u, (a - du) as usize) * pw(v, (b - dv) as usize))
        .sum()
}

/// BB coefficients of `p(x) = Σ m_e x^e` on `[a, b]`, by substituting
/// `x = a + (b − a) t` and `t^r = Σ_{i≥r} C(i,r)/C(n,r) B^n_i(t)`.
fn uni_bb_from_monomial(m: &[Q], dom: &[Q; 2]) -> Vec<Q> {
    let n = m.len() - 1;
    let h = &dom[1] - &dom[0];
    let mut g = vec![Q::zero(); n + 1];
    for (e, me) in m.iter().enumerate() {
        for (r, gr) in g.iter_mut().enumerate().take(e + 1) {
            *gr += me * Q::from_integer(binom(e, r)) * pw(&dom[0], e - r) * pw(&h, r);
        }
    }
    (0..=n)
        .map(|i| (0..=i).map(|r| &g[r] * Q::new(binom(i, r), binom(n, r))).sum())
        .collect()
}

proptest! {
    #![proptest_config(cfg(64))]

    #[test]
    fn tri_derivatives_match_monomials(p in polynomial(8), extra in 0usize..2, (u, v) in point()) {
        let f = p.to_triangle(p.total_degree() as usize + extra);
        let [fuu, fuv, fvv] = f.hessian();
        let at = |g: &TriBezier<Q>| tri_at(g, &bary(&u, &v));
        prop_assert_eq!(at(&f), monomial_deriv(&p, 0, 0, &u, &v));
        prop_assert_eq!(at(&f.deriv_u()), monomial_deriv(&p, 1, 0, &u, &v));
        prop_assert_eq!(at(&f.deriv_v()), monomial_deriv(&p, 0, 1, &u, &v));
        prop_assert_eq!(at(&fuu), monomial_deriv(&p, 2, 0, &u, &v));
        prop_assert_eq!(at(&fuv), monomial_deriv(&p, 1, 1, &u, &v));
        prop_assert_eq!(at(&fvv), monomial_deriv(&p, 0, 2, &u, &v));
    }

    #[test]
    fn tensor_derivatives_match_monomials(p in polynomial(6), split in 1i64..16, u in coord(), v in coord()) {
        let f = p.to_square();
        prop_assert_eq!(tensor_at(&f, &u, &v), monomial_deriv(&p, 0, 0, &u, &v));
        prop_assert_eq!(tensor_at(&f.deriv(Direction::U), &u, &v), monomial_deriv(&p, 1, 0, &u, &v));
        prop_assert_eq!(tensor_at(&f.deriv(Direction::V), &u, &v), monomial_deriv(&p, 0, 1, &u, &v));
        // On a sub-rectangle the derivative is still in domain coordinates.
        let (lo, _) = f.subdivide(Direction::U, q(split, 16)).unwrap();
        let (_, piece) = lo.subdivide(Direction::V, q(split, 17)).unwrap();
        let uv = monomial_deriv(&p, 1, 1, &u, &v);
        prop_assert_eq!(tensor_at(&piece.deriv(Direction::U).deriv(Direction::V), &u, &v), uv);
    }

    #[test]
    fn uni_derivative_matches_monomial(m in vec(rat(), 1..9), dom in domain(), x in coord()) {
        let f = UniBezier::new(uni_bb_from_monomial(&m, &dom), dom).unwrap();
        let value: Q = m.iter().enumerate().map(|(e, c)| c * pw(&x, e)).sum();
        let slope: Q = m.iter().enumerate().skip(1).map(|(e, c)| c * qi(e) * pw(&x, e - 1)).sum();
        prop_assert_eq!(f.eval(x.clone()), value);
        prop_assert_eq!(f.deriv().eval(x.clone()), slope);
    }
}

// ---------------------------------------------------------------------------
// 8. Tensor → two triangles; tensor subdivision
// ---------------------------------------------------------------------------

proptest! {
    #![proptest_config(cfg(64))]

    #[test]
    fn tensor_to_triangles_is_exact(f in tensor_poly(4, false), (s, t) in point()) {
        let [t0, t1] = f.to_triangles().unwrap();
        let (m, n) = f.degree();
        prop_assert_eq!((t0.degree(), t1.degree()), (m + n, m + n));
        let (du, dv) = f.domain();
        let u = &du[0] + (&du[1] - &du[0]) * &s;
        let v = &dv[0] + (&dv[1] - &dv[0]) * &t;
        let want = tensor_at(&f, &u, &v);
        // A polynomial identity: holds on and off each triangle.
        prop_assert_eq!(tri_at(&t0, &bary(&s, &t)), want.clone());
        let b1 = [Q::one() - &s, Q::one() - &t, &s + &t - Q::one()];
        prop_assert_eq!(tri_at(&t1, &b1), want);
    }

    #[test]
    fn tensor_subdivision_is_exact(f in tensor_poly(4, false), at in 1i64..32, u in coord(), v in coord()) {
        for dir in [Direction::U, Direction::V] {
            let side = match dir { Direction::U => f.domain().0.clone(), Direction::V => f.domain().1.clone() };
            let x = &side[0] + (&side[1] - &side[0]) * q(at, 32);
            let (lo, hi) = f.subdivide(dir, x.clone()).unwrap();
            let pick = |g: &TensorBezier<Q>| match dir { Direction::U => g.domain().0.clone(), Direction::V => g.domain().1.clone() };
            prop_assert_eq!(pick(&lo), [side[0].clone(), x.clone()]);
            prop_assert_eq!(pick(&hi), [x.clone(), side[1].clone()]);
            let want = tensor_at(&f, &u, &v);
            prop_assert_eq!(tensor_at(&lo, &u, &v), want.clone());
            prop_assert_eq!(tensor_at(&hi, &u, &v), want);
            prop_assert!(f.subdivide(dir, side[0].clone()).is_err());
            prop_assert!(f.subdivide(dir, &side[1] + q(1, 7)).is_err());
        }
    }
}

// ---------------------------------------------------------------------------
// 9. Monomial ↔ BB
// ---------------------------------------------------------------------------

proptest! {
    #![proptest_config(cfg(64))]

    #[test]
    fn monomial_bb_round_trip(p in polynomial(8), extra in 0usize..3, (u, v) in point()) {
        let f = p.to_triangle(p.total_degree() as usize + extra);
        prop_assert_eq!(f.degree(), p.total_degree() as usize + extra);
        prop_assert_eq!(&Polynomial::from_triangle(&f), &p);
        let want = monomial_deriv(&p, 0, 0, &u, &v);
        prop_assert_eq!(tri_at(&f, &bary(&u, &v)), want.clone());
        let sq = p.to_square();
        let (du, dv) = p.degrees();
        prop_assert_eq!(sq.degree(), (du as usize, dv as usize));
        prop_assert_eq!(tensor_at(&sq, &u, &v), want);
    }

    #[test]
    fn bb_monomial_round_trip(f in tri_poly(0, 8)) {
        let p = Polynomial::from_triangle(&f);
        prop_assert!(p.total_degree() as usize <= f.degree());
        prop_assert_eq!(p.to_triangle(f.degree()), f);
    }
}
