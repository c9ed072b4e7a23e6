//! Small oscillations about an equilibrium (the seed's chapter 24).
//!
//! Lagrange's equations R_k(q, q̇, q̈, t) = lhs_k − Q_k = 0 are expanded to
//! first order about q = q0, q̇ = 0, q̈ = 0 — the same as expanding E, U/V
//! and D/R to second order (sin θ ≈ θ, 1 − cos θ ≈ θ²/2):
//!
//! ```text
//! M·q̈ + C·q̇ + K·q = f(t),   M = ∂R/∂q̈, C = ∂R/∂q̇, K = ∂R/∂q at (q0, 0, 0),
//!                           f(t) = −R(q0, 0, 0, t)
//! ```
//!
//! f must have no constant part (q0 must be an equilibrium). Then the
//! characteristic polynomial (`characteristic.rs`: det(K − λ·M), λ = ω²,
//! or with gyroscopic terms — C skew — det(K + s·C + s²·M) at s² = −λ) is
//! factored over ℚ and its roots are solved exactly where they have a closed
//! form. The modes of a system without gyroscopic terms are the null vectors
//! of K − λᵢ·M normalized to the first coordinate (the seed's distribution
//! coefficients), computed exactly; a gyroscopic system's modes are complex
//! (its coordinates move out of phase, a circle for the Penning trap's
//! magnetron and cyclotron motions), and only its frequencies are given.
//! Stability is decided in `linear_stability.rs`.

/// The verdict on the linearized system (the same as for equilibria).
pub use super::equilibrium::Stability;
pub use super::linearize::Reference;
pub use super::steady::{SolvedRate, SteadyMotion};
use crate::algebra::sign::{sign_exact, sign_of, Sign, Values};
use crate::diag::Diagnostic;
use crate::expr::atom::{self, Atom};
use crate::expr::{func, Expr};
use crate::num::Q;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// The variable of the characteristic polynomial, λ = ω².
pub const LAMBDA: &str = "lambda";

/// The linearized system and its modes.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Modes {
    /// The coordinate names, in declaration order.
    pub coordinates: Vec<String>,
    /// The equilibrium q0.
    pub at: Vec<Expr>,
    /// M = ∂R/∂q̈ at the equilibrium.
    pub mass: Vec<Vec<Expr>>,
    /// C = ∂R/∂q̇ at the equilibrium.
    pub damping: Vec<Vec<Expr>>,
    /// K = ∂R/∂q at the equilibrium.
    pub stiffness: Vec<Vec<Expr>>,
    /// f(t) of M·q̈ + C·q̇ + K·q = f(t).
    pub forcing: Vec<Expr>,
    /// det(K − λ·M), expanded.
    pub characteristic: Expr,
    /// The factors of det(K − λ·M) over the rationals (with the constant
    /// content as a factor of degree 0).
    pub factors: Vec<Expr>,
    /// ω², ascending where the order can be decided; empty if no closed form.
    pub omega_squared: Vec<Expr>,
    /// For each ω²: the mode normalized to the first coordinate (the
    /// distribution coefficients μ = x_j/x_1), or to the first nonzero one.
    pub modes: Vec<Vec<Expr>>,
    /// Stable (all ω² > 0), unstable (some ω² < 0), or undecided.
    pub stability: Stability,
    /// C is skew and not zero (a spinning rotor, a rotating frame, a
    /// magnetic field): `characteristic` is det(K + s·C + s²·M) at s² = −λ,
    /// and `modes` is empty (the modes are complex).
    pub gyroscopic: bool,
    /// Why `omega_squared` is empty, when it is.
    pub no_closed_form: Option<String>,
    /// With constraints: the coordinates they make dependent, with their
    /// values at the equilibrium (`coordinates` are the independent ones).
    pub dependent: Vec<(String, Expr)>,
    /// A repeated ω² has fewer modes than its multiplicity (possible only
    /// when M is not definite): `modes` is empty.
    pub defective: bool,
    /// About a steady motion: its rates and conditions; `coordinates` are
    /// then the ones at rest (the steady ones reduced away with their
    /// momenta held).
    pub steady: Option<SteadyMotion>,
}

