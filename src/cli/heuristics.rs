//! `rootclip heuristics`: Park, Ji & Ko's (2013) experiment (
//! Examples 1–3), every end point refereed by the certified solver
//! ([`crate::heuristics::experiment`]).
//!
//! JSON out: `{"schema_version": 1, "example": "1", "options": {…},
//! "runs": [{"method", "start", "end": {"u", "v", "t"} | null, "iterations",
//! "verdict", "reason"}], "summary": [{"method", "correct", "wrong_hit",
//! "not_a_hit", "undecided", "failed", "mean_iterations"}]}`, runs method by
//! method (newton, halley, first-order, second-order), each over the 121
//! starts with `u₀` outer.

use super::json::document;
use super::values::DomainRuleArg;
use crate::error::Result;
use crate::heuristics::experiment::{grid_starts, run_example, tally, Run, Tally, Verdict, REFEREE_TOL};
use crate::heuristics::{IterOptions, Iteration};
use serde::Serialize;

/// Arguments of `rootclip heuristics`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct HeuristicsArgs {
    /// Which example of the paper: 1 (one hit), 2 (two hits), 3 (a ray tangent to the surface).
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=3))]
    example: u8,
    /// The step tolerance δ: an iteration has converged when a step is shorter.
    #[arg(long, default_value_t = 1e-6)]
    tol: f64,
    /// At most this many steps per run.
    #[arg(long, default_value_t = 50)]
    max_iterations: usize,
    /// What a step out of the parameter domain does: cut where it leaves (the paper's rule), clamp onto the domain, or stop.
    #[arg(long, value_enum, default_value = "clip")]
    domain_rule: DomainRuleArg,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Report<'a> {
    example: String,
    options: &'a IterOptions,
    referee_tol: f64,
    runs: &'a [Run],
    summary: &'a [Tally],
}

pub(super) fn run(args: &HeuristicsArgs) -> Result<String> {
    let opts = IterOptions::default()
        .with_tol(args.tol)
        .with_max_iterations(args.max_iterations)
        .with_domain_rule(args.domain_rule.into());
    let runs = run_example(args.example, &opts)?;
    let tallies = tally(&runs, &Iteration::ALL);
    if args.json {
        return Ok(document(&Report {
            example: args.example.to_string(),
            options: &opts,
            referee_tol: REFEREE_TOL,
            runs: &runs,
            summary: &tallies,
        }));
    }
    Ok(text(args.example, &opts, &runs, &tallies))
}

fn text(example: u8, opts: &IterOptions, runs: &[Run], tallies: &[Tally]) -> String {
    let starts = grid_starts(11).len();
    let mut out = format!(
        "Example {example}: {starts} starts per method, δ = {:e}, at most {} steps, domain rule {}; end points refereed by the certified solver (tolerance {REFEREE_TOL:e} in (u, v))\n",
        opts.tol,
        opts.max_iterations,
        opts.domain_rule.code()
    );
    out += "method        correct  wrong_hit  not_a_hit  undecided  failed  mean steps (correct)\n";
    for t in tallies {
        let [c, w, n, u, f] = t.counts;
        let mean = if t.mean_iterations.is_finite() {
            format!("{:.2}", t.mean_iterations)
        } else {
            "-".into()
        };
        out += &format!("{:12} {c:>8} {w:>10} {n:>10} {u:>10} {f:>7}  {mean}\n", t.method.code());
    }
    out += "\nVerdict per start (row u0 = 0, 0.1, …, 1; column v0 = 0, 0.1, …, 1): C correct, W wrong hit, N not a hit, U undecided, . failed\n";
    let cols: Vec<Vec<&Run>> = Iteration::ALL
        .iter()
        .map(|&m| runs.iter().filter(|r| r.method == m).collect())
        .collect();
    out += Iteration::ALL
        .iter()
        .map(|m| format!("{:13}", m.code()))
        .collect::<String>()
        .trim_end();
    for row in 0..11 {
        out.push('\n');
        for col in &cols {
            let cells: String = col[row * 11..(row + 1) * 11]
                .iter()
                .map(|r| letter(r.verdict))
                .collect();
            out += &format!("{cells:13}");
        }
        out.truncate(out.trim_end().len());
    }
    out
}

fn letter(v: Verdict) -> char {
    match v {
        Verdict::Correct => 'C',
        Verdict::WrongHit => 'W',
        Verdict::NotAHit => 'N',
        Verdict::Undecided => 'U',
        _ => '.',
    }
}
