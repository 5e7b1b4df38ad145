//! The heuristics at scale: random rays aimed at Example 1's patch, each
//! method from (½, ½) against the certified all-hits solve.

use super::{Args, Res, NAMES, ROUNDS, SEED};
use rayon::prelude::*;
use rootclip::heuristics::experiment::{example, judge, Verdict};
use rootclip::heuristics::{iterate, IterOptions, Iteration, Outcome};
use rootclip::internals::at_scale_rays;
use rootclip::ray::{intersect, RayOptions, RayOutcome};
use std::fmt::Write as _;
use std::time::Instant;

#[derive(Default, Clone)]
struct Count {
    correct: usize,
    wrong: usize,
    not_hit: usize,
    not_hit_past_range: usize,
    undecided: usize,
    failed: usize,
    hits_found: usize,
}

pub(super) fn at_scale(r: &mut String, args: &Args) -> Res<()> {
    let ex = example(1)?;
    let rays = at_scale_rays(&ex.patch, args.rays, SEED);
    let n = rays.len();
    let ray_opts = RayOptions::default().with_t_range(0.0, 3.0);
    let opts = IterOptions::default();
    // One thread, timed: ROUNDS rounds, the certified solve and each method
    // from (½, ½) interleaved, the fastest round kept.
    let mut certified: Vec<RayOutcome> = Vec::new();
    let mut outcomes: Vec<Vec<Outcome>> = vec![Vec::new(); 4];
    let mut us = [f64::INFINITY; 5];
    for _ in 0..ROUNDS {
        let t0 = Instant::now();
        certified = rays
            .iter()
            .map(|ray| intersect(&ex.patch, ray, &ray_opts))
            .collect::<Result<_, _>>()?;
        us[4] = us[4].min(t0.elapsed().as_secs_f64() * 1e6 / n as f64);
        for (k, m) in Iteration::ALL.into_iter().enumerate() {
            let t0 = Instant::now();
            outcomes[k] = rays
                .iter()
                .map(|ray| iterate(m, &ex.patch, ray, [0.5, 0.5], &opts))
                .collect();
            us[k] = us[k].min(t0.elapsed().as_secs_f64() * 1e6 / n as f64);
        }
    }
    let us_certified = us[4];
    // Refereed (not timed), in parallel.
    let judged: Vec<_> = (0..n)
        .into_par_iter()
        .map(|k| {
            let mine: Vec<Outcome> = outcomes.iter().map(|o| o[k]).collect();
            judge(&ex.patch, &rays[k], &mine, &ray_opts)
        })
        .collect::<Result<_, _>>()?;
    let true_hits: usize = certified
        .iter()
        .map(|o| o.hits().iter().filter(|h| h.is_certified()).count())
        .sum();
    let undecided_regions: usize = certified
        .iter()
        .map(|o| o.hits().iter().filter(|h| !h.is_certified()).count())
        .sum();
    let incomplete = certified.iter().filter(|o| !o.is_complete()).count();
    let multi = certified.iter().filter(|o| o.hits().len() > 1).count();
    let unproven_nearest = judged.iter().filter(|j| j.nearest.is_none()).count();
    let mut counts = vec![Count::default(); 4];
    for (k, j) in judged.iter().enumerate() {
        for (m, c) in counts.iter_mut().enumerate() {
            match j.verdicts[m].0 {
                Verdict::Correct => c.correct += 1,
                Verdict::WrongHit => c.wrong += 1,
                Verdict::NotAHit => {
                    c.not_hit += 1;
                    if outcomes[m][k].end.is_some_and(|e| e.t > 3.0) {
                        c.not_hit_past_range += 1;
                    }
                }
                Verdict::Undecided => c.undecided += 1,
                _ => c.failed += 1,
            }
            c.hits_found += usize::from(j.found[m].is_some());
        }
    }
    r.push_str("## Heuristics at scale\n\n");
    let _ = writeln!(
        r,
        "{n} rays on Example 1's patch, each aimed at `P = S(a, b)` with `a, b` uniform on [0, 1], from \
         `o = P + (U(2, 6), U(−3, 3), U(−3, 3))` along `P − o` (so `t = 1` is a hit), hits wanted for \
         `t ∈ [0, 3]` (`internals::at_scale_rays`, seed `{SEED:#x}`). The certified all-hits solve finds \
         {true_hits} certified hits ({multi} rays with more than one hit; {undecided_regions} undecided regions; \
         {incomplete} incomplete rays; the nearest hit is proven on {} rays). Each method starts from (½, ½) \
         with the default options; shares are of the {n} rays, except \"certified hits missed\", of the \
         {true_hits} certified hits.\n",
        n - unproven_nearest
    );
    r.push_str("| method | nearest hit found | nearest missed | wrong hit | not a hit | undecided | failed | certified hits missed | mean steps | µs per ray |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    let pct = |x: usize, of: usize| format!("{:.2}%", 100.0 * x as f64 / of as f64);
    for (m, (c, name)) in counts.iter().zip(NAMES).enumerate() {
        let steps = outcomes[m].iter().map(|o| o.iterations as f64).sum::<f64>() / n as f64;
        let _ = writeln!(
            r,
            "| {name} | {} | {} | {} | {}{} | {} | {} | {} | {steps:.2} | {:.2} |",
            pct(c.correct, n),
            pct(n - c.correct, n),
            pct(c.wrong, n),
            pct(c.not_hit, n),
            if c.not_hit_past_range > 0 {
                format!(" ({} past t = 3)", c.not_hit_past_range)
            } else {
                String::new()
            },
            pct(c.undecided, n),
            pct(c.failed, n),
            pct(true_hits - c.hits_found, true_hits),
            us[m],
        );
    }
    let _ = writeln!(
        r,
        "| certified, all hits | 100% proven{} | — | — | — | — | — | 0 | — | {us_certified:.1} |",
        if unproven_nearest > 0 {
            format!(" but {unproven_nearest}")
        } else {
            String::new()
        }
    );
    let failures: Vec<String> = Iteration::ALL
        .iter()
        .zip(NAMES)
        .enumerate()
        .map(|(m, (_, name))| {
            let mut by: Vec<(&str, usize)> = Vec::new();
            for o in &outcomes[m] {
                if let Some(f) = o.failure {
                    match by.iter_mut().find(|b| b.0 == f.code()) {
                        Some(b) => b.1 += 1,
                        None => by.push((f.code(), 1)),
                    }
                }
            }
            let list: Vec<String> = by.iter().map(|(w, c)| format!("{c} `{w}`")).collect();
            format!(
                "{name}: {}",
                if list.is_empty() {
                    "none".into()
                } else {
                    list.join(", ")
                }
            )
        })
        .collect();
    let _ = writeln!(r, "\nFailures by reason — {}.", failures.join("; "));
    let past = counts.iter().any(|c| c.not_hit_past_range > 0);
    let _ = writeln!(
        r,
        "\n\"Nearest missed\" is everything but `correct`. One start can find one hit: a ray's other hits are \
         missed by construction, which the column \"certified hits missed\" counts.{} Times are \
         single-threaded (the fastest of {ROUNDS} interleaved rounds); the heuristics' cost is their steps, \
         the certified solve's a proof of every hit in the range and of the absence of any other.\n",
        if past {
            " A `not a hit` end with `t > 3` is a point of the surface past the range asked for."
        } else {
            ""
        }
    );
    Ok(())
}