/// One degree of freedom in the standard form ÿ + 2α·ẏ + ω²·y = f(t)/M.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct StandardForm {
    /// ω², the square of the undamped natural frequency.
    pub omega_squared: Expr,
    /// The damping constant α (half the coefficient of ẏ).
    pub alpha: Expr,
    /// f(t)/M.
    pub forcing: Expr,
    /// ζ = α/ω (present when ω² is not zero).
    pub zeta: Option<Expr>,
    /// ω = √(ω²) when it is a single term over a single term with no
    /// radical inside (`√(k/m)`, `2·√(g/l)`); otherwise the text writes
    /// √(ω²) and leaves ζ as α/ω.
    pub omega: Option<Expr>,
    /// "undamped", "underdamped", "critically damped", "overdamped", or
    /// "undecided" when the sign of α² − ω² depends on the parameters.
    pub regime: String,
}

fn math(m: crate::expr::MathError) -> Diagnostic {
    let d = Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined);
    match m.hint {
        Some(h) => d.with_hint(h),
        None => d,
    }
}

/// Linearize about `at` (default q = 0) and find the modes.
pub fn modes(scene: &Scene, at: Option<&[Expr]>, set: &Values) -> Result<Modes, Diagnostic> {
    modes_about(scene, &Reference::at(at), set)
}

/// Linearize about `reference` (an equilibrium or a steady motion) and
/// find the modes, the scene's assumptions in force
/// ([`Scene::assumptions_in_force`]).
pub fn modes_about(
    scene: &Scene,
    reference: &Reference,
    set: &Values,
) -> Result<Modes, Diagnostic> {
    crate::diag::bounded(|| {
        scene.expanded_only("small oscillations")?;
        scene.assumptions_required("small oscillations")?;
        modes_assumed(scene, reference, set)
    })
}

/// [`modes_about`] once its preconditions hold.
fn modes_assumed(scene: &Scene, reference: &Reference, set: &Values) -> Result<Modes, Diagnostic> {
    let _context = crate::budget::enter(
        || "linearizing about the equilibrium for the small oscillations".into(),
        None,
    );
    let lin = super::linearize::linearize(scene, reference)?;
    let super::linearize::Linearization {
        coordinates: names,
        at: q0,
        mass,
        damping,
        stiffness,
        forcing,
        dependent,
        steady,
    } = lin;
    let n = names.len();
    let lv = atom::unknown(LAMBDA);
    let gyro = gyroscopic_part(&damping);
    let characteristic = super::characteristic::polynomial(&stiffness, &mass, gyro.as_deref(), lv)
        .ok_or_else(|| {
            Diagnostic::global("the characteristic polynomial failed")
                .with_kind(crate::diag::ErrorKind::Internal)
        })?;
    let symmetric = (0..n).all(|i| (0..n).all(|j| stiffness[i][j].equals(&stiffness[j][i])));
    // det(K − λ·M)'s roots are real for symmetric K and a definite M
    let mass_kind = super::definite::Mass::exact(&mass, set);
    let definite = matches!(
        mass_kind.definiteness(),
        super::definite::Definiteness::Positive | super::definite::Definiteness::Negative
    );
    let real = gyro.is_none() && symmetric && definite;
    let found = super::characteristic::roots(&characteristic, lv, real, set);
    let (mut roots, factors) = (found.roots, found.factors);
    sort_ascending(&mut roots, set);
    let (modes, defective) = if gyro.is_none() {
        modes_of(&stiffness, &mass, &roots, definite)?
    } else {
        (Vec::new(), false)
    };
    let system = super::linear_stability::Linearized {
        mass: &mass,
        damping: &damping,
        stiffness: &stiffness,
        gyroscopic: gyro.is_some(),
    };
    let stability =
        super::linear_stability::stability(&system, &mass_kind, &characteristic, lv, set);
    Ok(Modes {
        coordinates: names,
        at: q0,
        mass,
        damping,
        stiffness,
        forcing,
        characteristic,
        factors,
        omega_squared: roots,
        modes,
        stability,
        gyroscopic: gyro.is_some(),
        no_closed_form: found.why,
        dependent,
        defective,
        steady,
    })
}

