//! Character classes and token scanning on bytes: white space, comments,
//! names and numbers (the hot path), and the bracket scan of messages.

use super::*;

/// `ident_start ::= Letter | "_"` (Letter: Unicode `Alphabetic`)
pub(super) fn ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

/// `ident_char ::= Letter | [0-9] | "_"`
pub(super) fn ident_char(c: char) -> bool {
    c.is_alphabetic() || c.is_ascii_digit() || c == '_'
}

/// One character of `space` (everything white except the newline).
pub(super) fn is_space(c: char) -> bool {
    c != '\n' && (c.is_whitespace() || c == '\u{feff}')
}

/// Characters that have a meaning somewhere in the language.
pub(super) fn is_known(c: char) -> bool {
    ident_char(c) || is_space(c) || "\n#+-*/^'()[]{}=,:;.°".contains(c)
}

/// A character for a message: control characters escaped.
pub(super) fn show_char(c: char) -> String {
    if c.is_control() || c == '\u{feff}' {
        c.escape_default().to_string()
    } else {
        c.to_string()
    }
}

/// The next character of the input.
pub(super) fn first(i: &str) -> Option<char> {
    i.chars().next()
}

/// Does the input start with a character of `class` (`ident_start` or
/// `ident_char`)? ASCII is decided on the byte; other characters are decoded.
#[inline]
pub(super) fn starts_with_class(i: &str, class: fn(char) -> bool) -> bool {
    match i.as_bytes().first() {
        Some(&b) if b < 0x80 => class(char::from(b)),
        Some(_) => first(i).is_some_and(class),
        None => false,
    }
}

/// Does an `ident` start here?
#[inline]
pub(super) fn starts_ident(i: &str) -> bool {
    starts_with_class(i, ident_start)
}

/// Length in bytes of the `ident` at the start of `i` (0 if there is none).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn ident_len(i: &str) -> usize {
    let b = i.as_bytes();
    match b.first() {
        Some(&c) if c.is_ascii_alphabetic() || c == b'_' => {}
        Some(&c) if c >= 0x80 => return ident_len_unicode(i, 0),
        _ => return 0,
    }
    let mut p = 1;
    while let Some(&c) = b.get(p) {
        if c.is_ascii_alphanumeric() || c == b'_' {
            p += 1;
        } else if c >= 0x80 {
            return ident_len_unicode(i, p);
        } else {
            break;
        }
    }
    p
}

/// [`ident_len`] from byte `p` on (where `i` has a non-ASCII character or,
/// for `p == 0`, must start with an `ident_start`), decoding characters.
#[inline(never)]
pub(super) fn ident_len_unicode(i: &str, mut p: usize) -> usize {
    if p == 0 {
        match first(i) {
            Some(c) if ident_start(c) => p = c.len_utf8(),
            _ => return 0,
        }
    }
    while let Some(c) = first(&i[p..]) {
        if ident_char(c) {
            p += c.len_utf8();
        } else {
            break;
        }
    }
    p
}

/// Number of ASCII digits at the start of `i`.
#[inline]
pub(super) fn digits_len(i: &str) -> usize {
    i.bytes().take_while(u8::is_ascii_digit).count()
}

/// The number of `\n` bytes in `b` (eight bytes at a time).
pub(super) fn count_newlines(b: &[u8]) -> usize {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    let chunks = b.chunks_exact(8);
    let tail = chunks.remainder();
    let mut n = 0;
    for c in chunks {
        let x = u64::from_le_bytes(c.try_into().unwrap_or([0; 8])) ^ 0x0a0a_0a0a_0a0a_0a0a;
        // the high bit of each byte is set iff the byte is not zero
        let nonzero = (((x & LOW7) + LOW7) | x) & !LOW7;
        n += 8 - nonzero.count_ones() as usize;
    }
    n + tail.iter().filter(|&&c| c == b'\n').count()
}

/// Skip `( space | comment )*`, and newlines too if `nl` (`ws_nl`).
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn skip_ws(i: &str, nl: bool) -> &str {
    let b = i.as_bytes();
    // the common cases: no white space, or a single space before a token
    match b.first().map(|&c| WS_START[usize::from(c)]) {
        None | Some(NOT_WS) => i,
        Some(NEWLINE) if !nl => i,
        Some(SPACE)
            if b.get(1)
                .is_some_and(|&c| WS_START[usize::from(c)] == NOT_WS) =>
        {
            &i[1..]
        }
        Some(_) => skip_ws_loop(i, nl),
    }
}

