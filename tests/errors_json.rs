//! Errors a program can match: `--format json` (and `--output json`)
//! prints an error as one JSON object on stderr with its kind, message and
//! place; the library's [`Diagnostic::kind`] carries the same class with
//! its data; a second place is a label under the first.

use crate::bound::{qdot_bounded, qdot_scene, MEMORY_MIB, SECONDS};
use qdot::diag::ErrorKind;
use qdot::{Command, CommandOptions, Diagnostic, Format};

/// An error printed as JSON: its kind, message, line and column.
struct Expected<'a> {
    kind: &'a str,
    message: &'a str,
    line: Option<u64>,
    column: Option<u64>,
}

/// Exit status `code`, nothing on stdout (but for a simulation's rows) and
/// stderr exactly one JSON object `{"error": {…}}` with the expected
/// fields; the object's keys in the documented order.
#[track_caller]
fn assert_json_error(o: &crate::bound::Outcome, code: i32, want: Expected) -> serde_json::Value {
    o.assert_clean();
    assert_eq!(o.code, Some(code), "{o:?}");
    assert_eq!(o.stderr.lines().count(), 1, "one line on stderr: {o:?}");
    let v: serde_json::Value = serde_json::from_str(&o.stderr)
        .unwrap_or_else(|e| panic!("stderr is not JSON ({e}): {o:?}"));
    let top: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(top, ["error"]);
    let e = &v["error"];
    let keys: Vec<&str> = e.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(
        keys,
        ["kind", "data", "message", "line", "column", "hint", "labels"]
    );
    assert_eq!(e["kind"], want.kind, "{o:?}");
    assert_eq!(e["message"], want.message, "{o:?}");
    assert_eq!(e["line"].as_u64(), want.line, "{o:?}");
    assert_eq!(e["column"].as_u64(), want.column, "{o:?}");
    assert_eq!(e["line"].is_null(), want.line.is_none());
    e.clone()
}

const OSCILLATOR: &str =
    "coordinates x\nparameters m, g\nkinetic E = m*x'^2/2\npotential V = m*g*x^2\n";

#[test]
fn a_syntax_error_is_kind_syntax() {
    let o = qdot_scene(
        "json-syntax",
        b"coordinates x\nkinetic E = (x'^2\n",
        "solve",
        &["--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "syntax",
            message: "unclosed `(`",
            line: Some(2),
            column: Some(13),
        },
    );
    assert_eq!(e["data"], serde_json::json!({}));
    assert_eq!(e["hint"], "add the matching `)`");
    assert_eq!(e["labels"], serde_json::json!([]));
}

#[test]
fn an_unknown_name_is_kind_unknown_name() {
    let o = qdot_scene(
        "json-unknown",
        b"coordinates x\nkinetic E = m*x'^2/2\n",
        "derive",
        &["--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "unknown_name",
            message: "unknown name `m`",
            line: Some(2),
            column: Some(13),
        },
    );
    assert_eq!(e["data"], serde_json::json!({"name": "m"}));
}

#[test]
fn a_name_declared_twice_is_kind_duplicate_name_with_the_first_as_label() {
    let o = qdot_scene(
        "json-duplicate",
        b"coordinates x\nparameters m\ncoordinates x\n",
        "solve",
        &["--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "duplicate_name",
            message: "coordinate declared twice: `x` is already a coordinate",
            line: Some(3),
            column: Some(13),
        },
    );
    assert_eq!(
        e["labels"],
        serde_json::json!([{"line": 1, "column": 13, "message": "`x` is a coordinate here"}])
    );
}

#[test]
fn a_dimension_mismatch_is_kind_dimension_mismatch_with_the_annotations_as_labels() {
    let o = qdot_scene(
        "json-dimension",
        b"parameters m: mass, l: length\ncoordinates x: length\nkinetic E = m*x'^2/2\npotential V = m*x\n",
        "check",
        &["--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "dimension_mismatch",
            message: "this is of dimension mass·length; an energy is needed here (`V` is a potential energy)",
            line: Some(4),
            column: Some(15),
        },
    );
    assert_eq!(
        e["labels"],
        serde_json::json!([
            {"line": 1, "column": 15, "message": "`m` is a mass, declared here"},
            {"line": 2, "column": 16, "message": "`x` is a length, declared here"},
        ])
    );
}

