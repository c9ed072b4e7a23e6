//! Property tests of the kinetic energy's definiteness (issue 33, item 2):
//! random exact-rational mass and stiffness matrices (positive definite,
//! negative definite, indefinite), built into scenes E = ½·q̇ᵀ·M·q̇,
//! V = ½·qᵀ·K·q; every verdict of `modes` and of `equilibrium` agrees with
//! the eigenvalues λ of M⁻¹·K computed independently (nalgebra, floats).
//! Random inertia tensors are accepted exactly when their eigenvalues are
//! those of a rigid body.
//!
//! The oracle: the linearization M·q̈ + K·q = 0 grows when some λ is off
//! the positive axis (complex or negative). For a definite M, stable ⇔
//! every λ > 0. For an indefinite M qdot never says "stable" (the energy
//! bounds nothing, so the nonlinear terms decide); it says "unstable"
//! only when the linearization grows, and for two coordinates it always
//! finds that growth.

use nalgebra::DMatrix;
use proptest::prelude::*;
use qdot::solve::equilibrium::{equilibria, Stability, Values};
use qdot::solve::oscillations::modes;
use qdot::Scene;

/// A symmetric n×n matrix of small rationals a/d.
#[allow(clippy::needless_range_loop)] // matrix indices read best as indices
fn symmetric(n: usize) -> impl Strategy<Value = Vec<Vec<(i64, i64)>>> {
    proptest::collection::vec((-6i64..=6, 1i64..=3), n * (n + 1) / 2).prop_map(move |v| {
        let mut m = vec![vec![(0, 1); n]; n];
        let mut it = v.into_iter();
        for i in 0..n {
            for j in i..n {
                let x = it.next().expect("enough entries");
                m[i][j] = x;
                m[j][i] = x;
            }
        }
        m
    })
}

fn float(m: &[Vec<(i64, i64)>]) -> DMatrix<f64> {
    let n = m.len();
    DMatrix::from_fn(n, n, |i, j| m[i][j].0 as f64 / m[i][j].1 as f64)
}

/// ½·Σ X_ij·u_i·u_j in scene syntax.
fn quadratic(m: &[Vec<(i64, i64)>], u: &[String]) -> String {
    let mut terms = vec!["0".to_string()];
    for (i, row) in m.iter().enumerate() {
        for (j, &(a, d)) in row.iter().enumerate() {
            terms.push(format!("({a}/{d})*{}*{}", u[i], u[j]));
        }
    }
    format!("1/2*({})", terms.join(" + "))
}

fn scene(m: &[Vec<(i64, i64)>], k: &[Vec<(i64, i64)>]) -> String {
    let q: Vec<String> = (1..=m.len()).map(|i| format!("x{i}")).collect();
    let qd: Vec<String> = q.iter().map(|c| format!("{c}'")).collect();
    format!(
        "coordinates {}\nkinetic E = {}\npotential V = {}\n",
        q.join(", "),
        quadratic(m, &qd),
        quadratic(k, &q)
    )
}

#[derive(Debug, PartialEq, Eq, Clone, Copy)]
enum Kind {
    Positive,
    Negative,
    Indefinite,
}

/// M's definiteness from its eigenvalues; `None` near singular.
fn kind(m: &DMatrix<f64>) -> Option<Kind> {
    let e = m.clone().symmetric_eigen().eigenvalues;
    let scale = e.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if e.iter().any(|x| x.abs() <= 1e-6 * scale) {
        return None;
    }
    Some(if e.iter().all(|x| *x > 0.0) {
        Kind::Positive
    } else if e.iter().all(|x| *x < 0.0) {
        Kind::Negative
    } else {
        Kind::Indefinite
    })
}

/// Whether M⁻¹·K has an eigenvalue off the positive axis; `None` near
/// the boundary (a zero or nearly real, nearly repeated λ).
fn grows(m: &DMatrix<f64>, k: &DMatrix<f64>) -> Option<bool> {
    let a = m.clone().lu().solve(k)?;
    let l = a.complex_eigenvalues();
    let scale = l.iter().fold(0.0f64, |s, z| s.max(z.norm()));
    let (clear, blur) = (1e-5 * scale, 1e-7 * scale);
    let mut off = false;
    for z in l.iter() {
        if z.norm() <= clear || (z.im.abs() > blur && z.im.abs() <= clear) {
            return None;
        }
        off |= z.im.abs() > clear || z.re < 0.0;
    }
    Some(off)
}

