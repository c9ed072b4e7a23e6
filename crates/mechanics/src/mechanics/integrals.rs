//! Integrals of motion: cyclic coordinates and their momenta, the energy
//! (Jacobi) integral, and Routh's reduction.
//!
//! With L = E + (lagrangian) − V + U and Q̃ the generalized forces no
//! potential accounts for (and the constraints' λ·a):
//! * q_c is cyclic when L does not contain it and Q̃_c = 0 (no constraint
//!   acts on it): p_c = ∂L/∂q̇_c is conserved;
//! * h = Σ q̇_k·∂L/∂q̇_k − L is conserved when L has no explicit t, Q̃ = 0
//!   and every constraint is fixed (b = 0, a free of t); it is E + V when
//!   E is quadratic in the velocities and V, U are free of them;
//! * Routh: with the momenta p_c of the cyclic coordinates constant, the
//!   Routhian R = L − Σ p_c·q̇_c (the q̇_c solved from p_c = ∂L/∂q̇_c) is a
//!   Lagrangian for the remaining coordinates; −R at their rest is the
//!   effective potential.

use super::hamilton::momentum_name;
use super::{generalized_force_terms, ConstraintRows, Source};
use crate::algebra::linear::{self, split_linear};
use crate::diag::Diagnostic;
use crate::expr::{atom, Expr};
use crate::parse::ast::Role;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// The integrals of motion of a scene.
#[derive(Clone, Debug)]
pub struct Integrals {
    /// The coordinates, in declaration order.
    pub coordinates: Vec<String>,
    /// The cyclic coordinates with their conserved momenta ∂L/∂q̇ (in q, q̇).
    pub cyclic: Vec<(String, Expr)>,
    /// The energy integral h, when it is one.
    pub energy: Option<Expr>,
    /// Whether h is E + V (E quadratic in q̇, V and U free of them).
    pub energy_is_e_plus_v: bool,
    /// Routh's reduction, when some but not all coordinates are cyclic.
    pub routh: Option<Routh>,
    /// Why an integral is missing: one line each.
    pub notes: Vec<String>,
}

/// Routh's reduction over the cyclic coordinates.
#[derive(Clone, Debug)]
pub struct Routh {
    /// R(q_r, q̇_r, p_c, t), the p_c named `p_q` (constants).
    pub routhian: Expr,
    /// −R with the remaining velocities at 0.
    pub effective_potential: Expr,
    /// (coordinate, q̈) of the remaining coordinates, in p_c.
    pub accelerations: Vec<(String, Expr)>,
}

impl Integrals {
    /// Find the integrals of a scene.
    pub fn find(scene: &Scene) -> Result<Integrals, Diagnostic> {
        crate::diag::bounded(|| {
            scene.expanded_only("the search for first integrals")?;
            let _context = crate::budget::enter(|| "finding the integrals of motion".into(), None);
            let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
            if names.is_empty()
                || !(scene.has_role(Role::Kinetic) || scene.has_role(Role::Lagrangian))
            {
                return Err(Diagnostic::global(
                    "integrals of motion need coordinates and a kinetic energy or a Lagrangian",
                )
                .with_hint("declare `coordinates …` and write `kinetic E = …`")
                .with_kind(crate::diag::ErrorKind::NothingToSolve));
            }
            let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
            let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
            let qdd: Vec<Var> = names.iter().map(|c| atom::coord(c, 2)).collect();
            let l = super::lagrangian(scene);
            let rows = ConstraintRows::of(scene, &qd, &qdd)?;
            let forced = forced_coordinates(scene, &rows);
            let mut notes = Vec::new();
            let mut cyclic = Vec::new();
            for (k, name) in names.iter().enumerate() {
                if l.depends_on(q[k]) {
                    continue;
                }
                match &forced[k] {
                    Some(why) => notes.push(format!(
                        "{name} is absent from L, but {why} acts on it: p_{name} is not conserved"
                    )),
                    None => cyclic.push((name.clone(), l.diff(qd[k]))),
                }
            }
            let (energy, energy_is_e_plus_v) = energy_integral(scene, &l, &qd, &forced, &mut notes);
            let routh = if cyclic.is_empty() || cyclic.len() == names.len() {
                None
            } else if !rows.is_empty() {
                notes.push("Routh's reduction is not done for a scene with constraints".into());
                None
            } else {
                let other = super::hamilton::other_forces(scene, &qd, &qdd)?;
                Some(routh(&l, &names, &cyclic, &other, &qd, &qdd)?)
            };
            Ok(Integrals {
                coordinates: names,
                cyclic,
                energy,
                energy_is_e_plus_v,
                routh,
                notes,
            })
        })
    }
}

