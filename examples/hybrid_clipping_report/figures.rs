//! The figures: time vs accuracy per system (the paper's Figs. 4c, 5b, 7) and
//! diameter by level, ours against the paper's.

use super::svg::{self, Panel, Series};
use super::*;

const COLORS: [&str; 4] = ["#7f7f7f", "#2ca02c", "#1f77b4", "#d62728"];

fn time_label(k: i32) -> String {
    match k {
        k if k < 3 => format!("{} µs", 10i64.pow(k.max(0) as u32)),
        k if k < 6 => format!("{} ms", 10i64.pow((k - 3) as u32)),
        k => format!("{} s", 10i64.pow((k - 6) as u32)),
    }
}

pub(super) fn time_figure(ctx: &Ctx, i: usize) -> String {
    let series: Vec<Series> = Method::ALL
        .iter()
        .map(|&m| Series {
            label: m.name().into(),
            color: COLORS[midx(m)],
            dashed: false,
            pts: LG_EPS
                .iter()
                .zip(&ctx.timings[i][midx(m)])
                .map(|(&lg, t)| (-lg as f64, t.us.log10()))
                .collect(),
        })
        .collect();
    let ys: Vec<f64> = series.iter().flat_map(|s| s.pts.iter().map(|p| p.1)).collect();
    let (lo, hi) = min_max(&ys);
    let (lo, hi) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
    let (w, h) = (560.0, 380.0);
    let mut svg = svg::open(w, h);
    let panel = Panel {
        origin: (0.0, 0.0),
        size: (w - 120.0, h),
        title: format!(
            "{}: time of a certified solve vs accuracy",
            title(&ctx.examples[i].name)
        ),
        xlabel: "accuracy −lg ε",
        ylabel: "wall time per solve (median)",
        x: (1.5, 14.5),
        y: (lo, hi),
        xticks: LG_EPS.iter().map(|&lg| (-lg as f64, (-lg).to_string())).collect(),
        yticks: (lo as i32..=hi as i32).map(|k| (k as f64, time_label(k))).collect(),
    };
    svg::panel(&mut svg, &panel, &series);
    svg::legend(&mut svg, (w - 110.0, 40.0), &series);
    svg.push_str("</svg>\n");
    svg
}

pub(super) fn convergence_figure(ctx: &Ctx) -> String {
    let (pw, ph, cols) = (330.0, 250.0, 3usize);
    let (w, h) = (pw * cols as f64, ph * 2.0);
    let mut svg = svg::open(w, h);
    let mut legend = Vec::new();
    for (i, ex) in ctx.examples.iter().enumerate() {
        let mut series = Vec::new();
        for m in [Method::HcNoPre, Method::Hc] {
            let color = COLORS[midx(m)];
            let ours = tracked(ctx, i, m)
                .iter()
                .enumerate()
                .map(|(l, &d)| (l as f64, d.log10()))
                .collect();
            let paper = paper_diams(ctx, &ex.name, m)
                .iter()
                .enumerate()
                .map(|(l, &d)| (l as f64 + 1.0, d.log10()))
                .collect();
            series.push(Series {
                label: format!("{m}, ours"),
                color,
                dashed: false,
                pts: ours,
            });
            series.push(Series {
                label: format!("{m}, paper"),
                color,
                dashed: true,
                pts: paper,
            });
        }
        let max_level = series
            .iter()
            .flat_map(|s| s.pts.iter().map(|p| p.0))
            .fold(7.0, f64::max);
        let panel = Panel {
            origin: (pw * (i % cols) as f64, ph * (i / cols) as f64),
            size: (pw, ph),
            title: title(&ex.name),
            xlabel: "level",
            ylabel: "diameter",
            x: (0.0, max_level),
            y: (-17.0, 0.5),
            xticks: (0..=max_level as usize)
                .step_by(if max_level > 10.0 { 2 } else { 1 })
                .map(|l| (l as f64, l.to_string()))
                .collect(),
            yticks: (-16..=0).step_by(4).map(|k| (k as f64, svg::decade(k))).collect(),
        };
        svg::panel(&mut svg, &panel, &series);
        legend = series;
    }
    for s in &mut legend {
        s.pts.clear();
    }
    svg::legend(&mut svg, (pw * 2.0 + 40.0, ph + 60.0), &legend);
    let _ = writeln!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"10\">tri-box diameter by level, tracked root</text>",
        pw * 2.0 + 40.0,
        ph + 150.0
    );
    svg.push_str("</svg>\n");
    svg
}
