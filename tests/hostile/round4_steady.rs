//! The fourth hostile round (issue 46, items 13 and 14): Floquet's stops,
//! printed numbers and option lists; steady motions judged with the
//! values given, rate conditions quadratic in the rate, and the stability
//! of off-axis steady motions where they exist.

use crate::bound::*;

/// `qdot ARGS` from the repository root, no input, default bounds.
fn qdot(args: &[&str]) -> Outcome {
    qdot_bounded(args, "", SECONDS, MEMORY_MIB)
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

const MATHIEU: &str = "examples/mathieu.qd";

// ---- floquet: why an integration cannot cover the period ------------------

/// w = 1e-6: the period 2π/w ≈ 6.28e6 against a motion of rate ≈ 1 needs
/// more steps than the limit; refused at once, in words, in text and JSON.
#[test]
fn a_slow_modulation_is_refused_for_its_length_not_its_coefficients() {
    let set = "w=1e-6,m=1,delta=1,eps=0.1";
    let message = "the period T = 6.283185307179587e6 is too long to integrate: the linearized motion turns at rates up to 1.05 per unit time, so one period takes at least 6.6e6 steps, more than the 1,000,000 allowed";
    let hint = "the period is long against the motion's own time scale: raise --max-steps to at least 6.6e6 (the time grows in proportion), or choose parameter values with a shorter period";
    let o = qdot(&["floquet", MATHIEU, "--set", set]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(o.stderr, format!("error: {message}\n  = hint: {hint}\n"));
    let o = qdot(&["floquet", MATHIEU, "--set", set, "--output", "json"]);
    assert_eq!(o.code, Some(1), "{o:?}");
    let v = json(&o.stderr);
    assert_eq!(v["error"]["kind"], "integration", "{o:?}");
    assert_eq!(v["error"]["message"], message);
    assert_eq!(v["error"]["hint"], hint);
}

/// A run that reaches --max-steps says how much of the period it covered
/// and about how many steps the whole would take.
#[test]
fn a_run_that_reaches_the_step_limit_says_how_far_it_got() {
    let o = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "w=0.01,m=1,delta=1,eps=0.1",
        "--max-steps",
        "1000",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: the integration over the period T = 628.3185307179587 stopped at t = 358.3392: it took the most steps allowed (1,000) and had covered 57% of the period\n  = hint: the period is long against the motion's own time scale: raise --max-steps to about 1753 (the time grows in proportion), or choose parameter values with a shorter period\n"
    );
}

/// --period 1e308: refused with the reason, the number in scientific
/// notation (not 309 digits).
#[test]
fn an_absurd_period_is_refused_in_few_digits() {
    let o = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "w=1,m=1,delta=1,eps=0.1",
        "--period",
        "1e308",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: the period T = 1e308 is too long to integrate: the linearized motion turns at rates up to 0.951 per unit time, so one period takes at least 9.5e307 steps, more than the 1,000,000 allowed\n  = hint: the period is long against the motion's own time scale, beyond any integration (at least 9.5e307 steps): choose parameter values with a shorter period\n"
    );
}

/// Values of 1e12 in the table and the chart print as 1e12; the chart
/// names the first failure by parameter, not as a debug list.
#[test]
fn grid_values_print_in_scientific_notation_and_failures_by_name() {
    let o = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "m=1,eps=0.1,w=1",
        "--over",
        "delta=1e12:2e12:2",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    let rows: Vec<&str> = o.stdout.lines().skip(4).collect();
    assert!(
        rows[0].starts_with("delta  max |μ|  tr Φ(T)  ") && rows[0].ends_with("  verdict"),
        "{o:?}"
    );
    assert!(
        rows[1].starts_with(" 1e12        —        —  the period T = 6.283185307179586 is too long to integrate: the linearized motion turns at rates up to 1.00e6 per unit time"),
        "{o:?}"
    );
    assert!(rows[2].starts_with(" 2e12 "), "{o:?}");
    let o = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "m=1,w=1",
        "--over",
        "delta=1e12:2e12:2,eps=0:1e7:2",
    ]);
    o.assert_clean();
    assert!(
        o.stdout.contains(
            "  delta from 1e12 (left) to 2e12 (right); eps from 0 (bottom) to 1e7 (top)\n"
        ),
        "{o:?}"
    );
    assert!(
        o.stdout
            .contains("  first failure at delta = 1e12, eps = 0: the period T = "),
        "{o:?}"
    );
}

