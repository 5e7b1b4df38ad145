//! One workload in a loop, for profilers and A/B timings:
//! `profile_one [MODE][N] [EXAMPLE]` runs the hc solve of a paper example
//! (default `1`) N times (default 200): MODE empty is the certified solve
//! with default options, `noprobe` the certified solve without Krawczyk
//! probes, `plain` the same iteration in plain `f64`;
//! `profile_one stats [EXAMPLE]` prints the counters of the certified and
//! plain iterations.
use rootclip::inari::Interval;
use rootclip::internals::ball::TriBall;
use rootclip::internals::driver::{self, Exact, Limits, Probe};
use rootclip::internals::geo::GeoIv;
use rootclip::internals::repro;
use rootclip::internals::{solve_triangle, solve_triangle_f64};
use rootclip::solve::{Method, SolveOptions, SplitRule};
use rootclip::{Scalar, TriBezier};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = args.get(1).cloned().unwrap_or_default();
    let name = args.get(2).map_or("1", String::as_str);
    let ex = repro::examples()
        .unwrap()
        .into_iter()
        .find(|e| e.name == name)
        .expect("a paper example: 1, 2, 3k0, 3k2, 3k5");
    let n = ex.f.total_degree().max(ex.g.total_degree()).max(1) as usize;
    let f: TriBezier<Interval> = ex.f.to_triangle(n).map(Interval::from_rational);
    let g: TriBezier<Interval> = ex.g.to_triangle(n).map(Interval::from_rational);
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
            deadline: None,
        };
        let (fb, gb) = (TriBall::enclose(&f).unwrap(), TriBall::enclose(&g).unwrap());
        let ri = driver::run::<GeoIv>(&fb, &gb, Exact::None, &limits, &mut |_| Probe::Undecided(()));
        let rf = driver::run::<f64>(&fb, &gb, Exact::None, &limits, &mut |_| Probe::Undecided(()));
        println!(
            "certified: {:?} leaves {}\nplain:     {:?} leaves {}",
            ri.counters,
            ri.leaves.len(),
            rf.counters,
            rf.leaves.len()
        );
        let sol = solve_triangle(&f, &g, &SolveOptions::default()).unwrap();
        println!("solve_triangle stats: {:?}", sol.stats);
        return;
    }
    let (mode, count) = ["noprobe", "plain", ""]
        .iter()
        .find_map(|m| arg.strip_prefix(m).map(|rest| (*m, rest.parse().unwrap_or(200))))
        .expect("the empty prefix always matches");
    let opts = {
        let mut o = SolveOptions::default();
        o.probe = mode.is_empty();
        o
    };
    if mode == "plain" {
        let (ff, gf) = (f.map(|x| x.mid()), g.map(|x| x.mid()));
        for _ in 0..count {
            std::hint::black_box(solve_triangle_f64(&ff, &gf, &opts));
        }
        return;
    }
    for _ in 0..count {
        std::hint::black_box(solve_triangle(&f, &g, &opts).unwrap());
    }
}
