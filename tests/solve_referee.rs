//! Referee tests of the certified solver against independent computations:
//! exact rational roots of the paper's systems, Newton's method on random
//! dense systems, and hand-checked degenerate and multiple-root cases.

use num_rational::BigRational;
use num_traits::ToPrimitive;
use rootclip::solve::{solve, Domain, Method, Solution, SolveOptions, SquareRoute, TriangleRoute};
use rootclip::{parse_polynomial, Polynomial};
use serde_json::Value;

const PAPER: &str = include_str!("../papers/hybrid-clipping-2016/paper_tables.json");

fn q(s: &str) -> BigRational {
    let p = parse_polynomial(s).expect("rational");
    p.as_constant().expect("a constant")
}

/// Every method on the tri-boxes, then the box route (which has no method).
fn method_routes(methods: &[Method]) -> Vec<(Method, TriangleRoute)> {
    let mut out: Vec<_> = methods.iter().map(|&m| (m, TriangleRoute::Triangle)).collect();
    out.push((Method::Hc, TriangleRoute::Rect));
    out
}

/// Every box of `sol` that contains the exact point `(u, v)`, compared exactly.
fn covering(sol: &Solution, u: &BigRational, v: &BigRational) -> usize {
    let inside = |lo: f64, hi: f64, x: &BigRational| {
        BigRational::from_float(lo).unwrap() <= *x && *x <= BigRational::from_float(hi).unwrap()
    };
    sol.roots
        .iter()
        .filter(|r| inside(r.bx.u[0], r.bx.u[1], u) && inside(r.bx.v[0], r.bx.v[1], v))
        .count()
}

#[test]
fn paper_examples_exact_roots_are_certified_once_by_every_method() {
    let data: Value = serde_json::from_str(PAPER).unwrap();
    for name in ["1", "2"] {
        let e = &data["examples"][name];
        let f = parse_polynomial(e["f"].as_str().unwrap()).unwrap();
        let g = parse_polynomial(e["g"].as_str().unwrap()).unwrap();
        let roots: Vec<(BigRational, BigRational)> = e["roots"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| (q(r[0].as_str().unwrap()), q(r[1].as_str().unwrap())))
            .collect();
        for root in &roots {
            assert_eq!(f.eval(&root.0, &root.1), BigRational::from_integer(0.into()));
        }
        for (method, route) in method_routes(&Method::ALL) {
            let sol = solve(&f, &g, Domain::Triangle, &{
                let mut o = SolveOptions::default();
                o.method = method;
                o.triangle_route = route;
                o
            })
            .unwrap();
            assert!(
                sol.complete && sol.clusters.is_empty(),
                "example {name} {method} {route:?}"
            );
            assert_eq!(sol.roots.len(), roots.len(), "example {name} {method} {route:?}");
            for (u, v) in &roots {
                assert_eq!(
                    covering(&sol, u, v),
                    1,
                    "example {name} {method} {route:?}: root ({u}, {v})"
                );
            }
        }
    }
}

#[test]
fn example_3_roots_are_certified_for_every_k() {
    let data: Value = serde_json::from_str(PAPER).unwrap();
    for name in ["3k0", "3k2", "3k5"] {
        let e = &data["examples"][name];
        let f = parse_polynomial(e["f"].as_str().unwrap()).unwrap();
        let g = parse_polynomial(e["g"].as_str().unwrap()).unwrap();
        let sol = solve(&f, &g, Domain::Triangle, &SolveOptions::default()).unwrap();
        assert!(
            sol.complete && sol.clusters.is_empty() && sol.roots.len() == 2,
            "{name}"
        );
        for r in e["roots_approx"].as_array().unwrap() {
            let (u, v) = (r[0].as_f64().unwrap(), r[1].as_f64().unwrap());
            assert!(
                sol.roots
                    .iter()
                    .any(|x| (x.u - u).abs() < 1e-12 && (x.v - v).abs() < 1e-12),
                "{name}"
            );
        }
    }
}

#[test]
fn exact_double_root_is_one_small_cluster_never_a_certificate() {
    let f = parse_polynomial("u^2 + v^2 - 1/4").unwrap();
    let g = parse_polynomial("u*v - 1/8").unwrap();
    let sol = solve(&f, &g, Domain::Triangle, &SolveOptions::default()).unwrap();
    let r = 2f64.sqrt() / 4.0;
    assert!(sol.complete && sol.roots.is_empty());
    assert!(sol.clusters.iter().any(|c| c.bx.contains(r, r)));
    assert!(sol.clusters.iter().all(|c| c.bx.u[1] - c.bx.u[0] < 1e-6));
}

