//! The kinetostatic equations at one position, Aᵀ·λ + Σ F·∂s/∂q = M·q̈ − f,
//! with Coulomb friction as the seed writes it: a slider's force
//! F = −μ·|N|·sgn v_rel (21.75), a pin's couple −μ₀·r₀·√(H² + V²)·sgn ω_rel
//! (21.74). With the senses of the normal forces N fixed, a slider's
//! friction is linear in the reactions, so the equations are solved in
//! each of the 2^k cases of the signs of the k normal forces, and the
//! solutions that agree with their case are kept: none, one or several,
//! each proved. A pin's |R| is then the root of a quadratic (one pin with
//! friction) or found by Newton's method (several, whose failure proves
//! nothing). Where a relative velocity vanishes (a stick) the friction
//! may be anywhere between its values for sliding either way, and the
//! reactions are given at both.

use super::model::Model;
use super::scale::Scales;
use super::table::JointKind;
use nalgebra::{DMatrix, DVector};

/// The most steps of Newton's method on the reactions of a mechanism's
/// pins with Coulomb friction at one position (sliders and a single pin
/// are solved exactly); past it the row says it did not converge.
pub const MAX_FRICTION_ITERATIONS: u32 = 200;

/// A relative velocity below this fraction of the mechanism's velocity
/// (in natural units: radians, or the mechanism's size, per unit time)
/// is rest: friction's sense is undefined there.
const STICK_FRACTION: f64 = 1e-9;
/// At most this many sliders with friction: 2^k sign cases.
const MAX_SLIDERS: usize = 12;
/// A normal force below this fraction of the position's loads (in
/// energy per natural unit) is zero: it agrees with either sign.
const ZERO_FORCE: f64 = 1e-12;
/// Two solutions closer than this fraction of the loads are one.
const SAME_SOLUTION: f64 = 1e-9;

/// The kinetostatics at one position.
pub(super) enum Kinetostatics {
    /// Every multiplier (by constraint) and every friction (by joint with
    /// friction); `iterations` linear systems (sign cases and Newton
    /// steps) solved.
    Solved {
        lambda: Vec<f64>,
        friction: Vec<f64>,
        iterations: u32,
    },
    /// One joint's relative velocity vanishes: the reactions with its
    /// relative velocity taken → 0⁻ and → 0⁺, and the note.
    Stick {
        joint: String,
        minus: (Vec<f64>, Vec<f64>),
        plus: (Vec<f64>, Vec<f64>),
        iterations: u32,
        note: String,
    },
    /// Why the position has no reactions.
    Refused(String),
}

/// One solve with every friction's sense given.
enum Solve {
    One(Vec<f64>, Vec<f64>, u32),
    Refused(String),
}

/// What the kinetostatics need of one position.
pub(super) struct Position<'a> {
    pub a: &'a DMatrix<f64>,
    pub motion: &'a [f64],
    pub qd: &'a [f64],
    pub qdd: &'a [f64],
    pub scales: &'a Scales,
}

