//! `qdot check`: the dimension of every name of a scene, declared or
//! found, and of its results (accelerations, generalized forces); and the
//! `dimensions` key every JSON output of an annotated scene carries.

use super::text::padded;
use crate::diag::LineIndex;
use crate::expr::print::pretty_name;
use crate::scene::dimension::{
    Dimension, DimensionReport, DimensionSource, DimensionedName, NamedDimension,
};
use crate::scene::Scene;
use serde_json::{Map, Value};

/// A coordinate's acceleration and generalized force: their dimensions.
struct ResultDimensions {
    acceleration: Option<Dimension>,
    force: Option<Dimension>,
}

fn results(report: &DimensionReport, coordinate: &str) -> ResultDimensions {
    let q = report.of(coordinate);
    let time2 = Dimension::TIME.mul(&Dimension::TIME);
    ResultDimensions {
        acceleration: q.map(|d| d.div(&time2)),
        force: q.map(|d| Dimension::ENERGY.div(d)),
    }
}

fn kind_title(kind: DimensionedName) -> &'static str {
    match kind {
        DimensionedName::Coordinate => "coordinates",
        DimensionedName::Parameter => "parameters",
        DimensionedName::Function => "functions",
        DimensionedName::Unknown => "solve unknowns",
        DimensionedName::Definition => "definitions",
    }
}

fn source_text(lines: &LineIndex, n: &NamedDimension) -> String {
    match &n.source {
        DimensionSource::Declared(written) if *written != n.text() => {
            format!("declared as {written}")
        }
        DimensionSource::Declared(_) => "declared".into(),
        DimensionSource::Inferred(at) => {
            let (line, col) = lines.line_col(at.start);
            format!("found at {line}:{col}")
        }
        DimensionSource::Defined => String::new(),
        DimensionSource::Free => "free".into(),
    }
}

/// The text of `qdot check`.
pub fn check_text(scene: &Scene, report: &DimensionReport) -> String {
    let mut out = String::from("Dimensions\n");
    let lines = LineIndex::new(&scene.source);
    if !scene.dimensions_checked {
        out.push_str("  (no annotation: dimensions are relative to the free ones; annotate one to check every command)\n");
    }
    let names: Vec<String> = report
        .names
        .iter()
        .map(|n| pretty_name(&n.name, 0))
        .collect();
    let width = names.iter().map(|n| n.chars().count()).max().unwrap_or(1);
    let dim_width = report
        .names
        .iter()
        .map(|n| n.text().chars().count())
        .max()
        .unwrap_or(1);
    let kinds = [
        DimensionedName::Coordinate,
        DimensionedName::Parameter,
        DimensionedName::Function,
        DimensionedName::Unknown,
        DimensionedName::Definition,
    ];
    for kind in kinds {
        let mut first = true;
        for (n, shown) in report.names.iter().zip(&names) {
            if n.kind != kind {
                continue;
            }
            let title = if first { kind_title(kind) } else { "" };
            first = false;
            let line = format!(
                "  {}  {}  {}  {}",
                padded(title, 14),
                padded(shown, width),
                padded(&n.text(), dim_width),
                source_text(&lines, n)
            );
            out.push_str(line.trim_end());
            out.push('\n');
        }
    }
    if !scene.coordinates.is_empty() {
        out.push_str("\nResults\n");
        let shown = |d: &Option<Dimension>| match d {
            Some(d) => d.unicode(),
            None => "free".to_string(),
        };
        let mut rows: Vec<(String, String, &str)> = Vec::new();
        for c in &scene.coordinates {
            let r = results(report, &c.name);
            rows.push((pretty_name(&c.name, 2), shown(&r.acceleration), ""));
        }
        for c in &scene.coordinates {
            let r = results(report, &c.name);
            let label = format!("Q_{}", pretty_name(&c.name, 0));
            rows.push((label, shown(&r.force), "  (generalized force)"));
        }
        let width = rows.iter().map(|r| shown_width(&r.0)).max().unwrap_or(1);
        let dim_width = rows.iter().map(|r| shown_width(&r.1)).max().unwrap_or(1);
        for (label, dim, note) in rows {
            let pad = " ".repeat(width - shown_width(&label));
            let line = format!("  {label}{pad}  {}{note}", padded(&dim, dim_width));
            out.push_str(line.trim_end());
            out.push('\n');
        }
    }
    out
}

/// The columns a name takes on a terminal (combining dots take none).
fn shown_width(s: &str) -> usize {
    s.chars()
        .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
        .count()
}

fn ascii(d: Option<&Dimension>) -> Value {
    d.map_or(Value::Null, |d| Value::String(d.ascii()))
}

/// `dimensions`: coordinate, parameter and `solve` unknown → dimension in
/// annotation syntax, or null when the scene leaves it free.
pub fn dimensions_json(report: &DimensionReport) -> Value {
    let mut m = Map::new();
    for n in &report.names {
        if n.kind != DimensionedName::Definition {
            m.insert(n.name.clone(), ascii(n.dimension.as_ref()));
        }
    }
    Value::Object(m)
}

/// The JSON of `qdot check`: `dimensions`, `definitions`, `sources`
/// (name → "declared", "inferred", "defined" or "free"), `accelerations`
/// and `generalized_forces` (coordinate → dimension or null).
pub fn check_json(scene: &Scene, report: &DimensionReport) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("dimensions".into(), dimensions_json(report));
    let mut defs = Map::new();
    let mut sources = Map::new();
    for n in &report.names {
        if n.kind == DimensionedName::Definition {
            defs.insert(n.name.clone(), ascii(n.dimension.as_ref()));
        }
        let s = match n.source {
            DimensionSource::Declared(_) => "declared",
            DimensionSource::Inferred(_) => "inferred",
            DimensionSource::Defined => "defined",
            DimensionSource::Free => "free",
        };
        sources.insert(n.name.clone(), Value::String(s.into()));
    }
    m.insert("definitions".into(), Value::Object(defs));
    m.insert("sources".into(), Value::Object(sources));
    let mut acc = Map::new();
    let mut forces = Map::new();
    for c in &scene.coordinates {
        let r = results(report, &c.name);
        acc.insert(c.name.clone(), ascii(r.acceleration.as_ref()));
        forces.insert(c.name.clone(), ascii(r.force.as_ref()));
    }
    m.insert("accelerations".into(), Value::Object(acc));
    m.insert("generalized_forces".into(), Value::Object(forces));
    m
}
