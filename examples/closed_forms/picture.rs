//! The SVG figures: one grazing ray where the quadratic formula loses both
//! hits (the curve and the ray, and `f(t) = n·(b(t) − o)` near the
//! tangency, exactly and as the paper's float `A t² + B t + C`), and the
//! share of wrong answers against the grazing distance or angle.

use super::cases::{bez, Quad};
use num_rational::BigRational;
use rootclip::scalar::rational_to_f64;
use std::fmt::Write as _;

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

/// The paper's `A, B, C` (Eq. (9)) in `f64`, as the closed form computes them.
pub fn abc_f64(c: &Quad) -> [f64; 3] {
    let [p0, p1, p2] = c.p;
    let (o, d) = (c.o, c.d);
    let a2 = p0 - 2.0 * p1 + p2;
    let a1 = 2.0 * p1 - 2.0 * p0;
    [
        d.x * a2.y - d.y * a2.x,
        d.x * a1.y - d.y * a1.x,
        d.x * (p0.y - o.y) - d.y * (p0.x - o.x),
    ]
}

/// The same `A, B, C` in exact arithmetic from the float inputs.
pub fn abc_exact(c: &Quad) -> [Q; 3] {
    let [p0, p1, p2] = c.p.map(|p| (q(p.x), q(p.y)));
    let (ox, oy, dx, dy) = (q(c.o.x), q(c.o.y), q(c.d.x), q(c.d.y));
    let two = Q::from_integer(2.into());
    let a2 = (&p0.0 - &two * &p1.0 + &p2.0, &p0.1 - &two * &p1.1 + &p2.1);
    let a1 = (&two * (&p1.0 - &p0.0), &two * (&p1.1 - &p0.1));
    [
        &dx * &a2.1 - &dy * &a2.0,
        &dx * &a1.1 - &dy * &a1.0,
        &dx * (&p0.1 - &oy) - &dy * (&p0.0 - &ox),
    ]
}

/// `B² − 4AC`, in floats as the closed form computes it and exactly.
pub fn discriminants(c: &Quad) -> (f64, Q) {
    let [a, b, cc] = abc_f64(c);
    let [ea, eb, ec] = abc_exact(c);
    (b * b - 4.0 * a * cc, &eb * &eb - Q::from_integer(4.into()) * &ea * &ec)
}

