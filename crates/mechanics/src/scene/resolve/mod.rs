//! From statements to a [`Scene`]: the names are declared in a first pass
//! (so definitions may refer forward), then every statement is resolved
//! into exact values by the [`SyntaxEvaluator`], each kind by its own method of
//! [`Resolver`], with its errors built beside it.

use super::eval::SyntaxEvaluator;
use super::{
    first_unknown, latex_names, Binding, Coordinate, Definition, Force, GivenFunction, Load,
    Parameter, Scene, SolveSystem, SystemEquation, Torque, Value,
};
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::parse::ast::{self, Role, Span, Stmt};
use crate::poly::Var;
use rustc_hash::FxHashMap;

mod about;
mod assume;
mod bodies;
mod constraints;
mod inertia;
mod joints;

/// A definition as written: its name, its body and its role, if any.
type DefinitionAst<'a> = (&'a ast::Ident, &'a ast::Expr, Option<Role>);

/// The names a scene declares, read in a first pass over its statements.
struct Declarations<'a> {
    src: &'a str,
    names: FxHashMap<String, (Binding, Span)>,
    coordinates: Vec<Coordinate>,
    parameters: Vec<Parameter>,
    functions: Vec<GivenFunction>,
    definitions: Vec<DefinitionAst<'a>>,
    forces: Vec<(&'a ast::Ident, &'a ast::Expr)>,
    /// The unknowns of each `solve` block, in order.
    unknowns: Vec<Vec<Parameter>>,
    /// The indices in `definitions` of the `frame` statements.
    frames: Vec<usize>,
    /// The `constraint` statements, in order.
    constraints: Vec<&'a Stmt>,
    /// The `reaction` statements, in order.
    reactions: Vec<&'a Stmt>,
    /// The bodies that turn in the plane (`body` with an `angle`).
    turning: Vec<&'a str>,
}

