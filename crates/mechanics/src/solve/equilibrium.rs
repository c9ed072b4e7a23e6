//! Equilibria: the configurations where the generalized forces vanish
//! (the seed's eq. 23.10, Q_1 = … = Q_h = 0), solved in closed form where
//! possible, numerically otherwise, and classified by the Hessian of the
//! potential.
//!
//! The condition is taken at rest, q̇ = q̈ = 0, from the full equations:
//! F_k = Q_k − (d/dt ∂E/∂q̇_k − ∂E/∂q_k), so a kinetic energy that depends on
//! q at rest (a bead on a spinning hoop) contributes its centrifugal terms
//! (relative equilibria). Without such terms F_k = Q_k.
//!
//! Exact solving works coordinate by coordinate: an equation in one
//! coordinate q is solved in closed form when it is
//! * polynomial in q of degree ≤ 2 after taking out q^k (roots 0, −b/a,
//!   the quadratic formula with exact radicals);
//! * polynomial in sin q and cos q: factors sin q (q = 0, π) and cos q
//!   (q = ±π/2) come out, then `a·sin q + b·cos q = 0` gives
//!   q = atan(−b/a) and that ± π (the seed's tan θ = 2P/(3G)), `a·sin q + d = 0`
//!   gives asin, `b·cos q + d = 0` gives ±acos, and anything else of degree ≤ 2
//!   in tan(q/2) (Weierstrass) gives q = 2·atan(t);
//!
//! and the solutions are substituted into the other equations; equations
//! linear in all remaining coordinates are solved together. What is left
//! (coupled transcendental equations) is solved numerically, by Newton's
//! method with deflation ([`super::numeric`]), given parameter values.
//!
//! Stability (Lagrange–Dirichlet): K = −∂F/∂q at the equilibrium, the Hessian
//! of the potential for conservative forces. Positive definite (all leading
//! minors > 0, decided exactly: a polynomial in positive parameters with
//! coefficients of one sign has that sign) is stable; a negative eigenvalue
//! (a sign change among the minors, Jacobi's rule) is unstable, except that
//! an even number of them may be stabilized by gyroscopic terms. For one
//! coordinate with K = 0 the first non-vanishing derivative decides.

use super::definite::{
    matrix_at, negated, negated_f64, undamped_grows_f64, AtRest, Mass, Stiffness,
};
use super::numeric::{find_roots, RootOptions};
use crate::algebra::linear::det;
use crate::algebra::sign::sign_of;
pub use crate::algebra::sign::{sign_exact, Sign, Values};
use crate::dense::Lu;
use crate::diag::Diagnostic;
use crate::expr::atom::{self, Atom};
use crate::expr::{func, Expr};
use crate::limits::MAX_EQUILIBRIUM_CASES;
use crate::num::Q;
use crate::poly::{Poly, Var};
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// How stable an equilibrium is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stability {
    /// The potential has a strict minimum there: K positive definite (for one
    /// coordinate, the first non-vanishing derivative may decide).
    Stable,
    /// A small displacement grows: the potential decreases in a direction
    /// that gyroscopic terms cannot stabilize.
    Unstable,
    /// Not decided, with the reason.
    Undecided(String),
}

impl Stability {
    /// "stable", "unstable" or "undecided".
    pub fn word(&self) -> &'static str {
        match self {
            Stability::Stable => "stable",
            Stability::Unstable => "unstable",
            Stability::Undecided(_) => "undecided",
        }
    }
}

/// The coordinates of one equilibrium.
#[derive(Clone, Debug)]
pub enum Position {
    /// Exact values, one per coordinate; a coordinate that every value of
    /// satisfies (neutral) is its own symbol (see [`Equilibrium::free`]).
    Exact(Vec<Expr>),
    /// Numeric values (from `--set` parameter values).
    Numeric(Vec<f64>),
}

/// One equilibrium.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Equilibrium {
    /// The coordinates' values at the equilibrium.
    pub position: Position,
    /// Coordinates left free (indifferent equilibrium along them).
    pub free: Vec<usize>,
    /// Conditions for the equilibrium to exist (|x| ≤ 1 under asin/acos).
    pub conditions: Vec<String>,
    /// The numeric values of an exact position, given parameter values.
    pub approx: Option<Vec<f64>>,
    /// Stable, unstable or undecided (Lagrange–Dirichlet).
    pub stability: Stability,
    /// For one coordinate, the multiplicity of the root of the condition
    /// F = 0 (1 for a simple root; 2 or more where V'' = 0).
    pub multiplicity: u32,
    /// A numeric position's digits that are certified (one coordinate: a
    /// sign change of F encloses the root); `None` when not certified.
    pub certified: Option<Vec<String>>,
    /// The interval [lo, hi] where F changes sign around a certified
    /// numeric root (one coordinate), beside its digits.
    pub enclosure: Option<(f64, f64)>,
    /// With constraints: each multiplier's value there (name, λ); λ·∂g/∂q
    /// is the constraint's force at the equilibrium. Empty without.
    pub multipliers: Vec<(String, Expr)>,
}

impl Equilibrium {
    /// An isolated, simple equilibrium at `position`, nothing else known.
    pub(super) fn new(position: Position, stability: Stability) -> Equilibrium {
        Equilibrium {
            position,
            free: Vec::new(),
            conditions: Vec::new(),
            approx: None,
            stability,
            multiplicity: 1,
            certified: None,
            enclosure: None,
            multipliers: Vec::new(),
        }
    }
}

/// The equilibria of a scene.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Equilibria {
    /// The coordinate names, in declaration order (the order of every position).
    pub coordinates: Vec<String>,
    /// Q_k at rest.
    pub forces: Vec<Expr>,
    /// F_k: the equilibrium conditions F_k = 0 (Q_k, plus the kinetic
    /// energy's terms at rest when it has any).
    pub conditions: Vec<Expr>,
    /// Whether the kinetic energy contributes terms at rest.
    pub kinetic_terms: bool,
    /// The equilibria found.
    pub equilibria: Vec<Equilibrium>,
    /// True when the positions were found in closed form.
    pub exact: bool,
    /// Steady motions (`--steady`): the steady coordinates and their rates
    /// (the symbols q̇); `coordinates` are then the others. Empty for
    /// equilibria.
    pub steady: Vec<(String, Expr)>,
}

impl Equilibria {
    /// The steady motions found by [`super::steady::steady_motions`].
    pub(super) fn steady(
        coordinates: Vec<String>,
        forces: Vec<Expr>,
        conditions: Vec<Expr>,
        motions: Vec<Equilibrium>,
        steady: Vec<(String, Expr)>,
    ) -> Equilibria {
        Equilibria {
            coordinates,
            forces,
            conditions,
            kinetic_terms: true,
            equilibria: motions,
            exact: true,
            steady,
        }
    }
}

