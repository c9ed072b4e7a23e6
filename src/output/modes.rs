//! The readable text of `modes`: matrices, standard form, characteristic
//! equation, frequencies and modes, responses.

use super::text::matrix_text;
use super::{as_unicode, minus};
use crate::expr::print::{self, pretty_name};
use crate::expr::Expr;
use crate::solve::equilibrium::Values;
use crate::solve::oscillations::{self as osc, Modes, StandardForm};

/// The text of `qdot modes`.
pub fn modes_text(
    md: &Modes,
    set: &Values,
    free: Option<&[Expr]>,
    numeric: Option<&osc::NumericFree>,
) -> String {
    let names: Vec<String> = md.coordinates.iter().map(|c| pretty_name(c, 0)).collect();
    let standard = osc::standard_form(md, set);
    let mut out = linearized_text(md, &names);
    if let Some(sf) = &standard {
        out.push_str(&standard_form_text(&md.coordinates[0], sf, set));
    }
    out.push_str(&characteristic_text(md));
    out.push_str(&frequencies_text(md, set));
    out.push_str(&general_solution_text(md, &names, set));
    out.push_str(&stability_text(md));
    if let Some(free) = free {
        out.push_str(&free_response_text(md, &names, free));
    }
    if let Some(nf) = numeric {
        out.push_str(
            "\nFree response (undamped) from the initial conditions, numeric (10 significant digits, from the eigen-solver at the --set values)\n",
        );
        for (j, c) in names.iter().enumerate() {
            out.push_str(&format!("  {c}(t) = {}\n", numeric_response(nf, j, true)));
        }
    }
    out.push_str(&steady_state_text(md, &names, standard.as_ref()));
    out
}

/// The point of linearization and M, C, K, f(t).
fn linearized_text(md: &Modes, names: &[String]) -> String {
    let at: Vec<String> = names
        .iter()
        .zip(&md.at)
        .map(|(c, v)| format!("{c} = {}", as_unicode(v)))
        .collect();
    let mut out = match &md.steady {
        Some(sm) => steady_motion_text(sm, &at),
        None => format!(
            "Linearized about {}   M·q̈ + C·q̇ + K·q = f(t)\n",
            at.join(", ")
        ),
    };
    if !md.dependent.is_empty() {
        let held: Vec<String> = md
            .dependent
            .iter()
            .map(|(c, v)| format!("{} = {}", pretty_name(c, 0), as_unicode(v)))
            .collect();
        out.push_str(&format!(
            "  (on the constraints: {} there, dependent on {})\n",
            held.join(", "),
            names.join(", ")
        ));
    }
    matrix_text(&mut out, "Mass matrix M", &md.mass);
    if is_damped(md) {
        matrix_text(&mut out, "Damping matrix C", &md.damping);
    }
    matrix_text(&mut out, "Stiffness matrix K", &md.stiffness);
    if md.forcing.iter().any(|e| !e.is_zero()) {
        out.push_str("Forcing f(t)\n");
        for (c, f) in names.iter().zip(&md.forcing) {
            out.push_str(&format!("  {c}  {}\n", as_unicode(f)));
        }
    }
    out
}

/// The steady motion: its rates, the conditions that hold it, the rates
/// solved from them, and the Routh reduction the matrices come from.
fn steady_motion_text(sm: &osc::SteadyMotion, at: &[String]) -> String {
    let rates: Vec<String> = sm
        .rates
        .iter()
        .map(|(c, r)| {
            let rate = pretty_name(c, 1);
            if *r == crate::solve::steady::rate_symbol(c) {
                format!("{rate} = const")
            } else {
                format!("{rate} = {}", as_unicode(r))
            }
        })
        .collect();
    let mut out = format!("Steady motion  {}, {}\n", rates.join(", "), at.join(", "));
    for (c, f) in &sm.conditions {
        out.push_str(&format!(
            "  the equation of {} there: {} = 0\n",
            pretty_name(c, 0),
            as_unicode(f)
        ));
    }
    for (c, f) in &sm.held {
        out.push_str(&format!(
            "  the equation of {} there: {} = 0, which holds at the --set values\n",
            pretty_name(c, 0),
            as_unicode(f)
        ));
    }
    for s in &sm.solved {
        let rate = pretty_name(&s.coordinate, 1);
        let power = if s.squared { "²" } else { "" };
        out.push_str(&format!("  so {rate}{power} = {}", as_unicode(&s.value)));
        for o in &s.others {
            out.push_str(&format!(" or {rate}{power} = {}", as_unicode(o)));
        }
        if !s.others.is_empty() {
            out.push_str(&format!(
                "; below about the first (for another, add {}'=… to --at)",
                s.coordinate
            ));
        }
        out.push('\n');
    }
    let held: Vec<String> = sm
        .rates
        .iter()
        .map(|(c, _)| format!("p_{}", pretty_name(c, 0)))
        .collect();
    out.push_str(&format!(
        "Linearized about it, {} held (Routh's reduction)   M·q̈ + C·q̇ + K·q = f(t)\n",
        held.join(", ")
    ));
    out
}

