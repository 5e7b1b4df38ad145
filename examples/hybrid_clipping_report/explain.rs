//! The measurements behind "Why the numbers differ": Eq. (8)'s rank, the split
//! test, the rounding floor, the first step and the separation of close roots.

use super::*;
use inari::Interval;
use num_rational::BigRational;
use num_traits::Zero;
use rootclip::internals::ball::TriBall;
use rootclip::internals::driver::{self, Limits, Probe};
use rootclip::internals::fatcurve::ClipBounds;
use rootclip::internals::geo::GeoIv;
use rootclip::internals::method::{clip_bounds, preprocess, preprocess_general};
use rootclip::internals::tribox::TriBox;
use rootclip::solve::solve_bb;
use rootclip::{Scalar, TriBezier};

/// `f`, `g` on the unit triangle, enclosed, and exact.
fn system(ex: &Example) -> (TriBezier<Interval>, TriBezier<Interval>, [TriBezier<BigRational>; 2]) {
    let n = ex.f.total_degree().max(1).max(ex.g.total_degree()) as usize;
    let (ef, eg) = (ex.f.to_triangle(n), ex.g.to_triangle(n));
    (
        ef.map(Interval::from_rational),
        eg.map(Interval::from_rational),
        [ef, eg],
    )
}

/// The ball polynomial (the solver's working form) of an enclosed polynomial.
fn ball(p: &TriBezier<Interval>) -> TriBall {
    TriBall::enclose(p).expect("bounded coefficients")
}

fn rational(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

/// The exact polynomial on `tb` (local coordinates of `tb`).
fn exact_on(p: &TriBezier<BigRational>, tb: &TriBox) -> TriBezier<BigRational> {
    let verts = tb.verts.map(|[a, b]| {
        let (a, b) = (rational(a), rational(b));
        let w = BigRational::from_integer(1.into()) - &a - &b;
        [a, b, w]
    });
    p.subdivide(&verts)
}

/// All tri-boxes of the uniform 1-to-4 subdivision of the unit triangle to `depth`.
fn uniform_triboxes(depth: usize) -> Vec<TriBox> {
    let mut all = vec![TriBox::unit()];
    let mut frontier = all.clone();
    for _ in 0..depth {
        frontier = frontier.iter().flat_map(|t| t.split4().into_iter().flatten()).collect();
        all.extend(frontier.iter().cloned());
    }
    all
}

/// `det A(u_c, v_c)` of Eq. (8) at barycentric `c`, in exact arithmetic.
fn exact_det_a(fa: &TriBezier<BigRational>, fb: &TriBezier<BigRational>, c: [f64; 3]) -> BigRational {
    let d = fa.sub(fb);
    let (u, v) = (rational(c[0]), rational(c[1]));
    let b = [u.clone(), v.clone(), BigRational::from_integer(1.into()) - &u - &v];
    let at = |p: &TriBezier<BigRational>| p.eval_bary(&b);
    let (pu, pv) = (d.deriv_u(), d.deriv_v());
    let (duu, duv, dvv) = (at(&pu.deriv_u()), at(&pu.deriv_v()), at(&pv.deriv_v()));
    let (du, dv) = (at(&pu), at(&pv));
    let two = BigRational::from_integer(2.into());
    let a = [
        [duu.clone(), &u * &duu + &two * &du, &v * &duu],
        [duv.clone(), &u * &duv + &dv, &v * &duv + &du],
        [dvv.clone(), &u * &dvv, &v * &dvv + &two * &dv],
    ];
    let minor = |r: usize, c: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        &a[r1][c1] * &a[r2][c2] - &a[r1][c2] * &a[r2][c1]
    };
    (0..3).fold(<BigRational as Zero>::zero(), |acc, k| acc + &a[0][k] * minor(0, k))
}

/// Width `2δ/|∇l|` of the fat line of `p` (local coordinates).
fn strip_width(p: &TriBall) -> f64 {
    let r = p.reduce(1);
    let a = &r.approx;
    2.0 * r.delta / (a[1] - a[0]).hypot(a[2] - a[0])
}

