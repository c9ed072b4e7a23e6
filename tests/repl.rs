//! The REPL's engine (`qdot::repl::Session`) and its piped mode: every
//! statement, function and command, with the exact output.

use pretty_assertions::assert_eq;
use qdot::repl::{is_complete, Session};

/// Seed problem 23.4 entered line by line (examples/seed_23_4.qd).
const SEED_23_4: &[&str] = &[
    "coordinates y3, theta3",
    "parameters G, g, r",
    "mu = 1/8",
    "m = G/g",
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
    "forcefunction U = G*y1 + G*y2 + 3*G*y3",
    "work L = -mu*2*G*x5",
];

fn seed() -> Session {
    let mut s = Session::new();
    for l in SEED_23_4 {
        let r = s.execute(l);
        assert!(!r.failed, "{l}: {}", r.err);
    }
    s
}

/// The printer dots letters with combining marks (y + U+0307); the
/// expectations here are typed with the precomposed letters.
fn composed(s: &str) -> String {
    s.replace("y\u{307}", "ẏ")
        .replace("y\u{308}", "ÿ")
        .replace("x\u{307}", "ẋ")
        .replace("x\u{308}", "ẍ")
}

/// The output of one entry, which must succeed without warnings.
fn ok(s: &mut Session, entry: &str) -> String {
    let r = s.execute(entry);
    assert!(!r.failed, "{entry}: {}", r.err);
    assert_eq!(r.err, "", "{entry}");
    composed(&r.out)
}

/// The error text of one entry, which must fail.
fn err(s: &mut Session, entry: &str) -> String {
    let r = s.execute(entry);
    assert!(r.failed, "{entry} should fail, printed {}", r.out);
    composed(&r.err)
}

#[test]
fn seed_23_4_line_by_line_solves_to_the_corrected_answer() {
    let mut s = seed();
    let out = ok(&mut s, ":solve");
    assert!(out.contains("ÿ₃ = 343/460·g"), "{out}");
    assert!(out.contains("θ̈₃ = 13/460·g/r"), "{out}");
    // the same as the CLI on the bundled example
    let file = std::fs::read_to_string("examples/seed_23_4.qd").unwrap();
    let (cli, _) = qdot::output::run(
        qdot::output::Command::Solve,
        &file,
        qdot::output::Format::Text,
        &Default::default(),
    )
    .unwrap();
    assert_eq!(out, composed(&cli));
}

#[test]
fn definitions_echo_their_canonical_value() {
    let mut s = Session::new();
    ok(&mut s, "coordinates y3, theta3");
    assert_eq!(ok(&mut s, "parameters G, g, r"), "");
    assert_eq!(ok(&mut s, "m = G/g"), "m = G/g\n");
    assert_eq!(ok(&mut s, "x5 = y3/2"), "x₅ = 1/2·y₃\n");
    assert_eq!(
        ok(&mut s, "kinetic E5 = 1/2*(2*m)*x5'^2"),
        "E₅ = G/(4·g)·ẏ₃²\n"
    );
    // several statements on one line
    assert_eq!(ok(&mut s, "a = 1; b = a + 1"), "a = 1\nb = 2\n");
}