/// The modes of the roots ω² (ascending, equal roots together), each a
/// null vector of K − λ·M; and whether a repeated root has fewer modes
/// than its multiplicity (possible only when M is not `definite`: then
/// none are given).
fn modes_of(
    stiffness: &[Vec<Expr>],
    mass: &[Vec<Expr>],
    roots: &[Expr],
    definite: bool,
) -> Result<(Vec<Vec<Expr>>, bool), Diagnostic> {
    let mut modes: Vec<Vec<Expr>> = Vec::with_capacity(roots.len());
    let mut i = 0;
    while i < roots.len() {
        // equal roots share one null space: take its basis
        let same = roots[i..]
            .iter()
            .take_while(|r| r.equals(&roots[i]))
            .count();
        let basis = null_basis(stiffness, mass, &roots[i])?;
        if basis.len() < same && !definite {
            // an indefinite M can make a repeated root defective (a
            // Jordan block): its modes do not span
            return Ok((Vec::new(), true));
        }
        if basis.len() < same {
            return Err(Diagnostic::global(
                "internal error: fewer modes than the multiplicity of a root of det(K − λ·M)",
            )
            .with_kind(crate::diag::ErrorKind::Internal));
        }
        modes.extend(basis.into_iter().take(same));
        i += same;
    }
    Ok((modes, false))
}

/// C when it is skew and not zero (purely gyroscopic velocity terms);
/// `None` when C is zero or has a symmetric (damping) part.
#[allow(clippy::needless_range_loop)] // matrix indices read best as indices
fn gyroscopic_part(c: &[Vec<Expr>]) -> Option<Vec<Vec<Expr>>> {
    let n = c.len();
    let mut any = false;
    for i in 0..n {
        for j in 0..n {
            if !c[i][j].add(&c[j][i]).is_zero() {
                return None;
            }
            any |= !c[i][j].is_zero();
        }
    }
    any.then(|| c.to_vec())
}