/// A right triangle with legs `h` whose incenter is near `root`.
fn tribox_around(root: [f64; 2], h: f64) -> TriBox {
    let c = [root[0] - 0.3 * h, root[1] - 0.3 * h];
    TriBox {
        verts: [[c[0] + h, c[1]], [c[0], c[1] + h], c],
    }
}

pub(super) fn explain_preprocessing(ctx: &Ctx, s: &mut String) {
    s.push_str(
        "### 1. Eq. (8) is singular everywhere on Examples 1 and 2\n\n§2.3.1 solves \
`A(u_c, v_c) ℓ = −∇²f^β` with `A` built from `Δ = f^α − f^β` (Eq. (8)); *“otherwise [A not of \
full rank], we simply set f̂ = f^α”*. With `f̂ = f^α`, `hc` computes exactly what `hc-nopre` \
computes (a fat line of `f^α`, a fat conic of `f^β`). On the 85 tri-boxes of the uniform 1-to-4 \
subdivision of the triangle to depth 3, at each incenter: `det A` in exact rational arithmetic; \
how often rootclip's `method::preprocess` (Eq. (8) in `f64`, relative pivot test) declares `A` \
singular; how often `method::preprocess_general` has a solution.\n\n\
| system | f − g | det A = 0 exactly | `preprocess`: singular | `preprocess_general`: solved |\n|---|---|---:|---:|---:|\n",
    );
    let boxes = uniform_triboxes(3);
    for ex in &ctx.examples {
        let (_, _, [ef, eg]) = system(ex);
        let (mut zero, mut singular, mut general) = (0, 0, 0);
        for tb in &boxes {
            let (xa, xb) = (exact_on(&ef, tb), exact_on(&eg, tb));
            let c = tb.incenter_bary();
            zero += usize::from(exact_det_a(&xa, &xb, c).is_zero());
            let (fa, fb) = (
                ball(&xa.map(Interval::from_rational)),
                ball(&xb.map(Interval::from_rational)),
            );
            singular += usize::from(preprocess(&fa, &fb, c).is_none());
            general += usize::from(preprocess_general(&fa, &fb, c).is_some());
        }
        let n = boxes.len();
        let _ = writeln!(
            s,
            "| {} | `{}` | {zero}/{n} | {singular}/{n} | {general}/{n} |",
            title(&ex.name),
            ex.f.sub(&ex.g)
        );
    }
    let (p_nopre, p_hc) = (
        paper_diams(ctx, "1", Method::HcNoPre),
        paper_diams(ctx, "1", Method::Hc),
    );
    let pair = |l: usize| {
        opt(p_hc
            .get(l)
            .zip(p_nopre.get(l))
            .map(|(a, b)| format!("{} vs {} at level {}", sci(*a), sci(*b), l + 1)))
    };
    let _ = write!(
        s,
        "\nIn Example 1 `f − g` is linear, so every second derivative of `Δ` vanishes and the first \
row of `A` is zero; in Example 2 it is a function `φ(u)` alone, and then `det A = 0` identically \
(in any affine frame: with `Δ = φ(a s + b t + c)`, subtracting `s`·column 1 from column 2 and \
`t`·column 1 from column 3 leaves a determinant that cancels to 0). Where `preprocess` does not \
report the singular `A` of Example 2, the zero row is filled with rounding noise (~1e-16, the \
midpoints of the interval differences) and the pivot test, relative to each row's own size, \
accepts it: `f̂` is then built from a meaningless `ℓ` — still rigorous (any `ℓ` is), and the \
narrower-strip rule below decides whether it is used.\n\n\
So, taken literally, the paper's `hc` *is* `hc-nopre` on Examples 1 and 2 — yet its Table 2 \
lists different diameters for the two (`hc` vs `hc-nopre`: {}, {}), \
and so does Table 4 from level {} on. Whatever the paper's code did there, it was not the printed \
fallback. rootclip falls back to a generalised preprocessing `f̂ = ℓ·f^α + m·f^β` with two linear \
multipliers whose Hessian vanishes at the incenter (three equations, five unknowns; solvable \
whenever the gradients are transversal, i.e. at every simple root — see \
`method::preprocess_general`), and keeps whichever of the fat lines of `f̂` and `f^α` is narrower \
(both are rigorous). The effect on right triangles of legs h whose incenter is near the tracked \
root (fat-line width `2δ/|∇l|` in the tri-box's local coordinates):\n\n\
| system | h | width for f^α | width for f̂ | ratio |\n|---|---:|---:|---:|---:|\n",
        pair(0),
        pair(p_hc.len().min(p_nopre.len()).saturating_sub(2)),
        opt(paper_diams(ctx, "2", Method::Hc)
            .iter()
            .zip(&paper_diams(ctx, "2", Method::HcNoPre))
            .position(|(a, b)| a != b)
            .map(|l| l + 1)),
    );
    for ex in ctx.examples.iter().filter(|e| e.name == "1" || e.name == "2") {
        let (_, _, [ef, eg]) = system(ex);
        for h in [1e-1, 1e-2, 1e-3] {
            let tb = tribox_around(ex.tracked_root, h);
            let (fa, fb) = (
                ball(&exact_on(&ef, &tb).map(Interval::from_rational)),
                ball(&exact_on(&eg, &tb).map(Interval::from_rational)),
            );
            let plain = strip_width(&fa);
            let hat = preprocess_general(&fa, &fb, tb.incenter_bary()).map(|p| strip_width(&p));
            let ratio = hat.map(|w| format!("{:.1e}", w / plain));
            let _ = writeln!(
                s,
                "| {} | {h:.0e} | {} | {} | {} |",
                title(&ex.name),
                sci(plain),
                opt(hat.map(sci)),
                opt(ratio)
            );
        }
    }
    s.push_str(
        "\nIn local coordinates the width for `f^α` shrinks like h (δ = O(h²) against a gradient \
O(h)) and the width for `f̂` like h² (δ = O(h³)); that is Lemma 1, and it is what makes `hc` \
cubic. So our `hc` columns for Examples 1 and 2 show the algorithm §3 analyses, not the fallback \
§2.3.1 prints; with the printed fallback they would equal the `hc-nopre` columns.\n\n",
    );
}

