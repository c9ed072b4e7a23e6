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
    let src =
        std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/examples/heavy_top.qd")).unwrap();
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

/// A compound pendulum on a universal joint with a full inertia tensor
/// (products of inertia): 2 coordinates, M's determinant not constant.
const FULL_INERTIA: &str = "coordinates a, b
parameters m, d, e, g, Ixx, Iyy, Izz, Ixy, Iyz, Ixz
frame B = rot(x, a) * rot(y, b)
body p: mass m, inertia [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]], frame B, at B * [e, 0, -d]
gravity [0, 0, -g]
";

/// The planar double compound pendulum, two bars.
const TWO_BARS: &str = "coordinates th1, th2
parameters m1, m2, l1, l2, J1, J2, g
P = [l1*sin(th1), -l1*cos(th1)]
body bar1: mass m1, inertia J1, angle th1, at 1/2*P
body bar2: mass m2, inertia J2, angle th2, at P + l2/2*[sin(th2), -cos(th2)]
gravity [0, -g]
";

/// `qdot CMD` on `src` in `fmt`.
fn printed(cmd: Command, src: &str, fmt: Format) -> String {
    output::run_with(cmd, src, fmt, &Default::default())
        .unwrap_or_else(|d| panic!("{}", d.render("scene", src)))
        .0
}

