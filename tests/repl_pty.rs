//! The REPL in a real pseudo-terminal (rexpect): what a user types and
//! sees, with line editing, history, Ctrl-C and Ctrl-D.
//!
//! Each test starts `qdot` with its own data directory
//! (`XDG_DATA_HOME`), so the history file is the test's own.

use rexpect::session::PtySession;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Generous: CI machines are shared and slow.
const TIMEOUT_MS: u64 = 30_000;

fn data_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("qdot-pty-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn start(data: &Path, args: &[&str]) -> PtySession {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_qdot"));
    cmd.args(args)
        .env("XDG_DATA_HOME", data)
        .env("TERM", "xterm")
        .env("NO_COLOR", "1");
    let mut p = rexpect::session::spawn_command(cmd, Some(TIMEOUT_MS)).expect("qdot starts");
    expect(&mut p, ":help for help");
    prompt(&mut p);
    p
}

/// rexpect reads the terminal byte by byte, each byte a char: a needle
/// with UTF-8 text has to be spelled the same way.
fn bytes(s: &str) -> String {
    s.bytes().map(char::from).collect()
}

fn expect(p: &mut PtySession, needle: &str) {
    if let Err(e) = p.exp_string(&bytes(needle)) {
        panic!("expected `{needle}`: {e}");
    }
}

/// Type a line, wait for what it prints (`needle`, may be empty) and for
/// the next prompt, so that nothing is typed ahead of the line editor.
fn enter(p: &mut PtySession, line: &str, needle: &str) {
    p.send_line(line).expect("typed");
    if !needle.is_empty() {
        if let Err(e) = p.exp_string(&bytes(needle)) {
            panic!("after `{line}`, expected `{needle}`: {e}");
        }
    }
    prompt(p);
}

/// Wait for the prompt (`qdot> ` or the continuation `  ... `).
fn prompt(p: &mut PtySession) {
    use rexpect::ReadUntil;
    if let Err(e) = p.exp_any(vec![
        ReadUntil::String("qdot> ".into()),
        ReadUntil::String("  ... ".into()),
    ]) {
        panic!("expected a prompt: {e}");
    }
}

/// The printer dots letters with combining marks: ÿ is y + U+0308.
const Y_DDOT: &str = "y\u{308}";

#[test]
fn derive_seed_23_4_line_by_line_and_solve() {
    let data = data_dir("seed");
    let mut p = start(&data, &[]);
    enter(&mut p, "coordinates y3, theta3", "");
    enter(&mut p, "parameters G, g, r", "");
    enter(&mut p, "m = G/g", "m = G/g");
    for l in [
        "mu = 1/8",
        "J3 = 4*G*r^2/g",
        "J4 = 4*G*r^2/g",
        "y1 = y3 + 2*r*theta3",
        "y2 = y3 - r*theta3",
        "theta4 = y3/(2*r)",
        "x5 = y3/2",
        "kinetic E1 = 1/2*m*y1'^2",
        "kinetic E2 = 1/2*m*y2'^2",
        "kinetic E3 = 1/2*(3*m)*y3'^2 + 1/2*J3*theta3'^2",
        "kinetic E4 = 1/2*J4*theta4'^2",
        "kinetic E5 = 1/2*(2*m)*x5'^2",
    ] {
        enter(&mut p, l, "");
    }
    // a statement over two lines: the continuation prompt
    enter(&mut p, "forcefunction U = G*y1 + G*y2 +", "");
    enter(&mut p, "  3*G*y3", "U = 5·G·y₃ + G·r·θ₃");
    enter(&mut p, "work L = -mu*2*G*x5", "L = −1/8·G·y₃");
    p.send_line(":solve").unwrap();
    expect(&mut p, &format!("{Y_DDOT}₃ = 343/460·g"));
    expect(&mut p, "13/460·g/r");
    prompt(&mut p);
    enter(&mut p, "diff(U, y3)", "5·G");
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}

#[test]
fn a_typo_line_then_a_correct_one() {
    let data = data_dir("typo");
    let mut p = start(&data, &[]);
    enter(&mut p, "parameters m, k", "");
    p.send_line("w = sqrt(k/mm)").unwrap();
    expect(&mut p, "error: unknown name `mm`");
    expect(&mut p, "--> input:1:12");
    expect(&mut p, "^^");
    expect(&mut p, "did you mean `m`?");
    // the session is as it was: k and m are still there
    enter(&mut p, "w = sqrt(k/m)", "w = √(k)·√(m)/m");
    enter(&mut p, "w^2", "k/m");
    p.send_line(":quit").unwrap();
    p.exp_eof().unwrap();
}

#[test]
fn ctrl_c_drops_the_entry_being_typed_and_the_session_goes_on() {
    let data = data_dir("ctrlc");
    let mut p = start(&data, &[]);
    enter(&mut p, "parameters a", "");
    // half an entry, then Ctrl-C: dropped
    enter(&mut p, "b = (a +", "");
    p.send_control('c').unwrap();
    expect(&mut p, "(entry dropped)");
    prompt(&mut p);
    // text typed on the line, then Ctrl-C: the line is dropped
    p.send("c = 1").unwrap();
    p.flush().unwrap();
    p.send_control('c').unwrap();
    expect(&mut p, "(Ctrl-D or :quit leaves)");
    prompt(&mut p);
    enter(&mut p, "2*a + a", "3·a");
    enter(&mut p, ":show b", "`b` is not in the scene");
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}