#[test]
fn a_singular_mass_matrix_is_kind_singular_system() {
    let o = qdot_scene(
        "json-singular",
        b"coordinates x, y\nparameters m\nkinetic E = m*(x' + y')^2/2\n",
        "solve",
        &["--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "singular_system",
            message: "the mass matrix is singular: the coordinates x, y are not independent in the kinetic energy",
            line: None,
            column: None,
        },
    );
    assert_eq!(e["data"], serde_json::json!({"unknowns": ["x", "y"]}));
}

#[test]
fn the_budget_exceeded_is_kind_too_large() {
    let o = qdot_scene(
        "json-budget",
        b"coordinates x\nparameters a, b, c, d\nkinetic E = x'^2/2\npotential V = (a+b+c+d+x)^12\n",
        "derive",
        &["--format", "json", "--max-terms", "100"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "too_large",
            message: "expression too large: a product of 70 by 70 terms while evaluating `V` (the limit is 100 terms, and 800 term products)",
            line: Some(4),
            column: Some(15),
        },
    );
    assert_eq!(e["data"], serde_json::json!({"measure": "product"}));
}

#[test]
fn a_file_that_cannot_be_read_is_kind_unreadable_file() {
    let o = qdot_bounded(
        &["solve", "no/such/scene.qd", "--format", "json"],
        "",
        SECONDS,
        MEMORY_MIB,
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "unreadable_file",
            message: "cannot read `no/such/scene.qd`: No such file or directory (os error 2)",
            line: None,
            column: None,
        },
    );
    assert_eq!(e["data"], serde_json::json!({"path": "no/such/scene.qd"}));
}

#[test]
fn a_file_not_utf8_is_kind_not_utf8() {
    let o = qdot_scene(
        "json-latin1",
        b"coordinates x\nkinetic E = x'^2/2 # caf\xe9\n",
        "solve",
        &["--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "not_utf8",
            message: "the file is not valid UTF-8: byte 0xE9 here",
            line: Some(2),
            column: Some(25),
        },
    );
    assert_eq!(
        e["hint"],
        "save the file as UTF-8 (in Latin-1 or Windows-1252, 0xE9 is `é`)"
    );
}

#[test]
fn a_bad_option_value_is_kind_bad_option() {
    let o = qdot_scene(
        "json-option",
        OSCILLATOR.as_bytes(),
        "equilibrium",
        &["--set", "m=abc", "--format", "json"],
    );
    let e = assert_json_error(
        &o,
        1,
        Expected {
            kind: "bad_option",
            message: "`--set m=abc`: `abc` is not a number",
            line: None,
            column: None,
        },
    );
    assert_eq!(e["data"], serde_json::json!({"option": "--set"}));
    // simulate's options, under --output json
    let o = qdot_scene(
        "json-option-simulate",
        OSCILLATOR.as_bytes(),
        "simulate",
        &[
            "--t-end",
            "1",
            "--set",
            "m=1,g=1,k=2",
            "--init",
            "x=1,x'=0",
            "--output",
            "json",
        ],
    );
    assert_json_error(
        &o,
        1,
        Expected {
            kind: "bad_option",
            message: "`--set k=…`: `k` is not a parameter of the scene",
            line: None,
            column: None,
        },
    );
}

#[test]
fn a_scene_without_coordinates_is_kind_nothing_to_solve() {
    let o = qdot_scene(
        "json-nothing",
        b"parameters m\n",
        "solve",
        &["--format", "json"],
    );
    assert_json_error(
        &o,
        1,
        Expected {
            kind: "nothing_to_solve",
            message: "the scene declares no coordinates, so there are no Lagrange equations",
            line: None,
            column: None,
        },
    );
}

#[test]
fn contradictory_constraints_are_kind_constraints() {
    let o = qdot_scene(
        "json-constraints",
        b"coordinates x, y\nparameters m\nkinetic E = m*(x'^2 + y'^2)/2\nconstraint a: x = y\nconstraint b: x = y + 1\n",
        "solve",
        &["--format", "json"],
    );
    assert_json_error(
        &o,
        1,
        Expected {
            kind: "constraints",
            message:
                "the constraints `a`, `b` contradict each other: they differ by 1, which is not 0",
            line: None,
            column: None,
        },
    );
}

