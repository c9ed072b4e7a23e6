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
use crate::expr::tape::Tape;
use crate::expr::{atom, Expr};
use crate::num::Q;
use crate::parse::ast::Role;
use crate::poly::{Mono, Poly, Var};
use crate::scene::{Scene, Structure};
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
    /// q̇_k in q, p and t (through the intermediates when there are).
    pub velocities: Vec<Expr>,
    /// H(q, p, t).
    pub hamiltonian: Expr,
    /// ṗ_k = −∂H/∂q_k + Q̃_k, in q, p and t.
    pub momentum_rates: Vec<Expr>,
    /// Q̃_k, the generalized forces outside H, in q, p and t (zero for a
    /// conservative scene).
    pub other_forces: Vec<Expr>,
    /// The intermediates the expressions above are written through: the
    /// velocities `v_q` in q, p and t, and H, ṗ and Q̃ in them. `None`
    /// when everything is expanded.
    pub intermediates: Option<Box<Tape>>,
}

pub use crate::scene::momentum_name;

impl Hamiltonian {
    /// The Legendre transform of the scene's Lagrangian, expanded unless
    /// the expansion passes the size rule ([`Structure::Auto`]).
    pub fn derive(scene: &Scene) -> Result<Hamiltonian, Diagnostic> {
        Hamiltonian::derive_as(scene, Structure::Auto)
    }

    /// The Legendre transform written as `structure` asks: `Expanded`, in
    /// q, p and t throughout; `Kept`, through the velocities `v_q` as
    /// intermediates (ṗ is then a polynomial in them, where expanded it is
    /// over the square of M's determinant); `Auto`, expanded unless H, ṗ
    /// and Q̃ expanded pass [`crate::limits::STRUCTURE_ABOVE_TERMS`] terms.
    pub fn derive_as(scene: &Scene, structure: Structure) -> Result<Hamiltonian, Diagnostic> {
        crate::diag::bounded(|| {
            scene.expanded_only("Hamilton's equations")?;
            let _context = crate::budget::enter(|| "deriving Hamilton's equations".into(), None);
            let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
            check_scene(scene, &names)?;
            let t = Transform::of(scene, names)?;
            match structure {
                Structure::Expanded => t.expanded(),
                Structure::Kept => t.structured(scene),
                Structure::Auto => {
                    let limit = crate::limits::STRUCTURE_ABOVE_TERMS;
                    match crate::budget::probe(limit.saturating_mul(16), || t.expanded()) {
                        Ok(Ok(h)) if h.expanded_terms() <= limit => Ok(h),
                        Ok(Err(e)) => Err(e),
                        // past the rule, or far past it (the measuring budget)
                        Ok(Ok(_)) | Err(_) => t.structured(scene),
                    }
                }
            }
        })
    }

    /// Every expression the output prints: the momenta, the velocities,
    /// H, ṗ and Q̃ (the roots of [`Hamiltonian::intermediates`]).
    pub fn exprs(&self) -> impl Iterator<Item = &Expr> {
        self.momenta
            .iter()
            .chain(&self.velocities)
            .chain(std::iter::once(&self.hamiltonian))
            .chain(&self.momentum_rates)
            .chain(&self.other_forces)
    }

    /// The terms of H, ṗ and Q̃ (numerators and denominators): what the
    /// size rule measures.
    fn expanded_terms(&self) -> usize {
        std::iter::once(&self.hamiltonian)
            .chain(&self.momentum_rates)
            .chain(&self.other_forces)
            .map(|e| e.num().len() + e.den().len())
            .sum()
    }
}

