//! `modes` and `response` with `--set`: the closed forms evaluated beside
//! the formulas (ω² and ω in rad/s, f in Hz, ζ, ω_peak, the bandwidth),
//! with only the digits the evaluation certifies.

use crate::common::run::qdot;

fn lines_with(out: &str, needle: &str) -> Vec<String> {
    out.lines()
        .filter(|l| l.contains(needle))
        .map(String::from)
        .collect()
}

#[test]
fn modes_give_omega_and_f_beside_omega_squared() {
    let (code, out, err) = qdot(&["modes", "examples/seed_24_2.qd", "--set", "m=1,k=1,R=1"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        lines_with(&out, "rad/s"),
        [
            "      ω₁² = 0.166667, ω₁ = 0.408248 rad/s, f₁ = 0.0649747 Hz",
            "      ω₂² = 1.00000, ω₂ = 1.00000 rad/s, f₂ = 0.159155 Hz",
        ]
    );
    // without values, the closed forms alone
    let (_, out, _) = qdot(&["modes", "examples/seed_24_2.qd"]);
    assert!(!out.contains("rad/s"), "{out}");
}

#[test]
fn response_gives_zeta_the_peak_and_the_bandwidth() {
    let (code, out, err) = qdot(&[
        "response",
        "examples/forced_oscillator.qd",
        "--set",
        "m=1,k=4,c=0.2,F0=1",
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        lines_with(&out, "rad/s"),
        [
            "    ω₁² = 4.00000, ω₁ = 2.00000 rad/s, f₁ = 0.318310 Hz",
            "    ω₀² = 4.00000, ω₀ = 2.00000 rad/s, f₀ = 0.318310 Hz, ζ = 0.0500000",
            "    ω_peak = 1.99499 rad/s, f_peak = 0.317513 Hz",
            "    Ω₂ − Ω₁ = 0.200504 rad/s, Δf = 0.0319113 Hz",
        ]
    );
    let (_, out, _) = qdot(&["response", "examples/forced_oscillator.qd"]);
    assert!(!out.contains("rad/s"), "{out}");
}

/// `1.00004e−6` as a number and the half unit of its last digit.
fn printed(s: &str) -> (f64, f64) {
    let s = s.replace('−', "-");
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let exp: i32 = exp.parse().expect("an exponent");
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    let v: f64 = s.parse().expect("a number");
    (v, 0.5 * 10f64.powi(exp - decimals))
}

#[test]
fn a_bandwidth_lost_to_cancellation_shows_only_certain_digits() {
    // ζ = 2.5·10⁻⁷: (Ω₂ − Ω₁)² is the difference of two numbers near 8
    // that agree to 12 digits; Ω₂ − Ω₁ = 2ζω₀ = 10⁻⁶ to 13 digits
    let (code, out, err) = qdot(&[
        "response",
        "examples/forced_oscillator.qd",
        "--set",
        "m=1,k=4,c=1e-6,F0=1",
    ]);
    assert_eq!(code, 0, "{err}");
    let line = lines_with(&out, "Ω₂ − Ω₁ = ")
        .pop()
        .expect("the bandwidth's value");
    let value = line
        .split("Ω₂ − Ω₁ = ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .expect("a value");
    let (v, half) = printed(value);
    assert!(
        (v - 1e-6).abs() <= half,
        "{line}: {v} is not 1e-6 to its last digit"
    );
}
