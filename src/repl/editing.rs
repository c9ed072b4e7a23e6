//! The REPL's line editing without a terminal: the scanner of a line
//! ([`line_tokens`]), completion ([`completions`]) and highlighting
//! ([`highlight`]). The terminal (the `qdot` binary) puts them behind its
//! line editor.

use super::{commands, keywords};
use crate::parse::functions::{self, Builtin};

/// A completion candidate: what the list shows and what replaces the word.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Completion {
    /// Shown in the list of candidates.
    pub display: String,
    /// Put in place of the word being completed.
    pub replacement: String,
}

/// What a piece of a REPL line is, for completion and highlighting.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineTokenKind {
    /// A name or keyword: a letter or `_`, then letters, digits and `_`.
    Word,
    /// A number: a digit, then ASCII letters, digits and dots (`1.5e3`).
    Number,
    /// A `# …` comment, to the end of the line.
    Comment,
    /// A `:command` word at the start of the line.
    Command,
    /// One other character (operators, brackets, white space).
    Other,
}

/// One piece of a REPL line: its kind and byte range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineToken {
    /// What it is.
    pub kind: LineTokenKind,
    /// Where it starts (a byte offset).
    pub start: usize,
    /// Where it ends (exclusive).
    pub end: usize,
}

/// The pieces of a REPL line, in order, covering it: the one scanner of
/// completion and highlighting. Lenient where the parser is strict (an
/// unfinished line is still being typed).
pub fn line_tokens(line: &str) -> Vec<LineToken> {
    let mut out = Vec::new();
    let mut it = line.char_indices().peekable();
    let token = |kind, start, end| LineToken { kind, start, end };
    while let Some((i, c)) = it.next() {
        let mut end = i + c.len_utf8();
        let mut take = |accept: &dyn Fn(char) -> bool| {
            while let Some(&(j, d)) = it.peek() {
                if !accept(d) {
                    break;
                }
                end = j + d.len_utf8();
                it.next();
            }
            end
        };
        let t = if c == '#' {
            out.push(token(LineTokenKind::Comment, i, line.len()));
            break;
        } else if c == ':' && line[..i].trim().is_empty() {
            token(
                LineTokenKind::Command,
                i,
                take(&|d| d.is_alphanumeric() || d == '_' || d == '-'),
            )
        } else if c.is_alphabetic() || c == '_' {
            token(
                LineTokenKind::Word,
                i,
                take(&|d| d.is_alphanumeric() || d == '_'),
            )
        } else if c.is_ascii_digit() {
            token(
                LineTokenKind::Number,
                i,
                take(&|d| d.is_ascii_alphanumeric() || d == '.'),
            )
        } else {
            token(LineTokenKind::Other, i, end)
        };
        out.push(t);
    }
    out
}

/// The candidates for the word before `pos`: commands after a leading
/// `:`, otherwise names, functions (with `(`) and keywords.
pub fn completions(line: &str, pos: usize, names: &[&[String]]) -> (usize, Vec<Completion>) {
    let before = &line[..pos.min(line.len())];
    let last = line_tokens(before).pop();
    let (start, kind) = match last {
        Some(t) if t.end == before.len() && t.kind != LineTokenKind::Other => (t.start, t.kind),
        _ => (before.len(), LineTokenKind::Other),
    };
    if let Some(found) = option_completions(before) {
        return found;
    }
    let word = &before[start..];
    let mut out: Vec<Completion> = Vec::new();
    match kind {
        LineTokenKind::Command => {
            for c in commands() {
                let name = format!(":{}", c.name);
                if name.starts_with(word) {
                    out.push(Completion {
                        display: name.clone(),
                        replacement: name,
                    });
                }
            }
            return (start, out);
        }
        LineTokenKind::Word => {}
        _ => return (start, Vec::new()),
    }
    for list in names {
        for n in list.iter() {
            if n.starts_with(word) {
                out.push(Completion {
                    display: n.clone(),
                    replacement: n.clone(),
                });
            }
        }
    }
    for f in functions::names() {
        if f.starts_with(word) {
            out.push(Completion {
                display: format!("{f}("),
                replacement: format!("{f}("),
            });
        }
    }
    if line[..start].trim().is_empty() {
        for k in keywords::statement_keywords() {
            if k.starts_with(word) {
                out.push(Completion {
                    display: k.to_string(),
                    replacement: format!("{k} "),
                });
            }
        }
    }
    out.sort_by(|a, b| a.display.cmp(&b.display));
    out.dedup_by(|a, b| a.display == b.display);
    (start, out)
}

/// After `:command `, a word starting with `-`: the command's options.
fn option_completions(before: &str) -> Option<(usize, Vec<Completion>)> {
    let rest = before.trim_start().strip_prefix(':')?;
    let (name, _) = rest.split_once(char::is_whitespace)?;
    let start = before.rfind(char::is_whitespace).map_or(0, |i| i + 1);
    let word = &before[start..];
    if !word.starts_with('-') {
        return None;
    }
    let c = commands().into_iter().find(|c| c.name == name)?;
    let out = c
        .options
        .iter()
        .map(|o| format!("--{o}"))
        .filter(|o| o.starts_with(word))
        .map(|o| Completion {
            display: o.clone(),
            replacement: format!("{o} "),
        })
        .collect();
    Some((start, out))
}

const RESET: &str = "\x1b[0m";
const KEYWORD: &str = "\x1b[1;34m";
const COORD: &str = "\x1b[32m";
const PARAM: &str = "\x1b[33m";
const DEFINED: &str = "\x1b[36m";
const FUNCTION: &str = "\x1b[35m";
const NUMBER: &str = "\x1b[36m";
const COMMENT: &str = "\x1b[2m";
const COMMAND: &str = "\x1b[1;35m";

/// ANSI colours for one line: keywords, coordinates, parameters, other
/// names, functions, numbers, comments and `:commands`.
pub fn highlight(line: &str, coords: &[String], params: &[String], others: &[String]) -> String {
    if line.trim_start().starts_with(':') {
        return format!("{COMMAND}{line}{RESET}");
    }
    let mut out = String::with_capacity(line.len() + 32);
    let mut first_word = true;
    for t in line_tokens(line) {
        let text = &line[t.start..t.end];
        let colour = match t.kind {
            LineTokenKind::Comment => Some(COMMENT),
            LineTokenKind::Number => Some(NUMBER),
            LineTokenKind::Word => {
                let call = line[t.end..].starts_with('(');
                if call && Builtin::from_name(text).is_some() {
                    Some(FUNCTION)
                } else if coords.iter().any(|n| n == text) {
                    Some(COORD)
                } else if params.iter().any(|n| n == text) {
                    Some(PARAM)
                } else if others.iter().any(|n| n == text) {
                    Some(DEFINED)
                } else if (first_word || keywords::STOP.contains(&text))
                    && keywords::all().any(|k| k == text)
                {
                    Some(KEYWORD)
                } else {
                    None
                }
            }
            LineTokenKind::Command | LineTokenKind::Other => None,
        };
        match t.kind {
            LineTokenKind::Other if text == ";" => first_word = true,
            LineTokenKind::Other if text.trim().is_empty() => {}
            _ => first_word = false,
        }
        match colour {
            Some(col) => {
                out.push_str(col);
                out.push_str(text);
                out.push_str(RESET);
            }
            None => out.push_str(text),
        }
    }
    out
}
