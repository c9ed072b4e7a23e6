//! The stability verdict of `qdot modes` on non-conservative systems
//! (issue 46, item 2), exactly: Ziegler's double pendulum under a follower
//! load (flutter from P = (7/2 − √2)·k/l) and a Jeffcott rotor with
//! internal damping in coordinates turning with the shaft; and, as a
//! property, every verdict on random M, C, K (symmetric or not, gyroscopic,
//! circulatory, damped) against the eigenvalues of the first-order system.

use crate::common::run::qdot_on;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use qdot::solve::equilibrium::Values;
use qdot::solve::oscillations::{modes, Stability};
use qdot::Scene;

/// Ziegler's pendulum: bars l, rotational springs k, masses 2m (the joint)
/// and m (the tip), and the follower load P at the tip along the upper bar
/// as the generalized force it does (Q₁ = P·l·sin(θ₁ − θ₂), Q₂ = 0). With
/// a = m·l²·λ, det(K − λ·M) = 2a² − (7k − 2lP)·a + k²: real, positive and
/// distinct roots exactly when 7k − 2lP > 2√2·k.
pub(crate) const ZIEGLER: &str = "\
coordinates th1: angle, th2: angle
parameters m: mass, l: length, k: torque, P: force
kinetic T = m*l^2*th1'^2 + 1/2*m*l^2*(th1'^2 + th2'^2 + 2*cos(th1 - th2)*th1'*th2')
potential V = 1/2*k*th1^2 + 1/2*k*(th2 - th1)^2
force th1: P*l*sin(th1 - th2)
";

/// A Jeffcott rotor in coordinates turning with the shaft at W: external
/// damping c_e on the absolute velocity, internal c_i on the velocity
/// relative to the shaft. det(s²M + sC + K) = (m·s² + c·s + k − m·W²)² +
/// W²·(2m·s + c_e)², c = c_e + c_i, whose Hurwitz determinant Δ₃ is a
/// positive factor times k·(c_e + c_i)² − m·c_i²·W²: unstable above
/// W = √(k/m)·(1 + c_e/c_i).
pub(crate) const JEFFCOTT: &str = "\
coordinates x: length, y: length
parameters m: mass, k: stiffness, c_e: damping, c_i: damping, W: frequency
kinetic T = 1/2*m*((x' - W*y)^2 + (y' + W*x)^2)
potential V = 1/2*k*(x^2 + y^2)
rayleigh R = 1/2*c_i*(x'^2 + y'^2) + 1/2*c_e*((x' - W*y)^2 + (y' + W*x)^2)
";

fn verdict(src: &str, values: &[(&str, f64)]) -> Stability {
    let scene = Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene.qd", src)));
    let set: Values = values.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    modes(&scene, None, &set).expect("modes").stability
}

fn stability_line(tag: &str, src: &str, args: &[&str]) -> String {
    let (code, out, err) = qdot_on("stability", tag, src, "modes", args);
    assert_eq!(code, 0, "{err}");
    out.lines()
        .find(|l| l.starts_with("Stability of the equilibrium"))
        .unwrap_or_else(|| panic!("no verdict in\n{out}"))
        .to_string()
}

#[test]
fn zieglers_pendulum_flutters_past_the_exact_load() {
    assert_eq!(
        stability_line("ziegler", ZIEGLER, &[]),
        "Stability of the equilibrium: undecided (stable when 2·k·√2 + 2·l·P < 7·k; give values with --set)"
    );
    // (7/2 − √2) = 2.0858: P = 3 flutters (ω² complex), 2 does not
    assert_eq!(
        verdict(ZIEGLER, &[("m", 1.0), ("l", 1.0), ("k", 1.0), ("P", 3.0)]),
        Stability::Unstable
    );
    assert_eq!(
        verdict(ZIEGLER, &[("m", 1.0), ("l", 1.0), ("k", 1.0), ("P", 2.08)]),
        Stability::Stable
    );
    assert_eq!(
        verdict(ZIEGLER, &[("m", 1.0), ("l", 1.0), ("k", 1.0), ("P", 2.09)]),
        Stability::Unstable
    );
    assert_eq!(
        stability_line("ziegler_set", ZIEGLER, &["--set", "m=1,l=1,k=1,P=3"]),
        "Stability of the equilibrium: unstable"
    );
}

#[test]
fn zieglers_pendulum_below_the_divergence_load_is_not_called_stable_by_a_sum() {
    // P = 3 meets 7k − 2lP > 0 (the condition qdot printed alone) and
    // flutters all the same
    assert_eq!(
        verdict(ZIEGLER, &[("m", 2.0), ("l", 0.5), ("k", 0.5), ("P", 3.0)]),
        Stability::Unstable
    );
}

