//! Scenes: the parsed statements resolved into exact expressions.
//!
//! [`Scene::parse`] runs the parser, checks the declarations (no name
//! declared twice, `t` and `pi` reserved), evaluates the definitions the
//! statements use in dependency order (forward references allowed, cycles
//! reported with the whole cycle; the others are checked and evaluated when
//! small or asked for, see `lazy`), and collects the role statements,
//! loads, torques and `solve` blocks. Values are scalars or vectors ([`Value`]). Every error is
//! a [`Diagnostic`] pointing into the source.

pub mod dimension;
mod eval;
pub mod given;
mod lazy;
pub mod mechanism;
mod resolve;
pub mod rotation;
mod structure;

pub use eval::{axis_name, is_taylor_form};
pub use lazy::DeferredDefinition;

use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::parse::ast::{self, Role, Span, Stmt};
pub use rotation::Rotation;
pub use structure::Structure;

/// A generalized coordinate.
#[derive(Clone, Debug)]
pub struct Coordinate {
    /// The name as declared.
    pub name: String,
    /// Where it is declared.
    pub span: Span,
    /// The dimension annotation as written (`length` in `x: length`), if any.
    pub dimension: Option<String>,
}

/// A given function of time (`functions s`): prescribed, not a coordinate;
/// its derivatives stay symbolic, and `simulate` needs its definition.
#[derive(Clone, Debug)]
pub struct GivenFunction {
    /// The name as declared.
    pub name: String,
    /// Where it is declared.
    pub span: Span,
    /// The dimension annotation as written, if any.
    pub dimension: Option<String>,
}

/// A constant symbol.
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The name as declared.
    pub name: String,
    /// Where it is declared.
    pub span: Span,
    /// The dimension annotation as written (`force/length` in
    /// `k: force/length`), if any; [`Scene::dimension_report`] has its meaning.
    pub dimension: Option<String>,
}

/// The value of a definition: a scalar expression, a vector of them, or
/// a rotation (a frame's orientation).
#[derive(Clone, Debug)]
pub enum Value {
    /// A single expression.
    Scalar(Expr),
    /// A plane (2) or space (3) vector.
    Vector(Vec<Expr>),
    /// A rotation: `rot(z, phi) * rot(x, theta)`, a `frame`.
    Rotation(Box<Rotation>),
}

impl Value {
    /// The scalar, if this is one.
    pub fn as_scalar(&self) -> Option<&Expr> {
        match self {
            Value::Scalar(e) => Some(e),
            Value::Vector(_) | Value::Rotation(_) => None,
        }
    }
    /// The components: one for a scalar, the nine entries of a rotation's
    /// matrix row by row.
    pub fn components(&self) -> &[Expr] {
        match self {
            Value::Scalar(e) => std::slice::from_ref(e),
            Value::Vector(c) => c,
            Value::Rotation(r) => r.entries(),
        }
    }
    /// Apply `f` to every component of a number or a vector; a rotation
    /// is returned as it is (the evaluator refuses to negate,
    /// differentiate or substitute into a rotation before it gets here).
    pub fn map(&self, mut f: impl FnMut(&Expr) -> Expr) -> Value {
        match self {
            Value::Scalar(e) => Value::Scalar(f(e)),
            Value::Vector(c) => Value::Vector(c.iter().map(f).collect()),
            Value::Rotation(r) => Value::Rotation(r.clone()),
        }
    }
    /// "a number" / "a vector with 2 components" / "a rotation", for messages.
    pub fn describe(&self) -> String {
        match self {
            Value::Scalar(_) => "a number".into(),
            Value::Vector(c) => format!("a vector with {} components", c.len()),
            Value::Rotation(_) => "a rotation (a frame)".into(),
        }
    }
}

/// A named expression.
#[derive(Clone, Debug)]
pub struct Definition {
    /// The defined name.
    pub name: String,
    /// The evaluated right-hand side.
    pub value: Value,
    /// Where the name is written.
    pub span: Span,
    /// The role, for `kinetic E1 = …` and the like.
    pub role: Option<Role>,
}

