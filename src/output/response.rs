//! `qdot response FILE` without `--over`: the exact frequency response
//! ([`crate::solve::response`]) as text or JSON.

use super::{as_input, as_unicode};
use crate::algebra::sign::Values;
use crate::app::Context;
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::scene::Scene;
use crate::solve::oscillations as osc;
use crate::solve::response::{self, ForcedSystem, LoadPeak, Peak, Response, SingleDof};
use serde::Serialize;

/// The exact response of the scene `src` about `at` (`--at th=pi`, default
/// every q = 0), signs decided with `set`, written as `json` or text; the
/// work budget is `max_terms`.
pub fn response_output(
    src: &str,
    at: Option<&str>,
    set: &Values,
    max_terms: usize,
    json: bool,
) -> Result<String, Diagnostic> {
    let scene = Scene::parse(src)?;
    response::check_time_dependence(&scene)?;
    crate::scene::given::parameter_signs(&scene, set)?;
    crate::scene::given::set_names_are_parameters(&scene, set)?;
    let ctx = Context::new().with_max_terms(max_terms).for_scene(&scene);
    ctx.run(|| {
        let at = at.map(|a| scene.coordinate_values(a)).transpose()?;
        let md = osc::modes(&scene, at.as_deref(), set)?;
        let r = response::response(ForcedSystem::from_modes(&md)?, set)?;
        Ok(if json {
            super::wire::json_string(&ResponseJson::new(&md, &r))
        } else {
            text(&md, &r)
        })
    })
}

fn paren(e: &Expr) -> String {
    let s = as_unicode(e);
    if s.contains(" + ") || s.contains(" − ") || s.starts_with('−') {
        format!("({s})")
    } else {
        s
    }
}

/// The exact response for reading.
pub fn text(md: &osc::Modes, r: &Response) -> String {
    let sys = &r.system;
    let pretty = |q: &str| crate::expr::print::pretty_name(q, 0);
    let mut out = format!(
        "Harmonic load at the frequency Ω (the scene's {} replaced by Ω)\n",
        as_unicode(&sys.frequency)
    );
    for (j, q) in sys.coordinates.iter().enumerate() {
        let mut parts = Vec::new();
        if !sys.load_cos[j].is_zero() {
            parts.push(format!("{}·cos(Ω·t)", paren(&sys.load_cos[j])));
        }
        if !sys.load_sin[j].is_zero() {
            parts.push(format!("{}·sin(Ω·t)", paren(&sys.load_sin[j])));
        }
        let load = if parts.is_empty() {
            "0".to_string()
        } else {
            parts.join(" + ")
        };
        out.push_str(&format!("  f_{} = {load}\n", pretty(q)));
    }
    if !md.omega_squared.is_empty() {
        let list: Vec<String> = md.omega_squared.iter().map(as_unicode).collect();
        out.push_str(&format!(
            "  undamped natural frequencies: ω² = {}\n",
            list.join(", ")
        ));
    }
    out.push_str("\nReceptance X = (K − Ω²·M + i·Ω·C)⁻¹·F,  q(t) = |X|·cos(Ω·t − φ)\n");
    for (j, q) in sys.coordinates.iter().enumerate() {
        let q = pretty(q);
        out.push_str(&format!("  {q}:  Re X = {}\n", as_unicode(&r.real[j])));
        out.push_str(&format!("      Im X = {}\n", as_unicode(&r.imag[j])));
        out.push_str(&format!(
            "      |X|² = {}\n",
            as_unicode(&r.amplitude_squared[j])
        ));
        match &r.tan_phase[j] {
            Some(t) => out.push_str(&format!("      tan φ = {}\n", as_unicode(t))),
            None if r.amplitude_squared[j].is_zero() => {}
            None => out.push_str("      φ = ±π/2 (Re X = 0)\n"),
        }
    }
    out.push_str(&antiresonance_text(r));
    if let Some(s) = &r.single {
        out.push_str(&single_text(s));
    }
    out
}

