//! The kinetostatics of a driven mechanism, exactly: with every
//! coordinate's motion known from the kinematics (as many joint and drive
//! conditions as coordinates), Lagrange's equations of the first kind
//! M·q̈ = f + Aᵀ·λ + Σ F·∂s/∂q are linear in the reactions λ and are
//! solved for them as functions of q, q̇ and q̈: the textbook's
//! kinetostatic method (the seed's §21.5), body by body where the
//! equations allow (see [`super::system::solve_in_order`]).

use crate::diag::Diagnostic;
use crate::expr::{atom, Expr};
use crate::mechanics::Lagrange;
use crate::poly::Var;
use crate::scene::Scene;

/// A driven mechanism's reactions.
#[derive(Clone, Debug)]
pub struct MechanismReactions {
    /// Each reaction component, drive force and multiplier with its
    /// value, in the order solved: a value may use those before it, and
    /// the frictions `NAME_f` and the accelerations q̈.
    pub values: Vec<(String, Expr)>,
    /// Whether `values` are in solving order (each through the earlier
    /// ones) rather than each in the scene's names alone.
    pub in_order: bool,
    /// Each friction: its name, its coefficient, the name of the reaction
    /// components its magnitude is made of, and the relative velocity it
    /// opposes.
    pub friction: Vec<FrictionLaw>,
}

/// `NAME_f = −c·|N|·sgn v` of a joint with friction.
#[derive(Clone, Debug)]
pub struct FrictionLaw {
    /// `G_f`: the slider's friction force, or the pin's couple, on the
    /// second body.
    pub name: String,
    /// The coefficient c (μ, or μ₀·r₀).
    pub coefficient: Expr,
    /// The reaction components N is made of: `[G_n]` (|N|) or `[B_x,
    /// B_y]` (√(B_x² + B_y²)).
    pub normal: Vec<String>,
    /// The relative velocity v_rel (or ω_rel).
    pub relative_velocity: Expr,
}

/// Whether `scene` is a driven mechanism: joints or drives, and as many
/// conditions as coordinates.
pub fn is_driven_mechanism(scene: &Scene) -> bool {
    (!scene.joints.is_empty() || !scene.drives.is_empty())
        && scene.constraints.len() == scene.coordinates.len()
}

/// The reactions of a driven mechanism from its equations `lag`.
pub fn mechanism_reactions(
    scene: &Scene,
    lag: &Lagrange,
) -> Result<MechanismReactions, Diagnostic> {
    crate::diag::bounded(|| mechanism_reactions_within(scene, lag))
}

/// [`mechanism_reactions`] within the budget in force.
fn mechanism_reactions_within(
    scene: &Scene,
    lag: &Lagrange,
) -> Result<MechanismReactions, Diagnostic> {
    let _context = crate::budget::enter(|| "the kinetostatics of the mechanism".into(), None);
    let n = lag.coordinates.len();
    let qdd: Vec<Expr> = lag.coordinates.iter().map(|c| Expr::coord(c, 2)).collect();
    let mut friction = Vec::new();
    let mut rhs: Vec<Expr> = (0..n)
        .map(|k| {
            let mq = lag.mass_matrix[k]
                .iter()
                .zip(&qdd)
                .fold(Expr::zero(), |s, (m, a)| s.add(&m.mul(a)));
            mq.sub(&lag.forcing[k])
        })
        .collect();
    for jt in &scene.joints {
        let Some(f) = &jt.friction else { continue };
        let symbol = Expr::unknown(&f.unknown);
        for (k, d) in f.direction.iter().enumerate() {
            rhs[k] = rhs[k].sub(&symbol.mul(d));
        }
        let names = jt.reaction_names();
        friction.push(FrictionLaw {
            name: f.unknown.clone(),
            coefficient: f.coefficient.clone(),
            normal: match jt.kind {
                crate::parse::ast::JointKind::Pin => names,
                crate::parse::ast::JointKind::Slider => names.into_iter().take(1).collect(),
            },
            relative_velocity: f.relative_velocity.clone(),
        });
    }
    // Aᵀ: row k holds a_jk for every constraint j
    let m = lag.constraints.matrix.len();
    let at: Vec<Vec<Expr>> = (0..n)
        .map(|k| {
            (0..m)
                .map(|j| lag.constraints.matrix[j][k].clone())
                .collect()
        })
        .collect();
    let unknowns: Vec<Var> = lag
        .constraints
        .multipliers
        .iter()
        .map(|name| atom::unknown(name))
        .collect();
    let math = |e: crate::expr::MathError| {
        Diagnostic::global(e.message).with_kind(crate::diag::ErrorKind::Undefined)
    };
    if let Some(order) = super::system::solve_in_order(&at, &rhs, &unknowns).map_err(math)? {
        let values = order
            .into_iter()
            .map(|(j, v)| (lag.constraints.multipliers[j].clone(), v))
            .collect();
        return Ok(MechanismReactions {
            values,
            in_order: true,
            friction,
        });
    }
    let values = crate::algebra::linear::solve(&at, &rhs).map_err(|e| match e {
        crate::algebra::linear::SolveError::Singular { .. } => Diagnostic::global(
            "the joints and drives do not determine the reactions: the kinetostatic equations are singular (a joint or drive the others imply)",
        )
        .with_hint("remove the redundant joint or drive").with_kind(crate::diag::ErrorKind::SingularSystem { unknowns: Vec::new() }),
        crate::algebra::linear::SolveError::Math(m) => math(m),
    })?;
    Ok(MechanismReactions {
        values: lag
            .constraints
            .multipliers
            .iter()
            .cloned()
            .zip(values)
            .collect(),
        in_order: false,
        friction,
    })
}