#[test]
fn degenerate_systems_are_errors() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    for domain in [Domain::Triangle, Domain::Square] {
        for (f, g) in [
            ("0", "u - v"),
            ("(u-v)*(u+1/3)", "(u-v)*(v-1/5)"),
            ("u - 1/3", "3*u - 1"),
        ] {
            assert!(
                solve(&p(f), &p(g), domain, &SolveOptions::default()).is_err(),
                "{f}; {g}"
            );
        }
    }
    let bad = {
        let mut o = SolveOptions::default();
        o.eps = f64::NAN;
        o
    };
    assert!(solve(&p("u"), &p("v"), Domain::Triangle, &bad).is_err());
    let none = solve(&p("3/7"), &p("u - v"), Domain::Triangle, &SolveOptions::default()).unwrap();
    assert!(none.complete && none.roots.is_empty() && none.clusters.is_empty());
}

/// `f = s·(t − ¼) + e`, `g = s·(s + t − 1) + e` on the unit square, where the
/// edge coefficients `e` are intervals around 0 (as from a ray through a
/// collapsed patch edge): the edge `s = 0` may be a curve of roots. It comes
/// back as one thin undecided strip, the isolated root `(¾, ¼)` certified,
/// and the run complete; before the strip cut it ran out of budget.
#[test]
fn rectangle_edge_where_both_equations_may_vanish_is_one_strip() {
    use inari::interval;
    use rootclip::internals::rect::{solve_rect, RectOptions};
    use rootclip::poly::TensorBezier;
    use rootclip::solve::UndecidedReason;
    let e = interval!(-1e-18, 1e-18).unwrap();
    let pt = |x: f64| interval!(x, x).unwrap();
    // Bidegree (2, 1), row-major (i, j); rows i = 0 vanish up to e.
    let f = [e, e, pt(-0.125), pt(0.375), pt(-0.25), pt(0.75)];
    let g = [e, e, pt(-0.5), pt(0.0), pt(0.0), pt(1.0)];
    let f = TensorBezier::on_unit_square(2, 1, f.to_vec()).unwrap();
    let g = TensorBezier::on_unit_square(2, 1, g.to_vec()).unwrap();
    let sol = solve_rect(&f, &g, None, &RectOptions::default()).unwrap().solution;
    assert!(sol.complete, "{sol:?}");
    assert!(sol.stats.boxes < 100, "{:?}", sol.stats);
    assert_eq!(sol.roots.len(), 1, "{sol:?}");
    assert!(sol.roots[0].bx.contains(0.75, 0.25));
    let strips: Vec<_> = sol
        .clusters
        .iter()
        .filter(|c| c.reason == UndecidedReason::VanishingEdge)
        .collect();
    assert_eq!(strips.len(), 1, "{sol:?}");
    let b = strips[0].bx;
    assert!(
        b.u[0] <= 0.0 && b.u[1] > 0.0 && b.u[1] < 1e-8 && b.v == [0.0, 1.0],
        "{b:?}"
    );
}

