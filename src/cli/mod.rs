//! The `rootclip` command line (feature `cli`): a thin client of the library.
//! Errors print one line on stderr and exit 2. Not part of the API.

mod bernstein;
mod crosscheck;
mod heuristics;
mod input;
mod json;
mod output;
mod project;
mod ray;
mod solve;
mod ssi;
mod tables;
mod values;

use clap::{Parser, Subcommand};
use output::Answer;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "rootclip",
    version,
    about = "Certified roots of polynomial systems in Bernstein–Bézier form, and certified ray–patch hits"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Recompute Tables 1–6 of Liu et al. (2016) and print them beside the paper's.
    Tables(tables::TablesArgs),
    /// Every root of f = g = 0 in the domain, each in a certified box.
    Solve(solve::SolveArgs),
    /// Every hit of rays with a Bézier or B-spline patch, each certified.
    Ray(ray::RayArgs),
    /// Referee claimed ray hits (a fast solver's) against the certified hits.
    Crosscheck(crosscheck::CrosscheckArgs),
    /// The certified closest point of a patch to each of many points.
    Project(project::ProjectArgs),
    /// Every branch of the intersection curve of two patches, each point certified.
    Ssi(ssi::SsiArgs),
    /// Print the exact Bernstein–Bézier coefficients of a polynomial in u, v.
    Bernstein(bernstein::BernsteinArgs),
    /// Park, Ji & Ko's (2013) experiment: four ray–patch iterations from 121 starts, each end point refereed.
    Heuristics(heuristics::HeuristicsArgs),
}

/// Runs the command line: parses the arguments, runs the command, prints its
/// output (or one error line) and returns the exit code: 0; 1 when some
/// items of a batch failed (every item is printed, the failed ones with their
/// errors); 2 for bad input or an unwritable standard output (nothing on
/// standard output, one line on standard error).
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version: print as clap formats them, exit 0.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            eprintln!(
                "rootclip: missing subcommand (bernstein, crosscheck, heuristics, project, ray, solve, ssi, tables); see rootclip --help"
            );
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
    let answer = match cli.command {
        Command::Bernstein(args) => bernstein::run(&args).map(Answer::text),
        Command::Tables(args) => tables::run(&args).map(Answer::text),
        Command::Ray(args) => ray::run(&args),
        Command::Crosscheck(args) => crosscheck::run(&args),
        Command::Project(args) => project::run(&args),
        Command::Heuristics(args) => heuristics::run(&args).map(Answer::text),
        Command::Solve(args) => solve::run(&args),
        Command::Ssi(args) => ssi::run(&args).map(Answer::text),
    };
    let failed = answer.as_ref().map_or((0, 0), |a| a.failed);
    match answer.map(Answer::print) {
        // A closed pipe (`rootclip ... | head`) counts as written.
        Ok(Ok(())) if failed.0 > 0 => {
            eprintln!(
                "rootclip: {} of {} items failed (each is listed with its error)",
                failed.0, failed.1
            );
            ExitCode::from(1)
        }
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            eprintln!("rootclip: writing standard output: {e}");
            ExitCode::from(2)
        }
        Err(e) => {
            // One line, whatever the message holds.
            eprintln!("rootclip: {}", e.to_string().replace(['\n', '\r'], " "));
            ExitCode::from(2)
        }
    }
}
