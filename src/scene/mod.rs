//! Scenes: the parsed statements resolved into exact expressions.
//!
//! [`Scene::parse`] runs the parser, checks the declarations (no name
//! declared twice, `t` and `pi` reserved), evaluates every definition lazily
//! in dependency order (forward references allowed, cycles reported with
//! the whole cycle), and collects the role statements, loads, torques and
//! `solve` blocks. Values are scalars or vectors ([`Value`]). Every error is
//! a [`Diagnostic`] pointing into the source.

mod eval;

pub(crate) use eval::is_taylor_form;

use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::parse::ast::{self, Role, Span, Stmt};
use rustc_hash::FxHashMap;

/// A generalized coordinate.
#[derive(Clone, Debug)]
pub struct Coordinate {
    pub name: String,
    pub span: Span,
}

/// A constant symbol.
#[derive(Clone, Debug)]
pub struct Parameter {
    pub name: String,
    pub span: Span,
    /// The optional dimension annotation (`r: length`), not yet interpreted.
    pub dimension: Option<String>,
}

/// The value of a definition: a scalar expression or a vector of them.
#[derive(Clone, Debug)]
pub enum Value {
    Scalar(Expr),
    /// A plane (2) or space (3) vector.
    Vector(Vec<Expr>),
}

impl Value {
    /// The scalar, if this is one.
    pub fn as_scalar(&self) -> Option<&Expr> {
        match self {
            Value::Scalar(e) => Some(e),
            Value::Vector(_) => None,
        }
    }
    /// The components: one for a scalar.
    pub fn components(&self) -> &[Expr] {
        match self {
            Value::Scalar(e) => std::slice::from_ref(e),
            Value::Vector(c) => c,
        }
    }
    /// Apply `f` to every component.
    pub fn map(&self, mut f: impl FnMut(&Expr) -> Expr) -> Value {
        match self {
            Value::Scalar(e) => Value::Scalar(f(e)),
            Value::Vector(c) => Value::Vector(c.iter().map(f).collect()),
        }
    }
    /// "a number" / "a vector with 2 components", for messages.
    pub fn describe(&self) -> String {
        match self {
            Value::Scalar(_) => "a number".into(),
            Value::Vector(c) => format!("a vector with {} components", c.len()),
        }
    }
}

/// A named expression.
#[derive(Clone, Debug)]
pub struct Definition {
    pub name: String,
    pub value: Value,
    pub span: Span,
    /// The role, for `kinetic E1 = …` and the like.
    pub role: Option<Role>,
}

/// A generalized force added to one coordinate's Q.
#[derive(Clone, Debug)]
pub struct Force {
    pub coordinate: usize,
    pub value: Expr,
    pub span: Span,
}

/// `load F at P`: a force applied at a point (both vectors of one size,
/// or both scalars: a force along the line of a scalar displacement).
#[derive(Clone, Debug)]
pub struct Load {
    pub force: Value,
    pub point: Value,
    pub span: Span,
}

/// `torque M on phi`: a moment doing work on an angle.
#[derive(Clone, Debug)]
pub struct Torque {
    pub moment: Expr,
    pub angle: Expr,
    pub span: Span,
}

/// One scalar equation of a `solve` block, as `lhs − rhs = 0`.
#[derive(Clone, Debug)]
pub struct SystemEquation {
    pub residual: Expr,
    pub span: Span,
    /// For a vector equation, which component (0-based) this is.
    pub component: Option<usize>,
}

/// A `solve` block: unknowns and the equations that determine them.
#[derive(Clone, Debug)]
pub struct System {
    pub unknowns: Vec<Parameter>,
    pub equations: Vec<SystemEquation>,
    pub span: Span,
}

/// A resolved scene (`Scene::default()` is the empty scene).
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub source: String,
    pub coordinates: Vec<Coordinate>,
    pub parameters: Vec<Parameter>,
    /// Definitions (including role statements) in source order.
    pub definitions: Vec<Definition>,
    pub forces: Vec<Force>,
    pub loads: Vec<Load>,
    pub torques: Vec<Torque>,
    /// The `solve` blocks, in source order.
    pub systems: Vec<System>,
    /// Things worth a look that do not stop the computation.
    pub warnings: Vec<Diagnostic>,
    /// The `latex NAME = "…"` statements, in source order (a later one for
    /// the same name wins).
    pub latex_names: Vec<LatexName>,
}