/// Find and classify the equilibria of a scene, its assumptions in force
/// ([`Scene::assumptions_in_force`]).
pub fn equilibria(scene: &Scene, set: &Values) -> Result<Equilibria, Diagnostic> {
    crate::diag::bounded(|| {
        scene.expanded_only("the search for equilibria")?;
        scene.assumptions_required("the search for equilibria")?;
        equilibria_assumed(scene, set)
    })
}

/// [`equilibria`] once its preconditions hold.
fn equilibria_assumed(scene: &Scene, set: &Values) -> Result<Equilibria, Diagnostic> {
    let _context = crate::budget::enter(|| "finding the equilibria".into(), None);
    let n = scene.coordinates.len();
    if n == 0 {
        return Err(Diagnostic::global(
            "the scene declares no coordinates, so there is no equilibrium to find",
        )
        .with_hint("declare the generalized coordinates with `coordinates q1, q2, …`")
        .with_kind(crate::diag::ErrorKind::NothingToSolve));
    }
    let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
    let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
    let mut rest: FxHashMap<Var, Expr> = FxHashMap::default();
    // at rest every derivative vanishes; a scene has none past the second
    // (the resolver refuses them: see `Scene`)
    for c in &names {
        rest.insert(atom::coord(c, 1), Expr::zero());
        rest.insert(atom::coord(c, 2), Expr::zero());
    }
    let at_rest = |e: &Expr| {
        e.subs_many(&rest)
            .map_err(|m| Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined))
    };
    let mut forces = Vec::with_capacity(n);
    for f in crate::mechanics::generalized_forces(scene) {
        forces.push(at_rest(&f)?);
    }
    let mut conditions = forces.clone();
    let (kinetic_terms, inertia) = kinetic_at_rest(scene, &mut conditions, &at_rest)?;
    let inertia = inertia.as_ref();
    let t = atom::time();
    for (k, f) in conditions.iter().enumerate() {
        if f.depends_on(t) || has_given_function(f) {
            return Err(Diagnostic::global(format!(
                "the force on `{}` depends on time, so there is no static equilibrium",
                names[k]
            ))
            .with_hint("equilibria need time-independent forces (a given function of time counts as one that changes); remove driving terms in t to study the system at rest").with_kind(crate::diag::ErrorKind::NoEquilibrium));
        }
    }
    // K = −∂F/∂q, symbolic.
    let jac: Vec<Vec<Expr>> = conditions
        .iter()
        .map(|f| q.iter().map(|&v| f.diff(v).neg()).collect())
        .collect();
    let gyroscopic = has_gyroscopic_terms(scene, &names);
    let periodic = periodic_coordinates(&conditions, &q);

    if !scene.constraints.is_empty() {
        let (found, exact) = super::constrained::constrained_equilibria(
            scene,
            &conditions,
            &q,
            set,
            gyroscopic,
            inertia,
        )?;
        return Ok(Equilibria {
            coordinates: names,
            forces,
            conditions,
            kinetic_terms,
            equilibria: found,
            exact,
            steady: Vec::new(),
        });
    }
    let mut found = Vec::new();
    let exact = match solve_exact(&conditions, &q).map_err(|e| e.diagnostic())? {
        Some(sols) => {
            let all_set =
                !set.is_empty() && scene.parameters.iter().all(|p| set.contains_key(&p.name));
            for ExactSolution {
                values: vals,
                free,
                conditions: conds,
            } in sols
            {
                let approx = numeric_values(&vals, set);
                // (a free coordinate leaves the values symbolic: it exists)
                if all_set && approx.is_none() && free.is_empty() {
                    continue; // does not exist for these parameter values (|x| > 1)
                }
                // two closed forms can coincide at the given values (a double root)
                if let Some(a) = &approx {
                    let same = found.iter().any(|e: &Equilibrium| {
                        e.approx.as_ref().is_some_and(|b| close(a, b, &periodic))
                    });
                    if same {
                        continue;
                    }
                }
                let stability = if free.is_empty() {
                    classify_exact(&conditions, &jac, inertia, &q, &vals, set, gyroscopic)
                } else {
                    Stability::Undecided("neutral: a coordinate is free".into())
                };
                let multiplicity = match (q.as_slice(), vals.as_slice()) {
                    ([qk], [v]) if free.is_empty() => multiplicity(&conditions[0], *qk, v),
                    _ => 1,
                };
                found.push(Equilibrium {
                    position: Position::Exact(vals),
                    free,
                    conditions: if approx.is_some() { Vec::new() } else { conds },
                    approx,
                    stability,
                    multiplicity,
                    certified: None,
                    enclosure: None,
                    multipliers: Vec::new(),
                });
            }
            true
        }
        None => {
            let missing: Vec<&str> = scene
                .parameters
                .iter()
                .map(|p| p.name.as_str())
                .filter(|p| !set.contains_key(*p))
                .collect();
            if !missing.is_empty() {
                return Err(Diagnostic::global(
                    "no closed form for these equilibrium equations; they can be solved numerically given parameter values",
                )
                .with_hint(format!(
                    "give values for {} with `--set {}`",
                    missing.join(", "),
                    missing
                        .iter()
                        .map(|p| format!("{p}=…"))
                        .collect::<Vec<_>>()
                        .join(",")
                )).with_kind(crate::diag::ErrorKind::NoClosedForm));
            }
            found = solve_numeric(&conditions, &jac, inertia, &q, &periodic, set, gyroscopic);
            false
        }
    };
    Ok(Equilibria {
        coordinates: names,
        forces,
        conditions,
        kinetic_terms,
        equilibria: found,
        exact,
        steady: Vec::new(),
    })
}

/// The kinetic energy's terms at rest (centrifugal terms), taken from
/// the `conditions`, and whether there were any; and the inertia the
/// verdicts rest on (a scene with inertia forces only whose equations
/// fail to form has none: it is read as static).
fn kinetic_at_rest(
    scene: &Scene,
    conditions: &mut [Expr],
    at_rest: &impl Fn(&Expr) -> Result<Expr, Diagnostic>,
) -> Result<(bool, Option<AtRest>), Diagnostic> {
    let energies = scene.has_role(crate::parse::ast::Role::Kinetic)
        || scene.has_role(crate::parse::ast::Role::Lagrangian);
    let lagrange = if energies {
        Some(scene.lagrange()?)
    } else if scene.has_dynamics() {
        scene.lagrange().ok()
    } else {
        None
    };
    let mut kinetic_terms = false;
    if let (true, Some(l)) = (energies, &lagrange) {
        for (k, eq) in l.equations.iter().enumerate() {
            let lhs = at_rest(&eq.lhs)?;
            if !lhs.is_zero() {
                kinetic_terms = true;
                conditions[k] = conditions[k].sub(&lhs);
            }
        }
    }
    Ok((kinetic_terms, lagrange.as_ref().and_then(AtRest::of)))
}