impl<'a> Declarations<'a> {
    fn collect(src: &'a str, stmts: &'a [Stmt]) -> Result<Declarations<'a>, Diagnostic> {
        let mut d = Declarations {
            src,
            names: FxHashMap::default(),
            coordinates: Vec::new(),
            parameters: Vec::new(),
            functions: Vec::new(),
            definitions: Vec::new(),
            forces: Vec::new(),
            unknowns: Vec::new(),
            frames: Vec::new(),
            constraints: Vec::new(),
            reactions: Vec::new(),
            turning: Vec::new(),
        };
        for st in stmts {
            d.statement(st)?;
        }
        for st in stmts {
            d.reaction_names(st)?;
        }
        d.reserve_body_energies(stmts)?;
        d.names.insert("t".into(), (Binding::Time, Span::default()));
        d.names.insert("pi".into(), (Binding::Pi, Span::default()));
        Ok(d)
    }

    /// The source text of `span`.
    fn written(&self, span: Span) -> String {
        self.src[span.start..span.end].to_string()
    }

    fn statement(&mut self, st: &'a Stmt) -> Result<(), Diagnostic> {
        match st {
            Stmt::Coordinates(ds, _) => {
                for d in ds {
                    self.declare(&d.name, Binding::Coord)?;
                    self.coordinates.push(Coordinate {
                        name: d.name.name.clone(),
                        span: d.name.span,
                        dimension: d.dimension.as_ref().map(|e| self.written(e.span)),
                    });
                }
            }
            Stmt::Parameters(ds, _) => {
                for d in ds {
                    self.declare(&d.name, Binding::Param)?;
                    self.parameters.push(Parameter {
                        name: d.name.name.clone(),
                        span: d.name.span,
                        dimension: d.dimension.as_ref().map(|e| self.written(e.span)),
                    });
                }
            }
            Stmt::Functions(ds, _) => {
                for d in ds {
                    self.declare(&d.name, Binding::Given)?;
                    self.functions.push(GivenFunction {
                        name: d.name.name.clone(),
                        span: d.name.span,
                        dimension: d.dimension.as_ref().map(|e| self.written(e.span)),
                    });
                }
            }
            Stmt::Def { name, value, .. } => {
                self.declare(name, Binding::Def(self.definitions.len()))?;
                self.definitions.push((name, value, None));
            }
            Stmt::Role {
                role, name, value, ..
            } => {
                self.declare(name, Binding::Def(self.definitions.len()))?;
                self.definitions.push((name, value, Some(*role)));
            }
            Stmt::Force {
                coordinate, value, ..
            } => self.forces.push((coordinate, value)),
            Stmt::Frame { name, value, .. } => {
                self.frames.push(self.definitions.len());
                self.declare(name, Binding::Def(self.definitions.len()))?;
                self.definitions.push((name, value, None));
            }
            Stmt::Body(b) => {
                self.declare(&b.name, Binding::Body)?;
                if b.properties
                    .iter()
                    .any(|p| p.key == ast::PropertyKey::Angle)
                {
                    self.turning.push(&b.name.name);
                }
            }
            Stmt::Joint(_) | Stmt::Drive { .. } | Stmt::Friction { .. } => {}
            Stmt::Load { .. }
            | Stmt::Torque { .. }
            | Stmt::Latex { .. }
            | Stmt::Gravity { .. }
            | Stmt::Assume(..) => {}
            Stmt::Constraint { name, span, .. } => {
                let k = self.constraints.len();
                let multiplier = constraints::multiplier_name(name.as_ref(), k);
                // the multiplier's name is taken like any other name
                let at = name.as_ref().map_or(*span, |n| n.span);
                self.declare(
                    &ast::Ident {
                        name: multiplier,
                        span: at,
                    },
                    Binding::Multiplier,
                )?;
                self.constraints.push(st);
            }
            Stmt::Reaction { .. } => self.reactions.push(st),
            Stmt::Solve(block) => {
                let mut us = Vec::with_capacity(block.unknowns.len());
                for u in &block.unknowns {
                    self.declare(u, Binding::Unknown)?;
                    us.push(Parameter {
                        name: u.name.clone(),
                        span: u.span,
                        dimension: None,
                    });
                }
                self.unknowns.push(us);
            }
        }
        Ok(())
    }

    /// The names a joint's reaction, a drive's force and a friction take.
    fn reaction_names(&mut self, st: &'a Stmt) -> Result<(), Diagnostic> {
        let named = |name: String, span: Span| ast::Ident { name, span };
        match st {
            Stmt::Joint(j) => {
                let turns = |e: &ast::JointEnd| self.turning.contains(&e.body.name.as_str());
                let locked = turns(&j.first) && turns(&j.second);
                for n in super::mechanism::reaction_names(&j.name.name, j.kind, locked) {
                    self.declare(&named(n, j.name.span), Binding::Reaction)?;
                }
            }
            Stmt::Drive { name, .. } => self.declare(name, Binding::Reaction)?,
            Stmt::Friction { joint, .. } => self.declare(
                &named(super::mechanism::friction_name(&joint.name), joint.span),
                Binding::Reaction,
            )?,
            _ => {}
        }
        Ok(())
    }

    /// Give `name` its meaning, unless it is reserved or already has one.
    fn declare(&mut self, name: &ast::Ident, b: Binding) -> Result<(), Diagnostic> {
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
            .with_hint("choose another name")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        if let Some((prev, prev_span)) = self.names.get(&name.name) {
            return Err(self.declared_twice(name, &b, prev, *prev_span));
        }
        self.names.insert(name.name.clone(), (b, name.span));
        Ok(())
    }

    /// The error of `name` declared again as `b`, with its first
    /// declaration as a label.
    fn declared_twice(
        &self,
        name: &ast::Ident,
        b: &Binding,
        prev: &Binding,
        prev_span: Span,
    ) -> Diagnostic {
        let what = match prev {
            Binding::Body => "a body",
            Binding::Given => "a given function of time",
            Binding::Param => "a parameter",
            Binding::Coord => "a coordinate",
            Binding::Unknown => "an unknown of a `solve` block",
            Binding::Multiplier => "the multiplier of a constraint",
            Binding::Reaction => "a joint's reaction, a drive's force or a friction",
            _ => "defined",
        };
        let (line, _) = Diagnostic::line_col(self.src, prev_span.start);
        let first = |d: Diagnostic| {
            d.with_kind(crate::diag::ErrorKind::DuplicateName {
                name: name.name.clone(),
            })
            .with_label(prev_span, format!("`{}` is {what} here", name.name))
        };
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
            return first(
                Diagnostic::error(name.span, message)
                    .with_hint(hint)
                    .with_kind(crate::diag::ErrorKind::DuplicateName {
                        name: name.name.to_string(),
                    }),
            );
        }
        if matches!(b, Binding::Reaction) {
            return first(Diagnostic::error(
                name.span,
                format!("`{}`, which this statement names, is already {what}", name.name),
            )
            .with_hint("a joint NAME names its reaction NAME_x, NAME_y (a pin) or NAME_n, NAME_m (a slider), a drive its force, a friction NAME_f: rename the joint, drive or other name").with_kind(crate::diag::ErrorKind::DuplicateName { name: name.name.to_string() }));
        }
        if matches!(b, Binding::Multiplier) {
            return first(Diagnostic::error(
                name.span,
                format!(
                    "this constraint's multiplier `{}` is already {what}",
                    name.name
                ),
            )
            .with_hint("a constraint NAME brings the multiplier `lambda_NAME`: rename the constraint or the other name").with_kind(crate::diag::ErrorKind::DuplicateName { name: name.name.to_string() }));
        }
        let again = match (b, prev) {
            (Binding::Coord, Binding::Coord) => "coordinate declared twice",
            (Binding::Param, Binding::Param) => "parameter declared twice",
            _ => "name used twice",
        };
        first(Diagnostic::error(
            name.span,
            format!("{again}: `{}` is already {what}", name.name),
        )
        .with_hint("each name has one meaning in a scene; role statements add up, but their names must differ").with_kind(crate::diag::ErrorKind::DuplicateName { name: name.name.to_string() }))
    }
}

