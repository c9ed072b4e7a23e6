//! The details of `qdot modes` a lecturer checks (issue 37, item 4): a
//! zero frequency drifts (a + b·t) and has one verdict with and without
//! `--set`; stability conditions are printed as a lecturer writes them
//! (factored, perfect squares and sums of squares recognized, the scene's
//! assumptions used); a parameter named like a matrix of the output is a
//! warning only where the output reads as that matrix defined by itself.

use crate::common::run::{json, qdot, qdot_on};

/// Two masses joined by a spring, no anchor: ω² = 0 (the pair drifts) and
/// k·(m₁ + m₂)/(m₁·m₂).
const FREE_PAIR: &str = "\
coordinates x1: length, x2: length
parameters m1: mass, m2: mass, k: force/length
kinetic T = 1/2*m1*x1'^2 + 1/2*m2*x2'^2
potential V = k/2*(x2 - x1)^2
";

/// One free coordinate, damped: ω² = 0, x = a + b·e^(−c·t/m).
const DAMPED_FREE: &str = "\
coordinates x: length
parameters m: mass, c: mass/time
kinetic T = 1/2*m*x'^2
rayleigh R = 1/2*c*x'^2
";

/// `qdot modes` on `src` in a file named by `tag` (one tag per test: the
/// tests run at once, and a file rewritten while another test reads it
/// would be a race).
fn modes_on(tag: &str, src: &str, rest: &[&str]) -> (String, String) {
    let (code, out, err) = qdot_on("oscillation_details", tag, src, "modes", rest);
    assert_eq!(code, 0, "{err}");
    (out, err)
}

fn stability_line(out: &str) -> &str {
    out.lines()
        .find(|l| l.starts_with("Stability of the equilibrium"))
        .unwrap_or_else(|| panic!("no verdict in\n{out}"))
}

// --------------------------------------------------------- zero frequency

#[test]
fn a_zero_mode_drifts_in_the_general_solution() {
    let (out, _) = modes_on("pair_drift", FREE_PAIR, &[]);
    assert!(
        out.contains(
            "General solution (undamped)  q(t) = Σ Cᵢ·uᵢ·cos(ωᵢ·t + φᵢ), and (Aᵢ + Bᵢ·t)·uᵢ where ωᵢ = 0\n  x₁ = A₁ + B₁·t + C₂·cos(ω₂·t + φ₂)\n  x₂ = A₁ + B₁·t − m₁/m₂·C₂·cos(ω₂·t + φ₂)\n"
        ),
        "{out}"
    );
    assert!(!out.contains("cos(0"), "{out}");
}

#[test]
fn a_zero_frequency_of_one_coordinate_is_no_oscillation() {
    let src = "coordinates x: length\nparameters m: mass\nkinetic T = 1/2*m*x'^2\n";
    let (out, _) = modes_on("free", src, &[]);
    assert!(
        out.contains(
            "Standard form  ÿ + 2α·ẏ + ω²·y = f(t)/M\n  x\u{308} = 0\n  ω² = 0\n  ω = 0: no restoring force, the free motion does not oscillate: y = a + b·t\n  regime: undamped\n"
        ),
        "{out}"
    );
    assert!(!out.contains("√(0)"), "{out}");
    let (out, _) = modes_on("damped_drift", DAMPED_FREE, &[]);
    assert!(
        out.contains(
            "  x\u{308} + c/m·x\u{307} = 0\n  ω² = 0\n  ω = 0: no restoring force, the free motion does not oscillate: y = a + b·e^(−2α·t)\n  α = c/(2·m)\n"
        ),
        "{out}"
    );
}

/// ω² = 16/81·k/m − g/(9·r) is 0 at these values: the mode drifts there.
#[test]
fn a_frequency_zero_at_the_set_values_drifts_there() {
    let (code, out, err) = qdot(&[
        "modes",
        "examples/seed_24_1.qd",
        "--set",
        "m=1,r=1,k=9,g=16,c=1,F0=1,p=2",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("  y₁ = A₁ + B₁·t\n"), "{out}");
    assert!(
        out.contains("  ω = 0: no restoring force, the free motion does not oscillate: y = a + b·e^(−2α·t)\n"),
        "{out}"
    );
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (a zero frequency: higher-order terms decide)"
    );
}