pub(super) fn explain_split(ctx: &Ctx, s: &mut String) {
    let (hits, n) = bisection_matches(ctx);
    let hc_sum = |cells: &[RecursionCell], ex: &str| -> usize {
        LG_EPS
            .iter()
            .filter_map(|&lg| cell(cells, ex, Method::Hc, lg).and_then(|c| c.ours))
            .sum()
    };
    let worse: Vec<String> = ctx
        .examples
        .iter()
        .filter(|e| hc_sum(&ctx.literal, &e.name) > hc_sum(&ctx.halving, &e.name))
        .map(|e| title(&e.name))
        .collect();
    let bez = |cells: &[RecursionCell]| {
        join(
            ctx.examples
                .iter()
                .map(|e| opt(cell(cells, &e.name, Method::Bezier, -14).and_then(|c| c.ours))),
        )
    };
    // A weak clip the literal test accepts without a split: d_{l+1} > 0.6 d_l on a mid-sized tri-box.
    let weak = ctx.examples.iter().enumerate().find_map(|(i, e)| {
        let d = repro::tracked_diameters(&ctx.literal_runs[i][midx(Method::Hc)], e.tracked_root);
        (1..d.len().saturating_sub(1))
            .find(|&l| d[l] > 1e-3 && d[l + 1] > 0.6 * d[l])
            .map(|l| {
                format!(
                    "{}, `hc`, level {l} → {}: {} → {}",
                    title(&e.name),
                    l + 1,
                    sci(d[l]),
                    sci(d[l + 1])
                )
            })
    });
    let _ = write!(
        s,
        "### 2. The split test of Algorithm 1, line 7\n\nLine 7 splits when \
`u_min + v_min + w_min ≤ 0.5·diam(D)`. The left side is a sum of barycentric coordinates \
(dimensionless: roughly the fraction of D cut away), the right side a length. On the whole \
triangle (diam √2) a clip must cut away more than 0.71 to avoid a split; on a tri-box of \
diameter 1e-3, any clip that cuts away more than 0.05 % counts as progress, so small tri-boxes \
are almost never split and their levels are spent on clips however weak. The prose of §2.3.5 \
says something else — split *“if the diameter of tri-box D′ is larger than half of the size of \
D”* — and that is rootclip's default, which guarantees at least bisection speed.\n\n\
* Linear clipping: with the literal test our counts equal the paper's in {le} of {n} cells (halving: \
{he}); `hc-nopre`: {ne} (halving: {nh}). For `hc` the literal test costs levels on {worse}: on \
mid-sized tri-boxes it accepts, without a split, clips that shrink the diameter by far less than \
half (e.g. {weak}).\n\
* The paper's Bézier counts ({p1} on Example 1) equal ⌈log2(√2/ε)⌉ + 1 in \
{hits} of {n} cells: pure bisection, one level per halving, counting D0 as level 1 — as if its \
Bézier clip never removed anything. Our Bézier clip does shrink tri-boxes (contraction table in \
[Convergence order](#convergence-order)). At lg ε = −14 our Bézier counts on the {ns} systems \
are {h} with halving and {l} with the literal test; bisection needs {b}. Why the paper's Bézier \
clipping behaved exactly like bisection cannot be told from the paper.\n\n",
        le = agreement(&ctx.literal, Method::Linear).1,
        he = agreement(&ctx.halving, Method::Linear).1,
        ne = agreement(&ctx.literal, Method::HcNoPre).1,
        nh = agreement(&ctx.halving, Method::HcNoPre).1,
        worse = if worse.is_empty() {
            "no system".into()
        } else {
            join(worse)
        },
        weak = opt(weak),
        p1 = join(
            LG_EPS
                .iter()
                .map(|&lg| opt(cell(&ctx.halving, "1", Method::Bezier, lg).and_then(|c| c.paper)))
        ),
        ns = ctx.examples.len(),
        h = bez(&ctx.halving),
        l = bez(&ctx.literal),
        b = bisection_levels(-14),
    );
}

