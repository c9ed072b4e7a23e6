//! `joint`, `drive` and `friction` statements: each joint and drive
//! becomes constraints whose multipliers are its reaction, and the
//! records of [`crate::scene::mechanism`] keep the rest.

use super::{no_unknowns, positions_only, Resolver};
use crate::diag::Diagnostic;
use crate::expr::{atom, Expr};
use crate::parse::ast::{self, JointKind, JointStmt, Stmt};
use crate::poly::Var;
use crate::scene::mechanism::{friction_name, Drive, Joint, JointFriction};
use crate::scene::{Constraint, Turning, Value};

const POINT_HINT: &str = "a joint's point is a position in the plane, `[x, y]`, written through its own body's coordinates";

impl Resolver<'_> {
    /// The joints, then the drives, then their friction; their
    /// constraints join `constraints` (after the `constraint` statements).
    pub(super) fn mechanism(
        &mut self,
        stmts: &[Stmt],
        constraints: &mut Vec<Constraint>,
    ) -> Result<(Vec<super::super::mechanism::Joint>, Vec<Drive>), Diagnostic> {
        let mut joints = Vec::new();
        for st in stmts {
            if let Stmt::Joint(j) = st {
                if let Some(prev) = joints.iter().find(|p: &&Joint| p.name == j.name.name) {
                    let line = Diagnostic::line_col(self.src, prev.span.start).0;
                    return Err(Diagnostic::error(
                        j.name.span,
                        format!(
                            "the joint `{}` is already defined (line {line})",
                            j.name.name
                        ),
                    )
                    .with_hint("give each joint its own name")
                    .with_kind(crate::diag::ErrorKind::DuplicateName {
                        name: j.name.name.to_string(),
                    }));
                }
                let joint = self.joint(j, constraints)?;
                joints.push(joint);
            }
        }
        let mut drives: Vec<Drive> = Vec::new();
        for st in stmts {
            if let Stmt::Drive {
                name,
                coordinate,
                value,
                span,
            } = st
            {
                let d = self.drive(name, coordinate, value, *span, constraints)?;
                if let Some(prev) = drives.iter().find(|p| p.coordinate == d.coordinate) {
                    let line = Diagnostic::line_col(self.src, prev.span.start).0;
                    return Err(Diagnostic::error(
                        coordinate.span,
                        format!(
                            "`{}` is already driven by `{}` (line {line})",
                            coordinate.name, prev.name
                        ),
                    )
                    .with_hint("a coordinate has one law of motion: keep one drive")
                    .with_kind(crate::diag::ErrorKind::DuplicateName {
                        name: coordinate.name.to_string(),
                    }));
                }
                drives.push(d);
            }
        }
        for st in stmts {
            if let Stmt::Friction {
                joint,
                coefficient,
                span,
            } = st
            {
                self.friction(joint, coefficient, *span, &mut joints)?;
            }
        }
        Ok((joints, drives))
    }

    /// One joint: its bodies, points, direction and constraints.
    fn joint(
        &mut self,
        j: &JointStmt,
        constraints: &mut Vec<Constraint>,
    ) -> Result<Joint, Diagnostic> {
        let bodies = [
            self.joint_body(&j.first.body)?,
            self.joint_body(&j.second.body)?,
        ];
        if bodies[0] == bodies[1] {
            let what = match bodies[0] {
                None => "the ground to itself".to_string(),
                Some(b) => format!("`{}` to itself", self.bodies[b].info.name),
            };
            return Err(Diagnostic::error(
                j.second.body.span,
                format!("the joint `{}` joins {what}", j.name.name),
            )
            .with_hint("a joint joins two different bodies (or a body and `ground`)")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let p = self.joint_point(&j.first, bodies[0])?;
        let q = self.joint_point(&j.second, bodies[1])?;
        let along = match &j.along {
            Some(u) => Some(unit(
                self.slider_direction(u, bodies[0], &j.first.body)?,
                j.span,
            )?),
            None => None,
        };
        let names = super::super::mechanism::reaction_names(
            &j.name.name,
            j.kind,
            j.kind == JointKind::Slider && self.turns(bodies[0]) && self.turns(bodies[1]),
        );
        let mut gs: Vec<Expr> = Vec::new();
        let mut locked_angle = None;
        match (&along, j.kind) {
            (None, _) => {
                gs.push(q[0].sub(&p[0]));
                gs.push(q[1].sub(&p[1]));
            }
            (Some(u), _) => {
                // n̂·(Q − P) with n̂ = Û turned +90°: its multiplier is the
                // force on B along n̂
                let gap = [q[0].sub(&p[0]), q[1].sub(&p[1])];
                gs.push(u[0].mul(&gap[1]).sub(&u[1].mul(&gap[0])));
                if names.len() == 2 {
                    let angle = self.angle(bodies[1]).sub(&self.angle(bodies[0]));
                    gs.push(angle.dt());
                    locked_angle = Some(angle);
                }
            }
        }
        let mut indices = Vec::with_capacity(gs.len());
        for (g, name) in gs.into_iter().zip(&names) {
            self.check_room(constraints.len(), j.span)?;
            let label = format!("joint `{}` ({name})", j.name.name);
            let c = self.constraint_of(g, name, &label, j.span, j.span)?;
            indices.push(constraints.len());
            constraints.push(c);
        }
        Ok(Joint {
            name: j.name.name.clone(),
            kind: j.kind,
            bodies,
            points: [p, q],
            along,
            constraints: indices,
            locked_angle,
            friction: None,
            span: j.span,
        })
    }

    /// An error once the constraints fill every coordinate.
    fn check_room(&self, count: usize, span: ast::Span) -> Result<(), Diagnostic> {
        let n = self.coordinates.len();
        if count < n {
            return Ok(());
        }
        Err(Diagnostic::error(
            span,
            format!("more constraints than coordinates: the joints, drives and constraints hold {} conditions on {n} coordinate{}", count + 1, if n == 1 { "" } else { "s" }),
        )
        .with_hint("each body in the plane has its own x, y and angle (a particle x, y): declare them all, or remove a joint or drive the others imply").with_kind(crate::diag::ErrorKind::Constraints))
    }

    /// The body a joint names: an index into the bodies, `None` for `ground`.
    fn joint_body(&self, id: &ast::Ident) -> Result<Option<usize>, Diagnostic> {
        if let Some(i) = self.bodies.iter().position(|b| b.info.name == id.name) {
            if self.bodies[i].mass.is_none() {
                return Err(Diagnostic::error(
                    id.span,
                    format!("`{}` has no mass, and a joint's reaction on it carries its weight and inertia", id.name),
                )
                .with_hint(format!("give `{}` its mass (`mass m`) in its `body` statement", id.name)).with_kind(crate::diag::ErrorKind::InvalidScene));
            }
            return Ok(Some(i));
        }
        if id.name == "ground" {
            return Ok(None);
        }
        let names: Vec<&str> = self.bodies.iter().map(|b| b.info.name.as_str()).collect();
        Err(Diagnostic::error(id.span, format!("`{}` is not a body or a particle", id.name)).with_hint(
            if names.is_empty() {
                "declare the bodies first: `body rod: mass m, inertia J, angle th, at [x, y]`; the fixed frame is `ground`".to_string()
            } else {
                format!("a joint joins two of {} or `ground`", names.join(", "))
            },
        ).with_kind(crate::diag::ErrorKind::UnknownName { name: id.name.to_string() }))
    }

    /// A joint's point, checked to be a plane position on its own body.
    fn joint_point(
        &mut self,
        end: &ast::JointEnd,
        body: Option<usize>,
    ) -> Result<Vec<Expr>, Diagnostic> {
        let span = end.point.span;
        let p = match self.ev.value(&end.point)? {
            Value::Vector(v) if v.len() == 2 => v,
            Value::Vector(v) => {
                return Err(Diagnostic::error(
                    span,
                    format!(
                        "a joint's point has 2 components (joints are planar), and this has {}",
                        v.len()
                    ),
                )
                .with_hint(POINT_HINT)
                .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
            other => {
                return Err(Diagnostic::error(
                    span,
                    format!(
                        "a joint's point is a position, and this is {}",
                        other.describe()
                    ),
                )
                .with_hint(POINT_HINT)
                .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        no_unknowns(&p, span, "a joint's point")?;
        positions_only(&p, span, "a joint's point")?;
        self.on_body(&p, body, span, &end.body.name, "point")?;
        Ok(p)
    }

    /// A slider's direction: a nonzero plane vector that turns with the
    /// first body at most.
    fn slider_direction(
        &mut self,
        u: &ast::Expr,
        body: Option<usize>,
        who: &ast::Ident,
    ) -> Result<Vec<Expr>, Diagnostic> {
        let v = match self.ev.value(u)? {
            Value::Vector(v) if v.len() == 2 => v,
            other => {
                return Err(Diagnostic::error(u.span, format!("a slider's direction is a plane vector, and this is {}", other.describe()))
                    .with_hint("write it in ground components: `along [1, 0]`, or `along [cos(th), sin(th)]` for a guide that turns with the first body").with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        no_unknowns(&v, u.span, "a slider's direction")?;
        positions_only(&v, u.span, "a slider's direction")?;
        if v.iter().all(Expr::is_zero) {
            return Err(
                Diagnostic::error(u.span, "a slider's direction is the zero vector")
                    .with_hint("give the guide's direction: `along [1, 0]`")
                    .with_kind(crate::diag::ErrorKind::InvalidScene),
            );
        }
        self.on_body(&v, body, u.span, &who.name, "direction")?;
        Ok(v)
    }

    /// An error when `es` move with a coordinate that is not `body`'s.
    fn on_body(
        &self,
        es: &[Expr],
        body: Option<usize>,
        span: ast::Span,
        who: &str,
        what: &str,
    ) -> Result<(), Diagnostic> {
        let own = self.body_coordinates(body);
        let foreign = self
            .coordinate_vars
            .iter()
            .zip(self.coordinates)
            .find(|(v, _)| !own.contains(v) && es.iter().any(|e| e.depends_on(**v)));
        let Some((_, c)) = foreign else { return Ok(()) };
        let owner = match body {
            None => "the ground, which does not move".to_string(),
            Some(_) => {
                let names: Vec<&str> = self
                    .coordinate_vars
                    .iter()
                    .zip(self.coordinates)
                    .filter(|(v, _)| own.contains(v))
                    .map(|(_, c)| c.name.as_str())
                    .collect();
                format!("`{who}`, which moves with {}", names.join(", "))
            }
        };
        Err(Diagnostic::error(span, format!("this {what} moves with `{}`, a coordinate that is not of {owner}", c.name))
            .with_hint("write each joint's point through its own body: P through the first body's position and angle, Q through the second's").with_kind(crate::diag::ErrorKind::InvalidScene))
    }

    /// The coordinates a body's centre and angle move with (none for the ground).
    fn body_coordinates(&self, body: Option<usize>) -> Vec<Var> {
        let Some(b) = body else { return Vec::new() };
        let mp = &self.bodies[b].info.mass_properties;
        let mut es: Vec<&Expr> = mp.centre.iter().collect();
        if let Some(Turning::Plane { angle, .. }) = &mp.turning {
            es.push(angle);
        }
        self.coordinate_vars
            .iter()
            .copied()
            .filter(|&v| es.iter().any(|e| e.depends_on(v)))
            .collect()
    }

    /// Whether a body turns in the plane (a rigid body with an angle).
    fn turns(&self, body: Option<usize>) -> bool {
        body.is_some_and(|b| {
            matches!(
                self.bodies[b].info.mass_properties.turning,
                Some(Turning::Plane { .. })
            )
        })
    }

    /// A body's angle in the plane; 0 for the ground and a particle.
    fn angle(&self, body: Option<usize>) -> Expr {
        match body.map(|b| &self.bodies[b].info.mass_properties.turning) {
            Some(Some(Turning::Plane { angle, .. })) => angle.clone(),
            _ => Expr::zero(),
        }
    }

    /// `drive NAME: q = f(t)`.
    fn drive(
        &mut self,
        name: &ast::Ident,
        coordinate: &ast::Ident,
        value: &ast::Expr,
        span: ast::Span,
        constraints: &mut Vec<Constraint>,
    ) -> Result<Drive, Diagnostic> {
        let Some(k) = self
            .coordinates
            .iter()
            .position(|c| c.name == coordinate.name)
        else {
            return Err(Diagnostic::error(coordinate.span, format!("`{}` is not a coordinate", coordinate.name))
                .with_hint("a drive prescribes one of the scene's `coordinates` as a function of time: `drive M: phi = omega*t`").with_kind(crate::diag::ErrorKind::InvalidScene));
        };
        let f = match self.ev.value(value)? {
            Value::Scalar(e) => e,
            other => {
                return Err(Diagnostic::error(
                    value.span,
                    format!(
                        "a drive's law is a number, and this is {}",
                        other.describe()
                    ),
                )
                .with_hint("`drive M: phi = omega*t`")
                .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        no_unknowns(std::slice::from_ref(&f), value.span, "a drive's law")?;
        let moving = self
            .coordinates
            .iter()
            .find(|c| (0..=2).any(|k| f.depends_on(atom::coord(&c.name, k))));
        if let Some(c) = moving {
            return Err(Diagnostic::error(
                value.span,
                format!(
                    "a drive's law depends on time only, and this moves with `{}`",
                    c.name
                ),
            )
            .with_hint("a relation between coordinates is a `constraint`; a drive is q = f(t)")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let n = self.coordinates.len();
        if constraints.len() >= n {
            return Err(Diagnostic::error(
                span,
                format!(
                    "the drive `{}` prescribes `{}`, which the joints and drives before it already determine ({} conditions on {n} coordinates)",
                    name.name,
                    coordinate.name,
                    constraints.len() + 1
                ),
            )
            .with_hint("a driven mechanism has as many joint and drive conditions as coordinates: drive only the input, or give the bodies their own coordinates").with_kind(crate::diag::ErrorKind::Constraints));
        }
        let g = Expr::coord(&coordinate.name, 0).sub(&f);
        let label = format!("drive `{}`", name.name);
        let c = self.constraint_of(g, &name.name, &label, span, span)?;
        constraints.push(c);
        Ok(Drive {
            name: name.name.clone(),
            coordinate: k,
            value: f,
            constraint: constraints.len() - 1,
            span,
        })
    }

    /// `friction NAME: c` on the joint `NAME`.
    fn friction(
        &mut self,
        joint: &ast::Ident,
        coefficient: &ast::Expr,
        span: ast::Span,
        joints: &mut [Joint],
    ) -> Result<(), Diagnostic> {
        let Some(j) = joints.iter().position(|j| j.name == joint.name) else {
            let names: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
            return Err(Diagnostic::error(
                joint.span,
                format!("there is no joint `{}`", joint.name),
            )
            .with_hint(if names.is_empty() {
                "friction acts in a joint: declare it first, `joint B: pin rod at P, block at Q`"
                    .to_string()
            } else {
                format!("the scene's joints: {}", names.join(", "))
            })
            .with_kind(crate::diag::ErrorKind::UnknownName {
                name: joint.name.to_string(),
            }));
        };
        if let Some(prev) = &joints[j].friction {
            let line = Diagnostic::line_col(self.src, prev.span.start).0;
            return Err(Diagnostic::error(
                joint.span,
                format!(
                    "the joint `{}` already has friction (line {line})",
                    joint.name
                ),
            )
            .with_hint("one `friction` statement per joint")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let c = match self.ev.value(coefficient)? {
            Value::Scalar(e) => e,
            other => {
                return Err(Diagnostic::error(
                    coefficient.span,
                    format!(
                        "a friction coefficient is a number, and this is {}",
                        other.describe()
                    ),
                )
                .with_hint("`friction G: mu` (a slider), `friction A: mu0*r0` (a pin)")
                .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        no_unknowns(
            std::slice::from_ref(&c),
            coefficient.span,
            "a friction coefficient",
        )?;
        if self.moves(&c) || c.depends_on_time() || c.vars().into_iter().any(atom::is_moving) {
            return Err(Diagnostic::error(
                coefficient.span,
                "a friction coefficient is a constant",
            )
            .with_hint("write it with parameters and numbers: `friction G: mu`")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let jt = &joints[j];
        let relative = match &jt.along {
            Some(u) => {
                let gap = [
                    jt.points[1][0].sub(&jt.points[0][0]),
                    jt.points[1][1].sub(&jt.points[0][1]),
                ];
                u[0].mul(&gap[0]).add(&u[1].mul(&gap[1]))
            }
            None => {
                if !self.turns(jt.bodies[0]) && !self.turns(jt.bodies[1]) {
                    return Err(Diagnostic::error(joint.span, format!("the pin `{}` joins two things that do not turn, so it has no friction couple", joint.name))
                        .with_hint("a pin's friction opposes the relative rotation of two bodies with angles").with_kind(crate::diag::ErrorKind::InvalidScene));
                }
                self.angle(jt.bodies[1]).sub(&self.angle(jt.bodies[0]))
            }
        };
        let direction = self
            .coordinate_vars
            .iter()
            .map(|&v| relative.diff(v))
            .collect();
        joints[j].friction = Some(JointFriction {
            coefficient: c,
            unknown: friction_name(&joint.name),
            relative_velocity: relative.dt(),
            direction,
            span,
        });
        Ok(())
    }
}

/// Û = U/|U|, exactly (U itself for a unit direction such as
/// [cos θ, sin θ]).
fn unit(u: Vec<Expr>, span: ast::Span) -> Result<Vec<Expr>, Diagnostic> {
    let uu = u[0].mul(&u[0]).add(&u[1].mul(&u[1]));
    if uu.is_one() {
        return Ok(u);
    }
    let math = |m: crate::expr::MathError| {
        Diagnostic::error(span, m.message).with_kind(crate::diag::ErrorKind::Undefined)
    };
    let len = crate::expr::func::sqrt(&uu).map_err(math)?;
    u.iter().map(|c| c.div(&len).map_err(math)).collect()
}