/// Classes of a first byte for [`skip_ws`].
pub(super) const NOT_WS: u8 = 0;
pub(super) const SPACE: u8 = 1;
pub(super) const NEWLINE: u8 = 2;
/// Other bytes that may start `space` or `comment` (a non-ASCII byte may
/// start a Unicode space).
pub(super) const OTHER_WS: u8 = 3;

/// The class of each byte as the first byte of white space.
static WS_START: [u8; 256] = {
    let mut t = [NOT_WS; 256];
    let mut b = 0x80;
    while b < 256 {
        t[b] = OTHER_WS;
        b += 1;
    }
    t[b' ' as usize] = SPACE;
    t[b'\n' as usize] = NEWLINE;
    t[b'\t' as usize] = OTHER_WS;
    t[b'\r' as usize] = OTHER_WS;
    t[0x0B] = OTHER_WS;
    t[0x0C] = OTHER_WS;
    t[b'#' as usize] = OTHER_WS;
    t
};

/// [`skip_ws`] beyond its fast cases.
pub(super) fn skip_ws_loop(i: &str, nl: bool) -> &str {
    let b = i.as_bytes();
    let mut p = 0;
    while let Some(&c) = b.get(p) {
        match c {
            // the ASCII characters of `space` (`char::is_whitespace` but `\n`)
            b' ' | b'\t' | b'\r' | 0x0B | 0x0C => p += 1,
            b'\n' if nl => p += 1,
            // `comment`: up to (not including) the end of the line
            b'#' => match Parser::comment(&i[p..]) {
                Ok((rest, _)) => p = i.len() - rest.len(),
                Err(_) => break,
            },
            0x80.. => match first(&i[p..]) {
                Some(c) if is_space(c) => p += c.len_utf8(),
                _ => break,
            },
            _ => break,
        }
    }
    &i[p..]
}

/// Can an operand (an `atom`) start here? Used to detect `a b`.
///
/// Decided by a table on the first byte (this runs after every operand);
/// only `.` and non-ASCII characters look further.
#[inline]
pub(super) fn starts_operand(i: &str) -> bool {
    match i.as_bytes().first().map(|&b| OPERAND_START[usize::from(b)]) {
        None | Some(OPERAND_NO) => false,
        Some(OPERAND_YES) => true,
        Some(_) => starts_operand_slow(i),
    }
}

/// [`starts_operand`] for `.` and non-ASCII characters.
#[inline(never)]
pub(super) fn starts_operand_slow(i: &str) -> bool {
    match i.as_bytes() {
        [b'.', d, ..] => d.is_ascii_digit(),
        _ => starts_ident(i),
    }
}

/// Classes of a first byte for [`starts_operand`].
pub(super) const OPERAND_NO: u8 = 0;
pub(super) const OPERAND_YES: u8 = 1;
/// `.` (a number if a digit follows) and the bytes of non-ASCII characters.
pub(super) const OPERAND_MAYBE: u8 = 2;

/// The class of each byte as the first byte of an operand: digits, ASCII
/// letters, `_`, `(` and `[` start one.
static OPERAND_START: [u8; 256] = {
    let mut t = [OPERAND_NO; 256];
    let mut b = 0;
    while b < 256 {
        let c = b as u8;
        if c.is_ascii_alphanumeric() || c == b'_' || c == b'(' || c == b'[' {
            t[b] = OPERAND_YES;
        } else if c == b'.' || c >= 0x80 {
            t[b] = OPERAND_MAYBE;
        }
        b += 1;
    }
    t
};

/// Show a piece of source in a message, shortened if long.
pub(super) fn excerpt(s: &str) -> String {
    let s = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if s.chars().count() > 40 {
        let head: String = s.chars().take(37).collect();
        format!("{head}…")
    } else {
        s
    }
}

/// The innermost bracket (`(`, `[` or `{`, with its offset) that is still
/// open at the end of `src` and starts before `limit` (comments are skipped).
/// `)` and `]` close the last open `(` or `[`; `}` closes the last open `{`.
pub(super) fn unclosed_before(src: &str, limit: usize) -> Option<(usize, u8)> {
    let mut parens = Vec::new();
    let mut braces = Vec::new();
    let mut in_comment = false;
    for (p, c) in src.bytes().enumerate() {
        match c {
            b'\n' => in_comment = false,
            _ if in_comment => {}
            b'#' => in_comment = true,
            b'(' | b'[' => parens.push((p, c)),
            b')' | b']' => {
                parens.pop();
            }
            b'{' => braces.push((p, c)),
            b'}' => {
                braces.pop();
            }
            _ => {}
        }
    }
    let paren = parens.into_iter().rev().find(|&(p, _)| p < limit);
    let brace = braces.into_iter().rev().find(|&(p, _)| p < limit);
    paren.max(brace)
}