/// `latex theta3 = "\vartheta_{3}"`: the LaTeX notation of a name.
#[derive(Clone, Debug, PartialEq)]
pub struct LatexName {
    pub name: String,
    pub tex: String,
    pub span: Span,
}

/// The `latex` statements, with a warning for a name the scene never
/// declares and for a name given notation twice.
fn latex_names(
    stmts: &[Stmt],
    coordinates: &[Coordinate],
    parameters: &[Parameter],
    definitions: &[Definition],
    systems: &[System],
    warnings: &mut Vec<Diagnostic>,
) -> Vec<LatexName> {
    let mut out: Vec<LatexName> = Vec::new();
    for st in stmts {
        let Stmt::Latex { name, tex, span } = st else {
            continue;
        };
        let n = name.name.as_str();
        let declared = coordinates.iter().any(|c| c.name == n)
            || parameters.iter().any(|p| p.name == n)
            || definitions.iter().any(|d| d.name == n)
            || systems
                .iter()
                .flat_map(|s| &s.unknowns)
                .any(|u| u.name == n);
        if !declared {
            warnings.push(
                Diagnostic::warning(
                    name.span,
                    format!("`latex` gives notation for `{n}`, which the scene never declares"),
                )
                .with_hint("check the spelling: notation applies to coordinates, parameters, definitions and `solve` unknowns"),
            );
        }
        if out.iter().any(|l| l.name == n) {
            warnings.push(
                Diagnostic::warning(name.span, format!("`{n}` is given LaTeX notation twice"))
                    .with_hint("the later `latex` statement wins; remove the other"),
            );
        }
        out.push(LatexName {
            name: n.to_string(),
            tex: tex.clone(),
            span: *span,
        });
    }
    out
}

/// What a name means.
#[derive(Clone, Debug)]
pub(crate) enum Binding {
    Param,
    Unknown,
    Coord,
    Def(usize),
    Time,
    Pi,
}

impl Scene {
    /// Parse and resolve a scene.
    ///
    /// ```
    /// let scene = qdot::Scene::parse("coordinates x\nparameters m, k\n\
    ///     kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2").unwrap();
    /// assert_eq!(scene.coordinates[0].name, "x");
    /// ```
    pub fn parse(src: &str) -> Result<Scene, Diagnostic> {
        let stmts = crate::parse::parse_scene(src)?;
        Scene::from_statements(src, &stmts)
    }