/// A generalized force added to one coordinate's Q.
#[derive(Clone, Debug)]
pub struct Force {
    /// The index of the coordinate q_k in [`Scene::coordinates`].
    pub coordinate: usize,
    /// The generalized force Q_k it adds.
    pub value: Expr,
    /// Where the force's expression is written.
    pub span: Span,
}

/// `load F at P`: a force applied at a point (both vectors of one size,
/// or both scalars: a force along the line of a scalar displacement).
#[derive(Clone, Debug)]
pub struct Load {
    /// The force F: a vector, or a scalar along the line of the displacement.
    pub force: Value,
    /// The point of application: a position vector of the force's size, or a
    /// scalar displacement.
    pub point: Value,
    /// The whole `load` statement.
    pub span: Span,
}

/// `torque M on phi`: a moment doing work on an angle.
#[derive(Clone, Debug)]
pub struct Torque {
    /// The moment M about the axis of the angle.
    pub moment: Expr,
    /// The angle it does work on, a function of the coordinates and t.
    pub angle: Expr,
    /// The whole `torque` statement.
    pub span: Span,
}

/// One scalar equation of a `solve` block, as `lhs − rhs = 0`.
#[derive(Clone, Debug)]
pub struct SystemEquation {
    /// `lhs − rhs` of the equation (of one component, for a vector equation).
    pub residual: Expr,
    /// Where the equation is written.
    pub span: Span,
    /// For a vector equation, which component (0-based) this is.
    pub component: Option<usize>,
}

/// A `solve` block: unknowns and the equations that determine them.
#[derive(Clone, Debug)]
pub struct SolveSystem {
    /// The unknowns after `solve`, in order.
    pub unknowns: Vec<Parameter>,
    /// The scalar equations, a vector equation contributing one per component.
    pub equations: Vec<SystemEquation>,
    /// From `solve` to the closing `}`.
    pub span: Span,
}

/// A `body` or `particle` statement: its energies are the definitions
/// `E_NAME` (kinetic) and, with `gravity`, `V_NAME` (potential).
#[derive(Clone, Debug)]
pub struct Body {
    /// The body's name.
    pub name: String,
    /// `body` or `particle`.
    pub kind: ast::BodyKind,
    /// The whole statement.
    pub span: Span,
    /// The name of its kinetic energy among the definitions.
    pub kinetic: String,
    /// The name of gravity's potential on it, when the scene has gravity.
    pub gravity: Option<String>,
    /// What its kinetic energy is made of, for the recursive dynamics of
    /// a tree of bodies (`mechanics::articulated`).
    pub mass_properties: MassProperties,
}

/// A body's mass, centre and turning, as its statement gives them: the
/// kinetic energy ½·m·|ċ|² + ½·ωᵀ·I·ω read as a rigid body's.
#[derive(Clone, Debug)]
pub struct MassProperties {
    /// The mass, a positive constant; 0 for a body written without one
    /// (its centre is then fixed).
    pub mass: Expr,
    /// The centre of mass: 2 (plane) or 3 (space) components.
    pub centre: Vec<Expr>,
    /// How it turns; `None` for a particle (or a body without inertia).
    pub turning: Option<Turning>,
    /// The acceleration of gravity on it (the `gravity` statement), if any.
    pub gravity: Option<Vec<Expr>>,
}

/// How a rigid body turns, with its inertia about the centre of mass.
#[derive(Clone, Debug)]
pub enum Turning {
    /// In space: its frame (body axes in ground coordinates) and its
    /// inertia tensor along the body's axes.
    Space {
        /// The frame.
        frame: Box<Rotation>,
        /// The inertia tensor in the body's axes.
        inertia: [[Expr; 3]; 3],
    },
    /// In the plane: its angle and moment of inertia.
    Plane {
        /// The angle from the ground's x axis.
        angle: Expr,
        /// The moment of inertia about the centre.
        inertia: Expr,
    },
}

