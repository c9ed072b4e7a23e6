//! Hostile inputs: exact values at the edges — sin/cos/tan of huge
//! multiples of π, square roots of certainly negative quantities, and
//! functions nested past the bound.

use crate::bound::*;
use proptest::prelude::*;
use qdot::expr::print;
use qdot::Scene;

fn scene() -> Scene {
    Scene::parse("coordinates x\nparameters a, b\n").expect("scene")
}

fn value(src: &str) -> String {
    print::input(&scene().expr(src).expect("a value"))
}

fn error(src: &str) -> String {
    scene().expr(src).expect_err("an error").message
}

#[test]
fn multiples_of_pi_reduce_exactly_however_large() {
    assert_eq!(value("sin(10^18*pi + pi/6)"), "1/2");
    assert_eq!(value("sin(10^18*pi + 7*pi/6)"), "-1/2");
    assert_eq!(value("cos((2^60+1)*pi)"), "-1");
    assert_eq!(value("cos(2^60*pi)"), "1");
    assert_eq!(value("sin(x + (2^60+1)*pi)"), "-sin(x)");
    assert_eq!(value("cos(x + (2^100)*pi)"), "cos(x)");
    assert_eq!(value("cos(-(2^70+1/3)*pi)"), "1/2");
    assert_eq!(value("sin((10^40+1/2)*pi)"), "1");
    assert_eq!(value("sin((10^40+3/2)*pi)"), "-1");
    // A non-twelfth multiple reduces too: 10^40 + 3/7 ≡ 3/7 (mod 2).
    assert_eq!(value("sin((10^40+3/7)*pi)"), value("sin(3*pi/7)"));
    assert_eq!(value("sin((2^90+1 + 3/7)*pi)"), value("-sin(3*pi/7)"));
    assert_eq!(value("sin(-13*pi/5)"), value("-sin(3*pi/5)"));
}

#[test]
fn the_pentagon_and_octagon_angles_are_exact_radicals() {
    let s = scene();
    for (angle, radicals) in [
        ("cos(pi/5)", "(1 + sqrt(5))/4"),
        ("sin(pi/10)", "(sqrt(5) - 1)/4"),
        ("cos(2*pi/5)", "(sqrt(5) - 1)/4"),
        ("sin(pi/5)", "sqrt(10 - 2*sqrt(5))/4"),
        ("cos(pi/10)", "sqrt(2)*sqrt(5 - sqrt(5))*(1 + sqrt(5))/8"),
        ("cos(pi/8)", "sqrt(2 + sqrt(2))/2"),
        ("sin(pi/8)", "(sqrt(2) - 1)*sqrt(2 + sqrt(2))/2"),
        ("cos(7*pi/10)", "-sqrt(10 - 2*sqrt(5))/4"),
        ("sin(-5*pi/8)", "-sqrt(2 + sqrt(2))/2"),
    ] {
        let (a, r) = (
            s.expr(angle).expect(angle),
            s.expr(radicals).expect(radicals),
        );
        assert_eq!(a, r, "{angle} = {a}, not {radicals} = {r}");
    }
    assert_eq!(value("cos(pi/5)"), "sqrt(5)/4 + 1/4");
    // identities between them are decided
    assert_eq!(value("cos(pi/5) - cos(2*pi/5)"), "1/2");
    for zero in [
        "sin(pi/5)^2 + cos(pi/5)^2 - 1",
        "cos(2*pi/5) - (2*cos(pi/5)^2 - 1)",
        "cos(pi/5) - (1 - 2*sin(pi/10)^2)",
        "sin(pi/5) - 2*sin(pi/10)*cos(pi/10)",
        "sin(3*pi/5) - (3*sin(pi/5) - 4*sin(pi/5)^3)",
        "cos(pi/8)^2 - (1 + cos(pi/4))/2",
        "sin(pi/8) - cos(3*pi/8)",
        "sin(pi/4) - 2*sin(pi/8)*cos(pi/8)",
        "cos(pi/10)^2 - cos(pi/5)/2 - 1/2",
        "sin(x + pi/5) - (sin(x)*cos(pi/5) + cos(x)*sin(pi/5))",
    ] {
        assert_eq!(value(zero), "0", "{zero}");
    }
    assert_eq!(
        error("1/(cos(pi/5) - cos(2*pi/5) - 1/2)"),
        "division by zero: this divisor is exactly 0"
    );
    // every multiple of π/40 has the value of f64's sin and cos
    for j in -80..=80 {
        let angle = f64::from(j) * std::f64::consts::PI / 40.0;
        for (f, want) in [("sin", angle.sin()), ("cos", angle.cos())] {
            let src = format!("{f}({j}*pi/40)");
            let got = s
                .expr(&src)
                .expect("a value")
                .eval_f64(&|_| None)
                .expect("a number");
            assert!((got - want).abs() < 1e-15, "{src}: {got} vs {want}");
        }
        let one = s
            .expr(&format!("sin({j}*pi/40)^2 + cos({j}*pi/40)^2"))
            .expect("a value");
        assert!(one.is_one(), "{j}: {one}");
    }
}

