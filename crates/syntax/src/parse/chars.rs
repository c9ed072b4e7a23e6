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
use crate::unicode::{lookup, named, CharKind};

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
        if let Some((name, CharKind::Bidi)) = lookup(c) {
            let span = Span::new(p, p + c.len_utf8());
            return Err(Diagnostic::error(
                span,
                format!(
                    "invisible character {}, which reorders how the line is displayed",
                    named(c, &name)
                ),
            )
            .with_hint(BIDI_HINT)
            .with_kind(crate::diag::ErrorKind::Syntax));
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
        CharKind::Invisible => (
            format!("unknown character {what}, which is invisible"),
            "delete it (invisible characters often come with text pasted from a web page or a word processor)".into(),
        ),
        CharKind::Bidi => (
            format!("invisible character {what}, which reorders how the line is displayed"),
            BIDI_HINT.into(),
        ),
        CharKind::Control => (
            format!("unknown character {what}"),
            "delete it: control characters are not part of the .qd language".into(),
        ),
        CharKind::Like(a) => (
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
            Some((n, CharKind::Like(a))) => {
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
