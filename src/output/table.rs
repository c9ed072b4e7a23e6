//! What the numeric commands' tables share: the one CSV writer (RFC 4180:
//! cells joined by commas, a line per row; a text cell in double quotes,
//! each `"` in it doubled), every digit of a double for CSV and JSON,
//! 6 significant digits for reading, columns aligned right.

/// A CSV table being written: the header, then [`Csv::row`] per row.
#[derive(Clone, Debug, Default)]
pub struct Csv {
    // bytes: a number is written without a UTF-8 check of its own
    out: Vec<u8>,
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

    /// A row of numbers, each as [`full`] writes it; an empty cell for
    /// `None`.
    pub fn number_row(&mut self, cells: impl IntoIterator<Item = Option<f64>>) {
        for (k, c) in cells.into_iter().enumerate() {
            if k > 0 {
                self.out.push(b',');
            }
            if let Some(x) = c {
                write_full(&mut self.out, x);
            }
        }
        self.out.push(b'\n');
    }

    /// Room for `bytes` more bytes (a table's size known in advance).
    pub fn reserve(&mut self, bytes: usize) {
        self.out.reserve(bytes);
    }

    fn line<S: AsRef<str>>(&mut self, cells: impl IntoIterator<Item = S>) {
        for (k, c) in cells.into_iter().enumerate() {
            if k > 0 {
                self.out.push(b',');
            }
            self.out.extend_from_slice(c.as_ref().as_bytes());
        }
        self.out.push(b'\n');
    }

