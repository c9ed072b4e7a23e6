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

use crate::algebra::sign::Values;
use crate::cycle::Over;
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::atom;
use crate::expr::Expr;
use crate::poly::Var;
use crate::scene::given::{parse_ranges, RESPONSE_OVER};
use crate::scene::Scene;
use crate::solve::response::{natural_frequencies, ForcedSystem, OMEGA};
use qdot_compile::compile::{compile_with, Program};
use qdot_ode::dense::{solve_complex_scaled, Complex, Lu};
use rustc_hash::FxHashSet;

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

/// `--over` of `qdot response` ([`crate::scene::given::parse_ranges`]
/// with [`RESPONSE_OVER`]): the varied quantity must be Ω.
pub fn parse_over(s: &str) -> Result<Over, Diagnostic> {
    let over = parse_ranges(&RESPONSE_OVER, s)?.remove(0);
    check_axis(&over, s)?;
    Ok(over)
}

/// An error unless `over` (written `written`) varies Ω.
pub fn check_axis(over: &Over, written: &str) -> Result<(), Diagnostic> {
    if over.name != OMEGA && over.name != "Ω" {
        return Err(Diagnostic::global(format!(
            "`--over {written}`: `qdot response` varies the forcing frequency, `Omega`, not `{}`",
            over.name
        ))
        .with_hint(RESPONSE_OVER.hint)
        .with_kind(ErrorKind::bad_option("--over")));
    }
    Ok(())
}

impl CompiledResponse {
    /// Compile `sys`, linearized from `scene`, with every parameter but Ω
    /// bound to its value in `set`: the values checked as every numeric
    /// command checks them ([`crate::scene::given::parameter_map_of`]), each
    /// parameter of the system given (those of M not 0).
    pub fn new(
        scene: &Scene,
        sys: &ForcedSystem,
        set: &Values,
    ) -> Result<CompiledResponse, Diagnostic> {
        let n = sys.coordinates.len();
        let outputs: Vec<Expr> = [&sys.stiffness, &sys.mass, &sys.damping]
            .into_iter()
            .flat_map(|m| m.iter().flatten().cloned())
            .chain(sys.load_cos.iter().cloned())
            .chain(sys.load_sin.iter().cloned())
            .collect();
        let omega = atom::param(OMEGA);
        let used = |m: &[Expr]| -> FxHashSet<Var> {
            m.iter()
                .flat_map(|e| e.vars())
                .filter(|&v| v != omega)
                .collect()
        };
        let needed = used(&outputs);
        let massive = used(&sys.mass.concat());
        let inertial: Vec<String> = scene
            .parameters
            .iter()
            .filter(|p| massive.contains(&atom::param(&p.name)))
            .map(|p| p.name.clone())
            .collect();
        let mut params = crate::scene::given::parameter_map_of(scene, set, &inertial, &|p| {
            needed.contains(&atom::param(p))
        })?;
        params.retain(|v, _| needed.contains(v));
        let program = compile_with(&outputs, &[omega], &params).map_err(|e| {
            Diagnostic::global(format!("the frequency response does not compile: {e}"))
                .with_kind(e.kind())
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
        let nn = n * n;
        let (stiffness, rest) = self.values.split_at(nn);
        let (mass, rest) = rest.split_at(nn);
        let (damping, load) = rest.split_at(nn);
        let (load_cos, load_sin) = load.split_at(n);
        let w2 = omega * omega;
        for (z, ((&k, &m), &c)) in lu.a.iter_mut().zip(stiffness.iter().zip(mass).zip(damping)) {
            *z = Complex::new(k - w2 * m, omega * c);
        }
        for (z, (&fc, &fs)) in x.iter_mut().zip(load_cos.iter().zip(load_sin)) {
            *z = Complex::new(fc, -fs);
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
