//! The certified solver in 3 and 4 unknowns (`solve::nd`) against planted
//! zeros: systems `f_e = Π_k (a_e·x − c_ek)` with integer `a_e` and rational
//! `c_ek`, whose zeros are exactly the points `A x = (c_{1k_1}, …, c_{Nk_N})`
//! for every choice of `k` (rational, computed exactly). Bernstein
//! coefficients are computed in exact rational arithmetic and enclosed in
//! intervals; every certified box is re-checked exactly: it holds exactly one
//! planted zero, and every planted zero in the closed unit box is in a root
//! or undecided box.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use proptest::prelude::*;
use rootclip::scalar::rational_to_interval;
use rootclip::solve::nd::{solve_nd, BernsteinNd, NdOptions, NdSolution};

type Q = BigRational;

fn q(n: i64, d: i64) -> Q {
    Q::new(BigInt::from(n), BigInt::from(d))
}

fn qf(x: f64) -> Q {
    Q::from_float(x).unwrap()
}

/// A dense tensor over `Q`: degrees and row-major coefficients.
#[derive(Clone)]
struct TQ {
    deg: Vec<usize>,
    c: Vec<Q>,
}

fn binom(n: usize, k: usize) -> Q {
    let mut r = Q::one();
    for i in 0..k {
        r = r * Q::from_integer(BigInt::from(n - i)) / Q::from_integer(BigInt::from(i + 1));
    }
    r
}

fn unflatten(mut k: usize, deg: &[usize]) -> Vec<usize> {
    let mut out = vec![0; deg.len()];
    for d in (0..deg.len()).rev() {
        out[d] = k % (deg[d] + 1);
        k /= deg[d] + 1;
    }
    out
}

fn flatten(i: &[usize], deg: &[usize]) -> usize {
    i.iter().zip(deg).fold(0, |a, (&k, &n)| a * (n + 1) + k)
}

/// The affine form `a·x − c` as a tensor of degree 1 in every variable
/// (its coefficients are its values at the corners).
fn affine(a: &[i64], c: &Q) -> TQ {
    let n = a.len();
    let deg = vec![1; n];
    let c = (0..1usize << n)
        .map(|k| {
            let idx = unflatten(k, &deg);
            let mut v = -c.clone();
            for d in 0..n {
                if idx[d] == 1 {
                    v += Q::from_integer(BigInt::from(a[d]));
                }
            }
            v
        })
        .collect();
    TQ { deg, c }
}

/// The product of two tensors (Bernstein product formula, exact).
fn mul(p: &TQ, r: &TQ) -> TQ {
    let deg: Vec<usize> = p.deg.iter().zip(&r.deg).map(|(a, b)| a + b).collect();
    let len: usize = deg.iter().map(|d| d + 1).product();
    let mut c = vec![Q::zero(); len];
    for (ki, a) in p.c.iter().enumerate() {
        let i = unflatten(ki, &p.deg);
        for (kj, b) in r.c.iter().enumerate() {
            let j = unflatten(kj, &r.deg);
            let mut w = a * b;
            let s: Vec<usize> = i.iter().zip(&j).map(|(x, y)| x + y).collect();
            for d in 0..deg.len() {
                w = w * binom(p.deg[d], i[d]) * binom(r.deg[d], j[d]) / binom(deg[d], s[d]);
            }
            c[flatten(&s, &deg)] += w;
        }
    }
    TQ { deg, c }
}

fn enclose<const N: usize>(t: &TQ) -> BernsteinNd<N> {
    let deg: [usize; N] = std::array::from_fn(|d| t.deg[d]);
    let c: Vec<_> = t.c.iter().map(rational_to_interval).collect();
    BernsteinNd::from_intervals(deg, &c).unwrap()
}

/// A planted system: rows of `A` (integer, unimodular or at least
/// invertible over Q) and the offsets per equation.
struct Planted<const N: usize> {
    a: [[i64; N]; N],
    c: [Vec<Q>; N],
}

impl<const N: usize> Planted<N> {
    fn system(&self) -> [BernsteinNd<N>; N] {
        std::array::from_fn(|e| {
            let mut t = affine(&self.a[e], &self.c[e][0]);
            for ck in &self.c[e][1..] {
                t = mul(&t, &affine(&self.a[e], ck));
            }
            enclose(&t)
        })
    }

