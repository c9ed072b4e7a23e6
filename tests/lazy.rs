//! Lazy evaluation: a scene evaluates what its statements use; a
//! definition nothing uses is checked (names, cycles), evaluated when small
//! (its errors warnings), else deferred until something asks for it.

use qdot::output::{self, Command, Format};
use qdot::repl::Session;
use qdot::Scene;

const OSCILLATOR: &str = "coordinates x\nparameters m, k, a, b\n\
                          kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\n";

/// The oscillator with `n` unused definitions `u_i = (a+b+x)^30`.
fn with_unused(n: usize) -> String {
    let mut src = OSCILLATOR.to_string();
    for i in 1..=n {
        src.push_str(&format!("u{i} = (a+b+x)^30\n"));
    }
    src
}

#[test]
fn unused_definitions_change_no_answer() {
    let big = with_unused(300);
    for cmd in [
        Command::Solve,
        Command::Derive,
        Command::Forces,
        Command::Equilibrium,
        Command::Modes,
        Command::Hamilton,
        Command::Integrals,
    ] {
        for fmt in [Format::Text, Format::Json] {
            let without = output::run(cmd, OSCILLATOR, fmt, &Default::default());
            let with = output::run(cmd, &big, fmt, &Default::default());
            let (without, with) = (without.expect("runs"), with.expect("runs"));
            assert_eq!(with.1, Vec::new(), "{cmd:?}: warnings");
            assert_eq!(without.1, with.1);
            // JSON echoes nothing of the source but its results
            assert_eq!(with.0, without.0, "{cmd:?} {fmt:?}");
        }
    }
    let s = Scene::parse(&big).unwrap();
    let evaluated: Vec<&str> = s.definitions.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(evaluated, ["E", "V"]);
    assert_eq!(s.deferred.len(), 300);
    assert_eq!(s.deferred[299].name.name, "u300");
}

#[test]
fn small_unused_definitions_are_evaluated_in_source_order() {
    let src = format!("{OSCILLATOR}w = a + b\nr = [x, a]\n");
    let s = Scene::parse(&src).unwrap();
    let names: Vec<&str> = s.definitions.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, ["E", "V", "w", "r"]);
    assert!(s.deferred.is_empty());
    assert_eq!(s.definition("w").unwrap().to_string(), "a + b");
}

/// The warnings of a scene, rendered as the CLI does.
fn warnings(src: &str) -> String {
    let s = Scene::parse(src).expect("the scene is read");
    s.warnings
        .iter()
        .map(|w| w.render("scene.qd", src))
        .collect()
}

#[test]
fn an_unused_division_by_zero_is_a_warning_with_its_position() {
    let src = format!("{OSCILLATOR}z = m/(k - k)\n");
    assert_eq!(
        warnings(&src),
        "warning: division by zero: this divisor is exactly 0 (in `z`, which nothing in the scene uses)\n \
         --> scene.qd:5:8\n  |\n5 | z = m/(k - k)\n  |        ^^^^^\n  = hint: check the definitions it uses\n"
    );
    // asked for, it is an error
    let s = Scene::parse(&src).unwrap();
    assert!(s.value("z").is_none());
    let d = s.try_value("z").unwrap().unwrap_err();
    assert_eq!(d.message, "division by zero: this divisor is exactly 0");
    assert_eq!(
        s.expr("z + 1").unwrap_err().message,
        "`z` can't be evaluated: division by zero: this divisor is exactly 0 (line 5 of the scene)"
    );
    // the results do not depend on it
    let (out, _) = output::run(Command::Solve, &src, Format::Text, &Default::default()).unwrap();
    let (want, _) = output::run(
        Command::Solve,
        OSCILLATOR,
        Format::Text,
        &Default::default(),
    )
    .unwrap();
    assert_eq!(out, want);
}

#[test]
fn an_error_is_reported_once_at_the_definition_it_is_in() {
    let src = format!("{OSCILLATOR}z2 = z + 1\nz = m/(k - k)\nz3 = 2*z2\n");
    let s = Scene::parse(&src).unwrap();
    let spans: Vec<String> = s.warnings.iter().map(|w| format!("{:?}", w.span)).collect();
    assert_eq!(s.warnings.len(), 1, "{spans:?}");
    assert!(s.warnings[0]
        .message
        .ends_with("(in `z`, which nothing in the scene uses)"));
    let deferred: Vec<&str> = s.deferred.iter().map(|d| d.name.name.as_str()).collect();
    assert_eq!(deferred, ["z2", "z", "z3"]);
}