/// Whether `e` contains a given function of time (`functions s`), at any
/// depth: it changes with time, so no position is at rest for good.
pub(super) fn has_given_function(e: &Expr) -> bool {
    e.vars().into_iter().any(|v| {
        std::iter::once(v)
            .chain(atom::inner_atoms(v).iter().copied())
            .any(|w| matches!(atom::atom(w), Atom::Given(..)))
    })
}

/// Whether E has terms linear in the velocities (gyroscopic coupling).
fn has_gyroscopic_terms(scene: &Scene, names: &[String]) -> bool {
    use crate::parse::ast::Role;
    // the whole Lagrangian: a velocity-dependent potential couples too
    let e = scene
        .role_sum(Role::Kinetic)
        .add(&scene.role_sum(Role::Lagrangian))
        .sub(&scene.role_sum(Role::Potential))
        .add(&scene.role_sum(Role::ForceFunction));
    let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
    e.num().terms().iter().any(|(m, _)| {
        m.0.iter()
            .filter(|(v, _)| qd.contains(v))
            .map(|(_, k)| k)
            .sum::<u32>()
            % 2
            == 1
    })
}

// ---------------------------------------------------------------- exact solving

/// One equilibrium in closed form, as the exact search finds it.
pub(super) struct ExactSolution {
    /// One value per coordinate (the coordinate itself where it is free).
    pub(super) values: Vec<Expr>,
    /// The coordinates that any value satisfies.
    pub(super) free: Vec<usize>,
    /// The conditions for it to exist (`|x| ≤ 1` of an asin, …).
    pub(super) conditions: Vec<String>,
}

/// The exact search split into more than [`MAX_EQUILIBRIUM_CASES`] cases.
#[derive(Debug)]
pub(super) struct TooManyCases;

impl TooManyCases {
    /// The error of the command, naming the phase and the limit.
    pub(super) fn diagnostic(&self) -> Diagnostic {
        Diagnostic::global(format!(
            "too many equilibria: the exact search for the equilibria split into more than {} cases (each root of one equation put into the others is a case)",
            crate::budget::grouped(MAX_EQUILIBRIUM_CASES)
        ))
        .with_hint("n angles with two equilibria each (a chain of n pendulums) have 2ⁿ equilibria; study fewer coordinates at once, or fix some with a constraint").with_kind(crate::diag::ErrorKind::LimitExceeded)
    }
}

/// All equilibria in closed form, `Ok(None)` if some equation has none;
/// an error when the search splits into too many cases to list.
pub(super) fn solve_exact(
    eqs: &[Expr],
    q: &[Var],
) -> Result<Option<Vec<ExactSolution>>, TooManyCases> {
    let mut search = Search {
        q,
        assigned: vec![None; q.len()],
        conds: Vec::new(),
        out: Vec::new(),
        cases: 0,
    };
    let found = search.branch(eqs.to_vec());
    if search.too_many() {
        return Err(TooManyCases);
    }
    if found.is_none() {
        return Ok(None);
    }
    // de-duplicate
    let mut uniq: Vec<ExactSolution> = Vec::new();
    for s in search.out {
        if !uniq
            .iter()
            .any(|u| u.values.iter().zip(&s.values).all(|(a, b)| a.equals(b)))
        {
            uniq.push(s);
        }
    }
    Ok(Some(uniq))
}

/// The state of the exact search: a depth-first walk over the roots of
/// one equation at a time, each root put into the other equations.
struct Search<'a> {
    q: &'a [Var],
    /// The value of each coordinate on the current branch.
    assigned: Vec<Option<Expr>>,
    /// The conditions for the current branch's roots to exist.
    conds: Vec<String>,
    /// The solutions found.
    out: Vec<ExactSolution>,
    /// The cases (calls of [`Search::branch`]) entered so far; past
    /// [`MAX_EQUILIBRIUM_CASES`] the walk stops.
    cases: usize,
}

