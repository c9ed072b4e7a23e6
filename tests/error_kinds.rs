//! Errors a program can match: each class of error carries its
//! `ErrorKind`, named in `--format json` (crates/syntax/src/diag.rs).

use qdot::solve::equilibrium::Values;
use qdot::Scene;

/// The error of reading `src`, or of its equilibria: (kind, message).
fn error_of(src: &str) -> (String, String) {
    let ctx = qdot::Context::new();
    let d = match Scene::parse(src) {
        Err(d) => d,
        Ok(_) => match qdot::app::equilibria(&ctx, src, &Values::new()) {
            Err(d) => d,
            Ok(_) => panic!("no error: {src}"),
        },
    };
    (d.kind().name().to_string(), d.message)
}

#[test]
fn each_class_of_error_has_its_kind() {
    let cases = [
        (
            "coordinates x\nparameters m\nv = [x, 1]\nkinetic T = 1/2*m*v + x\n",
            "type_mismatch",
            "can't add a vector and a number",
        ),
        (
            "coordinates x\nparameters m, k\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2/0\n",
            "undefined",
            "division by zero: this divisor is exactly 0",
        ),
        (
            "coordinates th\nparameters m, l\nbody b: mass -m, angle th, at [l*cos(th), l*sin(th)], inertia m*l^2\n",
            "unphysical",
            "a mass must be positive; this one is negative",
        ),
        (
            "coordinates x\nparameters m\nassume m < 0\nkinetic T = 1/2*m*x'^2\n",
            "unphysical",
            "this fact is false for the parameters as declared",
        ),
        (
            "coordinates x\nparameters m\na = b\nb = a\nkinetic T = 1/2*m*x'^2 + a\n",
            "invalid_scene",
            "cyclic definition: a → b → a",
        ),
        (
            "coordinates x\nparameters m, k\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2*cos(t)\n",
            "no_equilibrium",
            "the force on `x` depends on time, so there is no static equilibrium",
        ),
        (
            "coordinates x\nparameters m, k\nkinetic T = 1/2*m*x'^2\npotential V = k*x^5 + k*x^4 + x^3*m + x + 1\n",
            "no_closed_form",
            "no closed form for these equilibrium equations; they can be solved numerically given parameter values",
        ),
    ];
    for (src, kind, message) in cases {
        assert_eq!(
            error_of(src),
            (kind.to_string(), message.to_string()),
            "{src}"
        );
    }
}

#[test]
fn the_kinds_have_distinct_names() {
    use qdot::diag::ErrorKind;
    let kinds = [
        ErrorKind::Syntax,
        ErrorKind::DimensionMismatch,
        ErrorKind::NothingToSolve,
        ErrorKind::Constraints,
        ErrorKind::Integration,
        ErrorKind::TypeMismatch,
        ErrorKind::InvalidScene,
        ErrorKind::Unphysical,
        ErrorKind::Undefined,
        ErrorKind::LimitExceeded,
        ErrorKind::Unsupported,
        ErrorKind::NoClosedForm,
        ErrorKind::NoEquilibrium,
        ErrorKind::Convergence,
        ErrorKind::Internal,
        ErrorKind::Other,
    ];
    let mut names: Vec<&str> = kinds.iter().map(ErrorKind::name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), kinds.len());
    for k in &kinds {
        assert_eq!(k.data(), serde_json::json!({}), "{}", k.name());
    }
}
