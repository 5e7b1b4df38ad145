//! The `rootclip` command line. Errors print one line on stderr and exit 2.

use clap::{Parser, Subcommand, ValueEnum};
use num_rational::BigRational;
use num_traits::One;
use rootclip::poly::tri_indices;
use rootclip::{parse_polynomial, Error};
use serde_json::{json, Value};
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

#[derive(Subcommand)]
enum Command {
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
            println!("{out}");
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
