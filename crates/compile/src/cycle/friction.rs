//! The kinetostatic equations at one position, Aᵀ·λ = M·q̈ − f − Σ F·∂s/∂q,
//! with Coulomb friction as the seed writes it: a slider's force
//! F = −μ·|N|·sgn v_rel (21.75), a pin's couple −μ₀·r₀·√(H² + V²)·sgn ω_rel
//! (21.74). The frictions depend on the reactions, so the equations are
//! solved by fixed-point iteration from the reactions without friction.

use super::model::Model;
use super::table::JointKind;
use nalgebra::{DMatrix, DVector};

use crate::limits::MAX_FRICTION_ITERATIONS;
/// A relative velocity below this fraction of the largest velocity is
/// rest: friction's sense is undefined there.
const STICK_FRACTION: f64 = 1e-9;

/// The kinetostatics at one position.
pub(super) enum Kinetostatics {
    /// Every multiplier (by constraint) and every friction (by joint with
    /// friction), after `iterations` friction steps.
    Solved {
        lambda: Vec<f64>,
        friction: Vec<f64>,
        iterations: u32,
    },
    /// Why the position has no reactions.
    Refused(String),
}

/// Solve the kinetostatics with `motion` the motion program's outputs at
/// (q, q̇, t), `a` the constraint Jacobian.
pub(super) fn kinetostatics(
    model: &Model,
    a: &DMatrix<f64>,
    motion: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Kinetostatics {
    let n = model.n;
    let lay = model.layout();
    let mass = DMatrix::from_row_slice(n, n, &motion[lay.mass..lay.mass + n * n]);
    let f = DVector::from_column_slice(&motion[lay.forcing..lay.forcing + n]);
    let r = &mass * DVector::from_column_slice(qdd) - f;
    let lu = a.transpose().lu();
    let Some(mut lambda) = lu.solve(&r) else {
        return Kinetostatics::Refused("the kinetostatic equations are singular here".into());
    };
    if model.frictions.is_empty() {
        return Kinetostatics::Solved {
            lambda: lambda.iter().copied().collect(),
            friction: Vec::new(),
            iterations: 0,
        };
    }
    let scale = qd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let nf = model.frictions.len();
    let mut signs = Vec::with_capacity(nf);
    for (i, fr) in model.frictions.iter().enumerate() {
        let v = motion[lay.relative + i];
        // a coefficient of 0 is no friction: no sense to find, even at rest
        if fr.coefficient == 0.0 {
            signs.push(0.0);
            continue;
        }
        if v.abs() <= STICK_FRACTION * scale || scale == 0.0 {
            return Kinetostatics::Refused(format!(
                "stick: the relative velocity in the joint `{}` vanishes here ({v:.1e}), so its friction's sense is undefined",
                fr.joint
            ));
        }
        signs.push(v.signum());
    }
    let mut forces = vec![0.0; nf];
    for iteration in 1..=MAX_FRICTION_ITERATIONS {
        let mut rhs = r.clone();
        for (i, fr) in model.frictions.iter().enumerate() {
            let normal = match fr.kind {
                JointKind::Slider => lambda[fr.rows[0]].abs(),
                JointKind::Pin => lambda[fr.rows[0]].hypot(lambda[fr.rows[1]]),
            };
            forces[i] = -fr.coefficient * normal * signs[i];
            let d = &motion[lay.direction + i * n..lay.direction + (i + 1) * n];
            for k in 0..n {
                rhs[k] -= forces[i] * d[k];
            }
        }
        let Some(next) = lu.solve(&rhs) else {
            return Kinetostatics::Refused("the kinetostatic equations are singular here".into());
        };
        let change = (&next - &lambda).amax();
        lambda = next;
        if change <= 1e-13 * (1.0 + lambda.amax()) {
            return Kinetostatics::Solved {
                lambda: lambda.iter().copied().collect(),
                friction: forces,
                iterations: iteration,
            };
        }
    }
    Kinetostatics::Refused(format!(
        "the friction iteration did not converge in {MAX_FRICTION_ITERATIONS} steps: with these coefficients the reactions may have no unique solution here"
    ))
}
