//! The ray adversary at scale: grazing rays against height-field patches
//! (the families of `tests/adversary/mod.rs`), every answer of
//! `rootclip::ray::intersect` judged by the exact referee there. Prints a
//! summary per family and one small reproduction per failure class; with
//! `--dump DIR` writes every failure as `DIR/<family>-<fault>-<seed>.json`
//! (the patch, as `rootclip ray --patch` reads it) and `.txt` (the report and
//! the command line, numbers round-tripping exactly).
//!
//! ```sh
//! cargo run --release -p rootclip-dev --bin adversary -- --seed 1 --cases 2000 --family all --dump /tmp/adv
//! cargo run --release -p rootclip-dev --bin adversary -- --family bspline --case-seed 0x1234
//! ```
//!
//! Options: `--seed S` (default 1), `--cases N` per family (default 2000),
//! `--family tensor|rational|triangle|bspline|nurbs|all` (default all), `--dump DIR`,
//! `--threads T` (default 1), `--case-seed X` (one case, its full report),
//! `--list` (one line per case: seed, answer, true hits, reported hits, label).

#[path = "../../../tests/adversary/mod.rs"]
mod adversary;

use adversary::{Answer, Case, Family, Fault, Verdict};
use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

struct Args {
    seed: u64,
    cases: u64,
    families: Vec<Family>,
    dump: Option<PathBuf>,
    threads: usize,
    case_seed: Option<u64>,
    list: bool,
}

fn parse_u64(s: &str) -> u64 {
    let parsed = match s.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => s.parse(),
    };
    parsed.unwrap_or_else(|_| die(&format!("not a number: {s}")))
}

fn die(msg: &str) -> ! {
    eprintln!("adversary: {msg}");
    std::process::exit(2)
}

fn parse_args() -> Args {
    let mut a = Args {
        seed: 1,
        cases: 2000,
        families: Family::ALL.to_vec(),
        dump: None,
        threads: 1,
        case_seed: None,
        list: false,
    };
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let mut it = argv.iter();
    while let Some(flag) = it.next() {
        let mut value = || {
            it.next()
                .unwrap_or_else(|| die(&format!("{flag} needs a value")))
                .clone()
        };
        match flag.as_str() {
            "--seed" => a.seed = parse_u64(&value()),
            "--cases" => a.cases = parse_u64(&value()),
            "--family" => {
                let v = value();
                a.families = if v == "all" {
                    Family::ALL.to_vec()
                } else {
                    vec![Family::parse(&v).unwrap_or_else(|| die(&format!("unknown family {v}")))]
                }
            }
            "--dump" => a.dump = Some(PathBuf::from(value())),
            "--threads" => a.threads = parse_u64(&value()).max(1) as usize,
            "--case-seed" => a.case_seed = Some(parse_u64(&value())),
            "--list" => a.list = true,
            other => die(&format!(
                "unknown option {other} (see the doc comment of dev/src/bin/adversary.rs)"
            )),
        }
    }
    a
}

/// The seed of case `k` of `family` in the run `seed`.
fn case_seed(seed: u64, family: Family, k: u64) -> u64 {
    let f = Family::ALL.iter().position(|x| *x == family).unwrap() as u64;
    adversary::Mix(seed ^ (f << 56) ^ k.wrapping_mul(0xd1b5_4a32_d192_ed03)).next_u64()
}

/// A judged case, or the panic it caused (in the generator, the referee or
/// the library).
enum Run {
    Judged(Case, Verdict),
    Panicked(Case, String),
}

fn run_one(family: Family, seed: u64) -> Run {
    let case = catch_unwind(|| adversary::generate(family, seed));
    let Ok(case) = case else {
        let dummy = adversary::generate(Family::Tensor, 0);
        return Run::Panicked(
            dummy,
            format!("generator panicked for {} seed {seed:#x}", family.name()),
        );
    };
    match catch_unwind(AssertUnwindSafe(|| adversary::judge(&case))) {
        Ok(v) => Run::Judged(case, v),
        Err(e) => {
            let msg = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Run::Panicked(case, msg)
        }
    }
}

