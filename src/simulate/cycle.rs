//! `qdot cycle`: a mechanism analysed over its cycle (the engine is
//! [`crate::cycle`]), and the table rendered as CSV, JSON or an aligned
//! text table.

use crate::cycle::{CycleRequest, CycleTable};
use crate::diag::Diagnostic;
use crate::scene::Scene;

/// A mechanism's cycle, with how to show its varied quantity.
pub struct CycleRun {
    /// The table.
    pub table: CycleTable,
    /// Whether the varied quantity is an angle (shown in degrees; its
    /// column holds radians).
    pub degrees: bool,
}

/// Read the scene `src` and analyse its mechanism as `req` asks.
pub fn run(src: &str, req: &CycleRequest) -> Result<CycleRun, Diagnostic> {
    let scene = Scene::parse(src)?;
    let table = crate::cycle::cycle(&scene, req)?;
    Ok(CycleRun {
        degrees: is_angle(&scene, &req.over.name),
        table,
    })
}

/// Whether the coordinate `name` is an angle: annotated `angle`, or a
/// body's angle in the plane.
fn is_angle(scene: &Scene, name: &str) -> bool {
    let Some(c) = scene.coordinates.iter().find(|c| c.name == name) else {
        return false;
    };
    if let Some(d) = &c.dimension {
        return d.trim() == "angle" || d.trim() == "rad";
    }
    let q = crate::expr::Expr::coord(name, 0);
    scene.bodies.iter().any(|b| {
        matches!(&b.mass_properties.turning,
            Some(crate::scene::Turning::Plane { angle, .. }) if angle.equals(&q))
    })
}

/// The table with only the columns `names` (comma-separated) after the
/// varied one, in the order given (`--columns O_x,O_y,M`).
pub fn select(table: &CycleTable, names: &str) -> Result<CycleTable, Diagnostic> {
    let mut keep = vec![0];
    for name in names.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        let Some(k) = table.columns.iter().skip(1).position(|c| c == name) else {
            return Err(Diagnostic::global(format!(
                "`--columns {name}`: the table has no column `{name}`"
            ))
            .with_hint(format!("the columns are {}", table.columns[1..].join(", ")))
            .with_kind(crate::diag::ErrorKind::bad_option("--columns")));
        };
        keep.push(k + 1);
    }
    let mut out = table.clone();
    out.columns = keep.iter().map(|&k| table.columns[k].clone()).collect();
    for row in &mut out.rows {
        row.values = keep.iter().map(|&k| row.values[k]).collect();
    }
    Ok(out)
}

/// A value as CSV and JSON print it: every digit of the double.
fn full(x: f64) -> String {
    format!("{x:.17e}")
}

/// The table as CSV: the columns, then a `note` column (empty unless the
/// position is special); an undetermined value is an empty cell.
pub fn csv(table: &CycleTable) -> String {
    let mut out = table.columns.join(",");
    out.push_str(",note\n");
    for row in &table.rows {
        let cells: Vec<String> = row
            .values
            .iter()
            .map(|v| v.map(full).unwrap_or_default())
            .collect();
        out.push_str(&cells.join(","));
        out.push(',');
        if let Some(note) = &row.note {
            out.push('"');
            out.push_str(&note.replace('"', "\"\""));
            out.push('"');
        }
        out.push('\n');
    }
    out
}

/// `cycle --output json`: the table, with null where a value is not
/// determined.
#[derive(serde::Serialize)]
pub struct CycleJson<'a> {
    /// The varied quantity: `t` or a driven coordinate.
    pub varied: &'a str,
    /// Every column's name (see [`CycleTable::columns`]).
    pub columns: &'a [String],
    /// One row per position.
    pub rows: Vec<Vec<Option<f64>>>,
    /// Per row, what is special about the position, or null.
    pub notes: Vec<Option<&'a str>>,
    /// Per row, the iterations the friction needed.
    pub iterations: Vec<u32>,
}

/// The table as JSON (one line): [`CycleJson`].
pub fn json(table: &CycleTable) -> String {
    let wire = CycleJson {
        varied: &table.varied,
        columns: &table.columns,
        rows: table.rows.iter().map(|r| r.values.clone()).collect(),
        notes: table.rows.iter().map(|r| r.note.as_deref()).collect(),
        iterations: table.rows.iter().map(|r| r.iterations).collect(),
    };
    serde_json::to_string(&wire).unwrap_or_default()
}

/// The table for reading: 6 significant digits in aligned columns, the
/// varied angle in degrees (when `degrees`), notes below the table.
pub fn text(table: &CycleTable, degrees: bool) -> String {
    let mut header: Vec<String> = table.columns.clone();
    if degrees {
        header[0] = format!("{} (deg)", header[0]);
    }
    let mut cells: Vec<Vec<String>> = vec![header];
    let mut notes = Vec::new();
    for (i, row) in table.rows.iter().enumerate() {
        let mut line: Vec<String> = row
            .values
            .iter()
            .enumerate()
            .map(|(k, v)| match v {
                Some(x) if k == 0 && degrees => format!("{:.6}", x.to_degrees())
                    .trim_end_matches('0')
                    .trim_end_matches('.')
                    .to_string(),
                Some(x) => short(*x),
                None => "—".to_string(),
            })
            .collect();
        if let Some(note) = &row.note {
            line[0].push_str(&format!(" [{}]", notes.len() + 1));
            notes.push(format!("[{}] row {}: {note}", notes.len() + 1, i + 1));
        }
        cells.push(line);
    }
    let mut out = right_aligned(&cells);
    for n in notes {
        out.push_str(&n);
        out.push('\n');
    }
    out
}

/// Rows of cells as columns aligned right, two spaces apart.
pub(crate) fn right_aligned(cells: &[Vec<String>]) -> String {
    let columns = cells.first().map_or(0, Vec::len);
    let widths: Vec<usize> = (0..columns)
        .map(|k| {
            cells
                .iter()
                .map(|r| r[k].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    for r in cells {
        let padded: Vec<String> = r
            .iter()
            .zip(&widths)
            .map(|(c, &w)| format!("{c:>w$}"))
            .collect();
        out.push_str(padded.join("  ").trim_end());
        out.push('\n');
    }
    out
}

/// 6 significant digits, without trailing zeros; 0 for what rounds to 0
/// at 1e-12 of the unit.
pub(crate) fn short(x: f64) -> String {
    if x.abs() < 1e-12 {
        return "0".into();
    }
    let s = format!("{:.5e}", x);
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    let e: i32 = e.parse().unwrap_or(0);
    if (-4..6).contains(&e) {
        let decimals = (5 - e).max(0) as usize;
        let f = format!("{x:.decimals$}");
        if f.contains('.') {
            return f.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        return f;
    }
    let m = m.trim_end_matches('0').trim_end_matches('.');
    format!("{m}e{e}")
}
