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
            let (row, rest) = split_linear(&velocity.dt(), qdd).map_err(|m| {
                Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
            })?;
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
        SolveError::Math(m) => {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
        }
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
        let pair = match dependent {
            [i, j] => proportional_pair(rows, i - n, j - n),
            _ => None,
        };
        let list = constraints.join(", ");
        let d = match pair {
            Some(Dependence::Redundant) => Diagnostic::global(format!(
                "the constraints {list} are redundant: one follows from the others, so their multipliers are not determined"
            ))
            .with_hint("remove the constraint that the others imply").with_kind(crate::diag::ErrorKind::Constraints),
            Some(Dependence::Contradict(gap)) => Diagnostic::global(format!(
                "the constraints {list} contradict each other: they differ by {}, which is not 0",
                crate::expr::print::unicode(&gap)
            ))
            .with_hint("no motion satisfies both; correct one of them").with_kind(crate::diag::ErrorKind::Constraints),
            Some(Dependence::AgreeOnlyIf(gap)) => Diagnostic::global(format!(
                "the constraints {list} are dependent: they agree only where {} = 0 (redundant then, contradictory otherwise), so their multipliers are not determined",
                crate::expr::print::unicode(&gap)
            ))
            .with_hint("keep one of them, or correct the one that contradicts the other").with_kind(crate::diag::ErrorKind::Constraints),
            None => Diagnostic::global(format!(
                "the constraints {list} are dependent (one's row is a combination of the others'): they are redundant or contradict each other, so their multipliers are not determined"
            ))
            .with_hint("remove the constraint that the others imply, or correct the one that contradicts them").with_kind(crate::diag::ErrorKind::Constraints),
        };
        return d.with_kind(crate::diag::ErrorKind::Constraints);
    }
    let names: Vec<String> = dependent
        .iter()
        .filter_map(|&i| coordinates.get(i).cloned())
        .collect();
    Diagnostic::global(format!(
        "the constrained system is singular: the motion of {} is determined neither by the kinetic energy nor by the constraints",
        if names.is_empty() { "the coordinates".to_string() } else { names.join(", ") }
    ))
    .with_hint("give those coordinates inertia, or constrain them")
    .with_kind(crate::diag::ErrorKind::SingularSystem { unknowns: names })
}

/// How two constraints with proportional rows relate.
enum Dependence {
    /// One is the other times a constant.
    Redundant,
    /// Their combination with the vanishing row is this nonzero constant.
    Contradict(Expr),
    /// They agree only when this constant of undecided sign is 0.
    AgreeOnlyIf(Expr),
}

/// Rows i and j proportional by a constant r (a_i = r·a_j): then
/// g_i − r·g_j (or b_i − r·b_j, for constraints on the velocities) is
/// constant on every motion, and decides whether they agree. None when
/// that cannot be told (r or the difference varies).
fn proportional_pair(rows: &ConstraintRows, i: usize, j: usize) -> Option<Dependence> {
    let (ai, aj) = (rows.matrix.get(i)?, rows.matrix.get(j)?);
    let k = aj.iter().position(|a| !a.is_zero())?;
    let r = ai[k].div(&aj[k]).ok()?;
    if r.depends_on_time() || r.vars().into_iter().any(crate::expr::atom::is_moving) {
        return None;
    }
    if !ai.iter().zip(aj).all(|(x, y)| x.equals(&r.mul(y))) {
        return None;
    }
    let gap = match (&rows.position[i], &rows.position[j]) {
        (Some(gi), Some(gj)) => gi.sub(&r.mul(gj)),
        _ => rows.velocity[i].sub(&r.mul(&rows.velocity[j])),
    };
    if gap.is_zero() {
        return Some(Dependence::Redundant);
    }
    if gap.vars().into_iter().any(crate::expr::atom::is_moving) {
        return None;
    }
    use crate::algebra::sign::{sign_exact, Sign};
    match sign_exact(&gap) {
        Some(Sign::Positive | Sign::Negative) => Some(Dependence::Contradict(gap)),
        Some(Sign::Zero) => Some(Dependence::Redundant),
        None => Some(Dependence::AgreeOnlyIf(gap)),
    }
}
