//! The syntax tree of a `.qd` scene, exactly as written (no evaluation).
//!
//! Every node carries a [`Span`] (byte offsets into the source) so that later
//! stages can point at the offending text. The grammar is `grammar/qd.ebnf`;
//! the parser in `parse/mod.rs` follows it rule by rule.

use num_rational::BigRational;

pub use super::functions::Builtin;
pub use crate::diag::Span;

/// An identifier with its position.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ident {
    /// The name as written.
    pub name: String,
    /// Where it is written.
    pub span: Span,
}

/// A declared name in `coordinates …` or `parameters …`, with an optional
/// dimension annotation (`r: length`, `k: force/length`), interpreted by
/// the scene's dimension check.
#[derive(Clone, Debug, PartialEq)]
pub struct Decl {
    /// The declared name.
    pub name: Ident,
    /// The dimension after the colon (`length` in `r: length`), if any: a
    /// product of dimension names and their powers, written as an expression.
    pub dimension: Option<Expr>,
}

/// The role a named expression plays in Lagrange's equations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// `kinetic` — kinetic energy E.
    Kinetic,
    /// `potential` — potential energy V: Q_k −= ∂V/∂q_k.
    Potential,
    /// `forcefunction` — the book's force function U = −V: Q_k += ∂U/∂q_k.
    ForceFunction,
    /// `work` — work L of non-conservative forces: Q_k += ∂L/∂q_k.
    Work,
    /// `dissipation` — the book's D ≤ 0: Q_k += ∂D/∂q̇_k.
    Dissipation,
    /// `rayleigh` — Rayleigh's R ≥ 0: Q_k −= ∂R/∂q̇_k.
    Rayleigh,
    /// `lagrangian` — a Lagrangian written directly (Landau's L = T − U,
    /// any function of q, q̇, t): it joins E on the left,
    /// d/dt(∂(E + L)/∂q̇_k) − ∂(E + L)/∂q_k = Q_k.
    Lagrangian,
}

impl Role {
    /// The keyword that introduces the role (`kinetic`, `potential`, …).
    pub fn keyword(self) -> &'static str {
        match self {
            Role::Kinetic => "kinetic",
            Role::Potential => "potential",
            Role::ForceFunction => "forcefunction",
            Role::Work => "work",
            Role::Dissipation => "dissipation",
            Role::Rayleigh => "rayleigh",
            Role::Lagrangian => "lagrangian",
        }
    }
    /// The role introduced by a keyword, if `s` is one.
    pub fn from_keyword(s: &str) -> Option<Role> {
        Some(match s {
            "kinetic" => Role::Kinetic,
            "potential" => Role::Potential,
            "forcefunction" => Role::ForceFunction,
            "work" => Role::Work,
            "dissipation" => Role::Dissipation,
            "rayleigh" => Role::Rayleigh,
            "lagrangian" => Role::Lagrangian,
            _ => return None,
        })
    }
}

