//! Oscillations about steady motions (`qdot modes --steady`): the SymPy
//! fixtures of tests/fixtures/gen_steady.py (Routh's effective potential,
//! not qdot's method), Bertrand's closure, the fast top, and the command
//! line's text, JSON and refusals.

use qdot::expr::{atom, Expr};
use qdot::solve::equilibrium::Values;
use qdot::solve::oscillations::{self as osc, Modes, Reference};
use qdot::solve::steady::rate_symbol;
use qdot::Scene;
use serde_json::Value;
use std::process::Command;

fn root() -> &'static str {
    env!("QDOT_ROOT")
}

fn scene(path: &str) -> Scene {
    let src = std::fs::read_to_string(format!("{}/{path}", root())).expect("scene exists");
    Scene::parse(&src).unwrap_or_else(|d| panic!("{}", d.render(path, &src)))
}

/// `text` in the scene, with `theta0` the general reference symbol of
/// `--at theta=theta0`.
fn expected(s: &Scene, text: &str) -> Expr {
    let e = s
        .expr(&text.replace("theta0", "theta"))
        .unwrap_or_else(|d| panic!("`{text}`: {}", d.message));
    e.subs(atom::coord("theta", 0), &Expr::unknown("theta0"))
        .expect("substitutes")
}

/// `modes --steady … --at …` through the library, as the command does it.
fn steady_modes(s: &Scene, steady: &[&str], at: &str) -> Modes {
    let v = s.motion_values(at).expect("--at reads");
    let (q0, rates) = (v.positions, v.rates);
    let mut reference: Vec<(usize, Expr)> = steady
        .iter()
        .map(|c| {
            let k = s
                .coordinates
                .iter()
                .position(|x| x.name == *c)
                .expect("a coordinate");
            (k, rate_symbol(c))
        })
        .collect();
    for (k, r) in rates {
        reference.retain(|(i, _)| *i != k);
        reference.push((k, r));
    }
    reference.sort_by_key(|(k, _)| *k);
    let r = Reference::at(Some(&q0)).steady(reference);
    s.assumptions_in_force(|| osc::modes_about(s, &r, &Values::new()))
        .unwrap_or_else(|d| panic!("{}", d.message))
}

fn fixtures() -> Vec<Value> {
    let text = std::fs::read_to_string(format!("{}/tests/fixtures/steady.json", root()))
        .expect("steady.json exists");
    let v: Value = serde_json::from_str(&text).expect("JSON");
    v["cases"].as_array().expect("cases").clone()
}

fn strings(v: &Value) -> Vec<&str> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_str().expect("a string"))
        .collect()
}

/// The conical pendulum, the heavy top's nutation, two circular orbits and
/// the bead on a rotating hoop: the solved rate and ω² exactly SymPy's.
#[test]
fn frequencies_about_steady_motions_agree_with_sympy() {
    let cases = fixtures();
    assert_eq!(cases.len(), 5);
    for case in &cases {
        let name = case["name"].as_str().expect("name");
        let s = scene(case["scene"].as_str().expect("scene"));
        let md = steady_modes(
            &s,
            &strings(&case["steady"]),
            case["at"].as_str().expect("at"),
        );
        let want = expected(&s, case["omega_squared"].as_str().expect("ω²"));
        assert_eq!(md.omega_squared.len(), 1, "{name}");
        assert!(
            md.omega_squared[0].equals(&want),
            "{name}: qdot ω² = {}, SymPy {want}",
            md.omega_squared[0]
        );
        let solved = case["solved"].as_array().expect("solved");
        let sm = md.steady.as_ref();
        assert_eq!(sm.map_or(0, |m| m.solved.len()), solved.len(), "{name}");
        for (got, want) in sm.map(|m| &m.solved[..]).unwrap_or(&[]).iter().zip(solved) {
            assert_eq!(
                got.coordinate,
                want["coordinate"].as_str().expect("c"),
                "{name}"
            );
            assert_eq!(got.squared, want["squared"].as_bool().expect("b"), "{name}");
            let v = expected(&s, want["value"].as_str().expect("value"));
            assert!(got.value.equals(&v), "{name}: {} vs {v}", got.value);
        }
        assert_eq!(md.stability.word(), stability_of(name), "{name}");
    }
}

