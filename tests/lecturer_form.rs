//! Conditions and mode shapes printed as a lecturer writes them: factors
//! of a known sign left out of a stability condition, one sum written as
//! `B < A` with positive terms on both sides, and a sign distributed into
//! a sum of mostly negative terms rather than pulled in front of it.

use std::path::Path;
use std::process::Command;

/// `qdot ARGS` run in the repository, its standard output.
fn qdot(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(Path::new(env!("QDOT_ROOT")))
        .output()
        .expect("qdot runs");
    assert!(out.status.success(), "{args:?}: {out:?}");
    String::from_utf8(out.stdout).expect("utf-8")
}

/// The lines of `text` that start (after indentation) with `prefix`.
fn lines_starting<'a>(text: &'a str, prefix: &str) -> Vec<&'a str> {
    text.lines()
        .map(str::trim_start)
        .filter(|l| l.starts_with(prefix))
        .collect()
}

#[test]
fn the_bead_on_a_rotating_hoop_is_stable_below_or_above_a_rate() {
    // K = m·R·(g − R·w²) at the bottom, m·(R²·w⁴ − g²)/w² off the axis:
    // m, R, w, g positive, R·w² + g > 0 left out
    let out = qdot(&["equilibrium", "examples/rotating_hoop.qd"]);
    assert_eq!(
        lines_starting(&out, "1. "),
        ["1. θ = 0  — undecided (stable when R·w² < g, unstable when R·w² > g; give values with --set)"]
    );
    assert_eq!(lines_starting(&out, "2. "), ["2. θ = π  — unstable"]);
    assert_eq!(
        lines_starting(&out, "3. "),
        ["3. θ = acos(g/(R·w²))  — undecided (stable when g < R·w², unstable when g > R·w²; give values with --set)"]
    );
}

#[test]
fn a_product_of_undecided_factors_stays_a_product() {
    // the gyrocompass off its meridian: three factors of unknown sign
    let out = qdot(&["equilibrium", "examples/gyrocompass.qd"]);
    assert_eq!(
        lines_starting(&out, "1. "),
        ["1. α = 0  — undecided (stable when A·Ω·cos(lat) < C·(Ω·cos(lat) + s), unstable when A·Ω·cos(lat) > C·(Ω·cos(lat) + s); give values with --set)"]
    );
    assert_eq!(
        lines_starting(&out, "3. "),
        ["3. α = π − acos(C·s/(Ω·cos(lat)·(C − A)))  — undecided (stable when (A − C)·(Ω·(A − C)·cos(lat) + C·s)·(Ω·(A − C)·cos(lat) − C·s) > 0, unstable when < 0; give values with --set)"]
    );
}

#[test]
fn the_double_pendulums_mode_shapes_distribute_the_sign_under_the_root() {
    let out = qdot(&["modes", "examples/double_pendulum.qd"]);
    let root = "√((2·l₁·l₂·m₂ + l₁²·m₁ + l₁²·m₂ + l₂²·m₁ + l₂²·m₂ − 2·l₁·l₂·m₁)·(m₁ + m₂))";
    // ω₁², ω₂² and their modes, the general solution
    assert!(out.matches(root).count() >= 5, "{out}");
    assert!(!out.contains("√(−"), "{out}");
    let mode = lines_starting(&out, "ω₁² = ");
    assert_eq!(mode.len(), 1, "{out}");
    assert!(
        mode[0].ends_with(&format!(
            "mode (1, (l₂·m₁ + l₂·m₂ + {root} − l₁·m₁ − l₁·m₂)/(2·l₂·m₂))"
        )),
        "{}",
        mode[0]
    );
}
