//! A scene prints the same whatever the process parsed before it (the
//! REPL, the Python package and these tests parse many scenes in one
//! process). Every example, printed in-process after all the others were
//! parsed in a shuffled order, is what the command line prints in a fresh
//! process: the text and the JSON, and the same error where the command
//! line refuses. `tests/determinism.rs` compares every command and format
//! after scenes that intern the same names in the opposite order.

use qdot::output::{run, Command, Format};
use std::process::Command as Process;

#[test]
fn every_example_prints_as_in_a_fresh_process() {
    let dir = std::path::Path::new(env!("QDOT_ROOT")).join("examples");
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
        for cmd in [Command::Solve, Command::Modes] {
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
    let (mut compared, mut refused) = (0, 0);
    for f in &files {
        let src = std::fs::read_to_string(f).expect("a scene");
        // the JSON of the two commands that print the most expressions
        for (name, cmd, fmt) in commands.iter().map(|&(n, c)| (n, c, Format::Text)).chain([
            ("solve", Command::Solve, Format::Json),
            ("modes", Command::Modes, Format::Json),
        ]) {
            let format = if fmt == Format::Json { "json" } else { "text" };
            let fresh = Process::new(env!("CARGO_BIN_EXE_qdot"))
                .args([name, f.to_str().expect("a path"), "--format", format])
                .output()
                .expect("qdot runs");
            compared += 1;
            let same = match run(cmd, &src, fmt, &none) {
                Ok((text, _)) => fresh.status.success() && text.as_bytes() == fresh.stdout,
                // refused here and there, with the same message
                Err(e) => {
                    refused += 1;
                    let stderr = String::from_utf8_lossy(&fresh.stderr);
                    let stdout = String::from_utf8_lossy(&fresh.stdout);
                    !fresh.status.success()
                        && (stderr.contains(&e.message) || stdout.contains(&e.message))
                }
            };
            if !same {
                differ.push(format!("{name} --format {format} {}", f.display()));
            }
        }
    }
    assert!(
        differ.is_empty(),
        "printed differently in-process: {differ:#?}"
    );
    // 48 examples × 8 outputs; a handful are refusals (no equilibrium, …)
    assert!(compared >= 380, "{compared} compared");
    assert!(refused * 4 < compared, "{refused} of {compared} refused");
}
