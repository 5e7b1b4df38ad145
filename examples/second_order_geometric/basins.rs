//! The basin pictures: every start of a grid, one pixel each, coloured by
//! the referee's verdict.

use super::{Args, Res};
use rayon::prelude::*;
use rootclip::heuristics::experiment::{example, grid_starts, run_starts, Run, Verdict};
use rootclip::heuristics::{IterOptions, Iteration};
use rootclip::ray::{intersect, RayOptions, RayOutcome};
use std::fmt::Write as _;
use std::path::Path;

const COLOURS: [(&str, [u8; 3]); 6] = [
    ("correct", [44, 160, 44]),
    ("wrong_hit", [255, 127, 14]),
    ("not_a_hit", [214, 39, 40]),
    ("undecided", [148, 103, 189]),
    ("failed: left_domain", [70, 70, 70]),
    ("failed: other reason", [170, 170, 170]),
];

fn colour(run: &Run) -> [u8; 3] {
    let k = match (run.verdict, run.reason) {
        (Verdict::Correct, _) => 0,
        (Verdict::WrongHit, _) => 1,
        (Verdict::NotAHit, _) => 2,
        (Verdict::Undecided, _) => 3,
        (_, Some("left_domain")) => 4,
        _ => 5,
    };
    COLOURS[k].1
}

pub(super) fn basins(r: &mut String, args: &Args) -> Res<()> {
    let k = args.grid.max(2);
    let starts = grid_starts(k);
    let opts = IterOptions::default();
    r.push_str("## Basins of attraction\n\n");
    let _ = writeln!(
        r,
        "Each method from every start of a {k} × {k} grid on the parameter square (one pixel per start, `u₀` \
         to the right, `v₀` up), coloured by the referee's verdict: {}. White crosses mark the proven nearest \
         hit, black crosses the other certified hits, a white ring an undecided one.\n",
        COLOURS
            .iter()
            .map(|(name, c)| format!(
                "{name} <span style=\"color:#{:02x}{:02x}{:02x}\">■</span>",
                c[0], c[1], c[2]
            ))
            .collect::<Vec<_>>()
            .join(", ")
    );
    r.push_str("| | Newton | Halley | first order | second order |\n|---|---|---|---|---|\n");
    let mut differ = Vec::new();
    let mut second_order_band = (0.0, 0.0);
    let fine = IterOptions::default().with_tol(1e-10);
    for (n, opts, tag) in [
        (1u8, &opts, ""),
        (2, &opts, ""),
        (3, &opts, ""),
        (3, &fine, "_tol1e-10"),
    ] {
        let ex = example(n)?;
        let hits = intersect(&ex.patch, &ex.ray, &RayOptions::default())?;
        let mut cells = Vec::new();
        let all: Vec<Vec<Run>> = Iteration::ALL
            .par_iter()
            .map(|&m| run_starts(&ex.patch, &ex.ray, &[m], &starts, opts, &RayOptions::default()))
            .collect::<Result<_, _>>()?;
        for (m, runs) in Iteration::ALL.iter().zip(&all) {
            let name = format!("basins_example{n}{tag}_{}.png", m.code());
            write_basin(&args.out.join(&name), k, runs, &hits)?;
            let share = |v: Verdict| runs.iter().filter(|x| x.verdict == v).count() as f64 / runs.len() as f64;
            let main = if n == 3 { Verdict::Undecided } else { Verdict::Correct };
            cells.push(format!(
                "![{} example {n}]({name})<br>{:.1}% {}",
                m.code(),
                100.0 * share(main),
                main.code()
            ));
        }
        let label = if tag.is_empty() {
            format!("Example {n}")
        } else {
            format!("Example {n}, δ = 1e-10")
        };
        let _ = writeln!(r, "| {label} | {} |", cells.join(" | "));
        differ.push(
            all[0]
                .iter()
                .zip(&all[2])
                .filter(|(a, b)| a.verdict != b.verdict)
                .count(),
        );
        if n == 1 {
            let bad = |x: &&Run| x.verdict != Verdict::Correct;
            let good = |x: &&Run| x.verdict == Verdict::Correct;
            second_order_band = (
                all[3].iter().filter(bad).map(|x| x.start[1]).fold(0.0, f64::max) + 1.0 / (k - 1) as f64,
                all[3].iter().filter(good).map(|x| x.start[1]).fold(1.0, f64::min),
            );
        }
    }
    let _ = write!(
        r,
        "\nNewton's and the first-order iteration's pictures differ in {} of the {} pixels of the four \
         examples: they take the same `(u, v)` steps (the Discussion's Eqs. (36)–(37)) and differ only in \
         their stopping tests. ",
        differ.iter().sum::<usize>(),
        4 * starts.len()
    );
    let _ = writeln!(
        r,
        "On Example 1 the second-order iteration is correct from every start with `v₀ ≥ {:.3}` (the right \
         leg and the top of the arch) and from none below `v₀ = {:.3}`; on Example 2 its wrong hits come \
         from the region around the farther hit. On Example 3 nothing is `correct`: the tangential hit is \
         never certified; at δ = 1e-6 the ends stop a few 1e-7 from it (`not_a_hit` at the referee's \
         tolerance 1e-8) except on most of the lines `u₀ = ½` (starts in the ray's plane `z = 0`) and \
         `v₀ = ½` (Case 3), where they end closer; at δ = 1e-10 they stop within the tolerance of the undecided region (`undecided`).\n",
        second_order_band.0,
        second_order_band.1
    );
    Ok(())
}

fn write_basin(path: &Path, k: usize, runs: &[Run], hits: &RayOutcome) -> Res<()> {
    const SCALE: usize = 2;
    let w = k * SCALE;
    let mut px = vec![0u8; w * w * 3];
    let mut put = |x: usize, y: usize, c: [u8; 3]| {
        if x < w && y < w {
            let at = 3 * ((w - 1 - y) * w + x);
            px[at..at + 3].copy_from_slice(&c);
        }
    };
    // Starts run u₀ outer, v₀ inner: run i·k + j is (u₀, v₀) = (i, j)/(k − 1).
    for (idx, run) in runs.iter().enumerate() {
        let (i, j) = (idx / k, idx % k);
        for dx in 0..SCALE {
            for dy in 0..SCALE {
                put(i * SCALE + dx, j * SCALE + dy, colour(run));
            }
        }
    }
    let nearest = match hits {
        RayOutcome::Hits(h) => h.nearest().first().map(|x| (x.u, x.v)),
        _ => None,
    };
    for h in hits.hits() {
        let (x, y) = (
            (h.u * (w - 1) as f64).round() as i64,
            (h.v * (w - 1) as f64).round() as i64,
        );
        let white = Some((h.u, h.v)) == nearest && h.is_certified();
        let c = if white || !h.is_certified() { [255; 3] } else { [0; 3] };
        for d in -6i64..=6 {
            let pts = if h.is_certified() {
                vec![(x + d, y), (x, y + d)]
            } else {
                let a = d as f64 * std::f64::consts::PI / 6.0;
                vec![((x as f64 + 6.0 * a.cos()) as i64, (y as f64 + 6.0 * a.sin()) as i64)]
            };
            for (a, b) in pts {
                if a >= 0 && b >= 0 {
                    put(a as usize, b as usize, c);
                }
            }
        }
    }
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = png::Encoder::new(file, w as u32, w as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(&px)?;
    Ok(())
}
