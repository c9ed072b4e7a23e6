//! The frequency response of the linearized system under harmonic forcing.
//!
//! About an equilibrium the motion obeys M·q̈ + C·q̇ + K·q = f(t)
//! (`linearize.rs`). When the load is harmonic, f(t) = F_c·cos(p·t) +
//! F_s·sin(p·t), its frequency p is replaced by a free frequency Ω (the
//! parameter `Omega`, printed Ω) and the steady state is
//! q(t) = Re(X·e^{iΩt}) with the receptance
//!
//! ```text
//! X(Ω) = (K − Ω²·M + i·Ω·C)⁻¹·F,   F = F_c − i·F_s
//! ```
//!
//! computed exactly as its real and imaginary parts, rational functions of
//! Ω and the parameters: (P + iQ)(x + iy) = F with P = K − Ω²M, Q = ΩC is
//! the real system [[P, −Q], [Q, P]]·[x; y] = [F_c; −F_s]. Each coordinate
//! moves as q_j = |X_j|·cos(Ω·t − φ_j) with |X_j|² = x_j² + y_j² and
//! tan φ_j = −y_j/x_j (the lag behind the load). The undamped system's
//! antiresonances are the roots in Ω² of the numerator of X_j (Den Hartog's
//! absorber: X₁ = 0 at Ω² = k₂/m₂). One degree of freedom adds the
//! textbook closed forms (ω₀, ζ, the magnification factor, the resonance
//! peak, the half-power points and the transmissibility), written with
//! α = c/(2m) so that every one is rational or a single square root.

use super::oscillations::Modes;
use crate::algebra::sign::{sign_of, Sign, Values};
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::atom::{self, Atom};
use crate::expr::{func, Expr};
use crate::num::Q;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// The name of the forcing frequency Ω (a parameter, printed Ω).
pub const OMEGA: &str = "Omega";

/// M·q̈ + C·q̇ + K·q = F_c·cos(Ω·t) + F_s·sin(Ω·t): the linearized system
/// with the scene's load at the free frequency Ω.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct ForcedSystem {
    /// The (independent) coordinate names.
    pub coordinates: Vec<String>,
    /// The load's frequency p as the scene writes it (before Ω replaced it).
    pub frequency: Expr,
    /// M.
    pub mass: Vec<Vec<Expr>>,
    /// C.
    pub damping: Vec<Vec<Expr>>,
    /// K.
    pub stiffness: Vec<Vec<Expr>>,
    /// F_c, the amplitudes of cos(Ω·t).
    pub load_cos: Vec<Expr>,
    /// F_s, the amplitudes of sin(Ω·t).
    pub load_sin: Vec<Expr>,
}

fn math(m: crate::expr::MathError) -> Diagnostic {
    let d = Diagnostic::global(m.message).with_kind(ErrorKind::Undefined);
    match m.hint {
        Some(h) => d.with_hint(h),
        None => d,
    }
}

/// What every refusal of a load says how to write.
const LOAD_HINT: &str =
    "write a harmonic load in the scene, e.g. `work L = F0*cos(p*t)*x` (p the forcing frequency)";

impl ForcedSystem {
    /// The system of `md` (from [`super::oscillations::modes`]) with its
    /// harmonic load.
    pub fn from_modes(md: &Modes) -> Result<ForcedSystem, Diagnostic> {
        crate::diag::bounded(|| {
            forced(
                md.coordinates.clone(),
                [&md.mass, &md.damping, &md.stiffness],
                &md.forcing,
            )
        })
    }

    /// The scene linearized about `at` (every q = 0 by default) with its
    /// harmonic load, without the characteristic polynomial and the modes
    /// (what a numeric sweep needs).
    pub fn of_scene(scene: &Scene, at: Option<&[Expr]>) -> Result<ForcedSystem, Diagnostic> {
        crate::diag::bounded(|| Self::of_scene_within(scene, at))
    }

    /// [`ForcedSystem::of_scene`] within the budget in force.
    fn of_scene_within(scene: &Scene, at: Option<&[Expr]>) -> Result<ForcedSystem, Diagnostic> {
        scene.expanded_only("the frequency response")?;
        check_time_dependence(scene)?;
        scene.assumptions_required("the frequency response")?;
        let lin = super::linearize::linearize(scene, &super::linearize::Reference::at(at))?;
        forced(
            lin.coordinates,
            [&lin.mass, &lin.damping, &lin.stiffness],
            &lin.forcing,
        )
    }

    /// Whether C has a part that is not zero.
    pub fn damped(&self) -> bool {
        self.damping.iter().flatten().any(|e| !e.is_zero())
    }

    /// C has a skew part (gyroscopic terms).
    pub fn gyroscopic(&self) -> bool {
        let c = &self.damping;
        (0..c.len()).any(|i| (0..c.len()).any(|j| !c[i][j].equals(&c[j][i])))
    }

    /// Whether M, C, K or the load depend on Ω (the load's frequency was
    /// also a parameter of the system: a rotating unbalance m·e·Ω²).
    pub fn depends_on_omega(&self) -> bool {
        let w = atom::param(OMEGA);
        self.mass
            .iter()
            .chain(&self.damping)
            .chain(&self.stiffness)
            .flatten()
            .chain(&self.load_cos)
            .chain(&self.load_sin)
            .any(|e| e.depends_on(w))
    }
}