/// The second pass: statements resolved into values, in source order.
struct Resolver<'d> {
    /// The scene's source text.
    src: &'d str,
    ev: SyntaxEvaluator<'d>,
    coordinates: &'d [Coordinate],
    /// The coordinates' variables (q, not q̇), to tell what moves.
    coordinate_vars: Vec<Var>,
    loads: Vec<Load>,
    torques: Vec<Torque>,
    systems: Vec<SolveSystem>,
    warnings: Vec<Diagnostic>,
    /// The bodies and particles, in source order.
    bodies: Vec<bodies::ResolvedBody>,
    /// Their kinetic energies and gravity's potential on each (`E_top`,
    /// `V_top`), definitions with a role.
    body_energies: Vec<Definition>,
    /// The `gravity` statement.
    gravity: Option<Span>,
    /// The scene's assumptions, once read.
    assumed: crate::algebra::assume::Assumptions,
}

pub(super) fn scene_from_statements(
    src: &str,
    stmts: &[Stmt],
    structured: bool,
    keep: &[String],
) -> Result<Scene, Diagnostic> {
    let decl = Declarations::collect(src, stmts)?;
    if structured {
        structure_allowed(stmts)?;
    }
    // Intern q, q̇, q̈ in declaration order: printing lists terms of equal
    // rank in the order the coordinates were declared.
    for c in &decl.coordinates {
        for k in 0..=2 {
            crate::expr::atom::coord(&c.name, k);
        }
    }
    let mut r = Resolver {
        src,
        ev: SyntaxEvaluator::new(&decl.names, &decl.definitions),
        coordinates: &decl.coordinates,
        coordinate_vars: decl
            .coordinates
            .iter()
            .map(|c| crate::expr::atom::coord(&c.name, 0))
            .collect(),
        loads: Vec::new(),
        torques: Vec::new(),
        systems: Vec::new(),
        warnings: Vec::new(),
        bodies: Vec::new(),
        body_energies: Vec::new(),
        gravity: None,
        assumed: Default::default(),
    };
    // the facts first, so that √(q²) in the definitions sees them (a
    // definition a fact uses is evaluated before the facts exist)
    let assumptions = r.assumptions(stmts, &decl.parameters)?;
    r.assumed = assumptions.clone();
    r.ev.assumed = assumptions.clone();
    if structured {
        keep_structure(&mut r.ev, &decl, keep)?;
    }
    let (values, unused) = evaluate_used(&mut r, &decl, stmts)?;
    for &i in &decl.frames {
        if let Some(v) = &values[i] {
            bodies::frame_value(decl.definitions[i].1, v)?;
        }
    }
    let forces = r.forces(&decl.forces)?;
    let mut blocks = decl.unknowns.iter().cloned();
    for st in stmts {
        match st {
            Stmt::Load { force, point, span } => r.load(force, point, *span)?,
            Stmt::Torque {
                moment,
                angle,
                span,
            } => r.torque(moment, angle, *span)?,
            Stmt::Solve(block) => r.solve_block(block, blocks.next().unwrap_or_default())?,
            Stmt::Body(b) => r.body(b)?,
            _ => {}
        }
    }
    r.gravity(stmts)?;
    let mut constraints = r.constraints(&decl.constraints)?;
    let (joints, drives) = r.mechanism(stmts, &mut constraints)?;
    let reactions = r.reactions(&decl.reactions, &constraints)?;
    let (mut definitions, deferred) = split_definitions(&mut r, &decl, values, &unused);
    definitions.append(&mut r.body_energies);
    let Resolver {
        mut ev,
        loads,
        torques,
        systems,
        mut warnings,
        bodies,
        gravity,
        ..
    } = r;
    let bodies = bodies.into_iter().map(|b| b.info).collect();
    let tape = ev.tape.take();
    warnings.extend(ev.warnings);
    let Declarations {
        coordinates,
        parameters,
        functions,
        ..
    } = decl;
    let defined = |n: &str| {
        decl.names
            .get(n)
            .is_some_and(|b| matches!(b.0, Binding::Def(_)))
    };
    let latex_names = latex_names(
        stmts,
        &coordinates,
        &parameters,
        &defined,
        &systems,
        &mut warnings,
    );
    if coordinates.is_empty() && definitions.iter().any(|d| d.role.is_some()) {
        warnings.push(Diagnostic::global_warning(
            "the scene has energies but no `coordinates`: there are no equations to derive",
        ));
    }
    let dimensions_checked = super::dimension::annotated(stmts);
    if dimensions_checked {
        let constant = |name: &str| {
            definitions
                .iter()
                .find(|d| d.name == name)
                .and_then(|d| d.value.as_scalar())
                .and_then(Expr::as_rational)
        };
        super::dimension::validate(src, stmts, &constant)?;
    }
    Ok(Scene {
        dimensions_checked,
        source: src.to_string(),
        coordinates,
        parameters,
        functions,
        definitions,
        deferred,
        forces,
        loads,
        torques,
        systems,
        bodies,
        gravity,
        constraints,
        reactions,
        joints,
        drives,
        assumptions,
        warnings,
        latex_names,
        tape,
    })
}

