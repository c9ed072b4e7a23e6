//! Equilibria on holonomic constraints: Lagrange's multiplier rule at rest.
//!
//! With the constraints g_j(q) = 0 and their gradients a_j = ∂g_j/∂q, a
//! position of rest is an equilibrium when the constraints can hold the
//! forces there:
//!
//! ```text
//! F_k(q) + Σ_j λ_j·a_jk(q) = 0  (k = 1…n),   g_j(q) = 0  (j = 1…m),
//! ```
//!
//! n + m equations in q and λ, solved by the exact search of free
//! equilibria (λ enters linearly), or without a closed form by Newton's
//! method over (q, λ) given every parameter. λ_j·a_j is the constraint force at the
//! equilibrium. Stability (Lagrange–Dirichlet on the constraint manifold):
//! the Hessian K = −∂(F + Aᵀ·λ)/∂q of V − λ·g, restricted to the tangent
//! space, K_c = Zᵀ·K·Z with A·Z = 0, decided by its leading minors.
//!
//! Small oscillations on the constraints use the same Z, chosen so that the
//! coordinates of no pivot of A (the *independent* ones) are themselves the
//! reduced coordinates: δq = Z·δs with δs those coordinates' displacements,
//! M_c = Zᵀ·M·Z, C_c = Zᵀ·C·Z, K_c = Zᵀ·K·Z and f_c = Zᵀ·f.

use super::definite::{
    matrix_at, negated, negated_f64, undamped_grows_f64, AtRest, Mass, Stiffness,
};
use super::equilibrium::{
    classify_numeric, distinct_roots, jacobi, minor_signs, numeric_values, periodic_coordinates,
    solve_exact, Equilibrium, Position, Stability,
};
use super::numeric::{find_roots, RootOptions};
use crate::algebra::sign::{Sign, Values};
use crate::diag::Diagnostic;
use crate::expr::atom::Atom;
use crate::expr::{atom, Expr};
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

const HINT: &str =
    "write the scene in independent coordinates (the pendulum's angle instead of x, y) for its equilibria";

const OSCILLATIONS_HINT: &str =
    "write the scene in independent coordinates for its small oscillations";

