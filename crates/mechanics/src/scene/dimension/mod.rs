//! Dimensions: every sum adds like quantities, every energy is an energy.
//!
//! A scene may annotate its coordinates and parameters (`r: length`,
//! `k: force/length`); as soon as one is annotated, [`check`] runs when the
//! scene is built. It gives every undeclared name an unknown dimension,
//! walks every statement's syntax tree (so an error points at the term that
//! makes it), infers what the scene determines and reports the first
//! contradiction with both dimensions and, where one fix is likely, a hint.
//! Dimensions are exact: vectors of rational exponents over mass, length,
//! time, charge and temperature.
//!
//! **Invariant:** the check runs after the scene resolved, so every name is
//! declared, there are no cycles among definitions and every call has its
//! arguments; it only adds errors, never changes a value.

mod annotation;
mod call;
mod dim;
mod form;
mod hint;
mod statements;
mod walk;

pub use dim::{
    dimension_named, Dimension, DimensionName, DimensionNameKind, BASE_DIMENSIONS, DIMENSION_NAMES,
};

use crate::diag::{Diagnostic, Span};
use crate::num::Q;
use crate::parse::ast::{self, Role, Stmt};
use form::DimForm;
use rustc_hash::{FxHashMap, FxHashSet};
use walk::{NameDim, Walker};

/// What kind of name a [`NamedDimension`] is of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DimensionedName {
    /// A generalized coordinate.
    Coordinate,
    /// A parameter.
    Parameter,
    /// A given function of time.
    Function,
    /// A definition (role statements included).
    Definition,
    /// A `solve` unknown.
    Unknown,
}

/// How a name's dimension became known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DimensionSource {
    /// Annotated in its declaration (the annotation as written, e.g.
    /// `N*m/rad`).
    Declared(String),
    /// Found from the expression at this span.
    Inferred(Span),
    /// The dimension of its definition's expression.
    Defined,
    /// Nothing in the scene decides it (it stays relative to other names'
    /// dimensions).
    Free,
}

/// The dimension of one name of the scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NamedDimension {
    /// The name.
    pub name: String,
    /// Coordinate, parameter, definition or `solve` unknown.
    pub kind: DimensionedName,
    /// Its dimension, when the scene decides it (a vector's components
    /// share it).
    pub dimension: Option<Dimension>,
    /// Where the scene leaves the dimension undecided: how it depends on
    /// the free ones (`dim(x)·length`), or `free`.
    pub relative: Option<String>,
    /// Declared, inferred, defined or free.
    pub source: DimensionSource,
}

/// The dimensions of a scene's names, in declaration order (coordinates,
/// parameters, `solve` unknowns, then definitions in source order).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DimensionReport {
    /// Every name with its dimension.
    pub names: Vec<NamedDimension>,
}

impl NamedDimension {
    /// The dimension as text: `length`, `force·length²`, `dim(x)·length`
    /// when it depends on a free one, `free`.
    pub fn text(&self) -> String {
        match (&self.dimension, &self.relative) {
            (Some(d), _) => d.unicode(),
            (None, Some(r)) => r.clone(),
            (None, None) => "any (zero)".into(),
        }
    }
}

impl DimensionReport {
    /// The dimension of `name`, if the scene decides it.
    pub fn of(&self, name: &str) -> Option<&Dimension> {
        self.names
            .iter()
            .find(|n| n.name == name)
            .and_then(|n| n.dimension.as_ref())
    }

    /// The names of one kind, in order.
    pub fn kind(&self, kind: DimensionedName) -> impl Iterator<Item = &NamedDimension> {
        self.names.iter().filter(move |n| n.kind == kind)
    }
}

/// Whether any declaration carries a dimension annotation.
pub fn annotated(stmts: &[Stmt]) -> bool {
    stmts.iter().any(|s| match s {
        Stmt::Coordinates(ds, _) | Stmt::Parameters(ds, _) | Stmt::Functions(ds, _) => {
            ds.iter().any(|d| d.dimension.is_some())
        }
        _ => false,
    })
}

/// Check the dimensions of a resolved scene's statements; `constant` gives
/// a definition's value when it is a rational number (for exponents).
pub fn check(
    src: &str,
    stmts: &[Stmt],
    constant: &dyn Fn(&str) -> Option<Q>,
) -> Result<DimensionReport, Diagnostic> {
    check_with(src, stmts, constant, true)
}

