//! `qdot sweep`: one scene, many runs, on every core.
//!
//! A parameter study (a stability chart over two parameters) or a
//! Monte-Carlo study over initial conditions: the scene is parsed and
//! derived once ([`Prepared`]); when only initial values vary it is also
//! compiled once and each run clones the compiled program; when parameters
//! vary each run compiles for its values (microseconds to milliseconds).
//! The runs are spread over a rayon pool; each keeps a summary, not its
//! trajectory, so memory stays O(runs).

use super::run::{status_word, Prepared, Request, Run};
use super::Status;
use crate::diag::{Diagnostic, ErrorKind};
use crate::limits::MAX_SWEEP_RUNS;
use qdot_exact::rng::SplitMix64;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// One varied name: a parameter, a coordinate (`theta`) or a velocity
/// (`theta'`), from `from` to `to`.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The name, as in `--set` or `--init`.
    pub name: String,
    /// The first value.
    pub from: f64,
    /// The last value.
    pub to: f64,
    /// How many evenly spaced values, ends included, on a grid (1: `from`
    /// alone); ignored by a random design.
    pub count: usize,
}

/// How the runs' values are chosen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Design {
    /// Every combination of the axes' values (the first axis varies slowest).
    Grid,
    /// `samples` points drawn uniformly in the box of the axes, from `seed`
    /// (the same seed gives the same points on every machine).
    Random {
        /// How many runs.
        samples: usize,
        /// The generator's seed ([`SplitMix64`]).
        seed: u64,
    },
}

/// What one run ended with.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// How it ended (`done`, `event`, …).
    pub status: Status,
    /// The last output time reached.
    pub t: f64,
    /// The state y = (q, q̇) there.
    pub y: Vec<f64>,
    /// The largest |qₖ| over the output times, per coordinate.
    pub max_abs_q: Vec<f64>,
    /// max |h(t) − h(0)| of the conserved energy, when the scene has one.
    pub energy_drift: Option<f64>,
    /// Accepted steps.
    pub steps: usize,
}

/// A finished sweep: one row per run, in the design's order.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The varied names, in the order of each run's `values`.
    pub names: Vec<String>,
    /// The coordinates (the order of `y` and `max_abs_q`).
    pub coordinates: Vec<String>,
    /// The runs: the varied values, and the outcome or the error's message.
    pub runs: Vec<(Vec<f64>, Result<Outcome, String>)>,
    /// Wall time of all runs.
    pub seconds: f64,
    /// The threads of the pool.
    pub threads: usize,
    /// How many times the equations were compiled (1 when only initial
    /// values vary).
    pub compilations: usize,
}

/// `NAME=FROM:TO:COUNT` (grid) or `NAME=FROM:TO` (random design).
pub fn parse_axis(text: &str) -> Result<Axis, Diagnostic> {
    let hint = "--vary NAME=FROM:TO:COUNT, e.g. --vary \"l=0.5:2:16\" (COUNT may be left out with --samples)";
    let bad = |what: String| {
        Diagnostic::global(format!("`--vary {text}`: {what}"))
            .with_hint(hint)
            .with_kind(ErrorKind::bad_option("--vary"))
    };
    let (name, range) = text.split_once('=').ok_or_else(|| bad("no `=`".into()))?;
    let name = name.trim();
    if name.is_empty() {
        return Err(bad("no name before `=`".into()));
    }
    let parts: Vec<&str> = range.split(':').map(str::trim).collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(bad("the range is FROM:TO or FROM:TO:COUNT".into()));
    }
    let number = |s: &str| -> Result<f64, Diagnostic> {
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(bad(format!("`{s}` is not a number"))),
        }
    };
    let (from, to) = (number(parts[0])?, number(parts[1])?);
    let count = match parts.get(2) {
        Some(c) => c
            .parse::<usize>()
            .ok()
            .filter(|&c| (1..=MAX_SWEEP_RUNS).contains(&c))
            .ok_or_else(|| {
                bad(format!(
                    "COUNT `{c}` must be a whole number from 1 to {}",
                    crate::budget::grouped(MAX_SWEEP_RUNS)
                ))
            })?,
        None => 0,
    };
    Ok(Axis {
        name: name.to_string(),
        from,
        to,
        count,
    })
}