/// Read the harmonic load off the forcing and put Ω in place of its
/// frequency.
fn forced(
    coordinates: Vec<String>,
    [mass, damping, stiffness]: [&Vec<Vec<Expr>>; 3],
    forcing: &[Expr],
) -> Result<ForcedSystem, Diagnostic> {
    let (p, cos, sin) = harmonic(forcing)?;
    let omega = Expr::param(OMEGA);
    let w = atom::param(OMEGA);
    let all = || {
        mass.iter()
            .chain(damping)
            .chain(stiffness)
            .flatten()
            .chain(&cos)
            .chain(&sin)
    };
    let mut map: FxHashMap<Var, Expr> = FxHashMap::default();
    match multiple_of_a_parameter(&p) {
        Some((v, q)) => {
            if v != w && all().any(|e| e.depends_on(w)) {
                return Err(Diagnostic::global(
                    "the scene has a parameter `Omega`, and `qdot response` names the forcing frequency Ω",
                )
                .with_hint("rename the scene's parameter `Omega`").with_kind(ErrorKind::DuplicateName { name: "Omega".into() }));
            }
            // p = q·v is Ω: v = Ω/q wherever the system has it
            let q_inv = Q::one().checked_div(&q).unwrap_or_else(Q::one);
            map.insert(v, omega.scale(&q_inv));
        }
        _ => {
            // Ω replaces the whole of p: nothing else may depend on its parts
            let parts = p.vars();
            if all().any(|e| parts.iter().any(|&v| e.depends_on(v))) {
                return Err(Diagnostic::global(format!(
                    "the load's frequency is {}, and the system also depends on its parameters: Ω cannot replace it",
                    p.to_unicode()
                ))
                .with_hint("name the forcing frequency with one parameter: `cos(p*t)`").with_kind(ErrorKind::Unsupported));
            }
        }
    }
    let subs = |rows: &[Vec<Expr>]| -> Result<Vec<Vec<Expr>>, Diagnostic> {
        rows.iter()
            .map(|r| r.iter().map(|e| e.subs_many(&map).map_err(math)).collect())
            .collect()
    };
    let load = |v: Vec<Expr>| -> Result<Vec<Expr>, Diagnostic> {
        v.iter().map(|e| e.subs_many(&map).map_err(math)).collect()
    };
    Ok(ForcedSystem {
        coordinates,
        frequency: p,
        mass: subs(mass)?,
        damping: subs(damping)?,
        stiffness: subs(stiffness)?,
        load_cos: load(cos)?,
        load_sin: load(sin)?,
    })
}

/// p = q·v with a rational q ≠ 0 and a parameter v: (v, q).
fn multiple_of_a_parameter(p: &Expr) -> Option<(Var, Q)> {
    let [v] = p.vars()[..] else {
        return None;
    };
    if !matches!(atom::atom(v), Atom::Param(_)) {
        return None;
    }
    let q = p.div(&Expr::var(v)).ok()?.as_rational()?;
    (!q.is_zero()).then_some((v, q))
}

/// cos^a θ · sin^b θ as Σ_k (A_k·cos kθ + B_k·sin kθ), k = 0..=a+b
/// (product to sum, one factor at a time).
fn power_harmonics(a: u32, b: u32) -> (Vec<Q>, Vec<Q>) {
    let n = (a + b) as usize;
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let (mut ca, mut sb) = (vec![Q::zero(); n + 2], vec![Q::zero(); n + 2]);
    ca[0] = Q::one();
    for step in 0..a + b {
        let by_cos = step < a;
        let (mut nc, mut ns) = (vec![Q::zero(); n + 2], vec![Q::zero(); n + 2]);
        // x·cos jθ (+ y·sin jθ) at the signed index j: cos even, sin odd
        let mut put = |j: i64, x: Q, y: Q| {
            let i = j.unsigned_abs() as usize;
            nc[i] += x;
            if j < 0 {
                ns[i] -= y;
            } else {
                ns[i] += y;
            }
        };
        for k in 0..=n {
            let (x, y) = (ca[k].clone(), sb[k].clone());
            if x.is_zero() && y.is_zero() {
                continue;
            }
            let (xh, yh) = (x * &half, y * &half);
            let k = k as i64;
            if by_cos {
                // cos·cos kθ = (cos(k+1)θ + cos(k−1)θ)/2, cos·sin kθ likewise
                put(k + 1, xh.clone(), yh.clone());
                put(k - 1, xh, yh);
            } else {
                // sin·cos kθ = (sin(k+1)θ − sin(k−1)θ)/2,
                // sin·sin kθ = (cos(k−1)θ − cos(k+1)θ)/2
                put(k + 1, -yh.clone(), xh.clone());
                put(k - 1, yh, -xh);
            }
        }
        ns[0] = Q::zero(); // sin 0 = 0
        ca = nc;
        sb = ns;
    }
    ca.truncate(n + 1);
    sb.truncate(n + 1);
    (ca, sb)
}