#[test]
fn an_integration_stopped_early_is_kind_integration_with_status_3() {
    let o = qdot_scene(
        "json-integration",
        OSCILLATOR.as_bytes(),
        "simulate",
        &[
            "--set",
            "m=1,g=1",
            "--init",
            "x=1,x'=0",
            "--t-end",
            "100",
            "--max-steps",
            "3",
            "--output",
            "json",
        ],
    );
    let e = assert_json_error(
        &o,
        3,
        Expected {
            kind: "integration",
            message: "the integration stopped early: too many steps at t = 2.128713e-1",
            line: None,
            column: None,
        },
    );
    assert_eq!(
        e["hint"],
        "raise --max-steps (it is 3), loosen --rtol and --atol, or use --method radau5 if the problem is stiff"
    );
    // the rows before the stop are still the result
    let rows: serde_json::Value = serde_json::from_str(&o.stdout).expect("JSON rows");
    assert_eq!(rows["status"], "too many steps");
}

#[test]
fn text_errors_are_unchanged_without_json() {
    let o = qdot_scene(
        "text-unknown",
        b"coordinates x\nkinetic E = m*x'^2/2\n",
        "derive",
        &[],
    );
    assert_eq!(o.code, Some(1));
    assert_eq!(
        o.stderr,
        "error: unknown name `m`\n --> scene.qd:2:13\n  |\n2 | kinetic E = m*x'^2/2\n  |             ^\n  \
         = hint: declare it with `parameters m` (a constant) or `coordinates m` (a function of time), or define it with `m = …`\n"
    );
}

#[test]
fn warnings_under_json_are_json_objects_one_a_line() {
    // a load on a point that does not move does no virtual work: a warning
    let o = qdot_scene(
        "json-warning",
        b"coordinates x\nparameters m, F\nkinetic E = m*x'^2/2\nload [F, 0, 0] at [1, 0, 0]\n",
        "solve",
        &["--format", "json"],
    );
    assert_eq!(o.code, Some(0), "{o:?}");
    let lines: Vec<&str> = o.stderr.lines().collect();
    assert!(!lines.is_empty(), "a warning: {o:?}");
    for line in lines {
        let v: serde_json::Value = serde_json::from_str(line).expect("a JSON line");
        assert_eq!(v["warning"]["kind"], "other", "{line}");
        assert!(v["warning"]["line"].is_u64(), "{line}");
    }
}

// ---------------------------------------------------------------- library

/// The error of `cmd` on `src`, through the library.
fn library_error(cmd: Command, src: &str) -> Diagnostic {
    match qdot::run_with(cmd, src, Format::Text, &CommandOptions::default()) {
        Ok((out, _)) => panic!("expected an error, got\n{out}"),
        Err(d) => d,
    }
}

#[test]
fn a_singular_mass_matrix_names_its_coordinates() {
    let d = library_error(
        Command::Solve,
        "coordinates x, y, z\nparameters m\nkinetic E = m*(x' + y')^2/2 + m*z'^2/2\n",
    );
    match d.kind() {
        ErrorKind::SingularSystem { unknowns } => assert_eq!(unknowns, &["x", "y"]),
        k => panic!("{k:?}: {d}"),
    }
}

#[test]
fn a_degenerate_lagrangian_names_the_velocities_hamilton_cannot_find() {
    let d = library_error(
        Command::Hamilton,
        "coordinates x, y\nparameters m\nkinetic E = m*(x' + y')^2/2\n",
    );
    assert_eq!(
        d.kind(),
        &ErrorKind::SingularSystem {
            unknowns: vec!["x".into(), "y".into()]
        },
        "{d}"
    );
}

#[test]
fn a_coordinate_without_inertia_or_constraint_is_named() {
    let d = library_error(
        Command::Solve,
        "coordinates x, y\nparameters m\nkinetic E = m*x'^2/2\nconstraint c: x = 1\n",
    );
    assert_eq!(
        d.kind(),
        &ErrorKind::SingularSystem {
            unknowns: vec!["y".into()]
        },
        "{d}"
    );
}