/// The Legendre transform's parts before the velocities are written in
/// the momenta: L = ½·q̇ᵀ·M·q̇ + bᵀ·q̇ + L₀, p = M·q̇ + b.
struct Transform {
    coordinates: Vec<String>,
    momentum_names: Vec<String>,
    /// The velocity atoms q̇.
    qd: Vec<Var>,
    /// p_k = ∂L/∂q̇_k in q, q̇ and t.
    momenta: Vec<Expr>,
    /// p − b.
    p_minus_b: Vec<Expr>,
    /// L₀ = L at q̇ = 0.
    l0: Expr,
    /// q̇ = M⁻¹·(p − b), expanded.
    velocities: Vec<Expr>,
    /// ∂L/∂q_k + Q̃_k in q, q̇ and t: ṗ_k once q̇ is written in p.
    rates: Vec<Expr>,
    /// Q̃_k in q, q̇ and t.
    other: Vec<Expr>,
}

impl Transform {
    fn of(scene: &Scene, names: Vec<String>) -> Result<Transform, Diagnostic> {
        let math = |m: crate::expr::MathError| {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
        };
        let q: Vec<Var> = names.iter().map(|c| atom::coord(c, 0)).collect();
        let qd: Vec<Var> = names.iter().map(|c| atom::coord(c, 1)).collect();
        let qdd: Vec<Var> = names.iter().map(|c| atom::coord(c, 2)).collect();
        let momentum_names: Vec<String> = names.iter().map(|c| momentum_name(c)).collect();
        let l = super::lagrangian(scene);
        let momenta: Vec<Expr> = qd.iter().map(|&v| l.diff(v)).collect();
        // p = M·q̇ + b, M free of the velocities
        let mut mass = Vec::with_capacity(names.len());
        let mut p_minus_b = Vec::with_capacity(names.len());
        for (pk, name) in momenta.iter().zip(&momentum_names) {
            let (row, rest) = split_linear(pk, &qd).map_err(math)?;
            if row
                .iter()
                .chain(std::iter::once(&rest))
                .any(|e| moves(e, &qd))
            {
                return Err(Diagnostic::global(
                    "the Lagrangian is not quadratic in the velocities, so the momenta are not linear in them and the Legendre transform has no closed form here",
                )
                .with_hint("Hamilton's equations need q̇ in terms of p: keep the kinetic energy quadratic in the velocities").with_kind(crate::diag::ErrorKind::NoClosedForm));
            }
            mass.push(row);
            p_minus_b.push(Expr::unknown(name).sub(&rest));
        }
        let velocities = linear::solve(&mass, &p_minus_b).map_err(|e| match e {
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
            SolveError::Math(m) => Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined),
        })?;
        let at_rest: FxHashMap<Var, Expr> = qd.iter().map(|&v| (v, Expr::zero())).collect();
        let l0 = l.subs_many(&at_rest).map_err(math)?;
        let other = other_forces(scene, &qd, &qdd)?;
        // ṗ_k = −∂H/∂q_k + Q̃_k = ∂L/∂q_k + Q̃_k at q̇(q, p)
        let rates = q
            .iter()
            .zip(&other)
            .map(|(&qk, o)| l.diff(qk).add(o))
            .collect();
        Ok(Transform {
            coordinates: names,
            momentum_names,
            qd,
            momenta,
            p_minus_b,
            l0,
            velocities,
            rates,
            other,
        })
    }

    /// H with the velocities `v` (expressions or intermediates) standing
    /// for q̇: H = Σ p_k·q̇_k − L = ½·Σ (p_k − b_k)·q̇_k − L₀, since
    /// p − b = M·q̇ (q̇ substituted into L would square the velocities'
    /// denominator).
    fn hamiltonian(&self, twice_kinetic: Expr) -> Result<Expr, Diagnostic> {
        let half = twice_kinetic.div(&Expr::int(2)).map_err(|m| {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
        })?;
        Ok(half.sub(&self.l0))
    }

    /// Everything in q, p and t.
    fn expanded(&self) -> Result<Hamiltonian, Diagnostic> {
        let in_p = AtVelocities::new(&self.qd, &self.velocities);
        let h = self.hamiltonian(in_p.twice_kinetic(&self.p_minus_b)?)?;
        // one substitution each (differentiating H, or adding two
        // substituted terms, combines denominators the canonical form
        // cannot see are equal)
        let momentum_rates = self
            .rates
            .iter()
            .map(|r| in_p.apply(r))
            .collect::<Result<Vec<_>, _>>()?;
        let other_forces = self
            .other
            .iter()
            .map(|o| in_p.apply(o))
            .collect::<Result<Vec<_>, _>>()?;
        debug_assert!(self
            .momentum_names
            .iter()
            .zip(&self.velocities)
            .all(|(name, v)| match Expr::unknown(name).as_var() {
                Some(var) => h.diff(var).equals(v),
                None => true,
            }));
        Ok(Hamiltonian {
            coordinates: self.coordinates.clone(),
            momentum_names: self.momentum_names.clone(),
            momenta: self.momenta.clone(),
            velocities: self.velocities.clone(),
            hamiltonian: h,
            momentum_rates,
            other_forces,
            intermediates: None,
        })
    }

    /// The velocities named `v_q` (in q, p and t), and H, ṗ and Q̃ written
    /// in them: ṗ and Q̃ are then what they are in q̇, with no denominator
    /// from M.
    fn structured(&self, scene: &Scene) -> Result<Hamiltonian, Diagnostic> {
        let mut tape = Tape::new();
        let taken = scene
            .parameters
            .iter()
            .map(|x| &x.name)
            .chain(scene.coordinates.iter().map(|x| &x.name))
            .chain(scene.definitions.iter().map(|x| &x.name))
            .chain(&self.momentum_names);
        for name in taken {
            tape.reserve(name);
        }
        let named: Vec<Expr> = self
            .coordinates
            .iter()
            .zip(&self.velocities)
            .map(|(c, v)| tape.define(&format!("v_{c}"), v.clone()))
            .collect();
        let to_named: FxHashMap<Var, Expr> =
            self.qd.iter().copied().zip(named.iter().cloned()).collect();
        // q̇ → an atom or a polynomial in atoms: no denominator arises
        let in_named = |e: &Expr| {
            e.subs_many(&to_named).map_err(|m| {
                Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
            })
        };
        let hamiltonian = self.hamiltonian(dot(&self.p_minus_b, &named))?;
        Ok(Hamiltonian {
            coordinates: self.coordinates.clone(),
            momentum_names: self.momentum_names.clone(),
            momenta: self.momenta.clone(),
            velocities: named,
            hamiltonian,
            momentum_rates: self.rates.iter().map(in_named).collect::<Result<_, _>>()?,
            other_forces: self.other.iter().map(in_named).collect::<Result<_, _>>()?,
            intermediates: (!tape.is_empty()).then(|| Box::new(tape)),
        })
    }
}