#[test]
fn expressions_and_the_functions_of_the_repl() {
    let mut s = seed();
    assert_eq!(ok(&mut s, "diff(E1, y3')"), "G/g·ẏ₃ + 2·G·r/g·θ̇₃\n");
    // `_` is the last result; dt is the total time derivative
    assert_eq!(ok(&mut s, "dt(_)"), "G/g·ÿ₃ + 2·G·r/g·θ̈₃\n");
    assert_eq!(ok(&mut s, "diff(U, y3)"), "5·G\n");
    assert_eq!(ok(&mut s, "diff(L, y3)"), "−1/8·G\n");
    assert_eq!(ok(&mut s, "subs(E3, theta3' = 0)"), "3/2·G/g·ẏ₃²\n");
    assert_eq!(ok(&mut s, "subs(U, y3 = 0, theta3 = 1)"), "G·r\n");
    assert_eq!(
        ok(&mut s, "taylor(cos(theta3), theta3, 4)"),
        "1 − 1/2·θ₃² + 1/24·θ₃⁴\n"
    );
    // series(f, q, n) with q a coordinate is the Taylor series
    assert_eq!(
        ok(&mut s, "series(sin(theta3), theta3, 5)"),
        "θ₃ − 1/6·θ₃³ + 1/120·θ₃⁵\n"
    );
    // about another point, in powers of θ − π
    assert_eq!(
        ok(&mut s, "taylor(sin(theta3), theta3 = pi, 3)"),
        "−(θ₃ − π) + 1/6·(θ₃ − π)³\n"
    );
    // the value is the polynomial itself: −θ + π + (θ − π)³/6 expanded
    assert_eq!(ok(&mut s, "_ - (pi - theta3) - (theta3 - pi)^3/6"), "0\n");
    assert_eq!(
        ok(&mut s, "series(exp(theta3), theta3 = -1, 2)"),
        "1/exp(1) + 1/exp(1)·(θ₃ + 1) + 1/(2·exp(1))·(θ₃ + 1)²\n"
    );
    // expand shows every term
    assert_eq!(
        ok(&mut s, "expand((y3 + r)^3)"),
        "y₃³ + 3·r·y₃² + 3·r²·y₃ + r³\n"
    );
    // over a sum: every numerator term, by descending degree
    assert_eq!(
        ok(&mut s, "expand((y3 + r)^2/(y3 - r))"),
        "(y₃² + 2·r·y₃ + r²)/(y₃ − r)\n"
    );
    // the value of expand/factor is the canonical expression itself
    assert_eq!(ok(&mut s, "expand((y3 + r)^2) - (y3 + r)^2"), "0\n");
    // vectors
    assert_eq!(ok(&mut s, "[y1, y2]'"), "[ẏ₃ + 2·r·θ̇₃, ẏ₃ − r·θ̇₃]\n");
    assert_eq!(ok(&mut s, "diff([y1, y2], theta3)"), "[2·r, −r]\n");
}

#[test]
fn factor_shows_irreducible_factors_over_the_rationals() {
    let mut s = Session::new();
    ok(&mut s, "parameters k, m, x, y");
    assert_eq!(ok(&mut s, "factor(x^2 - y^2)"), "(x + y)·(x − y)\n");
    assert_eq!(
        ok(&mut s, "factor(k^2 - 7*k*m + 6*m^2)"),
        "(k − 6·m)·(k − m)\n"
    );
    assert_eq!(ok(&mut s, "factor(2*x^2 + 4*x + 2)"), "2·(x + 1)²\n");
    assert_eq!(ok(&mut s, "factor(x^4 + 1)"), "x⁴ + 1\n");
    assert_eq!(
        ok(&mut s, "factor(-(x^2 - 1)/(2*x^2 + 4*x*y + 2*y^2))"),
        "−1/2·(x + 1)·(x − 1)/(x + y)²\n"
    );
    // the three-mass chain's irreducible quadratic in λ (names private to
    // this test: ties in the printer's order follow the order atoms were
    // first interned in, process-wide)
    ok(&mut s, "parameters kf, mf, lf");
    assert_eq!(
        ok(&mut s, "factor(2*kf^2 - 4*kf*mf*lf + mf^2*lf^2)"),
        "lf²·mf² − 4·kf·lf·mf + 2·kf²\n"
    );
    assert_eq!(
        ok(&mut s, "factor((x^2 - 1)/(x^2 + 2*x*y + y^2))"),
        "(x + 1)·(x − 1)/(x + y)²\n"
    );
    ok(&mut s, ":format latex");
    assert_eq!(
        ok(&mut s, "factor(-(x^2 - 1)/(2*x^2 + 4*x*y + 2*y^2))"),
        "-\\frac{\\left(x + 1\\right) \\left(x - 1\\right)}{2 \\left(x + y\\right)^{2}}\n"
    );
    assert_eq!(ok(&mut s, "factor(6*x^2/5)"), "\\frac{6 x^{2}}{5}\n");
}