// ---- option lists: a name given twice --------------------------------------

/// `--keep a,a` is refused like `--steady q,q`, `--set a=1,a=2`, `--init`
/// and `--vary` given twice: the option, the name, a hint.
#[test]
fn a_name_given_twice_in_an_option_list_is_refused() {
    let src = b"coordinates x\nparameters m, k\nalpha = x^2\nkinetic T = m/2*x'^2\npotential V = k*alpha\n";
    let o = qdot_scene("keep_twice", src, "derive", &["--keep", "alpha,alpha"]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: `--keep`: `alpha` is named twice\n  = hint: name each definition to keep once\n"
    );
    let o = qdot(&[
        "modes",
        "examples/spherical_pendulum.qd",
        "--steady",
        "phi,phi",
    ]);
    assert_eq!(
        o.stderr,
        "error: `--steady`: `phi` is named twice\n  = hint: name each steady coordinate once\n"
    );
    let o = qdot(&[
        "simulate",
        "examples/pendulum.qd",
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "theta=1,theta=2",
        "--t-end",
        "1",
    ]);
    assert_eq!(
        o.stderr,
        "error: `--init`: `theta` is given twice\n  = hint: give each position and velocity one value\n"
    );
    let o = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "m=1,w=1",
        "--over",
        "delta=0:1:2,delta=0:1:2",
    ]);
    assert_eq!(
        o.stderr,
        "error: `--over delta`: `delta` is varied twice\n  = hint: vary each parameter once\n"
    );
    let o = qdot(&["equilibrium", "examples/pendulum.qd", "--set", "m=1,m=2"]);
    assert_eq!(
        o.stderr,
        "error: `--set`: `m` is given twice\n  = hint: give each parameter one value\n"
    );
}

// ---- steady motions ---------------------------------------------------------

const HOOP: &str = "tests/data/steady/spinning_hoop.qd";
const PORTER: &str = "tests/data/steady/porter_governor.qd";
const MAGNETIC: &str = "tests/data/steady/magnetic_orbit.qd";
const ELASTIC: &str = "tests/data/steady/elastic_spherical.qd";

