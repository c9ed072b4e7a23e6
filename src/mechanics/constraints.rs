//! Lagrange's equations of the first kind: constraints and multipliers.
//!
//! With constraints Σ_k a_jk·q̇_k + b_j = 0 (a holonomic g_j(q, t) = 0
//! differentiated once) the equations gain the generalized constraint
//! forces Σ_j λ_j·a_jk:
//!
//! ```text
//! M·q̈ − Aᵀ·λ = f,    A·q̈ = γ,
//! ```
//!
//! the second line being the constraints differentiated to the level of
//! the accelerations (γ = −(Ȧ·q̇ + ḃ)). The augmented system is square and
//! solved exactly for q̈ and λ together.

use crate::algebra::linear::{split_linear, SolveError};
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::poly::Var;
use crate::scene::Scene;

/// The constraints of a scene at the level of the accelerations.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConstraintRows {
    /// The multipliers' names (`lambda_rod`), one per constraint.
    pub multipliers: Vec<String>,
    /// The constraints as messages name them (`` `rod` ``, `#2`).
    pub labels: Vec<String>,
    /// Whether each constraint is holonomic (g(q, t) = 0).
    pub holonomic: Vec<bool>,
    /// A: row j holds a_jk, per coordinate.
    pub matrix: Vec<Vec<Expr>>,
    /// γ with A·q̈ = γ.
    pub forcing: Vec<Expr>,
    /// a·q̇ + b, the constraint at the level of the velocities (0 on a motion).
    pub velocity: Vec<Expr>,
    /// g(q, t) of a holonomic constraint (0 on a motion), None otherwise.
    pub position: Vec<Option<Expr>>,
}

impl ConstraintRows {
    /// The rows of the scene's constraints; `qd` and `qdd` are the
    /// velocities' and accelerations' variables in declaration order.
    pub(super) fn of(scene: &Scene, qd: &[Var], qdd: &[Var]) -> Result<ConstraintRows, Diagnostic> {
        let mut rows = ConstraintRows::default();
        for (j, c) in scene.constraints.iter().enumerate() {
            let n = qdd.len();
            // a·q̇ + b, then its time derivative a·q̈ − γ
            let velocity = c
                .coefficients
                .iter()
                .zip(qd)
                .fold(c.rest.clone(), |s, (a, &v)| s.add(&a.mul(&Expr::var(v))));
            let (row, rest) =
                split_linear(&velocity.dt(), qdd).map_err(|m| Diagnostic::global(m.message))?;
            debug_assert_eq!(row.len(), n);
            debug_assert!(row.iter().zip(&c.coefficients).all(|(r, a)| r.equals(a)));
            rows.multipliers.push(c.multiplier.clone());
            rows.labels.push(c.label(j));
            rows.holonomic.push(c.holonomic);
            rows.matrix.push(c.coefficients.clone());
            rows.forcing.push(rest.neg());
            rows.velocity.push(velocity);
            rows.position
                .push(c.holonomic.then(|| c.expression.clone()));
        }
        Ok(rows)
    }

    /// Every expression of the rows, for substitutions and scans.
    pub fn expressions_mut(&mut self) -> impl Iterator<Item = &mut Expr> {
        self.matrix
            .iter_mut()
            .flatten()
            .chain(&mut self.forcing)
            .chain(&mut self.velocity)
            .chain(self.position.iter_mut().flatten())
    }

    /// Every expression of the rows.
    pub fn expressions(&self) -> impl Iterator<Item = &Expr> {
        self.matrix
            .iter()
            .flatten()
            .chain(&self.forcing)
            .chain(&self.velocity)
            .chain(self.position.iter().flatten())
    }

    /// True when the scene has no constraints.
    pub fn is_empty(&self) -> bool {
        self.multipliers.is_empty()
    }

    /// Σ_j λ_j·a_jk for coordinate `k`, one term per constraint acting on
    /// it (the multipliers as unknowns).
    pub fn force_terms(&self, k: usize) -> Vec<(usize, Expr)> {
        self.matrix
            .iter()
            .zip(&self.multipliers)
            .enumerate()
            .filter(|(_, (row, _))| !row[k].is_zero())
            .map(|(j, (row, name))| (j, Expr::unknown(name).mul(&row[k])))
            .collect()
    }
}

/// Solve [M −Aᵀ; A 0]·[q̈; λ] = [f; γ] exactly: (q̈, λ).
pub(super) fn solve_augmented(
    coordinates: &[String],
    mass: &[Vec<Expr>],
    forcing: &[Expr],
    rows: &ConstraintRows,
) -> Result<(Vec<Expr>, Vec<Expr>), Diagnostic> {
    let n = mass.len();
    let m = rows.matrix.len();
    let mut a: Vec<Vec<Expr>> = Vec::with_capacity(n + m);
    for (k, mk) in mass.iter().enumerate() {
        let mut r = mk.clone();
        r.extend(rows.matrix.iter().map(|row| row[k].neg()));
        a.push(r);
    }
    for row in &rows.matrix {
        let mut r = row.clone();
        r.extend(std::iter::repeat_n(Expr::zero(), m));
        a.push(r);
    }
    let b: Vec<Expr> = forcing.iter().chain(&rows.forcing).cloned().collect();
    let mut x = crate::algebra::linear::solve(&a, &b).map_err(|e| match e {
        SolveError::Singular { dependent } => singular(coordinates, rows, &dependent),
        SolveError::Math(m) => Diagnostic::global(m.message),
    })?;
    let lambda = x.split_off(n);
    Ok((x, lambda))
}

/// The error for a singular augmented system: redundant constraints when
/// the null vector lies among the multipliers, else coordinates the
/// constraints leave without inertia.
fn singular(coordinates: &[String], rows: &ConstraintRows, dependent: &[usize]) -> Diagnostic {
    let n = coordinates.len();
    let constraints: Vec<String> = dependent
        .iter()
        .filter(|&&i| i >= n)
        .filter_map(|&i| rows.labels.get(i - n).cloned())
        .collect();
    if !constraints.is_empty() && dependent.iter().all(|&i| i >= n) {
        return Diagnostic::global(format!(
            "the constraints {} are redundant: one follows from the others, so their multipliers are not determined",
            constraints.join(", ")
        ))
        .with_hint("remove the constraint that the others imply");
    }
    let names: Vec<&str> = dependent
        .iter()
        .filter_map(|&i| coordinates.get(i).map(String::as_str))
        .collect();
    Diagnostic::global(format!(
        "the constrained system is singular: the motion of {} is determined neither by the kinetic energy nor by the constraints",
        if names.is_empty() { "the coordinates".to_string() } else { names.join(", ") }
    ))
    .with_hint("give those coordinates inertia, or constrain them")
}
