//! Small oscillations (`qdot modes`, `qdot::solve::oscillations`): the
//! linearized M, C, K and f(t), det(K − λ·M), the exact ω² and modes
//! (distribution coefficients), stability, the standard form of one degree
//! of freedom, the free and forced responses — all checked exactly against
//! values derived by hand (the derivations are in the comments) — and the
//! exact ω² and modes against the numeric eigen-solver at random parameter
//! values; the command line's exit codes, errors and JSON contract.

use crate::common::run::{json, keys, qdot, qdot_on};
use proptest::test_runner::{Config, TestRunner};
use qdot::expr::atom::{self, Atom};
use qdot::solve::eigen::{distribution_coefficients, generalized_symmetric};
use qdot::solve::equilibrium::Values;
use qdot::solve::oscillations::{
    damped_steady_state, forced_amplitudes, free_response, modes, numeric_free_response,
    standard_form, Modes, Motion, Stability,
};
use qdot::{Expr, Scene};
use serde_json::Value;

// ------------------------------------------------------------------ scenes

/// Two equal pendulums (mass m, length l) hanging one from the other.
const DOUBLE_PENDULUM: &str = "\
coordinates th1, th2
parameters m, l, g
x1 = l*sin(th1)
y1 = -l*cos(th1)
x2 = x1 + l*sin(th2)
y2 = y1 - l*cos(th2)
kinetic E1 = 1/2*m*(x1'^2 + y1'^2)
kinetic E2 = 1/2*m*(x2'^2 + y2'^2)
potential V = m*g*y1 + m*g*y2
";

/// Three equal masses in a line, four equal springs, both ends fixed.
const CHAIN: &str = "\
coordinates x1, x2, x3
parameters m, k
kinetic E = 1/2*m*(x1'^2 + x2'^2 + x3'^2)
potential V = 1/2*k*(x1^2 + (x2 - x1)^2 + (x3 - x2)^2 + x3^2)
";

/// The same chain with unequal masses and springs (a general cubic).
const CHAIN_UNEQUAL: &str = "\
coordinates x1, x2, x3
parameters m1, m2, m3, k1, k2, k3, k4
kinetic E = 1/2*(m1*x1'^2 + m2*x2'^2 + m3*x3'^2)
potential V = 1/2*(k1*x1^2 + k2*(x2 - x1)^2 + k3*(x3 - x2)^2 + k4*x3^2)
";

/// A cart (mass M0) on a spring k with a pendulum (m, l) hanging from it.
const CART_PENDULUM: &str = "\
coordinates x, th
parameters M0, m, l, k, g
xb = x + l*sin(th)
yb = -l*cos(th)
kinetic E = 1/2*M0*x'^2 + 1/2*m*(xb'^2 + yb'^2)
potential V = 1/2*k*x^2 + m*g*yb
";

/// A simple pendulum (rod angle th from the downward vertical).
const PENDULUM: &str = "\
coordinates th
parameters m, l, g
kinetic E = 1/2*m*l^2*th'^2
potential V = -m*g*l*cos(th)
";

/// 24.2 with a force F0·cos(p·t) on body 1.
const FORCED_24_2: &str = "\
coordinates x1, x2
parameters m, k, R, F0, p
kinetic E1 = 1/2*4*m*x1'^2
kinetic E2 = 1/2*m*x2'^2 + 1/2*(m*R^2/2)*(x2'/R)^2
forcefunction U = -1/2*k*x1^2 - 1/2*k*(x2 - x1)^2
work L = F0*cos(p*t)*x1
";

// ------------------------------------------------------------------ helpers

fn parse(src: &str) -> Scene {
    Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene.qd", src)))
}

fn example_src(name: &str) -> String {
    let path = format!("{}/examples/{name}.qd", env!("QDOT_ROOT"));
    std::fs::read_to_string(&path).expect("example exists")
}

fn example(name: &str) -> Scene {
    parse(&example_src(name))
}

fn set(pairs: &[(&str, f64)]) -> Values {
    let mut v = Values::default();
    for (k, x) in pairs {
        v.insert(k.to_string(), *x);
    }
    v
}

/// The modes about q = 0 with no parameter values.
fn linearize(s: &Scene) -> Modes {
    linearize_at(s, None, &Values::default())
}

fn linearize_at(s: &Scene, at: Option<&[Expr]>, values: &Values) -> Modes {
    modes(s, at, values).unwrap_or_else(|d| panic!("modes failed: {}", d.message))
}

fn ex(s: &Scene, src: &str) -> Expr {
    s.expr(src)
        .unwrap_or_else(|d| panic!("`{src}` does not parse: {}", d.message))
}

fn lambda() -> Expr {
    Expr::unknown("lambda")
}

/// Exact equality, showing both sides on failure.
#[track_caller]
fn assert_exact(s: &Scene, got: &Expr, want: &str) {
    let w = ex(s, want);
    assert!(got.equals(&w), "got {got}, want {want} (= {w})");
}

#[track_caller]
fn assert_matrix(s: &Scene, got: &[Vec<Expr>], want: &[&[&str]]) {
    assert_eq!(got.len(), want.len(), "rows");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.len(), w.len(), "row {i}");
        for (j, (g, w)) in g.iter().zip(w.iter()).enumerate() {
            let we = ex(s, w);
            assert!(g.equals(&we), "[{i}][{j}]: got {g}, want {w}");
        }
    }
}

#[track_caller]
fn assert_list(s: &Scene, got: &[Expr], want: &[&str]) {
    let shown: Vec<String> = got.iter().map(|e| e.to_string()).collect();
    assert_eq!(got.len(), want.len(), "got {shown:?}, want {want:?}");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        let we = ex(s, w);
        assert!(g.equals(&we), "[{i}]: got {g}, want {w}");
    }
}

/// det(K − λ·M) at λ = `root`, exactly.
fn characteristic_at(md: &Modes, root: &Expr) -> Expr {
    md.characteristic
        .subs(atom::unknown("lambda"), root)
        .expect("substitution")
}

/// (K − ω²·M)·mode, exactly, for mode i.
fn residual(md: &Modes, i: usize) -> Vec<Expr> {
    let w2 = &md.omega_squared[i];
    let x = &md.modes[i];
    (0..x.len())
        .map(|r| {
            (0..x.len()).fold(Expr::zero(), |acc, c| {
                let a = md.stiffness[r][c].sub(&w2.mul(&md.mass[r][c]));
                acc.add(&a.mul(&x[c]))
            })
        })
        .collect()
}

/// Every ω² is a root of det(K − λ·M), every mode a null vector of
/// K − ω²·M with first entry 1, and det(K − λ·M) is the product of its
/// factors.
#[track_caller]
fn assert_consistent(md: &Modes) {
    let n = md.coordinates.len();
    assert_eq!(md.omega_squared.len(), n, "one ω² per coordinate");
    assert_eq!(md.modes.len(), n);
    for (i, w2) in md.omega_squared.iter().enumerate() {
        let d = characteristic_at(md, w2);
        assert!(d.is_zero(), "det(K − ω{i}²·M) = {d} ≠ 0 for ω² = {w2}");
        let first = md.modes[i].iter().find(|x| !x.is_zero());
        assert!(
            first.is_some_and(|x| x.is_one()),
            "mode {i} is not normalized: {:?}",
            md.modes[i]
        );
        for r in residual(md, i) {
            assert!(r.is_zero(), "(K − ω²M)·mode {i} = {r} ≠ 0");
        }
    }
    let prod = md.factors.iter().fold(Expr::one(), |a, f| a.mul(f));
    assert!(
        prod.equals(&md.characteristic),
        "Π factors = {prod} ≠ det = {}",
        md.characteristic
    );
}

