//! Whole certified solves of the paper's systems (Liu et al. 2016, §4) to
//! `eps = 1e-12`, and the cost of rigor.
//!
//! * `certified/<method>/<system>`: [`solve_triangle`] with default options
//!   (Krawczyk probes on) on pre-converted `Interval` BB input, so the exact
//!   conversion and common-factor check of [`solve`] are excluded;
//! * `exact_input/hc/1`: [`solve`] itself on Example 1 (exact polynomials →
//!   BB form, common-factor check, then the same solve) — the difference to
//!   `certified/hc/1` is that front-end cost;
//! * `rigor/<method>-<variant>/<system>` for `bezier` and `hc`: the same
//!   iteration certified without probes (`certified-noprobe`: exactly
//!   Algorithm 1, then Krawczyk on the final boxes) and in plain `f64` with
//!   [`solve_triangle_f64`] (`plain-f64`: no proofs); for `hc` also certified
//!   with probes (`certified`, the default). Before timing, each system prints
//!   how many certified roots the plain run ends near — a plain run that
//!   lost a root stopped early, and its time is no measure of rigor.
//!
//! Systems: `1`, `2`, `3k0`, `3k2`, `3k5` from `papers/hybrid-clipping-2016`.
//! `solve_triangle` has an exact system only when every input coefficient is
//! a float (Examples 1 and 3 with k = 0); elsewhere it cannot restart a
//! stalled tri-box from exact input.
//!
//! `cargo bench --bench solve` takes about two minutes; pass a filter
//! (`cargo bench --bench solve -- rigor`) to run one group.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use inari::Interval;
use rootclip::internals::repro::{self, Example};
use rootclip::internals::solve_triangle_f64;
use rootclip::scalar::rational_to_f64;
use rootclip::solve::{solve, solve_bb, Domain, Method, SolveOptions};
use rootclip::{Scalar, TriBezier};
use std::hint::black_box;
use std::time::Duration;

const EPS: f64 = 1e-12;
const SYSTEMS: [&str; 5] = ["1", "2", "3k0", "3k2", "3k5"];

/// One system in the three input forms.
struct Input {
    name: &'static str,
    example: Example,
    interval: [TriBezier<Interval>; 2],
    plain: [TriBezier<f64>; 2],
}

fn inputs() -> Vec<Input> {
    let all = repro::examples().expect("paper_tables.json parses");
    SYSTEMS
        .iter()
        .map(|&name| {
            let example = all
                .iter()
                .find(|e| e.name == name)
                .expect("system in the data file")
                .clone();
            let n = example.f.total_degree().max(example.g.total_degree()).max(1) as usize;
            let exact = [example.f.to_triangle(n), example.g.to_triangle(n)];
            let interval = exact.clone().map(|p| p.map(Interval::from_rational));
            let plain = exact.map(|p| p.map(rational_to_f64));
            Input {
                name,
                example,
                interval,
                plain,
            }
        })
        .collect()
}

fn options(method: Method) -> SolveOptions {
    {
        let mut o = SolveOptions::default();
        o.method = method;
        o.eps = EPS;
        o
    }
}

fn certified(c: &mut Criterion) {
    let inputs = inputs();
    let mut group = c.benchmark_group("certified");
    for method in Method::ALL {
        for x in &inputs {
            let [f, g] = &x.interval;
            let opts = options(method);
            group.bench_with_input(BenchmarkId::new(method.name(), x.name), &opts, |b, opts| {
                b.iter(|| solve_bb(black_box(f), black_box(g), opts).expect("valid input"))
            });
        }
    }
    group.finish();
}

fn exact_input(c: &mut Criterion) {
    let inputs = inputs();
    let x = &inputs[0];
    let opts = options(Method::Hc);
    let mut group = c.benchmark_group("exact_input");
    group.bench_with_input(BenchmarkId::new("hc", x.name), &opts, |b, opts| {
        b.iter(|| solve(black_box(&x.example.f), black_box(&x.example.g), Domain::Triangle, opts).expect("valid input"))
    });
    group.finish();
}

fn rigor(c: &mut Criterion) {
    let inputs = inputs();
    let mut group = c.benchmark_group("rigor");
    for x in &inputs {
        let [f, g] = &x.interval;
        let [pf, pg] = &x.plain;
        for method in [Method::Bezier, Method::Hc] {
            let probing = options(method);
            let no_probe = {
                let mut o = probing;
                o.probe = false;
                o
            };
            report_plain_roots(x, method, &no_probe);
            let name = |variant: &str| format!("{}-{variant}", method.name());
            if method == Method::Hc {
                group.bench_with_input(BenchmarkId::new(name("certified"), x.name), &probing, |b, opts| {
                    b.iter(|| solve_bb(black_box(f), black_box(g), opts).expect("valid input"))
                });
            }
            group.bench_with_input(
                BenchmarkId::new(name("certified-noprobe"), x.name),
                &no_probe,
                |b, opts| b.iter(|| solve_bb(black_box(f), black_box(g), opts).expect("valid input")),
            );
            group.bench_with_input(BenchmarkId::new(name("plain-f64"), x.name), &no_probe, |b, opts| {
                b.iter(|| solve_triangle_f64(black_box(pf), black_box(pg), opts))
            });
        }
    }
    group.finish();
}

/// Prints how many certified roots the plain `f64` run ends near: a plain
/// run that lost a root did less work, and its time is no cost of rigor.
fn report_plain_roots(x: &Input, method: Method, opts: &SolveOptions) {
    let [f, g] = &x.interval;
    let [pf, pg] = &x.plain;
    let roots = solve_bb(f, g, opts).expect("valid input").roots;
    let centres = solve_triangle_f64(pf, pg, opts);
    let found = roots
        .iter()
        .filter(|r| centres.iter().any(|c| (c[0] - r.u).hypot(c[1] - r.v) < 1e-6))
        .count();
    eprintln!(
        "rigor/{}/{}: plain f64 ends near {found} of the {} certified roots ({} final tri-boxes)",
        method.name(),
        x.name,
        roots.len(),
        centres.len()
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1200));
    targets = certified, exact_input, rigor
}
criterion_main!(benches);
