//! Results written through named intermediates (`expr::tape`): the
//! structured derivation equals the expanded one, exactly.

use qdot::expr::atom::Atom;
use qdot::expr::Expr;
use qdot::scene::Scene;

/// The 3D chain of `scripts/anchor_frames.py`.
fn chain3d(n: usize) -> String {
    qdot::engine::gallery::rod_chain_3d(n)
}

/// Every structured M, f and q̈, expanded, equals the expanded derivation.
fn assert_same_as_expanded(src: &str, exact_accelerations: bool) {
    let plain = Scene::parse(src).unwrap().lagrange().unwrap();
    let kept = Scene::parse_structured(src).unwrap().lagrange().unwrap();
    assert_same(&plain, &kept, exact_accelerations);
}

/// M and f through the intermediates equal the expanded ones exactly.
fn assert_same_equations(plain: &qdot::Lagrange, kept: &qdot::Lagrange) {
    let tape = kept.intermediates.as_deref().expect("a tape");
    let n = plain.coordinates.len();
    for i in 0..n {
        for j in 0..n {
            let e = tape.expand(&kept.mass_matrix[i][j]).unwrap();
            assert!(e.equals(&plain.mass_matrix[i][j]), "M[{i}][{j}]");
        }
        assert!(
            tape.expand(&kept.forcing[i])
                .unwrap()
                .equals(&plain.forcing[i]),
            "f[{i}]"
        );
    }
}

fn assert_same(plain: &qdot::Lagrange, kept: &qdot::Lagrange, exact_accelerations: bool) {
    let tape = kept.intermediates.as_deref().expect("a tape");
    let n = plain.coordinates.len();
    for i in 0..n {
        for j in 0..n {
            let e = tape.expand(&kept.mass_matrix[i][j]).unwrap();
            assert!(
                e.equals(&plain.mass_matrix[i][j]),
                "M[{i}][{j}]: {e} vs {}",
                plain.mass_matrix[i][j]
            );
        }
        let e = tape.expand(&kept.forcing[i]).unwrap();
        assert!(
            e.equals(&plain.forcing[i]),
            "f[{i}]: {e} vs {}",
            plain.forcing[i]
        );
    }
    let a_plain = plain.accelerations().unwrap();
    let a_kept = kept.accelerations().unwrap();
    let tape = a_kept.intermediates().expect("a tape");
    if exact_accelerations {
        for (x, y) in a_kept.values().iter().zip(a_plain.values()) {
            let e: Expr = tape.expand(x).unwrap();
            assert!(e.equals(y), "q̈: {e} vs {y}");
        }
    }
    // numerically at random states: the expansion of q̈ = L⁻ᵀ·D⁻¹·L⁻¹·f
    // is a cancellation of large quotients, exact but slow past n = 2
    let mut rng = qdot_exact::rng::SplitMix64::new(7);
    for _ in 0..5 {
        let seed = rng.next_u64();
        let value =
            |a: &Atom| Some(qdot_exact::rng::SplitMix64::keyed(seed, a).uniform(0.25, 1.75));
        for (x, y) in a_kept.values().iter().zip(a_plain.values()) {
            let s = tape.eval_f64(x, &value).unwrap();
            let c = y.eval_f64(&value).unwrap();
            assert!((s - c).abs() <= 1e-11 * (1.0 + c.abs()), "q̈: {s} vs {c}");
        }
    }
}

#[test]
fn chain_of_two_and_three_rods_expands_to_the_expanded_equations() {
    assert_same_as_expanded(&chain3d(2), true);
    assert_same_as_expanded(&chain3d(3), false);
}

/// The value of an atom at a fixture's state: parameters by name,
/// coordinates and velocities by index.
fn state_value(case: &serde_json::Value, a: &Atom) -> Option<f64> {
    let at = |key: &str, name: &str| -> Option<f64> {
        let k: usize = name.strip_prefix('q')?.parse().ok()?;
        case[key][k - 1].as_f64()
    };
    match a {
        Atom::Param(p) => case["params"][p.as_ref()].as_f64(),
        Atom::Coord(q, 0) => at("q", q),
        Atom::Coord(q, 1) => at("qd", q),
        _ => None,
    }
}

