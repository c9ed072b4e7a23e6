//! ARCHITECTURE.md's layer order, enforced: a module of `src/` may name
//! (`crate::x`, `super::super::x`) only the modules of lower layers and
//! its own. The table below is the one ARCHITECTURE.md states.

use std::path::Path;

/// Layers, lowest first; the modules of one layer do not use each other.
const LAYERS: &[&[&str]] = &[
    // exact arithmetic charges the work budget
    &["budget"],
    &["num", "cancel", "limits", "gallery", "unicode", "dense"],
    &["poly"],
    &["expr"],
    &["algebra"],
    &["diag"],
    &["parse"],
    &["scene"],
    &["mechanics"],
    &["solve"],
    &["output", "simulate"],
    &["repl"],
];

fn layer_of(module: &str) -> Option<usize> {
    // the crate root's re-exports, by the module they come from
    let module = match module {
        "Scene" => "scene",
        "Expr" => "expr",
        "Lagrange" => "mechanics",
        "Diagnostic" => "diag",
        m => m,
    };
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The top-level modules named by `crate::NAME` in `text` (comments left
/// out; a `use crate::{…}` list may span lines).
fn named_modules(text: &str) -> Vec<String> {
    let code: String = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let mut out = Vec::new();
    let mut rest = code.as_str();
    while let Some(i) = rest.find("crate::") {
        rest = &rest[i + "crate::".len()..];
        if let Some(list) = rest.strip_prefix('{') {
            out.extend(top_level_names(list));
        } else {
            let name = ident(rest);
            if !name.is_empty() {
                out.push(name);
            }
        }
    }
    out
}

/// The first name of each item of a `{a::b, c, d::{e, f}}` list (its
/// opening brace already read).
fn top_level_names(list: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut depth = 1;
    let mut at_start = true;
    let mut name = String::new();
    for c in list.chars() {
        match c {
            '{' => depth += 1,
            '}' if depth == 1 => break,
            '}' => depth -= 1,
            ',' if depth == 1 => {
                if !name.is_empty() {
                    out.push(std::mem::take(&mut name));
                }
                at_start = true;
            }
            c if at_start && (c.is_ascii_alphanumeric() || c == '_') => name.push(c),
            c if at_start && !c.is_whitespace() && !name.is_empty() => {
                out.push(std::mem::take(&mut name));
                at_start = false;
            }
            _ => {}
        }
    }
    if !name.is_empty() {
        out.push(name);
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).expect("src/ is readable") {
        let p = e.expect("an entry").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

#[test]
fn every_module_uses_only_lower_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut wrong = Vec::new();
    let mut unknown = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).expect("under src");
        let first = rel.components().next().expect("a component");
        let module = first
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        if module == "lib" || module == "main" {
            continue; // the crate roots re-export and drive everything
        }
        let Some(own) = layer_of(&module) else {
            unknown.push(module.clone());
            continue;
        };
        let text = std::fs::read_to_string(f).expect("readable");
        for used in named_modules(&text) {
            if used == module {
                continue;
            }
            match layer_of(&used) {
                Some(l) if l < own => {}
                Some(_) => wrong.push(format!("{}: uses crate::{used}", rel.display())),
                None => unknown.push(used),
            }
        }
    }
    unknown.sort();
    unknown.dedup();
    assert!(
        unknown.is_empty(),
        "modules missing from the layer table (and ARCHITECTURE.md): {unknown:?}"
    );
    wrong.sort();
    wrong.dedup();
    assert!(
        wrong.is_empty(),
        "uses of a module of the same or a higher layer:\n{wrong:?}"
    );
}

#[test]
fn the_scanner_finds_what_it_must() {
    let names = named_modules(
        "use crate::{\n    expr::{Expr, print},\n    poly::Poly, num};\nlet x = crate::num::Q::one(); // crate::repl\n",
    );
    assert_eq!(names, ["expr", "poly", "num", "num"]);
    assert_eq!(top_level_names("a, b::c}"), ["a", "b"]);
}

/// Functions allowed over 150 lines: ports of published algorithms, kept in
/// the shape of their source (ARCHITECTURE.md, "Size").
const LONG_PORTS: &[&str] = &["radau5_core", "gauss6", "zippel_gcd", "hensel_factor"];

/// The functions of `text` longer than `limit` lines (from the `fn` line to
/// the closing brace at the same indentation), with their lengths.
fn long_functions(text: &str, limit: usize) -> Vec<(String, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, l) in lines.iter().enumerate() {
        let body = l.trim_start();
        let indent = &l[..l.len() - body.len()];
        let after_fn = ["pub fn ", "pub(crate) fn ", "pub(super) fn ", "fn "]
            .iter()
            .find_map(|p| body.strip_prefix(p));
        let Some(rest) = after_fn else { continue };
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // a declaration without a body (in a trait) ends with `;`
        let Some(open) =
            (i..lines.len()).find(|&j| lines[j].contains('{') || lines[j].ends_with(';'))
        else {
            continue;
        };
        if !lines[open].contains('{') {
            continue;
        }
        let close = format!("{indent}}}");
        if let Some(end) = (open + 1..lines.len()).find(|&j| lines[j] == close) {
            if end - i + 1 > limit {
                out.push((name, end - i + 1));
            }
        }
    }
    out
}

#[test]
fn files_and_functions_stay_small() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut wrong = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("readable");
        let rel = f
            .strip_prefix(&src)
            .expect("under src")
            .display()
            .to_string();
        let n = text.lines().count();
        if n > 1500 {
            wrong.push(format!("{rel}: {n} lines"));
        }
        for (name, len) in long_functions(&text, 150) {
            if !LONG_PORTS.contains(&name.as_str()) {
                wrong.push(format!("{rel}: fn {name} is {len} lines"));
            }
        }
    }
    assert!(wrong.is_empty(), "over the size limits:\n{wrong:#?}");
}

#[test]
fn the_function_measure_counts_lines() {
    let text =
        "fn a() {\n    x;\n}\n    pub fn b(\n        y: u8,\n    ) -> u8 {\n        1\n    }\n";
    assert_eq!(
        long_functions(text, 2),
        [("a".to_string(), 3), ("b".to_string(), 5)]
    );
    assert!(long_functions(text, 5).is_empty());
}
