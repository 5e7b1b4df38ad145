//! Per-ray cost on issue 20's hard workloads against Park, Ji & Ko's (2013) Example 1
//! bicubic patch (`examples/data/seed000_bicubic.json`), one thread:
//!
//! * `aimed` (default): rays aimed at uniform random patch points
//!   `P = S(a, b)` from `o = P + (U(2, 6), U(−3, 3), U(−3, 3))`, direction
//!   `P − o`, every hit with `t ∈ [0, 3]`
//!   ([`rootclip::internals::surface_aimed_rays`]);
//! * `secondary`: origins on the patch (half of them exactly on it, at
//!   dyadic parameters), uniform directions, `t ≥ 0`
//!   ([`rootclip::internals::secondary_rays`]).
//!
//! Prints the distribution of the time per ray (mean, median, p90, p99,
//! max), the hit counts (certified, undecided, degenerate rays), and the
//! slowest rays as `ox oy oz dx dy dz` lines (`--slow K`), which
//! `rootclip ray --rays` reads. Each ray is timed `--reps R` times (default
//! 3) and its minimum kept, so that a neighbour's burst on a shared machine
//! is not charged to one ray.
//!
//! `cargo run --release -p rootclip-dev --bin hard_rays -- [aimed|secondary] [N] [--seed S] [--reps R] [--slow K] [--query all|nearest|any] [--route rect|triangles|rect-fat-line|rect-hybrid] [--dump FILE]`

use rootclip::internals::{secondary_rays, surface_aimed_rays};
use rootclip::ray::{intersect, Degeneracy, Patch, PatchSpec, Query, Ray, RayOptions, RayOutcome};
use rootclip::solve::SquareRoute;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut kind = "aimed".to_string();
    let (mut n, mut seed, mut reps, mut slow) = (10_000usize, 20u64, 3usize, 10usize);
    let (mut query, mut route, mut dump) = (Query::All, SquareRoute::Rect, None::<String>);
    let mut i = 0;
    while i < args.len() {
        let val = |i: usize| args.get(i + 1).cloned().ok_or(format!("{} needs a value", args[i]));
        match args[i].as_str() {
            "aimed" | "secondary" => kind = args[i].clone(),
            "--seed" => (seed, i) = (val(i)?.parse()?, i + 1),
            "--reps" => (reps, i) = (val(i)?.parse()?, i + 1),
            "--slow" => (slow, i) = (val(i)?.parse()?, i + 1),
            "--dump" => (dump, i) = (Some(val(i)?), i + 1),
            "--query" => {
                query = match val(i)?.as_str() {
                    "all" => Query::All,
                    "nearest" => Query::Nearest,
                    "any" => Query::Any,
                    q => return Err(format!("unknown query {q}").into()),
                };
                i += 1;
            }
            "--route" => {
                route = match val(i)?.as_str() {
                    "rect" => SquareRoute::Rect,
                    "triangles" => SquareRoute::Triangles,
                    "rect-fat-line" => SquareRoute::RectFatLine,
                    "rect-hybrid" => SquareRoute::RectHybrid,
                    r => return Err(format!("unknown route {r}").into()),
                };
                i += 1;
            }
            s => n = s.parse().map_err(|_| format!("unknown argument {s}"))?,
        }
        i += 1;
    }
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/data/seed000_bicubic.json"
    ))?;
    let spec: PatchSpec = serde_json::from_str(&text)?;
    let patch = Patch::from_spec(&spec)?;
    let (rays, opts): (Vec<Ray>, RayOptions) = match kind.as_str() {
        "aimed" => (
            surface_aimed_rays(&patch, n, seed),
            RayOptions::default().with_t_range(0.0, 3.0),
        ),
        _ => (secondary_rays(&patch, n, seed), RayOptions::default()),
    };
    let opts = opts.with_query(query).with_route(route);
    if let Some(path) = &dump {
        let lines: Vec<String> = rays.iter().map(line).collect();
        std::fs::write(path, lines.join("\n") + "\n")?;
    }
    let (mut times, mut outs) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for ray in &rays {
        let mut best = f64::INFINITY;
        let mut out = None;
        for _ in 0..reps.max(1) {
            let t0 = Instant::now();
            let o = intersect(&patch, ray, &opts)?;
            best = best.min(t0.elapsed().as_secs_f64() * 1e6);
            out = Some(o);
        }
        times.push(best);
        outs.push(out.expect("at least one repetition"));
    }
    let (mut certified, mut undecided, mut degenerate, mut with_two) = (0, 0, 0, 0);
    for o in &outs {
        match o {
            RayOutcome::Hits(h) => {
                certified += h.hits.iter().filter(|x| x.is_certified()).count();
                undecided += h.hits.iter().filter(|x| !x.is_certified()).count();
                with_two += usize::from(h.hits.len() >= 2);
            }
            RayOutcome::Degenerate(Degeneracy::Unresolved(h)) => {
                degenerate += 1;
                undecided += h.hits.len();
            }
            RayOutcome::Degenerate(_) => degenerate += 1,
        }
    }
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let q = |p: f64| sorted[((p * (n - 1) as f64).round() as usize).min(n - 1)];
    let mean = times.iter().sum::<f64>() / n as f64;
    let top: f64 = sorted.iter().rev().take(n / 100).sum();
    println!(
        "{kind} {n} rays (seed {seed}, {query:?}, {route:?}, min of {reps}): mean {mean:.2} µs, median {:.2}, p90 {:.2}, p99 {:.1}, max {:.1} µs; slowest 1% = {:.0}% of the time",
        q(0.5),
        q(0.9),
        q(0.99),
        sorted[n - 1],
        100.0 * top / times.iter().sum::<f64>()
    );
    println!(
        "hits: {certified} certified, {undecided} undecided; {degenerate} degenerate rays; {with_two} rays with two or more hits"
    );
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| times[b].total_cmp(&times[a]));
    for &k in order.iter().take(slow) {
        println!("slow {:9.1} µs  ray {k:5}: {}", times[k], line(&rays[k]));
    }
    Ok(())
}

fn line(r: &Ray) -> String {
    let (o, d) = (r.origin(), r.dir());
    format!("{:?} {:?} {:?} {:?} {:?} {:?}", o.x, o.y, o.z, d.x, d.y, d.z)
}
