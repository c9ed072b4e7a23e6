//! Planar mechanisms as scenes (issue 36): the `joint`, `drive` and
//! `friction` statements parsed and resolved, their reactions in
//! Lagrange's equations, the exact kinetostatics of the seed's problem
//! 21.3 (`qdot solve`), its cycle checked against the power balance, and
//! wrong scenes refused where they are wrong
//! (`tests/data/joints/wrong/NAME.qd` with the blessed error `NAME.txt`;
//! `QDOT_BLESS=1 cargo test --release --test it joints::` rewrites them,
//! and the book's figures of problem 21.3).

use crate::common::stmt_sexpr;
use pretty_assertions::assert_eq;
use qdot::cycle::{cycle, parse_guess, CycleRequest, Over};
use qdot::output::{self, Command, Format};
use qdot::Scene;
use std::path::Path;

const DATA: &str = concat!(env!("QDOT_ROOT"), "/tests/data/joints");
const ROOT: &str = env!("QDOT_ROOT");

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/examples/{name}")).expect("the example exists")
}

fn scene(src: &str) -> Scene {
    Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene", src)))
}

/// The values of `--set` of the book's problem 21.3.
const SEED_21_3_SET: &str =
    "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20";

#[test]
fn statements_parse_to_their_trees() {
    let src = "joint A: pin crank at [x, y] + R*[cos(phi), sin(phi)], rod at [u, v]
joint G: slider ground at [0, e], block at [xb, yb] along [cos(a), sin(a)]
drive M: phi = omega*t
friction G: mu";
    let stmts = qdot::parse::parse_scene(src).expect("parses");
    let trees: Vec<String> = stmts.iter().map(stmt_sexpr).collect();
    assert_eq!(
        trees,
        [
            "(joint A pin (crank (+ [x y] (* R [(cos phi) (sin phi)]))) (rod [u v]))",
            "(joint G slider (ground [0 e]) (block [xb yb]) (along [(cos a) (sin a)]))",
            "(drive M phi (* omega t))",
            "(friction G mu)",
        ]
    );
}

#[test]
fn keywords_are_still_names_elsewhere() {
    let s = scene("coordinates x\nparameters m\njoint = 2\ndrive = joint + 1\nfriction = drive*m\nkinetic E = 1/2*friction*x'^2");
    let l = s.lagrange().expect("derives");
    assert_eq!(l.mass_matrix[0][0].to_string(), "3*m");
}

#[test]
fn reactions_enter_the_equations_body_by_body() {
    let s = scene(&example("slider_crank_joints.qd"));
    let l = s.lagrange().expect("derives");
    let eqs: Vec<String> = l
        .equations
        .iter()
        .map(|e| format!("{} = {}", e.lhs, e.rhs))
        .collect();
    assert_eq!(
        eqs,
        [
            "m1*x1'' = O_x - A_x",
            "m1*y1'' = O_y - g*m1 - A_y",
            "J1*phi'' = A_x*R*sin(phi) - A_y*R*cos(phi) + M",
            "m2*x2'' = A_x - B_x",
            "m2*y2'' = A_y - g*m2 - B_y",
            "J2*th'' = L*(A_x + B_x)*sin(th)/2 - L*(A_y + B_y)*cos(th)/2",
            "m3*xb'' = -k*xb + B_x + k*l0",
            "m3*yb'' = B_y + G_n - g*m3",
        ]
    );
}

#[test]
fn a_sliders_direction_need_not_be_a_unit_vector() {
    // along [3, 4]: the guide's normal force is still a force, G_n, the
    // same as along the unit vector [3/5, 4/5]
    let with = |u: &str| {
        let src = format!(
            "coordinates x, y\nparameters m, g\nparticle p: mass m, at [x, y]\ngravity [0, -g]\n\
             joint G: slider ground at [0, 0], p at [x, y] along {u}\ndrive D: x = t"
        );
        let s = scene(&src);
        let l = s.lagrange().expect("derives");
        qdot::solve::kinetostatic::mechanism_reactions(&s, &l)
            .expect("solves")
            .values
            .iter()
            .map(|(n, v)| format!("{n} = {v}"))
            .collect::<Vec<_>>()
    };
    assert_eq!(with("[3, 4]"), with("[3/5, 4/5]"));
    assert_eq!(with("[1, 0]"), ["D = m*x''", "G_n = m*y'' + g*m"]);
}

