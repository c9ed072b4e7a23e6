//! Scenes: the parsed statements resolved into exact expressions.
//!
//! [`Scene::parse`] runs the parser, checks the declarations (no name
//! declared twice, `t` and `pi` reserved), evaluates every definition lazily
//! in dependency order (forward references allowed, cycles reported with
//! the whole cycle), and collects the role statements. Every error is a
//! [`Diagnostic`] pointing into the source.

mod eval;

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

/// A named expression.
#[derive(Clone, Debug)]
pub struct Definition {
    pub name: String,
    pub value: Expr,
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

/// A resolved scene.
#[derive(Clone, Debug)]
pub struct Scene {
    pub source: String,
    pub coordinates: Vec<Coordinate>,
    pub parameters: Vec<Parameter>,
    /// Definitions (including role statements) in source order.
    pub definitions: Vec<Definition>,
    pub forces: Vec<Force>,
    /// Things worth a look that do not stop the computation.
    pub warnings: Vec<Diagnostic>,
}

/// What a name means.
#[derive(Clone, Debug)]
pub(crate) enum Binding {
    Param,
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
            if let Some((prev, _)) = names.get(&name.name) {
                let what = match prev {
                    Binding::Param => "a parameter",
                    Binding::Coord => "a coordinate",
                    _ => "defined",
                };
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
                Stmt::Load { .. } | Stmt::Torque { .. } | Stmt::Solve(_) => {}
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
        for (i, (name, _, role)) in def_asts.iter().enumerate() {
            let value = ev.definition(i)?;
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
            forces.push(Force {
                coordinate: k,
                value: v,
                span: value.span,
            });
        }
        let mut warnings = ev.warnings;
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
            warnings,
        })
    }

    /// Evaluate an expression written in the scene's names (its parameters,
    /// coordinates with primes, definitions, `t`, `pi`).
    pub fn expr(&self, src: &str) -> Result<Expr, Diagnostic> {
        let e = crate::parse::parse_expr(src)?;
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
        let values: Vec<Expr> = self.definitions.iter().map(|d| d.value.clone()).collect();
        let mut ev = eval::Evaluator::with_values(&names, values);
        ev.expr(&e)
    }

    /// The definitions playing `role`, in source order.
    pub fn role(&self, role: Role) -> impl Iterator<Item = &Definition> {
        self.definitions
            .iter()
            .filter(move |d| d.role == Some(role))
    }

    /// The sum of all definitions playing `role` (zero if none).
    pub fn role_sum(&self, role: Role) -> Expr {
        self.role(role)
            .fold(Expr::zero(), |acc, d| acc.add(&d.value))
    }

    /// Whether any statement plays `role`.
    pub fn has_role(&self, role: Role) -> bool {
        self.role(role).next().is_some()
    }

    /// The value of a definition by name.
    pub fn definition(&self, name: &str) -> Option<&Expr> {
        self.definitions
            .iter()
            .find(|d| d.name == name)
            .map(|d| &d.value)
    }
}
