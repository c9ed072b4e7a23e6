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
        if let Some(l) = row.limits.as_mut() {
            l.minus = keep.iter().map(|&k| l.minus[k]).collect();
            l.plus = keep.iter().map(|&k| l.plus[k]).collect();
        }
    }
    Ok(out)
}

/// A value as CSV and JSON print it: every digit of the double.
fn full(x: f64) -> String {
    format!("{x:.17e}")
}

/// The table as CSV: the columns, then a `note` column (empty unless the
/// position is special, every note joined by "; "); an undetermined
/// value is an empty cell. A stick position is two lines, the reactions
/// at its two limits of sliding (the one that continues the previous
/// line first), each note saying which.
pub fn csv(table: &CycleTable) -> String {
    let table = &table.stick_rows_split();
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
    /// Per row, what is special about the position (every note, joined
    /// by "; "), or null.
    pub notes: Vec<Option<&'a str>>,
    /// Per row, the linear systems the friction needed (its cases of the
    /// normal forces' signs, and Newton's steps for pins).
    pub iterations: Vec<u32>,
    /// Per row, null, or at a stick (a friction whose relative velocity
    /// vanishes, its force anywhere between its values for sliding either
    /// way) the row's values at both limits: [`LimitsJson`].
    pub limits: Vec<Option<LimitsJson<'a>>>,
}

/// A stick row's values (every column, as `rows`) at its two limits of
/// sliding.
#[derive(serde::Serialize)]
pub struct LimitsJson<'a> {
    /// The joint whose relative velocity vanishes.
    pub joint: &'a str,
    /// The limit v_rel → 0⁻.
    pub minus: &'a [Option<f64>],
    /// The limit v_rel → 0⁺.
    pub plus: &'a [Option<f64>],
}

/// The table as JSON (one line): [`CycleJson`].
pub fn json(table: &CycleTable) -> String {
    let wire = CycleJson {
        varied: &table.varied,
        columns: &table.columns,
        rows: table.rows.iter().map(|r| r.values.clone()).collect(),
        notes: table.rows.iter().map(|r| r.note.as_deref()).collect(),
        iterations: table.rows.iter().map(|r| r.iterations).collect(),
        limits: table
            .rows
            .iter()
            .map(|r| {
                r.limits.as_ref().map(|l| LimitsJson {
                    joint: &l.joint,
                    minus: &l.minus,
                    plus: &l.plus,
                })
            })
            .collect(),
    };
    serde_json::to_string(&wire).unwrap_or_default()
}

/// The table for reading: 6 significant digits in aligned columns, the
/// varied angle in degrees (when `degrees`), notes below the table. A
/// stick position is two lines, the reactions at its two limits of
/// sliding, its note saying which is which.
pub fn text(table: &CycleTable, degrees: bool) -> String {
    let mut header: Vec<String> = table.columns.clone();
    if degrees {
        header[0] = format!("{} (deg)", header[0]);
    }
    let mut cells: Vec<Vec<String>> = vec![header];
    let mut notes = Vec::new();
    let split = table.stick_rows_split();
    // rounding noise prints as 0: below 1e-12 of the largest value of its
    // group (positions, velocities, accelerations, reactions), so that
    // no unit makes a small value vanish
    let n = table.coordinates;
    let group = |k: usize| {
        if k == 0 {
            0
        } else {
            ((k - 1) / n.max(1)).min(3) + 1
        }
    };
    let mut largest = [0.0f64; 5];
    for row in &split.rows {
        for (k, v) in row.values.iter().enumerate() {
            if let Some(x) = v.filter(|x| x.is_finite()) {
                largest[group(k)] = largest[group(k)].max(x.abs());
            }
        }
    }
    let cell = |k: usize, v: &Option<f64>| match v {
        Some(x) if k == 0 && degrees => format!("{:.6}", x.to_degrees())
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string(),
        Some(x) if x.abs() < 1e-12 * largest[group(k)] => "0".into(),
        Some(x) => short_nonzero(*x),
        None => "—".to_string(),
    };
    let mut lines = split.rows.iter();
    for (i, row) in table.rows.iter().enumerate() {
        let sides = if row.limits.is_some() { 2 } else { 1 };
        let mut said = Vec::new();
        for _ in 0..sides {
            let Some(line) = lines.next() else { break };
            said.push(line.note.clone());
            let mut line: Vec<String> = line
                .values
                .iter()
                .enumerate()
                .map(|(k, v)| cell(k, v))
                .collect();
            if row.note.is_some() {
                line[0].push_str(&format!(" [{}]", notes.len() + 1));
            }
            cells.push(line);
        }
        if let Some(note) = &row.note {
            let which = if sides == 2 {
                let side = |n: &Option<String>| {
                    if n.as_deref().is_some_and(|n| n.ends_with("v → 0⁻")) {
                        "v → 0⁻"
                    } else {
                        "v → 0⁺"
                    }
                };
                format!(
                    " (the first line the limit {}, the second {})",
                    side(&said[0]),
                    side(&said[1])
                )
            } else {
                String::new()
            };
            notes.push(format!(
                "[{}] row {}: {note}{which}",
                notes.len() + 1,
                i + 1
            ));
        }
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
    short_nonzero(x)
}

/// 6 significant digits, without trailing zeros.
fn short_nonzero(x: f64) -> String {
    if x == 0.0 {
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
