//! Christensen's (2008) closed forms against their certified referees (the harness of
//! `examples/closed_forms.rs`): on random rays they agree with the
//! referee; on the cases the write-up reports as failures the referee
//! catches them; and the 2D and 3D referees agree with each other.

#[path = "../examples/closed_forms/cases.rs"]
#[allow(dead_code)]
mod cases;
#[path = "../examples/closed_forms/oracle.rs"]
#[allow(dead_code)]
mod oracle;
#[path = "../examples/closed_forms/tally.rs"]
#[allow(dead_code)]
mod tally;

use rootclip::glam::{DVec2, DVec3};
use rootclip::heuristics::{ray_quadratic_bezier_2d, ray_segment_2d, ray_swept_quadratic_patch_3d, ClosedForm};
use rootclip::internals::Rng;
use tally::{Claim, Tally};

fn quad_tally(fam: &cases::Family<cases::Quad>) -> Tally {
    let mut t = Tally::default();
    for c in &fam.cases {
        let r = oracle::curve_2d(c.o, c.d, &c.p);
        let cf = ray_quadratic_bezier_2d(c.o, c.d, c.p).unwrap();
        let claims: Option<Vec<Claim>> = match &cf {
            ClosedForm::Failed(_) => None,
            _ => Some(cf.hits().iter().map(|h| Claim { t: h.t, u: None }).collect()),
        };
        t.add(claims.as_deref(), &r);
    }
    t
}

fn agrees(t: &Tally) -> bool {
    t.lost == 0 && t.invented == 0 && t.misplaced == 0 && t.failed == 0 && t.in_open == 0
}

#[test]
fn random_rays_agree_with_the_referee() {
    let mut rng = Rng(7);
    let t = quad_tally(&cases::quad_random(&mut rng, 300));
    assert!(agrees(&t) && t.oracle_hits > 250 && t.cf_hits == t.oracle_hits, "{t:?}");

    let mut t = Tally::default();
    for c in cases::seg_random(&mut rng, 300).cases {
        let r = oracle::curve_2d(c.o, c.d, &[c.b, c.a]);
        let cf = ray_segment_2d(c.o, c.d, c.a, c.b).unwrap();
        let claims: Vec<Claim> = cf.hits().iter().map(|h| Claim { t: h.t, u: None }).collect();
        t.add(Some(&claims), &r);
    }
    assert!(agrees(&t) && t.oracle_hits > 200, "{t:?}");

    let mut t = Tally::default();
    for c in cases::swept_random(&mut rng, 150).cases {
        let r = oracle::swept_3d(c.o, c.d, &oracle::swept_patch(c.p, c.e));
        let cf = ray_swept_quadratic_patch_3d(c.o, c.d, c.p, c.e).unwrap();
        let claims: Vec<Claim> = cf.hits().iter().map(|h| Claim { t: h.t, u: Some(h.u) }).collect();
        t.add(Some(&claims), &r);
    }
    assert!(agrees(&t) && t.oracle_hits > 100, "{t:?}");
}

#[test]
fn the_referee_catches_what_rounding_does_to_the_quadratic_formula() {
    let mut rng = Rng(11);
    // A hit 1e-300 outside t = 0: −B + √(B² − 4AC) cancels to 0, and t = 0
    // is kept. The referee proves the root lies outside: an invention, every
    // time.
    let t = quad_tally(&cases::quad_tiny_off_end(&mut rng, 50, false));
    assert_eq!((t.oracle_hits, t.invented), (0, 50), "{t:?}");
    // 1e-300 inside: the same 0, now right (within the tolerance).
    let t = quad_tally(&cases::quad_tiny_off_end(&mut rng, 50, true));
    assert!(agrees(&t) && t.oracle_hits == 50, "{t:?}");
    // Rays grazing at 1e-16 (below the inputs' resolution): the sign of
    // B² − 4AC is noise, and hits are lost and invented.
    let t = quad_tally(&cases::quad_grazing(&mut rng, 200, 1e-16, true));
    assert!(t.lost + t.invented > 0, "{t:?}");
    // An exact tangency is an undecided region of the referee, never a loss
    // or an invention.
    let t = quad_tally(&cases::quad_tangent(&mut rng, 50));
    assert_eq!(
        (t.oracle_hits, t.oracle_open, t.lost, t.invented),
        (0, 50, 0, 0),
        "{t:?}"
    );
}

#[test]
fn the_segment_formula_loses_near_parallel_hits_to_rounding() {
    let mut rng = Rng(13);
    let mut t = Tally::default();
    for c in cases::seg_near_parallel(&mut rng, 100, 1e-14).cases {
        let r = oracle::curve_2d(c.o, c.d, &[c.b, c.a]);
        let cf = ray_segment_2d(c.o, c.d, c.a, c.b).unwrap();
        let claims: Vec<Claim> = cf.hits().iter().map(|h| Claim { t: h.t, u: None }).collect();
        t.add(Some(&claims), &r);
    }
    // Every ray hits (the referee certifies it), but the formula's t is off
    // by ~1e-16/1e-14 = 1e-2 in most of them.
    assert_eq!(t.oracle_hits, 100);
    assert!(t.misplaced > 50, "{t:?}");
}