/// The energy (Jacobi) integral h of a scene when it is conserved: the
/// one decision `integrals`, `simulate`'s energy drift and `codegen`'s
/// energy function share.
pub fn conserved_energy(scene: &Scene) -> Result<Option<Expr>, Diagnostic> {
    crate::diag::bounded(|| {
        scene.expanded_only("the energy integral")?;
        let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
        let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
        let qdd: Vec<Var> = names.iter().map(|c| atom::coord(c, 2)).collect();
        let rows = ConstraintRows::of(scene, &qd, &qdd)?;
        let forced = forced_coordinates(scene, &rows);
        let l = super::lagrangian(scene);
        Ok(energy_integral(scene, &l, &qd, &forced, &mut Vec::new()).0)
    })
}

/// For each coordinate, what acts on it besides the potential: a
/// statement's kind, or a constraint.
fn forced_coordinates(scene: &Scene, rows: &ConstraintRows) -> Vec<Option<String>> {
    let terms = generalized_force_terms(scene);
    terms
        .iter()
        .enumerate()
        .map(|(k, ts)| {
            let source =
                ts.iter()
                    .find(|t| t.source != Source::Potential)
                    .map(|t| match t.source {
                        Source::Work => "the work L".to_string(),
                        Source::Dissipation => "a dissipation".to_string(),
                        Source::Force => "a `force`".to_string(),
                        Source::Load(_) => "a load".to_string(),
                        Source::Torque(_) => "a torque".to_string(),
                        Source::Potential | Source::Constraint(_) | Source::Friction(_) => {
                            "a force".to_string()
                        }
                    });
            let friction = || {
                scene.joints.iter().find_map(|jt| {
                    let f = jt.friction.as_ref()?;
                    (!f.direction[k].is_zero()).then(|| format!("the friction in `{}`", jt.name))
                })
            };
            source.or_else(friction).or_else(|| {
                rows.matrix
                    .iter()
                    .position(|r| !r[k].is_zero())
                    .map(|j| format!("the constraint {}", rows.labels[j]))
            })
        })
        .collect()
}

/// h = Σ q̇·∂L/∂q̇ − L when it is conserved, with whether it is E + V.
fn energy_integral(
    scene: &Scene,
    l: &Expr,
    qd: &[Var],
    forced: &[Option<String>],
    notes: &mut Vec<String>,
) -> (Option<Expr>, bool) {
    if l.depends_on(atom::time()) {
        notes.push("L depends on t explicitly: no energy integral".into());
        return (None, false);
    }
    if let Some(s) = l.given_function() {
        notes.push(format!(
            "L depends on t through the given function {s}: no energy integral (dh/dt = −∂L/∂t)"
        ));
        return (None, false);
    }
    let non_constraint = forced
        .iter()
        .flatten()
        .find(|why| !why.starts_with("the constraint"));
    if let Some(why) = non_constraint {
        notes.push(format!("{why} does work: no energy integral"));
        return (None, false);
    }
    for (j, c) in scene.constraints.iter().enumerate() {
        if let Some(why) = constraint_does_work(c) {
            notes.push(format!(
                "the constraint {} {why}: no energy integral",
                c.label(j)
            ));
            return (None, false);
        }
    }
    let h = jacobi_integral(l, qd);
    let e = scene
        .role_sum(Role::Kinetic)
        .add(&scene.role_sum(Role::Lagrangian));
    let v = scene
        .role_sum(Role::Potential)
        .sub(&scene.role_sum(Role::ForceFunction));
    let e_plus_v = h.equals(&e.add(&v));
    (Some(h), e_plus_v)
}

/// Why a constraint's reaction can do work on the motion, when it can:
/// with a·q̇ + b = 0 its power is λ·a·q̇ = −λ·b, which vanishes for every
/// motion only when b = 0; a constraint that depends on t (a moving
/// guide) does work too.
fn constraint_does_work(c: &crate::scene::Constraint) -> Option<String> {
    let moves = c.expression.depends_on_time()
        || c.rest.depends_on_time()
        || c.coefficients.iter().any(Expr::depends_on_time);
    if moves {
        return Some("moves (it depends on t)".into());
    }
    if !c.rest.is_zero() {
        return Some(format!(
            "is not homogeneous in the velocities (b = {} in a·q̇ + b = 0): its reaction does work",
            crate::expr::print::unicode(&c.rest)
        ));
    }
    None
}

