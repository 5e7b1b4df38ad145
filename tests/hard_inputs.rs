//! Issue 20's hard inputs: each must end (quickly, though no timing is
//! asserted) with the right certified answer, or with `complete = false`
//! and its leftovers — never a lost root, never a run of minutes.
//!
//! Rays starting exactly on the surface (the everyday secondary ray) put
//! the hit at `t = 0` exactly, where `t`'s numerator vanishes at the root:
//! exact settling used to contract the box with rationals doubling in size
//! each step, without end. Now the root, a rational point there, is found
//! exactly, and `t = 0` is decided as zero.

use glam::DVec3;
use rootclip::ray::{intersect, Hit, Patch, PatchSpec, Ray, RayOptions, RayOutcome};
use rootclip::solve::SquareRoute;

fn patch(json: &str) -> Patch {
    let spec: PatchSpec = serde_json::from_str(json).expect("a patch spec");
    Patch::from_spec(&spec).expect("a valid patch")
}

fn bicubic() -> Patch {
    patch(
        &std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/data/seed000_bicubic.json"
        ))
        .unwrap(),
    )
}

fn hits(patch: &Patch, ray: &Ray, opts: &RayOptions) -> Vec<Hit> {
    match intersect(patch, ray, opts).expect("valid input") {
        RayOutcome::Hits(h) => {
            assert!(h.complete);
            h.hits
        }
        other => panic!("unexpected outcome {other:?} for {ray:?}"),
    }
}

/// One certified hit at `t = 0`, its `t` box within the range `[0, ∞]`
/// (a certified hit never straddles the range's end).
fn assert_hit_at_zero(patch: &Patch, origin: DVec3, dir: DVec3, routes: &[SquareRoute]) {
    let ray = Ray::new(origin, dir).unwrap();
    for &route in routes {
        let hs = hits(patch, &ray, &RayOptions::default().with_route(route));
        let at_zero: Vec<&Hit> = hs.iter().filter(|h| h.bx.t[0] <= 1e-12).collect();
        assert_eq!(at_zero.len(), 1, "{route:?}: {hs:?}");
        let h = at_zero[0];
        assert!(h.is_certified(), "{route:?}: {h:?}");
        assert!(h.bx.t[0] == 0.0 && h.bx.t[1] >= 0.0, "{route:?}: {h:?}");
        assert!((h.point - origin).length() < 1e-9, "{route:?}: {h:?}");
    }
}

const ALL_ROUTES: [SquareRoute; 4] = [
    SquareRoute::Rect,
    SquareRoute::Triangles,
    SquareRoute::RectFatLine,
    SquareRoute::RectHybrid,
];

#[test]
fn bicubic_origin_on_the_surface() {
    let p = bicubic();
    let o = DVec3::new(1.5, 2.25, 0.0);
    assert_hit_at_zero(&p, o, DVec3::new(0.0, -1.0, 0.0), &ALL_ROUTES);
    assert_hit_at_zero(&p, o, DVec3::new(0.25, -1.0, 0.125), &ALL_ROUTES);
}

#[test]
fn bicubic_origin_one_ulp_off_the_surface() {
    let p = bicubic();
    let ray = Ray::new(DVec3::new(1.5, 2.25f64.next_up(), 0.0), DVec3::new(0.0, -1.0, 0.0)).unwrap();
    let hs = hits(&p, &ray, &RayOptions::default());
    assert_eq!(hs.len(), 1, "{hs:?}");
    assert!(hs[0].is_certified() && hs[0].bx.t[0] >= 0.0);
}