/// A resolved scene (`Scene::default()` is the empty scene).
///
/// Invariant (checked by the resolver): energies and the Lagrangian
/// depend on the coordinates, the velocities and t; forces, loads,
/// torques, `work` and `solve` equations at most on the accelerations;
/// points of application and torque angles on the coordinates and t only.
/// So the mechanics never meets a third derivative, and "at rest" is
/// q̇ = q̈ = 0.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The scene's source text (spans point into it).
    pub source: String,
    /// The generalized coordinates q, in declaration order.
    pub coordinates: Vec<Coordinate>,
    /// The parameters (constant symbols), in declaration order.
    pub parameters: Vec<Parameter>,
    /// The given functions of time, in declaration order.
    pub functions: Vec<GivenFunction>,
    /// The evaluated definitions (including role statements), in source
    /// order: those the scene's statements use, and unused ones small
    /// enough to check.
    pub definitions: Vec<Definition>,
    /// The definitions nothing uses, left unevaluated (too large to
    /// evaluate when the scene was read, or failing, which a warning
    /// reports), in source order: [`Scene::value`] evaluates one when
    /// asked.
    pub deferred: Vec<DeferredDefinition>,
    /// The `force q: Q` statements, in source order.
    pub forces: Vec<Force>,
    /// The `load F at P` statements, in source order.
    pub loads: Vec<Load>,
    /// The `torque M on phi` statements, in source order.
    pub torques: Vec<Torque>,
    /// The `solve` blocks, in source order.
    pub systems: Vec<SolveSystem>,
    /// The `body` and `particle` statements, in source order.
    pub bodies: Vec<Body>,
    /// The `gravity` statement, if any.
    pub gravity: Option<Span>,
    /// The `constraint` statements, in source order.
    pub constraints: Vec<Constraint>,
    /// The `reaction` statements, in source order.
    pub reactions: Vec<Reaction>,
    /// The `joint` statements, in source order (their constraints are
    /// among [`Scene::constraints`]).
    pub joints: Vec<mechanism::Joint>,
    /// The `drive` statements, in source order (each one constraint).
    pub drives: Vec<mechanism::Drive>,
    /// What the scene assumes beyond positive parameters (`assume`).
    pub assumptions: crate::algebra::assume::Assumptions,
    /// Things worth a look that do not stop the computation.
    pub warnings: Vec<Diagnostic>,
    /// The `latex NAME = "…"` statements, in source order (a later one for
    /// the same name wins).
    pub latex_names: Vec<LatexName>,
    /// Whether the scene annotates a dimension (`r: length`): it was
    /// checked then ([`dimension::validate`]), and
    /// [`Scene::dimension_report`] gives every name's dimension.
    pub dimensions_checked: bool,
    /// For a scene read by [`Scene::parse_structured`]: the intermediates
    /// its moving vectors and frames are kept as, which its values (and so
    /// the energies of its bodies) mention. `None` for an expanded scene.
    pub tape: Option<crate::expr::tape::Tape>,
}

/// The name of the momentum conjugate to the coordinate `q` (`p_theta`),
/// which `qdot hamilton` writes and expressions outside the scene may use.
pub fn momentum_name(q: &str) -> String {
    format!("p_{q}")
}

/// A `constraint` statement, resolved. At the velocity level it reads
/// Σ a_k·q̇_k + b = 0 (a holonomic g(q, t) = 0 differentiated once), and
/// its multiplier λ adds λ·a_k to the generalized force on q_k.
///
/// Invariant (checked by the resolver): `coefficients` has one entry per
/// coordinate, not all zero; they and `rest` depend on q and t only.
#[derive(Clone, Debug)]
pub struct Constraint {
    /// The name after `constraint`, when one is given.
    pub name: Option<String>,
    /// The multiplier's name: `lambda_NAME`, or `lambdaK` for the K-th
    /// constraint (1-based) when it has no name.
    pub multiplier: String,
    /// True when the constraint has no velocities: g(q, t) = 0.
    pub holonomic: bool,
    /// lhs − rhs as written: g(q, t), or a·q̇ + b.
    pub expression: Expr,
    /// a_k, per coordinate in declaration order.
    pub coefficients: Vec<Expr>,
    /// b.
    pub rest: Expr,
    /// The whole statement.
    pub span: Span,
}

/// `reaction rod at P`: where a constraint's force is asked for.
#[derive(Clone, Debug)]
pub struct Reaction {
    /// The index of the constraint in [`Scene::constraints`].
    pub constraint: usize,
    /// The point's components (one for a displacement along a line), in q
    /// and t.
    pub point: Vec<Expr>,
    /// The point as written.
    pub written: String,
    /// The whole statement.
    pub span: Span,
}