    pub fn from_statements(src: &str, stmts: &[Stmt]) -> Result<Scene, Diagnostic> {
        let mut names: FxHashMap<String, (Binding, Span)> = FxHashMap::default();
        let mut coordinates = Vec::new();
        let mut parameters = Vec::new();
        let mut def_asts: Vec<(&ast::Ident, &ast::Expr, Option<Role>)> = Vec::new();
        let mut force_asts = Vec::new();
        let mut unknowns: Vec<Vec<Parameter>> = Vec::new();

        let mut declare = |name: &ast::Ident, b: Binding| -> Result<(), Diagnostic> {
            if name.name == "t" || name.name == "pi" {
                let what = if name.name == "t" {
                    "time"
                } else {
                    "the constant π"
                };
                return Err(Diagnostic::error(
                    name.span,
                    format!("`{}` is reserved: it is {what}", name.name),
                )
                .with_hint("choose another name"));
            }
            if let Some((prev, prev_span)) = names.get(&name.name) {
                let what = match prev {
                    Binding::Param => "a parameter",
                    Binding::Coord => "a coordinate",
                    Binding::Unknown => "an unknown of a `solve` block",
                    _ => "defined",
                };
                let (line, _) = Diagnostic::line_col(src, prev_span.start);
                if matches!(b, Binding::Unknown) {
                    let hint = match prev {
                        Binding::Param => format!("a `solve` unknown is a new name that the equations determine; remove `{}` from `parameters` (line {line}) or solve for another name", name.name),
                        Binding::Unknown => format!("list each unknown once, in one `solve` block (`{}` is first at line {line})", name.name),
                        _ => format!("`{}` already has a value (line {line}); solve for a new name", name.name),
                    };
                    let message = if matches!(prev, Binding::Unknown) {
                        format!("the unknown `{}` is listed twice", name.name)
                    } else {
                        format!("the unknown `{}` is already {what}", name.name)
                    };
                    return Err(Diagnostic::error(name.span, message).with_hint(hint));
                }
                let again = match (&b, prev) {
                    (Binding::Coord, Binding::Coord) => "coordinate declared twice",
                    (Binding::Param, Binding::Param) => "parameter declared twice",
                    _ => "name used twice",
                };
                return Err(Diagnostic::error(
                    name.span,
                    format!("{again}: `{}` is already {what}", name.name),
                )
                .with_hint("each name has one meaning in a scene; role statements add up, but their names must differ"));
            }
            names.insert(name.name.clone(), (b, name.span));
            Ok(())
        };

        for st in stmts {
            match st {
                Stmt::Coordinates(ds, _) => {
                    for d in ds {
                        declare(&d.name, Binding::Coord)?;
                        coordinates.push(Coordinate {
                            name: d.name.name.clone(),
                            span: d.name.span,
                        });
                    }
                }
                Stmt::Parameters(ds, _) => {
                    for d in ds {
                        declare(&d.name, Binding::Param)?;
                        parameters.push(Parameter {
                            name: d.name.name.clone(),
                            span: d.name.span,
                            dimension: d.dimension.as_ref().map(|i| i.name.clone()),
                        });
                    }
                }
                Stmt::Def { name, value, .. } => {
                    declare(name, Binding::Def(def_asts.len()))?;
                    def_asts.push((name, value, None));
                }
                Stmt::Role {
                    role, name, value, ..
                } => {
                    declare(name, Binding::Def(def_asts.len()))?;
                    def_asts.push((name, value, Some(*role)));
                }
                Stmt::Force {
                    coordinate, value, ..
                } => force_asts.push((coordinate, value)),
                Stmt::Load { .. } | Stmt::Torque { .. } | Stmt::Latex { .. } => {}
                Stmt::Solve(block) => {
                    let mut us = Vec::with_capacity(block.unknowns.len());
                    for u in &block.unknowns {
                        declare(u, Binding::Unknown)?;
                        us.push(Parameter {
                            name: u.name.clone(),
                            span: u.span,
                            dimension: None,
                        });
                    }
                    unknowns.push(us);
                }
            }
        }
        names.insert("t".into(), (Binding::Time, Span::default()));
        names.insert("pi".into(), (Binding::Pi, Span::default()));
        // Intern q, q̇, q̈ in declaration order: printing lists terms of
        // equal rank in the order the coordinates were declared.
        for c in &coordinates {
            for k in 0..=2 {
                crate::expr::atom::coord(&c.name, k);
            }
        }

        let mut ev = eval::Evaluator::new(&names, &def_asts);
        let mut definitions = Vec::with_capacity(def_asts.len());
        for (i, (name, body, role)) in def_asts.iter().enumerate() {
            let value = ev.definition(i)?;
            if let (Some(role), Value::Vector(c)) = (role, &value) {
                return Err(Diagnostic::error(
                    body.span,
                    format!(
                        "`{} {}` must be a number, but this is a vector with {} components",
                        role.keyword(),
                        name.name,
                        c.len()
                    ),
                )
                .with_hint(match role {
                    Role::Kinetic => "the kinetic energy of a point with velocity v is 1/2*m*dot(v, v)",
                    _ => "energies, work and dissipation are numbers; use dot(F, r) for the work of a force",
                }));
            }
            if let (Some(role), Value::Scalar(e)) = (role, &value) {
                if let Some(u) = first_unknown(e) {
                    return Err(Diagnostic::error(
                        body.span,
                        format!(
                            "`{} {}` uses `{u}`, an unknown of a `solve` block",
                            role.keyword(),
                            name.name
                        ),
                    )
                    .with_hint("energies are functions of the coordinates and parameters; unknowns belong in `solve` equations"));
                }
                if let Some(acc) = energy_acceleration(*role, e) {
                    let at = second_prime_span(body).unwrap_or(body.span);
                    return Err(Diagnostic::error(
                        at,
                        format!(
                            "`{} {}` depends on the acceleration {acc}",
                            role.keyword(),
                            name.name
                        ),
                    )
                    .with_hint("energies and the Lagrangian are functions of the coordinates, the velocities and t (Lagrange's equations would differentiate an acceleration into a third derivative); a force that depends on an acceleration is a `force` or a `load`"));
                }
            }
            definitions.push(Definition {
                name: name.name.clone(),
                value,
                span: name.span,
                role: *role,
            });
        }
        let mut forces = Vec::new();
        for (c, value) in force_asts {
            let Some(k) = coordinates.iter().position(|x| x.name == c.name) else {
                let mut d = Diagnostic::error(
                    c.span,
                    format!(
                        "`force {}:` needs a coordinate, and `{}` is not one",
                        c.name, c.name
                    ),
                );
                let list: Vec<&str> = coordinates.iter().map(|c| c.name.as_str()).collect();
                d = d.with_hint(if list.is_empty() {
                    "declare it with `coordinates …`".to_string()
                } else {
                    format!("the coordinates are {}", list.join(", "))
                });
                return Err(d);
            };
            let v = ev.expr(value)?;
            no_unknowns(std::slice::from_ref(&v), value.span, "a generalized force")?;
            forces.push(Force {
                coordinate: k,
                value: v,
                span: value.span,
            });
        }
        let coord_vars: Vec<crate::poly::Var> = coordinates
            .iter()
            .map(|c| crate::expr::atom::coord(&c.name, 0))
            .collect();
        let moves = |e: &Expr| coord_vars.iter().any(|&q| e.depends_on(q));
        let mut loads = Vec::new();
        let mut torques = Vec::new();
        let mut systems = Vec::new();
        let mut warnings = Vec::new();
        let mut blocks = unknowns.into_iter();
        for st in stmts {
            match st {
                Stmt::Load { force, point, span } => {
                    let f = ev.value(force)?;
                    let p = ev.value(point)?;
                    match (&f, &p) {
                        (Value::Vector(a), Value::Vector(b)) if a.len() != b.len() => {
                            return Err(Diagnostic::error(
                                *span,
                                format!(
                                    "the force has {} components and the point {}",
                                    a.len(),
                                    b.len()
                                ),
                            )
                            .with_hint("write both in the plane [x, y] or both in space [x, y, z]"))
                        }
                        (Value::Scalar(_), Value::Vector(_))
                        | (Value::Vector(_), Value::Scalar(_)) => {
                            return Err(Diagnostic::error(
                                *span,
                                format!(
                                    "the force is {} but the point is {}",
                                    f.describe(),
                                    p.describe()
                                ),
                            )
                            .with_hint("a vector force needs a position vector `load [Fx, Fy] at [x, y]`; a number needs a displacement along its line `load G at y1`"))
                        }
                        _ => {}
                    }
                    no_unknowns(f.components(), force.span, "a load")?;
                    no_unknowns(p.components(), point.span, "a load's point")?;
                    if !p.components().iter().any(&moves) {
                        warnings.push(
                            Diagnostic::warning(point.span, "this load does no virtual work: its point does not move with any coordinate")
                                .with_hint("a force at a fixed point (a reaction of a support) does not enter the generalized forces; check the point's definition"),
                        );
                    }
                    loads.push(Load {
                        force: f,
                        point: p,
                        span: *span,
                    });
                }
                Stmt::Torque {
                    moment,
                    angle,
                    span,
                } => {
                    let m = ev.value(moment)?;
                    let m = match m {
                        Value::Scalar(m) => m,
                        Value::Vector(_) => {
                            return Err(Diagnostic::error(
                                moment.span,
                                format!("a torque is a number (the moment about the axis of its angle), found {}", m.describe()),
                            )
                            .with_hint("in the plane write the moment's z component, e.g. cross(r, F) of plane vectors"))
                        }
                    };
                    let a = ev.value(angle)?;
                    let a = match a {
                        Value::Scalar(a) => a,
                        Value::Vector(_) => {
                            return Err(Diagnostic::error(
                                angle.span,
                                format!(
                                    "a torque acts on an angle (a number), found {}",
                                    a.describe()
                                ),
                            )
                            .with_hint(
                                "write `torque M on theta` with theta an angle of the scene",
                            ))
                        }
                    };
                    no_unknowns(std::slice::from_ref(&m), moment.span, "a torque")?;
                    no_unknowns(std::slice::from_ref(&a), angle.span, "a torque's angle")?;
                    if !moves(&a) {
                        warnings.push(
                            Diagnostic::warning(angle.span, "this torque does no virtual work: its angle does not change with any coordinate")
                                .with_hint("check the angle's definition"),
                        );
                    }
                    torques.push(Torque {
                        moment: m,
                        angle: a,
                        span: *span,
                    });
                }
                Stmt::Solve(block) => {
                    let us = blocks.next().unwrap_or_default();
                    let mut equations = Vec::new();
                    for eq in &block.equations {
                        let l = ev.value(&eq.lhs)?;
                        let r = ev.value(&eq.rhs)?;
                        let comps = match (&l, &r) {
                            (Value::Scalar(a), Value::Scalar(b)) => {
                                equations.push(SystemEquation {
                                    residual: a.sub(b),
                                    span: eq.span,
                                    component: None,
                                });
                                continue;
                            }
                            (Value::Vector(a), Value::Vector(b)) if a.len() == b.len() => (a, b),
                            _ => {
                                return Err(Diagnostic::error(
                                    eq.span,
                                    format!(
                                        "the left side is {} and the right side {}",
                                        l.describe(),
                                        r.describe()
                                    ),
                                )
                                .with_hint("a vector equation needs vectors of one size on both sides, e.g. `[Fx, Fy] = m*a`; write `[0, 0]` for the zero vector"))
                            }
                        };
                        for (k, (a, b)) in comps.0.iter().zip(comps.1).enumerate() {
                            equations.push(SystemEquation {
                                residual: a.sub(b),
                                span: eq.span,
                                component: Some(k),
                            });
                        }
                    }
                    systems.push(System {
                        unknowns: us,
                        equations,
                        span: block.span,
                    });
                }
                _ => {}
            }
        }
        warnings.extend(ev.warnings);
        let latex_names = latex_names(
            stmts,
            &coordinates,
            &parameters,
            &definitions,
            &systems,
            &mut warnings,
        );
        if coordinates.is_empty() && definitions.iter().any(|d| d.role.is_some()) {
            warnings.push(Diagnostic::global(
                "the scene has energies but no `coordinates`: there are no equations to derive",
            ));
        }
        Ok(Scene {
            source: src.to_string(),
            coordinates,
            parameters,
            definitions,
            forces,
            loads,
            torques,
            systems,
            warnings,
            latex_names,
        })
    }