#[test]
fn an_unused_vector_plus_number_is_a_warning() {
    let src = format!("{OSCILLATOR}v = [1, 2] + a\n");
    assert_eq!(
        warnings(&src),
        "warning: can't add a vector and a number (in `v`, which nothing in the scene uses)\n \
         --> scene.qd:5:5\n  |\n5 | v = [1, 2] + a\n  |     ^^^^^^^^^^\n  \
         = hint: the left side is a vector and the right side a number; both sides of + and - must be numbers, or vectors of the same size\n"
    );
}

#[test]
fn a_large_unused_definition_is_checked_when_asked() {
    // too large to evaluate when the scene is read: no warning yet
    let src = format!("{OSCILLATOR}w = (a+b+x)^30/(x - x)\n");
    assert_eq!(warnings(&src), "");
    let s = Scene::parse(&src).unwrap();
    assert_eq!(s.deferred.len(), 1);
    assert_eq!(
        s.expr("w").unwrap_err().message,
        "`w` can't be evaluated: division by zero: this divisor is exactly 0 (line 5 of the scene)"
    );
}

#[test]
fn names_and_cycles_of_unused_definitions_are_still_errors() {
    let cases = [
        (
            format!("{OSCILLATOR}w = (a+b+q)^30\n"),
            "error: unknown name `q`\n --> scene.qd:5:10\n",
        ),
        (
            format!("{OSCILLATOR}w = sinn(x)^30\n"),
            "error: unknown function `sinn`\n --> scene.qd:5:5\n",
        ),
        (
            format!("{OSCILLATOR}p = q2 + 1\nq2 = 2*p\n"),
            "error: cyclic definition: p → q2 → p\n --> scene.qd:6:8\n",
        ),
    ];
    for (src, head) in cases {
        let err = match Scene::parse(&src) {
            Ok(_) => panic!("accepted: {src}"),
            Err(d) => d.render("scene.qd", &src),
        };
        assert!(err.starts_with(head), "{src}\ngot:\n{err}\nwant:\n{head}");
    }
}

#[test]
fn a_definition_used_only_from_expressions_evaluates() {
    let src = format!("{OSCILLATOR}w = (a+b+x)^30\nw2 = w - (a+b+x)^30 + x\n");
    let s = Scene::parse(&src).unwrap();
    assert_eq!(s.deferred.len(), 2);
    let want = s.expr("(a+b+x)^30").unwrap();
    assert!(s.expr("w").unwrap().equals(&want));
    assert!(s.definition("w").unwrap().equals(&want));
    assert_eq!(s.expr("w2").unwrap().to_string(), "x");
    assert_eq!(s.value("w2").unwrap().as_scalar().unwrap().to_string(), "x");
    // in the REPL too
    let mut repl = Session::new();
    for line in src.lines() {
        let r = repl.execute(line);
        assert!(!r.failed, "{line}: {}", r.err);
    }
    let r = repl.execute("w2 + 1");
    assert!(!r.failed, "{}", r.err);
    assert_eq!(r.out.trim(), "x + 1");
}

#[test]
fn a_used_definitions_error_is_still_an_error() {
    let src = "coordinates x\nparameters m, k\nz = m/(k - k)\n\
               kinetic E = 1/2*m*x'^2\npotential V = 1/2*z*x^2\n";
    let err = Scene::parse(src).unwrap_err();
    assert_eq!(
        err.render("scene.qd", src),
        "error: division by zero: this divisor is exactly 0\n --> scene.qd:3:8\n  |\n\
         3 | z = m/(k - k)\n  |        ^^^^^\n  = hint: check the definitions it uses\n"
    );
    // used by a load, a body or a `solve` block: the same
    for used in [
        "load z at x\n",
        "particle p: mass z, at [x, 0]\n",
        "solve u {\n  u = z\n}\n",
    ] {
        let src = format!(
            "coordinates x\nparameters m, k\nz = m/(k - k)\nkinetic E = 1/2*m*x'^2\n{used}"
        );
        let err = Scene::parse(&src).unwrap_err();
        assert_eq!(
            err.message, "division by zero: this divisor is exactly 0",
            "{used}"
        );
    }
}

#[test]
fn the_repl_refuses_a_definition_it_cannot_show() {
    let mut repl = Session::new();
    for line in OSCILLATOR.lines() {
        assert!(!repl.execute(line).failed, "{line}");
    }
    let r = repl.execute("z = m/(k - k)");
    assert!(r.failed, "{}", r.out);
    assert!(
        r.err
            .starts_with("error: division by zero: this divisor is exactly 0"),
        "{}",
        r.err
    );
}