fn stability_of(name: &str) -> &'static str {
    match name {
        // r0 is a declared length (positive): decided
        "circular orbit, Newtonian" | "circular orbit, harmonic" => "stable",
        // the signs of cos θ0 and of R·w² − g are not known
        _ => "undecided",
    }
}

/// Bertrand's theorem: about a circular orbit the radial frequency is the
/// orbital one under −k/r, twice it under k·r²/2 (the orbits close);
/// the fixtures' apsidal ratios, from qdot's ω² and solved φ̇².
#[test]
fn circular_orbits_close_as_bertrand_says() {
    for case in fixtures().iter().filter(|c| c["apsidal_ratio"].is_number()) {
        let s = scene(case["scene"].as_str().expect("scene"));
        let md = steady_modes(&s, &["phi"], "r=r0");
        let rate2 = &md.steady.as_ref().expect("steady").solved[0].value;
        let ratio = md.omega_squared[0].div(rate2).expect("φ̇² ≠ 0");
        let n = case["apsidal_ratio"].as_i64().expect("an integer");
        assert!(ratio.equals(&Expr::int(n * n)), "{}: {ratio}", case["name"]);
    }
}

/// The fast top: ω_nut → C·ω₃/I₁ as the precession slows (the spin
/// grows): ω²·φ̇² and a²·φ̇² agree at φ̇ = 0, a = C·ω₃/I₁ of the fixture.
#[test]
fn a_fast_top_nutates_at_c_omega3_over_i1() {
    let case = fixtures()
        .into_iter()
        .find(|c| {
            c["name"]
                .as_str()
                .is_some_and(|n| n.starts_with("heavy top"))
        })
        .expect("the top");
    let s = scene("examples/heavy_top.qd");
    let md = steady_modes(&s, &["phi", "psi"], "theta=theta0");
    let a = expected(&s, case["fast_top_rate"].as_str().expect("a"));
    let phid = atom::coord("phi", 1);
    let slow = |e: &Expr| {
        e.mul(&Expr::var(phid).powi(2).expect("φ̇²"))
            .subs(phid, &Expr::zero())
            .expect("at φ̇ = 0")
    };
    let lead = slow(&md.omega_squared[0]);
    assert!(lead.equals(&slow(&a.mul(&a))), "{lead}");
    assert!(
        lead.equals(&expected(&s, "(g*l*m)^2/(A + l^2*m)^2")),
        "{lead}"
    );
}

