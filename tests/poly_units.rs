//! Unit tests of the polynomial layer: the parser (exact decimals, malformed
//! input, round trips, garbage that must not panic), constructor contracts,
//! storage order, and the example systems of Liu et al. (2016) §4, read from
//! `papers/hybrid-clipping-2016/paper_tables.json`.

use inari::Interval;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::Config;
use rootclip::poly::{tri_index, tri_indices, tri_len};
use rootclip::{parse_polynomial, Error, Polynomial, TensorBezier, TriBezier, UniBezier};
use serde_json::Value;

type Q = BigRational;

fn q(n: i64, d: i64) -> Q {
    Q::new(n.into(), d.into())
}

fn parse(s: &str) -> Polynomial {
    parse_polynomial(s).unwrap_or_else(|e| panic!("{s:?} should parse: {e}"))
}

/// A rational written as `n` or `n/d` in the data file.
fn rational(s: &str) -> Q {
    match s.split_once('/') {
        Some((n, d)) => Q::new(n.trim().parse().unwrap(), d.trim().parse().unwrap()),
        None => Q::from_integer(s.trim().parse().unwrap()),
    }
}

/// `Σ c u^a v^b` straight from the terms (independent of `Polynomial::eval`).
fn eval_terms(p: &Polynomial, u: &Q, v: &Q) -> Q {
    p.terms()
        .iter()
        .map(|((a, b), c)| c * num_traits::pow(u.clone(), *a as usize) * num_traits::pow(v.clone(), *b as usize))
        .sum()
}