/// Sort ω² ascending where differences have a decided sign.
fn sort_ascending(roots: &mut [Expr], set: &Values) {
    // insertion sort with a partial comparison
    for i in 1..roots.len() {
        let mut j = i;
        while j > 0 && sign_of(&roots[j - 1].sub(&roots[j]), set) == Some(Sign::Positive) {
            roots.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// A basis of the null space of K − λ·M, each vector normalized so that
/// its first nonzero coordinate is 1 (the distribution coefficients).
fn null_basis(
    k: &[Vec<Expr>],
    m: &[Vec<Expr>],
    lambda: &Expr,
) -> Result<Vec<Vec<Expr>>, Diagnostic> {
    let n = k.len();
    let a: Vec<Vec<Expr>> = (0..n)
        .map(|i| (0..n).map(|j| k[i][j].sub(&lambda.mul(&m[i][j]))).collect())
        .collect();
    let syms: Vec<Expr> = (0..n)
        .map(|j| Expr::unknown(&format!("mode{}", j + 1)))
        .collect();
    let zero = vec![Expr::zero(); n];
    let sol = super::system::solve_rect(&a, &zero, &syms).map_err(|_| {
        Diagnostic::global("internal error: the mode equations failed")
            .with_kind(crate::diag::ErrorKind::Internal)
    })?;
    let mut out = Vec::new();
    for &f in &sol.shape.free {
        let map: FxHashMap<Var, Expr> = sol
            .shape
            .free
            .iter()
            .map(|&g| {
                let v = atom::unknown(&format!("mode{}", g + 1));
                (v, if g == f { Expr::one() } else { Expr::zero() })
            })
            .collect();
        let mut x = Vec::with_capacity(n);
        for v in &sol.values {
            x.push(v.subs_many(&map).map_err(math)?);
        }
        if let Some(p) = x.iter().position(|e| !e.is_zero()) {
            let pivot = x[p].clone();
            for e in x.iter_mut() {
                *e = e.div(&pivot).map_err(math)?;
            }
        }
        out.push(x);
    }
    // the first coordinate leads where it can: combine so that a vector
    // with x1 ≠ 0 comes first
    out.sort_by_key(|x| x.iter().position(|e| !e.is_zero()));
    Ok(out)
}

/// One coordinate: ÿ + 2α·ẏ + ω²·y = f/M.
pub fn standard_form(md: &Modes, set: &Values) -> Option<StandardForm> {
    if md.coordinates.len() != 1 {
        return None;
    }
    let m = &md.mass[0][0];
    let w2 = md.stiffness[0][0].div(m).ok()?;
    let two_alpha = md.damping[0][0].div(m).ok()?;
    let alpha = two_alpha.scale(&Q::new(1, 2).unwrap_or_else(Q::one));
    let forcing = md.forcing[0].div(m).ok()?;
    let zeta = if w2.is_zero() {
        None
    } else {
        func::sqrt(&w2).ok().and_then(|w| alpha.div(&w).ok())
    };
    // α is 0 also at a `--set` value of a parameter assumed real (c=0)
    let regime = if alpha.is_zero() || sign_of(&alpha, set) == Some(Sign::Zero) {
        "undamped".to_string()
    } else {
        match sign_of(&alpha.mul(&alpha).sub(&w2), set) {
            Some(Sign::Negative) => "underdamped".into(),
            Some(Sign::Zero) => "critically damped".into(),
            Some(_) => "overdamped".into(),
            None => "underdamped when α² < ω², overdamped when α² > ω²".to_string(),
        }
    };
    let omega = func::sqrt(&w2).ok().filter(|w| {
        w.num().len() == 1
            && w.den().len() == 1
            && !w
                .vars()
                .iter()
                .any(|&v| matches!(atom::atom(v), Atom::SqrtOf(_)))
    });
    Some(StandardForm {
        omega_squared: w2,
        alpha,
        forcing,
        zeta,
        regime,
        omega,
    })
}

/// The free response from initial positions and velocities (undamped):
/// q(t) = Σ_i u_i·(a_i·cos ω_i t + b_i·sin ω_i t). Returns q(t) per
/// coordinate, exactly.
pub fn free_response(md: &Modes, q0: &[Expr], v0: &[Expr]) -> Result<Vec<Expr>, Diagnostic> {
    crate::diag::bounded(|| free_response_unbounded(md, q0, v0))
}

/// [`free_response`] within the budget in force.
fn free_response_unbounded(md: &Modes, q0: &[Expr], v0: &[Expr]) -> Result<Vec<Expr>, Diagnostic> {
    let n = md.coordinates.len();
    if md.gyroscopic {
        return Err(Diagnostic::global(
            "the free response of a gyroscopic system needs its complex modes, which qdot does not give",
        )
        .with_hint("`qdot simulate` integrates the motion").with_kind(crate::diag::ErrorKind::Unsupported));
    }
    if md.defective {
        return Err(Diagnostic::global(
            "the free response needs a mode per frequency, and a repeated ω² here has fewer (the mass matrix is not definite)",
        )
        .with_hint("`qdot simulate` integrates the motion").with_kind(crate::diag::ErrorKind::Unsupported));
    }
    if md.omega_squared.len() != n {
        return Err(
            Diagnostic::global("the free response needs every frequency in closed form")
                .with_hint("give every parameter a value with --set for the numeric free response")
                .with_kind(crate::diag::ErrorKind::NoClosedForm),
        );
    }
    // U·a = q0, U·(ω∘b) = v0 with U's columns the modes
    let u: Vec<Vec<Expr>> = (0..n)
        .map(|j| (0..n).map(|i| md.modes[i][j].clone()).collect())
        .collect();
    let a = crate::algebra::linear::solve(&u, q0).map_err(|_| {
        Diagnostic::global("the modes are not independent").with_kind(
            crate::diag::ErrorKind::SingularSystem {
                unknowns: Vec::new(),
            },
        )
    })?;
    let wb = crate::algebra::linear::solve(&u, v0).map_err(|_| {
        Diagnostic::global("the modes are not independent").with_kind(
            crate::diag::ErrorKind::SingularSystem {
                unknowns: Vec::new(),
            },
        )
    })?;
    let t = Expr::time();
    let mut out = vec![Expr::zero(); n];
    for i in 0..n {
        let w = func::sqrt(&md.omega_squared[i]).map_err(math)?;
        let (s, c) = func::sin_cos(&w.mul(&t));
        let b = if w.is_zero() {
            Expr::zero()
        } else {
            wb[i].div(&w).map_err(math)?
        };
        let term = if w.is_zero() {
            a[i].add(&wb[i].mul(&t))
        } else {
            a[i].mul(&c).add(&b.mul(&s))
        };
        for (o, u) in out.iter_mut().zip(&md.modes[i]) {
            *o = o.add(&u.mul(&term));
        }
    }
    Ok(out)
}

/// A harmonic load f(t) = F·cos(p·t): (p, F), read off the forcing.
pub fn harmonic_load(md: &Modes) -> Option<(Expr, Vec<Expr>)> {
    let t = atom::time();
    // the driving angle u (cos u with u depending on t)
    let mut angle: Option<Expr> = None;
    for f in &md.forcing {
        for v in f.num().vars() {
            if let Atom::Cos(u) | Atom::Sin(u) = atom::atom(v) {
                if u.depends_on(t) {
                    angle = Some(u.clone());
                }
            }
        }
    }
    let u = angle?;
    let p = u.diff(t);
    if p.depends_on(t) {
        return None;
    }
    let (_, cv) = atom::intern_trig(&u);
    let mut amp = Vec::with_capacity(md.forcing.len());
    for f in &md.forcing {
        let cs = f.num().coeffs_in(cv);
        if cs.len() > 2 || cs.first().is_some_and(|c| !c.is_zero()) {
            return None; // not a pure cos(p·t) load
        }
        let c1 = cs.get(1).cloned().unwrap_or_default();
        amp.push(Expr::from_parts(c1, f.den().clone()).ok()?);
    }
    Some((p, amp))
}

/// Steady-state amplitudes X of an undamped system under f(t) = F·cos(p·t):
/// (K − p²·M)·X = F.
pub fn forced_amplitudes(md: &Modes) -> Option<(Expr, Vec<Expr>)> {
    let n = md.coordinates.len();
    let (p, amp) = harmonic_load(md)?;
    let p2 = p.mul(&p);
    let a: Vec<Vec<Expr>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| md.stiffness[i][j].sub(&p2.mul(&md.mass[i][j])))
                .collect()
        })
        .collect();
    let x = crate::algebra::linear::solve(&a, &amp).ok()?;
    Some((p, x))
}

