//! Hamilton's equations and integrals of motion (issue 17): exact values
//! for textbook systems (the SymPy cross-check of `qdot hamilton` is in
//! `sympy_fixtures`).

use qdot::mechanics::{Hamiltonian, Integrals};
use qdot::output::{self, Command, Format};
use qdot::Scene;

fn scene(src: &str) -> Scene {
    Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene", src)))
}

fn same(s: &Scene, got: &qdot::Expr, want: &str) {
    let w = s.expr(want).unwrap();
    assert!(got.equals(&w), "got {got}, want {w}");
}

const SPHERICAL: &str = "coordinates theta, phi
parameters m, g, l
kinetic E = 1/2*m*l^2*(theta'^2 + sin(theta)^2*phi'^2)
potential V = -m*g*l*cos(theta)
";

/// The spherical pendulum: H, Hamilton's equations, p_φ conserved, the
/// energy E + V, and Routh's reduction with the textbook effective
/// potential and θ̈.
#[test]
fn the_spherical_pendulum() {
    let s = scene(SPHERICAL);
    let h = Hamiltonian::derive(&s).unwrap();
    assert_eq!(h.momentum_names, ["p_theta", "p_phi"]);
    same(&s, &h.momenta[1], "m*l^2*sin(theta)^2*phi'");
    same(&s, &h.velocities[1], "p_phi/(m*l^2*sin(theta)^2)");
    same(
        &s,
        &h.hamiltonian,
        "p_theta^2/(2*m*l^2) + p_phi^2/(2*m*l^2*sin(theta)^2) - m*g*l*cos(theta)",
    );
    same(
        &s,
        &h.momentum_rates[0],
        "p_phi^2*cos(theta)/(m*l^2*sin(theta)^3) - m*g*l*sin(theta)",
    );
    same(&s, &h.momentum_rates[1], "0");
    assert!(h.other_forces.iter().all(qdot::Expr::is_zero));

    let i = Integrals::find(&s).unwrap();
    assert_eq!(i.cyclic.len(), 1);
    assert_eq!(i.cyclic[0].0, "phi");
    assert!(i.energy_is_e_plus_v);
    same(
        &s,
        i.energy.as_ref().unwrap(),
        "1/2*m*l^2*(theta'^2 + sin(theta)^2*phi'^2) - m*g*l*cos(theta)",
    );
    let r = i.routh.as_ref().unwrap();
    same(
        &s,
        &r.effective_potential,
        "p_phi^2/(2*m*l^2*sin(theta)^2) - m*g*l*cos(theta)",
    );
    assert_eq!(r.accelerations[0].0, "theta");
    same(
        &s,
        &r.accelerations[0].1,
        "p_phi^2*cos(theta)/(m^2*l^4*sin(theta)^3) - g/l*sin(theta)",
    );
}

/// Non-conservative forces: a damper on x keeps it out of H (Q̃ = −c·ẋ in
/// p) and breaks the energy integral; a force on a coordinate absent from L
/// keeps it from being cyclic; an explicit t in L has no energy integral.
#[test]
fn forces_outside_h_and_broken_integrals() {
    let damped = scene(
        "coordinates x, y
parameters m, k, c
kinetic E = 1/2*m*(x'^2 + y'^2)
potential V = 1/2*k*x^2
rayleigh R = 1/2*c*x'^2
",
    );
    let h = Hamiltonian::derive(&damped).unwrap();
    same(&damped, &h.other_forces[0], "-c*p_x/m");
    same(&damped, &h.momentum_rates[0], "-k*x - c*p_x/m");
    let i = Integrals::find(&damped).unwrap();
    assert_eq!(
        i.cyclic.iter().map(|(q, _)| q.as_str()).collect::<Vec<_>>(),
        ["y"]
    );
    assert!(i.energy.is_none());
    assert!(
        i.notes.iter().any(|n| n.contains("dissipation")),
        "{:?}",
        i.notes
    );

    let pushed = scene(
        "coordinates x
parameters m, F
kinetic E = 1/2*m*x'^2
force x: F
",
    );
    let i = Integrals::find(&pushed).unwrap();
    assert!(i.cyclic.is_empty());
    assert!(
        i.notes.iter().any(|n| n.contains("x is absent from L")),
        "{:?}",
        i.notes
    );

    let driven = scene(
        "coordinates x
parameters m, k, w
kinetic E = 1/2*m*x'^2
potential V = 1/2*k*x^2*cos(w*t)
",
    );
    let i = Integrals::find(&driven).unwrap();
    assert!(i.energy.is_none());
    assert!(i.notes.iter().any(|n| n.contains("explicitly")));
}

/// The heavy top: φ and ψ cyclic; the JSON of `hamilton` and `integrals`
/// carries the documented keys and re-parses.
#[test]
fn the_heavy_top_json() {
    let src = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/heavy_top.qd"
    ))
    .unwrap();
    let s = scene(&src);
    let (out, _) =
        output::run_with(Command::Integrals, &src, Format::Json, &Default::default()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["cyclic"], serde_json::json!(["phi", "psi"]));
    same(
        &s,
        &s.expr(v["momenta"]["psi"].as_str().unwrap()).unwrap(),
        "C*(psi' + cos(theta)*phi')",
    );
    assert_eq!(v["energy_is_e_plus_v"], true);
    assert!(v["reduced_accelerations"]["theta"].is_string());
    let (out, _) =
        output::run_with(Command::Hamilton, &src, Format::Json, &Default::default()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let h = s.expr(v["hamiltonian"].as_str().unwrap()).unwrap();
    same(
        &s,
        &h,
        "p_theta^2/(2*(A + m*l^2)) + (p_phi - p_psi*cos(theta))^2/(2*(A + m*l^2)*sin(theta)^2) + p_psi^2/(2*C) + m*g*l*cos(theta)",
    );
    let eqs = v["equations"].as_array().unwrap();
    assert_eq!(eqs.len(), 3);
    assert_eq!(eqs[1]["momentum"], "p_theta");
}

/// Refusals: a Lagrangian not quadratic in the velocities, a degenerate
/// one, a momentum name the scene already uses.
#[test]
fn hamilton_refuses_with_reasons() {
    for (src, words) in [
        (
            "coordinates x\nparameters m\nlagrangian L = m*x'^4\n",
            "not quadratic",
        ),
        (
            "coordinates x, y\nparameters m\nkinetic E = 1/2*m*(x' + y')^2\n",
            "degenerate",
        ),
        (
            "coordinates x\nparameters m, p_x\nkinetic E = 1/2*m*x'^2\n",
            "already uses",
        ),
    ] {
        let err = Hamiltonian::derive(&scene(src)).unwrap_err();
        assert!(err.message.contains(words), "{}", err.message);
        assert!(err.hint.is_some());
    }
}