fn cfg(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

// ---------------------------------------------------------------------------
// Parser: exact numbers, precedence, malformed input
// ---------------------------------------------------------------------------

#[test]
fn decimals_are_exact() {
    let cases = [
        ("0.1", q(1, 10)),
        ("2.5e-3", q(1, 400)),
        ("2.5E+3", q(2500, 1)),
        (".5", q(1, 2)),
        ("5.", q(5, 1)),
        ("1e0", q(1, 1)),
        ("007.250", q(29, 4)),
        ("1/3", q(1, 3)),
        ("0.3333", q(3333, 10000)),
        ("-0.125", q(-1, 8)),
        ("1e-30", Q::new(BigInt::one(), num_traits::pow(BigInt::from(10), 30))),
    ];
    for (src, want) in cases {
        assert_eq!(parse(src).as_constant(), Some(want.clone()), "{src}");
    }
    // 0.1 is 1/10, not the float nearest to it.
    assert_ne!(parse("0.1").as_constant(), Q::from_float(0.1));
}

#[test]
fn precedence_and_associativity() {
    let (u, v) = (q(3, 7), q(-5, 11));
    let at = |s: &str| eval_terms(&parse(s), &u, &v);
    assert_eq!(at("-u^2"), -(&u * &u));
    assert_eq!(at("(-u)^2"), &u * &u);
    assert_eq!(at("2-3-4"), q(-5, 1));
    assert_eq!(at("1/2/2"), q(1, 4));
    assert_eq!(at("2^3"), q(8, 1));
    assert_eq!(at("2*u^2*v/3"), q(2, 3) * &u * &u * &v);
    assert_eq!(at("u - -v"), &u + &v);
    assert_eq!(at("u*-v"), -(&u * &v));
    assert_eq!(at("u^0"), Q::one());
    assert_eq!(at("  u\t+\nv  "), &u + &v);
    assert_eq!(parse("u^2 - u^2").to_string(), "0");
    assert!(parse("(u - v)*(u + v) - (u^2 - v^2)").is_zero());
}

#[test]
fn malformed_inputs_are_errors() {
    let bad = [
        "u^",
        "3*(u+v",
        "u^-1",
        "x",
        "1/0",
        "",
        "   ",
        "2u",
        "u/v",
        "u^2^3",
        "(u+v)^300",
        "u^1.5",
        "u+",
        "*u",
        "()",
        "u)",
        ".",
        "1e",
        "1e+",
        "1e99999",
        "u/(v-v+0)",
        "u^200*v",
        "uv",
        "u v",
        "1..2",
        "ü",
    ];
    for src in bad {
        match parse_polynomial(src) {
            Err(Error::Parse { at, .. }) => assert!(at <= src.len(), "{src:?}: offset {at} past the end"),
            other => panic!("{src:?} should be a parse error, got {other:?}"),
        }
    }
}

#[test]
fn error_offsets_point_at_the_problem() {
    let at = |s: &str| match parse_polynomial(s) {
        Err(Error::Parse { at, .. }) => at,
        other => panic!("{s:?}: {other:?}"),
    };
    assert_eq!(at("x"), 0);
    assert_eq!(at("u + x"), 4);
    assert_eq!(at("u^"), 2);
    assert_eq!(at("1/0"), 1);
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!("{}u{}", "(".repeat(100_000), ")".repeat(100_000));
    assert!(parse_polynomial(&deep).is_err());
    let signs = format!("{}u", "-".repeat(100_000));
    assert!(parse_polynomial(&signs).is_err());
    // Moderate nesting is fine.
    let ok = format!("{}u{}", "(".repeat(50), ")".repeat(50));
    assert_eq!(parse(&ok), Polynomial::u());
    // Long flat sums are not nesting.
    let long = vec!["u"; 5000].join("+");
    assert_eq!(parse(&long), Polynomial::monomial(q(5000, 1), 1, 0));
}

#[test]
fn degree_limit_is_exact() {
    assert_eq!(parse("u^200").total_degree(), 200);
    assert_eq!(parse("u^100*v^100").total_degree(), 200);
    assert!(parse_polynomial("u^100*v^101").is_err());
    assert!(parse_polynomial("u^201").is_err());
    // Zero times anything stays allowed (degree of the product is 0).
    assert!(parse("0*u^200*u^200").is_zero());
}

// ---------------------------------------------------------------------------
// Parser properties
// ---------------------------------------------------------------------------

fn rat() -> impl Strategy<Value = Q> {
    (-50i64..50, 1i64..20).prop_map(|(n, d)| q(n, d))
}

fn polynomial(max_deg: u32) -> impl Strategy<Value = Polynomial> {
    vec((0..=max_deg, 0..=max_deg, rat()), 0..10).prop_map(|terms| {
        terms
            .into_iter()
            .fold(Polynomial::zero(), |p, (a, b, c)| p.add(&Polynomial::monomial(c, a, b)))
    })
}

/// An expression tree with its exact value computed alongside.
#[derive(Clone, Debug)]
enum Expr {
    /// A decimal literal (as written) and its value.
    Num(String, Q),
    U,
    V,
    Add(Box<Expr>, Box<Expr>),
    Sub(Box<Expr>, Box<Expr>),
    Mul(Box<Expr>, Box<Expr>),
    Neg(Box<Expr>),
    Pow(Box<Expr>, u32),
    /// Division by a non-zero literal.
    Div(Box<Expr>, String, Q),
}

impl Expr {
    fn prec(&self) -> u8 {
        match self {
            Expr::Add(..) | Expr::Sub(..) => 1,
            Expr::Mul(..) | Expr::Div(..) => 2,
            Expr::Neg(..) => 3,
            Expr::Pow(..) => 4,
            _ => 5,
        }
    }

    /// Renders with the fewest parentheses the grammar needs.
    fn render(&self) -> String {
        let wrap = |e: &Expr, min: u8| {
            if e.prec() >= min {
                e.render()
            } else {
                format!("({})", e.render())
            }
        };
        match self {
            Expr::Num(s, _) => s.clone(),
            Expr::U => "u".into(),
            Expr::V => "v".into(),
            Expr::Add(a, b) => format!("{} + {}", wrap(a, 1), wrap(b, 2)),
            Expr::Sub(a, b) => format!("{} - {}", wrap(a, 1), wrap(b, 2)),
            Expr::Mul(a, b) => format!("{}*{}", wrap(a, 2), wrap(b, 3)),
            Expr::Neg(a) => format!("-{}", wrap(a, 3)),
            Expr::Pow(a, e) => format!("{}^{e}", wrap(a, 5)),
            Expr::Div(a, s, _) => format!("{}/{s}", wrap(a, 2)),
        }
    }

    fn value(&self, u: &Q, v: &Q) -> Q {
        match self {
            Expr::Num(_, x) => x.clone(),
            Expr::U => u.clone(),
            Expr::V => v.clone(),
            Expr::Add(a, b) => a.value(u, v) + b.value(u, v),
            Expr::Sub(a, b) => a.value(u, v) - b.value(u, v),
            Expr::Mul(a, b) => a.value(u, v) * b.value(u, v),
            Expr::Neg(a) => -a.value(u, v),
            Expr::Pow(a, e) => num_traits::pow(a.value(u, v), *e as usize),
            Expr::Div(a, _, x) => a.value(u, v) / x,
        }
    }
}

/// A decimal literal such as `12`, `0.25`, `.5`, `3.`, `2.5e-3`, `7E+1`.
fn literal() -> impl Strategy<Value = (String, Q)> {
    (
        "[0-9]{0,3}",
        proptest::option::of("[0-9]{0,3}"),
        proptest::option::of((any::<bool>(), 0u32..4, "[eE]")),
    )
        .prop_filter("needs a digit", |(i, f, _)| {
            !i.is_empty() || f.as_deref().is_some_and(|f| !f.is_empty())
        })
        .prop_map(|(int, frac, exp)| {
            let mut s = int.clone();
            let mut digits = int;
            let mut scale: i64 = 0;
            if let Some(f) = frac {
                s += ".";
                s += &f;
                digits += &f;
                scale -= f.len() as i64;
            }
            if let Some((neg, e, mark)) = exp {
                s += &format!("{mark}{}{e}", if neg { "-" } else { "+" });
                scale += if neg { -i64::from(e) } else { i64::from(e) };
            }
            let mantissa = Q::from_integer(digits.parse::<BigInt>().unwrap_or_default());
            let ten = Q::from_integer(BigInt::from(10));
            let value = if scale >= 0 {
                mantissa * num_traits::pow(ten, scale as usize)
            } else {
                mantissa / num_traits::pow(ten, (-scale) as usize)
            };
            (s, value)
        })
}

fn expr() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        literal().prop_map(|(s, x)| Expr::Num(s, x)),
        Just(Expr::U),
        Just(Expr::V),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| Expr::Add(Box::new(a), Box::new(b))),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| Expr::Sub(Box::new(a), Box::new(b))),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| Expr::Mul(Box::new(a), Box::new(b))),
            inner.clone().prop_map(|a| Expr::Neg(Box::new(a))),
            (inner.clone(), 0u32..3).prop_map(|(a, e)| Expr::Pow(Box::new(a), e)),
            (inner, literal().prop_filter("non-zero", |(_, x)| !x.is_zero())).prop_map(|(a, (s, x))| Expr::Div(
                Box::new(a),
                s,
                x
            )),
        ]
    })
}

