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

/// A tensor patch `examples/data/ssi/{name}.json` (rootclip patch JSON,
/// polynomial).
fn load(name: &str) -> Patch {
    let path = format!("{}/examples/data/ssi/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let deg = &v["degree"];
    let pts = v["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| DVec3::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap(), p[2].as_f64().unwrap()))
        .collect();
    let (m, n) = (deg[0].as_u64().unwrap() as usize, deg[1].as_u64().unwrap() as usize);
    Patch::from(TensorPatch::new(m, n, pts, None).unwrap())
}

/// The bump `z = 4u(1 − u)v(1 − v)` on `[0, 1]²` (top `1/4` at the centre).
fn bump() -> Patch {
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let z = if i == 1 && j == 1 { 1.0 } else { 0.0 };
            pts.push(DVec3::new(0.5 * i as f64, 0.5 * j as f64, z));
        }
    }
    Patch::from(TensorPatch::new(2, 2, pts, None).unwrap())
}

#[test]
fn tiny_loops_close() {
    // Regression: the hyperplane Newton of the tracer demanded a step below
    // 1e-14, under the rounding floor where the curve's derivative across
    // it is ~r; loops of radius ≲ 3e-4 stopped 45° from each turning point.
    // `z = 1/4 − r²` cuts the bump in a loop of radius about r.
    for r in [1e-3, 3e-4, 1e-4, 3e-5, 1e-5] {
        let z = 0.25 - r * r;
        let h = 0.5;
        let p = |x: f64, y: f64| DVec3::new(0.5 + x * h, 0.5 + y * h, z);
        let a = Patch::from(
            TensorPatch::new(1, 1, vec![p(-1.0, -1.0), p(-1.0, 1.0), p(1.0, -1.0), p(1.0, 1.0)], None).unwrap(),
        );
        let b = bump();
        let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
        assert!(out.complete, "r = {r}: {:?}", out.singular);
        assert_eq!(out.branches.len(), 1, "r = {r}");
        let br = &out.branches[0];
        assert!(br.closed && br.points.len() >= 4, "r = {r}");
        on_both(&a, &b, &out);
        for q in &br.points {
            assert!(q.certified);
            let d = ((q.b[0] - 0.5).powi(2) + (q.b[1] - 0.5).powi(2)).sqrt();
            assert!((d / r - 1.0).abs() < 0.01, "r = {r}: a point at distance {d}");
        }
    }
}

#[test]
fn tiny_loop_data_file_closes() {
    let (a, b) = (load("tiny_loop_a"), load("tiny_loop_b"));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    assert!(out.branches[0].closed);
    assert!(out.branches[0].points.iter().all(|p| p.certified));
    on_both(&a, &b, &out);
}

