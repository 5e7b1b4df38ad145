//! Certified projection (`rootclip::project`) against an independent
//! reference: the distance at the reported `(u, v)` lies in the reported
//! enclosure, and no sampled point of the patch (a dense grid, refined by
//! Newton on the squared distance) is closer than its lower end.

use glam::DVec3;
use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::Config;
use rootclip::project::{project, FootKind, ProjectOptions, Projection, ProjectionStatus};
use rootclip::ray::{BsplineSurface, Patch, TensorPatch, TriPatch};

fn cfg(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

/// The smallest `|S − p|` found by sampling a grid of the domain and
/// polishing the best few samples by projected gradient steps: an upper
/// bound of the true minimum (every sample is a point of the patch).
fn sampled_min(patch: &Patch, p: DVec3, domain: ([f64; 2], [f64; 2]), triangle: bool) -> f64 {
    let ([u0, u1], [v0, v1]) = domain;
    let n = 120;
    let inside = |u: f64, v: f64| !triangle || u + v <= 1.0;
    let mut best: Vec<(f64, f64, f64)> = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (u, v) = (
                u0 + (u1 - u0) * i as f64 / n as f64,
                v0 + (v1 - v0) * j as f64 / n as f64,
            );
            if inside(u, v) {
                best.push(((patch.eval(u, v) - p).length(), u, v));
            }
        }
    }
    best.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut min = best[0].0;
    for &(_, mut u, mut v) in best.iter().take(8) {
        let mut step = (u1 - u0).max(v1 - v0) / n as f64;
        for _ in 0..200 {
            let d = (patch.eval(u, v) - p).length();
            let mut moved = false;
            for (du, dv) in [
                (step, 0.0),
                (-step, 0.0),
                (0.0, step),
                (0.0, -step),
                (step, -step),
                (-step, step),
                (step, step),
                (-step, -step),
            ] {
                let (a, b) = ((u + du).clamp(u0, u1), (v + dv).clamp(v0, v1));
                if inside(a, b) && (patch.eval(a, b) - p).length() < d {
                    (u, v, moved) = (a, b, true);
                    break;
                }
            }
            if !moved {
                step *= 0.5;
                if step < 1e-13 {
                    break;
                }
            }
        }
        min = min.min((patch.eval(u, v) - p).length());
    }
    min
}

fn check(
    patch: &Patch,
    p: DVec3,
    pr: &Projection,
    domain: ([f64; 2], [f64; 2]),
    triangle: bool,
) -> Result<(), TestCaseError> {
    let [lo, hi] = pr.distance;
    prop_assert!(lo <= hi, "{pr:?}");
    let at = (patch.eval(pr.u, pr.v) - p).length();
    let slack = 1e-12 * (1.0 + at);
    prop_assert!(
        lo - slack <= at && at <= hi + slack,
        "|S(u, v) − P| = {at} outside {:?}",
        pr.distance
    );
    let sampled = sampled_min(patch, p, domain, triangle);
    prop_assert!(
        sampled >= lo - slack,
        "a sampled point at {sampled} is closer than {lo}: {pr:?}"
    );
    if pr.status == ProjectionStatus::Unique {
        prop_assert!(
            hi - lo <= 1e-9 * (1.0 + hi),
            "a certified foot with a wide enclosure: {pr:?}"
        );
        prop_assert!(
            sampled >= lo - slack && sampled <= hi + 1e-7 * (1.0 + hi),
            "sampled {sampled} vs {:?}",
            pr.distance
        );
    }
    Ok(())
}

fn tensor_patch(m: usize, n: usize, offsets: &[f64], weights: Option<Vec<f64>>) -> TensorPatch {
    let mut pts = Vec::new();
    for i in 0..=m {
        for j in 0..=n {
            let o = &offsets[3 * (i * (n + 1) + j)..];
            pts.push(DVec3::new(
                i as f64 / m as f64 + 0.1 * o[0],
                j as f64 / n as f64 + 0.1 * o[1],
                0.5 * o[2],
            ));
        }
    }
    TensorPatch::new(m, n, pts, weights).unwrap()
}

fn tri_patch(n: usize, offsets: &[f64], weights: Option<Vec<f64>>) -> TriPatch {
    let mut pts = Vec::new();
    let mut k = 0;
    for j in 0..=n {
        for i in 0..=n - j {
            let o = &offsets[3 * k..];
            pts.push(DVec3::new(
                i as f64 / n as f64 + 0.1 * o[0],
                j as f64 / n as f64 + 0.1 * o[1],
                0.5 * o[2],
            ));
            k += 1;
        }
    }
    TriPatch::new(n, pts, weights).unwrap()
}

