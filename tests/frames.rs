//! Frames, rigid bodies and particles in space (issue 16): rotations and
//! their angular velocities against the textbook tables, the same top
//! written three ways, SymPy's `physics.mechanics` as the oracle on the
//! fixtures of `tests/fixtures/frames.json` (generated offline by
//! `tests/fixtures/gen_frames.py`), and wrong scenes refused where they
//! are wrong: `tests/data/frames/wrong/NAME.qd` with the blessed error
//! `NAME.txt` (`QDOT_BLESS=1 cargo test --release --test it frames::`
//! rewrites them).

use qdot::output::{self, Command, Format};
use qdot::Scene;
use std::path::Path;

const DATA: &str = concat!(env!("QDOT_ROOT"), "/tests/data/frames");

fn scene(src: &str) -> Scene {
    Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene", src)))
}

/// Every wrong scene is refused with a positioned error (blessed), by the
/// library and by every command alike.
#[test]
fn wrong_scenes_are_refused_where_written() {
    crate::common::refused_where_written(&Path::new(DATA).join("wrong"), 40);
}

/// The residuals lhs − Q of a scene's equations.
fn residuals(s: &Scene) -> Vec<qdot::Expr> {
    let l = s.lagrange().expect("equations");
    l.equations.iter().map(|e| e.lhs.sub(&e.rhs)).collect()
}

fn same_equations(a: &str, b: &str) {
    let (x, y) = (residuals(&scene(a)), residuals(&scene(b)));
    assert_eq!(x.len(), y.len());
    for (k, (p, q)) in x.iter().zip(&y).enumerate() {
        assert!(p.equals(q), "equation {k}: {p}\n  vs {q}");
    }
}

const TOP_FRAMES: &str = "coordinates phi, theta, psi
parameters A, C, m, g, l
frame B = rot(z, phi) * rot(x, theta) * rot(z, psi)
body top: mass m, inertia [A, A, C], frame B, at l*axis(B, 3)
gravity [0, 0, -g]
";

/// The heavy top with frames and `body`, with ω typed from the table,
/// and as a `lagrangian`: the same canonical equations.
#[test]
fn the_top_three_ways() {
    let by_hand = "coordinates phi, theta, psi
parameters A, C, m, g, l
w1 = phi'*sin(theta)*sin(psi) + theta'*cos(psi)
w2 = phi'*sin(theta)*cos(psi) - theta'*sin(psi)
w3 = phi'*cos(theta) + psi'
G = l*[sin(theta)*sin(phi), -sin(theta)*cos(phi), cos(theta)]
kinetic T = 1/2*m*dot(G', G') + 1/2*(A*w1^2 + A*w2^2 + C*w3^2)
potential V = m*g*l*cos(theta)
";
    let lagrangian = "coordinates phi, theta, psi
parameters A, C, m, g, l
frame B = rot(z, phi) * rot(x, theta) * rot(z, psi)
w = express(omega(B), B)
P = l*axis(B, 3)
lagrangian L = 1/2*m*dot(P', P') + 1/2*(A*w[1]^2 + A*w[2]^2 + C*w[3]^2) - m*g*P[3]
";
    same_equations(TOP_FRAMES, by_hand);
    same_equations(TOP_FRAMES, lagrangian);
    // the textbook's accelerations of the symmetric top
    let acc = scene(TOP_FRAMES)
        .lagrange()
        .unwrap()
        .accelerations()
        .unwrap();
    let s = scene(TOP_FRAMES);
    let want = s
        .expr("((l^2*m + A - C)*cos(theta)*sin(theta)*phi'^2 - C*sin(theta)*phi'*psi' + g*l*m*sin(theta))/(l^2*m + A)")
        .unwrap();
    let got = acc.iter().find(|(q, _)| *q == "theta").unwrap().1;
    assert!(got.equals(&want), "{got}");
}