#[test]
fn a_bad_line_changes_nothing_and_points_at_the_token() {
    let mut s = seed();
    let before = s.scene_text();
    let e = err(&mut s, "kinetic E6 = 1/2*m*y7'^2");
    assert_eq!(
        e,
        "error: unknown name `y7`\n --> input:1:20\n  |\n1 | kinetic E6 = 1/2*m*y7'^2\n  |                    ^^\n  = hint: did you mean `y1`? Otherwise declare it with `parameters y7` or define it with `y7 = …`\n"
    );
    assert_eq!(s.scene_text(), before);
    let e = err(&mut s, "x = (1 + ");
    assert!(e.contains("input:1:"), "{e}");
    let e = err(&mut s, "coordinates y3");
    assert!(e.contains("coordinate declared twice"), "{e}");
    assert!(e.contains("input:1:13"), "{e}");
    assert_eq!(s.scene_text(), before);
    // the next correct line works, with every earlier definition
    assert!(ok(&mut s, ":solve").contains("343/460·g"));
    // a typo in an expression
    let e = err(&mut s, "diff(E1, y3'')  + qq");
    assert!(
        e.contains("unknown name `qq`") && e.contains("input:1:19"),
        "{e}"
    );
    let e = err(&mut s, "diff(E1, m)");
    assert!(e.contains("`diff` needs a variable"), "{e}");
    let e = err(&mut s, "subs(E1, y3)");
    assert!(e.contains("expected `x = value` here"), "{e}");
    let e = err(&mut s, "taylor(E1, y3, -1)");
    assert!(e.contains("the order must be a whole number"), "{e}");
    let e = err(&mut s, "sin(x = 1)");
    assert!(e.contains("named argument"), "{e}");
}

#[test]
fn a_definition_typed_again_replaces_the_earlier_one() {
    let mut s = Session::new();
    ok(&mut s, "coordinates x");
    ok(&mut s, "parameters m, k");
    ok(&mut s, "kinetic E = 1/2*m*x'^2");
    ok(&mut s, "potential V = 1/2*k*x^2");
    assert!(ok(&mut s, ":solve").contains("ẍ = −k/m·x"));
    let r = s.execute("potential V = 2*k*x^2");
    assert_eq!(
        r.out,
        "(replaces the earlier `potential V = 1/2*k*x^2`)\nV = 2·k·x²\n"
    );
    assert!(ok(&mut s, ":solve").contains("ẍ = −4·k/m·x"));
    assert_eq!(
        s.scene_text(),
        "# qdot scene, written by the REPL\ncoordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = 2*k*x^2\n"
    );
    // :undo brings the old definition back
    ok(&mut s, ":undo");
    assert!(ok(&mut s, ":solve").contains("ẍ = −k/m·x"));
}

#[test]
fn the_last_result_in_a_statement_is_stored_as_its_value() {
    let mut s = Session::new();
    ok(&mut s, "coordinates x");
    ok(&mut s, "parameters m");
    ok(&mut s, "1/2*m*x'^2");
    assert_eq!(ok(&mut s, "kinetic E = _"), "E = 1/2·m·ẋ²\n");
    assert!(s.scene_text().contains("kinetic E = (m*x'^2/2)\n"));
    let mut fresh = Session::new();
    let e = err(&mut fresh, "_ + 1");
    assert!(
        e.contains("`_` is the last result, and there is none yet"),
        "{e}"
    );
}

#[test]
fn solve_blocks_over_several_lines() {
    let mut s = Session::new();
    ok(&mut s, "parameters m, g");
    let block = "solve a, T {\n  m*a = T - m*g\n  T = 2*m*g\n}";
    assert!(!is_complete("solve a, T {\n  m*a = T - m*g\n"));
    assert!(is_complete(&format!("{block}\n")));
    ok(&mut s, block);
    assert_eq!(
        ok(&mut s, ":solve"),
        "Solutions  (solve a, T)\n  a = g\n  T = 2·g·m\n"
    );
    // a contradiction is found when solving, and shown in the scene
    ok(&mut s, "solve b {\n  b = 1\n  b = 2\n}");
    let e = err(&mut s, ":solve");
    assert!(
        e.contains("contradicts the others") && e.contains("--> scene:8:3"),
        "{e}"
    );
}

#[test]
fn entries_continue_while_brackets_are_open_or_an_operator_ends_the_line() {
    assert!(is_complete("x = 1\n"));
    assert!(!is_complete("x = (1 +\n"));
    assert!(!is_complete("E = 1/2*m*x'^2 +\n"));
    assert!(is_complete("E = 1/2*m*x'^2 +\n  k\n"));
    assert!(!is_complete("v = [x,\n"));
    assert!(is_complete("# comment with ( and {\n"));
    assert!(is_complete("latex th = \"\\theta_{(\"\n"));
    assert!(is_complete(":solve\n"));
}

