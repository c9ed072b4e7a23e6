//! `qdot simulate`'s progress bar in a real pseudo-terminal (rexpect): it
//! appears on a terminal for a run longer than half a second, is cleared
//! before the results are printed, and never appears when standard error
//! is not a terminal.
//!
//! The run: the 10-link chain by RK4 with dt = 2·10⁻⁵ over 10 s (2·10⁶
//! right-hand sides, ≈ 1.2–5 s; at 8·10⁵ an idle machine finished in
//! 0.49 s, before the bar's half second), interpreted: machine code, the default past
//! 25,000 right-hand sides, could end it before the bar shows.

use rexpect::session::PtySession;
use std::path::PathBuf;
use std::process::Command;

/// Generous: CI machines are shared and slow.
const TIMEOUT_MS: u64 = 60_000;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("qdot-simpty-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The chain's scene in `d`, and the arguments of a long run of it.
fn long_run(d: &std::path::Path) -> Vec<String> {
    let file = d.join("chain10.qd");
    std::fs::write(&file, qdot::engine::gallery::pendulum_chain(10)).unwrap();
    let mut init: Vec<String> = (1..=10)
        .map(|i| format!("q{i}={}", 0.3 + 0.02 * (i - 1) as f64))
        .collect();
    init.extend((1..=10).map(|i| format!("q{i}'=0")));
    [
        "simulate",
        file.to_str().unwrap(),
        "--set",
        "m=1,l=1,g=9.81",
        "--init",
        &init.join(","),
        "--t-end",
        "10",
        "--method",
        "rk4",
        "--dt",
        "2e-5",
        "--points",
        "3",
        "--stats",
        "--evaluator",
        "interpreter",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

/// rexpect reads the terminal byte by byte, each byte a char.
fn text(s: &str) -> String {
    s.bytes().map(char::from).collect()
}

fn expect(p: &mut PtySession, needle: &str) -> String {
    match p.exp_string(&text(needle)) {
        Ok(before) => before,
        Err(e) => panic!("expected `{needle}`: {e}"),
    }
}

#[test]
fn the_bar_shows_on_a_terminal_and_is_cleared() {
    let d = dir("bar");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_qdot"));
    cmd.args(long_run(&d)).env("TERM", "xterm");
    let mut p = rexpect::session::spawn_command(cmd, Some(TIMEOUT_MS)).expect("qdot starts");
    expect(&mut p, "simulating to t = 10 [");
    // the bar moves: some percentage short of the end is drawn
    let drawn = expect(&mut p, "% ");
    assert!(drawn.len() < 300, "{drawn:?}");
    // the CSV header comes after the bar has been cleared (ESC [2K)
    let rest = expect(&mut p, "t,q1,q2,");
    assert!(rest.contains("\u{1b}[2K"), "not cleared: {rest:?}");
    let tail = expect(&mut p, "method rk4: 500001 steps");
    assert!(!tail.contains("simulating"), "{tail:?}");
    p.exp_eof().unwrap();
}

#[test]
fn no_bar_when_stderr_is_a_file() {
    let d = dir("file");
    let err = d.join("stderr.txt");
    // stdout is the terminal, stderr a file: the shell redirects it
    let quoted: Vec<String> = long_run(&d)
        .iter()
        .map(|a| format!("'{}'", a.replace('\'', "'\\''")))
        .collect();
    let script = format!(
        "'{}' {} 2> '{}'",
        env!("CARGO_BIN_EXE_qdot"),
        quoted.join(" "),
        err.display()
    );
    let mut cmd = Command::new("sh");
    cmd.args(["-c", &script]).env("TERM", "xterm");
    let mut p = rexpect::session::spawn_command(cmd, Some(TIMEOUT_MS)).expect("sh starts");
    let out = p.exp_eof().unwrap();
    assert!(out.contains("t,q1,q2,"), "{out:?}");
    assert!(!out.contains("simulating"), "{out:?}");
    let stderr = std::fs::read_to_string(&err).unwrap();
    assert!(stderr.starts_with("method rk4: 500001 steps"), "{stderr:?}");
    assert!(!stderr.contains("simulating"), "{stderr:?}");
    assert!(!stderr.contains('\u{1b}'), "{stderr:?}");
    assert!(!stderr.contains('%'), "{stderr:?}");
}