impl Search<'_> {
    /// Whether the walk entered more than [`MAX_EQUILIBRIUM_CASES`] cases.
    fn too_many(&self) -> bool {
        self.cases > MAX_EQUILIBRIUM_CASES
    }

    /// Solve `eqs` for the coordinates not yet assigned, pushing every
    /// solution of this branch to `out`; `None` when some equation has no
    /// closed form, or the search has too many cases ([`Search::too_many`]).
    fn branch(&mut self, eqs: Vec<Expr>) -> Option<()> {
        // 2ⁿ equilibria of n uncoupled angles make 2ⁿ⁺¹ cases: count them
        // before any work, so the walk stops within its bound
        self.cases += 1;
        if self.too_many() {
            return None;
        }
        let q = self.q;
        let eqs: Vec<Expr> = eqs.into_iter().filter(|e| !e.is_zero()).collect();
        let open: Vec<usize> = (0..q.len())
            .filter(|&k| self.assigned[k].is_none())
            .collect();
        let uses = |e: &Expr, k: usize| e.depends_on(q[k]);
        if eqs.iter().any(|e| !open.iter().any(|&k| uses(e, k))) {
            return Some(()); // a nonzero constant: no equilibrium on this branch
        }
        if eqs.is_empty() {
            let free: Vec<usize> = open.clone();
            let vals = (0..q.len())
                .map(|k| self.assigned[k].clone().unwrap_or_else(|| Expr::var(q[k])))
                .collect();
            self.out.push(ExactSolution {
                values: vals,
                free,
                conditions: self.conds.clone(),
            });
            return Some(());
        }
        // Linear in all open coordinates together?
        let open_vars: Vec<Var> = open.iter().map(|&k| q[k]).collect();
        if eqs.iter().all(|e| is_linear_in(e, &open_vars)) {
            return self.linear(&eqs, &open, &open_vars);
        }
        // An equation in a single open coordinate, the smallest first.
        let single = eqs
            .iter()
            .enumerate()
            .filter_map(|(i, e)| {
                let ks: Vec<usize> = open.iter().copied().filter(|&k| uses(e, k)).collect();
                (ks.len() == 1).then(|| (i, ks[0]))
            })
            .min_by_key(|&(i, _)| eqs[i].num().len());
        let Some((i, k)) = single else {
            // A product of a factor in one coordinate and the rest: branch on
            // both (sin θ·sin φ = 0 is θ ∈ {0, π} or sin φ = 0).
            let (i, k, factor, cofactor) = eqs.iter().enumerate().find_map(|(i, e)| {
                open.iter()
                    .find_map(|&k| single_factor(e, q[k], &open_vars).map(|(f, c)| (i, k, f, c)))
            })?;
            for (root, cond) in univariate(&factor, q[k])? {
                self.assign(&eqs, None, k, root, cond)?;
            }
            let mut rest = eqs.clone();
            rest[i] = cofactor;
            return self.branch(rest);
        };
        let roots = univariate(&eqs[i], q[k])?;
        for (root, cond) in roots {
            self.assign(&eqs, Some(i), k, root, cond)?;
        }
        Some(())
    }

    /// The equations, linear in all open coordinates, solved together.
    fn linear(&mut self, eqs: &[Expr], open: &[usize], open_vars: &[Var]) -> Option<()> {
        let q = self.q;
        let mut a = Vec::new();
        let mut b = Vec::new();
        for e in eqs {
            // (no closed form on this branch if a part has none)
            let (coefs, r) = crate::mechanics::split_linear(e, open_vars).ok()?;
            a.push(coefs);
            b.push(r.neg());
        }
        let symbols: Vec<Expr> = open_vars.iter().map(|&v| Expr::var(v)).collect();
        let sol = super::system::solve_rect(&a, &b, &symbols).ok()?;
        if sol.residuals.iter().any(|(_, r)| !r.is_zero()) {
            return Some(()); // inconsistent: none
        }
        let mut vals: Vec<Expr> = (0..q.len())
            .map(|k| self.assigned[k].clone().unwrap_or_else(|| Expr::var(q[k])))
            .collect();
        for (j, &k) in open.iter().enumerate() {
            vals[k] = sol.values[j].clone();
        }
        let free = sol.shape.free.iter().map(|&j| open[j]).collect();
        self.out.push(ExactSolution {
            values: vals,
            free,
            conditions: self.conds.clone(),
        });
        Some(())
    }

    /// Put q_k = root into the equations (all but `solved`, the one the
    /// root came from) and go on.
    fn assign(
        &mut self,
        eqs: &[Expr],
        solved: Option<usize>,
        k: usize,
        root: Expr,
        cond: Vec<String>,
    ) -> Option<()> {
        let mut next = Vec::with_capacity(eqs.len());
        for (j, e) in eqs.iter().enumerate() {
            if solved == Some(j) {
                continue;
            }
            match e.subs(self.q[k], &root) {
                Ok(x) => next.push(x),
                Err(_) => return Some(()), // a denominator vanishes here
            }
        }
        self.assigned[k] = Some(root);
        let n = self.conds.len();
        self.conds.extend(cond);
        let r = self.branch(next);
        self.conds.truncate(n);
        self.assigned[k] = None;
        r
    }
}

/// If `e`'s numerator is f·g with f a non-constant factor in `qk` alone
/// (free of the other open coordinates), (f, g).
fn single_factor(e: &Expr, qk: Var, open: &[Var]) -> Option<(Expr, Expr)> {
    let num = e.num();
    let others: Vec<Var> = num
        .vars()
        .into_iter()
        .filter(|&v| open.iter().any(|&o| o != qk && Expr::var(v).depends_on(o)))
        .collect();
    if others.is_empty() {
        return None;
    }
    // The content with respect to the other coordinates' atoms.
    let mut parts = vec![num.clone()];
    for &v in &others {
        parts = parts
            .into_iter()
            .flat_map(|p| p.coeffs_in(v))
            .filter(|p| !p.is_zero())
            .collect();
    }
    let mut g = parts.first()?.clone();
    for p in &parts[1..] {
        g = g.gcd(p);
        if g.is_constant() {
            return None;
        }
    }
    let f = Expr::from_poly(g.clone());
    if !f.depends_on(qk) || g.is_constant() {
        return None;
    }
    // keep only the part in q_k: drop a parameter content
    let cof = num.div_exact(&g)?;
    Some((f, Expr::from_poly(cof)))
}

/// Degree ≤ 1 jointly in `vs`, none inside a function or a denominator.
fn is_linear_in(e: &Expr, vs: &[Var]) -> bool {
    let plain = |v: Var| vs.contains(&v) || !vs.iter().any(|&x| Expr::var(v).depends_on(x));
    if e.den().vars().iter().any(|&v| !plain(v) || vs.contains(&v)) {
        return false;
    }
    e.num().terms().iter().all(|(m, _)| {
        m.0.iter().all(|&(v, _)| plain(v))
            && m.0
                .iter()
                .filter(|(v, _)| vs.contains(v))
                .map(|(_, k)| k)
                .sum::<u32>()
                <= 1
    })
}

/// A root with the conditions for it to exist.
pub(crate) type ExactRoot = (Expr, Vec<String>);

/// The real roots of `e = 0` in the one coordinate `q`, in closed form.
fn univariate(e: &Expr, q: Var) -> Option<Vec<ExactRoot>> {
    let qe = Expr::var(q);
    let (s, c) = atom::intern_trig(&qe);
    let num = e.num();
    let mut has_q = false;
    let mut has_trig = false;
    for v in num.vars() {
        if v == q {
            has_q = true;
        } else if v == s || v == c {
            has_trig = true;
        } else if Expr::var(v).depends_on(q) {
            return None; // q inside another function
        }
    }
    let mut roots: Vec<ExactRoot> = match (has_q, has_trig) {
        (true, false) => poly_roots(num, q)?,
        (false, true) => trig_roots(num, s, c)?,
        _ => return None,
    };
    // Keep the roots where e is defined and vanishes.
    roots.retain(|(r, _)| {
        let den = Expr::from_poly(e.den().clone());
        matches!(den.subs(q, r), Ok(d) if !d.is_zero())
            && matches!(e.subs(q, r), Ok(v) if vanishes(&v))
    });
    Some(roots)
}

/// Zero exactly, or (when the canonical form misses an identity between
/// radicals) zero at sample positive parameter values: at least one sample
/// where it is defined, and ≈ 0 at every such sample (a root under asin or
/// acos is undefined where its argument leaves [−1, 1]).
fn vanishes(v: &Expr) -> bool {
    if v.is_zero() {
        return true;
    }
    let mut defined = 0;
    for seed in [0.7316, 1.3719, 2.0457, 0.1234, 3.3301, 5.0107] {
        let f = |a: &Atom| match a {
            Atom::Param(n) | Atom::Unknown(n) => {
                let h = n.bytes().fold(seed, |h, b| (h * 31.0 + b as f64) % 7.0);
                Some(0.5 + h)
            }
            _ => None,
        };
        match v.eval_f64(&f) {
            Some(x) if x.is_finite() => {
                if x.abs() > 1e-9 {
                    return false;
                }
                defined += 1;
            }
            _ => {}
        }
    }
    defined > 0
}

