//! Compact printed forms (issue 18): the panel of scenes against SymPy's
//! `simplify`, the forms a lecturer writes, and every printed form
//! re-parsing to the same canonical value.
//!
//! tests/fixtures/compact_panel.json is written by
//! `scripts/compact_panel.py sympy` (SymPy 1.14, offline): for each
//! acceleration of the panel, qdot's canonical output before the compact
//! forms, SymPy's `simplify` of it (60 s cap) and both `count_ops`.

use crate::common::run::{json, qdot};
use proptest::prelude::*;
use qdot::expr::compact::count_ops;
use qdot::Scene;
use serde_json::Value;

fn panel() -> Vec<Value> {
    let text = std::fs::read_to_string("tests/fixtures/compact_panel.json").expect("fixture");
    let v: Value = serde_json::from_str(&text).expect("json");
    v["rows"].as_array().expect("rows").clone()
}

fn accelerations(scene: &str) -> serde_json::Map<String, Value> {
    let (code, out, err) = qdot(&["solve", scene, "--format", "json"]);
    assert_eq!(code, 0, "{scene}: {err}");
    json(&out)["accelerations"]
        .as_object()
        .expect("accelerations")
        .clone()
}

/// Our count of operations agrees with SymPy's `count_ops` on the
/// fixture's strings (within one: SymPy folds a sign into a product now and
/// then), and the panel's total is at most SymPy's `simplify`'s.
#[test]
fn the_panel_is_at_most_as_long_as_sympy_simplify() {
    let rows = panel();
    assert!(rows.len() >= 30, "{}", rows.len());
    let mut scenes: Vec<&str> = rows.iter().map(|r| r["scene"].as_str().unwrap()).collect();
    scenes.dedup();
    assert!(scenes.len() >= 10);
    let (mut ours, mut sympy, mut before) = (0usize, 0usize, 0usize);
    for scene in scenes {
        let acc = accelerations(scene);
        for r in rows.iter().filter(|r| r["scene"] == scene) {
            let input = r["input"].as_str().unwrap();
            let counted = r["input_ops"].as_u64().unwrap() as usize;
            assert!(
                count_ops(input).abs_diff(counted) <= 1,
                "{input}: {counted}"
            );
            let now = acc[r["coordinate"].as_str().unwrap()].as_str().unwrap();
            ours += count_ops(now);
            sympy += r["sympy_ops"].as_u64().unwrap() as usize;
            before += counted;
        }
    }
    assert!(
        ours <= sympy,
        "qdot {ours} operations, SymPy simplify {sympy}"
    );
    assert!(ours * 3 < before * 2, "qdot {ours}, before {before}");
}

/// Every acceleration of the panel, as JSON prints it, parses back to the
/// canonical value the library computes.
#[test]
fn the_panel_reparses_to_the_canonical_values() {
    let mut scenes: Vec<String> = panel()
        .iter()
        .map(|r| r["scene"].as_str().unwrap().to_string())
        .collect();
    scenes.dedup();
    for path in scenes {
        let src = std::fs::read_to_string(&path).expect("scene");
        let scene = Scene::parse(&src).expect("parses");
        let lagrange = qdot::mechanics::Lagrange::derive(&scene).expect("equations");
        let acc = lagrange.accelerations().expect("accelerations");
        let printed = accelerations(&path);
        for (name, value) in acc.coordinates().iter().zip(acc.values()) {
            let text = printed[name.as_str()].as_str().unwrap();
            let again = scene.expr(text).unwrap_or_else(|d| panic!("{text}: {d}"));
            assert_eq!(&again, value, "{path} {name}: {text}");
        }
    }
}

