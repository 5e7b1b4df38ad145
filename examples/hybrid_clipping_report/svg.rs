//! Hand-written SVG line charts for the report: a panel with axes, grid,
//! tick labels and polylines (y already in log10 units for log axes), and a
//! legend. No fonts are embedded; viewers use their sans-serif.

use std::fmt::Write as _;

/// One polyline.
pub struct Series {
    pub label: String,
    pub color: &'static str,
    /// Dashed line and hollow markers (the paper's numbers).
    pub dashed: bool,
    /// `(x, y)` in data units.
    pub pts: Vec<(f64, f64)>,
}

/// One chart: where it goes, its data ranges and tick labels.
pub struct Panel<'a> {
    pub origin: (f64, f64),
    pub size: (f64, f64),
    pub title: String,
    pub xlabel: &'a str,
    pub ylabel: &'a str,
    pub x: (f64, f64),
    pub y: (f64, f64),
    pub xticks: Vec<(f64, String)>,
    pub yticks: Vec<(f64, String)>,
}

/// The document header and a white background.
pub fn open(w: f64, h: f64) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" \
width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"11\">\n\
<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n"
    )
}

/// `10^k` as SVG text.
pub fn decade(k: i32) -> String {
    format!("10<tspan dy=\"-5\" font-size=\"8\">{k}</tspan>")
}

/// Draws `p` with `series`; points outside the y range are clamped to its edge.
pub fn panel(svg: &mut String, p: &Panel, series: &[Series]) {
    let (ml, mr, mt, mb) = (58.0, 12.0, 26.0, 40.0);
    let (x0, y0) = (p.origin.0 + ml, p.origin.1 + mt);
    let (pw, ph) = (p.size.0 - ml - mr, p.size.1 - mt - mb);
    let px = |x: f64| x0 + (x - p.x.0) / (p.x.1 - p.x.0) * pw;
    let py = |y: f64| y0 + (1.0 - (y.clamp(p.y.0, p.y.1) - p.y.0) / (p.y.1 - p.y.0)) * ph;
    let _ = writeln!(
        svg,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" font-size=\"13\">{}</text>",
        x0 + pw / 2.0,
        p.origin.1 + 16.0,
        p.title
    );
    for (x, label) in &p.xticks {
        let _ = writeln!(
            svg,
            "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{0:.1}\" y2=\"{2:.1}\" stroke=\"#e4e4e4\"/>\n\
<text x=\"{0:.1}\" y=\"{3:.1}\" text-anchor=\"middle\">{label}</text>",
            px(*x),
            y0,
            y0 + ph,
            y0 + ph + 14.0
        );
    }
    for (y, label) in &p.yticks {
        let _ = writeln!(
            svg,
            "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{2:.1}\" y2=\"{1:.1}\" stroke=\"#e4e4e4\"/>\n\
<text x=\"{3:.1}\" y=\"{4:.1}\" text-anchor=\"end\">{label}</text>",
            x0,
            py(*y),
            x0 + pw,
            x0 - 5.0,
            py(*y) + 4.0
        );
    }
    let _ = writeln!(
        svg,
        "<rect x=\"{x0:.1}\" y=\"{y0:.1}\" width=\"{pw:.1}\" height=\"{ph:.1}\" fill=\"none\" stroke=\"black\"/>\n\
<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
        x0 + pw / 2.0,
        y0 + ph + 32.0,
        p.xlabel
    );
    let (lx, ly) = (p.origin.0 + 14.0, y0 + ph / 2.0);
    let _ = writeln!(
        svg,
        "<text x=\"{lx:.1}\" y=\"{ly:.1}\" text-anchor=\"middle\" transform=\"rotate(-90 {lx:.1} {ly:.1})\">{}</text>",
        p.ylabel
    );
    for s in series {
        let pts: Vec<String> = s
            .pts
            .iter()
            .map(|&(x, y)| format!("{:.1},{:.1}", px(x), py(y)))
            .collect();
        let dash = if s.dashed { " stroke-dasharray=\"5 3\"" } else { "" };
        let _ = writeln!(
            svg,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"{dash}/>",
            pts.join(" "),
            s.color
        );
        let fill = if s.dashed { "white" } else { s.color };
        for &(x, y) in &s.pts {
            let _ = writeln!(
                svg,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"2.6\" fill=\"{fill}\" stroke=\"{}\"/>",
                px(x),
                py(y),
                s.color
            );
        }
    }
}

/// A legend: one line sample and label per series, from `at` downwards.
pub fn legend(svg: &mut String, at: (f64, f64), series: &[Series]) {
    for (k, s) in series.iter().enumerate() {
        let y = at.1 + 16.0 * k as f64;
        let dash = if s.dashed { " stroke-dasharray=\"5 3\"" } else { "" };
        let _ = writeln!(
            svg,
            "<line x1=\"{:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"{}\" stroke-width=\"1.6\"{dash}/>\n\
<text x=\"{:.1}\" y=\"{:.1}\">{}</text>",
            at.0,
            at.0 + 24.0,
            s.color,
            at.0 + 30.0,
            y + 4.0,
            s.label
        );
    }
}
