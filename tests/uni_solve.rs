//! The certified univariate solver against an independent exact oracle:
//! Sturm sequences over the rationals, on the power form converted here
//! (none of the solver's code). Roots are planted — simple, close pairs down
//! to 1e-12, double and triple, at and 1e-300 from the ends, with huge and
//! tiny coefficients — and every answer is checked against the contract:
//! each certified interval holds exactly one root, a simple one, in the
//! domain; no root lies outside the certified intervals, the undecided
//! regions and the leftovers; overlapping certified intervals are distinct
//! roots.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use proptest::prelude::*;
use rootclip::inari::Interval;
use rootclip::scalar::rational_to_interval;
use rootclip::solve::{solve_uni, UndecidedReason, UniOptions, UniSolution};
use rootclip::UniBezier;

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).unwrap()
}

fn int(n: i64) -> Q {
    Q::from_integer(n.into())
}

fn binom(n: usize, k: usize) -> BigInt {
    (0..k).fold(BigInt::one(), |acc, i| acc * (n - i) / (i + 1))
}

// ---------------------------------------------------------------------------
// The oracle: exact polynomials in the power basis (ascending coefficients).

fn trim(mut p: Vec<Q>) -> Vec<Q> {
    while p.len() > 1 && p.last().is_some_and(Zero::is_zero) {
        p.pop();
    }
    p
}

