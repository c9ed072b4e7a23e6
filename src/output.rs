//! Rendering results: readable text and the JSON contract.
//!
//! JSON keys are a public interface (scripts depend on them):
//! `coordinates`, `equations` (`coordinate`, `lhs`, `rhs`), `mass_matrix`,
//! `forcing`, `accelerations`. Every expression string is in qdot's input
//! syntax and re-parses to the same expression.

use crate::expr::print::{self, pretty_name};
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use serde_json::{json, Map, Value};

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Text,
    Json,
}

fn s(e: &Expr) -> String {
    print::input(e)
}

fn u(e: &Expr) -> String {
    print::unicode(e)
}

/// The JSON of `qdot derive`.
pub fn derive_json(l: &Lagrange) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(l.coordinates));
    m.insert(
        "equations".into(),
        Value::Array(
            l.equations
                .iter()
                .map(|e| json!({"coordinate": e.coordinate, "lhs": s(&e.lhs), "rhs": s(&e.rhs)}))
                .collect(),
        ),
    );
    m.insert(
        "mass_matrix".into(),
        json!(l
            .mass_matrix
            .iter()
            .map(|r| r.iter().map(s).collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    m.insert(
        "forcing".into(),
        json!(l.forcing.iter().map(s).collect::<Vec<_>>()),
    );
    m
}

/// The JSON of `qdot solve`: derive's keys plus `accelerations`.
pub fn solve_json(l: &Lagrange, acc: &[(String, Expr)]) -> Map<String, Value> {
    let mut m = derive_json(l);
    let mut a = Map::new();
    for (q, e) in acc {
        a.insert(q.clone(), Value::String(s(e)));
    }
    m.insert("accelerations".into(), Value::Object(a));
    m
}

/// The text of `qdot derive`.
pub fn derive_text(l: &Lagrange) -> String {
    let mut out = String::from("Lagrange's equations  d/dt(∂E/∂q̇) − ∂E/∂q = Q\n");
    let width = l
        .coordinates
        .iter()
        .map(|c| pretty_name(c, 0).chars().count())
        .max()
        .unwrap_or(1);
    for e in &l.equations {
        let name = pretty_name(&e.coordinate, 0);
        out.push_str(&format!(
            "  {name:<width$}  {} = {}\n",
            u(&e.lhs),
            u(&e.rhs)
        ));
    }
    out.push_str("\nMass matrix M  (M·q̈ = f)\n");
    let cells: Vec<Vec<String>> = l
        .mass_matrix
        .iter()
        .map(|r| r.iter().map(u).collect())
        .collect();
    let n = l.coordinates.len();
    let widths: Vec<usize> = (0..n)
        .map(|j| {
            cells
                .iter()
                .map(|r| r[j].chars().count())
                .max()
                .unwrap_or(1)
        })
        .collect();
    for r in &cells {
        let row: Vec<String> = r
            .iter()
            .enumerate()
            .map(|(j, c)| format!("{c:<w$}", w = widths[j]))
            .collect();
        out.push_str(&format!("  [ {} ]\n", row.join("   ")));
    }
    out.push_str("\nForcing f\n");
    for (c, f) in l.coordinates.iter().zip(&l.forcing) {
        out.push_str(&format!("  {:<width$}  {}\n", pretty_name(c, 0), u(f)));
    }
    out
}

/// The text of `qdot solve`: the accelerations, after the equations.
pub fn solve_text(l: &Lagrange, acc: &[(String, Expr)]) -> String {
    let mut out = derive_text(l);
    out.push_str("\nAccelerations\n");
    for (q, e) in acc {
        out.push_str(&format!("  {} = {}\n", pretty_name(q, 2), u(e)));
    }
    out
}
