//! The third hostile round (issue 33): answers that were silently wrong
//! and refusals that gave the wrong reason. By class:
//! * time dependence through a given function of time (`integrals`);
//! * what the JSON says beside the text (certified digits, caveats);
//! * a `--stop-when` sign change that is not a zero (a pole);
//! * a mode of zero frequency (a drift, not an oscillation);
//! * option values that contradict the scene or each other (`--set`
//!   against `assume`, `--vary` twice, `--samples 0`, `--threads`);
//! * generated C that would not compile (names that are macros);
//! * refusals with the right reason (contradictory constraints, a
//!   hidden-zero coefficient, NaN against ∞, the zero axis, the REPL).

use crate::bound::*;

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("{}/examples/{name}.qd", env!("QDOT_ROOT")))
        .expect("the example")
}

/// `qdot ARGS` from the repository root, no input, default bounds.
fn qdot(args: &[&str]) -> Outcome {
    qdot_bounded(args, "", SECONDS, MEMORY_MIB)
}

fn json(o: &Outcome) -> serde_json::Value {
    serde_json::from_str(&o.stdout).unwrap_or_else(|e| panic!("{e}: {o:?}"))
}

// ---- time dependence through a given function ----------------------------

/// E = ½m·(ẋ + ṡ)² with s(t) given: L depends on t through s, and h is
/// not conserved (dh/dt = −∂L/∂t): no energy integral, in every format.
#[test]
fn a_given_function_of_time_has_no_energy_integral() {
    let o = qdot(&["integrals", "examples/moving_support.qd"]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(
        o.stdout
            .contains("Energy integral  h = Σ q̇·∂L/∂q̇ − L\n  none\n"),
        "{o:?}"
    );
    assert!(
        o.stdout.contains(
            "  L depends on t through the given function s: no energy integral (dh/dt = −∂L/∂t)\n"
        ),
        "{o:?}"
    );
    let j = qdot(&[
        "integrals",
        "examples/moving_support.qd",
        "--format",
        "json",
    ]);
    let v = json(&j);
    assert_eq!(v["energy"], serde_json::Value::Null, "{j:?}");
    assert_eq!(
        v["notes"][0],
        "L depends on t through the given function s: no energy integral (dh/dt = −∂L/∂t)"
    );
    // the same decision for a support written inline in the energy
    let src = "coordinates x\nparameters m\nfunctions s\nkinetic E = 1/2*m*x'^2 + m*s'*x'\n";
    let o = qdot_scene("given_inline", src.as_bytes(), "integrals", &[]);
    assert!(o.stdout.contains("  none\n"), "{o:?}");
    // and simulate has no energy column for it
    let o = qdot(&[
        "simulate",
        "examples/moving_support.qd",
        "--set",
        "m=1,l=1,g=1",
        "--init",
        "theta=0.1,theta'=0",
        "--function",
        "s=t^2",
        "--t-end",
        "1",
        "--points",
        "2",
    ]);
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.starts_with("t,theta,theta'\n"), "{o:?}");
}

/// x' = y has b = −y ≠ 0: its reaction does work (power −λ·b), though
/// nothing in it moves with t.
#[test]
fn a_velocity_constraint_with_a_rest_term_does_work_and_does_not_move() {
    let src =
        "coordinates x, y\nparameters m\nkinetic E = 1/2*m*(x'^2 + y'^2)\nconstraint c: x' = y\n";
    let o = qdot_scene("rest_term", src.as_bytes(), "integrals", &[]);
    o.assert_clean();
    assert!(
        o.stdout.contains(
            "  the constraint `c` is not homogeneous in the velocities (b = −y in a·q̇ + b = 0): its reaction does work: no energy integral\n"
        ),
        "{o:?}"
    );
}

// ---- what the JSON says ---------------------------------------------------

