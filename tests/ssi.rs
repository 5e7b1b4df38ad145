//! Surface/surface intersection against curves known in closed form: every
//! point is checked on both patches (evaluated independently of the
//! tracer), branch counts and closure against the known curve, singular
//! inputs get their typed outcome.

use rootclip::glam::DVec3;
use rootclip::ray::{Patch, TensorPatch};
use rootclip::ssi::{intersect_surfaces, Intersection, SingularKind, SsiOptions};

/// The plane `z = const` over `[−h, h]²`.
fn plane(z: f64, h: f64) -> Patch {
    let p = |x: f64, y: f64| DVec3::new(x * h, y * h, z);
    Patch::from(TensorPatch::new(1, 1, vec![p(-1.0, -1.0), p(-1.0, 1.0), p(1.0, -1.0), p(1.0, 1.0)], None).unwrap())
}

/// `z = a(x² + y²) + c` over `[−1, 1]²` (degree 2: x² has coefficients 1, −1, 1).
fn paraboloid(a: f64, c: f64) -> Patch {
    let sq = [1.0, -1.0, 1.0];
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            pts.push(DVec3::new(i as f64 - 1.0, j as f64 - 1.0, a * (sq[i] + sq[j]) + c));
        }
    }
    Patch::from(TensorPatch::new(2, 2, pts, None).unwrap())
}

/// Every point lies on both patches (within `1e-9`).
fn on_both(a: &Patch, b: &Patch, out: &Intersection) {
    let eval = |p: &Patch, u: f64, v: f64| match p {
        Patch::Tensor(t) => t.eval(u, v),
        _ => unreachable!(),
    };
    for br in &out.branches {
        for p in &br.points {
            let (x, y) = (eval(a, p.a[0], p.a[1]), eval(b, p.b[0], p.b[1]));
            assert!((x - y).length() < 1e-9, "point {p:?} is off: {x} vs {y}");
            assert!(p.a.iter().chain(&p.b).all(|&c| (-1e-9..=1.0 + 1e-9).contains(&c)));
        }
    }
}

#[test]
fn plane_cuts_paraboloid_in_one_loop() {
    let (a, b) = (plane(0.5, 1.0), paraboloid(1.0, 0.0));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    assert!(out.branches[0].closed);
    on_both(&a, &b, &out);
    for p in &out.branches[0].points {
        assert!(p.certified);
        assert!((p.xyz[0].powi(2) + p.xyz[1].powi(2) - 0.5).abs() < 1e-9);
    }
}

#[test]
fn plane_cuts_paraboloid_in_four_arcs() {
    // z = 1.5: the circle of radius √1.5 leaves the square in four arcs.
    let (a, b) = (plane(1.5, 2.0), paraboloid(1.0, 0.0));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 4);
    assert!(out.branches.iter().all(|b| !b.closed && b.points.len() >= 2));
    on_both(&a, &b, &out);
}

#[test]
fn disjoint_patches_have_nothing() {
    let out = intersect_surfaces(&plane(3.0, 1.0), &paraboloid(1.0, 0.0), &SsiOptions::default()).unwrap();
    assert!(out.complete && out.branches.is_empty() && out.singular.is_empty());
}

#[test]
fn tangential_contact_is_typed() {
    // z = x² + y² touches z = 0 at the origin only.
    let out = intersect_surfaces(&plane(0.0, 1.5), &paraboloid(1.0, 0.0), &SsiOptions::default()).unwrap();
    assert!(!out.complete);
    assert!(out.singular.iter().any(|s| s.kind == SingularKind::TangentialContact));
}

#[test]
fn coplanar_patches_are_an_overlap() {
    let out = intersect_surfaces(&plane(0.0, 1.0), &plane(0.0, 2.0), &SsiOptions::default()).unwrap();
    assert!(!out.complete);
    assert!(out.singular.iter().any(|s| s.kind == SingularKind::Overlap));
}
