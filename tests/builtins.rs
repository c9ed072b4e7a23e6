//! The built-in functions: every name of the table resolves, when parsed,
//! to its own function, and evaluates to that function (none falls
//! through to another); a built-in's name declared a given function of
//! time is refused where it is called.

use crate::common::locate;
use qdot::expr::print;
use qdot::parse::ast::{Builtin, Callee, ExprKind};
use qdot::parse::parse_expr;
use qdot::{Scene, Value};

const SCENE: &str = "coordinates x\nparameters m\n";

/// A call of `b` and its value in the input syntax (a vector's or a
/// rotation's components in brackets). No wildcard: a new built-in
/// function fails to compile here until it has its sample.
fn sample(b: Builtin) -> (&'static str, &'static str) {
    match b {
        Builtin::Sin => ("sin(x)", "sin(x)"),
        Builtin::Cos => ("cos(x)", "cos(x)"),
        Builtin::Tan => ("tan(x)", "sin(x)/cos(x)"),
        Builtin::Sqrt => ("sqrt(m)", "sqrt(m)"),
        Builtin::Exp => ("exp(x)", "exp(x)"),
        Builtin::Ln => ("ln(m)", "ln(m)"),
        Builtin::Atan => ("atan(x)", "atan(x)"),
        Builtin::Asin => ("asin(x)", "asin(x)"),
        Builtin::Acos => ("acos(x)", "acos(x)"),
        Builtin::Dot => ("dot([x, 1], [2, x])", "3*x"),
        Builtin::Cross => ("cross([x, 1], [2, x])", "x^2 - 2"),
        Builtin::Norm => ("norm([3*m, 4*m])", "5*m"),
        Builtin::Rot => (
            "rot(z, x)",
            "[cos(x), -sin(x), 0, sin(x), cos(x), 0, 0, 0, 1]",
        ),
        Builtin::Axis => ("axis(rot(z, x), 2)", "[-sin(x), cos(x), 0]"),
        Builtin::Express => ("express([1, 0, 0], rot(z, x))", "[cos(x), -sin(x), 0]"),
        Builtin::Omega => ("omega(rot(z, x))", "[0, 0, x']"),
        Builtin::Inertia => ("inertia(m, x)", "m*x''"),
        Builtin::Series => ("series(m, m)", "m/2"),
        Builtin::Parallel => ("parallel(m, m)", "2*m"),
        Builtin::Diff => ("diff(m*x^2, x)", "2*m*x"),
        Builtin::Dt => ("dt(x^2)", "2*x*x'"),
        Builtin::Subs => ("subs(m*x, x = 2)", "2*m"),
        Builtin::Expand => ("expand((x + 1)^2)", "(x + 1)^2"),
        Builtin::Factor => ("factor(x^2 - 1)", "x^2 - 1"),
        Builtin::Taylor => ("taylor(exp(x), x, 2)", "x^2/2 + x + 1"),
    }
}

fn text(v: &Value) -> String {
    let cs: Vec<String> = v.components().iter().map(print::input).collect();
    match v {
        Value::Scalar(_) => cs.join(""),
        Value::Vector(_) | Value::Rotation(_) => format!("[{}]", cs.join(", ")),
    }
}

#[test]
fn every_builtin_function_resolves_and_evaluates_to_itself() {
    let s = Scene::parse(SCENE).unwrap();
    let mut wrong = Vec::new();
    for &b in Builtin::ALL {
        let (call, want) = sample(b);
        let e = parse_expr(call).unwrap();
        let ExprKind::Call(Callee::Builtin(resolved, _), _) = e.kind else {
            panic!("{call} is not a call of a built-in function: {e:?}");
        };
        assert_eq!(resolved, b, "{call}");
        let got = text(&s.value_of(call).unwrap());
        if got != want {
            wrong.push(format!("{call} = {got}, expected {want}"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// `functions sin` and a call `sin(t)`: the given function or the built-in?
/// The evaluator took the given function and the dimension check the
/// built-in; now the call is refused where it is written.
#[test]
fn a_builtin_name_declared_a_given_function_is_refused_where_called() {
    let src = "coordinates x\nfunctions sin\nparameters m\nkinetic E = 1/2*m*x'^2\npotential V = m*sin(t)*x\n";
    let err = Scene::parse(src).unwrap_err();
    assert_eq!(
        err.message,
        "`sin` is a built-in function and also a given function of time here"
    );
    assert_eq!(
        err.hint.as_deref(),
        Some("give the given function another name in `functions …`")
    );
    let at = locate(src, &err);
    assert_eq!((at.line, at.col, at.width), (5, 17, 3));
    // the given function itself, not called, is still the given function
    let uncalled = src.replace("sin(t)", "sin");
    let s = Scene::parse(&uncalled).unwrap();
    assert_eq!(print::input(&s.expr("sin'").unwrap()), "sin'");
}