/// Triple roots (found by the referee fuzzing; each ran for minutes): one
/// planted inside, one 1e-12 outside the triangle. Each ends complete, in
/// one undecided region that holds the exact root, in a bounded number of
/// tri-boxes (the exact phase has a budget; tri-boxes whose separating
/// combination is lost to rounding stop splitting; nearby regions join).
#[test]
fn triple_roots_end_in_one_region_quickly() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    let cases = [
        (
            "-u^3 + 269999999973/190000000000*u^2 - 24299999995140000000243/36100000000000000000000*u + v + 728999999095400000021869999999271/6859000000000000000000000000000000",
            "v - 0.0000000001",
            Method::Hc,
            Some(("89999999991/190000000000", "1/10000000000")),
        ),
        (
            "v - 11/19",
            "-u^3 - 0.000000000003*u^2 - 0.000000000000000000000003*u + v - 11000000000000000000000000000000000019/19000000000000000000000000000000000000",
            Method::Bezier,
            None, // (-1/10^12, 11/19): outside, may or may not be covered
        ),
    ];
    for (f, g, method, root) in cases {
        let opts = {
            let mut o = SolveOptions::default();
            o.method = method;
            o
        };
        let sol = solve(&p(f), &p(g), Domain::Triangle, &opts).unwrap();
        assert!(sol.complete && sol.roots.is_empty(), "{f}; {g}: {sol:?}");
        // Since clips are proposed in f64 and verified
        // (fatcurve::VERIFY_MARGIN), the stalled tri-boxes around the first
        // triple root are separated by proven-empty gaps of ~1e-11; regions
        // that nearly touch are joined into one.
        assert_eq!(sol.clusters.len(), 1, "{f}; {g}: {:?}", sol.clusters);
        assert!(sol.stats.boxes < 50_000, "{:?}", sol.stats);
        if let Some((u, v)) = root {
            let (u, v) = (q(u), q(v));
            let inside = |lo: f64, hi: f64, x: &BigRational| {
                BigRational::from_float(lo).unwrap() <= *x && *x <= BigRational::from_float(hi).unwrap()
            };
            assert!(
                sol.clusters
                    .iter()
                    .any(|c| inside(c.bx.u[0], c.bx.u[1], &u) && inside(c.bx.v[0], c.bx.v[1], &v)),
                "{:?}",
                sol.clusters
            );
        }
    }
}

/// Bézier clipping lost roots next to a second root 1e-7..1e-9 away
/// (referee fuzzing): a coefficient enclosure straddling 0 was taken as a
/// control point *at* 0, while its negative end, paired with positive
/// neighbours, puts hull crossings away from it. Every exact root in the
/// closed domain must lie in a returned region, for every method.
#[test]
fn close_roots_are_covered_by_every_method() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    let cases = [
        (
            "(u-1/2)^2 - 1/1000000000000000000",
            "v - 1/4",
            Domain::Triangle,
            vec![("499999999/1000000000", "1/4"), ("500000001/1000000000", "1/4")],
        ),
        (
            "u^2 + 8*u*v + 16*v^2 - 27499997/30000000*u - 27499997/7500000*v + 151249967/720000000",
            "4*u - 5*v - 11/6",
            Domain::Triangle,
            vec![("11/24", "0")],
        ),
        (
            "16*u^2 + 8*u*v + v^2 - 16000000017/425000000*u - 16000000017/1700000000*v + 8000000017/361250000",
            "2*v - 24/17",
            Domain::Square,
            vec![("1", "12/17")],
        ),
    ];
    let inside = |lo: f64, hi: f64, x: &BigRational| {
        BigRational::from_float(lo).unwrap() <= *x && *x <= BigRational::from_float(hi).unwrap()
    };
    for (f, g, domain, roots) in cases {
        for (method, route) in method_routes(&Method::ALL) {
            let opts = {
                let mut o = SolveOptions::default();
                o.method = method;
                o.triangle_route = route;
                o
            };
            let sol = solve(&p(f), &p(g), domain, &opts).unwrap();
            assert!(sol.complete, "{method} {route:?} {f}; {g}");
            for (u, v) in &roots {
                let (u, v) = (q(u), q(v));
                let covered = sol
                    .roots
                    .iter()
                    .map(|r| r.bx)
                    .chain(sol.clusters.iter().map(|c| c.bx))
                    .any(|b| inside(b.u[0], b.u[1], &u) && inside(b.v[0], b.v[1], &v));
                assert!(covered, "{method} {route:?} {f}; {g}: root ({u}, {v}) missed: {sol:?}");
            }
        }
    }
}

/// Two simple roots 1e-8 and 1e-9 apart (`u = 1/3 ± d` on a slanted
/// line): rounding leaves one of them in an undecided leaf, and Krawczyk in
/// exact arithmetic (bisecting where needed) certifies both. Each exact root
/// must lie in exactly one certified box.
#[test]
fn close_simple_roots_are_certified_in_exact_arithmetic() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    for k in [8, 9] {
        let f = format!("(u-1/3)^2 - 1/10^{}", 2 * k);
        let g = "v - 1/4 + (u-1/3)/7";
        let sol = solve(&p(&f), &p(g), Domain::Triangle, &SolveOptions::default()).unwrap();
        assert!(
            sol.complete && sol.clusters.is_empty() && sol.roots.len() == 2,
            "{f}: {sol:?}"
        );
        for sign in [1, -1] {
            let d = BigRational::new(1.into(), num_bigint::BigInt::from(10).pow(k as u32));
            let u = q("1/3") + d.clone() * BigRational::from_integer(sign.into());
            let v = q("1/4") - (&u - q("1/3")) / BigRational::from_integer(7.into());
            assert_eq!(covering(&sol, &u, &v), 1, "{f}: root u = 1/3 {sign:+}e-{k}: {sol:?}");
        }
    }
}