impl Constraint {
    /// How the constraint is named in messages: `rod`, or `#2`.
    pub fn label(&self, index: usize) -> String {
        match &self.name {
            Some(n) => format!("`{n}`"),
            None => format!("#{}", index + 1),
        }
    }
}

/// `latex theta3 = "\vartheta_{3}"`: the LaTeX notation of a name.
#[derive(Clone, Debug, PartialEq)]
pub struct LatexName {
    /// The name given notation.
    pub name: String,
    /// The LaTeX text, as written between the quotes.
    pub tex: String,
    /// The whole `latex` statement.
    pub span: Span,
}

/// The `latex` statements, with a warning for a name the scene never
/// declares and for a name given notation twice.
fn latex_names(
    stmts: &[Stmt],
    coordinates: &[Coordinate],
    parameters: &[Parameter],
    defined: &dyn Fn(&str) -> bool,
    systems: &[SolveSystem],
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
            || defined(n)
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
    /// A `body` or `particle` name: not a value.
    Body,
    /// A given function of time.
    Given,
    /// The Lagrange multiplier of a `constraint` (`lambda_rod`): found by
    /// solving, not a value in the scene.
    Multiplier,
    /// A joint's reaction component (`O_x`), a drive's force (`M`) or a
    /// friction (`G_f`): found by solving, not a value in the scene.
    Reaction,
    Time,
    Pi,
}

impl Scene {
    /// Parse and resolve a scene.
    ///
    /// ```
    /// let scene = qdot_mechanics::scene::Scene::parse("coordinates x\nparameters m, k\n\
    ///     kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2").unwrap();
    /// assert_eq!(scene.coordinates[0].name, "x");
    /// ```
    pub fn parse(src: &str) -> Result<Scene, Diagnostic> {
        crate::diag::bounded(|| {
            let stmts = crate::parse::parse_scene(src)?;
            Scene::from_statements(src, &stmts)
        })
    }

    /// Resolve parsed statements (see [`Scene::parse`]).
    pub fn from_statements(src: &str, stmts: &[Stmt]) -> Result<Scene, Diagnostic> {
        crate::diag::bounded(|| resolve::scene_from_statements(src, stmts, false, &[]))
    }

    /// Parse a scene keeping its kinematics structured: every moving vector
    /// and frame it defines becomes named intermediates on
    /// [`Scene::tape`] (`P1_x`, `B2_13`, `omega_B2_x`), and values that use
    /// them mention the names instead of their expansions. A chain of
    /// bodies stays the size of its links; [`crate::mechanics::Lagrange`]
    /// then derives through the tape. Scenes with constraints, reactions
    /// or given functions are refused (the error says so); they are read
    /// by [`Scene::parse`].
    pub fn parse_structured(src: &str) -> Result<Scene, Diagnostic> {
        Scene::parse_keeping(src, &[])
    }

    /// The scene with the definitions named in `keep` kept as intermediates,
    /// and only them (scalars too: `alpha = asin(R*sin(phi)/L)` stays
    /// `alpha`, with its rates `alpha_dot`, `alpha_ddot`); with `keep`
    /// empty, [`Scene::parse_structured`]. An error for a name that is not
    /// a definition of the scene, and for a kept name inside a rotation's
    /// angle.
    pub fn parse_keeping(src: &str, keep: &[String]) -> Result<Scene, Diagnostic> {
        crate::diag::bounded(|| {
            let stmts = crate::parse::parse_scene(src)?;
            resolve::scene_from_statements(src, &stmts, true, keep)
        })
    }

    /// Evaluate an expression written in the scene's names (its parameters,
    /// coordinates with primes, definitions, `t`, `pi`).
    pub fn expr(&self, src: &str) -> Result<Expr, Diagnostic> {
        match self.value_of(src)? {
            Value::Scalar(e) => Ok(e),
            v => Err(
                Diagnostic::global(format!("expected a number, found {}", v.describe()))
                    .with_kind(crate::diag::ErrorKind::TypeMismatch),
            ),
        }
    }