/// The chain's accelerations, mass matrix and forcing, evaluated through
/// the intermediates, equal Pinocchio's articulated-body algorithm (`aba`),
/// `crba` and nonlinear effects at the fixture's random states
/// (`scripts/pinocchio_chain.py` writes the fixture offline).
#[test]
fn chain_accelerations_equal_pinocchio_aba() {
    let text = std::fs::read_to_string("tests/fixtures/pinocchio_chain3d.json").unwrap();
    let fixture: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut checked = 0;
    for case in fixture["cases"].as_array().unwrap() {
        let n = case["n"].as_u64().unwrap() as usize;
        // the scene Pinocchio's model was checked against (through SymPy)
        let src = fixture["scenes"][n.to_string()].as_str().unwrap();
        let scene = Scene::parse_structured(src).unwrap();
        let l = scene.lagrange().unwrap();
        let acc = l.accelerations().unwrap();
        let tape = acc.intermediates().unwrap();
        let value = |a: &Atom| state_value(case, a);
        let scale = |xs: &[f64]| xs.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        let want: Vec<f64> = case["qdd"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        // through L·D·Lᵀ, and by the articulated-body recursion
        let rec = l.articulated_accelerations(&scene).unwrap();
        for (acc, tape) in [(&acc, tape), (&rec, rec.intermediates().unwrap())] {
            let got = tape.eval_many_f64(acc.values(), &value).unwrap();
            let err = got
                .iter()
                .zip(&want)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                err <= 1e-12 * scale(&want),
                "n = {n}: q̈ {got:?} vs aba {want:?}"
            );
        }
        let lt = l.intermediates.as_deref().unwrap();
        for i in 0..n {
            let nle = case["nle"][i].as_f64().unwrap();
            let f = lt.eval_f64(&l.forcing[i], &value).unwrap();
            assert!(
                (f + nle).abs() <= 1e-12 * (1.0 + nle.abs()),
                "n = {n}: f[{i}] {f} vs -nle {}",
                -nle
            );
            for j in 0..n {
                let m = case["mass_matrix"][i][j].as_f64().unwrap();
                let e = lt.eval_f64(&l.mass_matrix[i][j], &value).unwrap();
                assert!(
                    (e - m).abs() <= 1e-12 * (1.0 + m.abs()),
                    "n = {n}: M[{i}][{j}] {e} vs crba {m}"
                );
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 20);
}

/// Every scene of the examples, the book and the SymPy fixtures that can be
/// read with its kinematics kept derives, through its intermediates, the
/// same M and f exactly and the same accelerations (exactly for one and
/// two coordinates, at random states beyond).
#[test]
fn every_example_book_and_fixture_scene_expands_to_its_expanded_equations() {
    let mut scenes: Vec<(String, String)> = Vec::new();
    for dir in ["examples", "book/scenes"] {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "qd") {
                scenes.push((
                    p.display().to_string(),
                    std::fs::read_to_string(&p).unwrap(),
                ));
            }
        }
    }
    for f in ["lagrange", "frames", "hamilton", "modes"] {
        let text = std::fs::read_to_string(format!("tests/fixtures/{f}.json")).unwrap();
        let fixture: serde_json::Value = serde_json::from_str(&text).unwrap();
        for c in fixture["cases"].as_array().unwrap() {
            let name = format!("{f}:{}", c["name"].as_str().unwrap());
            scenes.push((name, c["scene"].as_str().unwrap().to_string()));
        }
    }
    let (mut kept_with_names, mut compared) = (0, 0);
    for (name, src) in &scenes {
        let Ok(plain_scene) = Scene::parse(src) else {
            continue;
        };
        let Ok(plain) = plain_scene.lagrange() else {
            continue;
        };
        // refused scenes (constraints, solve blocks, given functions) are
        // derived expanded: nothing to compare
        let Ok(kept_scene) = Scene::parse_structured(src) else {
            continue;
        };
        let kept = kept_scene
            .lagrange()
            .unwrap_or_else(|e| panic!("{name}: the structured derivation fails: {}", e.message));
        if kept_scene.tape.as_ref().is_some_and(|t| !t.is_empty()) {
            kept_with_names += 1;
        }
        // past the default budget the expanded accelerations are what the
        // intermediates are for (examples/rod_chain.qd): M and f still agree
        let limit = qdot::limits::DEFAULT_MAX_TERMS;
        if !matches!(
            qdot::budget::within(limit, || plain.accelerations()),
            Ok(Ok(_))
        ) {
            assert_same_equations(&plain, &kept);
            continue;
        }
        eprintln!("{name}");
        assert_same(&plain, &kept, plain.coordinates.len() <= 2);
        compared += 1;
    }
    // the test must have something to compare
    assert!(compared >= 80, "{compared} scenes compared");
    assert!(
        kept_with_names >= 20,
        "{kept_with_names} scenes with intermediates"
    );
}

