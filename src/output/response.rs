//! `qdot response`: without `--over` the exact frequency response
//! ([`crate::solve::response`]) as text or JSON; with it the swept table
//! ([`crate::simulate::response`]) as text, CSV or JSON.

use super::table::{right_aligned, short, Csv};
use super::{as_input, as_unicode};
use crate::app::{Command, Format, FrequencyResponse};
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::Expr;
use crate::simulate::response::ResponseTable;
use crate::solve::equilibrium::Values;
use crate::solve::oscillations as osc;
use crate::solve::response::{LoadPeak, Peak, Response, SingleDof, OMEGA};
use serde::Serialize;

/// `response`'s report in `fmt`: the exact response as text or JSON, the
/// swept one as text, CSV or JSON.
pub(super) fn render(r: &FrequencyResponse, fmt: Format) -> Result<String, Diagnostic> {
    Ok(match (r, fmt) {
        (FrequencyResponse::Exact(e), Format::Text) => text(&e.0, &e.1, &e.2),
        (FrequencyResponse::Exact(e), Format::Json) => {
            super::wire::json_string(&ResponseJson::new(&e.0, &e.1))
        }
        (FrequencyResponse::Swept(t), Format::Text) => swept_text(t),
        (FrequencyResponse::Swept(t), Format::Json) => swept_json(t),
        (FrequencyResponse::Swept(t), Format::Csv) => swept_csv(t),
        (FrequencyResponse::Exact(_), Format::Csv) => {
            return Err(Diagnostic::global("unknown output `csv`")
                .with_hint("--output json, --output text (csv with --over)")
                .with_kind(ErrorKind::bad_option("--output")))
        }
        (_, Format::Latex) => return Err(super::not_written(Command::Response, fmt)),
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

/// The exact response for reading, its frequencies evaluated at `set`
/// (when it gives every value).
pub fn text(md: &osc::Modes, r: &Response, set: &Values) -> String {
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
        for (i, w2) in md.omega_squared.iter().enumerate() {
            let sub = crate::expr::print::subscript(&(i + 1).to_string());
            if let Some(n) = super::at_values::frequency(&sub, w2, set) {
                out.push_str(&format!("    {n}\n"));
            }
        }
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
        out.push_str(&single_text(s, set));
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

fn single_text(s: &SingleDof, set: &Values) -> String {
    use super::at_values::evaluate;
    let mut out =
        String::from("\nOne degree of freedom  (ω₀² = K/M, α = C/(2M), ζ = α/ω₀, r = Ω/ω₀)\n");
    out.push_str(&format!(
        "  ω₀² = {}   α = {}   ζ² = {}\n",
        as_unicode(&s.omega0_squared),
        as_unicode(&s.alpha),
        as_unicode(&s.zeta_squared)
    ));
    if let Some(w) = super::at_values::frequency("₀", &s.omega0_squared, set) {
        let zeta = evaluate(&s.zeta_squared, set).and_then(|z| z.sqrt());
        let zeta = zeta
            .map(|z| format!(", ζ = {}", z.text()))
            .unwrap_or_default();
        out.push_str(&format!("    {w}{zeta}\n"));
    }
    // a frequency squared at the values, as ω in rad/s and f in Hz
    let at = |name: &str, f: &str, w2: &Expr| {
        evaluate(w2, set)
            .and_then(|v| v.sqrt())
            .map(|w| {
                format!(
                    "    {name} = {} rad/s, {f} = {} Hz\n",
                    w.text(),
                    w.per_turn().text()
                )
            })
            .unwrap_or_default()
    };
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
            out.push_str(&at("ω_peak", "f_peak", omega_squared));
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
                out.push_str(&at("Ω₂ − Ω₁", "Δf", b));
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

// ---- `response --over`: the swept table ----

/// The column names after `Omega`: `|X_x|`, `phi_x` per coordinate.
fn swept_columns(t: &ResponseTable) -> Vec<String> {
    let mut c = vec![OMEGA.to_string()];
    for q in &t.coordinates {
        c.push(format!("amp_{q}"));
        c.push(format!("phase_{q}"));
    }
    c
}

/// The table as CSV: Ω, then each coordinate's amplitude and phase
/// (radians); an empty cell where A is singular.
pub fn swept_csv(t: &ResponseTable) -> String {
    let mut table = Csv::new(swept_columns(t));
    // at most 25 bytes a number, and its comma
    table.reserve(t.omega.len() * (1 + 2 * t.coordinates.len()) * 26);
    for (k, w) in t.omega.iter().enumerate() {
        let cells = (0..t.coordinates.len()).flat_map(|j| [t.amplitude[k][j], t.phase[k][j]]);
        table.number_row(std::iter::once(Some(*w)).chain(cells));
    }
    table.finish()
}

/// `response --over … --output json`.
#[derive(serde::Serialize)]
pub struct ResponseSweepJson<'a> {
    /// The coordinates.
    pub coordinates: &'a [String],
    /// `Omega`, then `amp_q` and `phase_q` (radians) per coordinate q.
    pub columns: Vec<String>,
    /// One row per Ω, in the order of `columns`; null where
    /// K − Ω²·M + i·Ω·C is singular.
    pub rows: Vec<Vec<Option<f64>>>,
    /// The undamped natural frequencies ω_i, ascending.
    pub natural_frequencies: &'a [f64],
    /// Why `natural_frequencies` is empty, or null.
    pub natural_frequencies_note: Option<&'a str>,
    /// coordinate → the local maxima of its amplitude on the grid, each
    /// `[Omega, amplitude]`.
    pub peaks: serde_json::Map<String, serde_json::Value>,
}

/// The table as JSON (one line): [`ResponseSweepJson`].
pub fn swept_json(t: &ResponseTable) -> String {
    let rows = t
        .omega
        .iter()
        .enumerate()
        .map(|(k, w)| {
            let mut r = vec![Some(*w)];
            for j in 0..t.coordinates.len() {
                r.push(t.amplitude[k][j]);
                r.push(t.phase[k][j]);
            }
            r
        })
        .collect();
    let mut peaks = serde_json::Map::new();
    for (q, p) in t.coordinates.iter().zip(&t.peaks) {
        peaks.insert(
            q.clone(),
            serde_json::json!(p.iter().map(|(w, a)| [*w, *a]).collect::<Vec<_>>()),
        );
    }
    let wire = ResponseSweepJson {
        coordinates: &t.coordinates,
        columns: swept_columns(t),
        rows,
        natural_frequencies: &t.natural_frequencies,
        natural_frequencies_note: t.natural_note.as_deref(),
        peaks,
    };
    serde_json::to_string(&wire).unwrap_or_default()
}

/// 6 significant digits at any scale: `short` but for values below 1e-12,
/// which an amplitude or a frequency may be (k = 1e155: |x| = 1e-155).
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || x.abs() >= 1e-12 {
        return short(x);
    }
    let s = format!("{x:.5e}");
    let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
    let m = m.trim_end_matches('0').trim_end_matches('.');
    format!("{m}e{e}")
}

/// The table for reading: a header with the natural frequencies and the
/// peaks, then Ω, |X_j| and φ_j in degrees, 6 significant digits.
pub fn swept_text(t: &ResponseTable) -> String {
    let mut out = String::new();
    let pretty = |q: &str| crate::expr::print::pretty_name(q, 0);
    match &t.natural_note {
        None => out.push_str(&format!(
            "natural frequencies (undamped): {}\n",
            if t.natural_frequencies.is_empty() {
                "none".to_string()
            } else {
                t.natural_frequencies
                    .iter()
                    .map(|w| format!("ω = {}", significant(*w)))
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        )),
        Some(why) => out.push_str(&format!("natural frequencies: {why}\n")),
    }
    for (q, p) in t.coordinates.iter().zip(&t.peaks) {
        let list: Vec<String> = p
            .iter()
            .map(|(w, a)| format!("|X| = {} at Ω = {}", significant(*a), significant(*w)))
            .collect();
        out.push_str(&format!(
            "peaks of {} on the grid: {}\n",
            pretty(q),
            if list.is_empty() {
                "none".to_string()
            } else {
                list.join(", ")
            }
        ));
    }
    let mut header = vec!["Ω".to_string()];
    for q in &t.coordinates {
        header.push(format!("|{}|", pretty(q)));
        header.push(format!("φ({}) deg", pretty(q)));
    }
    let mut cells = vec![header];
    for (k, w) in t.omega.iter().enumerate() {
        let mut line = vec![significant(*w)];
        for j in 0..t.coordinates.len() {
            line.push(t.amplitude[k][j].map_or("∞".into(), significant));
            line.push(t.phase[k][j].map_or("—".into(), |p| short(p.to_degrees())));
        }
        cells.push(line);
    }
    out.push_str(&right_aligned(&cells));
    out
}