/// The verdict on a zero frequency is the same with and without values:
/// rounding splits its Jordan block into s ≈ ±1e-8, which once read as
/// "unstable" at some values and "stable" at others.
#[test]
fn a_zero_frequency_has_one_verdict_with_and_without_values() {
    let undecided =
        "Stability of the equilibrium: undecided (a zero frequency: higher-order terms decide)";
    let (out, _) = modes_on("pair", FREE_PAIR, &[]);
    assert_eq!(stability_line(&out), undecided);
    for set in ["m1=3,m2=7,k=11", "m1=0.3,m2=1.7,k=2.9", "m1=1,m2=3,k=5"] {
        let (out, _) = modes_on("pair", FREE_PAIR, &["--set", set]);
        assert_eq!(stability_line(&out), undecided, "--set {set}");
        // the zero ω² computed as −ε prints as 0
        assert!(
            out.contains("numeric ω² (eigen-solver): 0.0000000000, "),
            "{out}"
        );
        let (out, _) = modes_on("pair", FREE_PAIR, &["--set", set, "--format", "json"]);
        let v = json(&out);
        assert_eq!(v["stability"], "undecided", "--set {set}");
        assert_eq!(
            v["stability_note"],
            "a zero frequency: higher-order terms decide"
        );
    }
    for set in ["", "m=3,c=0.7", "m=0.1,c=13"] {
        let rest: &[&str] = if set.is_empty() { &[] } else { &["--set", set] };
        let (out, _) = modes_on("damped", DAMPED_FREE, rest);
        assert_eq!(stability_line(&out), undecided, "--set {set}");
    }
}

/// `qdot equilibrium` on the same pair: a line of equilibria x₁ = x₂,
/// neutral, with or without values (with values it was once dropped as
/// "not existing there", its position being symbolic in the free x₂).
#[test]
fn a_free_coordinate_is_the_same_equilibrium_with_values() {
    let line = "  1. x₁ = x₂, x₂ = any  — undecided (neutral: a coordinate is free)\n";
    for rest in [&[][..], &["--set", "m1=3,m2=7,k=11"][..]] {
        let (code, out, err) = qdot_on(
            "oscillation_details",
            "pair_eq",
            FREE_PAIR,
            "equilibrium",
            rest,
        );
        assert_eq!(code, 0, "{err}");
        assert!(
            out.ends_with(&format!("Equilibria\n{line}")),
            "{rest:?}: {out}"
        );
    }
}

// ------------------------------------------------------------- conditions

/// ω = √(g/l) ± W: the condition (g − l·W²)² > 0 is a perfect square.
#[test]
fn the_foucault_pendulum_is_stable_unless_the_frame_turns_at_its_rate() {
    let (code, out, err) = qdot(&["modes", "examples/foucault.qd"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (stable unless l·W² = g, where the linearization does not decide)"
    );
    let (_, out, _) = qdot(&[
        "modes",
        "examples/foucault.qd",
        "--set",
        "m=1,g=9.81,l=1,W=1",
    ]);
    assert_eq!(stability_line(&out), "Stability of the equilibrium: stable");
    // l·W² = g: the excluded point is undecided, not unstable
    let (_, out, _) = qdot(&["modes", "examples/foucault.qd", "--set", "m=1,g=4,l=1,W=2"]);
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (a zero frequency: higher-order terms decide)"
    );
}