    /// Evaluate an expression written in the scene's names (its parameters,
    /// coordinates with primes, definitions, `t`, `pi`).
    pub fn expr(&self, src: &str) -> Result<Expr, Diagnostic> {
        match self.value_of(src)? {
            Value::Scalar(e) => Ok(e),
            v => Err(Diagnostic::global(format!(
                "expected a number, found {}",
                v.describe()
            ))),
        }
    }

    /// Like [`Scene::expr`], for an expression that may be a vector.
    pub fn value_of(&self, src: &str) -> Result<Value, Diagnostic> {
        let e = crate::parse::parse_expr(src)?;
        Ok(self.evaluate(&e, &[])?.0)
    }

    /// Evaluate a parsed expression in the scene's names, with `extra`
    /// names bound to values (the REPL's `_`): the value and the warnings
    /// (spans point into the text `e` was parsed from).
    pub fn evaluate(
        &self,
        e: &ast::Expr,
        extra: &[(&str, Value)],
    ) -> Result<(Value, Vec<Diagnostic>), Diagnostic> {
        let mut names: FxHashMap<String, (Binding, Span)> = FxHashMap::default();
        for c in &self.coordinates {
            names.insert(c.name.clone(), (Binding::Coord, c.span));
        }
        for p in &self.parameters {
            names.insert(p.name.clone(), (Binding::Param, p.span));
        }
        for (i, d) in self.definitions.iter().enumerate() {
            names.insert(d.name.clone(), (Binding::Def(i), d.span));
        }
        names.insert("t".into(), (Binding::Time, Span::default()));
        names.insert("pi".into(), (Binding::Pi, Span::default()));
        for sys in &self.systems {
            for u in &sys.unknowns {
                names.insert(u.name.clone(), (Binding::Unknown, u.span));
            }
        }
        let mut values: Vec<Value> = self.definitions.iter().map(|d| d.value.clone()).collect();
        for (name, v) in extra {
            names.insert(
                (*name).to_string(),
                (Binding::Def(values.len()), Span::default()),
            );
            values.push(v.clone());
        }
        let mut ev = eval::Evaluator::with_values(&names, values);
        let v = ev.value(e)?;
        Ok((v, std::mem::take(&mut ev.warnings)))
    }

