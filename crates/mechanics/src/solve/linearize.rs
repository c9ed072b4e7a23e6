//! Lagrange's equations linearized about a reference motion.
//!
//! The residuals R_k(q, q̇, q̈, t) = lhs_k − Q_k are expanded to first order
//! about the reference (q = q0, q̇ = 0, q̈ = 0):
//!
//! ```text
//! M·q̈ + C·q̇ + K·q = f(t),   M = ∂R/∂q̈, C = ∂R/∂q̇, K = ∂R/∂q there,
//!                           f(t) = −R at the reference
//! ```
//!
//! f must have no constant part (the reference must be a motion). With
//! constraints the multipliers that hold the reference are found first,
//! and the system is reduced to the independent coordinates
//! (`constrained::reduce`). Small oscillations (`oscillations.rs`)
//! ask for constant M, C and K; parametric excitation allows them to
//! change with time.

use super::steady::{self, SteadyMotion};
use crate::diag::Diagnostic;
use crate::expr::atom;
use crate::expr::Expr;
use crate::poly::{Poly, Var};
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// What to linearize about.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct Reference {
    /// q0, one value per coordinate in declaration order (`None`: every
    /// q = 0).
    pub at: Option<Vec<Expr>>,
    /// The steady coordinates (a steady motion, `steady.rs`): index and
    /// rate, the rate the symbol q̇ where it is to be found. Empty: an
    /// equilibrium.
    pub steady: Vec<(usize, Expr)>,
    /// Whether M, C and K may depend on time (parametric excitation);
    /// without it such a dependence is refused.
    pub time_varying: bool,
    /// The `--set` values: a steady motion's condition that holds no
    /// unknown rate is judged at them.
    pub values: crate::algebra::sign::Values,
}

impl Reference {
    /// About `at` (every q = 0 when `None`), with constant coefficients.
    pub fn at(at: Option<&[Expr]>) -> Reference {
        Reference {
            at: at.map(<[Expr]>::to_vec),
            steady: Vec::new(),
            time_varying: false,
            values: crate::algebra::sign::Values::new(),
        }
    }

    /// This reference, with a steady motion's conditions judged at the
    /// `--set` values `values` where no rate satisfies them.
    pub fn with_values(mut self, values: &crate::algebra::sign::Values) -> Reference {
        self.values = values.clone();
        self
    }

    /// This reference with the coordinates of `steady` (index, rate)
    /// turning at constant rates.
    pub fn steady(mut self, steady: Vec<(usize, Expr)>) -> Reference {
        self.steady = steady;
        self
    }

    /// This reference, allowing coefficients that change with time.
    pub fn time_varying(mut self) -> Reference {
        self.time_varying = true;
        self
    }
}

/// M·q̈ + C·q̇ + K·q = f(t) about a reference.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Linearization {
    /// The (independent) coordinate names, in declaration order.
    pub coordinates: Vec<String>,
    /// The reference position of those coordinates.
    pub at: Vec<Expr>,
    /// M = ∂R/∂q̈ at the reference.
    pub mass: Vec<Vec<Expr>>,
    /// C = ∂R/∂q̇ at the reference.
    pub damping: Vec<Vec<Expr>>,
    /// K = ∂R/∂q at the reference.
    pub stiffness: Vec<Vec<Expr>>,
    /// f(t) = −R at the reference (no constant part).
    pub forcing: Vec<Expr>,
    /// With constraints: the coordinates they make dependent, with their
    /// values at the reference.
    pub dependent: Vec<(String, Expr)>,
    /// About a steady motion: its rates and conditions (the steady
    /// coordinates are reduced away, Routh's way).
    pub steady: Option<SteadyMotion>,
}

fn math(m: crate::expr::MathError) -> Diagnostic {
    let d = Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined);
    match m.hint {
        Some(h) => d.with_hint(h),
        None => d,
    }
}

/// Linearize the scene's equations about `reference` (the scene's
/// assumptions must be in force).
pub fn linearize(scene: &Scene, reference: &Reference) -> Result<Linearization, Diagnostic> {
    crate::diag::bounded(|| linearize_within(scene, reference))
}