#[test]
fn flat_bilinear_origin_on_the_surface() {
    let p = patch(r#"{"type": "tensor", "degree": [1, 1], "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]]}"#);
    assert_hit_at_zero(&p, DVec3::new(0.3, 0.4, 0.0), DVec3::new(0.1, 0.2, 1.0), &ALL_ROUTES);
    // Pointing into the patch from below and from above: the same hit.
    assert_hit_at_zero(
        &p,
        DVec3::new(0.3, 0.4, 0.0),
        DVec3::new(0.1, 0.2, -1.0),
        &[SquareRoute::Rect],
    );
}

#[test]
fn quadratic_triangle_origin_on_the_surface() {
    // z = uw + vw + 2uv; S(1/4, 1/4) = (1/4, 1/4, 3/8) exactly.
    let p = patch(
        r#"{"type": "triangle", "degree": 2, "points": [[0, 0, 0], [0.5, 0, 0.5], [1, 0, 0], [0, 0.5, 0.5], [0.5, 0.5, 1], [0, 1, 0]]}"#,
    );
    assert_hit_at_zero(
        &p,
        DVec3::new(0.25, 0.25, 0.375),
        DVec3::new(0.3, -0.2, 1.0),
        &[SquareRoute::Rect],
    );
}

/// The hit at `t = 0` exactly is outside a range starting just above 0:
/// decided exactly (no hit), not left undecided after a long contraction.
#[test]
fn origin_on_the_surface_with_a_range_above_zero() {
    let p = bicubic();
    let ray = Ray::new(DVec3::new(1.5, 2.25, 0.0), DVec3::new(0.0, -1.0, 0.0)).unwrap();
    let opts = RayOptions::default().with_t_range(1e-300, f64::INFINITY);
    let hs = hits(&p, &ray, &opts);
    assert!(hs.iter().all(|h| h.bx.t[1] >= 1e-300), "{hs:?}");
    assert!(hs.iter().all(|h| h.is_certified()), "{hs:?}");
}

/// Secondary rays: origins at dyadic parameters of the bicubic patch,
/// directions spread over the sphere. Wherever the `f64` evaluation of the
/// surface is exact the origin is on it and the ray has a certified hit at
/// `t = 0`; every ray ends.
#[test]
fn secondary_rays_from_the_surface_end() {
    let p = bicubic();
    let mut at_zero = 0;
    for k in 0..24 {
        let (a, b) = ((k % 8) as f64 / 8.0 + 1.0 / 16.0, (k / 8) as f64 / 4.0 + 1.0 / 8.0);
        let o = p.eval(a, b);
        let phi = 2.399_963 * k as f64;
        let z = 1.0 - 2.0 * (k as f64 + 0.5) / 24.0;
        let r = (1.0 - z * z).sqrt();
        let ray = Ray::new(o, DVec3::new(r * phi.cos(), r * phi.sin(), z)).unwrap();
        // A ray tangent to the surface at its origin may end undecided;
        // every outcome is accepted here, every certified hit checked.
        if let RayOutcome::Hits(hs) = intersect(&p, &ray, &RayOptions::default()).expect("valid input") {
            at_zero += hs.hits.iter().filter(|h| h.is_certified() && h.bx.t[0] == 0.0).count();
            assert!(hs.hits.iter().all(|h| h.bx.t[0] >= 0.0 || !h.is_certified()), "{hs:?}");
        }
    }
    assert!(at_zero > 0, "no ray started exactly on the surface");
}

/// Inputs whose numbers would come out non-finite (printed as JSON `null`)
/// are rejected with a typed error: a direction subnormal in every
/// component (`t` overflows), a subnormal weight (the points are 0/0).
#[test]
fn subnormal_directions_and_weights_are_typed_errors() {
    use rootclip::ray::TensorPatch;
    use rootclip::Error;
    let r = Ray::new(DVec3::new(0.5, 0.5, 1.0), DVec3::new(0.0, 0.0, -1e-320));
    assert!(matches!(r, Err(Error::NonFinite(_))), "{r:?}");
    assert!(Ray::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -1e-300)).is_ok());
    let pts = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
    ];
    let p = TensorPatch::new(1, 1, pts.clone(), Some(vec![1e-320; 4]));
    assert!(matches!(p, Err(Error::NonFinite(_))), "{p:?}");
    assert!(TensorPatch::new(1, 1, pts, Some(vec![1e-300; 4])).is_ok());
}

/// One rule for `eps` on every route: positive and finite. An `eps` of 1 or
/// more is valid on the box route as on the triangles (it stops early, still
/// soundly: the root is certified or left in a cluster).
#[test]
fn eps_rule_is_the_same_on_every_route() {
    use rootclip::poly::parse_polynomial;
    use rootclip::solve::{solve, Domain, SolveOptions};
    let f = parse_polynomial("u - 1/3").unwrap();
    let g = parse_polynomial("v - 1/4").unwrap();
    for route in ALL_ROUTES {
        for eps in [1e-12, 1.0, 10.0] {
            let opts = SolveOptions::default().with_eps(eps).with_square_route(route);
            let sol = solve(&f, &g, Domain::Square, &opts).unwrap_or_else(|e| panic!("{route:?} eps {eps}: {e}"));
            assert!(
                sol.complete && sol.roots.len() + sol.clusters.len() == 1,
                "{route:?} eps {eps}: {sol:?}"
            );
        }
        for eps in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let opts = SolveOptions::default().with_eps(eps).with_square_route(route);
            assert!(solve(&f, &g, Domain::Square, &opts).is_err(), "{route:?} eps {eps}");
        }
    }
}

