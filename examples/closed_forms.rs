//! Christensen's (2008) closed forms (*Ray intersections*) refereed
//! by the certified solvers: writes `papers/ray-intersections-2008/README.md`
//! and its figure. Every number in the write-up is computed here, from a
//! fixed seed; only the timings change from run to run.
//!
//! `cargo run --release --example closed_forms` (about a minute).

#[path = "closed_forms/cases.rs"]
mod cases;
#[path = "closed_forms/oracle.rs"]
mod oracle;
#[path = "closed_forms/picture.rs"]
mod picture;
#[path = "closed_forms/report.rs"]
mod report;
#[path = "closed_forms/tally.rs"]
mod tally;

use cases::{Family, Quad, Seg, Swept};
use oracle::Referee;
use report::{Report, Row, Sweeps};
use rootclip::heuristics::{
    ray_quadratic_bezier_2d, ray_segment_2d, ray_swept_quadratic_patch_3d, ClosedForm, FormulaFailure,
};
use rootclip::internals::Rng;
use std::hint::black_box;
use std::time::Instant;
use tally::{Claim, Tally};

const SEED: u64 = 0x5eed_0003_2008;
/// Queries per family (random families get four times as many).
const N: usize = 400;
const DIR: &str = "papers/ray-intersections-2008";

/// Seconds per call of `f` over `cases`, repeated until the run is long
/// enough to time.
fn per_query<C, T>(cases: &[C], f: impl Fn(&C) -> T) -> f64 {
    let mut reps = 1;
    loop {
        let start = Instant::now();
        for _ in 0..reps {
            for c in cases {
                black_box(f(black_box(c)));
            }
        }
        let el = start.elapsed().as_secs_f64();
        if el > 0.05 || reps >= 1 << 16 {
            return el / (reps * cases.len()) as f64;
        }
        reps *= 4;
    }
}

fn measure<C, H>(
    fam: &Family<C>,
    form: impl Fn(&C) -> ClosedForm<H>,
    claim: impl Fn(&H) -> Claim,
    referee: impl Fn(&C) -> Referee,
) -> (Row, Vec<Referee>) {
    let start = Instant::now();
    let refs: Vec<Referee> = fam.cases.iter().map(&referee).collect();
    let oracle_us = start.elapsed().as_secs_f64() / fam.cases.len() as f64 * 1e6;
    let cf_ns = per_query(&fam.cases, &form) * 1e9;
    let mut tally = Tally::default();
    let mut failures: Vec<(FormulaFailure, usize)> = Vec::new();
    for (c, r) in fam.cases.iter().zip(&refs) {
        match form(c) {
            ClosedForm::Failed(f) => {
                match failures.iter_mut().find(|(g, _)| *g == f) {
                    Some((_, k)) => *k += 1,
                    None => failures.push((f, 1)),
                }
                tally.add(None, r);
            }
            ClosedForm::Hits(h) => {
                let claims: Vec<Claim> = h.iter().map(&claim).collect();
                tally.add(Some(&claims), r);
            }
            _ => unreachable!("a closed form gives hits or a failure"),
        }
    }
    let row = Row {
        name: fam.name.clone(),
        tally,
        failures,
        cf_ns,
        oracle_us,
    };
    (row, refs)
}

fn quad_form(c: &Quad) -> ClosedForm<rootclip::heuristics::CurveHit> {
    ray_quadratic_bezier_2d(c.o, c.d, c.p).expect("valid input")
}

fn quad_referee(c: &Quad) -> Referee {
    oracle::curve_2d(c.o, c.d, &c.p)
}

fn seg_form(c: &Seg) -> ClosedForm<rootclip::heuristics::CurveHit> {
    ray_segment_2d(c.o, c.d, c.a, c.b).expect("valid input")
}

fn seg_referee(c: &Seg) -> Referee {
    // l(t) = t a + (1 − t) b: control points b (t = 0), a (t = 1).
    oracle::curve_2d(c.o, c.d, &[c.b, c.a])
}

fn swept_form(c: &Swept) -> ClosedForm<rootclip::heuristics::PatchHit> {
    ray_swept_quadratic_patch_3d(c.o, c.d, c.p, c.e).expect("valid input")
}

fn refs(rows: &[Row]) -> Vec<&Row> {
    rows.iter().collect()
}

fn swept_referee(c: &Swept) -> Referee {
    oracle::swept(c.o, c.d, c.p, c.e)
}

fn curve_claim(h: &rootclip::heuristics::CurveHit) -> Claim {
    Claim { t: h.t, u: None }
}

