//! Rotations in expressions: `rot`, `axis`, `express`, `omega`, a
//! rotation's products (`B * rot(y, b)`, `B * v`) and components `P[k]`.

use super::{SyntaxEvaluator, Value};
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::parse::ast::{self, BinOp, Builtin, ExprKind, Span};
use crate::scene::rotation::{Rotation, TurnError};

/// The hint for a rotation where a number or a vector is needed.
pub(super) const HINT_ROTATION: &str = "a rotation is a frame's orientation: axis(F, k) is its k-th unit vector, express(v, F) a vector's components along its axes, omega(F) its angular velocity, F * v the ground components of v given along F";

/// The axis named by a bare `x`, `y` or `z` as the first argument of
/// `rot(…)` (0, 1, 2): there these letters name axes, whatever the scene
/// declares.
pub fn axis_name(args: &[ast::Expr]) -> Option<usize> {
    match args.first().map(|a| &a.kind) {
        Some(ExprKind::Name(n)) => ["x", "y", "z"].iter().position(|a| a == n),
        _ => None,
    }
}

/// An error at `span` when `v` is a rotation: "a rotation {what}".
pub(super) fn not_a_rotation(v: &Value, span: Span, what: &str) -> Result<(), Diagnostic> {
    match v {
        Value::Rotation(_) => Err(Diagnostic::error(span, format!("a rotation {what}"))
            .with_hint(HINT_ROTATION)
            .with_kind(crate::diag::ErrorKind::InvalidScene)),
        _ => Ok(()),
    }
}

/// A space vector's three components.
fn space(c: &[Expr]) -> Option<[Expr; 3]> {
    match c {
        [a, b, c] => Some([a.clone(), b.clone(), c.clone()]),
        _ => None,
    }
}

/// `x op y` where one side is a rotation: `R * S` composes, `R * v` turns
/// a space vector; nothing else is defined.
pub(super) fn rotation_binary(
    op: BinOp,
    x: Value,
    y: Value,
    a: &ast::Expr,
    b: &ast::Expr,
) -> Result<Value, Diagnostic> {
    let span = a.span.to(b.span);
    match (op, &x, &y) {
        (BinOp::Mul, Value::Rotation(r), Value::Rotation(s)) => match r.then(s) {
            Ok(t) => Ok(Value::Rotation(Box::new(t))),
            Err(_) => Err(Diagnostic::error(
                span,
                format!(
                    "this rotation would be made of more than {} turns",
                    crate::limits::MAX_ROTATION_TURNS
                ),
            )
            .with_hint("a frame built on frames copies their turns; no mechanism needs this many").with_kind(crate::diag::ErrorKind::LimitExceeded)),
        },
        (BinOp::Mul, Value::Rotation(r), Value::Vector(v)) => match space(v) {
            Some(v) => Ok(Value::Vector(r.to_ground(&v).to_vec())),
            None => Err(Diagnostic::error(
                b.span,
                format!(
                    "a rotation turns a space vector [x, y, z], and this is {}",
                    y.describe()
                ),
            )
            .with_hint("write the vector with three components: [x, y, 0]").with_kind(crate::diag::ErrorKind::TypeMismatch)),
        },
        (BinOp::Mul, Value::Vector(_), Value::Rotation(_)) => Err(Diagnostic::error(
            span,
            "a vector times a rotation is not defined; the rotation comes first",
        )
        .with_hint("F * v gives the ground components of v given along F; express(v, F) the components of a ground vector along F").with_kind(crate::diag::ErrorKind::TypeMismatch)),
        _ => {
            let (side, other) = if matches!(x, Value::Rotation(_)) {
                (a, &y)
            } else {
                (b, &x)
            };
            let what = match op {
                BinOp::Add => "added to",
                BinOp::Sub => "subtracted from",
                BinOp::Mul => "multiplied by",
                BinOp::Div => "divided by",
                BinOp::Pow => "raised to",
            };
            Err(Diagnostic::error(
                side.span,
                format!("a rotation can't be {what} {}", other.describe()),
            )
            .with_hint(
                "rotations compose with `*` (rot(z, a) * rot(x, b)) and turn space vectors (F * [x, y, z]); "
                    .to_string()
                    + HINT_ROTATION,
            ).with_kind(crate::diag::ErrorKind::TypeMismatch))
        }
    }
}

