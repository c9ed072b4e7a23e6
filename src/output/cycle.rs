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
/// which is which. Each column prints with fixed decimals: 5 significant
/// digits of its largest value, and no finer than 6 of the largest of its
/// kind (positions, velocities, accelerations, reactions), since a
/// regular position's values are certain only to about 1e-6 of that
/// scale (Newton's method to 1e-12, the constraint Jacobian's pivot ratio
/// above 1e-6); a value below that resolution prints as 0.
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
    let decimals = column_decimals(&split, full);
    let cell = |k: usize, v: &Option<f64>| match v {
        Some(x) if k == 0 && degrees => format!("{:.6}", x.to_degrees())
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string(),
        Some(x) if k == 0 => short_nonzero(*x),
        Some(x) if x.is_finite() => fixed(*x, decimals[k]),
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

/// Per column of `shown` (a selection of `full`'s), the decimals it
/// prints with: see [`text`]. The varied column's entry is unused.
fn column_decimals(shown: &CycleTable, full: &CycleTable) -> Vec<usize> {
    let n = full.coordinates.max(1);
    // the kind of a column of `full`: positions, velocities,
    // accelerations, reactions (the varied one apart)
    let kind = |k: usize| if k == 0 { 0 } else { ((k - 1) / n).min(3) + 1 };
    let largest = |values: &mut dyn Iterator<Item = f64>| {
        values
            .filter(|x| x.is_finite())
            .fold(0.0f64, |m, x| m.max(x.abs()))
    };
    let mut of_kind = [0.0f64; 5];
    for (k, m) in of_kind.iter_mut().enumerate() {
        *m = largest(&mut full.rows.iter().flat_map(|r| {
            let mut all: Vec<f64> = Vec::new();
            let mut push = |vs: &[Option<f64>]| {
                all.extend(
                    vs.iter()
                        .enumerate()
                        .filter(|(j, _)| kind(*j) == k)
                        .filter_map(|(_, v)| *v),
                )
            };
            push(&r.values);
            if let Some(l) = &r.limits {
                push(&l.minus);
                push(&l.plus);
            }
            all
        }));
    }
    (0..shown.columns.len())
        .map(|k| {
            if k == 0 {
                return 0;
            }
            let name = &shown.columns[k];
            let in_full = full
                .columns
                .iter()
                .skip(1)
                .position(|c| c == name)
                .map_or(3 * n + 1, |j| j + 1);
            let column = largest(&mut shown.rows.iter().filter_map(|r| r.values[k]));
            let scale = of_kind[kind(in_full)];
            // the resolution: 5 digits of the column, 6 of its kind
            let exponent = |x: f64| (x > 0.0).then(|| x.log10().floor() as i32);
            let finest = [
                exponent(column).map(|e| e - 4),
                exponent(scale).map(|e| e - 5),
            ]
            .into_iter()
            .flatten()
            .max();
            let Some(finest) = finest else { return 0 };
            (-finest).clamp(0, 17) as usize
        })
        .collect()
}

/// `x` with `decimals` decimals, a value that rounds to zero as 0 (never
/// −0).
fn fixed(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        format!("{:.decimals$}", 0.0)
    } else {
        s
    }
}
