//! `simulate`'s writers: the run as CSV and as JSON ([`RunJson`]), and
//! the `--stats` lines.

use super::table::Csv;
use crate::simulate::compile::Engine;
use crate::simulate::run::{method_name, status_word, Run};
use crate::simulate::Status;

/// The run as CSV: a header line, then one line per output time, every
/// digit of each value.
pub fn csv(run: &Run) -> String {
    let mut table = Csv::new(&run.columns);
    for row in &run.rows {
        table.number_row(row.iter().map(|&x| Some(x)));
    }
    table.finish()
}

/// The run as JSON (one line): [`RunJson`].
pub fn json(run: &Run) -> String {
    let s = &run.solution.stats;
    let engine = &run.engine;
    let evaluator = &run.evaluator;
    let wire = RunJson {
        method: method_name(run.method),
        status: status_word(&run.solution.status),
        columns: &run.columns,
        rows: &run.rows,
        stats: StatsJson {
            steps: s.steps,
            rejected: s.rejected,
            rhs_evals: s.rhs_evals,
            jacobians: s.jacobians,
            factorizations: s.factorizations,
            seconds: run.seconds,
            compile_seconds: run.compile_seconds,
            engine: EngineJson {
                name: engine.ran.name(),
                requested: engine.requested.name(),
                compile_seconds: engine.compile_seconds,
                code_bytes: engine.code_bytes,
                reason: engine.reason.as_deref(),
            },
            evaluator: EvaluatorJson {
                name: evaluator.evaluator.name(),
                reason: &evaluator.reason,
                cost: CostJson {
                    mass_matrix: evaluator.mass_cost,
                    accelerations: evaluator.accelerations_cost,
                },
            },
            constraint_drift: run.constraint_drift,
        },
        stiff_at: run.solution.stiff_at,
        event_t: match run.solution.status {
            Status::Event { t } => Some(t),
            _ => None,
        },
        event_poles: &run.solution.event_poles,
    };
    let mut out = serde_json::to_string(&wire).unwrap_or_default();
    out.push('\n');
    out
}

/// `simulate --output json`: the run's table and what it cost.
#[derive(serde::Serialize)]
pub struct RunJson<'a> {
    /// The method's name (`dop853`, …).
    pub method: &'static str,
    /// How the run ended ([`status_word`]).
    pub status: &'static str,
    /// The columns' names: `t`, the coordinates and velocities, then
    /// `energy` and the constraints' drifts where the scene has them.
    pub columns: &'a [String],
    /// The output rows, one per output time.
    pub rows: &'a [Vec<f64>],
    /// The work done.
    pub stats: StatsJson<'a>,
    /// Where the problem became stiff, or null.
    pub stiff_at: Option<f64>,
    /// The time of the `--stop-when` event, or null.
    pub event_t: Option<f64>,
    /// The times the `--stop-when` condition changed sign through a pole
    /// or a jump, not a zero: not events.
    pub event_poles: &'a [f64],
}

/// A run's work.
#[derive(serde::Serialize)]
pub struct StatsJson<'a> {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Right-hand side evaluations.
    pub rhs_evals: usize,
    /// Jacobians formed.
    pub jacobians: usize,
    /// LU factorizations.
    pub factorizations: usize,
    /// The integration's wall time.
    pub seconds: f64,
    /// The compilation's wall time.
    pub compile_seconds: f64,
    /// What ran the equations.
    pub engine: EngineJson<'a>,
    /// What evaluated q̈.
    pub evaluator: EvaluatorJson<'a>,
    /// For a scene with constraints: the largest |g| over the output rows;
    /// absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub constraint_drift: Option<f64>,
}

/// What ran the equations.
#[derive(serde::Serialize)]
pub struct EngineJson<'a> {
    /// `jit` or `interpreter`.
    pub name: &'static str,
    /// What `--evaluator` asked for.
    pub requested: &'static str,
    /// The machine code's compile time.
    pub compile_seconds: f64,
    /// The machine code's size.
    pub code_bytes: usize,
    /// Why the interpreter ran, else null.
    pub reason: Option<&'a str>,
}

/// What evaluated q̈ and why.
#[derive(serde::Serialize)]
pub struct EvaluatorJson<'a> {
    /// The evaluator's name.
    pub name: &'static str,
    /// Why it was chosen.
    pub reason: &'a str,
    /// The estimated flops per right-hand side.
    pub cost: CostJson,
}

/// The estimated flops per right-hand side.
#[derive(serde::Serialize)]
pub struct CostJson {
    /// Of M, f and their solve.
    pub mass_matrix: f64,
    /// Of the exact accelerations, null when they were not derived.
    pub accelerations: Option<f64>,
}

/// The `--stats` lines: the method's work, then the evaluator of q̈ and
/// why it was chosen, then what ran it (machine code and its compile time
/// beside the integration's, or the interpreter and why).
pub fn stats_text(run: &Run) -> String {
    let s = &run.solution.stats;
    format!(
        "method {}: {} steps ({} rejected), {} RHS evaluations, {} Jacobians, {} factorizations; integration {:.3} ms, compilation {:.3} ms\nevaluator {}: {}\n",
        method_name(run.method),
        s.steps,
        s.rejected,
        s.rhs_evals,
        s.jacobians,
        s.factorizations,
        run.seconds * 1e3,
        run.compile_seconds * 1e3,
        run.evaluator.evaluator.name(),
        run.evaluator.reason
    ) + &engine_line(run)
        + &match run.constraint_drift {
        Some(d) => format!("constraint drift: max |g| = {d:.3e} over the output rows\n"),
        None => String::new(),
    }
}

/// The `--stats` line of [`Run::engine`](crate::simulate::run::Run::engine).
fn engine_line(run: &Run) -> String {
    let e = &run.engine;
    match (&e.reason, e.ran) {
        (None, Engine::Jit) => format!(
            "engine jit: machine code ({} bytes) compiled in {:.3} ms; integration {:.3} ms\n",
            e.code_bytes,
            e.compile_seconds * 1e3,
            run.seconds * 1e3
        ),
        (reason, _) => format!(
            "engine interpreter: {}\n",
            reason
                .as_deref()
                .unwrap_or("the register program interpreted")
        ),
    }
}
