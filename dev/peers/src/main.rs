//! Issue 20's hard rays against peer libraries, one thread, one process.
//!
//! The workload: seed 000's Example 1 bicubic
//! (`examples/data/seed000_bicubic.json`) and `--rays N` rays aimed at
//! uniform random patch points `P = S(a, b)` from
//! `o = P + (U(2, 6), U(−3, 3), U(−3, 3))`, direction `P − o` (so `t = 1`
//! hits), every hit with `t ∈ [0, 3]` — the rays of `hard_rays aimed` for the
//! same `--seed` (`rootclip::internals::surface_aimed_rays`).
//!
//! Each ray goes through every method in turn (rootclip certified, the
//! peers, plain Newton), each timed `--reps` times (default 3) with the
//! minimum kept. Every method's hits are refereed by rootclip's certified
//! ones: a certified hit with no hit of the method within `--tol` (relative
//! in `t`, default 1e-6) is missed, a hit of the method near no hit of
//! rootclip's is invented. Prints a Markdown table and the ratio of the
//! fastest zero-miss peer's time to rootclip's.
//!
//! `cargo run --release -- [--seed S] [--rays N] [--reps R] [--tol T] [--loose T] [--methods a,b,...]`
//! (from `dev/peers`; methods: rootclip, brepkit-ray, brepkit-line,
//! brepkit-curve, curvo, newton).

mod peers;
mod referee;

use peers::{Certified, Surfaces};
use referee::Tally;
use rootclip::glam::DVec3;
use rootclip::internals::surface_aimed_rays;
use rootclip::ray::{Patch, PatchSpec, Ray};
use std::hint::black_box;
use std::time::Instant;

/// The methods, in the table's order: name, what is called.
const METHODS: [(&str, &str); 6] = [
    (
        "rootclip",
        "rootclip certified all hits (`ray::intersect`, `Query::All`)",
    ),
    ("brepkit-ray", "brepkit-math `RaySurface::hits`"),
    ("brepkit-line", "brepkit-math `intersect_line_nurbs`, 10 samples"),
    ("brepkit-curve", "brepkit-math `intersect_curve_surface`"),
    ("curvo", "curvo `find_intersection` (surface × degree-1 curve)"),
    ("newton", "plain Newton from (½, ½)"),
];

struct Args {
    seed: u64,
    rays: usize,
    reps: usize,
    tol: f64,
    loose: f64,
    methods: Vec<usize>,
}

fn parse_args() -> Result<Args, String> {
    let mut a = Args {
        seed: 20,
        rays: 10_000,
        reps: 3,
        tol: 1e-6,
        loose: 1e-3,
        methods: (0..METHODS.len()).collect(),
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let val = it.next().ok_or(format!("{flag} needs a value"))?;
        let bad = || format!("{flag}: bad value {val:?}");
        match flag.as_str() {
            "--seed" => a.seed = val.parse().map_err(|_| bad())?,
            "--rays" => a.rays = val.parse().map_err(|_| bad())?,
            "--reps" => a.reps = val.parse::<usize>().map_err(|_| bad())?.max(1),
            "--tol" => a.tol = val.parse().map_err(|_| bad())?,
            "--loose" => a.loose = val.parse().map_err(|_| bad())?,
            "--methods" => {
                a.methods = val
                    .split(',')
                    .map(|m| {
                        METHODS
                            .iter()
                            .position(|(n, _)| *n == m)
                            .ok_or(format!("unknown method {m}"))
                    })
                    .collect::<Result<_, _>>()?;
                if !a.methods.contains(&0) {
                    a.methods.insert(0, 0); // the referee always runs
                }
            }
            _ => return Err(format!("unknown argument {flag}")),
        }
    }
    Ok(a)
}

/// The bicubic's JSON, as far as the conversions need it.
#[derive(serde::Deserialize)]
struct Bicubic {
    degree: [usize; 2],
    points: Vec<[f64; 3]>,
}

fn load() -> Result<Surfaces, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/data/seed000_bicubic.json"
    ))?;
    let spec: PatchSpec = serde_json::from_str(&text)?;
    let bicubic: Bicubic = serde_json::from_str(&text)?;
    if bicubic.degree != [3, 3] || bicubic.points.len() != 16 {
        return Err("expected a bicubic (degree [3, 3], 16 points)".into());
    }
    // Row-major: P_ij at 4 i + j, i along u.
    let grid: Vec<Vec<DVec3>> = bicubic
        .points
        .chunks(4)
        .map(|row| row.iter().map(|p| DVec3::from_array(*p)).collect())
        .collect();
    Ok(Surfaces::new(Patch::from_spec(&spec)?, &grid)?)
}

