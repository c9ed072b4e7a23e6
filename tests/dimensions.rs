//! Dimensions (issue 19): wrong scenes caught at the right term with both
//! dimensions, correct scenes with unusual units accepted, every example
//! annotated and clean, and the check's properties.
//!
//! Cases are data, in `tests/data/dimensions/`: `wrong/NAME.qd` (one
//! mistake each) with its blessed error `wrong/NAME.txt` (`LINE:COL`, then
//! the error as qdot prints it), and `right/NAME.qd` with the blessed
//! `qdot check` report `right/NAME.txt`.
//! `QDOT_BLESS=1 cargo test --release --test it dimensions::` rewrites the
//! blessed files; review the diff, they are the assertions.

use proptest::prelude::*;
use qdot::output::{self, Command, Format};
use qdot::scene::dimension::{self, Dimension, DimensionSource, DIMENSION_NAMES};
use qdot::Scene;
use std::path::{Path, PathBuf};

const DATA: &str = concat!(env!("QDOT_ROOT"), "/tests/data/dimensions");

fn cases(dir: &str) -> Vec<PathBuf> {
    crate::common::cases(&Path::new(DATA).join(dir))
}

use crate::common::blessed;

fn file_name(p: &Path) -> String {
    p.file_name().unwrap().to_string_lossy().into_owned()
}