/// `solve --format json` of the 4-rod chain starts with its intermediates;
/// every expression after them uses only names they define (or the
/// scene's); a small example has no such key; `--expand` of the chain
/// stops at the budget with the usual error.
#[test]
fn the_cli_writes_a_large_chain_through_intermediates_and_a_small_scene_as_before() {
    use crate::common::run::qdot;
    let (code, out, _) = qdot(&["solve", "--format", "json", "examples/rod_chain.qd"]);
    assert_eq!(code, 0);
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    let obj = j.as_object().unwrap();
    assert_eq!(obj.keys().next().map(String::as_str), Some("intermediates"));
    let list = j["intermediates"].as_array().unwrap();
    assert!(list.len() > 50, "{} intermediates", list.len());
    let names: Vec<&str> = list.iter().map(|e| e["name"].as_str().unwrap()).collect();
    assert!(names.contains(&"M_11") && names.contains(&"D_4") && names.contains(&"B2_33"));
    assert_eq!(j["mass_matrix"][0][1], "M_12");
    assert_eq!(j["mass_matrix"][1][0], "M_12");
    // each value re-parses in the scene's names and the names before it
    // (bound as symbols: their expansion is what the names avoid)
    let scene = Scene::parse(&std::fs::read_to_string("examples/rod_chain.qd").unwrap()).unwrap();
    let mut bound: Vec<(String, qdot::Value)> = Vec::new();
    for e in list {
        let ast = qdot::parse::parse_expr(e["value"].as_str().unwrap()).unwrap();
        let extra: Vec<(&str, qdot::Value)> =
            bound.iter().map(|(n, v)| (n.as_str(), v.clone())).collect();
        scene.evaluate(&ast, &extra).unwrap();
        let name = e["name"].as_str().unwrap().to_string();
        bound.push((name.clone(), qdot::Value::Scalar(Expr::unknown(&name))));
    }
    let (code, out, _) = qdot(&["solve", "--format", "json", "examples/heavy_top.qd"]);
    assert_eq!(code, 0);
    assert!(!out.contains("\"intermediates\""));
    let (code, _, err) = qdot(&["solve", "--expand", "examples/rod_chain.qd"]);
    assert_ne!(code, 0);
    assert!(err.contains("expression too large"), "{err}");
}

/// The size rule: the chain of three rods (118 terms of M and f) stays
/// expanded, the chain of four (508) is kept; `--structured` keeps the
/// three; a scene it cannot keep says why.
#[test]
fn the_size_rule_keeps_four_rods_and_expands_three() {
    let ctx = qdot::Context::new();
    let r3 = qdot::app::solve(&ctx, &chain3d(3)).unwrap();
    assert!(r3
        .result
        .dynamics
        .as_ref()
        .unwrap()
        .1
        .intermediates()
        .is_none());
    let r4 = qdot::app::solve(&ctx, &chain3d(4)).unwrap();
    assert!(r4
        .result
        .dynamics
        .as_ref()
        .unwrap()
        .1
        .intermediates()
        .is_some());
    let opts = qdot::CommandOptions {
        structure: qdot::app::Structure::Kept,
        ..Default::default()
    };
    let kept = qdot::app::run(&ctx, qdot::Command::Solve, &chain3d(3), &opts).unwrap();
    let text = qdot::render(&kept, qdot::Format::Text).unwrap();
    assert!(text.starts_with("Intermediates"), "{text}");
    let src = std::fs::read_to_string("examples/seed_22_2_constraints.qd").unwrap();
    let e = qdot::app::run(&ctx, qdot::Command::Solve, &src, &opts).unwrap_err();
    assert!(
        e.message
            .contains("is derived expanded, not through intermediates"),
        "{}",
        e.message
    );
}