/// The definitions the statements use, evaluated in source order (a
/// role's value checked), `None` for the others; and the others, each
/// checked without evaluating it (names, cycles) and listed after those
/// it uses.
fn evaluate_used(
    r: &mut Resolver,
    decl: &Declarations,
    stmts: &[Stmt],
) -> Result<(Vec<Option<Value>>, Vec<usize>), Diagnostic> {
    let roles = (decl.definitions.iter().enumerate()).filter_map(|(i, d)| d.2.map(|_| i));
    let roots = roles.chain(decl.frames.iter().copied());
    let used = super::lazy::used_definitions(&r.ev, &decl.names, stmts, roots);
    let (mut walked, mut unused) = (Vec::new(), Vec::new());
    let mut values: Vec<Option<Value>> = Vec::with_capacity(decl.definitions.len());
    for (i, &(name, body, role)) in decl.definitions.iter().enumerate() {
        if !used[i] {
            r.ev.check_unevaluated(i, &mut walked, &mut unused)?;
            values.push(None);
            continue;
        }
        let value = r.ev.definition(i)?;
        if let Some(role) = role {
            role_value_allowed(role, name, body, &value)?;
        }
        values.push(Some(value));
    }
    Ok((values, unused))
}

/// The definitions with their values, in source order: those the
/// statements used (`values`), the unused ones (`unused`, each after those
/// it uses) small enough to evaluate now, and the rest deferred; an unused
/// definition's evaluation error is a warning.
fn split_definitions(
    r: &mut Resolver,
    decl: &Declarations,
    mut values: Vec<Option<Value>>,
    unused: &[usize],
) -> (Vec<Definition>, Vec<super::DeferredDefinition>) {
    let idents: Vec<&ast::Ident> = decl.definitions.iter().map(|d| d.0).collect();
    let (checked, warnings) = super::lazy::check_unused(&mut r.ev, unused, &idents);
    r.warnings.extend(warnings);
    let mut definitions = Vec::with_capacity(values.len());
    let mut deferred = Vec::new();
    for (i, &(name, body, role)) in decl.definitions.iter().enumerate() {
        let found = values[i].take().or_else(|| checked.get(&i).cloned());
        // a definition a statement reached in a way the walk did not see
        match found.or_else(|| r.ev.evaluated(i).cloned()) {
            Some(value) => definitions.push(Definition {
                name: name.name.clone(),
                value,
                span: name.span,
                role,
            }),
            None => deferred.push(super::DeferredDefinition::new(name, body)),
        }
    }
    (definitions, deferred)
}

