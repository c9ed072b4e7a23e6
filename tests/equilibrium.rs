//! `qdot equilibrium`: the configurations where the generalized forces (plus
//! the kinetic energy's terms at rest) vanish, in closed form where possible,
//! numerically with `--set` otherwise, and their stability. Every expected
//! value is derived by hand in a comment; numeric roots are checked against
//! f64 evaluation of the equations and a sign-change count.

use crate::common::run::{qdot_on, EQUILIBRIUM_KEYS};
use qdot::solve::equilibrium::{equilibria, Equilibria, Equilibrium, Position, Stability};
use qdot::{Expr, Scene};

fn parse(src: &str) -> Scene {
    match Scene::parse(src) {
        Ok(s) => s,
        Err(d) => panic!("{}", d.render("scene.qd", src)),
    }
}

/// The equilibria with `--set` values (empty: none).
fn eq(s: &Scene, set: &str) -> Equilibria {
    let values = qdot::output::parse_set(set).expect("valid --set");
    match equilibria(s, &values) {
        Ok(e) => e,
        Err(d) => panic!("{}", d.render("scene.qd", &s.source)),
    }
}

fn exact(e: &Equilibrium) -> &[Expr] {
    match &e.position {
        Position::Exact(v) => v,
        Position::Numeric(x) => panic!("expected an exact position, got {x:?}"),
    }
}

fn numeric(e: &Equilibrium) -> &[f64] {
    match &e.position {
        Position::Numeric(x) => x,
        Position::Exact(v) => panic!("expected a numeric position, got {v:?}"),
    }
}

fn check(s: &Scene, got: &Expr, want: &str) {
    let w = s.expr(want).expect("expected value parses");
    assert!(got.equals(&w), "got {got}, want {want} (= {w})");
    assert_eq!(got, &w, "not in the same canonical form: {got} vs {w}");
}

/// The equilibrium at exactly `want` (one expression per coordinate).
fn at<'a>(s: &Scene, e: &'a Equilibria, want: &[&str]) -> &'a Equilibrium {
    let w: Vec<Expr> = want.iter().map(|x| s.expr(x).unwrap()).collect();
    let found: Vec<&Equilibrium> = e
        .equilibria
        .iter()
        .filter(|x| exact(x).iter().zip(&w).all(|(a, b)| a.equals(b)))
        .collect();
    assert_eq!(
        found.len(),
        1,
        "{want:?} found {} times among {:?}",
        found.len(),
        e.equilibria
            .iter()
            .map(|x| exact(x).iter().map(|v| v.to_string()).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    );
    found[0]
}

/// `qdot equilibrium FILE ARGS…` on a scene in a temporary file.
fn run(tag: &str, src: &str, args: &[&str]) -> (i32, String, String) {
    qdot_on("equilibrium", tag, src, "equilibrium", args)
}

/// The JSON of `qdot equilibrium --format json [--set …]`, checked against
/// the library: the key order, every expression string re-parsing to the
/// library's value, numbers for numeric positions, parallel lists.
fn equilibrium_json(tag: &str, src: &str, set: &str) -> serde_json::Value {
    let mut args = vec!["--format", "json"];
    if !set.is_empty() {
        args.extend(["--set", set]);
    }
    let (code, out, err) = run(tag, src, &args);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    let s = parse(src);
    assert_eq!(
        keys,
        crate::common::contract_keys(&v, &s, &EQUILIBRIUM_KEYS)
    );
    let e = eq(&s, set);
    let names: Vec<&str> = s.coordinates.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(v["coordinates"], serde_json::json!(names));
    for (k, n) in names.iter().enumerate() {
        let f = v["generalized_forces"][n].as_str().unwrap();
        assert_eq!(s.expr(f).unwrap(), e.forces[k], "Q_{n}: {f}");
        let c = v["conditions"][n].as_str().unwrap();
        assert_eq!(s.expr(c).unwrap(), e.conditions[k], "F_{n}: {c}");
        let keys: Vec<&str> = v["generalized_forces"]
            .as_object()
            .unwrap()
            .keys()
            .map(|k| k.as_str())
            .collect();
        assert_eq!(keys, names);
    }
    assert_eq!(v["exact"], e.exact);
    let list = v["equilibria"].as_array().unwrap();
    assert_eq!(list.len(), e.equilibria.len());
    assert_eq!(v["stability"].as_array().unwrap().len(), list.len());
    assert_eq!(v["notes"].as_array().unwrap().len(), list.len());
    for (i, (j, x)) in list.iter().zip(&e.equilibria).enumerate() {
        assert_eq!(v["stability"][i], x.stability.word());
        let keys: Vec<&str> = j.as_object().unwrap().keys().map(|k| k.as_str()).collect();
        assert_eq!(keys, names);
        for (k, n) in names.iter().enumerate() {
            match &x.position {
                Position::Exact(vals) => {
                    let got = j[n].as_str().expect("exact values are strings");
                    if x.free.contains(&k) {
                        assert_eq!(got, "any");
                    } else {
                        assert_eq!(s.expr(got).unwrap(), vals[k], "{n} = {got}");
                    }
                }
                Position::Numeric(xs) => {
                    assert_eq!(j[n].as_f64().expect("numeric values are numbers"), xs[k]);
                }
            }
        }
        let note = v["notes"][i].as_str().unwrap();
        match &x.stability {
            Stability::Undecided(why) => assert!(note.contains(why.as_str()), "{note}"),
            _ => {
                for c in &x.conditions {
                    assert!(note.contains(c.as_str()), "{note}");
                }
            }
        }
    }
    v
}

// ---------------------------------------------------------------- closed forms

const PENDULUM: &str = "coordinates th\nparameters m, l, g\n\
    kinetic E = 1/2*m*l^2*th'^2\npotential V = -m*g*l*cos(th)\n";

