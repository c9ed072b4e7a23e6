//! Two rules of the house, enforced by reading the library's source (the
//! `qdot` package's `src/` and every `crates/*/src/`, test modules left
//! out):
//!
//! - only the context that runs a command installs the thread-local state
//!   (the assumptions, the work budget, the print order); the engine takes
//!   it as it finds it, checks it where being wrong would be silently
//!   wrong, and nests an algorithm's trial budget with `budget::probe`;
//! - an error says what class it is (`ErrorKind`): the constructions left
//!   without a specific kind may not grow in number.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("QDOT_ROOT"))
}

/// Every library source file, by its path from the root, with its text up
/// to its test module.
fn library_sources() -> Vec<(String, String)> {
    let mut dirs = vec![root().join("src")];
    for e in std::fs::read_dir(root().join("crates")).expect("crates/ is readable") {
        let p = e.expect("an entry").path().join("src");
        if p.is_dir() {
            dirs.push(p);
        }
    }
    let mut files = Vec::new();
    for d in dirs {
        rust_files(&d, &mut files);
    }
    files.sort();
    files
        .into_iter()
        .filter(|p| p.file_name().is_some_and(|n| n != "tests.rs"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a source file is readable");
            let code = match text.find("#[cfg(test)]") {
                Some(i) => text[..i].to_string(),
                None => text,
            };
            let name = p
                .strip_prefix(root())
                .expect("under the root")
                .to_string_lossy()
                .replace('\\', "/");
            (name, code)
        })
        .collect()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("a source directory is readable") {
        let p = e.expect("an entry").path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n != "tests") {
                rust_files(&p, out);
            }
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The files that may install thread-local state, and why.
pub(crate) const INSTALLERS: &[(&str, &str)] = &[
    (
        "src/app/context.rs",
        "Context::within: the context of a command",
    ),
    (
        "crates/mechanics/src/scene/mod.rs",
        "Scene::assumptions_in_force: the library user's door to the engine",
    ),
    (
        "crates/exact/src/algebra/assume.rs",
        "assuming itself, and sign_under for a reader building a scene's assumptions",
    ),
    (
        "crates/exact/src/budget.rs",
        "within itself, bounded and probe",
    ),
    (
        "crates/exact/src/expr/print.rs",
        "with_coordinate_order itself",
    ),
    (
        "src/simulate/sweep.rs",
        "a thread pool's workers take the budget of the thread that started them",
    ),
];

/// The calls that install thread-local state: the function names, called
/// as functions (a method `ctx.within(…)` is a context's, allowed).
const SETTERS: &[&str] = &["assuming", "within", "with_coordinate_order"];

/// The places in `code` where one of [`SETTERS`] is called, by line.
fn setter_calls(code: &str) -> Vec<(usize, &'static str)> {
    let mut out = Vec::new();
    for (i, line) in code.lines().enumerate() {
        let line = line.split("//").next().unwrap_or("");
        for name in SETTERS {
            let mut from = 0;
            while let Some(k) = line[from..].find(name) {
                let at = from + k;
                from = at + name.len();
                let before = line[..at].chars().next_back();
                let after = line[from..].trim_start();
                let ident = |c: char| c.is_alphanumeric() || c == '_';
                if before.is_some_and(|c| ident(c) || c == '.') || !after.starts_with('(') {
                    continue;
                }
                if line[..at].trim_end().ends_with("fn") {
                    continue;
                }
                out.push((i + 1, *name));
            }
        }
    }
    out
}

#[test]
fn setter_calls_are_found() {
    let code = "let a = assuming(&s, || 1);\nctx.within(|| 2);\nfn within(x: usize) {}\nbudget::within(3, f)\nx.of_scene_within(1) // within(2)\n";
    assert_eq!(setter_calls(code), vec![(1, "assuming"), (4, "within")]);
}

#[test]
fn only_the_context_installs_assumptions_budgets_and_print_order() {
    let mut found = Vec::new();
    for (name, code) in library_sources() {
        if INSTALLERS.iter().any(|(f, _)| *f == name) {
            continue;
        }
        for (line, what) in setter_calls(&code) {
            found.push(format!("{name}:{line}: {what}"));
        }
    }
    assert!(
        found.is_empty(),
        "thread-local state installed outside the context (tests/house_rules.rs lists the allowed places; \
         a library function takes the scene's assumptions from its caller and checks them with \
         Scene::assumptions_required, and nests a trial budget with budget::probe):\n{}",
        found.join("\n")
    );
}

/// The error constructions (`Diagnostic::error(…)`, `Diagnostic::global(…)`)
/// without a specific kind: no `.with_kind(…)` in the chain of calls that
/// follows, or `.with_kind(ErrorKind::Other)`. By file and line.
fn kindless(code: &str) -> Vec<usize> {
    let s: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    for pat in ["Diagnostic::error(", "Diagnostic::global("] {
        let pat: Vec<char> = pat.chars().collect();
        let mut i = 0;
        while i + pat.len() <= s.len() {
            if s[i..i + pat.len()] != pat[..] {
                i += 1;
                continue;
            }
            let line = s[..i].iter().filter(|&&c| c == '\n').count() + 1;
            let mut end = skip_call(&s, i + pat.len() - 1);
            let mut kind = None;
            while let Some((method, open)) = next_method(&s, end) {
                let close = skip_call(&s, open);
                if method == "with_kind" {
                    kind = Some(s[open + 1..close - 1].iter().collect::<String>());
                }
                end = close;
            }
            if kind.is_none_or(|k| k.trim().ends_with("ErrorKind::Other")) {
                out.push(line);
            }
            i += pat.len();
        }
    }
    out.sort_unstable();
    out
}

/// The index past the parenthesis that closes the one at `open`, skipping
/// string and character literals and line comments.
fn skip_call(s: &[char], open: usize) -> usize {
    let mut depth = 0usize;
    let mut i = open;
    while i < s.len() {
        match s[i] {
            '"' => {
                // a raw string r#"…"# holds no escapes
                let raw = i > 0 && (s[i - 1] == 'r' || s[i - 1] == '#');
                let hashes = (0..i).rev().take_while(|&k| s[k] == '#').count();
                i += 1;
                while i < s.len() {
                    if !raw && s[i] == '\\' {
                        i += 2;
                        continue;
                    }
                    if s[i] == '"' && s[i + 1..].iter().take(hashes).all(|&c| c == '#') {
                        i += hashes;
                        break;
                    }
                    i += 1;
                }
            }
            '\'' if s.get(i + 1) == Some(&'\\') => {
                i += 2;
                while i < s.len() && s[i] != '\'' {
                    i += 1;
                }
            }
            '\'' if s.get(i + 2) == Some(&'\'') => i += 2,
            '/' if s.get(i + 1) == Some(&'/') => {
                while i < s.len() && s[i] != '\n' {
                    i += 1;
                }
            }
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    s.len()
}

/// `.name(` after `at` (past white space and line comments): the name and
/// the index of its `(`.
fn next_method(s: &[char], mut at: usize) -> Option<(String, usize)> {
    loop {
        while at < s.len() && s[at].is_whitespace() {
            at += 1;
        }
        if s.get(at) == Some(&'/') && s.get(at + 1) == Some(&'/') {
            while at < s.len() && s[at] != '\n' {
                at += 1;
            }
            continue;
        }
        break;
    }
    if s.get(at) != Some(&'.') {
        return None;
    }
    at += 1;
    while at < s.len() && s[at].is_whitespace() {
        at += 1;
    }
    let start = at;
    while at < s.len() && (s[at].is_alphanumeric() || s[at] == '_') {
        at += 1;
    }
    let name: String = s[start..at].iter().collect();
    while at < s.len() && s[at].is_whitespace() {
        at += 1;
    }
    (s.get(at) == Some(&'(') && !name.is_empty()).then_some((name, at))
}

#[test]
fn kindless_constructions_are_found() {
    let code = r#"fn f() {
    let a = Diagnostic::error(span, format!("a ({})", ')')).with_hint("h");
    let b = Diagnostic::global("x)")
        // why
        .with_kind(ErrorKind::Syntax);
    let c = Diagnostic::global(r"\").with_kind(crate::diag::ErrorKind::Other);
    let d = Diagnostic::global(m.message).with_hint(x).with_kind(kind.clone());
}"#;
    assert_eq!(kindless(code), vec![2, 6]);
}

/// The files whose constructions other work rewrites (the numeric studies,
/// the given functions, the frequency response, the budget and the
/// expressions): counted, and counted apart in the message.
const COUNTED_APART: &[&str] = &[
    "crates/study/src/cycle/",
    "crates/study/src/floquet/",
    "crates/mechanics/src/scene/given.rs",
    "crates/mechanics/src/solve/response.rs",
    "crates/exact/src/budget.rs",
    "crates/exact/src/limits.rs",
    "crates/exact/src/expr/",
];

/// The error constructions without a specific kind in the library, at
/// most: the two where none fits (`src/cli/study.rs`: a file that cannot
/// be written, where the kinds have a file that cannot be read); none in
/// `crates/`. Lower it when a site gets its kind.
const MAX_KINDLESS: usize = 2;

#[test]
fn errors_carry_a_specific_kind() {
    let mut sites = Vec::new();
    for (name, code) in library_sources() {
        for line in kindless(&code) {
            sites.push(format!("{name}:{line}"));
        }
    }
    let apart = sites
        .iter()
        .filter(|s| COUNTED_APART.iter().any(|p| s.starts_with(p)))
        .count();
    let in_src = sites.iter().filter(|s| s.starts_with("src/")).count();
    assert!(
        sites.len() <= MAX_KINDLESS,
        "{} error constructions without a specific ErrorKind (at most {MAX_KINDLESS}): {in_src} in src/, \
         {apart} in the files counted apart, {} in the rest of crates/; give each its kind \
         (crates/syntax/src/diag.rs lists them):\n{}",
        sites.len(),
        sites.len() - apart - in_src,
        sites.join("\n")
    );
}