/// omega(F) in the frame's components against the tables: 3-1-3 (Euler)
/// and 1-2-3 (Cardan) sequences; and in ground components it is R·ω_F.
#[test]
fn omega_matches_the_tables() {
    let s = scene(
        "coordinates a, b, c
frame E = rot(z, a) * rot(x, b) * rot(z, c)
frame K = rot(x, a) * rot(y, b) * rot(z, c)
",
    );
    let tables = [
        (
            "express(omega(E), E)",
            [
                "a'*sin(b)*sin(c) + b'*cos(c)",
                "a'*sin(b)*cos(c) - b'*sin(c)",
                "a'*cos(b) + c'",
            ],
        ),
        (
            "express(omega(K), K)",
            [
                "a'*cos(b)*cos(c) + b'*sin(c)",
                "-a'*cos(b)*sin(c) + b'*cos(c)",
                "a'*sin(b) + c'",
            ],
        ),
        (
            "omega(E)",
            [
                "b'*cos(a) + c'*sin(a)*sin(b)",
                "b'*sin(a) - c'*cos(a)*sin(b)",
                "a' + c'*cos(b)",
            ],
        ),
    ];
    for (expr, want) in tables {
        let got = s.value_of(expr).unwrap();
        for (k, w) in want.iter().enumerate() {
            let w = s.expr(w).unwrap();
            assert!(
                got.components()[k].equals(&w),
                "{expr}[{k}]: {}",
                got.components()[k]
            );
        }
    }
    // axes are orthonormal, express undoes F*v, and P[k] picks components
    for (e, want) in [
        ("dot(axis(E, 1), axis(E, 2))", "0"),
        ("dot(axis(K, 3), axis(K, 3))", "1"),
        ("express(E*[1, 2, 3], E)[3]", "3"),
        ("(E*[0, 0, 1])[2]", "-cos(a)*sin(b)"),
        ("axis(rot(z, a)*rot(x, b)*rot(x, -b), 2)[1]", "-sin(a)"),
    ] {
        let got = s.expr(e).unwrap_or_else(|d| panic!("{e}: {d}"));
        assert!(got.equals(&s.expr(want).unwrap()), "{e} = {got}");
    }
}