fn is_damped(md: &Modes) -> bool {
    md.damping.iter().flatten().any(|e| !e.is_zero())
}

/// One coordinate: ÿ + 2α·ẏ + ω²·y = f(t)/M, ω, α, ζ and the regime.
fn standard_form_text(q: &str, sf: &StandardForm, set: &Values) -> String {
    let mut out = String::from("\nStandard form  ÿ + 2α·ẏ + ω²·y = f(t)/M\n");
    let mut lhs = pretty_name(q, 2);
    if !sf.alpha.is_zero() {
        lhs.push_str(&format!(
            " + {}·{}",
            paren_str(&expanded(&sf.alpha.scale(&crate::num::Q::from_i64(2)))),
            pretty_name(q, 1)
        ));
    }
    if !sf.omega_squared.is_zero() {
        lhs.push_str(&format!(
            " + {}·{}",
            paren_str(&expanded(&sf.omega_squared)),
            pretty_name(q, 0)
        ));
    }
    out.push_str(&format!("  {lhs} = {}\n", as_unicode(&sf.forcing)));
    out.push_str(&format!("  ω² = {}\n", expanded(&sf.omega_squared)));
    let zero = crate::algebra::sign::sign_of(&sf.omega_squared, set)
        == Some(crate::algebra::sign::Sign::Zero);
    if zero {
        // no restoring force: the free motion drifts, it does not oscillate
        let free = if sf.alpha.is_zero() {
            "y = a + b·t"
        } else {
            "y = a + b·e^(−2α·t)"
        };
        out.push_str(&format!(
            "  ω = 0: no restoring force, the free motion does not oscillate: {free}\n"
        ));
        if !sf.alpha.is_zero() {
            out.push_str(&format!("  α = {}\n", expanded(&sf.alpha)));
        }
        out.push_str(&format!("  regime: {}\n", sf.regime));
        return out;
    }
    let ws = match &sf.omega {
        Some(w) => as_unicode(w),
        None => format!("√({})", expanded(&sf.omega_squared)),
    };
    out.push_str(&format!("  ω = {ws}   T = 2π/ω   f = ω/(2π)\n"));
    if let Some(n) = super::at_values::frequency("", &sf.omega_squared, set) {
        out.push_str(&format!("      {n}\n"));
    }
    if !sf.alpha.is_zero() {
        out.push_str(&format!("  α = {}", expanded(&sf.alpha)));
        match (&sf.zeta, &sf.omega) {
            (Some(z), Some(_)) => out.push_str(&format!("   ζ = α/ω = {}", as_unicode(z))),
            _ => out.push_str("   ζ = α/ω"),
        }
        out.push('\n');
        let alpha = super::at_values::evaluate(&sf.alpha, set);
        let zeta = sf
            .zeta
            .as_ref()
            .and_then(|z| super::at_values::evaluate(z, set));
        match (alpha, zeta) {
            (Some(a), Some(z)) => {
                out.push_str(&format!("      α = {} 1/s, ζ = {}\n", a.text(), z.text()))
            }
            (Some(a), None) => out.push_str(&format!("      α = {} 1/s\n", a.text())),
            _ => {}
        }
    }
    out.push_str(&format!("  regime: {}\n", sf.regime));
    out
}

/// det(K − λ·M) = 0, factored, constant factors left out.
fn characteristic_text(md: &Modes) -> String {
    let mut out = String::from(if md.gyroscopic {
        "\nCharacteristic equation  det(K + s·C + s²·M) = 0,  s = i·ω,  λ = ω² = −s²\n"
    } else {
        "\nCharacteristic equation  det(K − λ·M) = 0,  λ = ω²\n"
    });
    let lv = crate::expr::atom::unknown(osc::LAMBDA);
    // the equation is "= 0": constant factors are left out
    let mut shown: Vec<&Expr> = md.factors.iter().filter(|f| f.depends_on(lv)).collect();
    // the factorization's order follows the atoms' interning order; the
    // printed one must not: by degree, monomials first, then by text
    shown.sort_by_cached_key(|f| (f.num().degree(lv), f.num().len() > 1, lambda_poly(f)));
    let factors: Vec<String> = shown
        .iter()
        .map(|f| {
            let s = lambda_poly(f);
            if shown.len() > 1 && (s.contains(" + ") || s.contains(" − ")) {
                format!("({s})")
            } else {
                s
            }
        })
        .collect();
    if factors.is_empty() {
        out.push_str(&format!("  {} = 0\n", lambda_poly(&md.characteristic)));
    } else {
        out.push_str(&format!("  {} = 0\n", factors.join("·")));
    }
    out
}