/// A hoop turning freely: off the axis the bead's steady motion is stable
/// wherever it exists (Routh's reduced stiffness m·R²·φ̇²·sin²θ·(I +
/// m·R²·(1 + 3·cos²θ))/(I + m·R²·sin²θ) > 0); at the bottom a condition on
/// φ̇ that names `modes --at`, not `--set`.
#[test]
fn a_spinning_hoop_is_stable_off_the_axis() {
    let o = qdot(&["equilibrium", HOOP, "--steady", "phi"]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert_eq!(
        o.stdout,
        "Steady motions  φ̇ = const, the other coordinates at rest
Conditions (each coordinate's equation there)
  θ:  m·R²·cos(θ)·sin(θ)·φ̇² − g·m·R·sin(θ) = 0

Steady motions (stability about each: `qdot modes --steady`)
  1. θ = 0  — undecided (stable when R·φ̇² < g; at one rate: qdot modes --steady phi --at \"theta=…,phi'=…\")
  2. θ = π  — unstable
  3. θ = acos(g/(R·φ̇²))  — stable
     exists when |g/(R·φ̇²)| ≤ 1
  4. θ = −acos(g/(R·φ̇²))  — stable
     exists when |g/(R·φ̇²)| ≤ 1
"
    );
    assert!(!o.stdout.contains("--set"), "{o:?}");
    // one rate: ω² = 525/124 at m = R = g = I = 1, φ̇ = 2 (cos θ = 1/4)
    let o = qdot(&[
        "modes",
        HOOP,
        "--steady",
        "phi",
        "--at",
        "theta=acos(g/(4*R)),phi'=2",
    ]);
    assert!(
        o.stdout.contains(
            "  ω₁² = (3·g²·m + 16·m·R² + 16·I)·(4·R + g)·(4·R − g)/(4·R²·(16·m·R² + 16·I − g²·m))    mode (1)\n"
        ),
        "{o:?}"
    );
}

/// Porter's governor: the off-axis steady motions stable where they exist
/// (reduced stiffness 2·m·l²·φ̇²·(sin²θ + 4·cos²θ) > 0, M positive).
#[test]
fn a_porter_governor_is_stable_off_the_axis() {
    let o = qdot(&["equilibrium", PORTER, "--steady", "phi", "--format", "json"]);
    o.assert_clean();
    let v = json(&o.stdout);
    assert_eq!(v["equilibria"][2]["theta"], "acos(g*(M0 + m)/(l*m*phi'^2))");
    assert_eq!(v["stability"][2], "stable", "{o:?}");
    assert_eq!(v["stability"][3], "stable", "{o:?}");
    let o = qdot(&["equilibrium", PORTER, "--steady", "phi"]);
    assert!(
        o.stdout
            .contains("  3. θ = acos(g·(M₀ + m)/(l·m·φ̇²))  — stable\n     exists when |g·(M₀ + m)/(l·m·φ̇²)| ≤ 1\n"),
        "{o:?}"
    );
}

/// m·φ̇² + e·B·φ̇ = k: both roots, exactly; the analysis about the first
/// (ω² = (e²B² + 4km)/m², from Routh's V_eff = (p − eBr²/2)²/(2mr²) +
/// kr²/2), the second through --at.
#[test]
fn a_rate_condition_quadratic_in_the_rate_gives_both_roots() {
    let o = qdot(&["modes", MAGNETIC, "--steady", "phi", "--at", "r=r0"]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    let head: Vec<&str> = o.stdout.lines().take(3).collect();
    assert_eq!(
        head,
        [
            "Steady motion  φ̇ = const, r = r₀",
            "  the equation of r there: m·r₀·φ̇² + B·e·r₀·φ̇ − k·r₀ = 0",
            "  so φ̇ = (√(B²·e² + 4·k·m) − B·e)/(2·m) or φ̇ = −(B·e + √(B²·e² + 4·k·m))/(2·m); below about the first (for another, add phi'=… to --at)",
        ]
    );
    assert!(
        o.stdout.contains("  ω₁² = B²·e²/m² + 4·k/m    mode (1)\n"),
        "{o:?}"
    );
    assert!(
        o.stdout
            .ends_with("Stability of the steady motion: stable\n"),
        "{o:?}"
    );
    let o = qdot(&[
        "modes", MAGNETIC, "--steady", "phi", "--at", "r=r0", "--format", "json",
    ]);
    let v = json(&o.stdout);
    let solved = &v["steady_motion"]["solved"][0];
    assert_eq!(solved["squared"], false);
    assert_eq!(solved["value"], "(sqrt(B^2*e^2 + 4*k*m) - B*e)/(2*m)");
    assert_eq!(solved["others"][0], "-(B*e + sqrt(B^2*e^2 + 4*k*m))/(2*m)");
    let o = qdot(&[
        "modes",
        MAGNETIC,
        "--at",
        "r=r0,phi'=-(B*e + sqrt(B^2*e^2 + 4*k*m))/(2*m)",
    ]);
    o.assert_clean();
    assert!(
        o.stdout.contains("  ω₁² = B²·e²/m² + 4·k/m    mode (1)\n"),
        "{o:?}"
    );
}

/// A condition cubic in the rate is refused with its degree.
#[test]
fn a_rate_condition_of_degree_three_is_refused_with_its_degree() {
    let o = qdot(&[
        "modes",
        "tests/data/steady/cubic_rate.qd",
        "--steady",
        "phi",
        "--at",
        "r=1",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.starts_with("error: the steady motion needs 2·φ̇³ + φ̇² − 1 = 0 (the equation of `r`), of degree 3 in the rate: qdot solves a rate's condition of degree two at most\n"),
        "{o:?}"
    );
}

/// The elastic spherical pendulum at r = 5/3, θ = π/3: the conditions leave
/// 5k − 6gm − 3kl₀ = 0 on the parameters. At --set values where it holds
/// the steady motion is analysed, its ω² those of the scene with the
/// numbers written in (39/10 ∓ 9·√7/10); elsewhere refused with the value.
#[test]
fn a_condition_on_the_parameters_is_judged_at_the_set_values() {
    let at = ["--steady", "phi", "--at", "r=5/3,theta=pi/3"];
    let mut args = vec!["modes", ELASTIC];
    args.extend(at);
    args.extend(["--set", "m=1,g=1,k=3,l0=1"]);
    let o = qdot(&args);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(
        o.stdout.contains("  the equation of θ there: 5/27·√3·(5·k − 6·g·m − 3·k·l₀) = 0, which holds at the --set values\n"),
        "{o:?}"
    );
    assert!(
        o.stdout
            .contains("  numeric ω² (eigen-solver): 1.5188238200, 6.2811761800\n"),
        "{o:?}"
    );
    assert!(
        o.stdout
            .ends_with("Stability of the steady motion: stable\n"),
        "{o:?}"
    );
    let mut args = vec!["modes", "tests/data/steady/elastic_spherical_numbers.qd"];
    args.extend(at);
    let o = qdot(&args);
    assert!(
        o.stdout.contains("  ω₁² = 39/10 − 9/10·√7    mode")
            && o.stdout.contains("  ω₂² = 9/10·√7 + 39/10    mode"),
        "{o:?}"
    );
    // 39/10 ∓ 9·√7/10 to the ten decimals printed above
    let r7 = 7f64.sqrt();
    assert_eq!(format!("{:.10}", 3.9 - 0.9 * r7), "1.5188238200");
    assert_eq!(format!("{:.10}", 3.9 + 0.9 * r7), "6.2811761800");
    let mut args = vec!["modes", ELASTIC];
    args.extend(at);
    args.extend(["--set", "m=1,g=1,k=3,l0=1.5"]);
    let o = qdot(&args);
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: no steady motion at the --set values: the equation of `theta` needs 5/27·√3·(5·k − 6·g·m − 3·k·l₀) = 0, and there it is −5/6·√3\n  = hint: give values on which the condition holds, or the position that suits them (--at)\n"
    );
    let mut args = vec!["modes", ELASTIC];
    args.extend(at);
    let o = qdot(&args);
    assert_eq!(
        o.stderr,
        "error: the steady motion needs 5/27·√3·(5·k − 6·g·m − 3·k·l₀) = 0 (the equation of `theta`), which holds no rate: a condition on the parameters and the position\n  = hint: give the parameters values on which it holds (--set), or the position that suits them (--at)\n"
    );
}

/// About a steady motion at a symbolic position, --set cannot give θ₀:
/// the hint says where it comes from.
#[test]
fn a_symbol_set_cannot_give_is_named_with_its_option() {
    let o = qdot(&[
        "modes",
        "examples/spherical_pendulum.qd",
        "--steady",
        "phi",
        "--at",
        "theta=theta0",
    ]);
    o.assert_clean();
    assert!(
        o.stdout.ends_with("Stability of the steady motion: undecided (stable when cos(θ₀) > 0; give θ₀ a value with --at and the parameters with --set)\n"),
        "{o:?}"
    );
}
