//! The limits have one table, the book's limits page: every integer limit
//! appears there with its value. The
//! engine's are in crates/exact/src/limits.rs; a command's live with its
//! code (the `--over` grids' with their reader in scene/given.rs, the
//! cycle's friction iterations in cycle/friction.rs, the sweep's runs in
//! simulate/sweep.rs).

/// Where the limits are defined.
const SOURCES: [&str; 4] = [
    include_str!("../crates/exact/src/limits.rs"),
    include_str!("../src/simulate/sweep.rs"),
    include_str!("../crates/mechanics/src/scene/given.rs"),
    include_str!("../crates/study/src/cycle/friction.rs"),
];

/// `(NAME, value)` for every `pub const NAME: int = value;` of the
/// limits' sources.
fn limits() -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for line in SOURCES.iter().flat_map(|src| src.lines()) {
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
    for found in [
        "MAX_GRID_POINTS",
        "MAX_FRICTION_ITERATIONS",
        "MAX_SWEEP_RUNS",
    ] {
        assert!(all.iter().any(|(n, _)| n == found), "{found}: {all:?}");
    }
    let book = include_str!("../book/src/limits.md");
    for (name, v) in &all {
        let shown = grouped(*v);
        assert!(
            book.contains(&shown),
            "book/src/limits.md lacks {name} = {shown}"
        );
    }
}