/// Near-tangential pairs of simple roots (a line nearly tangent to a conic)
/// 1.6e-7 to 4.8e-7 apart, with conditions near 1e7: each root ends in its
/// own leaf at eps, where interval Krawczyk needs a box ~1e-9 wide (its
/// epsilon-inflation must grow towards K(X), not K(X) ∩ X) and exact
/// Krawczyk settles it if not (the leaves are retried before regions 1e-5
/// apart are joined). Found by referee round 5 as one undecided cluster
/// each; the hybrid methods must certify both roots of all three, Bézier
/// and linear clipping those of the first two (on the third their leaves
/// near (9/16, 7/12) form a region 2e-8 wide that exact Krawczyk, bisecting
/// three times, does not settle: an honest cluster). Each exact root lies in
/// exactly one box.
#[test]
fn near_tangential_close_roots_are_certified() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    let cases = [
        (
            "2*u + 4*v - 13/8",
            "u^2 + v^2 - 39/20*u - 227/80*v + 145434570312491/125000000000000",
            Domain::Triangle,
        ),
        (
            "3*u - 2*v",
            "u^2 + v^2 + 19/8*u - 47/16*v + 793457031249883/2500000000000000",
            Domain::Square,
        ),
        (
            "5*u + 3*v - 73/16",
            "16*u^2 + 24*u*v + 9*v^2 - 79999999/2500000*u - 239999997/10000000*v + 39999999/2500000",
            Domain::Square,
        ),
    ];
    for (i, (f, g, domain)) in cases.into_iter().enumerate() {
        let (fp, gp) = (p(f), p(g));
        let methods: &[Method] = if i < 2 {
            &Method::ALL
        } else {
            &[Method::HcNoPre, Method::Hc]
        };
        for (method, route) in method_routes(methods) {
            let opts = {
                let mut o = SolveOptions::default();
                o.method = method;
                o.triangle_route = route;
                o
            };
            let sol = solve(&fp, &gp, domain, &opts).unwrap();
            assert!(
                sol.complete && sol.clusters.is_empty() && sol.roots.len() == 2,
                "{f} | {g} ({method} {route:?}): {sol:?}"
            );
            let [a, b] = [&sol.roots[0].bx, &sol.roots[1].bx];
            assert!(a.u[1] < b.u[0] || b.u[1] < a.u[0] || a.v[1] < b.v[0] || b.v[1] < a.v[0]);
            if i == 0 && method == Method::Hc {
                // The first system's roots are rational, (3/8 ± 24/10^8,
                // 7/32 ∓ 12/10^8): both exact, each in exactly one box.
                for sign in [1i64, -1] {
                    let d = BigRational::new((24 * sign).into(), 100_000_000.into());
                    let (u, v) = (
                        q("3/8") + d.clone(),
                        q("7/32") - d / BigRational::from_integer(2.into()),
                    );
                    assert_eq!(fp.eval(&u, &v), q("0"));
                    assert_eq!(gp.eval(&u, &v), q("0"), "not a root: {u} {v}");
                    assert_eq!(covering(&sol, &u, &v), 1, "{sol:?}");
                }
            }
        }
    }
}

#[test]
fn square_diagonal_root_is_reported_once() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    let sol = solve(&p("u - v"), &p("u + v - 1"), Domain::Square, &SolveOptions::default()).unwrap();
    assert!(sol.complete && sol.roots.len() == 1 && sol.roots[0].bx.contains(0.5, 0.5));
    let sol = solve(&p("u*v - 1/8"), &p("u - v"), Domain::Square, &SolveOptions::default()).unwrap();
    assert!(sol.complete && sol.roots.len() == 1);
}

#[test]
fn roots_outside_the_domain_are_not_reported() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    // Root at (-1/1000, 1/2): outside the triangle.
    let sol = solve(
        &p("u + 1/1000"),
        &p("v - 1/2"),
        Domain::Triangle,
        &SolveOptions::default(),
    )
    .unwrap();
    assert!(sol.complete && sol.roots.is_empty() && sol.clusters.is_empty());
    // Root at (1/2, 1/2 + 1/10^6): outside by 1e-6 across u + v = 1.
    let sol = solve(
        &p("u - 1/2"),
        &p("v - 1/2 - 1/10^6"),
        Domain::Triangle,
        &SolveOptions::default(),
    )
    .unwrap();
    assert!(sol.roots.is_empty() && sol.clusters.is_empty());
}

