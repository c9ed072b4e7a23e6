//! The numeric commands on a resolved scene (`simulate`, `sweep`,
//! `codegen`), what their reports say beside the table, and the one
//! thread-pool policy of every parallel command.

use super::commands::report;
use super::report::{GeneratedCode, Simulation, SweepStudy};
use super::{CodegenReport, CommandOptions, Context, SimulateReport, SweepReport};
use crate::diag::{Diagnostic, ErrorKind};
use crate::scene::Scene;
use crate::simulate::codegen::{codegen_scene, CodegenRequest};
use crate::simulate::run::{self, Prepared, Request};
use crate::simulate::sweep::{design_points, sweep_within, Axis, Design};
use crate::simulate::Status;
use std::sync::Arc;

/// `sweep`'s options beyond the run's.
#[derive(Clone, Debug, Default)]
pub struct SweepOptions {
    /// `--vary NAME=FROM:TO:COUNT`, in order.
    pub axes: Vec<Axis>,
    /// A grid, or `--samples N` random points (`--seed`).
    pub design: Design,
    /// `--threads` ([`thread_count`]: 0 is one per core).
    pub threads: usize,
    /// Told how many runs are done, and of how many (a progress bar).
    pub progress: Option<ProgressHook>,
}

/// A callback told how many of a command's runs are done and of how many
/// (first with 0 before any run, then after each run, from any thread).
#[derive(Clone)]
pub struct ProgressHook(Arc<dyn Fn(usize, usize) + Send + Sync>);

impl ProgressHook {
    /// A hook calling `f(done, total)`.
    pub fn new(f: impl Fn(usize, usize) + Send + Sync + 'static) -> ProgressHook {
        ProgressHook(Arc::new(f))
    }
}

impl std::fmt::Debug for ProgressHook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ProgressHook")
    }
}

/// The threads a parallel command uses for `jobs` independent jobs when
/// `requested` are asked for (`--threads`; 0: one per core): never more
/// than the cores (the jobs are CPU-bound: more threads gain nothing), nor
/// than the jobs (each thread costs a stack), and at least one.
pub fn thread_count(requested: usize, jobs: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let wanted = if requested == 0 { cores } else { requested };
    wanted.min(cores).min(jobs).max(1)
}

/// A rayon pool of [`thread_count`]`(requested, jobs)` threads.
pub fn thread_pool(requested: usize, jobs: usize) -> Result<rayon::ThreadPool, Diagnostic> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(thread_count(requested, jobs))
        .build()
        .map_err(|e| {
            Diagnostic::global(format!("cannot start the threads: {e}"))
                .with_kind(crate::diag::ErrorKind::Internal)
        })
}

/// The run of `simulate`/`sweep`: the options' request with the `--set`
/// values.
fn request(opts: &CommandOptions) -> Request {
    Request {
        set: opts.set.clone(),
        ..opts.simulate.clone()
    }
}