/// The substitution q̇ → q̇(q, p, t), every velocity over one denominator:
/// q̇_k = N_k / D with N_k and D polynomials.
///
/// The canonical form reduces sin² + cos² = 1 and then takes gcds in the
/// free polynomial ring, where the reduced D² is no longer a multiple of
/// D: adding N/D to N'/D² term by term multiplies the denominators (a 1 KB
/// result becomes megabytes). So an expression polynomial in q̇ is
/// substituted over the single denominator D^degree, each term's numerator
/// N^e·D^(degree − |e|) a polynomial, and divided once.
struct AtVelocities<'a> {
    qd: &'a [Var],
    /// q̇ in q, p and t, canonical.
    velocities: &'a [Expr],
    /// `Some((N, D))` when the velocities have a common polynomial
    /// denominator.
    common: Option<(Vec<Expr>, Expr)>,
}

impl<'a> AtVelocities<'a> {
    fn new(qd: &'a [Var], velocities: &'a [Expr]) -> AtVelocities<'a> {
        AtVelocities {
            qd,
            velocities,
            common: common_denominator(velocities),
        }
    }

    /// Σ (p_k − b_k)·q̇_k over the velocities' own denominator.
    fn twice_kinetic(&self, p_minus_b: &[Expr]) -> Result<Expr, Diagnostic> {
        match &self.common {
            Some((numerators, den)) => dot(p_minus_b, numerators).div(den).map_err(|m| {
                Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
            }),
            None => Ok(dot(p_minus_b, self.velocities)),
        }
    }

    /// `e` (in q, q̇ and t) at q̇ = q̇(q, p, t).
    fn apply(&self, e: &Expr) -> Result<Expr, Diagnostic> {
        let math = |m: crate::expr::MathError| {
            Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined)
        };
        match &self.common {
            Some((numerators, den)) if self.polynomial_in_velocities(e) => {
                self.over_common(e, numerators, den).map_err(math)
            }
            _ => {
                let to_p: FxHashMap<Var, Expr> = self
                    .qd
                    .iter()
                    .copied()
                    .zip(self.velocities.iter().cloned())
                    .collect();
                e.subs_many(&to_p).map_err(math)
            }
        }
    }

    /// Whether `e` is a polynomial in the velocities: its denominator and
    /// its atoms other than q̇ (sin(q̇), …) free of them.
    fn polynomial_in_velocities(&self, e: &Expr) -> bool {
        !moves(&Expr::from_poly(e.den().clone()), self.qd)
            && e.vars()
                .into_iter()
                .all(|v| self.qd.contains(&v) || !moves(&Expr::var(v), self.qd))
    }

    /// `e` = Σ c_e(q, t)·q̇^e over F(q, t) as Σ c_e·N^e·D^(d − |e|) over
    /// F·D^d, d the degree in q̇.
    fn over_common(
        &self,
        e: &Expr,
        numerators: &[Expr],
        den: &Expr,
    ) -> Result<Expr, crate::expr::MathError> {
        let mut by_powers: std::collections::BTreeMap<Vec<u32>, Vec<(Mono, Q)>> =
            Default::default();
        for (m, c) in e.num().terms() {
            let mut powers = vec![0; self.qd.len()];
            let mut rest = Vec::new();
            for &(v, k) in m.pairs() {
                match self.qd.iter().position(|&w| w == v) {
                    Some(i) => powers[i] = k,
                    None => rest.push((v, k)),
                }
            }
            by_powers
                .entry(powers)
                .or_default()
                .push((Mono::from_pairs(rest), c.clone()));
        }
        let degree = by_powers
            .keys()
            .map(|e| e.iter().sum::<u32>())
            .max()
            .unwrap_or(0);
        let mut num = Expr::zero();
        for (powers, terms) in by_powers {
            let mut term = Expr::from_poly(Poly::from_terms(terms));
            for (n, &k) in numerators.iter().zip(&powers) {
                if k > 0 {
                    term = term.mul(&n.powi(i64::from(k))?);
                }
            }
            let missing = degree - powers.iter().sum::<u32>();
            num = num.add(&term.mul(&den.powi(i64::from(missing))?));
        }
        let whole = Expr::from_poly(e.den().clone()).mul(&den.powi(i64::from(degree))?);
        num.div(&whole)
    }
}

