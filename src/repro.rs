//! Reproduction of Tables 1–6 of Liu, Cao, Chen and Zeng (2016).
//!
//! The paper's systems and numbers are read from
//! `papers/hybrid-clipping-2016/paper_tables.json` (embedded at compile
//! time); ours are recomputed by running the certified solver with
//! Algorithm 1 (no Krawczyk probes, `ε = 1e-14`) in one of three
//! [`Variant`]s — rootclip's default (the halving split test, and for the
//! hybrid methods a second clip with the roles swapped before a split), one
//! role assignment, or the paper's Algorithm 1 as printed — and reading the
//! recursion tree:
//! * level `i` is the tri-box holding a root after `i` steps (a step is one
//!   call of Algorithm 1: a clip — with the default variant possibly two,
//!   intersected — followed by a 1-to-4 split when the clip did not halve the
//!   diameter); its diameter is its longest edge;
//! * `recursions(ε)` is the first level whose diameter is `< ε`, maximum over
//!   the roots — so Table 1's counts follow from Table 2's diameters.

use crate::error::{Error, Result};
use crate::scalar::rational_to_f64;
use crate::solve::{solve, Domain, Method, Solution, SolveOptions, SplitRule, TriangleRoute};
use crate::{parse_polynomial, Polynomial};
use serde_json::Value;

/// The paper's data file.
pub const PAPER_TABLES: &str = include_str!("../papers/hybrid-clipping-2016/paper_tables.json");

/// The examples in table order.
pub const EXAMPLES: [&str; 5] = ["1", "2", "3k0", "3k2", "3k5"];

/// `lg ε` columns of Tables 1, 3 and 5.
pub const LG_EPS: [i32; 7] = [-2, -4, -6, -8, -10, -12, -14];

/// One example system.
#[derive(Clone, Debug)]
pub struct Example {
    /// `"1"`, `"2"`, `"3k0"`, `"3k2"` or `"3k5"`.
    pub name: String,
    /// First equation.
    pub f: Polynomial,
    /// Second equation.
    pub g: Polynomial,
    /// The root whose diameters Tables 2/4/6 list (approximately).
    pub tracked_root: [f64; 2],
    /// The smallest distance between two of the system's roots in the
    /// triangle (`∞` for one root): a tri-box at least this wide may hold two
    /// roots, where §3's convergence theorem does not apply.
    pub separation: f64,
}

/// A recursion-count cell.
#[derive(Clone, Debug, PartialEq)]
pub struct RecursionCell {
    /// Example name.
    pub example: String,
    /// Method.
    pub method: Method,
    /// `lg ε`.
    pub lg_eps: i32,
    /// Ours (`None`: not reached).
    pub ours: Option<usize>,
    /// The paper's (`None` where the paper has no cell).
    pub paper: Option<usize>,
}

/// A diameter cell.
#[derive(Clone, Debug, PartialEq)]
pub struct DiameterCell {
    /// Example name.
    pub example: String,
    /// Method.
    pub method: Method,
    /// Level (1-based).
    pub level: usize,
    /// Ours (`None`: the run stopped before this level).
    pub ours: Option<f64>,
    /// The paper's.
    pub paper: Option<f64>,
}

fn data() -> Result<Value> {
    serde_json::from_str(PAPER_TABLES).map_err(|e| Error::Shape(format!("paper_tables.json: {e}")))
}

/// The example systems, parsed from the data file.
pub fn examples() -> Result<Vec<Example>> {
    let d = data()?;
    EXAMPLES
        .iter()
        .map(|&name| {
            let e = &d["examples"][name];
            let text = |k: &str| {
                e[k].as_str()
                    .ok_or_else(|| Error::Shape(format!("example {name}: no {k}")))
            };
            let tracked = match name {
                "1" => [0.5, 0.125],
                "2" => [0.125, 0.25],
                _ => {
                    let r = &e["roots_approx"][0];
                    [r[0].as_f64().unwrap_or(0.0), r[1].as_f64().unwrap_or(0.0)]
                }
            };
            let roots: Vec<[f64; 2]> = ["roots", "roots_approx"]
                .iter()
                .filter_map(|k| e[*k].as_array())
                .flatten()
                .map(|r| {
                    let x = |i: usize| {
                        r[i].as_f64()
                            .or_else(|| {
                                r[i].as_str()
                                    .and_then(|t| parse_polynomial(t).ok()?.as_constant())
                                    .map(|q| rational_to_f64(&q))
                            })
                            .unwrap_or(f64::NAN)
                    };
                    [x(0), x(1)]
                })
                .collect();
            let mut separation = f64::INFINITY;
            for (i, a) in roots.iter().enumerate() {
                for b in &roots[i + 1..] {
                    separation = separation.min((a[0] - b[0]).hypot(a[1] - b[1]));
                }
            }
            Ok(Example {
                name: name.to_string(),
                f: parse_polynomial(text("f")?)?,
                g: parse_polynomial(text("g")?)?,
                tracked_root: tracked,
                separation,
            })
        })
        .collect()
}

/// Which form of Algorithm 1 a table run uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    /// The split test.
    pub split: SplitRule,
    /// The hybrid methods' second clip with the roles swapped
    /// ([`SolveOptions::swap_roles`]).
    pub swap_roles: bool,
}