proptest! {
    #![proptest_config(cfg(256))]

    #[test]
    fn display_parse_round_trip(p in polynomial(12)) {
        let text = p.to_string();
        prop_assert_eq!(parse_polynomial(&text), Ok(p), "{}", text);
    }

    #[test]
    fn parsed_expression_has_exact_value(e in expr(), u in rat(), v in rat()) {
        let text = e.render();
        let p = parse_polynomial(&text).map_err(|err| TestCaseError::fail(format!("{text:?}: {err}")))?;
        prop_assert_eq!(eval_terms(&p, &u, &v), e.value(&u, &v), "{}", text);
        prop_assert_eq!(p.eval(&u, &v), e.value(&u, &v));
    }

    #[test]
    fn garbage_never_panics(s in "[uv0-9+*/^().eE -]{0,30}") {
        if let Ok(p) = parse_polynomial(&s) {
            // Whatever parses prints back to itself.
            prop_assert_eq!(parse_polynomial(&p.to_string()), Ok(p));
        }
    }

    #[test]
    fn unicode_never_panics(s in any::<String>()) {
        let _ = parse_polynomial(&s);
    }

    #[test]
    fn garbage_near_valid_never_panics(e in expr(), cut in any::<prop::sample::Index>(), junk in "[^a-z]{0,3}") {
        // Splice junk into a valid expression at a char boundary.
        let text = e.render();
        let mut at = cut.index(text.len() + 1);
        while !text.is_char_boundary(at) {
            at -= 1;
        }
        let s = format!("{}{junk}{}", &text[..at], &text[at..]);
        let _ = parse_polynomial(&s);
    }
}

