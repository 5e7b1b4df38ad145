//! The write-up: tables of the measured families, the figures' captions, and
//! the text, whose every number is read from the tallies.

use super::tally::{Tally, TOL};
use rootclip::heuristics::FormulaFailure;
use std::fmt::Write as _;

/// One measured family: the tally and the time per query.
pub struct Row {
    pub name: String,
    pub tally: Tally,
    pub failures: Vec<(FormulaFailure, usize)>,
    pub cf_ns: f64,
    pub oracle_us: f64,
}

impl Row {
    /// The share of queries with at least one lost, invented or misplaced
    /// hit.
    pub fn wrong_share(&self) -> f64 {
        self.tally.wrong_queries as f64 / self.tally.queries as f64
    }
}

fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.0e}")
    }
}

fn pct(k: usize, n: usize) -> String {
    format!("{:.1} %", 100.0 * k as f64 / n.max(1) as f64)
}

pub fn table(out: &mut String, rows: &[Row]) {
    out.push_str(
        "| family | queries | certified hits | undecided regions (unclaimed) | closed-form hits | lost | invented | \
misplaced (worst) | in undecided | failed (hits there) | worst matched \\|Δ\\| | closed form | referee |\n\
|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n",
    );
    for r in rows {
        let t = &r.tally;
        let failed = if t.failed == 0 {
            "0".to_string()
        } else {
            let why: Vec<String> = r.failures.iter().map(|(f, k)| format!("{k} {}", f.code())).collect();
            format!("{} ({}): {}", t.failed, t.failed_hits, why.join(", "))
        };
        let mut undecided = t.oracle_open.to_string();
        if t.oracle_open > 0 {
            let _ = write!(undecided, " ({})", t.open_unclaimed);
        }
        if t.oracle_degenerate > 0 {
            let _ = write!(undecided, " (+{} degenerate)", t.oracle_degenerate);
        }
        if t.oracle_incomplete > 0 {
            let _ = write!(undecided, " ({} incomplete)", t.oracle_incomplete);
        }
        if t.oracle_reduced > 0 {
            let _ = write!(undecided, "; {} by reduction", t.oracle_reduced);
        }
        let misplaced = if t.misplaced > 0 {
            format!("**{}** ({})", t.misplaced, sci(t.worst_misplaced))
        } else {
            "**0**".into()
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | **{}** | **{}** | {} | {} | {} | {} | {:.0} ns | {:.1} µs |",
            r.name,
            t.queries,
            t.oracle_hits,
            undecided,
            t.cf_hits,
            t.lost,
            t.invented,
            misplaced,
            t.in_open,
            failed,
            sci(t.worst),
            r.cf_ns,
            r.oracle_us
        );
    }
}

fn find<'a>(rows: &'a [Row], name: &str) -> &'a Row {
    rows.iter().find(|r| r.name == name).expect("family")
}

/// Totals over a set of rows: (queries, wrong queries, certified hits,
/// lost, invented, misplaced).
fn totals(rows: &[&Row]) -> [usize; 6] {
    rows.iter().fold([0; 6], |mut a, r| {
        let t = &r.tally;
        a[0] += t.queries;
        a[1] += t.wrong_queries;
        a[2] += t.oracle_hits;
        a[3] += t.lost;
        a[4] += t.invented;
        a[5] += t.misplaced;
        a
    })
}

/// Median closed-form and referee times over the rows (ns, µs).
fn median_times(rows: &[Row]) -> (f64, f64) {
    let mut cf: Vec<f64> = rows.iter().map(|r| r.cf_ns).collect();
    let mut or: Vec<f64> = rows.iter().map(|r| r.oracle_us).collect();
    cf.sort_by(f64::total_cmp);
    or.sort_by(f64::total_cmp);
    (cf[cf.len() / 2], or[or.len() / 2])
}

