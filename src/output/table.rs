//! The one CSV writer of the numeric commands' tables (RFC 4180: cells
//! joined by commas, a line per row; a text cell in double quotes, each
//! `"` in it doubled).

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