#[test]
fn an_arc_between_shared_edges_is_traced_whole() {
    // `(1 − u)²·4v(1 − v)` against the plane z = 1/2 whose edge lies on the
    // edge u = 0 (two faces sharing an edge). The arc's ends,
    // v = (1 ± √½)/2 on u = 0, lie on both patches' edges at once: each is
    // settled exactly (on the 2-face u_A = u_B = 0 the x difference vanishes
    // identically, and the other two equations have a proven zero there),
    // so the arc is traced whole from one end to the other.
    let (a, b) = (load("edge_twice_shared_a"), load("edge_twice_shared_b"));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    let br = &out.branches[0];
    assert!(!br.closed);
    on_both(&a, &b, &out);
    let (v0, v1) = (0.5 - 0.5f64.sqrt() / 2.0, 0.5 + 0.5f64.sqrt() / 2.0);
    let vs: Vec<f64> = br.points.iter().map(|p| p.a[1]).collect();
    let (lo, hi) = vs.iter().fold((1.0f64, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
    assert!((lo - v0).abs() < 1e-12 && (hi - v1).abs() < 1e-12, "v spans {lo}..{hi}");
    assert!(vs.windows(2).all(|w| w[0] < w[1]) || vs.windows(2).all(|w| w[0] > w[1]));
    for p in &br.points {
        assert!(p.certified);
        let [u, v] = p.a;
        assert!(((1.0 - u).powi(2) * 4.0 * v * (1.0 - v) - 0.5).abs() < 1e-9);
    }
    // The plane's edge moved 2⁻⁶⁰ past the shared edge, out of the bowl's
    // domain (the crossings are then interior to the plane, 10⁻¹⁸ from its
    // edge) or into it (the crossings lie on the plane's edge, inside the
    // bowl): either way the same arc, complete.
    for x0 in [-(2f64.powi(-60)), 2f64.powi(-60)] {
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.5);
        let plane =
            Patch::from(TensorPatch::new(1, 1, vec![p(x0, 0.0), p(x0, 1.0), p(1.0, 0.0), p(1.0, 1.0)], None).unwrap());
        let out = intersect_surfaces(&a, &plane, &SsiOptions::default()).unwrap();
        assert!(out.complete, "x0 = {x0:e}: {:?}", out.singular);
        assert_eq!(out.branches.len(), 1, "x0 = {x0:e}");
        on_both(&a, &plane, &out);
    }
}

#[test]
fn a_near_tangential_loop_closes() {
    // z = 10⁻⁶ on the bowl z = x² + y²: a loop of radius 10⁻³ where the
    // normals are 2·10⁻³ rad apart (`near_tangent_loop`). Before the
    // hyperplane Newton stopped at its rounding floor it stopped twice.
    let (a, b) = (paraboloid(1.0, 0.0), plane(1e-6, 1.0));
    let out = intersect_surfaces(&a, &b, &SsiOptions::default()).unwrap();
    assert!(out.complete, "{:?}", out.singular);
    assert_eq!(out.branches.len(), 1);
    assert!(out.branches[0].closed);
    on_both(&a, &b, &out);
    for p in &out.branches[0].points {
        assert!(p.certified);
        assert!((p.xyz[0].powi(2) + p.xyz[1].powi(2) - 1e-6).abs() < 1e-12);
    }
}

// ---------------------------------------------------------------------------
// The adversary: planes whose curve with an elliptic bowl pokes 1e-4 … 1e-14
// out of (or stays just inside) the bowl's edges, refereed exactly.
// ---------------------------------------------------------------------------

mod poke {
    use super::*;
    use num_rational::BigRational;
    use num_traits::{Signed, Zero};
    use proptest::prelude::*;
    use proptest::test_runner::Config;

    type Q = BigRational;

    fn q(x: f64) -> Q {
        Q::from_float(x).unwrap()
    }

    /// The bowl `z = α(x − cx)² + β(y − cy)²` over `[0, 1]²` with `x = u`,
    /// `y = v` exactly: biquadratic, control heights `α b_i(cx) + β b_j(cy)`
    /// with `b(c) = (c², c² − c, (1 − c)²)` the Bernstein coefficients of
    /// `(u − c)²` (exact for the dyadic inputs used).
    pub(super) fn bowl(alpha: f64, beta: f64, cx: f64, cy: f64) -> Patch {
        let b = |c: f64| [c * c, c * c - c, (1.0 - c) * (1.0 - c)];
        let (bx, by) = (b(cx), b(cy));
        let mut pts = Vec::new();
        for (i, x) in bx.iter().enumerate() {
            for (j, y) in by.iter().enumerate() {
                pts.push(DVec3::new(0.5 * i as f64, 0.5 * j as f64, alpha * x + beta * y));
            }
        }
        Patch::from(TensorPatch::new(2, 2, pts, None).unwrap())
    }

    /// The plane `z = c` over `[lo, hi]²`.
    pub(super) fn flat(c: f64, lo: f64, hi: f64) -> Patch {
        let p = |x: f64, y: f64| DVec3::new(x, y, c);
        Patch::from(TensorPatch::new(1, 1, vec![p(lo, lo), p(lo, hi), p(hi, lo), p(hi, hi)], None).unwrap())
    }

    /// What the exact referee says of the level set `α(x − cx)² + β(y − cy)² = c`
    /// on `[0, 1]²`: its crossings with the edges, and the number of arcs
    /// (closed loops) inside. `None` where the curve is tangent to an edge
    /// or passes through a corner exactly (not this family's business).
    #[derive(Debug, PartialEq)]
    pub(super) struct Truth {
        pub(super) crossings: usize,
        pub(super) arcs: usize,
        pub(super) loops: usize,
    }

    pub(super) fn truth(alpha: f64, beta: f64, cx: f64, cy: f64, c: f64) -> Option<Truth> {
        let (a, b, cx, cy, c) = (q(alpha), q(beta), q(cx), q(cy), q(c));
        let (zero, one) = (Q::zero(), Q::from_integer(1.into()));
        let mut crossings = 0;
        // Edge x = e: β(y − cy)² = c − α(e − cx)² =: r; roots cy ± √(r/β) in
        // [0, 1] iff r/β ≤ (1 − cy)², resp. ≤ cy² (equality: a corner).
        for (k, l, ck, cl) in [(&a, &b, &cx, &cy), (&b, &a, &cy, &cx)] {
            for e in [&zero, &one] {
                let d = e - ck;
                let r = &c - k * &d * &d;
                if r.is_zero() {
                    return None;
                }
                if r.is_negative() {
                    continue;
                }
                let s = &r / l;
                for room in [&one - cl, cl.clone()] {
                    let room2 = &room * &room;
                    if s == room2 {
                        return None;
                    }
                    if s < room2 {
                        crossings += 1;
                    }
                }
            }
        }
        if crossings > 0 {
            return Some(Truth {
                crossings,
                arcs: crossings / 2,
                loops: 0,
            });
        }
        // No crossing: the ellipse lies inside (c below α·(nearest x-edge)²
        // and β·(nearest y-edge)²) or around the square, or c ≤ 0.
        let near = |ck: &Q| if ck < &(&one - ck) { ck.clone() } else { &one - ck };
        let (nx, ny) = (near(&cx), near(&cy));
        let inside = c.is_positive() && c < &a * &nx * &nx && c < &b * &ny * &ny;
        Some(Truth {
            crossings: 0,
            arcs: 0,
            loops: usize::from(inside),
        })
    }

    /// The length of the level set inside `[0, 1]²`, by 2¹⁶ chords.
    fn inside_length(alpha: f64, beta: f64, cx: f64, cy: f64, c: f64) -> f64 {
        let (rx, ry) = ((c / alpha).sqrt(), (c / beta).sqrt());
        let n = 1 << 16;
        let at = |k: usize| {
            let th = std::f64::consts::TAU * k as f64 / n as f64;
            (cx + rx * th.cos(), cy + ry * th.sin())
        };
        let inside = |(x, y): (f64, f64)| (0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y);
        (0..n)
            .map(|k| (at(k), at(k + 1)))
            .filter(|&(p, r)| inside(p) && inside(r))
            .map(|(p, r)| ((p.0 - r.0).powi(2) + (p.1 - r.1).powi(2)).sqrt())
            .sum()
    }

    /// Runs one case and checks it against the truth: a complete answer
    /// has the true number of branches (loops closed, arcs open), every
    /// point certified on both patches and in both domains, every sample of
    /// the true curve within `2·tol` of a chord, and the branches' total
    /// length that of the curve inside. Returns whether the answer was
    /// complete.
    pub(super) fn check(alpha: f64, beta: f64, cx: f64, cy: f64, c: f64, shared: bool) -> Option<bool> {
        let t = truth(alpha, beta, cx, cy, c)?;
        let (lo, hi) = if shared { (0.0, 1.0) } else { (-1.0, 2.0) };
        let (a, b) = (flat(c, lo, hi), bowl(alpha, beta, cx, cy));
        let opts = SsiOptions::default();
        let out = intersect_surfaces(&a, &b, &opts).unwrap();
        let case = format!("α {alpha} β {beta} cx {cx} cy {cy} c {c:e} shared {shared}");
        on_both(&a, &b, &out);
        for br in &out.branches {
            for p in &br.points {
                assert!(
                    p.a.iter().chain(&p.b).all(|&x| (0.0..=1.0).contains(&x)),
                    "{case}: {p:?}"
                );
            }
        }
        if !out.complete {
            return Some(false);
        }
        let closed = out.branches.iter().filter(|b| b.closed).count();
        assert_eq!(
            (out.branches.len() - closed, closed),
            (t.arcs, t.loops),
            "{case}: {t:?}, branches {:?}",
            out.branches
                .iter()
                .map(|b| (b.points.len(), b.closed))
                .collect::<Vec<_>>()
        );
        let chords: Vec<(DVec3, DVec3)> = out
            .branches
            .iter()
            .flat_map(|br| {
                let p: Vec<DVec3> = br.points.iter().map(|p| DVec3::from_array(p.xyz)).collect();
                let mut segs: Vec<(DVec3, DVec3)> = p.windows(2).map(|w| (w[0], w[1])).collect();
                if br.closed {
                    segs.push((p[p.len() - 1], p[0]));
                }
                segs
            })
            .collect();
        let length: f64 = chords.iter().map(|(p, r)| (*p - *r).length()).sum();
        let want = inside_length(alpha, beta, cx, cy, c);
        assert!(
            (length - want).abs() <= 1e-2 * want + 1e-6,
            "{case}: branches {length}, curve {want}"
        );
        let (rx, ry) = ((c / alpha).sqrt(), (c / beta).sqrt());
        for k in 0..512 {
            let th = std::f64::consts::TAU * k as f64 / 512.0;
            let s = DVec3::new(cx + rx * th.cos(), cy + ry * th.sin(), c);
            if !((1e-9..=1.0 - 1e-9).contains(&s.x) && (1e-9..=1.0 - 1e-9).contains(&s.y)) {
                continue;
            }
            let d = chords
                .iter()
                .map(|&(p, r)| {
                    let e = r - p;
                    let h = ((s - p).dot(e) / e.length_squared().max(1e-300)).clamp(0.0, 1.0);
                    (p + e * h - s).length()
                })
                .fold(f64::INFINITY, f64::min);
            assert!(d <= 2.0 * opts.tol, "{case}: curve point {s} is {d} from every chord");
        }
        Some(true)
    }

    /// The level `c` at which the bowl's ellipse reaches `δ` past the edge
    /// `edge` (0: x = 0, 1: x = 1, 2: y = 0, 3: y = 1), rounded to `f64`;
    /// `δ < 0` stays inside.
    pub(super) fn level(alpha: f64, beta: f64, cx: f64, cy: f64, edge: usize, delta: f64) -> f64 {
        let (k, d) = match edge {
            0 => (alpha, cx),
            1 => (alpha, 1.0 - cx),
            2 => (beta, cy),
            _ => (beta, 1.0 - cy),
        };
        k * (d + delta) * (d + delta)
    }

    proptest! {
        // 160 cases here; `POKE_CASES=20000 cargo test --release --test ssi poke` for a long run.
        #![proptest_config(Config {
            cases: std::env::var("POKE_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(160),
            failure_persistence: None,
            ..Config::default()
        })]
        #[test]
        fn poking_curves_are_traced_arc_by_arc(
            a in 1u32..=8, b in 1u32..=8, kx in 4u32..=12, ky in 4u32..=12,
            edge in 0usize..4, exp in 4i32..=14, frac in 0u32..64, inward in any::<bool>(), shared in any::<bool>(),
        ) {
            let (alpha, beta) = (a as f64 / 4.0, b as f64 / 4.0);
            let (cx, cy) = (kx as f64 / 16.0, ky as f64 / 16.0);
            let delta = (1.0 + frac as f64 / 64.0) * 10f64.powi(-exp) * if inward { -1.0 } else { 1.0 };
            let c = level(alpha, beta, cx, cy, edge, delta);
            let done = check(alpha, beta, cx, cy, c, shared);
            // Every case of this family is transversal: it must finish.
            prop_assert!(done != Some(false), "incomplete: α {alpha} β {beta} cx {cx} cy {cy} c {c:e} shared {shared}");
        }
    }

    #[test]
    fn the_referee_by_hand() {
        // The circle r² = 1/4 + 2·10⁻⁵ about the centre pokes out of all four edges.
        let c = level(1.0, 1.0, 0.5, 0.5, 1, 1e-5);
        assert_eq!(
            truth(1.0, 1.0, 0.5, 0.5, c),
            Some(Truth {
                crossings: 8,
                arcs: 4,
                loops: 0
            })
        );
        // Off centre, out of x = 1 only; just inside: a loop.
        let c = level(1.0, 1.0, 0.5625, 0.5, 1, 1e-9);
        assert_eq!(
            truth(1.0, 1.0, 0.5625, 0.5, c),
            Some(Truth {
                crossings: 2,
                arcs: 1,
                loops: 0
            })
        );
        let c = level(1.0, 1.0, 0.5625, 0.5, 1, -1e-9);
        assert_eq!(
            truth(1.0, 1.0, 0.5625, 0.5, c),
            Some(Truth {
                crossings: 0,
                arcs: 0,
                loops: 1
            })
        );
        // Tangent to an edge exactly: not decided by this family.
        assert_eq!(truth(1.0, 1.0, 0.5, 0.5, 0.25), None);
    }
}
