use rootclip::inari::Interval;
use rootclip::internals::{solve_triangle, solve_triangle_f64};
use rootclip::solve::{solve, Domain, Method, SolveOptions};
use rootclip::{parse_polynomial, Scalar, TriBezier};
use std::time::Instant;
fn per_call(n: usize, mut f: impl FnMut()) -> f64 {
    f();
    let t = Instant::now();
    for _ in 0..n {
        f();
    }
    t.elapsed().as_secs_f64() / n as f64 * 1e6
}
fn main() {
    for (f, g) in [("u^3 - v", "u^3 + v - 1/4"), ("u^2+v^2-1/2", "u*v-1/8")] {
        let (f, g) = (parse_polynomial(f).unwrap(), parse_polynomial(g).unwrap());
        let nn = f.total_degree().max(g.total_degree()) as usize;
        let (ti, gi): (TriBezier<Interval>, TriBezier<Interval>) = (
            f.to_triangle(nn).map(Interval::from_rational),
            g.to_triangle(nn).map(Interval::from_rational),
        );
        let (tf, gf): (TriBezier<f64>, TriBezier<f64>) = (ti.map(|x| x.mid()), gi.map(|x| x.mid()));
        for m in Method::ALL {
            let o = {
                let mut o = SolveOptions::default();
                o.method = m;
                o
            };
            let full = per_call(500, || {
                drop(std::hint::black_box(solve(&f, &g, Domain::Triangle, &o).unwrap()))
            });
            let tri = per_call(2000, || {
                drop(std::hint::black_box(solve_triangle(&ti, &gi, &o).unwrap()))
            });
            let plain = per_call(2000, || drop(std::hint::black_box(solve_triangle_f64(&tf, &gf, &o))));
            println!(
                "{m:>9}: solve() {full:7.1} µs  solve_triangle {tri:7.1} µs  plain f64 {plain:7.1} µs  ratio {:.2}",
                tri / plain
            );
        }
    }
}