/// x = cos x with k = 1e-320: the text prints the certified `0.739`; the
/// JSON carries the same digits, that they are certified and the
/// enclosing sign change, and the search's caveat.
#[test]
fn json_carries_the_certified_digits_and_the_caveat() {
    let src =
        "coordinates x\nparameters k\npotential V = k*(x^2/2 - sin(x))\nkinetic E = 1/2*x'^2\n";
    let t = qdot_scene(
        "cosx",
        src.as_bytes(),
        "equilibrium",
        &["--set", "k=1e-320"],
    );
    assert!(t.stdout.contains("  1. x = 0.739  — stable\n"), "{t:?}");
    let o = qdot_scene(
        "cosx",
        src.as_bytes(),
        "equilibrium",
        &["--set", "k=1e-320", "--format", "json"],
    );
    o.assert_clean();
    let v = json(&o);
    assert_eq!(v["digits"], serde_json::json!([["0.739"]]));
    assert_eq!(v["certified"], serde_json::json!([true]));
    let (lo, hi) = (
        v["enclosure"][0]["x"][0].as_f64().expect("lo"),
        v["enclosure"][0]["x"][1].as_f64().expect("hi"),
    );
    let root = 0.739_085_133_215_160_6;
    assert!(lo < root && root < hi && hi - lo < 1e-3, "{lo} {hi}");
    assert_eq!(v["complete"], false);
    assert_eq!(
        v["caveat"],
        "found by Newton's method from many starting points: roots far from them may be missed; digits shown are certified by a sign change"
    );
}

/// V = k·x²·sin(1/x): infinitely many equilibria near 0, five found. The
/// text says the search may miss roots; so must the JSON.
#[test]
fn json_says_a_numeric_search_may_be_incomplete() {
    let src = "coordinates x\nparameters k\npotential V = k*x^2*sin(1/x)\nkinetic E = 1/2*x'^2\n";
    let o = qdot_scene(
        "sin_inv",
        src.as_bytes(),
        "equilibrium",
        &["--set", "k=1", "--format", "json"],
    );
    o.assert_clean();
    let v = json(&o);
    assert_eq!(v["complete"], false, "{o:?}");
    assert!(v["caveat"]
        .as_str()
        .is_some_and(|c| c.contains("roots far from them may be missed")));
    let n = v["equilibria"].as_array().map_or(0, Vec::len);
    assert!(n > 0);
    assert_eq!(v["certified"].as_array().map(Vec::len), Some(n));
    // a closed form is complete, with no digits to certify
    let o = qdot(&["equilibrium", "examples/seed_22_3.qd", "--format", "json"]);
    let v = json(&o);
    assert_eq!(v["complete"], true);
    assert_eq!(v["caveat"], serde_json::Value::Null);
    assert!(v["digits"]
        .as_array()
        .is_some_and(|d| d.iter().all(serde_json::Value::is_null)));
}

// ---- --stop-when through a pole -------------------------------------------

fn pendulum(extra: &[&str]) -> Outcome {
    let mut args = vec![
        "simulate",
        "examples/pendulum.qd",
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "theta=1,theta'=0",
        "--t-end",
        "3",
        "--points",
        "3",
    ];
    args.extend_from_slice(extra);
    qdot(&args)
}

