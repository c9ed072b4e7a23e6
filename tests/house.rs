//! The house's sizes, enforced: no source file of the workspace (the
//! `qdot` package's `src/` and every `crates/*/src/`) over 1,500 lines, no
//! function over 150 (ports of published algorithms excepted, by name).
//! The layer order itself is Cargo's: each layer is a crate, and a crate
//! names only the crates it depends on.

use std::path::{Path, PathBuf};

/// Every source directory of the workspace, with the prefix its files are
/// named by.
fn source_dirs() -> Vec<PathBuf> {
    let root = Path::new(env!("QDOT_ROOT"));
    let mut dirs = vec![root.join("src")];
    let mut crates: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .expect("crates/ is readable")
        .map(|e| e.expect("an entry").path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    crates.sort();
    dirs.extend(crates);
    dirs
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("a source directory is readable") {
        let p = e.expect("an entry").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Functions allowed over 150 lines: ports of published algorithms, kept in
/// the shape of their source (ARCHITECTURE.md, "Layers are crates").
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
    let root = Path::new(env!("QDOT_ROOT"));
    let mut files = Vec::new();
    for dir in source_dirs() {
        rust_files(&dir, &mut files);
    }
    assert!(
        files.len() > 100,
        "the scan finds the sources: {}",
        files.len()
    );
    let mut wrong = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("readable");
        let rel = f
            .strip_prefix(root)
            .expect("under the root")
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