/// The values of every run, in order: a grid's product or random points.
pub fn design_points(axes: &[Axis], design: Design) -> Result<Vec<Vec<f64>>, Diagnostic> {
    let too_many = |n: String| {
        Diagnostic::global(format!(
            "{n} runs: more than {}",
            crate::budget::grouped(MAX_SWEEP_RUNS)
        ))
            .with_hint("fewer values per axis (COUNT), or fewer --samples; split the study into several sweeps")
            .with_kind(ErrorKind::bad_option("--vary"))
    };
    match design {
        Design::Grid => {
            let mut total: usize = 1;
            for a in axes {
                if a.count == 0 {
                    return Err(Diagnostic::global(format!(
                        "`--vary {}`: a grid needs COUNT, the number of values",
                        a.name
                    ))
                    .with_hint(format!(
                        "--vary \"{}={}:{}:10\", or draw random points with --samples N",
                        a.name, a.from, a.to
                    ))
                    .with_kind(ErrorKind::bad_option("--vary")));
                }
                total = total
                    .checked_mul(a.count)
                    .filter(|&t| t <= MAX_SWEEP_RUNS)
                    .ok_or_else(|| {
                        too_many(
                            axes.iter()
                                .map(|a| a.count.to_string())
                                .collect::<Vec<_>>()
                                .join(" × "),
                        )
                    })?;
            }
            let mut points = Vec::with_capacity(total);
            for mut k in 0..total {
                let mut p = vec![0.0; axes.len()];
                // the last axis varies fastest
                for (j, a) in axes.iter().enumerate().rev() {
                    let i = k % a.count;
                    k /= a.count;
                    p[j] = if a.count == 1 {
                        a.from
                    } else {
                        a.from + (a.to - a.from) * i as f64 / (a.count - 1) as f64
                    };
                }
                points.push(p);
            }
            Ok(points)
        }
        Design::Random { samples, seed } => {
            if samples == 0 {
                return Err(Diagnostic::global(
                    "`--samples 0`: a random design needs at least one run",
                )
                .with_hint("--samples 100 draws 100 random points in the box of the --vary ranges")
                .with_kind(ErrorKind::bad_option("--samples")));
            }
            if samples > MAX_SWEEP_RUNS {
                return Err(too_many(samples.to_string()));
            }
            let mut rng = SplitMix64::new(seed);
            Ok((0..samples)
                .map(|_| axes.iter().map(|a| rng.uniform(a.from, a.to)).collect())
                .collect())
        }
    }
}

/// Run `base` once per point of the design, `axes` overriding its `set`
/// and `init`, on `threads` threads (0: one per core; see
/// [`thread_count`]). `progress` is
/// called with the number of finished runs after each run.
pub fn sweep(
    prepared: &Prepared,
    base: &Request,
    axes: &[Axis],
    design: Design,
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Sweep, Diagnostic> {
    let params = prepared.parameters();
    let coordinates = prepared.coordinates().to_vec();
    let mut varies_parameters = false;
    for (k, a) in axes.iter().enumerate() {
        given_once(a, &axes[..k], base)?;
        let base_name = a.name.trim_end_matches('\'');
        if params.iter().any(|p| p == &a.name) {
            varies_parameters = true;
        } else if !coordinates.iter().any(|q| q == base_name) || a.name.len() - base_name.len() > 1
        {
            return Err(Diagnostic::global(format!(
                "`--vary {}`: `{}` is not a parameter, a coordinate or a velocity",
                a.name, a.name
            ))
            .with_hint(format!(
                "the parameters are {}; the coordinates {} (velocities are written q')",
                params.join(", "),
                coordinates.join(", ")
            ))
            .with_kind(ErrorKind::bad_option("--vary")));
        }
    }
    let points = design_points(axes, design)?;
    let request_at = |values: &[f64]| {
        let mut req = base.clone();
        req.progress = false;
        for (a, &v) in axes.iter().zip(values) {
            if params.contains(&a.name) {
                req.set.insert(a.name.clone(), v);
            } else {
                req.init.insert(a.name.clone(), v);
            }
        }
        req
    };
    // Validate once, on the first point: a missing value or a bad option
    // is one error, not one per run. Compiled once here when only initial
    // values vary; else each run compiles (and a run whose values make M
    // singular fails alone).
    let first = request_at(points.first().map(Vec::as_slice).unwrap_or(&[]));
    prepared.check(&first)?;
    let shared = if varies_parameters {
        None
    } else {
        Some(prepared.compile(&first)?)
    };
    let compilations = AtomicUsize::new(usize::from(shared.is_some()));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(thread_count(threads, points.len()))
        .build()
        .map_err(|e| Diagnostic::global(format!("cannot start the sweep's threads: {e}")))?;
    // the pool's threads work under this thread's budget (`--max-terms`):
    // a run compiles exactly (the accelerations) when parameters vary
    let limit = crate::budget::limit();
    let done = AtomicUsize::new(0);
    let start = Instant::now();
    let runs: Vec<(Vec<f64>, Result<Outcome, String>)> = pool.install(|| {
        points
            .into_par_iter()
            .map(|values| {
                let req = request_at(&values);
                let compiled = match &shared {
                    Some(c) => Ok(c.clone()),
                    None => {
                        compilations.fetch_add(1, Ordering::Relaxed);
                        crate::budget::within(limit, || prepared.compile(&req))
                            .unwrap_or_else(|e| Err(crate::diag::too_large(&e)))
                    }
                };
                let outcome = compiled
                    .and_then(|c| prepared.integrate(c, &req))
                    .map(|run| summary(&run, coordinates.len()))
                    .map_err(|d| d.message);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1);
                (values, outcome)
            })
            .collect()
    });
    Ok(Sweep {
        names: axes.iter().map(|a| a.name.clone()).collect(),
        coordinates,
        runs,
        seconds: start.elapsed().as_secs_f64(),
        threads: pool.current_num_threads(),
        compilations: compilations.into_inner(),
    })
}

