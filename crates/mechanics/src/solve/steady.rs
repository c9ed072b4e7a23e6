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
    /// The other roots of a condition quadratic in the rate (the analysis
    /// is about `value`; `--at q'=…` gives one of these).
    pub others: Vec<Expr>,
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
    /// The conditions free of the unknown rates that do not vanish
    /// identically but do at the `--set` values (coordinate, F): the
    /// steady motion exists there, and on the surface F = 0.
    pub held: Vec<(String, Expr)>,
}

/// The rates found from a steady motion's conditions.
pub(super) struct Rates {
    /// The rates solved, in solving order.
    pub(super) solved: Vec<SolvedRate>,
    /// The conditions that hold only at the `--set` values.
    pub(super) held: Vec<(String, Expr)>,
}

fn math(m: crate::expr::MathError) -> Diagnostic {
    let d = Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined);
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
            .with_hint("a steady motion turns cyclic coordinates only; `qdot integrals` lists the scene's cyclic coordinates").with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
    }
    Ok(())
}

/// Solve the `conditions` (each must vanish) for the unknown rates among
/// `unknown` (coordinate names whose rate is the symbol q̇): each
/// condition in turn for the last unknown it is of degree one or two in
/// (or whose square alone it holds). A condition no rate can satisfy is
/// judged at the `--set` values `set`: one that vanishes there holds.
/// Errors name the condition that cannot be solved.
pub(super) fn solve_rates(
    conditions: &[(String, Expr)],
    unknown: &[String],
    set: &crate::algebra::sign::Values,
) -> Result<Rates, Diagnostic> {
    let mut solved: Vec<SolvedRate> = Vec::new();
    let mut held = Vec::new();
    for (coordinate, condition) in conditions {
        let mut f = condition.clone();
        for s in &solved {
            f = substitute_rate(&f, s)?;
        }
        if f.is_zero() {
            continue;
        }
        let open: Vec<&String> = unknown
            .iter()
            .filter(|u| !solved.iter().any(|s| &s.coordinate == *u))
            .collect();
        let found = open.iter().rev().find_map(|u| solve_one(&f, u, coordinate));
        if let Some(s) = found {
            solved.push(s?);
            continue;
        }
        if !set.is_empty() {
            let at = f.subs_many(&exact_values(set)).map_err(math)?;
            if at.is_zero() {
                held.push((coordinate.clone(), f));
                continue;
            }
            if is_number(&at) {
                return Err(Diagnostic::global(format!(
                    "no steady motion at the --set values: the equation of `{coordinate}` needs {} = 0, and there it is {}",
                    crate::expr::print::unicode(&f),
                    crate::expr::print::unicode(&at)
                ))
                .with_hint("give values on which the condition holds, or the position that suits them (--at)").with_kind(crate::diag::ErrorKind::NoEquilibrium));
            }
        }
        if unknown.is_empty() {
            return Err(Diagnostic::global(format!(
                "no steady motion here: the equation of `{coordinate}` leaves {} ≠ 0",
                crate::expr::print::unicode(&f)
            ))
            .with_hint("leave a rate to be found (--steady q without q' in --at), or give the position that suits the rates").with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
        let degree = open
            .iter()
            .map(|u| f.num().degree(atom::coord(u, 1)))
            .max()
            .unwrap_or(0);
        let why = if degree > 2 {
            format!(", of degree {degree} in the rate: qdot solves a rate's condition of degree two at most")
        } else if degree == 0 {
            ", which holds no rate: a condition on the parameters and the position".to_string()
        } else {
            ", and qdot cannot solve that for a rate".to_string()
        };
        return Err(Diagnostic::global(format!(
            "the steady motion needs {} = 0 (the equation of `{coordinate}`){why}",
            crate::expr::print::unicode(&f)
        ))
        .with_hint(if degree == 0 && set.is_empty() {
            "give the parameters values on which it holds (--set), or the position that suits them (--at)"
        } else {
            "give the rates with --at, e.g. --at \"theta=pi/3,phi'=2\", or the position that suits them"
        }).with_kind(crate::diag::ErrorKind::NoEquilibrium));
    }
    Ok(Rates { solved, held })
}

/// Whether `e` is a number (radicals and π allowed): no parameter,
/// coordinate, unknown or given function in it.
fn is_number(e: &Expr) -> bool {
    e.vars().into_iter().all(|v| {
        std::iter::once(v)
            .chain(atom::inner_atoms(v).iter().copied())
            .all(|w| {
                !matches!(
                    atom::atom(w),
                    atom::Atom::Param(_)
                        | atom::Atom::Coord(..)
                        | atom::Atom::Unknown(_)
                        | atom::Atom::Given(..)
                        | atom::Atom::Time
                )
            })
    })
}

/// The `--set` values as exact rationals: each double's shortest decimal,
/// the number as written.
fn exact_values(
    set: &crate::algebra::sign::Values,
) -> rustc_hash::FxHashMap<crate::poly::Var, Expr> {
    set.iter()
        .filter_map(|(k, v)| {
            let q: crate::num::Q = format!("{v}").parse().ok()?;
            Some((atom::param(k), Expr::rational(q)))
        })
        .collect()
}

/// `f = 0` solved for the rate of `coordinate` (the condition of
/// `of`): linear in it, in its square alone, or quadratic (both roots,
/// the one with +√ first); `None` when none of these.
fn solve_one(f: &Expr, coordinate: &str, of: &str) -> Option<Result<SolvedRate, Diagnostic>> {
    let u = atom::coord(coordinate, 1);
    if f.den().degree(u) > 0 {
        return None;
    }
    // the coefficients over their common factor (r0 of m·r0·u² + … = 0)
    let polys = f.num().coeffs_in(u);
    let common = polys
        .iter()
        .filter(|c| !c.is_zero())
        .fold(
            Poly::zero(),
            |g, c| if g.is_zero() { c.clone() } else { g.gcd(c) },
        );
    let cs: Vec<Expr> = polys
        .into_iter()
        .map(|c| Expr::from_poly(c.div_exact(&common).unwrap_or(c)))
        .collect();
    let solved = |squared: bool, value: Result<Vec<Expr>, Diagnostic>| {
        Some(value.map(|mut roots| {
            let value = roots.remove(0);
            SolvedRate {
                coordinate: coordinate.to_string(),
                squared,
                value,
                others: roots,
            }
        }))
    };
    let ratio = |a: &Expr, b: &Expr| a.neg().div(b).map_err(math);
    match cs.as_slice() {
        [c0, c1] if !c1.is_zero() => solved(false, ratio(c0, c1).map(|r| vec![r])),
        [c0, c1, c2] if c1.is_zero() && !c2.is_zero() && !c0.is_zero() => {
            solved(true, ratio(c0, c2).map(|r| vec![r]))
        }
        [c0, c1, c2] if !c1.is_zero() && !c2.is_zero() => {
            solved(false, quadratic_roots(c0, c1, c2, coordinate, of))
        }
        _ => None,
    }
}

/// The roots of c2·u² + c1·u + c0 = 0 (c1, c2 ≠ 0): (−c1 ± √D)/(2·c2),
/// the + root first; refused when D < 0 for every value of the
/// parameters.
fn quadratic_roots(
    c0: &Expr,
    c1: &Expr,
    c2: &Expr,
    coordinate: &str,
    of: &str,
) -> Result<Vec<Expr>, Diagnostic> {
    if c0.is_zero() {
        return Ok(vec![c1.neg().div(c2).map_err(math)?, Expr::zero()]);
    }
    let disc = c1
        .mul(c1)
        .sub(&c0.mul(c2).scale(&crate::num::Q::from_i64(4)));
    let rate = crate::expr::print::pretty_name(coordinate, 1);
    if crate::algebra::sign::sign_exact(&disc) == Some(crate::algebra::sign::Sign::Negative) {
        return Err(Diagnostic::global(format!(
            "no steady motion: the equation of `{of}` is quadratic in {rate} with the discriminant {} < 0, so no real rate satisfies it",
            crate::expr::print::unicode(&disc)
        )).with_kind(crate::diag::ErrorKind::NoEquilibrium));
    }
    let root = crate::expr::func::sqrt(&disc).map_err(math)?;
    let twice = c2.scale(&crate::num::Q::from_i64(2));
    let plus = c1.neg().add(&root).div(&twice).map_err(math)?;
    let minus = c1.neg().sub(&root).div(&twice).map_err(math)?;
    Ok(vec![plus, minus])
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
            .with_hint("a steady motion needs cyclic coordinates free of forces (no damping or load on them)").with_kind(crate::diag::ErrorKind::NoEquilibrium));
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
                ).with_kind(crate::diag::ErrorKind::SingularSystem { unknowns: Vec::new() })
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
/// ([`super::oscillations::modes_about`]). The scene's assumptions are
/// in force ([`crate::scene::Scene::assumptions_in_force`]).
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
        .with_hint("write the scene in independent coordinates")
        .with_kind(crate::diag::ErrorKind::Unsupported));
    }
    scene.assumptions_required("the search for steady motions")?;
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
            .with_hint("steady motions need time-independent forces")
            .with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
        conditions.push(f);
        at_rest.push(forces[k].subs_many(&point).map_err(math)?);
    }
    let q: Vec<crate::poly::Var> = rest.iter().map(|&k| atom::coord(&names[k], 0)).collect();
    let Some(found) =
        super::equilibrium::solve_exact(&conditions, &q).map_err(|e| e.diagnostic())?
    else {
        return Err(
            Diagnostic::global("no closed form for these steady-motion conditions")
                .with_hint("give the position and find the rate: qdot modes --steady q --at r=…")
                .with_kind(crate::diag::ErrorKind::NoClosedForm),
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
            Ok(md) => match &md.stability {
                Stability::Undecided(why) => within_existence(&md, &sol.values, rates)
                    .unwrap_or_else(|| {
                        let at: Vec<&str> = rest
                            .iter()
                            .map(|&k| scene.coordinates[k].name.as_str())
                            .collect();
                        Stability::Undecided(for_any_rate(why, &at, rates))
                    }),
                decided => decided.clone(),
            },
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

/// An undecided verdict's reason for a steady motion whose rates are
/// free: `--set` gives parameters, not rates, so its hint goes, and the
/// command that takes a rate is named.
fn for_any_rate(why: &str, at: &[&str], rates: &[(String, Expr)]) -> String {
    let plain = why
        .replace("; give values with --set", "")
        .replace(" (give values with --set)", "");
    if plain == why {
        return plain;
    }
    let given: Vec<String> = at
        .iter()
        .map(|c| format!("{c}=…"))
        .chain(rates.iter().map(|(c, _)| format!("{c}'=…")))
        .collect();
    let names: Vec<&str> = rates.iter().map(|(c, _)| c.as_str()).collect();
    format!(
        "{plain}; at one rate: qdot modes --steady {} --at \"{}\"",
        names.join(","),
        given.join(",")
    )
}

/// The verdict about a steady motion off an axis, θ0 = ±acos(w) (or
/// asin), decided where it exists: |w| < 1, written w = 1/(1 + ν) (w
/// positive), −1/(1 + ν) (negative) or (1 − ν)/(1 + ν) with ν > 0, the
/// rate solved from w and put into the reduced M, C and K. Stable when M
/// and K are positive definite and C is skew or its part is a positive
/// damping of one coordinate (Kelvin–Tait); unstable when K has an odd
/// number of negative directions (Kelvin–Tait–Chetaev). `None` when that
/// does not decide.
fn within_existence(
    md: &super::oscillations::Modes,
    at: &[Expr],
    rates: &[(String, Expr)],
) -> Option<super::equilibrium::Stability> {
    use super::equilibrium::Stability;
    use crate::algebra::sign::{sign_exact, Sign, Values};
    let w = at
        .iter()
        .flat_map(Expr::vars)
        .find_map(|v| match atom::atom(v) {
            atom::Atom::Acos(w) | atom::Atom::Asin(w) => Some(w),
            _ => None,
        })?;
    let nu = Expr::param("ν·exists");
    let one = Expr::one();
    let u = match sign_exact(&w) {
        Some(Sign::Positive) => one.div(&one.add(&nu)).ok()?,
        Some(Sign::Negative) => one.div(&one.add(&nu)).ok()?.neg(),
        _ => one.sub(&nu).div(&one.add(&nu)).ok()?,
    };
    // w = u has the roots of its numerator (w's denominator is not 0)
    let g = Expr::from_poly(w.sub(&u).num().clone());
    let open = open_rates(rates);
    let s = open
        .iter()
        .rev()
        .find_map(|c| solve_one(&g, c, c).and_then(Result::ok))
        .filter(|s| s.others.is_empty())?;
    let put = |e: &Expr| -> Option<Expr> {
        let e = substitute_rate(e, &s).ok()?;
        let free = open.iter().all(|c| !e.depends_on(atom::coord(c, 1)));
        free.then_some(e)
    };
    let all = |a: &[Vec<Expr>]| -> Option<Vec<Vec<Expr>>> {
        a.iter().map(|r| r.iter().map(&put).collect()).collect()
    };
    let (m, c, k) = (all(&md.mass)?, all(&md.damping)?, all(&md.stiffness)?);
    let none = Values::new();
    let n = m.len();
    let m_signs = super::equilibrium::minor_signs(&m, &none).ok()?;
    if !m_signs.iter().all(|s| *s == Some(Sign::Positive)) {
        return None;
    }
    let skew = (0..n).all(|i| (0..n).all(|j| c[i][j].add(&c[j][i]).is_zero()));
    let damped_one = n == 1 && sign_exact(&c[0][0]) == Some(Sign::Positive);
    if !(skew || damped_one) {
        return None;
    }
    let k_signs = super::equilibrium::minor_signs(&k, &none).ok()?;
    match super::equilibrium::jacobi(&k_signs, !skew || c.iter().flatten().any(|e| !e.is_zero())) {
        Stability::Undecided(_) => None,
        decided => Some(decided),
    }
}

/// A verdict about a steady motion whose matrices hold symbols `--set`
/// cannot give (a position `--at theta=theta0`, a rate still free): its
/// "give values with --set" names them and `--at` instead.
pub fn hint_for_free_symbols(mut md: super::oscillations::Modes) -> super::oscillations::Modes {
    use super::equilibrium::Stability;
    let Stability::Undecided(why) = &md.stability else {
        return md;
    };
    if md.steady.is_none() || !why.contains("give values with --set") {
        return md;
    }
    let mut free: Vec<crate::poly::Var> = Vec::new();
    for e in md
        .mass
        .iter()
        .chain(&md.damping)
        .chain(&md.stiffness)
        .flatten()
    {
        for v in e.vars() {
            for w in std::iter::once(v).chain(atom::inner_atoms(v).iter().copied()) {
                let symbol = matches!(
                    atom::atom(w),
                    atom::Atom::Unknown(_) | atom::Atom::Coord(_, 1)
                );
                if symbol && !free.contains(&w) {
                    free.push(w);
                }
            }
        }
    }
    if free.is_empty() {
        return md;
    }
    free.sort_by_key(|&v| crate::expr::print::unicode(&Expr::var(v)));
    let names: Vec<String> = free
        .iter()
        .map(|&v| crate::expr::print::unicode(&Expr::var(v)))
        .collect();
    let instead = format!(
        "give {} {} with --at and the parameters with --set",
        names.join(", "),
        if names.len() == 1 {
            "a value"
        } else {
            "values"
        }
    );
    md.stability = Stability::Undecided(why.replace("give values with --set", &instead));
    md
}
