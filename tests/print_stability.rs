//! A scene prints the same whatever the process parsed before it. The
//! canonical forms follow the atoms' interning order, which differs from
//! one process to the next (the REPL, the Python package and these tests
//! parse many scenes in one process); the printers must not. Every example,
//! printed in-process after all the others were parsed in a shuffled order,
//! is the text the command line prints in a fresh process.

use qdot::output::{run, Command, Format};
use std::process::Command as Process;

#[test]
fn every_example_prints_as_in_a_fresh_process() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("examples/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "qd"))
        .collect();
    files.sort();
    // intern every example's atoms first, in an order unlike the files'
    let mut shuffled = files.clone();
    shuffled.reverse();
    shuffled.rotate_left(files.len() / 3);
    let none = Default::default();
    for f in &shuffled {
        let src = std::fs::read_to_string(f).expect("a scene");
        for cmd in [Command::Solve, Command::Modes, Command::Hamilton] {
            let _ = run(cmd, &src, Format::Json, &none);
        }
    }
    let commands = [
        ("derive", Command::Derive),
        ("solve", Command::Solve),
        ("modes", Command::Modes),
        ("equilibrium", Command::Equilibrium),
        ("hamilton", Command::Hamilton),
        ("integrals", Command::Integrals),
    ];
    let mut differ = Vec::new();
    for f in &files {
        let src = std::fs::read_to_string(f).expect("a scene");
        for (name, cmd) in commands {
            let fresh = Process::new(env!("CARGO_BIN_EXE_qdot"))
                .args([name, f.to_str().expect("a path")])
                .output()
                .expect("qdot runs");
            let here = run(cmd, &src, Format::Text, &none);
            if let Ok((text, _)) = here {
                if fresh.status.success() && text.as_bytes() != fresh.stdout.as_slice() {
                    differ.push(format!("{name} {}", f.display()));
                }
            }
        }
    }
    assert!(
        differ.is_empty(),
        "printed differently in-process: {differ:#?}"
    );
}