/// Parameter values for `eval_f64`.
fn env<'a>(values: &'a [(&'a str, f64)]) -> impl Fn(&Atom) -> Option<f64> + 'a {
    move |a: &Atom| match a {
        Atom::Param(n) => values.iter().find(|(k, _)| **k == **n).map(|(_, v)| *v),
        _ => None,
    }
}

fn eval(e: &Expr, values: &[(&str, f64)]) -> f64 {
    let f = env(values);
    e.eval_f64(&f)
        .unwrap_or_else(|| panic!("{e} does not evaluate at {values:?}"))
}

fn eval_matrix(m: &[Vec<Expr>], values: &[(&str, f64)]) -> Vec<Vec<f64>> {
    m.iter()
        .map(|r| r.iter().map(|e| eval(e, values)).collect())
        .collect()
}

/// The time derivative of q(t).
fn dt(e: &Expr) -> Expr {
    e.diff(atom::time())
}

/// q(t) at t = 0.
fn at_t0(e: &Expr) -> Expr {
    e.subs(atom::time(), &Expr::zero()).expect("t = 0")
}

/// The free response satisfies M·q̈ + K·q = 0 and the initial conditions,
/// exactly.
#[track_caller]
fn assert_free_response(md: &Modes, q: &[Expr], q0: &[Expr], v0: &[Expr]) {
    let n = q.len();
    for j in 0..n {
        let x0 = at_t0(&q[j]);
        assert!(x0.equals(&q0[j]), "q{j}(0) = {x0}, want {}", q0[j]);
        let xd0 = at_t0(&dt(&q[j]));
        assert!(xd0.equals(&v0[j]), "q{j}'(0) = {xd0}, want {}", v0[j]);
    }
    let qdd: Vec<Expr> = q.iter().map(|x| dt(&dt(x))).collect();
    for r in 0..n {
        let mut eq = Expr::zero();
        for c in 0..n {
            eq = eq
                .add(&md.mass[r][c].mul(&qdd[c]))
                .add(&md.stiffness[r][c].mul(&q[c]));
        }
        assert!(eq.is_zero(), "(M·q̈ + K·q)[{r}] = {eq} ≠ 0");
    }
}

// ------------------------------------------------------------------ 24.1

/// Seed 24.1 (examples/seed_24_1.qd), q = y1.
///
/// E = ½·m·ẏ² + ½·(4mr²)·(ẏ/r)² + ½·(3m·(6r)²/3)·(ẏ/(3r))² = (½ + 2 + 2)·m·ẏ²
///   ⇒ M = 9m.
/// U = −½·k·(4r·y/(3r))² + 3m·g·3r·(1 − cos(y/(3r))) = −8/9·k·y² + 9mgr·(1 − cos(y/(3r)))
///   ⇒ Q_U = −16/9·k·y + 3mg·sin(y/(3r)) ≈ −(16k/9 − mg/r)·y ⇒ K = 16k/9 − mg/r.
/// D = −½·c·(2r·ẏ/(3r))² = −2/9·c·ẏ² ⇒ Q_D = −4/9·c·ẏ ⇒ C = 4c/9.
/// L = F0·cos(p·t)·y ⇒ f = F0·cos(p·t).
/// Standard form: ω² = K/M = 16k/(81m) − g/(9r), 2α = C/M = 4c/(81m) ⇒ α = 2c/(81m),
/// f/M = F0·cos(p·t)/(9m).
#[test]
fn seed_24_1_linearization_and_standard_form() {
    let s = example("seed_24_1");
    let md = linearize(&s);
    assert_eq!(md.coordinates, ["y1"]);
    assert_list(&s, &md.at, &["0"]);
    assert_matrix(&s, &md.mass, &[&["9*m"]]);
    assert_matrix(&s, &md.damping, &[&["4*c/9"]]);
    assert_matrix(&s, &md.stiffness, &[&["16*k/9 - m*g/r"]]);
    assert_list(&s, &md.forcing, &["F0*cos(p*t)"]);
    // det(K − λ·M) = 16k/9 − mg/r − 9m·λ
    let want = ex(&s, "16*k/9 - m*g/r").sub(&lambda().mul(&ex(&s, "9*m")));
    assert!(md.characteristic.equals(&want), "{}", md.characteristic);
    assert_list(&s, &md.omega_squared, &["16*k/(81*m) - g/(9*r)"]);
    assert_list(&s, &md.modes[0], &["1"]);
    assert_consistent(&md);

    let sf = standard_form(&md, &Values::default()).expect("one coordinate");
    assert_exact(&s, &sf.omega_squared, "16*k/(81*m) - g/(9*r)");
    assert_exact(&s, &sf.alpha, "2*c/(81*m)");
    assert_exact(&s, &sf.forcing, "F0*cos(p*t)/(9*m)");
    // ζ = α/ω: ζ² = α²/ω² exactly
    let zeta = sf.zeta.clone().expect("ω² ≠ 0");
    let want = ex(&s, "(2*c/(81*m))^2/(16*k/(81*m) - g/(9*r))");
    assert!(zeta.mul(&zeta).equals(&want), "ζ = {zeta}");
    // the sign of α² − ω² depends on the parameters
    assert!(sf.regime.starts_with("underdamped when"), "{}", sf.regime);
}

/// Steady state of 24.1 (undamped part): (K − p²·M)·X = F0 ⇒
/// X = F0/(16k/9 − mg/r − 9m·p²).
#[test]
fn seed_24_1_forced_amplitude() {
    let s = example("seed_24_1");
    let md = linearize(&s);
    let (p, x) = forced_amplitudes(&md).expect("a cos(p·t) load");
    assert_exact(&s, &p, "p");
    assert_list(&s, &x, &["F0/(16*k/9 - m*g/r - 9*m*p^2)"]);
}

/// The damped steady state of 24.1, y = X·cos(p·t − ψ) (the seed's 24.3):
/// X = (F0/(9m))/√((ω² − p²)² + 4α²p²), tan ψ = 2αp/(ω² − p²) with
/// ω² = 16k/(81m) − g/(9r), α = 2c/(81m); X is checked through X².
#[test]
fn seed_24_1_damped_steady_state() {
    let s = example("seed_24_1");
    let md = linearize(&s);
    let sf = standard_form(&md, &Values::default()).expect("one coordinate");
    let (p, x, tan_psi) = damped_steady_state(&md, &sf).expect("a cos(p·t) load");
    assert_exact(&s, &p, "p");
    let w2 = "(16*k/(81*m) - g/(9*r))";
    assert_exact(
        &s,
        &x.mul(&x),
        &format!("(F0/(9*m))^2/(({w2} - p^2)^2 + 4*(2*c/(81*m))^2*p^2)"),
    );
    assert_exact(&s, &tan_psi, &format!("2*(2*c/(81*m))*p/({w2} - p^2)"));
}

/// With m = r = c = F0 = p = 1, g = 9.81: ω² = 16k/81 − 9.81/9 = 16k/81 − 1.09,
/// > 0 for k = 10 (1.975 − 1.09), < 0 for k = 1 (0.198 − 1.09).
#[test]
fn seed_24_1_stability_depends_on_the_spring() {
    let s = example("seed_24_1");
    let md = linearize(&s);
    match &md.stability {
        Stability::Undecided(why) => assert!(why.contains("--set"), "{why}"),
        other => panic!("want undecided without values, got {other:?}"),
    }
    let stiff = set(&[
        ("m", 1.0),
        ("r", 1.0),
        ("k", 10.0),
        ("c", 1.0),
        ("g", 9.81),
        ("F0", 1.0),
        ("p", 1.0),
    ]);
    assert_eq!(linearize_at(&s, None, &stiff).stability, Stability::Stable);
    let mut soft = stiff.clone();
    soft.insert("k".into(), 1.0);
    assert_eq!(linearize_at(&s, None, &soft).stability, Stability::Unstable);
}

/// The damping regime from the sign of α² − ω² at given values. With
/// m = r = 1, g = 9: ω² = 16k/81 − 1 and α = 2c/81. k = 81/8 gives ω² = 1;
/// c = 81/2 gives α = 1 (critical), c = 1 gives α² ≪ 1 (under), c = 81
/// gives α = 2 (over).
#[test]
fn seed_24_1_damping_regimes() {
    let s = example("seed_24_1");
    let md = linearize(&s);
    let regime = |c: f64| {
        let v = set(&[
            ("m", 1.0),
            ("r", 1.0),
            ("k", 81.0 / 8.0),
            ("c", c),
            ("g", 9.0),
            ("F0", 1.0),
            ("p", 1.0),
        ]);
        standard_form(&md, &v).expect("one coordinate").regime
    };
    assert_eq!(regime(1.0), "underdamped");
    assert_eq!(regime(40.5), "critically damped");
    assert_eq!(regime(81.0), "overdamped");
}

#[test]
fn seed_24_1_cli() {
    let (code, out, err) = qdot(&["modes", "examples/seed_24_1.qd"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.is_empty());
    let values = "m=1,r=1,k=10,c=1,g=9.81,F0=1,p=1";
    let v = json_of(&[
        "modes",
        "examples/seed_24_1.qd",
        "--format",
        "json",
        "--set",
        values,
    ]);
    assert_eq!(v["stability"], "stable");
    let num = v["numeric_omega_squared"].as_array().expect("numeric ω²");
    let want = 16.0 * 10.0 / 81.0 - 9.81 / 9.0;
    assert_eq!(num.len(), 1);
    assert!((num[0].as_f64().unwrap() - want).abs() <= 1e-12 * want);
    let v = json_of(&[
        "modes",
        "examples/seed_24_1.qd",
        "--format",
        "json",
        "--set",
        "m=1,r=1,k=1,c=1,g=9.81,F0=1,p=1",
    ]);
    assert_eq!(v["stability"], "unstable");
    let v = json_of(&["modes", "examples/seed_24_1.qd", "--format", "json"]);
    assert_eq!(v["stability"], "undecided");
    assert_eq!(v["numeric_omega_squared"], Value::Null);
}

// ------------------------------------------------------------------ 24.2

/// Seed 24.2 (examples/seed_24_2.qd).
///
/// E = ½·4m·ẋ1² + ½·m·ẋ2² + ½·(mR²/2)·(ẋ2/R)² = 2m·ẋ1² + ¾·m·ẋ2² ⇒ M = diag(4m, 3m/2).
/// V = ½k·x1² + ½k·(x2 − x1)² ⇒ K = [[2k, −k], [−k, k]].
/// det(K − λM) = (2k − 4mλ)(k − 3mλ/2) − k² = k² − 7kmλ + 6m²λ² = (k − mλ)(k − 6mλ)
/// ⇒ ω1² = k/(6m), ω2² = k/m. Row 1: (2k − 4mλ) − k·μ = 0 ⇒ μ = 2 − 4mλ/k:
/// μ1 = 2 − 2/3 = 4/3, μ2 = 2 − 4 = −2.
#[test]
fn seed_24_2_frequencies_and_modes() {
    let s = example("seed_24_2");
    let md = linearize(&s);
    assert_eq!(md.coordinates, ["x1", "x2"]);
    assert_matrix(&s, &md.mass, &[&["4*m", "0"], &["0", "3*m/2"]]);
    assert_matrix(&s, &md.stiffness, &[&["2*k", "-k"], &["-k", "k"]]);
    assert_matrix(&s, &md.damping, &[&["0", "0"], &["0", "0"]]);
    assert_list(&s, &md.forcing, &["0", "0"]);
    let (m, k, l) = (ex(&s, "m"), ex(&s, "k"), lambda());
    let product = k.sub(&m.mul(&l)).mul(&k.sub(&ex(&s, "6*m").mul(&l)));
    assert!(
        md.characteristic.equals(&product),
        "det = {}",
        md.characteristic
    );
    // a polynomial: the canonical form is unique
    assert_eq!(md.characteristic, product);
    assert_list(&s, &md.omega_squared, &["k/(6*m)", "k/m"]);
    assert_list(&s, &md.modes[0], &["1", "4/3"]);
    assert_list(&s, &md.modes[1], &["1", "-2"]);
    assert_eq!(md.stability, Stability::Stable);
    assert_consistent(&md);
    // the factors are k − 6mλ and k − mλ, up to a constant
    let nonconstant: Vec<&Expr> = md
        .factors
        .iter()
        .filter(|f| f.depends_on(atom::unknown("lambda")))
        .collect();
    assert_eq!(nonconstant.len(), 2, "{:?}", md.factors);
    assert!(standard_form(&md, &Values::default()).is_none());
    assert!(
        forced_amplitudes(&md).is_none(),
        "no load, no forced response"
    );
}

/// Free response from x1(0) = 1 (x2(0) = ẋ1(0) = ẋ2(0) = 0): q = a1·u1·cos ω1t +
/// a2·u2·cos ω2t with a1·(1, 4/3) + a2·(1, −2) = (1, 0): a1 + a2 = 1,
/// 4/3·a1 = 2·a2 ⇒ a1 = 3/5, a2 = 2/5:
/// x1 = (3·cos ω1t + 2·cos ω2t)/5, x2 = (4·cos ω1t − 4·cos ω2t)/5.
#[test]
fn seed_24_2_free_response() {
    let s = example("seed_24_2");
    let md = linearize(&s);
    let (q0, v0) = (vec![Expr::one(), Expr::zero()], vec![Expr::zero(); 2]);
    let q = free_response(&md, &q0, &v0).expect("free response");
    assert_list(
        &s,
        &q,
        &[
            "3/5*cos(sqrt(k/(6*m))*t) + 2/5*cos(sqrt(k/m)*t)",
            "4/5*cos(sqrt(k/(6*m))*t) - 4/5*cos(sqrt(k/m)*t)",
        ],
    );
    assert_free_response(&md, &q, &q0, &v0);

    // with velocities too (the sin terms): any q0, v0 in the scene's names
    let q0 = vec![ex(&s, "1/10"), ex(&s, "-R/3")];
    let v0 = vec![ex(&s, "sqrt(k/m)"), ex(&s, "2")];
    let q = free_response(&md, &q0, &v0).expect("free response");
    assert_free_response(&md, &q, &q0, &v0);

    // the command line gives the same
    let v = json_of(&[
        "modes",
        "examples/seed_24_2.qd",
        "--format",
        "json",
        "--init",
        "x1=1/10,x2=-R/3,x1'=sqrt(k/m),x2'=2",
    ]);
    let fr = v["free_response"].as_object().expect("free_response");
    assert_eq!(
        fr.keys().map(String::as_str).collect::<Vec<_>>(),
        ["x1", "x2"]
    );
    for (j, c) in ["x1", "x2"].iter().enumerate() {
        let got = reparse(&s, "free_response", &fr[*c]);
        assert!(got.equals(&q[j]), "{c}: {got} vs {}", q[j]);
    }
}

/// 24.2 with F0·cos(p·t) on body 1: (K − p²M)·X = (F0, 0), det(K − p²M) =
/// (k − mp²)(k − 6mp²), X1 = F0·(k − 3mp²/2)/det, X2 = F0·k/det.
#[test]
fn seed_24_2_forced_on_body_1() {
    let s = parse(FORCED_24_2);
    let md = linearize(&s);
    assert_list(&s, &md.forcing, &["F0*cos(p*t)", "0"]);
    assert_list(&s, &md.omega_squared, &["k/(6*m)", "k/m"]);
    let (p, x) = forced_amplitudes(&md).expect("a cos(p·t) load");
    assert_exact(&s, &p, "p");
    assert_list(
        &s,
        &x,
        &[
            "F0*(k - 3*m*p^2/2)/((k - m*p^2)*(k - 6*m*p^2))",
            "F0*k/((k - m*p^2)*(k - 6*m*p^2))",
        ],
    );
}

#[test]
fn seed_24_2_cli() {
    let (code, out, err) = qdot(&["modes", "examples/seed_24_2.qd"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.is_empty());
    let (code, _, err) = qdot(&["modes", "examples/seed_24_2.qd", "--init", "x1=1"]);
    assert_eq!(code, 0, "{err}");
    let v = json_of(&[
        "modes",
        "examples/seed_24_2.qd",
        "--format",
        "json",
        "--set",
        "m=2,k=3,R=1",
    ]);
    assert_eq!(v["stability"], "stable");
    let num: Vec<f64> = v["numeric_omega_squared"]
        .as_array()
        .expect("numeric ω²")
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    // k/(6m) = 1/4, k/m = 3/2
    assert_eq!(num.len(), 2);
    assert!((num[0] - 0.25).abs() <= 1e-12 && (num[1] - 1.5).abs() <= 1e-12);
}

// ------------------------------------------------------------------ scenes no example uses

/// Double pendulum, equal m and l, about th1 = th2 = 0.
///
/// E = ½m·l²·θ̇1² + ½m·(l²θ̇1² + l²θ̇2² + 2l²·cos(θ1 − θ2)·θ̇1θ̇2) ⇒
/// M = [[2ml², ml²], [ml², ml²]]; V = −2mgl·cos θ1 − mgl·cos θ2 ⇒ K = diag(2mgl, mgl).
/// det(K − λM) = 2m²l²(g − lλ)² − m²l⁴λ² = m²l²·(2(g − lλ)² − l²λ²) ⇒
/// √2·(g − lλ) = ±lλ ⇒ λ = √2/(√2 ± 1)·g/l = (2 ∓ √2)·g/l.
/// Row 1: 2ml²(g/l − λ)·1 − ml²λ·μ = 0 ⇒ μ = 2(g − lλ)/(lλ) = ±√2.
#[test]
fn double_pendulum() {
    let s = parse(DOUBLE_PENDULUM);
    let md = linearize(&s);
    assert_matrix(&s, &md.mass, &[&["2*m*l^2", "m*l^2"], &["m*l^2", "m*l^2"]]);
    assert_matrix(&s, &md.stiffness, &[&["2*m*g*l", "0"], &["0", "m*g*l"]]);
    let l2 = lambda().mul(&lambda());
    let want = ex(&s, "m^2*l^2").mul(
        &ex(&s, "2*g^2")
            .sub(&ex(&s, "4*g*l").mul(&lambda()))
            .add(&ex(&s, "l^2").mul(&l2)),
    );
    assert!(md.characteristic.equals(&want), "{}", md.characteristic);
    assert_list(
        &s,
        &md.omega_squared,
        &["(2 - sqrt(2))*g/l", "(2 + sqrt(2))*g/l"],
    );
    assert_list(&s, &md.modes[0], &["1", "sqrt(2)"]);
    assert_list(&s, &md.modes[1], &["1", "-sqrt(2)"]);
    assert_consistent(&md);
}

/// (2 ∓ √2)·g/l > 0 for every positive g, l: the sign of the number 2 − √2
/// is decidable exactly, so the equilibrium is stable without --set.
#[test]
fn double_pendulum_is_stable() {
    let s = parse(DOUBLE_PENDULUM);
    assert_eq!(linearize(&s).stability, Stability::Stable);
}

/// Double pendulum about th1 = π, th2 = 0 (upper rod up, lower rod down:
/// Q1 = −2mgl·sin θ1 = 0, Q2 = −mgl·sin θ2 = 0). cos(θ1 − θ2) = −1 ⇒
/// M = [[2ml², −ml²], [−ml², ml²]]; K = diag(2mgl·cos π, mgl) = diag(−2mgl, mgl).
/// det(K − λM) = (−2mgl − 2ml²λ)(mgl − ml²λ) − m²l⁴λ² = m²l²·(l²λ² − 2g²)
/// ⇒ ω² = ∓√2·g/l: unstable. Row 1: −2ml²(g/l + λ) + ml²λ·μ = 0 ⇒
/// μ = 2(g + lλ)/(lλ) = 2 − √2 (λ = −√2g/l) and 2 + √2 (λ = √2g/l).
#[test]
fn double_pendulum_upper_rod_up() {
    let s = parse(DOUBLE_PENDULUM);
    let at = [Expr::pi(), Expr::zero()];
    let md = linearize_at(&s, Some(&at), &Values::default());
    assert_list(&s, &md.at, &["pi", "0"]);
    assert_matrix(
        &s,
        &md.mass,
        &[&["2*m*l^2", "-m*l^2"], &["-m*l^2", "m*l^2"]],
    );
    assert_matrix(&s, &md.stiffness, &[&["-2*m*g*l", "0"], &["0", "m*g*l"]]);
    assert_list(&s, &md.omega_squared, &["-sqrt(2)*g/l", "sqrt(2)*g/l"]);
    assert_list(&s, &md.modes[0], &["1", "2 - sqrt(2)"]);
    assert_list(&s, &md.modes[1], &["1", "2 + sqrt(2)"]);
    assert_eq!(md.stability, Stability::Unstable);
    assert_consistent(&md);
    // the same through the command line (th2 defaults to 0)
    let (code, out, err) = qdot_on(
        "modes",
        "dp_up",
        DOUBLE_PENDULUM,
        "modes",
        &["--at", "th1=pi", "--format", "json"],
    );
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    assert_eq!(v["at"], serde_json::json!({"th1": "pi", "th2": "0"}));
    assert_eq!(v["stability"], "unstable");
    check_json(&s, &v, &Values::default(), Some(&at), None);
}

/// Three equal masses, four equal springs: M = m·I,
/// K = k·[[2, −1, 0], [−1, 2, −1], [0, −1, 2]]; the eigenvalues of the
/// tridiagonal (2, −1) matrix are 2 − 2cos(jπ/4) = 2 − √2, 2, 2 + √2 with
/// eigenvectors sin(jπ·i/4) ∝ (1, √2, 1), (1, 0, −1), (1, −√2, 1).
/// det(K − λM) = −m³λ³ + 6km²λ² − 10k²mλ + 4k³ (sum 6, pairwise sum
/// 2(2 − √2) + 2(2 + √2) + 2 = 10, product 2·2 = 4, all times k/m).
#[test]
fn three_mass_chain() {
    let s = parse(CHAIN);
    let md = linearize(&s);
    assert_matrix(
        &s,
        &md.mass,
        &[&["m", "0", "0"], &["0", "m", "0"], &["0", "0", "m"]],
    );
    assert_matrix(
        &s,
        &md.stiffness,
        &[
            &["2*k", "-k", "0"],
            &["-k", "2*k", "-k"],
            &["0", "-k", "2*k"],
        ],
    );
    let l = lambda();
    let want = ex(&s, "-m^3")
        .mul(&l.powi(3).unwrap())
        .add(&ex(&s, "6*k*m^2").mul(&l.powi(2).unwrap()))
        .sub(&ex(&s, "10*k^2*m").mul(&l))
        .add(&ex(&s, "4*k^3"));
    assert!(md.characteristic.equals(&want), "{}", md.characteristic);
    assert_list(
        &s,
        &md.omega_squared,
        &["(2 - sqrt(2))*k/m", "2*k/m", "(2 + sqrt(2))*k/m"],
    );
    assert_list(&s, &md.modes[0], &["1", "sqrt(2)", "1"]);
    assert_list(&s, &md.modes[1], &["1", "0", "-1"]);
    assert_list(&s, &md.modes[2], &["1", "-sqrt(2)", "1"]);
    assert_consistent(&md);
}

#[test]
fn three_mass_chain_is_stable() {
    let s = parse(CHAIN);
    assert_eq!(linearize(&s).stability, Stability::Stable);
}

/// Unequal masses and springs: det(K − λM) is a general cubic in λ whose
/// roots have no closed form here (three real roots: casus irreducibilis);
/// the library says so (no ω²) and the command line falls back to the
/// numeric eigen-solver with --set. K is positive definite for positive
/// springs (Sylvester's criterion), so the chain is stable all the same.
/// With m = (1, 2, 3), k = (1, 2, 3, 4) the numeric ω² must agree with
/// `generalized_symmetric` on the same M and K.
#[test]
fn unequal_chain_has_no_closed_form() {
    let s = parse(CHAIN_UNEQUAL);
    let md = linearize(&s);
    assert_matrix(
        &s,
        &md.stiffness,
        &[
            &["k1 + k2", "-k2", "0"],
            &["-k2", "k2 + k3", "-k3"],
            &["0", "-k3", "k3 + k4"],
        ],
    );
    assert!(md.omega_squared.is_empty() && md.modes.is_empty());
    assert!(
        md.no_closed_form
            .as_deref()
            .is_some_and(|w| w.contains("casus irreducibilis")),
        "{:?}",
        md.no_closed_form
    );
    assert_eq!(md.stability, Stability::Stable);
    let q0 = [Expr::one(), Expr::zero(), Expr::zero()];
    let v0 = vec![Expr::zero(); 3];
    assert!(free_response(&md, &q0, &v0).is_err());
    let values = "m1=1,m2=2,m3=3,k1=1,k2=2,k3=3,k4=4";
    let (code, out, err) = qdot_on(
        "modes",
        "chain3",
        CHAIN_UNEQUAL,
        "modes",
        &["--format", "json", "--set", values],
    );
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    let num: Vec<f64> = v["numeric_omega_squared"]
        .as_array()
        .expect("numeric ω²")
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let vals = [
        ("m1", 1.0),
        ("m2", 2.0),
        ("m3", 3.0),
        ("k1", 1.0),
        ("k2", 2.0),
        ("k3", 3.0),
        ("k4", 4.0),
    ];
    let e = generalized_symmetric(
        &eval_matrix(&md.stiffness, &vals),
        &eval_matrix(&md.mass, &vals),
    )
    .unwrap();
    assert_eq!(num.len(), 3);
    for (a, b) in num.iter().zip(&e.values) {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs(),
            "{num:?} vs {:?}",
            e.values
        );
    }
    // the free response needs closed forms: a clear error
    let (code, _, err) = qdot_on(
        "modes",
        "chain3_init",
        CHAIN_UNEQUAL,
        "modes",
        &["--init", "x1=1"],
    );
    assert_eq!(code, 1);
    assert!(err.contains("closed form"), "{err}");
}

/// Cart x (M0) on a spring k, pendulum th (m, l). The bob is at
/// (x + l·sin θ, −l·cos θ):
/// E = ½(M0 + m)ẋ² + m·l·cos θ·ẋθ̇ + ½m·l²θ̇² ⇒ M = [[M0 + m, ml], [ml, ml²]];
/// V = ½k·x² − mgl·cos θ ⇒ K = diag(k, mgl).
/// det(K − λM) = (k − (M0 + m)λ)(mgl − ml²λ) − m²l²λ²
///             = ml·(M0·l·λ² − (kl + (M0 + m)g)·λ + kg)
/// ⇒ λ = (B ∓ √(B² − 4·M0·l·k·g))/(2·M0·l), B = kl + (M0 + m)g.
/// Row 1: (k − (M0 + m)λ) − ml·λ·μ = 0 ⇒ μ = (k − (M0 + m)λ)/(mlλ).
#[test]
fn cart_with_pendulum() {
    let s = parse(CART_PENDULUM);
    let md = linearize(&s);
    assert_matrix(&s, &md.mass, &[&["M0 + m", "m*l"], &["m*l", "m*l^2"]]);
    assert_matrix(&s, &md.stiffness, &[&["k", "0"], &["0", "m*g*l"]]);
    let l = lambda();
    let want = ex(&s, "m*l").mul(
        &ex(&s, "M0*l")
            .mul(&l.mul(&l))
            .sub(&ex(&s, "k*l + (M0 + m)*g").mul(&l))
            .add(&ex(&s, "k*g")),
    );
    assert!(md.characteristic.equals(&want), "{}", md.characteristic);
    let b = "(k*l + (M0 + m)*g)";
    let disc = format!("sqrt({b}^2 - 4*M0*l*k*g)");
    assert_list(
        &s,
        &md.omega_squared,
        &[
            &format!("({b} - {disc})/(2*M0*l)"),
            &format!("({b} + {disc})/(2*M0*l)"),
        ],
    );
    // Vieta: ω1² + ω2² = B/(M0·l), ω1²·ω2² = k·g/(M0·l)
    let (w1, w2) = (&md.omega_squared[0], &md.omega_squared[1]);
    assert_exact(&s, &w1.add(w2), &format!("{b}/(M0*l)"));
    assert_exact(&s, &w1.mul(w2), "k*g/(M0*l)");
    for (i, w) in md.omega_squared.iter().enumerate() {
        let mu = ex(&s, "k").sub(&ex(&s, "M0 + m").mul(w));
        let mu = mu.div(&ex(&s, "m*l").mul(w)).unwrap();
        assert!(md.modes[i][1].equals(&mu), "mode {i}: {}", md.modes[i][1]);
    }
    assert_consistent(&md);
    // both ω² are positive for all positive parameters (B² − 4M0·l·k·g =
    // (kl − M0·g)² + … > 0 and B > √(…)); the library may not prove it
    // without values, but it must never call this unstable
    assert_ne!(md.stability, Stability::Unstable);
    let values = set(&[("M0", 2.0), ("m", 1.0), ("l", 0.5), ("k", 3.0), ("g", 9.81)]);
    assert_eq!(linearize_at(&s, None, &values).stability, Stability::Stable);
}

/// A pendulum about its upright equilibrium th = π: M = ml², K = ∂²V/∂θ² =
/// mgl·cos π = −mgl ⇒ ω² = −g/l < 0: unstable.
#[test]
fn inverted_pendulum() {
    let s = parse(PENDULUM);
    let md = linearize_at(&s, Some(&[Expr::pi()]), &Values::default());
    assert_matrix(&s, &md.mass, &[&["m*l^2"]]);
    assert_matrix(&s, &md.stiffness, &[&["-m*g*l"]]);
    assert_list(&s, &md.omega_squared, &["-g/l"]);
    assert_eq!(md.stability, Stability::Unstable);
    assert_consistent(&md);
    // hanging down: ω² = g/l, stable
    let md = linearize(&s);
    assert_list(&s, &md.omega_squared, &["g/l"]);
    assert_eq!(md.stability, Stability::Stable);

    let (code, out, err) = qdot_on(
        "modes",
        "pendulum_up",
        PENDULUM,
        "modes",
        &["--at", "th=pi", "--format", "json"],
    );
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    assert_eq!(v["at"], serde_json::json!({"th": "pi"}));
    assert_eq!(v["omega_squared"], serde_json::json!(["-g/l"]));
    assert_eq!(v["stability"], "unstable");
    let (code, _, err) = qdot_on(
        "modes",
        "pendulum_up_text",
        PENDULUM,
        "modes",
        &["--at", "th=pi"],
    );
    assert_eq!(code, 0, "{err}");
}

/// th = π/2 is not an equilibrium: Q = −mgl·sin θ = −mgl ≠ 0.
#[test]
fn not_an_equilibrium_is_an_error() {
    let s = parse(PENDULUM);
    let at = [ex(&s, "pi/2")];
    let err = modes(&s, Some(&at), &Values::default()).expect_err("not an equilibrium");
    assert!(
        err.message.contains("is not an equilibrium"),
        "{}",
        err.message
    );
    let (code, out, err) = qdot_on(
        "modes",
        "pendulum_side",
        PENDULUM,
        "modes",
        &["--at", "th=pi/2"],
    );
    assert_eq!(code, 1, "{out}");
    assert!(err.contains("is not an equilibrium"), "{err}");
    // a spring with a constant load is not in equilibrium at x = 0 either
    let src = "coordinates x\nparameters m, k, G\nkinetic E = 1/2*m*x'^2\n\
               forcefunction U = G*x - 1/2*k*x^2\n";
    let (code, _, err) = qdot_on("modes", "loaded", src, "modes", &[]);
    assert_eq!(code, 1);
    assert!(err.contains("is not an equilibrium"), "{err}");
    // …but it is at x = G/k: ω² = k/m
    let s = parse(src);
    let md = linearize_at(&s, Some(&[ex(&s, "G/k")]), &Values::default());
    assert_list(&s, &md.omega_squared, &["k/m"]);
    let (code, _, err) = qdot_on("modes", "loaded_at", src, "modes", &["--at", "x=G/k"]);
    assert_eq!(code, 0, "{err}");
}

/// Bad options: exit 1 with a message naming the problem.
#[test]
fn bad_options_are_errors() {
    let cases: &[(&[&str], &str)] = &[
        (&["--at", "phi=0"], "not a coordinate"),
        (&["--at", "x1"], "expected name=value"),
        (&["--at", "x1=zz"], "--at"),
        (&["--init", "y=1"], "not a coordinate"),
        (&["--init", "x1'=)"], "--init"),
        (&["--set", "q=1"], "not a parameter"),
    ];
    for (args, want) in cases {
        let mut all = vec!["modes", "examples/seed_24_2.qd"];
        all.extend_from_slice(args);
        let (code, out, err) = qdot(&all);
        assert_eq!(code, 1, "{args:?}: {out}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    let (code, _, err) = qdot(&["modes", "examples/no_such_file.qd"]);
    assert_eq!(code, 1, "{err}");
    // a scene with an error
    let (code, _, err) = qdot_on(
        "modes",
        "broken",
        "coordinates x\nkinetic E = 1/2*q*x'^2\n",
        "modes",
        &[],
    );
    assert_eq!(code, 1);
    assert!(!err.is_empty());
}

/// Two masses joined by one spring, no walls: K = k·[[1, −1], [−1, 1]],
/// M = diag(m1, m2), det(K − λM) = λ·(m1·m2·λ − k·(m1 + m2)) ⇒ ω² = 0 (the
/// rigid translation, mode (1, 1)) and k·(m1 + m2)/(m1·m2); row 1:
/// (k − λm1) − k·μ = 0 ⇒ μ = 1 − λm1/k = −m1/m2. A zero frequency leaves the
/// stability to higher-order terms. From ẋ1(0) = ẋ2(0) = 1 the body
/// translates: x1 = x2 = t.
#[test]
fn free_body_has_a_zero_frequency() {
    let src = "\
coordinates x1, x2
parameters m1, m2, k
kinetic E = 1/2*m1*x1'^2 + 1/2*m2*x2'^2
potential V = 1/2*k*(x2 - x1)^2
";
    let s = parse(src);
    let md = linearize(&s);
    assert_list(&s, &md.omega_squared, &["0", "k*(m1 + m2)/(m1*m2)"]);
    assert_list(&s, &md.modes[0], &["1", "1"]);
    assert_list(&s, &md.modes[1], &["1", "-m1/m2"]);
    match &md.stability {
        Stability::Undecided(why) => assert!(why.contains("zero frequency"), "{why}"),
        other => panic!("want undecided, got {other:?}"),
    }
    assert_consistent(&md);
    let (q0, v0) = (vec![Expr::zero(); 2], vec![Expr::one(); 2]);
    let q = free_response(&md, &q0, &v0).expect("free response");
    assert_list(&s, &q, &["t", "t"]);
    assert_free_response(&md, &q, &q0, &v0);
    let q0 = vec![ex(&s, "1/2"), Expr::zero()];
    let v0 = vec![Expr::zero(), ex(&s, "3")];
    let q = free_response(&md, &q0, &v0).expect("free response");
    assert_free_response(&md, &q, &q0, &v0);
}

/// A pendulum on a vibrating support: K = m·(g + a·cos(p·t))·l depends on
/// time, which small oscillations with constant K cannot describe.
#[test]
fn parametric_excitation_is_an_error() {
    let src = "\
coordinates th
parameters m, l, g, a, p
kinetic E = 1/2*m*l^2*th'^2
potential V = -m*(g + a*cos(p*t))*l*cos(th)
";
    let err = modes(&parse(src), None, &Values::default()).expect_err("K(t)");
    assert!(err.message.contains("depend on time"), "{}", err.message);
    let (code, _, err) = qdot_on("modes", "parametric", src, "modes", &[]);
    assert_eq!(code, 1);
    assert!(err.contains("depend on time"), "{err}");
}

/// Two identical uncoupled oscillators: det(K − λM) = (k − mλ)², a double
/// root. Expected: ω² = [k/m, k/m] with two independent modes spanning the
/// plane (e.g. (1, 0) and (0, 1)), and from y(0) = 1 the free response
/// x = 0, y = cos(√(k/m)·t).
#[test]
fn repeated_frequency() {
    let src = "\
coordinates x, y
parameters m, k
kinetic E = 1/2*m*(x'^2 + y'^2)
potential V = 1/2*k*(x^2 + y^2)
";
    let s = parse(src);
    let md = linearize(&s);
    assert_list(&s, &md.omega_squared, &["k/m", "k/m"]);
    assert_consistent(&md);
    // the two modes are independent: det[u1 u2] ≠ 0
    let d = md.modes[0][0]
        .mul(&md.modes[1][1])
        .sub(&md.modes[0][1].mul(&md.modes[1][0]));
    let shown: Vec<Vec<String>> = md
        .modes
        .iter()
        .map(|u| u.iter().map(|x| x.to_string()).collect())
        .collect();
    assert!(!d.is_zero(), "dependent modes {shown:?}");
    let (q0, v0) = (vec![Expr::zero(), Expr::one()], vec![Expr::zero(); 2]);
    let q = free_response(&md, &q0, &v0).expect("free response");
    assert_list(&s, &q, &["0", "cos(sqrt(k/m)*t)"]);
    let (code, _, err) = qdot_on("modes", "twin", src, "modes", &["--init", "y=1"]);
    assert_eq!(code, 0, "{err}");
}

/// Two uncoupled oscillators with their own parameters: det(K − λM) =
/// (k1 − m1λ)(k2 − m2λ) ⇒ ω² = k1/m1 (mode (1, 0)) and k2/m2 (mode (0, 1)),
/// in an order only parameter values decide. Actual: `modes` fails with
/// "internal error: no mode found for an exact root of det(K − λ·M)" — the
/// quadratic formula leaves √((k1·m2 − k2·m1)²), whose sign is unknown, so
/// K − λM is not recognized as singular.
#[test]
fn uncoupled_oscillators() {
    let src = "\
coordinates x, y
parameters m1, m2, k1, k2
kinetic E = 1/2*m1*x'^2 + 1/2*m2*y'^2
potential V = 1/2*k1*x^2 + 1/2*k2*y^2
";
    let s = parse(src);
    let md = modes(&s, None, &Values::default())
        .unwrap_or_else(|d| panic!("modes failed: {}", d.message));
    assert_consistent(&md);
    let (k1m1, k2m2) = (ex(&s, "k1/m1"), ex(&s, "k2/m2"));
    let i = if md.omega_squared[0].equals(&k1m1) {
        0
    } else {
        1
    };
    assert!(md.omega_squared[i].equals(&k1m1), "{:?}", md.omega_squared);
    assert!(
        md.omega_squared[1 - i].equals(&k2m2),
        "{:?}",
        md.omega_squared
    );
    assert_list(&s, &md.modes[i], &["1", "0"]);
    assert_list(&s, &md.modes[1 - i], &["0", "1"]);
    // with values the order is ascending: k2/m2 = 1 < k1/m1 = 4
    let v = set(&[("m1", 1.0), ("m2", 1.0), ("k1", 4.0), ("k2", 1.0)]);
    let md = linearize_at(&s, None, &v);
    assert_list(&s, &md.omega_squared, &["k2/m2", "k1/m1"]);
    let (code, _, err) = qdot_on("modes", "uncoupled", src, "modes", &[]);
    assert_eq!(code, 0, "{err}");
}

// ------------------------------------------------------------------ series / parallel

/// series(k1, k2) = 1/(1/k1 + 1/k2) = k1·k2/(k1 + k2); parallel(k1, k2) = k1 + k2.
/// A mass on two springs in series: V = ½·series(k1, k2)·x² ⇒
/// ω² = k1·k2/((k1 + k2)·m); between two springs tied to opposite walls
/// (parallel): ω² = (k1 + k2)/m.
#[test]
fn series_and_parallel_springs() {
    let src = "\
coordinates x
parameters m, k1, k2, k3
ks = series(k1, k2)
kp = parallel(k1, k2)
ks3 = series(k1, k2, k3)
kp3 = parallel(k1, k2, k3)
kinetic E = 1/2*m*x'^2
potential V = 1/2*ks*x^2
";
    let s = parse(src);
    assert_exact(&s, &ex(&s, "ks"), "k1*k2/(k1 + k2)");
    assert_exact(&s, &ex(&s, "kp"), "k1 + k2");
    assert_exact(&s, &ex(&s, "ks3"), "k1*k2*k3/(k1*k2 + k2*k3 + k1*k3)");
    assert_exact(&s, &ex(&s, "kp3"), "k1 + k2 + k3");
    assert_exact(
        &s,
        &ex(&s, "series(k1, parallel(k2, k3))"),
        "k1*(k2 + k3)/(k1 + k2 + k3)",
    );
    let md = linearize(&s);
    assert_list(&s, &md.omega_squared, &["k1*k2/((k1 + k2)*m)"]);
    assert_eq!(md.stability, Stability::Stable);

    // between two springs: the left one stretches by x, the right one shortens by x
    let s = parse(
        "coordinates x\nparameters m, k1, k2\nkinetic E = 1/2*m*x'^2\n\
         potential V = 1/2*k1*x^2 + 1/2*k2*x^2\n",
    );
    let p = parse(
        "coordinates x\nparameters m, k1, k2\nkinetic E = 1/2*m*x'^2\n\
         potential V = 1/2*parallel(k1, k2)*x^2\n",
    );
    assert_list(&s, &linearize(&s).omega_squared, &["(k1 + k2)/m"]);
    assert_list(&p, &linearize(&p).omega_squared, &["(k1 + k2)/m"]);
}

#[test]
fn series_needs_two_springs() {
    for f in ["series", "parallel"] {
        let src = format!(
            "coordinates x\nparameters m, k1\nkinetic E = 1/2*m*x'^2\n\
             potential V = 1/2*{f}(k1)*x^2\n"
        );
        let e = Scene::parse(&src).expect_err("one spring");
        assert!(e.message.contains("two or more"), "{}", e.message);
    }
}

// ------------------------------------------------------------------ exact vs numeric

/// A scene whose exact ω² and modes are compared with the numeric solver.
struct System {
    name: &'static str,
    params: &'static [&'static str],
    modes: Modes,
}

fn system(name: &'static str, src: &str, params: &'static [&'static str]) -> System {
    let s = parse(src);
    let modes = linearize(&s);
    assert_eq!(
        modes.omega_squared.len(),
        modes.coordinates.len(),
        "{name}: closed form"
    );
    System {
        name,
        params,
        modes,
    }
}

/// The exact ω² at `vals`, against `generalized_symmetric` on M and K
/// evaluated there (both ascending): relative error ≤ 1e-12; the exact
/// modes' distribution coefficients against the numeric eigenvectors'.
fn compare_numeric(sys: &System, vals: &[f64]) -> Result<(), String> {
    let values: Vec<(&str, f64)> = sys
        .params
        .iter()
        .copied()
        .zip(vals.iter().copied())
        .collect();
    let md = &sys.modes;
    let k = eval_matrix(&md.stiffness, &values);
    let m = eval_matrix(&md.mass, &values);
    let e = generalized_symmetric(&k, &m).map_err(|e| format!("{}: {e}", sys.name))?;
    let exact: Vec<f64> = md.omega_squared.iter().map(|w| eval(w, &values)).collect();
    // the library's order is ascending wherever it is decidable, and these
    // are decidable for positive parameters
    for w in exact.windows(2) {
        if w[0] > w[1] {
            return Err(format!("{}: exact ω² not ascending: {exact:?}", sys.name));
        }
    }
    for (i, (a, b)) in exact.iter().zip(&e.values).enumerate() {
        let rel = (a - b).abs() / b.abs();
        if rel > 1e-12 {
            return Err(format!(
                "{}: ω{i}² exact {a:e} vs numeric {b:e} (rel {rel:e}) at {values:?}",
                sys.name
            ));
        }
    }
    for (i, v) in e.vectors.iter().enumerate() {
        let numeric = distribution_coefficients(v)
            .ok_or_else(|| format!("{}: mode {i} does not move x1", sys.name))?;
        for (j, (x, y)) in md.modes[i].iter().zip(&numeric).enumerate() {
            let x = eval(x, &values);
            if (x - y).abs() > 1e-10 * y.abs().max(1.0) {
                return Err(format!(
                    "{}: mode {i}[{j}] exact {x:e} vs numeric {y:e} at {values:?}",
                    sys.name
                ));
            }
        }
    }
    Ok(())
}

#[test]
fn exact_agrees_with_the_numeric_eigen_solver() {
    let systems = [
        system("double pendulum", DOUBLE_PENDULUM, &["m", "l", "g"]),
        system("three-mass chain", CHAIN, &["m", "k"]),
        system("seed 24.2", &example_src("seed_24_2"), &["m", "k", "R"]),
        system(
            "cart with pendulum",
            CART_PENDULUM,
            &["M0", "m", "l", "k", "g"],
        ),
    ];
    let mut runner = TestRunner::new(Config {
        cases: 64,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = proptest::collection::vec(0.5f64..5.0, 5);
    let cases = std::cell::Cell::new(0usize);
    runner
        .run(&strategy, |vals| {
            cases.set(cases.get() + 1);
            for sys in &systems {
                compare_numeric(sys, &vals[..sys.params.len()])
                    .map_err(proptest::test_runner::TestCaseError::fail)?;
            }
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(cases.get() >= 64, "{} cases", cases.get());
}

// ------------------------------------------------------------------ JSON contract

const KEYS: [&str; 21] = [
    "coordinates",
    "at",
    "mass_matrix",
    "stiffness_matrix",
    "damping_matrix",
    "forcing",
    "characteristic_polynomial",
    "characteristic_factors",
    "gyroscopic",
    "omega_squared",
    "modes",
    "no_closed_form",
    "stability",
    "stability_note",
    "standard_form",
    "numeric_omega_squared",
    "numeric_modes",
    "numeric_modes_note",
    "free_response",
    "numeric_free_response",
    "forced_response",
];

/// `qdot ARGS` must succeed with JSON on stdout.
fn json_of(args: &[&str]) -> Value {
    let (code, out, err) = qdot(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    json(&out)
}

#[track_caller]
fn reparse(s: &Scene, what: &str, v: &Value) -> Expr {
    let src = v
        .as_str()
        .unwrap_or_else(|| panic!("{what} is not a string: {v}"));
    s.expr(src)
        .unwrap_or_else(|d| panic!("{what} `{src}` does not re-parse: {}", d.message))
}

/// A string with `lambda`, re-parsed in the scene extended by a parameter
/// `lambda` that is then replaced by the `solve`-unknown λ the library uses.
#[track_caller]
fn reparse_lambda(s: &Scene, what: &str, v: &Value) -> Expr {
    let src = v
        .as_str()
        .unwrap_or_else(|| panic!("{what} is not a string: {v}"));
    let lam = atom::param("lambda");
    let ext = Scene::parse(&format!("parameters lambda\n{}", scene_names(s)))
        .unwrap_or_else(|d| panic!("extended scene: {}", d.message));
    let p = ext
        .expr(src)
        .unwrap_or_else(|d| panic!("{what} `{src}` does not re-parse: {}", d.message));
    p.subs(lam, &lambda()).expect("λ substitution")
}

/// The declarations of a scene (its coordinates and parameters), enough
/// to re-parse matrices and polynomials.
fn scene_names(s: &Scene) -> String {
    let cs: Vec<&str> = s.coordinates.iter().map(|c| c.name.as_str()).collect();
    let ps: Vec<&str> = s.parameters.iter().map(|p| p.name.as_str()).collect();
    let mut out = String::new();
    if !cs.is_empty() {
        out.push_str(&format!("coordinates {}\n", cs.join(", ")));
    }
    if !ps.is_empty() {
        out.push_str(&format!("parameters {}\n", ps.join(", ")));
    }
    out
}

#[track_caller]
fn check_exprs(s: &Scene, what: &str, got: &Value, want: &[Expr]) {
    let arr = got
        .as_array()
        .unwrap_or_else(|| panic!("{what} is not an array: {got}"));
    assert_eq!(arr.len(), want.len(), "{what}: {got}");
    for (i, (g, w)) in arr.iter().zip(want).enumerate() {
        let e = reparse(s, what, g);
        assert!(
            e.equals(w),
            "{what}[{i}]: `{g}` re-parses to {e}, library {w}"
        );
    }
}

#[track_caller]
fn check_named(s: &Scene, what: &str, got: &Value, names: &[String], want: &[Expr]) {
    assert_eq!(keys(got), names, "{what}");
    for (n, w) in names.iter().zip(want) {
        let e = reparse(s, what, &got[n]);
        assert!(
            e.equals(w),
            "{what}.{n}: `{}` re-parses to {e}, library {w}",
            got[n]
        );
    }
}

/// The whole JSON of `qdot modes` against the library on the same scene,
/// equilibrium, values and initial conditions.
fn check_json(
    s: &Scene,
    v: &Value,
    values: &Values,
    at: Option<&[Expr]>,
    init: Option<(&[Expr], &[Expr])>,
) {
    assert_eq!(keys(v), crate::common::contract_keys(v, s, &KEYS));
    let md = linearize_at(s, at, values);
    assert_eq!(v["coordinates"], serde_json::json!(md.coordinates));
    check_named(s, "at", &v["at"], &md.coordinates, &md.at);
    for (key, m) in [
        ("mass_matrix", &md.mass),
        ("stiffness_matrix", &md.stiffness),
        ("damping_matrix", &md.damping),
    ] {
        let rows = v[key].as_array().unwrap();
        assert_eq!(rows.len(), m.len(), "{key}");
        for (row, want) in rows.iter().zip(m) {
            check_exprs(s, key, row, want);
        }
    }
    check_exprs(s, "forcing", &v["forcing"], &md.forcing);
    let ch = reparse_lambda(
        s,
        "characteristic_polynomial",
        &v["characteristic_polynomial"],
    );
    assert!(
        ch.equals(&md.characteristic),
        "{ch} vs {}",
        md.characteristic
    );
    let fs = v["characteristic_factors"].as_array().unwrap();
    assert_eq!(fs.len(), md.factors.len());
    for (f, w) in fs.iter().zip(&md.factors) {
        let e = reparse_lambda(s, "characteristic_factors", f);
        assert!(e.equals(w), "factor `{f}` re-parses to {e}, library {w}");
    }
    check_exprs(s, "omega_squared", &v["omega_squared"], &md.omega_squared);
    let ms = v["modes"].as_array().unwrap();
    assert_eq!(ms.len(), md.modes.len());
    for (m, w) in ms.iter().zip(&md.modes) {
        check_exprs(s, "modes", m, w);
    }
    assert_eq!(v["stability"], md.stability.word());
    match &md.stability {
        Stability::Undecided(why) => assert_eq!(v["stability_note"], why.as_str()),
        _ => assert!(v["stability_note"].is_null()),
    }
    match standard_form(&md, values) {
        None => assert_eq!(v["standard_form"], Value::Null),
        Some(sf) => {
            let j = &v["standard_form"];
            assert_eq!(
                keys(j),
                ["omega_squared", "alpha", "zeta", "forcing", "regime"]
            );
            assert!(reparse(s, "ω²", &j["omega_squared"]).equals(&sf.omega_squared));
            assert!(reparse(s, "α", &j["alpha"]).equals(&sf.alpha));
            assert!(reparse(s, "f/M", &j["forcing"]).equals(&sf.forcing));
            match &sf.zeta {
                None => assert_eq!(j["zeta"], Value::Null),
                Some(z) => assert!(reparse(s, "ζ", &j["zeta"]).equals(z), "ζ {}", j["zeta"]),
            }
            assert_eq!(j["regime"], sf.regime.as_str());
        }
    }
    if values.is_empty() {
        assert_eq!(v["numeric_omega_squared"], Value::Null);
        assert_eq!(v["numeric_modes"], Value::Null);
    } else {
        let vals: Vec<(&str, f64)> = values.iter().map(|(k, x)| (k.as_str(), *x)).collect();
        let e = generalized_symmetric(
            &eval_matrix(&md.stiffness, &vals),
            &eval_matrix(&md.mass, &vals),
        )
        .unwrap();
        let num: Vec<f64> = v["numeric_omega_squared"]
            .as_array()
            .expect("numeric ω² with --set")
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(num, e.values);
        // the M-normalized eigenvectors of the same solver
        assert_eq!(v["numeric_modes"], serde_json::json!(e.vectors));
        let exact: Vec<f64> = md.omega_squared.iter().map(|w| eval(w, &vals)).collect();
        for (a, b) in exact.iter().zip(&num) {
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{exact:?} vs {num:?}");
        }
    }
    match init {
        None => assert_eq!(v["free_response"], Value::Null),
        Some((q0, v0)) => {
            // exact, so no numeric response
            assert_eq!(v["numeric_free_response"], Value::Null);
            let q = free_response(&md, q0, v0).unwrap();
            check_named(s, "free_response", &v["free_response"], &md.coordinates, &q);
        }
    }
    let damped = md.damping.iter().flatten().any(|e| !e.is_zero());
    if damped {
        // one damped coordinate: y = X·cos(p·t − ψ)
        let j = &v["forced_response"];
        match standard_form(&md, values).and_then(|sf| damped_steady_state(&md, &sf)) {
            None => assert_eq!(*j, Value::Null),
            Some((p, x, tan_psi)) => {
                assert_eq!(keys(j), ["p", "amplitude", "tan_psi"]);
                assert!(reparse(s, "p", &j["p"]).equals(&p));
                assert!(
                    reparse(s, "X", &j["amplitude"]).equals(&x),
                    "{}",
                    j["amplitude"]
                );
                assert!(reparse(s, "tan ψ", &j["tan_psi"]).equals(&tan_psi));
            }
        }
        return;
    }
    match forced_amplitudes(&md) {
        None => assert_eq!(v["forced_response"], Value::Null),
        Some((p, x)) => {
            let j = &v["forced_response"];
            assert_eq!(keys(j), ["p", "amplitudes"]);
            assert!(reparse(s, "p", &j["p"]).equals(&p));
            check_named(s, "amplitudes", &j["amplitudes"], &md.coordinates, &x);
        }
    }
}

#[test]
fn json_contract_seed_24_2() {
    let s = example("seed_24_2");
    let v = json_of(&["modes", "examples/seed_24_2.qd", "--format", "json"]);
    check_json(&s, &v, &Values::default(), None, None);
    assert_eq!(v["omega_squared"], serde_json::json!(["k/(6*m)", "k/m"]));
    assert_eq!(v["modes"], serde_json::json!([["1", "4/3"], ["1", "-2"]]));
    assert_eq!(v["stability"], "stable");

    let v = json_of(&[
        "modes",
        "examples/seed_24_2.qd",
        "--format",
        "json",
        "--init",
        "x1=1",
        "--set",
        "m=1,k=2,R=3",
    ]);
    let (q0, v0) = ([Expr::one(), Expr::zero()], [Expr::zero(), Expr::zero()]);
    check_json(
        &s,
        &v,
        &set(&[("m", 1.0), ("k", 2.0), ("R", 3.0)]),
        None,
        Some((&q0, &v0)),
    );
}

#[test]
fn json_contract_seed_24_1() {
    let s = example("seed_24_1");
    let v = json_of(&["modes", "examples/seed_24_1.qd", "--format", "json"]);
    check_json(&s, &v, &Values::default(), None, None);
    let values = [
        ("m", 1.0),
        ("r", 1.0),
        ("k", 10.0),
        ("c", 1.0),
        ("g", 9.81),
        ("F0", 1.0),
        ("p", 1.0),
    ];
    let v = json_of(&[
        "modes",
        "examples/seed_24_1.qd",
        "--format",
        "json",
        "--set",
        "m=1,r=1,k=10,c=1,g=9.81,F0=1,p=1",
        "--init",
        "y1=1/10,y1'=0",
    ]);
    let (q0, v0) = ([ex(&s, "1/10")], [Expr::zero()]);
    check_json(&s, &v, &set(&values), None, Some((&q0, &v0)));
    assert_eq!(v["standard_form"]["regime"], "underdamped");
}

#[test]
fn json_contract_other_scenes() {
    for (tag, src) in [
        ("dp", DOUBLE_PENDULUM),
        ("chain", CHAIN),
        ("chain3", CHAIN_UNEQUAL),
        ("cart", CART_PENDULUM),
        ("forced", FORCED_24_2),
    ] {
        let (code, out, err) = qdot_on("modes", tag, src, "modes", &["--format", "json"]);
        assert_eq!(code, 0, "{tag}: {err}");
        check_json(&parse(src), &json(&out), &Values::default(), None, None);
        let (code, _, err) = qdot_on("modes", tag, src, "modes", &[]);
        assert_eq!(code, 0, "{tag}: {err}");
    }
}

/// The cart with a pendulum on a spring is stable for every positive
/// parameter: ω₁² = (A − √D)/(2·l·M0) with A = g·M0 + g·m + k·l and
/// A² − D = 4·g·k·l·M0 > 0, decided exactly (no --set).
#[test]
fn cart_pendulum_is_stable_exactly() {
    let src = "coordinates x, th\nparameters M0, m, l, g, k\n\
        px = x + l*sin(th); py = -l*cos(th)\n\
        kinetic E = 1/2*M0*x'^2 + 1/2*m*(px'^2 + py'^2)\n\
        potential V = 1/2*k*x^2 + m*g*py\n";
    let s = Scene::parse(src).unwrap();
    let md = qdot::solve::oscillations::modes(&s, None, &Default::default()).unwrap();
    assert_eq!(md.stability, qdot::solve::equilibrium::Stability::Stable);
    for w2 in &md.omega_squared {
        assert_eq!(
            qdot::solve::equilibrium::sign_exact(w2),
            Some(qdot::solve::equilibrium::Sign::Positive),
            "{w2}"
        );
    }
}

/// A characteristic cubic without a λ² term (every potential satisfying
/// Laplace's equation) has rational roots: found by factoring over ℚ, not
/// "no closed form". Issue 18's bug.
#[test]
fn a_cubic_without_its_square_term_is_factored() {
    let s = parse(
        "coordinates x, y, z\nparameters m, k\nkinetic T = 1/2*m*(x'^2 + y'^2 + z'^2)\npotential V = k/2*(2*z^2 - x^2 - y^2)\n",
    );
    let md = linearize(&s);
    assert_list(&s, &md.omega_squared, &["-k/m", "-k/m", "2*k/m"]);
    assert_consistent(&md);
    assert_eq!(md.stability, Stability::Unstable);
}

/// Four equal masses between two walls: det(K − λ·M) factors over ℚ into
/// two irreducible quadratics, and every ω² is exact,
/// (3 ± √5)·k/(2m) and (5 ± √5)·k/(2m), in ascending order.
#[test]
fn a_chain_of_four_masses_has_exact_frequencies() {
    let s = parse(
        "coordinates x1, x2, x3, x4\nparameters m, k\nkinetic T = 1/2*m*(x1'^2 + x2'^2 + x3'^2 + x4'^2)\npotential V = k/2*(x1^2 + (x2 - x1)^2 + (x3 - x2)^2 + (x4 - x3)^2 + x4^2)\n",
    );
    let md = linearize(&s);
    assert_list(
        &s,
        &md.omega_squared,
        &[
            "(3 - sqrt(5))*k/(2*m)",
            "(5 - sqrt(5))*k/(2*m)",
            "(3 + sqrt(5))*k/(2*m)",
            "(5 + sqrt(5))*k/(2*m)",
        ],
    );
    assert_consistent(&md);
    assert_eq!(md.stability, Stability::Stable);
    // the lowest mode: sin(jπ/5) ratios, x2/x1 = 2·cos(π/5) = (1 + √5)/2
    assert_exact(&s, &md.modes[0][1], "(1 + sqrt(5))/2");
}

/// √(n/d) = √(n·d)/|d|: a denominator of unknown sign (g·M − 6·k·l) is
/// not taken positive. The amplitude of a rod's free response was printed
/// negative (−1.1 for 1.1 at M = l = k = g = 1) before.
#[test]
fn a_square_root_over_a_denominator_of_unknown_sign_keeps_its_sign() {
    let s = parse(
        "coordinates x\nparameters M, l, k, g\nkinetic T = 1/2*M*x'^2\npotential V = 1/2*k*x^2 - M*g*x^2/(12*l)\n",
    );
    let md = linearize(&s);
    let free = free_response(&md, &[ex(&s, "1/10")], &[ex(&s, "1")]).expect("free response");
    let (a, _) = qdot::solve::oscillations::free_amplitude_phase(&md, &free).expect("A and φ");
    let at = |v: f64| move |_: &Atom| Some(v);
    // M = l = k = g = 1: ω² = 5/6, A = √(1/100 + 6/5) = 1.1
    let got = a.eval_f64(&at(1.0)).expect("numeric");
    assert!((got - 1.1).abs() < 1e-12, "A = {a} = {got}");
    // |d| is shown as such, and the input syntax re-parses to the value
    // (which of ±(g·M − 6·k·l) shows depends on the order atoms were met)
    let shown = format!("{a:#}");
    assert!(
        [
            "|g·M − 6·k·l|",
            "|6·k·l − g·M|",
            "|−g·M + 6·k·l|",
            "|−6·k·l + g·M|"
        ]
        .iter()
        .any(|t| shown.contains(t)),
        "{shown}"
    );
    assert!(a.to_latex().contains(r"\left|"), "{}", a.to_latex());
    assert!(ex(&s, &a.to_string()).equals(&a), "{a}");
    // the sign of the canonical denominator (l − M or M − l) is irrelevant
    let vals = |x: &Atom| match x {
        Atom::Param(p) if &**p == "M" => Some(1.0),
        Atom::Param(p) if &**p == "l" => Some(3.0),
        _ => None,
    };
    for src in ["1/(l - M)", "-1/(M - l)", "M/(l - M)", "2*M/(2*l - 2*M)"] {
        let e = qdot::expr::func::sqrt(&ex(&s, src)).expect("a root");
        let v = e.eval_f64(&vals).expect("numeric");
        assert!((v - 0.5f64.sqrt()).abs() < 1e-12, "√({src}) = {e} = {v}");
    }
}

/// A coefficient whose denominator's first term is negative carries one
/// sign, outside: the cart with a pendulum printed `x(t) = −−(2·g·k·l·M …`
/// (JSON `"--(2*g*k…"`) before. Issue 18's case.
#[test]
fn a_free_response_never_prints_a_double_minus() {
    let src = "coordinates x, theta\nparameters M, m, l, k, g\nkinetic T = 1/2*M*x'^2 + 1/2*m*((x' + l*cos(theta)*theta')^2 + (l*sin(theta)*theta')^2)\npotential V = 1/2*k*x^2 - m*g*l*cos(theta)\n";
    for init in ["x=1/10,x'=0,theta=0,theta'=0", "x=0,x'=1,theta=0,theta'=0"] {
        for fmt in ["text", "json"] {
            let (code, out, err) = qdot_on(
                "modes",
                "cart",
                src,
                "modes",
                &["--init", init, "--format", fmt],
            );
            assert_eq!(code, 0, "{err}");
            assert!(
                out.contains("(t) = ") || out.contains("\"free_response\""),
                "{out}"
            );
            assert!(
                !out.contains("−−") && !out.contains("--") && !out.contains("+ −"),
                "{out}"
            );
        }
    }
}

// ------------------------------------------------------------------ SymPy fixtures

/// `tests/fixtures/modes.json`, written by `tests/fixtures/gen_modes.py`
/// (SymPy derives M, C and K from its own Lagrangian, det(K + s·C + s²·M)
/// or det(K − λ·M), factors it over ℚ and solves each factor).
fn modes_fixtures() -> Vec<Value> {
    let path = format!("{}/tests/fixtures/modes.json", env!("QDOT_ROOT"));
    let text = std::fs::read_to_string(path).expect("modes.json exists");
    let v: Value = serde_json::from_str(&text).expect("modes.json is JSON");
    v["cases"].as_array().expect("cases").clone()
}

/// The four-mass chain, the quadrupole (a Laplace potential, a cubic without
/// its λ² term), the Penning trap (magnetron, cyclotron and axial
/// frequencies), a particle on an anisotropic spring in a rotating frame
/// and a spinning top: every ω² exactly SymPy's, as a multiset, and the
/// characteristic polynomial SymPy's at a sample λ.
#[test]
fn exact_frequencies_agree_with_sympy() {
    let cases = modes_fixtures();
    assert!(cases.len() >= 5);
    for case in &cases {
        let name = case["name"].as_str().expect("name");
        let s = parse(case["scene"].as_str().expect("scene"));
        let md = linearize(&s);
        assert_eq!(
            md.gyroscopic,
            case["gyroscopic"].as_bool().expect("gyroscopic"),
            "{name}"
        );
        let want: Vec<Expr> = case["omega_squared"]
            .as_array()
            .expect("ω²")
            .iter()
            .map(|w| ex(&s, w.as_str().expect("a string")))
            .collect();
        let got: Vec<String> = md.omega_squared.iter().map(|e| e.to_string()).collect();
        assert_eq!(md.omega_squared.len(), want.len(), "{name}: {got:?}");
        let mut left: Vec<&Expr> = md.omega_squared.iter().collect();
        for w in &want {
            let i = left
                .iter()
                .position(|g| g.equals(w))
                .unwrap_or_else(|| panic!("{name}: SymPy's ω² = {w} is not among {got:?}"));
            left.remove(i);
        }
        // the characteristic polynomial at λ = 7/3
        let p = case["characteristic"].as_str().expect("characteristic");
        let sympy = ex(&s, &p.replace("lambda", "(7/3)"));
        let lv = qdot::expr::atom::unknown("lambda");
        let ours = md.characteristic.subs(lv, &ex(&s, "7/3")).expect("at 7/3");
        assert!(ours.equals(&sympy), "{name}: {ours} vs {sympy}");
    }
}

/// With every parameter given, the verdict is never "undecided" (nothing
/// has a zero frequency here): the four scenes of the fixtures, the unequal
/// chain (no closed form), the double pendulum and the cart with a
/// pendulum, at several values; and the gyroscopic verdicts are the
/// textbook ones.
#[test]
fn stability_under_set_is_decided() {
    let mut scenes: Vec<(String, Scene)> = modes_fixtures()
        .iter()
        .map(|c| {
            let name = c["name"].as_str().expect("name").to_string();
            (name, parse(c["scene"].as_str().expect("scene")))
        })
        .collect();
    for (name, src) in [
        ("chain_unequal", CHAIN_UNEQUAL),
        ("double_pendulum", DOUBLE_PENDULUM),
        ("cart_pendulum", CART_PENDULUM),
        ("chain3", CHAIN),
    ] {
        scenes.push((name.to_string(), parse(src)));
    }
    let values = [0.5, 1.0, 2.0, 3.0, 7.0];
    for (name, s) in &scenes {
        for (i, &base) in values.iter().enumerate() {
            let mut v = Values::default();
            for (j, p) in s.parameters.iter().enumerate() {
                v.insert(p.name.to_string(), values[(i + j) % values.len()] * base);
            }
            let md = linearize_at(s, None, &v);
            assert!(
                !matches!(md.stability, Stability::Undecided(_)),
                "{name} at {v:?}: {:?}",
                md.stability
            );
        }
    }
    let verdict = |name: &str, pairs: &[(&str, f64)]| {
        let (_, s) = scenes.iter().find(|(n, _)| n == name).expect("scene");
        linearize_at(s, None, &set(pairs)).stability
    };
    // the top: stable when C²Ω² > 4·(A + m·l²)·m·g·l = 8 here
    let top = [("A", 1.0), ("C", 1.0), ("m", 1.0), ("g", 1.0), ("l", 1.0)];
    let with = |w: f64| [top.as_slice(), &[("Omega", w)]].concat();
    assert_eq!(verdict("spinning_top", &with(3.0)), Stability::Stable);
    assert_eq!(verdict("spinning_top", &with(2.0)), Stability::Unstable);
    // the shaft: stable below the first critical speed, unstable between
    // the two, stable again above the second (K negative definite there)
    let shaft = |w: f64| [("m", 1.0), ("k1", 1.0), ("k2", 4.0), ("Omega", w)];
    assert_eq!(verdict("rotating_shaft", &shaft(0.5)), Stability::Stable);
    assert_eq!(verdict("rotating_shaft", &shaft(1.5)), Stability::Unstable);
    assert_eq!(verdict("rotating_shaft", &shaft(3.0)), Stability::Stable);
    // Penning: stable when e·B² > 2·m·V0/d²
    let penning = |b: f64| [("m", 1.0), ("e", 1.0), ("V0", 1.0), ("d", 1.0), ("B", b)];
    assert_eq!(verdict("penning", &penning(3.0)), Stability::Stable);
    assert_eq!(verdict("penning", &penning(1.0)), Stability::Unstable);
}

/// Without values, a gyroscopic system's verdict is the condition, reduced:
/// the roots' existence (a real square root) and their sign are one
/// condition, and positive factors are left out.
#[test]
fn gyroscopic_stability_conditions() {
    let cases = modes_fixtures();
    let case = |n: &str| {
        let c = cases.iter().find(|c| c["name"] == n).expect("case");
        parse(c["scene"].as_str().expect("scene"))
    };
    for (name, want) in [
        ("penning", "stable when 2·m·V₀ < B²·d²·e"),
        ("spinning_top", "stable when 4·g·l·m·(l²·m + A) < C²·Ω²"),
    ] {
        match linearize(&case(name)).stability {
            Stability::Undecided(why) => assert!(why.starts_with(want), "{name}: {why}"),
            other => panic!("{name}: {other:?}"),
        }
    }
    assert!(linearize(&case("penning")).modes.is_empty());
    // a gyroscopic system's free response is refused, with a reason
    let s = case("spinning_top");
    let md = linearize(&s);
    let err = free_response(
        &md,
        &[Expr::one(), Expr::zero()],
        &[Expr::zero(), Expr::zero()],
    )
    .expect_err("refused");
    assert!(err.message.contains("gyroscopic"), "{}", err.message);
}

// ------------------------------------------------- numeric free response

/// M·q̈ + K·q = 0 integrated by classical RK4 (step `h`) from q0, v0 to
/// each time of `ts` (ascending): q at those times.
fn rk4(
    m: &[Vec<f64>],
    k: &[Vec<f64>],
    q0: &[f64],
    v0: &[f64],
    ts: &[f64],
    h: f64,
) -> Vec<Vec<f64>> {
    let n = q0.len();
    let mm = nalgebra::DMatrix::from_fn(n, n, |i, j| m[i][j]);
    let kk = nalgebra::DMatrix::from_fn(n, n, |i, j| k[i][j]);
    // q̈ = A·q with A = −M⁻¹·K
    let a = -(mm.try_inverse().expect("M invertible") * kk);
    let f = |y: &nalgebra::DVector<f64>| {
        let q = y.rows(0, n).into_owned();
        let v = y.rows(n, n).into_owned();
        let mut d = nalgebra::DVector::zeros(2 * n);
        d.rows_mut(0, n).copy_from(&v);
        d.rows_mut(n, n).copy_from(&(&a * q));
        d
    };
    let mut y = nalgebra::DVector::from_iterator(2 * n, q0.iter().chain(v0).copied());
    let mut t = 0.0;
    let mut out = Vec::new();
    for &target in ts {
        while t < target - 1e-12 {
            let step = h.min(target - t);
            let k1 = f(&y);
            let k2 = f(&(&y + &k1 * (step / 2.0)));
            let k3 = f(&(&y + &k2 * (step / 2.0)));
            let k4 = f(&(&y + &k3 * step));
            y += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (step / 6.0);
            t += step;
        }
        out.push(y.rows(0, n).iter().copied().collect());
    }
    out
}

/// A `numeric_free_response` string, re-parsed and evaluated at time t.
fn eval_at(s: &Scene, src: &str, t: f64) -> f64 {
    let e = ex(s, src);
    e.eval_f64(&|a: &Atom| matches!(a, Atom::Time).then_some(t))
        .unwrap_or_else(|| panic!("`{src}` does not evaluate at t = {t}"))
}

/// The unequal chain has no closed form: under `--set` and `--init` the
/// free response is numeric, in the text and in JSON (decimal strings
/// that re-parse), and agrees with RK4 on M·q̈ + K·q = 0 to 1e-8.
#[test]
fn numeric_free_response_without_closed_form() {
    let s = parse(CHAIN_UNEQUAL);
    let vals = [
        ("m1", 1.0),
        ("m2", 2.0),
        ("m3", 3.0),
        ("k1", 1.0),
        ("k2", 2.0),
        ("k3", 3.0),
        ("k4", 4.0),
    ];
    let values = "m1=1,m2=2,m3=3,k1=1,k2=2,k3=3,k4=4";
    let init = "x1=1,x3=-1/2,x2'=1/2";
    let (q0, v0) = ([1.0, 0.0, -0.5], [0.0, 0.5, 0.0]);
    let md = linearize_at(&s, None, &set(&vals));
    assert!(md.omega_squared.is_empty());
    let ts = [0.0, 0.37, 1.0, 2.5, 4.0, 7.25];
    let want = rk4(
        &eval_matrix(&md.mass, &vals),
        &eval_matrix(&md.stiffness, &vals),
        &q0,
        &v0,
        &ts,
        1e-3,
    );
    // the library's q(t)
    let q0e: Vec<Expr> = ["1", "0", "-1/2"].iter().map(|x| ex(&s, x)).collect();
    let v0e: Vec<Expr> = ["0", "1/2", "0"].iter().map(|x| ex(&s, x)).collect();
    let nf = numeric_free_response(&md, &set(&vals), &q0e, &v0e).expect("numeric");
    assert!(nf.modes.iter().all(|m| m.motion == Motion::Oscillates));
    for (t, w) in ts.iter().zip(&want) {
        for (a, b) in nf.at(*t).iter().zip(w) {
            assert!((a - b).abs() <= 1e-10, "t = {t}: {a} vs RK4 {b}");
        }
    }
    // JSON: decimal strings in input syntax
    let (code, out, err) = qdot_on(
        "modes",
        "chain3_numeric",
        CHAIN_UNEQUAL,
        "modes",
        &["--format", "json", "--set", values, "--init", init],
    );
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    assert_eq!(v["free_response"], Value::Null);
    let fr = v["numeric_free_response"]
        .as_object()
        .expect("numeric_free_response");
    assert_eq!(fr.keys().collect::<Vec<_>>(), ["x1", "x2", "x3"]);
    for (j, c) in ["x1", "x2", "x3"].iter().enumerate() {
        let src = fr[*c].as_str().unwrap();
        assert!(src.contains("cos(") && src.contains("sin("), "{src}");
        for (t, w) in ts.iter().zip(&want) {
            let got = eval_at(&s, src, *t);
            assert!(
                (got - w[j]).abs() <= 1e-8,
                "{c}({t}) = {got} vs RK4 {}",
                w[j]
            );
        }
    }
    // the text says it is numeric, with no double minus
    let (code, out, err) = qdot_on(
        "modes",
        "chain3_numeric_text",
        CHAIN_UNEQUAL,
        "modes",
        &["--set", values, "--init", init],
    );
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("Free response (undamped) from the initial conditions, numeric"),
        "{out}"
    );
    assert!(
        out.contains("  x₁(t) = −0.01118690064·cos(0.8403624841·t) + 0.2664915803·sin("),
        "{out}"
    );
    assert!(
        !out.contains("−−") && !out.contains("- -") && !out.contains("+ −"),
        "{out}"
    );
    // without --set: the error says how to get it
    let (code, _, err) = qdot_on(
        "modes",
        "chain3_init",
        CHAIN_UNEQUAL,
        "modes",
        &["--init", "x1=1"],
    );
    assert_eq!(code, 1);
    assert!(
        err.contains("closed form") && err.contains("--set"),
        "{err}"
    );
}

/// The unequal chain with its first spring pushing (−k1): one ω² < 0,
/// whose mode grows as cosh/sinh (printed as exponentials), against RK4.
const CHAIN_PUSHED: &str = "\
coordinates x1, x2, x3
parameters m1, m2, m3, k1, k2, k3, k4
kinetic E = 1/2*(m1*x1'^2 + m2*x2'^2 + m3*x3'^2)
potential V = 1/2*(-k1*x1^2 + k2*(x2 - x1)^2 + k3*(x3 - x2)^2 + k4*x3^2)
";

#[test]
fn numeric_free_response_grows_when_unstable() {
    let s = parse(CHAIN_PUSHED);
    let vals = [
        ("m1", 1.0),
        ("m2", 2.0),
        ("m3", 3.0),
        ("k1", 6.0),
        ("k2", 2.0),
        ("k3", 3.0),
        ("k4", 4.0),
    ];
    let md = linearize_at(&s, None, &set(&vals));
    let q0e: Vec<Expr> = ["1/10", "0", "0"].iter().map(|x| ex(&s, x)).collect();
    let v0e: Vec<Expr> = ["0", "0", "1/5"].iter().map(|x| ex(&s, x)).collect();
    let nf = numeric_free_response(&md, &set(&vals), &q0e, &v0e).expect("numeric");
    assert_eq!(nf.modes[0].motion, Motion::Grows, "{:?}", nf.modes);
    let ts = [0.0, 0.5, 1.5, 3.0];
    let want = rk4(
        &eval_matrix(&md.mass, &vals),
        &eval_matrix(&md.stiffness, &vals),
        &[0.1, 0.0, 0.0],
        &[0.0, 0.0, 0.2],
        &ts,
        1e-3,
    );
    for (t, w) in ts.iter().zip(&want) {
        for (a, b) in nf.at(*t).iter().zip(w) {
            assert!(
                (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                "t = {t}: {a} vs RK4 {b}"
            );
        }
    }
    let (code, out, err) = qdot_on(
        "modes",
        "chain3_unstable",
        CHAIN_PUSHED,
        "modes",
        &[
            "--format",
            "json",
            "--set",
            "m1=1,m2=2,m3=3,k1=6,k2=2,k3=3,k4=4",
            "--init",
            "x1=1/10,x3'=1/5",
        ],
    );
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    for (j, c) in ["x1", "x2", "x3"].iter().enumerate() {
        let src = v["numeric_free_response"][*c].as_str().unwrap();
        assert!(src.contains("exp("), "{src}");
        for (t, w) in ts.iter().zip(&want) {
            let got = eval_at(&s, src, *t);
            assert!(
                (got - w[j]).abs() <= 1e-8 * (1.0 + w[j].abs()),
                "{c}({t}) = {got} vs {}",
                w[j]
            );
        }
    }
}

/// Where the exact free response exists, the numeric one agrees with it at
/// random parameter values, initial conditions and times: the four-mass
/// chain (ω² with square roots) and a free body (ω² = 0 drifts as a + b·t).
#[test]
fn numeric_free_response_agrees_with_exact() {
    let free_body = "\
coordinates x1, x2
parameters m1, m2, k
kinetic E = 1/2*m1*x1'^2 + 1/2*m2*x2'^2
potential V = 1/2*k*(x2 - x1)^2
";
    let cases: [(Scene, &[&str]); 2] = [
        (example("four_mass_chain"), &["m", "k"]),
        (parse(free_body), &["m1", "m2", "k"]),
    ];
    let mut runner = TestRunner::new(Config {
        cases: 24,
        ..Config::default()
    });
    for (s, params) in &cases {
        let md = linearize(s);
        let n = md.coordinates.len();
        assert_eq!(md.omega_squared.len(), n);
        runner
            .run(
                &(
                    proptest::collection::vec(1i64..=9, params.len()),
                    proptest::collection::vec(-9i64..=9, 2 * n),
                    proptest::collection::vec(0u32..=80, 3),
                ),
                |(p, init, times)| {
                    let vals: Vec<(&str, f64)> = params
                        .iter()
                        .zip(&p)
                        .map(|(k, x)| (*k, *x as f64))
                        .collect();
                    let q0: Vec<Expr> =
                        init[..n].iter().map(|x| ex(s, &format!("{x}/4"))).collect();
                    let v0: Vec<Expr> =
                        init[n..].iter().map(|x| ex(s, &format!("{x}/3"))).collect();
                    let exact = free_response(&md, &q0, &v0).expect("exact");
                    let nf = numeric_free_response(&md, &set(&vals), &q0, &v0).expect("numeric");
                    for &tt in &times {
                        let t = f64::from(tt) / 10.0;
                        let got = nf.at(t);
                        for (j, e) in exact.iter().enumerate() {
                            let f = env(&vals);
                            let want = e
                                .eval_f64(&|a: &Atom| match a {
                                    Atom::Time => Some(t),
                                    _ => f(a),
                                })
                                .expect("evaluates");
                            if (got[j] - want).abs() > 1e-9 * (1.0 + want.abs() + t) {
                                return Err(proptest::test_runner::TestCaseError::fail(format!(
                                    "{p:?} {init:?} t = {t}: q{j} numeric {} vs exact {want}",
                                    got[j]
                                )));
                            }
                        }
                    }
                    Ok(())
                },
            )
            .unwrap();
    }
}

/// A gyroscopic system keeps refusing `--init`, even under `--set`.
#[test]
fn numeric_free_response_refuses_gyroscopic() {
    let (code, _, err) = qdot(&[
        "modes",
        "examples/penning_modes.qd",
        "--set",
        "m=1,e=1,V0=1,d=1,B=3",
        "--init",
        "x=1",
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("gyroscopic") && err.contains("simulate"),
        "{err}"
    );
}