/// The Jacobi integral h = Σ q̇_k·∂L/∂q̇_k − L (E + V when E is quadratic
/// in the velocities and V free of them).
pub fn jacobi_integral(l: &Expr, qd: &[Var]) -> Expr {
    qd.iter()
        .fold(l.neg(), |h, &v| h.add(&Expr::var(v).mul(&l.diff(v))))
}

/// Routh's reduction over the cyclic coordinates.
fn routh(
    l: &Expr,
    names: &[String],
    cyclic: &[(String, Expr)],
    other: &[Expr],
    qd: &[Var],
    qdd: &[Var],
) -> Result<Routh, Diagnostic> {
    let is_cyclic = |k: usize| cyclic.iter().any(|(c, _)| *c == names[k]);
    let c_idx: Vec<usize> = (0..names.len()).filter(|&k| is_cyclic(k)).collect();
    let r_idx: Vec<usize> = (0..names.len()).filter(|&k| !is_cyclic(k)).collect();
    let c_vel: Vec<Var> = c_idx.iter().map(|&k| qd[k]).collect();
    // p_c = Σ M_cc'·q̇_c' + (the rest): solve for the cyclic velocities
    let mut mass = Vec::with_capacity(c_idx.len());
    let mut rhs = Vec::with_capacity(c_idx.len());
    for (&k, (_, p_expr)) in c_idx.iter().zip(cyclic) {
        let (row, rest) = split_linear(p_expr, &c_vel).map_err(|m| {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
        })?;
        if row.iter().any(|e| c_vel.iter().any(|&v| e.depends_on(v))) {
            return Err(Diagnostic::global(
                "the momenta of the cyclic coordinates are not linear in their velocities: no Routhian in closed form",
            )
            .with_hint("keep the kinetic energy quadratic in the velocities").with_kind(crate::diag::ErrorKind::NoClosedForm));
        }
        mass.push(row);
        rhs.push(Expr::unknown(&momentum_name(&names[k])).sub(&rest));
    }
    let vel = linear::solve(&mass, &rhs).map_err(|_| {
        Diagnostic::global("the cyclic coordinates' momenta do not determine their velocities")
            .with_hint("a cyclic coordinate needs kinetic energy of its own")
            .with_kind(crate::diag::ErrorKind::SingularSystem {
                unknowns: Vec::new(),
            })
    })?;
    let map: FxHashMap<Var, Expr> = c_vel.iter().copied().zip(vel.iter().cloned()).collect();
    let subs = |e: &Expr| {
        e.subs_many(&map)
            .map_err(|m| Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined))
    };
    let mut r = l.clone();
    for (&k, v) in c_idx.iter().zip(&vel) {
        r = r.sub(&Expr::unknown(&momentum_name(&names[k])).mul(v));
    }
    let routhian = subs(&r)?;
    let rest: FxHashMap<Var, Expr> = r_idx.iter().map(|&k| (qd[k], Expr::zero())).collect();
    let effective_potential = routhian
        .subs_many(&rest)
        .map_err(|m| Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined))?
        .neg();
    let r_acc: Vec<Var> = r_idx.iter().map(|&k| qdd[k]).collect();
    let mut m = Vec::with_capacity(r_idx.len());
    let mut f = Vec::with_capacity(r_idx.len());
    for &k in &r_idx {
        let q = atom::coord(&names[k], 0);
        // d/dt ∂R/∂q̇ − ∂R/∂q = Q̃ (the p_c are constants)
        let lhs = routhian
            .diff(qd[k])
            .dt()
            .sub(&routhian.diff(q))
            .sub(&subs(&other[k])?);
        let (row, rest) = split_linear(&lhs, &r_acc).map_err(|m| {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
        })?;
        m.push(row);
        f.push(rest.neg());
    }
    let acc = linear::solve(&m, &f).map_err(|_| {
        Diagnostic::global("the reduced equations are singular in the remaining accelerations")
            .with_hint("the remaining coordinates need kinetic energy of their own")
            .with_kind(crate::diag::ErrorKind::SingularSystem {
                unknowns: Vec::new(),
            })
    })?;
    Ok(Routh {
        routhian,
        effective_potential,
        accelerations: r_idx.iter().map(|&k| names[k].clone()).zip(acc).collect(),
    })
}