/// One statement (one logical line) of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// `coordinates y3, theta3`
    Coordinates(Vec<Decl>, Span),
    /// `parameters G, g, r`
    Parameters(Vec<Decl>, Span),
    /// `functions s, u` — given functions of time (a support's motion, a
    /// control input): written `s` or `s(t)`, their derivatives `s'`, `s''`.
    Functions(Vec<Decl>, Span),
    /// `m = G/g`
    Def {
        /// The name being defined.
        name: Ident,
        /// The right-hand side.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `kinetic E1 = 1/2*m*y1'^2`; the name is also an ordinary definition.
    Role {
        /// Which role.
        role: Role,
        /// The name being defined.
        name: Ident,
        /// The right-hand side.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `force theta: M0*cos(t)` — a generalized force on one coordinate.
    Force {
        /// The coordinate q_k whose generalized force Q_k receives the value.
        coordinate: Ident,
        /// The generalized force (after the colon).
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `load F at P` — a force F (vector or scalar) applied at the point P
    /// (a position vector, or a scalar displacement along F's line).
    Load {
        /// The force F (a vector, or a scalar along the line of `point`).
        force: Expr,
        /// The point of application P (a position vector or a scalar displacement).
        point: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `torque M on phi` — a moment M doing work on the angle phi.
    Torque {
        /// The moment M.
        moment: Expr,
        /// The angle it does work on.
        angle: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `solve a, b { lhs = rhs … }` — a system of equations for the unknowns.
    Solve(SolveBlock),
    /// `frame B = rot(z, phi) * rot(x, theta)` — a named rotation: the
    /// orientation of a frame in the ground frame. The name is also an
    /// ordinary definition, whose value must be a rotation.
    Frame {
        /// The frame's name.
        name: Ident,
        /// The rotation.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `body top: mass m, inertia [A, A, C], frame B, at P` or
    /// `particle p: mass m, at P` — its kinetic energy joins E.
    Body(BodyStmt),
    /// `constraint rod: x^2 + y^2 = l^2` — a holonomic constraint or one
    /// linear in the velocities, with a Lagrange multiplier.
    Constraint {
        /// The name after `constraint`, when one is given (`rod`).
        name: Option<Ident>,
        /// The constraint `lhs = rhs`.
        equation: Equation,
        /// The whole statement.
        span: Span,
    },
    /// `reaction rod at P` — the force of a constraint at a point: the
    /// vector R with Σ_i R_i·∂P_i/∂q_k = λ·a_k.
    Reaction {
        /// The constraint's name.
        constraint: Ident,
        /// The point (a position vector, or a displacement along a line).
        point: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `joint A: pin crank at P, rod at Q` or `joint G: slider ground at
    /// P, block at Q along U` — two bodies joined, with the joint's reaction.
    Joint(JointStmt),
    /// `drive M: phi = omega*t` — a coordinate prescribed as a function of
    /// time; the drive's force `M` is the one that holds it so.
    Drive {
        /// The drive's name: the name of the force it applies.
        name: Ident,
        /// The driven coordinate.
        coordinate: Ident,
        /// Its prescribed value, a function of t.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `friction B: mu` — Coulomb friction in the joint `B`.
    Friction {
        /// The joint's name.
        joint: Ident,
        /// The coefficient: μ for a slider, μ₀·r₀ for a pin.
        coefficient: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `assume e real, R > r` — what the scene assumes beyond "every
    /// parameter is positive".
    Assume(Vec<Fact>, Span),
    /// `gravity [0, -g]` — V = −Σ M·G·P over every body and particle.
    Gravity {
        /// The acceleration of gravity G, a vector.
        value: Expr,
        /// The whole statement.
        span: Span,
    },
    /// `latex theta3 = "\vartheta_{3}"` — the LaTeX notation of a name.
    Latex {
        /// The name given notation.
        name: Ident,
        /// The LaTeX text between the quotes.
        tex: String,
        /// The whole statement.
        span: Span,
    },
}

/// One fact of an `assume` statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Fact {
    /// `e real`: the parameter e may have either sign (or be 0).
    Real(Ident),
    /// `R > r` (or `r < R`): `greater` exceeds `less`.
    Order {
        /// The larger side.
        greater: Expr,
        /// The smaller side.
        less: Expr,
        /// The whole fact.
        span: Span,
    },
}

/// A rigid body or a particle: `body NAME: property, …`.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyStmt {
    /// `body` or `particle`.
    pub kind: BodyKind,
    /// The body's name.
    pub name: Ident,
    /// The properties after the colon, in the order written.
    pub properties: Vec<BodyProperty>,
    /// The whole statement.
    pub span: Span,
}

/// The keyword of a [`BodyStmt`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BodyKind {
    /// `body`: mass, inertia, a frame (space) or an angle (plane), a position.
    Rigid,
    /// `particle`: mass and position.
    Particle,
}

impl BodyKind {
    /// The keyword: `body` or `particle`.
    pub fn keyword(self) -> &'static str {
        match self {
            BodyKind::Rigid => "body",
            BodyKind::Particle => "particle",
        }
    }
}

/// One `key value` of a body statement (`mass m`, `at [x, y]`).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyProperty {
    /// Which property.
    pub key: PropertyKey,
    /// Where the key word is written.
    pub key_span: Span,
    /// Its value.
    pub value: Expr,
    /// `about P` after an inertia: the point the inertia is taken about
    /// (ground components), when it is not the centre of mass.
    pub about: Option<About>,
}

/// `about P`: the point an inertia is given about.
#[derive(Clone, Debug, PartialEq)]
pub struct About {
    /// Where the word `about` is written.
    pub key_span: Span,
    /// The point, in ground components.
    pub point: Expr,
}

/// The properties a body statement may give.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PropertyKey {
    /// `mass M`.
    Mass,
    /// `inertia I`: a number (plane), `[I1, I2, I3]` or a symmetric 3×3,
    /// optionally `about P`.
    Inertia,
    /// `frame F`: the body's orientation (a rotation).
    Frame,
    /// `angle theta`: the body's angle in the plane.
    Angle,
    /// `at P`: the centre of mass.
    At,
}

impl PropertyKey {
    /// Every property, in the order the book lists them.
    pub const ALL: [PropertyKey; 5] = [
        PropertyKey::Mass,
        PropertyKey::Inertia,
        PropertyKey::Frame,
        PropertyKey::Angle,
        PropertyKey::At,
    ];
    /// The key word.
    pub fn keyword(self) -> &'static str {
        match self {
            PropertyKey::Mass => "mass",
            PropertyKey::Inertia => "inertia",
            PropertyKey::Frame => "frame",
            PropertyKey::Angle => "angle",
            PropertyKey::At => "at",
        }
    }
    /// The property named `word`, if any.
    pub fn from_keyword(word: &str) -> Option<PropertyKey> {
        PropertyKey::ALL.into_iter().find(|k| k.keyword() == word)
    }
}

/// Which kind of joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointKind {
    /// `pin`: a point of one body kept on a point of the other.
    Pin,
    /// `slider`: a point of one body kept on a line of the other.
    Slider,
}