    /// The table's text.
    pub fn finish(self) -> String {
        // every cell came from a str or is ASCII: the check cannot fail
        String::from_utf8(self.out)
            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
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
    let mut s = Vec::with_capacity(25);
    write_full(&mut s, x);
    // ASCII: the check cannot fail
    String::from_utf8(s).unwrap_or_default()
}

/// [`full`]'s text appended to `out`. The 18 significant digits of `{:.17e}`,
/// rounded half to even as Rust's formatter rounds, are computed exactly
/// in 128-bit integers where the double allows it (normal numbers from
/// 2e-15 to 1.7e38: the tables' values), a tenth of the formatter's cost;
/// anything else (0, subnormal, huge, tiny, NaN, ±∞) goes to the
/// formatter itself.
pub fn write_full(out: &mut Vec<u8>, x: f64) {
    let Some((digits, exponent)) = eighteen_digits(x.abs()) else {
        use std::io::Write;
        // writing to a Vec cannot fail
        let _ = write!(out, "{x:.17e}");
        return;
    };
    // sign, d.ddddddddddddddddd, e, exponent: at most 1 + 19 + 1 + 4 bytes
    let mut buf = [0u8; 25];
    let mut len = 0;
    if x.is_sign_negative() {
        buf[0] = b'-';
        len = 1;
    }
    let mut d = [0u8; 18];
    let mut q = digits;
    for pair in (0..9).rev() {
        let two = (q % 100) as usize;
        q /= 100;
        d[2 * pair..2 * pair + 2].copy_from_slice(&PAIRS[2 * two..2 * two + 2]);
    }
    buf[len] = d[0];
    buf[len + 1] = b'.';
    buf[len + 2..len + 19].copy_from_slice(&d[1..]);
    buf[len + 19] = b'e';
    len += 20;
    if exponent < 0 {
        buf[len] = b'-';
        len += 1;
    }
    let e = exponent.unsigned_abs();
    if e >= 100 {
        buf[len] = b'0' + (e / 100) as u8;
        len += 1;
    }
    if e >= 10 {
        buf[len] = b'0' + (e / 10 % 10) as u8;
        len += 1;
    }
    buf[len] = b'0' + (e % 10) as u8;
    len += 1;
    out.extend_from_slice(&buf[..len]);
}

/// "00" to "99", two bytes each.
const PAIRS: [u8; 200] = {
    let mut t = [0u8; 200];
    let mut k = 0;
    while k < 100 {
        t[2 * k] = b'0' + (k / 10) as u8;
        t[2 * k + 1] = b'0' + (k % 10) as u8;
        k += 1;
    }
    t
};

/// 10^17, the smallest number of 18 digits.
const LOW: u128 = 100_000_000_000_000_000;

/// `a` (positive) as q·10^(E − 17) with q of exactly 18 digits, rounded
/// half to even: (q, E). None where it is not a normal double in the
/// range that 128 bits hold exactly: a = m·2^e (m < 2^53), scaled by
/// 10^k = 5^k·2^k with 5^k ≤ 5^32 < 2^75 (a ≥ 2^-49), or divided by 10^j
/// with m·2^e < 2^128 (a < 1.7e38).
fn eighteen_digits(a: f64) -> Option<(u64, i32)> {
    let bits = a.to_bits();
    let biased = (bits >> 52) as i32;
    if biased == 0 || biased >= 0x7ff {
        return None;
    }
    let m = u128::from((bits & ((1 << 52) - 1)) | (1 << 52));
    let e = biased - 1075;
    // a ∈ [2^(e+52), 2^(e+53)): ⌊(e + 52)·log10 2⌋ is ⌊log10 a⌋ or one less
    // (1233/4096 a little below log10 2: the same floor for |e| < 1100, or
    // one less still, which the loop mends)
    let mut exponent = ((e + 52) * 1233) >> 12;
    for _ in 0..3 {
        let (q, half) = scaled(m, e, 17 - exponent)?;
        if q >= 10 * LOW {
            exponent += 1;
            continue;
        }
        if q < LOW {
            exponent -= 1;
            continue;
        }
        let up = match half {
            std::cmp::Ordering::Greater => true,
            std::cmp::Ordering::Equal => q % 2 == 1,
            std::cmp::Ordering::Less => false,
        };
        let q = q + u128::from(up);
        return Some(if q == 10 * LOW {
            (LOW as u64, exponent + 1)
        } else {
            (q as u64, exponent)
        });
    }
    None
}

/// ⌊m·2^e·10^k⌋ and how the remainder compares with one half, exactly;
/// None where 128 bits do not suffice.
fn scaled(m: u128, e: i32, k: i32) -> Option<(u128, std::cmp::Ordering)> {
    use std::cmp::Ordering;
    if k >= 0 {
        let p = m * POW5.get(k as usize)?;
        let s = e + k;
        if s >= 0 {
            // an integer: no remainder
            if 128 - p.leading_zeros() as i32 + s > 127 {
                return None;
            }
            return Some((p << s, Ordering::Less));
        }
        let t = -s;
        if t >= 128 {
            return None;
        }
        let rem = p & ((1u128 << t) - 1);
        Some((p >> t, rem.cmp(&(1u128 << (t - 1)))))
    } else {
        if !(0..=74).contains(&e) {
            return None;
        }
        let n = m << e;
        let d = *POW10.get((-k) as usize)?;
        Some((n / d, (2 * (n % d)).cmp(&d)))
    }
}

/// 5^0 … 5^32 (5^32 < 2^75, so m·5^k < 2^128).
const POW5: [u128; 33] = {
    let mut t = [1u128; 33];
    let mut k = 1;
    while k < 33 {
        t[k] = t[k - 1] * 5;
        k += 1;
    }
    t
};

/// 10^0 … 10^38.
const POW10: [u128; 39] = {
    let mut t = [1u128; 39];
    let mut k = 1;
    while k < 39 {
        t[k] = t[k - 1] * 10;
        k += 1;
    }
    t
};

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
    use proptest::prelude::*;

    /// `write_full` is `{:.17e}`, byte for byte.
    fn same_as_formatter(x: f64) -> Result<(), TestCaseError> {
        let mut ours = b"x,".to_vec();
        write_full(&mut ours, x);
        let want = format!("{x:.17e}");
        prop_assert_eq!(&ours[2..], want.as_bytes(), "bits {:#x}", x.to_bits());
        prop_assert_eq!(full(x), format!("{x:.17e}"));
        Ok(())
    }