/// A structured scene is refused where the expanded values are needed,
/// never treated as if its names were constants.
#[test]
fn commands_that_need_expanded_values_refuse_a_structured_scene() {
    let s = Scene::parse_structured(&chain3d(2)).unwrap();
    let set = Default::default();
    let e = qdot::equilibria(&s, &set).unwrap_err();
    assert!(
        e.message.contains("needs the scene expanded"),
        "{}",
        e.message
    );
    assert!(qdot::modes(&s, None, &set).is_err());
    assert!(qdot::mechanics::Hamiltonian::derive(&s).is_err());
    // the generalized forces go through the tape, expanded
    let plain = Scene::parse(&chain3d(2)).unwrap();
    let q1 = qdot::mechanics::generalized_forces(&s);
    let q2 = qdot::mechanics::generalized_forces(&plain);
    for (a, b) in q1.iter().zip(&q2) {
        assert!(a.equals(b), "{a} vs {b}");
    }
}

/// A singular mass matrix (a rod without inertia about the axis it
/// spins on) is refused through the intermediates as it is expanded.
#[test]
fn a_singular_mass_matrix_is_refused_through_intermediates() {
    let src = "coordinates phi, theta\nparameters m, A, l\n\
        frame B = rot(z, phi)\n\
        body rod: mass m, inertia [A, A, 0], frame B, at [0, 0, 0]\n\
        frame C = rot(x, theta)\n\
        body bob: mass m, inertia [A, A, A], frame C, at l*axis(C, 3)\n";
    let s = Scene::parse_structured(src).unwrap();
    let e = s.lagrange().unwrap().accelerations().unwrap_err();
    assert!(
        e.message.contains("the mass matrix is singular"),
        "{}",
        e.message
    );
}

/// The work budget bounds the structured derivation: a budget far below
/// the 20-rod chain's needs stops it with the usual error.
#[test]
fn the_budget_bounds_the_structured_derivation() {
    let ctx = qdot::Context::new().with_max_terms(2_000);
    let e = qdot::app::solve(&ctx, &chain3d(20)).unwrap_err();
    assert!(e.message.contains("expression too large"), "{}", e.message);
}

