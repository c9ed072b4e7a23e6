//! Steady motions (relative equilibria): cyclic coordinates turning at
//! constant rates, the other coordinates at rest.
//!
//! A coordinate absent from the equations (cyclic) can turn at a constant
//! rate Ω while the others stay at q0 when every other equation holds
//! there: those equations at (q0, q̇_c = Ω, q̈ = 0) are the steady motion's
//! conditions, solved here for a rate (linear in it: Ω = …; in its square
//! only: Ω² = …) when the rates are not all given.
//!
//! Linearized about the steady motion, a cyclic row is a time derivative,
//! d/dt(M_cc·δq̇_c + M_cr·δq̇_r + C_cr·δq_r) = 0, whose integral is the
//! perturbation of the cyclic momentum. Holding the momenta (Routh's
//! reduction, δp_c = 0) gives δq̇_c = −M_cc⁻¹·(M_cr·δq̇_r + C_cr·δq_r), and
//! the other rows become
//!
//! ```text
//! (M_rr − M_rc·A·M_cr)·δq̈ + (C_rr − M_rc·A·C_cr − C_rc·A·M_cr)·δq̇
//!                         + (K_rr − C_rc·A·C_cr)·δq = f_r,     A = M_cc⁻¹,
//! ```
//!
//! the linearization of Routh's reduced equations: its frequencies are
//! the oscillations about the steady motion (the top's nutation, the
//! conical pendulum's wobble), without the zero roots of the drift along
//! the cyclic coordinates.

use crate::diag::Diagnostic;
use crate::expr::atom;
use crate::expr::Expr;
use crate::poly::Poly;

/// A rate found from a steady motion's condition.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SolvedRate {
    /// The steady coordinate whose rate this is.
    pub coordinate: String,
    /// Whether `value` is the rate's square (the condition held only
    /// its square).
    pub squared: bool,
    /// The rate (or its square).
    pub value: Expr,
}

/// The steady motion a linearization is about.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SteadyMotion {
    /// The steady coordinates and their rates (given, or the symbol q̇
    /// itself), before solving.
    pub rates: Vec<(String, Expr)>,
    /// The other coordinates' equations at the steady motion that were
    /// not identically satisfied (coordinate, F = 0 required), as found.
    pub conditions: Vec<(String, Expr)>,
    /// The rates solved from those conditions, in solving order.
    pub solved: Vec<SolvedRate>,
}

fn math(m: crate::expr::MathError) -> Diagnostic {
    let d = Diagnostic::global(m.message);
    match m.hint {
        Some(h) => d.with_hint(h),
        None => d,
    }
}

/// The symbol of a steady coordinate's unknown rate: its velocity q̇.
pub fn rate_symbol(coordinate: &str) -> Expr {
    Expr::var(atom::coord(coordinate, 1))
}

/// Refuse a steady coordinate that appears in the equations (not cyclic).
pub(super) fn check_cyclic(
    names: &[String],
    residuals: &[Expr],
    steady: &[usize],
) -> Result<(), Diagnostic> {
    for &c in steady {
        let v = atom::coord(&names[c], 0);
        if let Some(k) = residuals.iter().position(|r| r.depends_on(v)) {
            return Err(Diagnostic::global(format!(
                "`{}` appears in the equation of `{}`, so it cannot turn at a constant rate with the others at rest",
                names[c], names[k]
            ))
            .with_hint("a steady motion turns cyclic coordinates only; `qdot integrals` lists the scene's cyclic coordinates"));
        }
    }
    Ok(())
}