/// The equilibria of a scene with constraints: `conditions` are the
/// F_k at rest (free of t), `q` the coordinates' variables; and whether
/// they were found in closed form (else numerically, given every
/// parameter's value).
pub(super) fn constrained_equilibria(
    scene: &Scene,
    conditions: &[Expr],
    q: &[Var],
    set: &Values,
    gyroscopic: bool,
    inertia: Option<&AtRest>,
) -> Result<(Vec<Equilibrium>, bool), Diagnostic> {
    let n = q.len();
    let mut gs = Vec::with_capacity(scene.constraints.len());
    let mut lambdas = Vec::with_capacity(scene.constraints.len());
    for (j, c) in scene.constraints.iter().enumerate() {
        if !c.holonomic {
            return Err(Diagnostic::error(
                c.span,
                format!("equilibria under the constraint {} are not found: it restricts the velocities, not the position", c.label(j)),
            )
            .with_hint(super::integrable::hint(c, q, HINT)).with_kind(crate::diag::ErrorKind::Unsupported));
        }
        if c.expression.depends_on(atom::time())
            || super::equilibrium::has_given_function(&c.expression)
        {
            return Err(Diagnostic::error(
                c.span,
                format!(
                    "the constraint {} moves with time, so there is no static equilibrium",
                    c.label(j)
                ),
            )
            .with_hint("equilibria need fixed constraints")
            .with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
        gs.push(c.expression.clone());
        lambdas.push(atom::unknown(&c.multiplier));
    }
    let m = gs.len();
    // a_jk = ∂g_j/∂q_k, and F + Aᵀ·λ
    let a: Vec<Vec<Expr>> = gs
        .iter()
        .map(|g| q.iter().map(|&v| g.diff(v)).collect())
        .collect();
    let mut eqs: Vec<Expr> = (0..n)
        .map(|k| {
            (0..m).fold(conditions[k].clone(), |s, j| {
                s.add(&Expr::var(lambdas[j]).mul(&a[j][k]))
            })
        })
        .collect();
    let k_full: Vec<Vec<Expr>> = eqs
        .iter()
        .map(|f| q.iter().map(|&v| f.diff(v).neg()).collect())
        .collect();
    eqs.extend(gs.iter().cloned());
    let vars: Vec<Var> = q.iter().chain(&lambdas).copied().collect();
    let all_set = !set.is_empty() && scene.parameters.iter().all(|p| set.contains_key(&p.name));
    let Some(sols) = solve_exact(&eqs, &vars).map_err(|e| e.diagnostic())? else {
        if !all_set {
            return Err(Diagnostic::global(
                "no closed form for the equilibria on these constraints; they can be solved numerically given parameter values",
            )
            .with_hint("give every parameter a value with `--set`").with_kind(crate::diag::ErrorKind::NoClosedForm));
        }
        let numeric = Numeric {
            eqs: &eqs,
            k_full: &k_full,
            a: &a,
            inertia,
            vars: &vars,
            n,
        };
        return Ok((numeric.solve(set, gyroscopic), false));
    };
    let mut found = Vec::new();
    for s in sols {
        let (qv, lv) = s.values.split_at(n);
        let approx = numeric_values(qv, set);
        if all_set && approx.is_none() {
            continue;
        }
        let stability = if s.free.is_empty() {
            classify(&k_full, &a, inertia, &vars, &s.values, set, gyroscopic)
        } else {
            Stability::Undecided("neutral: a coordinate or a multiplier is free".into())
        };
        let mut e = Equilibrium::new(Position::Exact(qv.to_vec()), stability);
        e.free = s.free.iter().copied().filter(|&k| k < n).collect();
        e.conditions = if approx.is_some() {
            Vec::new()
        } else {
            s.conditions
        };
        e.approx = approx;
        e.multipliers = scene
            .constraints
            .iter()
            .zip(lv)
            .map(|(c, v)| (c.multiplier.clone(), v.clone()))
            .collect();
        found.push(e);
    }
    Ok((found, true))
}

/// The augmented equilibrium conditions, solved numerically by Newton's
/// method with deflation over (q, λ), every parameter given.
struct Numeric<'a> {
    eqs: &'a [Expr],
    k_full: &'a [Vec<Expr>],
    a: &'a [Vec<Expr>],
    inertia: Option<&'a AtRest>,
    vars: &'a [Var],
    n: usize,
}

impl Numeric<'_> {
    fn solve(&self, set: &Values, gyroscopic: bool) -> Vec<Equilibrium> {
        let eval = |e: &Expr, x: &[f64]| -> Option<f64> {
            e.eval_f64(&|at: &Atom| match at {
                Atom::Param(name) => set.get(&**name).copied(),
                Atom::Coord(..) | Atom::Unknown(_) => self
                    .vars
                    .iter()
                    .position(|&v| atom::atom(v) == *at)
                    .map(|i| x[i]),
                _ => None,
            })
            .filter(|v| v.is_finite())
        };
        let matrix = |m: &[Vec<Expr>], x: &[f64]| -> Option<Vec<Vec<f64>>> {
            m.iter()
                .map(|row| row.iter().map(|e| eval(e, x)).collect())
                .collect()
        };
        let jac: Vec<Vec<Expr>> = self
            .eqs
            .iter()
            .map(|f| self.vars.iter().map(|&v| f.diff(v)).collect())
            .collect();
        let f = |x: &[f64]| -> Option<Vec<f64>> { self.eqs.iter().map(|e| eval(e, x)).collect() };
        let j = |x: &[f64]| matrix(&jac, x);
        let mut periodic = periodic_coordinates(self.eqs, &self.vars[..self.n]);
        periodic.resize(self.vars.len(), false);
        let opts = RootOptions {
            periodic,
            ..RootOptions::default()
        };
        let roots = find_roots(&f, &j, &opts);
        distinct_roots(roots, &opts.periodic)
            .into_iter()
            .map(|r| {
                let stability = match (matrix(self.k_full, &r.x), matrix(self.a, &r.x)) {
                    (Some(k), Some(a)) => match numeric_null_basis(&a, self.n) {
                        Some(z) if !z.is_empty() => {
                            let kc = sandwich_f64(&k, &z);
                            let potential = |negate: bool| {
                                classify_numeric(
                                    &if negate { negated_f64(&kc) } else { kc.clone() },
                                    gyroscopic,
                                )
                            };
                            match self.inertia.map(|i| matrix(i.mass(), &r.x)) {
                                None => potential(false),
                                Some(None) => {
                                    Stability::Undecided("the mass matrix is undefined here".into())
                                }
                                Some(Some(m)) => {
                                    let mc = sandwich_f64(&m, &z);
                                    let free = || self.inertia.is_some_and(AtRest::velocity_free);
                                    Mass::numeric(&mc).verdict(
                                        || Stiffness::numeric(&kc),
                                        free,
                                        || free() && undamped_grows_f64(&mc, &kc),
                                        potential,
                                    )
                                }
                            }
                        }
                        Some(_) => Stability::Undecided("the constraints leave no motion".into()),
                        None => Stability::Undecided("the constraints are dependent here".into()),
                    },
                    _ => Stability::Undecided("the Hessian is undefined here".into()),
                };
                Equilibrium::new(Position::Numeric(r.x[..self.n].to_vec()), stability)
            })
            .collect()
    }
}