    /// The definitions playing `role`, in source order.
    pub fn role(&self, role: Role) -> impl Iterator<Item = &Definition> {
        self.definitions
            .iter()
            .filter(move |d| d.role == Some(role))
    }

    /// The sum of all definitions playing `role` (zero if none).
    pub fn role_sum(&self, role: Role) -> Expr {
        self.role(role).fold(Expr::zero(), |acc, d| match &d.value {
            Value::Scalar(e) => acc.add(e),
            // role statements are checked to be scalars when the scene is built
            Value::Vector(_) => acc,
        })
    }

    /// Whether any statement plays `role`.
    pub fn has_role(&self, role: Role) -> bool {
        self.role(role).next().is_some()
    }

    /// The value of a scalar definition by name.
    pub fn definition(&self, name: &str) -> Option<&Expr> {
        self.value(name).and_then(Value::as_scalar)
    }

    /// The value of a definition (scalar or vector) by name.
    pub fn value(&self, name: &str) -> Option<&Value> {
        self.definitions
            .iter()
            .find(|d| d.name == name)
            .map(|d| &d.value)
    }

    /// Whether the scene has equations of motion: coordinates, and a kinetic
    /// energy or inertia forces (terms in q̈) among its loads, torques or
    /// forces — a scene in D'Alembert's form. A scene with coordinates and
    /// only static loads (seed 23.1) has generalized forces and equilibria
    /// but no accelerations.
    pub fn has_dynamics(&self) -> bool {
        if self.coordinates.is_empty() {
            return false;
        }
        if self.has_role(Role::Kinetic) || self.has_role(Role::Lagrangian) {
            return true;
        }
        let qdd: Vec<crate::poly::Var> = self
            .coordinates
            .iter()
            .map(|c| crate::expr::atom::coord(&c.name, 2))
            .collect();
        let inertial = |e: &Expr| qdd.iter().any(|&v| e.depends_on(v));
        self.loads
            .iter()
            .any(|l| l.force.components().iter().any(inertial))
            || self.torques.iter().any(|t| inertial(&t.moment))
            || self.forces.iter().any(|f| inertial(&f.value))
    }
}

