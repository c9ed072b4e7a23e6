//! Hostile inputs for the mechanics: velocity-dependent potentials (which
//! were differentiated by q only), a Lagrangian written directly,
//! accelerations inside energies, derivatives past the second, points of
//! application that move with the velocities, definition chains thousands
//! deep or sharing their arguments, and a Taylor series about a point
//! where the function is undefined.

use crate::bound::*;
use qdot::Scene;

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("{}/examples/{name}.qd", env!("QDOT_ROOT")))
        .expect("the example")
}

fn accelerations(src: &str) -> Vec<String> {
    let scene = Scene::parse(src).expect("the scene");
    let acc = scene
        .lagrange()
        .expect("equations")
        .accelerations()
        .expect("solved");
    acc.iter().map(|(q, e)| format!("{q}'' = {e}")).collect()
}

/// Acceptance 3 of issue 14: the magnetic force of a Penning trap written
/// as a velocity-dependent potential, as a load and as a Lagrangian gives
/// the same equations — the Lorentz force's generalized components.
#[test]
fn the_penning_trap_three_ways_gives_the_lorentz_force() {
    let want = [
        "rho'' = rho*phi'^2 + B*e*rho*phi'/m + e*V0*rho/(2*d^2*m)",
        "phi'' = -rho'*(2*m*phi' + B*e)/(m*rho)",
        "z'' = -e*V0*z/(d^2*m)",
    ];
    for name in ["penning_potential", "penning_load", "penning_lagrangian"] {
        assert_eq!(accelerations(&example(name)), want, "{name}");
    }
    // the potential and the load give the same equations, term for term
    let derive = |name: &str| {
        let scene = Scene::parse(&example(name)).expect("scene");
        let l = scene.lagrange().expect("equations");
        let eqs: Vec<(String, String)> = l
            .equations
            .iter()
            .map(|e| (e.lhs.to_string(), e.rhs.to_string()))
            .collect();
        (
            eqs,
            format!("{:?}", l.mass_matrix),
            format!("{:?}", l.forcing),
        )
    };
    assert_eq!(derive("penning_potential"), derive("penning_load"));
    let pot = derive("penning_potential");
    assert_eq!(pot.0[0].1, "B*e*rho*phi' + e*V0*rho/(2*d^2)");
    assert_eq!(pot.0[1].1, "-B*e*rho*rho'");
    // the Lagrangian's: everything on the left, Q = 0
    let lag = derive("penning_lagrangian");
    assert_eq!(
        lag.0[1].0,
        "m*rho^2*phi'' + 2*m*rho*phi'*rho' + B*e*rho*rho'"
    );
    assert!(lag.0.iter().all(|(_, q)| q == "0"));
    assert_eq!(lag.1, pot.1);
    assert_eq!(lag.2, pot.2);
}

/// A force function is minus a potential, velocities included.
#[test]
fn a_velocity_dependent_force_function_has_the_opposite_sign() {
    let pot = example("penning_potential");
    let ff = pot.replace(
        "potential U = e*V0/(2*d^2)*(z^2 - rho^2/2) - e*dot(A, P')",
        "forcefunction W = -e*V0/(2*d^2)*(z^2 - rho^2/2) + e*dot(A, P')",
    );
    assert_ne!(pot, ff);
    assert_eq!(accelerations(&ff), accelerations(&pot));
}

/// A velocity-dependent potential quadratic in the velocities adds to the
/// mass: U = −1/2·μ·x'² is a kinetic energy of mass μ.
#[test]
fn a_potential_quadratic_in_the_velocities_adds_inertia() {
    let src = "coordinates x\nparameters m, mu, k\nkinetic E = 1/2*m*x'^2\npotential U = 1/2*k*x^2 - 1/2*mu*x'^2\n";
    assert_eq!(accelerations(src), ["x'' = -k*x/(m + mu)"]);
}