/// [`check`] without building the report: what every command runs on an
/// annotated scene.
pub fn validate(
    src: &str,
    stmts: &[Stmt],
    constant: &dyn Fn(&str) -> Option<Q>,
) -> Result<(), Diagnostic> {
    check_with(src, stmts, constant, false).map(|_| ())
}

fn check_with(
    src: &str,
    stmts: &[Stmt],
    constant: &dyn Fn(&str) -> Option<Q>,
    with_report: bool,
) -> Result<DimensionReport, Diagnostic> {
    // Definitions in source order first: scenes rarely refer forward, and
    // the dependency order costs a second walk of every definition.
    match attempt(src, stmts, constant, false, with_report) {
        Ok(Some(r)) => Ok(r),
        Err((e, false)) => Err(e),
        Ok(None) | Err((_, true)) => match attempt(src, stmts, constant, true, with_report) {
            Ok(r) => Ok(r.unwrap_or_default()),
            Err((e, _)) => Err(e),
        },
    }
}

/// A name of the report: its kind, and its annotation's span (`Some(None)`
/// for a name not annotated, `None` for a definition).
type ReportRow<'a> = (&'a str, DimensionedName, Option<Option<Span>>);

/// One pass over the statements, definitions in source order or in
/// dependency order: the report, or `None` (or an error marked `true`)
/// when a definition in source order used one not checked yet.
fn attempt(
    src: &str,
    stmts: &[Stmt],
    constant: &dyn Fn(&str) -> Option<Q>,
    by_dependency: bool,
    with_report: bool,
) -> Result<Option<DimensionReport>, (Diagnostic, bool)> {
    let mut w = Walker {
        src,
        vars: form::DimVars::default(),
        names: FxHashMap::default(),
        coordinates: FxHashSet::default(),
        defs: Vec::new(),
        constant,
        forward: false,
        origins: FxHashMap::default(),
    };
    let forward = |w: &Walker| !by_dependency && w.forward;
    match walk_statements(&mut w, stmts, by_dependency) {
        Ok(_) if forward(&w) => Ok(None),
        Ok(order) if with_report => Ok(Some(report(&mut w, &order))),
        Ok(_) => Ok(Some(DimensionReport::default())),
        Err(e) => {
            let f = forward(&w);
            Err((e, f))
        }
    }
}

/// The names in report order, after checking every statement.
fn walk_statements<'a>(
    w: &mut Walker<'a>,
    stmts: &'a [Stmt],
    by_dependency: bool,
) -> Result<Vec<ReportRow<'a>>, Diagnostic> {
    let mut order: Vec<ReportRow> = Vec::with_capacity(stmts.len() + 8);
    let mut definitions: Vec<(&ast::Ident, &ast::Expr, Option<Role>)> =
        Vec::with_capacity(stmts.len());
    w.names.reserve(stmts.len() + 8);
    for st in stmts {
        match st {
            Stmt::Coordinates(ds, _) | Stmt::Parameters(ds, _) | Stmt::Functions(ds, _) => {
                let kind = match st {
                    Stmt::Coordinates(..) => {
                        w.coordinates
                            .extend(ds.iter().map(|d| d.name.name.as_str()));
                        DimensionedName::Coordinate
                    }
                    Stmt::Functions(..) => DimensionedName::Function,
                    _ => DimensionedName::Parameter,
                };
                for d in ds {
                    let n = d.name.name.as_str();
                    let f = match &d.dimension {
                        Some(e) => DimForm::known(annotation::dimension_of(e)?),
                        None => DimForm::var(w.vars.fresh(n)),
                    };
                    w.names.insert(n, NameDim::Fixed(f));
                    if let Some(e) = &d.dimension {
                        w.origins.insert(n, e.span);
                    }
                    order.push((n, kind, Some(d.dimension.as_ref().map(|e| e.span))));
                }
            }
            Stmt::Def { name, value, .. } | Stmt::Frame { name, value, .. } => {
                definitions.push((name, value, None))
            }
            Stmt::Role {
                role, name, value, ..
            } => definitions.push((name, value, Some(*role))),
            Stmt::Solve(b) => {
                for u in &b.unknowns {
                    let n = u.name.as_str();
                    let v = w.vars.fresh(n);
                    w.names.insert(n, NameDim::Fixed(DimForm::var(v)));
                    order.push((n, DimensionedName::Unknown, Some(None)));
                }
            }
            _ => {}
        }
    }
    for (i, (name, _, _)) in definitions.iter().enumerate() {
        w.names.insert(name.name.as_str(), NameDim::Def(i));
        w.origins.insert(name.name.as_str(), name.span);
        order.push((name.name.as_str(), DimensionedName::Definition, None));
    }
    w.names.insert("t", NameDim::Time);
    w.names.insert("pi", NameDim::Pi);
    w.defs = vec![None; definitions.len()];
    let sequence = if by_dependency {
        dependency_order(&w.names, &definitions)
    } else {
        (0..definitions.len()).collect()
    };
    for i in sequence {
        let (name, body, role) = definitions[i];
        let want = role.map(|r| statements::role_want(r, &name.name));
        let v = w.value(body, want.as_ref())?;
        w.defs[i] = Some(v);
    }
    for st in stmts {
        match st {
            Stmt::Force {
                coordinate, value, ..
            } => statements::force(w, coordinate, value)?,
            Stmt::Load { force, point, .. } => statements::load(w, force, point)?,
            Stmt::Torque { moment, angle, .. } => statements::torque(w, moment, angle)?,
            Stmt::Solve(b) => statements::solve_block(w, b)?,
            Stmt::Body(b) => statements::body(w, b)?,
            Stmt::Gravity { value, .. } => statements::gravity(w, value)?,
            Stmt::Assume(facts, _) => statements::assumption(w, facts)?,
            Stmt::Constraint { equation, .. } => statements::constraint(w, equation)?,
            _ => {}
        }
    }
    Ok(order)
}