/// One coordinate with damping, f = F·cos(p·t): the steady state
/// y = X·cos(p·t − ψ) with X = (F/M)/√((ω² − p²)² + 4α²p²) and
/// tan ψ = 2αp/(ω² − p²) (the seed's 24.3). Returns (p, X, tan ψ).
pub fn damped_steady_state(md: &Modes, sf: &StandardForm) -> Option<(Expr, Expr, Expr)> {
    let (p, f) = harmonic_load(md)?;
    let q = f[0].div(&md.mass[0][0]).ok()?;
    let p2 = p.mul(&p);
    let d = sf.omega_squared.sub(&p2);
    let two_ap = sf.alpha.mul(&p).scale(&Q::from_i64(2));
    let den = func::sqrt(&d.mul(&d).add(&two_ap.mul(&two_ap))).ok()?;
    let x = q.div(&den).ok()?;
    let tan_psi = two_ap.div(&d).ok()?;
    Some((p, x, tan_psi))
}

/// The amplitude and phase of a one-coordinate free response `q(t)`
/// (see [`amplitude_phase`]), read from q(0) and q̇(0).
pub fn free_amplitude_phase(md: &Modes, free: &[Expr]) -> Option<(Expr, Expr)> {
    if md.coordinates.len() != 1 || md.omega_squared.len() != 1 {
        return None;
    }
    let t = atom::time();
    let zero: FxHashMap<_, _> = [(t, Expr::zero())].into_iter().collect();
    let y0 = free[0].subs_many(&zero).ok()?;
    let v0 = free[0].diff(t).subs_many(&zero).ok()?;
    amplitude_phase(&md.omega_squared[0], &y0, &v0)
}

