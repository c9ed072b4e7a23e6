//! Hostile inputs for the kinetic energy's definiteness (issue 33, item 2):
//! a kinetic energy that is negative, indefinite, singular or of a sign the
//! parameters leave open, where a stability verdict rests on M being
//! positive definite; and a body's inertia that no rigid body can have.

use crate::bound::*;

const NEGATIVE: &str =
    "coordinates x\nparameters m, k\nkinetic E = -1/2*m*x'^2\npotential V = 1/2*k*x^2\n";

/// Runs `command` on `src` and returns stdout, asserting a clean success.
fn ok(tag: &str, src: &str, command: &str, rest: &[&str]) -> String {
    let o = qdot_scene(tag, src.as_bytes(), command, rest);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    o.stdout
}

/// The line of `modes` that gives the verdict.
fn modes_verdict(tag: &str, src: &str, rest: &[&str]) -> String {
    let out = ok(tag, src, "modes", rest);
    out.lines()
        .find(|l| l.starts_with("Stability of the equilibrium: "))
        .unwrap_or_else(|| panic!("no verdict in {out}"))
        .to_string()
}

/// The verdict of the one equilibrium `equilibrium` finds.
fn equilibrium_verdict(tag: &str, src: &str, rest: &[&str]) -> String {
    let out = ok(tag, src, "equilibrium", rest);
    let line = out
        .lines()
        .find(|l| l.starts_with("  1. "))
        .unwrap_or_else(|| panic!("no equilibrium in {out}"));
    line.split_once("  — ").expect("a verdict").1.to_string()
}

/// ẍ = (k/m)·x grows: −L is an oscillator with a negative spring, so the
/// equilibrium is unstable (it was "stable" with ω² = −k/m), and with a
/// negative potential too the system of −L is a stable oscillator.
#[test]
fn a_negative_kinetic_energy_is_judged_as_the_system_of_minus_l() {
    assert_eq!(
        modes_verdict("negative", NEGATIVE, &[]),
        "Stability of the equilibrium: unstable"
    );
    assert_eq!(equilibrium_verdict("negative", NEGATIVE, &[]), "unstable");
    let json = ok("negative", NEGATIVE, "modes", &["--format", "json"]);
    assert!(
        json.contains("  \"stability\": \"unstable\",\n  \"stability_note\": null,\n"),
        "{json}"
    );
    let both = NEGATIVE.replace("V = 1/2*k*x^2", "V = -1/2*k*x^2");
    assert_eq!(
        modes_verdict("both_negative", &both, &[]),
        "Stability of the equilibrium: stable"
    );
    assert_eq!(equilibrium_verdict("both_negative", &both, &[]), "stable");
}

/// `assume e real` leaves the kinetic energy's sign open: undecided, with
/// the reason in the text and the JSON, until `--set` decides it
/// (e = −1: ẍ = k·x grows; e = 1: an oscillator).
#[test]
fn a_kinetic_energy_of_either_sign_is_undecided_until_set() {
    let src = "coordinates x\nparameters e, k\nassume e real\nkinetic E = 1/2*e*x'^2\npotential V = 1/2*k*x^2\n";
    let why = "the sign of the kinetic energy here depends on the parameters: the mass matrix's leading minor D1 = e has no decided sign; give values with --set";
    assert_eq!(
        modes_verdict("either", src, &[]),
        format!("Stability of the equilibrium: undecided ({why})")
    );
    assert_eq!(
        equilibrium_verdict("either", src, &[]),
        format!("undecided ({why})")
    );
    let json = ok("either", src, "modes", &["--format", "json"]);
    assert!(
        json.contains(&format!(
            "  \"stability\": \"undecided\",\n  \"stability_note\": \"{why}\",\n"
        )),
        "{json}"
    );
    let json = ok("either", src, "equilibrium", &["--format", "json"]);
    assert!(
        json.contains(&format!("\"notes\": [\n    \"{why}\"\n  ]")),
        "{json}"
    );
    for set in ["e=-1", "e=-1,k=1"] {
        assert_eq!(
            modes_verdict("either", src, &["--set", set]),
            "Stability of the equilibrium: unstable",
            "{set}"
        );
    }
    assert_eq!(
        equilibrium_verdict("either", src, &["--set", "e=-1,k=1"]),
        "unstable"
    );
    assert_eq!(
        modes_verdict("either", src, &["--set", "e=1,k=1"]),
        "Stability of the equilibrium: stable"
    );
    assert!(equilibrium_verdict("either", src, &["--set", "e=1,k=1"]).ends_with("stable"));
}