/// Roots of a polynomial in q: its irreducible factors over ℚ (with the
/// parameters) of degree ≤ 2 in q, each root once; `None` when a factor of
/// higher degree has roots no closed form gives. Factoring first makes a
/// multiple root one root ((1 + q)¹⁰⁰) and finds the small factors of a
/// product whose expansion has a high degree (q·(q² − 2)²).
fn poly_roots(p: &Poly, q: Var) -> Option<Vec<ExactRoot>> {
    if p.degree(q) <= 2 {
        return poly_roots_low(p, q);
    }
    let f = crate::poly::factor::factor(p);
    let mut out: Vec<ExactRoot> = Vec::new();
    for (g, _) in &f.factors {
        if g.degree(q) == 0 {
            continue;
        }
        if g.degree(q) > 2 {
            return None;
        }
        for r in poly_roots_low(g, q)? {
            if !out.iter().any(|o| o.0.equals(&r.0)) {
                out.push(r);
            }
        }
    }
    Some(out)
}

/// Roots of a polynomial in q of degree ≤ 2 after taking out q^k.
fn poly_roots_low(p: &Poly, q: Var) -> Option<Vec<ExactRoot>> {
    let cs = p.coeffs_in(q);
    let mut k = 0;
    while k < cs.len() && cs[k].is_zero() {
        k += 1;
    }
    let mut out: Vec<ExactRoot> = Vec::new();
    if k > 0 {
        out.push((Expr::zero(), Vec::new()));
    }
    let cs: Vec<Expr> = cs[k..].iter().map(|c| Expr::from_poly(c.clone())).collect();
    out.extend(quadratic(&cs)?);
    Some(out)
}

/// Roots of c0 + c1·x + c2·x² (c2 may be zero; degree ≤ 2 only).
pub(crate) fn quadratic(cs: &[Expr]) -> Option<Vec<ExactRoot>> {
    match cs.len() {
        0 | 1 => Some(Vec::new()),
        2 => Some(vec![(cs[0].neg().div(&cs[1]).ok()?, Vec::new())]),
        3 => {
            let (c0, c1, c2) = (&cs[0], &cs[1], &cs[2]);
            let disc = c1.mul(c1).sub(&c0.mul(c2).scale(&Q::from_i64(4)));
            let two_a = c2.scale(&Q::from_i64(2));
            if disc.is_zero() {
                return Some(vec![(c1.neg().div(&two_a).ok()?, Vec::new())]);
            }
            let cond = match sign_exact(&disc) {
                Some(Sign::Negative) => return Some(Vec::new()),
                Some(_) => Vec::new(),
                None => vec![format!("{} ≥ 0", crate::expr::print::unicode(&disc))],
            };
            // a perfect square P²/D² gives the pair (−c1 ± P/D)/(2c2)
            // whatever the sign of P/D (uncoupled oscillators)
            let r = match (disc.num().exact_sqrt(), disc.den().exact_sqrt()) {
                (Some(p), Some(d)) => Expr::from_parts(p, d).ok()?,
                _ => func::sqrt(&disc).ok()?,
            };
            Some(vec![
                (c1.neg().sub(&r).div(&two_a).ok()?, cond.clone()),
                (c1.neg().add(&r).div(&two_a).ok()?, cond),
            ])
        }
        _ => None,
    }
}

/// Roots of a polynomial in s = sin q, c = cos q.
fn trig_roots(p: &Poly, s: Var, c: Var) -> Option<Vec<ExactRoot>> {
    let pi = Expr::pi();
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let mut out: Vec<ExactRoot> = Vec::new();
    let mut p = p.clone();
    // sin q as a factor: q = 0, π.
    let cs = p.coeffs_in(s);
    if cs.first().is_some_and(|c0| c0.is_zero()) {
        out.push((Expr::zero(), Vec::new()));
        out.push((pi.clone(), Vec::new()));
        let k = cs.iter().take_while(|c| c.is_zero()).count();
        p = Poly::zero();
        for (i, ci) in cs.iter().enumerate().skip(k) {
            p = &p + &(ci * &Poly::var(s).pow((i - k) as u32));
        }
    }
    // cos q as a factor (c² is reduced, so: every term has c¹).
    let cc = p.coeffs_in(c);
    if cc.first().is_some_and(|c0| c0.is_zero()) && cc.len() == 2 {
        out.push((pi.scale(&half), Vec::new()));
        out.push((pi.scale(&half).neg(), Vec::new()));
        p = cc[1].clone();
    }
    if !p.contains_var(s) && !p.contains_var(c) {
        return Some(out);
    }
    let cc = p.coeffs_in(c);
    let a = cc.first().cloned().unwrap_or_default(); // A(s)
    let b = cc.get(1).cloned().unwrap_or_default(); // B(s)
    let sa = a.coeffs_in(s);
    let sb = b.coeffs_in(s);
    let ex = |p: &Poly| Expr::from_poly(p.clone());
    if sa.len() <= 2 && sb.len() <= 1 {
        let a0 = ex(sa.first().unwrap_or(&Poly::zero()));
        let a1 = ex(sa.get(1).unwrap_or(&Poly::zero()));
        let b0 = ex(sb.first().unwrap_or(&Poly::zero()));
        if a0.is_zero() && !a1.is_zero() && !b0.is_zero() {
            // a1·sin q + b0·cos q = 0: tan q = −b0/a1
            let x = b0.neg().div(&a1).ok()?;
            let r = func::atan(&x);
            let other = match sign_exact(&x) {
                Some(Sign::Positive) => r.sub(&pi),
                _ => r.add(&pi),
            };
            out.push((r, Vec::new()));
            out.push((other, Vec::new()));
            return Some(out);
        }
        if b0.is_zero() && !a1.is_zero() {
            // a1·sin q + a0 = 0
            let x = a0.neg().div(&a1).ok()?;
            out.extend(asin_roots(&x)?);
            return Some(out);
        }
        if a1.is_zero() && !b0.is_zero() {
            // b0·cos q + a0 = 0
            let x = a0.neg().div(&b0).ok()?;
            out.extend(acos_roots(&x)?);
            return Some(out);
        }
    }
    if b.is_zero() && sa.len() == 3 {
        // quadratic in sin q
        let cs: Vec<Expr> = sa.iter().map(ex).collect();
        for (x, mut cond) in quadratic(&cs)? {
            for (r, c2) in asin_roots(&x)? {
                cond.extend(c2);
                out.push((r, cond.clone()));
            }
        }
        return Some(out);
    }
    out.extend(weierstrass(&p, s, c)?);
    Some(out)
}

