//! Parse errors: position (line, column, width in characters), message and
//! hint.
//!
//! Most cases are data, in `tests/data/parse_errors/`: a scene `NAME.qd`
//! (parsed with [`parse_scene`]) or an expression `expr/NAME.expr` (parsed
//! with [`parse_expr`]), and beside it `NAME.txt`, its blessed output: a
//! first line `LINE:COL WIDTH` (the width of the error's span in
//! characters, which may run past its line), then the diagnostic exactly as
//! [`qdot::diag::Diagnostic::render`] prints it (as the command line does).
//! [`data_cases`] checks every case and names all that differ;
//! `QDOT_BLESS=1 cargo test --release --test it parse_errors::` rewrites the
//! `.txt` files from the current output (review the diff before committing).
//! `tests/data/README.md` says how to add a case.
//!
//! What stays here is what a file holds badly: sources built with `repeat`
//! (the nesting and depth limits, lines of up to 200 000 characters) and
//! sources whose point is a character that can't be seen (a control
//! character, a zero-width space, a bidirectional control): in a file such a
//! case reads as another text than the one parsed, here the escape names it.

use crate::common::{expr_err, locate, scene_err};
use pretty_assertions::assert_eq;
use qdot::parse::{parse_expr, parse_scene, MAX_DEPTH, MAX_NESTING};
use std::path::{Path, PathBuf};

const DATA: &str = concat!(env!("QDOT_ROOT"), "/tests/data/parse_errors");
const BLESS: &str = "QDOT_BLESS=1 cargo test --release --test it parse_errors::";

/// The blessed output of one case: `LINE:COL WIDTH`, then the rendered
/// diagnostic; an error when the source parses or the error has no place.
fn case_output(file: &str, src: &str, expression: bool) -> Result<String, String> {
    let err = if expression {
        parse_expr(src).err()
    } else {
        parse_scene(src).err()
    };
    let d = err.ok_or("parsed without an error; every case here must be a parse error")?;
    if d.span.is_none() {
        return Err(format!("the error has no position: {}", d.message));
    }
    let at = locate(src, &d);
    Ok(format!(
        "{}:{} {}\n{}",
        at.line,
        at.col,
        at.width,
        d.render(file, src)
    ))
}

/// The entries of `dir`, sorted.
fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    v.sort();
    v
}

/// Every case of `tests/data/parse_errors/` against its blessed output;
/// fails naming every case that differs (with a diff on stderr), has no
/// `.txt`, or does not fail to parse, and every `.txt` without its case.
#[test]
fn data_cases() {
    let bless = std::env::var_os("QDOT_BLESS").is_some();
    let root = Path::new(DATA);
    let mut failures = Vec::new();
    let mut cases = 0;
    for (dir, ext) in [(root.to_path_buf(), "qd"), (root.join("expr"), "expr")] {
        for path in entries(&dir) {
            let shown = path
                .strip_prefix(root)
                .unwrap_or(&path)
                .display()
                .to_string();
            if path.is_dir() && path == root.join("expr") {
                continue;
            }
            match path.extension().and_then(|e| e.to_str()) {
                Some(e) if e == ext => {}
                Some("txt") => {
                    if !path.with_extension(ext).exists() {
                        failures.push(format!(
                            "{shown}: blessed output of no case (its .{ext} is gone?)"
                        ));
                    }
                    continue;
                }
                _ => {
                    failures.push(format!("{shown}: neither a .{ext} case nor a .txt output"));
                    continue;
                }
            }
            cases += 1;
            let file = path.file_name().expect("a file name").to_string_lossy();
            let src = match std::fs::read(&path).map(String::from_utf8) {
                Ok(Ok(s)) => s,
                Ok(Err(_)) => {
                    failures.push(format!(
                        "{shown}: not UTF-8 (such a case belongs in parse_errors.rs)"
                    ));
                    continue;
                }
                Err(e) => panic!("{shown}: {e}"),
            };
            let actual = match case_output(&file, &src, ext == "expr") {
                Ok(s) => s,
                Err(why) => {
                    failures.push(format!("{shown}: {why}"));
                    continue;
                }
            };
            let blessed = path.with_extension("txt");
            let expected = std::fs::read_to_string(&blessed).ok();
            if bless {
                if expected.as_deref() != Some(actual.as_str()) {
                    std::fs::write(&blessed, &actual).expect("write the blessed output");
                    eprintln!("blessed {}", blessed.display());
                }
                continue;
            }
            match expected {
                None => failures.push(format!("{shown}: no blessed output (.txt)")),
                Some(expected) if expected != actual => {
                    eprintln!(
                        "{shown}: the output differs from its .txt (< blessed, > now):\n{}",
                        pretty_assertions::StrComparison::new(&expected, &actual)
                    );
                    failures.push(format!("{shown}: the output differs from its .txt"));
                }
                Some(_) => {}
            }
        }
    }
    // the directory did not go missing or empty
    assert!(cases >= 200, "only {cases} cases in {DATA}");
    assert!(
        failures.is_empty(),
        "{} of {cases} parse-error cases failed:\n  {}\nif the new output is right, run {BLESS}",
        failures.len(),
        failures.join("\n  ")
    );
}

