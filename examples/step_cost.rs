//! Times the pieces of one clipping step (interval kernel) on Example 1's
//! first tri-box: subdivision, fat curves, preprocessing, candidate geometry.
use inari::Interval;
use rootclip::solve::method::{clip_bounds, fat_curve, preprocess_general, Method};
use rootclip::solve::tribox::TriBox;
use rootclip::{parse_polynomial, Scalar};
use std::time::Instant;
fn time(name: &str, n: usize, mut f: impl FnMut()) {
    let t = Instant::now();
    for _ in 0..n {
        f();
    }
    println!("{name:>28}: {:8.2} µs", t.elapsed().as_secs_f64() / n as f64 * 1e6);
}
fn main() {
    let f = parse_polynomial("u^3 - v")
        .unwrap()
        .to_triangle(3)
        .map(Interval::from_rational);
    let g = parse_polynomial("u^3 + v - 1/4")
        .unwrap()
        .to_triangle(3)
        .map(Interval::from_rational);
    let tb = TriBox {
        verts: [[0.6, 0.1], [0.45, 0.3], [0.4, 0.05]],
    };
    let verts = tb.bary_intervals();
    let (fa, fb) = (f.subdivide(&verts), g.subdivide(&verts));
    let c = tb.incenter_bary();
    let n = 20000;
    time("subdivide (deg 3)", n, || {
        std::hint::black_box(f.subdivide(&verts));
    });
    time("fat line (deg 3)", n, || {
        std::hint::black_box(fat_curve(&fa, 1));
    });
    time("fat conic (deg 3)", n, || {
        std::hint::black_box(fat_curve(&fb, 2));
    });
    time("preprocess_general", n, || {
        std::hint::black_box(preprocess_general(&fa, &fb, c));
    });
    for m in Method::ALL {
        time(&format!("clip_bounds {m}"), n, || {
            std::hint::black_box(clip_bounds(m, &fa, &fb, c));
        });
    }
    let (a, b) = (Interval::from_f64(0.3).unwrap(), Interval::from_f64(0.7).unwrap());
    time("1e6 interval mul", 1, || {
        let mut x = a;
        for _ in 0..1_000_000 {
            x = std::hint::black_box(x * b + a);
        }
        std::hint::black_box(x);
    });
}
