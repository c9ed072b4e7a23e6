//! Results written through named intermediates (`expr::tape`): the
//! structured derivation equals the expanded one, exactly.

use qdot::expr::atom::Atom;
use qdot::expr::Expr;
use qdot::scene::Scene;

/// The 3D chain of `scripts/anchor_frames.py`.
pub fn chain3d(n: usize) -> String {
    let mut s = String::from("coordinates ");
    s += &(1..=n)
        .map(|k| format!("q{k}"))
        .collect::<Vec<_>>()
        .join(", ");
    s += "\nparameters m, A, C, l, g\n";
    for k in 1..=n {
        let ax = if k % 2 == 1 { "x" } else { "y" };
        if k == 1 {
            s += "frame B1 = rot(x, q1)\n";
        } else {
            s += &format!("frame B{k} = B{} * rot({ax}, q{k})\n", k - 1);
        }
    }
    for k in 1..=n {
        let base = if k == 1 {
            String::new()
        } else {
            format!("P{} ", k - 1)
        };
        let lead = if k == 1 { "-l/2*" } else { "- l/2*" };
        s += &format!(
            "body b{k}: mass m, inertia [A, A, C], frame B{k}, at {base}{lead}axis(B{k}, 3)\n"
        );
        if k < n {
            let lead = if k == 1 { "-l*" } else { "- l*" };
            s += &format!("P{k} = {base}{lead}axis(B{k}, 3)\n");
        }
    }
    s += "gravity [0, 0, -g]\n";
    s
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
        let value = |a: &Atom| -> Option<f64> {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            std::hash::Hash::hash(a, &mut h);
            let mut r = qdot_exact::rng::SplitMix64::new(seed ^ std::hash::Hasher::finish(&h));
            Some(r.uniform(-1.5, 1.5).abs() + 0.25)
        };
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
        let src = fixture["scenes"][n.to_string()].as_str().unwrap();
        let body = |s: &str| -> Vec<String> {
            s.lines()
                .filter(|l| !l.starts_with('#'))
                .map(|l| l.trim().to_string())
                .collect()
        };
        assert_eq!(
            body(src),
            body(&chain3d(n)),
            "the fixture's scene is this file's chain"
        );
        let l = Scene::parse_structured(src).unwrap().lagrange().unwrap();
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
        let got: Vec<f64> = acc
            .values()
            .iter()
            .map(|e| tape.eval_f64(e, &value).unwrap())
            .collect();
        let err = got
            .iter()
            .zip(&want)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            err <= 1e-12 * scale(&want),
            "n = {n}: q̈ {got:?} vs aba {want:?}"
        );
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