/// The figure, for a query whose certified hits lie in `roots` (t intervals).
pub fn grazing_svg(c: &Quad, roots: &[[f64; 2]], h: f64) -> String {
    let (w, hgt) = (860.0, 400.0);
    let mut s = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" \
height=\"{hgt}\" viewBox=\"0 0 {w} {hgt}\" font-family=\"sans-serif\" font-size=\"12\">\n\
<rect width=\"{w}\" height=\"{hgt}\" fill=\"white\"/>\n"
    );
    // Left: the curve and the ray in the plane.
    let (x0, y0, side) = (40.0, 50.0, 280.0);
    let pts: Vec<_> = (0..=100).map(|k| bez(&c.p, k as f64 / 100.0)).collect();
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for p in pts.iter().chain([c.o, c.o + 2.5 * c.d].iter()) {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let scale = side / (hi - lo).max_element();
    let map = |p: rootclip::glam::DVec2| (x0 + (p.x - lo.x) * scale, y0 + side - (p.y - lo.y) * scale);
    let _ = writeln!(
        s,
        "<text x=\"{:.0}\" y=\"30\" text-anchor=\"middle\" font-size=\"13\">the curve and the ray ({h:.0e} from it)</text>",
        x0 + side / 2.0
    );
    let path: Vec<String> = pts
        .iter()
        .map(|p| {
            let (x, y) = map(*p);
            format!("{x:.1},{y:.1}")
        })
        .collect();
    let _ = writeln!(
        s,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2\"/>",
        path.join(" ")
    );
    let (ax, ay) = map(c.o);
    let (bx, by) = map(c.o + 2.5 * c.d);
    let _ = writeln!(
        s,
        "<line x1=\"{ax:.1}\" y1=\"{ay:.1}\" x2=\"{bx:.1}\" y2=\"{by:.1}\" stroke=\"#d62728\" stroke-width=\"1.5\"/>\n\
<circle cx=\"{ax:.1}\" cy=\"{ay:.1}\" r=\"3\" fill=\"#d62728\"/>"
    );
    for r in roots {
        let (x, y) = map(bez(&c.p, 0.5 * (r[0] + r[1])));
        let _ = writeln!(
            s,
            "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"5\" fill=\"none\" stroke=\"black\"/>"
        );
    }
    // Right: f near the tangency.
    let (px0, py0, pw, ph) = (420.0, 50.0, 400.0, 260.0);
    let mid = 0.5 * (roots[0][0] + roots[roots.len() - 1][1]);
    let half = (roots[roots.len() - 1][1] - roots[0][0]).max(1e-12) * 1.5;
    let [ea, eb, ec] = abc_exact(c);
    let [a, b, cc] = abc_f64(c);
    let n = 240;
    let ts: Vec<f64> = (0..=n).map(|k| mid - half + 2.0 * half * k as f64 / n as f64).collect();
    let exact: Vec<f64> = ts
        .iter()
        .map(|&t| {
            let tq = q(t);
            rational_to_f64(&(&ea * &tq * &tq + &eb * &tq + &ec))
        })
        .collect();
    let float: Vec<f64> = ts.iter().map(|&t| a * t * t + b * t + cc).collect();
    let ymax = exact.iter().chain(&float).fold(0.0f64, |m, v| m.max(v.abs())) * 1.1;
    let fx = |t: f64| px0 + (t - (mid - half)) / (2.0 * half) * pw;
    let fy = |v: f64| py0 + ph / 2.0 - v / ymax * ph / 2.0;
    let _ = writeln!(
        s,
        "<text x=\"{:.0}\" y=\"30\" text-anchor=\"middle\" font-size=\"13\">f(t) = n·(b(t) − o) near the tangency</text>\n\
<rect x=\"{px0}\" y=\"{py0}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"black\"/>\n\
<line x1=\"{px0}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#999\"/>",
        px0 + pw / 2.0,
        fy(0.0),
        px0 + pw,
        fy(0.0)
    );
    for (vals, color, dash, label) in [
        (&exact, "#1f77b4", "", "exact (rationals)"),
        (&float, "#ff7f0e", " stroke-dasharray=\"4 3\"", "A t² + B t + C in f64"),
    ] {
        let pts: Vec<String> = ts
            .iter()
            .zip(vals)
            .map(|(&t, &v)| format!("{:.1},{:.1}", fx(t), fy(v)))
            .collect();
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{color}\" stroke-width=\"1.5\"{dash}/>",
            pts.join(" ")
        );
        let ly = if dash.is_empty() { py0 + 16.0 } else { py0 + 32.0 };
        let _ = writeln!(
            s,
            "<line x1=\"{:.0}\" y1=\"{ly:.0}\" x2=\"{:.0}\" y2=\"{ly:.0}\" stroke=\"{color}\" stroke-width=\"1.5\"{dash}/>\
<text x=\"{:.0}\" y=\"{:.0}\">{label}</text>",
            px0 + 10.0,
            px0 + 34.0,
            px0 + 40.0,
            ly + 4.0
        );
    }
    for r in roots {
        let x = fx(0.5 * (r[0] + r[1]));
        let _ = writeln!(
            s,
            "<line x1=\"{x:.1}\" y1=\"{py0}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"black\" stroke-dasharray=\"2 2\"/>",
            py0 + ph
        );
    }
    let (df, de) = discriminants(c);
    let _ = writeln!(
        s,
        "<text x=\"{px0}\" y=\"{:.0}\">t − {mid:.12} ∈ ±{half:.1e}; |f| ≤ {ymax:.1e}</text>\n\
<text x=\"{px0}\" y=\"{:.0}\">B² − 4AC: {df:.3e} in f64, {:.3e} exactly</text>\n\
<text x=\"{px0}\" y=\"{:.0}\">dashed verticals: certified roots</text>",
        py0 + ph + 22.0,
        py0 + ph + 42.0,
        rational_to_f64(&de),
        py0 + ph + 62.0,
    );
    s.push_str("</svg>\n");
    s
}