/// Angle between the curves at `p`: `asin(|∇f × ∇g| / (|∇f| |∇g|))`.
fn crossing_angle(ex: &Example, p: [f64; 2]) -> f64 {
    let (f, g, _) = system(ex);
    let grad = |q: &TriBezier<Interval>| {
        let q = q.map(|c| c.mid());
        let b = [p[0], p[1], 1.0 - p[0] - p[1]];
        [q.deriv_u().eval_bary(&b), q.deriv_v().eval_bary(&b)]
    };
    let (a, b) = (grad(&f), grad(&g));
    ((a[0] * b[1] - a[1] * b[0]).abs() / (a[0].hypot(a[1]) * b[0].hypot(b[1]))).asin()
}

pub(super) fn explain_rigor(ctx: &Ctx, s: &mut String) -> Res<()> {
    s.push_str(
        "### 3. Rigor: the floor of certified diameters\n\nEvery clip here is a proof: the BB \
coefficients on a tri-box are ball polynomials (float coefficients and one rigorous radius, \
`poly::TriBall`) computed for exactly its `f64` vertices, fat-curve widths are rigorous bounds, \
clip bounds are lower ends of enclosures of the critical points, and a clipped triangle is pushed \
out a few ulps until its covering is proven. Diameters cannot go below ~1e-15 (the float grid of \
the vertices), and our last tri-boxes are a few 1e-15 wide. The \
paper's last diameters below 1e-15 are of the order of one ulp of the root's coordinates — \
triangles whose vertices are adjacent floats, which no computation can certify:\n\n\
| system | method | paper's last diameter | ulp(u), ulp(v) at the root | our last diameter |\n|---|---|---:|---:|---:|\n",
    );
    for (i, ex) in ctx.examples.iter().enumerate() {
        for m in [Method::HcNoPre, Method::Hc] {
            let Some(&last) = paper_diams(ctx, &ex.name, m).last().filter(|&&d| d < 1e-15) else {
                continue;
            };
            let [u, v] = ex.tracked_root;
            let ours = tracked(ctx, i, m).last().copied();
            let _ = writeln!(
                s,
                "| {} | {m} | {} | {}, {} | {} |",
                title(&ex.name),
                sci(last),
                sci(ulp(u)),
                sci(ulp(v)),
                opt(ours.map(sci))
            );
        }
    }
    let k5 = sys(ctx, "3k5")?;
    let ex = &ctx.examples[k5];
    let sol = &ctx.runs[k5][midx(Method::Hc)];
    let theta = crossing_angle(ex, ex.tracked_root);
    let (f, g, _) = system(ex);
    let enclosed = solve_bb(&f, &g, &repro::table_options(Method::Hc, 1e-14, Variant::DEFAULT))?;
    let lv = |sol: &Solution, lg: i32| opt(sol.recursions(10f64.powi(lg)));
    let path = |sol: &Solution| join(repro::tracked_diameters(sol, ex.tracked_root).iter().map(|&d| sci(d)));
    let _ = write!(
        s,
        "\nNear a tangential intersection the rounding of the coefficients (~1e-16 absolute, \
inherited from the root triangle's scale) is amplified by 1/θ, θ the angle between the curves. \
In Example 3 with k = 5 the curves cross at θ = {theta:.2e} rad, so the float noise floor is \
~1e-16/θ ≈ {floor:.0e}. A tri-box whose coefficients are noisy relative to their values (the \
ball's diameter above 1e-9 of its largest coefficient) is therefore recomputed in compensated \
(double-double) arithmetic, whose radius is a few ulps of the tri-box's *own* coefficients, and a \
stalled one below `EXACT_BELOW` = 1e-6 from the exact rational input when there is one. For `hc` \
on this system, tracked root:\n\n\
| input | compensated restarts | exact restarts | tri-boxes | levels to 1e-12 | levels to 1e-14 | diameters by level |\n|---|---:|---:|---:|---:|---:|---|\n\
| exact rational (`solve`) | {xc} | {xr} | {xb} | {x12} | {x14} | {xp} |\n\
| enclosed `f64` BB (`solve_bb` on intervals) | {ec} | {er} | {eb} | {e12} | {e14} | {ep} |\n\n\
With enclosed input (1/4·(1 + 1e-5) is not a float, so `solve_bb` on its interval enclosure has no exact system, and \
the compensated coefficients still carry the input's own rounding, one ulp of 1/4) the clips \
stall at that floor and only splits, a factor 2 per level, get below it. \
The paper reports {p12} and {p14} levels at −12 and −14, its path ending in {plast} — about one ulp, \
not a certified box.\n\n",
        p12 = opt(cell(&ctx.halving, "3k5", Method::Hc, -12).and_then(|c| c.paper)),
        p14 = opt(cell(&ctx.halving, "3k5", Method::Hc, -14).and_then(|c| c.paper)),
        plast = opt(paper_diams(ctx, "3k5", Method::Hc).last().map(|&d| sci(d))),
        floor = 1.1e-16 / theta,
        xc = sol.stats.compensated_restarts,
        xr = sol.stats.exact_restarts,
        xb = sol.stats.boxes,
        x12 = lv(sol, -12),
        x14 = lv(sol, -14),
        xp = path(sol),
        ec = enclosed.stats.compensated_restarts,
        er = enclosed.stats.exact_restarts,
        eb = enclosed.stats.boxes,
        e12 = lv(&enclosed, -12),
        e14 = lv(&enclosed, -14),
        ep = path(&enclosed),
    );
    Ok(())
}