/// q = asin x and π − asin x (when |x| ≤ 1).
fn asin_roots(x: &Expr) -> Option<Vec<ExactRoot>> {
    let pi = Expr::pi();
    if let Some(v) = x.as_rational() {
        if v.abs() > Q::one() {
            return Some(Vec::new());
        }
        if v.abs().is_one() {
            return Some(vec![(func::asin(x).ok()?, Vec::new())]);
        }
    }
    let cond = abs_condition(x);
    let r = func::asin(x).ok()?;
    Some(vec![(r.clone(), cond.clone()), (pi.sub(&r), cond)])
}

/// q = ±acos x (when |x| ≤ 1).
fn acos_roots(x: &Expr) -> Option<Vec<ExactRoot>> {
    if let Some(v) = x.as_rational() {
        if v.abs() > Q::one() {
            return Some(Vec::new());
        }
        if v.abs().is_one() {
            return Some(vec![(func::acos(x).ok()?, Vec::new())]);
        }
    }
    let cond = abs_condition(x);
    let r = func::acos(x).ok()?;
    Some(vec![(r.clone(), cond.clone()), (r.neg(), cond)])
}

fn abs_condition(x: &Expr) -> Vec<String> {
    if x.as_rational().is_some() {
        return Vec::new();
    }
    vec![format!("|{}| ≤ 1", crate::expr::print::unicode(x))]
}

/// The general case by t = tan(q/2): sin q = 2t/(1 + t²), cos q = (1 − t²)/(1 + t²).
fn weierstrass(p: &Poly, s: Var, c: Var) -> Option<Vec<ExactRoot>> {
    let tv = atom::unknown("tan(q/2)");
    let t = Expr::var(tv);
    let one = Expr::one();
    let d = one.add(&t.mul(&t));
    let mut map = FxHashMap::default();
    map.insert(s, t.scale(&Q::from_i64(2)).div(&d).ok()?);
    map.insert(c, one.sub(&t.mul(&t)).div(&d).ok()?);
    let e = Expr::from_poly(p.clone()).subs_many(&map).ok()?;
    let cs: Vec<Expr> = e
        .num()
        .coeffs_in(tv)
        .into_iter()
        .map(Expr::from_poly)
        .collect();
    let mut out = Vec::new();
    // q = π is t = ∞: the leading coefficient drops when p(0, −1) = 0.
    let at_pi = Expr::from_poly(p.clone())
        .subs_many(&[(s, Expr::zero()), (c, one.neg())].into_iter().collect())
        .ok()?;
    if at_pi.is_zero() {
        out.push((Expr::pi(), Vec::new()));
    }
    for (r, cond) in poly_like_roots(&cs)? {
        out.push((func::atan(&r).scale(&Q::from_i64(2)), cond));
    }
    Some(out)
}

/// Roots of Σ cs[i]·x^i with x^k taken out, degree ≤ 2.
fn poly_like_roots(cs: &[Expr]) -> Option<Vec<ExactRoot>> {
    let k = cs.iter().take_while(|c| c.is_zero()).count();
    let mut out = Vec::new();
    if k > 0 && k < cs.len() {
        out.push((Expr::zero(), Vec::new()));
    }
    let mut rest: Vec<Expr> = cs[k.min(cs.len())..].to_vec();
    while rest.last().is_some_and(|c| c.is_zero()) {
        rest.pop();
    }
    out.extend(quadratic(&rest)?);
    Some(out)
}

/// Which coordinates are angles: they appear in sin/cos and never bare.
pub(super) fn periodic_coordinates(conditions: &[Expr], q: &[Var]) -> Vec<bool> {
    q.iter()
        .map(|&v| {
            let (s, c) = atom::intern_trig(&Expr::var(v));
            conditions
                .iter()
                .any(|e| e.num().contains_var(s) || e.num().contains_var(c))
                && !conditions.iter().any(|e| e.num().contains_var(v))
        })
        .collect()
}

/// Whether two positions are the same point (angles modulo 2π).
fn close(a: &[f64], b: &[f64], periodic: &[bool]) -> bool {
    close_within(a, b, periodic, 1e-9)
}

pub(super) fn close_within(a: &[f64], b: &[f64], periodic: &[bool], tol: f64) -> bool {
    a.iter().zip(b).zip(periodic).all(|((x, y), &p)| {
        let mut d = (x - y).abs();
        if p {
            d = d.rem_euclid(2.0 * std::f64::consts::PI);
            d = d.min(2.0 * std::f64::consts::PI - d);
        }
        d <= tol * (1.0 + x.abs().max(y.abs()))
    })
}

/// The numeric values of exact positions at `set`, if every parameter is given.
pub(super) fn numeric_values(vals: &[Expr], set: &Values) -> Option<Vec<f64>> {
    if set.is_empty() {
        return None;
    }
    vals.iter()
        .map(|v| {
            v.eval_f64(&|a: &Atom| match a {
                Atom::Param(n) => set.get(&**n).copied(),
                _ => None,
            })
        })
        .map(|x| x.filter(|v| v.is_finite()))
        .collect::<Option<Vec<f64>>>()
}

// ---------------------------------------------------------------- stability

/// The verdict at an exact equilibrium: K's minors (Lagrange–Dirichlet,
/// Jacobi) when the kinetic energy is positive definite there, and
/// [`Mass::verdict`] otherwise.
fn classify_exact(
    conditions: &[Expr],
    jac: &[Vec<Expr>],
    inertia: Option<&AtRest>,
    q: &[Var],
    vals: &[Expr],
    set: &Values,
    gyroscopic: bool,
) -> Stability {
    let map: FxHashMap<Var, Expr> = q.iter().copied().zip(vals.iter().cloned()).collect();
    let Some(k) = matrix_at(jac, &map) else {
        return Stability::Undecided("the Hessian is undefined here".into());
    };
    let potential = |negate: bool| {
        let (k, f) = if negate {
            (negated(&k), conditions[0].neg())
        } else {
            (k.clone(), conditions[0].clone())
        };
        classify_potential(&f, &k, q, vals, set, gyroscopic)
    };
    let Some(inertia) = inertia else {
        return potential(false);
    };
    let Some(m) = matrix_at(inertia.mass(), &map) else {
        return Stability::Undecided("the mass matrix is undefined here".into());
    };
    if let Some(v) = non_conservative(inertia, &map, &m, &k, set) {
        return v;
    }
    Mass::exact(&m, set).verdict(
        || Stiffness::exact(&k, set),
        || inertia.velocity_free(),
        || inertia.velocity_free() && super::linear_stability::undamped_grows(&m, &k, set),
        potential,
    )
}