/// A polynomial in sin θ (`sv`) and cos θ (`cv`) as its harmonics: per k,
/// the coefficients of cos kθ and sin kθ.
fn harmonics(
    p: &crate::poly::Poly,
    sv: Var,
    cv: Var,
) -> Vec<(crate::poly::Poly, crate::poly::Poly)> {
    use crate::poly::Poly;
    let mut out: Vec<(Poly, Poly)> = Vec::new();
    for (m, c) in p.terms() {
        let (a, b) = (m.degree(cv), m.degree(sv));
        let rest = m.without(cv).without(sv);
        let (ca, sb) = power_harmonics(a, b);
        if out.len() < ca.len() {
            out.resize(ca.len(), (Poly::zero(), Poly::zero()));
        }
        for (k, (x, y)) in ca.iter().zip(&sb).enumerate() {
            let mut coef = c.clone();
            coef *= x;
            out[k].0 = &out[k].0 + &Poly::monomial(rest.clone(), coef);
            let mut coef = c.clone();
            coef *= y;
            out[k].1 = &out[k].1 + &Poly::monomial(rest.clone(), coef);
        }
    }
    out
}

/// Whether the angle `u` is ω·t + φ with ω and φ constant (periodic).
fn linear_in_time(u: &Expr) -> bool {
    let w = u.diff(atom::time());
    !w.depends_on_time() && !u.sub(&w.mul(&Expr::time())).depends_on_time()
}

/// The mean of `f` over time, and whether `f` changes with time: each
/// term's mean over a period of the sines and cosines of t in it (their
/// frequencies taken as independent: cos²(p·t)·cos(w·t) averages 0,
/// cos²(p·t)·cos²(w·t) averages 1/4); a term with any other time
/// dependence (t itself, e^t, cos(t²)) counts as moving, with no mean
/// taken.
/// `None` when the denominator depends on time.
pub(super) fn mean_over_time(f: &Expr) -> Option<(Expr, bool)> {
    use crate::poly::Poly;
    let t = atom::time();
    if f.den().vars().iter().any(|&v| Expr::var(v).depends_on(t)) {
        return None;
    }
    let mut mean = Poly::zero();
    let mut moving = false;
    for (m, c) in f.num().terms() {
        let mut coef = c.clone();
        let mut rest = m.clone();
        let mut trig = true;
        let mut timed = false;
        for (v, _) in m.pairs().iter().copied() {
            if !Expr::var(v).depends_on(t) {
                continue;
            }
            timed = true;
            rest = rest.without(v);
            match atom::atom(v) {
                Atom::Cos(u) | Atom::Sin(u) if linear_in_time(&u) => {
                    let (sv, cv) = atom::intern_trig(&u);
                    // each angle once: the pair's exponents together
                    if v == sv && m.degree(cv) > 0 {
                        continue;
                    }
                    let (a, b) = (m.degree(cv), m.degree(sv));
                    let (ca, _) = power_harmonics(a, b);
                    coef *= &ca[0];
                }
                _ => trig = false,
            }
        }
        moving |= timed;
        if trig && !coef.is_zero() {
            mean = &mean + &Poly::monomial(rest, coef);
        }
    }
    Some((Expr::from_parts(mean, f.den().clone()).ok()?, moving))
}

fn no_harmonic_load() -> Diagnostic {
    Diagnostic::global(
        "the scene has no harmonic load: the frequency response needs a force F·cos(p·t) (or sin) on the system",
    )
    .with_hint(LOAD_HINT)
    .with_kind(crate::diag::ErrorKind::NothingToSolve)
}

/// The error of a scene in which nothing depends on time (no definition,
/// load, torque, force or constraint mentions `t` or a given function):
/// it has no harmonic load, which is known before any linearization.
pub fn check_time_dependence(scene: &Scene) -> Result<(), Diagnostic> {
    let timed = |e: &Expr| e.depends_on_time();
    let any = scene
        .definitions
        .iter()
        .any(|d| d.value.components().iter().any(timed))
        || !scene.deferred.is_empty()
        || !scene.functions.is_empty()
        || !scene.drives.is_empty()
        || scene.loads.iter().any(|l| {
            l.force.components().iter().any(timed) || l.point.components().iter().any(timed)
        })
        || scene
            .torques
            .iter()
            .any(|q| timed(&q.moment) || timed(&q.angle))
        || scene.forces.iter().any(|f| timed(&f.value))
        || scene
            .constraints
            .iter()
            .any(|c| timed(&c.expression) || timed(&c.rest) || c.coefficients.iter().any(timed));
    if any {
        Ok(())
    } else {
        Err(no_harmonic_load())
    }
}

