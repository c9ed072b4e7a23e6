//! ARCHITECTURE.md against the code: what can be checked mechanically
//! (its length, the crate table against the crates' manifests, the
//! command list against `app::Command::ALL`, the installers of
//! thread-local state against `tests/house_rules.rs`).

use qdot::app::Command;

const DOC: &str = include_str!("../ARCHITECTURE.md");

#[test]
fn the_architecture_stays_short() {
    let lines = DOC.lines().count();
    assert!(lines <= 300, "ARCHITECTURE.md has {lines} lines");
}

/// `(crate, directory, qdot dependencies)` of the crate table's rows.
fn crate_table() -> Vec<(String, String, Vec<String>)> {
    let mut rows = Vec::new();
    for line in DOC.lines().filter(|l| l.starts_with("| `qdot")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let name = cells[1].trim_matches('`').to_string();
        let dir = cells[2].trim_matches('`').to_string();
        let deps = match cells[3] {
            "—" => Vec::new(),
            "all of the above" => vec!["*".to_string()],
            list => list.split(", ").map(|d| format!("qdot-{d}")).collect(),
        };
        rows.push((name, dir, deps));
    }
    rows
}

/// The `qdot-*` names among a manifest's `[dependencies]`.
fn qdot_dependencies(manifest: &str) -> Vec<String> {
    let Some(start) = manifest.find("\n[dependencies]") else {
        return Vec::new();
    };
    let section = &manifest[start + 15..];
    let section = &section[..section.find("\n[").unwrap_or(section.len())];
    let mut deps: Vec<String> = section
        .lines()
        .filter_map(|l| l.split_once(" = ").map(|(k, _)| k.trim().to_string()))
        .filter(|k| k.starts_with("qdot-"))
        .collect();
    deps.sort();
    deps
}

#[test]
fn the_crate_table_is_the_manifests() {
    let rows = crate_table();
    assert_eq!(rows.len(), 7, "{rows:?}");
    let mut crates_seen = Vec::new();
    for (name, dir, mut deps) in rows {
        let path = if dir == "src/" {
            "Cargo.toml".to_string()
        } else {
            format!("{dir}/Cargo.toml")
        };
        let manifest = std::fs::read_to_string(&path).expect("the crate's manifest");
        assert!(
            manifest.contains(&format!("name = \"{name}\"")),
            "{path} is not {name}"
        );
        let actual = qdot_dependencies(&manifest);
        if deps == ["*"] {
            deps = crates_seen.clone();
        }
        deps.sort();
        assert_eq!(actual, deps, "the qdot dependencies of {name}");
        crates_seen.push(name);
    }
}

#[test]
fn the_command_list_is_the_applications() {
    let start = DOC
        .find("Commands (`app::Command::ALL`, in order): ")
        .expect("the command list")
        + "Commands (`app::Command::ALL`, in order): ".len();
    let list = &DOC[start..start + DOC[start..].find('.').expect("its end")];
    let listed: Vec<String> = list
        .split(',')
        .map(|c| c.split_whitespace().collect::<String>())
        .collect();
    let actual: Vec<String> = Command::ALL.iter().map(|c| c.name().to_string()).collect();
    assert_eq!(listed, actual);
}

#[test]
fn the_installers_are_the_ones_the_house_rules_allow() {
    for (file, _) in crate::house_rules::INSTALLERS {
        // a module's name: its file's, or its folder's for a mod.rs
        let mut parts = file.rsplit('/');
        let name = parts.next().unwrap_or(file);
        let stem = match name {
            "mod.rs" => parts.next().unwrap_or(name),
            _ => name.trim_end_matches(".rs"),
        };
        assert!(
            DOC.contains(stem) || DOC.contains(file),
            "ARCHITECTURE.md does not name {file}, which installs thread-local state"
        );
    }
}
