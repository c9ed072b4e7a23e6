//! Constraints and Lagrange's multipliers (issue 17): the Cartesian
//! pendulum's multiplier is its rod's tension, a rheonomic constraint
//! reproduces the one-coordinate scene, the rolling coin's nonholonomic
//! accelerations, redundant constraints named, constrained simulation
//! against the angle pendulum, and wrong scenes refused where they are
//! wrong (`tests/data/constraints/wrong/NAME.qd` with the blessed error
//! `NAME.txt`; `QDOT_BLESS=1 cargo test --release --test it constraints::`
//! rewrites them).

use qdot::expr::atom;
use qdot::output::{self, Command, Format};
use qdot::{Expr, Scene};
use rustc_hash::FxHashMap;
use std::path::Path;

const DATA: &str = concat!(env!("QDOT_ROOT"), "/tests/data/constraints");

fn scene(src: &str) -> Scene {
    Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene", src)))
}

const CARTESIAN: &str = "coordinates x, y
parameters m, g, l
kinetic E = 1/2*m*(x'^2 + y'^2)
potential V = m*g*y
constraint rod: x^2 + y^2 = l^2
";

const ANGLE: &str = "coordinates th
parameters m, g, l
kinetic E = 1/2*m*l^2*th'^2
potential V = -m*g*l*cos(th)
solve T { m*l*th'^2 = T - m*g*cos(th) }
";

/// x = l·sin θ, y = −l·cos θ and their velocities: the Cartesian
/// pendulum's state on its constraint, in the angle's.
fn on_the_circle(s: &Scene) -> FxHashMap<qdot::engine::poly::Var, Expr> {
    let mut at = FxHashMap::default();
    for (v, text) in [
        (atom::coord("x", 0), "l*sin(th)"),
        (atom::coord("y", 0), "-l*cos(th)"),
        (atom::coord("x", 1), "l*cos(th)*th'"),
        (atom::coord("y", 1), "l*sin(th)*th'"),
    ] {
        at.insert(v, s.expr(text).unwrap());
    }
    at
}

/// The multiplier of the Cartesian pendulum is the rod's tension: the
/// constraint force λ·∇g = 2λ·(x, y) has magnitude −2λ·l, which on the
/// circle is the T a kinetostatic `solve` block finds for the angle
/// pendulum; and ẍ, ÿ are the second derivatives of l·sin θ, −l·cos θ.
#[test]
fn the_multiplier_is_the_rods_tension() {
    let cart = scene(CARTESIAN);
    let angle = scene(ANGLE);
    let acc = cart.lagrange().unwrap().accelerations().unwrap();
    let [(name, lambda)] = acc.multipliers() else {
        panic!("one multiplier: {:?}", acc.multipliers())
    };
    assert_eq!(name, "lambda_rod");
    let at = on_the_circle(&angle);
    let blocks = qdot::solve::system::solve_scene(&angle).unwrap();
    let (_, tension) = &blocks[0].values[0];
    let from_lambda = lambda
        .subs_many(&at)
        .unwrap()
        .mul(&angle.expr("-2*l").unwrap());
    assert!(
        from_lambda.equals(tension),
        "−2·λ·l = {from_lambda}, T = {tension}"
    );
    // ẍ = d²/dt²(l sin θ) with θ̈ of the angle pendulum
    let th_dd = angle.lagrange().unwrap().accelerations().unwrap()["th"].clone();
    let mut with_th = at.clone();
    with_th.insert(atom::coord("th", 2), th_dd);
    for (q, path) in [("x", "l*sin(th)"), ("y", "-l*cos(th)")] {
        let want = angle
            .expr(&format!("({path})''"))
            .unwrap()
            .subs_many(&with_th)
            .unwrap();
        let got = acc[q].subs_many(&at).unwrap();
        assert!(got.equals(&want), "{q}'': {got} vs {want}");
    }
}

/// The bead on a hoop turning at the rate Ω, with the turning written as
/// the rheonomic constraint φ = Ω·t: θ̈ on the constraint is that of the
/// one-coordinate scene, and the multiplier is the torque that keeps the
/// hoop turning, d/dt(m·R²·sin²θ·Ω).
#[test]
fn a_rheonomic_constraint_is_the_one_coordinate_scene() {
    let constrained = scene(
        "coordinates th, ph
parameters m, g, R, Omega
kinetic E = 1/2*m*R^2*(th'^2 + sin(th)^2*ph'^2)
potential V = -m*g*R*cos(th)
constraint spin: ph = Omega*t
",
    );
    let single = scene(
        "coordinates th
parameters m, g, R, Omega
kinetic E = 1/2*m*R^2*(th'^2 + sin(th)^2*Omega^2)
potential V = -m*g*R*cos(th)
",
    );
    let acc = constrained.lagrange().unwrap().accelerations().unwrap();
    let mut at = FxHashMap::default();
    at.insert(atom::coord("ph", 1), single.expr("Omega").unwrap());
    let want = single.lagrange().unwrap().accelerations().unwrap()["th"].clone();
    assert!(
        acc["th"].subs_many(&at).unwrap().equals(&want),
        "{}",
        acc["th"]
    );
    assert!(acc["ph"].is_zero(), "φ̈ = {}", acc["ph"]);
    let torque = single.expr("2*m*R^2*sin(th)*cos(th)*th'*Omega").unwrap();
    let lambda = acc.multipliers()[0].1.subs_many(&at).unwrap();
    assert!(lambda.equals(&torque), "λ_spin = {lambda}");
}

const DOUBLE: &str = "coordinates x1, y1, x2, y2
parameters m, g, l
kinetic E = 1/2*m*(x1'^2 + y1'^2 + x2'^2 + y2'^2)
potential V = m*g*(y1 + y2)
constraint rod1: x1^2 + y1^2 = l^2
constraint rod2: (x2 - x1)^2 + (y2 - y1)^2 = l^2
";

const COIN: &str = "# a coin rolling upright: contact point x, y, heading phi, spin theta
coordinates x, y, phi, theta
parameters m, r, A, C
kinetic E = 1/2*m*(x'^2 + y'^2) + 1/2*A*phi'^2 + 1/2*C*theta'^2
constraint rollx: x' = r*cos(phi)*theta'
constraint rolly: y' = r*sin(phi)*theta'
";

/// The upright rolling coin (two nonholonomic constraints): the contact
/// point turns with the heading, the spin and the heading rates stay, and
/// the multipliers are the contact forces m·ẍ, m·ÿ.
#[test]
fn the_rolling_coin() {
    let s = scene(COIN);
    let acc = s.lagrange().unwrap().accelerations().unwrap();
    for (q, want) in [
        ("x", "-r*sin(phi)*phi'*theta'"),
        ("y", "r*cos(phi)*phi'*theta'"),
        ("phi", "0"),
        ("theta", "0"),
    ] {
        assert!(acc[q].equals(&s.expr(want).unwrap()), "{q}'' = {}", acc[q]);
    }
    let names: Vec<&str> = acc.multipliers().iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["lambda_rollx", "lambda_rolly"]);
    for ((_, l), q) in acc.multipliers().iter().zip(["x", "y"]) {
        let m_acc = s.expr("m").unwrap().mul(&acc[q]);
        assert!(l.equals(&m_acc), "{l} vs m·{q}''");
    }
    let rows = &s.lagrange().unwrap().constraints;
    assert_eq!(rows.holonomic, [false, false]);
}

/// Redundant constraints are refused by name; the JSON of a constrained
/// scene carries `constraints` and, from `solve`, `multipliers`.
#[test]
fn redundant_constraints_and_json() {
    let redundant = CARTESIAN.to_string() + "constraint twice: 2*x^2 + 2*y^2 = 2*l^2\n";
    let s = scene(&redundant);
    let err = s.lagrange().unwrap().accelerations().unwrap_err();
    assert!(
        err.message.contains("`rod`")
            && err.message.contains("`twice`")
            && err.message.contains("redundant"),
        "{}",
        err.message
    );
    let (out, _) =
        output::run_with(Command::Solve, CARTESIAN, Format::Json, &Default::default()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let c = &v["constraints"][0];
    assert_eq!(
        (&c["name"], &c["multiplier"], &c["kind"], &c["expression"]),
        (
            &"rod".into(),
            &"lambda_rod".into(),
            &"holonomic".into(),
            &"x^2 + y^2 - l^2".into()
        )
    );
    assert_eq!(c["coefficients"], serde_json::json!(["2*x", "2*y"]));
    let s = scene(CARTESIAN);
    let lambda = s
        .expr(v["multipliers"]["lambda_rod"].as_str().unwrap())
        .unwrap();
    let want = s.expr("m*(g*y - x'^2 - y'^2)/(2*(x^2 + y^2))").unwrap();
    assert!(lambda.equals(&want), "{lambda}");
    // a scene without constraints has neither key
    let (plain, _) =
        output::run_with(Command::Solve, ANGLE, Format::Json, &Default::default()).unwrap();
    assert!(!plain.contains("\"constraints\"") && !plain.contains("\"multipliers\""));
}

/// Equilibria on holonomic constraints by the multiplier rule: the
/// Cartesian pendulum hangs (stable) or stands (unstable) with the rod's
/// multiplier; a particle on a sphere; a bead at the bottom of a parabolic
/// wire. A velocity constraint or a moving one is refused with a reason.
#[test]
fn equilibria_on_constraints() {
    let eq = qdot::equilibria(&scene(CARTESIAN), &Default::default()).unwrap();
    let s = scene(CARTESIAN);
    let want = [
        ("-l", "-g*m/(2*l)", "stable"),
        ("l", "g*m/(2*l)", "unstable"),
    ];
    assert_eq!(eq.equilibria.len(), 2);
    for (e, (y, lambda, stability)) in eq.equilibria.iter().zip(want) {
        let qdot::solve::equilibrium::Position::Exact(v) = &e.position else {
            panic!("exact")
        };
        assert!(v[0].is_zero() && v[1].equals(&s.expr(y).unwrap()), "{v:?}");
        assert_eq!(e.multipliers[0].0, "lambda_rod");
        assert!(e.multipliers[0].1.equals(&s.expr(lambda).unwrap()));
        assert_eq!(e.stability.word(), stability);
    }
    let sphere = "coordinates x, y, z
parameters m, g, R
kinetic E = 1/2*m*(x'^2 + y'^2 + z'^2)
potential V = m*g*z
constraint sphere: x^2 + y^2 + z^2 = R^2
";
    let eq = qdot::equilibria(&scene(sphere), &Default::default()).unwrap();
    let words: Vec<&str> = eq.equilibria.iter().map(|e| e.stability.word()).collect();
    assert_eq!(words, ["stable", "unstable"]);
    let wire = "coordinates x, y
parameters m, g, a
kinetic E = 1/2*m*(x'^2 + y'^2)
potential V = m*g*y
constraint wire: 2*a*y = x^2
";
    let (out, _) = output::run(
        Command::Equilibrium,
        wire,
        Format::Json,
        &Default::default(),
    )
    .unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["stability"], serde_json::json!(["stable"]));
    assert_eq!(v["multipliers"][0]["lambda_wire"], "g*m/(2*a)");
    for (src, words) in [
        (COIN, "velocities"),
        (
            "coordinates x, y\nparameters m, g, w\nkinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = m*g*y\nconstraint c: x = sin(w*t)\n",
            "moves with time",
        ),
        (
            "coordinates x, y\nparameters m, k\nfunctions s\nkinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = 1/2*k*(x^2 + y^2)\nconstraint c: x = s\n",
            "moves with time",
        ),
    ] {
        let err = output::run(Command::Equilibrium, src, Format::Text, &Default::default()).unwrap_err();
        assert!(err.message.contains(words), "{}", err.message);
        assert!(err.span.is_some() && err.hint.is_some());
    }
}

/// A given function of time in a force is a force that changes: no static
/// equilibrium (it used to be solved as a constant, x = s).
#[test]
fn a_given_function_has_no_static_equilibrium() {
    let src = "coordinates x\nparameters m, k\nfunctions s\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*(x - s)^2\n";
    let err =
        output::run(Command::Equilibrium, src, Format::Text, &Default::default()).unwrap_err();
    assert!(err.message.contains("depends on time"), "{}", err.message);
    // nor constant small oscillations when it enters the stiffness
    let src = "coordinates x\nparameters m, k\nfunctions s\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*s*x^2\n";
    let err = output::run(Command::Modes, src, Format::Text, &Default::default()).unwrap_err();
    assert!(
        err.message.contains("parametric excitation"),
        "{}",
        err.message
    );
}

/// Without a closed form, the augmented conditions are solved numerically
/// over (q, λ) given every parameter: the Cartesian double pendulum's four
/// equilibria, only hanging straight down stable.
#[test]
fn numeric_equilibria_on_constraints() {
    let double = scene(DOUBLE);
    assert!(qdot::equilibria(&double, &Default::default()).is_err());
    let set = qdot::output::parse_set("m=1,g=1,l=1").unwrap();
    let eq = qdot::equilibria(&double, &set).unwrap();
    assert!(!eq.exact);
    let mut found: Vec<(i64, i64, &str)> = eq
        .equilibria
        .iter()
        .map(|e| {
            let qdot::solve::equilibrium::Position::Numeric(x) = &e.position else {
                panic!("numeric")
            };
            assert!(x[0].abs() < 1e-9 && x[2].abs() < 1e-9, "{x:?}");
            (x[1].round() as i64, x[3].round() as i64, e.stability.word())
        })
        .collect();
    found.sort();
    assert_eq!(
        found,
        [
            (-1, -2, "stable"),
            (-1, 0, "unstable"),
            (1, 0, "unstable"),
            (1, 2, "unstable")
        ]
    );
}

/// Small oscillations on holonomic constraints, in the independent
/// coordinates: the Cartesian pendulum's ω² = g/l (and −g/l upside down),
/// the Cartesian double pendulum's (2 ∓ √2)·g/l with the mode x2/x1 = 1 ± √2,
/// and a position off the constraint refused.
#[test]
fn modes_on_constraints() {
    let s = scene(CARTESIAN);
    let at = |src: &str| s.coordinate_values(src).unwrap();
    let md = qdot::modes(&s, Some(&at("x=0,y=-l")), &Default::default()).unwrap();
    assert_eq!(md.coordinates, ["x"]);
    assert_eq!(md.dependent.len(), 1);
    assert!(md.omega_squared[0].equals(&s.expr("g/l").unwrap()));
    assert_eq!(md.stability.word(), "stable");
    let md = qdot::modes(&s, Some(&at("x=0,y=l")), &Default::default()).unwrap();
    assert!(md.omega_squared[0].equals(&s.expr("-g/l").unwrap()));
    assert_eq!(md.stability.word(), "unstable");
    let err = qdot::modes(&s, None, &Default::default()).unwrap_err();
    assert!(
        err.message.contains("not on the constraint"),
        "{}",
        err.message
    );

    let double = scene(DOUBLE);
    let q0 = double.coordinate_values("x1=0,y1=-l,x2=0,y2=-2*l").unwrap();
    let md = qdot::modes(&double, Some(&q0), &Default::default()).unwrap();
    assert_eq!(md.coordinates, ["x1", "x2"]);
    for (k, want_w2, want_mode) in [
        (0, "(2 - sqrt(2))*g/l", "1 + sqrt(2)"),
        (1, "(2 + sqrt(2))*g/l", "1 - sqrt(2)"),
    ] {
        let w2 = &md.omega_squared[k];
        assert!(w2.equals(&double.expr(want_w2).unwrap()), "{w2}");
        let mu = &md.modes[k][1];
        assert!(mu.equals(&double.expr(want_mode).unwrap()), "{mu}");
    }
    let (out, _) = output::run_with(
        Command::Modes,
        CARTESIAN,
        Format::Json,
        &output::CommandOptions {
            at: Some("x=0,y=-l".into()),
            ..Default::default()
        },
    )
    .unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["dependent"]["y"], "-l");
}

/// The Cartesian pendulum simulated with its constraint follows the angle
/// pendulum (x = l·sin θ) and keeps |x² + y² − l²| ≤ 1e-9 over 100
/// periods at rtol 1e-10 (Baumgarte's stabilization); without the
/// stabilization the drift is orders of magnitude larger.
#[test]
fn constrained_simulation_follows_the_angle_pendulum() {
    use qdot::simulate::run::{simulate, Request};
    let request = |init: &str, baumgarte: f64| Request {
        set: qdot::output::parse_set("m=1,g=9.81,l=1").unwrap(),
        init: qdot::simulate::run::parse_init(init).unwrap(),
        t_end: 250.0,
        rtol: 1e-10,
        atol: 1e-12,
        points: 501,
        baumgarte,
        ..Default::default()
    };
    // released from 60°: period ≈ 2.15 s, so 250 s is over 100 periods
    let (s, c) = (3f64.sqrt() / 2.0, 0.5);
    let cart = simulate(
        CARTESIAN,
        &request(&format!("x={s},y=-{c},x'=0,y'=0"), 10.0),
    )
    .unwrap();
    let angle = simulate(
        ANGLE,
        &request(&format!("th={},th'=0", std::f64::consts::FRAC_PI_3), 10.0),
    )
    .unwrap();
    let drift = cart.constraint_drift.unwrap();
    assert!(drift <= 1e-9, "drift {drift:e}");
    let col = |name: &str| cart.columns.iter().position(|c| c == name).unwrap();
    assert_eq!(cart.columns.last().map(String::as_str), Some("drift_rod"));
    let mut worst: f64 = 0.0;
    for (rc, ra) in cart.rows.iter().zip(&angle.rows) {
        worst = worst.max((rc[col("x")] - ra[1].sin()).abs());
    }
    assert!(worst < 1e-6, "x vs l·sin θ: {worst:e}");
    let loose = simulate(CARTESIAN, &request(&format!("x={s},y=-{c},x'=0,y'=0"), 0.0)).unwrap();
    assert!(loose.constraint_drift.unwrap() > 100.0 * drift);
}

/// Every wrong scene is refused with a positioned error and a hint
/// (blessed), by the library and by `derive` alike.
#[test]
fn wrong_constraints_are_refused_where_written() {
    crate::common::refused_where_written(&Path::new(DATA).join("wrong"), 15);
}

/// The seed's kinetostatic problems 21.2 and 22.2 rewritten with one
/// coordinate per body and the kinematic tables as constraints: the same
/// accelerations, and the multipliers give the reactions the `solve` blocks
/// of the kinetostatic scenes find, as exact identities.
#[test]
fn seed_reactions_from_the_multipliers() {
    let example = |name: &str| {
        let path = format!("{}/examples/{name}.qd", env!("QDOT_ROOT"));
        scene(&std::fs::read_to_string(path).unwrap())
    };
    let block = |s: &Scene| -> FxHashMap<String, Expr> {
        qdot::solve::system::solve_scene(s).unwrap()[0]
            .values
            .iter()
            .cloned()
            .collect()
    };
    let lambdas = |s: &Scene| -> (qdot::Accelerations, FxHashMap<String, Expr>) {
        let acc = s.lagrange().unwrap().accelerations().unwrap();
        let l = acc.multipliers().iter().cloned().collect();
        (acc, l)
    };

    // 21.2: T1 = −λ_rope1, T2 = −λ_rope2, T4 = λ_slide, λ_pulley = r·(2·T3 − T4)
    let s = example("seed_21_2_constraints");
    let kin = block(&example("seed_21_2_kinetostatic"));
    let (acc, l) = lambdas(&s);
    assert!(acc["y3"].equals(&kin["a3"]), "a3 = {}", acc["y3"]);
    assert!(acc["theta3"].equals(&kin["eps3"]), "ε3 = {}", acc["theta3"]);
    let r = s.expr("r").unwrap();
    assert!(l["lambda_rope1"].neg().equals(&kin["T1"]));
    assert!(l["lambda_rope2"].neg().equals(&kin["T2"]));
    assert!(l["lambda_slide"].equals(&kin["T4"]));
    let t3 = l["lambda_pulley"]
        .div(&r)
        .unwrap()
        .add(&kin["T4"])
        .div(&Expr::int(2))
        .unwrap();
    assert!(t3.equals(&kin["T3"]), "T3 = {t3}");

    // 22.2: T1 = −λ_rope1, Ff = 2·λ_roll4/(3r), T4 = λ_rope4 + Ff,
    // T3 = (λ_pulley3 + r·T4)/(2r), T2 = (λ_disk2 + r·T3)/(2r)
    let s = example("seed_22_2_constraints");
    let one = example("seed_22_2");
    let kin = block(&one);
    let (acc, l) = lambdas(&s);
    let a1 = one.lagrange().unwrap().accelerations().unwrap()["y1"].clone();
    assert!(acc["y1"].equals(&a1), "a1 = {}", acc["y1"]);
    let r = s.expr("r").unwrap();
    let half_r = |e: Expr| e.div(&r.mul(&Expr::int(2))).unwrap();
    assert!(l["lambda_rope1"].neg().equals(&kin["T1"]));
    let ff = l["lambda_roll4"]
        .mul(&Expr::int(2))
        .div(&r.mul(&Expr::int(3)))
        .unwrap();
    assert!(ff.equals(&kin["Ff"]), "Ff = {ff}");
    let t4 = l["lambda_rope4"].add(&ff);
    assert!(t4.equals(&kin["T4"]), "T4 = {t4}");
    let t3 = half_r(l["lambda_pulley3"].add(&r.mul(&t4)));
    assert!(t3.equals(&kin["T3"]), "T3 = {t3}");
    let t2 = half_r(l["lambda_disk2"].add(&r.mul(&t3)));
    assert!(t2.equals(&kin["T2"]), "T2 = {t2}");
}

/// `reaction rod at [x, y]`: the rod's force on the bob, 2·λ·(x, y), whose
/// magnitude on the circle is the tension; a rope between two bodies has no
/// single point of action and is refused with a reason.
#[test]
fn reactions_at_points() {
    let src = CARTESIAN.to_string() + "reaction rod at [x, y]\n";
    let s = scene(&src);
    let acc = s.lagrange().unwrap().accelerations().unwrap();
    let forces = qdot::solve::constrained::reaction_forces(&s, &acc).unwrap();
    let lambda = &acc.multipliers()[0].1;
    for (k, q) in ["x", "y"].iter().enumerate() {
        let want = lambda.mul(&s.expr(&format!("2*{q}")).unwrap());
        assert!(forces[0][k].equals(&want), "{}", forces[0][k]);
    }
    // |R| on the circle: R·(x, y)/l = −T
    let angle = scene(ANGLE);
    let at = on_the_circle(&angle);
    let radial = forces[0][0]
        .mul(&s.expr("x").unwrap())
        .add(&forces[0][1].mul(&s.expr("y").unwrap()))
        .subs_many(&at)
        .unwrap()
        .div(&angle.expr("-l").unwrap())
        .unwrap();
    let tension = &qdot::solve::system::solve_scene(&angle).unwrap()[0].values[0].1;
    assert!(radial.equals(tension), "{radial} vs {tension}");
    let (out, _) = output::run(Command::Solve, &src, Format::Json, &Default::default()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["reactions"][0]["constraint"], "rod");
    assert_eq!(v["reactions"][0]["point"], "[x, y]");

    let path = format!("{}/examples/seed_21_2_constraints.qd", env!("QDOT_ROOT"));
    let two = std::fs::read_to_string(path).unwrap() + "reaction rope1 at y1\n";
    let err = output::run(Command::Solve, &two, Format::Text, &Default::default()).unwrap_err();
    assert!(
        err.message.contains("does not act at this point alone"),
        "{}",
        err.message
    );
    assert!(err.span.is_some() && err.hint.is_some());
}

/// A velocity constraint that integrates is refused by `equilibrium` and
/// `modes` with its position form as the hint, in the scene's syntax, its
/// constant such that it holds where every coordinate is 0; one whose
/// integral through 0 is singular leaves the constant to the user; one
/// exact only after dividing by a coefficient integrates too; the rolling
/// coin's does not integrate, and keeps the general hint.
#[test]
fn an_integrable_velocity_constraint_hints_its_position_form() {
    let cart = |constraint: &str| {
        format!(
            "coordinates x, s, phi\nparameters M0, m, R, k\nkinetic E = 1/2*M0*x'^2 + 1/2*m*s'^2 + 1/4*m*R^2*phi'^2\npotential V = 1/2*k*x^2\n{constraint}\n"
        )
    };
    let rolling = cart("constraint roll: s' + R*phi' = x'");
    for command in [Command::Equilibrium, Command::Modes] {
        let err = output::run(command, &rolling, Format::Text, &Default::default()).unwrap_err();
        assert!(
            err.message
                .ends_with("under the constraint `roll` are not found: it restricts the velocities, not the position"),
            "{}",
            err.message
        );
        assert_eq!(
            err.hint.as_deref(),
            Some("the constraint integrates: write it in the positions, `constraint roll: s + R*phi = x` (the constant of integration taken so that it holds where every coordinate is 0)")
        );
    }
    // the hint's form works
    let (out, _) = output::run(
        Command::Modes,
        &cart("constraint roll: s + R*phi = x"),
        Format::Text,
        &Default::default(),
    )
    .unwrap();
    assert!(out.contains("ω₂² = 3·k/(3·M₀ + m)"), "{out}");
    let hint = |constraint: &str| {
        output::run(
            Command::Equilibrium,
            &cart(constraint),
            Format::Text,
            &Default::default(),
        )
        .unwrap_err()
        .hint
        .unwrap()
    };
    assert_eq!(
        hint("constraint c: sin(phi)*phi' = x'"),
        "the constraint integrates: write it in the positions, `constraint c: x + cos(phi) = 1` (the constant of integration taken so that it holds where every coordinate is 0)"
    );
    assert_eq!(
        hint("constraint x*x' + s*s' = 0"),
        "the constraint integrates: write it in the positions, `constraint x^2/2 + s^2/2 = C0` with C0 a parameter, the constant of integration, from the initial position"
    );
    // exact after the factor 1/cos(phi), one coefficient's reciprocal
    assert_eq!(
        hint("constraint c: cos(phi)*x' = cos(phi)*s'"),
        "the constraint integrates: write it in the positions, `constraint c: x = s` (the constant of integration taken so that it holds where every coordinate is 0)"
    );
    let err = output::run(
        Command::Equilibrium,
        COIN,
        Format::Text,
        &Default::default(),
    )
    .unwrap_err();
    assert_eq!(
        err.hint.as_deref(),
        Some("write the scene in independent coordinates (the pendulum's angle instead of x, y) for its equilibria")
    );
}
