//! `frame`, `body`, `particle` and `gravity`: rigid bodies and particles
//! become kinetic energies (`E_top`), gravity a potential on each (`V_top`),
//! definitions with a role like the ones a scene writes by hand.

use super::about::Owner;
use super::{positions_only, Declarations, Definition, Resolver, Value};
use crate::algebra::sign::Sign;
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::parse::ast::{
    self, BodyKind, BodyProperty, BodyStmt, ExprKind, PropertyKey, Role, Span, Stmt,
};
use crate::scene::rotation::Rotation;
use crate::scene::{MassProperties, Turning};

/// The name of the kinetic energy of body `name`.
pub(crate) fn kinetic_name(name: &str) -> String {
    format!("E_{name}")
}

/// The name of gravity's potential on body `name`.
pub(crate) fn gravity_name(name: &str) -> String {
    format!("V_{name}")
}

/// A body or particle, resolved.
#[derive(Clone, Debug)]
pub(super) struct ResolvedBody {
    pub(super) info: crate::scene::Body,
    /// `None` for a body without a mass, its centre fixed.
    pub(super) mass: Option<Expr>,
    /// The centre of mass: 2 or 3 components.
    position: Vec<Expr>,
}

/// An error unless a `frame` statement's value `v` (written `e`) is a rotation.
pub(super) fn frame_value(e: &ast::Expr, v: &Value) -> Result<(), Diagnostic> {
    match v {
        Value::Rotation(_) => Ok(()),
        other => Err(Diagnostic::error(
            e.span,
            format!("a frame is a rotation, and this is {}", other.describe()),
        )
        .with_hint("write it as rot(AXIS, ANGLE) or a product of them: `frame B = rot(z, phi) * rot(x, theta)`").with_kind(crate::diag::ErrorKind::TypeMismatch)),
    }
}

impl Declarations<'_> {
    /// The names the bodies give their energies (`E_top`, `V_top`) must be
    /// free.
    pub(super) fn reserve_body_energies(&self, stmts: &[Stmt]) -> Result<(), Diagnostic> {
        for st in stmts {
            let Stmt::Body(b) = st else { continue };
            for generated in [kinetic_name(&b.name.name), gravity_name(&b.name.name)] {
                if let Some((_, at)) = self.names.get(&generated) {
                    let (line, _) = Diagnostic::line_col(self.src, at.start);
                    return Err(Diagnostic::error(
                        b.name.span,
                        format!(
                            "`{} {}` names its energies `{}` and `{}`, and `{generated}` is already declared (line {line})",
                            b.kind.keyword(),
                            b.name.name,
                            kinetic_name(&b.name.name),
                            gravity_name(&b.name.name)
                        ),
                    )
                    .with_hint("rename the body or the other name")
                    .with_kind(crate::diag::ErrorKind::DuplicateName { name: generated }));
                }
            }
        }
        Ok(())
    }
}

/// The properties of one body statement, each at most once.
struct Properties<'a> {
    given: [Option<&'a BodyProperty>; 5],
}

