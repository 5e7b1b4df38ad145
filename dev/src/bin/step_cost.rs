//! Times the pieces of one clipping step on Example 1's first tri-box, in the
//! certified solver's ball arithmetic (geometry in `GeoIv`) and in the plain
//! `f64` iteration: subdivision, fat curves, preprocessing, a clip per method,
//! the verified tri-box clip.
use rootclip::inari::Interval;
use rootclip::internals::ball::TriBall;
use rootclip::internals::geo::GeoIv;
use rootclip::internals::method::{clip_bounds, fat_curve, preprocess_general};
use rootclip::internals::tribox::TriBox;
use rootclip::solve::Method;
use rootclip::{parse_polynomial, Scalar};
use std::time::Instant;
fn time(name: &str, n: usize, mut f: impl FnMut()) {
    let t = Instant::now();
    for _ in 0..n {
        f();
    }
    println!("{name:>32}: {:8.3} µs", t.elapsed().as_secs_f64() / n as f64 * 1e6);
}
fn main() {
    let ball =
        |s: &str| TriBall::enclose(&parse_polynomial(s).unwrap().to_triangle(3).map(Interval::from_rational)).unwrap();
    let (f, g) = (ball("u^3 - v"), ball("u^3 + v - 1/4"));
    let tb = TriBox {
        verts: [[0.6, 0.1], [0.45, 0.3], [0.4, 0.05]],
    };
    let (fa, fb) = (f.subdivide(&tb.verts), g.subdivide(&tb.verts));
    let c = tb.incenter_bary();
    let n = 200_000;
    time("subdivide (deg 3)", n, || {
        std::hint::black_box(f.subdivide(std::hint::black_box(&tb.verts)));
    });
    time("fat line (deg 3), GeoIv", n, || {
        std::hint::black_box(fat_curve::<GeoIv>(&fa, 1));
    });
    time("fat conic (deg 3), GeoIv", n, || {
        std::hint::black_box(fat_curve::<GeoIv>(&fb, 2));
    });
    time("preprocess_general", n, || {
        std::hint::black_box(preprocess_general(&fa, &fb, c));
    });
    for m in Method::ALL {
        time(&format!("clip_bounds {m}, GeoIv"), n, || {
            std::hint::black_box(clip_bounds::<GeoIv>(m, &fa, &fb, c));
        });
        time(&format!("clip_bounds {m}, f64"), n, || {
            std::hint::black_box(clip_bounds::<f64>(m, &fa, &fb, c));
        });
    }
    time("TriBox::clip (verified)", n, || {
        std::hint::black_box(tb.clip(std::hint::black_box([0.1, 0.2, 0.3])));
    });
    time("TriBox::clip_unverified", n, || {
        std::hint::black_box(tb.clip_unverified(std::hint::black_box([0.1, 0.2, 0.3])));
    });
    time("TriBox::split4", n, || {
        std::hint::black_box(std::hint::black_box(&tb).split4());
    });
}