struct Lcg(u64);

impl Lcg {
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + ((self.0 >> 33) % (hi - lo + 1) as u64) as i64
    }
}

fn random_poly(rng: &mut Lcg, deg: u32) -> Polynomial {
    let mut p = Polynomial::zero();
    for a in 0..=deg {
        for b in 0..=deg - a {
            let c = BigRational::new(rng.int(-20, 20).into(), rng.int(1, 9).into());
            p = p.add(&Polynomial::monomial(c, a, b));
        }
    }
    p
}

fn eval_grad(p: &Polynomial, u: f64, v: f64) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (&(a, b), c) in p.terms() {
        let c = c.to_f64().unwrap();
        out[0] += c * u.powi(a as i32) * v.powi(b as i32);
        if a > 0 {
            out[1] += c * a as f64 * u.powi(a as i32 - 1) * v.powi(b as i32);
        }
        if b > 0 {
            out[2] += c * b as f64 * u.powi(a as i32) * v.powi(b as i32 - 1);
        }
    }
    out
}

/// Newton from a grid of starts: an independent (heuristic) root finder.
fn newton_roots(f: &Polynomial, g: &Polynomial) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = Vec::new();
    for i in 0..=12 {
        for j in 0..=12 {
            let (mut u, mut v) = (i as f64 / 12.0, j as f64 / 12.0);
            for _ in 0..50 {
                let [fv, fu, fw] = eval_grad(f, u, v);
                let [gv, gu, gw] = eval_grad(g, u, v);
                let det = fu * gw - fw * gu;
                if det == 0.0 || !(u.abs() < 10.0 && v.abs() < 10.0) {
                    break;
                }
                u -= (fv * gw - fw * gv) / det;
                v -= (fu * gv - fv * gu) / det;
            }
            let (fv, gv) = (eval_grad(f, u, v)[0], eval_grad(g, u, v)[0]);
            let new = out.iter().all(|r| (r[0] - u).abs() + (r[1] - v).abs() > 1e-8);
            if fv.abs() < 1e-11 && gv.abs() < 1e-11 && new {
                out.push([u, v]);
            }
        }
    }
    out
}

#[test]
fn random_dense_systems_miss_no_newton_root() {
    let mut rng = Lcg(2026);
    let mut checked = 0;
    for k in 0..60 {
        let domain = if k % 2 == 0 { Domain::Triangle } else { Domain::Square };
        let (df, dg) = (rng.int(2, 6) as u32, rng.int(2, 6) as u32);
        let (f, g) = (random_poly(&mut rng, df), random_poly(&mut rng, dg));
        let sol = solve(&f, &g, domain, &SolveOptions::default()).expect("random systems are not degenerate");
        assert!(sol.complete, "system {k}");
        for (i, a) in sol.roots.iter().enumerate() {
            for b in &sol.roots[i + 1..] {
                let apart =
                    a.bx.u[1] < b.bx.u[0] || b.bx.u[1] < a.bx.u[0] || a.bx.v[1] < b.bx.v[0] || b.bx.v[1] < a.bx.v[0];
                assert!(apart, "system {k}: certified boxes overlap");
            }
        }
        let inside = |u: f64, v: f64| match domain {
            Domain::Triangle => u > 1e-9 && v > 1e-9 && u + v < 1.0 - 1e-9,
            Domain::Square => u > 1e-9 && v > 1e-9 && u < 1.0 - 1e-9 && v < 1.0 - 1e-9,
        };
        for [u, v] in newton_roots(&f, &g).into_iter().filter(|r| inside(r[0], r[1])) {
            checked += 1;
            let near = |b: &rootclip::solve::Box2| {
                b.u[0] - 1e-9 <= u && u <= b.u[1] + 1e-9 && b.v[0] - 1e-9 <= v && v <= b.v[1] + 1e-9
            };
            assert!(
                sol.roots.iter().any(|r| near(&r.bx)) || sol.clusters.iter().any(|c| near(&c.bx)),
                "system {k}: Newton root ({u}, {v}) not covered\nf = {f}\ng = {g}"
            );
        }
    }
    assert!(checked >= 5, "the referee must actually check roots ({checked})");
}