/// The definitions in an order where each comes after those it uses
/// (depth first, with an explicit stack: chains of definitions are as
/// long as a scene is).
fn dependency_order(
    names: &FxHashMap<&str, NameDim>,
    definitions: &[(&ast::Ident, &ast::Expr, Option<Role>)],
) -> Vec<usize> {
    let uses = |i: usize| -> Vec<usize> {
        let mut out = Vec::new();
        walk::for_each_name(&[definitions[i].1], |n| {
            if let Some(NameDim::Def(j)) = names.get(n) {
                out.push(*j);
            }
        });
        out
    };
    let mut state = vec![0u8; definitions.len()]; // 0 new, 1 open, 2 done
    let mut order = Vec::with_capacity(definitions.len());
    for root in 0..definitions.len() {
        if state[root] != 0 {
            continue;
        }
        let mut stack: Vec<(usize, Vec<usize>)> = vec![(root, uses(root))];
        state[root] = 1;
        while let Some((i, pending)) = stack.last_mut() {
            match pending.pop() {
                Some(j) if state[j] == 0 => {
                    state[j] = 1;
                    let next = uses(j);
                    stack.push((j, next));
                }
                Some(_) => {}
                None => {
                    let i = *i;
                    state[i] = 2;
                    order.push(i);
                    stack.pop();
                }
            }
        }
    }
    order
}

fn report(w: &mut Walker, order: &[ReportRow]) -> DimensionReport {
    let mut names = Vec::with_capacity(order.len());
    for &(name, kind, ref declared) in order {
        let value = w.name(name);
        let form = value
            .components()
            .iter()
            .flatten()
            .next()
            .map(|f| w.vars.normalize(f));
        let dimension = form.as_ref().and_then(|f| f.as_known().cloned());
        let source = match (declared, &dimension) {
            (Some(Some(at)), _) => DimensionSource::Declared(w.src[at.start..at.end].to_string()),
            (None, _) => DimensionSource::Defined,
            (Some(None), Some(_)) => match w.unknown_of(name).and_then(|v| w.vars.solution(v)) {
                Some(s) => DimensionSource::Inferred(s.at),
                None => DimensionSource::Free,
            },
            (Some(None), None) => DimensionSource::Free,
        };
        let relative = match &form {
            Some(_) if dimension.is_some() => None,
            Some(f) => Some(match w.unknown_of(name) {
                Some(v) if f == &DimForm::var(v) => "free".to_string(),
                _ => w.vars.unicode(f),
            }),
            None => None,
        };
        names.push(NamedDimension {
            name: name.to_string(),
            kind,
            dimension,
            relative,
            source,
        });
    }
    DimensionReport { names }
}
