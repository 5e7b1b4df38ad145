//! The hot Bernstein–Bézier kernels of the solver, `f64` against
//! `inari::Interval`, for total degrees 3 to 10.
//!
//! Each group runs the `f64` and the `Interval` variant of one degree back to
//! back (`subdivide/f64/5`, `subdivide/Interval/5`, …) so the cost of rigour
//! reads off adjacent lines. Coefficients are deterministic pseudo-random
//! numbers in `[-1, 1]`; with intervals they are the same numbers as point
//! intervals (inari's cost does not depend on the width).
//!
//! `cargo bench --bench bernstein` takes about two minutes; pass a filter
//! (`cargo bench --bench bernstein -- reduce_l2_2`) to run one group.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use inari::Interval;
use rootclip::internals::triangle::de_casteljau_step;
use rootclip::{Scalar, TriBezier};
use std::hint::black_box;
use std::time::Duration;

const DEGREES: std::ops::RangeInclusive<usize> = 3..=10;

/// A generic interior sub-triangle (no vertex on an edge, no symmetry the
/// kernels could exploit), in the parent's barycentric coordinates.
const SUB_TRIANGLE: [[f64; 3]; 3] = [[0.6, 0.3, 0.1], [0.2, 0.7, 0.1], [0.25, 0.25, 0.5]];

/// SplitMix64: deterministic, dependency-free pseudo-random numbers.
struct SplitMix(u64);

impl SplitMix {
    fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        // 53 random bits → [0, 1) → [-1, 1).
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// The same pseudo-random polynomial of degree `n` in both kernels.
fn random_poly(n: usize, seed: u64) -> (TriBezier<f64>, TriBezier<Interval>) {
    let mut rng = SplitMix(seed ^ ((n as u64) << 32));
    let f = TriBezier::from_fn(n, |_, _, _| rng.next_unit());
    let g = f.map(|&c| <Interval as Scalar>::from_f64(c).expect("finite"));
    (f, g)
}

fn verts<S: Scalar>() -> [[S; 3]; 3] {
    SUB_TRIANGLE.map(|v| v.map(|x| S::from_f64(x).expect("finite")))
}

fn subdivide(c: &mut Criterion) {
    let mut group = c.benchmark_group("subdivide");
    for n in DEGREES {
        let (f, g) = random_poly(n, 1);
        let (vf, vg) = (verts::<f64>(), verts::<Interval>());
        group.bench_with_input(BenchmarkId::new("f64", n), &n, |b, _| {
            b.iter(|| black_box(&f).subdivide(black_box(&vf)))
        });
        group.bench_with_input(BenchmarkId::new("Interval", n), &n, |b, _| {
            b.iter(|| black_box(&g).subdivide(black_box(&vg)))
        });
    }
    group.finish();
}

fn reduce_l2(c: &mut Criterion) {
    for k in [1, 2] {
        let mut group = c.benchmark_group(format!("reduce_l2_{k}"));
        for n in DEGREES {
            let (f, g) = random_poly(n, 2);
            group.bench_with_input(BenchmarkId::new("f64", n), &n, |b, _| {
                b.iter(|| black_box(&f).reduce_l2(k).expect("k < n"))
            });
            group.bench_with_input(BenchmarkId::new("Interval", n), &n, |b, _| {
                b.iter(|| black_box(&g).reduce_l2(k).expect("k < n"))
            });
        }
        group.finish();
    }
}

fn split4(c: &mut Criterion) {
    let mut group = c.benchmark_group("split4");
    for n in DEGREES {
        let (f, g) = random_poly(n, 3);
        group.bench_with_input(BenchmarkId::new("f64", n), &n, |b, _| b.iter(|| black_box(&f).split4()));
        group.bench_with_input(BenchmarkId::new("Interval", n), &n, |b, _| {
            b.iter(|| black_box(&g).split4())
        });
    }
    group.finish();
}

/// Evaluation by `n` in-place de Casteljau steps (the solver's inner step).
fn de_casteljau(c: &mut Criterion) {
    fn eval<S: Scalar>(coeffs: &[S], n: usize, p: &[S; 3]) -> S {
        let mut net = coeffs.to_vec();
        for m in (1..=n).rev() {
            de_casteljau_step(&mut net, m, p);
        }
        net.swap_remove(0)
    }
    let mut group = c.benchmark_group("de_casteljau");
    for n in DEGREES {
        let (f, g) = random_poly(n, 4);
        let (pf, pg) = (verts::<f64>()[2], verts::<Interval>()[2]);
        group.bench_with_input(BenchmarkId::new("f64", n), &n, |b, _| {
            b.iter(|| eval(black_box(f.coeffs()), n, black_box(&pf)))
        });
        group.bench_with_input(BenchmarkId::new("Interval", n), &n, |b, _| {
            b.iter(|| eval(black_box(g.coeffs()), n, black_box(&pg)))
        });
    }
    group.finish();
}

/// Products of two polynomials of degree `n` (degrees the solver meets).
fn mul(c: &mut Criterion) {
    let mut group = c.benchmark_group("mul");
    for n in 3..=5 {
        let (f1, g1) = random_poly(n, 5);
        let (f2, g2) = random_poly(n, 6);
        group.bench_with_input(BenchmarkId::new("f64", n), &n, |b, _| {
            b.iter(|| black_box(&f1).mul(black_box(&f2)))
        });
        group.bench_with_input(BenchmarkId::new("Interval", n), &n, |b, _| {
            b.iter(|| black_box(&g1).mul(black_box(&g2)))
        });
    }
    group.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(700))
        .sample_size(20)
}

criterion_group! {
    name = benches;
    config = config();
    targets = subdivide, reduce_l2, split4, de_casteljau, mul
}
criterion_main!(benches);