    /// Like [`Scene::expr`], for an expression that may be a vector.
    pub fn value_of(&self, src: &str) -> Result<Value, Diagnostic> {
        crate::diag::bounded(|| {
            let e = crate::parse::parse_expr(src)?;
            Ok(self.evaluate(&e, &[])?.0)
        })
    }

    /// Evaluate a parsed expression in the scene's names, with `extra`
    /// names bound to values (the REPL's `_`): the value and the warnings
    /// (spans point into the text `e` was parsed from).
    pub fn evaluate(
        &self,
        e: &ast::Expr,
        extra: &[(&str, Value)],
    ) -> Result<(Value, Vec<Diagnostic>), Diagnostic> {
        crate::diag::bounded(|| self.evaluate_in_scene(e, extra))
    }

    /// The dimensions of the scene's names, declared or found (for a scene
    /// without annotations, relative to the dimensions it leaves free; a
    /// contradiction is still an error).
    pub fn dimension_report(&self) -> Result<dimension::DimensionReport, Diagnostic> {
        crate::diag::bounded(|| {
            let stmts = crate::parse::parse_scene(&self.source)?;
            let constant = |name: &str| self.definition(name).and_then(Expr::as_rational);
            dimension::check(&self.source, &stmts, &constant)
        })
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
            Value::Vector(_) | Value::Rotation(_) => acc,
        })
    }

    /// An error when the scene was read with its kinematics kept
    /// ([`Scene::parse_structured`]) and has intermediates: `what` works on
    /// expanded values only (an intermediate hides what it depends on).
    pub fn expanded_only(&self, what: &str) -> Result<(), Diagnostic> {
        if self.tape.as_ref().is_some_and(|t| !t.is_empty()) {
            return Err(Diagnostic::global(format!(
                "{what} needs the scene expanded, and it was read with its kinematics kept as intermediates"
            ))
            .with_hint("read it with Scene::parse (the command line does so for every command but derive, solve and simulate)").with_kind(crate::diag::ErrorKind::Unsupported));
        }
        Ok(())
    }

    /// Run `f` with the scene's assumptions (`assume …`) in force: for a
    /// library user who calls the engine's functions (equilibria, modes,
    /// steady motions) directly rather than through `qdot::app`, whose
    /// context installs them.
    pub fn assumptions_in_force<T>(&self, f: impl FnOnce() -> T) -> T {
        crate::algebra::assume::assuming(&self.assumptions, f)
    }

    /// An error unless the scene's assumptions are in force: `what`
    /// decides signs under them, and without them it could decide one for
    /// positive parameters where the scene assumes otherwise.
    pub fn assumptions_required(&self, what: &str) -> Result<(), Diagnostic> {
        let in_force = crate::algebra::assume::in_force(&self.assumptions);
        debug_assert!(in_force, "{what}: the scene's assumptions are not in force");
        if in_force {
            return Ok(());
        }
        Err(Diagnostic::global(format!(
            "{what} needs the scene's assumptions (`assume …`) in force, and they are not"
        ))
        .with_hint("run it through qdot::app, or within Scene::assumptions_in_force")
        .with_kind(crate::diag::ErrorKind::Internal))
    }

    /// Whether any statement plays `role`.
    pub fn has_role(&self, role: Role) -> bool {
        self.role(role).next().is_some()
    }

    /// The value of a scalar definition by name.
    pub fn definition(&self, name: &str) -> Option<&Expr> {
        self.value(name).and_then(Value::as_scalar)
    }

    /// The value of a definition (scalar or vector) by name, a deferred
    /// one evaluated on first ask ([`Scene::try_value`] has its error).
    pub fn value(&self, name: &str) -> Option<&Value> {
        self.try_value(name).and_then(Result::ok)
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

/// The name of the first `solve` unknown an expression uses, if any.
pub fn first_unknown(e: &Expr) -> Option<String> {
    use crate::expr::atom::{self, Atom};
    e.vars().into_iter().find_map(|v| {
        std::iter::once(v)
            .chain(atom::inner_atoms(v).iter().copied())
            .find_map(|w| match atom::atom(w) {
                Atom::Unknown(n) => Some(n.to_string()),
                _ => None,
            })
    })
}