// ---------------------------------------------------------------------------
// Constructor contracts and storage order
// ---------------------------------------------------------------------------

#[test]
fn triangle_storage_is_j_outer_i_inner() {
    for n in 0..=8 {
        let f = TriBezier::from_fn(n, |i, j, k| (100 * i + 10 * j + k) as f64);
        let mut pos = 0;
        for j in 0..=n {
            for i in 0..=n - j {
                let k = n - i - j;
                assert_eq!(f.coeffs()[pos], (100 * i + 10 * j + k) as f64);
                assert_eq!(tri_index(n, i, j), pos);
                assert_eq!(*f.coeff(i, j), f.coeffs()[pos]);
                pos += 1;
            }
        }
        assert_eq!(pos, tri_len(n));
        assert_eq!(tri_indices(n).count(), tri_len(n));
    }
}

#[test]
fn constructors_reject_bad_input() {
    assert!(matches!(TriBezier::new(2, vec![0.0; 5]), Err(Error::Shape(_))));
    assert!(matches!(
        TriBezier::new(1, vec![0.0, f64::NAN, 1.0]),
        Err(Error::NonFinite(_))
    ));
    assert!(matches!(
        TriBezier::new(0, vec![f64::INFINITY]),
        Err(Error::NonFinite(_))
    ));
    assert!(matches!(UniBezier::<f64>::on_unit(vec![]), Err(Error::Shape(_))));
    assert!(matches!(
        UniBezier::new(vec![1.0], [1.0, 1.0]),
        Err(Error::Degenerate(_))
    ));
    assert!(matches!(
        UniBezier::new(vec![1.0], [2.0, 1.0]),
        Err(Error::Degenerate(_))
    ));
    assert!(matches!(
        UniBezier::new(vec![1.0], [0.0, f64::NAN]),
        Err(Error::NonFinite(_))
    ));
    // An interval domain must be provably non-empty.
    let overlap = [
        Interval::try_from((0.0, 1.0)).unwrap(),
        Interval::try_from((0.5, 2.0)).unwrap(),
    ];
    assert!(UniBezier::new(vec![Interval::try_from((1.0, 1.0)).unwrap()], overlap).is_err());
    assert!(matches!(
        TensorBezier::on_unit_square(1, 1, vec![0.0; 3]),
        Err(Error::Shape(_))
    ));
    assert!(TensorBezier::new(0, 0, vec![0.0], [0.0, 1.0], [3.0, 3.0]).is_err());
    assert!(TensorBezier::on_unit_square(0, 0, vec![f64::NAN]).is_err());
    let f = TriBezier::new(2, vec![0.0; 6]).unwrap();
    assert!(f.elevate(1).is_err());
    assert!(f.reduce_l2(2).is_err());
    assert!(f.reduce_l2(3).is_err());
    let p = UniBezier::on_unit(vec![0.0, 1.0]).unwrap();
    for x in [0.0, 1.0, -0.5, 2.0, f64::NAN] {
        assert!(p.subdivide(x).is_err(), "split at {x}");
    }
}

#[test]
fn derivative_of_constant_is_zero_constant() {
    let f = TriBezier::new(0, vec![q(7, 3)]).unwrap();
    for d in [f.deriv_u(), f.deriv_v()] {
        assert_eq!(d.degree(), 0);
        assert!(d.is_zero());
    }
    let g = UniBezier::new(vec![q(7, 3)], [q(-1, 1), q(2, 1)]).unwrap();
    assert_eq!(g.deriv().coeffs(), &[Q::zero()]);
}

// ---------------------------------------------------------------------------
// Liu et al. (2016) §4 example systems, from the data file
// ---------------------------------------------------------------------------

fn examples() -> serde_json::Map<String, Value> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/papers/hybrid-clipping-2016/paper_tables.json"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let data: Value = serde_json::from_str(&text).expect("valid JSON");
    data["examples"].as_object().expect("examples object").clone()
}

fn system(ex: &Value) -> (Polynomial, Polynomial) {
    (parse(ex["f"].as_str().unwrap()), parse(ex["g"].as_str().unwrap()))
}