/// Give the evaluator a tape (the scene's names reserved on it) and mark
/// the definitions `keep` names; an error for a name that is not a
/// definition without a role.
fn keep_structure(
    ev: &mut SyntaxEvaluator,
    decl: &Declarations,
    keep: &[String],
) -> Result<(), Diagnostic> {
    let mut tape = crate::expr::tape::Tape::new();
    for name in decl.names.keys() {
        tape.reserve(name);
    }
    ev.tape = Some(tape);
    for (k, name) in keep.iter().enumerate() {
        if keep[..k].contains(name) {
            return Err(
                Diagnostic::global(format!("`--keep`: `{name}` is named twice"))
                    .with_hint("name each definition to keep once")
                    .with_kind(crate::diag::ErrorKind::bad_option("--keep")),
            );
        }
        match decl.definitions.iter().position(|d| d.0.name == *name) {
            Some(i) if decl.definitions[i].2.is_none() => ev.kept_by_name[i] = true,
            _ => {
                return Err(Diagnostic::global(format!(
                    "`--keep {name}`: the scene has no definition `{name}` to keep"
                ))
                .with_hint(
                    "keep names the scene defines with `NAME = …` (not energies or other roles)",
                )
                .with_kind(crate::diag::ErrorKind::bad_option("--keep")))
            }
        }
    }
    Ok(())
}

/// What a scene read with its kinematics kept may not have: the
/// statements whose derivation needs expanded values.
fn structure_allowed(stmts: &[Stmt]) -> Result<(), Diagnostic> {
    for st in stmts {
        let what = match st {
            Stmt::Constraint { .. } => "constraints",
            Stmt::Reaction { .. } => "reactions",
            Stmt::Joint(_) | Stmt::Drive { .. } => "joints and drives",
            Stmt::Functions(..) => "given functions of time",
            _ => continue,
        };
        return Err(Diagnostic::error(
            st.span(),
            format!("a scene with {what} is derived expanded, not through intermediates"),
        )
        .with_hint("drop `--structured`: qdot expands this scene")
        .with_kind(crate::diag::ErrorKind::Unsupported));
    }
    Ok(())
}

