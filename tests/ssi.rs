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

#[test]
fn two_bumps_make_two_loops() {
    // z = (x² − 1/2)² + y² over [−1, 1]² (degree (4, 2)) cut by z = 1/10:
    // two closed loops around x = ±√½, apart (at x = 0, z ≥ 1/4).
    let px = [0.25, -0.75, 19.0 / 12.0, -0.75, 0.25];
    let sq = [1.0, -1.0, 1.0];
    let mut pts = Vec::new();
    for (i, p) in px.iter().enumerate() {
        for (j, q) in sq.iter().enumerate() {
            pts.push(DVec3::new(-1.0 + 0.5 * i as f64, j as f64 - 1.0, p + q));
        }
    }
    let bumps = Patch::from(TensorPatch::new(4, 2, pts, None).unwrap());
    let a = plane(0.1, 2.0);
    let out = intersect_surfaces(&a, &bumps, &SsiOptions::default().with_tol(1e-4)).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 2);
    assert!(out.branches.iter().all(|b| b.closed && b.points.len() > 8));
    on_both(&a, &bumps, &out);
    // One loop on each side of x = 0.
    let sides: Vec<bool> = out.branches.iter().map(|b| b.points[0].xyz[0] > 0.0).collect();
    assert!(sides[0] != sides[1]);
    for b in &out.branches {
        assert!(b.points.iter().all(|p| (p.xyz[0] > 0.0) == (b.points[0].xyz[0] > 0.0)));
        for p in &b.points {
            let (x, y) = (p.xyz[0], p.xyz[1]);
            assert!(((x * x - 0.5).powi(2) + y * y - 0.1).abs() < 1e-9);
        }
    }
}

#[test]
fn rational_cylinder_against_a_tilted_plane() {
    // The quarter cylinder x² + z² = 1 (x, z ≥ 0), y ∈ [0, 2], rational
    // (degree (2, 1)), cut by z = 3/10 + y/5: one arc from y = 0 to y = 2.
    let s = 0.5f64.sqrt();
    let cyl = TensorPatch::new(
        2,
        1,
        vec![
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 2.0, 1.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.0, 2.0, 1.0),
        ],
        Some(vec![1.0, 1.0, s, s, 1.0, 1.0]),
    )
    .unwrap();
    let p = |x: f64, y: f64| DVec3::new(x, y, 0.3 + 0.2 * y);
    let tilted = TensorPatch::new(1, 1, vec![p(-2.0, -1.0), p(-2.0, 3.0), p(2.0, -1.0), p(2.0, 3.0)], None).unwrap();
    let (a, b) = (Patch::from(tilted), Patch::from(cyl));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    let br = &out.branches[0];
    assert!(!br.closed);
    on_both(&a, &b, &out);
    for q in &br.points {
        let [x, y, z] = q.xyz;
        assert!((x * x + z * z - 1.0).abs() < 1e-9 && (z - 0.3 - 0.2 * y).abs() < 1e-12);
    }
    let ends = [br.points[0].xyz[1], br.points[br.points.len() - 1].xyz[1]];
    assert!(ends.iter().any(|y| y.abs() < 1e-9) && ends.iter().any(|y| (y - 2.0).abs() < 1e-9));
}

#[test]
fn triangle_against_paraboloid() {
    // The flat triangle (−1, −1, ½), (3, −1, ½), (−1, 3, ½) holds the whole
    // circle x² + y² = ½ of z = ½ on the paraboloid: one closed loop.
    use rootclip::ray::TriPatch;
    let tri = TriPatch::new(
        1,
        vec![
            DVec3::new(-1.0, -1.0, 0.5),
            DVec3::new(3.0, -1.0, 0.5),
            DVec3::new(-1.0, 3.0, 0.5),
        ],
        None,
    )
    .unwrap();
    let (a, b) = (Patch::from(tri.clone()), paraboloid(1.0, 0.0));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    assert!(out.branches[0].closed);
    for p in &out.branches[0].points {
        assert!(p.certified);
        let [x, y, z] = p.xyz;
        assert!((x * x + y * y - 0.5).abs() < 1e-9 && (z - 0.5).abs() < 1e-12);
        // The triangle's parameters: u, v ≥ 0, u + v ≤ 1, and T(u, v) is the point.
        let q = tri.eval(p.a[0], p.a[1]);
        assert!((q.x - x).abs() < 1e-9 && (q.y - y).abs() < 1e-9);
    }
}

#[test]
fn a_small_loop_is_found() {
    // z = 10⁻⁴ cuts the paraboloid in a circle of radius 10⁻²: a loop far
    // smaller than a tracer step, found by its turning points alone.
    let (a, b) = (plane(1e-4, 1.0), paraboloid(1.0, 0.0));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default().with_tol(1e-6)).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    assert!(out.branches[0].closed && out.branches[0].points.len() >= 4);
    on_both(&a, &b, &out);
    for p in &out.branches[0].points {
        assert!(p.certified);
        assert!((p.xyz[0].powi(2) + p.xyz[1].powi(2) - 1e-4).abs() < 1e-12);
    }
}

#[test]
fn barely_overlapping_patches_keep_their_arcs() {
    // The paraboloid reaches z = 2 only at its corners; z = 2 − 10⁻⁴ cuts
    // off four arcs about 10⁻⁴ long there, where the patches' bounding
    // boxes overlap by 10⁻⁴ in z.
    let (a, b) = (plane(2.0 - 1e-4, 2.0), paraboloid(1.0, 0.0));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 4);
    assert!(out.branches.iter().all(|b| !b.closed && b.points.len() >= 2));
    on_both(&a, &b, &out);
    for br in &out.branches {
        for p in &br.points {
            let [x, y, _] = p.xyz;
            assert!((x * x + y * y - (2.0 - 1e-4)).abs() < 1e-9 && x.abs() > 0.99 && y.abs() > 0.99);
        }
    }
}
