//! `qdot sweep`: one scene, many runs, on every core.
//!
//! A parameter study (a stability chart over two parameters) or a
//! Monte-Carlo study over initial conditions: the scene is parsed and
//! derived once ([`Prepared`]); when only initial values vary it is also
//! compiled once and each run clones the compiled program; when parameters
//! vary each run compiles for its values (microseconds to milliseconds).
//! The runs are spread over a rayon pool; each keeps a summary, not its
//! trajectory, so memory stays O(runs).

use super::run::{Prepared, Request, Run};
use super::Status;
use crate::app::Context;
use crate::diag::{Diagnostic, ErrorKind};
use qdot_exact::rng::SplitMix64;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The most runs of one `qdot sweep` (grid points or `--samples`): each
/// keeps its summary (final state, max |q|, energy drift) in memory.
pub const MAX_SWEEP_RUNS: usize = 1_000_000;

/// `sweep --vary l=0.5:2:16` (one range a `--vary`; COUNT may be left out
/// with `--samples`).
pub const SWEEP_VARY: crate::scene::given::RangeSyntax = crate::scene::given::RangeSyntax {
    option: "--vary",
    hint: "--vary NAME=FROM:TO:COUNT, e.g. --vary \"l=0.5:2:16\" (COUNT may be left out with --samples)",
    max_ranges: 1,
    too_many: "one name varies per --vary",
    count_optional: true,
    max_points: MAX_SWEEP_RUNS,
};

/// One varied name: a parameter, a coordinate (`theta`) or a velocity
/// (`theta'`), from `from` to `to` in `count` evenly spaced values, ends
/// included, on a grid (1: `from` alone); a random design ignores `count`
/// (0 when `--vary` leaves it out).
pub use crate::scene::given::GridAxis as Axis;

/// How the runs' values are chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Design {
    /// Every combination of the axes' values (the first axis varies slowest).
    #[default]
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

/// `NAME=FROM:TO:COUNT` (grid) or `NAME=FROM:TO` (random design): the one
/// range reader, [`crate::scene::given::parse_ranges`] with [`SWEEP_VARY`].
pub fn parse_axis(text: &str) -> Result<Axis, Diagnostic> {
    crate::scene::given::parse_ranges(&SWEEP_VARY, text)?
        .into_iter()
        .next()
        .ok_or_else(|| {
            Diagnostic::global(format!("`--vary {text}`: no range"))
                .with_hint(SWEEP_VARY.hint)
                .with_kind(ErrorKind::bad_option("--vary"))
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
/// [`crate::app::thread_count`]), under the work budget of the calling
/// thread. `progress` is called with the number of finished runs after
/// each run.
pub fn sweep(
    prepared: &Prepared,
    base: &Request,
    axes: &[Axis],
    design: Design,
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Sweep, Diagnostic> {
    let ctx = Context::new().with_max_terms(crate::budget::limit());
    sweep_within(&ctx, prepared, base, axes, design, threads, progress)
}

/// [`sweep`] with every run in `ctx` (its budget, and the scene's
/// assumptions on the pool's threads too).
pub fn sweep_within(
    ctx: &Context,
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
    let pool = crate::app::thread_pool(threads, points.len())?;
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
                        // the pool's threads work in the context too: a run
                        // compiles exactly (the accelerations) when parameters vary
                        ctx.run(|| prepared.compile(&req))
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

pub use crate::app::thread_count;

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

// the writers at their first paths, for library users
pub use crate::output::sweep::{csv, json, SweepJson, SweepRunJson};

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