/// An error if any of `es` uses a `solve` unknown: forces enter Lagrange's
/// equations, which are solved before any block.
fn no_unknowns(es: &[Expr], span: Span, what: &str) -> Result<(), Diagnostic> {
    match es.iter().find_map(first_unknown) {
        Some(u) => Err(Diagnostic::error(
            span,
            format!("{what} uses `{u}`, an unknown of a `solve` block"),
        )
        .with_hint("loads, torques and forces enter the equations of motion, which are solved before the blocks; a reaction found by a block can't drive the motion")),
        None => Ok(()),
    }
}

/// The name of the first `solve` unknown an expression uses, if any.
/// The first acceleration (a coordinate's derivative of order ≥ 2, as
/// `x''`) in `e`, when `e` is a role's expression that must not have one:
/// every role but `work`, whose inertia forces carry accelerations in
/// D'Alembert's form.
fn energy_acceleration(role: Role, e: &Expr) -> Option<String> {
    use crate::expr::atom::{self, Atom};
    if role == Role::Work {
        return None;
    }
    fn walk(e: &Expr) -> Option<String> {
        for v in e.vars() {
            let a = atom::atom(v);
            if let Atom::Coord(n, k) = &a {
                if *k >= 2 {
                    return Some(format!("{n}{}", "'".repeat(*k as usize)));
                }
            }
            if let Some(n) = a.argument().and_then(walk) {
                return Some(n);
            }
        }
        None
    }
    walk(e)
}

/// The span of the first `x''` (two or more primes, or a prime of a primed
/// expression) in an expression as written, found without recursion.
fn second_prime_span(e: &ast::Expr) -> Option<Span> {
    use ast::ExprKind as K;
    let mut stack = vec![(e, 0u32)];
    while let Some((e, primes)) = stack.pop() {
        match &e.kind {
            K::Prime(inner, k) => {
                if primes + k >= 2 {
                    return Some(e.span);
                }
                stack.push((inner, primes + k));
            }
            K::Neg(x) => stack.push((x, primes)),
            K::Bin(_, a, b) | K::Assign(a, b) => {
                stack.push((b, primes));
                stack.push((a, primes));
            }
            K::Call(_, args) | K::Vector(args) => {
                stack.extend(args.iter().rev().map(|a| (a, primes)));
            }
            K::Num(_) | K::Degrees(_) | K::Name(_) => {}
        }
    }
    None
}

pub fn first_unknown(e: &Expr) -> Option<String> {
    use crate::expr::atom::{self, Atom};
    fn walk(e: &Expr) -> Option<String> {
        for v in e.vars() {
            let a = atom::atom(v);
            if let Atom::Unknown(n) = &a {
                return Some(n.to_string());
            }
            if let Some(n) = a.argument().and_then(walk) {
                return Some(n);
            }
        }
        None
    }
    walk(e)
}