/// The amplitude per unit mass F/M of a harmonic load on one coordinate.
pub fn load_per_mass(md: &Modes) -> Option<Expr> {
    let (_, f) = harmonic_load(md)?;
    f[0].div(&md.mass[0][0]).ok()
}

/// The generalized symmetric eigenproblem K·v = ω²·M·v, numerically at
/// the parameter values `set` (none when a value is missing).
///
/// A gyroscopic system's ω² = −s² come from the eigenvalues s of its
/// first-order system (each pair ±s once), when they are all real, with
/// no vectors (its modes are complex).
pub fn numeric_modes(md: &Modes, set: &Values) -> Option<crate::solve::eigen::GeneralizedEigen> {
    numeric_modes_or_why(md, set).ok().flatten()
}

/// [`numeric_modes`], or why the eigen-solver refused the values (M not
/// positive definite there, singular, …): `Ok(None)` when there is
/// nothing to compute (no `--set`, or complex gyroscopic modes).
pub fn numeric_modes_or_why(
    md: &Modes,
    set: &Values,
) -> Result<Option<crate::solve::eigen::GeneralizedEigen>, String> {
    if set.is_empty() {
        return Ok(None);
    }
    if md.gyroscopic {
        let Some(s) =
            super::linear_stability::eigenvalues(&md.mass, &md.damping, &md.stiffness, set)?
        else {
            return Ok(None);
        };
        let lambda: Vec<_> = s.iter().map(|z| -(z * z)).collect();
        let scale = lambda.iter().fold(0.0f64, |a, z| a.max(z.norm()));
        if lambda.iter().any(|z| z.im.abs() > 1e-9 * scale) {
            return Ok(None);
        }
        let mut re: Vec<f64> = lambda.iter().map(|z| z.re).collect();
        re.sort_by(f64::total_cmp);
        return Ok(Some(crate::solve::eigen::GeneralizedEigen {
            values: re.into_iter().step_by(2).collect(),
            vectors: Vec::new(),
        }));
    }
    let (Some(k), Some(m)) = (
        numeric_matrix(&md.stiffness, set),
        numeric_matrix(&md.mass, set),
    ) else {
        return Ok(None);
    };
    crate::solve::eigen::generalized_symmetric(&k, &m)
        .map(Some)
        .map_err(|e| e.to_string())
}

/// A matrix of expressions in the parameters at the values `set`; `None`
/// when a parameter has no value (or an entry is not finite there).
pub(super) fn numeric_matrix(m: &[Vec<Expr>], set: &Values) -> Option<Vec<Vec<f64>>> {
    let at = |a: &Atom| match a {
        Atom::Param(n) => set.get(&**n).copied(),
        _ => None,
    };
    m.iter()
        .map(|r| r.iter().map(|e| e.eval_f64(&at)).collect())
        .collect()
}

/// One coordinate, undamped: y = A·sin(ω·t + φ) from y(0) = y0, ẏ(0) = v0
/// (the seed's 24.46–24.47): A = √(y0² + (v0/ω)²), φ = atan(y0·ω/v0)
/// (φ = ±π/2 when v0 = 0). Returns (A, φ).
pub fn amplitude_phase(omega_squared: &Expr, y0: &Expr, v0: &Expr) -> Option<(Expr, Expr)> {
    let w = func::sqrt(omega_squared).ok()?;
    let a = func::sqrt(&y0.mul(y0).add(&v0.div(&w).ok()?.powi(2).ok()?)).ok()?;
    let phi = if v0.is_zero() {
        let half_pi = Expr::pi().scale(&Q::new(1, 2).unwrap_or_else(Q::one));
        match sign_exact(y0) {
            Some(Sign::Negative) => half_pi.neg(),
            _ => half_pi,
        }
    } else {
        func::atan(&y0.mul(&w).div(v0).ok()?)
    };
    Some((a, phi))
}