/// The families the write-up names; built in `main` and read here.
pub struct Sweeps<'a> {
    pub heights: &'a [f64],
    pub quad_inside: Vec<&'a Row>,
    pub quad_outside: Vec<&'a Row>,
    pub angles: &'a [f64],
    pub seg_angle: Vec<&'a Row>,
    pub swept_heights: &'a [f64],
    pub swept_inside: Vec<&'a Row>,
    pub swept_outside: Vec<&'a Row>,
}

/// The three tables, the figures and the text.
pub struct Report<'a> {
    pub provenance: String,
    pub n: usize,
    pub quad: &'a [Row],
    pub seg: &'a [Row],
    pub swept: &'a [Row],
    pub sweeps: Sweeps<'a>,
    /// The grazing family of the first figure.
    pub figure: Option<String>,
}

impl Report<'_> {
    pub fn write(&self, out: &mut String) {
        self.intro(out);
        self.summary(out);
        out.push_str("\n## Quadratic Bézier curve (§1.2, Eqs. (3)–(10): the quadratic formula)\n\n");
        table(out, self.quad);
        out.push_str("\n## Line segment (§1.1, Eqs. (1)–(2))\n\n");
        table(out, self.seg);
        out.push_str("\n## Swept quadratic Bézier patch (§2.1, Eq. (11) on top of (8)–(10))\n\n");
        table(out, self.swept);
        self.figures(out);
        self.mechanisms(out);
        differences(out);
        let _ = writeln!(
            out,
            "\n## Reproduce\n\n```sh\ncargo run --release --example closed_forms   # this page and its figures (about a minute)\n\
cargo test --release --test closed_forms     # the harness against its own claims\n```"
        );
    }

    fn intro(&self, out: &mut String) {
        let _ = writeln!(
            out,
            "# Closed-form ray intersections, refereed (Christensen 2008)\n\n\
<!-- Generated by `cargo run --release --example closed_forms`; do not edit by hand. -->\n\n\
Paper: J. Christensen (2008), *Ray intersections* (Christensen 2008): a 2D ray against a line segment (§1.1) and a \
quadratic Bézier curve (§1.2), and a 3D ray against the quadratic Bézier curve swept along `z` (§2.1), each \
in closed form. The note derives the formulas and measures nothing, so there is no table to reproduce; what \
this page measures is what issue 18 asks — how often the formulas, computed in `f64` exactly as the paper \
writes them ([`rootclip::heuristics::{{ray_segment_2d, ray_quadratic_bezier_2d, \
ray_swept_quadratic_patch_3d}}`](../../src/heuristics/closed_form.rs)), lose or invent intersections through \
cancellation, and what they cost beside a certified answer. Every number is computed by \
`examples/closed_forms.rs` from a fixed seed ({n} queries per family, {n4} for the random ones); only the \
timings change from run to run ({prov}).\n",
            n = self.n,
            n4 = 4 * self.n,
            prov = self.provenance
        );
        let _ = writeln!(
            out,
            "**The referees.** In 2D the hits are the roots `t ∈ [0, 1]` of `f(t) = n·(b(t) − o)`, `n = (−d_y, d_x)`, \
with `s ≥ 0`. `f`'s BB coefficients `n·(p_i − o)` are enclosed in intervals and solved by the certified \
univariate solver `solve::solve_uni`; where that leaves anything undecided or a root interval wider than \
1e-13, the coefficients are recomputed exactly in rationals (the float inputs are exact rationals) and \
solved again, so a certified root is a root of the exact problem the floats describe. The sign of `s` at a \
root is that of `g(t) = d·(b(t) − o)`, decided exactly (an interval filter, then exact BB coefficients of `g` \
on ever smaller root intervals). In 3D the referee is `ray::intersect` on the swept patch as a tensor patch of \
bidegree (2, 1) with control points `(p_i, 0)`, `(p_i, e)`; where it leaves a region undecided (it does for \
rays grazing the curve in plan and rays nearly along the sweep), the exact reduction to 2D decides it: the \
projected ray's roots by `solve_uni` on exact coefficients, `s ≥ 0` and `u = (o_z + d_z s)/e ∈ [0, 1]` as \
three exact signs at each root, `t` bisected exactly until `u` is enclosed to 1e-13 (\"by reduction\" in the \
table counts those queries).\n\n\
**The verdicts.** A closed-form hit *matches* a certified hit when it lies within {TOL:.0e} of the \
certified interval in `t` (and `u`); matching is one-to-one, nearest first. A certified hit with no match is \
**lost**; a closed-form hit matching nothing, and not within {TOL:.0e} of an undecided region either, is \
**invented** — the referee proves there is no intersection there. A query with both is counted as \
**misplaced** (a hit reported more than {TOL:.0e} from where it is; *worst* is the largest such distance). \
Closed-form hits near an undecided region of the referee (an exact tangency, a double root) are counted \
apart (*in undecided*), as are the undecided regions no closed-form hit comes near (*unclaimed*). \
*Failed* counts queries where the formula divides by zero or overflows (the reason codes of \
`heuristics::FormulaFailure`), with the certified hits of those queries. Times are per query: the closed \
form (repeated until the run is long enough to time) and the referee (once per query).\n"
        );
    }
}