#[test]
fn kinds_carry_the_name_and_the_measure() {
    let d = library_error(Command::Derive, "coordinates x\nkinetic E = mass*x'^2/2\n");
    assert_eq!(
        d.kind(),
        &ErrorKind::UnknownName {
            name: "mass".into()
        }
    );
    let d = library_error(Command::Derive, "parameters m\nparameters m\n");
    assert_eq!(d.kind(), &ErrorKind::DuplicateName { name: "m".into() });
    assert_eq!(d.labels.len(), 1);
    assert_eq!(d.labels[0].span, qdot::Span::new(11, 12));
    let d = library_error(Command::Derive, "coordinates x\nkinetic E = x'^2/2 +\n");
    assert_eq!(d.kind(), &ErrorKind::Syntax);
    let opts = CommandOptions {
        max_terms: 100,
        ..CommandOptions::default()
    };
    let d = qdot::run_with(
        Command::Derive,
        "coordinates x\nparameters a, b, c, d\nkinetic E = x'^2/2\npotential V = (a+b+c+d+x)^12\n",
        Format::Text,
        &opts,
    )
    .unwrap_err();
    assert_eq!(
        d.kind(),
        &ErrorKind::TooLarge {
            measure: qdot::budget::Measure::Product(70, 70)
        }
    );
}

#[test]
fn a_label_is_a_second_caret_line_with_its_message() {
    let src = "coordinates x\nparameters m\ncoordinates x\n";
    let d = library_error(Command::Derive, src);
    assert_eq!(
        d.render("scene.qd", src),
        "error: coordinate declared twice: `x` is already a coordinate\n \
         --> scene.qd:3:13\n  \
         |\n\
         3 | coordinates x\n  \
         |             ^\n  \
         |\n\
         1 | coordinates x\n  \
         |             - `x` is a coordinate here\n  \
         = hint: each name has one meaning in a scene; role statements add up, but their names must differ\n"
    );
    // a label on the main line goes under the same copy of it
    let d = Diagnostic::error(qdot::Span::new(4, 5), "not this")
        .with_label(qdot::Span::new(0, 3), "because of this");
    assert_eq!(
        d.render("s.qd", "abc def\n"),
        "error: not this\n --> s.qd:1:5\n  |\n1 | abc def\n  |     ^\n  | --- because of this\n"
    );
}

#[test]
fn to_json_of_a_global_error_has_null_places() {
    let d = Diagnostic::global("no").with_kind(ErrorKind::bad_option("--set"));
    assert_eq!(
        d.to_json(""),
        r#"{"error":{"kind":"bad_option","data":{"option":"--set"},"message":"no","line":null,"column":null,"hint":null,"labels":[]}}"#
    );
}

/// The application layer's own refusals carry their kinds too: a `--set`
/// name that is no parameter, `--at` changing with time, `forces` of a
/// scene without coordinates.
#[test]
fn the_application_layers_refusals_have_kinds() {
    use qdot::app::{self, CommandOptions, Context};
    use qdot::diag::ErrorKind;
    let pendulum = std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/examples/first.qd"))
        .expect("the example");
    let ctx = Context::new();
    let mut set = qdot::solve::equilibrium::Values::default();
    set.insert("k".to_string(), 1.0);
    let e = app::equilibria(&ctx, &pendulum, &set).expect_err("k is no parameter");
    assert_eq!(e.kind(), &ErrorKind::bad_option("--set"));
    let opts = CommandOptions {
        at: Some("theta=t".to_string()),
        ..CommandOptions::default()
    };
    let e = app::modes(&ctx, &pendulum, &opts).expect_err("--at moves");
    assert_eq!(e.kind(), &ErrorKind::bad_option("--at"));
    let e = app::run(
        &ctx,
        qdot::Command::Forces,
        "parameters m\n",
        &CommandOptions::default(),
    )
    .expect_err("no coordinates");
    assert_eq!(e.kind(), &ErrorKind::NothingToSolve);
}
