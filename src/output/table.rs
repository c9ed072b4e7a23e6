//! What the numeric commands' tables share: the one CSV writer (RFC 4180:
//! cells joined by commas, a line per row; a text cell in double quotes,
//! each `"` in it doubled), every digit of a double for CSV and JSON,
//! 6 significant digits for reading, columns aligned right.

/// A CSV table being written: the header, then [`Csv::row`] per row.
#[derive(Clone, Debug, Default)]
pub struct Csv {
    out: String,
}

impl Csv {
    /// A table with these column names (a name with a comma, a quote or a
    /// line break is quoted; qdot's names have none).
    pub fn new<S: AsRef<str>>(header: impl IntoIterator<Item = S>) -> Csv {
        let mut csv = Csv::default();
        csv.line(header.into_iter().map(|name| {
            let name = name.as_ref();
            if name.contains([',', '"', '\n', '\r']) {
                quoted(name)
            } else {
                name.to_string()
            }
        }));
        csv
    }

    /// A row of cells already written ([`full`], [`quoted`], …).
    pub fn row<S: AsRef<str>>(&mut self, cells: impl IntoIterator<Item = S>) {
        self.line(cells);
    }

    fn line<S: AsRef<str>>(&mut self, cells: impl IntoIterator<Item = S>) {
        for (k, c) in cells.into_iter().enumerate() {
            if k > 0 {
                self.out.push(',');
            }
            self.out.push_str(c.as_ref());
        }
        self.out.push('\n');
    }

    /// The table's text.
    pub fn finish(self) -> String {
        self.out
    }
}

/// A text cell: in double quotes, each `"` doubled (RFC 4180), so that a
/// message with commas or quotes reads back as it was.
pub fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// A number with every digit of the double (`{:.17e}`): what the CSV and
/// JSON of the numeric commands print, read back bit for bit.
pub fn full(x: f64) -> String {
    format!("{x:.17e}")
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_is_rfc_4180() {
        let mut t = Csv::new(["t", "x'", "a,b"]);
        t.row([full(0.5), String::new(), quoted("say \"hi\", twice")]);
        assert_eq!(
            t.finish(),
            "t,x',\"a,b\"\n5.00000000000000000e-1,,\"say \"\"hi\"\", twice\"\n"
        );
    }
}
