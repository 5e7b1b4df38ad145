//! `rootclip solve`: a system from expressions or BB coefficients, every root
//! certified (text or JSON).

use super::bernstein::{parse_bb, Bb};
use super::input::read_input;
use super::json::write_document;
use super::output::Answer;
use super::values::{DomainArg, MethodArg, SquareRouteArg, TriangleRouteArg};
use crate::error::{Error, Result};
use crate::poly::{parse_polynomial, Polynomial};
use crate::solve::{solve, solve_bb, solve_reduced, Domain, ReducedSolution, Solution, SolveOptions};

/// Arguments of `rootclip solve`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct SolveArgs {
    /// The first equation, e.g. "u^3 - v".
    #[arg(
        long = "f",
        allow_hyphen_values = true,
        required_unless_present = "f_bb",
        conflicts_with = "f_bb"
    )]
    f: Option<String>,
    /// The second equation.
    #[arg(
        long = "g",
        allow_hyphen_values = true,
        required_unless_present = "g_bb",
        conflicts_with = "g_bb"
    )]
    g: Option<String>,
    /// The first equation as BB coefficients: a file ("-" for stdin) in the JSON that "rootclip bernstein --json" prints; the domain comes from the file.
    #[arg(long = "f-bb", requires = "g_bb")]
    f_bb: Option<String>,
    /// The second equation as BB coefficients (same domain as --f-bb).
    #[arg(long = "g-bb", requires = "f_bb")]
    g_bb: Option<String>,
    /// The domain (for --f and --g).
    #[arg(long, value_enum, default_value = "triangle", conflicts_with = "f_bb")]
    domain: DomainArg,
    /// The clipping method.
    #[arg(long, value_enum, default_value = "hc")]
    method: MethodArg,
    /// Refine regions until their diameter is below this.
    #[arg(long, default_value_t = 1e-12, allow_negative_numbers = true)]
    eps: f64,
    /// Budget: tri-boxes per triangle (boxes, on the rectangle routes).
    #[arg(long, default_value_t = 50_000)]
    max_boxes: usize,
    /// How the square is solved: natively on boxes (default), or as two
    /// triangles with --method (the paper's conversion).
    #[arg(long, value_enum, default_value = "rect")]
    square_route: SquareRouteArg,
    /// How the triangle is solved (exact input): on boxes of the unit
    /// square (default), or on tri-boxes with --method (Liu et al. 2016).
    #[arg(long, value_enum, default_value = "rect")]
    triangle_route: TriangleRouteArg,
    /// Wall-clock budget in seconds: past it no further box is processed,
    /// and the answer lists the unexplored regions as leftovers (complete =
    /// false).
    #[arg(long)]
    timeout: Option<f64>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub(super) fn run(args: &SolveArgs) -> Result<Answer> {
    let opts = SolveOptions::default()
        .with_method(args.method.into())
        .with_eps(args.eps)
        .with_max_boxes(args.max_boxes)
        .with_square_route(args.square_route.into())
        .with_triangle_route(args.triangle_route.into());
    let opts = match args.timeout {
        Some(s) => opts.with_timeout(super::input::duration("--timeout", s)?),
        None => opts,
    };
    // The system as exact polynomials with its domain, for the common-factor
    // route; and the solve.
    let (exact, sol) = match (&args.f, &args.g, &args.f_bb, &args.g_bb) {
        (Some(f), Some(g), None, None) => {
            let f = parse_polynomial(f).map_err(|e| prefix("--f", e))?;
            let g = parse_polynomial(g).map_err(|e| prefix("--g", e))?;
            let sol = solve(&f, &g, args.domain.into(), &opts);
            ((f, g, args.domain.into()), sol)
        }
        (None, None, Some(fp), Some(gp)) => {
            if fp == "-" && gp == "-" {
                return Err(Error::InvalidOption(
                    "--f-bb and --g-bb cannot both read standard input".into(),
                ));
            }
            let f = parse_bb(&read_input(fp)?, "--f-bb")?;
            let g = parse_bb(&read_input(gp)?, "--g-bb")?;
            match (f, g) {
                (Bb::Triangle(f), Bb::Triangle(g)) => {
                    let sol = solve_bb(&f, &g, &opts);
                    let p = (Polynomial::from_triangle(&f), Polynomial::from_triangle(&g));
                    ((p.0, p.1, Domain::Triangle), sol)
                }
                (Bb::Square(f), Bb::Square(g)) => {
                    let sol = solve_bb(&f, &g, &opts);
                    let p = (Polynomial::from_square(&f), Polynomial::from_square(&g));
                    ((p.0, p.1, Domain::Square), sol)
                }
                _ => {
                    return Err(Error::InvalidOption(
                        "--f-bb and --g-bb must have the same domain".into(),
                    ))
                }
            }
        }
        _ => return Err(Error::InvalidOption("give --f and --g, or --f-bb and --g-bb".into())),
    };
    // A common factor is a curve of roots: listed as the factor, with the
    // isolated roots of the reduced system.
    let reduced = match sol {
        Ok(sol) => ReducedSolution {
            common_factor: "1".into(),
            solution: sol,
        },
        Err(Error::CommonFactor { .. }) => solve_reduced(&exact.0, &exact.1, exact.2, &opts)?,
        Err(e) => return Err(e),
    };
    Ok(if args.json {
        if reduced.common_factor == "1" {
            Answer::new(move |out| write_document(out, &reduced.solution))
        } else {
            Answer::new(move |out| write_document(out, &reduced))
        }
    } else {
        let secs = reduced.solution.stats.seconds;
        let head = if reduced.common_factor == "1" {
            String::new()
        } else {
            format!(
                "common factor {}: its zeros are a curve of roots (not listed); the other roots:\n",
                reduced.common_factor
            )
        };
        Answer::text(head + &solution_text(&reduced.solution, secs))
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
        s.boxes,
        s.clips,
        s.splits,
        s.sign_exclusions,
        s.clip_exclusions,
        s.krawczyk_calls,
        secs * 1e6
    );
    out
}