/// A role's value must be a number of the coordinates, velocities,
/// parameters and t: no vector, no `solve` unknown, no acceleration.
fn role_value_allowed(
    role: Role,
    name: &ast::Ident,
    body: &ast::Expr,
    value: &Value,
) -> Result<(), Diagnostic> {
    let e = match value {
        v @ (Value::Vector(_) | Value::Rotation(_)) => return Err(Diagnostic::error(
            body.span,
            format!(
                "`{} {}` must be a number, but this is {}",
                role.keyword(),
                name.name,
                v.describe()
            ),
        )
        .with_hint(match role {
            Role::Kinetic => "the kinetic energy of a point with velocity v is 1/2*m*dot(v, v)",
            _ => {
                "energies, work and dissipation are numbers; use dot(F, r) for the work of a force"
            }
        })
        .with_kind(crate::diag::ErrorKind::TypeMismatch)),
        Value::Scalar(e) => e,
    };
    if let Some(u) = first_unknown(e) {
        return Err(Diagnostic::error(
            body.span,
            format!(
                "`{} {}` uses `{u}`, an unknown of a `solve` block",
                role.keyword(),
                name.name
            ),
        )
        .with_hint("energies are functions of the coordinates and parameters; unknowns belong in `solve` equations").with_kind(crate::diag::ErrorKind::InvalidScene));
    }
    if let Some(acc) = energy_acceleration(role, e) {
        let at = second_prime_span(body).unwrap_or(body.span);
        return Err(Diagnostic::error(
            at,
            format!(
                "`{} {}` depends on the acceleration {acc}",
                role.keyword(),
                name.name
            ),
        )
        .with_hint("energies and the Lagrangian are functions of the coordinates, the velocities and t (Lagrange's equations would differentiate an acceleration into a third derivative); a force that depends on an acceleration is a `force` or a `load`").with_kind(crate::diag::ErrorKind::InvalidScene));
    }
    let what = format!("`{} {}`", role.keyword(), name.name);
    forces_in_order(std::slice::from_ref(e), body.span, &what)
}

