//! Solving a polynomial system with rootclip, three ways: from expressions,
//! from Bernstein–Bézier coefficients in `f64`, and with a tight budget to see
//! what an incomplete answer looks like.
//!
//! `cargo run --release --example solve`

use rootclip::solve::{solve, solve_bb, Domain, Method, Solution, SolveOptions};
use rootclip::{parse_polynomial, TensorBezier};

fn report(what: &str, sol: &Solution) {
    println!(
        "{what}: {} certified root(s), {} undecided region(s), {}",
        sol.roots.len(),
        sol.clusters.len(),
        if sol.complete { "complete" } else { "INCOMPLETE" }
    );
    for r in &sol.roots {
        println!(
            "  root  u = {:.15}  v = {:.15}   box width {:.1e}{}",
            r.u,
            r.v,
            r.bx.width(),
            if r.on_boundary { "  (on the boundary)" } else { "" }
        );
    }
    for c in &sol.clusters {
        println!("  region {:?} x {:?}: {}", c.bx.u, c.bx.v, c.reason.describe());
    }
    for l in &sol.leftovers {
        println!("  unexplored {:?} x {:?}", l.bx.u, l.bx.v);
    }
}

fn main() -> rootclip::Result<()> {
    // 1. Expressions on the unit triangle: a circle and a hyperbola, which
    // cross twice.
    let f = parse_polynomial("u^2 + v^2 - 1/4")?;
    let g = parse_polynomial("16*u*v - 1")?;
    let sol = solve(&f, &g, Domain::Triangle, &SolveOptions::default())?;
    report("circle × hyperbola", &sol);

    // A circle and a line tangent to it: one double root, which no method
    // can certify as simple. rootclip reports an undecided region around it
    // instead of guessing.
    let circle = parse_polynomial("(u - 1/3)^2 + (v - 1/3)^2 - 1/16")?;
    let tangent = parse_polynomial("u - 7/12")?;
    let sol = solve(&circle, &tangent, Domain::Triangle, &SolveOptions::default())?;
    report("circle × tangent line", &sol);

    // 2. BB coefficients on the unit square, bidegree (1, 1), row-major
    // c[i][j] at the corner (i, j): f = u − v, g = u + v − 1 (they cross at
    // the centre).
    let f = TensorBezier::on_unit_square(1, 1, vec![0.0, -1.0, 1.0, 0.0])?;
    let g = TensorBezier::on_unit_square(1, 1, vec![-1.0, 0.0, 0.0, 1.0])?;
    let sol = solve_bb(&f, &g, &SolveOptions::default().with_method(Method::Bezier))?;
    report("BB on the square", &sol);

    // 3. A budget ends a run honestly: `complete = false`, the unexplored
    // regions listed, never a silent "no roots".
    let f = parse_polynomial("(u - 1/4)*(u - 1/2)*(u - 3/4) + v/1000")?;
    let g = parse_polynomial("(v - 1/3)*(v - 2/3) + u/1000")?;
    let sol = solve(&f, &g, Domain::Square, &SolveOptions::default().with_max_boxes(2))?;
    report("six roots, budget of 2 tri-boxes", &sol);
    let sol = solve(&f, &g, Domain::Square, &SolveOptions::default())?;
    report("six roots, default budget", &sol);
    Ok(())
}
