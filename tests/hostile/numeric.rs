//! Hostile inputs for the numeric answers: multiple roots (which the
//! numeric search reported several times, or missed), degenerate
//! equilibria (an inflection reported stable), and roots whose printed
//! digits were not certified.

use crate::bound::*;

fn equilibrium(tag: &str, potential: &str, set: &str) -> Outcome {
    let src = format!(
        "coordinates x\nparameters m, k, eps\nkinetic E = 1/2*m*x'^2\npotential V = {potential}\n"
    );
    let o = qdot_scene(tag, src.as_bytes(), "equilibrium", &["--set", set]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{tag}: {o:?}");
    o
}

fn equilibria_part(o: &Outcome) -> &str {
    let i = o.stdout.find("\nEquilibria").unwrap_or(0);
    &o.stdout[i + 1..]
}

/// Acceptance 4 of issue 14: V = k·(1 + x)ⁿ has one equilibrium, x = −1,
/// a root of multiplicity n − 1 of V' = 0, stable for n even (a minimum)
/// and unstable for n odd (an inflection).
#[test]
fn one_plus_x_to_the_n_has_one_equilibrium_with_its_multiplicity() {
    for n in (2..=12).chain([100]) {
        let o = equilibrium("power", &format!("k*(1+x)^{n}"), "k=1,m=1,eps=1");
        let word = if n % 2 == 0 { "stable" } else { "unstable" };
        let mut want = format!("Equilibria\n  1. x = −1  ≈ (−1.000000)  — {word}\n");
        if n > 2 {
            want.push_str(&format!(
                "     a root of multiplicity {} of the condition (V'' = 0 there; decided by the first derivative of V that is not 0)\n",
                n - 1
            ));
        }
        assert_eq!(equilibria_part(&o), want, "n = {n}");
        let j = qdot_scene(
            "power_json",
            format!("coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = k*(1+x)^{n}\n").as_bytes(),
            "equilibrium",
            &["--format", "json"],
        );
        let v: serde_json::Value = serde_json::from_str(&j.stdout).expect("json");
        assert_eq!(v["multiplicity"], serde_json::json!([n - 1]), "n = {n}");
        assert_eq!(v["stability"], serde_json::json!([word]), "n = {n}");
    }
}

/// V = k·(x² − 2)³: V' = 6k·x·(x² − 2)², so ±√2 are double roots of
/// V' = 0 where V''' ≠ 0: inflections, unstable; x = 0 is a minimum.
#[test]
fn x_squared_minus_two_cubed_has_unstable_inflections_at_root_two() {
    let o = equilibrium("inflection", "k*(x^2-2)^3", "k=1,m=1,eps=1");
    assert_eq!(
        equilibria_part(&o),
        "Equilibria\n  1. x = 0  ≈ (0.000000)  — stable\n  \
         2. x = −√2  ≈ (−1.414214)  — unstable\n     a root of multiplicity 2 of the condition (V'' = 0 there; decided by the first derivative of V that is not 0)\n  \
         3. x = √2  ≈ (1.414214)  — unstable\n     a root of multiplicity 2 of the condition (V'' = 0 there; decided by the first derivative of V that is not 0)\n"
    );
}

/// The root of x = cos x, and of k·x = ε·cos x with a tiny ε: only
/// certified digits are printed (the old output showed 0.0000000000, and
/// digits beyond the ones a double resolves).
#[test]
fn numeric_roots_print_only_certified_digits() {
    let o = equilibrium("cos", "k*(x^2/2 - sin(x))", "k=1,m=1,eps=1");
    let part = equilibria_part(&o);
    assert!(
        part.contains(
            "roots far from them may be missed; digits shown are certified by a sign change"
        ),
        "{part}"
    );
    let line = part
        .lines()
        .find(|l| l.starts_with("  1. x = "))
        .expect("a root");
    let digits = line["  1. x = ".len()..].split(' ').next().unwrap_or("");
    // every printed digit agrees with the root 0.73908513321516064165…
    assert!(digits.len() >= 12, "{line}");
    assert!("0.7390851332151606416553".starts_with(digits), "{line}");
    let o = equilibrium("tiny", "k*x^2/2 - eps*sin(x)", "k=1,m=1,eps=1e-12");
    let part = equilibria_part(&o);
    let line = part
        .lines()
        .find(|l| l.starts_with("  1. x = "))
        .expect("a root");
    let digits = line["  1. x = ".len()..].split(' ').next().unwrap_or("");
    // x = 1e-12·cos(x) = 0.99999999999999999999999950e-12
    assert!(digits.ends_with("e-12"), "{line}");
    let mantissa = digits.trim_end_matches("e-12");
    assert!(
        mantissa.len() >= 10 && "1.000000000000000".starts_with(mantissa),
        "{line}"
    );
}

/// Parameter values past the double range say so (they were "not a
/// number", and 1e-400 "0 is not positive").
#[test]
fn set_values_past_the_double_range_say_so() {
    let run = |v: &str| {
        let o = qdot_bounded(
            &[
                "modes",
                "examples/pendulum.qd",
                "--set",
                &format!("m=1,l=1,g={v}"),
            ],
            "",
            SECONDS,
            MEMORY_MIB,
        );
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{o:?}");
        o.stderr
    };
    assert!(run("1e400").starts_with(
        "error: `--set g=1e400`: `1e400` is beyond the range of double precision (about 1.8e308)\n"
    ));
    assert!(run("1e-400").starts_with(
        "error: `--set g=1e-400`: `1e-400` is below the smallest double (about 4.9e-324)\n"
    ));
    assert!(run("0").starts_with("error: `--set g=0`: parameters are positive, and 0 is not\n"));
    assert!(run("inf").starts_with("error: `--set g=inf`: `inf` is not a number\n"));
}

/// `modes --at` takes an equilibrium: a constant position.
#[test]
fn modes_at_a_moving_position_is_refused() {
    let o = qdot_bounded(
        &["modes", "examples/pendulum.qd", "--at", "theta=sin(t)"],
        "",
        SECONDS,
        MEMORY_MIB,
    );
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(o.stderr.starts_with("error: `--at theta=sin(t)`: an equilibrium is a constant position, and this changes with time\n"), "{o:?}");
}