fn patch_claim(h: &rootclip::heuristics::PatchHit) -> Claim {
    Claim { t: h.t, u: Some(h.u) }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut rng = Rng(SEED);
    let heights = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14, 1e-15, 1e-16, 1e-17];

    // Quadratic Bézier curve, 2D.
    let mut quad_fams = vec![cases::quad_random(&mut rng, 4 * N)];
    for inside in [true, false] {
        for h in heights {
            quad_fams.push(cases::quad_grazing(&mut rng, N, h, inside));
        }
    }
    quad_fams.push(cases::quad_tangent(&mut rng, N));
    quad_fams.push(cases::quad_aimed_end(&mut rng, N, 0));
    quad_fams.push(cases::quad_aimed_end(&mut rng, N, 2));
    quad_fams.push(cases::quad_tiny_off_end(&mut rng, N, true));
    quad_fams.push(cases::quad_tiny_off_end(&mut rng, N, false));
    let mut quad_rows = Vec::new();
    let mut figure = None;
    for fam in &quad_fams {
        let (row, refs) = measure(fam, quad_form, curve_claim, quad_referee);
        if figure.is_none() && fam.name.contains("inside") && row.tally.lost > 0 {
            // The first grazing case whose hits the formula loses entirely.
            let k = fam
                .cases
                .iter()
                .zip(&refs)
                .position(|(c, r)| r.hits.len() == 2 && quad_form(c).hits().is_empty());
            if let Some(k) = k {
                let roots: Vec<[f64; 2]> = refs[k].hits.iter().map(|h| h.t).collect();
                figure = Some((fam.cases[k], roots, fam.name.clone()));
            }
        }
        eprintln!("quadratic: {}", row.name);
        quad_rows.push(row);
    }

    // Segment, 2D.
    let mut seg_fams = vec![cases::seg_random(&mut rng, 4 * N)];
    let angles = [1e-4, 1e-8, 1e-12, 1e-14, 1e-15, 1e-16];
    for angle in angles {
        seg_fams.push(cases::seg_near_parallel(&mut rng, N, angle));
    }
    seg_fams.push(cases::seg_aimed_end(&mut rng, N));
    seg_fams.push(cases::seg_tiny_off_end(&mut rng, N, true));
    seg_fams.push(cases::seg_tiny_off_end(&mut rng, N, false));
    let mut seg_rows = Vec::new();
    for fam in &seg_fams {
        eprintln!("segment: {}", fam.name);
        seg_rows.push(measure(fam, seg_form, curve_claim, seg_referee).0);
    }

    // Swept quadratic patch, 3D.
    let mut swept_fams = vec![cases::swept_random(&mut rng, 4 * N)];
    let swept_heights = [1e-8, 1e-12, 1e-14, 1e-15];
    for inside in [true, false] {
        for h in swept_heights {
            swept_fams.push(cases::swept_grazing(&mut rng, N, h, inside));
        }
    }
    for eps in [1e-4, 1e-8, 1e-12, 1e-15] {
        swept_fams.push(cases::swept_near_vertical(&mut rng, N / 4, eps));
    }
    swept_fams.push(cases::swept_tiny_off_edge(&mut rng, N / 8, true));
    swept_fams.push(cases::swept_tiny_off_edge(&mut rng, N / 8, false));
    let mut swept_rows = Vec::new();
    for fam in &swept_fams {
        eprintln!("swept: {}", fam.name);
        swept_rows.push(measure(fam, swept_form, patch_claim, swept_referee).0);
    }

    let (nh, na, ns) = (heights.len(), angles.len(), swept_heights.len());
    let sweeps = Sweeps {
        heights: &heights,
        quad_inside: refs(&quad_rows[1..1 + nh]),
        quad_outside: refs(&quad_rows[1 + nh..1 + 2 * nh]),
        angles: &angles,
        seg_angle: refs(&seg_rows[1..1 + na]),
        swept_heights: &swept_heights,
        swept_inside: refs(&swept_rows[1..1 + ns]),
        swept_outside: refs(&swept_rows[1 + ns..1 + 2 * ns]),
    };
    let series = |label: &str, color, dash, rows: &[&Row], xs: &[f64]| {
        let pts = rows.iter().zip(xs).map(|(r, x)| (*x, r.wrong_share())).collect();
        (label.to_string(), color, dash, pts)
    };
    let rates = picture::rates_svg(
        "Queries answered wrongly near tangency",
        "grazing distance h, or angle α (log scale)",
        &[
            series(
                "quadratic, grazing inside",
                "#1f77b4",
                "",
                &sweeps.quad_inside,
                &heights,
            ),
            series(
                "quadratic, grazing outside",
                "#1f77b4",
                "5 3",
                &sweeps.quad_outside,
                &heights,
            ),
            series(
                "swept, inside in plan",
                "#2ca02c",
                "",
                &sweeps.swept_inside,
                &swept_heights,
            ),
            series(
                "swept, outside in plan",
                "#2ca02c",
                "5 3",
                &sweeps.swept_outside,
                &swept_heights,
            ),
            series("segment, at angle α", "#d62728", "", &sweeps.seg_angle, &angles),
        ],
    );
    let mut out = String::new();
    Report {
        provenance: provenance(),
        n: N,
        quad: &quad_rows,
        seg: &seg_rows,
        swept: &swept_rows,
        sweeps,
        figure: figure.as_ref().map(|f| f.2.clone()),
    }
    .write(&mut out);
    std::fs::create_dir_all(DIR)?;
    std::fs::write(format!("{DIR}/README.md"), &out)?;
    std::fs::write(format!("{DIR}/rates.svg"), rates)?;
    if let Some((c, roots, name)) = &figure {
        let h: f64 = name
            .split_whitespace()
            .nth(2)
            .and_then(|s| s.trim_end_matches(',').parse().ok())
            .unwrap_or(0.0);
        std::fs::write(format!("{DIR}/grazing.svg"), picture::grazing_svg(c, roots, h))?;
    }
    print!("{out}");
    Ok(())
}

/// The machine and the commit the numbers come from.
fn provenance() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            let l = s.lines().find(|l| l.starts_with("model name"))?;
            Some(l.split(':').nth(1)?.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    let git = |args: &[&str]| {
        let o = std::process::Command::new("git").args(args).output().ok()?;
        o.status
            .success()
            .then(|| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let commit = match git(&["rev-parse", "--short", "HEAD"]) {
        None => "rootclip (commit unknown)".to_string(),
        Some(h) => {
            let dirty = git(&["status", "--porcelain", "--", "src"]).is_some_and(|s| !s.is_empty());
            format!(
                "rootclip at commit `{h}`{}",
                if dirty {
                    " with uncommitted changes in `src/`"
                } else {
                    ""
                }
            )
        }
    };
    format!("{cpu}, {threads} hardware threads shared with other jobs, {commit}")
}
