//! `qdot cycle` chooses its output by where it goes: on a terminal (a real
//! pseudo-terminal, rexpect) the reactions as an aligned table, piped the
//! whole CSV, whose columns have unique names; `--output`/`--format`
//! choose either way.

use crate::common::run::qdot;
use std::process::Command;

/// Generous: CI machines are shared and slow.
const TIMEOUT_MS: u64 = 60_000;

/// The slider-crank of seed 21.3 at 5 positions.
const ARGS: [&str; 8] = [
    "cycle",
    "examples/seed_21_3.qd",
    "--over",
    "phi=0:360deg:5",
    "--set",
    "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20",
    "--guess",
    "x2=0.25,xB=0.5",
];

/// The table a terminal shows.
const TABLE: &str = "\
phi (deg)       O_x      O_y       A_x       A_y       B_x       B_y      S_n        M       S_f
    0 [1]  -95.2082   29.375  -95.2082     9.375  -28.3121    -5.625   15.625   0.9375   2.34375
    0 [1]  -90.5207   29.375  -90.5207     9.375  -23.6246    -5.625   15.625   0.9375  -2.34375
       90  -15.1637  5.02115  -15.1637  -14.9789  -21.0857   8.24745  1.75255  1.51637  0.262883
  180 [2]   8.66542   29.375   8.66542     9.375  -46.7627    -5.625   15.625  -0.9375   2.34375
  180 [2]   13.3529   29.375   13.3529     9.375  -42.0752    -5.625   15.625  -0.9375  -2.34375
      270   -10.651   54.894   -10.651    34.894   -16.573  -18.3323  28.3323  -1.0651  -4.24984
  360 [3]  -90.5207   29.375  -90.5207     9.375  -23.6246    -5.625   15.625   0.9375  -2.34375
  360 [3]  -95.2082   29.375  -95.2082     9.375  -28.3121    -5.625   15.625   0.9375   2.34375
[1] row 1: stick: the relative velocity in the joint `S` vanishes here (0.0e0), so its friction may be anywhere between its values for sliding either way: the reactions are given at both, the limits v → 0⁻ and v → 0⁺ (the first line the limit v → 0⁻, the second v → 0⁺)
[2] row 3: stick: the relative velocity in the joint `S` vanishes here (-1.8e-16), so its friction may be anywhere between its values for sliding either way: the reactions are given at both, the limits v → 0⁻ and v → 0⁺ (the first line the limit v → 0⁻, the second v → 0⁺)
[3] row 5: stick: the relative velocity in the joint `S` vanishes here (6.1e-16), so its friction may be anywhere between its values for sliding either way: the reactions are given at both, the limits v → 0⁻ and v → 0⁺ (the first line the limit v → 0⁺, the second v → 0⁻)
";

/// What qdot printed on a pseudo-terminal, line ends as written.
fn on_terminal(extra: &[&str]) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_qdot"));
    cmd.args(ARGS)
        .args(extra)
        .current_dir(env!("QDOT_ROOT"))
        .env("TERM", "xterm");
    let mut p = rexpect::session::spawn_command(cmd, Some(TIMEOUT_MS)).expect("qdot starts");
    let out = p.exp_eof().expect("qdot ends");
    // rexpect reads byte by byte, each byte a char
    let bytes: Vec<u8> = out.chars().map(|c| c as u8).collect();
    String::from_utf8(bytes)
        .expect("UTF-8")
        .replace("\r\n", "\n")
}

#[test]
fn a_terminal_gets_the_reactions_as_a_table() {
    assert_eq!(on_terminal(&[]), TABLE);
    // asked for, CSV on a terminal too
    let csv = on_terminal(&["--format", "csv"]);
    assert!(csv.starts_with("phi (varied),x1,y1,phi,"), "{csv}");
}

#[test]
fn a_pipe_gets_the_csv_with_unique_column_names() {
    let (code, out, err) = qdot(&ARGS);
    assert_eq!(code, 0, "{err}");
    let header = out.lines().next().unwrap_or("");
    assert_eq!(
        header,
        "phi (varied),x1,y1,phi,x2,y2,alpha,xB,yB,x1',y1',phi',x2',y2',alpha',xB',yB',\
         x1'',y1'',phi'',x2'',y2'',alpha'',xB'',yB'',O_x,O_y,A_x,A_y,B_x,B_y,S_n,M,S_f,note"
    );
    // the rows keep every digit
    let second = out.lines().nth(3).unwrap_or("");
    assert!(
        second.starts_with("1.57079632679489656e0,0.00000000000000000e0,"),
        "{second}"
    );
    // asked for, the table when piped too
    let (_, text, _) = qdot(&[&ARGS[..], &["--output", "text"]].concat());
    assert_eq!(text, TABLE);
}