/// `lagrangian` combines with the other roles.
#[test]
fn a_lagrangian_combines_with_kinetic_and_potential() {
    let src = "coordinates x\nparameters m, k, c\nkinetic E = 1/2*m*x'^2\nlagrangian L = -1/2*k*x^2\nrayleigh R = 1/2*c*x'^2\n";
    assert_eq!(accelerations(src), ["x'' = -c*x'/m - k*x/m"]);
    let o = qdot_scene("lagrangian", src.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert!(
        o.stdout.contains("x\u{308} = −c/m·x\u{307} − k/m·x"),
        "{o:?}"
    );
}

#[test]
fn an_acceleration_in_an_energy_is_refused_at_its_position() {
    // the line, the role and name, the text the caret starts at
    let cases = [
        ("kinetic E = 1/2*m*x'^2 + m*x*x''", "kinetic E", "x''"),
        ("kinetic E = 1/2*m*x''^2", "kinetic E", "x''"),
        ("potential V = k*x*x''", "potential V", "x''"),
        ("lagrangian L = 1/2*m*x'^2 - m*x''*x", "lagrangian L", "x''"),
        ("rayleigh R = 1/2*c*(x')'^2", "rayleigh R", "x')'"),
    ];
    for (line, what, at) in cases {
        let (l, c) = (3, line.find(at).expect("the marker") + 1);
        let src = format!("coordinates x\nparameters m, k, c\n{line}\n");
        let o = qdot_scene("acceleration", src.as_bytes(), "derive", &[]);
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{line}: {o:?}");
        assert!(
            o.stderr.starts_with(&format!(
                "error: `{what}` depends on the acceleration x''\n --> scene.qd:{l}:{c}\n"
            )),
            "{line}: {}",
            o.stderr
        );
        assert!(o.stderr.contains("hint: energies and the Lagrangian are functions of the coordinates, the velocities and t"), "{}", o.stderr);
        // never "the kinetic energy is zero"
        assert!(!o.stderr.contains("is zero"), "{}", o.stderr);
    }
    // an acceleration through a definition: the whole expression is shown
    let src = "coordinates x\nparameters m\na = x''\nkinetic E = 1/2*m*x'^2 + m*a*x\n";
    let o = qdot_scene("acceleration_def", src.as_bytes(), "derive", &[]);
    assert!(
        o.stderr.starts_with(
            "error: `kinetic E` depends on the acceleration x''\n --> scene.qd:4:13\n"
        ),
        "{}",
        o.stderr
    );
    // the virtual work may hold D'Alembert's inertia forces
    let src = "coordinates x\nparameters m, k\nwork L = -m*x''*x - k*x*x\n";
    let o = qdot_scene("dalembert_work", src.as_bytes(), "forces", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("Q_x = −m·x\u{308} − 2·k·x"), "{o:?}");
}

/// The fuzzer's finding: `cos(theta2)` with 61 primes inside a position
/// vector took minutes (the n-th derivative has as many terms as n has
/// partitions), and the equilibria it printed treated θ₂⁽¹⁵⁾ as a
/// constant. Time derivatives are bounded, and stop at their position.
#[test]
fn time_derivatives_past_the_bound_are_refused_at_their_position() {
    let path = concat!(
        env!("QDOT_ROOT"),
        "/fuzz/regressions/pipeline/high-order-derivative"
    );
    let src = std::fs::read_to_string(path).expect("the fuzz finding");
    let o = qdot_scene("primes", src.as_bytes(), "equilibrium", &[]);
    o.assert_clean();
    o.assert_cpu_below(5.0);
    assert!(
        o.stderr.starts_with(
            "error: this takes the time derivative of order 65 of `theta2`; qdot allows at most 10\n --> scene.qd:8:60\n"
        ),
        "{}",
        o.stderr
    );
    // nested primes and dt() add up; 10 is allowed
    let cases = [
        ("a = (x'''''')'''''", 5),
        ("a = dt(dt(x''''''''''))", 8),
        ("a = dt(sin(x)''''''''''')", 8),
    ];
    for (line, col) in cases {
        // a force uses `a`: an unused definition's error is a warning
        let src =
            format!("coordinates x\nparameters m\n{line}\nkinetic T = 1/2*m*x'^2\nforce x: 0*a\n");
        let o = qdot_scene("primes", src.as_bytes(), "derive", &[]);
        o.assert_clean();
        assert!(
            o.stderr.starts_with(&format!(
                "error: this takes the time derivative of order 11 of `x`; qdot allows at most 10\n --> scene.qd:3:{col}\n"
            )),
            "{line}: {}",
            o.stderr
        );
    }
    let src = "coordinates x\nparameters m\na = x''''''''''\nkinetic T = 1/2*m*x'^2\n";
    let o = qdot_scene("primes_ok", src.as_bytes(), "derive", &[]);
    assert_eq!(o.code, Some(0), "{o:?}");
}

/// A third derivative in a force would stay in the equations of motion as
/// if it were a constant; a point of application moving with a velocity
/// would make δr = Σ ∂r/∂q_k·δq_k wrong. Both are refused where written.
#[test]
fn forces_past_the_acceleration_and_moving_points_are_refused() {
    let head = "coordinates x, y\nparameters m, c, k\nkinetic T = 1/2*m*(x'^2 + y'^2)\n";
    let order3 =
        |what: &str, d: &str| format!("{what} depends on {d}, a time derivative of order 3");
    let moving = |what: &str, d: &str| {
        format!("{what} depends on {d}; it must be a position, a function of the coordinates and t")
    };
    let cases = [
        ("load -c*x''' at x", order3("a load", "x'''"), 6),
        ("load [0, -c*y'''] at [x, y]", order3("a load", "y'''"), 6),
        ("torque -c*x''' on x", order3("a torque", "x'''"), 8),
        (
            "force x: -c*x'''",
            order3("a generalized force", "x'''"),
            10,
        ),
        ("work W = -c*x'''*x", order3("`work W`", "x'''"), 10),
        ("load -c at x + x'", moving("a load's point", "x'"), 12),
        (
            "load [0, -m] at [x, y*y'']",
            moving("a load's point", "y''"),
            17,
        ),
        ("torque k on x'", moving("a torque's angle", "x'"), 13),
    ];
    for (line, msg, col) in cases {
        let src = format!("{head}{line}\n");
        let o = qdot_scene("order", src.as_bytes(), "solve", &[]);
        o.assert_clean();
        assert!(
            o.stderr
                .starts_with(&format!("error: {msg}\n --> scene.qd:4:{col}\n")),
            "{line}: {}",
            o.stderr
        );
    }
    // a `solve` equation: at most the accelerations
    let src = format!("{head}solve N {{\n  N = m*x'''\n}}\n");
    let o = qdot_scene("order_block", src.as_bytes(), "solve", &[]);
    assert!(
        o.stderr.starts_with(&format!(
            "error: {}\n --> scene.qd:5:3\n",
            order3("a `solve` equation", "x'''")
        )),
        "{}",
        o.stderr
    );
    // D'Alembert's inertia force and a velocity-dependent force are fine
    let src = format!("{head}load -m*x'' - c*x' at x\n");
    let o = qdot_scene("order_ok", src.as_bytes(), "forces", &[]);
    assert_eq!(o.code, Some(0), "{o:?}");
}

/// Definitions that each apply two functions to the previous one
/// (`f_i = sin(f_{i-1}) + cos(f_{i-1})`) share their arguments: the value
/// is small, but written out it doubles per line, and printing,
/// differentiating and evaluating pay it at every occurrence. Such an
/// argument is bounded where it is built; below the bound, printing a
/// result past the work budget stops with the budget's error.
#[test]
fn definitions_sharing_their_arguments_do_not_hang() {
    let chain = |n: usize| {
        let mut src = String::from("coordinates x\nparameters m\nf0 = x\n");
        for i in 1..=n {
            src.push_str(&format!("f{i} = sin(f{}) + cos(f{})\n", i - 1, i - 1));
        }
        src.push_str(&format!("kinetic T = 1/2*m*x'^2\npotential V = f{n}\n"));
        src
    };
    for n in [9, 40] {
        let o = qdot_scene(
            "shared",
            chain(n).as_bytes(),
            "equilibrium",
            &["--set", "m=1"],
        );
        o.assert_clean();
        o.assert_cpu_below(5.0);
        assert!(
            o.stderr.starts_with(
                "error: a function's argument here is 2,044 symbols long written out; qdot allows at most 2,000\n  --> scene.qd:12:6\n"
            ),
            "{}",
            o.stderr
        );
    }
    // at the bound's edge: the equilibria of sin∘…, numerically, in seconds
    let o = qdot_scene(
        "shared_8",
        chain(8).as_bytes(),
        "equilibrium",
        &["--set", "m=1"],
    );
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("x = 0.785398163397  — stable"), "{o:?}");
    // a result that would print past the budget
    let o = qdot_scene(
        "shared_print",
        chain(8).as_bytes(),
        "forces",
        &["--max-terms", "20000"],
    );
    o.assert_clean();
    assert!(
        o.stderr.starts_with(
            "error: expression too large to print: 514,305 symbols written out (the limit is 20,000)\n"
        ),
        "{}",
        o.stderr
    );
}