impl Report<'_> {
    fn summary(&self, out: &mut String) {
        let s = &self.sweeps;
        out.push_str("## What was measured\n\n");
        let randoms = [
            ("quadratic", find(self.quad, "random (aimed near the curve)")),
            ("segment", find(self.seg, "random (aimed near the segment)")),
            ("swept patch", find(self.swept, "random (aimed near the patch)")),
        ];
        let parts: Vec<String> = randoms
            .iter()
            .map(|(what, r)| {
                format!(
                    "{what}: {} of {} queries wrong, {} certified hits, worst distance {}",
                    r.tally.wrong_queries,
                    r.tally.queries,
                    r.tally.oracle_hits,
                    sci(r.tally.worst)
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "* **Random rays** (aimed at a random point of the curve or patch, blurred by 0.1): the closed forms \
are right — {}.",
            parts.join("; ")
        );
        let wrong_at = |k: usize| s.quad_inside[k].tally.wrong_queries + s.quad_outside[k].tally.wrong_queries > 0;
        let k0 = (0..s.heights.len()).find(|&k| wrong_at(k));
        let mut text = match k0 {
            None => format!(
                "the quadratic formula answers every query right down to `h = {}`",
                sci(s.heights[s.heights.len() - 1])
            ),
            Some(k) => {
                let mut t = match k {
                    0 => "the quadratic formula answers queries wrongly already at the largest `h`".to_string(),
                    _ => format!(
                        "the quadratic formula answers every query right down to `h = {}`",
                        sci(s.heights[k - 1])
                    ),
                };
                for j in k..s.heights.len() {
                    let [n, w, _, l, i, m] = totals(&[s.quad_inside[j], s.quad_outside[j]]);
                    let _ = write!(
                        t,
                        "; at `h = {}` {} of {} queries are wrong ({}: {} hits lost, {} invented, {} misplaced)",
                        sci(s.heights[j]),
                        w,
                        n,
                        pct(w, n),
                        l,
                        i,
                        m
                    );
                }
                t
            }
        };
        if let Some(k) = k0 {
            let r = s.quad_inside[k];
            let _ = write!(
                text,
                ". That is at the resolution of the inputs themselves (the ray's origin has coordinates near 1, \
whose spacing is 2.2e-16), and the certified hit counts show it: the rays meant to pass {} inside the curve \
meet it {} times, not {}",
                sci(s.heights[k]),
                r.tally.oracle_hits,
                2 * r.tally.queries
            );
        }
        let _ = writeln!(
            out,
            "* **Grazing rays** (parallel to the curve's tangent at distance `h`, on the concave side — two hits — or \
the convex side — none): {text}. Above that, the cancellation in `B² − 4AC` costs digits, not hits: the worst \
matched distance grows like `ε/√h` (the table's column)."
        );
        let tan = find(self.quad, "exact tangency (double root)");
        let _ = writeln!(
            out,
            "* **Exact tangencies** (dyadic inputs with an exact double root): the referee leaves each one \
undecided (a double root is never certified); the formula reports {} hits near them and nothing at all at \
{} of {} tangencies (`B² − 4AC` rounded below zero).",
            tan.tally.in_open, tan.tally.open_unclaimed, tan.tally.oracle_open
        );
        let p0 = find(self.quad, "aimed at p0 (t = 0)");
        let p2 = find(self.quad, "aimed at p2 (t = 1)");
        let a = find(self.seg, "aimed at a (t = 1)");
        let qout = find(self.quad, "1e-300 outside the end t = 0");
        let sout = find(self.seg, "1e-300 outside the end t = 0");
        let _ = writeln!(
            out,
            "* **Hits at the ends of the parameter range** (rays aimed at an end point, `d = p − o` rounded, so the \
hit lies within rounding of the end, inside or outside): at `p₀` (`t = 0`) the quadratic formula invents {} \
hits and loses {}; at `p₂` (`t = 1`) it loses {} and invents {}; the segment formula aimed at `a` (`t = 1`) \
loses {} and invents {}. A hit 1e-300 outside `t = 0` is invented {} times in {} by the quadratic formula \
(`−B + √(B² − 4AC)` cancels to exactly 0, which is in `[0, 1]`) and {} times by the segment formula, whose \
numerator keeps the tiny value.",
            p0.tally.invented,
            p0.tally.lost,
            p2.tally.lost,
            p2.tally.invented,
            a.tally.lost,
            a.tally.invented,
            qout.tally.invented,
            qout.tally.queries,
            sout.tally.invented
        );
        let seg_parts: Vec<String> = s
            .seg_angle
            .iter()
            .zip(s.angles)
            .filter(|(r, _)| r.tally.wrong_queries > 0)
            .map(|(r, a)| {
                format!(
                    "{} at {} (worst {})",
                    pct(r.tally.wrong_queries, r.tally.queries),
                    sci(*a),
                    sci(r.tally.worst_misplaced)
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "* **Near-parallel rays against a segment** (at angle `α`, through its midpoint): every query right \
down to `α = {}`, then hits misplaced by errors of order `ε/α` in `t` (cancellation in the denominator) — queries wrong: {}; at `α = {}` the \
denominator also rounds to zero ({} `parallel` failures).",
            s.seg_angle
                .iter()
                .position(|r| r.tally.wrong_queries > 0)
                .and_then(|k| k.checked_sub(1))
                .map_or("—".into(), |k| sci(s.angles[k])),
            seg_parts.join(", "),
            sci(*s.angles.last().expect("angles")),
            s.seg_angle.last().map_or(0, |r| r.tally.failed)
        );
        let [sn, sw, sh, sl, si, sm] = totals(
            &s.swept_inside
                .iter()
                .chain(&s.swept_outside)
                .copied()
                .collect::<Vec<_>>(),
        );
        let verts: Vec<String> = self
            .swept
            .iter()
            .filter(|r| r.name.starts_with("direction"))
            .map(|r| {
                format!(
                    "{}: {} wrong of {} ({} lost, {} invented, {} misplaced, worst {})",
                    r.name.trim_start_matches("direction (ε w, 1), "),
                    r.tally.wrong_queries,
                    r.tally.queries,
                    r.tally.lost,
                    r.tally.invented,
                    r.tally.misplaced,
                    sci(r.tally.worst_misplaced.max(r.tally.worst))
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "* **The swept patch** inherits the quadratic formula's behaviour in plan (grazing in plan at `h` down \
to {}: {} of {} queries wrong, {} certified hits, {} lost, {} invented, {} misplaced) and adds one: a ray \
nearly along the sweep, direction `(ε w, 1)`, gets `s = (b_x(t) − o_x)/d_x` from a divisor of size `ε`, so \
`s` and `u = (o_z + d_z s)/e` carry an error of order `ε_mach/ε` (times the curve's size over `e`) — {}.",
            sci(*s.swept_heights.last().expect("heights")),
            sw,
            sn,
            sh,
            sl,
            si,
            sm,
            verts.join("; ")
        );
        let (qc, qo) = median_times(self.quad);
        let (sc, so) = median_times(self.seg);
        let (wc, wo) = median_times(self.swept);
        let rq = find(self.quad, "random (aimed near the curve)");
        let rs = find(self.seg, "random (aimed near the segment)");
        let rw = find(self.swept, "random (aimed near the patch)");
        let _ = writeln!(
            out,
            "* **Time per query** (random rays; the median over all families in brackets): quadratic {:.0} ns \
against the referee's {:.1} µs ({:.0}×) [{:.0} ns, {:.1} µs]; segment {:.0} ns against {:.1} µs ({:.0}×) \
[{:.0} ns, {:.1} µs]; swept patch {:.0} ns against {:.1} µs ({:.0}×) [{:.0} ns, {:.1} µs]. The referee is \
slow exactly where the formulas are fragile: near tangencies and ends it goes to exact rationals, and \
there it costs up to milliseconds.",
            rq.cf_ns,
            rq.oracle_us,
            rq.oracle_us * 1e3 / rq.cf_ns,
            qc,
            qo,
            rs.cf_ns,
            rs.oracle_us,
            rs.oracle_us * 1e3 / rs.cf_ns,
            sc,
            so,
            rw.cf_ns,
            rw.oracle_us,
            rw.oracle_us * 1e3 / rw.cf_ns,
            wc,
            wo
        );
    }
}

impl Report<'_> {
    fn figures(&self, out: &mut String) {
        out.push_str("\n## Where the closed forms fail\n\n");
        out.push_str(
            "![Share of queries answered wrongly against the grazing distance or the angle](rates.svg)\n\n\
*The share of queries with a lost, invented or misplaced hit, against the distance `h` of a grazing ray from \
the curve (in plan, for the swept patch) and against the angle `α` between a ray and a segment. The formulas \
are exact to the last few digits until the geometry is at the rounding level of the inputs; the segment \
formula's `t` goes wrong four orders of magnitude earlier (misplaced, not lost: see below).*\n\n",
        );
        if let Some(name) = &self.figure {
            let _ = writeln!(
                out,
                "![A grazing ray whose two hits the quadratic formula loses](grazing.svg)\n\n\
*One query of the family \"{name}\" where the quadratic formula returns no hit and the referee certifies two \
(circles, left; dashed verticals, right). Right: `f(t) = A t² + B t + C` near the tangency, exactly (solid) \
and as the formula's rounded `A`, `B`, `C` evaluate it (dashed), with both discriminants: the rounded `B² − 4AC` \
has the wrong sign.*"
            );
        }
    }

    fn mechanisms(&self, out: &mut String) {
        out.push_str(
            "\n## Why they fail there\n\n\
1. **The discriminant** (Eq. (9), solved by the textbook formula). For a ray at distance `h` from the curve, \
`B² − 4AC` is of relative size `h` against `B²`, and is computed with an absolute error of a few `ε B²` \
(`ε = 2^-53`): the roots, `√h` apart, move by `≈ ε/√h` (the *worst matched* column follows it), and at \
`h ≲ ε` the sign of the discriminant is noise — two hits become none (lost) and none become two (invented). \
At an exact tangency it rounds below zero (no hit), to zero (one) or above (two, about `√ε` from the \
double root).\n\
2. **The small root.** `−B + √(B² − 4AC)` cancels when `|4AC| ≪ B²`, i.e. when a hit lies near `t = 0` (`C` \
is `f(0)`). At `|4AC| < ε B²` it is exactly 0, so a hit just outside `t = 0` is reported at `t = 0` — kept, \
since `0 ∈ [0, 1]` — an invention every time (1e-300 outside), and a hit just inside is reported at 0 too \
(right by the tolerance). The standard cure, `q = −(B + sign(B)√(B² − 4AC))/2`, `t₁ = q/A`, `t₂ = C/q`, is \
not the paper's and is not measured here.\n\
3. **The range tests** `t ∈ [0, 1]`, `s ≥ 0`, `u ∈ [0, 1]` are decided on rounded values. For a hit within \
rounding of an end (rays aimed at `p₀`, `p₂`, `a`), the decision is a coin toss either way: lost when the \
rounded `t` leaves the range, invented when it enters it. No formula evaluated in floating point can do \
better there without knowing its own error; the referee decides these signs exactly.\n\
4. **The segment's denominator** `d_x (a_y − b_y) − d_y (a_x − b_x)` is `|d| |a − b| sin α`, computed with an \
absolute error of about `ε |d| |a − b|`: `t` carries a relative error `ε/α` in its distance from the line's \
foot, so from `α ≈ 1e-12` on a hit is found but misplaced (by up to the *worst* of the *misplaced* column). At `α` below the \
inputs' resolution the ray's direction itself is parallel in floats (`parallel` failures) or not, at random.\n\
5. **The swept patch's `s` and `u`** divide by `d_x` (Eq. (8)) or `d_y` (Eq. (10)): for a ray nearly along \
the sweep the divisor is of size `ε_dir` and `s`, `u` carry errors of `ε/ε_dir` — correct `t`, wrong `u`. \
Dividing by the larger of `|d_x|`, `|d_y|` (the paper picks `d_x` whenever it is non-zero) would not help \
here: both are small.\n",
        );
    }
}

fn differences(out: &mut String) {
    out.push_str(
        "\n## Differences from the paper\n\n\
The note has no experiments, so no measured number differs from a printed one; these are the places where \
the code had to decide something the text leaves open or gets wrong, each documented on the function too.\n\n\
* **Garbled conditions.** (1) and (7) say `d_x ≠ 0 ∧ d_y ≠ 0`, but the text then treats `d_x = 0`: the \
condition meant is `d ≠ 0`. After (9), \"matching values of `t` given by (10)\" means values of `s`. §2.1 \
writes `p(u, v) = r(s)` for a patch it calls `p(t, u)`.\n\
* **`d_x = 0` in (9).** The paper says the coefficients become `−A, −B, −C`; they have the same roots, so the \
code uses `A, B, C` in all cases (the formula is valid for `d_x = 0`) and switches only `s` to Eq. (10).\n\
* **The 3D reduction.** §2.1 says \"Equation (9) gives us the values of t\" without saying for which ray: the \
first two components of `p(t, u) = r(s)` are the 2D problem of the projected ray `(o_x, o_y) + s (d_x, d_y)` \
with the same `s`, and that is what the code solves. When `d_x = d_y = 0` every coefficient vanishes, a case \
the paper does not treat: `FormulaFailure::AlongSweep` (the ray meets the patch in a segment or not at all).\n\
* **No linear case.** When `A = 0` (the ray parallel to `p₀ − 2p₁ + p₂`, or a straight curve) the paper's \
quadratic formula divides by zero; the code reports `FormulaFailure::LeadingZero` rather than adding a \
linear solve the paper does not have. No measured family hit it; the formulas are measured as written.\n\
* **Zero discriminant, overflow.** The paper does not say what a zero or negative `B² − 4AC` means: one \
hit, and none. A non-finite quotient (a tiny divisor) is `FormulaFailure::NotFinite`, never a NaN hit.\n\
* **Orientation.** The paper's segment is `l(t) = t a + (1 − t) b`: `t = 1` at `a`; kept as written.\n\
* **Closed ranges.** The paper keeps `t ∈ [0, 1]`, `s ≥ 0`, `u ∈ [0, 1]` with the ends included; so do the \
code and the referee (a hit exactly at an end, or at the ray's origin, counts).\n\
* **What the paper implies and the measurement qualifies.** The note presents the formulas as exact. They \
are, in exact arithmetic; in `f64` they are right on random rays and wrong near tangencies, near the ends of \
the parameter ranges and for rays nearly parallel to the segment or the sweep, in the proportions above.\n",
    );
}