/// M = [[1, 2], [2, 1]] (eigenvalues 3 and −1) with K = k·E: ω² = k/3 and
/// −k, unstable (it was "stable"); M = diag(1, −1) with K = diag(k, −k)
/// only oscillates linearly, but an indefinite energy bounds nothing:
/// undecided, never stable; with K's off-diagonal 3/2 the roots of
/// det(K − λ·M) are complex: unstable.
#[test]
fn an_indefinite_mass_matrix_is_never_stable() {
    let coupled = "coordinates x, y\nparameters k\nkinetic E = 1/2*(x'^2 + 4*x'*y' + y'^2)\npotential V = 1/2*k*(x^2 + y^2)\n";
    assert_eq!(
        modes_verdict("coupled", coupled, &[]),
        "Stability of the equilibrium: unstable"
    );
    assert_eq!(equilibrium_verdict("coupled", coupled, &[]), "unstable");
    let opposite = "coordinates x, y\nparameters k\nkinetic E = 1/2*(x'^2 - y'^2)\npotential V = 1/2*k*(x^2 - y^2)\n";
    let why = "the kinetic energy is indefinite here (the mass matrix's leading minors D1 = 1 and D2 = −1): the linearization does not decide";
    assert_eq!(
        modes_verdict("opposite", opposite, &[]),
        format!("Stability of the equilibrium: undecided ({why})")
    );
    assert_eq!(
        modes_verdict("opposite", opposite, &["--set", "k=2"]),
        format!("Stability of the equilibrium: undecided ({why})")
    );
    assert_eq!(
        equilibrium_verdict("opposite", opposite, &[]),
        format!("undecided ({why})")
    );
    let complex =
        "coordinates x, y\nkinetic E = 1/2*(x'^2 - y'^2)\npotential V = 1/2*(x^2 + 3*x*y - y^2)\n";
    assert_eq!(
        modes_verdict("complex", complex, &[]),
        "Stability of the equilibrium: unstable"
    );
    assert_eq!(equilibrium_verdict("complex", complex, &[]), "unstable");
}

/// At θ = 0 the spherical pendulum's azimuth has no inertia (M singular):
/// det(K − λ·M) vanishes identically, and the verdict "stable" it gave
/// rested on nothing.
#[test]
fn a_singular_mass_matrix_gives_no_verdict() {
    let src = std::fs::read_to_string(concat!(
        env!("QDOT_ROOT"),
        "/examples/spherical_pendulum.qd"
    ))
    .expect("the example");
    assert_eq!(
        modes_verdict("singular", &src, &[]),
        "Stability of the equilibrium: undecided (the mass matrix is singular here (det M = 0: a direction without inertia, or coordinates singular here such as an azimuth at the pole): the linearization does not decide)"
    );
}