#[test]
fn seed_21_3_reactions_exactly_in_solving_order() {
    let s = scene(&example("seed_21_3.qd"));
    let l = s.lagrange().expect("derives");
    let r = qdot::solve::kinetostatic::mechanism_reactions(&s, &l).expect("solves");
    assert!(r.in_order);
    let got: Vec<String> = r.values.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    assert_eq!(
        got,
        [
            "B_x = G3*xB''/g + k*xB - S_f - k*l0",
            "A_x = G2*x2''/g + B_x",
            "O_x = G1*x1''/g + A_x",
            "A_y = (G2*(AB - AC)*cos(alpha)*y2'' - g*J2*alpha'' + g*G2*(AB - AC)*cos(alpha) + g*(AB*B_x - AC*B_x + A_x*AC)*sin(alpha))/(AB*g*cos(alpha))",
            "B_y = (g*(AB*B_x - AC*B_x + A_x*AC)*sin(alpha) - AC*G2*cos(alpha)*y2'' - g*J2*alpha'' - AC*g*G2*cos(alpha))/(AB*g*cos(alpha))",
            "O_y = G1*y1''/g + A_y + G1",
            "M = G1*R^2*phi''/(2*g) + A_y*R*cos(phi) - A_x*R*sin(phi)",
            "S_n = G3*yB''/g + G3 - B_y",
        ]
    );
    let f = &r.friction[0];
    assert_eq!(
        (
            f.name.as_str(),
            f.coefficient.to_string(),
            f.normal.clone(),
            f.relative_velocity.to_string()
        ),
        (
            "S_f",
            "mu".to_string(),
            vec!["S_n".to_string()],
            "xB'".to_string()
        )
    );
}

/// The seed's problem 21.3 over a cycle, each row against the power
/// balance M·φ̇ = q̇ᵀ·(M·q̈ − f) − S_f·ẋ_B (the friction's power is its
/// loss): the drive's couple from the kinetostatics equals the one from
/// virtual work with the inertia forces.
#[test]
fn seed_21_3_cycle_balances_power_at_every_position() {
    let src = example("seed_21_3.qd");
    let s = scene(&src);
    let req = CycleRequest {
        over: Over::parse("phi=0:360deg:73").unwrap(),
        set: output::parse_set_any_sign(SEED_21_3_SET)
            .unwrap()
            .into_iter()
            .collect(),
        guess: parse_guess("x2=0.25,xB=0.5").unwrap(),
    };
    let table = cycle(&s, &req).expect("the cycle runs");
    let l = s.lagrange().unwrap();
    let n = s.coordinates.len();
    let col = |name: &str| table.columns.iter().position(|c| c == name).unwrap();
    let set = output::parse_set_any_sign(SEED_21_3_SET).unwrap();
    let mut checked = 0;
    for row in &table.rows {
        let (Some(m), Some(sf)) = (row.values[col("M")], row.values[col("S_f")]) else {
            assert!(
                row.note.as_deref().unwrap().starts_with("stick"),
                "{:?}",
                row.note
            );
            continue;
        };
        let value = |a: &qdot::expr::atom::Atom| -> Option<f64> {
            use qdot::expr::atom::Atom;
            match a {
                Atom::Param(p) => set.get(&**p).copied(),
                Atom::Coord(c, k) => {
                    let suffix = ["", "'", "''"][*k as usize];
                    row.values[col(&format!("{c}{suffix}"))]
                }
                _ => None,
            }
        };
        let qd: Vec<f64> = (0..n).map(|k| row.values[1 + n + k].unwrap()).collect();
        let qdd: Vec<f64> = (0..n).map(|k| row.values[1 + 2 * n + k].unwrap()).collect();
        let mut power = 0.0;
        for (k, v) in qd.iter().enumerate() {
            let mq: f64 = (0..n)
                .map(|j| l.mass_matrix[k][j].eval_f64(&value).unwrap() * qdd[j])
                .sum();
            power += (mq - l.forcing[k].eval_f64(&value).unwrap()) * v;
        }
        let xb_dot = row.values[col("xB'")].unwrap();
        let expected = (power - sf * xb_dot) / 20.0;
        assert!(
            (m - expected).abs() <= 1e-10 * (1.0 + m.abs()),
            "{m} vs {expected}"
        );
        // friction only takes power out
        assert!(sf * xb_dot <= 0.0);
        checked += 1;
    }
    assert_eq!(checked, 70, "every row but the three dead centres");
}

#[test]
fn simulate_and_codegen_refuse_friction_rather_than_drop_it() {
    let src = example("seed_21_3.qd");
    let l = scene(&src).lagrange().unwrap();
    let err = l.accelerations().unwrap_err();
    assert_eq!(
        err.message,
        "the equations have Coulomb friction in a joint (−c·|N|·sgn v), which is not linear in the reactions, so the accelerations have no closed form"
    );
}

#[test]
fn solve_json_has_the_mechanism() {
    let src = example("slider_crank_joints.qd");
    let (out, _) = output::run(Command::Solve, &src, Format::Json, &Default::default()).unwrap();
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let m = &v["mechanism"];
    assert_eq!(m["reactions"]["B_x"], "m3*xb'' + k*xb - k*l0");
    assert_eq!(
        m["reactions"]["M"],
        "J1*phi'' + A_y*R*cos(phi) - A_x*R*sin(phi)"
    );
    assert_eq!(m["in_order"], true);
    assert_eq!(m["equations"][7]["rhs"], "B_y + G_n - g*m3");
}

