//! `qdot check`: the dimension of every name of a scene, declared or
//! found, and of its results (accelerations, generalized forces). Its
//! JSON is [`super::wire::CheckJson`].

use super::text::padded;
use crate::diag::LineIndex;
use crate::expr::print::pretty_name;
use crate::scene::dimension::{
    Dimension, DimensionReport, DimensionSource, DimensionedName, NamedDimension,
};
use crate::scene::Scene;

/// A coordinate's acceleration and generalized force: their dimensions.
pub(super) struct ResultDimensions {
    pub(super) acceleration: Option<Dimension>,
    pub(super) force: Option<Dimension>,
}

pub(super) fn results(report: &DimensionReport, coordinate: &str) -> ResultDimensions {
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
