//! Hamilton's equations: the Legendre transform of the Lagrangian.
//!
//! With L = E + (lagrangian) − V + U, the momenta p_k = ∂L/∂q̇_k are
//! linear in the velocities when L is quadratic in them, p = M·q̇ + b(q, t);
//! the velocities come back exactly as q̇ = M⁻¹·(p − b), and
//!
//! ```text
//! H(q, p, t) = Σ p_k·q̇_k − L,   q̇_k = ∂H/∂p_k,   ṗ_k = −∂H/∂q_k + Q̃_k,
//! ```
//!
//! Q̃ being the generalized forces no potential accounts for (work,
//! dissipation, `force`, loads, torques, and the constraints' λ·a), written
//! in q, p and t. The momentum of q is named `p_q` (`p_theta`).

use super::{generalized_force_terms, ConstraintRows, Source};
use crate::algebra::linear::{self, split_linear, SolveError};
use crate::diag::Diagnostic;
use crate::expr::{atom, Expr};
use crate::parse::ast::Role;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// The Hamiltonian form of a scene's equations.
#[derive(Clone, Debug)]
pub struct Hamiltonian {
    /// The coordinates q, in declaration order.
    pub coordinates: Vec<String>,
    /// The momenta's names (`p_theta`), one per coordinate.
    pub momentum_names: Vec<String>,
    /// p_k = ∂L/∂q̇_k, in q, q̇ and t.
    pub momenta: Vec<Expr>,
    /// q̇_k in q, p and t.
    pub velocities: Vec<Expr>,
    /// H(q, p, t).
    pub hamiltonian: Expr,
    /// ṗ_k = −∂H/∂q_k + Q̃_k, in q, p and t.
    pub momentum_rates: Vec<Expr>,
    /// Q̃_k, the generalized forces outside H, in q, p and t (zero for a
    /// conservative scene).
    pub other_forces: Vec<Expr>,
}

pub use crate::scene::momentum_name;

impl Hamiltonian {
    /// The Legendre transform of the scene's Lagrangian.
    pub fn derive(scene: &Scene) -> Result<Hamiltonian, Diagnostic> {
        scene.expanded_only("Hamilton's equations")?;
        let _context = crate::budget::enter(|| "deriving Hamilton's equations".into(), None);
        let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
        check_scene(scene, &names)?;
        let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
        let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
        let qdd: Vec<Var> = names.iter().map(|c| atom::coord(c, 2)).collect();
        let momentum_names: Vec<String> = names.iter().map(|c| momentum_name(c)).collect();
        let p: Vec<Expr> = momentum_names.iter().map(|n| Expr::unknown(n)).collect();
        let l = super::lagrangian(scene);
        let momenta: Vec<Expr> = qd.iter().map(|&v| l.diff(v)).collect();
        // p = M·q̇ + b, M free of the velocities
        let mut mass = Vec::with_capacity(names.len());
        let mut offset = Vec::with_capacity(names.len());
        for pk in &momenta {
            let (row, rest) = split_linear(pk, &qd).map_err(|m| Diagnostic::global(m.message))?;
            if row
                .iter()
                .chain(std::iter::once(&rest))
                .any(|e| moves(e, &qd))
            {
                return Err(Diagnostic::global(
                    "the Lagrangian is not quadratic in the velocities, so the momenta are not linear in them and the Legendre transform has no closed form here",
                )
                .with_hint("Hamilton's equations need q̇ in terms of p: keep the kinetic energy quadratic in the velocities"));
            }
            mass.push(row);
            offset.push(rest);
        }
        let rhs: Vec<Expr> = p.iter().zip(&offset).map(|(pk, b)| pk.sub(b)).collect();
        let velocities = linear::solve(&mass, &rhs).map_err(|e| match e {
            SolveError::Singular { dependent } => {
                let unknowns: Vec<String> = dependent
                    .iter()
                    .filter_map(|&i| names.get(i).cloned())
                    .collect();
                Diagnostic::global(format!(
                    "the momenta do not determine the velocities of {}: the Lagrangian is degenerate in them",
                    unknowns.join(", ")
                ))
                .with_hint("Hamilton's equations need a kinetic energy in every velocity (a regular Lagrangian)")
                .with_kind(crate::diag::ErrorKind::SingularSystem { unknowns })
            }
            SolveError::Math(m) => Diagnostic::global(m.message),
        })?;
        let to_p: FxHashMap<Var, Expr> =
            qd.iter().copied().zip(velocities.iter().cloned()).collect();
        let in_p = |e: &Expr| {
            e.subs_many(&to_p)
                .map_err(|m| Diagnostic::global(m.message))
        };
        let mut h = in_p(&l)?.neg();
        for (pk, vk) in p.iter().zip(&velocities) {
            h = h.add(&pk.mul(vk));
        }
        let other = other_forces(scene, &qd, &qdd)?;
        let mut other_forces = Vec::with_capacity(names.len());
        let mut momentum_rates = Vec::with_capacity(names.len());
        for (k, &qk) in q.iter().enumerate() {
            let extra = in_p(&other[k])?;
            momentum_rates.push(h.diff(qk).neg().add(&extra));
            other_forces.push(extra);
        }
        debug_assert!(p.iter().zip(&velocities).all(|(pk, v)| match pk.as_var() {
            Some(var) => h.diff(var).equals(v),
            None => true,
        }));
        Ok(Hamiltonian {
            coordinates: names,
            momentum_names,
            momenta,
            velocities,
            hamiltonian: h,
            momentum_rates,
            other_forces,
        })
    }
}

