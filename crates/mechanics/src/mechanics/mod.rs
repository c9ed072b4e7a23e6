//! Lagrange's equations of the second kind.
//!
//! For every coordinate q_k (the seed's eq. 23.90, extended to V and R):
//!
//! ```text
//! d/dt(∂E/∂q̇_k) − ∂E/∂q_k = Q_k,
//! Q_k = −∂V/∂q_k + ∂U/∂q_k + ∂L/∂q_k + ∂D/∂q̇_k − ∂R/∂q̇_k + (force on q_k)
//!       + Σ F·∂P/∂q_k (loads, eq. 23.8) + Σ M·∂φ/∂q_k (torques, eq. 22.28)
//! ```
//!
//! A potential may depend on the velocities (Goldstein's generalized
//! potential, the charged particle's U = e·φ − e·A·v): then its term is
//! d/dt(∂(V − U)/∂q̇_k) − ∂(V − U)/∂q_k. A `lagrangian` L written directly
//! joins E on the left: E above stands for E + L.
//!
//! and the split M(q,t)·q̈ = f(q,q̇,t), read off `lhs − Q` as the
//! coefficients of q̈_j (the equations are linear in q̈). Without loads that
//! carry inertia, M_ij = ∂²E/∂q̇_i∂q̇_j; a scene in D'Alembert's form puts
//! inertia forces `inertia(m, x)` among its loads (E may then be absent),
//! and their q̈ terms join M.

mod accelerations;
mod articulated;
mod constraints;
pub mod hamilton;
pub mod integrals;
mod structured;

pub use crate::algebra::linear::split_linear;
use crate::diag::Diagnostic;
use crate::expr::tape::{Calculus, Expanded, Tape};
use crate::expr::{atom, Expr};
use crate::parse::ast::Role;
use crate::poly::Var;
use crate::scene::Scene;
pub use accelerations::Accelerations;
pub use constraints::ConstraintRows;
pub use hamilton::Hamiltonian;
pub use integrals::Integrals;

/// One equation: `lhs = rhs` for a coordinate.
#[derive(Clone, Debug)]
pub struct Equation {
    /// The name of the coordinate q_k.
    pub coordinate: String,
    /// d/dt(∂E/∂q̇_k) − ∂E/∂q_k.
    pub lhs: Expr,
    /// The generalized force Q_k.
    pub rhs: Expr,
    /// Q_k term by term, by source (their sum is `rhs`).
    pub rhs_terms: Vec<ForceTerm>,
}

/// Lagrange's equations of a scene, with the mass matrix and forcing.
#[derive(Clone, Debug)]
pub struct Lagrange {
    /// The generalized coordinates q, in declaration order.
    pub coordinates: Vec<String>,
    /// Total kinetic energy E, plus the scene's `lagrangian` terms if any
    /// (the function whose derivatives make the left-hand sides).
    pub kinetic: Expr,
    /// One equation per coordinate, in the order of `coordinates`.
    pub equations: Vec<Equation>,
    /// M_ij = ∂²E/∂q̇_i∂q̇_j.
    pub mass_matrix: Vec<Vec<Expr>>,
    /// f with M·q̈ = f (+ Aᵀ·λ with constraints).
    pub forcing: Vec<Expr>,
    /// The scene's constraints at the level of the accelerations (empty
    /// without `constraint` statements).
    pub constraints: ConstraintRows,
    /// The intermediates the expressions above are written through, for a
    /// scene read with its kinematics kept ([`Scene::parse_structured`]);
    /// `None` when they are expanded.
    pub intermediates: Option<Box<Tape>>,
}

impl Lagrange {
    /// Derive the equations of a scene.
    pub fn derive(scene: &Scene) -> Result<Lagrange, Diagnostic> {
        crate::diag::bounded(|| {
            let n = scene.coordinates.len();
            if n == 0 {
                return Err(Diagnostic::global(
                    "the scene declares no coordinates, so there are no Lagrange equations",
                )
                .with_hint("declare the generalized coordinates with `coordinates q1, q2, …`")
                .with_kind(crate::diag::ErrorKind::NothingToSolve));
            }
            if !scene.has_dynamics() {
                if !scene.loads.is_empty() || !scene.torques.is_empty() {
                    return Err(Diagnostic::global(
                        "the scene is static: it has loads but no kinetic energy and no inertia forces, so there are no accelerations",
                    )
                    .with_hint("`qdot forces` prints its generalized forces and `qdot equilibrium` its equilibria; for motion add `kinetic E = …` or inertia forces `load G - inertia(m, y) at y`")
                    .with_kind(crate::diag::ErrorKind::NothingToSolve));
                }
                return Err(Diagnostic::global("the scene has no kinetic energy")
                    .with_hint("add `kinetic E = …` (several `kinetic` lines add up), or write the inertia forces as loads: `load G - inertia(m, y) at y`")
                    .with_kind(crate::diag::ErrorKind::NothingToSolve));
            }
            let _context = crate::budget::enter(|| "deriving Lagrange's equations".into(), None);
            match &scene.tape {
                Some(tape) => {
                    let mut tape = tape.clone();
                    let mut l = Lagrange::derive_with(scene, &mut tape)?;
                    structured::name_equations(&mut tape, &mut l);
                    l.intermediates = Some(Box::new(tape));
                    Ok(l)
                }
                None => Lagrange::derive_with(scene, &mut Expanded),
            }
        })
    }