/// ωᵢ² with their modes, then the numeric eigen-solution under `--set`.
fn frequencies_text(md: &Modes, set: &Values) -> String {
    let mut out = String::new();
    if md.omega_squared.is_empty() {
        let why = md.no_closed_form.as_deref().unwrap_or("no closed form");
        if why.starts_with("no closed form") {
            out.push_str(&format!("  ({why})\n"));
        } else {
            out.push_str(&format!("  (no closed form for its roots: {why})\n"));
        }
    } else if md.gyroscopic || md.defective {
        out.push_str(if md.gyroscopic {
            "\nNatural frequencies  (gyroscopic: the modes are complex, their coordinates move out of phase; not given)\n"
        } else {
            "\nNatural frequencies  (a repeated ω² has fewer modes than its multiplicity, the mass matrix not being definite; not given)\n"
        });
        for (i, w2) in md.omega_squared.iter().enumerate() {
            out.push_str(&format!(
                "  ω{}² = {}\n",
                print::subscript(&(i + 1).to_string()),
                expanded(w2)
            ));
        }
    } else {
        out.push_str(
            "\nNatural frequencies and modes  (distribution coefficients μ_j = x_j/x_1)\n",
        );
        for (i, (w2, mode)) in md.omega_squared.iter().zip(&md.modes).enumerate() {
            let m: Vec<String> = mode.iter().map(as_unicode).collect();
            let sub = print::subscript(&(i + 1).to_string());
            out.push_str(&format!(
                "  ω{sub}² = {}    mode ({})\n",
                expanded(w2),
                m.join(", ")
            ));
            if let Some(n) = super::at_values::frequency(&sub, w2, set) {
                out.push_str(&format!("      {n}\n"));
            }
        }
    }
    let numeric = osc::numeric_modes_or_why(md, set);
    if let Err(why) = &numeric {
        out.push_str(&format!("  numeric ω²: none at these values: {why}\n"));
    }
    if let Ok(Some(g)) = numeric {
        // a zero ω² is computed as ±ε·max|ω²|: shown as 0, not −0
        let biggest = g.values.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let v: Vec<String> = g
            .values
            .iter()
            .map(|&x| if x.abs() <= 1e-11 * biggest { 0.0 } else { x })
            .map(|x| minus(format!("{x:.10}")))
            .collect();
        if md.gyroscopic {
            out.push_str(&format!(
                "  numeric ω² (eigenvalues s = ±i·ω of the first-order system): {}\n",
                v.join(", ")
            ));
            return out;
        }
        out.push_str(&format!("  numeric ω² (eigen-solver): {}\n", v.join(", ")));
        out.push_str("  mass-normalized modes (numeric, vᵀ·M·v = 1):\n");
        for v in &g.vectors {
            let c: Vec<String> = v.iter().map(|x| minus(format!("{x:.8}"))).collect();
            out.push_str(&format!("    ({})\n", c.join(", ")));
        }
    }
    out
}