/// The error `derive` gives for a body with inertia `inertia`.
fn body_error(tag: &str, inertia: &str) -> (String, usize) {
    let line = format!("body b: mass m, inertia {inertia}, frame B, at [0, 0, l]");
    let src = format!("coordinates phi\nparameters A, C, m, l\nframe B = rot(z, phi)\n{line}\n");
    let o = qdot_scene(tag, src.as_bytes(), "derive", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    (o.stderr, line.find(inertia).expect("the inertia") + 1)
}

const HINT: &str = "  = hint: a rigid body's inertia is positive semidefinite and its principal moments satisfy the triangle inequality (each at most the sum of the other two; equal for a flat body)\n";

/// An inertia tensor with eigenvalues 3, −1, 1 (the simulation blew up)
/// is refused where it is written.
#[test]
fn an_indefinite_inertia_tensor_is_refused_where_written() {
    let inertia = "[[1, 2, 0], [2, 1, 0], [0, 0, 1]]";
    let (err, col) = body_error("indefinite_inertia", inertia);
    assert_eq!(
        err,
        format!(
            "error: an inertia matrix is positive semidefinite, and this one is not: its minor of rows 1, 2 is -3 < 0\n --> scene.qd:4:{col}\n  |\n4 | body b: mass m, inertia {inertia}, frame B, at [0, 0, l]\n  | {}{}\n{HINT}",
            " ".repeat(col - 1),
            "^".repeat(inertia.chars().count())
        )
    );
    // eigenvalues 7, 1, 1: positive definite, but 7 > 1 + 1
    let inertia = "[[4, 3, 0], [3, 4, 0], [0, 0, 1]]";
    let (err, col) = body_error("triangle_matrix", inertia);
    assert!(
        err.starts_with(&format!(
            "error: the principal moments of this inertia matrix violate the triangle inequality: tr(I)/2·E − I is not positive semidefinite (its minor of rows 1, 2 is -35/4 < 0)\n --> scene.qd:4:{col}\n"
        )),
        "{err}"
    );
}

/// [1, 1, 3] is no rigid body's (3 > 1 + 1): refused at the 3.
#[test]
fn principal_moments_violating_the_triangle_inequality_are_refused() {
    let (err, col) = body_error("triangle", "[1, 1, 3]");
    let col = col + "[1, 1, ".len();
    assert_eq!(
        err,
        format!(
            "error: the principal moments of inertia of `b` violate the triangle inequality: 3 > 1 + 1\n --> scene.qd:4:{col}\n  |\n4 | body b: mass m, inertia [1, 1, 3], frame B, at [0, 0, l]\n  | {}^\n{HINT}",
            " ".repeat(col - 1)
        )
    );
}

/// [A − C, A, C]: A − C may be negative; a warning says so (it passed in
/// silence), and `assume A > C` decides it.
#[test]
fn an_inertia_of_undecided_sign_is_a_warning() {
    let line = "body b: mass m, inertia [A - C, A, C], frame B, at [0, 0, l]";
    let src = format!("coordinates phi\nparameters A, C, m, l\nframe B = rot(z, phi)\n{line}\n");
    let o = qdot_scene("undecided_inertia", src.as_bytes(), "derive", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    let col = line.find("A - C").expect("the moment") + 1;
    assert_eq!(
        o.stderr,
        format!(
            "warning: qdot can't tell that the inertia of `b` is one a rigid body can have: A - C ≥ 0 is not decided\n --> scene.qd:4:{col}\n  |\n4 | {line}\n  | {}^^^^^\n{}; state it with `assume A - C > 0` or give numbers\n",
            " ".repeat(col - 1),
            HINT.trim_end()
        )
    );
    let assumed = src.replacen("frame B =", "assume A > C\nframe B =", 1);
    let o = qdot_scene("assumed_inertia", assumed.as_bytes(), "derive", &[]);
    o.assert_clean();
    assert_eq!((o.code, o.stderr.as_str()), (Some(0), ""), "{o:?}");
}

/// M = [[0, 1], [1, 1]], K = [[0, −1], [−1, 0]]: det(K − λ·M) = (1 + λ)²
/// with one mode only (an indefinite M allows a Jordan block). It was an
/// internal error; the frequencies are given without modes, unstable.
#[test]
fn a_defective_repeated_root_gives_the_frequencies_without_modes() {
    let src = "coordinates x1, x2\nkinetic E = 1/2*(x2'^2 + 2*x1'*x2')\npotential V = -x1*x2\n";
    let out = ok("defective", src, "modes", &[]);
    assert!(
        out.contains("\nNatural frequencies  (a repeated ω² has fewer modes than its multiplicity, the mass matrix not being definite; not given)\n  ω₁² = −1\n  ω₂² = −1\n\nStability of the equilibrium: unstable\n"),
        "{out}"
    );
}