#[test]
fn ctrl_c_interrupts_a_long_computation() {
    let data = data_dir("long");
    let mut p = start(&data, &[]);
    enter(&mut p, "parameters a, b, c, d, e, f", "");
    enter(&mut p, "x = 2*a", "x = 2·a");
    // past the default work budget: raised, so that it runs for minutes
    enter(
        &mut p,
        ":max-terms 1000000000",
        "(at most 1,000,000,000 terms per expression)",
    );
    // takes minutes: interrupted after a moment
    p.send_line("(a + b + c + d + e + f)^40").unwrap();
    // Enter accepted (the line editor has left raw mode, so Ctrl-C is a
    // signal now), and the computation under way
    p.exp_string("\r\n").unwrap();
    std::thread::sleep(std::time::Duration::from_millis(500));
    p.send_control('c').unwrap();
    expect(&mut p, "(interrupted; the session is as it was)");
    prompt(&mut p);
    // the session answers at once, with its definitions
    enter(&mut p, "x + a", "3·a");
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}

#[test]
fn history_is_recalled_after_a_restart() {
    let data = data_dir("history");
    let mut p = start(&data, &[]);
    enter(&mut p, "parameters m, k", "");
    enter(&mut p, "sqrt(k/m) * 7", "7·√(k)·√(m)/m");
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
    let file = data.join("qdot").join("history.txt");
    let saved = std::fs::read_to_string(&file).expect("the history file");
    assert!(saved.contains("sqrt(k/m) * 7"), "{saved}");

    // a new session: Up recalls the last entry, Up again the one before
    let mut p = start(&data, &[]);
    p.send("\x1b[A\x1b[A").unwrap(); // Up, Up: `parameters m, k`
    p.flush().unwrap();
    p.send_line("").unwrap();
    // the redraws after Up also show `qdot> `: wait for Enter's newline
    p.exp_string("\r\n").unwrap();
    prompt(&mut p);
    p.send("\x1b[A\x1b[A").unwrap(); // Up, Up: the expression (after the new entry)
    p.flush().unwrap();
    p.send_line("").unwrap();
    expect(&mut p, "7·√(k)·√(m)/m");
    prompt(&mut p);
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}

#[test]
fn repl_starts_from_a_file_and_completes_names() {
    let data = data_dir("file");
    let mut p = start(&data, &["repl", "examples/seed_23_4.qd"]);
    // start() saw the banner and the prompt; the file was loaded between
    // them, so ask for something from it
    enter(&mut p, ":show mu", "μ = 1/8");
    // Tab completes the only name starting with `x`
    p.send("1 + x").unwrap();
    p.send("\t").unwrap();
    p.flush().unwrap();
    p.send("\r").unwrap();
    p.flush().unwrap();
    expect(&mut p, "1/2·y₃ + 1");
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}

/// Thirty lines typed ahead in one write (a fast paste, or a script driving
/// the terminal), each defining `x_k` from `x_{k-1}`: every line is read and
/// run, in order, so the last one's value is 2^30 times the first.
#[test]
fn lines_typed_ahead_are_all_processed_in_order() {
    let data = data_dir("typeahead");
    let mut p = start(&data, &[]);
    // a comment on each line makes the block (~3 KB) longer than the line
    // editor's read buffer, so part of it waits in the terminal while the
    // first entries run
    let pad = "# doubled ".repeat(8);
    let mut block = String::from("x1 = 1\n");
    for k in 2..=30 {
        block.push_str(&format!("x{k} = 2*x{}  {pad}\n", k - 1));
    }
    assert!(block.len() > 2048);
    block.push_str("x30 + 0\n");
    p.send(&block).unwrap();
    p.flush().unwrap();
    // 2^29: x1 = 1 doubled 29 times
    expect(&mut p, "\n536870912");
    prompt(&mut p);
    enter(&mut p, ":show x17", "= 65536");
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}

/// The banner is printed once, before the first prompt.
#[test]
fn the_banner_is_printed_once() {
    let data = data_dir("banner");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_qdot"));
    cmd.env("XDG_DATA_HOME", &data)
        .env("TERM", "xterm")
        .env("NO_COLOR", "1");
    let mut p = rexpect::session::spawn_command(cmd, Some(TIMEOUT_MS)).expect("qdot starts");
    expect(&mut p, ":help for help");
    // between the banner and the first prompt: no second banner
    let before = p.exp_string("qdot> ").expect("the first prompt");
    assert!(!before.contains(":help for help"), "{before:?}");
    enter(&mut p, "1 + 1", "2");
    p.send_control('d').unwrap();
    let rest = p.exp_eof().expect("the end");
    assert!(!rest.contains(":help for help"), "{rest:?}");
}

/// A bracketed paste (what a terminal sends when text is pasted) of several
/// lines, a command among them: each line is taken as if typed on its own.
#[test]
fn a_pasted_block_runs_line_by_line() {
    let data = data_dir("paste");
    let mut p = start(&data, &[]);
    p.send("\x1b[200~parameters a\nb = 3*a\n:show b\nb + a\x1b[201~\r")
        .unwrap();
    p.flush().unwrap();
    expect(&mut p, "b = 3·a");
    expect(&mut p, "4·a");
    prompt(&mut p);
    p.send_control('d').unwrap();
    p.exp_eof().unwrap();
}