/// A 2-coordinate body's `hamilton` is no larger than its `solve` (issue
/// 35): it printed 5.7 MB (two bars) or ran out of budget (full inertia)
/// where `solve` prints 2–5 KB. Past the size rule it is written through
/// the velocities `v_q`, in text and JSON (and LaTeX, whose prose makes
/// the two bars' 6 % longer than `solve`'s).
#[test]
fn a_two_coordinate_body_hamilton_is_no_larger_than_its_solve() {
    for (src, names) in [
        (FULL_INERTIA, ["v_a", "v_b"]),
        (TWO_BARS, ["v_th1", "v_th2"]),
    ] {
        for fmt in [Format::Text, Format::Json] {
            let h = printed(Command::Hamilton, src, fmt);
            let s = printed(Command::Solve, src, fmt);
            assert!(
                h.len() <= s.len(),
                "{fmt:?}: hamilton {} B, solve {} B",
                h.len(),
                s.len()
            );
        }
        let latex = printed(Command::Hamilton, src, Format::Latex);
        assert!(latex.contains("The intermediates, in order"), "{latex}");
        let text = printed(Command::Hamilton, src, Format::Text);
        assert!(
            text.starts_with("Intermediates  (in order: each is written in the ones before it)\n")
        );
        let json: serde_json::Value =
            serde_json::from_str(&printed(Command::Hamilton, src, Format::Json)).unwrap();
        let listed: Vec<&str> = json["intermediates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|i| i["name"].as_str().unwrap())
            .collect();
        assert_eq!(listed, names);
        assert_eq!(json["velocities"][&names[0][2..]], names[0]);
    }
    let text = printed(Command::Hamilton, FULL_INERTIA, Format::Text);
    assert!(
        text.contains(
            "  H = −d·g·m·cos(a)·cos(b) − e·g·m·cos(a)·sin(b) + 1/2·p_a·v_a + 1/2·p_b·v_b\n"
        ),
        "{text}"
    );
    assert!(
        text.contains("  ṗ_a = −d·g·m·cos(b)·sin(a) − e·g·m·sin(a)·sin(b)\n"),
        "{text}"
    );
}

/// The structured Hamiltonian expanded through its intermediates is the
/// expanded one, exactly; and the expanded one satisfies its definition:
/// q̇ = ∂H/∂p and ṗ = −∂H/∂q + Q̃.
#[test]
fn structured_hamilton_expands_to_the_expanded_one() {
    use qdot::scene::Structure;
    for src in [FULL_INERTIA, TWO_BARS] {
        let s = scene(src);
        let kept = Hamiltonian::derive_as(&s, Structure::Kept).unwrap();
        let tape = kept.intermediates.as_deref().expect("written through v_q");
        let plain = Hamiltonian::derive_as(&s, Structure::Expanded).unwrap();
        assert!(plain.intermediates.is_none());
        let expanded = |e: &qdot::Expr| tape.expand(e).unwrap();
        assert!(expanded(&kept.hamiltonian).equals(&plain.hamiltonian));
        for k in 0..2 {
            assert!(expanded(&kept.velocities[k]).equals(&plain.velocities[k]));
            assert!(expanded(&kept.momentum_rates[k]).equals(&plain.momentum_rates[k]));
            assert!(expanded(&kept.other_forces[k]).equals(&plain.other_forces[k]));
            assert!(kept.momenta[k].equals(&plain.momenta[k]));
        }
    }
    let s = scene(TWO_BARS);
    let h = Hamiltonian::derive_as(&s, Structure::Expanded).unwrap();
    for (k, q) in ["th1", "th2"].iter().enumerate() {
        let p = qdot::Expr::unknown(&h.momentum_names[k]).as_var().unwrap();
        let qk = qdot::Expr::coord(q, 0).as_var().unwrap();
        assert!(h.hamiltonian.diff(p).equals(&h.velocities[k]));
        assert!(h.hamiltonian.diff(qk).neg().equals(&h.momentum_rates[k]));
    }
}

/// The double pendulum's expanded H and ṗ are the textbook ones (H was
/// 256 KB of unreduced fractions: q̇ substituted into L squared the
/// velocities' denominator, which the canonical form cannot cancel).
#[test]
fn the_double_pendulum_hamiltonian_is_the_textbook_one() {
    let src = std::fs::read_to_string(concat!(env!("QDOT_ROOT"), "/examples/double_pendulum.qd"))
        .unwrap();
    let s = scene(&src);
    let h = Hamiltonian::derive(&s).unwrap();
    assert!(h.intermediates.is_none());
    let den = "(m1 + m2*sin(th1 - th2)^2)";
    let kinetic =
        "(m2*l2^2*p_th1^2 + (m1 + m2)*l1^2*p_th2^2 - 2*m2*l1*l2*p_th1*p_th2*cos(th1 - th2))";
    same(
        &s,
        &h.hamiltonian,
        &format!("{kinetic}/(2*m2*l1^2*l2^2*{den}) - (m1 + m2)*g*l1*cos(th1) - m2*g*l2*cos(th2)"),
    );
    let c1 = format!("p_th1*p_th2*sin(th1 - th2)/(l1*l2*{den})");
    let c2 = format!("{kinetic}*sin(2*(th1 - th2))/(2*l1^2*l2^2*{den}^2)");
    same(
        &s,
        &h.momentum_rates[0],
        &format!("-(m1 + m2)*g*l1*sin(th1) - {c1} + {c2}"),
    );
    same(
        &s,
        &h.momentum_rates[1],
        &format!("-m2*g*l2*sin(th2) + {c1} - {c2}"),
    );
    assert!(printed(Command::Hamilton, &src, Format::Text).len() < 4_000);
}

/// ṗ = ∂L/∂q + Q̃ is substituted once: adding −∂H/∂q (over the square of
/// the velocity's denominator) to Q̃ (over it once) made a 1-coordinate
/// scene's ṗ 117 KB.
#[test]
fn forces_outside_h_share_the_velocity_denominator() {
    let src = "coordinates q1
parameters a, b, c, k, m, g
x = q1 + k*sin(q1)
y = c*cos(q1)
kinetic E = 1/2*a*b^2*q1'^2 + 1/2*a*(x'^2 + y'^2)
potential V = c*g*y
forcefunction U = m*cos(q1)
dissipation D = -1/2*k*q1^2*q1'^2
force q1: -k*q1'
";
    let s = scene(src);
    let h = Hamiltonian::derive(&s).unwrap();
    assert!(h.intermediates.is_none());
    let q1 = qdot::Expr::coord("q1", 0).as_var().unwrap();
    let want = h.hamiltonian.diff(q1).neg().add(&h.other_forces[0]);
    assert!(h.momentum_rates[0].equals(&want));
    same(
        &s,
        &h.other_forces[0],
        "-k*(q1^2 + 1)*p_q1/(a*(b^2 + (1 + k*cos(q1))^2 + c^2*sin(q1)^2))",
    );
    assert!(printed(Command::Hamilton, src, Format::Text).len() < 3_000);
}