#[test]
fn pendulum_hangs_stably_and_stands_unstably() {
    // Q = −m g l sin θ = 0: θ = 0 (V'' = m g l > 0, stable) and
    // θ = π (V'' = −m g l, unstable).
    let s = parse(PENDULUM);
    let e = eq(&s, "");
    assert!(e.exact && !e.kinetic_terms);
    check(&s, &e.forces[0], "-m*g*l*sin(th)");
    assert_eq!(e.equilibria.len(), 2);
    check(&s, &exact(&e.equilibria[0])[0], "0");
    check(&s, &exact(&e.equilibria[1])[0], "pi");
    assert_eq!(e.equilibria[0].stability, Stability::Stable);
    assert_eq!(e.equilibria[1].stability, Stability::Unstable);
    let v = equilibrium_json("pendulum", PENDULUM, "");
    assert_eq!(
        v["equilibria"],
        serde_json::json!([{"th": "0"}, {"th": "pi"}])
    );
    assert_eq!(v["stability"], serde_json::json!(["stable", "unstable"]));
    assert_eq!(v["notes"], serde_json::json!(["", ""]));
    let (code, out, err) = run("pendulum", PENDULUM, &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "Generalized forces  δL = Σ Q_k·δq_k\n  Q_θ = −g·l·m·sin(θ)\n\n\
         Equilibria\n  1. θ = 0  — stable\n  2. θ = π  — unstable\n"
    );
    // the same with --set: the values are shown, the verdicts unchanged
    let (code, out, _) = run("pendulum", PENDULUM, &["--set", "m=2,l=0.5,g=9.81"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("  2. θ = π  ≈ (3.141593)  — unstable\n"),
        "{out}"
    );
}

const HOOP: &str = "coordinates th\nparameters m, r, g, W\n\
    kinetic E = 1/2*m*r^2*(th'^2 + W^2*sin(th)^2)\n\
    potential V = -m*g*r*cos(th)\n";

#[test]
fn bead_on_a_spinning_hoop_relative_equilibria() {
    // At rest the kinetic energy contributes ∂E/∂θ = m r² W² sin θ cos θ:
    //   F = m r² W² sin θ cos θ − m g r sin θ = m r sin θ·(r W² cos θ − g)
    // so θ = 0, π, and cos θ = g/(r W²): θ = ±acos(g/(r W²)) when it exists.
    // K = −F' = m g r cos θ − m r² W² cos 2θ:
    //   θ = 0:  K = m r (g − r W²)  — stable iff r W² < g;
    //   θ = π:  K = −m r (g + r W²) < 0 — unstable;
    //   acos:   K = m r² W² − m g²/W² = m (r² W⁴ − g²)/W² — stable iff it exists.
    let s = parse(HOOP);
    let e = eq(&s, "");
    assert!(e.exact && e.kinetic_terms);
    check(&s, &e.forces[0], "-m*g*r*sin(th)");
    check(&s, &e.conditions[0], "m*r*sin(th)*(r*W^2*cos(th) - g)");
    assert_eq!(e.equilibria.len(), 4);
    let zero = at(&s, &e, &["0"]);
    let Stability::Undecided(why) = &zero.stability else {
        panic!("θ = 0 depends on the parameters: {:?}", zero.stability)
    };
    assert!(
        why.contains("stable when r·W² < g, unstable when r·W² > g"),
        "{why}"
    );
    assert_eq!(at(&s, &e, &["pi"]).stability, Stability::Unstable);
    for root in ["acos(g/(r*W^2))", "-acos(g/(r*W^2))"] {
        let x = at(&s, &e, &[root]);
        assert_eq!(x.conditions, ["|g/(r·W²)| ≤ 1"]);
        let Stability::Undecided(why) = &x.stability else {
            panic!("{root}: {:?}", x.stability)
        };
        assert!(
            why.contains("stable when g < r·W², unstable when g > r·W²"),
            "{why}"
        );
        // cos θ = g/(r W²) indeed
        check(&s, &qdot::expr::func::cos(&exact(x)[0]), "g/(r*W^2)");
    }
    let v = equilibrium_json("hoop", HOOP, "");
    assert_eq!(v["notes"][2], "exists when |g/(r·W²)| ≤ 1; stable when g < r·W², unstable when g > r·W²; give values with --set");

    // Fast: r W² = 25 > g = 9.81. θ = 0 is unstable, the bead rides at
    // θ = ±acos(0.3924) = ±1.16756 (stable).
    let e = eq(&s, "m=1,r=1,g=9.81,W=5");
    assert_eq!(e.equilibria.len(), 4);
    assert_eq!(at(&s, &e, &["0"]).stability, Stability::Unstable);
    assert_eq!(at(&s, &e, &["pi"]).stability, Stability::Unstable);
    for (root, sign) in [("acos(g/(r*W^2))", 1.0), ("-acos(g/(r*W^2))", -1.0)] {
        let x = at(&s, &e, &[root]);
        assert_eq!(x.stability, Stability::Stable, "{root}");
        assert!(x.conditions.is_empty(), "{:?}", x.conditions);
        let approx = x.approx.as_ref().expect("a numeric value")[0];
        assert!(
            (approx - sign * (9.81f64 / 25.0).acos()).abs() < 1e-12,
            "{approx}"
        );
    }
    equilibrium_json("hoop", HOOP, "m=1,r=1,g=9.81,W=5");
    // Slow: r W² = 4 < g. acos(9.81/4) does not exist: two equilibria left.
    let e = eq(&s, "m=1,r=1,g=9.81,W=2");
    assert_eq!(e.equilibria.len(), 2);
    assert_eq!(at(&s, &e, &["0"]).stability, Stability::Stable);
    assert_eq!(at(&s, &e, &["pi"]).stability, Stability::Unstable);
    let v = equilibrium_json("hoop", HOOP, "m=1,r=1,g=9.81,W=2");
    assert_eq!(v["stability"], serde_json::json!(["stable", "unstable"]));
    // Some values only: the existence conditions stay
    let e = eq(&s, "m=1,r=1,g=9.81");
    assert_eq!(e.equilibria.len(), 4);
    assert_eq!(at(&s, &e, &["acos(g/(r*W^2))"]).conditions.len(), 1);
}

#[test]
fn the_spinning_hoop_three_ways_has_the_same_equilibria() {
    // The bead at r = a·(sin θ cos Wt, sin θ sin Wt, −cos θ) in space: by its
    // kinetic energy (t cancels: E = ½ m a² (θ'² + W² sin² θ)), and in
    // D'Alembert's form with the inertia force as a load.
    let given = parse(
        "coordinates th\nparameters m, a, g, W\n\
         kinetic E = 1/2*m*a^2*(th'^2 + W^2*sin(th)^2)\npotential V = -m*g*a*cos(th)\n",
    );
    let space = parse(
        "coordinates th\nparameters m, a, g, W\n\
         r = a*[sin(th)*cos(W*t), sin(th)*sin(W*t), -cos(th)]\n\
         kinetic E = 1/2*m*dot(r', r')\nload [0, 0, -m*g] at r\n",
    );
    let dalembert = parse(
        "coordinates th\nparameters m, a, g, W\n\
         r = a*[sin(th)*cos(W*t), sin(th)*sin(W*t), -cos(th)]\n\
         load [0, 0, -m*g] - inertia(m, r) at r\n",
    );
    let l = space.lagrange().unwrap();
    check(&space, &l.kinetic, "1/2*m*a^2*(th'^2 + W^2*sin(th)^2)");
    let base = eq(&given, "");
    for s in [&space, &dalembert] {
        let e = eq(s, "");
        assert_eq!(e.conditions, base.conditions);
        assert_eq!(e.equilibria.len(), 4);
        for (x, y) in e.equilibria.iter().zip(&base.equilibria) {
            assert_eq!(exact(x), exact(y));
            assert_eq!(x.stability, y.stability);
        }
    }
    // D'Alembert: the centrifugal term is in Q itself (no kinetic energy)
    let e = eq(&dalembert, "");
    assert!(!e.kinetic_terms);
    check(&dalembert, &e.forces[0], "m*a*sin(th)*(a*W^2*cos(th) - g)");
    // and the accelerations agree
    let acc = |s: &Scene| s.lagrange().unwrap().accelerations().unwrap();
    assert_eq!(acc(&space), acc(&given));
    assert_eq!(acc(&dalembert), acc(&given));
}

#[test]
fn hoop_at_the_bifurcation_is_consistent() {
    // r W² = g: F = m g r sin θ (cos θ − 1) ≈ −m g r θ³/2, V ≈ m g r θ⁴/8:
    // θ = 0 is (weakly) stable, and the acos roots are θ = 0 again.
    let s = parse(HOOP);
    let e = eq(&s, "m=1,r=1,g=4,W=2");
    assert_eq!(at(&s, &e, &["0"]).stability, Stability::Stable);
    for x in &e.equilibria {
        let v = x.approx.as_ref().unwrap()[0];
        if v.abs() < 1e-9 {
            assert_eq!(x.stability, Stability::Stable, "θ = {}", exact(x)[0]);
        }
    }
}

#[test]
fn a_pendulum_with_a_constant_torque() {
    // Q = −m g l sin θ + M: sin θ = M/(m g l). θ = asin(x) (K = m g l cos θ
    // > 0, stable) and π − asin(x) (unstable), when x ≤ 1.
    let src = "coordinates th\nparameters m, g, l, M\n\
               kinetic E = 1/2*m*l^2*th'^2\npotential V = -m*g*l*cos(th)\n\
               torque M on th\n";
    let s = parse(src);
    let e = eq(&s, "");
    assert_eq!(e.equilibria.len(), 2);
    let a = at(&s, &e, &["asin(M/(m*g*l))"]);
    assert_eq!(a.stability, Stability::Stable);
    assert_eq!(a.conditions, ["|M/(g·l·m)| ≤ 1"]);
    let b = at(&s, &e, &["pi - asin(M/(m*g*l))"]);
    assert_eq!(b.stability, Stability::Unstable);
    check(&s, &qdot::expr::func::sin(&exact(b)[0]), "M/(m*g*l)");
    equilibrium_json("torque", src, "");
    // M = m g l/2: θ = π/6 and 5π/6
    let e = eq(&s, "m=1,g=1,l=1,M=0.5");
    let mut v: Vec<f64> = e
        .equilibria
        .iter()
        .map(|x| x.approx.as_ref().unwrap()[0])
        .collect();
    v.sort_by(f64::total_cmp);
    assert_eq!(v.len(), 2);
    assert!((v[0] - std::f64::consts::FRAC_PI_6).abs() < 1e-12, "{v:?}");
    assert!(
        (v[1] - 5.0 * std::f64::consts::FRAC_PI_6).abs() < 1e-12,
        "{v:?}"
    );
    // M > m g l: the torque wins, no equilibrium
    assert!(eq(&s, "m=1,g=1,l=1,M=2").equilibria.is_empty());
    let (code, out, _) = run("torque", src, &["--set", "m=1,g=1,l=1,M=2"]);
    assert_eq!(code, 0);
    assert!(out.ends_with("\nEquilibria\n  none\n"), "{out}");
}

#[test]
fn a_pendulum_with_the_critical_torque() {
    let s = parse(
        "coordinates th\nparameters m, g, l, M\n\
         kinetic E = 1/2*m*l^2*th'^2\npotential V = -m*g*l*cos(th)\ntorque M on th\n",
    );
    let e = eq(&s, "m=1,g=1,l=1,M=1");
    for x in &e.equilibria {
        let v = x.approx.as_ref().unwrap()[0];
        assert!((v - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{v}");
        assert_ne!(x.stability, Stability::Stable, "θ = {}", exact(x)[0]);
    }
}

#[test]
fn a_hanging_spring_chain_is_solved_linearly() {
    // y down, springs of zero natural length: spring 3 carries m3 g, spring 2
    // (m2 + m3) g, spring 1 (m1 + m2 + m3) g, so
    //   y1 = (m1 + m2 + m3) g/k1, y2 = y1 + (m2 + m3) g/k2, y3 = y2 + m3 g/k3.
    // K is tridiagonal with leading minors k1 + k2, k1k2 + k1k3 + k2k3,
    // k1k2k3 > 0: stable.
    let src = "coordinates y1, y2, y3\nparameters m1, m2, m3, k1, k2, k3, g\n\
               kinetic E = 1/2*m1*y1'^2 + 1/2*m2*y2'^2 + 1/2*m3*y3'^2\n\
               potential V = 1/2*k1*y1^2 + 1/2*k2*(y2 - y1)^2 + 1/2*k3*(y3 - y2)^2 \
               - g*(m1*y1 + m2*y2 + m3*y3)\n";
    let s = parse(src);
    let e = eq(&s, "");
    assert!(e.exact);
    assert_eq!(e.equilibria.len(), 1);
    let x = exact(&e.equilibria[0]);
    check(&s, &x[0], "(m1 + m2 + m3)*g/k1");
    check(&s, &x[1], "(m1 + m2 + m3)*g/k1 + (m2 + m3)*g/k2");
    check(&s, &x[2], "(m1 + m2 + m3)*g/k1 + (m2 + m3)*g/k2 + m3*g/k3");
    assert_eq!(e.equilibria[0].stability, Stability::Stable);
    check(&s, &e.forces[2], "-k3*(y3 - y2) + m3*g");
    equilibrium_json("springs", src, "");
    // Pulled sideways by F on a horizontal chain: x1 = F/k1, x2 = F/k1 + F/k2
    let s = parse(
        "coordinates x1, x2\nparameters k1, k2, F\n\
         potential V = 1/2*k1*x1^2 + 1/2*k2*(x2 - x1)^2\nload F at x2\n",
    );
    let e = eq(&s, "");
    let x = exact(&e.equilibria[0]);
    check(&s, &x[0], "F/k1");
    check(&s, &x[1], "F/k1 + F/k2");
    assert_eq!(e.equilibria[0].stability, Stability::Stable);
    // Two masses joined by a spring and nothing else, V = ½k(x2 − x1)²:
    // x2 = x1 with x1 free (the pair may sit anywhere), neutral.
    let s = parse("coordinates x1, x2\nparameters k\npotential V = 1/2*k*(x2 - x1)^2\n");
    let e = eq(&s, "");
    assert_eq!(e.equilibria.len(), 1);
    assert_eq!(e.equilibria[0].free.len(), 1);
    let Stability::Undecided(why) = &e.equilibria[0].stability else {
        panic!("{:?}", e.equilibria[0].stability)
    };
    assert!(why.contains("neutral"), "{why}");
}

#[test]
fn neutral_coordinates_are_any() {
    // V = ½ k y²: y = 0, x anything.
    let src = "coordinates x, y\nparameters k, m\n\
               kinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = 1/2*k*y^2\n";
    let s = parse(src);
    let e = eq(&s, "");
    assert_eq!(e.equilibria.len(), 1);
    assert_eq!(e.equilibria[0].free, [0]);
    check(&s, &exact(&e.equilibria[0])[1], "0");
    let v = equilibrium_json("neutral", src, "");
    assert_eq!(v["equilibria"], serde_json::json!([{"x": "any", "y": "0"}]));
    assert_eq!(v["stability"], serde_json::json!(["undecided"]));
    assert_eq!(
        v["notes"],
        serde_json::json!(["neutral: a coordinate is free"])
    );
    let (_, out, _) = run("neutral", src, &[]);
    assert!(
        out.contains("  1. x = any, y = 0  — undecided (neutral: a coordinate is free)\n"),
        "{out}"
    );
}

#[test]
fn polynomial_equilibria_and_higher_order_stability() {
    // Double well V = a x⁴/4 − b x²/2: F = x (b − a x²): x = 0 (K = −b,
    // unstable) and x = ±√(b/a) (K = 3a x² − b = 2b, stable).
    let s = parse(
        "coordinates x\nparameters a, b, m\nkinetic E = 1/2*m*x'^2\n\
         potential V = a*x^4/4 - b*x^2/2\n",
    );
    let e = eq(&s, "");
    assert_eq!(e.equilibria.len(), 3);
    assert_eq!(at(&s, &e, &["0"]).stability, Stability::Unstable);
    assert_eq!(at(&s, &e, &["sqrt(b/a)"]).stability, Stability::Stable);
    assert_eq!(at(&s, &e, &["-sqrt(b/a)"]).stability, Stability::Stable);
    // K = 0: the first non-vanishing derivative of V decides
    for (v, want) in [
        ("k*x^4", Stability::Stable),
        ("-k*x^4", Stability::Unstable),
        ("k*x^3", Stability::Unstable),
        ("k*x^6", Stability::Stable),
    ] {
        let s = parse(&format!(
            "coordinates x\nparameters k, m\nkinetic E = 1/2*m*x'^2\npotential V = {v}\n"
        ));
        let e = eq(&s, "");
        assert_eq!(e.equilibria.len(), 1, "{v}");
        check(&s, &exact(&e.equilibria[0])[0], "0");
        assert_eq!(e.equilibria[0].stability, want, "V = {v}");
    }
    // a constant force: no equilibrium at all
    let s = parse("coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload F at x\n");
    let e = eq(&s, "");
    assert!(e.exact && e.equilibria.is_empty());
    let (code, out, _) = run("constant-force", &s.source, &[]);
    assert_eq!(code, 0);
    assert!(out.ends_with("\nEquilibria\n  none\n"), "{out}");
}

#[test]
fn a_sum_of_sine_and_cosine_by_the_half_angle() {
    // sin θ + cos θ = 1/2. With t = tan(θ/2): 2t + 1 − t² = (1 + t²)/2, so
    // 3t² − 4t − 1 = 0, t = (2 ± √7)/3 and θ = 2·atan((2 ± √7)/3):
    // √2·sin(θ + π/4) = 1/2 gives θ ≈ −0.42403 and ≈ 1.99483.
    let s = parse("coordinates th\nforce th: sin(th) + cos(th) - 1/2\n");
    let e = eq(&s, "");
    assert!(e.exact);
    assert_eq!(e.equilibria.len(), 2);
    let r1 = at(&s, &e, &["2*atan((2 + sqrt(7))/3)"]);
    let r2 = at(&s, &e, &["2*atan((2 - sqrt(7))/3)"]);
    let a = (1.0 / (2.0 * 2f64.sqrt())).asin();
    let val = |x: &Equilibrium| exact(x)[0].eval_f64(&|_| None).unwrap();
    assert!((val(r1) - (std::f64::consts::PI - a - std::f64::consts::FRAC_PI_4)).abs() < 1e-12);
    assert!((val(r2) - (a - std::f64::consts::FRAC_PI_4)).abs() < 1e-12);
    // K = −F' = sin θ − cos θ: > 0 at 1.99 (stable), < 0 at −0.42 (unstable)
    assert_eq!(r1.stability, Stability::Stable);
    assert_eq!(r2.stability, Stability::Unstable);
    equilibrium_json("half-angle", &s.source, "");
}

// ---------------------------------------------------------------- acceptance

/// Three bars of length 2l hinged in a chain at O, weights G at their
/// middles, a horizontal force P at the free end; y points down, θi are
/// absolute angles from the vertical. By hand (eq. 23.11):
///   middle of bar i: Σ_{j<i} 2l·e_j + l·e_i, free end: 2l·(e1 + e2 + e3),
///   e_j = (sin θj, cos θj);
///   Q1 = −G l s1 − 2G l s1 − 2G l s1 + 2P l c1 = −5G l s1 + 2P l c1
///   Q2 = −3G l s2 + 2P l c2,  Q3 = −G l s3 + 2P l c3.
/// Equilibrium: tan θ1 = 2P/(5G), tan θ2 = 2P/(3G), tan θ3 = 2P/G; each
/// also − π (a bar pointing up). K = diag(5Gl c1 + 2Pl s1, …) is positive
/// only with every bar hanging: that one is stable, the 7 others unstable.
const THREE_BARS: &str = "coordinates theta1, theta2, theta3\nparameters G, P, l\n\
    e1 = [sin(theta1), cos(theta1)]\n\
    e2 = [sin(theta2), cos(theta2)]\n\
    e3 = [sin(theta3), cos(theta3)]\n\
    load [0, G] at l*e1\n\
    load [0, G] at 2*l*e1 + l*e2\n\
    load [0, G] at 2*l*(e1 + e2) + l*e3\n\
    load [P, 0] at 2*l*(e1 + e2 + e3)\n";

#[test]
fn three_bar_chain_with_a_horizontal_force() {
    let s = parse(THREE_BARS);
    let q = qdot::mechanics::generalized_forces(&s);
    check(&s, &q[0], "-5*G*l*sin(theta1) + 2*P*l*cos(theta1)");
    check(&s, &q[1], "-3*G*l*sin(theta2) + 2*P*l*cos(theta2)");
    check(&s, &q[2], "-G*l*sin(theta3) + 2*P*l*cos(theta3)");
    let e = eq(&s, "");
    assert!(e.exact && !e.kinetic_terms);
    assert_eq!(e.equilibria.len(), 8);
    let tans = ["2*P/(5*G)", "2*P/(3*G)", "2*P/G"];
    let mut stable = 0;
    for mask in 0..8 {
        let want: Vec<String> = (0..3)
            .map(|i| {
                if mask & (1 << i) == 0 {
                    format!("atan({})", tans[i])
                } else {
                    format!("atan({}) - pi", tans[i])
                }
            })
            .collect();
        let want: Vec<&str> = want.iter().map(|x| x.as_str()).collect();
        let x = at(&s, &e, &want);
        for (i, v) in exact(x).iter().enumerate() {
            check(&s, &qdot::expr::func::tan(v).unwrap(), tans[i]);
        }
        if mask == 0 {
            assert_eq!(x.stability, Stability::Stable, "the hanging chain");
            stable += 1;
        } else {
            assert_eq!(x.stability, Stability::Unstable, "{want:?}");
        }
    }
    assert_eq!(stable, 1);
    let v = equilibrium_json("three-bars", THREE_BARS, "");
    assert_eq!(
        v["equilibria"][0],
        serde_json::json!({
            "theta1": "atan(2*P/(5*G))",
            "theta2": "atan(2*P/(3*G))",
            "theta3": "atan(2*P/G)"
        })
    );
    assert_eq!(v["stability"][0], "stable");
    // numerically, with G = 1, P = 1: θ ≈ (0.3805, 0.5880, 1.1071)
    let e = eq(&s, "G=1,P=1,l=1");
    let x = at(&s, &e, &["atan(2/5*P/G)", "atan(2/3*P/G)", "atan(2*P/G)"]);
    let a = x.approx.as_ref().unwrap();
    for (got, want) in a
        .iter()
        .zip([0.4f64.atan(), (2.0f64 / 3.0).atan(), 2f64.atan()])
    {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}

/// A spherical pendulum with a constant horizontal force F along x:
/// r = l·(sin θ cos φ, sin θ sin φ, −cos θ), loads [0, 0, −m g] and
/// [F, 0, 0] at r. Q_θ = F l cos θ cos φ − m g l sin θ,
/// Q_φ = −F l sin θ sin φ. Q_φ = 0: sin θ = 0 or sin φ = 0.
///   φ = 0: tan θ = F/(m g): θ = atan(F/(m g)) (the bob deflected along the
///   force, K = diag(l·√(F² + m²g²), F² l/√(F² + m²g²)) > 0: stable) and
///   atan(F/(m g)) − π (above the pivot: unstable).
///   φ = π: tan θ = −F/(m g), the same two points again (θ → −θ).
///   θ = 0 or π: Q_θ = ±F l cos φ = 0 at φ = ±π/2 (the chart's poles;
///   det K = −F² l² < 0 there: unstable).
const SPHERICAL: &str = "coordinates th, ph\nparameters m, g, l, F\n\
    r = l*[sin(th)*cos(ph), sin(th)*sin(ph), -cos(th)]\n\
    kinetic E = 1/2*m*dot(r', r')\n\
    load [0, 0, -m*g] at r\n\
    load [F, 0, 0] at r\n";

#[test]
fn spherical_pendulum_with_a_horizontal_force() {
    let s = parse(SPHERICAL);
    let e = eq(&s, "");
    check(&s, &e.forces[0], "F*l*cos(th)*cos(ph) - m*g*l*sin(th)");
    check(&s, &e.forces[1], "-F*l*sin(th)*sin(ph)");
    // E = ½ m l² (θ'² + sin² θ φ'²) has no terms at rest
    assert!(!e.kinetic_terms);
    assert!(e.exact);
    assert_eq!(e.equilibria.len(), 8);
    let x = at(&s, &e, &["atan(F/(m*g))", "0"]);
    assert_eq!(x.stability, Stability::Stable);
    check(&s, &qdot::expr::func::tan(&exact(x)[0]).unwrap(), "F/(m*g)");
    assert_eq!(
        at(&s, &e, &["atan(F/(m*g)) - pi", "0"]).stability,
        Stability::Unstable
    );
    assert_eq!(
        at(&s, &e, &["-atan(F/(m*g))", "pi"]).stability,
        Stability::Stable
    );
    assert_eq!(
        at(&s, &e, &["pi - atan(F/(m*g))", "pi"]).stability,
        Stability::Unstable
    );
    // at the poles sin θ = 0 leaves φ without inertia (M singular): they
    // are equilibria of the chart, not of the pendulum, and no verdict
    // rests on a singular kinetic energy
    for pole in [
        ["0", "pi/2"],
        ["0", "-pi/2"],
        ["pi", "pi/2"],
        ["pi", "-pi/2"],
    ] {
        assert!(
            matches!(&at(&s, &e, &pole).stability,
                Stability::Undecided(why) if why.starts_with("the mass matrix is singular here")),
            "{pole:?}"
        );
    }
    equilibrium_json("spherical", SPHERICAL, "");
    // the deflection for m g = F: 45°
    let e = eq(&s, "m=1,g=2,l=1,F=2");
    let x = at(&s, &e, &["atan(F/(m*g))", "0"]);
    assert!((x.approx.as_ref().unwrap()[0] - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
}

// ---------------------------------------------------------------- numeric

/// f64 value of `e` at coordinate values `x` and parameters `set`.
fn eval(e: &Expr, coords: &[&str], x: &[f64], set: &[(&str, f64)]) -> f64 {
    use qdot::expr::atom::Atom;
    e.eval_f64(&|a| match a {
        Atom::Param(n) => set.iter().find(|(p, _)| *p == &**n).map(|(_, v)| *v),
        Atom::Coord(n, 0) => coords.iter().position(|c| *c == &**n).map(|i| x[i]),
        _ => None,
    })
    .unwrap()
}

/// The roots of f on [lo, hi] by sign changes on a fine grid (simple roots;
/// choose bounds so that no grid point is a root).
fn sign_changes(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Vec<f64> {
    let n = 400_000;
    let mut out = Vec::new();
    let mut prev = f(lo);
    for i in 1..=n {
        let x = lo + (hi - lo) * i as f64 / n as f64;
        let v = f(x);
        if (v > 0.0) != (prev > 0.0) {
            out.push(x);
        }
        prev = v;
    }
    out
}

#[test]
fn no_closed_form_needs_parameter_values() {
    // a·sin θ − b·θ = 0 has no closed form (besides θ = 0).
    let src = "coordinates th\nparameters a, b\nforce th: a*sin(th) - th*b\n";
    let (code, out, err) = run("numeric-missing", src, &[]);
    assert_eq!(code, 1);
    assert!(out.is_empty(), "{out}");
    assert_eq!(
        err,
        "error: no closed form for these equilibrium equations; they can be solved numerically given parameter values\n  \
         = hint: give values for a, b with `--set a=…,b=…`\n"
    );
    // only the missing ones are named
    let (code, _, err) = run("numeric-missing", src, &["--set", "a=3"]);
    assert_eq!(code, 1);
    assert!(err.contains("give values for b with `--set b=…`"), "{err}");
    let s = parse(src);
    let values = qdot::output::parse_set("b=1").unwrap();
    let d = equilibria(&s, &values).unwrap_err();
    assert!(d.message.starts_with("no closed form"), "{}", d.message);
    assert!(
        d.hint
            .as_deref()
            .unwrap()
            .contains("give values for a with"),
        "{d:?}"
    );
}

#[test]
fn numeric_roots_of_a_sin_theta_minus_b_theta() {
    // 10·sin θ = θ: roots in |θ| ≤ 10, seven of them (0, ±2.852, ±7.068,
    // ±8.423); K = −F' = b − a·cos θ alternates: stable where cos θ > b/a.
    let src = "coordinates th\nparameters a, b\nforce th: a*sin(th) - th*b\n";
    let s = parse(src);
    let e = eq(&s, "a=10,b=1");
    assert!(!e.exact);
    let f = |x: f64| 10.0 * x.sin() - x;
    let want = sign_changes(f, -11.0, 11.3);
    assert_eq!(want.len(), 7);
    assert_eq!(e.equilibria.len(), want.len());
    let mut got: Vec<f64> = e.equilibria.iter().map(|x| numeric(x)[0]).collect();
    got.sort_by(f64::total_cmp);
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-3, "{g} vs grid {w}");
        assert!(f(*g).abs() < 1e-9, "F({g}) = {}", f(*g));
        assert!(eval(&e.conditions[0], &["th"], &[*g], &[("a", 10.0), ("b", 1.0)]).abs() < 1e-9);
    }
    for x in &e.equilibria {
        let th = numeric(x)[0];
        let k = 1.0 - 10.0 * th.cos();
        let want = if k > 0.0 {
            Stability::Stable
        } else {
            Stability::Unstable
        };
        assert_eq!(x.stability, want, "θ = {th}");
        assert!(x.approx.is_none() && x.conditions.is_empty());
    }
    // symmetric pairs, and 0 exactly
    assert!(got.iter().any(|x| x.abs() < 1e-12));
    for (lo, hi) in got.iter().zip(got.iter().rev()) {
        assert!((lo + hi).abs() < 1e-9, "{lo} vs {hi}");
    }
    let v = equilibrium_json("numeric-sin", src, "a=10,b=1");
    assert_eq!(v["exact"], false);
    assert_eq!(v["equilibria"].as_array().unwrap().len(), 7);
    // a = 3, b = 1: three roots, θ = ±2.27886 stable and 0 unstable
    let e = eq(&s, "a=3,b=1");
    let mut got: Vec<(f64, &str)> = e
        .equilibria
        .iter()
        .map(|x| (numeric(x)[0], x.stability.word()))
        .collect();
    got.sort_by(|p, q| p.0.total_cmp(&q.0));
    assert_eq!(got.len(), 3);
    assert!((got[2].0 - 2.278_862_660_075_828).abs() < 1e-9, "{got:?}");
    assert_eq!(
        got.iter().map(|p| p.1).collect::<Vec<_>>(),
        ["stable", "unstable", "stable"]
    );
    let (code, out, _) = run("numeric-sin", src, &["--set", "a=3,b=1"]);
    assert_eq!(code, 0);
    assert!(
        out.ends_with(
            "\nEquilibria (numeric: no closed form)\n  (found by Newton's method from many starting points: \
             roots far from them may be missed; digits shown are certified by a sign change)\n  \
             1. θ = −2.278862660076  — stable\n  2. θ = 0  — unstable\n  3. θ = 2.278862660076  — stable\n"
        ),
        "{out}"
    );
}

#[test]
fn numeric_roots_of_x_minus_c_cos_x() {
    // x = c·cos x. c = 1: the Dottie number 0.739085…, K = −(1 + sin x) < 0.
    let src = "coordinates x\nparameters c\nforce x: x - cos(x)*c\n";
    let s = parse(src);
    let e = eq(&s, "c=1");
    assert_eq!(e.equilibria.len(), 1);
    let x = numeric(&e.equilibria[0])[0];
    assert!((x - 0.739_085_133_215_160_6).abs() < 1e-12, "{x}");
    assert_eq!(e.equilibria[0].stability, Stability::Unstable);
    // c = 10: seven roots in |x| ≤ 10
    let e = eq(&s, "c=10");
    let f = |x: f64| x - 10.0 * x.cos();
    let want = sign_changes(f, -11.0, 11.0);
    assert_eq!(want.len(), 7);
    let mut got: Vec<f64> = e.equilibria.iter().map(|x| numeric(x)[0]).collect();
    got.sort_by(f64::total_cmp);
    assert_eq!(got.len(), 7, "{got:?}");
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-3 && f(*g).abs() < 1e-9, "{g} vs {w}");
    }
    for x in &e.equilibria {
        let v = numeric(x)[0];
        // K = −F' = −(1 + 10 sin x)
        let stable = -(1.0 + 10.0 * v.sin()) > 0.0;
        assert_eq!(x.stability == Stability::Stable, stable, "x = {v}");
    }
    equilibrium_json("numeric-cos", src, "c=10");
}

#[test]
fn numeric_roots_of_a_periodic_equation_are_wrapped() {
    // sin θ = c·cos³ θ has no closed form (degree 4 in tan(θ/2)); F(θ + π)
    // = −F(θ), so with c = 1 there are two roots in (−π, π]: θ0 ≈ 0.59877
    // (K = −(cos θ + 3 cos² θ sin θ) < 0, unstable) and θ0 − π (stable).
    let s = parse("coordinates th\nparameters c\nforce th: sin(th) - c*cos(th)^3\n");
    let e = eq(&s, "c=1");
    assert!(!e.exact);
    let f = |x: f64| x.sin() - x.cos().powi(3);
    let mut got: Vec<(f64, Stability)> = e
        .equilibria
        .iter()
        .map(|x| (numeric(x)[0], x.stability.clone()))
        .collect();
    got.sort_by(|p, q| p.0.total_cmp(&q.0));
    assert_eq!(got.len(), 2, "{got:?}");
    let want = sign_changes(f, -std::f64::consts::PI, std::f64::consts::PI);
    assert_eq!(want.len(), 2);
    for ((g, _), w) in got.iter().zip(&want) {
        assert!(*g > -std::f64::consts::PI - 1e-12 && *g <= std::f64::consts::PI);
        assert!((g - w).abs() < 1e-3 && f(*g).abs() < 1e-9, "{g} vs {w}");
    }
    assert!((got[1].0 - got[0].0 - std::f64::consts::PI).abs() < 1e-9);
    assert_eq!(got[0].1, Stability::Stable);
    assert_eq!(got[1].1, Stability::Unstable);
}

#[test]
fn a_multiple_root_is_one_equilibrium() {
    // F = −k (x − 1)³: V = k (x − 1)⁴/4, one equilibrium x = 1, a minimum,
    // found exactly (by factoring) with its multiplicity
    let s = parse("coordinates x\nparameters k\nforce x: -k*(x - 1)^3\n");
    let e = eq(&s, "k=1");
    assert!(e.exact);
    assert_eq!(e.equilibria.len(), 1, "{:?}", e.equilibria);
    let one = at(&s, &e, &["1"]);
    assert_eq!(one.multiplicity, 3);
    assert_eq!(one.stability, Stability::Stable);
    // in two coordinates: V ≥ 0 vanishes only at (1/2, 1/2)
    let s =
        parse("coordinates x, y\nparameters k\npotential V = k*(x - y)^2/2 + k*(x + y - 1)^4\n");
    let e = eq(&s, "k=1");
    assert_eq!(e.equilibria.len(), 1, "{:?}", e.equilibria);
}

#[test]
fn a_double_root_and_a_simple_one_numerically() {
    // F = −k (x − 1)² (x + 2) (degree 3: no closed form is tried).
    //   x = −2: F'(−2) = −9k, K = −F' = 9k > 0, stable;
    //   x = 1, a double root: F ≤ 0 on both sides, unstable.
    // (found exactly by factoring: each root once, with its multiplicity)
    let s = parse("coordinates x\nparameters k\nforce x: -k*(x - 1)^2*(x + 2)\n");
    let e = eq(&s, "k=1");
    assert!(e.exact);
    assert_eq!(e.equilibria.len(), 2, "{:?}", e.equilibria);
    let simple = at(&s, &e, &["-2"]);
    assert_eq!(
        (simple.multiplicity, &simple.stability),
        (1, &Stability::Stable)
    );
    let double = at(&s, &e, &["1"]);
    assert_eq!(
        (double.multiplicity, &double.stability),
        (2, &Stability::Unstable)
    );
}

#[test]
fn two_coupled_transcendental_equations() {
    // F1 = a·sin x − y, F2 = x − b·y, not derived from a potential
    // (∂F1/∂y = −1 but ∂F2/∂x = 1). y = x/b and a·sin x = x/b: with a = 2,
    // b = 1, x = 2·sin x: x = y = 0 and x = y = ±1.895494267033981.
    let src = "coordinates x, y\nparameters a, b\nforce x: a*sin(x) - y\nforce y: x - y*b\n";
    let s = parse(src);
    let e = eq(&s, "a=2,b=1");
    assert!(!e.exact);
    let mut got: Vec<Vec<f64>> = e.equilibria.iter().map(|x| numeric(x).to_vec()).collect();
    got.sort_by(|p, q| p[0].total_cmp(&q[0]));
    assert_eq!(got.len(), 3, "{got:?}");
    for (p, want) in got
        .iter()
        .zip([-1.895_494_267_033_981, 0.0, 1.895_494_267_033_981])
    {
        assert!((p[0] - want).abs() < 1e-9, "{p:?}");
        assert!((p[1] - want).abs() < 1e-9, "{p:?}");
        for c in &e.conditions {
            assert!(eval(c, &["x", "y"], p, &[("a", 2.0), ("b", 1.0)]).abs() < 1e-9);
        }
    }
    // ∂Q_x/∂y = −1 ≠ ∂Q_y/∂x = 1: not conservative, so undecided
    for x in &e.equilibria {
        let Stability::Undecided(why) = &x.stability else {
            panic!("{:?}", x.stability)
        };
        assert!(why.contains("not conservative"), "{why}");
    }
    equilibrium_json("coupled", src, "a=2,b=1");
}

// ---------------------------------------------------------------- errors

#[test]
fn set_errors_and_time_dependence() {
    let cases: &[(&str, &str)] = &[
        (
            "z=1",
            "error: `--set z=…`: `z` is not a parameter of the scene\n  = hint: the parameters are m, l, g\n",
        ),
        (
            "m=abc",
            "error: `--set m=abc`: `abc` is not a number\n  = hint: write numbers or constant expressions: --set m=1.5,g=9.81,Omega=2*pi\n",
        ),
        (
            "m=1,g=inf",
            "error: `--set g=inf`: `inf` is not a number\n",
        ),
        (
            "m=0",
            "error: `--set m=0`: parameters are positive, and 0 is not\n",
        ),
        (
            "l=-2.5",
            "error: `--set l=-2.5`: parameters are positive, and -2.5 is not\n",
        ),
        (
            "m",
            "error: `--set m`: expected name=value\n  = hint: for example --set m=1,g=9.81,l=0.5\n",
        ),
    ];
    for (set, want) in cases {
        let (code, out, err) = run("set-errors", PENDULUM, &["--set", set]);
        assert_eq!(code, 1, "--set {set}");
        assert!(out.is_empty(), "{out}");
        assert!(err.starts_with(want), "--set {set}:\n{err}\nwant:\n{want}");
    }
    // the library parses the same way
    assert!(qdot::output::parse_set("m=1, g = 9.81 ,").is_ok());
    let v = qdot::output::parse_set("m=1.5,g=9.81").unwrap();
    assert_eq!(v["m"], 1.5);
    assert_eq!(v["g"], 9.81);
    // explicit time: no static equilibrium
    let src = "coordinates x\nparameters m, k, F0, w\nkinetic E = 1/2*m*x'^2\n\
               potential V = 1/2*k*x^2\nwork L = F0*cos(w*t)*x\n";
    let (code, _, err) = run("time", src, &[]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with(
            "error: the force on `x` depends on time, so there is no static equilibrium\n"
        ),
        "{err}"
    );
    // time in the kinematics that does not cancel: a driven support
    let s = parse(
        "coordinates th\nparameters m, l, a, w, g\n\
         x = a*cos(w*t) + l*sin(th)\ny = -l*cos(th)\n\
         kinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = m*g*y\n",
    );
    let d = equilibria(&s, &Default::default()).unwrap_err();
    assert!(d.message.contains("depends on time"), "{}", d.message);
    // no coordinates
    let (code, _, err) = run("no-coordinates", "parameters a\nb = 2*a\n", &[]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with(
            "error: the scene declares no coordinates, so there is no equilibrium to find\n"
        ),
        "{err}"
    );
}

#[test]
fn dalembert_scenes_are_taken_at_rest() {
    // seed 22.3 (virtual work with inertia loads): at rest the inertia
    // forces vanish, Q = (4G, G r) — constant, so no equilibrium; the same
    // as seed 21.2 by Lagrange.
    let read = |n: &str| {
        std::fs::read_to_string(format!("{}/examples/{n}.qd", env!("QDOT_ROOT"))).unwrap()
    };
    let a = parse(&read("seed_22_3"));
    let b = parse(&read("seed_21_2"));
    let ea = eq(&a, "");
    let eb = eq(&b, "");
    assert_eq!(ea.forces, eb.forces);
    check(&a, &ea.forces[0], "4*G");
    check(&a, &ea.forces[1], "G*r");
    assert!(ea.equilibria.is_empty() && eb.equilibria.is_empty());
    // seed 23.1: two bars, tan θ1 = 2P/(3G), tan θ2 = 2P/G, hanging stable
    let s = parse(&read("seed_23_1"));
    let e = eq(&s, "");
    assert_eq!(
        at(&s, &e, &["atan(2*P/(3*G))", "atan(2*P/G)"]).stability,
        Stability::Stable
    );
    equilibrium_json("seed-23-1", &read("seed_23_1"), "");
}

#[test]
fn gyroscopic_terms_and_jacobis_rule() {
    // A particle on a plane turning at the rate W, in the turning frame:
    // E = ½m((x' − W y)² + (y' + W x)²) has the Coriolis terms
    // m W (x y' − y x'), linear in the velocities (gyroscopic), and the
    // centrifugal ½ m W² (x² + y²), which acts at rest.
    let rotating = "coordinates x, y\nparameters m, k, c, W\n\
                    kinetic E = 1/2*m*((x' - W*y)^2 + (y' + W*x)^2)\n";
    // On a hill V = −½k(x² + y²): F = (k + m W²)·(x, y), only (0, 0), with
    // K = −(k + m W²)·I: two negative directions, which gyroscopic forces
    // may stabilize: undecided (and unstable without the rotation).
    let s = parse(&format!("{rotating}potential V = -1/2*k*(x^2 + y^2)\n"));
    let e = eq(&s, "");
    assert!(e.kinetic_terms);
    check(&s, &e.conditions[0], "(k + m*W^2)*x");
    check(&s, &e.conditions[1], "(k + m*W^2)*y");
    assert_eq!(e.equilibria.len(), 1);
    let Stability::Undecided(why) = &e.equilibria[0].stability else {
        panic!("{:?}", e.equilibria[0].stability)
    };
    assert!(why.contains("2 negative directions"), "{why}");
    assert!(why.contains("gyroscopic"), "{why}");
    let s = parse(
        "coordinates x, y\nparameters m, k\nkinetic E = 1/2*m*(x'^2 + y'^2)\n\
         potential V = -1/2*k*(x^2 + y^2)\n",
    );
    assert_eq!(eq(&s, "").equilibria[0].stability, Stability::Unstable);
    // A saddle V = ½k x² − ½c y²: K = diag(k − m W², −c − m W²). With
    // k = 10, c = 1, m = W = 1: diag(9, −2), one negative direction, which
    // no gyroscopic force can stabilize: unstable. Without values the sign
    // of k − m W² is open.
    let s = parse(&format!("{rotating}potential V = 1/2*k*x^2 - 1/2*c*y^2\n"));
    let e = eq(&s, "");
    assert!(matches!(e.equilibria[0].stability, Stability::Undecided(_)));
    let e = eq(&s, "m=1,k=10,c=1,W=1");
    assert_eq!(e.equilibria[0].stability, Stability::Unstable);
    // k = 1/2 < m W²: diag(−1/2, −2), two negative directions: undecided
    let e = eq(&s, "m=1,k=0.5,c=1,W=1");
    assert!(matches!(e.equilibria[0].stability, Stability::Undecided(_)));
}