    /// [`Lagrange::derive`] with the derivatives of `calc`.
    fn derive_with(scene: &Scene, calc: &mut impl Calculus) -> Result<Lagrange, Diagnostic> {
        let n = scene.coordinates.len();
        let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
        let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
        let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
        let qdd: Vec<Var> = names.iter().map(|c| atom::coord(c, 2)).collect();

        let e = scene.role_sum(Role::Kinetic);
        let e = if scene.has_role(Role::Lagrangian) {
            e.add(&scene.role_sum(Role::Lagrangian))
        } else {
            e
        };
        let forces = force_terms_with(scene, calc);

        let constraints = ConstraintRows::of(scene, &qd, &qdd)?;
        let mut equations = Vec::with_capacity(n);
        let mut mass = vec![vec![Expr::zero(); n]; n];
        let mut forcing = Vec::with_capacity(n);
        for (k, mut rhs_terms) in forces.into_iter().enumerate() {
            let rhs = sum_terms(&rhs_terms);
            let p = if calc.depends(&e, qd[k]) {
                calc.partial(&e, qd[k])
            } else {
                Expr::zero()
            };
            let mut lhs = calc.dt(&p);
            if calc.depends(&e, q[k]) {
                lhs = lhs.sub(&calc.partial(&e, q[k]));
            }
            // Mass-matrix row and the rest: lhs − Q = M_k·q̈ − f_k.
            let (row, rest) = split_linear(&lhs.sub(&rhs), &qdd).map_err(|m| {
                Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
            })?;
            for (j, m) in row.into_iter().enumerate() {
                mass[k][j] = m;
            }
            forcing.push(rest.neg());
            // the constraint forces join Q after the split: f keeps no λ
            let mut rhs = rhs;
            for (j, value) in constraints.force_terms(k) {
                rhs = rhs.add(&value);
                rhs_terms.push(ForceTerm {
                    source: Source::Constraint(j),
                    value,
                });
            }
            for (i, jt) in scene.joints.iter().enumerate() {
                let Some(f) = jt.friction.as_ref().filter(|f| !f.direction[k].is_zero()) else {
                    continue;
                };
                let value = Expr::unknown(&f.unknown).mul(&f.direction[k]);
                rhs = rhs.add(&value);
                rhs_terms.push(ForceTerm {
                    source: Source::Friction(i),
                    value,
                });
            }
            equations.push(Equation {
                coordinate: names[k].clone(),
                lhs,
                rhs,
                rhs_terms,
            });
        }
        if mass.iter().flatten().all(Expr::is_zero) {
            return Err(Diagnostic::global(
                "the equations have no accelerations: the kinetic energy is zero and no load carries an inertia force",
            )
            .with_hint("add `kinetic E = …`, or inertia forces as loads: `load G - inertia(m, y) at y`").with_kind(crate::diag::ErrorKind::NothingToSolve));
        }
        Ok(Lagrange {
            coordinates: names,
            kinetic: e,
            equations,
            mass_matrix: mass,
            forcing,
            constraints,
            intermediates: None,
        })
    }

    /// The exact accelerations q̈ = M⁻¹·f of a tree of rigid bodies by the
    /// articulated-body recursion: O(n) intermediates where
    /// [`Lagrange::accelerations`] writes O(n³) through the tape, for a
    /// scene read with its kinematics kept. Checked against M⁻¹·f at
    /// random states; an error says why the recursion does not apply
    /// (the equations are expanded, a kinetic energy besides the bodies',
    /// bodies that do not form a tree of rigid joints, …).
    pub fn articulated_accelerations(&self, scene: &Scene) -> Result<Accelerations, String> {
        let _context = crate::budget::enter(
            || "the articulated-body recursion for the accelerations".into(),
            None,
        );
        crate::budget::bounded(
            || {
                let (values, tape) = articulated::articulated(scene, self)?;
                let mut a = Accelerations::new(self.coordinates.clone(), values);
                a.set_intermediates(tape);
                Ok(a)
            },
            |e| e.message(),
        )
    }

