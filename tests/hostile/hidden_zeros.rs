//! Hostile inputs: zeros the canonical form cannot see. cos(π/7) −
//! cos(2π/7) + cos(3π/7) − 1/2 is 0, but sin(π/7) and cos(π/7) are atoms
//! related only by sin² + cos² = 1 and the multiple-angle formulas, so its
//! canonical form is not 0. (The same held for cos(π/5) − cos(2π/5) − 1/2
//! until the pentagon's angles got exact values.) qdot used to divide by it and print a result with a zero
//! denominator; it now refuses to divide by what it cannot prove nonzero,
//! and takes a provable pivot first in its eliminations.

use crate::bound::*;
use proptest::prelude::*;
use qdot::expr::atom::Atom;
use qdot::expr::Expr;
use qdot::solve::system::solve_scene;
use qdot::Scene;

/// cos(π/7) − cos(2π/7) + cos(3π/7) − 1/2, which is 0 (the real part of
/// ζ + ζ³ + ζ⁵ for ζ = exp(iπ/7), a sum of roots of ζ⁷ = −1, is 1/2).
const HIDDEN_ZERO: &str = "(cos(pi/7) - cos(2*pi/7) + cos(3*pi/7) - 1/2)";

fn scene() -> Scene {
    Scene::parse("coordinates x\nparameters a, b\n").expect("scene")
}

/// The value at a = 2, b = 3, x = 1/2.
fn numeric(e: &Expr) -> f64 {
    e.eval_f64(&|atom| match atom {
        Atom::Param(n) if &**n == "a" => Some(2.0),
        Atom::Param(n) if &**n == "b" => Some(3.0),
        Atom::Coord(..) => Some(0.5),
        _ => None,
    })
    .expect("a value")
}

#[test]
fn the_hidden_zero_is_not_seen_by_the_canonical_form_but_is_zero() {
    let z = scene().expr(HIDDEN_ZERO).expect("a value");
    assert!(
        !z.is_zero(),
        "the canonical form now sees it: update this suite"
    );
    assert!(numeric(&z).abs() < 1e-15, "{}", numeric(&z));
}

#[test]
fn dividing_by_a_hidden_zero_is_refused_with_its_position() {
    for src in [
        format!("1/{HIDDEN_ZERO}"),
        format!("x/(a*{HIDDEN_ZERO})"),
        format!("1/(a*{HIDDEN_ZERO} + b*x*{HIDDEN_ZERO})"),
        format!("(a + b)/{HIDDEN_ZERO}^2"),
    ] {
        let e = scene().expr(&src).expect_err(&src);
        assert!(
            e.message.starts_with("this divisor may be zero: ")
                && e.message.contains("is 0 to 9 digits"),
            "{src}: {}",
            e.message
        );
        assert!(
            e.hint
                .as_deref()
                .is_some_and(|h| h.contains("exact value") && h.contains("2·sin(x/2)·cos(x/2)")),
            "{src}: {:?}",
            e.hint
        );
    }
    refused_in_a_scene("hidden_zero", HIDDEN_ZERO, "k/c*x^2", "scene.qd:5:17");
}

/// `qdot derive` of a scene (`tag`, its file's name) with c = `zero` and
/// the potential `potential` (which divides by c) stops with the refusal
/// at `position`.
fn refused_in_a_scene(tag: &str, zero: &str, potential: &str, position: &str) {
    let src = format!(
        "coordinates x\nparameters m, k\nc = {zero}\nkinetic E = 1/2*m*x'^2\npotential V = {potential}\n"
    );
    let o = qdot_scene(tag, src.as_bytes(), "derive", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.contains("error: this divisor may be zero: "),
        "{}",
        o.stderr
    );
    assert!(o.stderr.contains(position), "{}", o.stderr);
}

#[test]
fn dividing_by_constants_that_are_not_zero_still_works() {
    let s = scene();
    let c = |k: f64| (k * std::f64::consts::PI / 7.0).cos();
    // cos(π/7) − cos(2π/7) + cos(3π/7) = 1/2: its reciprocal is 2, printed unsimplified
    for (src, want) in [
        ("1/(cos(pi/7) - cos(2*pi/7) + cos(3*pi/7))", 2.0),
        ("1/(cos(pi/7) - cos(2*pi/7))", 1.0 / (c(1.0) - c(2.0))),
        ("1/sin(pi/7)", 1.0 / (std::f64::consts::PI / 7.0).sin()),
        (
            "a/(a*(cos(pi/7) - cos(2*pi/7) + cos(3*pi/7) - 1/2) + b)",
            2.0 / 3.0,
        ),
        ("1/(cos(1)^2 + sin(1)^2 - cos(2))", 1.0 / (1.0 - 2f64.cos())),
    ] {
        let v = numeric(&s.expr(src).expect(src));
        assert!(
            (v - want).abs() < 1e-12 * want.abs(),
            "{src}: {v} vs {want}"
        );
    }
}

