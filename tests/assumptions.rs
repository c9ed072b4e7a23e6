//! `assume` (issue 16): parameters of either sign and order facts between
//! parameters, used wherever qdot decides a sign.

use qdot::engine::algebra::assume::{assuming, Assumptions};
use qdot::engine::algebra::sign::{sign_exact, Sign};
use qdot::output::{self, Command, Format};
use qdot::Scene;

const CYLINDER: &str = "coordinates theta
parameters m, g, R, r
kinetic E = 3/4*m*(R - r)^2*theta'^2
potential V = -m*g*(R - r)*cos(theta)
";

fn run(cmd: Command, src: &str, set: &str) -> Result<String, String> {
    let set = output::parse_set_any_sign(set).map_err(|d| d.message)?;
    output::run(cmd, src, Format::Text, &set)
        .map(|(s, _)| s)
        .map_err(|d| d.message)
}

/// The disk rolling inside a cylinder: undecided without the order of the
/// radii, decided with it.
#[test]
fn an_order_fact_decides_stability() {
    let without = run(Command::Equilibrium, CYLINDER, "").unwrap();
    assert!(without.contains("undecided"), "{without}");
    let with = format!("{CYLINDER}assume R > r\n");
    let eq = run(Command::Equilibrium, &with, "").unwrap();
    assert!(eq.contains("θ = 0  — stable"), "{eq}");
    assert!(eq.contains("θ = π  — unstable"), "{eq}");
    let modes = run(Command::Modes, &with, "").unwrap();
    assert!(
        modes.contains("Stability of the equilibrium: stable"),
        "{modes}"
    );
    // written the other way round, and about definitions of parameters
    let other = format!("{CYLINDER}d = R - r\nassume r < R, d > 0\n");
    assert!(run(Command::Equilibrium, &other, "")
        .unwrap()
        .contains("θ = 0  — stable"));
}

/// A parameter of either sign: signs are decided case by case, and
/// `--set` may give it a negative value (and no other parameter).
#[test]
fn real_parameters() {
    let s = Scene::parse("parameters k, e\nassume e real\n").unwrap();
    let at = |x: &str| assuming(&s.assumptions, || sign_exact(&s.expr(x).unwrap()));
    assert_eq!(at("k + e^2"), Some(Sign::Positive));
    assert_eq!(at("k*e^2"), None, "zero at e = 0");
    assert_eq!(at("e"), None);
    assert_eq!(at("-k - e^2"), Some(Sign::Negative));
    // without the assumption e is positive
    let plain = Scene::parse("parameters k, e\n").unwrap();
    assert_eq!(sign_exact(&plain.expr("e").unwrap()), Some(Sign::Positive));
    let charge = "coordinates x\nparameters m, k, e, E0\nassume e real\n\
        kinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2 - e*E0*x\n";
    let eq = run(Command::Equilibrium, charge, "m=1,k=2,e=-1,E0=3").unwrap();
    assert!(eq.contains("x = e·E₀/k"), "{eq}");
    let err = run(Command::Equilibrium, charge, "m=1,k=-2,e=1,E0=3").unwrap_err();
    assert!(err.contains("parameters are positive"), "{err}");
    // the strict reader of --set still refuses every negative value
    assert!(output::parse_set("e=-1").is_err());
}

/// Order facts by elimination: R = r + δ.
#[test]
fn eliminations() {
    let s = Scene::parse("parameters R, r, a\nassume R > r, a > 2*R\n").unwrap();
    let at = |x: &str| assuming(&s.assumptions, || sign_exact(&s.expr(x).unwrap()));
    assert_eq!(at("R - r"), Some(Sign::Positive));
    assert_eq!(at("r - R"), Some(Sign::Negative));
    assert_eq!(at("a - R - r"), Some(Sign::Positive));
    assert_eq!(at("(R - r)^2 - 1"), None);
    assert_eq!(at("R^2 - r^2"), Some(Sign::Positive));
    // outside `assuming`, nothing is assumed
    assert_eq!(sign_exact(&s.expr("R - r").unwrap()), None);
    let none = Assumptions::default();
    assert!(none.is_empty());
}

/// A body's mass may be a difference the scene orders.
#[test]
fn a_mass_positive_by_assumption() {
    let src = "coordinates x\nparameters M, m\nparticle p: mass M - m, at [x, 0]\n";
    assert!(Scene::parse(src).is_err());
    assert!(Scene::parse(&format!("{src}assume M > m\n")).is_ok());
}

#[test]
fn wrong_facts_are_refused() {
    for (src, message) in [
        ("coordinates x\nassume x real\n", "needs a parameter"),
        ("parameters a\nassume a > a + 1\n", "this fact is false"),
        (
            "parameters a, b\nassume a >= b\n",
            "only strict order facts",
        ),
        (
            "coordinates x\nparameters a\nassume a > x\n",
            "changes with time",
        ),
        ("parameters a\nassume a\n", "`<` or `>`"),
    ] {
        let err = Scene::parse(src).unwrap_err();
        assert!(err.span.is_some(), "{src}");
        assert!(err.message.contains(message), "{src}: {}", err.message);
    }
}

/// √(q²) is q where the facts make q positive, −q where negative, and
/// |q| otherwise: in definitions and in expressions typed later.
#[test]
fn square_roots_of_squares() {
    let s = Scene::parse(
        "parameters R, r, a\nassume R > r\nd = sqrt((R - r)^2)\nn = sqrt((r - R)^2)\nu = ((a - r)^2)^(1/2)\n",
    )
    .unwrap();
    let want = s.expr("R - r").unwrap();
    assert!(s.definition("d").unwrap().equals(&want));
    assert!(s.definition("n").unwrap().equals(&want));
    assert!(s.expr("sqrt((r - R)^2)").unwrap().equals(&want));
    // a − r has no decided sign: it stays √((a − r)²), printed |a − r|
    assert!(!s.definition("u").unwrap().equals(&s.expr("a - r").unwrap()));
    assert!(s.definition("u").unwrap().to_unicode().starts_with('|'));
}