/// 5,000 definitions each using the next (forward references), also
/// through the REPL's `:load`: no stack overflow, the right value.
#[test]
fn definition_chains_thousands_deep_evaluate_without_recursion() {
    let mut src = String::from("coordinates x\nparameters m, k\n");
    for i in 0..5000 {
        src.push_str(&format!("a{i} = a{} + 1\n", i + 1));
    }
    src.push_str("a5000 = x\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*a0^2\n");
    let o = qdot_scene("chain", src.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("x\u{308} = −k/m·x − 5000·k/m"), "{o:?}");
    // the same file through the REPL
    let dir = std::env::temp_dir().join(format!("qdot-hostile-{}", std::process::id()));
    let path = dir.join("chain.qd");
    let o = qdot_bounded(
        &["repl"],
        &format!(":load {}\n:solve\n", path.display()),
        SECONDS,
        MEMORY_MIB,
    );
    o.assert_clean();
    assert!(o.stdout.contains("x\u{308} = −k/m·x − 5000·k/m"), "{o:?}");
    // a 5,000-long cycle is reported, whole, without recursion
    let mut src = String::from("coordinates x\n");
    for i in 0..5000 {
        src.push_str(&format!("b{i} = b{} + 1\n", (i + 1) % 5000));
    }
    let o = qdot_scene("cycle", src.as_bytes(), "derive", &[]);
    o.assert_clean();
    assert!(
        o.stderr.starts_with(
            "error: cyclic definition: b0 → b1 → b2 → b3 → b4 → … → b4995 → b4996 → b4997 → b4998 → b4999 → b0 (5000 definitions)\n    --> scene.qd:5001:"
        ),
        "{o:?}"
    );
}