/// q(t) = Σ Cᵢ·uᵢ·cos(ωᵢ·t + φᵢ), when every frequency is in closed form;
/// a zero frequency's mode drifts, (Aᵢ + Bᵢ·t)·uᵢ, and a negative ω²'s
/// grows, (Aᵢ·e^(κᵢ·t) + Bᵢ·e^(−κᵢ·t))·uᵢ.
fn general_solution_text(md: &Modes, names: &[String], set: &Values) -> String {
    if md.gyroscopic
        || md.defective
        || md.omega_squared.is_empty()
        || md.omega_squared.len() != md.coordinates.len()
    {
        return String::new();
    }
    use crate::algebra::sign::{sign_of, Sign};
    // each mode's motion: a drift at ω² = 0, a growth where ω² < 0 (at
    // the --set values when given: ω² = 16/81·k/m − g/(9·r) can be 0 there)
    let kinds: Vec<Option<Sign>> = md.omega_squared.iter().map(|w| sign_of(w, set)).collect();
    let mut out = String::from("\nGeneral solution (undamped)  q(t) = Σ Cᵢ·uᵢ·cos(ωᵢ·t + φᵢ)");
    if kinds.contains(&Some(Sign::Zero)) {
        out.push_str(", and (Aᵢ + Bᵢ·t)·uᵢ where ωᵢ = 0");
    }
    if kinds.contains(&Some(Sign::Negative)) {
        out.push_str(", and (Aᵢ·e^(κᵢ·t) + Bᵢ·e^(−κᵢ·t))·uᵢ with κᵢ² = −ωᵢ² where ωᵢ² < 0");
    }
    if kinds.contains(&None) {
        out.push_str(" (the cosine where ωᵢ² > 0)");
    }
    out.push('\n');
    for (j, c) in names.iter().enumerate() {
        let mut terms = Vec::new();
        for (i, mode) in md.modes.iter().enumerate() {
            let mu = &mode[j];
            if mu.is_zero() {
                continue;
            }
            let i1 = print::subscript(&(i + 1).to_string());
            let (wave, bare) = match kinds[i] {
                Some(Sign::Zero) => (format!("(A{i1} + B{i1}·t)"), format!("A{i1} + B{i1}·t")),
                Some(Sign::Negative) => {
                    let w = format!("A{i1}·e^(κ{i1}·t) + B{i1}·e^(−κ{i1}·t)");
                    (format!("({w})"), w)
                }
                _ => {
                    let w = format!("C{i1}·cos(ω{i1}·t + φ{i1})");
                    (w.clone(), w)
                }
            };
            let (neg, body) = signed_coefficient(&as_unicode(mu));
            terms.push((
                neg,
                match body.as_str() {
                    // added with coefficient 1, a sum needs no parentheses
                    "1" if !neg => bare,
                    "1" => wave,
                    _ => format!("{body}·{wave}"),
                },
            ));
        }
        let line = print::join_terms(terms.into_iter(), print::Style::Unicode);
        out.push_str(&format!("  {c} = {line}\n"));
    }
    out
}

fn stability_text(md: &Modes) -> String {
    let about = if md.steady.is_some() {
        "the steady motion"
    } else {
        "the equilibrium"
    };
    let mut out = format!("\nStability of {about}: {}", md.stability.word());
    if let osc::Stability::Undecided(why) = &md.stability {
        out.push_str(&format!(" ({why})"));
    }
    out.push('\n');
    if md.coordinates.len() > 1 && is_damped(md) && !md.gyroscopic {
        out.push_str("  (the modes are those of the undamped system)\n");
    }
    out
}

/// q(t) from `--init`, and for one coordinate the seed's A·sin(ω·t + φ).
fn free_response_text(md: &Modes, names: &[String], free: &[Expr]) -> String {
    let mut out = String::from("\nFree response (undamped) from the initial conditions\n");
    for (c, q) in names.iter().zip(free) {
        out.push_str(&format!("  {c}(t) = {}\n", as_unicode(q)));
    }
    if let Some((a, phi)) = osc::free_amplitude_phase(md, free) {
        out.push_str(&format!(
            "  = A·sin(ω·t + φ),  A = √(y₀² + (v₀/ω)²) = {},  φ = atan(y₀·ω/v₀) = {}\n",
            as_unicode(&a),
            as_unicode(&phi)
        ));
    }
    out
}

/// The steady state under a harmonic load: damped (one coordinate) or
/// undamped amplitudes.
fn steady_state_text(md: &Modes, names: &[String], standard: Option<&StandardForm>) -> String {
    let mut out = String::new();
    if let Some(sf) = standard.filter(|sf| !sf.alpha.is_zero()) {
        if let Some((p, _, tan_psi)) = osc::damped_steady_state(md, sf) {
            // X is exact in the JSON; the formula reads better here
            out.push_str(&format!(
                "\nSteady state under F·cos(p·t), p = {}:  y = X·cos(p·t − ψ)\n  X = (F/M)/√((ω² − p²)² + 4α²p²),  F/M = {}\n  tan ψ = 2αp/(ω² − p²) = {}\n",
                as_unicode(&p),
                osc::load_per_mass(md).map(|a| as_unicode(&a)).unwrap_or_default(),
                as_unicode(&tan_psi)
            ));
        }
    }
    if let Some((p, x)) = osc::forced_amplitudes(md) {
        if !is_damped(md) {
            out.push_str(&format!(
                "\nSteady state under f = F·cos(p·t), p = {}  (undamped amplitudes; resonance at p² = ωᵢ²)\n",
                as_unicode(&p)
            ));
            for (c, a) in names.iter().zip(&x) {
                out.push_str(&format!("  {c}: {}·cos(p·t)\n", paren(a)));
            }
        }
    }
    out
}

fn expanded(e: &Expr) -> String {
    print::expanded(e)
}