#[test]
fn tan_at_a_huge_odd_multiple_of_half_pi_is_an_error() {
    assert_eq!(
        error("tan((10^30+1/2)*pi)"),
        "tan is undefined here: cos of its argument is zero"
    );
    assert_eq!(value("tan((10^30+1/4)*pi)"), "1");
    assert_eq!(value("tan((10^30+3/4)*pi)"), "-1");
}

#[test]
fn square_roots_of_certainly_negative_quantities_are_errors() {
    for src in [
        "sqrt(-a)",
        "sqrt(-a-b)",
        "sqrt(-x^2-1)",
        "sqrt(-a*x^2 - b)",
        "sqrt(-1)",
    ] {
        let e = scene().expr(src).expect_err(src);
        assert!(
            e.message.starts_with("square root of"),
            "{src}: {}",
            e.message
        );
        assert!(e.message.contains("negative"), "{src}: {}", e.message);
    }
    assert_eq!(
        error("sqrt(-a)"),
        "square root of a negative quantity: -a < 0"
    );
    // Not certainly negative: these stay radicals.
    assert_eq!(value("sqrt(a-b)"), "sqrt(a - b)");
    assert_eq!(value("sqrt(-x^2)"), "sqrt(-x^2)");
    assert_eq!(value("sqrt(-x)"), "sqrt(-x)");
    assert_eq!(value("sqrt(4*a^2)"), "2*a");
}

#[test]
fn negative_radicand_is_positioned_in_a_scene() {
    let o = qdot_scene(
        "sqrt_neg",
        b"coordinates x\nparameters m, a\nkinetic E = 1/2*m*x'^2\npotential V = sqrt(-a)*x\n",
        "derive",
        &[],
    );
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr
            .contains("error: square root of a negative quantity: -a < 0"),
        "{}",
        o.stderr
    );
    assert!(o.stderr.contains("scene.qd:4:15"), "{}", o.stderr);
    assert!(o.stderr.contains("parameters are positive"), "{}", o.stderr);
}

/// A chain of `n` definitions a_i = sin(a_{i−1}) and an energy using the last.
fn sin_chain(n: usize) -> String {
    let mut s = String::from("coordinates x\nparameters a, k\na1 = sin(x)\n");
    for i in 2..=n {
        s.push_str(&format!("a{i} = sin(a{})\n", i - 1));
    }
    s.push_str("kinetic E = 1/2*a*x'^2\n");
    s.push_str(&format!("potential V = 1/2*k*x^2 + a*a{n}\n"));
    s
}

#[test]
fn nesting_past_the_bound_is_an_error_at_the_call() {
    for n in [201, 50_000] {
        let o = qdot_scene("deep", sin_chain(n).as_bytes(), "derive", &[]);
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{o:?}");
        assert!(
            o.stderr
                .contains("error: functions nested 201 deep here; qdot allows at most 200"),
            "{}",
            o.stderr
        );
        assert!(o.stderr.contains("scene.qd:203:8"), "{}", o.stderr);
    }
}

#[test]
fn nesting_at_the_bound_derives_solves_and_prints() {
    let src = sin_chain(200);
    for command in ["derive", "solve", "forces", "latex"] {
        let o = qdot_scene("deep200", src.as_bytes(), command, &[]);
        o.assert_clean();
        assert_eq!(o.code, Some(0), "{command}: {}", o.stderr);
    }
}

proptest! {
    /// sin(k·π + r·π) = (−1)^k·sin(r·π) for any integer k, big or small.
    #[test]
    fn sine_has_period_two_pi_exactly(k in any::<i64>(), big in 0u32..200, r in 1i64..24) {
        let k_text = format!("({k}*2^{big})");
        let shifted = value(&format!("sin({k_text}*pi + {r}*pi/12 + x)"));
        let even = k == 0 || big > 0 || k % 2 == 0;
        let base = value(&format!("sin({r}*pi/12 + x)"));
        let expected = if even { base } else { value(&format!("-sin({r}*pi/12 + x)")) };
        prop_assert_eq!(shifted, expected);
    }
}

/// A literal of a million digits is refused at once (reading it is
/// quadratic), and so is a power of a number with too many digits.
#[test]
fn numbers_past_ten_thousand_digits_are_refused() {
    let src = format!(
        "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2\npotential V = {}*x^2\n",
        "7".repeat(1_000_000)
    );
    let o = qdot_scene("million_digits", src.as_bytes(), "solve", &[]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.starts_with("error: a number of 1000000 digits; qdot reads numbers of at most 10000 digits\n --> scene.qd:4:15\n"),
        "{o:?}"
    );
    // the shown line is cut around the caret
    assert!(o.stderr.len() < 1000, "{o:?}");
    assert!(o.stderr.contains("7777…\n"), "{o:?}");
    o.assert_cpu_below(5.0);
    assert_eq!(error("7^20000"), "exponent 20000 is too large");
    assert_eq!(
        error("66610^3066"),
        "this power of a number has about 14789 digits; qdot keeps numbers to 10000 digits"
    );
    assert_eq!(value("2^1000 / 2^999"), "2");
}