/// Solve the kinetostatics at `at`: `motion` the motion program's
/// outputs at (q, q̇, t), `a` the constraint Jacobian.
pub(super) fn kinetostatics(model: &Model, at: &Position) -> Kinetostatics {
    let n = model.n;
    let lay = model.layout();
    let motion = at.motion;
    let mass = DMatrix::from_row_slice(n, n, &motion[lay.mass..lay.mass + n * n]);
    let f = DVector::from_column_slice(&motion[lay.forcing..lay.forcing + n]);
    let r = &mass * DVector::from_column_slice(at.qdd) - f;
    if model.frictions.is_empty() {
        let Some(lambda) = at.a.transpose().lu().solve(&r) else {
            return Kinetostatics::Refused("the kinetostatic equations are singular here".into());
        };
        return Kinetostatics::Solved {
            lambda: lambda.iter().copied().collect(),
            friction: Vec::new(),
            iterations: 0,
        };
    }
    // the mechanism's velocity in natural units per unit time
    let pace = at.scales.norm(at.qd);
    let mut senses = Vec::with_capacity(model.frictions.len());
    let mut stuck = Vec::new();
    for (i, fr) in model.frictions.iter().enumerate() {
        let v = motion[lay.relative + i];
        // a coefficient of 0 is no friction: no sense to find, even at rest
        if fr.coefficient == 0.0 {
            senses.push(0.0);
            continue;
        }
        let unit = match fr.kind {
            JointKind::Slider => at.scales.length,
            JointKind::Pin => 1.0,
        };
        if v.abs() <= STICK_FRACTION * unit * pace || pace == 0.0 {
            stuck.push((i, v));
            senses.push(0.0);
        } else {
            senses.push(v.signum());
        }
    }
    let solve = |senses: &[f64]| solve(model, at, &r, senses);
    match stuck[..] {
        [] => match solve(&senses) {
            Solve::One(lambda, friction, iterations) => Kinetostatics::Solved {
                lambda,
                friction,
                iterations,
            },
            Solve::Refused(why) => Kinetostatics::Refused(why),
        },
        [(i, v)] => {
            let joint = model.frictions[i].joint.clone();
            let side = |s: f64| {
                let mut senses = senses.clone();
                senses[i] = s;
                solve(&senses)
            };
            match (side(-1.0), side(1.0)) {
                (Solve::One(lm, fm, im), Solve::One(lp, fp, ip)) => Kinetostatics::Stick {
                    note: format!("stick: the relative velocity in the joint `{joint}` vanishes here ({v:.1e}), so its friction may be anywhere between its values for sliding either way: the reactions are given at both, the limits v → 0⁻ and v → 0⁺"),
                    joint,
                    minus: (lm, fm),
                    plus: (lp, fp),
                    iterations: im + ip,
                },
                (Solve::Refused(why), _) | (_, Solve::Refused(why)) => Kinetostatics::Refused(
                    format!("stick: the relative velocity in the joint `{joint}` vanishes here ({v:.1e}), and sliding either way: {why}"),
                ),
            }
        }
        _ => {
            let names: Vec<String> = stuck
                .iter()
                .map(|&(i, _)| format!("`{}`", model.frictions[i].joint))
                .collect();
            Kinetostatics::Refused(format!(
                "stick: the relative velocities in the joints {} vanish here together, so their frictions' senses are undefined",
                names.join(" and ")
            ))
        }
    }
}

/// A solution in the sign case of the sliders' normal forces.
struct Candidate {
    lambda: DVector<f64>,
    friction: Vec<f64>,
}