/// One line of [`rates_svg`]: a label, a colour, a dash pattern (empty for
/// solid) and its points `(x, share)`, `x > 0`.
pub type Series = (String, &'static str, &'static str, Vec<(f64, f64)>);

/// Shares in `[0, 1]` against a logarithmic `x` axis running from `x_max`
/// on the left to `x_min` on the right (nearer to tangency going right).
pub fn rates_svg(title: &str, x_label: &str, series: &[Series]) -> String {
    let (w, h) = (720.0, 400.0);
    let (x0, y0, pw, ph) = (70.0, 40.0, 400.0, 300.0);
    let xs = series.iter().flat_map(|s| s.3.iter().map(|p| p.0.log10()));
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    let (lo, hi) = (lo.floor(), hi.ceil());
    let fx = |x: f64| x0 + (hi - x.log10()) / (hi - lo).max(1.0) * pw;
    let fy = |y: f64| y0 + ph - y * ph;
    let mut s = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" \
height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"12\">\n\
<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n\
<text x=\"{:.0}\" y=\"24\" text-anchor=\"middle\" font-size=\"13\">{title}</text>\n\
<rect x=\"{x0}\" y=\"{y0}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"black\"/>\n",
        x0 + pw / 2.0
    );
    for k in 0..=4 {
        let y = k as f64 / 4.0;
        let _ = writeln!(
            s,
            "<line x1=\"{x0}\" y1=\"{0:.1}\" x2=\"{1}\" y2=\"{0:.1}\" stroke=\"#ddd\"/>\
<text x=\"{2}\" y=\"{3:.1}\" text-anchor=\"end\">{4:.0}%</text>",
            fy(y),
            x0 + pw,
            x0 - 6.0,
            fy(y) + 4.0,
            100.0 * y
        );
    }
    let mut e = hi as i32;
    while e >= lo as i32 {
        let x = fx(10f64.powi(e));
        let _ = writeln!(
            s,
            "<line x1=\"{x:.1}\" y1=\"{y0}\" x2=\"{x:.1}\" y2=\"{0}\" stroke=\"#eee\"/>\
<text x=\"{x:.1}\" y=\"{1}\" text-anchor=\"middle\">1e{e}</text>",
            y0 + ph,
            y0 + ph + 16.0
        );
        e -= 2;
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.0}\" y=\"{:.0}\" text-anchor=\"middle\">{x_label}</text>\n\
<text x=\"18\" y=\"{:.0}\" transform=\"rotate(-90 18 {:.0})\" text-anchor=\"middle\">queries answered wrongly</text>",
        x0 + pw / 2.0,
        y0 + ph + 36.0,
        y0 + ph / 2.0,
        y0 + ph / 2.0
    );
    for (k, (label, color, dash, pts)) in series.iter().enumerate() {
        let dash = if dash.is_empty() {
            String::new()
        } else {
            format!(" stroke-dasharray=\"{dash}\"")
        };
        let line: Vec<String> = pts.iter().map(|&(x, y)| format!("{:.1},{:.1}", fx(x), fy(y))).collect();
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{color}\" stroke-width=\"2\"{dash}/>",
            line.join(" ")
        );
        for &(x, y) in pts {
            let _ = writeln!(
                s,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3\" fill=\"{color}\"/>",
                fx(x),
                fy(y)
            );
        }
        let ly = y0 + 10.0 + 22.0 * k as f64;
        let _ = writeln!(
            s,
            "<line x1=\"{0:.0}\" y1=\"{ly:.0}\" x2=\"{1:.0}\" y2=\"{ly:.0}\" stroke=\"{color}\" stroke-width=\"2\"{dash}/>\
<text x=\"{2:.0}\" y=\"{3:.0}\">{label}</text>",
            x0 + pw + 16.0,
            x0 + pw + 44.0,
            x0 + pw + 50.0,
            ly + 4.0
        );
    }
    s.push_str("</svg>\n");
    s
}