/// A polynomial in λ in ascending powers: k − 6·m·λ, 2·k² − 4·k·m·λ + m²·λ².
fn lambda_poly(f: &Expr) -> String {
    let lv = crate::expr::atom::unknown(crate::solve::oscillations::LAMBDA);
    if !f.den().is_one() || !f.num().contains_var(lv) {
        return as_unicode(f);
    }
    let mut terms = Vec::new();
    for (i, c) in f.num().coeffs_in(lv).into_iter().enumerate() {
        if c.is_zero() {
            continue;
        }
        let (neg, cs) = signed_coefficient(&expanded(&Expr::from_poly(c)));
        let pow = match i {
            0 => String::new(),
            1 => "λ".to_string(),
            k => format!("λ{}", print::superscript(k as u32)),
        };
        let term = match (i, cs.as_str()) {
            (0, _) => cs.clone(),
            (_, "1") => pow,
            _ => format!("{cs}·{pow}"),
        };
        terms.push((neg, term));
    }
    print::join_terms(terms.into_iter(), print::Style::Unicode)
}

/// A printed coefficient as (sign outside, body): `−a` → (true, `a`), a
/// sum → (false, `(a − b)`), else (false, itself).
fn signed_coefficient(s: &str) -> (bool, String) {
    if s.contains(" + ") || s.contains(" − ") {
        return (false, format!("({s})"));
    }
    match s.strip_prefix('−') {
        Some(r) => (true, r.to_string()),
        None => (false, s.to_string()),
    }
}

fn paren(e: &Expr) -> String {
    paren_str(&as_unicode(e))
}

fn paren_str(s: &str) -> String {
    if s.contains(" + ") || s.contains(" − ") || s.starts_with('−') {
        format!("({s})")
    } else {
        s.to_string()
    }
}

/// Coordinate `j` of a numeric free response with 10 significant digits:
/// `c·cos(r·t) + d·sin(r·t)`, growth as `exp(±r·t)`, drift as `c + d·t`.
/// `unicode`: `·` and `−` for the text, else qdot's input syntax.
pub(super) fn numeric_response(nf: &osc::NumericFree, j: usize, unicode: bool) -> String {
    let dot = if unicode { "·" } else { "*" };
    let neg = if unicode { "−" } else { "-" };
    let t = |r: f64| format!("{}{dot}t", significant(r));
    let mut terms: Vec<(bool, String)> = Vec::new();
    let mut push = |c: f64, wave: String| {
        if c == 0.0 {
            return;
        }
        let body = if wave.is_empty() {
            significant(c)
        } else {
            format!("{}{dot}{wave}", significant(c))
        };
        terms.push((c < 0.0, body));
    };
    for (motion, r, c, d) in nf.terms(j) {
        match motion {
            osc::Motion::Oscillates => {
                push(c, format!("cos({})", t(r)));
                push(d, format!("sin({})", t(r)));
            }
            // c·cosh + d·sinh = (c + d)/2·exp(r·t) + (c − d)/2·exp(−r·t)
            osc::Motion::Grows => {
                push((c + d) / 2.0, format!("exp({})", t(r)));
                push((c - d) / 2.0, format!("exp({neg}{})", t(r)));
            }
            osc::Motion::Drifts => {
                push(c, String::new());
                push(d, "t".into());
            }
        }
    }
    let mut out = String::new();
    for (i, (negative, body)) in terms.iter().enumerate() {
        match (i, negative) {
            (0, true) => out.push_str(&format!("{neg}{body}")),
            (0, false) => out.push_str(body),
            (_, true) => out.push_str(&format!(" {neg} {body}")),
            (_, false) => out.push_str(&format!(" + {body}")),
        }
    }
    if out.is_empty() {
        out.push('0');
    }
    out
}

/// |x| in decimal notation with 10 significant digits, trailing zeros
/// dropped.
fn significant(x: f64) -> String {
    let e = format!("{:.9e}", x.abs());
    let Some((mantissa, exp)) = e.split_once('e') else {
        return e;
    };
    let exp: i32 = exp.parse().unwrap_or(0);
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let (int, frac) = if exp >= 0 {
        let k = exp as usize + 1;
        if k >= digits.len() {
            (
                format!("{digits}{}", "0".repeat(k - digits.len())),
                String::new(),
            )
        } else {
            (digits[..k].to_string(), digits[k..].to_string())
        }
    } else {
        let zeros = "0".repeat((-exp - 1) as usize);
        ("0".to_string(), format!("{zeros}{digits}"))
    };
    let frac = frac.trim_end_matches('0');
    if frac.is_empty() {
        int
    } else {
        format!("{int}.{frac}")
    }
}
