//! `sweep`'s writers: the runs as CSV and as JSON ([`SweepJson`]).

use super::table::{full, quoted, Csv};
use crate::simulate::run::status_word;
use crate::simulate::sweep::Sweep;

/// The sweep as CSV: the varied values, `status`, `t`, the final state
/// (`q(t)`, `q'(t)`),
/// `max|q|` per coordinate, `energy_drift` (empty when not conserved),
/// `steps`; a failed run has `error: ` and its message in `status`
/// (quoted, RFC 4180) and empty cells.
pub fn csv(s: &Sweep) -> String {
    let mut header: Vec<String> = s.names.clone();
    header.extend(["status".into(), "t".into()]);
    // the final state, q(t): the varied names may include q itself
    header.extend(s.coordinates.iter().map(|q| format!("{q}(t)")));
    header.extend(s.coordinates.iter().map(|q| format!("{q}'(t)")));
    header.extend(s.coordinates.iter().map(|q| format!("max|{q}|")));
    header.extend(["energy_drift".into(), "steps".into()]);
    let mut table = Csv::new(&header);
    let n = s.coordinates.len();
    for (values, outcome) in &s.runs {
        let mut cells: Vec<String> = values.iter().map(|v| format!("{v}")).collect();
        match outcome {
            Ok(o) => {
                cells.push(status_word(&o.status).into());
                cells.push(full(o.t));
                cells.extend(o.y.iter().chain(&o.max_abs_q).map(|&x| full(x)));
                cells.push(o.energy_drift.map_or(String::new(), |d| format!("{d:.3e}")));
                cells.push(o.steps.to_string());
            }
            Err(m) => {
                cells.push(quoted(&format!("error: {m}")));
                cells.extend(std::iter::repeat_n(String::new(), 1 + 3 * n + 2));
            }
        }
        table.row(&cells);
    }
    table.finish()
}

/// The `--stats` line: runs, threads, wall time, runs per second, and
/// how many times the equations were compiled.
pub fn stats_text(s: &Sweep) -> String {
    format!(
        "{} runs on {} threads in {:.3} s: {:.0} runs per second; equations compiled {} time{}\n",
        s.runs.len(),
        s.threads,
        s.seconds,
        s.runs.len() as f64 / s.seconds.max(1e-9),
        s.compilations,
        if s.compilations == 1 { "" } else { "s" }
    )
}

/// The sweep as JSON (one line): [`SweepJson`].
pub fn json(s: &Sweep) -> String {
    let wire = SweepJson {
        names: &s.names,
        coordinates: &s.coordinates,
        runs: s
            .runs
            .iter()
            .map(|(values, outcome)| match outcome {
                Ok(o) => SweepRunJson::Done {
                    values,
                    status: status_word(&o.status),
                    t: o.t,
                    y: &o.y,
                    max_abs_q: &o.max_abs_q,
                    energy_drift: o.energy_drift,
                    steps: o.steps,
                },
                Err(error) => SweepRunJson::Failed { values, error },
            })
            .collect(),
        seconds: s.seconds,
        threads: s.threads,
    };
    let mut out = serde_json::to_string(&wire).unwrap_or_default();
    out.push('\n');
    out
}

/// `sweep --output json`.
#[derive(serde::Serialize)]
pub struct SweepJson<'a> {
    /// The varied names.
    pub names: &'a [String],
    /// The coordinates.
    pub coordinates: &'a [String],
    /// One entry per run.
    pub runs: Vec<SweepRunJson<'a>>,
    /// The sweep's wall time.
    pub seconds: f64,
    /// The threads used.
    pub threads: usize,
}

/// One run of a sweep.
#[derive(serde::Serialize)]
#[serde(untagged)]
pub enum SweepRunJson<'a> {
    /// A run that integrated.
    Done {
        /// The varied names' values.
        values: &'a [f64],
        /// How it ended.
        status: &'static str,
        /// The time it reached.
        t: f64,
        /// The state there.
        y: &'a [f64],
        /// max |q| per coordinate over the output times.
        max_abs_q: &'a [f64],
        /// The energy drift, or null.
        energy_drift: Option<f64>,
        /// Accepted steps.
        steps: usize,
    },
    /// A run that could not start.
    Failed {
        /// The varied names' values.
        values: &'a [f64],
        /// Why.
        error: &'a str,
    },
}