    /// Every zero in ℝ^N: `A x = (c_{e k_e})`, by exact Gaussian elimination.
    fn zeros(&self) -> Vec<[Q; N]> {
        let counts: Vec<usize> = self.c.iter().map(|c| c.len()).collect();
        let total: usize = counts.iter().product();
        let mut out = Vec::new();
        for mut k in 0..total {
            let rhs: [Q; N] = std::array::from_fn(|e| {
                let j = k % counts[e];
                k /= counts[e];
                self.c[e][j].clone()
            });
            out.push(solve_exact(&self.a, rhs));
        }
        out
    }
}

fn solve_exact<const N: usize>(a: &[[i64; N]; N], b: [Q; N]) -> [Q; N] {
    let mut m: Vec<Vec<Q>> = (0..N)
        .map(|r| {
            let mut row: Vec<Q> = a[r].iter().map(|&x| Q::from_integer(BigInt::from(x))).collect();
            row.push(b[r].clone());
            row
        })
        .collect();
    for col in 0..N {
        let piv = (col..N).find(|&r| !m[r][col].is_zero()).expect("A is invertible");
        m.swap(col, piv);
        let p = m[col][col].clone();
        for x in m[col].iter_mut() {
            *x = &*x / &p;
        }
        for r in 0..N {
            if r != col && !m[r][col].is_zero() {
                let f = m[r][col].clone();
                let pivot_row = m[col].clone();
                for (x, p) in m[r].iter_mut().zip(&pivot_row) {
                    *x -= p * &f;
                }
            }
        }
    }
    std::array::from_fn(|r| m[r][N].clone())
}

fn in_box<const N: usize>(x: &[Q; N], bx: &[[f64; 2]; N]) -> bool {
    (0..N).all(|d| qf(bx[d][0]) <= x[d] && x[d] <= qf(bx[d][1]))
}

fn in_unit<const N: usize>(x: &[Q; N]) -> bool {
    x.iter().all(|v| *v >= Q::zero() && *v <= Q::one())
}

/// The contract, checked exactly against the planted zeros; returns the
/// number of certified roots.
fn check<const N: usize>(p: &Planted<N>, sol: &NdSolution<N>) -> usize {
    let zeros = p.zeros();
    let mut claimed = vec![false; zeros.len()];
    for r in &sol.roots {
        let inside: Vec<usize> = (0..zeros.len()).filter(|&k| in_box(&zeros[k], &r.bx)).collect();
        assert_eq!(
            inside.len(),
            1,
            "root box {:?} holds {} planted zeros",
            r.bx,
            inside.len()
        );
        assert!(!claimed[inside[0]], "two root boxes hold the same zero");
        claimed[inside[0]] = true;
    }
    if sol.complete {
        for (k, z) in zeros.iter().enumerate() {
            if in_unit(z) {
                let covered = claimed[k] || sol.undecided.iter().any(|u| in_box(z, &u.bx));
                assert!(covered, "planted zero {z:?} is missed");
            }
        }
    }
    sol.roots.len()
}

#[test]
fn grid_of_eight_zeros_in_three_unknowns() {
    let p = Planted::<3> {
        a: [[1, 0, 0], [1, 1, 0], [0, 1, 2]],
        c: [vec![q(1, 5), q(3, 4)], vec![q(1, 2), q(6, 5)], vec![q(1, 3), q(7, 4)]],
    };
    let sol = solve_nd(&p.system(), &NdOptions::default()).unwrap();
    assert!(sol.complete && sol.undecided.is_empty());
    let inside = p.zeros().iter().filter(|z| in_unit(z)).count();
    assert_eq!(check(&p, &sol), inside);
    assert!(inside >= 4);
}

#[test]
fn zeros_on_faces_and_corners() {
    // x = 0 or 1, y = 0 or 1/2, z = 1 or 1/3: every zero on a face.
    let p = Planted::<3> {
        a: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
        c: [vec![q(0, 1), q(1, 1)], vec![q(0, 1), q(1, 2)], vec![q(1, 1), q(1, 3)]],
    };
    let sol = solve_nd(&p.system(), &NdOptions::default()).unwrap();
    assert!(sol.complete);
    check(&p, &sol);
    // A zero exactly on a face is within rounding of it: certified with a box
    // reaching over the face, or undecided, never lost.
    assert!(sol.roots.iter().all(|r| r.on_boundary));
}