#[test]
fn commands() {
    let mut s = seed();
    let eq = ok(&mut s, ":equations");
    assert!(eq.starts_with("Lagrange's equations"), "{eq}");
    assert!(eq.contains("13/2·G/g·ÿ₃ + G·r/g·θ̈₃ = 39/8·G"), "{eq}");
    let f = ok(&mut s, ":forces");
    assert!(f.contains("39/8·G"), "{f}");
    assert_eq!(
        ok(&mut s, ":show E4"),
        "kinetic E₄ = G/(2·g)·ẏ₃²\n  (as written: kinetic E4 = 1/2*J4*theta4'^2)\n"
    );
    assert!(ok(&mut s, ":show theta3").contains("generalized coordinate"));
    assert!(ok(&mut s, ":show g").contains("parameter"));
    assert!(err(&mut s, ":show nothing").contains("not in the scene"));
    assert_eq!(
        err(&mut s, ":sovle"),
        "error: unknown command `:sovle`\n  = hint: did you mean `:solve`? :help lists the commands\n"
    );
    assert_eq!(
        err(&mut s, ":equilibirum"),
        "error: unknown command `:equilibirum`\n  = hint: did you mean `:equilibrium`? :help lists the commands\n"
    );
    assert_eq!(
        err(&mut s, ":xyzzy"),
        "error: unknown command `:xyzzy`\n  = hint: :help lists the commands\n"
    );
    assert_eq!(
        err(&mut s, ":modes --sett g=1"),
        "error: `:modes` takes no option `--sett`\n  = hint: did you mean `--set`? :modes takes --set, --at, --init, --steady\n"
    );
    assert!(err(&mut s, ":so").contains("did you mean `:solve`"));
    let help = ok(&mut s, ":help");
    for c in [":equations", ":solve", ":modes", ":latex", ":undo", ":quit"] {
        assert!(help.contains(c), "{c}");
    }
    assert!(s.execute(":quit").quit);
    assert!(s.execute(":q").quit);
}

#[test]
fn formats_latex_and_json() {
    let mut s = seed();
    ok(&mut s, ":format latex");
    assert_eq!(
        ok(&mut s, "diff(E1, y3')"),
        "\\frac{G}{g} \\dot{y}_{3} + \\frac{2 G r}{g} \\dot{\\theta}_{3}\n"
    );
    let solved = ok(&mut s, ":solve");
    assert!(solved.contains("\\frac{343}{460} g"), "{solved}");
    ok(&mut s, ":format json");
    assert_eq!(ok(&mut s, "diff(U, y3)"), "{\"value\":\"5*G\"}\n");
    assert_eq!(
        ok(&mut s, "m2 = 2*m"),
        "{\"name\":\"m2\",\"value\":\"2*G/g\"}\n"
    );
    let j: serde_json::Value = serde_json::from_str(&ok(&mut s, ":solve")).unwrap();
    assert_eq!(j["accelerations"]["y3"], "343*g/460");
    ok(&mut s, ":format text");
    // :latex is the last result, :latex steps the whole derivation
    ok(&mut s, "diff(E3, theta3')");
    assert_eq!(
        ok(&mut s, ":latex"),
        "\\frac{4 G r^{2}}{g} \\dot{\\theta}_{3}\n"
    );
    let steps = ok(&mut s, ":latex steps");
    assert!(steps.contains("\\frac{343}{460} g"), "{steps}");
    assert!(steps.contains("\\partial"), "{steps}");
    assert!(err(&mut s, ":format html").contains("unknown format"));
}

#[test]
fn modes_and_equilibrium_take_options() {
    let mut s = Session::new();
    for l in [
        "coordinates th",
        "parameters m, g, l",
        "kinetic E = 1/2*m*l^2*th'^2",
        "potential V = -m*g*l*cos(th)",
    ] {
        ok(&mut s, l);
    }
    let m = ok(&mut s, ":modes");
    assert!(m.contains("ω² = g/l"), "{m}");
    let m = ok(&mut s, ":modes --at th=pi");
    assert!(m.contains("unstable"), "{m}");
    let e = ok(&mut s, ":equilibrium --set m=1,g=9.81,l=1");
    assert!(e.contains("θ = 0") && e.contains("stable"), "{e}");
    assert!(err(&mut s, ":solve --at th=0").contains("no option"));
    assert!(err(&mut s, ":modes --set").contains("needs a value"));
}

