//! The `rootclip bernstein` command, run as a process.
//!
//! Expected coefficients are computed here by the explicit formulas, from terms
//! the test generates itself (never through the library):
//! ```text
//! triangle, degree n:    u^a v^b = Σ_{i≥a, j≥b} C(i,a) C(j,b) / C(n; a, b, n−a−b) · B^n_ijk
//! square, bidegree m,n:  u^a v^b = Σ_{i≥a, j≥b} C(i,a)/C(m,a) · C(j,b)/C(n,b) · B^m_i B^n_j
//! ```

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::Config;
use serde_json::Value;
use std::collections::BTreeMap;
use std::process::{Command, Output};

type Q = BigRational;
type Terms = BTreeMap<(usize, usize), Q>;

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rootclip"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn bernstein_json(f: &str, domain: &str) -> Value {
    let out = run(&["bernstein", "--f", f, "--domain", domain, "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{f:?} on {domain}: {stderr}");
    assert!(stderr.is_empty(), "stderr on success: {stderr}");
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{f:?}: not JSON ({e})"))
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

/// A value printed as `p` or `p/q`, checked to be a reduced fraction.
fn fraction(s: &str) -> Q {
    let (num, den) = match s.split_once('/') {
        Some((n, d)) => (n.parse::<BigInt>().unwrap(), d.parse::<BigInt>().unwrap()),
        None => (s.parse::<BigInt>().unwrap(), BigInt::one()),
    };
    assert!(!s.starts_with('+') && !s.contains(' '), "{s:?} is not canonical");
    assert!(den > BigInt::zero(), "{s:?}: denominator must be positive");
    assert!(num.gcd(&den).is_one(), "{s:?} is not reduced");
    assert_eq!(s.contains('/'), !den.is_one(), "{s:?}: integers print without '/1'");
    Q::new(num, den)
}

fn degree(terms: &Terms) -> usize {
    terms.keys().map(|(a, b)| a + b).max().unwrap_or(0)
}

fn triangle_expected(terms: &Terms) -> BTreeMap<(usize, usize), Q> {
    let n = degree(terms);
    let mut out = BTreeMap::new();
    for j in 0..=n {
        for i in 0..=n - j {
            let c: Q = terms
                .iter()
                .filter(|((a, b), _)| a <= &i && b <= &j)
                .map(|((a, b), c)| c * Q::new(binom(i, *a) * binom(j, *b), multinom(*a, *b, n - a - b)))
                .sum();
            out.insert((i, j), c);
        }
    }
    out
}

fn square_expected(terms: &Terms) -> (usize, usize, BTreeMap<(usize, usize), Q>) {
    let m = terms.keys().map(|k| k.0).max().unwrap_or(0);
    let n = terms.keys().map(|k| k.1).max().unwrap_or(0);
    let mut out = BTreeMap::new();
    for i in 0..=m {
        for j in 0..=n {
            let c: Q = terms
                .iter()
                .filter(|((a, b), _)| a <= &i && b <= &j)
                .map(|((a, b), c)| c * Q::new(binom(i, *a), binom(m, *a)) * Q::new(binom(j, *b), binom(n, *b)))
                .sum();
            out.insert((i, j), c);
        }
    }
    (m, n, out)
}

fn keys(v: &Value) -> Vec<&str> {
    let mut k: Vec<&str> = v.as_object().expect("object").keys().map(String::as_str).collect();
    k.sort_unstable();
    k
}

fn index(v: &Value, key: &str) -> usize {
    v[key]
        .as_u64()
        .unwrap_or_else(|| panic!("{key} is not an index in {v}")) as usize
}

fn check_triangle(f: &str, terms: &Terms) {
    let out = bernstein_json(f, "triangle");
    assert_eq!(keys(&out), ["coefficients", "degree", "domain", "schema_version"]);
    assert_eq!(out["schema_version"], 1);
    assert_eq!(out["domain"], "triangle");
    let n = degree(terms);
    assert_eq!(out["degree"].as_u64(), Some(n as u64), "{f}");
    let want = triangle_expected(terms);
    let coeffs = out["coefficients"].as_array().expect("array");
    assert_eq!(coeffs.len(), (n + 1) * (n + 2) / 2);
    // Storage order: j outer, i inner.
    let order = (0..=n).flat_map(|j| (0..=n - j).map(move |i| (i, j)));
    for (c, (i, j)) in coeffs.iter().zip(order) {
        assert_eq!(keys(c), ["i", "j", "k", "value"]);
        assert_eq!((index(c, "i"), index(c, "j"), index(c, "k")), (i, j, n - i - j));
        let value = fraction(c["value"].as_str().expect("value is a string"));
        assert_eq!(value, want[&(i, j)], "{f}: f_{i}{j}");
    }
}

fn check_square(f: &str, terms: &Terms) {
    let out = bernstein_json(f, "square");
    assert_eq!(keys(&out), ["coefficients", "degree", "domain", "schema_version"]);
    assert_eq!(out["schema_version"], 1);
    assert_eq!(out["domain"], "square");
    let (m, n, want) = square_expected(terms);
    assert_eq!(out["degree"], serde_json::json!([m, n]), "{f}");
    let coeffs = out["coefficients"].as_array().expect("array");
    assert_eq!(coeffs.len(), (m + 1) * (n + 1));
    let order = (0..=m).flat_map(|i| (0..=n).map(move |j| (i, j)));
    for (c, (i, j)) in coeffs.iter().zip(order) {
        assert_eq!(keys(c), ["i", "j", "value"]);
        assert_eq!((index(c, "i"), index(c, "j")), (i, j));
        let value = fraction(c["value"].as_str().expect("value is a string"));
        assert_eq!(value, want[&(i, j)], "{f}: f_{i}{j}");
    }
}

fn q(n: i64, d: i64) -> Q {
    Q::new(n.into(), d.into())
}

fn terms(list: &[((usize, usize), Q)]) -> Terms {
    let mut t = Terms::new();
    for (k, c) in list {
        *t.entry(*k).or_insert_with(Q::zero) += c;
    }
    t.retain(|_, c| !c.is_zero());
    t
}

#[test]
fn cubic_minus_v_on_the_triangle() {
    // f_ij = [i = 3] − j/3 (Liu et al. 2016, Example 1).
    let t = terms(&[((3, 0), q(1, 1)), ((0, 1), q(-1, 1))]);
    check_triangle("u^3 - v", &t);
    check_square("u^3 - v", &t);
    let out = bernstein_json("u^3 - v", "triangle");
    let c = &out["coefficients"];
    assert_eq!(c[3]["value"], "1"); // f_300
    assert_eq!(c[9]["value"], "-1"); // f_030
    assert_eq!(c[4]["value"], "-1/3"); // f_012
}

#[test]
fn fixed_polynomials() {
    let cases: Vec<(&str, Terms)> = vec![
        ("0", terms(&[])),
        ("7/3", terms(&[((0, 0), q(7, 3))])),
        ("u*v", terms(&[((1, 1), q(1, 1))])),
        ("-u", terms(&[((1, 0), q(-1, 1))])),
        ("0.1*v^2 - 2.5e-3", terms(&[((0, 2), q(1, 10)), ((0, 0), q(-1, 400))])),
        (
            "(u - v)^2",
            terms(&[((2, 0), q(1, 1)), ((1, 1), q(-2, 1)), ((0, 2), q(1, 1))]),
        ),
        (
            "u^2 + v^2 - 1/4*(1 + 1/10^2)",
            terms(&[((2, 0), q(1, 1)), ((0, 2), q(1, 1)), ((0, 0), q(-101, 400))]),
        ),
    ];
    for (f, t) in &cases {
        check_triangle(f, t);
        check_square(f, t);
    }
    // Text defaults to the triangle.
    let out = run(&["bernstein", "--f", "u*v"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "triangle, degree 2: u*v");
    assert_eq!(
        &lines[1..],
        [
            "f[0,0,2] = 0",
            "f[1,0,1] = 0",
            "f[2,0,0] = 0",
            "f[0,1,1] = 0",
            "f[1,1,0] = 1/2",
            "f[0,2,0] = 0"
        ]
    );
    let out = run(&["bernstein", "--f", "u*v", "--domain", "square"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(
        text.lines().collect::<Vec<_>>(),
        [
            "square, degree [1,1]: u*v",
            "f[0,0] = 0",
            "f[0,1] = 0",
            "f[1,0] = 0",
            "f[1,1] = 1"
        ]
    );
}

fn render(list: &[((usize, usize), Q)]) -> String {
    if list.is_empty() {
        return "0".into();
    }
    list.iter()
        .map(|((a, b), c)| format!("({c})*u^{a}*v^{b}"))
        .collect::<Vec<_>>()
        .join(" + ")
}

proptest! {
    #![proptest_config(Config { cases: 24, failure_persistence: None, ..Config::default() })]

    #[test]
    fn random_polynomials_match_the_formula(
        list in vec(((0usize..=6, 0usize..=6), (-50i64..50, 1i64..20)), 0..6),
    ) {
        let list: Vec<((usize, usize), Q)> = list
            .into_iter()
            .filter(|((a, b), _)| a + b <= 8)
            .map(|(k, (n, d))| (k, q(n, d)))
            .collect();
        let f = render(&list);
        let t = terms(&list);
        check_triangle(&f, &t);
        check_square(&f, &t);
    }
}

/// Exit code 2, nothing on stdout, one line on stderr starting `rootclip: `.
fn assert_fails_cleanly(args: &[&str]) -> String {
    let out = run(args);
    let stderr = String::from_utf8(out.stderr).expect("UTF-8 stderr");
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(
        out.stdout.is_empty(),
        "{args:?}: stdout {:?}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(stderr.starts_with("rootclip: "), "{args:?}: {stderr:?}");
    assert!(stderr.ends_with('\n'), "{args:?}: {stderr:?}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr:?}");
    assert!(!stderr.contains('\r'), "{args:?}: {stderr:?}");
    stderr
}

#[test]
fn malformed_polynomials_fail_cleanly() {
    for f in [
        "u^",
        "3*(u+v",
        "u^-1",
        "x",
        "1/0",
        "",
        "2u",
        "u/v",
        "u^2^3",
        "(u+v)^300",
        "u\n+\nx",
        "é",
    ] {
        for domain in ["triangle", "square"] {
            let err = assert_fails_cleanly(&["bernstein", "--f", f, "--domain", domain, "--json"]);
            assert!(err.contains("parse error"), "{f:?}: {err}");
        }
    }
}

#[test]
fn malformed_arguments_fail_cleanly() {
    assert_fails_cleanly(&["bernstein"]);
    assert_fails_cleanly(&["bernstein", "--f"]);
    assert_fails_cleanly(&["bernstein", "--f", "u", "--domain", "cube"]);
    assert_fails_cleanly(&["bernstein", "--f", "u", "--domain", "tri\nangle"]);
    assert_fails_cleanly(&["bernstein", "--f", "u", "--bogus"]);
    assert_fails_cleanly(&["bernstein", "--f", "u", "--json=yes"]);
    assert_fails_cleanly(&["frobnicate"]);
}

#[test]
fn help_goes_to_stdout() {
    let out = run(&["bernstein", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("--domain"));
}
