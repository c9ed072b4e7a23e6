//! Hostile inputs for the work budget's reach: searches whose every step is
//! small but whose steps are exponentially many (the equilibria of n
//! uncoupled angles, the recombination of a polynomial's factors modulo a
//! prime). Each stops within 30 s and 2 GiB with an error naming the
//! phase, or answers.

use crate::bound::*;

/// `qdot COMMAND scene.qd ARGS` on `src` within 30 s and 2 GiB, ended by
/// itself without a panic.
fn run(tag: &str, src: &str, command: &str, args: &[&str]) -> Outcome {
    let o = qdot_scene_within(tag, src.as_bytes(), command, args, 30, 2048);
    o.assert_clean();
    o
}

/// Issue 33, item 10: the 30-link chain's 2³⁰ equilibria ran 300 s into
/// 12 GB. The 12-link chain's 4,096 (8,191 cases) are listed; the 30-link
/// chain stops at the case limit at once.
#[test]
fn the_equilibria_of_a_thirty_link_chain_stop_at_the_case_limit() {
    let o = run(
        "equilibria12",
        &qdot::engine::gallery::pendulum_chain(12),
        "equilibrium",
        &[],
    );
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("\n  4096. q₁ = π, q₂ = π, "), "{o:?}");
    assert!(!o.stdout.contains("\n  4097. "), "{o:?}");
    let o = run(
        "equilibria30",
        &qdot::engine::gallery::pendulum_chain(30),
        "equilibrium",
        &[],
    );
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: too many equilibria: the exact search for the equilibria split into more than 10,000 cases (each root of one equation put into the others is a case)\n  = hint: n angles with two equilibria each (a chain of n pendulums) have 2ⁿ equilibria; study fewer coordinates at once, or fix some with a constraint\n"
    );
}

/// A force that is the Swinnerton-Dyer polynomial of √2, √3, √5, √7, √11
/// and √13 (degree 64, irreducible over ℚ, 32 factors or more modulo every
/// prime: 2³¹ subsets to recombine), written as its 64 linear factors.
fn swinnerton_dyer_force() -> String {
    let roots = [2, 3, 5, 7, 11, 13];
    let factors: Vec<String> = (0..64u32)
        .map(|signs| {
            let terms: String = roots
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let sign = if signs >> i & 1 == 1 { '-' } else { '+' };
                    format!(" {sign} sqrt({p})")
                })
                .collect();
            format!("(x{terms})")
        })
        .collect();
    format!(
        "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2\nforce x: {}\n",
        factors.join("*")
    )
}

/// Factoring the force for its roots hung (`equilibrium`), and so did
/// printing it (`derive`: the printer tries to factor short sums): the
/// roots stop at the budget's subsets, the printed force is expanded.
#[test]
fn a_swinnerton_dyer_force_stops_factoring_within_the_budget() {
    let src = swinnerton_dyer_force();
    let o = run("swinnerton_dyer", &src, "equilibrium", &[]);
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: factoring too costly: 250,001 subsets of modular factors tried while finding the equilibria (the limit is 2,000,000 terms, and 250,000 subsets)\n  = hint: a polynomial whose factors modulo every prime are many takes time exponential in their number to factor over ℚ; to go on, raise the limit: --max-terms 20000000\n"
    );
    let o = run("swinnerton_dyer_derive", &src, "derive", &[]);
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(
        o.stdout
            .contains("  x  m·x\u{308} = x⁶⁴ − 1312·x⁶² + 792048·x⁶⁰ − 293134944·x⁵⁸ + "),
        "{o:?}"
    );
}

/// det(K − λ·M) of the 40-link chain: elimination over canonical fractions
/// took a gcd per entry per step, unbounded (28 s for 30 links, minutes
/// for 40); fraction-free, it is charged to the budget and takes a second.
#[test]
fn the_characteristic_polynomial_of_a_forty_link_chain_is_fraction_free() {
    let o = run(
        "modes40",
        &qdot::engine::gallery::pendulum_chain(40),
        "modes",
        &[],
    );
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(
        o.stdout.contains("\nCharacteristic equation  det(K − λ·M) = 0,  λ = ω²\n  815915283247897734345611269596115894272000000000·g⁴⁰·l⁴⁰·m⁴⁰ − 32636611329915909373824450783844635770880000000000·g³⁹·l⁴¹·m⁴⁰·λ + "),
        "{o:?}"
    );
    assert!(
        o.stdout.contains("\n  (no closed form for its roots: an irreducible factor of degree 40, not solved here)\n"),
        "{o:?}"
    );
}