/// The verdict of the whole linearization M·q̈ + C·q̇ + K·q = 0 (as
/// `modes` decides it) where K's minors alone would mislead: K not
/// symmetric (circulatory forces: flutter), or velocity terms that may
/// feed energy in (C's symmetric part of no proved sign); `None` otherwise.
fn non_conservative(
    inertia: &AtRest,
    at: &FxHashMap<Var, Expr>,
    m: &[Vec<Expr>],
    k: &[Vec<Expr>],
    set: &Values,
) -> Option<Stability> {
    let n = k.len();
    let symmetric = (0..n).all(|i| (0..i).all(|j| k[i][j].equals(&k[j][i])));
    if symmetric && inertia.velocity_free() {
        return None;
    }
    let c = matrix_at(&inertia.velocity_terms()?, at)?;
    if symmetric && super::hurwitz::dissipation(&c, set) != super::hurwitz::Dissipation::Unknown {
        return None;
    }
    Some(super::linear_stability::of_matrices(m, &c, k, set))
}

/// The verdict of the potential's Hessian K (for a positive definite
/// kinetic energy); `f` is the first condition (one coordinate: the
/// derivatives past K decide when K = 0).
fn classify_potential(
    f: &Expr,
    k: &[Vec<Expr>],
    q: &[Var],
    vals: &[Expr],
    set: &Values,
    gyroscopic: bool,
) -> Stability {
    let n = q.len();
    let signs = match minor_signs(k, set) {
        Ok(s) => s,
        Err(undecided) => return undecided,
    };
    if n == 1 && signs[0] == Some(Sign::Zero) {
        return higher_order(f, q[0], &vals[0], set);
    }
    if n == 1 && signs[0].is_none() {
        let verdict = super::condition::sign_decides(&k[0][0]).unwrap_or_else(|| {
            format!(
                "stable when {} > 0, unstable when < 0",
                crate::expr::print::unicode(&k[0][0])
            )
        });
        return Stability::Undecided(format!("{verdict}; give values with --set"));
    }
    jacobi(&signs, gyroscopic)
}

/// Newton's roots without repeats: a multiple root draws the iterates into
/// a cluster of near-roots, and the one with the smallest residual of each
/// cluster is kept.
pub(super) fn distinct_roots(
    mut roots: Vec<super::numeric::Root>,
    periodic: &[bool],
) -> Vec<super::numeric::Root> {
    roots.sort_by(|a, b| a.residual.total_cmp(&b.residual));
    let mut kept: Vec<super::numeric::Root> = Vec::new();
    for r in roots {
        if !kept
            .iter()
            .any(|k| close_within(&k.x, &r.x, periodic, 1e-3))
        {
            kept.push(r);
        }
    }
    kept
}

/// The signs of the leading minors of a symmetric K (exactly, or at
/// `set`); the verdict instead when K is not symmetric or a minor cannot
/// be evaluated.
#[allow(clippy::needless_range_loop)] // matrix indices read best as indices
pub(super) fn minor_signs(k: &[Vec<Expr>], set: &Values) -> Result<Vec<Option<Sign>>, Stability> {
    let n = k.len();
    for i in 0..n {
        for j in i + 1..n {
            if !k[i][j].equals(&k[j][i]) {
                return Err(Stability::Undecided(
                    "the forces are not conservative here (∂Q_i/∂q_j ≠ ∂Q_j/∂q_i)".into(),
                ));
            }
        }
    }
    let mut signs = Vec::with_capacity(n);
    for m in 1..=n {
        let sub: Vec<Vec<Expr>> = k[..m].iter().map(|r| r[..m].to_vec()).collect();
        let Some(d) = det(sub) else {
            return Err(Stability::Undecided(
                "the Hessian could not be evaluated".into(),
            ));
        };
        signs.push(sign_of(&d, set));
    }
    Ok(signs)
}

/// Stable / unstable from the signs of the leading minors.
pub(super) fn jacobi(signs: &[Option<Sign>], gyroscopic: bool) -> Stability {
    if signs.iter().all(|s| *s == Some(Sign::Positive)) {
        return Stability::Stable;
    }
    if signs.iter().any(|s| s.is_none()) {
        return Stability::Undecided(
            "the sign of the Hessian's minors depends on the parameters; give values with --set"
                .into(),
        );
    }
    if signs.contains(&Some(Sign::Zero)) {
        // a zero leading minor and det K ≠ 0: K is not positive definite
        // and not singular, so it has a negative eigenvalue
        if !gyroscopic && matches!(signs.last(), Some(Some(Sign::Positive | Sign::Negative))) {
            return Stability::Unstable;
        }
        return Stability::Undecided(
            "the Hessian is singular here: higher-order terms decide".into(),
        );
    }
    let mut prev = Sign::Positive;
    let mut negative = 0;
    for s in signs.iter().flatten() {
        if *s != prev {
            negative += 1;
        }
        prev = *s;
    }
    if gyroscopic && negative % 2 == 0 {
        return Stability::Undecided(format!(
            "the potential has {negative} negative directions; gyroscopic terms may stabilize an even number"
        ));
    }
    Stability::Unstable
}

/// One coordinate with V'' = 0: the first non-vanishing derivative decides.
fn higher_order(f: &Expr, q: Var, at: &Expr, set: &Values) -> Stability {
    let mut d = f.diff(q); // F' = −V''
    for order in 3..=MAX_STABILITY_DERIVATIVE {
        d = d.diff(q); // F^(order−1) = −V^(order)
        let Ok(v) = d.subs(q, at) else {
            break;
        };
        match sign_of(&v.neg(), set) {
            Some(Sign::Zero) => continue,
            Some(Sign::Positive) if order % 2 == 0 => return Stability::Stable,
            Some(_) => return Stability::Unstable,
            None => break,
        }
    }
    Stability::Undecided(format!(
        "V'' = 0 here and the derivatives up to order {MAX_STABILITY_DERIVATIVE} do not decide"
    ))
}

/// The highest derivative of V the stability test of a degenerate
/// equilibrium takes (V = (1 + x)¹⁰⁰ needs the 100th).
const MAX_STABILITY_DERIVATIVE: u32 = 202;

/// The multiplicity of the root `at` of the condition `f` (one
/// coordinate): how many of f, f', f'', … vanish there (at most
/// `MAX_STABILITY_DERIVATIVE`).
pub fn multiplicity(f: &Expr, q: Var, at: &Expr) -> u32 {
    let mut d = f.clone();
    for m in 0..MAX_STABILITY_DERIVATIVE {
        match d.subs(q, at) {
            Ok(v) if v.is_zero() => d = d.diff(q),
            _ => return m.max(1),
        }
    }
    MAX_STABILITY_DERIVATIVE
}

// ---------------------------------------------------------------- numeric