/// N and D with velocities[k] = N_k / D, D the lcm of their denominators
/// in the polynomial ring; `None` if the division leaves a denominator.
fn common_denominator(velocities: &[Expr]) -> Option<(Vec<Expr>, Expr)> {
    let mut den = Expr::one();
    for v in velocities {
        let dk = Expr::from_poly(v.den().clone());
        let ratio = den.div(&dk).ok()?;
        den = den.mul(&Expr::from_poly(ratio.den().clone()));
    }
    let numerators: Vec<Expr> = velocities.iter().map(|v| v.mul(&den)).collect();
    numerators
        .iter()
        .all(Expr::is_poly)
        .then_some((numerators, den))
}

/// Σ a_k·b_k.
fn dot(a: &[Expr], b: &[Expr]) -> Expr {
    a.iter()
        .zip(b)
        .fold(Expr::zero(), |s, (x, y)| s.add(&x.mul(y)))
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
            .with_hint(format!("rename `{p}` in the scene"))
            .with_kind(crate::diag::ErrorKind::DuplicateName {
                name: p.to_string(),
            }));
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
            .with_hint("write the inertia as a kinetic energy: `kinetic E = …`").with_kind(crate::diag::ErrorKind::Unsupported));
        }
        out.push(q);
    }
    Ok(out)
}