/// A direction so short that `t` overflows `f64` at the hit: a typed error,
/// never a hit with `t = ∞` (JSON `null`).
#[test]
fn a_hit_whose_t_overflows_is_a_typed_error() {
    use rootclip::Error;
    let p = patch(r#"{"type": "tensor", "degree": [1, 1], "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]]}"#);
    let ray = Ray::new(DVec3::new(0.3, 0.4, 1e10), DVec3::new(0.0, 0.0, -1e-300)).unwrap();
    let out = intersect(&p, &ray, &RayOptions::default());
    assert!(matches!(out, Err(Error::NonFinite(_))), "{out:?}");
    // The same ray with a longer direction: t = 1e10 / 1e-290, finite.
    let ray = Ray::new(DVec3::new(0.3, 0.4, 1e10), DVec3::new(0.0, 0.0, -1e-290)).unwrap();
    let hs = hits(&p, &ray, &RayOptions::default());
    assert!(hs.len() == 1 && hs[0].is_certified() && hs[0].t.is_finite(), "{hs:?}");
}

/// A wall-clock deadline ends a solve with `complete = false` and its
/// leftovers, never a wrong answer: with a zero timeout nothing is
/// explored, on both domains and every square route; with a generous one
/// the answer is the complete one.
#[test]
fn a_deadline_ends_a_solve_incomplete_with_leftovers() {
    use rootclip::poly::parse_polynomial;
    use rootclip::solve::{solve, Domain, SolveOptions};
    use std::time::Duration;
    let f = parse_polynomial("(u - 1/3)*(u - 2/3)").unwrap();
    let g = parse_polynomial("(v - 1/4)*(v - 1/2)").unwrap();
    for (domain, route) in [
        (Domain::Triangle, SquareRoute::Triangles),
        (Domain::Square, SquareRoute::Triangles),
        (Domain::Square, SquareRoute::Rect),
        (Domain::Square, SquareRoute::RectHybrid),
    ] {
        let opts = SolveOptions::default().with_square_route(route);
        let sol = solve(&f, &g, domain, &opts.with_timeout(Duration::ZERO)).unwrap();
        assert!(
            !sol.complete && !sol.leftovers.is_empty(),
            "{domain:?} {route:?}: {sol:?}"
        );
        let full = solve(&f, &g, domain, &opts.with_timeout(Duration::from_secs(600))).unwrap();
        let want = if domain == Domain::Triangle { 3 } else { 4 };
        assert!(
            full.complete && full.roots.len() == want,
            "{domain:?} {route:?}: {full:?}"
        );
    }
}

/// `∏ (a u + b v + c)` as an expression.
fn lines_product(lines: &[(i64, i64, i64, i64)]) -> String {
    lines
        .iter()
        .map(|(a, b, c, d)| format!("(({a})*u + ({b})*v + ({c})/({d}))"))
        .collect::<Vec<_>>()
        .join("*")
}

/// Every root certified, none undecided, `complete`, and each expected
/// crossing (exact rationals `(u, v)`) inside exactly one root box.
fn assert_all_certified(f: &str, g: &str, domain: rootclip::solve::Domain, route: SquareRoute, want: &[(f64, f64)]) {
    use rootclip::solve::SolveOptions;
    assert_all_certified_with(f, g, domain, &SolveOptions::default().with_square_route(route), want);
}

/// [`assert_all_certified`] with any options.
fn assert_all_certified_with(
    f: &str,
    g: &str,
    domain: rootclip::solve::Domain,
    opts: &rootclip::solve::SolveOptions,
    want: &[(f64, f64)],
) {
    use rootclip::poly::parse_polynomial;
    use rootclip::solve::solve;
    let route = (opts.square_route, opts.triangle_route);
    let (f, g) = (parse_polynomial(f).unwrap(), parse_polynomial(g).unwrap());
    let sol = solve(&f, &g, domain, opts).unwrap();
    assert!(
        sol.complete && sol.clusters.is_empty(),
        "{route:?}: {} clusters",
        sol.clusters.len()
    );
    assert_eq!(sol.roots.len(), want.len(), "{route:?}");
    for &(u, v) in want {
        let n = sol.roots.iter().filter(|r| r.bx.contains(u, v)).count();
        assert_eq!(n, 1, "{route:?}: ({u}, {v}) in {n} boxes");
    }
}

/// A pencil of ten lines through `(0, ½)` on the square's edge against two
/// verticals: 20 simple roots 1/30 apart in `v`, where `∂f/∂v` is ~1e-10
/// and the coefficients' rounding hides the sign in a band ~1e-7 wide (the
/// box route used to leave 6 of them as clusters).
#[test]
fn a_pencil_through_an_edge_point_is_all_certified() {
    use rootclip::solve::Domain;
    // v = ½ + s u with s = (k − 5)/10 + 1/20: 20 s u − 20 v + 10 = 0, with
    // 20 s = 2k − 9.
    let pencil: Vec<(i64, i64, i64, i64)> = (0..10).map(|k| (2 * k - 9, -20, 10, 1)).collect();
    let f = lines_product(&pencil);
    let g = "(u - 1/3)*(u - 2/3)";
    let mut want = Vec::new();
    for u in [1.0 / 3.0, 2.0 / 3.0] {
        for k in 0..10 {
            want.push((u, 0.5 + (2 * k - 9) as f64 / 20.0 * u));
        }
    }
    for route in [SquareRoute::Rect, SquareRoute::Triangles] {
        assert_all_certified(&f, g, Domain::Square, route, &want);
    }
}

/// Grids of lines `∏ (u − i/(n+1)) = ∏ (v − j/(n+1)) = 0`: `n²` simple roots
/// (on the triangle, those with `u + v ≤ 1`), all certified. Degree 12 here
/// (the degree 20–25 cases of `dev/hard/families.py` take seconds).
#[test]
fn grids_of_lines_are_all_certified() {
    use rootclip::solve::{Domain, SolveOptions, TriangleRoute};
    let n = 12;
    let d = n + 1;
    let f = lines_product(&(1..=n).map(|i| (1, 0, -i, d)).collect::<Vec<_>>());
    let g = lines_product(&(1..=n).map(|j| (0, 1, -j, d)).collect::<Vec<_>>());
    let mut square = Vec::new();
    let mut triangle = Vec::new();
    for i in 1..=n {
        for j in 1..=n {
            let (u, v) = (i as f64 / d as f64, j as f64 / d as f64);
            square.push((u, v));
            if i + j <= d {
                triangle.push((u, v));
            }
        }
    }
    assert_all_certified(&f, &g, Domain::Square, SquareRoute::Rect, &square);
    for route in [TriangleRoute::Rect, TriangleRoute::Triangle] {
        let opts = SolveOptions::default().with_triangle_route(route);
        assert_all_certified_with(&f, &g, Domain::Triangle, &opts, &triangle);
    }
}

/// Degrees the box route's scratch arrays once did not hold (≥ 24: no
/// clipping, no local Krawczyk, only subdivision): one root each, certified.
#[test]
fn high_degree_squares_end_with_their_root() {
    use rootclip::solve::Domain;
    let half = 0.5f64;
    assert_all_certified(
        "u^60 - 1/2",
        "v^60 - 1/3",
        Domain::Square,
        SquareRoute::Rect,
        &[(half.powf(1.0 / 60.0), (1.0f64 / 3.0).powf(1.0 / 60.0))],
    );
    assert_all_certified(
        "u^200 - 1/2",
        "v - 1/3",
        Domain::Square,
        SquareRoute::Rect,
        &[(half.powf(1.0 / 200.0), 1.0 / 3.0)],
    );
    // Simple roots at two corners: the exact test's box reaches a tenth
    // past the edges, where extrapolating a degree-100 line from the short
    // piece inside blew its Jacobian up by ~10¹⁴ (the root at (1, 1) was
    // left undecided).
    assert_all_certified(
        "u^100 - v",
        "v^100 - u",
        Domain::Square,
        SquareRoute::Rect,
        &[(0.0, 0.0), (1.0, 1.0)],
    );
    let r = 0.5 * half.powf(1.0 / 40.0);
    assert_all_certified("(u+v)^40 - 1/2", "u - v", Domain::Square, SquareRoute::Rect, &[(r, r)]);
}

/// The crossings of every line of `f` with every line of `g` (each
/// `a u + b v + c = 0`, integers) in the closed domain, decided exactly.
fn crossings(f: &[(i64, i64, i64)], g: &[(i64, i64, i64)], triangle: bool) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for &(a1, b1, c1) in f {
        for &(a2, b2, c2) in g {
            let (a1, b1, c1, a2, b2, c2) = (a1 as i128, b1 as i128, c1 as i128, a2 as i128, b2 as i128, c2 as i128);
            let det = a1 * b2 - a2 * b1;
            if det == 0 {
                continue;
            }
            // u = nu/det, v = nv/det; compare with the sign of det folded in.
            let (nu, nv, d) = (b1 * c2 - b2 * c1, c1 * a2 - c2 * a1, det);
            let (nu, nv, d) = if d < 0 { (-nu, -nv, -d) } else { (nu, nv, d) };
            let inside = nu >= 0 && nv >= 0 && if triangle { nu + nv <= d } else { nu <= d && nv <= d };
            if inside {
                out.push((nu as f64 / d as f64, nv as f64 / d as f64));
            }
        }
    }
    out
}