/// `simulate` on `scene` (in `ctx`).
pub(super) fn simulate(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<SimulateReport, Diagnostic> {
    let request = request(opts);
    let run = Prepared::of_scene(Arc::clone(scene), &request.functions)?.run(&request)?;
    Ok(report(ctx, scene, Simulation { run, request }))
}

/// `sweep` on `scene` (in `ctx`, its runs too).
pub(super) fn sweep(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<SweepReport, Diagnostic> {
    let progress = |done: usize, total: usize| {
        if let Some(p) = &opts.sweep.progress {
            (p.0)(done, total);
        }
    };
    sweep_study(ctx, scene, request(opts), &opts.sweep, &progress)
}

/// `sweep` of `base` on `scene` as `o` asks (its `progress` aside: told
/// to `progress`).
pub(super) fn sweep_study(
    ctx: &Context,
    scene: &Arc<Scene>,
    base: Request,
    o: &SweepOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<SweepReport, Diagnostic> {
    let prepared = Prepared::of_scene(Arc::clone(scene), &base.functions)?;
    // the design's errors before the names': as the command line always said
    let total = design_points(&o.axes, o.design)?.len();
    progress(0, total);
    let tick = |done: usize| progress(done, total);
    let sweep = sweep_within(ctx, &prepared, &base, &o.axes, o.design, o.threads, &tick)?;
    let axes = o.axes.clone();
    Ok(report(ctx, scene, SweepStudy { sweep, base, axes }))
}

/// `codegen` on `scene` (in `ctx`).
pub(super) fn codegen(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<CodegenReport, Diagnostic> {
    let request = CodegenRequest {
        set: opts.set.clone(),
        ..opts.codegen.clone()
    };
    let code = codegen_scene(scene, &request)?;
    Ok(report(ctx, scene, GeneratedCode { code, request }))
}

impl Simulation {
    /// Which velocities the run started at 0 because `--init` left them
    /// out, or `None`.
    pub fn zero_velocities_note(&self) -> Option<String> {
        let coordinates = self.run.columns.iter().filter_map(|c| c.strip_suffix('\''));
        run::zero_velocities_note(coordinates, |v| self.request.init.contains_key(v))
    }

    /// What the integrator noticed on the way: a stiff problem, a
    /// `--stop-when` condition that changed sign through a pole.
    pub fn run_warnings(&self) -> Vec<Diagnostic> {
        let s = &self.run.solution;
        let stiff = s.stiff_at.map(|t| Diagnostic::global_warning(format!(
            "the problem looks stiff from t = {t:.6e} on (Hairer's test); --method radau5 integrates it in far fewer steps"
        )));
        let poles = s.event_poles.iter().map(|t| Diagnostic::global_warning(format!(
            "the --stop-when condition changed sign at t = {t:.6e} without passing through zero (a pole or a jump): not an event, the run went on"
        )));
        stiff.into_iter().chain(poles).collect()
    }

    /// Where the `--stop-when` event ended the run, if it did.
    pub fn event_note(&self) -> Option<String> {
        match self.run.solution.status {
            Status::Event { t } => Some(format!(
                "stopped at t = {t:.15e}, where the --stop-when condition changes sign"
            )),
            _ => None,
        }
    }

    /// The error of a run that stopped before `--t-end` for want of steps
    /// or of a finite value (its rows up to there are the table), or
    /// `None`.
    pub fn stopped_early(&self) -> Option<Diagnostic> {
        let status = &self.run.solution.status;
        let (t, hint) = match *status {
            Status::Done | Status::Event { .. } => return None,
            Status::TooManySteps { t } => (t, format!("raise --max-steps (it is {}), loosen --rtol and --atol, or use --method radau5 if the problem is stiff", self.request.max_steps)),
            Status::StepTooSmall { t } => (t, "the solution may blow up there; check the scene and the initial values, or loosen the tolerances".to_string()),
            Status::NotFinite { t } => (t, self.run.not_finite_reason()),
        };
        Some(
            Diagnostic::global(format!(
                "the integration stopped early: {} at t = {t:.6e}",
                run::status_word(status),
            ))
            .with_hint(hint)
            .with_kind(ErrorKind::Integration),
        )
    }
}

impl SweepStudy {
    /// Which velocities every run started at 0 (given neither by `--init`
    /// nor by `--vary`), or `None`.
    pub fn zero_velocities_note(&self) -> Option<String> {
        let given =
            |v: &str| self.base.init.contains_key(v) || self.axes.iter().any(|a| a.name == v);
        run::zero_velocities_note(self.sweep.coordinates.iter().map(String::as_str), given)
    }

    /// The warning that some runs failed (their rows say why), or `None`.
    pub fn failures(&self) -> Option<Diagnostic> {
        let runs = &self.sweep.runs;
        let failed = runs.iter().filter(|(_, r)| r.is_err()).count();
        (failed > 0).then(|| {
            Diagnostic::global_warning(format!(
                "{failed} of {} runs failed (their rows say why)",
                runs.len()
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_are_never_more_than_the_cores_or_the_jobs() {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        assert_eq!(thread_count(0, 1_000), cores);
        assert_eq!(thread_count(1_000, 1_000), cores);
        assert_eq!(thread_count(0, 1), 1);
        assert_eq!(thread_count(1, 1_000), 1);
        assert_eq!(thread_count(5, 0), 1);
    }
}