/// 50,000 definitions each applying sin to the previous one: the nesting
/// bound stops it with a positioned error.
#[test]
fn a_50000_deep_sin_chain_is_bounded() {
    let mut src = String::from("coordinates x\nparameters m, k\na0 = x\n");
    for i in 1..=50_000 {
        src.push_str(&format!("a{i} = sin(a{})\n", i - 1));
    }
    src.push_str("kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*a50000^2\n");
    let o = qdot_scene("sin_chain", src.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.starts_with("error: functions nested 201 deep here; qdot allows at most 200\n   --> scene.qd:204:8\n"),
        "{}",
        &o.stderr[..300.min(o.stderr.len())]
    );
}

#[test]
fn a_taylor_series_about_an_undefined_point_says_so() {
    let scene = Scene::parse("coordinates x\nparameters m\n").expect("scene");
    let e = scene
        .expr("taylor(sin(x)/x, x, 5)")
        .expect_err("undefined at 0");
    assert_eq!(
        e.message,
        "this function is not defined at x = 0 (it divides by zero there), so it has no Taylor series about that point"
    );
    let at = e.span.expect("a position");
    assert_eq!((at.start, at.end), (7, 15));
    assert!(e
        .hint
        .as_deref()
        .unwrap_or("")
        .contains("taylor(f, x = 1, 5)"));
    // about another point it expands
    assert!(scene.expr("taylor(sin(x)/x, x = pi, 1)").is_ok());
}