impl<'a> Properties<'a> {
    fn collect(b: &'a BodyStmt) -> Result<Properties<'a>, Diagnostic> {
        let mut given: [Option<&BodyProperty>; 5] = [None; 5];
        for p in &b.properties {
            let slot = &mut given[p.key as usize];
            if slot.is_some() {
                return Err(Diagnostic::error(
                    p.key_span,
                    format!("`{}` is given twice for `{}`", p.key.keyword(), b.name.name),
                )
                .with_hint("give each property once")
                .with_kind(crate::diag::ErrorKind::DuplicateName {
                    name: p.key.keyword().to_string(),
                }));
            }
            *slot = Some(p);
        }
        let props = Properties { given };
        let example = match b.kind {
            BodyKind::Rigid => "`body top: mass m, inertia [A, A, C], frame B, at P` in space, `body disk: mass m, inertia J, angle theta, at [x, y]` in the plane",
            BodyKind::Particle => "`particle p: mass m, at P`",
        };
        if b.kind == BodyKind::Particle {
            for key in [PropertyKey::Inertia, PropertyKey::Frame, PropertyKey::Angle] {
                if let Some(p) = props.get(key) {
                    return Err(Diagnostic::error(
                        p.key_span,
                        format!("a particle has no `{}`", key.keyword()),
                    )
                    .with_hint("a particle is a point mass; a body with an orientation and an inertia is a `body`").with_kind(crate::diag::ErrorKind::InvalidScene));
                }
            }
        }
        // a rigid body may leave out its mass (its centre must then be
        // fixed, checked when resolved), not both mass and inertia
        let rigid = b.kind == BodyKind::Rigid;
        let no_inertia = rigid && props.get(PropertyKey::Inertia).is_none();
        let mut missing: Vec<&str> = [PropertyKey::Mass, PropertyKey::At]
            .into_iter()
            .filter(|&k| props.get(k).is_none())
            .filter(|&k| k != PropertyKey::Mass || !rigid || no_inertia)
            .map(PropertyKey::keyword)
            .collect();
        if no_inertia {
            let after_mass = usize::from(props.get(PropertyKey::Mass).is_none());
            missing.insert(after_mass, "inertia");
        }
        if !missing.is_empty() {
            return Err(Diagnostic::error(
                b.name.span,
                format!("`{}` has no {}", b.name.name, missing.join(", no ")),
            )
            .with_hint(format!("a {} is written {example}", b.kind.keyword()))
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        if b.kind == BodyKind::Rigid {
            match (props.get(PropertyKey::Frame), props.get(PropertyKey::Angle)) {
                (Some(_), Some(a)) => {
                    return Err(Diagnostic::error(
                        a.key_span,
                        "a body has a `frame` (in space) or an `angle` (in the plane), not both",
                    )
                    .with_hint(format!("write {example}"))
                    .with_kind(crate::diag::ErrorKind::InvalidScene))
                }
                (None, None) => {
                    return Err(Diagnostic::error(
                        b.name.span,
                        format!("`{}` has no orientation", b.name.name),
                    )
                    .with_hint(format!(
                        "give its `frame F` in space or its `angle theta` in the plane: {example}"
                    ))
                    .with_kind(crate::diag::ErrorKind::InvalidScene))
                }
                _ => {}
            }
        }
        Ok(props)
    }

    fn get(&self, key: PropertyKey) -> Option<&'a BodyProperty> {
        self.given[key as usize]
    }
}

impl Resolver<'_> {
    /// A `body` or `particle` statement: its kinetic energy `E_name`.
    pub(super) fn body(&mut self, b: &BodyStmt) -> Result<(), Diagnostic> {
        let props = Properties::collect(b)?;
        let Some(at) = props.get(PropertyKey::At) else {
            return Err(Diagnostic::global("internal: a body without a position")
                .with_kind(crate::diag::ErrorKind::Internal));
        };
        let m = match props.get(PropertyKey::Mass) {
            Some(mass) => Some(self.mass(mass)?),
            None => None,
        };
        let position = self.position(at)?;
        if m.is_none() {
            fixed_centre(b, at, &position)?;
        }
        let owner = Owner {
            name: &b.name.name,
            mass: m.as_ref(),
            centre: &position,
        };
        let mut energy = match &m {
            Some(m) => {
                let mut speed2 = Expr::zero();
                for c in &position {
                    let v = self.ev.time_derivative(c);
                    speed2 = speed2.add(&v.mul(&v));
                }
                m.mul(&speed2)
            }
            None => Expr::zero(),
        };
        let mut turning = None;
        if let Some(inertia) = props.get(PropertyKey::Inertia) {
            if let Some(frame) = props.get(PropertyKey::Frame) {
                let r = self.frame_of(frame)?;
                if position.len() != 3 {
                    return Err(Diagnostic::error(
                        at.value.span,
                        "a body with a frame moves in space: its position needs three components",
                    )
                    .with_hint("write it as [x, y, z]; a body in the plane has an `angle` instead of a frame").with_kind(crate::diag::ErrorKind::TypeMismatch));
                }
                let mut i = self.inertia_tensor(inertia, &b.name.name)?;
                if let Some(about) = &inertia.about {
                    i = self.space_about(inertia, about, i, &r, &owner)?;
                }
                let w = r.omega_frame();
                energy = energy.add(&quadratic_form(&i, &w));
                turning = Some(Turning::Space {
                    frame: Box::new(r),
                    inertia: i,
                });
            } else if let Some(angle) = props.get(PropertyKey::Angle) {
                if position.len() != 2 {
                    return Err(Diagnostic::error(
                        at.value.span,
                        format!(
                            "a body with an angle moves in the plane: its position needs two components, this one has {}",
                            position.len()
                        ),
                    )
                    .with_hint("write it as [x, y]; a body in space has a `frame` instead of an angle").with_kind(crate::diag::ErrorKind::TypeMismatch));
                }
                let mut j = self.planar_inertia(inertia, &b.name.name)?;
                let theta = self.ev.expr(&angle.value)?;
                positions_only(
                    std::slice::from_ref(&theta),
                    angle.value.span,
                    "a body's angle",
                )?;
                if let Some(about) = &inertia.about {
                    j = self.plane_about(inertia, about, j, &theta, &owner)?;
                }
                let w = self.ev.time_derivative(&theta);
                energy = energy.add(&j.mul(&w).mul(&w));
                turning = Some(Turning::Plane {
                    angle: theta,
                    inertia: j,
                });
            }
        }
        let half = Expr::rational(crate::num::Q::new(1, 2).unwrap_or_else(crate::num::Q::one));
        self.body_energies.push(Definition {
            name: kinetic_name(&b.name.name),
            value: Value::Scalar(energy.mul(&half)),
            span: b.name.span,
            role: Some(Role::Kinetic),
        });
        self.bodies.push(ResolvedBody {
            info: crate::scene::Body {
                name: b.name.name.clone(),
                kind: b.kind,
                span: b.span,
                kinetic: kinetic_name(&b.name.name),
                gravity: None,
                mass_properties: MassProperties {
                    mass: m.clone().unwrap_or_else(Expr::zero),
                    centre: position.clone(),
                    turning,
                    gravity: None,
                },
            },
            mass: m,
            position,
        });
        Ok(())
    }

    /// A body's mass: a positive constant.
    fn mass(&mut self, p: &BodyProperty) -> Result<Expr, Diagnostic> {
        let m = self.ev.expr(&p.value)?;
        if m.is_time_dependent() {
            return Err(Diagnostic::error(
                p.value.span,
                "a mass must be constant, and this one changes with time",
            )
            .with_hint("a body's mass is a parameter or a number")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let sign = crate::algebra::assume::sign_under(&self.assumed, &m);
        if sign != Some(Sign::Positive) {
            let why = match sign {
                Some(Sign::Zero) => "this one is 0".to_string(),
                Some(Sign::Negative) => "this one is negative".to_string(),
                _ => format!("qdot can't tell that {} is", m.to_input()),
            };
            return Err(
                Diagnostic::error(p.value.span, format!("a mass must be positive; {why}"))
                    .with_hint(
                    "write the mass as a parameter (parameters are positive) or a positive number",
                ).with_kind(crate::diag::ErrorKind::Unphysical),
            );
        }
        Ok(m)
    }

    /// A body's centre of mass: a plane or space vector of the
    /// coordinates and t.
    fn position(&mut self, p: &BodyProperty) -> Result<Vec<Expr>, Diagnostic> {
        match self.ev.value(&p.value)? {
            Value::Vector(c) => {
                positions_only(&c, p.value.span, "a body's position")?;
                Ok(c)
            }
            v => Err(Diagnostic::error(
                p.value.span,
                format!("a position is a vector, and this is {}", v.describe()),
            )
            .with_hint("write the centre of mass as [x, y] in the plane or [x, y, z] in space")
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
        }
    }

    /// A body's `frame`: a rotation.
    fn frame_of(&mut self, p: &BodyProperty) -> Result<Rotation, Diagnostic> {
        match self.ev.value(&p.value)? {
            Value::Rotation(r) => Ok(*r),
            v => Err(Diagnostic::error(
                p.value.span,
                format!("a body's frame is a rotation, and this is {}", v.describe()),
            )
            .with_hint(
                "name a frame (`frame B = rot(z, phi)`) or write a rotation: frame rot(z, phi)",
            )
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
        }
    }

    /// The inertia of a body in the plane: one constant, not negative.
    fn planar_inertia(&mut self, p: &BodyProperty, body: &str) -> Result<Expr, Diagnostic> {
        let v = self.ev.value(&p.value)?;
        let Value::Scalar(j) = v else {
            return Err(Diagnostic::error(
                p.value.span,
                format!(
                    "a body in the plane has one moment of inertia (about its centre of mass), and this is {}",
                    v.describe()
                ),
            )
            .with_hint("write `inertia J`; principal moments [I1, I2, I3] belong to a body in space, with a `frame`").with_kind(crate::diag::ErrorKind::TypeMismatch));
        };
        self.moment(&j, p.value.span)?;
        if crate::algebra::assume::sign_under(&self.assumed, &j).is_none() {
            self.warnings.push(
                Diagnostic::warning(
                    p.value.span,
                    format!(
                        "qdot can't tell that the inertia of `{body}` is one a rigid body can have: {} ≥ 0 is not decided",
                        j.to_input()
                    ),
                )
                .with_hint(format!(
                    "a moment of inertia is ≥ 0; state it with `assume {} > 0` or give a number",
                    j.to_input()
                )),
            );
        }
        Ok(j)
    }

    /// A moment of inertia: constant and not negative.
    fn moment(&self, j: &Expr, span: Span) -> Result<(), Diagnostic> {
        if j.is_time_dependent() {
            return Err(Diagnostic::error(span, "a moment of inertia must be constant, and this one changes with time")
                .with_hint("the inertia is about the centre of mass along the body's own axes, which turn with it").with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        if crate::algebra::assume::sign_under(&self.assumed, j) == Some(Sign::Negative) {
            return Err(Diagnostic::error(
                span,
                format!(
                    "a moment of inertia can't be negative, and {} is",
                    j.to_input()
                ),
            )
            .with_hint("moments of inertia are parameters or numbers ≥ 0")
            .with_kind(crate::diag::ErrorKind::Unphysical));
        }
        Ok(())
    }

    /// The inertia of a body in space: `[I1, I2, I3]` (principal, along the
    /// body's axes) or a symmetric 3×3 `[[Ixx, Ixy, Ixz], …]`. One about
    /// the centre is checked to be a rigid body's here; one `about` a
    /// point after it is moved to the centre (valid there, it is valid
    /// about every point of the body).
    fn inertia_tensor(
        &mut self,
        p: &BodyProperty,
        body: &str,
    ) -> Result<[[Expr; 3]; 3], Diagnostic> {
        let e = &p.value;
        let hint = "write the principal moments [I1, I2, I3] or the symmetric matrix [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]";
        let mut m: [[Expr; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| Expr::zero()));
        match &e.kind {
            ExprKind::Vector(rows) if rows.iter().any(|r| matches!(r.kind, ExprKind::Vector(_))) => {
                if rows.len() != 3 {
                    return Err(Diagnostic::error(e.span, format!("an inertia matrix has 3 rows, this one {}", rows.len())).with_hint(hint).with_kind(crate::diag::ErrorKind::TypeMismatch));
                }
                for (i, row) in rows.iter().enumerate() {
                    let ExprKind::Vector(items) = &row.kind else {
                        return Err(Diagnostic::error(row.span, "each row of an inertia matrix is [a, b, c]").with_hint(hint).with_kind(crate::diag::ErrorKind::TypeMismatch));
                    };
                    if items.len() != 3 {
                        return Err(Diagnostic::error(row.span, format!("a row of an inertia matrix has 3 entries, this one {}", items.len())).with_hint(hint).with_kind(crate::diag::ErrorKind::TypeMismatch));
                    }
                    for (j, item) in items.iter().enumerate() {
                        m[i][j] = self.ev.expr(item)?;
                        if m[i][j].is_time_dependent() {
                            return Err(Diagnostic::error(item.span, "an inertia must be constant, and this entry changes with time")
                                .with_hint("the inertia is about the centre of mass along the body's own axes, which turn with it").with_kind(crate::diag::ErrorKind::InvalidScene));
                        }
                    }
                }
                for (i, j) in [(0, 1), (0, 2), (1, 2)] {
                    if !m[i][j].equals(&m[j][i]) {
                        let ExprKind::Vector(ri) = &rows[i].kind else { continue };
                        let at = ri[j].span;
                        return Err(Diagnostic::error(
                            at,
                            format!(
                                "an inertia matrix is symmetric, but entry ({}, {}) is {} and entry ({}, {}) is {}",
                                i + 1, j + 1, m[i][j].to_input(), j + 1, i + 1, m[j][i].to_input()
                            ),
                        )
                        .with_hint(hint).with_kind(crate::diag::ErrorKind::Unphysical));
                    }
                }
                for (k, row) in rows.iter().enumerate() {
                    if let ExprKind::Vector(items) = &row.kind {
                        self.moment(&m[k][k], items[k].span)?;
                    }
                }
            }
            _ => match self.ev.value(e)? {
                Value::Vector(c) if c.len() == 3 => {
                    for (k, c) in c.into_iter().enumerate() {
                        let at = match &e.kind {
                            ExprKind::Vector(items) => items[k].span,
                            _ => e.span,
                        };
                        self.moment(&c, at)?;
                        m[k][k] = c;
                    }
                }
                v => {
                    return Err(Diagnostic::error(
                        e.span,
                        format!("a body in space has an inertia of three principal moments or a 3×3 matrix, and this is {}", v.describe()),
                    )
                    .with_hint(hint).with_kind(crate::diag::ErrorKind::TypeMismatch))
                }
            },
        }
        let moments = match &e.kind {
            ExprKind::Vector(items)
                if items.len() == 3
                    && !items.iter().any(|r| matches!(r.kind, ExprKind::Vector(_))) =>
            {
                Some([items[0].span, items[1].span, items[2].span])
            }
            _ => None,
        };
        let written = super::inertia::Written {
            body,
            span: e.span,
            moments,
            about: None,
        };
        if p.about.is_none() {
            if let Some(w) = super::inertia::check(&m, &written, &self.assumed)? {
                self.warnings.push(w);
            }
        }
        Ok(m)
    }

    /// `gravity G`: V = −M·G·P on every body and particle (`V_name`).
    pub(super) fn gravity(&mut self, stmts: &[Stmt]) -> Result<(), Diagnostic> {
        let mut found: Option<Span> = None;
        for st in stmts {
            let Stmt::Gravity { value, span } = st else {
                continue;
            };
            if found.is_some() {
                return Err(Diagnostic::error(*span, "gravity is given twice")
                    .with_hint("one `gravity` statement acts on every body and particle")
                    .with_kind(crate::diag::ErrorKind::DuplicateName {
                        name: "gravity".into(),
                    }));
            }
            found = Some(*span);
            self.gravity = Some(*span);
            let g = match self.ev.value(value)? {
                Value::Vector(c) => c,
                v => {
                    return Err(Diagnostic::error(
                        value.span,
                        format!("gravity is a vector, and this is {}", v.describe()),
                    )
                    .with_hint(
                        "write `gravity [0, -g]` in the plane or `gravity [0, 0, -g]` in space",
                    )
                    .with_kind(crate::diag::ErrorKind::TypeMismatch))
                }
            };
            positions_only(&g, value.span, "gravity")?;
            if self.bodies.is_empty() {
                self.warnings.push(
                    Diagnostic::warning(*span, "gravity acts on bodies and particles, and the scene has none")
                        .with_hint("declare them with `body` or `particle`; a hand-written potential is `potential V = m*g*y`"),
                );
            }
            for b in &mut self.bodies {
                // gravity does no work on a body whose centre is fixed
                let Some(mass) = &b.mass else { continue };
                if b.position.len() != g.len() {
                    return Err(Diagnostic::error(
                        value.span,
                        format!(
                            "gravity has {} components and the position of `{}` {}",
                            g.len(),
                            b.info.name,
                            b.position.len()
                        ),
                    )
                    .with_hint("write gravity and every position in the plane [x, y] or all in space [x, y, z]").with_kind(crate::diag::ErrorKind::TypeMismatch));
                }
                let work = g
                    .iter()
                    .zip(&b.position)
                    .fold(Expr::zero(), |s, (gc, p)| s.add(&gc.mul(p)));
                b.info.gravity = Some(gravity_name(&b.info.name));
                b.info.mass_properties.gravity = Some(g.clone());
                self.body_energies.push(Definition {
                    name: gravity_name(&b.info.name),
                    value: Value::Scalar(mass.mul(&work).neg()),
                    span: *span,
                    role: Some(Role::Potential),
                });
            }
        }
        Ok(())
    }
}

/// An error unless the centre of a body without a mass is fixed: only
/// then is its kinetic energy its turning's alone, whatever its mass.
fn fixed_centre(b: &BodyStmt, at: &BodyProperty, position: &[Expr]) -> Result<(), Diagnostic> {
    if position.iter().any(Expr::is_time_dependent) {
        return Err(Diagnostic::error(
            b.name.span,
            format!("`{}` has no mass, and its centre moves", b.name.name),
        )
        .with_label(at.value.span, "this moves with time")
        .with_hint(format!(
            "a body whose centre moves needs its mass: `body {}: mass m, …`; only a body turning about its fixed centre (`at [0, 0, 0]`) may leave it out",
            b.name.name
        )).with_kind(crate::diag::ErrorKind::InvalidScene));
    }
    Ok(())
}

/// ωᵀ·I·ω.
fn quadratic_form(i: &[[Expr; 3]; 3], w: &[Expr; 3]) -> Expr {
    let mut s = Expr::zero();
    for a in 0..3 {
        for b in 0..3 {
            if !i[a][b].is_zero() {
                s = s.add(&i[a][b].mul(&w[a]).mul(&w[b]));
            }
        }
    }
    s
}
