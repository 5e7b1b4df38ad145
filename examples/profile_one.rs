//! One workload in a loop, for profilers: the certified hc solve of Example 1
//! (`profile_one N`), or the counters of both kernels (`profile_one stats`).
use inari::Interval;
use rootclip::poly::TriBall;
use rootclip::solve::driver::{self, Limits, Probe};
use rootclip::solve::num::GeoIv;
use rootclip::solve::{solve_triangle, Method, SolveOptions, SplitRule};
use rootclip::{parse_polynomial, Scalar};
fn main() {
    let arg = std::env::args().nth(1).unwrap_or_default();
    let f = parse_polynomial("u^3 - v")
        .unwrap()
        .to_triangle(3)
        .map(Interval::from_rational);
    let g = parse_polynomial("u^3 + v - 1/4")
        .unwrap()
        .to_triangle(3)
        .map(Interval::from_rational);
    if arg == "f64" {
        for ex in rootclip::repro::examples().unwrap() {
            let n = ex.f.total_degree().max(ex.g.total_degree()) as usize;
            let (ff, gf) = (
                ex.f.to_triangle(n).map(f64::from_rational),
                ex.g.to_triangle(n).map(f64::from_rational),
            );
            for m in Method::ALL {
                let o = SolveOptions {
                    method: m,
                    ..SolveOptions::default()
                };
                let pts = rootclip::solve::solve_triangle_f64(&ff, &gf, &o);
                println!("example {} {m}: {} leaves {:?}", ex.name, pts.len(), pts.first());
            }
        }
        return;
    }
    if arg == "stats" {
        let limits = Limits {
            method: Method::Hc,
            eps: 1e-12,
            max_boxes: 100000,
            max_depth: 400,
            max_exact: driver::MAX_EXACT_BOXES,
            probe_below: 0.0,
            split: SplitRule::Halving,
            swap_roles: true,
        };
        let (fb, gb) = (TriBall::enclose(&f).unwrap(), TriBall::enclose(&g).unwrap());
        let ri = driver::run::<GeoIv>(&fb, &gb, driver::Exact::None, &limits, &mut |_| Probe::Undecided);
        let rf = driver::run::<f64>(&fb, &gb, driver::Exact::None, &limits, &mut |_| Probe::Undecided);
        println!(
            "interval: {:?} leaves {}\nf64:      {:?} leaves {}",
            ri.counters,
            ri.leaves.len(),
            rf.counters,
            rf.leaves.len()
        );
        let sol = solve_triangle(&f, &g, &SolveOptions::default()).unwrap();
        println!("solve_triangle stats: {:?}", sol.stats);
        return;
    }
    if let Some(k) = arg.strip_prefix("plain") {
        let (ff, gf) = (f.map(|x| x.mid()), g.map(|x| x.mid()));
        let opts = SolveOptions {
            probe: false,
            ..SolveOptions::default()
        };
        for _ in 0..k.parse().unwrap_or(200) {
            std::hint::black_box(rootclip::solve::solve_triangle_f64(&ff, &gf, &opts));
        }
        return;
    }
    let n: usize = arg.parse().unwrap_or(200);
    for _ in 0..n {
        std::hint::black_box(solve_triangle(&f, &g, &SolveOptions::default()).unwrap());
    }
}