/// Two pencils of twenty lines, through `(0, ½)` and `(⅓, 0)` on the edges:
/// near the pencils' points each product vanishes to order 20, its values
/// fall below double-double's reach of the domain's coefficients, and the
/// box route recomputes those boxes from the exact input in fixed point
/// (it used to run out of any budget with half the roots certified).
#[test]
fn two_pencils_of_twenty_lines_are_all_certified() {
    use rootclip::solve::{Domain, SolveOptions};
    // v = ½ + s u, s = (4k − 39)/40: (4k − 39) u − 40 v + 20 = 0; and
    // u = ⅓ − s v: 120 u + 3 (4l − 39) v − 40 = 0.
    let f: Vec<(i64, i64, i64)> = (0..20).map(|k| (4 * k - 39, -40, 20)).collect();
    let g: Vec<(i64, i64, i64)> = (0..20).map(|l| (120, 3 * (4 * l - 39), -40)).collect();
    let expr =
        |lines: &[(i64, i64, i64)]| lines_product(&lines.iter().map(|&(a, b, c)| (a, b, c, 1)).collect::<Vec<_>>());
    let (fe, ge) = (expr(&f), expr(&g));
    let square = crossings(&f, &g, false);
    let triangle = crossings(&f, &g, true);
    assert_eq!((square.len(), triangle.len()), (301, 233));
    assert_all_certified(&fe, &ge, Domain::Square, SquareRoute::Rect, &square);
    assert_all_certified_with(&fe, &ge, Domain::Triangle, &SolveOptions::default(), &triangle);
}