/// The forms the issue names.
#[test]
fn the_forms_a_lecturer_writes() {
    let (_, out, _) = qdot(&["solve", "tests/data/compact/double_pendulum.qd"]);
    assert!(
        out.contains("/(l₁·(2·m₁ + m₂ − m₂·cos(2·θ₁ − 2·θ₂)))"),
        "{out}"
    );
    let (_, out, _) = qdot(&["derive", "examples/disk_in_cylinder.qd"]);
    assert!(out.contains("3/2·m·(R − r)²·θ̈"), "{out}");
    // a coefficient cancels against its own denominator before it is
    // compacted: g·m·(R − r)³/(R − r)² is g·m·(R − r)
    let (_, out, _) = qdot(&["hamilton", "examples/disk_in_cylinder.qd"]);
    assert!(
        out.contains("H = −g·m·(R − r)·cos(θ) + p_θ²/(3·m·(R − r)²)"),
        "{out}"
    );
    let (_, out, _) = qdot(&["latex", "--steps", "examples/disk_in_cylinder.qd"]);
    assert!(
        out.contains(r"E &= \frac{3}{4} m (R - r)^{2} \dot{\theta}^{2}"),
        "{out}"
    );
    let (_, out, _) = qdot(&["solve", "tests/data/compact/sliding_support.qd"]);
    assert!(
        out.contains(" = m·sin(θ)·(l·θ̇² + g·cos(θ))/(m·sin²(θ) + M)\n"),
        "{out}"
    );
    let (_, out, _) = qdot(&["solve", "examples/heavy_top.qd"]);
    assert!(
        out.contains(
            "ψ̈ = θ̇·((l²·m + A − C)·cos²(θ)·φ̇ − C·cos(θ)·ψ̇ + (l²·m + A)·φ̇)/(sin(θ)·(l²·m + A))"
        ),
        "{out}"
    );
    // the same form in LaTeX
    let (_, out, _) = qdot(&["latex", "tests/data/compact/double_pendulum.qd"]);
    assert!(
        out.contains(r"2 m_{1} + m_{2} - m_{2} \cos(2 \theta_{1} - 2 \theta_{2})"),
        "{out}"
    );
}

fn trig_term() -> impl Strategy<Value = String> {
    let atom = prop_oneof![
        Just("sin(x)"),
        Just("cos(x)"),
        Just("sin(y)"),
        Just("cos(y)"),
        Just("sin(x - y)"),
        Just("cos(2*x)"),
        Just("a"),
        Just("b"),
        Just("x'"),
    ];
    (-3i32..4, prop::collection::vec(atom, 1..4))
        .prop_map(|(c, fs)| format!("{c}*{}", fs.join("*")))
}

fn trig_poly() -> impl Strategy<Value = String> {
    prop::collection::vec(trig_term(), 1..6).prop_map(|ts| ts.join(" + "))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(300), ..ProptestConfig::default() })]

    /// Quotients of trigonometric polynomials in two angles (where the
    /// compact forms rewrite most: both reductions, Fourier form,
    /// cancellation, factoring) print to text that parses back to the same
    /// value.
    #[test]
    fn compact_forms_reparse_exactly(n in trig_poly(), d in trig_poly()) {
        let scene = Scene::parse("coordinates x, y\nparameters a, b\n").expect("scene");
        let src = format!("({n})/({d})");
        let Ok(e) = scene.expr(&src) else { return Ok(()) };
        let printed = e.to_input();
        let again = scene.expr(&printed).unwrap_or_else(|d| panic!("{printed}: {d}"));
        // equal as values, decided exactly (cross-multiplied and reduced
        // modulo sin² + cos² = 1): a quotient that cancels only modulo the
        // ideal, cos²y/cos y, prints as cos y, whose canonical form is
        // the reduced one
        prop_assert!(again.equals(&e), "{} printed as {}", src, printed);
    }
}

/// A rewriting's size is estimated before it is made: high powers of
/// several angles print at once, in the canonical form (expanding them
/// into a Fourier series or polynomials in cos would take 11⁵ and 101³
/// terms).
#[test]
fn high_powers_of_several_angles_are_not_expanded() {
    let scene = Scene::parse("coordinates a, b, c, d, e\nparameters m\n").expect("scene");
    for src in [
        "sin(a)^10*sin(b)^10*sin(c)^10*sin(d)^10*sin(e)^10 + m",
        "sin(a)^200*sin(b)^200*sin(c)^200 + m",
    ] {
        let e = scene.expr(src).expect("value");
        let printed = e.to_input();
        assert!(
            scene.expr(&printed).expect("re-parses").equals(&e),
            "{printed}"
        );
    }
}
