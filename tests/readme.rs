//! Every command of the README runs as written: each `qdot …` line of its
//! code blocks (and `cargo run --release -- …`, the same program) is run
//! by the built binary, in order, in a fresh directory where `examples/`
//! is the repository's and the files the README writes with
//! `cat > FILE <<'END'` … `END` are written first; each must succeed.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A step of the README: write a file, or run qdot with these arguments.
#[derive(Debug, PartialEq)]
enum Step {
    Write(String, String),
    Run(Vec<String>),
}

/// `line`'s words as a POSIX shell splits them (single and double quotes,
/// no expansions), up to an unquoted `#`.
fn words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word: Option<String> = None;
    let mut quote: Option<char> = None;
    for c in line.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, '#') if word.is_none() => break,
            (None, c) if c.is_whitespace() => out.extend(word.take()),
            (None, c) => word.get_or_insert_with(String::new).push(c),
        }
    }
    out.extend(word);
    out
}

/// The README's steps, in order.
fn steps(readme: &str) -> Vec<Step> {
    let mut out = Vec::new();
    let mut in_block = false;
    let mut writing: Option<(String, String, String)> = None;
    for line in readme.lines() {
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            continue;
        }
        if !in_block {
            continue;
        }
        if let Some((file, end, mut text)) = writing.take() {
            if line.trim() == end {
                out.push(Step::Write(file, text));
            } else {
                text.push_str(line);
                text.push('\n');
                writing = Some((file, end, text));
            }
            continue;
        }
        let w = words(line);
        match w.iter().map(String::as_str).collect::<Vec<_>>().as_slice() {
            ["cat", ">", file, here] if here.starts_with("<<") => {
                let end = here.trim_start_matches('<').to_string();
                writing = Some((file.to_string(), end, String::new()));
            }
            ["qdot", ..] => out.push(Step::Run(w[1..].to_vec())),
            ["cargo", "run", "--release", "--", ..] => out.push(Step::Run(w[4..].to_vec())),
            _ => {}
        }
    }
    out
}

/// A fresh directory with `examples/` linked to the repository's.
fn workdir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("qdot-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("a temporary directory");
    let examples = Path::new(env!("QDOT_ROOT")).join("examples");
    std::os::unix::fs::symlink(examples, d.join("examples")).expect("a link to examples/");
    d
}

#[test]
fn every_readme_command_runs_as_written() {
    let readme = include_str!("../README.md");
    let steps = steps(readme);
    let runs = steps.iter().filter(|s| matches!(s, Step::Run(_))).count();
    assert!(runs >= 6, "{steps:?}");
    let dir = workdir();
    for step in &steps {
        match step {
            Step::Write(file, text) => std::fs::write(dir.join(file), text).expect("written"),
            Step::Run(args) => {
                let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
                    .args(args)
                    .current_dir(&dir)
                    .output()
                    .expect("qdot runs");
                assert!(
                    out.status.success(),
                    "qdot {}: {}\n{}",
                    args.join(" "),
                    out.status,
                    String::from_utf8_lossy(&out.stderr)
                );
                assert!(
                    !out.stdout.is_empty(),
                    "qdot {} printed nothing",
                    args.join(" ")
                );
            }
        }
    }
    // the first session's plot
    let svg = std::fs::read_to_string(dir.join("pendulum.svg")).expect("the plot is written");
    assert!(
        svg.contains("A pendulum"),
        "the title is the scene's first comment"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn readme_steps_are_read_as_a_shell_reads_them() {
    assert_eq!(
        words("qdot simulate p.qd --init \"theta=1,theta'=0\"   # a comment"),
        ["qdot", "simulate", "p.qd", "--init", "theta=1,theta'=0"]
    );
    assert_eq!(
        steps("```sh\ncat > a.qd <<'END'\ncoordinates x\nEND\nqdot derive a.qd\npip install x\n```\nqdot outside\n"),
        [
            Step::Write("a.qd".into(), "coordinates x\n".into()),
            Step::Run(vec!["derive".into(), "a.qd".into()])
        ]
    );
}