/// `f_ij` of the degree-`n` BB form on the unit triangle, by `(i, j)`.
fn tri_coeffs(p: &Polynomial) -> impl Fn(usize, usize) -> Q {
    let f = p.to_triangle(0);
    move |i, j| f.coeff(i, j).clone()
}

#[test]
fn example_files_have_the_expected_shape() {
    let ex = examples();
    for key in ["1", "2", "3k0", "3k2", "3k5"] {
        assert!(ex.contains_key(key), "missing example {key}");
    }
    for (key, e) in &ex {
        let (f, g) = system(e);
        assert!(!f.is_zero() && !g.is_zero(), "example {key}");
        assert!(
            e.get("roots").is_some() || e.get("roots_approx").is_some(),
            "example {key}"
        );
    }
}

#[test]
fn example_1_bb_coefficients() {
    // u^3 → [i = 3]; v → j/3 (from v = v (u + v + w)^2); constants are constant.
    let ex = examples();
    let (f, g) = system(&ex["1"]);
    assert_eq!(f.to_triangle(0).degree(), 3);
    let (fc, gc) = (tri_coeffs(&f), tri_coeffs(&g));
    for (i, j, _) in tri_indices(3) {
        let cube = if i == 3 { Q::one() } else { Q::zero() };
        let v = q(j as i64, 3);
        assert_eq!(fc(i, j), &cube - &v, "f_{i}{j}");
        assert_eq!(gc(i, j), cube + v - q(1, 4), "g_{i}{j}");
    }
    assert_eq!(fc(3, 0), Q::one());
    assert_eq!(fc(0, 3), -Q::one());
}

#[test]
fn example_2_bb_coefficients() {
    // p(u) = 10(u − 1/2)(u − 1/4)(u − 1/8) = 10u³ − 35/4 u² + 35/16 u − 5/32.
    // A function of u alone has f_ijk = c_i, the univariate BB coefficients
    // c_i = Σ_{a≤i} C(i,a)/C(3,a) m_a: −5/32, 55/96, −155/96, 105/32.
    let c = [q(-5, 32), q(55, 96), q(-155, 96), q(105, 32)];
    let ex = examples();
    let (f, g) = system(&ex["2"]);
    let (fc, gc) = (tri_coeffs(&f), tri_coeffs(&g));
    for (i, j, _) in tri_indices(3) {
        let rest = q(1, 4) - q(j as i64, 3);
        assert_eq!(fc(i, j), &c[i] + &rest, "f_{i}{j}");
        assert_eq!(gc(i, j), -&c[i] + rest, "g_{i}{j}");
    }
}

#[test]
fn example_3_bb_coefficients() {
    // u² → [i = 2], v² → [j = 2], uv → ij/2 in degree 2.
    let ex = examples();
    for (key, k) in [("3k0", 0u32), ("3k2", 2), ("3k5", 5)] {
        let (f, g) = system(&ex[key]);
        let r = q(1, 4) * (Q::one() + Q::new(BigInt::one(), num_traits::pow(BigInt::from(10), k as usize)));
        let (fc, gc) = (tri_coeffs(&f), tri_coeffs(&g));
        for (i, j, _) in tri_indices(2) {
            let sq = |x| if x == 2 { Q::one() } else { Q::zero() };
            assert_eq!(fc(i, j), sq(i) + sq(j) - &r, "{key}: f_{i}{j}");
            assert_eq!(gc(i, j), q((i * j) as i64, 2) - q(1, 8), "{key}: g_{i}{j}");
        }
    }
}