/// The target for the tables: `hc` needs no more levels than the
/// paper in any cell of Tables 1, 3 and 5 (recursion counts are
/// deterministic: no timing involved). With one role assignment (the
/// paper's clip) Example 3 with k = 2 and 5 are 1–2 levels behind, which is
/// why the second clip exists; that is checked too, so this test notices if
/// the swap stops mattering.
#[test]
fn hc_recursion_counts_match_or_beat_the_paper() {
    let (cells, _) = rootclip::internals::repro::tables(rootclip::internals::repro::Variant::DEFAULT).unwrap();
    let hc: Vec<_> = cells.iter().filter(|c| c.method == Method::Hc).collect();
    assert_eq!(hc.len(), 35);
    for c in &hc {
        let (ours, paper) = (c.ours.expect("every cell reached"), c.paper.expect("paper cell"));
        assert!(
            ours <= paper,
            "{} lg eps {}: {ours} > paper {paper}",
            c.example,
            c.lg_eps
        );
    }
    let (one_role, _) = rootclip::internals::repro::tables(rootclip::internals::repro::Variant::ONE_ROLE).unwrap();
    assert!(one_role
        .iter()
        .any(|c| c.method == Method::Hc && c.ours.unwrap_or(usize::MAX) > c.paper.unwrap_or(0)));
}

/// The plain-`f64` iteration (a heuristic, and the baseline of the cost of
/// rigor) ends near every root of the paper's systems with every method. It
/// used to lose them: its fat curves had only relative slack while the
/// subdivided coefficients carry absolute rounding noise.
#[test]
fn plain_f64_iteration_ends_near_every_root() {
    use rootclip::internals::solve_triangle_f64;
    use rootclip::scalar::rational_to_f64;
    for ex in rootclip::internals::repro::examples().unwrap() {
        let certified = solve(&ex.f, &ex.g, Domain::Triangle, &SolveOptions::default()).unwrap();
        assert!(certified.complete && !certified.roots.is_empty(), "{}", ex.name);
        let n = ex.f.total_degree().max(ex.g.total_degree()) as usize;
        let (f, g) = (
            ex.f.to_triangle(n).map(rational_to_f64),
            ex.g.to_triangle(n).map(rational_to_f64),
        );
        for method in Method::ALL {
            let opts = {
                let mut o = SolveOptions::default();
                o.method = method;
                o
            };
            let leaves = solve_triangle_f64(&f, &g, &opts);
            for r in &certified.roots {
                assert!(
                    leaves.iter().any(|p| (p[0] - r.u).hypot(p[1] - r.v) < 1e-6),
                    "example {} {method}: plain f64 lost the root ({}, {})",
                    ex.name,
                    r.u,
                    r.v
                );
            }
        }
    }
}

/// Equations scaled by 1e±300 are valid systems with the same roots (referee
/// round 7: their BB coefficients overflowed the float conversion, which
/// reported "non-finite input" or, converting the square to triangles,
/// panicked). Every method and square route certifies the exact root once.
#[test]
fn extreme_scales_are_solved() {
    let big = "1".to_string() + &"0".repeat(300);
    let cases = [
        (format!("{big}*(3*u - 1)"), "4*v - 1".to_string()),
        (format!("(3*u - 1)/{big}"), format!("{big}*(4*v - 1)*(u + 1)")),
        (format!("{big}*{big}*(3*u - 1)*u*v + (3*u - 1)"), "4*v - 1".to_string()),
    ];
    let (u, v) = (q("1/3"), q("1/4"));
    for (f, g) in &cases {
        let (fp, gp) = (parse_polynomial(f).unwrap(), parse_polynomial(g).unwrap());
        for domain in [Domain::Triangle, Domain::Square] {
            for (method, route) in method_routes(&Method::ALL) {
                for square_route in [SquareRoute::Triangles, SquareRoute::Rect] {
                    let opts = {
                        let mut o = SolveOptions::default();
                        o.method = method;
                        o.triangle_route = route;
                        o.square_route = square_route;
                        o
                    };
                    let sol = solve(&fp, &gp, domain, &opts).unwrap_or_else(|e| panic!("{f} | {g}: {e}"));
                    assert!(sol.complete, "{f} | {g} {domain:?} {method} {route:?}");
                    assert_eq!(
                        covering(&sol, &u, &v),
                        1,
                        "{f} | {g} {domain:?} {method} {route:?}: {sol:?}"
                    );
                }
            }
        }
    }
}