/// 1/(θ − ½) changes sign where θ = ½, through a pole: not a zero, so not
/// an event. The run goes on to t_end and says so; θ − ½ = 0 at the same
/// time is an event.
#[test]
fn a_sign_change_through_a_pole_is_not_an_event() {
    let o = pendulum(&["--stop-when", "1/(theta-0.5) = 0"]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert_eq!(o.stdout.lines().count(), 4, "the run reaches t = 3: {o:?}");
    assert!(
        o.stderr.starts_with(
            "warning: the --stop-when condition changed sign at t = 1.126844e0 without passing through zero (a pole or a jump): not an event, the run went on\n"
        ),
        "{o:?}"
    );
    assert!(!o.stderr.contains("stopped at"), "{o:?}");
    let j = pendulum(&["--stop-when", "1/(theta-0.5) = 0", "--output", "json"]);
    let v = json(&j);
    assert_eq!(v["status"], "done");
    assert_eq!(v["event_t"], serde_json::Value::Null);
    let t = v["event_poles"][0].as_f64().expect("one pole");
    assert!((t - 1.126_844_213_346_94).abs() < 1e-9, "{t}");
    // the zero at the same place is an event
    let o = pendulum(&["--stop-when", "theta - 0.5 = 0"]);
    assert!(
        o.stderr.contains(
            "stopped at t = 1.126844213346943e0, where the --stop-when condition changes sign"
        ),
        "{o:?}"
    );
}

// ---- a zero frequency -----------------------------------------------------

/// Two masses joined by a spring: ω₁ = 0 is a drift A₁ + B₁·t, not
/// C₁·cos(0·t + φ₁); a negative ω² a growth, not a cosine.
#[test]
fn a_mode_of_zero_or_negative_omega_squared_does_not_oscillate() {
    let src = "coordinates x, y\nparameters m, k\nkinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = 1/2*k*(x - y)^2\n";
    let o = qdot_scene("free_pair", src.as_bytes(), "modes", &[]);
    o.assert_clean();
    assert!(
        o.stdout.contains(
            "General solution (undamped)  q(t) = Σ Cᵢ·uᵢ·cos(ωᵢ·t + φᵢ), and (Aᵢ + Bᵢ·t)·uᵢ where ωᵢ = 0\n  x = A₁ + B₁·t + C₂·cos(ω₂·t + φ₂)\n  y = A₁ + B₁·t − C₂·cos(ω₂·t + φ₂)\n"
        ),
        "{o:?}"
    );
    // ω² = −k/m: the mode grows, it does not oscillate
    let src = "coordinates x, y\nparameters m, k\nkinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = 1/2*k*x^2 - 1/2*k*y^2\n";
    let o = qdot_scene("saddle", src.as_bytes(), "modes", &[]);
    o.assert_clean();
    assert!(
        o.stdout.contains(
            "General solution (undamped)  q(t) = Σ Cᵢ·uᵢ·cos(ωᵢ·t + φᵢ), and (Aᵢ·e^(κᵢ·t) + Bᵢ·e^(−κᵢ·t))·uᵢ with κᵢ² = −ωᵢ² where ωᵢ² < 0\n  x = C₂·cos(ω₂·t + φ₂)\n  y = A₁·e^(κ₁·t) + B₁·e^(−κ₁·t)\n"
        ),
        "{o:?}"
    );
}

// ---- options that contradict the scene or each other ----------------------

/// `assume R > r` and `--set R=1,r=2`: the values break the fact the
/// scene's results rely on; refused, as a negative value of a positive
/// parameter is.
#[test]
fn set_values_that_break_an_assumption_are_refused() {
    for (cmd, set, shown) in [
        ("modes", "R=1,r=2,m=1,g=1", "it is -1 there"),
        ("equilibrium", "R=1,r=1", "it is 0 there"),
    ] {
        let o = qdot(&[cmd, "examples/disk_in_cylinder.qd", "--set", set]);
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{o:?}");
        let pair = if set.starts_with("R=1,r=2") {
            "R=1,r=2"
        } else {
            "R=1,r=1"
        };
        assert_eq!(
            o.stderr,
            format!("error: `--set {pair}` breaks the scene's assumption R − r > 0: {shown}\n  = hint: give values that keep every `assume` fact, or change the fact\n"),
            "{cmd}"
        );
    }
    // values that keep it, and values that leave it open, pass
    let o = qdot(&[
        "modes",
        "examples/disk_in_cylinder.qd",
        "--set",
        "R=2,r=1,m=1,g=1",
    ]);
    assert_eq!(o.code, Some(0), "{o:?}");
    let o = qdot(&[
        "equilibrium",
        "examples/disk_in_cylinder.qd",
        "--set",
        "m=1",
    ]);
    assert_eq!(o.code, Some(0), "{o:?}");
}

fn sweep(extra: &[&str]) -> Outcome {
    let mut args = vec!["sweep", "examples/pendulum.qd", "--t-end", "1"];
    args.extend_from_slice(extra);
    qdot(&args)
}

/// A column named twice would mislabel every row: a varied name is given
/// by its `--vary` alone.
#[test]
fn a_name_varied_twice_or_also_set_is_refused() {
    let hint = "  = hint: vary each name once, and leave it out of --set and --init\n";
    for (set, init, vary2, why) in [
        (
            "m=1,g=1",
            "theta=1,theta'=0",
            "l=1:2:3",
            "`l` is varied twice",
        ),
        (
            "m=1,g=1,l=1",
            "theta=1,theta'=0",
            "",
            "`l` is also given by --set",
        ),
    ] {
        let mut args = vec!["--set", set, "--init", init, "--vary", "l=1:2:3"];
        if !vary2.is_empty() {
            args.extend(["--vary", vary2]);
        }
        let o = sweep(&args);
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{o:?}");
        assert_eq!(o.stderr, format!("error: `--vary l`: {why}\n{hint}"));
    }
    let o = sweep(&[
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "theta=1,theta'=0",
        "--vary",
        "theta=0:1:2",
    ]);
    assert_eq!(
        o.stderr,
        format!("error: `--vary theta`: `theta` is also given by --init\n{hint}")
    );
}

#[test]
fn sweep_options_are_checked_before_any_run() {
    let o = sweep(&[
        "--set",
        "m=1,g=1",
        "--init",
        "theta'=0",
        "--vary",
        "l=1:2",
        "--vary",
        "theta=0:1",
        "--samples",
        "0",
    ]);
    o.assert_clean();
    assert_eq!(
        o.stderr,
        "error: `--samples 0`: a random design needs at least one run\n  = hint: --samples 100 draws 100 random points in the box of the --vary ranges\n"
    );
    // an event that names nothing is one error, not one per row
    let o = sweep(&[
        "--set",
        "m=1,g=1",
        "--init",
        "theta=1,theta'=0",
        "--vary",
        "l=1:2:3",
        "--stop-when",
        "zzz=0",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(o.stdout.is_empty(), "{o:?}");
    assert!(
        o.stderr
            .starts_with("error: `--stop-when zzz=0`: unknown name `zzz`\n"),
        "{o:?}"
    );
}

/// `--threads 100000` on 3 runs: as many threads as runs at most, and no
/// more than the cores; done at once.
#[test]
fn sweep_threads_are_capped_by_cores_and_runs() {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let o = qdot_bounded(
        &[
            "sweep",
            "examples/pendulum.qd",
            "--set",
            "m=1,g=1",
            "--init",
            "theta=1,theta'=0",
            "--vary",
            "l=1:2:3",
            "--t-end",
            "1",
            "--threads",
            "100000",
            "--stats",
        ],
        "",
        SECONDS,
        512,
    );
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    let threads = cores.min(3);
    assert!(
        o.stderr
            .starts_with(&format!("3 runs on {threads} threads in ")),
        "{o:?}"
    );
}

/// Without a terminal a long sweep says how far it has come.
#[test]
fn a_sweep_without_a_terminal_logs_its_progress() {
    let o = sweep(&[
        "--set",
        "m=1,g=1",
        "--init",
        "theta'=0",
        "--vary",
        "l=1:2:40",
        "--vary",
        "theta=0.1:3:40",
        "--threads",
        "1",
        "--points",
        "2000",
        "--log-every",
        "0",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    let first = o.stderr.lines().next().unwrap_or("");
    assert!(
        first.starts_with("sweep: ") && first.contains(" of 1,600 runs done in "),
        "{o:?}"
    );
}

// ---- generated C ----------------------------------------------------------

/// Parameters named like the macros of <math.h> and GCC (the Earth's mass
/// `M_E`) get names of their own; the C compiles with gcc's default
/// dialect, where they are defined.
#[test]
fn c_names_that_are_macros_are_renamed() {
    let names = "M_E, M_PI, unix, linux, FP_NAN, FP_ZERO, MATH_ERRNO, math_errhandling, M_SQRT2";
    let src = format!(
        "coordinates x\nparameters {names}\nkinetic E = 1/2*M_E*x'^2\npotential V = 1/2*({})*x^2\n",
        names.replace(", ", " + ")
    );
    let o = qdot_scene("macros", src.as_bytes(), "codegen", &["--lang", "c"]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    for n in names.split(", ") {
        assert!(o.stdout.contains(&format!("{n} (v_{n})")), "{n}: {o:?}");
        assert!(!o.stdout.contains(&format!("double {n},")), "{n}");
    }
    let dir = std::env::temp_dir().join(format!("qdot-macros-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a directory");
    std::fs::write(dir.join("gen.c"), &o.stdout).expect("written");
    let gcc = std::process::Command::new("gcc")
        .args(["-c", "-O1", "-Wall", "-Werror", "gen.c", "-o", "gen.o"])
        .current_dir(&dir)
        .output()
        .expect("gcc runs (the machine ships it)");
    assert!(
        gcc.status.success(),
        "{}",
        String::from_utf8_lossy(&gcc.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

// ---- refusals with the right reason ----------------------------------------

#[test]
fn contradictory_constraints_are_said_to_contradict() {
    let base = "coordinates x, y\nparameters m, l, k\nkinetic E = 1/2*m*(x'^2 + y'^2)\n";
    for (pair, want) in [
        (
            "constraint a: x = y\nconstraint b: x = y + l\n",
            "error: the constraints `a`, `b` contradict each other: they differ by l, which is not 0\n  = hint: no motion satisfies both; correct one of them\n",
        ),
        (
            "constraint a: x = y\nconstraint b: 2*x = 2*y\n",
            "error: the constraints `a`, `b` are redundant: one follows from the others, so their multipliers are not determined\n  = hint: remove the constraint that the others imply\n",
        ),
        (
            "constraint a: x = y + k\nconstraint b: x = y + l\n",
            "error: the constraints `a`, `b` are dependent: they agree only where l − k = 0 (redundant then, contradictory otherwise), so their multipliers are not determined\n  = hint: keep one of them, or correct the one that contradicts the other\n",
        ),
    ] {
        let src = format!("{base}{pair}");
        let o = qdot_scene("contradict", src.as_bytes(), "solve", &[]);
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{o:?}");
        assert_eq!(o.stderr, want);
    }
}

/// (sin a − 2·sin(a/2)·cos(a/2))·x = 1 is 0 = 1: the constraint involves
/// no coordinate (it used to be read as x lacking inertia).
#[test]
fn a_constraint_whose_coefficient_is_a_hidden_zero_involves_no_coordinate() {
    let src = "coordinates x, y\nparameters m, a\nkinetic E = 1/2*m*y'^2\nconstraint c: (sin(a) - 2*sin(a/2)*cos(a/2))*x = 1\n";
    let o = qdot_scene("hidden_zero_constraint", src.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.starts_with(
            "error: constraint `c` involves no coordinate: its coefficient sin(a) − 2·cos(1/2·a)·sin(1/2·a) is 0\n --> scene.qd:4:15\n"
        ),
        "{o:?}"
    );
}

/// V = √x from x < 0: q̈ is NaN (√ outside its domain), not a value out of
/// the double range.
#[test]
fn nan_and_infinity_are_told_apart() {
    let src = "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2\npotential V = sqrt(x)\n";
    let o = qdot_scene(
        "sqrt_negative",
        src.as_bytes(),
        "simulate",
        &[
            "--set",
            "m=1",
            "--init",
            "x=1,x'=-3",
            "--t-end",
            "3",
            "--points",
            "3",
        ],
    );
    o.assert_clean();
    assert_eq!(o.code, Some(3), "{o:?}");
    assert!(
        o.stderr.contains(
            "  = hint: q̈ was NaN or infinite within the step after the last row: a function outside its domain (√ or ln of a negative number, asin or acos past ±1), 0/0, ∞·0 or ∞ − ∞, or a division by zero, or a value out of the double range\n"
        ),
        "{o:?}"
    );
    let o = qdot_scene(
        "sqrt_negative",
        src.as_bytes(),
        "simulate",
        &[
            "--set",
            "m=1",
            "--init",
            "x=-1,x'=0",
            "--t-end",
            "1",
            "--points",
            "3",
        ],
    );
    assert!(
        o.stderr
            .contains("  = hint: `energy` is NaN there: a function outside its domain"),
        "{o:?}"
    );
}

/// In the REPL, `:solve` after a line ending in `+` is a command of its
/// own: the unfinished entry is refused alone, then the command runs.
#[test]
fn a_repl_command_never_continues_an_unfinished_entry() {
    let input = "coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2 +\n:solve\n";
    let o = qdot_bounded(&["repl"], input, SECONDS, MEMORY_MIB);
    o.assert_clean();
    assert!(
        o.stderr.starts_with(
            "error: expected an expression after `+`, but the file ends\n --> stdin:3:24\n"
        ),
        "{o:?}"
    );
    assert!(
        o.stderr
            .contains("error: the scene has no kinetic energy\n"),
        "the entry was refused, and :solve ran on the scene without it: {o:?}"
    );
    assert!(!o.stderr.contains(":solve"), "{o:?}");
}

#[test]
fn the_examples_still_have_their_energy_integral() {
    // the shared decision still finds h where it is conserved
    for name in ["pendulum", "double_pendulum", "spinning_top"] {
        let src = example(name);
        let o = qdot_scene(name, src.as_bytes(), "integrals", &[]);
        o.assert_clean();
        assert!(
            o.stdout
                .contains("Energy integral  h = Σ q̇·∂L/∂q̇ − L\n  h = "),
            "{name}: {o:?}"
        );
    }
}

/// `--set` values where M is not positive definite: the eigen-solver's
/// refusal is said (text and JSON), not a silently missing section.
#[test]
fn numeric_modes_refused_by_the_values_say_why() {
    let src = "coordinates x, y\nparameters e, k\nassume e real\nkinetic E = 1/2*e*x'^2 + 1/2*y'^2\npotential V = 1/2*k*(x^2 + y^2)\n";
    let why = "M is not positive definite (Cholesky factorization failed)";
    let o = qdot_scene(
        "numeric_modes_why",
        src.as_bytes(),
        "modes",
        &["--set", "e=-1,k=1"],
    );
    o.assert_clean();
    assert!(
        o.stdout
            .contains(&format!("  numeric ω²: none at these values: {why}\n")),
        "{o:?}"
    );
    let o = qdot_scene(
        "numeric_modes_why",
        src.as_bytes(),
        "modes",
        &["--set", "e=-1,k=1", "--format", "json"],
    );
    let v = json(&o);
    assert_eq!(v["numeric_modes"], serde_json::Value::Null);
    assert_eq!(v["numeric_modes_note"], why);
    // values where M is definite: modes, and no note
    let o = qdot_scene(
        "numeric_modes_why",
        src.as_bytes(),
        "modes",
        &["--set", "e=2,k=1", "--format", "json"],
    );
    let v = json(&o);
    assert_eq!(v["numeric_modes_note"], serde_json::Value::Null);
    let w: Vec<f64> = v["numeric_omega_squared"]
        .as_array()
        .map(|a| a.iter().filter_map(serde_json::Value::as_f64).collect())
        .unwrap_or_default();
    assert_eq!(w.len(), 2, "{v}");
    assert!(
        (w[0] - 0.5).abs() < 1e-14 && (w[1] - 1.0).abs() < 1e-14,
        "{w:?}"
    );
}

// ---- a reader that leaves -------------------------------------------------

/// `qdot simulate … | head -1`: the reader closes the pipe after one line,
/// and `print!` panicked on it ("failed printing to stdout: Broken pipe",
/// a backtrace). The rest is dropped now, quietly, with the run's status.
#[test]
fn a_closed_pipe_is_not_a_panic() {
    use std::io::{BufRead, BufReader, Read};
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .current_dir(env!("QDOT_ROOT"))
        .args([
            "simulate",
            "examples/seed_23_4.qd",
            "--set",
            "G=1,g=9.81,r=1",
            "--init",
            "y3=0,theta3=0,y3'=0,theta3'=0",
            "--t-end",
            "10",
            "--points",
            "100000",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("qdot starts");
    let mut first = String::new();
    BufReader::new(child.stdout.take().expect("stdout"))
        .read_line(&mut first)
        .expect("a line");
    // the reader is dropped here: the pipe is closed
    let mut err = String::new();
    child
        .stderr
        .take()
        .expect("stderr")
        .read_to_string(&mut err)
        .expect("stderr read");
    let status = child.wait().expect("qdot ends");
    assert!(first.starts_with("t,"), "{first:?}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err, "", "nothing on stderr");
    assert_eq!(status.code(), Some(0));
}

/// A fuzz finding (fuzz/regressions/pipeline/abs-of-denominator-unreduced-
/// square): the gyrocompass with its frame tilted by π/4 − lat. |d| of a
/// denominator d holding cos(lat) was √(d²) with d² unreduced (cos² left
/// in). The equilibria at these values: sin(α)·(…) = 0 with A = C, so
/// α = 0 and π, the generalized force +c·sin(α) with c > 0 pushing away
/// from α = 0.
#[test]
fn a_tilted_gyrocompass_reduces_the_square_under_its_absolute_value() {
    let src = "coordinates alpha: angle\n\
        parameters A: mass*length^2, C: mass*length^2, s: 1/time, Omega: 1/time, lat: angle\n\
        assume C < 2*A, cos(lat) > 0\n\
        frame L = rot(z, Omega*t) * rot(y, pi/4 - lat) * rot(z, pi)\n\
        frame B = L * rot(z, alpha) * rot(x, s*t)\n\
        body rotor: inertia [C, A, A], frame B, at [0, 0, 0]\n";
    let o = qdot_scene(
        "tilted_gyrocompass",
        src.as_bytes(),
        "equilibrium",
        &["--set", "A=1,C=1,s=1,Omega=1,lat=1"],
    );
    o.assert_clean();
    assert!(
        o.stdout.contains(
            "Equilibria\n  1. α = 0  ≈ (0.000000)  — unstable\n  2. α = π  ≈ (3.141593)  — stable\n"
        ),
        "{o:?}"
    );
}
