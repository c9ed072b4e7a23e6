//! `qdot response --over Omega=FROM:TO:COUNT`: the frequency response
//! swept numerically (the exact one is [`crate::solve::response`]).
//!
//! M, C, K and the load F_c, F_s (see
//! [`crate::solve::response::ForcedSystem`]) are compiled once into one
//! register program of Ω with the `--set` values folded in; at each Ω the
//! program gives A = K − Ω²·M + i·Ω·C and F = F_c − i·F_s, and A·X = F is
//! solved by complex LU with partial pivoting on A equilibrated by powers
//! of two (`dense::solve_complex_scaled`: no overflow at any scale of A).
//! Amplitude |X_j| and phase φ_j = arg(X̄_j) (q_j = |X_j|·cos(Ω·t − φ_j))
//! of every coordinate, the undamped natural frequencies and the sweep's
//! resonance peaks (local maxima of |X_j| on the grid).

use super::cycle::short;
use crate::algebra::sign::Values;
use crate::cycle::Over;
use crate::diag::{Diagnostic, ErrorKind};
use crate::engine::dense::{solve_complex_scaled, Complex, Lu};
use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::poly::Var;
use crate::solve::response::{natural_frequencies, ForcedSystem, OMEGA};
use qdot_compile::compile::{compile_with, Program};
use rustc_hash::FxHashMap;

/// The swept frequency response.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct ResponseTable {
    /// The coordinates, in declaration order.
    pub coordinates: Vec<String>,
    /// The frequencies Ω, one per row.
    pub omega: Vec<f64>,
    /// |X_j| per row, per coordinate; `None` where K − Ω²·M + i·Ω·C is
    /// singular (an undamped resonance on the grid).
    pub amplitude: Vec<Vec<Option<f64>>>,
    /// φ_j in radians (−π, π] per row, per coordinate (`None` as above).
    pub phase: Vec<Vec<Option<f64>>>,
    /// The undamped natural frequencies ω_i, ascending.
    pub natural_frequencies: Vec<f64>,
    /// Why there are none, when they could not be computed.
    pub natural_note: Option<String>,
    /// Per coordinate, the local maxima of |X_j| on the grid: (Ω, |X_j|).
    pub peaks: Vec<Vec<(f64, f64)>>,
}

/// The system compiled for a sweep: one program of Ω whose outputs are K,
/// M, C (n² each, row by row), F_c and F_s (n each).
pub struct CompiledResponse {
    n: usize,
    program: Program,
    registers: Vec<f64>,
    values: Vec<f64>,
    natural: Result<Vec<f64>, String>,
    coordinates: Vec<String>,
}

/// `--over` of `qdot response`: the varied quantity must be Ω.
pub fn parse_over(s: &str) -> Result<Over, Diagnostic> {
    const HINT: &str = "--over Omega=0:3:600: the first and last frequencies, and how many";
    let over = Over::parse(s).map_err(|d| d.with_hint(HINT))?;
    if over.name != OMEGA && over.name != "Ω" {
        return Err(Diagnostic::global(format!(
            "`--over {s}`: `qdot response` varies the forcing frequency, `Omega`, not `{}`",
            over.name
        ))
        .with_hint(HINT)
        .with_kind(ErrorKind::bad_option("--over")));
    }
    Ok(over)
}

impl CompiledResponse {
    /// Compile `sys` with every parameter but Ω bound to its value in `set`.
    pub fn new(sys: &ForcedSystem, set: &Values) -> Result<CompiledResponse, Diagnostic> {
        let n = sys.coordinates.len();
        let outputs: Vec<Expr> = [&sys.stiffness, &sys.mass, &sys.damping]
            .into_iter()
            .flat_map(|m| m.iter().flatten().cloned())
            .chain(sys.load_cos.iter().cloned())
            .chain(sys.load_sin.iter().cloned())
            .collect();
        let omega = atom::param(OMEGA);
        let mut missing: Vec<String> = Vec::new();
        let mut params: FxHashMap<Var, f64> = FxHashMap::default();
        for e in &outputs {
            for v in e.vars() {
                if v == omega {
                    continue;
                }
                if let Atom::Param(name) = atom::atom(v) {
                    match set.get(&*name) {
                        Some(&x) => {
                            params.insert(v, x);
                        }
                        None if !missing.iter().any(|m| **m == *name) => {
                            missing.push(name.to_string())
                        }
                        None => {}
                    }
                }
            }
        }
        if !missing.is_empty() {
            missing.sort();
            return Err(Diagnostic::global(format!(
                "the swept frequency response needs a value for every parameter, and {} {} none",
                missing.join(", "),
                if missing.len() == 1 { "has" } else { "have" }
            ))
            .with_hint(format!(
                "give them with --set {}",
                missing
                    .iter()
                    .map(|m| format!("{m}=…"))
                    .collect::<Vec<_>>()
                    .join(",")
            ))
            .with_kind(ErrorKind::bad_option("--set")));
        }
        let program = compile_with(&outputs, &[omega], &params).map_err(|e| {
            Diagnostic::global(format!("the frequency response does not compile: {e}"))
        })?;
        Ok(CompiledResponse {
            n,
            registers: program.registers(),
            values: vec![0.0; outputs.len()],
            program,
            natural: natural_frequencies(sys, set),
            coordinates: sys.coordinates.clone(),
        })
    }