    /// A double from its sign, its biased exponent and its mantissa bits.
    fn double(negative: bool, biased: u64, mantissa: u64) -> f64 {
        f64::from_bits((u64::from(negative) << 63) | (biased << 52) | (mantissa & ((1 << 52) - 1)))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 20_000, ..ProptestConfig::default() })]

        #[test]
        fn every_double_prints_as_the_formatter_does(bits in any::<u64>()) {
            // every exponent alike: subnormals, NaNs, ±∞, the huge and the tiny
            same_as_formatter(f64::from_bits(bits))?;
        }

        #[test]
        fn the_fast_range_prints_as_the_formatter_does(
            negative in any::<bool>(),
            // 1e-16 to 1e39: both ends of the exact path and beyond
            biased in 970u64..1155,
            mantissa in any::<u64>(),
        ) {
            same_as_formatter(double(negative, biased, mantissa))?;
        }

        #[test]
        fn integers_and_short_mantissas_print_as_the_formatter_does(
            n in any::<i64>(),
            shift in -80i32..80,
            low_bits in 0u32..64,
        ) {
            // integers, and binary fractions of few bits whose decimal
            // expansion ends within or just past 18 digits (ties)
            let m = if low_bits == 0 { n } else { n >> low_bits };
            same_as_formatter(m as f64 * 2f64.powi(shift))?;
        }
    }

    #[test]
    fn ties_round_half_to_even_as_the_formatter_does() {
        // 2^53 > m·125 ≥ 1e18: 19 digits ending in 5, half way at 18
        for m in [
            8_000_000_000_000_001u64,
            8_000_000_000_000_003,
            9_007_199_254_740_991,
        ] {
            let x = m as f64 / 8.0;
            assert!(eighteen_digits(x).is_some());
            assert_eq!(full(x), format!("{x:.17e}"));
        }
        assert_eq!(full(1e15 + 0.125), "1.00000000000000012e15");
        assert_eq!(full(1e15 + 0.375), "1.00000000000000038e15");
        assert_eq!(full(-(1e15 + 0.625)), "-1.00000000000000062e15");
    }

    #[test]
    fn specials_print_as_the_formatter_does() {
        let specials = [
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            1.0,
            -1.0,
            0.1,
            1e-15,
            1e-16,
            1.7e38,
            1e17,
            1e18,
            9.999_999_999_999_999e17,
            123_456_789_012_345_680_000.0,
        ];
        for x in specials {
            let mut s = Vec::new();
            write_full(&mut s, x);
            assert_eq!(s, format!("{x:.17e}").as_bytes(), "{x:e}");
        }
        assert_eq!(full(-0.0), "-0.00000000000000000e0");
        assert_eq!(full(0.01), "1.00000000000000002e-2");
    }

    #[test]
    fn the_exact_path_covers_the_tables_range() {
        // the formatter is only the fallback: 2e-15 ≤ |x| < 1.7e38, normal
        for x in [
            2e-15,
            7.010424395773538e-4,
            0.5,
            1.0,
            2.5,
            3.25,
            1e17,
            1e18,
            1e38,
        ] {
            assert!(eighteen_digits(x).is_some(), "{x:e}");
        }
        for x in [0.0, 1e-16, 5e-324, 1e39, f64::INFINITY, f64::NAN] {
            assert!(eighteen_digits(x).is_none(), "{x:e}");
        }
    }

    #[test]
    fn a_table_is_rfc_4180() {
        let mut t = Csv::new(["t", "x'", "a,b"]);
        t.row([full(0.5), String::new(), quoted("say \"hi\", twice")]);
        assert_eq!(
            t.finish(),
            "t,x',\"a,b\"\n5.00000000000000000e-1,,\"say \"\"hi\"\", twice\"\n"
        );
        let mut t = Csv::new(["Omega", "amp_x"]);
        t.number_row([Some(0.01), None]);
        t.number_row([Some(-2.5), Some(1e-300)]);
        assert_eq!(
            t.finish(),
            "Omega,amp_x\n1.00000000000000002e-2,\n-2.50000000000000000e0,1.00000000000000003e-300\n"
        );
    }
}
