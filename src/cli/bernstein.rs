//! `rootclip bernstein`: the exact BB coefficients of a polynomial, and the
//! JSON document they are printed in — which `rootclip solve --f-bb` reads
//! back.

use super::json::document;
use super::values::DomainArg;
use crate::error::{Error, Result};
use crate::poly::{parse_polynomial, tri_indices, Polynomial, TensorBezier, TriBezier};
use crate::solve::Domain;
use num_rational::BigRational;
use num_traits::One;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Arguments of `rootclip bernstein`.
#[derive(Clone, Debug, clap::Args)]
pub(super) struct BernsteinArgs {
    /// The polynomial, e.g. "10*(u-1/2)*(u-1/4)*(u-1/8) + 1/4 - v".
    #[arg(long = "f", allow_hyphen_values = true)]
    f: String,
    /// The domain of the BB form.
    #[arg(long, value_enum, default_value = "triangle")]
    domain: DomainArg,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// BB coefficients as a document: `{"domain": "triangle", "degree": n,
/// "coefficients": [{"i", "j", "k", "value"}, …]}` (square: `"degree": [m,
/// n]` and no `"k"`). Values are exact strings (`"-1/8"`, `"0.1"` = 1/10) or
/// JSON numbers (read as the exact value of the `f64`).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BbDocument {
    #[serde(default, skip_serializing)]
    schema_version: Option<u32>,
    domain: Domain,
    degree: Degree,
    coefficients: Vec<Coefficient>,
}

#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Degree {
    Total(usize),
    Bi([usize; 2]),
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Coefficient {
    i: usize,
    j: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    k: Option<usize>,
    value: Value,
}

#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Value {
    Exact(String),
    Float(f64),
}

/// An exact BB polynomial read from a [`BbDocument`].
// Built once per file and consumed at once: boxing buys nothing.
#[allow(clippy::large_enum_variant)]
pub(super) enum Bb {
    Triangle(TriBezier<BigRational>),
    Square(TensorBezier<BigRational>),
}

fn fraction(q: &BigRational) -> String {
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}

pub(super) fn run(args: &BernsteinArgs) -> Result<String> {
    let poly = parse_polynomial(&args.f)?;
    let domain = Domain::from(args.domain);
    poly.check_conversion_cost(domain == Domain::Square)?;
    let doc = to_document(&poly, domain);
    if args.json {
        return Ok(document(&doc));
    }
    let degree = match doc.degree {
        Degree::Total(n) => n.to_string(),
        Degree::Bi([m, n]) => format!("[{m},{n}]"),
    };
    let name = match domain {
        Domain::Square => "square",
        _ => "triangle",
    };
    let mut out = format!("{name}, degree {degree}: {poly}\n");
    let rows: Vec<String> = doc
        .coefficients
        .iter()
        .map(|c| {
            let v = match &c.value {
                Value::Exact(s) => s.clone(),
                Value::Float(x) => x.to_string(),
            };
            match c.k {
                Some(k) => format!("f[{},{},{k}] = {v}", c.i, c.j),
                None => format!("f[{},{}] = {v}", c.i, c.j),
            }
        })
        .collect();
    out += &rows.join("\n");
    Ok(out)
}

fn to_document(poly: &Polynomial, domain: Domain) -> BbDocument {
    let (degree, coefficients) = match domain {
        Domain::Square => {
            let s = poly.to_square();
            let (m, n) = s.degree();
            let coeffs = (0..=m)
                .flat_map(|i| (0..=n).map(move |j| (i, j)))
                .map(|(i, j)| Coefficient {
                    i,
                    j,
                    k: None,
                    value: Value::Exact(fraction(s.coeff(i, j))),
                })
                .collect();
            (Degree::Bi([m, n]), coeffs)
        }
        _ => {
            let t = poly.to_triangle(0);
            let coeffs = tri_indices(t.degree())
                .zip(t.coeffs())
                .map(|((i, j, k), c)| Coefficient {
                    i,
                    j,
                    k: Some(k),
                    value: Value::Exact(fraction(c)),
                })
                .collect();
            (Degree::Total(t.degree()), coeffs)
        }
    };
    BbDocument {
        schema_version: None,
        domain,
        degree,
        coefficients,
    }
}

/// Reads a BB document (`what` names it in errors): every index exactly
/// once, values exact.
pub(super) fn parse_bb(text: &str, what: &str) -> Result<Bb> {
    let doc: BbDocument = serde_json::from_str(text).map_err(|e| Error::Format(format!("{what}: {e}")))?;
    let bad = |m: String| Error::Format(format!("{what}: {m}"));
    if let Some(v) = doc.schema_version.filter(|&v| v > super::json::SCHEMA_VERSION) {
        return Err(bad(format!("schema_version {v} is newer than this rootclip reads")));
    }
    let mut values: BTreeMap<(usize, usize, Option<usize>), BigRational> = BTreeMap::new();
    for c in &doc.coefficients {
        let q = match &c.value {
            Value::Exact(s) => parse_polynomial(s)
                .ok()
                .and_then(|p| p.as_constant())
                .ok_or_else(|| bad(format!("value {s:?} is not a number")))?,
            Value::Float(x) => {
                BigRational::from_float(*x).ok_or_else(|| Error::NonFinite(format!("{what}: a value is {x}")))?
            }
        };
        if values.insert((c.i, c.j, c.k), q).is_some() {
            return Err(bad(format!("coefficient ({}, {}) given twice", c.i, c.j)));
        }
    }
    let take = |key: (usize, usize, Option<usize>)| {
        values
            .get(&key)
            .cloned()
            .ok_or_else(|| bad(format!("coefficient {key:?} is missing")))
    };
    match (doc.domain, doc.degree) {
        (Domain::Triangle, Degree::Total(n)) => {
            let coeffs = tri_indices(n)
                .map(|(i, j, k)| take((i, j, Some(k))))
                .collect::<Result<Vec<_>>>()?;
            if values.len() != coeffs.len() {
                return Err(bad(format!(
                    "degree {n} has {} coefficients, got {}",
                    coeffs.len(),
                    values.len()
                )));
            }
            Ok(Bb::Triangle(TriBezier::new(n, coeffs)?))
        }
        (Domain::Square, Degree::Bi([m, n])) => {
            let coeffs = (0..=m)
                .flat_map(|i| (0..=n).map(move |j| (i, j)))
                .map(|(i, j)| take((i, j, None)))
                .collect::<Result<Vec<_>>>()?;
            if values.len() != coeffs.len() {
                return Err(bad(format!(
                    "bidegree [{m}, {n}] has {} coefficients, got {}",
                    coeffs.len(),
                    values.len()
                )));
            }
            Ok(Bb::Square(TensorBezier::on_unit_square(m, n, coeffs)?))
        }
        _ => Err(bad(
            "\"degree\" must be a number on the triangle and [m, n] on the square".into(),
        )),
    }
}
