use super::*;

fn q(n: i64, d: i64) -> BigRational {
    BigRational::new(n.into(), d.into())
}

/// The exact restriction of a tensor net to `[α, α + (1 − α)γ]` per
/// direction, by rational de Casteljau.
fn exact_restrict(c: &[BigRational], m: usize, n: usize, params: [(f64, f64); 2]) -> Vec<BigRational> {
    let mut c = c.to_vec();
    let w = n + 1;
    for (d, &(alpha, gamma)) in params.iter().enumerate() {
        let (a, g) = (
            BigRational::from_float(alpha).unwrap(),
            BigRational::from_float(gamma).unwrap(),
        );
        let k = if d == 0 { m } else { n };
        let lines = if d == 0 { w } else { m + 1 };
        for line in 0..lines {
            let idx = |i: usize| if d == 0 { i * w + line } else { line * w + i };
            let mut v: Vec<BigRational> = (0..=k).map(|i| c[idx(i)].clone()).collect();
            for r in 1..=k {
                for i in 0..=k - r {
                    v[i] = &v[i] + &a * (&v[i + 1] - &v[i]);
                }
            }
            for r in 1..=k {
                for i in (r..=k).rev() {
                    v[i] = &v[i - 1] + &g * (&v[i] - &v[i - 1]);
                }
            }
            for i in 0..=k {
                c[idx(i)] = v[i].clone();
            }
        }
    }
    c
}

#[test]
fn restriction_encloses_the_exact_one_tightly() {
    // A product of lines in u times one in v, bidegree (6, 3): tiny
    // between its roots, where f64 from the domain's coefficients is lost.
    let (m, n) = (6, 3);
    let mut f = vec![BigRational::zero(); (m + 1) * (n + 1)];
    let mut g = vec![BigRational::zero(); (m + 1) * (n + 1)];
    for i in 0..=m {
        for j in 0..=n {
            f[i * (n + 1) + j] = q((i as i64 * 7 - 20) * (j as i64 + 1), 13) + q(1, 3 + i as i64);
            g[i * (n + 1) + j] = q(j as i64 * 5 - 8, 11) - q(i as i64, 17);
        }
    }
    let sys = DdSystem::new(m, n, &f, &g).unwrap();
    let sh = Shape::pair(m, n);
    for outer in [
        [[0.0, 1.0], [0.0, 1.0]],
        [[0.3, 0.3000001], [0.71, 0.7100002]],
        [[0.1, 0.6], [0.9, 1.0]],
        [[0.0, 1e-9], [0.5, 0.5 + 1e-12]],
    ] {
        let (c, bx) = sys.restrict(sh, outer).unwrap();
        for d in 0..2 {
            assert!(bx[d][0].lo <= outer[d][0] && bx[d][1].hi >= outer[d][1]);
        }
        let params = params(outer);
        for (k, poly) in [&f, &g].iter().enumerate() {
            let exact = exact_restrict(poly, m, n, params);
            let scale = top_exponent(poly).unwrap();
            let mag = exact.iter().map(|x| rational_to_f64(x).abs()).fold(0.0, f64::max);
            for (i, e) in exact.iter().enumerate() {
                let x: Iv = c[k * sh.len + i];
                let e = e * BigRational::from_float(2f64.powi(-scale as i32)).unwrap();
                let (lo, hi) = (
                    BigRational::from_float(x.lo).unwrap(),
                    BigRational::from_float(x.hi).unwrap(),
                );
                assert!(lo <= e && e <= hi, "coefficient {i} of poly {k} on {outer:?}");
                // Tight: within 1e-25 of the domain's scale plus a few ulps of the box's.
                let w = x.hi - x.lo;
                assert!(
                    w <= 1e-25 + 1e-14 * mag * 2f64.powi(-scale as i32),
                    "width {w} on {outer:?}"
                );
            }
        }
    }
}

/// Parameters `(α, γ)` per direction of the box holding `outer`.
fn params(outer: [[f64; 2]; 2]) -> [(f64, f64); 2] {
    restart_box(outer).unwrap().0
}

/// Each interval of `c` (poly `k`) holds the exact coefficient times one
/// positive factor common to the polynomial (the ratio's range over the
/// non-zero coefficients is one point), and is within `rel` of the
/// largest coefficient's magnitude.
fn assert_encloses(c: &[Iv], sh: Shape, k: usize, exact: &[BigRational], rel: f64) {
    use num_traits::Signed;
    let big = exact.iter().max_by(|a, b| a.abs().cmp(&b.abs())).unwrap();
    let top = c[k * sh.len + exact.iter().position(|x| x == big).unwrap()];
    // factor = top / big, enclosed: every x must hold e·factor.
    let (tlo, thi) = (
        BigRational::from_float(top.lo).unwrap(),
        BigRational::from_float(top.hi).unwrap(),
    );
    let mag = top.lo.abs().max(top.hi.abs());
    for (i, e) in exact.iter().enumerate() {
        let x = c[k * sh.len + i];
        let (lo, hi) = (
            BigRational::from_float(x.lo).unwrap(),
            BigRational::from_float(x.hi).unwrap(),
        );
        // e·[tlo, thi]/big must meet [lo, hi] (the factor is one number).
        let r = e / big;
        let (a, b) = (&r * &tlo, &r * &thi);
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        assert!(a <= hi && lo <= b, "coefficient {i} of poly {k}");
        assert!(
            x.hi - x.lo <= rel * mag,
            "coefficient {i} of poly {k}: {x:?}, top {top:?}"
        );
    }
}