/// [`linearize`] within the budget in force.
fn linearize_within(scene: &Scene, reference: &Reference) -> Result<Linearization, Diagnostic> {
    let l = scene.lagrange()?;
    let names = l.coordinates.clone();
    let n = names.len();
    let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
    let q0: Vec<Expr> = match &reference.at {
        Some(v) => v.clone(),
        None => vec![Expr::zero(); n],
    };
    let mut point: FxHashMap<Var, Expr> = FxHashMap::default();
    for (k, c) in names.iter().enumerate() {
        point.insert(q[k], q0[k].clone());
        point.insert(atom::coord(c, 1), Expr::zero());
        point.insert(atom::coord(c, 2), Expr::zero());
    }
    let residuals: Vec<Expr> = l.equations.iter().map(|e| e.lhs.sub(&e.rhs)).collect();
    if !reference.steady.is_empty() {
        if !scene.constraints.is_empty() {
            return Err(Diagnostic::global(
                "steady motions of a scene with constraints are not supported",
            )
            .with_hint("write the scene in independent coordinates")
            .with_kind(crate::diag::ErrorKind::Unsupported));
        }
        return linearize_steady(&names, &q0, &residuals, point, reference);
    }
    if !scene.constraints.is_empty() {
        // the multipliers that hold the reference
        let rest: Vec<Expr> = residuals
            .iter()
            .map(|r| {
                let mut p = point.clone();
                for c in &scene.constraints {
                    p.insert(atom::unknown(&c.multiplier), Expr::zero());
                }
                r.subs_many(&p).map_err(math)
            })
            .collect::<Result<_, _>>()?;
        point.extend(super::constrained::multipliers_at(scene, &rest, &q, &q0)?);
    }
    let [mass, damping, stiffness] = jacobians(&names, &residuals, &point, reference)?;
    let forcing = forcing_at(&names, &q0, &residuals, &point)?;
    if scene.constraints.is_empty() {
        return Ok(Linearization {
            coordinates: names,
            at: q0,
            mass,
            damping,
            stiffness,
            forcing,
            dependent: Vec::new(),
            steady: None,
        });
    }
    let ([m, c, k], f, kept) =
        super::constrained::reduce(scene, &q, &q0, [&mass, &damping, &stiffness], &forcing)?;
    let dependent = (0..n)
        .filter(|i| !kept.contains(i))
        .map(|i| (names[i].clone(), q0[i].clone()))
        .collect();
    Ok(Linearization {
        coordinates: kept.iter().map(|&i| names[i].clone()).collect(),
        at: kept.iter().map(|&i| q0[i].clone()).collect(),
        mass: m,
        damping: c,
        stiffness: k,
        forcing: f,
        dependent,
        steady: None,
    })
}