pub(super) fn explain_first_step(ctx: &Ctx, s: &mut String) -> Res<()> {
    s.push_str(
        "### 4. Level 1: the paper's 0.70\n\nA level-1 diameter of √2/2 = 0.707 is a 1-to-4 split of the \
*unclipped* triangle (a split after a clip gives diam(D′)/2 < 0.707). Our first step, recomputed (`method::clip_bounds` \
on the whole triangle, then `TriBox::clip`):\n\n\
| system | method | u_min, v_min, w_min | clipped diam | halving splits | literal splits | level 1, ours | level 1, paper |\n\
|---|---|---|---:|---|---|---:|---:|\n",
    );
    let (mut unclipped_paper, mut unclipped_ours, mut clipped_paper) = (Vec::new(), Vec::new(), Vec::new());
    let mut k0_mins = None;
    let mut ex1_level1 = Vec::new();
    for (i, ex) in ctx.examples.iter().enumerate() {
        let (f, g, _) = system(ex);
        for m in [Method::HcNoPre, Method::Hc] {
            let ClipBounds::Keep(mins) = clip_bounds::<GeoIv>(m, &ball(&f), &ball(&g), TriBox::unit().incenter_bary())
            else {
                return Err("the first clip excluded the whole triangle".into());
            };
            let clipped = TriBox::unit().clip(mins).map_or(DIAM0, |t| t.diam());
            let yes = |b: bool| if b { "yes" } else { "no" };
            let ours = tracked(ctx, i, m).get(1).copied();
            let paper = paper_diams(ctx, &ex.name, m).first().copied();
            let _ = writeln!(
                s,
                "| {} | {m} | {:.3}, {:.3}, {:.3} | {clipped:.3} | {} | {} | {} | {} |",
                title(&ex.name),
                mins[0].max(0.0),
                mins[1].max(0.0),
                mins[2].max(0.0),
                yes(clipped > 0.5 * DIAM0),
                yes(mins.iter().sum::<f64>() <= 0.5 * DIAM0),
                opt(ours.map(|x| format!("{x:.3}"))),
                opt(paper.map(|x| format!("{x:.2}")))
            );
            if ex.name == "3k0" && m == Method::Hc {
                k0_mins = Some(mins);
            }
            if let (Some(o), Some(p), false) = (ours, paper, (paper.unwrap_or(0.0) - 0.5 * DIAM0).abs() < 0.01) {
                ex1_level1.push(format!("{} `{m}`: paper {p:.2}, ours {o:.3}", title(&ex.name)));
            }
            let near = |x: Option<f64>| x.is_some_and(|x| (x - 0.5 * DIAM0).abs() < 0.01);
            let group = if near(paper) {
                &mut unclipped_paper
            } else {
                &mut clipped_paper
            };
            if m == Method::Hc {
                group.push(title(&ex.name));
                if near(paper) && near(ours) {
                    unclipped_ours.push(title(&ex.name));
                }
            }
        }
    }
    let _ = write!(
        s,
        "\nThe paper split the unclipped triangle on {}; we do too on {}, because our first clip \
there removes (almost) nothing. Elsewhere our first clip cuts the triangle down and the split \
follows (level 1 = half the clipped diameter), so from level 1 on the tri-boxes — and every later \
split line — differ from the paper's. On {} the paper's level 1 is below 0.707 too: its first \
step clipped as well ({ex1}).\n\n\
On Example 3, `g = uv − 1/8` is quadratic, so its fat conic is `g` itself (δ = 0 up to rounding), \
and inside the triangle the hyperbola `uv = 1/8` has u, v ≥ (1 − 1/√2)/2 = {hyp:.4} (where it \
meets u + v = 1: §2.3.3's third kind of critical point). Any clip that follows §2.3.3 cuts away \
at least u < {hyp:.4} and v < {hyp:.4} on the whole triangle — ours gives u_min, v_min = {k0} \
on k = 0. The paper's 0.70 on Example 3 therefore suggests that its first step split D itself \
rather than the clipped D′ (Algorithm 1, line 8 says D′).\n\n",
        if unclipped_paper.is_empty() {
            "no system".into()
        } else {
            join(unclipped_paper)
        },
        if unclipped_ours.is_empty() {
            "none of them".into()
        } else {
            join(unclipped_ours)
        },
        if clipped_paper.is_empty() {
            "no system".into()
        } else {
            join(clipped_paper)
        },
        hyp = 0.5 * (1.0 - std::f64::consts::FRAC_1_SQRT_2),
        ex1 = join(ex1_level1),
        k0 = opt(k0_mins.map(|m| format!("{:.4}, {:.4}", m[0], m[1]))),
    );
    Ok(())
}