/// The fuzzers' double pendulum with `1e308·ẋ₂²`: its terms are those of
/// `ẋ₂²`, but every coefficient of the Hamiltonian's derivatives has
/// thousands of digits, and `hamilton` took 29 s under a budget it never
/// passed. The arithmetic on big numbers is charged to the budget: it stops
/// `solve` of `1e1000` under a smaller one, naming the phase. `hamilton`
/// no longer needs that arithmetic: expanded it stops at the budget, and
/// written through its velocities it answers at once, exactly; `1e30`
/// answers expanded.
#[test]
fn arithmetic_on_thousand_digit_numbers_is_charged_to_the_budget() {
    let scene = |k: &str| {
        format!(
            "coordinates th1: angle, th2: angle\n\
             parameters m1: mass, m2: mass, l1: length, l2: length, g: acceleration\n\
             x1 = l1*sin(th1)\ny1 = -l1*cos(th1)\n\
             x2 = x1 + l2*sin(th2)\ny2 = y1 - l2*cos(th2)\n\
             kinetic E = 1/2*m1*(x1'^2 + y1'^2) + 1/2*m2*({k}*x2'^2 + y2'^2)\n\
             potential V = m1*g*y1 + m2*g*y2\n"
        )
    };
    let o = run(
        "digits1000",
        &scene("1e1000"),
        "solve",
        &["--max-terms", "20000"],
    );
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.starts_with("error: exact arithmetic too costly: "),
        "{o:?}"
    );
    assert!(
        o.stderr.contains(
            " word products on numbers of up to 2,000 digits while solving M·q̈ = f for the accelerations "
        ),
        "{o:?}"
    );
    assert!(
        o.stderr
            .contains("(the limit is 20,000 terms, and 1,000,000 word products)"),
        "{o:?}"
    );
    assert!(o.stderr.contains("hint: exact numbers this long"), "{o:?}");
    let o = run("digits308", &scene("1e308"), "hamilton", &[]);
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.starts_with("Intermediates  (in order"), "{o:?}");
    assert!(
        o.stdout.contains(
            "  H = 1/2·p_θ₁·v_th1 + 1/2·p_θ₂·v_th2 − g·l₁·(m₁ + m₂)·cos(θ₁) − g·l₂·m₂·cos(θ₂)\n"
        ),
        "{o:?}"
    );
    let o = run("digits30", &scene("1e30"), "hamilton", &[]);
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(
        o.stdout
            .contains("p_θ₁ = 999999999999999999999999999999·l₁²·m₂·cos²(θ₁)·θ̇₁ + "),
        "{o:?}"
    );
}

/// A planar chain of `n` rods, each a `body` hinged to the end of the one
/// before.
fn planar_rod_chain(n: usize) -> String {
    rod_chain(n, false)
}

/// [`planar_rod_chain`], with `per_rod` a mass and a length per rod
/// (`m1`…, `l1`…), as `scripts/hostile_table.sh` writes it.
fn rod_chain(n: usize, per_rod: bool) -> String {
    let qs: Vec<String> = (1..=n).map(|i| format!("q{i}: angle")).collect();
    let params = if per_rod {
        let ms: Vec<String> = (1..=n).map(|i| format!("m{i}: mass")).collect();
        let ls: Vec<String> = (1..=n).map(|i| format!("l{i}: length")).collect();
        format!("{}, {}, g: acceleration", ms.join(", "), ls.join(", "))
    } else {
        "m: mass, l: length, g: acceleration".to_string()
    };
    let mut s = format!("coordinates {}\nparameters {params}\n", qs.join(", "));
    for i in 1..=n {
        let (m, l) = if per_rod {
            (format!("m{i}"), format!("l{i}"))
        } else {
            ("m".to_string(), "l".to_string())
        };
        let link = format!("[sin(q{i}), -cos(q{i})]");
        let prev = if i > 1 {
            format!("P{} + ", i - 1)
        } else {
            String::new()
        };
        s.push_str(&format!(
            "body b{i}: mass {m}, inertia 1/12*{m}*{l}^2, angle q{i}, at {prev}{l}/2*{link}\nP{i} = {prev}{l}*{link}\n"
        ));
    }
    s.push_str("gravity [0, -g]\n");
    s
}

