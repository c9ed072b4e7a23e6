//! The joints, drives and friction of a planar mechanism, resolved.
//!
//! Each joint and drive is also a set of [`super::Constraint`]s whose
//! multipliers are the joint's reaction (`O_x`, `O_y`, `G_n`, `G_m`) and
//! the drive's force (`M`), so Lagrange's equations of the first kind
//! hold them like any constraint; these records keep what the constraints
//! forget: which bodies, which points, the slider's direction, friction.

use crate::expr::Expr;
use crate::parse::ast::{JointKind, Span};

/// `joint NAME: pin A at P, B at Q` or `… slider A at P, B at Q along U`.
///
/// Invariant (checked by the resolver): `points` have 2 components; each
/// point depends on its own body's coordinates (none for the ground) and
/// parameters only; `constraints` index [`super::Scene::constraints`].
#[derive(Clone, Debug)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Pin or slider.
    pub kind: JointKind,
    /// The two bodies as indices into [`super::Scene::bodies`] (`None`
    /// for the ground): the reaction is the force on the second from the
    /// first.
    pub bodies: [Option<usize>; 2],
    /// P on the first body and Q on the second, in ground components.
    pub points: [Vec<Expr>; 2],
    /// A slider's unit direction Û = U/|U|, in ground components.
    pub along: Option<Vec<Expr>>,
    /// The constraints that hold it, in the order of its reaction's
    /// components: x, y for a pin; n (and m, the locked angle) for a slider.
    pub constraints: Vec<usize>,
    /// For a slider between two rigid bodies: θ_B − θ_A, held at its
    /// assembled value (its constraint holds it at the level of the
    /// velocities).
    pub locked_angle: Option<Expr>,
    /// Coulomb friction in the joint, if any.
    pub friction: Option<JointFriction>,
    /// The whole statement.
    pub span: Span,
}

/// `friction NAME: c`: Coulomb friction in a joint, as the seed writes it:
/// a slider's force −c·|N|·sgn v_rel along the guide (c = μ), a pin's
/// couple −c·|R|·sgn ω_rel (c = μ₀·r₀).
#[derive(Clone, Debug)]
pub struct JointFriction {
    /// The coefficient c, a constant.
    pub coefficient: Expr,
    /// The friction's name among the unknowns: `NAME_f`, the slider's
    /// friction force or the pin's friction couple on the second body.
    pub unknown: String,
    /// The relative velocity whose sense it opposes: the slide
    /// d/dt[Û·(Q − P)], or ω_B − ω_A.
    pub relative_velocity: Expr,
    /// The generalized force per unit of the friction, per coordinate:
    /// ∂s/∂q_k for a slider (s = Û·(Q − P)), ∂(θ_B − θ_A)/∂q_k for a pin.
    pub direction: Vec<Expr>,
    /// The whole `friction` statement.
    pub span: Span,
}

/// `drive NAME: q = f(t)`: a coordinate prescribed in time.
#[derive(Clone, Debug)]
pub struct Drive {
    /// The drive's name: its force's.
    pub name: String,
    /// The driven coordinate's index.
    pub coordinate: usize,
    /// f(t).
    pub value: Expr,
    /// Its constraint q − f(t) = 0 in [`super::Scene::constraints`].
    pub constraint: usize,
    /// The whole statement.
    pub span: Span,
}

impl Joint {
    /// The names of its reaction's components, in the order of
    /// `constraints`.
    pub fn reaction_names(&self) -> Vec<String> {
        reaction_names(&self.name, self.kind, self.locked_angle.is_some())
    }
}

/// The reaction components of a joint `name`: `name_x`, `name_y` for a
/// pin; `name_n` (and `name_m` when the angle is locked) for a slider.
pub fn reaction_names(name: &str, kind: JointKind, locked: bool) -> Vec<String> {
    let suffixes: &[&str] = match (kind, locked) {
        (JointKind::Pin, _) => &["x", "y"],
        (JointKind::Slider, false) => &["n"],
        (JointKind::Slider, true) => &["n", "m"],
    };
    suffixes.iter().map(|s| format!("{name}_{s}")).collect()
}

/// The name of a joint's friction unknown.
pub fn friction_name(joint: &str) -> String {
    format!("{joint}_f")
}