fn antiresonance_text(r: &Response) -> String {
    let sys = &r.system;
    let pretty = |q: &str| crate::expr::print::pretty_name(q, 0);
    let mut out = String::from("\nAntiresonances (undamped: X = 0)\n");
    if let Some(why) = &r.antiresonance_note {
        out.push_str(&format!("  {why}\n"));
        return out;
    }
    for (q, roots) in sys.coordinates.iter().zip(&r.antiresonances) {
        let list = if roots.is_empty() {
            "none".to_string()
        } else {
            roots
                .iter()
                .map(|w| format!("Ω² = {}", as_unicode(w)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        out.push_str(&format!("  {}: {list}\n", pretty(q)));
    }
    out
}

fn single_text(s: &SingleDof) -> String {
    let mut out =
        String::from("\nOne degree of freedom  (ω₀² = K/M, α = C/(2M), ζ = α/ω₀, r = Ω/ω₀)\n");
    out.push_str(&format!(
        "  ω₀² = {}   α = {}   ζ² = {}\n",
        as_unicode(&s.omega0_squared),
        as_unicode(&s.alpha),
        as_unicode(&s.zeta_squared)
    ));
    if let Some(x) = &s.static_deflection {
        out.push_str(&format!("  static deflection F/K = {}\n", as_unicode(x)));
    }
    out.push_str(&format!(
        "  magnification factor D = 1/√((1 − r²)² + (2ζr)²),  D² = {}\n",
        as_unicode(&s.magnification_squared)
    ));
    out.push_str(&format!(
        "  phase tan φ = 2ζr/(1 − r²) = {}\n",
        as_unicode(&s.tan_phase)
    ));
    out.push_str(&format!(
        "  transmissibility T = √(1 + (2ζr)²)/√((1 − r²)² + (2ζr)²),  T² = {}\n",
        as_unicode(&s.transmissibility_squared)
    ));
    match &s.peak {
        Peak::Load(l) => out.push_str(&load_peak_text(l)),
        Peak::Undamped if s.static_deflection.is_none() => {
            out.push_str("  resonance: undamped, |X| is infinite at Ω = ω₀\n")
        }
        Peak::Undamped => out.push_str("  resonance: undamped, D is infinite at Ω = ω₀\n"),
        Peak::None => out.push_str("  resonance: no peak (ζ² ≥ 1/2): D falls from 1 at Ω = 0\n"),
        Peak::At {
            omega_squared,
            magnification_squared,
            amplitude,
            half_power,
            bandwidth_squared,
            condition,
        } => {
            out.push_str(&format!(
                "  resonance peak ω_peak² = ω₀²·(1 − 2ζ²) = {}{}\n",
                as_unicode(omega_squared),
                match condition {
                    Some(c) => format!("  (when ζ² < 1/2: {} > 0)", as_unicode(c)),
                    None => String::new(),
                }
            ));
            out.push_str(&format!(
                "  D_peak = 1/(2ζ·√(1 − ζ²)),  D_peak² = {}\n",
                as_unicode(magnification_squared)
            ));
            if let Some(a) = amplitude {
                out.push_str(&format!("  peak amplitude X_peak = {}\n", as_unicode(a)));
            }
            out.push_str(
                "  half-power frequencies (D = D_peak/√2) Ω₁,₂² = ω₀²·(1 − 2ζ² ∓ 2ζ·√(1 − ζ²))\n",
            );
            match &half_power.0 {
                Some(l) => out.push_str(&format!("    Ω₁² = {}\n", as_unicode(l))),
                None => out.push_str("    Ω₁: none (Ω₁² ≤ 0)\n"),
            }
            out.push_str(&format!("    Ω₂² = {}\n", as_unicode(&half_power.1)));
            if let Some(b) = bandwidth_squared {
                out.push_str(&format!(
                    "  bandwidth (Ω₂ − Ω₁)² = {}  (≈ (2ζω₀)² = 4α² for light damping)\n",
                    as_unicode(b)
                ));
            }
        }
    }
    out
}

/// The peak of |X| for a load that depends on Ω, and D's for comparison.
fn load_peak_text(l: &LoadPeak) -> String {
    let mut out = String::from(
        "  the load depends on Ω: the resonance below is the peak of |X| for this load\n",
    );
    if let Some(w2) = &l.omega_squared {
        out.push_str(&format!(
            "  resonance peak of |X|: Ω_peak² = {}{}\n",
            as_unicode(w2),
            match &l.condition {
                Some(c) => format!("  (when {} > 0)", as_unicode(c)),
                None => String::new(),
            }
        ));
    }
    if let Some(a) = &l.amplitude_squared {
        out.push_str(&format!("  peak amplitude |X_peak|² = {}\n", as_unicode(a)));
        if let Some(n) = &l.half_power_note {
            out.push_str(&format!("  {n}\n"));
        } else {
            out.push_str("  half-power frequencies (|X| = |X_peak|/√2)\n");
        }
        for (name, h) in [("Ω₁", &l.half_power.0), ("Ω₂", &l.half_power.1)] {
            match h {
                Some(v) => out.push_str(&format!("    {name}² = {}\n", as_unicode(v))),
                None if l.half_power_note.is_none() => out.push_str(&format!("    {name}: none\n")),
                None => {}
            }
        }
    }
    if let Some(n) = &l.note {
        out.push_str(&format!("  {n}\n"));
    }
    if let Some(d) = &l.constant_force_peak {
        out.push_str(&format!(
            "  (D, the factor of a constant-amplitude force, peaks at ω₀²·(1 − 2ζ²) = {})\n",
            as_unicode(d)
        ));
    }
    out
}

/// `qdot response --format json` (without `--over`): every expression in
/// qdot's input syntax, `Omega` the forcing frequency.
#[derive(Serialize)]
pub struct ResponseJson {
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// The load's frequency as the scene writes it, replaced by `Omega`.
    pub frequency: String,
    /// F_c per coordinate: f = F_c·cos(Ω·t) + F_s·sin(Ω·t).
    pub load_cos: Vec<String>,
    /// F_s per coordinate.
    pub load_sin: Vec<String>,
    /// The undamped ω² in closed form (empty when there is none).
    pub omega_squared: Vec<String>,
    /// Re X per coordinate, X = (K − Ω²·M + i·Ω·C)⁻¹·(F_c − i·F_s).
    pub real: Vec<String>,
    /// Im X per coordinate.
    pub imag: Vec<String>,
    /// |X|² per coordinate.
    pub amplitude_squared: Vec<String>,
    /// tan φ per coordinate (q = |X|·cos(Ω·t − φ)); null where Re X = 0.
    pub tan_phase: Vec<Option<String>>,
    /// The Ω² where each coordinate's undamped X is zero.
    pub antiresonances: Vec<Vec<String>>,
    /// Why no antiresonances were computed, or null.
    pub antiresonance_note: Option<String>,
    /// One degree of freedom: [`SingleDofJson`]; else null.
    pub single: Option<SingleDofJson>,
}

/// The closed forms of one degree of freedom.
#[derive(Serialize)]
pub struct SingleDofJson {
    /// ω₀² = K/M.
    pub omega0_squared: String,
    /// α = C/(2M).
    pub alpha: String,
    /// ζ².
    pub zeta_squared: String,
    /// F/K, or null when F depends on Ω.
    pub static_deflection: Option<String>,
    /// D² in Ω.
    pub magnification_squared: String,
    /// tan φ in Ω.
    pub tan_phase: String,
    /// T² in Ω.
    pub transmissibility_squared: String,
    /// `"undamped"`, `"peak"` or `"none"` (ζ² ≥ 1/2, or no peak of |X|
    /// for a load that depends on Ω), `"undecided"` (see
    /// `resonance_note`). The peak is that of |X| for the scene's load.
    pub resonance: &'static str,
    /// For a load that depends on Ω: what the peak is of, or why it is
    /// not given; else null.
    pub resonance_note: Option<String>,
    /// For a load that depends on Ω: where D (a constant-amplitude
    /// force) peaks, ω₀² − 2α², for comparison; else null.
    pub constant_force_peak_omega_squared: Option<String>,
    /// ω_peak², or null.
    pub peak_omega_squared: Option<String>,
    /// The expression that must be positive for the peak (ζ² < 1/2), when
    /// its sign was not decided; else null.
    pub peak_condition: Option<String>,
    /// D_peak², or null.
    pub peak_magnification_squared: Option<String>,
    /// X_peak, or null.
    pub peak_amplitude: Option<String>,
    /// [Ω₁², Ω₂²] (Ω₁² null when it is not positive; Ω₂² null where |X|
    /// of a load that depends on Ω stays above |X_peak|/√2), or null.
    pub half_power_squared: Option<[Option<String>; 2]>,
    /// (Ω₂ − Ω₁)², or null.
    pub bandwidth_squared: Option<String>,
}

impl ResponseJson {
    /// The JSON of `r` (with `md`'s ω²).
    pub fn new(md: &osc::Modes, r: &Response) -> ResponseJson {
        let all = |v: &[Expr]| v.iter().map(as_input).collect::<Vec<_>>();
        let sys = &r.system;
        ResponseJson {
            coordinates: sys.coordinates.clone(),
            frequency: as_input(&sys.frequency),
            load_cos: all(&sys.load_cos),
            load_sin: all(&sys.load_sin),
            omega_squared: all(&md.omega_squared),
            real: all(&r.real),
            imag: all(&r.imag),
            amplitude_squared: all(&r.amplitude_squared),
            tan_phase: r
                .tan_phase
                .iter()
                .map(|t| t.as_ref().map(as_input))
                .collect(),
            antiresonances: r.antiresonances.iter().map(|a| all(a)).collect(),
            antiresonance_note: r.antiresonance_note.clone(),
            single: r.single.as_ref().map(SingleDofJson::new),
        }
    }
}

impl SingleDofJson {
    fn new(s: &SingleDof) -> SingleDofJson {
        let mut j = SingleDofJson {
            omega0_squared: as_input(&s.omega0_squared),
            alpha: as_input(&s.alpha),
            zeta_squared: as_input(&s.zeta_squared),
            static_deflection: s.static_deflection.as_ref().map(as_input),
            magnification_squared: as_input(&s.magnification_squared),
            tan_phase: as_input(&s.tan_phase),
            transmissibility_squared: as_input(&s.transmissibility_squared),
            resonance: "none",
            resonance_note: None,
            constant_force_peak_omega_squared: None,
            peak_omega_squared: None,
            peak_condition: None,
            peak_magnification_squared: None,
            peak_amplitude: None,
            half_power_squared: None,
            bandwidth_squared: None,
        };
        match &s.peak {
            Peak::Load(l) => {
                j.resonance = match (&l.omega_squared, &l.note) {
                    (Some(_), _) => "peak",
                    (None, Some(n)) if n.starts_with("no peak") => "none",
                    _ => "undecided",
                };
                j.resonance_note =
                    Some(l.note.clone().unwrap_or_else(|| {
                        "the peak of |X| for this load, which depends on Ω".into()
                    }));
                j.constant_force_peak_omega_squared = l.constant_force_peak.as_ref().map(as_input);
                j.peak_omega_squared = l.omega_squared.as_ref().map(as_input);
                j.peak_condition = l.condition.as_ref().map(as_input);
                j.peak_amplitude = l
                    .amplitude_squared
                    .as_ref()
                    .and_then(|a| crate::expr::func::sqrt(a).ok())
                    .as_ref()
                    .map(as_input);
                if l.amplitude_squared.is_some() && l.half_power_note.is_none() {
                    j.half_power_squared = Some([
                        l.half_power.0.as_ref().map(as_input),
                        l.half_power.1.as_ref().map(as_input),
                    ]);
                }
            }
            Peak::Undamped => j.resonance = "undamped",
            Peak::None => {}
            Peak::At {
                omega_squared,
                magnification_squared,
                amplitude,
                half_power,
                bandwidth_squared,
                condition,
            } => {
                j.resonance = "peak";
                j.peak_omega_squared = Some(as_input(omega_squared));
                j.peak_condition = condition.as_ref().map(as_input);
                j.peak_magnification_squared = Some(as_input(magnification_squared));
                j.peak_amplitude = amplitude.as_ref().map(as_input);
                j.half_power_squared = Some([
                    half_power.0.as_ref().map(as_input),
                    Some(as_input(&half_power.1)),
                ]);
                j.bandwidth_squared = bandwidth_squared.as_ref().map(as_input);
            }
        }
        j
    }
}