#[test]
fn eliminations_take_a_provable_pivot_first_and_refuse_a_doubtful_one() {
    // solvable: x − y = 0 gives the pivot (x = y = G/(1 + k) = G)
    let solvable =
        format!("parameters G\nk = {HIDDEN_ZERO}\nsolve x, y {{\n  k*x + y = G\n  x - y = 0\n}}\n");
    let o = qdot_scene("pivot_ok", solvable.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{}", o.stderr);
    let s = Scene::parse(&solvable).expect("scene");
    let blocks = solve_scene(&s).expect("solved");
    assert_eq!(blocks[0].values.len(), 2);
    for (name, value) in &blocks[0].values {
        let v = value
            .eval_f64(&|a| matches!(a, Atom::Param(n) if &**n == "G").then_some(1.0))
            .expect("a number");
        assert!((v - 1.0).abs() < 1e-13, "{name} = {v}");
    }
    // the same with k = sin a − 2·sin(a/2)·cos(a/2), zero for every a
    let half_angle = "parameters G, a\nk = sin(a) - 2*sin(a/2)*cos(a/2)\nsolve x, y {\n  k*x + y = G\n  x - y = 0\n}\n";
    let blocks = solve_scene(&Scene::parse(half_angle).expect("scene")).expect("solved");
    assert_eq!(blocks[0].values.len(), 2);
    // inconsistent (k = 0: y = G and 2y = 3G): no pivot can be proved
    let inconsistent = format!(
        "parameters G\nk = {HIDDEN_ZERO}\nsolve x, y {{\n  k*x + y = G\n  2*k*x + 2*y = 3*G\n}}\n"
    );
    let o = qdot_scene("pivot_doubt", inconsistent.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{}", o.stdout);
    assert!(
        o.stderr.contains("error: this divisor may be zero: "),
        "{}",
        o.stderr
    );
}

/// sin x and sin(x/2) are independent atoms: sin x − 2·sin(x/2)·cos(x/2)
/// is zero as a function, with a nonzero canonical form.
#[test]
fn angles_and_their_fractions_are_not_divided_by_when_they_cancel() {
    let s = scene();
    for src in [
        "1/(sin(x) - 2*sin(x/2)*cos(x/2))",
        "a/(cos(x) - cos(x/2)^2 + sin(x/2)^2)",
        "1/(b*(cos(x/3)^3 - 3/4*cos(x/3)) - b/4*cos(x))",
        "1/(sin(x/2 + a) - sin(x/2)*cos(a) - cos(x/2)*sin(a) + sin(x/4)*(sin(x) - 2*sin(x/2)*cos(x/2)))",
    ] {
        let e = s.expr(src).expect_err(src);
        assert!(
            e.message.starts_with("this divisor may be zero: "),
            "{src}: {}",
            e.message
        );
    }
    // related angles that do not cancel divide, to the right value
    for (src, want) in [
        (
            "1/(sin(x) - sin(x/2))",
            1.0 / (0.5f64.sin() - 0.25f64.sin()),
        ),
        ("1/(sin(x) - 2*sin(x/2)*cos(x/2) + a)", 0.5),
    ] {
        let v = numeric(&s.expr(src).expect(src));
        assert!(
            (v - want).abs() < 1e-12 * want.abs(),
            "{src}: {v} vs {want}"
        );
    }
    // in a scene, the error points at the divisor
    refused_in_a_scene(
        "half_angle",
        "sin(x) - 2*sin(x/2)*cos(x/2)",
        "k*x^2/c",
        "scene.qd:5:21",
    );
}

fn small_poly() -> impl Strategy<Value = String> {
    let atom = prop::sample::select(vec!["sin(pi/7)", "cos(pi/7)", "sqrt(2)", "a", "1"]);
    prop::collection::vec(
        (prop_oneof![-3i32..=-1, 1i32..=3], atom.clone(), atom),
        1..5,
    )
    .prop_map(|ts| {
        ts.iter()
            .map(|(c, u, v)| format!("({c})*{u}*{v}"))
            .collect::<Vec<_>>()
            .join(" + ")
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(64), ..ProptestConfig::default() })]

    /// A multiple of the hidden zero is never divided by; the same plus
    /// one always is, to the right value.
    #[test]
    fn multiples_of_a_hidden_zero_are_refused_and_shifts_are_not(r in small_poly()) {
        let s = scene();
        let rv = s.expr(&r).expect("a value");
        prop_assume!(numeric(&rv).abs() > 1e-6);
        let zero = s.expr(&format!("1/(({r})*{HIDDEN_ZERO})"));
        prop_assert!(zero.is_err(), "{r}: divided by a hidden zero");
        let one = s.expr(&format!("1/(({r})*{HIDDEN_ZERO} + 1)")).expect("divisible");
        prop_assert!((numeric(&one) - 1.0).abs() < 1e-12, "{r}: {}", numeric(&one));
    }
}