impl Variant {
    /// rootclip's default: the halving split test, roles swapped before a split.
    pub const DEFAULT: Variant = Variant {
        split: SplitRule::Halving,
        swap_roles: true,
    };
    /// The halving split test, one role assignment (the paper's clip).
    pub const ONE_ROLE: Variant = Variant {
        split: SplitRule::Halving,
        swap_roles: false,
    };
    /// Algorithm 1 as printed: the literal split test, one role assignment.
    pub const LITERAL: Variant = Variant {
        split: SplitRule::PaperLiteral,
        swap_roles: false,
    };
}

/// Options of a table run: Algorithm 1 without Krawczyk probes, down to
/// `eps`, in the given variant.
pub fn table_options(method: Method, eps: f64, variant: Variant) -> SolveOptions {
    SolveOptions {
        method,
        eps,
        probe: false,
        split: variant.split,
        swap_roles: variant.swap_roles,
        triangle_route: TriangleRoute::Triangle,
        ..SolveOptions::default()
    }
}

/// Solves one example with one method for the tables.
pub fn run(example: &Example, method: Method, eps: f64, variant: Variant) -> Result<Solution> {
    solve(
        &example.f,
        &example.g,
        Domain::Triangle,
        &table_options(method, eps, variant),
    )
}

fn paper_recursions(d: &Value, example: &str, method: Method, lg: i32) -> Option<usize> {
    d["recursions"].as_array()?.iter().find_map(|c| {
        (c["example"] == example && c["method"] == method.name() && c["lg_eps"] == lg)
            .then(|| c["recursions"].as_u64().map(|x| x as usize))
            .flatten()
    })
}

fn paper_diameter(d: &Value, example: &str, method: Method, level: usize) -> Option<f64> {
    d["diameters"].as_array()?.iter().find_map(|c| {
        (c["example"] == example && c["method"] == method.name() && c["level"] == level as u64)
            .then(|| c["diam"].as_f64())
            .flatten()
    })
}

/// The diameters by level of the root nearest `target` (level 0 first).
pub fn tracked_diameters(sol: &Solution, target: [f64; 2]) -> Vec<f64> {
    let dist = |u: f64, v: f64| (u - target[0]).hypot(v - target[1]);
    let roots = sol.roots.iter().map(|r| (dist(r.u, r.v), &r.diameters));
    let clusters = sol.clusters.iter().map(|c| {
        (
            dist(0.5 * (c.bx.u[0] + c.bx.u[1]), 0.5 * (c.bx.v[0] + c.bx.v[1])),
            &c.diameters,
        )
    });
    roots
        .chain(clusters)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|x| x.1.clone())
        .unwrap_or_default()
}

/// All cells of Tables 1–6: recursion counts for every example × method ×
/// `lg ε`, and diameters by level for `hc-nopre` and `hc`, in the given
/// variant of Algorithm 1.
pub fn tables(variant: Variant) -> Result<(Vec<RecursionCell>, Vec<DiameterCell>)> {
    let d = data()?;
    let mut rec = Vec::new();
    let mut diam = Vec::new();
    for ex in examples()? {
        for method in Method::ALL {
            let sol = run(&ex, method, 1e-14, variant)?;
            for lg in LG_EPS {
                rec.push(RecursionCell {
                    example: ex.name.clone(),
                    method,
                    lg_eps: lg,
                    ours: sol.recursions(10f64.powi(lg)),
                    paper: paper_recursions(&d, &ex.name, method, lg),
                });
            }
            if matches!(method, Method::Hc | Method::HcNoPre) {
                let ours = tracked_diameters(&sol, ex.tracked_root);
                let levels = (1..ours.len()).chain(1..=12).max().unwrap_or(0);
                for level in 1..=levels {
                    let paper = paper_diameter(&d, &ex.name, method, level);
                    let mine = ours.get(level).copied();
                    if paper.is_some() || mine.is_some() {
                        diam.push(DiameterCell {
                            example: ex.name.clone(),
                            method,
                            level,
                            ours: mine,
                            paper,
                        });
                    }
                }
            }
        }
    }
    Ok((rec, diam))
}

/// The measured convergence order from a diameter sequence: the median of
/// `log(d_{i+1}/d_i) / log(d_i/d_{i−1})` over steps that start below
/// `min(0.2, separation)` and end above `1e-12`. Below `separation` (the
/// distance to the nearest other root) a tri-box holds one root, the setting
/// of §3's theorem; a larger one may hold two, and its clips are not in the
/// asymptotic regime. A step that ends below `1e-12` measures the rounding
/// floor (certified tri-boxes stop at 1e-15..1e-13 around a root; the
/// paper's float ones at ~1e-16), not the method: the cubic bound
/// `d_{i+1} ≤ C d_i³` is about exact arithmetic. `None` when no step
/// qualifies.
pub fn convergence_order(diams: &[f64], separation: f64) -> Option<f64> {
    let mut orders = convergence_samples(diams, separation);
    if orders.is_empty() {
        return None;
    }
    orders.sort_by(f64::total_cmp);
    Some(orders[orders.len() / 2])
}

/// The per-window estimates behind [`convergence_order`], in level order.
pub fn convergence_samples(diams: &[f64], separation: f64) -> Vec<f64> {
    let start_below = separation.min(0.2);
    let d: Vec<f64> = diams.iter().copied().take_while(|&x| x > 1e-15).collect();
    d.windows(3)
        .filter(|w| w[1] < w[0] && w[2] < w[1] && w[0] < start_below && w[2] > 1e-12)
        .map(|w| (w[2] / w[1]).ln() / (w[1] / w[0]).ln())
        .collect()
}
