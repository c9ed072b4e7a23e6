//! Differential tests against SymPy: `tests/fixtures/lagrange.json` holds
//! random scenes and classics with SymPy's Lagrange equations, mass matrices
//! and accelerations, generated offline by `tests/fixtures/gen_lagrange.py`.
//! qdot must agree exactly (the difference is zero in canonical form).

use qdot::Scene;
use serde_json::Value;

fn fixtures() -> Value {
    let path = format!(
        "{}/tests/fixtures/lagrange.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).expect("fixture file exists");
    serde_json::from_str(&text).expect("fixture file is JSON")
}

#[test]
fn agrees_with_sympy() {
    let f = fixtures();
    let cases = f["cases"].as_array().expect("cases");
    assert!(cases.len() >= 50, "only {} cases", cases.len());
    let mut checked_acc = 0;
    let mut failures = Vec::new();
    for case in cases {
        let name = case["name"].as_str().unwrap_or("?");
        let src = case["scene"].as_str().expect("scene");
        let scene = match Scene::parse(src) {
            Ok(s) => s,
            Err(d) => panic!("{name}: {}", d.render(name, src)),
        };
        let ex = |s: &str| {
            scene
                .expr(s)
                .unwrap_or_else(|d| panic!("{name}: expected value `{s}`: {d}"))
        };
        let l = scene
            .lagrange()
            .unwrap_or_else(|d| panic!("{name}: derive: {d}"));
        for (k, r) in case["residuals"]
            .as_array()
            .expect("residuals")
            .iter()
            .enumerate()
        {
            let want = ex(r.as_str().expect("string"));
            let got = l.equations[k].lhs.sub(&l.equations[k].rhs);
            if !got.equals(&want) {
                failures.push(format!("{name}: residual {k}: qdot {got}, SymPy {want}"));
            }
        }
        for (i, row) in case["mass_matrix"]
            .as_array()
            .expect("mass")
            .iter()
            .enumerate()
        {
            for (j, m) in row.as_array().expect("row").iter().enumerate() {
                let want = ex(m.as_str().expect("string"));
                if !l.mass_matrix[i][j].equals(&want) {
                    failures.push(format!(
                        "{name}: M[{i}][{j}]: qdot {}, SymPy {want}",
                        l.mass_matrix[i][j]
                    ));
                }
            }
        }
        if let Some(acc) = case.get("accelerations").and_then(|a| a.as_object()) {
            let got = l
                .accelerations()
                .unwrap_or_else(|d| panic!("{name}: solve: {d}"));
            for (q, e) in &got {
                let want = ex(acc[q].as_str().expect("string"));
                if !e.equals(&want) {
                    failures.push(format!("{name}: {q}'': qdot {e}, SymPy {want}"));
                }
            }
            checked_acc += 1;
        }
    }
    assert!(
        failures.is_empty(),
        "{} mismatches:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(
        checked_acc >= 40,
        "only {checked_acc} cases with accelerations"
    );
}