/// Issue 46, item 11: `response` on a 30-body chain linearized it and
/// found its modes (9 s of CPU) before saying that it has no harmonic
/// load; nothing in the scene depends on time, which is seen at once.
#[test]
fn a_chain_without_a_harmonic_load_is_refused_before_any_work() {
    let o = run("response30", &planar_rod_chain(30), "response", &[]);
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: the scene has no harmonic load: the frequency response needs a force F·cos(p·t) (or sin) on the system\n  = hint: write a harmonic load in the scene, e.g. `work L = F0*cos(p*t)*x` (p the forcing frequency)\n"
    );
    o.assert_cpu_below(2.0);
}

/// Issue 46, item 11: `forces` on a 3D chain of 30 rods expanded every
/// intermediate (its frames, its points) and held them all, to 3.6 GB and
/// a failed allocation; the terms held by one expansion are bounded
/// together, as one expression's.
#[test]
fn the_forces_of_a_thirty_rod_chain_in_space_stop_at_the_budget() {
    let o = run(
        "forces_rods30",
        &qdot::engine::gallery::rod_chain_3d(30),
        "forces",
        &[],
    );
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: expression too large: 2,374,772 terms while expanding the generalized forces from the intermediates (the limit is 2,000,000)\n  = hint: exact expressions this large are rarely what a scene means (expand less, or choose other coordinates); to go on, raise the limit: --max-terms 20000000\n"
    );
}

/// Issue 46, acceptance 4: expanded, the accelerations of 30 rods with a
/// mass and a length each took 50 s of CPU and 1.5 GB (`latex --steps`;
/// `hamilton` 25 s, 0.9 GB) before the elimination passed its term
/// products: nearly every product was a new term of some 30 variables,
/// which the products did not count. The terms built are charged by their
/// variable powers: both stop within seconds.
#[test]
fn a_chain_of_rods_with_their_own_masses_and_lengths_stops_at_the_terms_built() {
    let src = rod_chain(30, true);
    let o = run("steps30u", &src, "latex", &["--steps"]);
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: expression too large: 32,202,569 variable powers in the terms built in all while solving M·q̈ = f for the accelerations (the limit is 2,000,000 terms, and 32,000,000 variable powers in the terms built in all)\n  = hint: exact expressions this large are rarely what a scene means (expand less, or choose other coordinates); to go on, raise the limit: --max-terms 20000000\n"
    );
    o.assert_cpu_below(10.0);
    let o = run("hamilton30u", &src, "hamilton", &[]);
    assert_eq!(o.code, Some(1), "{o:?}");
    assert_eq!(
        o.stderr,
        "error: expression too large: 32,847,150 variable powers in the terms built in all while deriving Hamilton's equations (the limit is 2,000,000 terms, and 32,000,000 variable powers in the terms built in all)\n  = hint: exact expressions this large are rarely what a scene means (expand less, or choose other coordinates); to go on, raise the limit: --max-terms 20000000\n"
    );
    o.assert_cpu_below(10.0);
}

/// Issue 46, acceptance 4: `latex` on 30 rods expanded the accelerations
/// until the budget stopped it (50 s); `solve` writes them through the
/// scene's intermediates in a second, and so does `latex` now, line for
/// line as `solve --format latex`.
#[test]
fn latex_writes_a_large_chain_through_its_intermediates() {
    let src = rod_chain(30, true);
    let o = run("latex30u", &src, "latex", &[]);
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(
        o.stdout.starts_with(
            "The intermediates, in order (each is written in the ones before it):\n\\begin{align*}\n  P1_{x} &= l_{1} \\sin q_{1} \\\\\n"
        ),
        "{o:?}"
    );
    assert!(
        o.stdout
            .ends_with("  \\ddot{q}_{30} &= z_{30}\n\\end{align*}\n"),
        "{o:?}"
    );
    o.assert_cpu_below(10.0);
    let solve = run("solve30u", &src, "solve", &["--format", "latex"]);
    assert_eq!(o.stdout, solve.stdout);
}