#[test]
fn fixed_point_restriction_encloses_the_exact_one_tightly() {
    let (m, n) = (5, 4);
    let f: Vec<BigRational> = (0..30).map(|i| q((i * 7 % 11) - 5, 3 + i)).collect();
    let g: Vec<BigRational> = (0..30).map(|i| q((i * 5 % 13) - 6, 7 + 2 * i)).collect();
    let sh = Shape::pair(m, n);
    let big = BigSystem::new(m, n, &f, &g, FIRST_BITS).unwrap();
    for outer in [
        [[0.0, 1.0], [0.0, 1.0]],
        [[0.3, 0.3000001], [0.71, 1.0]],
        [[0.0, 1e-9], [0.5, 0.5 + 1e-12]],
    ] {
        let (c, _) = big.restrict(sh, outer).unwrap();
        for (k, poly) in [&f, &g].iter().enumerate() {
            assert_encloses(&c, sh, k, &exact_restrict(poly, m, n, params(outer)), 1e-14);
        }
    }
    // Floor shifts of negative numbers round down (the error bound's premise).
    assert_eq!(BigInt::from(-5) >> 1usize, BigInt::from(-3));
}

/// Twenty roots 1/1000 apart in u: between them the values are ~10⁻³⁸
/// of the domain's coefficients, beyond double-double; the restart
/// climbs to fixed point and comes back with clean coefficients.
#[test]
fn a_swamped_box_is_restarted_in_fixed_point() {
    // f = ∏ (u − 1/3 − k/1000) (bidegree (20, 1), constant in v), g = v − ½.
    let (m, n) = (20, 1);
    let mut line = vec![q(1, 1)];
    for k in 1..=20 {
        // (u − r)·p in Bernstein form, degree d → d + 1:
        // c'_i = (i/(d+1)) (1 − r) c_{i−1} − ((d+1−i)/(d+1)) r c_i.
        let r = q(1, 3) + q(k, 1000);
        let d = line.len() - 1;
        let mut next = vec![BigRational::zero(); d + 2];
        for (i, c) in next.iter_mut().enumerate() {
            let up = BigRational::new((i as i64).into(), ((d + 1) as i64).into());
            let down = BigRational::new(((d + 1 - i) as i64).into(), ((d + 1) as i64).into());
            if i > 0 {
                *c += up * (q(1, 1) - &r) * &line[i - 1];
            }
            if i <= d {
                *c -= down * &r * &line[i];
            }
        }
        line = next;
    }
    let f: Vec<BigRational> = line.iter().flat_map(|c| [c.clone(), c.clone()]).collect();
    let g: Vec<BigRational> = (0..=m).flat_map(|_| [q(-1, 2), q(1, 2)]).collect();
    let sh = Shape::pair(m, n);
    let outer = [[1.0 / 3.0 + 0.0102, 1.0 / 3.0 + 0.0108], [0.25, 0.75]];
    let dd = DdSystem::new(m, n, &f, &g).unwrap();
    assert!(swamped(&dd.restrict(sh, outer).unwrap().0, sh));
    let mut r = Restarts::new(m, n, &f, &g);
    let (c, bx) = r.restrict(sh, outer).unwrap();
    assert!(!swamped(&c, sh) && !r.big.is_empty());
    assert!(bx[0][0].lo <= outer[0][0] && bx[0][1].hi >= outer[0][1]);
    for (k, poly) in [&f, &g].iter().enumerate() {
        assert_encloses(&c, sh, k, &exact_restrict(poly, m, n, params(outer)), 1e-14);
    }
}

/// The fixed-width steps compute the same integers as `BigInt`'s: nets
/// of both signs near the width's limit, parameters from ½ to 2⁻³⁰⁰
/// (shifts past every limb).
#[test]
fn fixed_width_steps_match_big_integers() {
    let mut seed = 0x9e3779b97f4a7c15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let (m, n) = (4, 3);
    for round in 0..40 {
        let c: Vec<BigInt> = (0..20)
            .map(|_| {
                let mut x = BigInt::from(next() >> 1);
                for _ in 0..3 {
                    x = (x << 64) + BigInt::from(next());
                }
                // 256-bit magnitudes, then down to fit 4 limbs (253 bits).
                let x = x >> (3 + (next() % 40) as usize);
                if next() % 2 == 0 {
                    -x
                } else {
                    x
                }
            })
            .collect();
        let taus = [0.5, 0.3, 1e-5, 0.999999, 2f64.powi(-300), 0.123456789];
        let params = [
            (taus[round % 6], taus[(round / 6) % 6]),
            (taus[(round + 3) % 6], taus[(round + 1) % 6]),
        ];
        let fast = restrict_fx::<4>(&c, m, n, &params).unwrap();
        let mut slow = c.clone();
        for (d, &(a, g)) in params.iter().enumerate() {
            restrict_fixed(&mut slow, m, n, d, a, g).unwrap();
        }
        assert_eq!(fast, slow, "round {round}");
    }
    assert!(Fx::<4>::from_big(&(BigInt::from(1) << 253usize)).is_none());
    let x: BigInt = -(BigInt::from(1) << 252usize) + 12345;
    assert_eq!(Fx::<4>::from_big(&x).unwrap().to_big(), x);
}

#[test]
fn degenerate_input_gives_none() {
    let z = vec![BigRational::zero(); 4];
    let one = vec![q(1, 1); 4];
    assert!(DdSystem::new(1, 1, &z, &one).is_none());
    assert!(DdSystem::new(1, 1, &one, &one[..3]).is_none());
    let sys = DdSystem::new(1, 1, &one, &one).unwrap();
    assert!(sys.restrict(Shape::pair(1, 1), [[1.5, 2.0], [0.0, 1.0]]).is_none());
    assert!(sys.restrict(Shape::pair(2, 1), [[0.0, 1.0], [0.0, 1.0]]).is_none());
}
