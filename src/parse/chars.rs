//! Characters a reader can't see, or can't tell from ASCII: what messages
//! say about them (the code point, its Unicode name, what it resembles) and
//! which letters in a name are refused.
//!
//! A name may be written in any script (`θ3`, `масса`), but a letter that is
//! drawn like an ASCII letter (Cyrillic `а`, Greek `Ο`, fullwidth `ｘ`) makes
//! a second name that looks exactly like the first; such a letter is refused
//! where it could only be a mistake: next to ASCII letters, or in a name whose
//! letters all look like ASCII ones.

use super::{is_known, show_char};
use crate::diag::Diagnostic;
use crate::parse::ast::Span;

/// What a character is, for a message.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
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
const TABLE: &[(char, &str, Kind)] = &[
    ('\u{00AD}', "SOFT HYPHEN", Kind::Invisible),
    ('\u{02B9}', "MODIFIER LETTER PRIME", Kind::Like('\'')),
    ('\u{02BC}', "MODIFIER LETTER APOSTROPHE", Kind::Like('\'')),
    (
        '\u{02C8}',
        "MODIFIER LETTER VERTICAL LINE",
        Kind::Like('\''),
    ),
    ('\u{034F}', "COMBINING GRAPHEME JOINER", Kind::Invisible),
    ('\u{037E}', "GREEK QUESTION MARK", Kind::Like(';')),
    ('\u{0391}', "GREEK CAPITAL LETTER ALPHA", Kind::Like('A')),
    ('\u{0392}', "GREEK CAPITAL LETTER BETA", Kind::Like('B')),
    ('\u{0395}', "GREEK CAPITAL LETTER EPSILON", Kind::Like('E')),
    ('\u{0396}', "GREEK CAPITAL LETTER ZETA", Kind::Like('Z')),
    ('\u{0397}', "GREEK CAPITAL LETTER ETA", Kind::Like('H')),
    ('\u{0399}', "GREEK CAPITAL LETTER IOTA", Kind::Like('I')),
    ('\u{039A}', "GREEK CAPITAL LETTER KAPPA", Kind::Like('K')),
    ('\u{039C}', "GREEK CAPITAL LETTER MU", Kind::Like('M')),
    ('\u{039D}', "GREEK CAPITAL LETTER NU", Kind::Like('N')),
    ('\u{039F}', "GREEK CAPITAL LETTER OMICRON", Kind::Like('O')),
    ('\u{03A1}', "GREEK CAPITAL LETTER RHO", Kind::Like('P')),
    ('\u{03A4}', "GREEK CAPITAL LETTER TAU", Kind::Like('T')),
    ('\u{03A5}', "GREEK CAPITAL LETTER UPSILON", Kind::Like('Y')),
    ('\u{03A7}', "GREEK CAPITAL LETTER CHI", Kind::Like('X')),
    ('\u{03BF}', "GREEK SMALL LETTER OMICRON", Kind::Like('o')),
    ('\u{0405}', "CYRILLIC CAPITAL LETTER DZE", Kind::Like('S')),
    (
        '\u{0406}',
        "CYRILLIC CAPITAL LETTER BYELORUSSIAN-UKRAINIAN I",
        Kind::Like('I'),
    ),
    ('\u{0408}', "CYRILLIC CAPITAL LETTER JE", Kind::Like('J')),
    ('\u{0410}', "CYRILLIC CAPITAL LETTER A", Kind::Like('A')),
    ('\u{0412}', "CYRILLIC CAPITAL LETTER VE", Kind::Like('B')),
    ('\u{0415}', "CYRILLIC CAPITAL LETTER IE", Kind::Like('E')),
    ('\u{041A}', "CYRILLIC CAPITAL LETTER KA", Kind::Like('K')),
    ('\u{041C}', "CYRILLIC CAPITAL LETTER EM", Kind::Like('M')),
    ('\u{041D}', "CYRILLIC CAPITAL LETTER EN", Kind::Like('H')),
    ('\u{041E}', "CYRILLIC CAPITAL LETTER O", Kind::Like('O')),
    ('\u{0420}', "CYRILLIC CAPITAL LETTER ER", Kind::Like('P')),
    ('\u{0421}', "CYRILLIC CAPITAL LETTER ES", Kind::Like('C')),
    ('\u{0422}', "CYRILLIC CAPITAL LETTER TE", Kind::Like('T')),
    ('\u{0423}', "CYRILLIC CAPITAL LETTER U", Kind::Like('Y')),
    ('\u{0425}', "CYRILLIC CAPITAL LETTER HA", Kind::Like('X')),
    ('\u{0430}', "CYRILLIC SMALL LETTER A", Kind::Like('a')),
    ('\u{0435}', "CYRILLIC SMALL LETTER IE", Kind::Like('e')),
    ('\u{043E}', "CYRILLIC SMALL LETTER O", Kind::Like('o')),
    ('\u{0440}', "CYRILLIC SMALL LETTER ER", Kind::Like('p')),
    ('\u{0441}', "CYRILLIC SMALL LETTER ES", Kind::Like('c')),
    ('\u{0443}', "CYRILLIC SMALL LETTER U", Kind::Like('y')),
    ('\u{0445}', "CYRILLIC SMALL LETTER HA", Kind::Like('x')),
    ('\u{0455}', "CYRILLIC SMALL LETTER DZE", Kind::Like('s')),
    (
        '\u{0456}',
        "CYRILLIC SMALL LETTER BYELORUSSIAN-UKRAINIAN I",
        Kind::Like('i'),
    ),
    ('\u{0458}', "CYRILLIC SMALL LETTER JE", Kind::Like('j')),
    ('\u{04BB}', "CYRILLIC SMALL LETTER SHHA", Kind::Like('h')),
    (
        '\u{04CF}',
        "CYRILLIC SMALL LETTER PALOCHKA",
        Kind::Like('l'),
    ),
    ('\u{0501}', "CYRILLIC SMALL LETTER KOMI DE", Kind::Like('d')),
    ('\u{051B}', "CYRILLIC SMALL LETTER QA", Kind::Like('q')),
    ('\u{051D}', "CYRILLIC SMALL LETTER WE", Kind::Like('w')),
    ('\u{0589}', "ARMENIAN FULL STOP", Kind::Like(':')),
    ('\u{061C}', "ARABIC LETTER MARK", Kind::Bidi),
    ('\u{180E}', "MONGOLIAN VOWEL SEPARATOR", Kind::Invisible),
    ('\u{200B}', "ZERO WIDTH SPACE", Kind::Invisible),
    ('\u{200C}', "ZERO WIDTH NON-JOINER", Kind::Invisible),
    ('\u{200D}', "ZERO WIDTH JOINER", Kind::Invisible),
    ('\u{200E}', "LEFT-TO-RIGHT MARK", Kind::Bidi),
    ('\u{200F}', "RIGHT-TO-LEFT MARK", Kind::Bidi),
    ('\u{2010}', "HYPHEN", Kind::Like('-')),
    ('\u{2011}', "NON-BREAKING HYPHEN", Kind::Like('-')),
    ('\u{2012}', "FIGURE DASH", Kind::Like('-')),
    ('\u{2018}', "LEFT SINGLE QUOTATION MARK", Kind::Like('\'')),
    ('\u{201C}', "LEFT DOUBLE QUOTATION MARK", Kind::Like('"')),
    ('\u{201D}', "RIGHT DOUBLE QUOTATION MARK", Kind::Like('"')),
    ('\u{2024}', "ONE DOT LEADER", Kind::Like('.')),
    ('\u{202A}', "LEFT-TO-RIGHT EMBEDDING", Kind::Bidi),
    ('\u{202B}', "RIGHT-TO-LEFT EMBEDDING", Kind::Bidi),
    ('\u{202C}', "POP DIRECTIONAL FORMATTING", Kind::Bidi),
    ('\u{202D}', "LEFT-TO-RIGHT OVERRIDE", Kind::Bidi),
    ('\u{202E}', "RIGHT-TO-LEFT OVERRIDE", Kind::Bidi),
    ('\u{2044}', "FRACTION SLASH", Kind::Like('/')),
    ('\u{2060}', "WORD JOINER", Kind::Invisible),
    ('\u{2061}', "FUNCTION APPLICATION", Kind::Invisible),
    ('\u{2062}', "INVISIBLE TIMES", Kind::Invisible),
    ('\u{2063}', "INVISIBLE SEPARATOR", Kind::Invisible),
    ('\u{2064}', "INVISIBLE PLUS", Kind::Invisible),
    ('\u{2066}', "LEFT-TO-RIGHT ISOLATE", Kind::Bidi),
    ('\u{2067}', "RIGHT-TO-LEFT ISOLATE", Kind::Bidi),
    ('\u{2068}', "FIRST STRONG ISOLATE", Kind::Bidi),
    ('\u{2069}', "POP DIRECTIONAL ISOLATE", Kind::Bidi),
    ('\u{2217}', "ASTERISK OPERATOR", Kind::Like('*')),
    ('\u{2236}', "RATIO", Kind::Like(':')),
    ('\u{FE63}', "SMALL HYPHEN-MINUS", Kind::Like('-')),
    ('\u{FFF9}', "INTERLINEAR ANNOTATION ANCHOR", Kind::Invisible),
    (
        '\u{FFFA}',
        "INTERLINEAR ANNOTATION SEPARATOR",
        Kind::Invisible,
    ),
    (
        '\u{FFFB}',
        "INTERLINEAR ANNOTATION TERMINATOR",
        Kind::Invisible,
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
fn lookup(c: char) -> Option<(String, Kind)> {
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
        return Some((name.to_string(), Kind::Control));
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
        return Some((name, Kind::Like(a)));
    }
    // mathematical alphanumeric symbols: 13 alphabets of A–Z a–z, then
    // 5 of the digits 0–9
    if (0x1D400..=0x1D6A3).contains(&u) {
        let k = ((u - 0x1D400) % 52) as u8;
        let a = if k < 26 { b'A' + k } else { b'a' + k - 26 };
        return Some(("a mathematical letter".into(), Kind::Like(char::from(a))));
    }
    if (0x1D7CE..=0x1D7FF).contains(&u) {
        let a = char::from(b'0' + ((u - 0x1D7CE) % 10) as u8);
        return Some(("a mathematical digit".into(), Kind::Like(a)));
    }
    let description = match u {
        0x0300..=0x036F => "a combining mark",
        0xFE00..=0xFE0F | 0xE0100..=0xE01EF => "a variation selector",
        0xE0000..=0xE007F => "a tag character",
        0x206A..=0x206F => "a deprecated format character",
        0xFEFF => "ZERO WIDTH NO-BREAK SPACE",
        _ => return None,
    };
    Some((description.to_string(), Kind::Invisible))
}

/// Can't `c` be seen, or does it reorder the display of its line? (A tab
/// shows as white space, and the `\r` of a CRLF line end as nothing.)
pub fn is_hidden(c: char) -> bool {
    if c.is_ascii() {
        return c.is_ascii_control() && c != '\t' && c != '\r';
    }
    matches!(
        lookup(c),
        Some((_, Kind::Invisible | Kind::Bidi | Kind::Control))
    )
}

/// `U+200B (ZERO WIDTH SPACE)`, or `U+0430 (CYRILLIC SMALL LETTER A)`.
fn named(c: char, name: &str) -> String {
    format!("{} ({name})", code_point(c))
}

const BIDI_HINT: &str =
    "delete it: with it the text shown is not the text read (it is refused in comments and strings too)";

/// Refuse a bidirectional control anywhere in `src`, comments and strings
/// included (as rustc does): it reorders how its line is displayed, so a
/// reader would see other text than qdot reads ("Trojan Source",
/// CVE-2021-42574). Their UTF-8 starts with 0xD8 or 0xE2, so only those
/// bytes are decoded.
pub fn no_bidi_control(src: &str) -> Result<(), Diagnostic> {
    let b = src.as_bytes();
    for (p, _) in b
        .iter()
        .enumerate()
        .filter(|(_, &x)| x == 0xE2 || x == 0xD8)
    {
        let Some(c) = src.get(p..).and_then(|s| s.chars().next()) else {
            continue;
        };
        if let Some((name, Kind::Bidi)) = lookup(c) {
            let span = Span::new(p, p + c.len_utf8());
            return Err(Diagnostic::error(
                span,
                format!(
                    "invisible character {}, which reorders how the line is displayed",
                    named(c, &name)
                ),
            )
            .with_hint(BIDI_HINT));
        }
    }
    Ok(())
}

/// The message and hint for a character that has no place in the language
/// and that a reader can't see or can't tell from ASCII; `None` for other
/// characters (they are shown as they are).
pub fn describe(c: char) -> Option<(String, String)> {
    let (name, kind) = lookup(c)?;
    let what = named(c, &name);
    Some(match kind {
        Kind::Invisible => (
            format!("unknown character {what}, which is invisible"),
            "delete it (invisible characters often come with text pasted from a web page or a word processor)".into(),
        ),
        Kind::Bidi => (
            format!("invisible character {what}, which reorders how the line is displayed"),
            BIDI_HINT.into(),
        ),
        Kind::Control => (
            format!("unknown character {what}"),
            "delete it: control characters are not part of the .qd language".into(),
        ),
        Kind::Like(a) => (
            format!("unknown character {what}, which looks like `{a}`"),
            format!("replace it with the ASCII `{a}`"),
        ),
    })
}

/// The first letter of the name `name` that is refused (see the module
/// documentation), with its byte offset in `name`, the message and the hint.
/// Only for names with non-ASCII characters.
pub fn refused_letter(name: &str) -> Option<(usize, char, String, String)> {
    let mut first_like = None;
    let mut ascii_letter = false;
    let mut only_like = true;
    for (p, c) in name.char_indices() {
        if c.is_ascii_alphabetic() {
            ascii_letter = true;
            only_like = false;
            continue;
        }
        if c.is_ascii() {
            continue;
        }
        match lookup(c) {
            Some((n, Kind::Like(a))) => {
                let always = a == '\'' || !is_greek_or_cyrillic(c);
                if always {
                    return Some(refusal(name, p, c, &n, a));
                }
                if first_like.is_none() {
                    first_like = Some((p, c, n, a));
                }
            }
            _ => {
                if c.is_alphabetic() {
                    only_like = false;
                }
            }
        }
    }
    let (p, c, n, a) = first_like?;
    (ascii_letter || only_like).then(|| refusal(name, p, c, &n, a))
}

fn is_greek_or_cyrillic(c: char) -> bool {
    // Greek (U+0370..U+03FF), then Cyrillic and its supplement
    matches!(u32::from(c), 0x0370..=0x052F)
}

fn refusal(name: &str, p: usize, c: char, n: &str, a: char) -> (usize, char, String, String) {
    let what = named(c, n);
    let hint = if a == '\'' {
        "write a time derivative with the ASCII prime `'`: `x'`".to_string()
    } else {
        format!("retype it as the ASCII `{a}`: a name spelled with a look-alike letter is another name, though it looks the same")
    };
    (
        p,
        c,
        format!("the name `{name}` has the character {what}, which looks like `{a}`"),
        hint,
    )
}

/// The message and hint for the character `c` where it has no place;
/// `shown` is the token it starts, as named in messages.
pub fn unexpected(c: char, shown: &str) -> (String, String) {
    match c {
        '\n' => (
            "unexpected end of the line".into(),
            "the statement is incomplete".into(),
        ),
        ')' => (
            "unmatched `)`".into(),
            "remove it, or add the matching `(` before it".into(),
        ),
        '=' => (
            "unexpected `=`".into(),
            "a statement has one `=`; put each statement on its own line or separate them with `;`".into(),
        ),
        ',' => (
            "unexpected `,`".into(),
            "commas separate call arguments like `atan(y, x)` and the names after `coordinates` or `parameters`".into(),
        ),
        ':' => (
            "unexpected `:`".into(),
            "`:` appears only in `force COORD: expression` and in annotations like `parameters r: length`".into(),
        ),
        '\'' => (
            "unexpected `'`".into(),
            "a prime (time derivative) follows a name, a call or a parenthesized expression: `x'`, `sin(x)'`, `(x*y)'`".into(),
        ),
        '°' => (
            "unexpected `°`".into(),
            "`°` follows a number: `30°`".into(),
        ),
        '.' => (
            "unexpected `.`".into(),
            "a decimal point belongs inside a number, like `0.5`".into(),
        ),
        '(' => (
            "unexpected `(`".into(),
            "to call a function write the name directly before `(`: `sin(x)`; to multiply, write `*`".into(),
        ),
        '+' | '-' | '*' | '/' | '^' => (
            format!("unexpected `{c}`"),
            format!("to continue an expression on the next line, end the previous line with the operator `{c}`"),
        ),
        ';' => (
            "unexpected `;`".into(),
            "`;` separates two statements on one line".into(),
        ),
        '²' | '³' | '¹' => (
            format!("unknown character `{c}`"),
            "write powers with `^`, like `x^2`".into(),
        ),
        '×' | '·' | '⋅' | '∙' => (
            format!("unknown character `{c}`"),
            "write multiplication with `*`".into(),
        ),
        '÷' | '∕' => (
            format!("unknown character `{c}`"),
            "write division with `/`".into(),
        ),
        '−' | '–' | '—' => (
            format!("unknown character `{c}`"),
            "write minus with the ASCII `-`".into(),
        ),
        '′' | '’' | '`' | '´' => (
            format!("unknown character `{c}`"),
            "write a time derivative with the ASCII prime `'`: `x'`".into(),
        ),
        '"' => (
            "unknown character `\"`".into(),
            "a string is only the notation of `latex NAME = \"…\"`".into(),
        ),
        '[' => (
            "unexpected `[`".into(),
            "a vector like `[x, y]` stands where an expression is expected".into(),
        ),
        ']' => (
            "unmatched `]`".into(),
            "remove it, or add the matching `[` before it".into(),
        ),
        '{' => (
            "unexpected `{`".into(),
            "braces hold the equations of a solve block: `solve x, y { … }`; group expressions with `(` and `)`".into(),
        ),
        '}' => (
            "unmatched `}`".into(),
            "remove it, or open a solve block before it: `solve x, y { … }`".into(),
        ),
        _ if !is_known(c) => describe(c).unwrap_or_else(|| {
            (
                format!("unknown character `{}`", show_char(c)),
                "this character is not part of the .qd language".into(),
            )
        }),
        _ => (
            format!("unexpected {shown}"),
            "check the statement against `NAME = expression`".into(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_sorted_for_binary_search() {
        assert!(TABLE.windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn names_in_other_scripts_are_names() {
        for ok in ["θ3", "масса", "Δx", "ν", "ωₙ", "mж", "αβ"] {
            assert_eq!(refused_letter(ok).map(|r| r.0), None, "{ok}");
        }
    }

    #[test]
    fn look_alike_letters_are_refused_where_they_deceive() {
        // Cyrillic а in a Latin name; a name of look-alikes only; fullwidth
        assert_eq!(refused_letter("m\u{430}ss").map(|r| r.0), Some(1));
        assert_eq!(refused_letter("\u{43E}\u{445}").map(|r| r.0), Some(0));
        assert_eq!(refused_letter("\u{FF58}").map(|r| r.1), Some('\u{FF58}'));
        assert_eq!(refused_letter("x\u{2BC}").map(|r| r.0), Some(1));
        assert_eq!(refused_letter("\u{1D465}").map(|r| r.0), Some(0));
    }

    #[test]
    fn descriptions() {
        let (m, h) = describe('\u{200B}').unwrap();
        assert_eq!(
            m,
            "unknown character U+200B (ZERO WIDTH SPACE), which is invisible"
        );
        assert!(h.starts_with("delete it"));
        let (m, h) = describe('\u{FF1B}').unwrap();
        assert_eq!(
            m,
            "unknown character U+FF1B (a fullwidth form), which looks like `;`"
        );
        assert_eq!(h, "replace it with the ASCII `;`");
        assert_eq!(describe('→'), None);
    }
}