/// Solve the `conditions` (each must vanish) for the unknown rates among
/// `unknown` (coordinate names whose rate is the symbol q̇): each
/// condition in turn for the last unknown it is linear in, or whose square
/// alone it holds. Errors name the condition that cannot be solved.
pub(super) fn solve_rates(
    conditions: &[(String, Expr)],
    unknown: &[String],
) -> Result<Vec<SolvedRate>, Diagnostic> {
    let mut solved: Vec<SolvedRate> = Vec::new();
    for (coordinate, condition) in conditions {
        let mut f = condition.clone();
        for s in &solved {
            f = substitute_rate(&f, s)?;
        }
        if f.is_zero() {
            continue;
        }
        let open = unknown
            .iter()
            .filter(|u| !solved.iter().any(|s| &s.coordinate == *u));
        let found = open
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .find_map(|u| solve_one(&f, u));
        match found {
            Some(s) => solved.push(s?),
            None if unknown.is_empty() => {
                return Err(Diagnostic::global(format!(
                    "no steady motion here: the equation of `{coordinate}` leaves {} ≠ 0",
                    crate::expr::print::unicode(&f)
                ))
                .with_hint("leave a rate to be found (--steady q without q' in --at), or give the position that suits the rates"))
            }
            None => {
                return Err(Diagnostic::global(format!(
                    "the steady motion needs {} = 0 (the equation of `{coordinate}`), and qdot cannot solve that for a rate",
                    crate::expr::print::unicode(&f)
                ))
                .with_hint("give the rates with --at, e.g. --at \"theta=pi/3,phi'=2\", or the position that suits them"))
            }
        }
    }
    Ok(solved)
}

/// `f = 0` solved for the rate of `coordinate`: linear in it, or in its
/// square alone; `None` when neither.
fn solve_one(f: &Expr, coordinate: &str) -> Option<Result<SolvedRate, Diagnostic>> {
    let u = atom::coord(coordinate, 1);
    if f.den().degree(u) > 0 {
        return None;
    }
    let cs = f.num().coeffs_in(u);
    let over = |a: &Poly, b: &Poly| -> Result<Expr, Diagnostic> {
        let num = Expr::from_parts(a.clone(), Poly::one()).map_err(math)?;
        let den = Expr::from_parts(b.clone(), Poly::one()).map_err(math)?;
        num.neg().div(&den).map_err(math)
    };
    let solved = |squared: bool, value: Result<Expr, Diagnostic>| {
        Some(value.map(|value| SolvedRate {
            coordinate: coordinate.to_string(),
            squared,
            value,
        }))
    };
    match cs.as_slice() {
        [c0, c1] if !c1.is_zero() => solved(false, over(c0, c1)),
        [c0, c1, c2] if c1.is_zero() && !c2.is_zero() && !c0.is_zero() => {
            solved(true, over(c0, c2))
        }
        _ => None,
    }
}

/// `e` with a solved rate put in: the rate replaced, or for a solved
/// square every u^(2j+e) written v^j·u^e.
pub fn substitute_rate(e: &Expr, s: &SolvedRate) -> Result<Expr, Diagnostic> {
    let u = atom::coord(&s.coordinate, 1);
    if !s.squared {
        return e.subs(u, &s.value).map_err(math);
    }
    let reduce = |p: &Poly| -> Result<Expr, Diagnostic> {
        let mut out = Expr::zero();
        for (k, c) in p.coeffs_in(u).into_iter().enumerate() {
            if c.is_zero() {
                continue;
            }
            let c = Expr::from_parts(c, Poly::one()).map_err(math)?;
            let even = s.value.powi(k as i64 / 2).map_err(math)?;
            let odd = if k % 2 == 1 {
                Expr::var(u)
            } else {
                Expr::one()
            };
            out = out.add(&c.mul(&even).mul(&odd));
        }
        Ok(out)
    };
    reduce(e.num())?.div(&reduce(e.den())?).map_err(math)
}

/// M, C and K.
type Matrices = [Vec<Vec<Expr>>; 3];