    /// The exact accelerations q̈ = M⁻¹·f; with constraints, q̈ and the
    /// multipliers λ of the augmented system (see [`ConstraintRows`]).
    pub fn accelerations(&self) -> Result<Accelerations, Diagnostic> {
        crate::diag::bounded(|| {
            let friction = self
                .equations
                .iter()
                .flat_map(|e| &e.rhs_terms)
                .any(|t| matches!(t.source, Source::Friction(_)));
            if friction {
                return Err(Diagnostic::global(
                    "the equations have Coulomb friction in a joint (−c·|N|·sgn v), which is not linear in the reactions, so the accelerations have no closed form",
                )
                .with_hint("`qdot cycle` solves a driven mechanism with friction position by position; without a drive, remove the `friction` statements").with_kind(crate::diag::ErrorKind::NoClosedForm));
            }
            if !self.constraints.is_empty() {
                let _context = crate::budget::enter(
                    || {
                        "solving M·q̈ − Aᵀ·λ = f, A·q̈ = γ for the accelerations and the multipliers"
                            .into()
                    },
                    None,
                );
                let (acc, lambda) = constraints::solve_augmented(
                    &self.coordinates,
                    &self.mass_matrix,
                    &self.forcing,
                    &self.constraints,
                )?;
                let mut a = Accelerations::new(self.coordinates.clone(), acc);
                a.set_multipliers(self.constraints.multipliers.clone(), lambda);
                return Ok(a);
            }
            let _context =
                crate::budget::enter(|| "solving M·q̈ = f for the accelerations".into(), None);
            if let Some(tape) = &self.intermediates {
                let mut tape: Tape = (**tape).clone();
                let acc = structured::solve_ldl(
                    &mut tape,
                    &self.coordinates,
                    &self.mass_matrix,
                    &self.forcing,
                )?;
                let mut a = Accelerations::new(self.coordinates.clone(), acc);
                a.set_intermediates(tape);
                return Ok(a);
            }
            let sol = crate::algebra::linear::solve(&self.mass_matrix, &self.forcing).map_err(|e| {
                match e {
                    crate::algebra::linear::SolveError::Singular { dependent } => {
                        let names: Vec<&str> = dependent
                            .iter()
                            .filter_map(|&i| self.coordinates.get(i).map(|s| s.as_str()))
                            .collect();
                        Diagnostic::global(format!(
                            "the mass matrix is singular: the coordinates {} are not independent in the kinetic energy",
                            names.join(", ")
                        ))
                        .with_hint("a combination of their velocities carries no kinetic energy; remove a redundant coordinate or add the missing inertia")
                        .with_kind(crate::diag::ErrorKind::SingularSystem {
                            unknowns: names.iter().map(|s| s.to_string()).collect(),
                        })
                    }
                    crate::algebra::linear::SolveError::Math(m) => Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined),
                }
            })?;
            Ok(Accelerations::new(self.coordinates.clone(), sol))
        })
    }
}

/// The generalized forces Q_k, one per coordinate in declaration order: the
/// right-hand sides of Lagrange's equations (see the module docs). The
/// virtual work of the scene is δL = Σ Q_k·δq_k.
pub fn generalized_forces(scene: &Scene) -> Vec<Expr> {
    generalized_force_terms(scene)
        .iter()
        .map(|terms| sum_terms(terms))
        .collect()
}

/// [`generalized_forces`], each expanded from the scene's intermediates
/// when it was read with its kinematics kept: an error, not a name left
/// in a result, when an expansion fails (a division by what is zero once
/// the intermediates are expanded).
pub fn expanded_generalized_forces(scene: &Scene) -> Result<Vec<Expr>, Diagnostic> {
    crate::diag::bounded(|| {
        let Some(tape) = &scene.tape else {
            return Ok(generalized_forces(scene));
        };
        let _context = crate::budget::enter(
            || "expanding the generalized forces from the intermediates".into(),
            None,
        );
        let mut tape = tape.clone();
        force_terms_with(scene, &mut tape)
            .iter()
            .map(|terms| {
                tape.expand(&sum_terms(terms)).map_err(|e| {
                    Diagnostic::global(e.message).with_kind(crate::diag::ErrorKind::Undefined)
                })
            })
            .collect()
    })
}

/// The Lagrangian L = E + (lagrangian) − V + U of a scene's roles.
pub fn lagrangian(scene: &Scene) -> Expr {
    scene
        .role_sum(Role::Kinetic)
        .add(&scene.role_sum(Role::Lagrangian))
        .sub(&scene.role_sum(Role::Potential))
        .add(&scene.role_sum(Role::ForceFunction))
}