proptest! {
    #![proptest_config(cfg(24))]

    /// Random (rational) tensor patches and points near, on and far from them.
    #[test]
    fn tensor_projection_is_certified(
        m in 1usize..=3,
        n in 1usize..=3,
        offsets in vec(-1.0f64..1.0, 48),
        weights in prop::option::of(vec(0.5f64..2.0, 16)),
        q in prop::array::uniform3(-0.5f64..1.5),
        lift in prop::sample::select(vec![0.0, 1e-9, 0.3, 3.0]),
    ) {
        let w = weights.map(|w| w[..(m + 1) * (n + 1)].to_vec());
        let patch: Patch = tensor_patch(m, n, &offsets, w).into();
        let p = DVec3::new(q[0], q[1], q[2]) + DVec3::Z * lift;
        let pr = project(&patch, p, &ProjectOptions::default()).unwrap();
        check(&patch, p, &pr, ([0.0, 1.0], [0.0, 1.0]), false)?;
    }

    /// Random triangular patches.
    #[test]
    fn triangle_projection_is_certified(
        n in 1usize..=3,
        offsets in vec(-1.0f64..1.0, 30),
        q in prop::array::uniform3(-0.5f64..1.5),
    ) {
        let patch: Patch = tri_patch(n, &offsets, None).into();
        let p = DVec3::new(q[0], q[1], q[2]);
        let pr = project(&patch, p, &ProjectOptions::default()).unwrap();
        check(&patch, p, &pr, ([0.0, 1.0], [0.0, 1.0]), true)?;
    }

    /// Points on the patch are inverted: the enclosure holds 0 and the foot is
    /// the planted parameter.
    #[test]
    fn inversion(
        m in 1usize..=3,
        n in 1usize..=3,
        offsets in vec(-1.0f64..1.0, 48),
        uv in prop::array::uniform2(0.05f64..0.95),
    ) {
        let patch: Patch = tensor_patch(m, n, &offsets, None).into();
        let p = patch.eval(uv[0], uv[1]);
        let pr = project(&patch, p, &ProjectOptions::default()).unwrap();
        prop_assert!(pr.distance[0] <= 1e-12 && pr.distance[1] <= 1e-9, "{pr:?}");
        let found = pr.feet.iter().any(|f| f.bx.u[0] - 1e-9 <= uv[0] && uv[0] <= f.bx.u[1] + 1e-9 && f.bx.v[0] - 1e-9 <= uv[1] && uv[1] <= f.bx.v[1] + 1e-9);
        prop_assert!(found || (patch.eval(pr.u, pr.v) - p).length() <= 1e-9, "{pr:?}");
    }
}

/// A B-spline surface (three bicubic pieces with a crease in the middle).
#[test]
fn bspline_projection() {
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let pts: Vec<DVec3> = (0..5)
        .flat_map(|i| {
            (0..3).map(move |j| {
                DVec3::new(
                    i as f64,
                    j as f64,
                    if i == 2 { 1.0 } else { ((i + j) % 2) as f64 * 0.3 },
                )
            })
        })
        .collect();
    let s = BsplineSurface::new((2, 2), ku, kv, pts, None).unwrap();
    let patch: Patch = s.into();
    for p in [
        DVec3::new(2.0, 1.0, 3.0),
        DVec3::new(0.5, 0.5, -1.0),
        DVec3::new(5.0, 5.0, 5.0),
        DVec3::new(1.3, 0.7, 0.4),
    ] {
        let pr = project(&patch, p, &ProjectOptions::default()).unwrap();
        let runner =
            |pr: &Projection| -> Result<(), TestCaseError> { check(&patch, p, pr, ([0.0, 2.0], [0.0, 1.0]), false) };
        runner(&pr).unwrap();
    }
}

/// Equidistant feet: the parabolic cylinder z = (2y − 1)² over the unit
/// square, seen from a point above its axis' side walls — two feet, mirror
/// images, which intervals cannot tell apart: `Ties`, both certified.
#[test]
fn medial_axis_ties() {
    // z = (2v − 1)²: a quadratic in v, linear (constant) in u.
    let pts = vec![
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(0.0, 0.5, -1.0),
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(1.0, 0.5, -1.0),
        DVec3::new(1.0, 1.0, 1.0),
    ];
    let patch: Patch = TensorPatch::new(1, 2, pts, None).unwrap().into();
    let p = DVec3::new(0.5, 0.5, 1.0); // above the valley's bottom, between the walls
    let pr = project(&patch, p, &ProjectOptions::default()).unwrap();
    check(&patch, p, &pr, ([0.0, 1.0], [0.0, 1.0]), false).unwrap();
    assert_eq!(pr.status, ProjectionStatus::Ties, "{pr:?}");
    assert_eq!(pr.feet.len(), 2, "{pr:?}");
    assert!(pr.feet.iter().all(|f| f.certified && f.kind == FootKind::Interior));
    let (a, b) = (pr.feet[0].v, pr.feet[1].v);
    assert!((a + b - 1.0).abs() < 1e-9, "mirror feet {a}, {b}");
}

/// The focal point of a circular arc swept along u: every point of the
/// arc is a foot (a curve of critical points). The distance is still
/// enclosed (more loosely: the lower bound over a whole arc of minima comes
/// from a refinement of bounded size) and the status says undecided.
#[test]
fn focal_point_is_undecided() {
    // A rational quadratic quarter circle of radius 1 about the axis x = z = 0,
    // swept along y ∈ [0, 1].
    let h = 0.5f64.sqrt();
    let pts = vec![
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let w = vec![1.0, 1.0, h, h, 1.0, 1.0];
    let patch: Patch = TensorPatch::new(2, 1, pts, Some(w)).unwrap().into();
    let p = DVec3::new(0.0, 0.5, 0.0);
    let pr = project(&patch, p, &ProjectOptions::default()).unwrap();
    assert!(
        pr.distance[0] <= 1.0 && 1.0 <= pr.distance[1] && pr.distance[1] - pr.distance[0] < 0.05,
        "{pr:?}"
    );
    assert_eq!(pr.status, ProjectionStatus::Undecided, "{pr:?}");
}