/// Every wrong scene fails with a dimension error at its blessed place,
/// naming two dimensions; every command refuses it the same way.
#[test]
fn wrong_scenes_are_caught_at_the_term() {
    let all = cases("wrong");
    assert!(all.len() >= 25, "{} wrong scenes", all.len());
    let mut failures = Vec::new();
    for case in &all {
        let src = std::fs::read_to_string(case).unwrap();
        let err = match Scene::parse(&src) {
            Ok(_) => {
                failures.push(format!("{}: accepted", case.display()));
                continue;
            }
            Err(d) => d,
        };
        let span = err.span.expect("a dimension error has a position");
        let (line, col) = qdot::Diagnostic::line_col(&src, span.start);
        let text = format!("{line}:{col}\n{}", err.render(&file_name(case), &src));
        blessed(case, &text, &mut failures);
        // the same error from every command (the check runs when the scene is built)
        for cmd in [Command::Derive, Command::Check] {
            let got = output::run(cmd, &src, Format::Text, &Default::default());
            assert_eq!(got.err().map(|d| d.message), Some(err.message.clone()));
        }
        let names_two = err.message.contains("; ")
            || err.message.contains(", but ")
            || err.message.contains(", the first is ")
            || err.message.starts_with("unknown dimension")
            || err.message.starts_with("this is not a dimension");
        assert!(names_two, "{}: {}", case.display(), err.message);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Correct scenes with unusual units pass, and `qdot check` reports their
/// dimensions as blessed.
#[test]
fn right_scenes_are_accepted() {
    let all = cases("right");
    assert!(all.len() >= 10, "{} right scenes", all.len());
    let mut failures = Vec::new();
    for case in &all {
        let src = std::fs::read_to_string(case).unwrap();
        let scene = match Scene::parse(&src) {
            Ok(s) => s,
            Err(d) => {
                failures.push(d.render(&file_name(case), &src));
                continue;
            }
        };
        assert!(scene.dimensions_checked, "{}", case.display());
        let (text, _) =
            output::run(Command::Check, &src, Format::Text, &Default::default()).unwrap();
        blessed(case, &text, &mut failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every example is annotated, checks clean, and decides the dimension of
/// every coordinate, parameter and `solve` unknown.
#[test]
fn examples_are_annotated_and_clean() {
    let dir = concat!(env!("QDOT_ROOT"), "/examples");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "qd") {
            continue;
        }
        n += 1;
        let src = std::fs::read_to_string(&path).unwrap();
        let scene = Scene::parse(&src).unwrap();
        assert!(scene.dimensions_checked);
        let report = scene.dimension_report().unwrap();
        for name in &report.names {
            if name.kind != dimension::DimensionedName::Definition {
                assert!(
                    name.dimension.is_some(),
                    "{}: {} is {}",
                    path.display(),
                    name.name,
                    name.text()
                );
            }
        }
    }
    assert!(n >= 20);
}

/// Seed 23.4: the accelerations have the dimensions of g and g/r, the
/// coordinates are declared and the definitions found.
#[test]
fn seed_23_4_dimensions() {
    let src =
        std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/examples/seed_23_4.qd")).unwrap();
    let (json, _) = output::run(Command::Check, &src, Format::Json, &Default::default()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["accelerations"]["y3"], "acceleration");
    assert_eq!(v["accelerations"]["theta3"], "1/time^2");
    assert_eq!(v["generalized_forces"]["y3"], "force");
    assert_eq!(v["generalized_forces"]["theta3"], "energy");
    assert_eq!(v["definitions"]["m"], "mass");
    assert_eq!(v["definitions"]["J3"], "inertia");
    assert_eq!(v["dimensions"]["theta3"], "1");
    assert_eq!(v["sources"]["y3"], "declared");
    assert_eq!(v["sources"]["E1"], "defined");
}

/// A scene without annotations is not checked when built (it behaves as
/// before), but `qdot check` still finds what it can, relative to the
/// dimensions it leaves free.
#[test]
fn unannotated_scenes_are_unchanged() {
    let src = "coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x\n";
    let scene = Scene::parse(src).unwrap();
    assert!(!scene.dimensions_checked);
    let (json, _) = output::run(Command::Derive, src, Format::Json, &Default::default()).unwrap();
    assert!(!json.contains("dimensions"));
    let report = scene.dimension_report().unwrap();
    let k = report.names.iter().find(|n| n.name == "k").unwrap();
    // E is an energy, so V = k·x ties k to x and m; one of them stays free
    assert_eq!(k.source, DimensionSource::Free);
    assert!(k.dimension.is_none());
    let x = report.names.iter().find(|n| n.name == "x").unwrap();
    let text = x.text();
    assert!(text.contains("dim(") && text.contains("energy"), "{text}");
    // one annotation turns the check on: k*x is then not an energy
    let annotated = src.replace("parameters m, k", "parameters m: mass, k: stiffness");
    let err = Scene::parse(&annotated).unwrap_err();
    assert!(
        err.message.contains("a force; an energy is needed"),
        "{}",
        err.message
    );
}

/// An inferred name's origin is reported, and a conflict shows both places.
#[test]
fn inference_reports_where() {
    let src = "coordinates x\nparameters m: mass, g: acceleration\nkinetic E = 1/2*m*x'^2\npotential V = m*g*x^2\n";
    let err = Scene::parse(src).unwrap_err();
    let hint = err.hint.unwrap();
    assert!(hint.contains("`x` is a length, found from 3:13"), "{hint}");
    let ok = "coordinates x\nparameters m: mass, g: acceleration\nkinetic E = 1/2*m*x'^2\npotential V = m*g*x\n";
    let report = Scene::parse(ok).unwrap().dimension_report().unwrap();
    let x = &report.names[0];
    assert_eq!(x.dimension, Some(Dimension::from_small([0, 1, 0, 0, 0])));
    assert!(matches!(x.source, DimensionSource::Inferred(_)));
}

/// The table has no name twice, and every name reads back as itself.
#[test]
fn names_read_back() {
    for (i, a) in DIMENSION_NAMES.iter().enumerate() {
        assert!(DIMENSION_NAMES[i + 1..].iter().all(|b| b.name != a.name));
        let d = dimension::dimension_named(a.name).unwrap();
        assert_eq!(d, Dimension::from_small(a.exponents));
    }
}

/// The dimension `d` read back from its annotation syntax.
fn read_back(ascii: &str) -> Dimension {
    let src = format!("parameters p: {ascii}\nx = p\n");
    let report = Scene::parse(&src).unwrap().dimension_report().unwrap();
    report.of("p").cloned().unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// A dimension printed in annotation syntax reads back as itself.
    #[test]
    fn ascii_round_trip(e in proptest::array::uniform5(-4i8..=4)) {
        let d = Dimension::from_small(e);
        prop_assert_eq!(read_back(&d.ascii()), d);
    }

    /// A scene consistent by construction passes; scaling one term by a
    /// base dimension makes it fail at that term.
    #[test]
    fn consistent_scenes_pass_and_one_wrong_term_is_found(
        ea in proptest::array::uniform5(-3i8..=3),
        eb in proptest::array::uniform5(-3i8..=3),
        wrong in 0usize..5,
        which in 0usize..3,
    ) {
        // V = a·x^2 + b·x + c with x a length: a = energy/length², b =
        // energy/length, c = energy; a and b get arbitrary dimensions
        // times those, carried by the extra parameters p and q
        let pa = Dimension::from_small(ea);
        let pb = Dimension::from_small(eb);
        let energy = Dimension::from_small([1, 2, -2, 0, 0]);
        let l = Dimension::from_small([0, 1, 0, 0, 0]);
        let a = energy.div(&l).div(&l).div(&pa);
        let b = energy.div(&l).div(&pb);
        let scene = |terms: [&str; 3], extra: &str| format!(
            "coordinates x: length\nparameters m: mass, a: {}, b: {}, c: energy, p: {}, q: {}{extra}\nkinetic E = 1/2*m*x'^2\npotential V = {} + {} + {}\n",
            a.ascii(), b.ascii(), pa.ascii(), pb.ascii(), terms[0], terms[1], terms[2]
        );
        let mut terms = ["a*p*x^2", "b*q*x", "c"];
        let src = scene(terms, "");
        prop_assert!(Scene::parse(&src).is_ok(), "{}", src);
        let base = dimension::BASE_DIMENSIONS[wrong];
        let term = format!("{}*s", terms[which]);
        terms[which] = &term;
        let bad = scene(terms, &format!(", s: {base}"));
        let err = Scene::parse(&bad).unwrap_err();
        let at = err.span.unwrap();
        prop_assert_eq!(&bad[at.start..at.end], term.as_str(), "{}", err.message);
    }
}

/// The book's table of dimension names is `DIMENSION_NAMES`, row by row.
#[test]
fn book_table_is_the_table() {
    let page =
        std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/book/src/dimensions.md")).unwrap();
    let table = page
        .split("<!-- dimension-names -->")
        .nth(1)
        .and_then(|t| t.split("<!-- /dimension-names -->").next())
        .expect("the marked table");
    let rows: Vec<String> = table
        .lines()
        .filter(|l| l.starts_with("| `"))
        .map(str::to_string)
        .collect();
    let want: Vec<String> = DIMENSION_NAMES
        .iter()
        .map(|d| {
            let kind = match d.kind {
                dimension::DimensionNameKind::Base => "base",
                dimension::DimensionNameKind::Derived => "derived",
                dimension::DimensionNameKind::Synonym => "synonym",
                dimension::DimensionNameKind::Unit => "unit",
            };
            let dim = Dimension::from_small(d.exponents);
            let shown = factors_ascii(&dim);
            format!("| `{}` | {shown} | {kind} |", d.name)
        })
        .collect();
    pretty_assertions::assert_eq!(rows, want);
}

/// A dimension in base dimensions only, annotation syntax.
fn factors_ascii(d: &Dimension) -> String {
    let e = d.exponents();
    let mut num = Vec::new();
    let mut den = Vec::new();
    for (i, name) in dimension::BASE_DIMENSIONS.iter().enumerate() {
        let x = e[i].as_i64().unwrap();
        let p = |k: i64| {
            if k == 1 {
                name.to_string()
            } else {
                format!("{name}^{k}")
            }
        };
        if x > 0 {
            num.push(p(x));
        } else if x < 0 {
            den.push(p(-x));
        }
    }
    let mut s = if num.is_empty() {
        "1".to_string()
    } else {
        num.join("*")
    };
    for d in den {
        s.push('/');
        s.push_str(&d);
    }
    s
}

/// Definitions may refer forward: the check then takes them in dependency
/// order, and finds the same dimensions and the same errors.
#[test]
fn forward_references() {
    let ok = "coordinates x: length\nparameters m: mass, k: stiffness\nkinetic E = 1/2*m*v^2\npotential V = 1/2*k*x^2\nv = x'\n";
    let report = Scene::parse(ok).unwrap().dimension_report().unwrap();
    assert_eq!(
        report.of("v"),
        Some(&Dimension::from_small([0, 1, -1, 0, 0]))
    );
    let bad = ok.replace("v = x'", "v = x");
    let err = Scene::parse(&bad).unwrap_err();
    let at = err.span.unwrap();
    assert_eq!(&bad[at.start..at.end], "1/2*m*v^2", "{}", err.message);
    assert!(
        err.message.contains("an energy is needed"),
        "{}",
        err.message
    );
}

/// Products and sums as long as the parser allows are checked without
/// exhausting the stack (a test thread's 2 MiB).
#[test]
fn long_products_and_sums() {
    let n = 990;
    let product = vec!["a"; n].join("*");
    let quotient = vec!["a"; n].join("/");
    let sum = vec!["x"; n].join(" + ");
    let src = format!(
        "coordinates x: length\nparameters m: mass, a: 1\nkinetic E = 1/2*m*x'^2\nV1 = {product}*x\nV2 = {quotient}/x\nV3 = m*({sum})\nV4 = {product}*m*x^2/x\n"
    );
    let report = Scene::parse(&src).unwrap().dimension_report().unwrap();
    assert_eq!(
        report.of("V1"),
        Some(&Dimension::from_small([0, 1, 0, 0, 0]))
    );
    assert_eq!(
        report.of("V2"),
        Some(&Dimension::from_small([0, -1, 0, 0, 0]))
    );
    assert_eq!(
        report.of("V3"),
        Some(&Dimension::from_small([1, 1, 0, 0, 0]))
    );
    let bad = format!("{src}potential V = {product}*m*x\n");
    let err = Scene::parse(&bad).unwrap_err();
    assert!(
        err.message.contains("an energy is needed"),
        "{}",
        err.message
    );
}