/// `particle` and the planar `body` give the energies written by hand.
#[test]
fn particles_and_planar_bodies() {
    same_equations(
        "coordinates x, theta
parameters m, M, J, g, l
particle cart: mass M, at [x, 0]
body rod: mass m, inertia J, angle theta, at [x + l*sin(theta), -l*cos(theta)]
gravity [0, -g]
",
        "coordinates x, theta
parameters m, M, J, g, l
kinetic E1 = 1/2*M*x'^2
kinetic E2 = 1/2*m*((x' + l*cos(theta)*theta')^2 + (l*sin(theta)*theta')^2) + 1/2*J*theta'^2
potential V = -m*g*l*cos(theta)
",
    );
}

/// A body's energies are definitions with roles (`E_top`, `V_top`), seen
/// by the REPL and `Scene::expr`, and shown in `latex --steps`.
#[test]
fn body_energies_are_named_definitions() {
    let s = scene(TOP_FRAMES);
    let v = s.definition("V_top").expect("V_top");
    assert!(v.equals(&s.expr("m*g*l*cos(theta)").unwrap()), "{v}");
    assert!(s.definition("E_top").is_some());
    let opts = output::CommandOptions {
        steps: true,
        ..Default::default()
    };
    let (tex, _) = output::run_with(Command::Latex, TOP_FRAMES, Format::Text, &opts).unwrap();
    assert!(
        tex.contains("E_{top}") || tex.contains("E_{\\mathrm{top}}"),
        "{tex}"
    );
    assert!(
        tex.contains("V_{top}") || tex.contains("V_{\\mathrm{top}}"),
        "{tex}"
    );
}

/// The JSON of a scene with bodies names each body's statement and
/// energies (`bodies`); without gravity a body has no potential.
#[test]
fn bodies_in_json() {
    let json = |src: &str, cmd| {
        let (out, _) = output::run_with(cmd, src, Format::Json, &Default::default()).expect("runs");
        serde_json::from_str::<serde_json::Value>(&out).expect("JSON")
    };
    let s = scene(TOP_FRAMES);
    for cmd in [Command::Derive, Command::Solve] {
        let v = json(TOP_FRAMES, cmd);
        let b = &v["bodies"][0];
        assert_eq!(v["bodies"].as_array().map(Vec::len), Some(1));
        assert_eq!(
            (&b["name"], &b["kind"], &b["line"]),
            (&"top".into(), &"body".into(), &4.into())
        );
        assert_eq!(b["kinetic"]["name"], "E_top");
        assert_eq!(b["potential"]["name"], "V_top");
        let read = |k: &str| s.expr(b[k]["value"].as_str().expect("a string")).unwrap();
        assert!(read("potential").equals(&s.expr("m*g*l*cos(theta)").unwrap()));
        let e = "(A + m*l^2)/2*(theta'^2 + sin(theta)^2*phi'^2) + C/2*(psi' + cos(theta)*phi')^2";
        assert!(read("kinetic").equals(&s.expr(e).unwrap()));
    }
    let free = "coordinates x, y\nparameters m\nparticle p: mass m, at [x, y]\n";
    let v = json(free, Command::Derive);
    assert_eq!(v["bodies"][0]["kind"], "particle");
    assert_eq!(v["bodies"][0]["potential"], serde_json::Value::Null);
    let old = "coordinates x\nparameters m, k\nkinetic E = m*x'^2/2\npotential V = k*x^2/2\n";
    assert!(json(old, Command::Derive).get("bodies").is_none());
}

const SUPPORT: &str = "coordinates theta
parameters m, l, g
functions s
particle bob: mass m, at [s(t) + l*sin(theta), -l*cos(theta)]
gravity [0, -g]
";

/// A given function of time: its derivatives stay symbolic in the
/// equations, and `simulate` runs with its definition exactly as with the
/// definition written into the scene.
#[test]
fn given_functions_of_time() {
    let s = scene(SUPPORT);
    let acc = s.lagrange().unwrap().accelerations().unwrap();
    let want = s.expr("-s''*cos(theta)/l - g/l*sin(theta)").unwrap();
    assert!(acc.iter().next().unwrap().1.equals(&want));
    // `s` and `s(t)` are one thing; s(2*t) is refused
    assert!(s.expr("s(t) - s").unwrap().is_zero());
    let err = Scene::parse(&SUPPORT.replace("s(t)", "s(2*t)")).unwrap_err();
    assert!(
        err.message.contains("given function of time"),
        "{}",
        err.message
    );
    let written = SUPPORT
        .replace("functions s\n", "")
        .replace("s(t)", "(1/10*sin(2*t))");
    let req = |functions: Vec<String>| qdot::simulate::run::Request {
        set: [("m", 1.0), ("l", 1.0), ("g", 9.81)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect(),
        init: [("theta", 0.1), ("theta'", 0.0)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect(),
        t_end: 2.0,
        functions,
        ..Default::default()
    };
    let a = qdot::simulate::run::simulate(SUPPORT, &req(vec!["s=1/10*sin(2*t)".into()])).unwrap();
    let b = qdot::simulate::run::simulate(&written, &req(vec![])).unwrap();
    let (ra, rb) = (a.rows.last().unwrap(), b.rows.last().unwrap());
    for (x, y) in ra.iter().zip(rb) {
        assert!((x - y).abs() <= 1e-12 * (1.0 + y.abs()), "{ra:?} vs {rb:?}");
    }
    let missing = qdot::simulate::run::simulate(SUPPORT, &req(vec![])).unwrap_err();
    assert!(
        missing.message.contains("needs a definition"),
        "{}",
        missing.message
    );
    let moving = qdot::simulate::run::simulate(SUPPORT, &req(vec!["s=theta".into()])).unwrap_err();
    assert!(
        moving.message.contains("t and the parameters"),
        "{}",
        moving.message
    );
}

/// Hostile frames: a chain of frames past the limit of turns, and turns
/// about many different constant angles (whose matrix doubles in size per
/// turn), stop with an error, quickly and in bounded memory.
#[test]
fn hostile_chains_of_frames_are_refused() {
    let chain = |n: usize, angle: &dyn Fn(usize) -> String| {
        let mut s = String::from("coordinates q\nparameters m\nframe B0 = rot(z, q)\n");
        for i in 1..n {
            s.push_str(&format!("frame B{i} = B{} * rot(x, {})\n", i - 1, angle(i)));
        }
        s.push_str(&format!("particle p: mass m, at axis(B{}, 3)\n", n - 1));
        s
    };
    let many = chain(5000, &|_| "0".to_string());
    let err = output::run(Command::Derive, &many, Format::Text, &Default::default()).unwrap_err();
    assert!(
        err.message.contains("more than 1,000 turns")
            || err.message.contains("more than 1000 turns"),
        "{}",
        err.message
    );
    let growing = chain(3000, &|i| format!("{i}/1000"));
    let err =
        output::run(Command::Derive, &growing, Format::Text, &Default::default()).unwrap_err();
    assert!(
        err.message.starts_with("expression too large"),
        "{}",
        err.message
    );
}
