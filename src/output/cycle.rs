//! `qdot cycle`'s table ([`crate::app::CycleRun`]) as CSV, JSON or an
//! aligned text table.

use super::table::{full, quoted, right_aligned, short_nonzero};
use crate::app::CycleRun;
use crate::cycle::CycleTable;

/// The table as CSV: the columns, then a `note` column (empty unless the
/// position is special, every note joined by "; "); an undetermined
/// value is an empty cell. A stick position is two lines, the reactions
/// at its two limits of sliding (the one that continues the previous
/// line first), each note saying which.
pub fn csv(table: &CycleTable) -> String {
    let table = &table.stick_rows_split();
    let mut out = unique_columns(table).join(",");
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
            out.push_str(&quoted(note));
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

/// `qdot cycle`'s text: the `--columns` asked for, else the reactions
/// (every joint's components, every drive and friction force) against
/// the varied quantity; see [`text`].
pub fn reading(run: &CycleRun) -> String {
    let table = &run.table;
    let reactions: Vec<String> = table
        .columns
        .iter()
        .skip(1 + 3 * table.coordinates)
        .cloned()
        .collect();
    let chosen = match &run.shown {
        Some(shown) => std::borrow::Cow::Borrowed(shown),
        // a table with no reaction column shows all it has
        None if reactions.is_empty() => std::borrow::Cow::Borrowed(table),
        None => match table.select(&reactions) {
            Ok(t) => std::borrow::Cow::Owned(t),
            Err(_) => std::borrow::Cow::Borrowed(table),
        },
    };
    aligned(&chosen, table, run.degrees)
}

/// The table for reading: aligned columns, the varied angle in degrees
/// (when `degrees`), notes below the table. A stick position is two
/// lines, the reactions at its two limits of sliding, its note saying
/// which is which. Each value prints with 6 significant digits; rounding
/// noise prints as 0: below 1e-12 of the largest value of its kind
/// (positions, velocities, accelerations, reactions), so that no unit
/// makes a small value vanish.
pub fn text(table: &CycleTable, degrees: bool) -> String {
    aligned(table, table, degrees)
}

/// [`text`] of `shown`, a selection of `full`'s columns, its scales read
/// from `full`.
fn aligned(shown: &CycleTable, full: &CycleTable, degrees: bool) -> String {
    let mut header: Vec<String> = unique_columns(shown);
    if degrees {
        header[0] = format!("{} (deg)", shown.columns[0]);
    }
    let mut cells: Vec<Vec<String>> = vec![header];
    let mut notes = Vec::new();
    let split = shown.stick_rows_split();
    let noise = column_noise(&split, full);
    let cell = |k: usize, v: &Option<f64>| match v {
        Some(x) if k == 0 && degrees => format!("{:.6}", x.to_degrees())
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string(),
        Some(x) if x.abs() < noise[k] => "0".into(),
        Some(x) => short_nonzero(*x),
        None => "—".to_string(),
    };
    let mut lines = split.rows.iter();
    for (i, row) in shown.rows.iter().enumerate() {
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

/// The columns' names, the varied one renamed `NAME (varied)` where a
/// coordinate's column has its name (a driven coordinate varied: both
/// hold the same values).
fn unique_columns(table: &CycleTable) -> Vec<String> {
    let mut names = table.columns.clone();
    if names.iter().skip(1).any(|c| *c == names[0]) {
        names[0] = format!("{} (varied)", names[0]);
    }
    names
}

/// Per column of `shown` (a selection of `full`'s), the size below which
/// a value is rounding noise: 1e-12 of the largest value of its kind in
/// `full` (see [`text`]).
fn column_noise(shown: &CycleTable, full: &CycleTable) -> Vec<f64> {
    let n = full.coordinates.max(1);
    // the kind of a column of `full`: positions, velocities,
    // accelerations, reactions (the varied one apart)
    let kind = |k: usize| if k == 0 { 0 } else { ((k - 1) / n).min(3) + 1 };
    let mut of_kind = [0.0f64; 5];
    for r in &full.rows {
        let sides = [
            Some(&r.values),
            r.limits.as_ref().map(|l| &l.minus),
            r.limits.as_ref().map(|l| &l.plus),
        ];
        for values in sides.into_iter().flatten() {
            for (k, v) in values.iter().enumerate() {
                if let Some(x) = v.filter(|x| x.is_finite()) {
                    of_kind[kind(k)] = of_kind[kind(k)].max(x.abs());
                }
            }
        }
    }
    (0..shown.columns.len())
        .map(|k| {
            if k == 0 {
                return 1e-12 * of_kind[0];
            }
            let in_full = full
                .columns
                .iter()
                .skip(1)
                .position(|c| *c == shown.columns[k])
                .map_or(3 * n + 1, |j| j + 1);
            1e-12 * of_kind[kind(in_full)]
        })
        .collect()
}