#[test]
fn scene_save_and_load_round_trip_through_the_cli() {
    let mut s = seed();
    ok(&mut s, "solve T {\n  T = G*mu\n}");
    let dir = std::env::temp_dir().join(format!("qdot-repl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("saved.qd");
    let p = path.to_str().unwrap();
    assert_eq!(
        ok(&mut s, &format!(":save {p}")),
        format!("(saved 18 statements to {p})\n")
    );
    let saved = std::fs::read_to_string(&path).unwrap();
    assert_eq!(saved, s.scene_text());
    // `qdot solve` on the saved file answers as the session does
    let in_repl = ok(&mut s, ":solve");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(["solve", p])
        .output()
        .unwrap();
    assert!(run.status.success());
    assert!(run.stderr.is_empty());
    let cli = String::from_utf8(run.stdout).unwrap();
    assert_eq!(in_repl, composed(&cli));
    // and so does its JSON
    ok(&mut s, ":format json");
    let json_repl = ok(&mut s, ":solve");
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(["solve", p, "--format", "json"])
        .output()
        .unwrap();
    assert_eq!(json_repl, String::from_utf8(run.stdout).unwrap());
    ok(&mut s, ":format text");
    assert!(
        cli.contains("343/460·g") && cli.contains("T = 1/8·G"),
        "{cli}"
    );
    // :load into a fresh session gives the same scene
    let mut t = Session::new();
    assert_eq!(
        ok(&mut t, &format!(":load {p}")),
        format!("(loaded 18 statements from {p})\n")
    );
    assert_eq!(t.scene_text(), s.scene_text());
    // a file with an error names the file and changes nothing
    let bad = dir.join("bad.qd");
    std::fs::write(&bad, "coordinates x\nkinetic E = 1/2*mm*x'^2\n").unwrap();
    let e = err(&mut t, &format!(":load {}", bad.display()));
    assert!(e.contains(&format!("--> {}:2:17", bad.display())), "{e}");
    assert_eq!(t.scene_text(), s.scene_text());
    assert!(err(&mut t, ":load /nonexistent/file.qd").contains("cannot read"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn undo_and_reset() {
    let mut s = Session::new();
    ok(&mut s, "parameters a");
    ok(&mut s, "b = 2*a");
    ok(&mut s, ":reset");
    assert_eq!(s.scene_text(), "# qdot scene, written by the REPL\n");
    assert!(err(&mut s, "b").contains("unknown name `b`"));
    ok(&mut s, ":undo");
    assert_eq!(ok(&mut s, "b"), "2·a\n");
    ok(&mut s, ":undo"); // the expression
    ok(&mut s, ":undo"); // b
    assert!(err(&mut s, "b").contains("unknown name"));
    ok(&mut s, ":undo"); // a
    assert!(err(&mut s, ":undo").contains("nothing to undo"));
}

#[test]
fn series_of_three_springs_still_means_springs_with_a_warning() {
    let mut s = Session::new();
    ok(&mut s, "parameters k1, k2");
    let r = s.execute("series(k1, k2, 2)");
    assert_eq!(r.out, "2·k₁·k₂/(k₁·k₂ + 2·k₁ + 2·k₂)\n");
    assert!(r.err.contains("combines three springs"), "{}", r.err);
    assert_eq!(ok(&mut s, "series(k1, k2)"), "k₁·k₂/(k₁ + k₂)\n");
}

#[test]
fn the_language_functions_work_in_scene_files_too() {
    let src = "coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\n\
               potential V = taylor(k*(1 - cos(x)), x, 2)\nF = diff(V, x)\n";
    let scene = qdot::Scene::parse(src).unwrap();
    assert_eq!(scene.definition("F").unwrap().to_string(), "k*x");
    let acc = scene.lagrange().unwrap().accelerations().unwrap();
    assert_eq!(acc["x"].to_string(), "-k*x/m");
}

#[test]
fn piped_mode_reads_entries_without_prompts() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .arg("repl")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = SEED_23_4.join("\n");
    input.push_str("\nqq\nsolve T {\n  T = G\n}\n:solve\n:quit\nnever = 1\n");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stdout = composed(&String::from_utf8(out.stdout).unwrap());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(!stdout.contains("qdot>"), "{stdout}");
    assert!(stdout.contains("ÿ₃ = 343/460·g"), "{stdout}");
    assert!(stdout.contains("T = G"), "{stdout}");
    assert!(!stdout.contains("never"), "{stdout}");
    assert!(stderr.contains("unknown name `qq`"), "{stderr}");
    // an entry failed: exit status 1
    assert_eq!(out.status.code(), Some(1));
}

/// A script piped in: each error points at the script's line, a
/// multi-line entry's at the line inside it, a loaded file's at the file's.
#[test]
fn piped_errors_point_at_the_scripts_lines() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let dir = std::env::temp_dir().join(format!("qdot-piped-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.qd");
    std::fs::write(&file, "coordinates y\n\nkinetic T = y'^2 + zz\n").unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .arg("repl")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let input = format!(
        "coordinates x\nparameters m, k\n\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*xx^2\nw = (1 +\n  2 +\n  )\n:load {}\n",
        file.display()
    );
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains(
            " --> stdin:5:21\n  |\n5 | potential V = 1/2*k*xx^2\n  |                     ^^\n"
        ),
        "{stderr}"
    );
    assert!(
        stderr.contains(" --> stdin:8:3\n  |\n8 |   )\n  |   ^\n"),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!(" --> {}:3:20\n", file.display())),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn completion_and_highlighting() {
    use qdot::repl::editing::{completions, highlight};
    let names = ["theta3".to_string(), "theta4".to_string(), "G".to_string()];
    let (start, c) = completions("diff(E, the", 11, &[&names]);
    assert_eq!(start, 8);
    let shown: Vec<&str> = c.iter().map(|p| p.display.as_str()).collect();
    assert_eq!(shown, ["theta3", "theta4"]);
    let (_, c) = completions(":so", 3, &[&names]);
    assert_eq!(c[0].replacement, ":solve");
    let (_, c) = completions("x = ta", 6, &[&names]);
    let shown: Vec<&str> = c.iter().map(|p| p.display.as_str()).collect();
    assert_eq!(shown, ["tan(", "taylor("]);
    let (_, c) = completions("kin", 3, &[&names]);
    assert_eq!(c[0].replacement, "kinetic ");
    let h = highlight(
        "kinetic E = 1/2*G*theta3'^2 # note",
        &["theta3".into()],
        &["G".into()],
        &[],
    );
    assert_eq!(
        h,
        "\u{1b}[1;34mkinetic\u{1b}[0m E = \u{1b}[36m1\u{1b}[0m/\u{1b}[36m2\u{1b}[0m*\u{1b}[33mG\u{1b}[0m*\u{1b}[32mtheta3\u{1b}[0m'^\u{1b}[36m2\u{1b}[0m \u{1b}[2m# note\u{1b}[0m"
    );
}

/// One scanner feeds completion and highlighting: the pieces cover the
/// line, a `:command` only at its start, a comment to its end.
#[test]
fn the_line_scanner_covers_the_line() {
    use qdot::repl::editing::{line_tokens, LineTokenKind as K};
    let line = "x2 = 1.5e3*sin(θ)' # ok";
    let t = line_tokens(line);
    let pieces: Vec<(K, &str)> = t.iter().map(|t| (t.kind, &line[t.start..t.end])).collect();
    assert_eq!(
        pieces,
        [
            (K::Word, "x2"),
            (K::Other, " "),
            (K::Other, "="),
            (K::Other, " "),
            (K::Number, "1.5e3"),
            (K::Other, "*"),
            (K::Word, "sin"),
            (K::Other, "("),
            (K::Word, "θ"),
            (K::Other, ")"),
            (K::Other, "'"),
            (K::Other, " "),
            (K::Comment, "# ok"),
        ]
    );
    let t = line_tokens("  :max-terms 5 a:b");
    assert_eq!((t[2].kind, t[2].start, t[2].end), (K::Command, 2, 12));
    assert!(t.iter().skip(3).all(|t| t.kind != K::Command), "{t:?}");
    // completion of a word after an operator, and of nothing after a space
    let (start, c) = qdot::repl::editing::completions("x = 2*si", 8, &[]);
    assert_eq!((start, c[0].display.as_str()), (6, "sin("));
    let (_, c) = qdot::repl::editing::completions("x = ", 4, &[]);
    assert!(c.is_empty());
}

#[test]
fn every_statement_kind_works_as_a_line() {
    let mut s = Session::new();
    ok(&mut s, "coordinates x, phi");
    ok(&mut s, "parameters m, k, F, M0, J, c");
    ok(&mut s, "kinetic E = 1/2*m*x'^2 + 1/2*J*phi'^2");
    ok(&mut s, "potential V = 1/2*k*x^2");
    assert_eq!(ok(&mut s, "load F at x"), "");
    assert_eq!(ok(&mut s, "torque M0*cos(phi) on phi"), "");
    assert_eq!(ok(&mut s, "force x: -c*x'"), "");
    ok(&mut s, "rayleigh R = 1/2*c*phi'^2");
    assert_eq!(ok(&mut s, "latex phi = \"\\vartheta\""), "");
    ok(&mut s, "load [F, 0] at [x, 0]");
    assert_eq!(
        ok(&mut s, ":forces"),
        "Generalized forces  δL = Σ Q_k·δq_k\n  Q_x = −c·ẋ − k·x + 2·F\n  Q_φ = −c·φ̇ + M₀·cos(φ)\n"
    );
    // the scene's LaTeX notation applies to results
    ok(&mut s, ":format latex");
    assert_eq!(ok(&mut s, "phi'"), "\\dot{\\vartheta}\n");
    // a load at a point that does not move is the scene's usual warning
    ok(&mut s, ":format text");
    let r = s.execute("load F at c");
    assert!(!r.failed);
    assert!(r.err.contains("does no virtual work"), "{}", r.err);
    assert!(r.err.contains("--> input:1:"), "{}", r.err);
}

/// A misspelled keyword typed in the REPL: "did you mean", at the word,
/// also when the rest of the line would read as an expression.
#[test]
fn a_misspelled_keyword_is_named() {
    let mut s = seed();
    let before = s.scene_text();
    assert_eq!(
        err(&mut s, "potental V = G*y3"),
        "error: unknown keyword `potental`\n --> input:1:1\n  |\n1 | potental V = G*y3\n  | ^^^^^^^^\n  = hint: did you mean `potential`?\n"
    );
    assert_eq!(
        err(&mut s, "solv a { a = 1 }"),
        "error: unknown keyword `solv`\n --> input:1:1\n  |\n1 | solv a { a = 1 }\n  | ^^^^\n  = hint: did you mean `solve`?\n"
    );
    // a bare name near a keyword is still a name
    assert!(err(&mut s, "kinetc").starts_with("error: unknown name `kinetc`"));
    assert_eq!(s.scene_text(), before);
}

/// An invisible character typed (or pasted) in the REPL, and a file that
/// is not UTF-8 given to `:load`.
#[test]
fn invisible_characters_and_invalid_utf8_are_positioned() {
    let mut s = seed();
    assert_eq!(
        err(&mut s, "z = m\u{200B}*g"),
        "error: unknown character U+200B (ZERO WIDTH SPACE), which is invisible\n --> input:1:6\n  |\n1 | z = m\u{FFFD}*g\n  |      ^\n  = hint: delete it (invisible characters often come with text pasted from a web page or a word processor)\n"
    );
    let path = std::env::temp_dir().join(format!("qdot-repl-latin1-{}.qd", std::process::id()));
    std::fs::write(&path, b"parameters b\nz = b*\xE9\n").unwrap();
    let p = path.to_str().unwrap();
    assert_eq!(
        err(&mut s, &format!(":load {p}")),
        format!("error: the file is not valid UTF-8: byte 0xE9 here\n --> {p}:2:7\n  |\n2 | z = b*\u{FFFD}\n  |       ^\n  = hint: save the file as UTF-8 (in Latin-1 or Windows-1252, 0xE9 is `é`)\n")
    );
    let _ = std::fs::remove_file(&path);
}

/// The canonical form's variable order is the order atoms were first seen
/// in the process, so two sessions (or two names) can meet them in either
/// order; what `expand` prints must not depend on it.
#[test]
fn expand_does_not_depend_on_the_order_names_were_first_seen() {
    let mut s = Session::new();
    // zqx seen before aqx, aqy before zqy (both pairs are new to the process)
    ok(&mut s, "parameters zqx, aqx, aqy, zqy");
    ok(&mut s, "zqx + 2*aqx");
    ok(&mut s, "aqy + 2*zqy");
    for i in ["x", "y"] {
        let a = format!("aq{i}");
        let z = format!("zq{i}");
        assert_eq!(
            ok(&mut s, &format!("expand(({a} + {z})^2/({z} - {a}))")),
            format!("(−{a}² − 2·{a}·{z} − {z}²)/({a} − {z})\n"),
        );
        assert_eq!(
            ok(&mut s, &format!("expand(({z} - {a})^3)")),
            format!("−{a}³ + 3·{a}²·{z} − 3·{a}·{z}² + {z}³\n"),
        );
    }
}

/// `:latex` typesets the last result: an expression, or the last command
/// that printed one (`:modes`, `:solve`, …) with its options.
#[test]
fn latex_of_the_last_result_is_the_last_command_or_expression() {
    let mut s = Session::new();
    for line in [
        "coordinates x1, x2",
        "parameters m, k",
        "kinetic E = 1/2*m*(x1'^2 + x2'^2)",
        "potential V = 1/2*k*(x1^2 + (x2 - x1)^2 + x2^2)",
    ] {
        ok(&mut s, line);
    }
    let modes = s.execute(":modes");
    assert!(!modes.failed, "{}", modes.err);
    let tex = ok(&mut s, ":latex");
    assert!(tex.contains("The characteristic equation:"), "{tex}");
    assert!(tex.contains(r"\omega_{2}^{2} &= \frac{3 k}{m}"), "{tex}");
    ok(&mut s, ":solve");
    let tex = ok(&mut s, ":latex");
    assert!(tex.contains(r"\ddot{x}_{1}"), "{tex}");
    assert!(!tex.contains("characteristic"), "{tex}");
    // an expression after the command is the last result again
    ok(&mut s, "k*m");
    assert_eq!(ok(&mut s, ":latex"), "k m\n");
}

/// A second place elsewhere in the scene is not in the entry the REPL
/// shows: the error of a name declared twice points at the entry only,
/// never at a label placed by the scene's offsets in the entry's text.
#[test]
fn a_label_outside_the_entry_is_left_out() {
    let mut s = qdot::repl::Session::new();
    assert!(!s.execute("coordinates x").failed);
    let r = s.execute("coordinates x");
    assert!(r.failed);
    assert_eq!(
        r.err,
        "error: coordinate declared twice: `x` is already a coordinate\n --> input:1:13\n  |\n1 | coordinates x\n  |             ^\n  = hint: each name has one meaning in a scene; role statements add up, but their names must differ\n"
    );
}

#[test]
fn bare_command_words_are_understood() {
    let mut s = Session::new();
    // `exit` and `quit` leave, `help` is `:help`
    for word in ["exit", "quit", "  exit  "] {
        let r = s.execute(word);
        assert!(r.quit && !r.failed, "{word}: {r:?}");
        assert_eq!((r.out.as_str(), r.err.as_str()), ("", ""), "{word}");
    }
    assert_eq!(ok(&mut s, "help"), ok(&mut s, ":help"));
    // a command's name without its colon says to type it
    assert_eq!(
        err(&mut s, "solve"),
        "error: `solve` is a command: commands start with a colon\n  = hint: type `:solve`\n"
    );
    assert_eq!(
        err(&mut s, "modes --set k=1"),
        "error: `modes` is a command: commands start with a colon\n  = hint: type `:modes --set k=1`\n"
    );
    assert_eq!(
        err(&mut s, "equations"),
        "error: `equations` is a command: commands start with a colon\n  = hint: type `:equations`\n"
    );
    // a scene's own name is its value; a solve block is a statement
    ok(&mut s, "parameters exit, help");
    assert_eq!(ok(&mut s, "exit"), "exit\n");
    assert_eq!(ok(&mut s, "help"), "help\n");
    assert!(!s.execute("exit").quit);
    ok(&mut s, "parameters a, b");
    assert_eq!(ok(&mut s, "solve u { u = a + b }"), "");
}

#[test]
fn a_derivative_written_in_words_suggests_the_prime() {
    let mut s = Session::new();
    ok(&mut s, "coordinates theta, x");
    assert_eq!(
        err(&mut s, "thetadot"),
        "error: unknown name `thetadot`\n --> input:1:1\n  |\n1 | thetadot\n  | ^^^^^^^^\n  = hint: a time derivative is written with primes: `theta'` (`theta'` the velocity, `theta''` the acceleration)\n"
    );
    assert!(err(&mut s, "2*xddot").contains("written with primes: `x''`"));
    // in a statement too
    assert!(err(&mut s, "kinetic E = thetadot^2").contains("`theta'`"));
    // a name that is no coordinate's keeps the usual hint
    assert!(err(&mut s, "phidot").contains("declare it with `parameters phidot`"));
}

#[test]
fn undo_says_what_it_undid() {
    let mut s = Session::new();
    ok(&mut s, "parameters a");
    ok(&mut s, "b = 2*a");
    ok(&mut s, "b + 1");
    ok(&mut s, "c = 1\nd = 2");
    ok(&mut s, ":reset");
    assert_eq!(ok(&mut s, ":undo"), "(undone: :reset)\n");
    assert_eq!(ok(&mut s, ":undo"), "(undone: 2 statements from `c = 1`)\n");
    assert_eq!(ok(&mut s, ":undo"), "(undone: the result of `b + 1`)\n");
    assert_eq!(ok(&mut s, ":undo"), "(undone: `b = 2*a`)\n");
    assert_eq!(ok(&mut s, ":undo"), "(undone: `parameters a`)\n");
    assert_eq!(err(&mut s, ":undo"), "error: nothing to undo\n");
}