#[test]
fn near_double_zero_in_four_unknowns() {
    let p = Planted::<4> {
        a: [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, -1], [1, 0, 0, 1]],
        c: [
            vec![q(1, 2), q(1, 2) + q(1, 10_000_000)],
            vec![q(1, 4)],
            vec![q(-1, 8)],
            vec![q(5, 8)],
        ],
    };
    let sol = solve_nd(&p.system(), &NdOptions::default()).unwrap();
    assert!(sol.complete);
    assert_eq!(check(&p, &sol), 2, "two zeros 1e-7 apart are both certified");
}

#[test]
fn exact_double_zero_is_undecided_never_wrong() {
    let p = Planted::<3> {
        a: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
        c: [vec![q(1, 3), q(1, 3)], vec![q(2, 5)], vec![q(3, 7)]],
    };
    let sol = solve_nd(&p.system(), &NdOptions::default()).unwrap();
    assert!(sol.complete);
    assert!(sol.roots.is_empty());
    let z = &p.zeros()[0];
    assert!(sol.undecided.iter().any(|u| in_box(z, &u.bx)));
}

#[test]
fn budget_ends_incomplete_with_leftovers() {
    let p = Planted::<3> {
        a: [[1, 0, 0], [1, 1, 0], [0, 1, 2]],
        c: [vec![q(1, 5), q(3, 4)], vec![q(1, 2), q(6, 5)], vec![q(1, 3), q(7, 4)]],
    };
    let sol = solve_nd(&p.system(), &NdOptions::default().with_max_boxes(3)).unwrap();
    assert!(!sol.complete && !sol.leftovers.is_empty());
    // Whatever was certified is still right.
    check(&p, &sol);
    for z in p.zeros().iter().filter(|z| in_unit(z)) {
        let covered = sol.roots.iter().any(|r| in_box(z, &r.bx))
            || sol.undecided.iter().any(|u| in_box(z, &u.bx))
            || sol.leftovers.iter().any(|b| in_box(z, b));
        assert!(covered);
    }
}

#[test]
fn degenerate_and_invalid_input_are_errors() {
    let zero = BernsteinNd::<3>::new([1, 1, 1], vec![0.0; 8]).unwrap();
    let one = BernsteinNd::<3>::new([1, 1, 1], vec![1.0; 8]).unwrap();
    let sys = [zero, one.clone(), one.clone()];
    assert_eq!(solve_nd(&sys, &NdOptions::default()).unwrap_err().code(), "degenerate");
    assert_eq!(
        BernsteinNd::<3>::new([1, 1, 1], vec![0.0; 7]).unwrap_err().code(),
        "shape"
    );
    let sys = [one.clone(), one.clone(), one];
    assert_eq!(
        solve_nd(&sys, &NdOptions::default().with_eps(0.0)).unwrap_err().code(),
        "invalid_option"
    );
}

fn offsets() -> impl Strategy<Value = Vec<Q>> {
    prop::collection::vec((-4i64..36, 1i64..9), 1..3).prop_map(|v| v.into_iter().map(|(n, d)| q(n, 4 * d)).collect())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]

    /// Random unimodular-ish integer rows and rational offsets: every
    /// certified box holds exactly one planted zero, and none is missed.
    #[test]
    fn planted_zeros_in_three_unknowns(
        a in prop::array::uniform3(prop::array::uniform3(-2i64..3)),
        c0 in offsets(), c1 in offsets(), c2 in offsets(),
    ) {
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        prop_assume!(det != 0);
        let distinct = |c: &Vec<Q>| c.iter().enumerate().all(|(i, x)| c[..i].iter().all(|y| y != x));
        prop_assume!(distinct(&c0) && distinct(&c1) && distinct(&c2));
        let p = Planted::<3> { a, c: [c0, c1, c2] };
        let sys = p.system();
        let sol = solve_nd(&sys, &NdOptions::default()).unwrap();
        prop_assert!(sol.complete);
        check(&p, &sol);
    }
}