fn qdot(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("qdot runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The conical pendulum as the command line writes it: the condition, the
/// rate solved, Routh's reduction named, ω² at θ₀ = π/3 exactly 7g/(2l).
#[test]
fn the_cli_writes_the_conical_pendulum() {
    let (ok, out, err) = qdot(&[
        "modes",
        "examples/spherical_pendulum.qd",
        "--steady",
        "phi",
        "--at",
        "theta=pi/3",
    ]);
    assert!(ok, "{err}");
    let head: Vec<&str> = out.lines().take(4).collect();
    assert_eq!(
        head,
        [
            "Steady motion  φ̇ = const, θ = 1/3·π",
            "  the equation of θ there: 1/4·l²·m·√3·φ̇² − 1/2·g·l·m·√3 = 0",
            "  so φ̇² = 2·g/l",
            "Linearized about it, p_φ held (Routh's reduction)   M·q̈ + C·q̇ + K·q = f(t)",
        ]
    );
    assert!(out.contains("  ω₁² = 7/2·g/l    mode (1)\n"), "{out}");
    assert!(
        out.contains("Stability of the steady motion: stable\n"),
        "{out}"
    );
}

/// A rate given with --at: the orbit at φ̇ = w is a steady motion only at
/// the radius that suits it, and the JSON carries the steady motion.
#[test]
fn given_rates_are_checked_and_written_in_json() {
    let (ok, _, err) = qdot(&["modes", "examples/central_force.qd", "--at", "r=r0,phi'=1"]);
    assert!(!ok);
    assert!(
        err.contains("error: no steady motion here: the equation of `r` leaves "),
        "{err}"
    );
    let (ok, out, err) = qdot(&[
        "modes",
        "examples/central_force.qd",
        "--steady",
        "phi",
        "--at",
        "r=r0",
        "--format",
        "json",
    ]);
    assert!(ok, "{err}");
    let v: Value = serde_json::from_str(&out).expect("JSON");
    let sm = &v["steady_motion"];
    assert_eq!(sm["rates"]["phi"], "phi'");
    assert_eq!(sm["conditions"]["r"], "m*r0*phi'^2 - k/r0^2");
    assert_eq!(sm["solved"][0]["coordinate"], "phi");
    assert_eq!(sm["solved"][0]["squared"], true);
    assert_eq!(sm["solved"][0]["value"], "k/(m*r0^3)");
    assert_eq!(v["omega_squared"][0], "k/(m*r0^3)");
    assert_eq!(v["stability"], "stable");
}

/// Refusals: a coordinate that is not cyclic; a rate at an equilibrium
/// command; a condition with no rate to solve for.
#[test]
fn steady_motions_are_refused_with_reasons() {
    let (ok, _, err) = qdot(&[
        "modes",
        "examples/spherical_pendulum.qd",
        "--steady",
        "theta",
    ]);
    assert!(!ok);
    assert!(err.contains("error: `theta` appears in the equation of `phi`, so it cannot turn at a constant rate with the others at rest"), "{err}");
    assert!(err.contains("hint: a steady motion turns cyclic coordinates only; `qdot integrals` lists the scene's cyclic coordinates"), "{err}");
    let (ok, _, err) = qdot(&["modes", "examples/spherical_pendulum.qd", "--steady", "chi"]);
    assert!(!ok);
    assert!(
        err.contains("`--steady`: `chi` is not a coordinate of the scene"),
        "{err}"
    );
    let (ok, _, err) = qdot(&[
        "modes",
        "examples/spherical_pendulum.qd",
        "--at",
        "theta=pi/3,phi'=2",
    ]);
    assert!(!ok);
    assert!(
        err.contains("no steady motion here: the equation of `theta` leaves"),
        "{err}"
    );
}

/// `equilibrium --steady`: the conical pendulum's steady motions, cos θ =
/// g/(l·φ̇²) and its mirror stable, the poles undecided with the reason;
/// the JSON names the steady rates.
#[test]
fn equilibrium_finds_the_steady_motions() {
    let (ok, out, err) = qdot(&[
        "equilibrium",
        "examples/spherical_pendulum.qd",
        "--steady",
        "phi",
    ]);
    assert!(ok, "{err}");
    let pole = "undecided (the steady coordinates' mass matrix is singular there (a coordinate singularity, like an azimuth at the pole), so their momenta do not fix their rates)";
    assert_eq!(
        out,
        format!(
            "Steady motions  φ̇ = const, the other coordinates at rest
Conditions (each coordinate's equation there)
  θ:  l²·m·cos(θ)·sin(θ)·φ̇² − g·l·m·sin(θ) = 0

Steady motions (stability about each: `qdot modes --steady`)
  1. θ = 0  — {pole}
  2. θ = π  — {pole}
  3. θ = acos(g/(l·φ̇²))  — stable
     exists when |g/(l·φ̇²)| ≤ 1
  4. θ = −acos(g/(l·φ̇²))  — stable
     exists when |g/(l·φ̇²)| ≤ 1
"
        )
    );
    let (ok, out, _) = qdot(&[
        "equilibrium",
        "examples/spherical_pendulum.qd",
        "--steady",
        "phi",
        "--format",
        "json",
    ]);
    assert!(ok);
    let v: Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(v["steady"]["phi"], "phi'");
    assert_eq!(v["equilibria"][2]["theta"], "acos(g/(l*phi'^2))");
    assert_eq!(v["stability"][2], "stable");
}