#[test]
fn a_jeffcott_rotor_with_internal_damping_whirls_above_its_threshold() {
    assert_eq!(
        stability_line("jeffcott", JEFFCOTT, &[]),
        "Stability of the equilibrium: undecided (stable when c_i²·m·W² < k·(c_e + c_i)²; give values with --set)"
    );
    // threshold W = 1 + c_e/c_i = 2
    let at = |w: f64| {
        verdict(
            JEFFCOTT,
            &[
                ("m", 1.0),
                ("k", 1.0),
                ("c_e", 0.05),
                ("c_i", 0.05),
                ("W", w),
            ],
        )
    };
    assert_eq!(at(3.0), Stability::Unstable);
    assert_eq!(at(2.01), Stability::Unstable);
    assert_eq!(at(1.99), Stability::Stable);
    assert_eq!(at(0.5), Stability::Stable);
}

#[test]
fn negative_damping_under_a_stiff_spring_grows() {
    // K > 0 but the "damper" feeds energy in: m·ẍ − c·ẋ + k·x = 0
    let src = "coordinates x\nparameters m, k, c\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nforce x: c*x'\n";
    assert_eq!(verdict(src, &[]), Stability::Unstable);
    let src = "coordinates x, y\nparameters m, k, c\nkinetic T = 1/2*m*(x'^2 + y'^2)\npotential V = 1/2*k*(x^2 + y^2)\nforce x: c*y'\n";
    // C = [[0, −c], [0, 0]]: neither damping nor gyroscopic; p(s) =
    // (m·s² + k)² has its roots on the imaginary axis, double
    assert!(
        matches!(verdict(src, &[]), Stability::Undecided(_)),
        "{:?}",
        verdict(src, &[])
    );
}

#[test]
fn a_damped_circulatory_system_with_enough_damping_is_stable() {
    // m = 1, c = 2, k = 2, a follower coupling b: det = (s² + 2s + 2)² + b²
    let src = "coordinates x, y\nparameters b\nkinetic T = 1/2*(x'^2 + y'^2)\npotential V = x^2 + y^2\nrayleigh R = x'^2 + y'^2\nforce x: -b*y\nforce y: b*x\n";
    // s² + 2s + 2 ± i·b = 0: s = −1 ± √(−1 ∓ i·b), whose real part
    // √((√(1 + b²) − 1)/2) − 1 < 0 while b² < 8
    assert_eq!(
        verdict(src, &[]),
        Stability::Undecided("stable when b² < 8; give values with --set".into())
    );
    assert_eq!(verdict(src, &[("b", 2.82)]), Stability::Stable);
    assert_eq!(verdict(src, &[("b", 2.83)]), Stability::Unstable);
}

// ------------------------------------------------------------- property

/// The kinds of velocity and position terms drawn.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Conservative,
    Gyroscopic,
    Damped,
    Circulatory,
    General,
}

const KINDS: [Kind; 5] = [
    Kind::Conservative,
    Kind::Gyroscopic,
    Kind::Damped,
    Kind::Circulatory,
    Kind::General,
];

/// A drawn system: the matrices (as numbers) and its scene.
#[derive(Debug)]
struct Case {
    m: Vec<Vec<f64>>,
    c: Vec<Vec<f64>>,
    k: Vec<Vec<f64>>,
    src: String,
}

/// An entry p/q as a number and as text.
type Entry = (f64, String);

fn entry((p, q): (i64, i64)) -> Entry {
    (p as f64 / q as f64, format!("({p}/{q})"))
}

fn zero() -> Entry {
    (0.0, "0".into())
}

/// x made symmetric (or skew) from its lower triangle.
#[allow(clippy::needless_range_loop)] // matrix indices read best as indices
fn symmetrize(x: &mut [Vec<Entry>], skew: bool) {
    let n = x.len();
    for i in 0..n {
        for j in 0..i {
            let (v, t) = x[i][j].clone();
            x[j][i] = if skew {
                (-v, format!("(-{t})"))
            } else {
                (v, t)
            };
        }
        if skew {
            x[i][i] = zero();
        }
    }
}

/// M = Lᵀ·L + I (L integer: M exact in both forms), and K, C of `kind`
/// written as generalized forces −(K·q + C·q̇).
fn case(n: usize, kind: Kind, l: &[i64], kc: &[(i64, i64)]) -> Case {
    let lm = |r: usize, c: usize| l[r * n + c];
    let m: Vec<Vec<i64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| (0..n).map(|r| lm(r, i) * lm(r, j)).sum::<i64>() + i64::from(i == j))
                .collect()
        })
        .collect();
    let mut k: Vec<Vec<Entry>> = (0..n)
        .map(|i| (0..n).map(|j| entry(kc[i * n + j])).collect())
        .collect();
    let mut c: Vec<Vec<Entry>> = (0..n)
        .map(|i| (0..n).map(|j| entry(kc[n * n + i * n + j])).collect())
        .collect();
    let clear = |x: &mut Vec<Vec<Entry>>| x.iter_mut().flatten().for_each(|e| *e = zero());
    match kind {
        Kind::Conservative => {
            symmetrize(&mut k, false);
            clear(&mut c);
        }
        Kind::Gyroscopic => {
            symmetrize(&mut k, false);
            symmetrize(&mut c, true);
        }
        Kind::Damped => {
            symmetrize(&mut k, false);
            symmetrize(&mut c, false);
        }
        Kind::Circulatory => clear(&mut c),
        Kind::General => {}
    }
    let q: Vec<String> = (1..=n).map(|i| format!("x{i}")).collect();
    let mut src = format!("coordinates {}\n", q.join(", "));
    let t: Vec<String> = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| format!("{}*{}'*{}'", m[i][j], q[i], q[j]))
        .collect();
    src.push_str(&format!("kinetic T = 1/2*({})\n", t.join(" + ")));
    for i in 0..n {
        let terms: Vec<String> = (0..n)
            .flat_map(|j| {
                [
                    format!("{}*{}", k[i][j].1, q[j]),
                    format!("{}*{}'", c[i][j].1, q[j]),
                ]
            })
            .collect();
        src.push_str(&format!("force {}: -({})\n", q[i], terms.join(" + ")));
    }
    let value = |x: &[Vec<Entry>]| x.iter().map(|r| r.iter().map(|e| e.0).collect()).collect();
    Case {
        m: m.iter()
            .map(|r| r.iter().map(|&v| v as f64).collect())
            .collect(),
        c: value(&c),
        k: value(&k),
        src,
    }
}