/// Does `e` depend on a velocity?
fn moves(e: &Expr, qd: &[Var]) -> bool {
    qd.iter().any(|&v| e.depends_on(v))
}

/// The scene must have coordinates, a kinetic energy, no inertia forces
/// among its loads, and momentum names that are free.
fn check_scene(scene: &Scene, names: &[String]) -> Result<(), Diagnostic> {
    if names.is_empty() {
        return Err(Diagnostic::global(
            "the scene declares no coordinates, so there are no Hamilton's equations",
        )
        .with_hint("declare the generalized coordinates with `coordinates q1, q2, …`")
        .with_kind(crate::diag::ErrorKind::NothingToSolve));
    }
    if !scene.has_role(Role::Kinetic) && !scene.has_role(Role::Lagrangian) {
        return Err(Diagnostic::global(
            "Hamilton's equations need a kinetic energy or a Lagrangian, and the scene has neither",
        )
        .with_hint("inertia forces written as loads (D'Alembert's form) have no Legendre transform: write `kinetic E = …`")
        .with_kind(crate::diag::ErrorKind::NothingToSolve));
    }
    for n in names {
        let p = momentum_name(n);
        let taken = scene.parameters.iter().any(|x| x.name == p)
            || scene.coordinates.iter().any(|x| x.name == p)
            || scene.definitions.iter().any(|x| x.name == p)
            || scene.deferred.iter().any(|x| x.name.name == p);
        if taken {
            return Err(Diagnostic::global(format!(
                "the momentum of `{n}` is named `{p}`, which the scene already uses"
            ))
            .with_hint(format!("rename `{p}` in the scene")));
        }
    }
    Ok(())
}

/// Q̃_k: every generalized force but the potential's, and the constraints'
/// λ·a; in q, q̇ and t (an inertia force, with q̈, is refused).
pub(super) fn other_forces(
    scene: &Scene,
    qd: &[Var],
    qdd: &[Var],
) -> Result<Vec<Expr>, Diagnostic> {
    let rows = ConstraintRows::of(scene, qd, qdd)?;
    let mut out = Vec::with_capacity(qd.len());
    for (k, terms) in generalized_force_terms(scene).into_iter().enumerate() {
        let mut q = Expr::zero();
        for t in terms {
            if t.source != Source::Potential {
                q = q.add(&t.value);
            }
        }
        for (_, value) in rows.force_terms(k) {
            q = q.add(&value);
        }
        if qdd.iter().any(|&v| q.depends_on(v)) {
            return Err(Diagnostic::global(
                "a generalized force depends on an acceleration (an inertia force among the loads), which Hamilton's equations can't carry",
            )
            .with_hint("write the inertia as a kinetic energy: `kinetic E = …`"));
        }
        out.push(q);
    }
    Ok(out)
}