/// Zᵀ·K·Z for numeric K (n×n) and the columns of Z.
fn sandwich_f64(k: &[Vec<f64>], z: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let kz: Vec<Vec<f64>> = z
        .iter()
        .map(|zc| k.iter().map(|row| dot(row, zc)).collect())
        .collect();
    z.iter()
        .map(|zi| kz.iter().map(|kzj| dot(zi, kzj)).collect())
        .collect()
}

/// A basis of {z : A·z = 0} for numeric A (m×n) by Gauss–Jordan with
/// partial pivoting; None when A's rows are dependent (relative 1e-10).
fn numeric_null_basis(a: &[Vec<f64>], n: usize) -> Option<Vec<Vec<f64>>> {
    let mut rows = a.to_vec();
    let scale = rows
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let mut pivots = Vec::with_capacity(rows.len());
    for r in 0..rows.len() {
        let (col, big) = (0..n)
            .filter(|c| !pivots.contains(c))
            .map(|c| (c, rows[r][c].abs()))
            .max_by(|x, y| x.1.total_cmp(&y.1))?;
        if big <= 1e-10 * scale {
            return None;
        }
        let p = rows[r][col];
        for x in rows[r].iter_mut() {
            *x /= p;
        }
        let pivot_row = rows[r].clone();
        for (i, row) in rows.iter_mut().enumerate() {
            if i != r {
                let f = row[col];
                for (x, y) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * y;
                }
            }
        }
        pivots.push(col);
    }
    Some(
        (0..n)
            .filter(|c| !pivots.contains(c))
            .map(|free| {
                let mut z = vec![0.0; n];
                z[free] = 1.0;
                for (r, &p) in pivots.iter().enumerate() {
                    z[p] = -rows[r][free];
                }
                z
            })
            .collect(),
    )
}

