//! Characters a reader can't see, or can't tell from ASCII: their code
//! points, Unicode names and kinds. Below every other layer, because the
//! lexer's messages and the diagnostics' source lines both need it.

/// What a character is, for a message.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CharKind {
    /// Takes no room on screen.
    Invisible,
    /// Reorders the display of the line (bidirectional controls).
    Bidi,
    /// A C0/C1 control character.
    Control,
    /// Drawn like the given ASCII character.
    Like(char),
}

/// The characters named in messages: code point, Unicode name, kind.
const TABLE: &[(char, &str, CharKind)] = &[
    ('\u{00AD}', "SOFT HYPHEN", CharKind::Invisible),
    ('\u{02B9}', "MODIFIER LETTER PRIME", CharKind::Like('\'')),
    (
        '\u{02BC}',
        "MODIFIER LETTER APOSTROPHE",
        CharKind::Like('\''),
    ),
    (
        '\u{02C8}',
        "MODIFIER LETTER VERTICAL LINE",
        CharKind::Like('\''),
    ),
    ('\u{034F}', "COMBINING GRAPHEME JOINER", CharKind::Invisible),
    ('\u{037E}', "GREEK QUESTION MARK", CharKind::Like(';')),
    (
        '\u{0391}',
        "GREEK CAPITAL LETTER ALPHA",
        CharKind::Like('A'),
    ),
    ('\u{0392}', "GREEK CAPITAL LETTER BETA", CharKind::Like('B')),
    (
        '\u{0395}',
        "GREEK CAPITAL LETTER EPSILON",
        CharKind::Like('E'),
    ),
    ('\u{0396}', "GREEK CAPITAL LETTER ZETA", CharKind::Like('Z')),
    ('\u{0397}', "GREEK CAPITAL LETTER ETA", CharKind::Like('H')),
    ('\u{0399}', "GREEK CAPITAL LETTER IOTA", CharKind::Like('I')),
    (
        '\u{039A}',
        "GREEK CAPITAL LETTER KAPPA",
        CharKind::Like('K'),
    ),
    ('\u{039C}', "GREEK CAPITAL LETTER MU", CharKind::Like('M')),
    ('\u{039D}', "GREEK CAPITAL LETTER NU", CharKind::Like('N')),
    (
        '\u{039F}',
        "GREEK CAPITAL LETTER OMICRON",
        CharKind::Like('O'),
    ),
    ('\u{03A1}', "GREEK CAPITAL LETTER RHO", CharKind::Like('P')),
    ('\u{03A4}', "GREEK CAPITAL LETTER TAU", CharKind::Like('T')),
    (
        '\u{03A5}',
        "GREEK CAPITAL LETTER UPSILON",
        CharKind::Like('Y'),
    ),
    ('\u{03A7}', "GREEK CAPITAL LETTER CHI", CharKind::Like('X')),
    (
        '\u{03BF}',
        "GREEK SMALL LETTER OMICRON",
        CharKind::Like('o'),
    ),
    (
        '\u{0405}',
        "CYRILLIC CAPITAL LETTER DZE",
        CharKind::Like('S'),
    ),
    (
        '\u{0406}',
        "CYRILLIC CAPITAL LETTER BYELORUSSIAN-UKRAINIAN I",
        CharKind::Like('I'),
    ),
    (
        '\u{0408}',
        "CYRILLIC CAPITAL LETTER JE",
        CharKind::Like('J'),
    ),
    ('\u{0410}', "CYRILLIC CAPITAL LETTER A", CharKind::Like('A')),
    (
        '\u{0412}',
        "CYRILLIC CAPITAL LETTER VE",
        CharKind::Like('B'),
    ),
    (
        '\u{0415}',
        "CYRILLIC CAPITAL LETTER IE",
        CharKind::Like('E'),
    ),
    (
        '\u{041A}',
        "CYRILLIC CAPITAL LETTER KA",
        CharKind::Like('K'),
    ),
    (
        '\u{041C}',
        "CYRILLIC CAPITAL LETTER EM",
        CharKind::Like('M'),
    ),
    (
        '\u{041D}',
        "CYRILLIC CAPITAL LETTER EN",
        CharKind::Like('H'),
    ),
    ('\u{041E}', "CYRILLIC CAPITAL LETTER O", CharKind::Like('O')),
    (
        '\u{0420}',
        "CYRILLIC CAPITAL LETTER ER",
        CharKind::Like('P'),
    ),
    (
        '\u{0421}',
        "CYRILLIC CAPITAL LETTER ES",
        CharKind::Like('C'),
    ),
    (
        '\u{0422}',
        "CYRILLIC CAPITAL LETTER TE",
        CharKind::Like('T'),
    ),
    ('\u{0423}', "CYRILLIC CAPITAL LETTER U", CharKind::Like('Y')),
    (
        '\u{0425}',
        "CYRILLIC CAPITAL LETTER HA",
        CharKind::Like('X'),
    ),
    ('\u{0430}', "CYRILLIC SMALL LETTER A", CharKind::Like('a')),
    ('\u{0435}', "CYRILLIC SMALL LETTER IE", CharKind::Like('e')),
    ('\u{043E}', "CYRILLIC SMALL LETTER O", CharKind::Like('o')),
    ('\u{0440}', "CYRILLIC SMALL LETTER ER", CharKind::Like('p')),
    ('\u{0441}', "CYRILLIC SMALL LETTER ES", CharKind::Like('c')),
    ('\u{0443}', "CYRILLIC SMALL LETTER U", CharKind::Like('y')),
    ('\u{0445}', "CYRILLIC SMALL LETTER HA", CharKind::Like('x')),
    ('\u{0455}', "CYRILLIC SMALL LETTER DZE", CharKind::Like('s')),
    (
        '\u{0456}',
        "CYRILLIC SMALL LETTER BYELORUSSIAN-UKRAINIAN I",
        CharKind::Like('i'),
    ),
    ('\u{0458}', "CYRILLIC SMALL LETTER JE", CharKind::Like('j')),
    (
        '\u{04BB}',
        "CYRILLIC SMALL LETTER SHHA",
        CharKind::Like('h'),
    ),
    (
        '\u{04CF}',
        "CYRILLIC SMALL LETTER PALOCHKA",
        CharKind::Like('l'),
    ),
    (
        '\u{0501}',
        "CYRILLIC SMALL LETTER KOMI DE",
        CharKind::Like('d'),
    ),
    ('\u{051B}', "CYRILLIC SMALL LETTER QA", CharKind::Like('q')),
    ('\u{051D}', "CYRILLIC SMALL LETTER WE", CharKind::Like('w')),
    ('\u{0589}', "ARMENIAN FULL STOP", CharKind::Like(':')),
    ('\u{061C}', "ARABIC LETTER MARK", CharKind::Bidi),
    ('\u{180E}', "MONGOLIAN VOWEL SEPARATOR", CharKind::Invisible),
    ('\u{200B}', "ZERO WIDTH SPACE", CharKind::Invisible),
    ('\u{200C}', "ZERO WIDTH NON-JOINER", CharKind::Invisible),
    ('\u{200D}', "ZERO WIDTH JOINER", CharKind::Invisible),
    ('\u{200E}', "LEFT-TO-RIGHT MARK", CharKind::Bidi),
    ('\u{200F}', "RIGHT-TO-LEFT MARK", CharKind::Bidi),
    ('\u{2010}', "HYPHEN", CharKind::Like('-')),
    ('\u{2011}', "NON-BREAKING HYPHEN", CharKind::Like('-')),
    ('\u{2012}', "FIGURE DASH", CharKind::Like('-')),
    (
        '\u{2018}',
        "LEFT SINGLE QUOTATION MARK",
        CharKind::Like('\''),
    ),
    (
        '\u{201C}',
        "LEFT DOUBLE QUOTATION MARK",
        CharKind::Like('"'),
    ),
    (
        '\u{201D}',
        "RIGHT DOUBLE QUOTATION MARK",
        CharKind::Like('"'),
    ),
    ('\u{2024}', "ONE DOT LEADER", CharKind::Like('.')),
    ('\u{202A}', "LEFT-TO-RIGHT EMBEDDING", CharKind::Bidi),
    ('\u{202B}', "RIGHT-TO-LEFT EMBEDDING", CharKind::Bidi),
    ('\u{202C}', "POP DIRECTIONAL FORMATTING", CharKind::Bidi),
    ('\u{202D}', "LEFT-TO-RIGHT OVERRIDE", CharKind::Bidi),
    ('\u{202E}', "RIGHT-TO-LEFT OVERRIDE", CharKind::Bidi),
    ('\u{2044}', "FRACTION SLASH", CharKind::Like('/')),
    ('\u{2060}', "WORD JOINER", CharKind::Invisible),
    ('\u{2061}', "FUNCTION APPLICATION", CharKind::Invisible),
    ('\u{2062}', "INVISIBLE TIMES", CharKind::Invisible),
    ('\u{2063}', "INVISIBLE SEPARATOR", CharKind::Invisible),
    ('\u{2064}', "INVISIBLE PLUS", CharKind::Invisible),
    ('\u{2066}', "LEFT-TO-RIGHT ISOLATE", CharKind::Bidi),
    ('\u{2067}', "RIGHT-TO-LEFT ISOLATE", CharKind::Bidi),
    ('\u{2068}', "FIRST STRONG ISOLATE", CharKind::Bidi),
    ('\u{2069}', "POP DIRECTIONAL ISOLATE", CharKind::Bidi),
    ('\u{2217}', "ASTERISK OPERATOR", CharKind::Like('*')),
    ('\u{2236}', "RATIO", CharKind::Like(':')),
    ('\u{FE63}', "SMALL HYPHEN-MINUS", CharKind::Like('-')),
    (
        '\u{FFF9}',
        "INTERLINEAR ANNOTATION ANCHOR",
        CharKind::Invisible,
    ),
    (
        '\u{FFFA}',
        "INTERLINEAR ANNOTATION SEPARATOR",
        CharKind::Invisible,
    ),
    (
        '\u{FFFB}',
        "INTERLINEAR ANNOTATION TERMINATOR",
        CharKind::Invisible,
    ),
];