/// Routh's reduction of the linearized system about a steady motion: the
/// rows and columns of `steady` removed, the momenta held (see the module
/// documentation). Returns the reduced [M, C, K] and forcing over `rest`.
pub(super) fn routh_reduce(
    names: &[String],
    [m, c, k]: [&[Vec<Expr>]; 3],
    forcing: &[Expr],
    steady: &[usize],
) -> Result<(Matrices, Vec<Expr>), Diagnostic> {
    let n = names.len();
    let rest: Vec<usize> = (0..n).filter(|i| !steady.contains(i)).collect();
    for &i in steady {
        let pushed = rest.iter().any(|&j| !k[i][j].is_zero())
            || steady.iter().any(|&j| !c[i][j].is_zero())
            || !forcing[i].is_zero();
        if pushed {
            return Err(Diagnostic::global(format!(
                "a force acts on `{}` about the steady motion, so its momentum is not conserved and Routh's reduction does not apply",
                names[i]
            ))
            .with_hint("a steady motion needs cyclic coordinates free of forces (no damping or load on them)"));
        }
    }
    let block = |a: &[Vec<Expr>], rows: &[usize], cols: &[usize]| -> Vec<Vec<Expr>> {
        rows.iter()
            .map(|&i| cols.iter().map(|&j| a[i][j].clone()).collect())
            .collect()
    };
    let m_cc = block(m, steady, steady);
    // A·X for each column X of a steady-by-rest block
    let inverse_times = |b: Vec<Vec<Expr>>| -> Result<Vec<Vec<Expr>>, Diagnostic> {
        let mut cols = Vec::with_capacity(rest.len());
        for j in 0..rest.len() {
            let col: Vec<Expr> = b.iter().map(|row| row[j].clone()).collect();
            cols.push(crate::algebra::linear::solve(&m_cc, &col).map_err(|_| {
                Diagnostic::global(
                    "the steady coordinates' mass matrix is singular there (a coordinate singularity, like an azimuth at the pole), so their momenta do not fix their rates",
                )
            })?);
        }
        Ok((0..steady.len())
            .map(|i| cols.iter().map(|col| col[i].clone()).collect())
            .collect())
    };
    let am = inverse_times(block(m, steady, &rest))?;
    let ac = inverse_times(block(c, steady, &rest))?;
    let (m_rc, c_rc) = (block(m, &rest, steady), block(c, &rest, steady));
    let times = |a: &[Vec<Expr>], b: &[Vec<Expr>], i: usize, j: usize| -> Expr {
        (0..steady.len()).fold(Expr::zero(), |s, l| s.add(&a[i][l].mul(&b[l][j])))
    };
    let r = rest.len();
    let mut out = [
        block(m, &rest, &rest),
        block(c, &rest, &rest),
        block(k, &rest, &rest),
    ];
    #[allow(clippy::needless_range_loop)] // three matrices at (i, j)
    for i in 0..r {
        for j in 0..r {
            out[0][i][j] = out[0][i][j].sub(&times(&m_rc, &am, i, j));
            out[1][i][j] = out[1][i][j]
                .sub(&times(&m_rc, &ac, i, j))
                .sub(&times(&c_rc, &am, i, j));
            out[2][i][j] = out[2][i][j].sub(&times(&c_rc, &ac, i, j));
        }
    }
    let f = rest.iter().map(|&i| forcing[i].clone()).collect();
    Ok((out, f))
}

/// The rate variables of the steady coordinates that are still symbols.
pub(super) fn open_rates(rates: &[(String, Expr)]) -> Vec<String> {
    rates
        .iter()
        .filter(|(c, r)| r == &rate_symbol(c))
        .map(|(c, _)| c.clone())
        .collect()
}

/// The steady motions of a scene in which the coordinates `steady` turn at
/// constant rates (their symbols q̇): the other coordinates' equations at
/// (q̇_r = 0, q̇_c = q̇_c, q̈ = 0) solved for those coordinates in closed
/// form, each solution classified by the linearization about it
/// ([`super::oscillations::modes_about`]).
pub fn steady_motions(
    scene: &crate::scene::Scene,
    steady: &[usize],
    set: &crate::algebra::sign::Values,
) -> Result<super::equilibrium::Equilibria, Diagnostic> {
    crate::diag::bounded(|| steady_motions_within(scene, steady, set))
}