/// [`linearize`] about a steady motion: the steady coordinates turn at
/// their rates (unknown rates solved from the other equations), then are
/// reduced away with their momenta held.
fn linearize_steady(
    names: &[String],
    q0: &[Expr],
    residuals: &[Expr],
    mut point: FxHashMap<Var, Expr>,
    reference: &Reference,
) -> Result<Linearization, Diagnostic> {
    let idx: Vec<usize> = reference.steady.iter().map(|(i, _)| *i).collect();
    steady::check_cyclic(names, residuals, &idx)?;
    let mut rates = Vec::with_capacity(idx.len());
    for (i, rate) in &reference.steady {
        point.insert(atom::coord(&names[*i], 0), Expr::zero());
        point.insert(atom::coord(&names[*i], 1), rate.clone());
        rates.push((names[*i].clone(), rate.clone()));
    }
    let t = atom::time();
    let mut conditions = Vec::new();
    for (k, r) in residuals.iter().enumerate() {
        let (fixed, _) = split_time(&r.subs_many(&point).map_err(math)?.neg(), t);
        if !fixed.is_zero() && !idx.contains(&k) {
            conditions.push((names[k].clone(), fixed));
        }
    }
    let steady::Rates { solved, held } =
        steady::solve_rates(&conditions, &steady::open_rates(&rates), &reference.values)?;
    let put = |e: &Expr| -> Result<Expr, Diagnostic> {
        solved
            .iter()
            .try_fold(e.clone(), |e, s| steady::substitute_rate(&e, s))
    };
    let [mass, damping, stiffness] = jacobians(names, residuals, &point, reference)?;
    let mut forcing = Vec::with_capacity(names.len());
    for (k, r) in residuals.iter().enumerate() {
        let f = put(&r.subs_many(&point).map_err(math)?.neg())?;
        let (fixed, _) = split_time(&f, t);
        // a condition that holds at the --set values leaves no force there
        if held.iter().any(|(c, _)| c == &names[k]) {
            forcing.push(f.sub(&fixed));
            continue;
        }
        if !fixed.is_zero() {
            return Err(Diagnostic::global(format!(
                "no steady motion here: the equation of `{}` leaves {} ≠ 0",
                names[k],
                crate::expr::print::unicode(&fixed)
            ))
            .with_hint("a steady motion needs one unknown rate per condition; give the rates with --at q'=value").with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
        forcing.push(f);
    }
    let ([m, c, k], f) =
        steady::routh_reduce(names, [&mass, &damping, &stiffness], &forcing, &idx)?;
    let put_all = |a: Vec<Vec<Expr>>| -> Result<Vec<Vec<Expr>>, Diagnostic> {
        a.iter().map(|row| row.iter().map(put).collect()).collect()
    };
    let rest: Vec<usize> = (0..names.len()).filter(|i| !idx.contains(i)).collect();
    Ok(Linearization {
        coordinates: rest.iter().map(|&i| names[i].clone()).collect(),
        at: rest.iter().map(|&i| q0[i].clone()).collect(),
        mass: put_all(m)?,
        damping: put_all(c)?,
        stiffness: put_all(k)?,
        forcing: f,
        dependent: Vec::new(),
        steady: Some(SteadyMotion {
            rates,
            conditions,
            solved,
            held,
        }),
    })
}

/// M = ∂R/∂q̈, C = ∂R/∂q̇ and K = ∂R/∂q at `point`; refused when they
/// change with time and the reference does not allow it.
fn jacobians(
    names: &[String],
    residuals: &[Expr],
    point: &FxHashMap<Var, Expr>,
    reference: &Reference,
) -> Result<[Vec<Vec<Expr>>; 3], Diagnostic> {
    let n = names.len();
    let at_point = |e: &Expr| e.subs_many(point).map_err(math);
    let mut mass = vec![vec![Expr::zero(); n]; n];
    let mut damping = vec![vec![Expr::zero(); n]; n];
    let mut stiffness = vec![vec![Expr::zero(); n]; n];
    let t = atom::time();
    let changes = |e: &Expr| e.depends_on(t) || super::equilibrium::has_given_function(e);
    for (k, r) in residuals.iter().enumerate() {
        for (j, c) in names.iter().enumerate() {
            mass[k][j] = at_point(&r.diff(atom::coord(c, 2)))?;
            damping[k][j] = at_point(&r.diff(atom::coord(c, 1)))?;
            stiffness[k][j] = at_point(&r.diff(atom::coord(c, 0)))?;
            let moving =
                changes(&stiffness[k][j]) || changes(&mass[k][j]) || changes(&damping[k][j]);
            if moving && !reference.time_varying {
                return Err(Diagnostic::global(format!(
                    "the linearized coefficients of `{}` depend on time (parametric excitation)",
                    names[k]
                ))
                .with_hint("small oscillations need constant M, C and K; for periodic ones `qdot floquet` gives the Floquet multipliers and the stability").with_kind(crate::diag::ErrorKind::Unsupported));
            }
        }
    }
    Ok([mass, damping, stiffness])
}

/// f(t) = −R at the reference, refused when it has a constant part (the
/// reference is then not a motion of the scene).
fn forcing_at(
    names: &[String],
    q0: &[Expr],
    residuals: &[Expr],
    point: &FxHashMap<Var, Expr>,
) -> Result<Vec<Expr>, Diagnostic> {
    let t = atom::time();
    let mut forcing = Vec::with_capacity(names.len());
    for (k, r) in residuals.iter().enumerate() {
        let f = r.subs_many(point).map_err(math)?.neg();
        // the mean over time: cos(2·p·t) = 1 − 2·sin²(p·t) has none
        let (static_part, moving) = super::response::mean_over_time(&f).unwrap_or_else(|| {
            let (fixed, moving) = split_time(&f, t);
            (fixed, !moving.is_zero())
        });
        if !static_part.is_zero() {
            let what = if moving { "has the mean" } else { "is" };
            let q0s: Vec<String> = names
                .iter()
                .zip(q0)
                .map(|(c, v)| format!("{c} = {}", crate::expr::print::input(v)))
                .collect();
            return Err(Diagnostic::global(format!(
                "{} is not an equilibrium: the force on `{}` there {what} {} ≠ 0",
                q0s.join(", "),
                names[k],
                crate::expr::print::unicode(&static_part)
            ))
            .with_hint(
                "`qdot equilibrium` finds the equilibria; linearize about one with --at q=value",
            )
            .with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
        forcing.push(f);
    }
    Ok(forcing)
}

/// Split e into (terms free of t, terms with t) over its denominator.
pub(super) fn split_time(e: &Expr, t: Var) -> (Expr, Expr) {
    let mut fixed = Poly::zero();
    let mut moving = Poly::zero();
    for (m, c) in e.num().terms() {
        let term = Poly::monomial(m.clone(), c.clone());
        if m.0.iter().any(|&(v, _)| Expr::var(v).depends_on(t)) {
            moving = &moving + &term;
        } else {
            fixed = &fixed + &term;
        }
    }
    let den = e.den().clone();
    (
        Expr::from_parts(fixed, den.clone()).unwrap_or_else(|_| Expr::zero()),
        Expr::from_parts(moving, den).unwrap_or_else(|_| Expr::zero()),
    )
}
