//! Every integer limit is a `pub const` of crates/exact/src/limits.rs or
//! of the command it bounds (listed in [`SOURCES`]); each appears, with
//! its value, in README's "Limits" section and in the book's limits page.

/// The files that define limits: the exact crate's, and the commands'.
const SOURCES: [&str; 2] = [
    include_str!("../crates/exact/src/limits.rs"),
    include_str!("../src/simulate/sweep.rs"),
];

/// `(NAME, value)` for every `pub const NAME: int = value;` of [`SOURCES`].
fn limits() -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for line in SOURCES.iter().flat_map(|s| s.lines()) {
        let Some(rest) = line.strip_prefix("pub const ") else {
            continue;
        };
        let Some((name, value)) = rest.split_once(':') else {
            continue;
        };
        let value = value
            .split('=')
            .nth(1)
            .unwrap_or("")
            .trim()
            .trim_end_matches(';');
        if let Ok(v) = value.replace('_', "").parse::<u64>() {
            out.push((name.to_string(), v));
        }
    }
    out
}

fn grouped(n: u64) -> String {
    qdot::budget::grouped(n as usize)
}

#[test]
fn every_limit_is_documented_with_its_value() {
    let all = limits();
    assert!(all.len() >= 8, "{all:?}");
    // a command's own limit, beside the command
    assert!(
        all.contains(&("MAX_SWEEP_RUNS".to_string(), 1_000_000)),
        "{all:?}"
    );
    let readme = include_str!("../README.md");
    let section = &readme[readme.find("## Limits").expect("a Limits section")..];
    let section = &section[..section[3..].find("\n## ").map_or(section.len(), |i| i + 3)];
    let book = include_str!("../book/src/limits.md");
    for (name, v) in &all {
        let shown = grouped(*v);
        assert!(
            section.contains(&shown),
            "README's Limits section lacks {name} = {shown}"
        );
        assert!(
            book.contains(&shown),
            "book/src/limits.md lacks {name} = {shown}"
        );
    }
}
