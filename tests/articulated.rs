//! The accelerations of a tree of rigid bodies by the articulated-body
//! recursion (`Lagrange::articulated_accelerations`): equal to Pinocchio's
//! `aba` and to M⁻¹·f, and refused with a reason where it does not apply.

use qdot::expr::atom::Atom;
use qdot::scene::Scene;

fn chain3d(n: usize) -> String {
    qdot::engine::gallery::rod_chain_3d(n)
}

/// The value of an atom in a case of the Pinocchio fixture.
fn state_value(case: &serde_json::Value, a: &Atom) -> Option<f64> {
    super::structured::state_value(case, a)
}

/// q̈ of the recursion at the fixture's states equals `aba` to 1e-12.
#[test]
fn the_recursion_equals_pinocchio_aba_on_the_rod_chain() {
    let text = std::fs::read_to_string("tests/fixtures/pinocchio_chain3d.json").unwrap();
    let fixture: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut checked = 0;
    for case in fixture["cases"].as_array().unwrap() {
        let n = case["n"].as_u64().unwrap() as usize;
        let src = fixture["scenes"][n.to_string()].as_str().unwrap();
        let scene = Scene::parse_structured(src).unwrap();
        let l = scene.lagrange().unwrap();
        let acc = l.articulated_accelerations(&scene).unwrap();
        let tape = acc.intermediates().unwrap();
        let value = |a: &Atom| state_value(case, a);
        let want: Vec<f64> = case["qdd"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let got = tape.eval_many_f64(acc.values(), &value).unwrap();
        let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (a, b) in got.iter().zip(&want) {
            assert!(
                (a - b).abs() <= 1e-12 * scale,
                "n = {n}: {got:?} vs aba {want:?}"
            );
        }
        checked += 1;
    }
    assert_eq!(checked, 20);
}

#[test]
fn scratch() {
    for n in [1, 2, 3, 5, 10] {
        let scene = Scene::parse_structured(&chain3d(n)).unwrap();
        let l = scene.lagrange().unwrap();
        let t = std::time::Instant::now();
        let acc = l.articulated_accelerations(&scene);
        eprintln!(
            "{n}: {:?} {:?}",
            acc.as_ref().map(|a| a.intermediates().unwrap().len()),
            t.elapsed()
        );
    }
}