#[test]
fn example_roots_make_the_system_vanish() {
    let mut exact_roots = 0;
    let mut approx_roots = 0;
    for (key, e) in &examples() {
        let (f, g) = system(e);
        for r in e.get("roots").and_then(Value::as_array).into_iter().flatten() {
            let (u, v) = (rational(r[0].as_str().unwrap()), rational(r[1].as_str().unwrap()));
            assert!(eval_terms(&f, &u, &v).is_zero(), "{key}: f({u}, {v}) ≠ 0");
            assert!(eval_terms(&g, &u, &v).is_zero(), "{key}: g({u}, {v}) ≠ 0");
            // Roots lie in the closed unit triangle, where the BB form vanishes too.
            assert!(u >= Q::zero() && v >= Q::zero() && &u + &v <= Q::one());
            let w = Q::one() - &u - &v;
            let bary = [u.clone(), v.clone(), w];
            assert!(f.to_triangle(0).eval_bary(&bary).is_zero());
            assert!(g.to_triangle(0).eval_bary(&bary).is_zero());
            exact_roots += 1;
        }
        for r in e.get("roots_approx").and_then(Value::as_array).into_iter().flatten() {
            let (u, v) = (r[0].as_f64().unwrap(), r[1].as_f64().unwrap());
            let (uq, vq) = (Q::from_float(u).unwrap(), Q::from_float(v).unwrap());
            for (name, p) in [("f", &f), ("g", &g)] {
                let val = eval_terms(p, &uq, &vq);
                let err = num_traits::ToPrimitive::to_f64(&val).unwrap().abs();
                assert!(err < 1e-14, "{key}: {name}({u}, {v}) = {err:e}");
            }
            assert!(
                u > 0.0 && v > 0.0 && u + v < 1.0,
                "{key}: ({u}, {v}) outside the triangle"
            );
            approx_roots += 1;
        }
    }
    assert_eq!((exact_roots, approx_roots), (4, 6));
}

// ---------------------------------------------------------------------------
// Regressions
// ---------------------------------------------------------------------------

#[test]
fn from_triangle_works_past_the_parser_degree_limit() {
    // Used to panic ("bounded") for any degree above MAX_DEGREE = 200.
    let n = 203;
    let nonzero = [
        (n, 0, q(1, 2)),
        (100, 100, q(-3, 7)),
        (0, 190, q(5, 1)),
        (150, 23, q(2, 9)),
    ];
    let mut coeffs = vec![Q::zero(); tri_len(n)];
    for (i, j, c) in &nonzero {
        coeffs[tri_index(n, *i, *j)] = c.clone();
    }
    let p = Polynomial::from_triangle(&TriBezier::new(n, coeffs).unwrap());
    assert_eq!(p.total_degree() as usize, n);
    let fact = |n: usize| (1..=n).fold(BigInt::one(), |a, t| a * t);
    for (u, v) in [(q(1, 3), q(1, 5)), (q(-1, 2), q(3, 4)), (q(1, 1), q(0, 1))] {
        let w = Q::one() - &u - &v;
        // Σ c_ijk n!/(i! j! k!) u^i v^j w^k over the non-zero coefficients.
        let want: Q = nonzero
            .iter()
            .map(|(i, j, c)| {
                let k = n - i - j;
                let multi = Q::new(fact(n), fact(*i) * fact(*j) * fact(k));
                c * multi
                    * num_traits::pow(u.clone(), *i)
                    * num_traits::pow(v.clone(), *j)
                    * num_traits::pow(w.clone(), k)
            })
            .sum();
        assert_eq!(eval_terms(&p, &u, &v), want);
    }
}

#[test]
fn tensor_with_collapsed_domain_after_map_does_not_panic() {
    // A valid exact domain [1, 1 + 10^-30] rounds to the point 1.0 in f64 and
    // to overlapping intervals; evaluation and derivatives used to panic.
    let tiny = Q::new(BigInt::one(), num_traits::pow(BigInt::from(10), 30));
    let f = TensorBezier::new(
        1,
        1,
        vec![q(1, 1), q(2, 1), q(3, 1), q(4, 1)],
        [q(1, 1), q(1, 1) + tiny],
        [q(0, 1), q(1, 1)],
    )
    .unwrap();
    let ff = f.map(rootclip::scalar::rational_to_f64);
    let _ = ff.eval(1.0, 0.5);
    let _ = ff.deriv(rootclip::poly::Direction::U);
    let fi = f.map(rootclip::scalar::rational_to_interval);
    let point = |x: f64| Interval::try_from((x, x)).unwrap();
    let y = fi.eval(point(1.0), point(0.5));
    // Still an enclosure: f is 1 + v·1 + … at u = 1 (local s = 0): 1 + 0.5 = 1.5.
    assert!(y.contains(1.5), "{y:?}");
    let _ = fi.deriv(rootclip::poly::Direction::U);
}