/// f(t) = F_c·cos(p·t) + F_s·sin(p·t): (p, F_c, F_s), or why the forcing
/// is not one harmonic load. A polynomial in cos θ and sin θ (θ = ω·t)
/// is read by its harmonics: F·cos(2·p·t) is the load at 2·p, and several
/// harmonics are several frequencies.
#[allow(clippy::type_complexity)] // a triple read by one caller
fn harmonic(forcing: &[Expr]) -> Result<(Expr, Vec<Expr>, Vec<Expr>), Diagnostic> {
    let t = atom::time();
    let mut angles: Vec<Expr> = Vec::new();
    for f in forcing {
        for v in f.num().vars().into_iter().chain(f.den().vars()) {
            if let Atom::Cos(u) | Atom::Sin(u) = atom::atom(v) {
                if u.depends_on(t) && !angles.iter().any(|a| a.equals(&u)) {
                    angles.push(u);
                }
            }
        }
    }
    let u = match &angles[..] {
        [u] => u.clone(),
        [] => return Err(no_harmonic_load()),
        [_, _, ..] => {
            // named in text order, not in the order the atoms were made
            let mut named: Vec<String> = angles.iter().map(Expr::to_unicode).collect();
            named.sort();
            return Err(more_than_one(&named[0], &named[1]));
        }
    };
    let w = u.diff(t);
    if w.depends_on_time() || !u.sub(&w.mul(&Expr::time())).is_zero() {
        return Err(Diagnostic::global(format!(
            "the load's angle {} is not p·t with a constant p: the frequency response takes F·cos(p·t) and F·sin(p·t)",
            u.to_unicode()
        ))
        .with_hint(LOAD_HINT).with_kind(ErrorKind::Unsupported));
    }
    let (sv, cv) = atom::intern_trig(&u);
    let not_harmonic = |f: &Expr| {
        Diagnostic::global(format!(
            "the forcing {} is not F_c·cos(p·t) + F_s·sin(p·t): the frequency response takes one harmonic load",
            f.to_unicode()
        ))
        .with_hint(LOAD_HINT).with_kind(ErrorKind::Unsupported)
    };
    // per coordinate, per harmonic k: (cos kθ, sin kθ)
    let mut table: Vec<Vec<(Expr, Expr)>> = Vec::with_capacity(forcing.len());
    for f in forcing {
        if f.den().contains_var(sv)
            || f.den().contains_var(cv)
            || Expr::from_poly(f.den().clone()).depends_on_time()
        {
            return Err(not_harmonic(f));
        }
        let mut row = Vec::new();
        for (c, s) in harmonics(f.num(), sv, cv) {
            let c = Expr::from_parts(c, f.den().clone()).map_err(math)?;
            let s = Expr::from_parts(s, f.den().clone()).map_err(math)?;
            if c.depends_on_time() || s.depends_on_time() {
                return Err(not_harmonic(f));
            }
            row.push((c, s));
        }
        if row.first().is_some_and(|(c, _)| !c.is_zero()) {
            return Err(Diagnostic::global(format!(
                "the forcing {} has the constant part {}: the frequency response takes a load without one",
                f.to_unicode(),
                row[0].0.to_unicode()
            ))
            .with_hint(LOAD_HINT).with_kind(ErrorKind::Unsupported));
        }
        table.push(row);
    }
    let present: Vec<usize> = (1..table.iter().map(Vec::len).max().unwrap_or(0))
        .filter(|&k| {
            table
                .iter()
                .any(|r| r.get(k).is_some_and(|(c, s)| !c.is_zero() || !s.is_zero()))
        })
        .collect();
    let angle = |k: usize| u.scale(&Q::from_i64(k as i64)).to_unicode();
    let k = match present[..] {
        [k] => k,
        [] => return Err(no_harmonic_load()),
        [a, b, ..] => return Err(more_than_one(&angle(a), &angle(b))),
    };
    let pick = |i: usize| -> (Expr, Expr) {
        table[i]
            .get(k)
            .cloned()
            .unwrap_or_else(|| (Expr::zero(), Expr::zero()))
    };
    let (cos, sin): (Vec<Expr>, Vec<Expr>) = (0..forcing.len()).map(pick).unzip();
    Ok((w.scale(&Q::from_i64(k as i64)), cos, sin))
}

fn more_than_one(a: &str, b: &str) -> Diagnostic {
    Diagnostic::global(format!(
        "the load has more than one frequency (cos({a}) and cos({b})): the frequency response takes one harmonic load"
    ))
    .with_hint("keep one frequency in the scene; the responses to several add up").with_kind(ErrorKind::Unsupported)
}

/// The exact frequency response.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Response {
    /// The system and its load.
    pub system: ForcedSystem,
    /// Re X_j(Ω).
    pub real: Vec<Expr>,
    /// Im X_j(Ω).
    pub imag: Vec<Expr>,
    /// |X_j|² = (Re X_j)² + (Im X_j)².
    pub amplitude_squared: Vec<Expr>,
    /// tan φ_j = −Im X_j/Re X_j, q_j = |X_j|·cos(Ω·t − φ_j); `None` where
    /// Re X_j is identically zero (φ_j = ±π/2, or no motion).
    pub tan_phase: Vec<Option<Expr>>,
    /// Per coordinate, the Ω² where the undamped X_j is zero.
    pub antiresonances: Vec<Vec<Expr>>,
    /// Why `antiresonances` is empty, when they were not computed.
    pub antiresonance_note: Option<String>,
    /// One degree of freedom: the textbook closed forms.
    pub single: Option<SingleDof>,
}

/// One degree of freedom m·ẍ + c·ẋ + k·x = F·cos(Ω·t): ω₀² = k/m,
/// α = c/(2m), ζ = α/ω₀, r = Ω/ω₀.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SingleDof {
    /// ω₀² = k/m.
    pub omega0_squared: Expr,
    /// α = c/(2m).
    pub alpha: Expr,
    /// ζ² = α²/ω₀² = c²/(4km).
    pub zeta_squared: Expr,
    /// The static deflection F/k (|F|/k for a load with both a cosine and
    /// a sine part; `None` when F depends on Ω).
    pub static_deflection: Option<Expr>,
    /// The magnification factor squared, D² = 1/((1 − r²)² + (2ζr)²) in Ω.
    pub magnification_squared: Expr,
    /// tan φ = 2ζr/(1 − r²) in Ω.
    pub tan_phase: Expr,
    /// The resonance peak of D.
    pub peak: Peak,
    /// The transmissibility squared, T² = (1 + (2ζr)²)/((1 − r²)² + (2ζr)²).
    pub transmissibility_squared: Expr,
}