/// Referee round 7 (ball arithmetic), two regressions against the interval
/// version, both fixed:
/// * two simple roots 2.9e-10 apart (nearly tangent circles): a stalled
///   tri-box holding both, computed exactly, stopped at the float-precision
///   singular floor (1e-9) instead of being split; both must be certified;
/// * a sparse system whose terms span 1e-30..1e80: on the triangle left after
///   the vanishing edge u = 0 is cut, `g`'s coefficients are all positive but
///   ~1e-37, below one ball radius sized for the largest; they must be
///   proven one by one (exact recomputation), not split 50,000 times.
#[test]
fn referee_round7_regressions() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    let (f, g) = (
        p("v^2 + u^2 - 71/35*v - 2/15*u + 10399/11025"),
        p("v^2 + u^2 - 35200000000000000007/56000000000000000000*v - 2/15*u - 6410239999999999995564799999999999999559/112896000000000000000000000000000000000000"),
    );
    let sol = solve(&f, &g, Domain::Triangle, &SolveOptions::default()).unwrap();
    assert!(
        sol.complete && sol.clusters.is_empty() && sol.roots.len() == 2,
        "{sol:?}"
    );
    let (f, g) = (
        p("5/7*v^4 + u*v^3 + 1/600000000000000000000000000000*u^2*v^2 - 700000000000000000012000000000000000000060000000000000000001180000000000000000077/21*u^3*v + 1/3500000000000000000000000000000*u^4 + 3/7*u*v^2 - 1/5000000000000000000000000000000*u^2*v + 1/3*u^3 + 2/7*u*v + 1/175000000000000000000000000000"),
        p("-2*u*v^3 - 2/3*u^2*v^2 + 3/2*u^3*v + 4199999999999999999944000000000000000000119999999999999999992020000000000000000049/42*u^4 + 2/5*v^3 + 3/2*u^3 + 3/7*v^2 - 5/7*u^2 + 4/3*u - 1"),
    );
    for (method, route) in method_routes(&Method::ALL) {
        let opts = {
            let mut o = SolveOptions::default();
            o.method = method;
            o.triangle_route = route;
            o
        };
        let sol = solve(&f, &g, Domain::Triangle, &opts).unwrap();
        assert!(
            sol.complete && sol.stats.boxes < 100,
            "{method} {route:?}: {:?}",
            sol.stats
        );
    }
    // Round 8: two cubics running within ~1e-10 of each other along an arc;
    // the finer singular floor of exact coefficients, unbounded, split that
    // arc until the 50,000-box budget ran out (the interval version
    // completed). It is bounded now (`driver::FINE_BUDGET`).
    let (f, g) = (p("-36/35*u*v^4 - 2400000000000000000009/7000000000000000000000*u*v^3 - 18/35*u^2*v^2 - 6*v^3 + 351428571428571428571/500000000000000000000*u*v^2 - 3/5*u^2*v + 2999999999999999999991/1000000000000000000000*v^2 - 54543999999999999999997/16800000000000000000000*u*v - 1/7*u^2 + 8080000000000000000001/4000000000000000000000*v - 1759/1260*u + 15520000000000000000003/14400000000000000000000"), p("-36/35*u*v^4 - 14400000000000000000009/7000000000000000000000*u*v^3 - 18/35*u^2*v^2 - 6*v^3 + 1559999999999999999997/1000000000000000000000*u*v^2 - 51/35*u^2*v + 2999999999999999999991/1000000000000000000000*v^2 - 46863999999999999999991/16800000000000000000000*u*v - 3/7*u^2 + 8079999999999999999991/4000000000000000000000*v - 919/420*u + 25600000000000000000009/14400000000000000000000"));
    let opts = {
        let mut o = SolveOptions::default();
        o.method = Method::HcNoPre;
        o
    };
    let sol = solve(&f, &g, Domain::Triangle, &opts).unwrap();
    assert!(sol.complete, "{:?}", sol.stats);
}