/// The verdicts of `modes` and of the one equilibrium, in that order.
fn verdicts(src: &str) -> [Stability; 2] {
    let s = Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene", src)));
    let none = Values::default();
    let md = modes(&s, None, &none).expect("modes");
    let eq = equilibria(&s, &none).expect("equilibria");
    assert_eq!(eq.equilibria.len(), 1, "{src}");
    [md.stability, eq.equilibria[0].stability.clone()]
}

fn check(m: Vec<Vec<(i64, i64)>>, k: Vec<Vec<(i64, i64)>>) -> Result<(), TestCaseError> {
    let (mf, kf) = (float(&m), float(&k));
    let Some(kind) = kind(&mf) else {
        return Err(TestCaseError::reject("M near singular"));
    };
    prop_assume!(kf.determinant().abs() > 1e-6, "K singular");
    let Some(grows) = grows(&mf, &kf) else {
        return Err(TestCaseError::reject("at the boundary"));
    };
    let src = scene(&m, &k);
    for (what, v) in ["modes", "equilibrium"].into_iter().zip(verdicts(&src)) {
        match kind {
            Kind::Positive | Kind::Negative => {
                let want = if grows {
                    Stability::Unstable
                } else {
                    Stability::Stable
                };
                prop_assert_eq!(&v, &want, "{} {:?}\n{}", what, kind, src);
            }
            Kind::Indefinite => {
                prop_assert!(v != Stability::Stable, "{what}: stable\n{src}");
                if v == Stability::Unstable {
                    prop_assert!(grows, "{what}: unstable, but it does not grow\n{src}");
                }
                if m.len() == 2 || !grows {
                    let want_unstable = grows;
                    prop_assert_eq!(
                        v == Stability::Unstable,
                        want_unstable,
                        "{} {:?}\n{}",
                        what,
                        v,
                        src
                    );
                }
            }
        }
    }
    Ok(())
}

/// Whether the eigenvalues of a symmetric I are a rigid body's (≥ 0, each
/// at most the sum of the other two); `None` at the boundary.
fn rigid(i: &DMatrix<f64>) -> Option<bool> {
    let e = i.clone().symmetric_eigen().eigenvalues;
    let scale = e.iter().fold(1.0f64, |a, x| a.max(x.abs()));
    let tol = 1e-9 * scale;
    let sum: f64 = e.iter().sum();
    let margins: Vec<f64> = e
        .iter()
        .copied()
        .chain(e.iter().map(|x| sum - 2.0 * x))
        .collect();
    if margins.iter().any(|x| x.abs() <= tol) {
        return None;
    }
    Some(margins.iter().all(|x| *x > 0.0))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn two_coordinates_agree_with_the_eigenvalues(m in symmetric(2), k in symmetric(2)) {
        check(m, k)?;
    }

    #[test]
    fn three_coordinates_agree_with_the_eigenvalues(m in symmetric(3), k in symmetric(3)) {
        check(m, k)?;
    }

    #[test]
    fn an_inertia_tensor_is_accepted_when_a_rigid_body_has_it(i in symmetric(3)) {
        let Some(want) = rigid(&float(&i)) else {
            return Err(TestCaseError::reject("at the boundary"));
        };
        let rows: Vec<String> = i
            .iter()
            .map(|r| {
                let e: Vec<String> = r.iter().map(|(a, d)| format!("{a}/{d}")).collect();
                format!("[{}]", e.join(", "))
            })
            .collect();
        let src = format!(
            "coordinates phi\nparameters m\nframe B = rot(z, phi)\nbody b: mass m, inertia [{}], frame B, at [0, 0, 0]\n",
            rows.join(", ")
        );
        match Scene::parse(&src) {
            Ok(s) => {
                prop_assert!(want, "accepted\n{src}");
                prop_assert!(s.warnings.is_empty(), "{:?}", s.warnings);
            }
            Err(d) => prop_assert!(!want, "refused: {}\n{src}", d.message),
        }
    }
}
