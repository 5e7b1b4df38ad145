//! `rootclip tables`: Tables 1–6 of Liu et al. (2016) recomputed beside the
//! paper's numbers.

use super::json::document;
use super::values::SplitArg;
use crate::error::Result;
use crate::repro;
use crate::solve::Method;
use serde::Serialize;

/// Arguments of `rootclip tables`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct TablesArgs {
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
}

/// A recursion-count cell of Tables 1, 3, 5 (keys in alphabetical order, as
/// the tables' JSON has always printed them).
#[derive(Serialize)]
struct RecursionJson<'a> {
    example: &'a str,
    lg_eps: i32,
    method: Method,
    paper: Option<usize>,
    recursions: Option<usize>,
}

/// A diameter cell of Tables 2, 4, 6.
#[derive(Serialize)]
struct DiameterJson<'a> {
    diam: Option<f64>,
    example: &'a str,
    level: usize,
    method: Method,
    paper: Option<f64>,
}

#[derive(Serialize)]
#[serde(untagged)]
enum Cell<'a> {
    Recursion(RecursionJson<'a>),
    Diameter(DiameterJson<'a>),
}

#[derive(Serialize)]
struct TablesJson<'a> {
    cells: Vec<Cell<'a>>,
    source: &'static str,
}

pub(super) fn run(args: &TablesArgs) -> Result<String> {
    let (rec, diam) = repro::tables(repro::Variant {
        split: args.split.into(),
        swap_roles: !args.one_role,
    })?;
    if args.json {
        let mut cells: Vec<Cell> = rec
            .iter()
            .map(|c| {
                Cell::Recursion(RecursionJson {
                    example: &c.example,
                    lg_eps: c.lg_eps,
                    method: c.method,
                    paper: c.paper,
                    recursions: c.ours,
                })
            })
            .collect();
        cells.extend(diam.iter().map(|c| {
            Cell::Diameter(DiameterJson {
                diam: c.ours,
                example: &c.example,
                level: c.level,
                method: c.method,
                paper: c.paper,
            })
        }));
        return Ok(document(&TablesJson {
            cells,
            source: "Liu, Cao, Chen, Zeng (2016), doi:10.1631/FITEE.1500390",
        }));
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