/// The kinetostatics with every friction's sense given (0: no friction):
/// every sign case of the sliders' normal forces.
fn solve(model: &Model, at: &Position, r: &DVector<f64>, senses: &[f64]) -> Solve {
    let n = model.n;
    let lay = model.layout();
    let direction = |i: usize| &at.motion[lay.direction + i * n..lay.direction + (i + 1) * n];
    let sliders: Vec<usize> = (0..model.frictions.len())
        .filter(|&i| senses[i] != 0.0 && model.frictions[i].kind == JointKind::Slider)
        .collect();
    let pins: Vec<usize> = (0..model.frictions.len())
        .filter(|&i| senses[i] != 0.0 && model.frictions[i].kind == JointKind::Pin)
        .collect();
    if sliders.len() > MAX_SLIDERS {
        return Solve::Refused(format!(
            "{} sliders with friction: the reactions are solved for at most {MAX_SLIDERS} (2^k cases of their normal forces' signs)",
            sliders.len()
        ));
    }
    // loads in energy per natural unit: the scale of "zero" and "the same"
    let rows = at.scales.rows(at.a);
    let at_t = at.a.transpose();
    let mut energy = (0..n).fold(0.0f64, |m, j| m.max((r[j] * at.scales.coordinate[j]).abs()));
    let mut candidates: Vec<Candidate> = Vec::new();
    let mut iterations = 0u32;
    // a case not solved: the count of solutions is then not proved
    let mut failure: Option<String> = None;
    let mut newton = false;
    for case in 0..1usize << sliders.len() {
        let sign = |k: usize| if case >> k & 1 == 0 { 1.0 } else { -1.0 };
        // Aᵀ·λ + Σ F_i·d_i = r with F_i = −μ·s_i·σ_i·N_i, N_i = λ[row_i]
        let mut k = at_t.clone();
        for (c, &i) in sliders.iter().enumerate() {
            let fr = &model.frictions[i];
            let coefficient = -fr.coefficient * senses[i] * sign(c);
            for (row, d) in direction(i).iter().enumerate() {
                k[(row, fr.rows[0])] += coefficient * d;
            }
        }
        iterations += 1;
        let lu = k.lu();
        let Some(base) = lu.solve(r) else {
            failure = Some("the friction equations are singular in one case of the normal forces' signs (the friction may lock the mechanism here)".into());
            continue;
        };
        // a pin's couple −μ₀·r₀·s·ρ moved to the right: λ = base + Σ ρ_p·w_p
        let mut w = Vec::with_capacity(pins.len());
        for &p in &pins {
            let fr = &model.frictions[p];
            let rhs = DVector::from_iterator(
                n,
                direction(p).iter().map(|d| fr.coefficient * senses[p] * d),
            );
            match lu.solve(&rhs) {
                Some(x) => w.push(x),
                None => {
                    return Solve::Refused("the kinetostatic equations are singular here".into())
                }
            }
        }
        let magnitudes = match pins.len() {
            0 => vec![Vec::new()],
            1 => one_pin(&base, &w[0], &model.frictions[pins[0]].rows),
            _ => match several_pins(model, &pins, &base, &w) {
                Ok((rho, steps)) => {
                    iterations += steps;
                    newton = true;
                    vec![rho]
                }
                Err(why) => {
                    failure = Some(why);
                    Vec::new()
                }
            },
        };
        for rho in magnitudes {
            let mut lambda = base.clone();
            for (x, &m) in w.iter().zip(&rho) {
                lambda += x * m;
            }
            energy = energy.max((0..n).fold(0.0f64, |m, j| m.max((lambda[j] * rows[j]).abs())));
            let agrees = sliders.iter().enumerate().all(|(c, &i)| {
                let row = model.frictions[i].rows[0];
                sign(c) * lambda[row] * rows[row] >= -ZERO_FORCE * energy
            });
            if !agrees {
                continue;
            }
            let friction = (0..model.frictions.len())
                .map(|i| {
                    let fr = &model.frictions[i];
                    let normal = match fr.kind {
                        JointKind::Slider => lambda[fr.rows[0]].abs(),
                        JointKind::Pin => lambda[fr.rows[0]].hypot(lambda[fr.rows[1]]),
                    };
                    -fr.coefficient * normal * senses[i]
                })
                .collect();
            candidates.push(Candidate { lambda, friction });
        }
    }
    // the same solution found in two cases (a normal force of zero) is one
    let mut distinct: Vec<Candidate> = Vec::new();
    for c in candidates {
        let same = distinct.iter().any(|d| {
            (0..n).all(|j| ((d.lambda[j] - c.lambda[j]) * rows[j]).abs() <= SAME_SOLUTION * energy)
        });
        if !same {
            distinct.push(c);
        }
    }
    let cases = 1usize << sliders.len();
    if let Some(why) = failure {
        return Solve::Refused(why);
    }
    match distinct.len() {
        1 => {
            let c = distinct.remove(0);
            Solve::One(c.lambda.iter().copied().collect(), c.friction, iterations)
        }
        0 if newton => Solve::Refused("the friction equations were not solved here: Newton's method on the pins' reactions found no solution that agrees with the normal forces' signs, which does not prove there is none".into()),
        0 if sliders.is_empty() => Solve::Refused("the friction equations have no solution here: no magnitude of the pin's reaction agrees with the friction couple it makes (friction this large locks the mechanism)".into()),
        0 => Solve::Refused(format!(
            "the friction equations have no solution here: in none of the {cases} cases of the normal forces' signs do the reactions agree with their case (friction this large locks the mechanism)"
        )),
        k if sliders.is_empty() => Solve::Refused(format!(
            "the friction equations have {k} solutions here ({k} magnitudes of the pin's reaction agree with the friction couple it makes), so the reactions are not determined"
        )),
        k => Solve::Refused(format!(
            "the friction equations have {k} solutions here (in the {cases} cases of the normal forces' signs), so the reactions are not determined"
        )),
    }
}