/// `--keep alpha` on the slider-crank: the reactions are written in α and
/// its rates, each smaller than expanded, and equal to the expanded ones at
/// random instants and parameters (where α is defined: L > R).
#[test]
fn kept_alpha_writes_the_slider_crank_reactions_in_alpha_and_its_rates() {
    let src = std::fs::read_to_string("examples/slider_crank.qd").unwrap();
    let plain = Scene::parse(&src).unwrap();
    let plain = qdot::solve::system::solve_scene(&plain).unwrap();
    let kept_scene = Scene::parse_keeping(&src, &["alpha".to_string()]).unwrap();
    let kept = qdot::solve::system::solve_scene(&kept_scene).unwrap();
    let tape = kept_scene.tape.as_ref().unwrap();
    let names: Vec<String> = tape.entries().iter().map(|e| e.input_name()).collect();
    assert_eq!(names, ["alpha", "alpha_dot", "alpha_ddot"]);
    let mut rng = qdot_exact::rng::SplitMix64::new(3);
    for _ in 0..5 {
        let seed = rng.next_u64();
        let value = |a: &Atom| -> Option<f64> {
            let mut r = qdot_exact::rng::SplitMix64::keyed(seed, a);
            Some(match a {
                Atom::Param(p) if p.as_ref() == "L" => r.uniform(2.0, 3.0),
                Atom::Param(p) if p.as_ref() == "R" => r.uniform(0.5, 1.0),
                _ => r.uniform(0.5, 1.5),
            })
        };
        // in solving order, each through the unknowns before it
        let mut known = rustc_hash::FxHashMap::default();
        for (name, x) in &kept[0].values {
            let y = &plain[0].values.iter().find(|(n, _)| n == name).unwrap().1;
            let resolved = x.subs_many(&known).unwrap();
            let (a, b) = (
                tape.eval_f64(&resolved, &value).unwrap(),
                y.eval_f64(&value).unwrap(),
            );
            assert!(
                (a - b).abs() <= 1e-10 * (1.0 + b.abs()),
                "{name}: {a} vs {b}"
            );
            assert!(
                x.to_input().len() * 4 < y.to_input().len(),
                "{name} is not 4 times smaller"
            );
            known.insert(qdot::expr::atom::unknown(name), resolved);
        }
    }
    let order: Vec<&str> = kept[0].values.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(order, ["Bx", "Ax", "Ay", "By", "N", "M"]);
    let size = |v: &[(String, Expr)]| v.iter().map(|(_, x)| x.to_input().len()).sum::<usize>();
    assert!(size(&kept[0].values) * 6 < size(&plain[0].values));
    assert_eq!(
        kept[0].values[5].1.to_input(),
        "Ax*R*sin(omega*t) - Ay*R*cos(omega*t)"
    );
    assert_eq!(kept[0].values[4].1.to_input(), "g*mB + By");
    let e = Scene::parse_keeping(&src, &["beta".to_string()]).unwrap_err();
    assert!(e.message.contains("no definition `beta`"), "{}", e.message);
    let turned = "coordinates x\nparameters m\na = x/2\nframe B = rot(z, a)\n\
        body b: mass m, inertia [m, m, m], frame B, at [x, 0, 0]\n";
    let e = Scene::parse_keeping(turned, &["a".to_string()]).unwrap_err();
    assert!(e.message.contains("a rotation's angle"), "{}", e.message);
}

/// Two particles on a spring: the spring's length is a square root of
/// kept components (an intermediate inside a function), differentiated
/// through it.
#[test]
fn a_spring_between_kept_points_is_differentiated_through_the_root() {
    let src = "coordinates x1, y1, x2, y2\nparameters m, k, l0\n\
        P1 = [x1, y1 + x1^2]\nP2 = [x2 + y1, y2*x2]\n\
        particle a: mass m, at P1\nparticle b: mass 2*m, at P2\n\
        potential V = 1/2*k*(norm(P2 - P1) - l0)^2\n";
    assert_same_as_expanded(src, false);
}

/// `forces` reads a body scene with its kinematics kept: the bodies'
/// kinetic energies stay in names (not expanded), and the generalized
/// forces, expanded from the intermediates, equal the expanded reading's.
#[test]
fn forces_do_not_expand_the_kinetic_energy_of_a_body_chain() {
    let src = chain3d(8);
    let kept = Scene::read(&src, qdot::scene::Structure::Auto).unwrap();
    assert!(kept.tape.as_ref().is_some_and(|t| !t.is_empty()));
    for d in kept.role(qdot::parse::ast::Role::Kinetic) {
        let e = d.value.as_scalar().unwrap();
        assert!(e.num().len() < 40, "{} has {} terms", d.name, e.num().len());
    }
    let plain = Scene::parse(&src).unwrap();
    let want = qdot::mechanics::generalized_forces(&plain);
    let got = qdot::mechanics::expanded_generalized_forces(&kept).unwrap();
    assert_eq!(got.len(), 8);
    for (a, b) in got.iter().zip(&want) {
        assert!(a.equals(b), "{a} vs {b}");
    }
    // the expanded reading's kinetic energy is what `forces` no longer forms
    let expanded: usize = plain
        .role(qdot::parse::ast::Role::Kinetic)
        .map(|d| d.value.as_scalar().unwrap().num().len())
        .sum();
    assert!(expanded > 1000, "{expanded}");
    // the JSON names the energies' intermediates; the forces are expanded
    let (out, _) = qdot::run(
        qdot::Command::Forces,
        &src,
        qdot::Format::Json,
        &Default::default(),
    )
    .unwrap();
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let names: Vec<&str> = json["intermediates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"omega_B8_x"), "{names:?}");
    assert_eq!(
        json["generalized_forces"]["q8"].as_str().unwrap(),
        qdot::expr::print::input(&want[7])
    );
}