impl Resolver<'_> {
    /// Does `e` change with some coordinate?
    fn moves(&self, e: &Expr) -> bool {
        self.coordinate_vars.iter().any(|&q| e.depends_on(q))
    }

    /// The `force q: Q` statements, in order.
    fn forces(&mut self, asts: &[(&ast::Ident, &ast::Expr)]) -> Result<Vec<Force>, Diagnostic> {
        let mut forces = Vec::new();
        for &(c, value) in asts {
            let Some(k) = self.coordinates.iter().position(|x| x.name == c.name) else {
                let mut d = Diagnostic::error(
                    c.span,
                    format!(
                        "`force {}:` needs a coordinate, and `{}` is not one",
                        c.name, c.name
                    ),
                )
                .with_kind(crate::diag::ErrorKind::InvalidScene);
                let list: Vec<&str> = self.coordinates.iter().map(|c| c.name.as_str()).collect();
                d = d.with_hint(if list.is_empty() {
                    "declare it with `coordinates …`".to_string()
                } else {
                    format!("the coordinates are {}", list.join(", "))
                });
                return Err(d);
            };
            let v = self.ev.expr(value)?;
            no_unknowns(std::slice::from_ref(&v), value.span, "a generalized force")?;
            forces_in_order(std::slice::from_ref(&v), value.span, "a generalized force")?;
            forces.push(Force {
                coordinate: k,
                value: v,
                span: value.span,
            });
        }
        Ok(forces)
    }

    /// `load F at P`: a force and its point, both numbers or both vectors
    /// of one size.
    fn load(&mut self, force: &ast::Expr, point: &ast::Expr, span: Span) -> Result<(), Diagnostic> {
        let f = self.ev.value(force)?;
        let p = self.ev.value(point)?;
        for (v, e, what) in [(&f, force, "force"), (&p, point, "point")] {
            if let Value::Rotation(_) = v {
                return Err(Diagnostic::error(
                    e.span,
                    format!("a load's {what} is a vector or a number, and this is a rotation"),
                )
                .with_hint(
                    "axis(F, k) is the k-th unit vector of a frame F: `load -m*g*axis(B, 3) at P`",
                )
                .with_kind(crate::diag::ErrorKind::TypeMismatch));
            }
        }
        match (&f, &p) {
            (Value::Vector(a), Value::Vector(b)) if a.len() != b.len() => {
                return Err(Diagnostic::error(
                    span,
                    format!(
                        "the force has {} components and the point {}",
                        a.len(),
                        b.len()
                    ),
                )
                .with_hint("write both in the plane [x, y] or both in space [x, y, z]").with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
            (Value::Scalar(_), Value::Vector(_)) | (Value::Vector(_), Value::Scalar(_)) => {
                return Err(Diagnostic::error(
                    span,
                    format!(
                        "the force is {} but the point is {}",
                        f.describe(),
                        p.describe()
                    ),
                )
                .with_hint("a vector force needs a position vector `load [Fx, Fy] at [x, y]`; a number needs a displacement along its line `load G at y1`").with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
            _ => {}
        }
        no_unknowns(f.components(), force.span, "a load")?;
        no_unknowns(p.components(), point.span, "a load's point")?;
        forces_in_order(f.components(), force.span, "a load")?;
        positions_only(p.components(), point.span, "a load's point")?;
        if !p.components().iter().any(|e| self.moves(e)) {
            self.warnings.push(
                Diagnostic::warning(point.span, "this load does no virtual work: its point does not move with any coordinate")
                    .with_hint("a force at a fixed point (a reaction of a support) does not enter the generalized forces; check the point's definition"),
            );
        }
        self.loads.push(Load {
            force: f,
            point: p,
            span,
        });
        Ok(())
    }

    /// `torque M on φ`: two numbers.
    fn torque(
        &mut self,
        moment: &ast::Expr,
        angle: &ast::Expr,
        span: Span,
    ) -> Result<(), Diagnostic> {
        let m = match self.ev.value(moment)? {
            Value::Scalar(m) => m,
            m @ (Value::Vector(_) | Value::Rotation(_)) => return Err(Diagnostic::error(
                moment.span,
                format!(
                    "a torque is a number (the moment about the axis of its angle), found {}",
                    m.describe()
                ),
            )
            .with_hint(
                "in the plane write the moment's z component, e.g. cross(r, F) of plane vectors",
            )
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
        };
        let a = match self.ev.value(angle)? {
            Value::Scalar(a) => a,
            a @ (Value::Vector(_) | Value::Rotation(_)) => {
                return Err(Diagnostic::error(
                    angle.span,
                    format!(
                        "a torque acts on an angle (a number), found {}",
                        a.describe()
                    ),
                )
                .with_hint("write `torque M on theta` with theta an angle of the scene")
                .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        no_unknowns(std::slice::from_ref(&m), moment.span, "a torque")?;
        no_unknowns(std::slice::from_ref(&a), angle.span, "a torque's angle")?;
        forces_in_order(std::slice::from_ref(&m), moment.span, "a torque")?;
        positions_only(std::slice::from_ref(&a), angle.span, "a torque's angle")?;
        if !self.moves(&a) {
            self.warnings.push(
                Diagnostic::warning(angle.span, "this torque does no virtual work: its angle does not change with any coordinate")
                    .with_hint("check the angle's definition"),
            );
        }
        self.torques.push(Torque {
            moment: m,
            angle: a,
            span,
        });
        Ok(())
    }

    /// A `solve` block: each equation a residual, a vector equation one
    /// residual per component.
    fn solve_block(
        &mut self,
        block: &ast::SolveBlock,
        unknowns: Vec<Parameter>,
    ) -> Result<(), Diagnostic> {
        let mut equations = Vec::new();
        for eq in &block.equations {
            let l = self.ev.value(&eq.lhs)?;
            let r = self.ev.value(&eq.rhs)?;
            for (v, side) in [(&l, &eq.lhs), (&r, &eq.rhs)] {
                if let Value::Rotation(_) = v {
                    return Err(Diagnostic::error(
                        side.span,
                        "a `solve` equation is between numbers or vectors, and this is a rotation",
                    )
                    .with_hint(
                        "compare a frame's axes or components instead: axis(B, 3) = [0, 0, 1]",
                    )
                    .with_kind(crate::diag::ErrorKind::TypeMismatch));
                }
            }
            for side in [&l, &r] {
                forces_in_order(side.components(), eq.span, "a `solve` equation")?;
            }
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
                    .with_hint("a vector equation needs vectors of one size on both sides, e.g. `[Fx, Fy] = m*a`; write `[0, 0]` for the zero vector").with_kind(crate::diag::ErrorKind::TypeMismatch))
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
        self.systems.push(SolveSystem {
            unknowns,
            equations,
            span: block.span,
        });
        Ok(())
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
        .with_hint("loads, torques and forces enter the equations of motion, which are solved before the blocks; a reaction found by a block can't drive the motion").with_kind(crate::diag::ErrorKind::InvalidScene)),
        None => Ok(()),
    }
}

/// The name of the first `solve` unknown an expression uses, if any.
/// The first acceleration (a coordinate's derivative of order ≥ 2, as
/// `x''`) in `e`, when `e` is a role's expression that must not have one:
/// every role but `work`, whose inertia forces carry accelerations in
/// D'Alembert's form (and are checked as forces, [`forces_in_order`]).
fn energy_acceleration(role: Role, e: &Expr) -> Option<String> {
    if role == Role::Work {
        return None;
    }
    derivative_past(std::slice::from_ref(e), 1).map(|(d, _)| d)
}

/// The highest time derivative in `es`, written as `x'''`, with its
/// order, when that order passes `max`.
fn derivative_past(es: &[Expr], max: u32) -> Option<(String, u32)> {
    es.iter()
        .filter_map(Expr::highest_time_derivative)
        .max_by_key(|(_, k)| *k)
        .filter(|(_, k)| *k > max)
        .map(|(n, k)| (format!("{n}{}", "'".repeat(k as usize)), k))
}

/// An error when a force (`what`) depends on a derivative past the
/// acceleration: Lagrange's equations are of second order, and a third
/// derivative would be left in them as if it were a constant.
fn forces_in_order(es: &[Expr], span: Span, what: &str) -> Result<(), Diagnostic> {
    match derivative_past(es, 2) {
        Some((d, k)) => Err(Diagnostic::error(
            span,
            format!("{what} depends on {d}, a time derivative of order {k}"),
        )
        .with_hint("forces depend on the coordinates, the velocities and t, and (D'Alembert's inertia forces) on the accelerations; the equations of motion are of second order").with_kind(crate::diag::ErrorKind::InvalidScene)),
        None => Ok(()),
    }
}

/// An error when a point of application (`what`) moves with a velocity or
/// an acceleration: virtual work takes δr = Σ ∂r/∂q_k·δq_k at fixed
/// velocities, which such a point would make wrong.
fn positions_only(es: &[Expr], span: Span, what: &str) -> Result<(), Diagnostic> {
    match derivative_past(es, 0) {
        Some((d, _)) => Err(Diagnostic::error(
            span,
            format!(
                "{what} depends on {d}; it must be a position, a function of the coordinates and t"
            ),
        )
        .with_hint("a force that depends on the velocities goes in the force: `load -c*r' at r`")
        .with_kind(crate::diag::ErrorKind::InvalidScene)),
        None => Ok(()),
    }
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
            K::Bin(_, a, b) | K::Assign(a, b) | K::Index(a, b) => {
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
