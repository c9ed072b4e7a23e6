//! `constraint` statements: holonomic g(q, t) = 0, or linear in the
//! velocities a(q, t)·q̇ + b(q, t) = 0, each with a Lagrange multiplier.

use super::{derivative_past, no_unknowns, positions_only, Resolver};
use crate::diag::Diagnostic;
use crate::expr::{atom, Expr};
use crate::parse::ast::{self, Stmt};
use crate::poly::Var;
use crate::scene::{Constraint, Reaction, Value};

/// The multiplier of the `index`-th constraint (0-based): `lambda_NAME`,
/// or `lambdaK` (1-based) without a name.
pub(super) fn multiplier_name(name: Option<&ast::Ident>, index: usize) -> String {
    match name {
        Some(n) => format!("lambda_{}", n.name),
        None => format!("lambda{}", index + 1),
    }
}

const FORMS: &str = "a constraint is holonomic, `constraint rod: x^2 + y^2 = l^2` (coordinates and t), or linear in the velocities, `constraint roll: x' = r*phi'`";

/// The hint of a constraint that involves no coordinate.
const NO_COORDINATE_HINT: &str =
    "a constraint restricts the coordinates or their velocities; a relation between parameters is an `assume` fact";

impl Resolver<'_> {
    /// The `constraint` statements, in order.
    pub(super) fn constraints(&mut self, stmts: &[&Stmt]) -> Result<Vec<Constraint>, Diagnostic> {
        let mut out: Vec<Constraint> = Vec::with_capacity(stmts.len());
        for (k, st) in stmts.iter().enumerate() {
            let Stmt::Constraint {
                name,
                equation,
                span,
            } = st
            else {
                continue;
            };
            let n = self.coordinates.len();
            if k == n {
                return Err(Diagnostic::error(
                    *span,
                    format!(
                        "more constraints than coordinates: with {n} coordinate{s} at most {n} constraint{s} can be independent",
                        s = if n == 1 { "" } else { "s" }
                    ),
                )
                .with_hint("remove the constraints the others imply, or add the coordinates they constrain").with_kind(crate::diag::ErrorKind::Constraints));
            }
            let c = self.constraint(name.as_ref(), equation, *span, k)?;
            if let Some(prev) = out.iter().position(|p| p.expression.equals(&c.expression)) {
                let line = |c: &Constraint| Diagnostic::line_col(self.src, c.span.start).0;
                return Err(Diagnostic::error(
                    equation.span,
                    format!(
                        "constraint {} repeats constraint {} (line {})",
                        c.label(k),
                        out[prev].label(prev),
                        line(&out[prev])
                    ),
                )
                .with_hint(
                    "each constraint once: a repeated constraint has no multiplier of its own",
                )
                .with_kind(crate::diag::ErrorKind::Constraints));
            }
            out.push(c);
        }
        Ok(out)
    }

    fn constraint(
        &mut self,
        name: Option<&ast::Ident>,
        equation: &ast::Equation,
        span: ast::Span,
        index: usize,
    ) -> Result<Constraint, Diagnostic> {
        let side = |v: Value, e: &ast::Expr| match v {
            Value::Scalar(x) => Ok(x),
            other => Err(Diagnostic::error(
                e.span,
                format!(
                    "a constraint is one equation between numbers, and this is {}",
                    other.describe()
                ),
            )
            .with_hint("write one `constraint` per component: `constraint cx: P[1] = 0`")
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
        };
        let lhs = side(self.ev.value(&equation.lhs)?, &equation.lhs)?;
        let rhs = side(self.ev.value(&equation.rhs)?, &equation.rhs)?;
        let g = lhs.sub(&rhs);
        let label = match name {
            Some(n) => format!("constraint `{}`", n.name),
            None => "this constraint".to_string(),
        };
        let mut c = self.constraint_of(
            g,
            &multiplier_name(name, index),
            &label,
            equation.span,
            span,
        )?;
        c.name = name.map(|n| n.name.clone());
        Ok(c)
    }

    /// The constraint g = 0 (holonomic, or linear in the velocities),
    /// checked, with its multiplier `multiplier`; `label` names it in
    /// messages and `equation` is where its expression is written.
    pub(super) fn constraint_of(
        &mut self,
        g: Expr,
        multiplier: &str,
        label: &str,
        equation: ast::Span,
        span: ast::Span,
    ) -> Result<Constraint, Diagnostic> {
        no_unknowns(std::slice::from_ref(&g), equation, label)?;
        if let Some((d, _)) = derivative_past(std::slice::from_ref(&g), 1) {
            return Err(Diagnostic::error(
                equation,
                format!("{label} depends on the acceleration {d}"),
            )
            .with_hint(FORMS)
            .with_kind(crate::diag::ErrorKind::Constraints));
        }
        let q: Vec<Var> = self.coordinate_vars.clone();
        let qd: Vec<Var> = self
            .coordinates
            .iter()
            .map(|c| atom::coord(&c.name, 1))
            .collect();
        let holonomic = !qd.iter().any(|&v| g.depends_on(v));
        if !q.iter().chain(&qd).any(|&v| g.depends_on(v)) {
            let what = if g.is_zero() {
                "holds for every motion (both sides are equal)".to_string()
            } else {
                "involves no coordinate".to_string()
            };
            return Err(Diagnostic::error(equation, format!("{label} {what}"))
                .with_hint(NO_COORDINATE_HINT)
                .with_kind(crate::diag::ErrorKind::Constraints));
        }
        let velocity_level = if holonomic { g.dt() } else { g.clone() };
        let (coefficients, rest) = crate::algebra::linear::split_linear(&velocity_level, &qd)
            .map_err(|m| {
                Diagnostic::error(equation, m.message).with_kind(crate::diag::ErrorKind::Undefined)
            })?;
        let moving = |e: &Expr| qd.iter().any(|&v| e.depends_on(v));
        if coefficients.iter().any(moving) || moving(&rest) {
            return Err(Diagnostic::error(
                equation,
                format!("{label} is not linear in the velocities"),
            )
            .with_hint(FORMS)
            .with_kind(crate::diag::ErrorKind::Constraints));
        }
        debug_assert!(coefficients.iter().any(|a| !a.is_zero()));
        // a coefficient can be zero in a form the canonical one does not
        // show (sin a − 2·sin(a/2)·cos(a/2)): all of them so, and the
        // constraint involves no coordinate after all
        if coefficients
            .iter()
            .all(|a| a.is_zero() || crate::expr::hidden_zero::may_be_zero(a.num()))
        {
            let zeros: Vec<String> = coefficients
                .iter()
                .filter(|a| !a.is_zero())
                .map(crate::expr::print::unicode)
                .collect();
            return Err(Diagnostic::error(
                equation,
                format!(
                    "{label} involves no coordinate: its coefficient {} is 0",
                    zeros.join(", ")
                ),
            )
            .with_hint(NO_COORDINATE_HINT)
            .with_kind(crate::diag::ErrorKind::Constraints));
        }
        Ok(Constraint {
            name: Some(multiplier.to_string()),
            multiplier: multiplier.to_string(),
            holonomic,
            expression: g,
            coefficients,
            rest,
            span,
        })
    }

    /// The `reaction NAME at P` statements, in order.
    pub(super) fn reactions(
        &mut self,
        stmts: &[&Stmt],
        constraints: &[Constraint],
    ) -> Result<Vec<Reaction>, Diagnostic> {
        let mut out = Vec::with_capacity(stmts.len());
        for st in stmts {
            let Stmt::Reaction {
                constraint,
                point,
                span,
            } = st
            else {
                continue;
            };
            let Some(j) = constraints
                .iter()
                .position(|c| c.name.as_deref() == Some(constraint.name.as_str()))
            else {
                let names: Vec<&str> = constraints
                    .iter()
                    .filter_map(|c| c.name.as_deref())
                    .collect();
                return Err(Diagnostic::error(
                    constraint.span,
                    format!("`{}` is not the name of a constraint", constraint.name),
                )
                .with_hint(if names.is_empty() {
                    "name the constraint: `constraint rod: x^2 + y^2 = l^2`, then `reaction rod at [x, y]`".to_string()
                } else {
                    format!("the scene's named constraints: {}", names.join(", "))
                }).with_kind(crate::diag::ErrorKind::UnknownName { name: constraint.name.to_string() }));
            };
            let value = self.ev.value(point)?;
            let components =
                match value {
                    Value::Scalar(e) => vec![e],
                    Value::Vector(v) => v,
                    Value::Rotation(_) => return Err(Diagnostic::error(
                        point.span,
                        "a reaction's point is a position, and this is a rotation",
                    )
                    .with_hint(
                        "a point is a position vector, `[x, y]`, or a displacement along a line",
                    )
                    .with_kind(crate::diag::ErrorKind::TypeMismatch)),
                };
            no_unknowns(&components, point.span, "a reaction's point")?;
            positions_only(&components, point.span, "a reaction's point")?;
            if !components.iter().any(|e| self.moves(e)) {
                return Err(Diagnostic::error(point.span, "this point does not move with any coordinate, so no force there does virtual work")
                    .with_hint("name the point the constraint holds: its position in the coordinates").with_kind(crate::diag::ErrorKind::InvalidScene));
            }
            out.push(Reaction {
                constraint: j,
                point: components,
                written: self.src[point.span.start..point.span.end].to_string(),
                span: *span,
            });
        }
        Ok(out)
    }
}