/// Names of the control characters most often met in text.
const CONTROLS: &[(char, &str)] = &[
    ('\u{0}', "NULL"),
    ('\u{7}', "BELL"),
    ('\u{8}', "BACKSPACE"),
    ('\u{1B}', "ESCAPE"),
    ('\u{7F}', "DELETE"),
    ('\u{85}', "NEXT LINE"),
];

/// `U+200B`.
pub fn code_point(c: char) -> String {
    format!("U+{:04X}", u32::from(c))
}

/// The name and kind of `c`, if messages single it out; names outside the
/// table are built for whole blocks (fullwidth forms, mathematical letters
/// and digits) or are a description in lower case.
pub fn lookup(c: char) -> Option<(String, CharKind)> {
    if let Ok(k) = TABLE.binary_search_by_key(&c, |&(t, _, _)| t) {
        let (_, name, kind) = TABLE[k];
        return Some((name.to_string(), kind));
    }
    let u = u32::from(c);
    if c.is_control() {
        let name = CONTROLS
            .iter()
            .find(|&&(t, _)| t == c)
            .map_or("a control character", |&(_, n)| n);
        return Some((name.to_string(), CharKind::Control));
    }
    // fullwidth ASCII: U+FF01..U+FF5E are U+0021..U+007E shifted
    if (0xFF01..=0xFF5E).contains(&u) {
        let a = char::from_u32(u - 0xFEE0)?;
        let name = if a.is_ascii_uppercase() {
            format!("FULLWIDTH LATIN CAPITAL LETTER {a}")
        } else if a.is_ascii_lowercase() {
            format!("FULLWIDTH LATIN SMALL LETTER {}", a.to_ascii_uppercase())
        } else if a.is_ascii_digit() {
            format!("FULLWIDTH DIGIT {a}")
        } else {
            "a fullwidth form".to_string()
        };
        return Some((name, CharKind::Like(a)));
    }
    // mathematical alphanumeric symbols: 13 alphabets of A–Z a–z, then
    // 5 of the digits 0–9
    if (0x1D400..=0x1D6A3).contains(&u) {
        let k = ((u - 0x1D400) % 52) as u8;
        let a = if k < 26 { b'A' + k } else { b'a' + k - 26 };
        return Some((
            "a mathematical letter".into(),
            CharKind::Like(char::from(a)),
        ));
    }
    if (0x1D7CE..=0x1D7FF).contains(&u) {
        let a = char::from(b'0' + ((u - 0x1D7CE) % 10) as u8);
        return Some(("a mathematical digit".into(), CharKind::Like(a)));
    }
    let description = match u {
        0x0300..=0x036F => "a combining mark",
        0xFE00..=0xFE0F | 0xE0100..=0xE01EF => "a variation selector",
        0xE0000..=0xE007F => "a tag character",
        0x206A..=0x206F => "a deprecated format character",
        0xFEFF => "ZERO WIDTH NO-BREAK SPACE",
        _ => return None,
    };
    Some((description.to_string(), CharKind::Invisible))
}

/// Can't `c` be seen, or does it reorder the display of its line? (A tab
/// shows as white space, and the `\r` of a CRLF line end as nothing.)
pub fn is_hidden(c: char) -> bool {
    if c.is_ascii() {
        return c.is_ascii_control() && c != '\t' && c != '\r';
    }
    matches!(
        lookup(c),
        Some((_, CharKind::Invisible | CharKind::Bidi | CharKind::Control))
    )
}

/// `U+200B (ZERO WIDTH SPACE)`, or `U+0430 (CYRILLIC SMALL LETTER A)`.
pub fn named(c: char, name: &str) -> String {
    format!("{} ({name})", code_point(c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_sorted_for_binary_search() {
        assert!(TABLE.windows(2).all(|w| w[0].0 < w[1].0));
    }
}