/// Q_k from its terms.
fn sum_terms(terms: &[ForceTerm]) -> Expr {
    terms.iter().fold(Expr::zero(), |q, t| q.add(&t.value))
}

/// Where a term of a generalized force comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// −∂(V − U)/∂q_k: the potential and the force function together
    /// (plus d/dt ∂(V − U)/∂q̇_k when they depend on the velocities).
    Potential,
    /// ∂L/∂q_k: the work of the non-conservative forces.
    Work,
    /// ∂(D − R)/∂q̇_k: the dissipation and Rayleigh functions together.
    Dissipation,
    /// The `force` statements on q_k.
    Force,
    /// F·∂P/∂q_k for the i-th load (0-based, in source order).
    Load(usize),
    /// M·∂φ/∂q_k for the i-th torque.
    Torque(usize),
    /// λ_j·a_jk: the generalized force of the j-th constraint.
    Constraint(usize),
    /// F·∂s/∂q_k: the friction of the i-th joint (0-based), an unknown
    /// like the reactions.
    Friction(usize),
}

/// One nonzero contribution to a generalized force.
#[derive(Clone, Debug)]
pub struct ForceTerm {
    /// Where the contribution comes from.
    pub source: Source,
    /// Its value, a term of Q_k.
    pub value: Expr,
}

/// The contributions to each Q_k, per coordinate in declaration order, in
/// the order of the module docs; only the sources that mention q_k.
pub fn generalized_force_terms(scene: &Scene) -> Vec<Vec<ForceTerm>> {
    let Some(tape) = &scene.tape else {
        return force_terms_with(scene, &mut Expanded);
    };
    // through the scene's intermediates, then expanded: the terms are
    // returned without a tape to read them by
    let mut tape = tape.clone();
    let mut terms = force_terms_with(scene, &mut tape);
    for t in terms.iter_mut().flatten() {
        if let Ok(v) = tape.expand(&t.value) {
            t.value = v;
        }
    }
    terms
}

/// [`generalized_force_terms`] with the derivatives of `calc`.
fn force_terms_with(scene: &Scene, calc: &mut impl Calculus) -> Vec<Vec<ForceTerm>> {
    let names: Vec<&str> = scene.coordinates.iter().map(|c| c.name.as_str()).collect();
    let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
    let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
    // V − U as one potential; L; D − R as one (book-sign) dissipation.
    let has_v = scene.has_role(Role::Potential) || scene.has_role(Role::ForceFunction);
    let v = if has_v {
        scene
            .role_sum(Role::Potential)
            .sub(&scene.role_sum(Role::ForceFunction))
    } else {
        Expr::zero()
    };
    let l = scene.role_sum(Role::Work);
    let has_d = scene.has_role(Role::Dissipation) || scene.has_role(Role::Rayleigh);
    let d = if has_d {
        scene
            .role_sum(Role::Dissipation)
            .sub(&scene.role_sum(Role::Rayleigh))
    } else {
        Expr::zero()
    };
    let mut out = Vec::with_capacity(q.len());
    for k in 0..q.len() {
        let mut terms = Vec::new();
        let mut push = |source, value: Expr| {
            if !value.is_zero() {
                terms.push(ForceTerm { source, value });
            }
        };
        let mut potential = Expr::zero();
        if calc.depends(&v, q[k]) {
            potential = calc.partial(&v, q[k]).neg();
        }
        if calc.depends(&v, qd[k]) {
            // a generalized potential U(q, q̇, t): Q_k = d/dt(∂U/∂q̇_k) − ∂U/∂q_k
            let p = calc.partial(&v, qd[k]);
            potential = potential.add(&calc.dt(&p));
        }
        push(Source::Potential, potential);
        if calc.depends(&l, q[k]) {
            push(Source::Work, calc.partial(&l, q[k]));
        }
        if calc.depends(&d, qd[k]) {
            push(Source::Dissipation, calc.partial(&d, qd[k]));
        }
        let force = scene
            .forces
            .iter()
            .filter(|f| f.coordinate == k)
            .fold(Expr::zero(), |s, f| s.add(&f.value));
        push(Source::Force, force);
        for (i, ld) in scene.loads.iter().enumerate() {
            let mut w = Expr::zero();
            for (f, p) in ld.force.components().iter().zip(ld.point.components()) {
                if calc.depends(p, q[k]) {
                    w = w.add(&f.mul(&calc.partial(p, q[k])));
                }
            }
            push(Source::Load(i), w);
        }
        for (i, t) in scene.torques.iter().enumerate() {
            if calc.depends(&t.angle, q[k]) {
                push(
                    Source::Torque(i),
                    t.moment.mul(&calc.partial(&t.angle, q[k])),
                );
            }
        }
        out.push(terms);
    }
    out
}