#[test]
fn wrong_scenes_are_refused_where_written() {
    crate::common::refused_where_written(&Path::new(DATA).join("wrong"), 17);
}

/// The book's figures of problem 21.3 are what `qdot cycle --plot
/// --animate` draws today.
#[test]
fn the_books_figures_are_current() {
    let dir = std::env::temp_dir().join(format!("qdot-joints-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (svg, html) = (dir.join("r.svg"), dir.join("a.html"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_qdot"))
        .current_dir(ROOT)
        .args([
            "cycle",
            "examples/seed_21_3.qd",
            "--over",
            "phi=0:360deg:181",
            "--set",
            SEED_21_3_SET,
        ])
        .args(["--guess", "x2=0.25,xB=0.5", "--plot"])
        .arg(&svg)
        .arg("--animate")
        .arg(&html)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for (made, name) in [(&svg, "seed_21_3_reactions.svg"), (&html, "seed_21_3.html")] {
        let book = format!("{ROOT}/book/src/mechanisms/{name}");
        let now = std::fs::read_to_string(made).unwrap();
        if std::env::var_os("QDOT_BLESS").is_some() {
            std::fs::write(&book, &now).unwrap();
        }
        assert!(
            std::fs::read_to_string(&book).unwrap() == now,
            "{book} drifted: QDOT_BLESS=1 cargo test --release --test it joints::"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A drive law that cannot be evaluated (1/t at t = 0) is an error at the
/// drive for the first position and a row that says so later, never a
/// panic; values that overflow are left out with a note.
#[test]
fn non_finite_conditions_and_values_are_said_not_printed() {
    let src =
        example("slider_crank_joints.qd").replace("drive M: phi = omega*t", "drive M: phi = 1/t");
    let s = scene(&src);
    let set = "R=0.1,L=0.4,omega=10,m1=1,J1=0.01,m2=2,J2=0.03,m3=1.5,g=9.81,k=100,l0=0.4";
    let req = |over: &str, guess: &str| CycleRequest {
        over: Over::parse(over).unwrap(),
        set: output::parse_set_any_sign(set).unwrap(),
        guess: parse_guess(guess).unwrap(),
    };
    let err = cycle(&s, &req("t=0:1:3", "xb=0.5")).unwrap_err();
    assert_eq!(
        err.message,
        "the mechanism cannot be assembled at the first position (t = 0): the drive `M` cannot be evaluated there (not finite: a division by zero or an overflow in its condition)"
    );
    assert_eq!(
        qdot::Diagnostic::line_col(&src, err.span.unwrap().start),
        (14, 1)
    );
    let t = cycle(&s, &req("t=-1:1:3", "xb=0.5,x2=0.3")).unwrap();
    assert!(t.rows[1].values[1..].iter().all(Option::is_none));
    assert_eq!(
        t.rows[1].note.as_deref(),
        Some("the mechanism cannot be assembled here: the drive `M` cannot be evaluated there (not finite: a division by zero or an overflow in its condition)")
    );
    // ω = 1e200 overflows the velocities: no inf or NaN is printed
    let fast = example("slider_crank_joints.qd");
    let set = set.replace("omega=10", "omega=1e200");
    let r = CycleRequest {
        over: Over::parse("phi=0:0:1").unwrap(),
        set: output::parse_set_any_sign(&set).unwrap(),
        guess: parse_guess("xb=0.5").unwrap(),
    };
    let t = cycle(&scene(&fast), &r).unwrap();
    assert!(t.rows[0].values.iter().flatten().all(|x| x.is_finite()));
    assert!(t.rows[0]
        .note
        .as_deref()
        .unwrap()
        .starts_with("some values are not finite here"));
}

/// The LaTeX of a friction whose relative velocity is long names it and
/// writes it on a row of its own (the quick-return's slide on its lever);
/// a short one stays inside sgn (problem 21.3's ẋ_B).
#[test]
fn a_long_relative_velocity_gets_its_own_row_in_latex() {
    let opts = output::CommandOptions {
        steps: true,
        ..Default::default()
    };
    let tex = |name: &str| {
        let src = example(name);
        output::run_with(Command::Latex, &src, Format::Latex, &opts)
            .unwrap()
            .0
    };
    let quick = tex("mechanisms/quick_return.qd");
    assert!(quick.contains(
        "S_{f} &= -\\mu \\, \\left|S_{n}\\right| \\operatorname{sgn}\\left(v_{\\mathrm{S}}\\right) \\\\\n  v_{\\mathrm{S}} &= "
    ));
    let seed = tex("seed_21_3.qd");
    assert!(seed.contains(
        "S_{f} &= -\\mu \\, \\left|S_{n}\\right| \\operatorname{sgn}\\left(\\dot{x}_{B}\\right)"
    ));
}