/// Stability from K restricted to the constraints' tangent space.
fn classify(
    k_full: &[Vec<Expr>],
    a: &[Vec<Expr>],
    inertia: Option<&AtRest>,
    vars: &[Var],
    values: &[Expr],
    set: &Values,
    gyroscopic: bool,
) -> Stability {
    let map: FxHashMap<Var, Expr> = vars.iter().copied().zip(values.iter().cloned()).collect();
    let at = |rows: &[Vec<Expr>]| -> Option<Vec<Vec<Expr>>> {
        rows.iter()
            .map(|r| r.iter().map(|x| x.subs_many(&map).ok()).collect())
            .collect()
    };
    let (Some(k), Some(a)) = (at(k_full), at(a)) else {
        return Stability::Undecided("the Hessian is undefined here".into());
    };
    let Some(z) = null_basis(&a, k.len()) else {
        return Stability::Undecided(
            "the constraints are dependent here (their gradients are not independent)".into(),
        );
    };
    if z.is_empty() {
        return Stability::Undecided("the constraints leave no motion".into());
    }
    // K_c = Zᵀ·K·Z, M_c = Zᵀ·M·Z
    let kc = sandwich(&k, &z);
    let potential = |negate: bool| {
        classify_restricted(
            &if negate { negated(&kc) } else { kc.clone() },
            set,
            gyroscopic,
        )
    };
    let Some(inertia) = inertia else {
        return potential(false);
    };
    let Some(m) = matrix_at(inertia.mass(), &map) else {
        return Stability::Undecided("the mass matrix is undefined here".into());
    };
    let mc = sandwich(&m, &z);
    Mass::exact(&mc, set).verdict(
        || Stiffness::exact(&kc, set),
        || inertia.velocity_free(),
        || inertia.velocity_free() && super::linear_stability::undamped_grows(&mc, &kc, set),
        potential,
    )
}

/// Zᵀ·X·Z for the columns of Z.
fn sandwich(x: &[Vec<Expr>], z: &[Vec<Expr>]) -> Vec<Vec<Expr>> {
    let xz: Vec<Vec<Expr>> = z
        .iter()
        .map(|zc| (0..x.len()).map(|i| dot(&x[i], zc)).collect())
        .collect();
    (0..z.len())
        .map(|i| (0..z.len()).map(|j| dot(&z[i], &xz[j])).collect())
        .collect()
}

/// The verdict of the restricted Hessian K_c (for a positive definite
/// kinetic energy on the constraints).
fn classify_restricted(kc: &[Vec<Expr>], set: &Values, gyroscopic: bool) -> Stability {
    let r = kc.len();
    let signs = match minor_signs(kc, set) {
        Ok(s) => s,
        Err(undecided) => return undecided,
    };
    if r == 1 && signs[0].is_none() {
        let verdict = super::condition::sign_decides(&kc[0][0]).unwrap_or_else(|| {
            format!(
                "stable when {} > 0, unstable when < 0",
                crate::expr::print::unicode(&kc[0][0])
            )
        });
        return Stability::Undecided(format!("{verdict}; give values with --set"));
    }
    if r == 1 && signs[0] == Some(Sign::Zero) {
        return Stability::Undecided(
            "the restricted Hessian vanishes: higher-order terms decide".into(),
        );
    }
    jacobi(&signs, gyroscopic)
}

/// Σ x_i·y_i.
fn dot(x: &[Expr], y: &[Expr]) -> Expr {
    x.iter()
        .zip(y)
        .fold(Expr::zero(), |s, (a, b)| s.add(&a.mul(b)))
}

/// A basis of {z : A·z = 0} (each a vector of `n` entries), by exact
/// Gauss–Jordan elimination; None when A's rows are dependent.
fn null_basis(a: &[Vec<Expr>], n: usize) -> Option<Vec<Vec<Expr>>> {
    null_basis_free(a, n).map(|(z, _)| z)
}

/// [`null_basis`] with the column each basis vector is 1 in: the free
/// (independent) coordinates, in order.
fn null_basis_free(a: &[Vec<Expr>], n: usize) -> Option<(Vec<Vec<Expr>>, Vec<usize>)> {
    let mut rows: Vec<Vec<Expr>> = a.to_vec();
    let mut pivots: Vec<usize> = Vec::with_capacity(rows.len());
    for r in 0..rows.len() {
        let col = (0..n).find(|&c| !pivots.contains(&c) && !rows[r][c].is_zero())?;
        let p = rows[r][col].clone();
        rows[r] = rows[r]
            .iter()
            .map(|x| x.div(&p).ok())
            .collect::<Option<_>>()?;
        for i in 0..rows.len() {
            if i != r && !rows[i][col].is_zero() {
                let f = rows[i][col].clone();
                let pivot_row = rows[r].clone();
                for (x, y) in rows[i].iter_mut().zip(&pivot_row) {
                    *x = x.sub(&f.mul(y));
                }
            }
        }
        pivots.push(col);
    }
    let free: Vec<usize> = (0..n).filter(|c| !pivots.contains(c)).collect();
    let basis = free
        .iter()
        .map(|&f| {
            let mut z = vec![Expr::zero(); n];
            z[f] = Expr::int(1);
            for (r, &p) in pivots.iter().enumerate() {
                z[p] = rows[r][f].neg();
            }
            z
        })
        .collect();
    Some((basis, free))
}