#[derive(Default)]
struct Tally {
    cases: u64,
    roots: u64,
    near_feature: u64,
    certified: u64,
    undecided: u64,
    /// Cases with a fault of each kind.
    faults: BTreeMap<Fault, u64>,
    incomplete: u64,
    unresolved: u64,
    zero_equation: u64,
    errors: u64,
    panics: u64,
    degenerate: u64,
    /// A few cases whose truth is a curve of hits.
    degenerate_examples: Vec<String>,
    time: Duration,
    slowest: (Duration, u64),
    /// Fault kind → (construction, feature) → cases.
    by_label: BTreeMap<Fault, BTreeMap<String, u64>>,
    /// Fault kind → the smallest failing case.
    smallest: BTreeMap<Fault, (usize, u64, String)>,
}

/// `"cross"`, `"vertical"`, … and the feature aimed at, from a case's label.
fn construction(label: &str) -> String {
    let kind = label
        .split(": ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .unwrap_or("?");
    let feature = label.rsplit("@ ").next().unwrap_or("?");
    let feature = feature.split(['=', '(']).next().unwrap_or(feature).trim();
    format!("{kind} @ {feature}")
}

fn record(t: &mut Tally, run: &Run, dump: Option<&Path>) {
    t.cases += 1;
    let (case, v) = match run {
        Run::Panicked(case, msg) => {
            t.panics += 1;
            eprintln!(
                "PANIC {} seed {:#x} ({}): {msg}",
                case.family.name(),
                case.seed,
                case.label
            );
            return;
        }
        Run::Judged(case, v) => (case, v),
    };
    t.roots += v.roots as u64;
    t.near_feature += v.near_feature as u64;
    t.certified += v.certified as u64;
    t.undecided += v.undecided as u64;
    t.degenerate += u64::from(v.degenerate);
    if v.degenerate && t.degenerate_examples.len() < 3 {
        t.degenerate_examples
            .push(format!("{:#x} {:?}: {}", case.seed, v.answer, case.label));
    }
    match v.answer {
        Answer::Complete => {}
        Answer::Incomplete => t.incomplete += 1,
        Answer::Unresolved => t.unresolved += 1,
        Answer::ZeroEquation => t.zero_equation += 1,
        Answer::Error => t.errors += 1,
    }
    t.time += v.time;
    if v.time > t.slowest.0 {
        t.slowest = (v.time, case.seed);
    }
    let mut kinds: Vec<Fault> = v.faults.iter().map(|f| f.0).collect();
    kinds.sort();
    kinds.dedup();
    for f in kinds {
        *t.faults.entry(f).or_default() += 1;
        *t.by_label
            .entry(f)
            .or_default()
            .entry(construction(&case.label))
            .or_default() += 1;
        let name = format!("{}-{}-{:016x}", case.family.name(), f.name(), case.seed);
        let path = dump.map(|d| d.join(format!("{name}.json")));
        let shown = path
            .as_ref()
            .map_or("PATCH.json".to_string(), |p| p.display().to_string());
        let text = adversary::report(case, v, &shown);
        if let (Some(d), Some(p)) = (dump, &path) {
            let write = std::fs::write(p, case.patch_json()).and(std::fs::write(d.join(format!("{name}.txt")), &text));
            write.unwrap_or_else(|e| die(&format!("cannot write {}: {e}", p.display())));
        }
        let key = (case.size(), case.seed, text);
        let better = t.smallest.get(&f).is_none_or(|old| (old.0, old.1) > (key.0, key.1));
        if better {
            t.smallest.insert(f, key);
        }
    }
}

fn run_family(args: &Args, family: Family) -> (Tally, Duration) {
    let tally = Mutex::new(Tally::default());
    let next = Mutex::new(0u64);
    let start = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..args.threads {
            s.spawn(|| loop {
                let k = {
                    let mut n = next.lock().unwrap();
                    if *n >= args.cases {
                        break;
                    }
                    *n += 1;
                    *n - 1
                };
                let run = run_one(family, case_seed(args.seed, family, k));
                if let (true, Run::Judged(c, v)) = (args.list, &run) {
                    let big = c.origin.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                    println!(
                        "{:#018x} {:?} true {} (edge {}) cert {} undec {} {:.1}ms |o| {big:.0e}  {}",
                        c.seed,
                        v.answer,
                        v.roots,
                        v.near_feature,
                        v.certified,
                        v.undecided,
                        v.time.as_secs_f64() * 1e3,
                        c.label
                    );
                }
                record(&mut tally.lock().unwrap(), &run, args.dump.as_deref());
            });
        }
    });
    (tally.into_inner().unwrap(), start.elapsed())
}