/// [`steady_motions`] within the budget in force.
fn steady_motions_within(
    scene: &crate::scene::Scene,
    steady: &[usize],
    set: &crate::algebra::sign::Values,
) -> Result<super::equilibrium::Equilibria, Diagnostic> {
    scene.expanded_only("the search for steady motions")?;
    if !scene.constraints.is_empty() {
        return Err(Diagnostic::global(
            "steady motions of a scene with constraints are not supported",
        )
        .with_hint("write the scene in independent coordinates"));
    }
    crate::algebra::assume::assuming(&scene.assumptions, || {
        let _context = crate::budget::enter(|| "finding the steady motions".into(), None);
        let l = scene.lagrange()?;
        let names = l.coordinates.clone();
        let residuals: Vec<Expr> = l.equations.iter().map(|e| e.lhs.sub(&e.rhs)).collect();
        check_cyclic(&names, &residuals, steady)?;
        let rest: Vec<usize> = (0..names.len()).filter(|i| !steady.contains(i)).collect();
        let mut point = rustc_hash::FxHashMap::default();
        for (k, c) in names.iter().enumerate() {
            let rate = if steady.contains(&k) {
                rate_symbol(c)
            } else {
                Expr::zero()
            };
            point.insert(atom::coord(c, 1), rate);
            point.insert(atom::coord(c, 2), Expr::zero());
        }
        let forces = crate::mechanics::generalized_forces(scene);
        let mut conditions = Vec::with_capacity(rest.len());
        let mut at_rest = Vec::with_capacity(rest.len());
        for &k in &rest {
            let f = residuals[k].subs_many(&point).map_err(math)?.neg();
            if f.depends_on_time() {
                return Err(Diagnostic::global(format!(
                    "the force on `{}` depends on time, so there is no steady motion",
                    names[k]
                ))
                .with_hint("steady motions need time-independent forces"));
            }
            conditions.push(f);
            at_rest.push(forces[k].subs_many(&point).map_err(math)?);
        }
        let q: Vec<crate::poly::Var> = rest.iter().map(|&k| atom::coord(&names[k], 0)).collect();
        let Some(found) =
            super::equilibrium::solve_exact(&conditions, &q).map_err(|e| e.diagnostic())?
        else {
            return Err(
                Diagnostic::global("no closed form for these steady-motion conditions").with_hint(
                    "give the position and find the rate: qdot modes --steady q --at r=…",
                ),
            );
        };
        let rates: Vec<(String, Expr)> = steady
            .iter()
            .map(|&k| (names[k].clone(), rate_symbol(&names[k])))
            .collect();
        let motions = found
            .into_iter()
            .map(|sol| classified(scene, &rest, steady, &rates, sol, set))
            .collect::<Result<_, _>>()?;
        Ok(super::equilibrium::Equilibria::steady(
            rest.iter().map(|&k| names[k].clone()).collect(),
            at_rest,
            conditions,
            motions,
            rates,
        ))
    })
}

/// One steady motion of the search, with the verdict of the linearization
/// about it (undecided, with the reason, where that fails: the azimuth of
/// a pendulum hanging straight down is not defined).
fn classified(
    scene: &crate::scene::Scene,
    rest: &[usize],
    steady: &[usize],
    rates: &[(String, Expr)],
    sol: super::equilibrium::ExactSolution,
    set: &crate::algebra::sign::Values,
) -> Result<super::equilibrium::Equilibrium, Diagnostic> {
    use super::equilibrium::{Equilibrium, Position, Stability};
    let stability = if sol.free.is_empty() {
        let mut at = vec![Expr::zero(); rest.len() + steady.len()];
        for (&k, v) in rest.iter().zip(&sol.values) {
            at[k] = v.clone();
        }
        let reference = super::linearize::Reference::at(Some(&at)).steady(
            steady
                .iter()
                .zip(rates)
                .map(|(&k, (_, r))| (k, r.clone()))
                .collect(),
        );
        match super::oscillations::modes_about(scene, &reference, set) {
            Ok(md) => md.stability,
            Err(d) => Stability::Undecided(d.message),
        }
    } else {
        Stability::Undecided("neutral: a coordinate is free".into())
    };
    let mut e = Equilibrium::new(Position::Exact(sol.values), stability);
    e.free = sol.free;
    e.conditions = sol.conditions;
    Ok(e)
}