impl SyntaxEvaluator<'_> {
    /// `axis(F, k)`: the k-th unit vector of the frame F (its number of
    /// arguments is checked by the caller, as for `express`, `omega`, `rot`).
    pub(super) fn axis(&mut self, args: &[ast::Expr]) -> Result<Value, Diagnostic> {
        let r = self.rotation(&args[0], Builtin::Axis)?;
        let k = self.component_number(&args[1], 3, "a frame has the axes")?;
        Ok(Value::Vector(r.axis(k).to_vec()))
    }

    /// `express(v, F)`: the components of the space vector v along F's axes.
    pub(super) fn express(&mut self, args: &[ast::Expr]) -> Result<Value, Diagnostic> {
        let v = self.value(&args[0])?;
        let Some(v3) = space(v.components()).filter(|_| matches!(v, Value::Vector(_))) else {
            return Err(Diagnostic::error(
                args[0].span,
                format!(
                    "express(v, F) needs a space vector [x, y, z], and this is {}",
                    v.describe()
                ),
            )
            .with_hint("a frame's axes are in space; write a plane vector as [x, y, 0]")
            .with_kind(crate::diag::ErrorKind::TypeMismatch));
        };
        let r = self.rotation(&args[1], Builtin::Express)?;
        Ok(Value::Vector(r.to_frame(&v3).to_vec()))
    }

    /// `omega(F)`: the angular velocity of the frame F, in ground components.
    pub(super) fn omega(&mut self, args: &[ast::Expr]) -> Result<Value, Diagnostic> {
        let r = self.rotation(&args[0], Builtin::Omega)?;
        Ok(Value::Vector(r.omega_ground().to_vec()))
    }

    /// `rot(AXIS, ANGLE)`.
    pub(super) fn rot(&mut self, args: &[ast::Expr]) -> Result<Value, Diagnostic> {
        let axis = match axis_name(args) {
            Some(k) => Rotation::unit(k),
            None if matches!(&args[0].kind, ExprKind::Name(n) if !self.names.contains_key(n.as_str())) => {
                return Err(Diagnostic::error(
                    args[0].span,
                    "the axis of a rotation is x, y, z or a unit vector [ux, uy, uz]",
                )
                .with_hint(
                    "rot(z, phi) turns by phi about z; rot([0, 3/5, 4/5], a) about a unit vector",
                )
                .with_kind(crate::diag::ErrorKind::InvalidScene))
            }
            None => {
                let v = self.value(&args[0])?;
                match (&v, space(v.components())) {
                    (Value::Vector(_), Some(u)) => u,
                    _ => {
                        return Err(Diagnostic::error(
                            args[0].span,
                            format!(
                                "the axis of a rotation is x, y, z or a unit vector [ux, uy, uz], and this is {}",
                                v.describe()
                            ),
                        )
                        .with_hint("rot(z, phi) turns by phi about z; rot([0, 3/5, 4/5], a) about a unit vector").with_kind(crate::diag::ErrorKind::TypeMismatch))
                    }
                }
            }
        };
        let angle = self.expr(&args[1])?;
        self.expanded_only(
            &Value::Scalar(angle.clone()),
            args[1].span,
            "a rotation's angle",
        )?;
        if let Some((name, _)) = angle.highest_time_derivative().filter(|(_, k)| *k > 0) {
            return Err(Diagnostic::error(
                args[1].span,
                format!("the angle of a rotation depends on the velocity {name}'; it must be a function of the coordinates and t"),
            )
            .with_hint("a frame's orientation is a position; its angular velocity follows (omega(F))").with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        Rotation::turn(axis, angle)
            .map(|r| Value::Rotation(Box::new(r)))
            .map_err(|e| match e {
                TurnError::NotUnit(length2) if length2 == "0" => Diagnostic::error(
                    args[0].span,
                    "the axis of a rotation must be a unit vector, and this one is the zero vector: it has no direction",
                )
                .with_hint("name the axis: rot(z, a), or a unit vector such as rot([0, 3/5, 4/5], a)").with_kind(crate::diag::ErrorKind::InvalidScene),
                TurnError::NotUnit(length2) => Diagnostic::error(
                    args[0].span,
                    format!("the axis of a rotation must be a unit vector; the squared length of this one is {length2}"),
                )
                .with_hint(format!("divide it by its length: rot(AXIS/sqrt({length2}), ANGLE)")).with_kind(crate::diag::ErrorKind::InvalidScene),
                TurnError::TooManyTurns => Diagnostic::global("internal: one turn is too many").with_kind(crate::diag::ErrorKind::Internal),
                TurnError::Moving => Diagnostic::error(
                    args[0].span,
                    "the axis of a rotation must be constant, and this one moves",
                )
                .with_hint("to turn about a moving axis, compose frames: B * rot(x, a) turns about the x axis of B").with_kind(crate::diag::ErrorKind::InvalidScene),
            })
    }

    /// The rotation `e` must be (`what`: the function asking).
    fn rotation(&mut self, e: &ast::Expr, what: Builtin) -> Result<Rotation, Diagnostic> {
        let what = what.name();
        match self.value(e)? {
            Value::Rotation(r) => Ok(*r),
            v => Err(Diagnostic::error(
                e.span,
                format!("`{what}` needs a frame (a rotation), and this is {}", v.describe()),
            )
            .with_hint("define a frame with `frame B = rot(z, phi)`, or write the rotation in place: rot(z, phi)").with_kind(crate::diag::ErrorKind::TypeMismatch)),
        }
    }

    /// A component number from 1 to `n`, written in `what` (0-based result).
    fn component_number(
        &mut self,
        e: &ast::Expr,
        n: usize,
        what: &str,
    ) -> Result<usize, Diagnostic> {
        let k = self.expr(e)?;
        k.as_rational()
            .filter(|q| q.is_integer())
            .and_then(|q| q.as_i64())
            .and_then(|k| usize::try_from(k).ok())
            .filter(|k| (1..=n).contains(k))
            .map(|k| k - 1)
            .ok_or_else(|| {
                Diagnostic::error(
                    e.span,
                    format!("{what} 1 to {n}, and this is not one of them"),
                )
                .with_hint(
                    "components are counted from 1: P[1] is the first (x), P[3] the third (z)",
                )
                .with_kind(crate::diag::ErrorKind::InvalidScene)
            })
    }

    /// `P[k]`: the k-th component of a vector, counted from 1.
    pub(super) fn index(&mut self, v: &ast::Expr, k: &ast::Expr) -> Result<Value, Diagnostic> {
        let value = self.value(v)?;
        let c = match value {
            Value::Vector(c) => c,
            Value::Rotation(_) => {
                return Err(
                    Diagnostic::error(v.span, "a rotation has no components `[k]`")
                        .with_hint("axis(F, k) is the k-th unit vector of the frame F")
                        .with_kind(crate::diag::ErrorKind::TypeMismatch),
                )
            }
            Value::Scalar(_) => {
                return Err(Diagnostic::error(
                    v.span,
                    "`[k]` takes a component of a vector, and this is a number",
                )
                .with_hint("P[k] is the k-th component of a vector P, counted from 1")
                .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        let i = self.component_number(k, c.len(), "this vector has the components")?;
        Ok(Value::Scalar(c[i].clone()))
    }
}