/// A folded angle a ± b is written as a lecturer writes it: a sum after
/// `+` needs no parentheses, after `−` it does (text and LaTeX).
#[test]
fn folded_angles_have_parentheses_only_where_a_sign_needs_them() {
    let src = "coordinates x\nparameters m\nf1 = sin(x) + cos(x)\nkinetic T = 1/2*m*x'^2\npotential V = sin(f1) + cos(f1)\n";
    let o = qdot_scene("folded", src.as_bytes(), "forces", &[]);
    assert!(
        o.stdout
            .contains("Q_x = sin(x + cos(x) + sin(x)) − cos(x − (cos(x) + sin(x)))"),
        "{o:?}"
    );
    let o = qdot_scene(
        "folded_tex",
        src.as_bytes(),
        "forces",
        &["--format", "latex"],
    );
    assert!(
        o.stdout
            .contains(r"Q_{x} &= \sin(x + \cos x + \sin x) - \cos(x - (\cos x + \sin x))"),
        "{o:?}"
    );
}

/// The dimension check is linear in the scene: 100,000 names whose
/// dimensions are found from each other (each one substituted into every
/// earlier solution took minutes), all of them annotated, and long sums
/// whose terms vote on their dimension.
#[test]
fn the_dimension_check_scales() {
    let n = 100_000;
    let params: Vec<String> = (0..n).map(|i| format!("p{i}")).collect();
    let chain: String = (1..n)
        .map(|i| format!("x{i} = p{i} + p{}\n", i - 1))
        .collect();
    let found = format!(
        "coordinates q\nparameters p0: length, {}\n{chain}",
        params[1..].join(", ")
    );
    let o = qdot_scene("dimension_chain", found.as_bytes(), "check", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("found at"));
    let annotated: Vec<String> = params.iter().map(|p| format!("{p}: length")).collect();
    let declared = format!(
        "coordinates q: length\nparameters {}\n{chain}",
        annotated.join(", ")
    );
    let o = qdot_scene("dimension_declared", declared.as_bytes(), "check", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    // 999 known terms and one unknown, in 2,000 statements
    let terms = vec!["a"; 999].join(" + ");
    let sums: String = (0..2000)
        .map(|i| format!("s{i} = {terms} + b{i}\n"))
        .collect();
    let bs: Vec<String> = (0..2000).map(|i| format!("b{i}")).collect();
    let voting = format!(
        "coordinates q\nparameters a: length, {}\n{sums}",
        bs.join(", ")
    );
    let o = qdot_scene("dimension_votes", voting.as_bytes(), "check", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
}

/// Constraints that grow: 300 constraints on two coordinates are refused
/// at the first extra one at once; a chain of 25 trigonometric constraints
/// ends at the work budget with the phase named (not a hang, not a crash),
/// and `--max-terms` lowers the bound so it ends sooner.
#[test]
fn constraints_that_grow_end_with_a_reason() {
    let mut many =
        String::from("coordinates x, y\nparameters m, l\nkinetic E = 1/2*m*(x'^2 + y'^2)\n");
    for i in 0..300 {
        many.push_str(&format!("constraint c{i}: x^{} + y = l\n", i + 2));
    }
    let o = qdot_scene("many_constraints", many.as_bytes(), "solve", &[]);
    o.assert_clean();
    o.assert_cpu_below(2.0);
    assert!(
        o.stderr.starts_with("error: more constraints than coordinates: with 2 coordinates at most 2 constraints can be independent\n --> scene.qd:6:1\n"),
        "{}",
        o.stderr
    );
    let n = 25;
    let mut chain = format!(
        "coordinates {}\nparameters m, k\nkinetic E = 1/2*m*({})\npotential V = 1/2*k*x0^2\n",
        (0..n)
            .map(|i| format!("x{i}"))
            .collect::<Vec<_>>()
            .join(", "),
        (0..n)
            .map(|i| format!("x{i}'^2"))
            .collect::<Vec<_>>()
            .join(" + ")
    );
    for i in 0..n - 1 {
        chain.push_str(&format!("constraint c{i}: x{} = x{i} + sin(x{i})\n", i + 1));
    }
    let o = qdot_scene(
        "constraint_chain",
        chain.as_bytes(),
        "solve",
        &["--max-terms", "200000"],
    );
    o.assert_clean();
    assert!(
        o.stderr.starts_with("error: expression too large")
            && o.stderr.contains("while solving M·q̈ − Aᵀ·λ = f, A·q̈ = γ"),
        "{}",
        o.stderr
    );
}