/// A varied name is given by its `--vary` alone: once among the axes, and
/// not by `--set` or `--init` too (which of two values would a row's
/// column mean?).
fn given_once(axis: &Axis, earlier: &[Axis], base: &Request) -> Result<(), Diagnostic> {
    let name = &axis.name;
    let also = if earlier.iter().any(|e| &e.name == name) {
        "is varied twice"
    } else if base.set.contains_key(name) {
        "is also given by --set"
    } else if base.init.contains_key(name) {
        "is also given by --init"
    } else {
        return Ok(());
    };
    Err(
        Diagnostic::global(format!("`--vary {name}`: `{name}` {also}"))
            .with_hint("vary each name once, and leave it out of --set and --init")
            .with_kind(ErrorKind::bad_option("--vary")),
    )
}

/// The threads a sweep of `runs` runs uses for `requested` (0: one per
/// core): never more than the cores, nor than the runs (each thread costs
/// a stack, and CPU-bound runs gain nothing from more threads than cores).
pub fn thread_count(requested: usize, runs: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let wanted = if requested == 0 { cores } else { requested };
    wanted.min(cores).min(runs).max(1)
}

/// What a sweep keeps of one run.
fn summary(run: &Run, n: usize) -> Outcome {
    let last = run.rows.last();
    let energy = run.columns.iter().position(|c| c == "energy");
    let mut max_abs_q = vec![0.0f64; n];
    let mut energy_drift = energy.map(|_| 0.0f64);
    for row in &run.rows {
        for (k, m) in max_abs_q.iter_mut().enumerate() {
            *m = m.max(row[1 + k].abs());
        }
        if let (Some(j), Some(d)) = (energy, energy_drift.as_mut()) {
            *d = d.max((row[j] - run.rows[0][j]).abs());
        }
    }
    Outcome {
        status: run.solution.status.clone(),
        t: last.map_or(0.0, |r| r[0]),
        y: last.map_or_else(Vec::new, |r| r[1..1 + 2 * n].to_vec()),
        max_abs_q,
        energy_drift,
        steps: run.solution.stats.steps,
    }
}

/// The sweep as CSV: the varied values, `status`, `t`, the final state
/// (`q(t)`, `q'(t)`),
/// `max|q|` per coordinate, `energy_drift` (empty when not conserved),
/// `steps`; a failed run has its message in `status` and empty cells.
pub fn csv(s: &Sweep) -> String {
    let mut header: Vec<String> = s.names.clone();
    header.extend(["status".into(), "t".into()]);
    // the final state, q(t): the varied names may include q itself
    header.extend(s.coordinates.iter().map(|q| format!("{q}(t)")));
    header.extend(s.coordinates.iter().map(|q| format!("{q}'(t)")));
    header.extend(s.coordinates.iter().map(|q| format!("max|{q}|")));
    header.extend(["energy_drift".into(), "steps".into()]);
    let mut out = header.join(",") + "\n";
    let n = s.coordinates.len();
    for (values, outcome) in &s.runs {
        let mut cells: Vec<String> = values.iter().map(|v| format!("{v}")).collect();
        match outcome {
            Ok(o) => {
                cells.push(status_word(&o.status).into());
                cells.push(format!("{:.17e}", o.t));
                cells.extend(o.y.iter().chain(&o.max_abs_q).map(|x| format!("{x:.17e}")));
                cells.push(o.energy_drift.map_or(String::new(), |d| format!("{d:.3e}")));
                cells.push(o.steps.to_string());
            }
            Err(m) => {
                cells.push(format!("\"error: {}\"", m.replace('"', "'")));
                cells.extend(std::iter::repeat_n(String::new(), 1 + 3 * n + 2));
            }
        }
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A seed's points are SplitMix64's stream, axis by axis, run by run,
    /// bit for bit: `qdot sweep --samples 2 --seed 7` prints these values.
    #[test]
    fn a_random_design_is_the_seeded_stream() {
        let axes = [
            parse_axis("theta=0.1:3").expect("axis"),
            parse_axis("theta'=-1:1").expect("axis"),
        ];
        let design = Design::Random {
            samples: 2,
            seed: 7,
        };
        assert_eq!(
            design_points(&axes, design).expect("points"),
            [
                [1.2305062703346874, -0.9664234109436878],
                [2.712205973759962, 0.16586058605615617],
            ]
        );
    }
}