/// The constraints at `q0` for small oscillations: each multiplier's value
/// there (so that the equations balance: Aᵀ·λ0 = r0, r0 the residuals at
/// rest without the multipliers) as a substitution, after checking that
/// q0 lies on every constraint.
pub(super) fn multipliers_at(
    scene: &Scene,
    residuals_at_rest: &[Expr],
    q: &[Var],
    q0: &[Expr],
) -> Result<FxHashMap<Var, Expr>, Diagnostic> {
    let point: FxHashMap<Var, Expr> = q.iter().copied().zip(q0.iter().cloned()).collect();
    let at = |e: &Expr| {
        e.subs_many(&point)
            .map_err(|m| Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined))
    };
    let mut at_rows: Vec<Vec<Expr>> = Vec::with_capacity(q.len());
    let mut lambdas = Vec::new();
    for (j, c) in scene.constraints.iter().enumerate() {
        if !c.holonomic
            || c.expression.depends_on(atom::time())
            || super::equilibrium::has_given_function(&c.expression)
        {
            return Err(Diagnostic::error(
                c.span,
                format!(
                    "small oscillations under the constraint {} are not found: it {}",
                    c.label(j),
                    if c.holonomic {
                        "moves with time"
                    } else {
                        "restricts the velocities, not the position"
                    }
                ),
            )
            .with_hint(if c.holonomic {
                OSCILLATIONS_HINT.to_string()
            } else {
                super::integrable::hint(c, q, OSCILLATIONS_HINT)
            })
            .with_kind(crate::diag::ErrorKind::Unsupported));
        }
        if !at(&c.expression)?.is_zero() {
            return Err(Diagnostic::global(format!(
                "the position is not on the constraint {}: {} ≠ 0 there",
                c.label(j),
                crate::expr::print::unicode(&c.expression)
            ))
            .with_hint("linearize about an equilibrium on the constraints: --at x=0,y=-l (`qdot equilibrium` lists them)").with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
        lambdas.push(Expr::unknown(&c.multiplier));
    }
    // Aᵀ·λ = r0: n equations in the m multipliers
    for &qk in q {
        let row = scene
            .constraints
            .iter()
            .map(|c| at(&c.expression.diff(qk)))
            .collect::<Result<Vec<_>, _>>()?;
        at_rows.push(row);
    }
    let r0 = residuals_at_rest
        .iter()
        .map(at)
        .collect::<Result<Vec<_>, _>>()?;
    let sol = super::system::solve_rect(&at_rows, &r0, &lambdas).map_err(|_| {
        Diagnostic::global("the constraints' gradients are dependent at this position")
            .with_kind(crate::diag::ErrorKind::Constraints)
    })?;
    if sol.residuals.iter().any(|(_, r)| !r.is_zero()) || !sol.shape.free.is_empty() {
        return Err(Diagnostic::global(
            "this position is not an equilibrium on the constraints: no multipliers balance the forces there",
        )
        .with_hint("`qdot equilibrium` finds the equilibria on the constraints; linearize about one with --at").with_kind(crate::diag::ErrorKind::NoEquilibrium));
    }
    Ok(scene
        .constraints
        .iter()
        .map(|c| atom::unknown(&c.multiplier))
        .zip(sol.values)
        .collect())
}

/// Reduce M, C, K (n×n) and f to the independent coordinates of the
/// constraints at `q0`: the reduced matrices, f_c, and the indices of the
/// coordinates kept.
#[allow(clippy::type_complexity)]
pub(super) fn reduce(
    scene: &Scene,
    q: &[Var],
    q0: &[Expr],
    matrices: [&[Vec<Expr>]; 3],
    forcing: &[Expr],
) -> Result<([Vec<Vec<Expr>>; 3], Vec<Expr>, Vec<usize>), Diagnostic> {
    let point: FxHashMap<Var, Expr> = q.iter().copied().zip(q0.iter().cloned()).collect();
    let a = scene
        .constraints
        .iter()
        .map(|c| {
            q.iter()
                .map(|&v| c.expression.diff(v).subs_many(&point))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(|m| {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Constraints)
        })?;
    let Some((z, free)) = null_basis_free(&a, q.len()) else {
        return Err(Diagnostic::global(
            "the constraints' gradients are dependent at this position",
        )
        .with_hint("remove the constraint that the others imply")
        .with_kind(crate::diag::ErrorKind::Constraints));
    };
    if z.is_empty() {
        return Err(Diagnostic::global(
            "the constraints leave no motion: there are no oscillations",
        )
        .with_kind(crate::diag::ErrorKind::Constraints));
    }
    let sandwich = |m: &[Vec<Expr>]| -> Vec<Vec<Expr>> {
        let mz: Vec<Vec<Expr>> = z
            .iter()
            .map(|zc| m.iter().map(|row| dot(row, zc)).collect())
            .collect();
        z.iter()
            .map(|zi| mz.iter().map(|mzj| dot(zi, mzj)).collect())
            .collect()
    };
    let reduced = [
        sandwich(matrices[0]),
        sandwich(matrices[1]),
        sandwich(matrices[2]),
    ];
    let f = z.iter().map(|zc| dot(zc, forcing)).collect();
    Ok((reduced, f, free))
}

/// The force of each `reaction NAME at P` of the scene: R with
/// Σ_i R_i·∂P_i/∂q_k = λ·a_k for every coordinate k (λ from `acc`), solved
/// exactly; an error when no such R exists (the constraint acts elsewhere
/// too) or the point does not determine it.
pub fn reaction_forces(
    scene: &Scene,
    acc: &crate::mechanics::Accelerations,
) -> Result<Vec<Vec<Expr>>, Diagnostic> {
    let q: Vec<Var> = scene
        .coordinates
        .iter()
        .map(|c| atom::coord(&c.name, 0))
        .collect();
    let mut out = Vec::with_capacity(scene.reactions.len());
    for r in &scene.reactions {
        let c = &scene.constraints[r.constraint];
        let Some((_, lambda)) = acc.multipliers().get(r.constraint) else {
            return Err(
                Diagnostic::global("internal: a reaction without its multiplier")
                    .with_kind(crate::diag::ErrorKind::Internal),
            );
        };
        // Jᵀ: one row per coordinate, one column per component of P
        let jt: Vec<Vec<Expr>> = q
            .iter()
            .map(|&v| r.point.iter().map(|p| p.diff(v)).collect())
            .collect();
        let b: Vec<Expr> = c.coefficients.iter().map(|a| lambda.mul(a)).collect();
        let symbols: Vec<Expr> = (0..r.point.len())
            .map(|i| Expr::unknown(&format!("R{}", i + 1)))
            .collect();
        let label = c.label(r.constraint);
        let sol = super::system::solve_rect(&jt, &b, &symbols).map_err(|_| {
            Diagnostic::error(
                r.span,
                format!(
                    "the force of the constraint {label} at this point could not be solved for"
                ),
            )
            .with_kind(crate::diag::ErrorKind::Constraints)
        })?;
        if sol.residuals.iter().any(|(_, x)| !x.is_zero()) {
            return Err(Diagnostic::error(
                r.span,
                format!("the constraint {label} does not act at this point alone: no force there gives its generalized forces λ·a"),
            )
            .with_hint("name the point of the one body the constraint holds (a rope between two bodies acts on both)").with_kind(crate::diag::ErrorKind::Constraints));
        }
        if !sol.shape.free.is_empty() {
            return Err(Diagnostic::error(
                r.span,
                format!("the point does not determine the force of the constraint {label}: it moves in fewer directions than it has components"),
            )
            .with_hint("write the point with as many components as it moves in").with_kind(crate::diag::ErrorKind::Constraints));
        }
        out.push(sol.values);
    }
    Ok(out)
}