/// How one mode of a numeric free response moves: ω² > 0 oscillates
/// (cos, sin), ω² < 0 grows (cosh, sinh), ω² = 0 drifts (1, t).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// ω² > 0: cos and sin
    Oscillates,
    /// ω² < 0: cosh and sinh
    Grows,
    /// ω² = 0: 1 and t
    Drifts,
}

/// One mode of a numeric free response: the mode contributes
/// `vector·(a·f(t) + b·g(t))` with f, g = cos(r·t), sin(r·t)/r (ω² = r²),
/// cosh(r·t), sinh(r·t)/r (ω² = −r²) or 1, t (ω² = 0).
#[derive(Clone, Debug)]
pub struct NumericMode {
    /// the eigen-solver's ω²
    pub omega_squared: f64,
    /// its kind of motion
    pub motion: Motion,
    /// r = √|ω²| (0 when the mode drifts)
    pub rate: f64,
    /// the M-normalized vector (vᵀ·M·v = 1)
    pub vector: Vec<f64>,
    /// a = vᵀ·M·q0
    pub a: f64,
    /// b = vᵀ·M·v0
    pub b: f64,
}

/// The free response of the undamped system computed numerically from the
/// M-orthonormal eigenvectors at the `--set` values (when the ω² have no
/// closed form): q(t) = Σ_i v_i·(a_i·f_i(t) + b_i·g_i(t)).
#[derive(Clone, Debug)]
pub struct NumericFree {
    /// one per eigenvalue, ω² ascending
    pub modes: Vec<NumericMode>,
}

/// |ω²| at or below this fraction of the largest |ω²| is a zero frequency
/// (the eigen-solver's rounding is about ε·max|ω²|).
const ZERO_OMEGA_SQUARED: f64 = 1e-11;

impl NumericFree {
    /// q(t), each coordinate.
    pub fn at(&self, t: f64) -> Vec<f64> {
        let n = self.modes.first().map_or(0, |m| m.vector.len());
        let mut q = vec![0.0; n];
        for m in &self.modes {
            let (f, g) = match m.motion {
                Motion::Oscillates => ((m.rate * t).cos(), (m.rate * t).sin() / m.rate),
                Motion::Grows => ((m.rate * t).cosh(), (m.rate * t).sinh() / m.rate),
                Motion::Drifts => (1.0, t),
            };
            let c = m.a * f + m.b * g;
            for (qj, vj) in q.iter_mut().zip(&m.vector) {
                *qj += vj * c;
            }
        }
        q
    }

    /// Coordinate `j` as terms (motion, rate, c, d) meaning c·cos(r·t) +
    /// d·sin(r·t), c·cosh(r·t) + d·sinh(r·t) or c + d·t; modes of one
    /// frequency are summed, and terms below the rounding (1e-11 of the
    /// largest coefficient of any coordinate) are left out.
    pub fn terms(&self, j: usize) -> Vec<(Motion, f64, f64, f64)> {
        let raw = |m: &NumericMode, k: usize| {
            let s = if m.motion == Motion::Drifts {
                1.0
            } else {
                m.rate
            };
            (m.vector[k] * m.a, m.vector[k] * m.b / s)
        };
        let n = self.modes.first().map_or(0, |m| m.vector.len());
        let scale = self
            .modes
            .iter()
            .flat_map(|m| (0..n).map(move |k| (m, k)))
            .map(|(m, k)| {
                let (c, d) = raw(m, k);
                c.abs().max(d.abs())
            })
            .fold(0.0f64, f64::max);
        let mut out: Vec<(Motion, f64, f64, f64)> = Vec::new();
        for m in &self.modes {
            let (c, d) = raw(m, j);
            let same = out.iter_mut().find(|(mo, r, _, _)| {
                *mo == m.motion && (r - m.rate).abs() <= 1e-10 * r.abs().max(m.rate.abs())
            });
            match same {
                Some(e) => {
                    e.2 += c;
                    e.3 += d;
                }
                None => out.push((m.motion, m.rate, c, d)),
            }
        }
        let tiny = ZERO_OMEGA_SQUARED * scale;
        for e in out.iter_mut() {
            if e.2.abs() <= tiny {
                e.2 = 0.0;
            }
            if e.3.abs() <= tiny {
                e.3 = 0.0;
            }
        }
        out.retain(|e| e.2 != 0.0 || e.3 != 0.0);
        out
    }
}