fn solve_numeric(
    conditions: &[Expr],
    jac: &[Vec<Expr>],
    inertia: Option<&AtRest>,
    q: &[Var],
    periodic: &[bool],
    set: &Values,
    gyroscopic: bool,
) -> Vec<Equilibrium> {
    let eval = |e: &Expr, x: &[f64]| -> Option<f64> {
        e.eval_f64(&|a: &Atom| match a {
            Atom::Param(name) => set.get(&**name).copied(),
            Atom::Coord(name, 0) => q
                .iter()
                .position(|&v| matches!(atom::atom(v), Atom::Coord(ref m, 0) if m == name))
                .map(|i| x[i]),
            _ => None,
        })
        .filter(|v| v.is_finite())
    };
    let f = |x: &[f64]| -> Option<Vec<f64>> { conditions.iter().map(|e| eval(e, x)).collect() };
    // K = −∂F/∂q, so ∂F/∂q = −K.
    let j = |x: &[f64]| -> Option<Vec<Vec<f64>>> {
        jac.iter()
            .map(|row| row.iter().map(|e| eval(e, x).map(|v| -v)).collect())
            .collect()
    };
    let opts = RootOptions {
        periodic: periodic.to_vec(),
        ..RootOptions::default()
    };
    let roots = find_roots(&f, &j, &opts);
    // A multiple root draws Newton's iterates into a cluster of
    // near-roots; keep the best of each cluster.
    let mut kept = distinct_roots(roots, &opts.periodic);
    kept.sort_by(|a, b| {
        a.x.iter()
            .zip(&b.x)
            .map(|(p, q)| p.total_cmp(q))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    kept.into_iter()
        .map(|r| {
            let k = j(&r.x).map(|m| {
                m.into_iter()
                    .map(|row| row.into_iter().map(|v| -v).collect::<Vec<f64>>())
                    .collect::<Vec<_>>()
            });
            let side = |x: f64| f(&[x]).map(|v| v[0]);
            let stability = match k {
                Some(k) => {
                    let potential = |negate: bool| {
                        let k = if negate { negated_f64(&k) } else { k.clone() };
                        let s = classify_numeric(&k, gyroscopic);
                        match (r.x.as_slice(), &s) {
                            ([x], Stability::Undecided(_)) => flat(&side, *x, negate).unwrap_or(s),
                            _ => s,
                        }
                    };
                    let mass = inertia.map(|i| {
                        i.mass()
                            .iter()
                            .map(|row| row.iter().map(|e| eval(e, &r.x)).collect())
                            .collect::<Option<Vec<Vec<f64>>>>()
                    });
                    let velocity = |x: &[f64]| {
                        let c = inertia?.velocity_terms()?;
                        c.iter()
                            .map(|row| row.iter().map(|e| eval(e, x)).collect())
                            .collect::<Option<Vec<Vec<f64>>>>()
                    };
                    match mass {
                        None => potential(false),
                        Some(None) => {
                            Stability::Undecided("the mass matrix is undefined here".into())
                        }
                        Some(Some(m)) => (inertia.is_some_and(|i| !i.velocity_free())
                            || !symmetric_f64(&k))
                        .then(|| velocity(&r.x))
                        .flatten()
                        .and_then(|c| super::linear_stability::numeric_verdict(&m, &c, &k))
                        .unwrap_or_else(|| {
                            Mass::numeric(&m).verdict(
                                || Stiffness::numeric(&k),
                                || inertia.is_some_and(AtRest::velocity_free),
                                || {
                                    inertia.is_some_and(AtRest::velocity_free)
                                        && undamped_grows_f64(&m, &k)
                                },
                                potential,
                            )
                        }),
                    }
                }
                None => Stability::Undecided("the Hessian is undefined here".into()),
            };
            // one coordinate: certify the digits by a sign change of F
            let enclosure = (r.x.len() == 1)
                .then(|| {
                    let f1 = |x: f64| f(&[x]).map(|v| v[0]);
                    super::certify::enclose(&f1, r.x[0])
                })
                .flatten();
            let mut e = Equilibrium::new(Position::Numeric(r.x), stability);
            e.certified = enclosure.map(|e| vec![e.digits()]);
            e.enclosure = enclosure.map(|e| (e.lo, e.hi));
            e
        })
        .collect()
}

/// One coordinate where K vanishes: the force `side(x)` just left and
/// right of the root `x` decides. Restoring on both sides is stable,
/// pushed away on either side unstable, a side with no force not decided
/// (never guessed); `negate` for a negative mass (ẍ = −F/|m|).
fn flat(side: &impl Fn(f64) -> Option<f64>, x: f64, negate: bool) -> Option<Stability> {
    let h = 1e-3 * (1.0 + x.abs());
    let sign = if negate { -1.0 } else { 1.0 };
    let (lo, hi) = (sign * side(x - h)?, sign * side(x + h)?);
    if lo > 0.0 && hi < 0.0 {
        Some(Stability::Stable)
    } else if lo < 0.0 || hi > 0.0 {
        Some(Stability::Unstable)
    } else {
        None
    }
}

/// Whether a numeric K is symmetric (as [`classify_numeric`] reads it).
fn symmetric_f64(k: &[Vec<f64>]) -> bool {
    let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    k.iter().enumerate().all(|(i, r)| {
        r.iter()
            .enumerate()
            .all(|(j, v)| (v - k[j][i]).abs() <= 1e-8 * scale)
    })
}

#[allow(clippy::needless_range_loop)] // matrix indices read best as indices
pub(super) fn classify_numeric(k: &[Vec<f64>], gyroscopic: bool) -> Stability {
    let n = k.len();
    let scale = k
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    for i in 0..n {
        for j in i + 1..n {
            if (k[i][j] - k[j][i]).abs() > 1e-8 * scale {
                return Stability::Undecided(
                    "the forces are not conservative here (∂Q_i/∂q_j ≠ ∂Q_j/∂q_i)".into(),
                );
            }
        }
    }
    let mut signs = Vec::with_capacity(n);
    for m in 1..=n {
        let d = det_f64(k[..m].iter().map(|r| r[..m].to_vec()).collect());
        let tol = 1e-9 * scale.powi(m as i32);
        signs.push(Some(if d.abs() <= tol {
            Sign::Zero
        } else if d > 0.0 {
            Sign::Positive
        } else {
            Sign::Negative
        }));
    }
    jacobi(&signs, gyroscopic)
}

/// The determinant of a numeric matrix, by LU with partial pivoting
/// (0 for a zero pivot).
pub(super) fn det_f64(m: Vec<Vec<f64>>) -> f64 {
    let mut lu = Lu::new(m.len(), 0.0);
    lu.a = m.concat();
    if lu.factor() {
        lu.determinant()
    } else {
        0.0
    }
}