/// Where the magnification factor D(Ω) peaks.
#[derive(Clone, Debug)]
pub enum Peak {
    /// Undamped: D is infinite at Ω = ω₀.
    Undamped,
    /// ω_peak² = ω₀²·(1 − 2ζ²) = ω₀² − 2α² (`condition`: the sign of
    /// 1/2 − ζ² was not decided, and this is when the peak exists).
    At {
        /// ω_peak² = ω₀² − 2α².
        omega_squared: Expr,
        /// D at the peak squared, 1/(4ζ²(1 − ζ²)).
        magnification_squared: Expr,
        /// The peak amplitude, (F/k)/(2ζ·√(1 − ζ²)) (`None` when F
        /// depends on Ω).
        amplitude: Option<Expr>,
        /// The half-power frequencies Ω₁,₂² = ω₀² − 2α² ∓ 2α·√(ω₀² − α²)
        /// (D = D_peak/√2); Ω₁² only when it is positive.
        half_power: (Option<Expr>, Expr),
        /// (Ω₂ − Ω₁)² = 2(ω₀² − 2α²) − 2·√(ω₀⁴ − 8α²ω₀² + 8α⁴), when
        /// both half-power points exist.
        bandwidth_squared: Option<Expr>,
        /// When the existence of the peak is undecided: the condition
        /// (ζ² < 1/2) as an expression that must be positive.
        condition: Option<Expr>,
    },
    /// ζ² ≥ 1/2: D falls from Ω = 0 on.
    None,
    /// A load that depends on Ω (a rotating unbalance m·e·Ω², a base
    /// moved through a spring and a damper): where |X| itself peaks.
    Load(LoadPeak),
}

/// The peak of |X| for a load that depends on Ω, from the stationary
/// points of |X|² = N(λ)/D(λ) in λ = Ω²: the roots of N'·D − N·D'.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct LoadPeak {
    /// Ω_peak², or `None` when |X| has no peak at a finite Ω > 0 or it
    /// was not found (`note` says which).
    pub omega_squared: Option<Expr>,
    /// When the peak's existence is undecided: the expression (Ω_peak²)
    /// that must be positive.
    pub condition: Option<Expr>,
    /// |X_peak|².
    pub amplitude_squared: Option<Expr>,
    /// The half-power frequencies squared (|X| = |X_peak|/√2) below and
    /// above the peak, each where it exists.
    pub half_power: (Option<Expr>, Option<Expr>),
    /// What was not found or does not exist, and why.
    pub note: Option<String>,
    /// Why the half-power frequencies are not given, when they are not.
    pub half_power_note: Option<String>,
    /// Where D, the magnification factor of a constant-amplitude force,
    /// peaks: ω₀² − 2α², when it does (not a property of this load).
    pub constant_force_peak: Option<Expr>,
}

/// The exact frequency response of `sys`, signs decided with `set`.
pub fn response(sys: ForcedSystem, set: &Values) -> Result<Response, Diagnostic> {
    crate::diag::bounded(|| response_within(sys, set))
}

/// [`response`] within the budget in force.
fn response_within(sys: ForcedSystem, set: &Values) -> Result<Response, Diagnostic> {
    let _context = crate::budget::enter(|| "computing the frequency response".into(), None);
    let (real, imag) = receptance(&sys)?;
    let mut amplitude_squared = Vec::with_capacity(real.len());
    let mut tan_phase = Vec::with_capacity(real.len());
    for (x, y) in real.iter().zip(&imag) {
        amplitude_squared.push(x.mul(x).add(&y.mul(y)));
        tan_phase.push(if x.is_zero() {
            None
        } else {
            Some(y.neg().div(x).map_err(math)?)
        });
    }
    let (antiresonances, antiresonance_note) = antiresonances(&sys, set)?;
    let single = single_dof(&sys, set)?;
    Ok(Response {
        system: sys,
        real,
        imag,
        amplitude_squared,
        tan_phase,
        antiresonances,
        antiresonance_note,
        single,
    })
}

fn matrix(n: usize, f: impl Fn(usize, usize) -> Expr) -> Vec<Vec<Expr>> {
    (0..n).map(|i| (0..n).map(|j| f(i, j)).collect()).collect()
}

/// (Re X, Im X) from [[P, −Q], [Q, P]]·[x; y] = [F_c; −F_s].
fn receptance(sys: &ForcedSystem) -> Result<(Vec<Expr>, Vec<Expr>), Diagnostic> {
    let n = sys.coordinates.len();
    let omega = Expr::param(OMEGA);
    let w2 = omega.mul(&omega);
    let p = matrix(n, |i, j| sys.stiffness[i][j].sub(&w2.mul(&sys.mass[i][j])));
    let minus_sin: Vec<Expr> = sys.load_sin.iter().map(Expr::neg).collect();
    let singular = |_| {
        Diagnostic::global("K − Ω²·M + i·Ω·C is singular for every Ω: the steady state is not unique")
            .with_hint("a free coordinate (a zero row of M, C and K) has no steady response; fix it or remove it")
            .with_kind(ErrorKind::SingularSystem { unknowns: Vec::new() })
    };
    if !sys.damped() {
        let x = crate::algebra::linear::solve(&p, &sys.load_cos).map_err(singular)?;
        let y = crate::algebra::linear::solve(&p, &minus_sin).map_err(singular)?;
        return Ok((x, y));
    }
    let q = matrix(n, |i, j| omega.mul(&sys.damping[i][j]));
    let big = matrix(2 * n, |i, j| match (i < n, j < n) {
        (true, true) => p[i][j].clone(),
        (true, false) => q[i][j - n].neg(),
        (false, true) => q[i - n][j].clone(),
        (false, false) => p[i - n][j - n].clone(),
    });
    let rhs: Vec<Expr> = sys.load_cos.iter().chain(&minus_sin).cloned().collect();
    let xy = crate::algebra::linear::solve(&big, &rhs).map_err(singular)?;
    Ok((xy[..n].to_vec(), xy[n..].to_vec()))
}