fn mul(a: &[Q], b: &[Q]) -> Vec<Q> {
    let mut out = vec![Q::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

fn horner(p: &[Q], x: &Q) -> Q {
    p.iter().rev().fold(Q::zero(), |acc, c| acc * x + c)
}

fn derivative(p: &[Q]) -> Vec<Q> {
    if p.len() <= 1 {
        return vec![Q::zero()];
    }
    p.iter().enumerate().skip(1).map(|(i, c)| c * int(i as i64)).collect()
}

/// The remainder of `a` divided by `b` (`b` trimmed, non-zero).
fn rem(a: &[Q], b: &[Q]) -> Vec<Q> {
    let mut r = a.to_vec();
    let lead = b.last().unwrap().clone();
    while r.len() >= b.len() && !(r.len() == 1 && r[0].is_zero()) {
        let k = r.len() - b.len();
        let f = r.last().unwrap() / &lead;
        for (i, c) in b.iter().enumerate() {
            r[k + i] -= &f * c;
        }
        r.pop();
        r = trim(r);
        if r.is_empty() {
            r.push(Q::zero());
        }
    }
    trim(r)
}

fn is_zero(p: &[Q]) -> bool {
    p.iter().all(Zero::is_zero)
}

/// The quotient of `a` by `b` (`b` trimmed, non-zero; exact when `b | a`).
fn quotient(a: &[Q], b: &[Q]) -> Vec<Q> {
    let mut r = trim(a.to_vec());
    if r.len() < b.len() {
        return vec![Q::zero()];
    }
    let lead = b.last().unwrap().clone();
    let mut out = vec![Q::zero(); r.len() - b.len() + 1];
    while r.len() >= b.len() && !is_zero(&r) {
        let k = r.len() - b.len();
        let f = r.last().unwrap() / &lead;
        for (i, c) in b.iter().enumerate() {
            r[k + i] -= &f * c;
        }
        out[k] = f;
        r.pop();
    }
    trim(out)
}

fn gcd(a: &[Q], b: &[Q]) -> Vec<Q> {
    let (mut a, mut b) = (trim(a.to_vec()), trim(b.to_vec()));
    while !is_zero(&b) {
        let r = rem(&a, &b);
        a = b;
        b = r;
    }
    a
}

/// The polynomial `p = Σ c_i C(n, i) t^i (1 − t)^(n−i)` in the power basis.
fn bb_to_power(c: &[Q]) -> Vec<Q> {
    let n = c.len() - 1;
    let mut out = vec![Q::zero(); n + 1];
    for (i, ci) in c.iter().enumerate() {
        for k in 0..=n - i {
            let mut term = ci * Q::from_integer(binom(n, i) * binom(n - i, k));
            if k % 2 == 1 {
                term = -term;
            }
            out[i + k] += term;
        }
    }
    trim(out)
}

/// Counts distinct real roots with Sturm's theorem (on the square-free part).
struct Oracle {
    sturm: Vec<Vec<Q>>,
    /// The multiple roots' polynomial `gcd(p, p')` (constant if none).
    multiple: Option<Box<Oracle>>,
    p: Vec<Q>,
}

impl Oracle {
    fn new(p: Vec<Q>) -> Self {
        let p = trim(p);
        let g = gcd(&p, &derivative(&p));
        let multiple = (g.len() > 1).then(|| Box::new(Oracle::new(g.clone())));
        // Sturm's sequence of the square-free part, whose roots are simple.
        let s = quotient(&p, &g);
        let mut sturm = vec![s.clone(), trim(derivative(&s))];
        while !is_zero(sturm.last().unwrap()) && sturm.last().unwrap().len() > 1 {
            let k = sturm.len();
            let r: Vec<Q> = rem(&sturm[k - 2], &sturm[k - 1]).into_iter().map(|x| -x).collect();
            if is_zero(&r) {
                break;
            }
            sturm.push(r);
        }
        Self { sturm, multiple, p }
    }

    fn variations(&self, x: &Q) -> usize {
        let signs: Vec<bool> = self
            .sturm
            .iter()
            .map(|s| horner(s, x))
            .filter(|v| !v.is_zero())
            .map(|v| v.is_positive())
            .collect();
        signs.windows(2).filter(|w| w[0] != w[1]).count()
    }

    fn is_root(&self, x: &Q) -> bool {
        horner(&self.p, x).is_zero()
    }

    /// Distinct roots in the half-open `(lo, hi]` (`lo < hi`): Sturm's
    /// theorem on the square-free part `p / gcd(p, p')` (the variation count
    /// drops by one across each of its simple roots and is right-continuous
    /// there).
    fn half_open(&self, lo: &Q, hi: &Q) -> usize {
        if self.p.len() == 1 {
            return 0;
        }
        self.variations(lo) - self.variations(hi)
    }

    /// Distinct roots in the closed `[lo, hi]`.
    fn closed(&self, lo: &Q, hi: &Q) -> usize {
        if lo == hi {
            return usize::from(self.is_root(lo));
        }
        self.half_open(lo, hi) + usize::from(self.is_root(lo))
    }

    /// Distinct roots in the open `(lo, hi)`.
    fn open(&self, lo: &Q, hi: &Q) -> usize {
        if lo >= hi {
            return 0;
        }
        self.half_open(lo, hi) - usize::from(self.is_root(hi))
    }

    /// Multiple roots in the closed `[lo, hi]`.
    fn multiple_in(&self, lo: &Q, hi: &Q) -> usize {
        self.multiple.as_ref().map_or(0, |m| m.closed(lo, hi))
    }
}

/// Checks the [`UniSolution`] contract for the exact polynomial with BB
/// coefficients `c` on `[a, b]`, against the oracle. Returns the number of
/// distinct roots in the closed domain.
fn check_contract(sol: &UniSolution, c: &[Q], a: &Q, b: &Q) -> usize {
    // The oracle works in x: p(x) = Σ c_i B_i((x − a)/(b − a)).
    let w = b - a;
    let t_of_x = vec![-a / &w, Q::one() / &w];
    let pt = bb_to_power(c);
    let mut px = vec![Q::zero()];
    let mut power = vec![Q::one()];
    for ck in &pt {
        let term: Vec<Q> = power.iter().map(|x| x * ck).collect();
        px = add(&px, &term);
        power = mul(&power, &t_of_x);
    }
    let oracle = Oracle::new(px);
    let total = oracle.closed(a, b);
    let mut covered: Vec<(Q, Q)> = Vec::new();
    for r in &sol.roots {
        let (lo, hi) = (q(r.interval[0]), q(r.interval[1]));
        assert!(lo <= hi, "root interval {:?} is empty", r.interval);
        assert!(lo <= q(r.x) && q(r.x) <= hi);
        assert_eq!(
            oracle.closed(&lo, &hi),
            1,
            "root interval {:?} must hold exactly one root",
            r.interval
        );
        assert_eq!(
            oracle.multiple_in(&lo, &hi),
            0,
            "the root in {:?} must be simple",
            r.interval
        );
        let (clo, chi) = (lo.clone().max(a.clone()), hi.clone().min(b.clone()));
        assert!(
            clo <= chi && oracle.closed(&clo, &chi) == 1,
            "root {:?} must be in the domain",
            r.interval
        );
        covered.push((lo, hi));
    }
    for (i, x) in covered.iter().enumerate() {
        for y in &covered[i + 1..] {
            if x.0 <= y.1 && y.0 <= x.1 {
                let (lo, hi) = (x.0.clone().min(y.0.clone()), x.1.clone().max(y.1.clone()));
                assert!(
                    oracle.closed(&lo, &hi) >= 2,
                    "overlapping root intervals must be distinct roots"
                );
            }
        }
    }
    for cl in &sol.clusters {
        covered.push((q(cl.interval[0]), q(cl.interval[1])));
    }
    for l in &sol.leftovers {
        covered.push((q(l[0]), q(l[1])));
    }
    assert_eq!(sol.complete, sol.leftovers.is_empty());
    // Every root of [a, b] is covered: the gaps hold none.
    covered.sort();
    let mut from = a.clone();
    let mut from_closed = true;
    for (lo, hi) in &covered {
        if *lo > from {
            let missed = oracle.open(&from, lo) + usize::from(from_closed && oracle.is_root(&from));
            assert_eq!(missed, 0, "a root in the gap ({from}, {lo}) is missing: {sol:?}");
        }
        if *hi > from || (*hi == from && from_closed) {
            from = hi.clone();
            from_closed = false;
        }
    }
    if from < *b || (from == *b && from_closed) {
        let missed =
            oracle.open(&from, b) + usize::from(oracle.is_root(b)) + usize::from(from_closed && oracle.is_root(&from));
        assert_eq!(missed, 0, "a root in the gap after {from} is missing: {sol:?}");
    }
    total
}

fn add(a: &[Q], b: &[Q]) -> Vec<Q> {
    let mut out = vec![Q::zero(); a.len().max(b.len())];
    for (i, x) in a.iter().enumerate() {
        out[i] += x;
    }
    for (i, x) in b.iter().enumerate() {
        out[i] += x;
    }
    out
}

// ---------------------------------------------------------------------------
// Planting roots.

/// `k · Π (t − r)^m` in the power basis.
fn planted(roots: &[(Q, usize)], k: &Q) -> Vec<Q> {
    let mut p = vec![k.clone()];
    for (r, m) in roots {
        for _ in 0..*m {
            p = mul(&p, &[-r.clone(), Q::one()]);
        }
    }
    p
}

/// The BB coefficients on `[0, 1]` of a power-basis polynomial of degree
/// at most `n`: `c_j = Σ_{i ≤ j} C(j, i)/C(n, i) a_i`.
fn power_to_bb(a: &[Q], n: usize) -> Vec<Q> {
    (0..=n)
        .map(|j| {
            (0..=j.min(a.len() - 1))
                .map(|i| &a[i] * Q::new(binom(j, i), binom(n, i)))
                .fold(Q::zero(), |s, x| s + x)
        })
        .collect()
}

fn bb(roots: &[(Q, usize)], k: &Q) -> Vec<Q> {
    let p = planted(roots, k);
    let n = p.len() - 1;
    power_to_bb(&p, n)
}

fn opts() -> UniOptions {
    UniOptions::default()
}

/// Solves the exact polynomial as rationals and as enclosures, checks both
/// against the oracle, and returns the exact solve.
fn solve_exact_and_enclosed(c: &[Q]) -> UniSolution {
    let exact = solve_uni(&UniBezier::on_unit(c.to_vec()).unwrap(), &opts()).unwrap();
    check_contract(&exact, c, &Q::zero(), &Q::one());
    let iv: Vec<Interval> = c.iter().map(rational_to_interval).collect();
    let enclosed = solve_uni(&UniBezier::on_unit(iv).unwrap(), &opts()).unwrap();
    check_contract(&enclosed, c, &Q::zero(), &Q::one());
    exact
}

fn holds(sol: &UniSolution, x: &Q) -> bool {
    sol.roots
        .iter()
        .any(|r| q(r.interval[0]) <= *x && *x <= q(r.interval[1]))
}

fn clustered(sol: &UniSolution, x: &Q) -> bool {
    sol.clusters
        .iter()
        .any(|c| q(c.interval[0]) <= *x && *x <= q(c.interval[1]))
}

// ---------------------------------------------------------------------------

#[test]
fn oracle_counts_known_roots() {
    // (t − 1/4)² (t − 1/2) (t + 1): distinct roots 1/4, 1/2 in [0, 1].
    let p = planted(
        &[
            (Q::new(1.into(), 4.into()), 2),
            (Q::new(1.into(), 2.into()), 1),
            (int(-1), 1),
        ],
        &int(3),
    );
    let o = Oracle::new(p);
    assert_eq!(o.closed(&Q::zero(), &Q::one()), 2);
    assert_eq!(o.closed(&Q::new(1.into(), 4.into()), &Q::new(1.into(), 4.into())), 1);
    assert_eq!(o.open(&Q::new(1.into(), 4.into()), &Q::new(1.into(), 2.into())), 0);
    assert_eq!(o.closed(&int(-2), &Q::one()), 3);
    assert_eq!(o.multiple_in(&Q::zero(), &Q::one()), 1);
}

#[test]
fn simple_roots_are_certified_in_every_kernel() {
    let roots: Vec<(Q, usize)> = [0.1, 0.35, 0.8, 0.95].iter().map(|&r| (q(r), 1)).collect();
    let c = bb(&roots, &int(1));
    let sol = solve_exact_and_enclosed(&c);
    assert!(
        sol.complete && sol.clusters.is_empty() && sol.roots.len() == 4,
        "{sol:?}"
    );
    for (r, _) in &roots {
        assert!(holds(&sol, r));
    }
    // f64 input: the coefficients rounded to floats; the oracle checks that
    // polynomial, whose roots are within rounding of the planted ones.
    let f: Vec<f64> = c.iter().map(rootclip::scalar::rational_to_f64).collect();
    let sol = solve_uni(&UniBezier::on_unit(f.clone()).unwrap(), &opts()).unwrap();
    let fq: Vec<Q> = f.iter().map(|&x| q(x)).collect();
    assert_eq!(check_contract(&sol, &fq, &Q::zero(), &Q::one()), 4);
    assert_eq!(sol.roots.len(), 4);
    for r in &sol.roots {
        assert!(r.interval[1] - r.interval[0] < 1e-14, "{:?}", r.interval);
    }
}

#[test]
fn close_pairs_down_to_1e_12_are_separated_exactly() {
    for k in [4, 6, 8, 10, 11, 12] {
        let delta = 10f64.powi(-k);
        let (r0, r1) = (q(0.4), q(0.4) + q(delta));
        let c = bb(&[(r0.clone(), 1), (r1.clone(), 1), (q(0.9), 1)], &int(1));
        let sol = solve_exact_and_enclosed(&c);
        assert!(sol.complete, "{sol:?}");
        assert_eq!(sol.roots.len(), 3, "δ = {delta}: {sol:?}");
        assert!(holds(&sol, &r0) && holds(&sol, &r1));
    }
}

#[test]
fn double_and_triple_roots_are_undecided_never_certified() {
    for m in [2, 3] {
        let r = q(0.3);
        let c = bb(&[(r.clone(), m), (q(0.7), 1)], &int(2));
        let sol = solve_exact_and_enclosed(&c);
        assert!(sol.complete);
        assert!(!holds(&sol, &r) && clustered(&sol, &r), "multiplicity {m}: {sol:?}");
        assert!(sol
            .clusters
            .iter()
            .all(|c| c.reason == UndecidedReason::MultipleOrClose));
        assert!(holds(&sol, &q(0.7)));
        // The exact retry narrows the region to a few ulps of the root.
        let cl = sol
            .clusters
            .iter()
            .find(|c| q(c.interval[0]) <= r && r <= q(c.interval[1]))
            .unwrap();
        assert!(cl.interval[1] - cl.interval[0] < 1e-12, "{cl:?}");
    }
}

#[test]
fn roots_at_and_near_the_ends_are_settled_exactly() {
    let tiny = q(1e-300);
    let sub = q(f64::from_bits(1)); // 2^-1074
    let one = Q::one();
    // (planted roots, expected certified, expected absent)
    type Case = (Vec<(Q, usize)>, Vec<Q>, Vec<Q>);
    let cases: Vec<Case> = vec![
        (
            vec![(Q::zero(), 1), (q(0.5), 1), (one.clone(), 1)],
            vec![Q::zero(), q(0.5), one.clone()],
            vec![],
        ),
        (vec![(tiny.clone(), 1), (q(0.5), 1)], vec![tiny.clone(), q(0.5)], vec![]),
        (vec![(-tiny.clone(), 1), (q(0.5), 1)], vec![q(0.5)], vec![-tiny.clone()]),
        (vec![(-sub.clone(), 1), (q(0.25), 1)], vec![q(0.25)], vec![-sub.clone()]),
        (vec![(sub.clone(), 1), (q(0.25), 1)], vec![sub.clone(), q(0.25)], vec![]),
        (vec![(&one + &tiny, 1), (q(0.5), 1)], vec![q(0.5)], vec![&one + &tiny]),
        (
            vec![(&one - q(f64::EPSILON / 2.0), 1), (q(0.5), 1)],
            vec![&one - q(f64::EPSILON / 2.0), q(0.5)],
            vec![],
        ),
        (
            vec![(&one + q(f64::EPSILON), 1), (q(0.5), 1)],
            vec![q(0.5)],
            vec![&one + q(f64::EPSILON)],
        ),
    ];
    for (roots, inside, outside) in cases {
        let c = bb(&roots, &int(1));
        let exact = solve_uni(&UniBezier::on_unit(c.clone()).unwrap(), &opts()).unwrap();
        let n = check_contract(&exact, &c, &Q::zero(), &Q::one());
        assert!(exact.complete && exact.clusters.is_empty(), "{roots:?}: {exact:?}");
        assert_eq!(exact.roots.len(), n);
        assert_eq!(n, inside.len());
        for x in &inside {
            assert!(holds(&exact, x), "{x} must be certified: {exact:?}");
        }
        for x in &outside {
            assert!(!holds(&exact, x), "{x} is outside the domain: {exact:?}");
        }
        // Enclosures: the contract still holds (a root within rounding of an
        // end may stay undecided, with reason `boundary`).
        let iv: Vec<Interval> = c.iter().map(rational_to_interval).collect();
        let enclosed = solve_uni(&UniBezier::on_unit(iv).unwrap(), &opts()).unwrap();
        check_contract(&enclosed, &c, &Q::zero(), &Q::one());
    }
}

#[test]
fn huge_and_tiny_coefficients() {
    let roots: Vec<(Q, usize)> = vec![(q(0.2), 1), (q(0.6), 1), (q(0.6) + q(1e-9), 1)];
    for scale in [1e300, 1e-300, 2f64.powi(-1070), 1e150] {
        let c = bb(&roots, &q(scale));
        let sol = solve_exact_and_enclosed(&c);
        assert_eq!(sol.roots.len(), 3, "scale {scale}: {sol:?}");
        let f: Vec<f64> = c.iter().map(rootclip::scalar::rational_to_f64).collect();
        if f.iter().all(|x| x.is_finite()) {
            let sol = solve_uni(&UniBezier::on_unit(f.clone()).unwrap(), &opts()).unwrap();
            let fq: Vec<Q> = f.iter().map(|&x| q(x)).collect();
            check_contract(&sol, &fq, &Q::zero(), &Q::one());
        }
    }
}

#[test]
fn other_domains() {
    let c = bb(&[(q(0.25), 1), (q(0.5), 1), (Q::one(), 1)], &int(1));
    let f: Vec<f64> = c.iter().map(rootclip::scalar::rational_to_f64).collect();
    // [2, 5] in f64: roots at 2.75, 3.5, 5.
    let sol = solve_uni(&UniBezier::new(f, [2.0, 5.0]).unwrap(), &opts()).unwrap();
    check_contract(&sol, &c, &int(2), &int(5));
    assert_eq!(sol.roots.len(), 3);
    assert!(sol.roots[2].on_boundary && sol.roots[2].interval[1] <= 5.0);
    // [1/3, 2/3] in rationals: roots at 5/12, 1/2, 2/3.
    let (a, b) = (Q::new(1.into(), 3.into()), Q::new(2.into(), 3.into()));
    let sol = solve_uni(&UniBezier::new(c.clone(), [a.clone(), b.clone()]).unwrap(), &opts()).unwrap();
    check_contract(&sol, &c, &a, &b);
    assert_eq!(sol.roots.len(), 3);
}

#[test]
fn errors_are_typed() {
    let zero = UniBezier::on_unit(vec![0.0, 0.0, 0.0]).unwrap();
    assert_eq!(solve_uni(&zero, &opts()).unwrap_err().code(), "degenerate");
    let big = UniBezier::on_unit(vec![1.0; 66]).unwrap();
    assert_eq!(solve_uni(&big, &opts()).unwrap_err().code(), "too_large");
    let p = UniBezier::on_unit(vec![1.0, -1.0]).unwrap();
    assert_eq!(
        solve_uni(&p, &opts().with_eps(f64::NAN)).unwrap_err().code(),
        "invalid_option"
    );
    assert_eq!(
        solve_uni(&p, &opts().with_max_boxes(0)).unwrap_err().code(),
        "invalid_option"
    );
    let wide = UniBezier::new(
        vec![Interval::try_from((1.0, 1.0)).unwrap(); 2],
        [
            Interval::try_from((0.0, 0.5)).unwrap(),
            Interval::try_from((1.0, 1.0)).unwrap(),
        ],
    )
    .unwrap();
    assert_eq!(solve_uni(&wide, &opts()).unwrap_err().code(), "shape");
    // A zero enclosure (not exactly zero) is one undecided region.
    let blur = Interval::try_from((-1e-9, 1e-9)).unwrap();
    let sol = solve_uni(&UniBezier::on_unit(vec![blur; 3]).unwrap(), &opts()).unwrap();
    assert!(sol.complete && sol.roots.is_empty() && sol.clusters.len() == 1);
    assert_eq!(sol.clusters[0].interval, [0.0, 1.0]);
}

#[test]
fn a_budget_leaves_leftovers_never_a_silent_none() {
    let roots: Vec<(Q, usize)> = (1..=9).map(|k| (q(k as f64 / 10.0), 1)).collect();
    let c = bb(&roots, &int(1));
    let sol = solve_uni(&UniBezier::on_unit(c.clone()).unwrap(), &opts().with_max_boxes(3)).unwrap();
    assert!(!sol.complete && !sol.leftovers.is_empty());
    check_contract(&sol, &c, &Q::zero(), &Q::one());
}

#[test]
fn degree_zero_and_one() {
    let sol = solve_uni(&UniBezier::on_unit(vec![2.5]).unwrap(), &opts()).unwrap();
    assert!(sol.complete && sol.roots.is_empty() && sol.clusters.is_empty());
    let c = vec![q(-1.0), q(3.0)];
    let sol = solve_uni(&UniBezier::on_unit(c.clone()).unwrap(), &opts()).unwrap();
    assert_eq!(check_contract(&sol, &c, &Q::zero(), &Q::one()), 1);
    assert_eq!(sol.roots.len(), 1);
}

/// A planted root: a dyadic in `[−1/4, 5/4]` (some just outside the domain),
/// with multiplicity 1 to 3, sometimes a close partner.
fn root_strategy() -> impl Strategy<Value = Vec<(Q, usize)>> {
    let one = (-256i64..=1280, 1usize..=3, prop::option::of(20i32..=45));
    prop::collection::vec(one, 1..=4).prop_map(|v| {
        let mut out = Vec::new();
        for (k, m, partner) in v {
            let r = Q::new(k.into(), 1024.into());
            if let Some(e) = partner {
                out.push((&r + Q::new(1.into(), BigInt::one() << e), 1));
            }
            out.push((r, m));
        }
        out
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, ..ProptestConfig::default() })]

    #[test]
    fn planted_roots_meet_the_contract(roots in root_strategy(), e in -400i32..400, neg in any::<bool>()) {
        let scale = Q::from_integer(BigInt::one() << e.unsigned_abs());
        let mut k = if e < 0 { Q::one() / scale } else { scale };
        if neg {
            k = -k;
        }
        let c = bb(&roots, &k);
        prop_assume!(c.len() - 1 <= 12);
        let sol = solve_exact_and_enclosed(&c);
        prop_assert!(sol.complete);
        // Exact input: every simple planted root in the domain is certified
        // (close partners 2^-45 apart included); multiple ones never are.
        for (r, m) in &roots {
            let mult: usize = roots.iter().filter(|(s, _)| s == r).map(|(_, m)| m).sum();
            let inside = *r >= Q::zero() && *r <= Q::one();
            if inside && mult == 1 {
                prop_assert!(holds(&sol, r), "{r} (m = {m}): {sol:?}");
            }
            if mult > 1 {
                prop_assert!(!holds(&sol, r));
            }
        }
    }
}