/// The magnitudes ρ ≥ 0 of the pin's reaction R = a + ρ·b with |R| = ρ:
/// the roots of (|b|² − 1)·ρ² + 2(a·b)·ρ + |a|² = 0.
fn one_pin(base: &DVector<f64>, w: &DVector<f64>, rows: &[usize]) -> Vec<Vec<f64>> {
    let a = [base[rows[0]], base[rows[1]]];
    let b = [w[rows[0]], w[rows[1]]];
    let qa = b[0] * b[0] + b[1] * b[1] - 1.0;
    let qb = 2.0 * (a[0] * b[0] + a[1] * b[1]);
    let qc = a[0] * a[0] + a[1] * a[1];
    let mut roots = Vec::new();
    if qa.abs() <= 1e-12 * (1.0 + b[0] * b[0] + b[1] * b[1]) {
        if qb != 0.0 {
            roots.push(-qc / qb);
        } else if qc == 0.0 {
            roots.push(0.0);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            // the root without cancellation, then the other from the product
            let big = -(qb + qb.signum() * disc.sqrt()) / 2.0;
            if big != 0.0 {
                roots.push(big / qa);
                roots.push(qc / big);
            } else {
                roots.push(0.0);
            }
        }
    }
    let mut out: Vec<Vec<f64>> = Vec::new();
    for rho in roots {
        // |a + ρ·b| = ρ needs ρ ≥ 0; −0 from rounding is 0
        let rho = if rho < 0.0 && rho >= -1e-12 * qc.sqrt() {
            0.0
        } else {
            rho
        };
        if rho >= 0.0 && rho.is_finite() && !out.iter().any(|r| r[0] == rho) {
            out.push(vec![rho]);
        }
    }
    out
}

/// The pins' magnitudes ρ with |R_p(base + Σ ρ_q·w_q)| = ρ_p by Newton's
/// method from the reactions without friction, and its steps.
fn several_pins(
    model: &Model,
    pins: &[usize],
    base: &DVector<f64>,
    w: &[DVector<f64>],
) -> Result<(Vec<f64>, u32), String> {
    let k = pins.len();
    let reaction = |rho: &[f64], p: usize| {
        let rows = &model.frictions[pins[p]].rows;
        let mut r = [base[rows[0]], base[rows[1]]];
        for (q, x) in w.iter().enumerate() {
            r[0] += rho[q] * x[rows[0]];
            r[1] += rho[q] * x[rows[1]];
        }
        r
    };
    let mut rho: Vec<f64> = (0..k)
        .map(|p| {
            let r = reaction(&vec![0.0; k], p);
            r[0].hypot(r[1])
        })
        .collect();
    for step in 1..=MAX_FRICTION_ITERATIONS {
        let mut h = DVector::zeros(k);
        let mut jac = DMatrix::zeros(k, k);
        for p in 0..k {
            let r = reaction(&rho, p);
            let norm = r[0].hypot(r[1]);
            h[p] = norm - rho[p];
            let rows = &model.frictions[pins[p]].rows;
            for q in 0..k {
                let d = if norm > 0.0 {
                    (r[0] * w[q][rows[0]] + r[1] * w[q][rows[1]]) / norm
                } else {
                    0.0
                };
                jac[(p, q)] = d - if p == q { 1.0 } else { 0.0 };
            }
        }
        let Some(dx) = jac.lu().solve(&(-&h)) else {
            break;
        };
        for (x, d) in rho.iter_mut().zip(dx.iter()) {
            *x += d;
        }
        let top = rho.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if dx.amax() <= 1e-13 * top || top == 0.0 {
            if rho.iter().all(|&x| x >= 0.0) {
                return Ok((rho, step));
            }
            break;
        }
    }
    Err(format!(
        "the friction equations were not solved here: Newton's method on the pins' reactions did not converge in {MAX_FRICTION_ITERATIONS} steps, so the reactions may have no solution or several"
    ))
}