/// What the eigenvalues s of [[0, I], [−M⁻¹K, −M⁻¹C]] say: unstable with
/// Re s > 0, stable with every Re s < 0, or on the imaginary axis with
/// simple nonzero eigenvalues; `None` near a boundary (a repeated or zero
/// eigenvalue on the axis, or Re s within the tolerance of 0 and not
/// simple).
fn expected(case: &Case) -> Option<Stability> {
    use nalgebra::DMatrix;
    let n = case.m.len();
    let m = DMatrix::from_fn(n, n, |i, j| case.m[i][j]);
    let k = DMatrix::from_fn(n, n, |i, j| case.k[i][j]);
    let c = DMatrix::from_fn(n, n, |i, j| case.c[i][j]);
    let lu = m.lu();
    let (mk, mc) = (lu.solve(&k)?, lu.solve(&c)?);
    let a = DMatrix::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
        (true, true) => 0.0,
        (true, false) => f64::from(u8::from(j - n == i)),
        (false, true) => -mk[(i - n, j)],
        (false, false) => -mc[(i - n, j - n)],
    });
    let s: Vec<_> = nalgebra::Schur::try_new(a, f64::EPSILON, 10_000)?
        .complex_eigenvalues()
        .iter()
        .copied()
        .collect();
    let scale = s.iter().fold(1.0f64, |x, z| x.max(z.norm()));
    let tol = 1e-6 * scale;
    let re = s.iter().fold(f64::NEG_INFINITY, |x, z| x.max(z.re));
    if re > tol {
        return Some(Stability::Unstable);
    }
    if re < -tol {
        return Some(Stability::Stable);
    }
    let simple = s.iter().enumerate().all(|(i, a)| {
        a.norm() > 1e-3 * scale && s[..i].iter().all(|b| (a - b).norm() > 1e-3 * scale)
    });
    simple.then_some(Stability::Stable)
}

#[test]
fn verdicts_agree_with_the_eigenvalues_of_the_first_order_system() {
    use proptest::test_runner::{RngAlgorithm, TestRng};
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 300,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let strategy = (1usize..=3, 0usize..KINDS.len()).prop_flat_map(|(n, kind)| {
        (
            Just(n),
            Just(kind),
            proptest::collection::vec(-2i64..=2, n * n),
            proptest::collection::vec((-4i64..=4, 1i64..=3), 2 * n * n),
        )
    });
    let counts = std::cell::RefCell::new([0usize; 4]); // decided, undecided, boundary, all
    runner
        .run(&strategy, |(n, kind, l, kc)| {
            let case = case(n, KINDS[kind], &l, &kc);
            let scene = Scene::parse(&case.src)
                .map_err(|d| TestCaseError::fail(d.render("scene.qd", &case.src)))?;
            let got = modes(&scene, None, &Values::new())
                .map_err(|d| TestCaseError::fail(format!("{}\n{}", d.message, case.src)))?
                .stability;
            let mut counts = counts.borrow_mut();
            counts[3] += 1;
            let Some(want) = expected(&case) else {
                counts[2] += 1;
                return Ok(());
            };
            match got {
                Stability::Undecided(_) => counts[1] += 1,
                ref v if *v == want => counts[0] += 1,
                v => {
                    return Err(TestCaseError::fail(format!(
                        "verdict {v:?}, eigenvalues say {want:?}:\n{}{case:?}",
                        case.src
                    )))
                }
            }
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
    let [decided, undecided, boundary, all] = *counts.borrow();
    eprintln!("{decided} decided, {undecided} undecided, {boundary} at a boundary of {all}");
    assert_eq!(all, 300);
    assert!(boundary * 5 < all, "{boundary} of {all} at a boundary");
    assert!(
        undecided * 10 < decided,
        "{undecided} undecided against {decided} decided"
    );
}