#[test]
fn the_2d_and_3d_referees_agree() {
    // Horizontal rays at half height: the 3D hits are the 2D hits of the
    // projection, at u = 1/2.
    let mut rng = Rng(17);
    for c in cases::quad_random(&mut rng, 60).cases {
        let e = 2.0;
        let r2 = oracle::curve_2d(c.o, c.d, &c.p);
        let o = DVec3::new(c.o.x, c.o.y, 1.0);
        let d = DVec3::new(c.d.x, c.d.y, 0.0);
        let r3 = oracle::swept_3d(o, d, &oracle::swept_patch(c.p, e));
        assert!(r2.open.is_empty() && r3.open.is_empty() && !r3.degenerate);
        assert_eq!(r2.hits.len(), r3.hits.len(), "{c:?}");
        for h in &r2.hits {
            let m = 0.5 * (h.t[0] + h.t[1]);
            assert!(r3.hits.iter().any(|k| {
                let u = k.u.unwrap();
                (k.t[0] - 1e-9..=k.t[1] + 1e-9).contains(&m) && u[0] <= 0.5 && 0.5 <= u[1]
            }));
        }
    }
    // A ray along the sweep through the curve: a segment of hits, which
    // the 3D referee leaves undecided (one region over the whole sweep) and
    // the formula declines.
    let p = [DVec2::new(-1.0, 1.0), DVec2::new(0.0, -1.0), DVec2::new(1.0, 1.0)];
    let r3 = oracle::swept_3d(DVec3::new(0.0, 0.0, -1.0), DVec3::Z, &oracle::swept_patch(p, 1.0));
    let covers_sweep = r3.open.iter().any(|o| o.u.is_some_and(|u| u[0] <= 0.0 && 1.0 <= u[1]));
    assert!(r3.degenerate || (r3.hits.is_empty() && covers_sweep), "{r3:?}");
    let cf = ray_swept_quadratic_patch_3d(DVec3::new(0.0, 0.0, -1.0), DVec3::Z, p, 1.0).unwrap();
    assert!(cf.failure().is_some());
}

#[test]
fn the_reduction_to_2d_agrees_with_the_tensor_referee_and_decides_what_it_leaves() {
    let mut rng = Rng(19);
    // Where the tensor-patch referee decides everything, the exact
    // reduction finds the same hits, at the same (t, u).
    for c in cases::swept_random(&mut rng, 80).cases {
        let r3 = oracle::swept_3d(c.o, c.d, &oracle::swept_patch(c.p, c.e));
        let red = oracle::swept_reduced(c.o, c.d, &c.p, c.e).expect("decided");
        assert!(r3.complete && r3.open.is_empty());
        assert_eq!(r3.hits.len(), red.hits.len(), "{c:?}");
        for h in &red.hits {
            let (t, u) = (0.5 * (h.t[0] + h.t[1]), h.u.map(|u| 0.5 * (u[0] + u[1])).unwrap());
            assert!(r3.hits.iter().any(|k| {
                let ku = k.u.unwrap();
                (k.t[0] - 1e-9..=k.t[1] + 1e-9).contains(&t) && (ku[0] - 1e-9..=ku[1] + 1e-9).contains(&u)
            }));
        }
    }
    // A grazing ray in plan the tensor referee leaves undecided: decided,
    // both hits certified, and the closed form agrees.
    let fam = cases::swept_grazing(&mut rng, 20, 1e-15, true);
    let mut t = Tally::default();
    for c in &fam.cases {
        let r = oracle::swept(c.o, c.d, c.p, c.e);
        let cf = ray_swept_quadratic_patch_3d(c.o, c.d, c.p, c.e).unwrap();
        let claims: Vec<Claim> = cf.hits().iter().map(|h| Claim { t: h.t, u: Some(h.u) }).collect();
        t.add(Some(&claims), &r);
    }
    assert!(agrees(&t) && t.oracle_hits == 40 && t.oracle_reduced > 0, "{t:?}");
    // Nearly along the sweep (ε = 1e-12): t right, u wrong by ~1e-4.
    let mut t = Tally::default();
    for c in cases::swept_near_vertical(&mut rng, 20, 1e-12).cases {
        let r = oracle::swept(c.o, c.d, c.p, c.e);
        let cf = ray_swept_quadratic_patch_3d(c.o, c.d, c.p, c.e).unwrap();
        let claims: Vec<Claim> = cf.hits().iter().map(|h| Claim { t: h.t, u: Some(h.u) }).collect();
        t.add(Some(&claims), &r);
    }
    assert_eq!(t.oracle_hits, 20, "{t:?}");
    assert!(t.misplaced > 10 && t.worst_misplaced > 1e-6, "{t:?}");
}
