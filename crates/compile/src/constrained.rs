//! Constrained scenes in a simulation.
//!
//! The augmented system [M −Aᵀ; A 0]·[q̈; λ] = [f; γ] is solved exactly
//! once, with the constraints' acceleration level stabilized after
//! Baumgarte (1972): a holonomic g = 0 is integrated as
//! g̈ + 2α·ġ + α²·g = 0 (critically damped), a velocity constraint h = 0 as
//! ḣ + α·h = 0, so that the drift the integrator's error brings decays at
//! the rate α instead of growing. The result is an unconstrained system
//! M = 1, f = q̈(q, q̇, t), which the compiled evaluators run as any other.
//! α is `Request::baumgarte` (in 1/time of the scene, 1 by default: the
//! work-precision report measured it against 0 and 10; 0 turns the
//! stabilization off); the drift |g| (or |h|) is reported per constraint.

use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::poly::Var;

/// The name of the parameter atom that carries α in the compiled
/// equations: not a name the language can write, so no scene shadows it.
const ALPHA: &str = "(baumgarte alpha)";

/// The variable of α, to give it its value among the parameters.
pub fn alpha_var() -> Var {
    crate::expr::atom::param(ALPHA)
}

/// `lag` as an unconstrained system whose accelerations are those of the
/// stabilized augmented system (unchanged when it has no constraints).
pub fn stabilized(lag: Lagrange) -> Result<Lagrange, Diagnostic> {
    if lag.constraints.is_empty() {
        return Ok(lag);
    }
    let alpha = Expr::param(ALPHA);
    let two_alpha = alpha.mul(&Expr::int(2));
    let alpha2 = alpha.mul(&alpha);
    let mut stab = lag.clone();
    let rows = &mut stab.constraints;
    for j in 0..rows.forcing.len() {
        let h = &rows.velocity[j];
        let extra = match &rows.position[j] {
            Some(g) => two_alpha.mul(h).add(&alpha2.mul(g)),
            None => alpha.mul(h),
        };
        rows.forcing[j] = rows.forcing[j].sub(&extra);
    }
    let acc = stab.accelerations()?;
    let n = lag.coordinates.len();
    let identity = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i == j { Expr::int(1) } else { Expr::zero() })
                .collect()
        })
        .collect();
    Ok(Lagrange {
        mass_matrix: identity,
        forcing: acc.values().to_vec(),
        constraints: Default::default(),
        ..lag
    })
}

/// What the drift column of each constraint measures: g(q, t) for a
/// holonomic constraint, a·q̇ + b otherwise; with the columns' names
/// (`drift_rod`, `drift2`).
pub fn drift(lag: &Lagrange) -> Vec<(String, Expr)> {
    let rows = &lag.constraints;
    (0..rows.velocity.len())
        .map(|j| {
            let name = rows.multipliers[j]
                .strip_prefix("lambda_")
                .map(str::to_string)
                .unwrap_or_else(|| (j + 1).to_string());
            let e = rows.position[j]
                .clone()
                .unwrap_or_else(|| rows.velocity[j].clone());
            (format!("drift_{name}"), e)
        })
        .collect()
}