/// The roots in λ = Ω² of each undamped X_j's numerator (C dropped; a
/// load free of Ω with one of F_c, F_s zero).
#[allow(clippy::type_complexity)] // per coordinate, the roots; and a note
fn antiresonances(
    sys: &ForcedSystem,
    set: &Values,
) -> Result<(Vec<Vec<Expr>>, Option<String>), Diagnostic> {
    let n = sys.coordinates.len();
    let none = |why: &str| Ok((vec![Vec::new(); n], Some(why.to_string())));
    if sys.gyroscopic() {
        return none(
            "C has gyroscopic terms, which the undamped system keeps: no antiresonances computed",
        );
    }
    if sys.depends_on_omega() {
        return none("the system depends on Ω beyond K − Ω²·M: no antiresonances computed");
    }
    let load = match (
        sys.load_cos.iter().all(Expr::is_zero),
        sys.load_sin.iter().all(Expr::is_zero),
    ) {
        (_, true) => &sys.load_cos,
        (true, false) => &sys.load_sin,
        (false, false) => return none(
            "the load has both cos(Ω·t) and sin(Ω·t) parts out of step: no antiresonances computed",
        ),
    };
    let lv = atom::unknown(super::oscillations::LAMBDA);
    let lambda = Expr::var(lv);
    let a = matrix(n, |i, j| {
        sys.stiffness[i][j].sub(&lambda.mul(&sys.mass[i][j]))
    });
    let Ok(x) = crate::algebra::linear::solve(&a, load) else {
        return none("K − Ω²·M is singular for every Ω: no antiresonances computed");
    };
    let mut out = Vec::with_capacity(n);
    for xj in &x {
        if xj.is_zero() || !xj.num().contains_var(lv) {
            out.push(Vec::new());
            continue;
        }
        let numerator = Expr::from_poly(xj.num().clone());
        let found = super::characteristic::roots(&numerator, lv, false, set);
        let mut roots: Vec<Expr> = Vec::new();
        for r in found.roots {
            let real_frequency = !matches!(sign_of(&r, set), Some(Sign::Negative | Sign::Zero));
            if real_frequency && !roots.iter().any(|s| s.equals(&r)) {
                roots.push(r);
            }
        }
        out.push(roots);
    }
    Ok((out, None))
}

/// The closed forms of one degree of freedom (none for more, or for a
/// coordinate without mass or stiffness).
fn single_dof(sys: &ForcedSystem, set: &Values) -> Result<Option<SingleDof>, Diagnostic> {
    if sys.coordinates.len() != 1 {
        return Ok(None);
    }
    let (m, c, k) = (&sys.mass[0][0], &sys.damping[0][0], &sys.stiffness[0][0]);
    let w = atom::param(OMEGA);
    if m.is_zero() || k.is_zero() || [m, c, k].iter().any(|e| e.depends_on(w)) {
        return Ok(None);
    }
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let w0sq = k.div(m).map_err(math)?;
    let alpha = c.div(m).map_err(math)?.scale(&half);
    let a2 = alpha.mul(&alpha);
    let zeta_squared = a2.div(&w0sq).map_err(math)?;
    let omega = Expr::param(OMEGA);
    let w2 = omega.mul(&omega);
    // (k − mΩ²)² + c²Ω² over k²: (1 − r²)² + (2ζr)²
    let d = k.sub(&m.mul(&w2));
    let den = d.mul(&d).add(&c.mul(c).mul(&w2));
    let k2 = k.mul(k);
    let magnification_squared = k2.div(&den).map_err(math)?;
    let tan_phase = c.mul(&omega).div(&d).map_err(math)?;
    let transmissibility_squared = k2.add(&c.mul(c).mul(&w2)).div(&den).map_err(math)?;
    let (fc, fs) = (&sys.load_cos[0], &sys.load_sin[0]);
    // F/k itself where the load is a cosine or a sine, the modulus otherwise
    let static_deflection = if fc.depends_on(w) || fs.depends_on(w) {
        None
    } else if fs.is_zero() || fc.is_zero() {
        Some(fc.add(fs).div(k).map_err(math)?)
    } else {
        let f2 = fc.mul(fc).add(&fs.mul(fs));
        Some(func::sqrt(&f2.div(&k2).map_err(math)?).map_err(math)?)
    };
    let load_depends_on_omega = fc.depends_on(w) || fs.depends_on(w);
    let peak = if load_depends_on_omega && !alpha.is_zero() {
        let f2 = fc.mul(fc).add(&fs.mul(fs));
        Peak::Load(load_peak(&f2.div(&den).map_err(math)?, &w0sq, &alpha, set)?)
    } else {
        peak(&w0sq, &alpha, static_deflection.as_ref(), set)?
    };
    Ok(Some(SingleDof {
        omega0_squared: w0sq,
        alpha,
        zeta_squared,
        static_deflection,
        magnification_squared,
        tan_phase,
        peak,
        transmissibility_squared,
    }))
}