/// The `t`s one method reports for one ray, and whether it flags the ray
/// as doubtful (only brepkit's `RaySurface` says so).
fn run(s: &Surfaces, method: usize, ray: &Ray) -> (Vec<f64>, bool) {
    match method {
        1 => s.brepkit_ray(ray),
        2 => (s.brepkit_line(ray), false),
        3 => (s.brepkit_curve(ray), false),
        4 => (s.curvo(ray), false),
        _ => (s.newton(ray), false),
    }
}

/// The minimum over `reps` runs of `f`, µs, and its last answer.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps {
        let t0 = Instant::now();
        let o = black_box(f());
        best = best.min(t0.elapsed().as_secs_f64() * 1e6);
        out = Some(o);
    }
    (best, out.expect("at least one repetition"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = parse_args()?;
    let s = load()?;
    let rays = surface_aimed_rays(&s.patch, args.rays, args.seed);
    // Warm-up: caches, page faults, lazy statics.
    for ray in rays.iter().take(100) {
        black_box(s.rootclip(ray));
        for &m in &args.methods[1..] {
            black_box(run(&s, m, ray));
        }
    }
    let mut tallies: Vec<Tally> = args.methods.iter().map(|_| Tally::default()).collect();
    let (mut uncertified, mut degenerate) = (0, 0);
    for ray in &rays {
        let (micros, answer): (f64, Certified) = timed(args.reps, || s.rootclip(ray));
        uncertified += answer.uncertified.len();
        degenerate += usize::from(answer.degenerate);
        let certified: Vec<f64> = answer.certified.iter().map(|b| 0.5 * (b[0] + b[1])).collect();
        let doubt = degenerate_or_undecided(&answer);
        tallies[0].add(micros, (&certified, doubt), &answer, args.tol, args.loose);
        for (k, &m) in args.methods.iter().enumerate().skip(1) {
            let (micros, (ts, flagged)) = timed(args.reps, || run(&s, m, ray));
            tallies[k].add(micros, (&ts, flagged), &answer, args.tol, args.loose);
        }
    }
    report(&args, &tallies, uncertified, degenerate);
    Ok(())
}

/// Whether rootclip's own answer for the ray is in doubt.
fn degenerate_or_undecided(answer: &Certified) -> bool {
    answer.degenerate || !answer.uncertified.is_empty()
}

fn report(args: &Args, tallies: &[Tally], uncertified: usize, degenerate: usize) {
    println!(
        "seed {}: {} rays aimed at S(a, b) from S(a, b) + (U(2, 6), U(-3, 3), U(-3, 3)), t in [0, 3]; one thread, each ray min of {}; refereed at {:e} relative in t ({:e} in the last column)",
        args.seed, args.rays, args.reps, args.tol, args.loose
    );
    println!(
        "rootclip: {} certified hits, {uncertified} uncertified, {degenerate} degenerate rays\n",
        tallies[0].hits
    );
    println!("| method | µs/ray mean | median | p99 | max | hits | missed | invented | duplicates | missed / invented at {:e} | rays flagged (hits missed there) |", args.loose);
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (t, &m) in tallies.iter().zip(&args.methods) {
        let [mean, median, p99, max] = t.distribution();
        println!(
            "| {} | {mean:.1} | {median:.1} | {p99:.1} | {max:.0} | {} | {} | {} | {} | {} / {} | {} ({}) |",
            METHODS[m].1,
            t.hits,
            t.missed,
            t.invented,
            t.duplicates,
            t.missed_loose,
            t.invented_loose,
            t.flagged,
            t.missed_flagged
        );
    }
    let rc = tallies[0].distribution();
    let best = tallies
        .iter()
        .zip(&args.methods)
        .skip(1)
        .filter(|(t, _)| t.missed == 0)
        .min_by(|a, b| a.0.distribution()[0].total_cmp(&b.0.distribution()[0]));
    match best {
        Some((t, &m)) => {
            let d = t.distribution();
            println!(
                "\nfastest zero-miss peer: {} — {:.2}× rootclip's mean time, {:.2}× its median",
                METHODS[m].0,
                d[0] / rc[0],
                d[1] / rc[1]
            );
        }
        None => println!("\nno peer found every certified hit"),
    }
}