fn short(src: &str) -> String {
    src.chars().take(60).collect()
}

/// Check one scene error: position `line:col`, width, exact message, and a
/// piece of the hint.
#[track_caller]
fn check(src: &str, line: usize, col: usize, width: usize, message: &str, hint_part: &str) {
    let at = scene_err(src);
    assert_eq!(
        (at.line, at.col, at.width, at.message.as_str()),
        (line, col, width, message),
        "for {:?}",
        short(src)
    );
    assert!(
        at.hint.contains(hint_part),
        "hint {:?} lacks {hint_part:?} for {:?}",
        at.hint,
        short(src)
    );
}

/// Characters that can't be seen are named by their code point; columns
/// count characters. (The look-alike characters are data cases.)
#[test]
fn invisible_characters() {
    check(
        "x = \u{1}",
        1,
        5,
        1,
        "unknown character U+0001 (a control character)",
        "delete it",
    );
    let invisible = ", which is invisible";
    check(
        "θ = 1\nx = a\u{200B} + b",
        2,
        6,
        1,
        &format!("unknown character U+200B (ZERO WIDTH SPACE){invisible}"),
        "delete it",
    );
    // a bidirectional control, even in a comment or a string
    check(
        "x = a + b # \u{202E}c",
        1,
        13,
        1,
        "invisible character U+202E (RIGHT-TO-LEFT OVERRIDE), which reorders how the line is displayed",
        "refused in comments and strings too",
    );
    check(
        "y = 1\nlatex x = \"\u{2066}\"",
        2,
        12,
        1,
        "invisible character U+2066 (LEFT-TO-RIGHT ISOLATE), which reorders how the line is displayed",
        "the text shown is not the text read",
    );
    assert_eq!(
        expr_err("a + \u{200F}b").message,
        "invisible character U+200F (RIGHT-TO-LEFT MARK), which reorders how the line is displayed"
    );
    check(
        "x = a\u{2060}",
        1,
        6,
        1,
        &format!("unknown character U+2060 (WORD JOINER){invisible}"),
        "delete it",
    );
}

/// What looks like an error case but is not one.
#[test]
fn not_errors() {
    // names in other scripts are names
    assert!(parse_scene("масса = 1\nθ3 = 2*масса\nΔx = θ3").is_ok());
    // a no-break space is white space
    assert!(parse_scene("x =\u{A0}1").is_ok());
    // a definition of a name that looks like a keyword is a definition
    assert!(parse_scene("potental = 3").is_ok());
}