    /// X(Ω) into `x`; false where A is singular or a value is not finite.
    /// `lu` is scratch of size n.
    fn solve_at(&mut self, omega: f64, lu: &mut Lu<Complex<f64>>, x: &mut [Complex<f64>]) -> bool {
        let n = self.n;
        self.program
            .eval(&[omega], &mut self.registers, &mut self.values);
        let v = &self.values;
        let nn = n * n;
        let w2 = omega * omega;
        for (k, z) in lu.a.iter_mut().enumerate() {
            *z = Complex::new(v[k] - w2 * v[nn + k], omega * v[2 * nn + k]);
        }
        for (j, z) in x.iter_mut().enumerate() {
            *z = Complex::new(v[3 * nn + j], -v[3 * nn + n + j]);
        }
        solve_complex_scaled(lu, x).is_ok()
            && x.iter().all(|z| z.re.is_finite() && z.im.is_finite())
    }

    /// The response at every Ω of `over`.
    pub fn run(&mut self, over: &Over) -> ResponseTable {
        let n = self.n;
        let mut lu = Lu::new(n, Complex::new(0.0, 0.0));
        let mut x = vec![Complex::new(0.0, 0.0); n];
        let mut omega = Vec::with_capacity(over.count);
        let mut amplitude = Vec::with_capacity(over.count);
        let mut phase = Vec::with_capacity(over.count);
        for k in 0..over.count {
            let w = over.value(k);
            omega.push(w);
            if self.solve_at(w, &mut lu, &mut x) {
                amplitude.push(x.iter().map(|z| Some(z.re.hypot(z.im))).collect());
                phase.push(x.iter().map(|z| Some((-z.im).atan2(z.re))).collect());
            } else {
                amplitude.push(vec![None; n]);
                phase.push(vec![None; n]);
            }
        }
        let peaks = (0..n)
            .map(|j| {
                let col: Vec<Option<f64>> =
                    amplitude.iter().map(|r: &Vec<Option<f64>>| r[j]).collect();
                local_maxima(&omega, &col)
            })
            .collect();
        let (natural_frequencies, natural_note) = match &self.natural {
            Ok(w) => (w.clone(), None),
            Err(why) => (Vec::new(), Some(why.clone())),
        };
        ResponseTable {
            coordinates: self.coordinates.clone(),
            omega,
            amplitude,
            phase,
            natural_frequencies,
            natural_note,
            peaks,
        }
    }
}

/// The interior local maxima of `a` against `w` (a plateau counts once).
fn local_maxima(w: &[f64], a: &[Option<f64>]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for k in 1..a.len().saturating_sub(1) {
        if let (Some(l), Some(m), Some(r)) = (a[k - 1], a[k], a[k + 1]) {
            if m > l && m >= r {
                out.push((w[k], m));
            }
        }
    }
    out
}

/// Solve A·x = b in place for complex A (n×n, row-major, re/im
/// interleaved) and b (re/im interleaved) by the equilibrated complex LU
/// of [`crate::engine::dense::solve_complex_scaled`]; false when A is
/// singular or a value is not finite.
pub fn complex_lu_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    if a.len() < 2 * n * n || b.len() < 2 * n {
        return false;
    }
    let mut lu = Lu::new(n, Complex::new(0.0, 0.0));
    for (z, p) in lu.a.iter_mut().zip(a.chunks_exact(2)) {
        *z = Complex::new(p[0], p[1]);
    }
    let mut x: Vec<Complex<f64>> = b[..2 * n]
        .chunks_exact(2)
        .map(|p| Complex::new(p[0], p[1]))
        .collect();
    let ok = solve_complex_scaled(&mut lu, &mut x).is_ok();
    for (p, z) in b.chunks_exact_mut(2).zip(&x) {
        p[0] = z.re;
        p[1] = z.im;
    }
    ok && b.iter().all(|v| v.is_finite())
}

/// The scene `src` linearized about `at` (`--at th=pi`) and swept over `over` at the
/// values `set`.
pub fn sweep(
    src: &str,
    at: Option<&str>,
    set: &Values,
    over: &Over,
) -> Result<ResponseTable, Diagnostic> {
    let scene = crate::scene::Scene::parse(src)?;
    crate::scene::given::set_names_are_parameters(&scene, set)?;
    let at = at.map(|a| scene.coordinate_values(a)).transpose()?;
    let sys = ForcedSystem::of_scene(&scene, at.as_deref())?;
    Ok(CompiledResponse::new(&sys, set)?.run(over))
}

/// A value as CSV and JSON print it: every digit of the double.
fn full(x: f64) -> String {
    format!("{x:.17e}")
}

/// The column names after `Omega`: `|X_x|`, `phi_x` per coordinate.
fn columns(t: &ResponseTable) -> Vec<String> {
    let mut c = vec![OMEGA.to_string()];
    for q in &t.coordinates {
        c.push(format!("amp_{q}"));
        c.push(format!("phase_{q}"));
    }
    c
}

/// The table as CSV: Ω, then each coordinate's amplitude and phase
/// (radians); an empty cell where A is singular.
pub fn csv(t: &ResponseTable) -> String {
    let mut out = columns(t).join(",");
    out.push('\n');
    for (k, w) in t.omega.iter().enumerate() {
        out.push_str(&full(*w));
        for j in 0..t.coordinates.len() {
            for v in [t.amplitude[k][j], t.phase[k][j]] {
                out.push(',');
                out.push_str(&v.map(full).unwrap_or_default());
            }
        }
        out.push('\n');
    }
    out
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
pub fn json(t: &ResponseTable) -> String {
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
        columns: columns(t),
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
pub fn text(t: &ResponseTable) -> String {
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
    out.push_str(&super::cycle::right_aligned(&cells));
    out
}