/// The level at which the tracked root and its nearest other root are first
/// in different tri-boxes of the `hc`/`hc-nopre` recursion tree, and their
/// distance. `None` for one-root systems.
fn separation_in_tree(ex: &Example, m: Method, variant: Variant) -> Res<Option<(f64, Option<usize>)>> {
    let (f, g, exact) = system(ex);
    let o = repro::table_options(m, 1e-14, variant);
    let limits = Limits {
        method: m,
        eps: o.eps,
        max_boxes: o.max_boxes,
        max_depth: o.max_depth,
        max_exact: driver::MAX_EXACT_BOXES,
        probe_below: 0.0,
        split: o.split,
        swap_roles: o.swap_roles,
        deadline: None,
    };
    let run = driver::run::<GeoIv>(
        &ball(&f),
        &ball(&g),
        driver::Exact::Rational(&exact),
        &limits,
        &mut |_| Probe::Undecided(()),
    );
    let sol = repro::run(ex, m, 1e-14, variant)?;
    let near = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let roots: Vec<[f64; 2]> = sol.roots.iter().map(|r| [r.u, r.v]).collect();
    let Some(&a) = roots
        .iter()
        .min_by(|x, y| near(**x, ex.tracked_root).total_cmp(&near(**y, ex.tracked_root)))
    else {
        return Ok(None);
    };
    let Some(&b) = roots
        .iter()
        .filter(|r| **r != a)
        .min_by(|x, y| near(**x, a).total_cmp(&near(**y, a)))
    else {
        return Ok(None);
    };
    let path = |p: [f64; 2]| -> Vec<usize> {
        let leaf = run
            .leaves
            .iter()
            .min_by(|x, y| near(x.tb.point_at([1.0 / 3.0; 3]), p).total_cmp(&near(y.tb.point_at([1.0 / 3.0; 3]), p)));
        let mut out = Vec::new();
        let mut cur = leaf.map(|l| l.node);
        while let Some(i) = cur {
            out.push(i);
            cur = run.nodes[i].parent;
        }
        out.reverse();
        out
    };
    let level = path(a).iter().zip(&path(b)).position(|(x, y)| x != y);
    Ok(Some((near(a, b), level)))
}