fn print_summary(rows: &[(Family, Tally, Duration)]) {
    println!(
        "\n{:<9} {:>6} {:>6} {:>6} {:>6} {:>6} | {:>5} {:>6} {:>7} {:>5} {:>7} {:>5} {:>4} {:>6} {:>5} {:>5} | {:>6} {:>6} {:>4} {:>5} | {:>8} {:>9}",
        "family", "cases", "true", "edge", "cert", "undec", "miss", "miss-t", "phantom", "multi", "tangent", "t-box", "dup", "domain", "zero", "panic",
        "incomp", "unres", "err", "degen", "lib s", "slowest"
    );
    for (f, t, wall) in rows {
        let n = |k: Fault| t.faults.get(&k).copied().unwrap_or(0);
        println!(
            "{:<9} {:>6} {:>6} {:>6} {:>6} {:>6} | {:>5} {:>6} {:>7} {:>5} {:>7} {:>5} {:>4} {:>6} {:>5} {:>5} | {:>6} {:>6} {:>4} {:>5} | {:>8.2} {:>7.0}ms   (wall {:.1} s, slowest seed {:#x})",
            f.name(),
            t.cases,
            t.roots,
            t.near_feature,
            t.certified,
            t.undecided,
            n(Fault::Miss),
            n(Fault::MissT),
            n(Fault::Phantom),
            n(Fault::Multiple),
            n(Fault::Tangent),
            n(Fault::TBox),
            n(Fault::Duplicate),
            n(Fault::Domain),
            n(Fault::ZeroEquation),
            t.panics,
            t.incomplete,
            t.unresolved,
            t.errors,
            t.degenerate,
            t.time.as_secs_f64(),
            t.slowest.0.as_secs_f64() * 1e3,
            wall.as_secs_f64(),
            t.slowest.1,
        );
    }
    println!(
        "(true = exact hits with t ≥ 0, edge = those within 1e-12 of an edge or knot line; cert/undec = reported\n\
         hits; fault columns count cases; zero = ZeroEquation answers, suspicious but within the contract)"
    );
}

fn main() {
    std::panic::set_hook(Box::new(|_| {}));
    let args = parse_args();
    if let Some(seed) = args.case_seed {
        for &family in &args.families {
            match run_one(family, seed) {
                Run::Judged(case, v) => {
                    println!("{}", adversary::report(&case, &v, "PATCH.json"));
                    println!("PATCH.json: {}", case.patch_json());
                }
                Run::Panicked(case, msg) => println!("PANIC ({}): {msg}", case.label),
            }
        }
        return;
    }
    if let Some(d) = &args.dump {
        std::fs::create_dir_all(d).unwrap_or_else(|e| die(&format!("cannot create {}: {e}", d.display())));
    }
    let mut rows = Vec::new();
    for &family in &args.families {
        let (t, wall) = run_family(&args, family);
        eprintln!("{}: {} cases in {:.1} s", family.name(), t.cases, wall.as_secs_f64());
        rows.push((family, t, wall));
    }
    print_summary(&rows);
    let failing = rows
        .iter()
        .any(|(_, t, _)| t.panics > 0 || t.faults.keys().any(|f| f.breaks_contract()));
    for (f, t, _) in &rows {
        for d in &t.degenerate_examples {
            println!("{} degenerate truth (a curve of hits, not judged): {d}", f.name());
        }
        for (fault, labels) in &t.by_label {
            println!(
                "\n== {} / {}: {} case(s) by construction:",
                f.name(),
                fault.name(),
                t.faults[fault]
            );
            for (label, n) in labels {
                println!("   {n:>5}  {label}");
            }
            if let Some((_, _, text)) = t.smallest.get(fault) {
                println!("-- smallest reproduction:\n{text}");
            }
        }
    }
    if failing {
        std::process::exit(1);
    }
}