/// Products of 30 lines: between the middle roots the system is ~10⁻¹⁸ of
/// its coefficients, below their rounding, and boxes there are restarted
/// from the exact input (the box route used to certify 641 of the 900 in 60 s).
#[test]
fn products_of_thirty_lines_are_all_certified() {
    use rootclip::solve::Domain;
    let n = 30;
    let d = n + 1;
    let f = lines_product(&(1..=n).map(|i| (1, 0, -i, d)).collect::<Vec<_>>());
    let g = lines_product(&(1..=n).map(|j| (0, 1, -j, d)).collect::<Vec<_>>());
    let want: Vec<(f64, f64)> = (1..=n)
        .flat_map(|i| (1..=n).map(move |j| (i as f64 / d as f64, j as f64 / d as f64)))
        .collect();
    assert_all_certified(&f, &g, Domain::Square, SquareRoute::Rect, &want);
}

/// Two pencils through the vertex `(1, 0)` (10 and 5 lines): one root of
/// multiplicity 50 there and no other. One honest `multiple_or_close` region
/// at the vertex, on both domains — found exactly as a multiple root, so
/// the square's answer is not retried on the triangles.
#[test]
fn two_pencils_through_a_vertex_leave_one_region_there() {
    use rootclip::poly::parse_polynomial;
    use rootclip::solve::{solve, Domain, SolveOptions, UndecidedReason};
    let f: Vec<String> = (1..=10).map(|k| format!("(({k}/11)*(u - 1) + v)")).collect();
    let g: Vec<String> = (1..=5).map(|k| format!("(({k}/6 + 1/18)*(u - 1) + v)")).collect();
    let (f, g) = (
        parse_polynomial(&f.join("*")).unwrap(),
        parse_polynomial(&g.join("*")).unwrap(),
    );
    for domain in [Domain::Square, Domain::Triangle] {
        let sol = solve(&f, &g, domain, &SolveOptions::default()).unwrap();
        assert!(sol.complete && sol.roots.is_empty(), "{domain:?}: {sol:?}");
        assert_eq!(sol.clusters.len(), 1, "{domain:?}");
        let c = &sol.clusters[0];
        assert!(
            c.reason == UndecidedReason::MultipleOrClose && c.bx.contains(1.0, 0.0),
            "{domain:?}: {c:?}"
        );
    }
}