/// The triangle's box route (the default on exact input) decides the
/// triangle's edges exactly: roots on the hypotenuse, on the legs and at
/// the vertices are kept once, roots `2⁻⁵⁰` beyond the hypotenuse dropped
/// and `2⁻⁵⁰` inside it kept; both routes give the same answer.
#[test]
fn triangle_box_route_settles_the_edges_exactly() {
    let p = |s: &str| parse_polynomial(s).unwrap();
    let cases = [
        ("u - 1/3", "u + v - 1", vec![("1/3", "2/3")]),
        (
            "(u - 1/3)*(u - 2/3)",
            "v*(u + v - 1)",
            vec![("1/3", "0"), ("2/3", "0"), ("1/3", "2/3"), ("2/3", "1/3")],
        ),
        ("u*(u - 1)", "v*(v - 1)", vec![("0", "0"), ("1", "0"), ("0", "1")]),
        ("u - 1/2", "u + v - 1 - 1/1125899906842624", vec![]),
        (
            "u - 1/2",
            "u + v - 1 + 1/1125899906842624",
            vec![("1/2", "562949953421311/1125899906842624")],
        ),
        (
            "(u - 3/5)*(u - 1/5)",
            "(v - 3/5)*(v - 1/5)",
            vec![("1/5", "1/5"), ("1/5", "3/5"), ("3/5", "1/5")],
        ),
    ];
    for (f, g, roots) in cases {
        for route in [TriangleRoute::Rect, TriangleRoute::Triangle] {
            let opts = SolveOptions::default().with_triangle_route(route);
            let sol = solve(&p(f), &p(g), Domain::Triangle, &opts).unwrap();
            assert!(sol.complete && sol.clusters.is_empty(), "{f} | {g} {route:?}: {sol:?}");
            assert_eq!(sol.roots.len(), roots.len(), "{f} | {g} {route:?}: {sol:?}");
            for (u, v) in &roots {
                assert_eq!(
                    covering(&sol, &q(u), &q(v)),
                    1,
                    "{f} | {g} {route:?}: ({u}, {v}) in {sol:?}"
                );
            }
        }
    }
}

/// Random dense systems on the triangle (integer coefficients in [−9, 9],
/// degrees 2–5, both curves shifted through one random point of the
/// triangle so that each system has roots there): where both routes end
/// complete without undecided regions, they certify the same roots (each
/// box of one meets exactly one of the other's).
#[test]
fn triangle_routes_agree_on_random_dense_systems() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) % 19) as i64 - 9
    };
    let mut dense = |n: u32, at: (&BigRational, &BigRational)| {
        let mut terms = Vec::new();
        for a in 0..=n {
            for b in 0..=n - a {
                terms.push(format!("({})*u^{a}*v^{b}", next()));
            }
        }
        let p = parse_polynomial(&terms.join(" + ")).unwrap();
        p.sub(&Polynomial::constant(p.eval(at.0, at.1)))
    };
    let meets = |a: &rootclip::solve::Box2, b: &rootclip::solve::Box2| {
        a.u[0] <= b.u[1] && b.u[0] <= a.u[1] && a.v[0] <= b.v[1] && b.v[0] <= a.v[1]
    };
    let (mut compared, mut total, mut roots) = (0, 0, 0);
    for n in 2..=5 {
        for k in 0..8i64 {
            let (i, j) = ((3 * k + n as i64) % 13, (5 * k + 2) % 13);
            let (pu, pv) = (q(&format!("{}/13", i.min(12 - j))), q(&format!("{j}/13")));
            let (f, g) = (dense(n, (&pu, &pv)), dense(n, (&pu, &pv)));
            let run = |route| {
                solve(
                    &f,
                    &g,
                    Domain::Triangle,
                    &SolveOptions::default().with_triangle_route(route),
                )
            };
            let (Ok(a), Ok(b)) = (run(TriangleRoute::Rect), run(TriangleRoute::Triangle)) else {
                continue;
            };
            total += 1;
            if !(a.complete && b.complete && a.clusters.is_empty() && b.clusters.is_empty()) {
                continue;
            }
            compared += 1;
            roots += a.roots.len();
            assert_eq!(a.roots.len(), b.roots.len(), "{f} | {g}: {a:?} vs {b:?}");
            for r in &a.roots {
                let n = b.roots.iter().filter(|s| meets(&r.bx, &s.bx)).count();
                assert_eq!(n, 1, "{f} | {g}: root {r:?} meets {n} boxes of {b:?}");
            }
        }
    }
    assert!(
        compared * 10 >= total * 9 && roots > 20,
        "{compared} of {total} compared, {roots} roots"
    );
}