/// A·ω² = Ω·cos(lat)·(C·s + (C − A)·Ω·cos(lat)): factored in cos(lat)
/// (the canonical form writes cos² as 1 − sin²), Ω > 0 left out, and with
/// `assume cos(lat) > 0` that factor too.
#[test]
fn the_gyrocompass_condition_is_factored_and_uses_the_assumptions() {
    let (code, out, err) = qdot(&["modes", "examples/gyrocompass.qd"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (stable when A·Ω·cos(lat) < C·(Ω·cos(lat) + s); give values with --set)"
    );
    let src = std::fs::read_to_string("examples/gyrocompass.qd")
        .expect("the example")
        .replace(", cos(lat) > 0", "");
    let (out, _) = modes_on("gyrocompass", &src, &[]);
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (stable when cos(lat)·(Ω·(C − A)·cos(lat) + C·s) > 0; give values with --set)"
    );
    let (_, out, _) = qdot(&[
        "modes",
        "examples/gyrocompass.qd",
        "--set",
        "A=1,C=1.5,s=100,Omega=0.0000729,lat=0.8",
    ]);
    assert_eq!(stability_line(&out), "Stability of the equilibrium: stable");
}

/// A negative factor flips the inequality, a positive one is left out.
#[test]
fn a_condition_keeps_only_the_factors_of_undecided_sign() {
    // K = k·(a − b)·(a + b)/… : stable when b < a (a + b > 0 left out)
    let src = "coordinates x\nparameters m, k, a, b\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*(a^2 - b^2)*x^2\n";
    let (out, _) = modes_on("difference", src, &[]);
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (stable when b < a; give values with --set)"
    );
    let src = "coordinates x\nparameters m, k, a, b\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*(b - a)^3*x^2\n";
    let (out, _) = modes_on("cube", src, &[]);
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (stable when a < b; give values with --set)"
    );
}

/// (a − b)² + (c − d)² is a sum of squares: 0 only where both are.
#[test]
fn a_sum_of_squares_is_stable_unless_every_square_is_zero() {
    let src = "coordinates x\nparameters m, a, b, c, d\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*((a - b)^2 + (c - d)^2)*x^2\n";
    let (out, _) = modes_on("squares", src, &[]);
    assert_eq!(
        stability_line(&out),
        "Stability of the equilibrium: undecided (stable unless a = b and c = d, where the linearization does not decide)"
    );
}

// --------------------------------------------------- M, C, K as parameters

/// The sleeping top's axial moment C is in its gyroscopic matrix C: the
/// output reads C = [[0, C·Ω], [−C·Ω, 0]], a real clash.
#[test]
fn a_parameter_in_the_matrix_of_its_name_is_a_warning() {
    let (code, _, err) = qdot(&["modes", "examples/spinning_top.qd"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warning: the parameter `C` has the name of the damping matrix C of `modes`' output, and is in its entries"),
        "{err}"
    );
    assert_eq!(err.matches("warning").count(), 1, "{err}");
}

/// A top's mass M is in its mass matrix (A + M·l²) and its axial
/// moment C in the gyroscopic matrix when it spins: both warn; when it
/// does not spin, C is in no matrix and does not.
#[test]
fn a_top_warns_of_the_names_in_their_own_matrices() {
    let src = "\
coordinates a, b
parameters A, C, M, g, l, W
assume C < 2*A
frame B = rot(x, a) * rot(y, b) * rot(z, W*t)
body top: mass M, inertia [A, A, C], frame B, at l*axis(B, 3)
gravity [0, 0, -g]
";
    let (_, err) = modes_on("top", src, &[]);
    assert!(
        err.contains("the parameter `M` has the name of the mass matrix M"),
        "{err}"
    );
    assert!(
        err.contains("the parameter `C` has the name of the damping matrix C"),
        "{err}"
    );
    let (_, err) = modes_on("still", &src.replace("W*t", "0"), &[]);
    assert!(err.contains("parameter `M`"), "{err}");
    assert!(!err.contains("parameter `C`"), "{err}");
}

/// The gyrocompass's C is only in K (its C matrix is zero); a load's
/// amplitude K only in f(t): no warning.
#[test]
fn a_parameter_named_like_a_matrix_but_not_in_it_is_no_warning() {
    let (code, _, err) = qdot(&["modes", "examples/gyrocompass.qd"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning"), "{err}");
    let src = "coordinates x\nparameters m, k, K, p\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nforce x: K*cos(p*t)\n";
    let (out, err) = modes_on("load", src, &[]);
    assert!(out.contains("Forcing f(t)\n  x  K·cos(p·t)\n"), "{out}");
    assert!(!err.contains("warning"), "{err}");
}