/// The resonance peak, the half-power points and the bandwidth from ω₀²
/// and α (`x_static` = F/k).
fn peak(
    w0sq: &Expr,
    alpha: &Expr,
    x_static: Option<&Expr>,
    set: &Values,
) -> Result<Peak, Diagnostic> {
    if alpha.is_zero() {
        return Ok(Peak::Undamped);
    }
    let two = Q::from_i64(2);
    let a2 = alpha.mul(alpha);
    let peak2 = w0sq.sub(&a2.scale(&two));
    let condition = match sign_of(&peak2, set) {
        Some(Sign::Positive) => None,
        Some(_) => return Ok(Peak::None),
        None => Some(peak2.clone()),
    };
    // ω₀² − α² = ω_d², positive where the peak exists
    let wd2 = w0sq.sub(&a2);
    let root = func::sqrt(&wd2).map_err(math)?;
    let spread = alpha.mul(&root).scale(&two);
    let lower = peak2.sub(&spread);
    let upper = peak2.add(&spread);
    let lower = match sign_of(&lower, set) {
        Some(Sign::Negative | Sign::Zero) => None,
        _ => Some(lower),
    };
    // 1/(4ζ²(1 − ζ²)) = ω₀⁴/(4α²(ω₀² − α²))
    let magnification_squared = w0sq
        .mul(w0sq)
        .div(&a2.mul(&wd2).scale(&Q::from_i64(4)))
        .map_err(math)?;
    let amplitude = match x_static {
        Some(x) => Some(
            x.mul(w0sq)
                .div(&alpha.mul(&root).scale(&two))
                .map_err(math)?,
        ),
        None => None,
    };
    let bandwidth_squared = if lower.is_some() {
        let product = w0sq
            .mul(w0sq)
            .sub(&a2.mul(w0sq).scale(&Q::from_i64(8)))
            .add(&a2.mul(&a2).scale(&Q::from_i64(8)));
        let r = func::sqrt(&product).map_err(math)?;
        Some(peak2.sub(&r).scale(&two))
    } else {
        None
    };
    Ok(Peak::At {
        omega_squared: peak2,
        magnification_squared,
        amplitude,
        half_power: (lower, upper),
        bandwidth_squared,
        condition,
    })
}

/// An even polynomial in Ω as the polynomial in λ = Ω² (`None` when it
/// has an odd power of Ω).
fn in_omega_squared(p: &crate::poly::Poly, lv: Var) -> Option<Expr> {
    let cs = p.coeffs_in(atom::param(OMEGA));
    let mut out = Expr::zero();
    let lambda = Expr::var(lv);
    let mut power = Expr::one();
    for (i, c) in cs.into_iter().enumerate() {
        if i % 2 == 1 {
            if !c.is_zero() {
                return None;
            }
            power = power.mul(&lambda);
            continue;
        }
        out = out.add(&Expr::from_poly(c).mul(&power));
    }
    Some(out)
}

/// The coefficients of `e`'s numerator in `lv`, each over its denominator.
fn coefficients(e: &Expr, lv: Var) -> Result<Vec<Expr>, Diagnostic> {
    e.num()
        .coeffs_in(lv)
        .into_iter()
        .map(|c| Expr::from_parts(c, e.den().clone()).map_err(math))
        .collect()
}

fn positive(e: &Expr, set: &Values) -> Option<bool> {
    match sign_of(e, set)? {
        Sign::Positive => Some(true),
        _ => Some(false),
    }
}

