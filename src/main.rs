//! The `rootclip` command line. Errors print one line on stderr and exit 2.

use clap::{Parser, Subcommand, ValueEnum};
use num_rational::BigRational;
use num_traits::One;
use rootclip::poly::tri_indices;
use rootclip::solve::{self, Method, Solution, SolveOptions, SquareRoute};
use rootclip::{parse_polynomial, Error};
use serde_json::{json, Value};
use std::io::Write;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "rootclip",
    version,
    about = "Certified roots of bivariate polynomial systems in Bernstein–Bézier form"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum Domain {
    /// The unit triangle {u, v >= 0, u + v <= 1}; degree = total degree.
    Triangle,
    /// The unit square [0, 1]^2; bidegree = (degree in u, degree in v).
    Square,
}

#[derive(Clone, Copy, ValueEnum)]
enum SquareRouteArg {
    /// Two triangles of degree m + n, solved with --method (default).
    Triangles,
    /// Bézier clipping on boxes.
    Rect,
    /// Fat-line clipping on boxes.
    RectFatLine,
    /// Hybrid clipping (fat line + fat conic) on boxes.
    RectHybrid,
}

impl From<SquareRouteArg> for SquareRoute {
    fn from(r: SquareRouteArg) -> Self {
        match r {
            SquareRouteArg::Triangles => SquareRoute::Triangles,
            SquareRouteArg::Rect => SquareRoute::Rect,
            SquareRouteArg::RectFatLine => SquareRoute::RectFatLine,
            SquareRouteArg::RectHybrid => SquareRoute::RectHybrid,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    /// Hybrid clipping with preprocessing (default).
    Hc,
    /// Hybrid clipping without preprocessing.
    HcNopre,
    /// Linear fat curves for both equations.
    Linear,
    /// Triangular Bézier clipping.
    Bezier,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Self {
        match m {
            MethodArg::Hc => Method::Hc,
            MethodArg::HcNopre => Method::HcNoPre,
            MethodArg::Linear => Method::Linear,
            MethodArg::Bezier => Method::Bezier,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum SplitArg {
    /// Split when a clip does not halve the diameter.
    Halving,
    /// Split when u_min + v_min + w_min <= 0.5 diam(D), as printed in the paper.
    Paper,
}

#[derive(Subcommand)]
enum Command {
    /// Recompute Tables 1–6 of Liu et al. (2016) and print them beside the paper's.
    Tables {
        /// Print JSON cells instead of text tables.
        #[arg(long)]
        json: bool,
        /// The split test: "halving" (split when a clip does not halve the
        /// diameter; default) or "paper" (Algorithm 1 line 7 as printed).
        #[arg(long, value_enum, default_value = "halving")]
        split: SplitArg,
        /// Hybrid methods clip with one role assignment only (f linear, g
        /// quadratic), as the paper's Algorithm 1; by default a clip that does
        /// not halve the tri-box is followed by one with the roles swapped.
        #[arg(long)]
        one_role: bool,
    },
    /// Every root of f = g = 0 in the domain, each in a certified box.
    Solve {
        /// The first equation, e.g. "u^3 - v".
        #[arg(long = "f", allow_hyphen_values = true)]
        f: String,
        /// The second equation.
        #[arg(long = "g", allow_hyphen_values = true)]
        g: String,
        /// The domain.
        #[arg(long, value_enum, default_value = "triangle")]
        domain: Domain,
        /// The clipping method.
        #[arg(long, value_enum, default_value = "hc")]
        method: MethodArg,
        /// Refine tri-boxes until their diameter is below this.
        #[arg(long, default_value_t = 1e-12, allow_negative_numbers = true)]
        eps: f64,
        /// Budget: tri-boxes per triangle (boxes, on the rectangle routes).
        #[arg(long, default_value_t = 50_000)]
        max_boxes: usize,
        /// How the square is solved: as two triangles with --method (the
        /// paper's conversion), or natively on boxes.
        #[arg(long, value_enum, default_value = "triangles")]
        square_route: SquareRouteArg,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Every hit of rays with a Bézier or B-spline patch, each certified.
    Ray(rootclip::ray::cli::RayArgs),
    /// Print the exact Bernstein–Bézier coefficients of a polynomial in u, v.
    Bernstein {
        /// The polynomial, e.g. "10*(u-1/2)*(u-1/4)*(u-1/8) + 1/4 - v".
        #[arg(long = "f", allow_hyphen_values = true)]
        f: String,
        /// The domain of the BB form.
        #[arg(long, value_enum, default_value = "triangle")]
        domain: Domain,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version: print as clap formats them, exit 0.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            eprintln!("rootclip: missing subcommand (bernstein, ray, solve, tables); see rootclip --help");
            return ExitCode::from(2);
        }
        Err(e) => {
            // One line: clap's message up to its usage block, joined.
            let text = e.to_string();
            let message: Vec<&str> = text
                .lines()
                .take_while(|l| !l.starts_with("Usage:"))
                .map(|l| l.trim().trim_start_matches("error: "))
                .filter(|l| !l.is_empty() && !l.starts_with("tip:") && !l.starts_with("For more information"))
                .collect();
            eprintln!("rootclip: {} (see rootclip --help)", message.join(" "));
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(out) => {
            // A closed pipe (`rootclip ... | head`) is not an error worth a panic.
            let _ = writeln!(std::io::stdout(), "{out}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("rootclip: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<String, Error> {
    match cli.command {
        Command::Bernstein { f, domain, json } => bernstein(&f, domain, json),
        Command::Tables { json, split, one_role } => tables_cmd(json, split, one_role),
        Command::Ray(args) => rootclip::ray::cli::run(&args),
        Command::Solve {
            f,
            g,
            domain,
            method,
            eps,
            max_boxes,
            square_route,
            json,
        } => {
            let opts = SolveOptions {
                method: method.into(),
                eps,
                max_boxes,
                square_route: square_route.into(),
                ..SolveOptions::default()
            };
            solve_cmd(&f, &g, domain, &opts, json)
        }
    }
}

fn fraction(q: &BigRational) -> String {
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}

fn bernstein(expr: &str, domain: Domain, json: bool) -> Result<String, Error> {
    let poly = parse_polynomial(expr)?;
    poly.check_conversion_cost(matches!(domain, Domain::Square))?;
    let (header, degree, rows): (&str, Value, Vec<(Value, String)>) = match domain {
        Domain::Triangle => {
            let t = poly.to_triangle(0);
            let rows = tri_indices(t.degree())
                .zip(t.coeffs())
                .map(|((i, j, k), c)| {
                    (
                        json!({"i": i, "j": j, "k": k, "value": fraction(c)}),
                        format!("f[{i},{j},{k}] = {}", fraction(c)),
                    )
                })
                .collect();
            ("triangle", json!(t.degree()), rows)
        }
        Domain::Square => {
            let s = poly.to_square();
            let (m, n) = s.degree();
            let rows = (0..=m)
                .flat_map(|i| (0..=n).map(move |j| (i, j)))
                .map(|(i, j)| {
                    let c = s.coeff(i, j);
                    (
                        json!({"i": i, "j": j, "value": fraction(c)}),
                        format!("f[{i},{j}] = {}", fraction(c)),
                    )
                })
                .collect();
            ("square", json!([m, n]), rows)
        }
    };
    if json {
        let coeffs: Vec<Value> = rows.into_iter().map(|r| r.0).collect();
        Ok(json!({"domain": header, "degree": degree, "coefficients": coeffs}).to_string())
    } else {
        let mut out = format!("{header}, degree {degree}: {poly}\n");
        out += &rows.into_iter().map(|r| r.1).collect::<Vec<_>>().join("\n");
        Ok(out)
    }
}

fn solve_cmd(f: &str, g: &str, domain: Domain, opts: &SolveOptions, json: bool) -> Result<String, Error> {
    let f = parse_polynomial(f).map_err(|e| prefix("--f", e))?;
    let g = parse_polynomial(g).map_err(|e| prefix("--g", e))?;
    let d = match domain {
        Domain::Triangle => solve::Domain::Triangle,
        Domain::Square => solve::Domain::Square,
    };
    let t0 = std::time::Instant::now();
    let sol = solve::solve(&f, &g, d, opts)?;
    let secs = t0.elapsed().as_secs_f64();
    Ok(if json {
        solution_json(&sol, secs).to_string()
    } else {
        solution_text(&sol, secs)
    })
}

fn prefix(what: &str, e: Error) -> Error {
    match e {
        Error::Parse { message, at } => Error::Parse {
            message: format!("{what}: {message}"),
            at,
        },
        other => other,
    }
}

fn box_json(b: &solve::Box2) -> Value {
    json!({"u": b.u, "v": b.v})
}

fn solution_json(sol: &Solution, secs: f64) -> Value {
    let roots: Vec<Value> = sol
        .roots
        .iter()
        .map(|r| json!({"u": r.u, "v": r.v, "box": box_json(&r.bx), "certified": r.certified, "on_boundary": r.on_boundary}))
        .collect();
    let clusters: Vec<Value> = sol
        .clusters
        .iter()
        .map(|c| json!({"box": box_json(&c.bx), "reason": c.reason.describe()}))
        .collect();
    let leftovers: Vec<Value> = sol
        .leftovers
        .iter()
        .map(|l| json!({"box": box_json(&l.bx), "triangle": l.triangle}))
        .collect();
    let s = &sol.stats;
    json!({
        "complete": sol.complete,
        "roots": roots,
        "clusters": clusters,
        "leftovers": leftovers,
        "stats": {
            "tri_boxes": s.run.boxes, "clips": s.run.clips, "role_swaps": s.run.role_swaps, "splits": s.run.splits,
            "sign_exclusions": s.run.sign_exclusions, "clip_exclusions": s.run.clip_exclusions,
            "krawczyk_calls": s.krawczyk_calls, "krawczyk_exclusions": s.krawczyk_exclusions,
            "leaves": s.leaves, "outside_domain": s.outside_domain, "max_level": s.max_level,
            "probes": s.run.probes, "compensated_boxes": s.run.compensated_boxes,
            "exact_boxes": s.run.exact_boxes, "seconds": secs
        }
    })
}

fn solution_text(sol: &Solution, secs: f64) -> String {
    let mut out = format!(
        "{} root(s), {} undecided cluster(s){}\n",
        sol.roots.len(),
        sol.clusters.len(),
        if sol.complete {
            ", complete"
        } else {
            ", INCOMPLETE (budget reached; see leftovers)"
        }
    );
    for r in &sol.roots {
        out += &format!(
            "root u = {:.17} v = {:.17}  box u [{:e}, {:e}] v [{:e}, {:e}]{}\n",
            r.u,
            r.v,
            r.bx.u[0],
            r.bx.u[1],
            r.bx.v[0],
            r.bx.v[1],
            if r.on_boundary {
                "  (on the domain boundary)"
            } else {
                ""
            }
        );
    }
    for c in &sol.clusters {
        out += &format!(
            "cluster box u [{:e}, {:e}] v [{:e}, {:e}]: {}\n",
            c.bx.u[0],
            c.bx.u[1],
            c.bx.v[0],
            c.bx.v[1],
            c.reason.describe()
        );
    }
    for l in &sol.leftovers {
        out += &format!(
            "leftover box u [{:e}, {:e}] v [{:e}, {:e}]\n",
            l.bx.u[0], l.bx.u[1], l.bx.v[0], l.bx.v[1]
        );
    }
    let s = &sol.stats;
    out += &format!(
        "{} tri-boxes, {} clips, {} splits, {} sign exclusions, {} clip exclusions, {} Krawczyk calls, {:.1} µs",
        s.run.boxes,
        s.run.clips,
        s.run.splits,
        s.run.sign_exclusions,
        s.run.clip_exclusions,
        s.krawczyk_calls,
        secs * 1e6
    );
    out
}

fn opt<T: std::fmt::Display>(x: &Option<T>) -> String {
    x.as_ref().map_or("-".to_string(), |v| v.to_string())
}

/// The paper's table for an example: recursion counts (Tables 1, 3, 5) or
/// diameters by level (Tables 2, 4, 6).
fn table_title(example: &str, diameters: bool) -> String {
    let number = match example {
        "1" => 1,
        "2" => 3,
        _ => 5,
    } + usize::from(diameters);
    match example.strip_prefix("3k") {
        Some(k) => format!("Table {number}, k = {k}"),
        None => format!("Table {number}"),
    }
}

fn tables_cmd(json: bool, split: SplitArg, one_role: bool) -> Result<String, Error> {
    use rootclip::repro;
    let split = match split {
        SplitArg::Halving => solve::SplitRule::Halving,
        SplitArg::Paper => solve::SplitRule::PaperLiteral,
    };
    let (rec, diam) = repro::tables(repro::Variant {
        split,
        swap_roles: !one_role,
    })?;
    if json {
        let mut cells: Vec<Value> = rec
            .iter()
            .map(|c| json!({"example": c.example, "method": c.method.name(), "lg_eps": c.lg_eps, "recursions": c.ours, "paper": c.paper}))
            .collect();
        cells.extend(diam.iter().map(|c| {
            json!({"example": c.example, "method": c.method.name(), "level": c.level, "diam": c.ours, "paper": c.paper})
        }));
        return Ok(
            json!({"source": "Liu, Cao, Chen, Zeng (2016), doi:10.1631/FITEE.1500390", "cells": cells}).to_string(),
        );
    }
    let mut out = String::new();
    for ex in repro::EXAMPLES {
        let title = table_title(ex, false);
        out += &format!("\n{title} (Example {ex}): recursions to reach diam < eps, ours (paper)\n");
        out += &format!("{:<10}", "method");
        for lg in repro::LG_EPS {
            out += &format!("{:>10}", format!("lg {lg}"));
        }
        out += "\n";
        for m in Method::ALL {
            out += &format!("{:<10}", m.name());
            for lg in repro::LG_EPS {
                let c = rec.iter().find(|c| c.example == ex && c.method == m && c.lg_eps == lg);
                let cell = c.map_or("-".to_string(), |c| format!("{} ({})", opt(&c.ours), opt(&c.paper)));
                out += &format!("{cell:>10}");
            }
            out += "\n";
        }
    }
    for ex in repro::EXAMPLES {
        let title = table_title(ex, true);
        out += &format!("\n{title} (Example {ex}): diam of the tri-box holding the root, by level: ours (paper)\n");
        out += &format!("{:<6}{:>26}{:>26}\n", "level", "hc-nopre", "hc");
        let levels = diam
            .iter()
            .filter(|c| c.example == ex)
            .map(|c| c.level)
            .max()
            .unwrap_or(0);
        for level in 1..=levels {
            let cell = |m: Method| {
                diam.iter()
                    .find(|c| c.example == ex && c.method == m && c.level == level)
                    .map_or("-".to_string(), |c| {
                        let f = |x: &Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.2e}"));
                        format!("{} ({})", f(&c.ours), f(&c.paper))
                    })
            };
            out += &format!("{level:<6}{:>26}{:>26}\n", cell(Method::HcNoPre), cell(Method::Hc));
        }
    }
    Ok(out)
}