/// The numeric free response (undamped) at the `--set` values `set` from
/// q(0) = q0, q̇(0) = v0: a = Vᵀ·M·q0, b = Vᵀ·M·v0 with V's columns the
/// M-normalized eigenvectors of K·v = ω²·M·v. Refuses a gyroscopic system
/// (complex modes) and a parameter without a value.
pub fn numeric_free_response(
    md: &Modes,
    set: &Values,
    q0: &[Expr],
    v0: &[Expr],
) -> Result<NumericFree, Diagnostic> {
    if md.gyroscopic {
        return Err(Diagnostic::global(
            "the free response of a gyroscopic system needs its complex modes, which qdot does not give",
        )
        .with_hint("`qdot simulate` integrates the motion").with_kind(crate::diag::ErrorKind::Unsupported));
    }
    let missing = || {
        Diagnostic::global("the numeric free response needs a value for every parameter")
            .with_hint("give them with --set NAME=VALUE,…")
            .with_kind(crate::diag::ErrorKind::bad_option("--set"))
    };
    let g = numeric_modes(md, set).ok_or_else(|| {
        let at = |a: &Atom| match a {
            Atom::Param(n) => set.get(&**n).copied(),
            _ => None,
        };
        let mass: Option<Vec<Vec<f64>>> = md
            .mass
            .iter()
            .map(|r| r.iter().map(|e| e.eval_f64(&at)).collect())
            .collect();
        match mass.map(|m| super::definite::Mass::numeric(&m).definiteness()) {
            Some(d) if d != super::definite::Definiteness::Positive => Diagnostic::global(
                "the numeric free response needs a positive definite mass matrix, and this one is not at these values",
            )
            .with_hint("`qdot simulate` integrates the motion").with_kind(crate::diag::ErrorKind::Unphysical),
            _ => missing(),
        }
    })?;
    let at = |a: &Atom| match a {
        Atom::Param(n) => set.get(&**n).copied(),
        _ => None,
    };
    let num = |v: &[Expr]| -> Option<Vec<f64>> { v.iter().map(|e| e.eval_f64(&at)).collect() };
    let (q0, v0) = match (num(q0), num(v0)) {
        (Some(q), Some(v)) => (q, v),
        _ => return Err(missing()),
    };
    let mass: Vec<Vec<f64>> = md
        .mass
        .iter()
        .map(|r| {
            r.iter()
                .map(|e| e.eval_f64(&at))
                .collect::<Option<Vec<f64>>>()
        })
        .collect::<Option<_>>()
        .ok_or_else(missing)?;
    let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
    if !finite(&q0) || !finite(&v0) || !finite(&g.values) {
        return Err(
            Diagnostic::global("the numeric free response is not finite at these values")
                .with_kind(crate::diag::ErrorKind::Convergence),
        );
    }
    // vᵀ·M·x
    let project = |v: &[f64], x: &[f64]| -> f64 {
        (0..v.len())
            .map(|i| v[i] * (0..x.len()).map(|j| mass[i][j] * x[j]).sum::<f64>())
            .sum()
    };
    let biggest = g.values.iter().fold(0.0f64, |a, w| a.max(w.abs()));
    let modes = g
        .values
        .iter()
        .zip(&g.vectors)
        .map(|(&w2, v)| {
            let motion = if w2.abs() <= ZERO_OMEGA_SQUARED * biggest {
                Motion::Drifts
            } else if w2 > 0.0 {
                Motion::Oscillates
            } else {
                Motion::Grows
            };
            NumericMode {
                omega_squared: w2,
                motion,
                rate: if motion == Motion::Drifts {
                    0.0
                } else {
                    w2.abs().sqrt()
                },
                vector: v.clone(),
                a: project(v, &q0),
                b: project(v, &v0),
            }
        })
        .collect();
    Ok(NumericFree { modes })
}