/// From diameters by level (index = level, 0 the whole triangle): the latest
/// level by which two roots `dist` apart are in different tri-boxes. A tri-box
/// holding both has diameter ≥ dist, and so do its clips; split children have
/// at least half that.
fn separation_bound(d: &[f64], dist: f64) -> Option<usize> {
    (1..d.len()).find(|&l| d[l] < dist || d.get(l + 1).is_some_and(|&n| n < 0.5 * dist))
}

pub(super) fn explain_separation(ctx: &Ctx, s: &mut String) -> Res<()> {
    s.push_str(
        "### 5. Separating close roots: the second clip with the roles swapped\n\nWhile two roots \
lie in one tri-box no clip can shrink it below their distance; a split or a luckier clip must \
separate them, and the fast convergence starts after that. With the paper's clip alone (f linear, \
g quadratic: `--one-role`) our `hc` separated the two roots of Example 3 later than the paper and \
needed more levels in the cells listed below. rootclip therefore adds one step to Algorithm 1 for \
the hybrid methods: where a clip would not halve the tri-box, it clips once more with the roles \
swapped (g linear — preprocessed for `hc` — and f quadratic) and keeps what both clips keep \
(`Limits::swap_roles`). Both clips are rigorous, so their intersection is; the two role \
assignments bound the region from different sides, and on two close roots the swapped one often \
cuts between them, so no split is needed. It costs one more clip on each tri-box that would \
otherwise be split ([timings](#time-vs-accuracy-figs-4c-5b-7)).\n\nTracked root vs its nearest \
other root: the level at which they are in different tri-boxes of the recursion tree, ours and \
with one role, and the bound that the paper's diameters give (by this level at the latest):\n\n\
| system | method | distance | ours, from the tree | one role, from the tree | paper, bound from diameters |\n\
|---|---|---:|---:|---:|---:|\n",
    );
    for ex in &ctx.examples {
        for m in [Method::HcNoPre, Method::Hc] {
            let Some((dist, tree)) = separation_in_tree(ex, m, Variant::DEFAULT)? else {
                continue;
            };
            let one = separation_in_tree(ex, m, Variant::ONE_ROLE)?.and_then(|x| x.1);
            let mut paper = vec![DIAM0];
            paper.extend(paper_diams(ctx, &ex.name, m));
            let _ = writeln!(
                s,
                "| {} | {m} | {} | {} | {} | {} |",
                title(&ex.name),
                sci(dist),
                opt(tree),
                opt(one),
                opt(separation_bound(&paper, dist))
            );
        }
    }
    s.push_str(
        "\nCells where our `hc` needs more levels than the paper, with the levels each root needs:\n\n\
| variant | system | lg ε | ours | paper | levels per root |\n|---|---|---:|---:|---:|---|\n",
    );
    let mut excess = [Vec::new(), Vec::new()];
    for (k, (label, cells, variant)) in [
        ("ours", &ctx.halving, Variant::DEFAULT),
        ("one role", &ctx.one_role, Variant::ONE_ROLE),
    ]
    .into_iter()
    .enumerate()
    {
        for ex in &ctx.examples {
            let mut sol = None;
            for lg in LG_EPS {
                let Some(RecursionCell {
                    ours: Some(o),
                    paper: Some(p),
                    ..
                }) = cell(cells, &ex.name, Method::Hc, lg)
                else {
                    continue;
                };
                if o <= p {
                    continue;
                }
                if !excess[k].contains(&title(&ex.name)) {
                    excess[k].push(title(&ex.name));
                }
                if sol.is_none() {
                    sol = Some(repro::run(ex, Method::Hc, 1e-14, variant)?);
                }
                let per = sol.iter().flat_map(|x| &x.roots).map(|r| {
                    format!(
                        "({:.3}, {:.3}): {}",
                        r.u,
                        r.v,
                        opt(r.diameters.iter().position(|&d| d < 10f64.powi(lg)))
                    )
                });
                let _ = writeln!(
                    s,
                    "| {label} | {} | {lg} | {o} | {p} | {} |",
                    title(&ex.name),
                    join(per)
                );
            }
        }
    }
    if excess.iter().all(Vec::is_empty) {
        s.push_str("| (none) | | | | | |\n");
    }
    let none = |v: &[String]| {
        if v.is_empty() {
            "no system".to_string()
        } else {
            join(v.iter().cloned())
        }
    };
    let _ = write!(
        s,
        "\nOur `hc` needs more levels than the paper in some cell of {} (ours) and of {} (one role). \
The separation level is not a property of the method alone: it follows from where the earlier \
clips left the split lines, and with a different first clip either implementation could be the \
lucky one; the second clip makes rootclip less dependent on that luck.\n",
        none(&excess[0]),
        none(&excess[1])
    );
    Ok(())
}