#[test]
fn nesting_limits() {
    let n = MAX_NESTING as usize;
    // parentheses: the top-level expression is one level, each group one more
    let ok = format!("x = {}1{}", "(".repeat(n - 1), ")".repeat(n - 1));
    assert!(parse_scene(&ok).is_ok());
    let deep = format!("x = {}1{}", "(".repeat(n), ")".repeat(n));
    check(
        &deep,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    let huge = format!("x = {}1{}", "(".repeat(100_000), ")".repeat(100_000));
    check(
        &huge,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    // calls, unary signs and power towers
    let calls = format!("x = {}1{}", "f(".repeat(50_000), ")".repeat(50_000));
    assert_eq!(
        scene_err(&calls).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let signs = format!("x = {}x", "-".repeat(100_000));
    assert_eq!(
        scene_err(&signs).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let tower = format!("x = 2{}", "^2".repeat(100_000));
    assert_eq!(
        scene_err(&tower).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let unclosed = "(".repeat(100_000);
    assert!(parse_expr(&unclosed).is_err());
    assert!(parse_scene(&format!("x = {unclosed}")).is_err());
}

#[test]
fn depth_limit_on_long_chains() {
    let n = MAX_DEPTH as usize;
    // `1+1+…+1` with n terms has depth n
    let ok = format!("x = 1{}", "+1".repeat(n - 1));
    assert!(parse_scene(&ok).is_ok());
    let deep = format!("x = 1{}", "+1".repeat(n));
    check(
        &deep,
        1,
        4 + 2 * n + 1,
        1,
        "expression too deep (more than 1000 levels)",
        "split it",
    );
    let huge = format!("x = 1{}", "*x".repeat(200_000));
    assert_eq!(
        scene_err(&huge).message,
        "expression too deep (more than 1000 levels)"
    );
    // many primes are one node
    let primes = format!("x = y{}", "'".repeat(10_000));
    assert!(parse_scene(&primes).is_ok());
}

#[test]
fn rendered_error() {
    let src = "m = 1\nx = 3 $ 4\n";
    let d = parse_scene(src).unwrap_err();
    assert_eq!(
        d.render("scene.qd", src),
        "error: unknown character `$`\n --> scene.qd:2:7\n  |\n2 | x = 3 $ 4\n  |       ^\n  = hint: this character is not part of the .qd language\n"
    );
    let at = locate(src, &d);
    assert_eq!((at.line, at.col), (2, 7));
}

#[test]
fn nesting_limits_of_vectors() {
    let n = MAX_NESTING as usize;
    let ok = format!("x = {}1{}", "[".repeat(n - 1), "]".repeat(n - 1));
    assert!(parse_scene(&ok).is_ok());
    let deep = format!("x = {}1{}", "[".repeat(n), "]".repeat(n));
    check(
        &deep,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    let huge = format!("x = {}1{}", "[".repeat(100_000), "]".repeat(100_000));
    check(
        &huge,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    let mixed = format!("x = {}1{}", "[(".repeat(50_000), ")]".repeat(50_000));
    assert_eq!(
        scene_err(&mixed).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let unclosed = "[".repeat(100_000);
    assert!(parse_expr(&unclosed).is_err());
    assert!(parse_scene(&format!("x = {unclosed}")).is_err());
    assert!(parse_scene(&format!("load {unclosed}")).is_err());
    assert!(parse_scene(&format!("solve x {{ {unclosed}")).is_err());
    // long vectors are flat: many components are one level
    let long = format!("x = [{}]", vec!["a"; 10_000].join(", "));
    assert!(parse_scene(&long).is_ok());
    // many equations are fine too
    let eqs = format!("solve x {{\n{}}}", "x = 1\n".repeat(10_000));
    assert!(parse_scene(&eqs).is_ok());
}

/// The echoed source line: an invisible character shows as `�` (one
/// character for one, so the caret stays under its column), but a tab and
/// the `\r` of a CRLF line end are printed as they are.
#[test]
fn the_echoed_line_shows_invisible_characters() {
    let src = "x = 1\r\ny =\t3 \u{200B} 4\r\n";
    let d = parse_scene(src).unwrap_err();
    assert_eq!(
        d.render("scene.qd", src),
        "error: unknown character U+200B (ZERO WIDTH SPACE), which is invisible\n --> scene.qd:2:7\n  |\n2 | y =\t3 \u{FFFD} 4\r\n  |    \t  ^\n  = hint: delete it (invisible characters often come with text pasted from a web page or a word processor)\n"
    );
}

/// A diagnostic rendered without its source (or with another) shows no
/// place rather than indexing past the text: `render` never panics.
#[test]
fn a_span_outside_the_source_is_rendered_without_a_place() {
    use qdot::diag::{Diagnostic, Span};
    let d = Diagnostic::error(Span::new(292, 300), "too large").with_hint("raise it");
    assert_eq!(
        d.render("x.qd", ""),
        "error: too large\n  = hint: raise it\n"
    );
    assert_eq!(
        d.render("x.qd", "θθθ"),
        "error: too large\n  = hint: raise it\n"
    );
    // a span inside a character is not a place either
    let d = Diagnostic::error(Span::new(1, 2), "m");
    assert_eq!(d.render("x.qd", "θ"), "error: m\n");
}