impl JointKind {
    /// The word after the joint's name: `pin` or `slider`.
    pub fn keyword(self) -> &'static str {
        match self {
            JointKind::Pin => "pin",
            JointKind::Slider => "slider",
        }
    }
}

/// `joint NAME: pin A at P, B at Q` / `… slider A at P, B at Q along U`.
#[derive(Clone, Debug, PartialEq)]
pub struct JointStmt {
    /// The joint's name; its reaction's components are named after it.
    pub name: Ident,
    /// Pin or slider.
    pub kind: JointKind,
    /// The first body (or `ground`) and its point P.
    pub first: JointEnd,
    /// The second body (or `ground`) and its point Q: the reaction is the
    /// force on this body from the first.
    pub second: JointEnd,
    /// A slider's direction U, in ground components.
    pub along: Option<Expr>,
    /// The whole statement.
    pub span: Span,
}

/// One side of a joint: a body (or `ground`) and its point, written
/// through that body's coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct JointEnd {
    /// The body's, particle's name, or `ground`.
    pub body: Ident,
    /// The joint's point.
    pub point: Expr,
}

/// `solve a3, T1 { … }`: unknowns and the equations that determine them.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveBlock {
    /// The names after `solve`, in order.
    pub unknowns: Vec<Ident>,
    /// The equations between the braces, in order.
    pub equations: Vec<Equation>,
    /// From `solve` to the closing `}`.
    pub span: Span,
}

/// `lhs = rhs`, one equation of a `solve` block.
#[derive(Clone, Debug, PartialEq)]
pub struct Equation {
    /// The left-hand side.
    pub lhs: Expr,
    /// The right-hand side.
    pub rhs: Expr,
    /// From the start of `lhs` to the end of `rhs`.
    pub span: Span,
}

impl Stmt {
    /// The source range of the whole statement.
    pub fn span(&self) -> Span {
        match self {
            Stmt::Coordinates(_, s) | Stmt::Parameters(_, s) | Stmt::Functions(_, s) => *s,
            Stmt::Def { span, .. }
            | Stmt::Role { span, .. }
            | Stmt::Force { span, .. }
            | Stmt::Load { span, .. }
            | Stmt::Torque { span, .. }
            | Stmt::Latex { span, .. }
            | Stmt::Frame { span, .. }
            | Stmt::Gravity { span, .. }
            | Stmt::Constraint { span, .. }
            | Stmt::Reaction { span, .. } => *span,
            Stmt::Solve(b) => b.span,
            Stmt::Body(b) => b.span,
            Stmt::Joint(j) => j.span,
            Stmt::Drive { span, .. } | Stmt::Friction { span, .. } => *span,
            Stmt::Assume(_, s) => *s,
        }
    }
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`, also implicit multiplication (`2r`).
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

/// An expression as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What the expression is.
    pub kind: ExprKind,
    /// Where it is written.
    pub span: Span,
}

/// The forms of an [`Expr`].
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// An exact number: `3`, `0.25` (= 1/4), `1.5e-3` (= 3/2000).
    Num(BigRational),
    /// An angle in degrees: `30deg` or `30°`; the value is the number of degrees.
    Degrees(BigRational),
    /// A name: parameter, coordinate, definition, `t` or `pi`.
    Name(String),
    /// Unary minus.
    Neg(Box<Expr>),
    /// `a + b`, `a - b`, `a * b` (also implicit: `2r`, `2(x+y)`), `a / b`, `a ^ b`.
    Bin(BinOp, Box<Expr>, Box<Expr>),
    /// `sin(x)`, `sqrt(x)`, `s(t)`, … — the function called and its arguments.
    Call(Callee, Vec<Expr>),
    /// `x'` (order 1), `x''` (order 2), …: the total time derivative.
    Prime(Box<Expr>, u32),
    /// `[x, y]` or `[x, y, z]`: a vector literal (at least one component).
    Vector(Vec<Expr>),
    /// `P[k]`: the k-th component (1-based) of a vector.
    Index(Box<Expr>, Box<Expr>),
    /// `x = value`: a call argument that names a value (`subs(E, x = 0)`,
    /// `taylor(f, x = a, 3)`); only inside call arguments.
    Assign(Box<Expr>, Box<Expr>),
}

/// The function a call names, resolved when the call is parsed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Callee {
    /// A built-in function (`sin`, `dot`, …), with where its name is written.
    Builtin(Builtin, Span),
    /// Any other name: a given function of time (`s(t)`), or a name that is
    /// no function, which evaluation reports.
    Named(Ident),
}

impl Callee {
    /// The built-in function `name` names, else the name itself.
    pub fn resolve(name: Ident) -> Callee {
        match Builtin::from_name(&name.name) {
            Some(b) => Callee::Builtin(b, name.span),
            None => Callee::Named(name),
        }
    }
    /// The name as written.
    pub fn name(&self) -> &str {
        match self {
            Callee::Builtin(b, _) => b.name(),
            Callee::Named(id) => &id.name,
        }
    }
    /// Where the name is written.
    pub fn span(&self) -> Span {
        match self {
            Callee::Builtin(_, span) => *span,
            Callee::Named(id) => id.span,
        }
    }
}