/// The peak of |X|² = `amp2` (a rational function of Ω, the load's
/// amplitude over (k − mΩ²)² + c²Ω²), its half-power points, and D's
/// peak for comparison. Exact where the stationary points of |X|² in
/// λ = Ω² have a closed form and their signs are decided; otherwise
/// `note` says what is missing.
fn load_peak(amp2: &Expr, w0sq: &Expr, alpha: &Expr, set: &Values) -> Result<LoadPeak, Diagnostic> {
    let d_peak = w0sq.sub(&alpha.mul(alpha).scale(&Q::from_i64(2)));
    let mut out = LoadPeak {
        omega_squared: None,
        condition: None,
        amplitude_squared: None,
        half_power: (None, None),
        note: None,
        half_power_note: None,
        constant_force_peak: match sign_of(&d_peak, set) {
            Some(Sign::Negative | Sign::Zero) => None,
            _ => Some(d_peak),
        },
    };
    let lv = atom::unknown(super::oscillations::LAMBDA);
    let (Some(n), Some(d)) = (
        in_omega_squared(amp2.num(), lv),
        in_omega_squared(amp2.den(), lv),
    ) else {
        out.note = Some("|X|² has odd powers of Ω: its peak is not computed".into());
        return Ok(out);
    };
    // d|X|²/dλ = (N'·D − N·D')/D²: its sign is that of the numerator
    let slope = n.diff(lv).mul(&d).sub(&n.mul(&d.diff(lv)));
    let mut cs = coefficients(&slope, lv)?;
    while cs.len() > 1 && cs[0].is_zero() {
        cs.remove(0); // λ = 0 is not a peak at Ω > 0
    }
    if cs.iter().all(Expr::is_zero) {
        out.note = Some("|X| does not change with Ω: no peak".into());
        return Ok(out);
    }
    let first = positive(&cs[0], set);
    let lambda = Expr::var(lv);
    let reduced = cs.iter().enumerate().fold(Expr::zero(), |acc, (i, c)| {
        acc.add(&c.mul(&lambda.powi(i as i64).unwrap_or_else(|_| Expr::one())))
    });
    let mut roots = Vec::new();
    if cs.len() > 1 {
        let found = super::characteristic::roots(&reduced, lv, false, set);
        if let Some(why) = found.why {
            out.note = Some(format!(
                "|X| is stationary where {} = 0 (λ = Ω²): {why}",
                reduced.to_unicode()
            ));
            return Ok(out);
        }
        roots = found.roots;
    }
    let mut candidates: Vec<Expr> = Vec::new();
    let mut undecided = false;
    for r in roots {
        match sign_of(&r, set) {
            Some(Sign::Negative | Sign::Zero) => {}
            s => {
                undecided |= s.is_none();
                if !candidates.iter().any(|c| c.equals(&r)) {
                    candidates.push(r);
                }
            }
        }
    }
    let monotone = |rises: bool| {
        if rises {
            "no peak: |X| rises with Ω for every Ω > 0"
        } else {
            "no peak: |X| falls with Ω for every Ω > 0"
        }
    };
    let peak = match (&candidates[..], first) {
        ([], Some(rises)) => {
            out.note = Some(monotone(rises).into());
            return Ok(out);
        }
        ([r], Some(true)) => r.clone(),
        ([_], Some(false)) if !undecided => {
            out.note = Some("no peak: |X| has a minimum and no maximum at Ω > 0".into());
            return Ok(out);
        }
        _ => {
            let list: Vec<String> = candidates.iter().map(Expr::to_unicode).collect();
            out.note = Some(format!(
                "|X| is stationary where {} = 0 (λ = Ω²){}: which is its peak is not decided",
                reduced.to_unicode(),
                if list.is_empty() {
                    String::new()
                } else {
                    format!(", at λ = {}", list.join(", "))
                }
            ));
            return Ok(out);
        }
    };
    if undecided {
        out.condition = Some(peak.clone());
    }
    let at_peak = |e: &Expr| e.subs(lv, &peak).map_err(math);
    let a_peak = at_peak(&n)?.div(&at_peak(&d)?).map_err(math)?;
    // |X|² = |X_peak|²/2: 2·N − |X_peak|²·D = 0
    let half = n.scale(&Q::from_i64(2)).sub(&a_peak.mul(&d));
    let hs = coefficients(&half, lv)?;
    match super::equilibrium::quadratic(&hs) {
        Some(roots) => {
            for (r, _) in roots {
                let above = r.sub(&peak);
                match (sign_of(&r, set), sign_of(&above, set)) {
                    (Some(Sign::Negative | Sign::Zero), _) => {}
                    (Some(Sign::Positive), Some(Sign::Negative)) => out.half_power.0 = Some(r),
                    (Some(Sign::Positive), Some(Sign::Positive)) => out.half_power.1 = Some(r),
                    _ => {
                        out.half_power = (None, None);
                        out.half_power_note = Some(
                            "half-power frequencies: where they lie about the peak is not decided"
                                .into(),
                        );
                        break;
                    }
                }
            }
        }
        None => {
            out.half_power_note = Some(
                "half-power frequencies: roots of an equation of degree > 2 in Ω², not computed"
                    .into(),
            );
        }
    }
    out.omega_squared = Some(peak);
    out.amplitude_squared = Some(a_peak);
    Ok(out)
}

/// The undamped natural frequencies ω_i at the values `set`, ascending:
/// the square roots of the positive ω² of K·v = ω²·M·v, or for a
/// gyroscopic system the ω of its eigenvalues s = ±i·ω. Why not, when
/// they cannot be computed (a missing value, M not definite).
pub fn natural_frequencies(sys: &ForcedSystem, set: &Values) -> Result<Vec<f64>, String> {
    if [&sys.mass, &sys.stiffness, &sys.damping]
        .iter()
        .any(|m| m.iter().flatten().any(|e| e.depends_on(atom::param(OMEGA))))
    {
        return Err("M, C or K depend on Ω: no natural frequencies".into());
    }
    if sys.gyroscopic() {
        let skew = matrix(sys.coordinates.len(), |i, j| {
            sys.damping[i][j]
                .sub(&sys.damping[j][i])
                .scale(&Q::new(1, 2).unwrap_or_else(Q::one))
        });
        let s = super::linear_stability::eigenvalues(&sys.mass, &skew, &sys.stiffness, set)?
            .ok_or("a parameter has no value")?;
        let scale = s.iter().fold(0.0f64, |a, z| a.max(z.norm()));
        let mut w: Vec<f64> = s
            .iter()
            .filter(|z| z.re.abs() <= 1e-9 * scale && z.im > 0.0)
            .map(|z| z.im)
            .collect();
        w.sort_by(f64::total_cmp);
        return Ok(w);
    }
    let numeric = super::oscillations::numeric_matrix;
    let (Some(k), Some(m)) = (numeric(&sys.stiffness, set), numeric(&sys.mass, set)) else {
        return Err("a parameter has no value".into());
    };
    let g = super::eigen::generalized_symmetric(&k, &m).map_err(|e| e.to_string())?;
    Ok(g.values
        .iter()
        .filter(|&&l| l > 0.0)
        .map(|l| l.sqrt())
        .collect())
}
