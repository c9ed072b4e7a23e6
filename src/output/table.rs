//! What the numeric studies' tables share: every digit of a double for
//! CSV and JSON, 6 significant digits for reading, columns aligned right,
//! a CSV cell quoted.

/// A value as CSV and JSON print it: every digit of the double.
pub(crate) fn full(x: f64) -> String {
    format!("{x:.17e}")
}

/// `text` as one CSV cell: in double quotes, a `"` doubled.
pub(crate) fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
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
pub(crate) fn short_nonzero(x: f64) -> String {
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
