//! The numeric studies on a resolved scene, in its context: `cycle`,
//! `response` and `floquet`, each as a typed report.

use super::commands::report;
use super::report::{CycleReport, CycleRun, FloquetReport, FloquetRun, FrequencyResponse};
use super::{Command, CommandOptions, Context, ResponseReport};
use crate::diag::{Diagnostic, ErrorKind};
use crate::poly::Var;
use crate::scene::given::{parse_ranges, GridAxis, CYCLE_OVER};
use crate::scene::Scene;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// `--over TEXT` of `cmd` as [`CommandOptions::over`]: `cycle`'s varied
/// quantity (`phi=0:360deg:73`), `response`'s frequency
/// (`Omega=0.5:2:301`), `floquet`'s one or two parameters
/// (`delta=-1:3:81,eps=0:2:41`).
pub fn parse_over(cmd: Command, text: &str) -> Result<Vec<GridAxis>, Diagnostic> {
    match cmd {
        Command::Cycle => parse_ranges(&CYCLE_OVER, text),
        Command::Response => Ok(vec![crate::simulate::response::parse_over(text)?]),
        Command::Floquet => crate::simulate::floquet::parse_over(text),
        _ => Err(no_over(cmd)),
    }
}

/// The error of an `over` that `cmd` does not take.
fn no_over(cmd: Command) -> Diagnostic {
    Diagnostic::global(format!("`qdot {}` takes no --over", cmd.name()))
        .with_hint("--over varies a quantity of `cycle`, `response` and `floquet`")
        .with_kind(ErrorKind::bad_option("--over"))
}

/// An error unless every axis of `over` has 1 to
/// [`crate::scene::given::MAX_GRID_POINTS`] values, and the grid as many
/// points at most (an `over` not read by [`parse_over`]).
fn bounded_grid(over: &[GridAxis]) -> Result<(), Diagnostic> {
    let max = crate::scene::given::MAX_GRID_POINTS;
    let total = over
        .iter()
        .try_fold(1usize, |t, a| t.checked_mul(a.count).filter(|&t| t >= 1));
    match total {
        Some(t) if t <= max => Ok(()),
        _ => Err(Diagnostic::global(format!(
            "--over: every range has 1 to {} values, and the grid as many points at most",
            crate::budget::grouped(max)
        ))
        .with_kind(ErrorKind::bad_option("--over"))),
    }
}

/// `cycle`: the mechanism of `scene` over `opts.over` (one axis).
pub(super) fn cycle(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<CycleReport, Diagnostic> {
    let [over] = opts.over.as_slice() else {
        return Err(Diagnostic::global(format!(
            "`qdot cycle` varies one quantity, and {} were given",
            opts.over.len()
        ))
        .with_hint(CYCLE_OVER.hint)
        .with_kind(ErrorKind::bad_option("--over")));
    };
    bounded_grid(&opts.over)?;
    let req = crate::cycle::CycleRequest {
        over: over.clone(),
        set: opts.set.clone(),
        guess: opts.guess.clone(),
    };
    let table = crate::cycle::cycle(scene, &req)?;
    let shown = opts
        .columns
        .as_deref()
        .map(|c| table.select(c))
        .transpose()?;
    let run = CycleRun {
        degrees: is_angle(scene, &over.name),
        table,
        shown,
    };
    Ok(report(ctx, scene, run))
}

/// Whether the coordinate `name` is an angle: annotated `angle`, or a
/// body's angle in the plane.
fn is_angle(scene: &Scene, name: &str) -> bool {
    let Some(c) = scene.coordinates.iter().find(|c| c.name == name) else {
        return false;
    };
    if let Some(d) = &c.dimension {
        return d.trim() == "angle" || d.trim() == "rad";
    }
    let q = crate::expr::Expr::coord(name, 0);
    scene.bodies.iter().any(|b| {
        matches!(&b.mass_properties.turning,
            Some(crate::scene::Turning::Plane { angle, .. }) if angle.equals(&q))
    })
}

/// `response`: exact without `opts.over`, else swept over its `Omega`.
pub(super) fn response(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<ResponseReport, Diagnostic> {
    use crate::solve::response::{self as exact, ForcedSystem};
    let set = &opts.set;
    let study = match opts.over.as_slice() {
        [] => {
            exact::check_time_dependence(scene)?;
            crate::scene::given::parameter_signs(scene, set)?;
            crate::scene::given::set_names_are_parameters(scene, set)?;
            let at = at_values(scene, opts)?;
            let md = crate::solve::oscillations::modes(scene, at.as_deref(), set)?;
            let r = exact::response(ForcedSystem::from_modes(&md)?, set)?;
            FrequencyResponse::Exact(Box::new((md, r, set.clone())))
        }
        [over] => {
            bounded_grid(&opts.over)?;
            let written = format!("{}={}:{}:{}", over.name, over.from, over.to, over.count);
            crate::simulate::response::check_axis(over, &written)?;
            crate::scene::given::set_names_are_parameters(scene, set)?;
            let at = at_values(scene, opts)?;
            let sys = ForcedSystem::of_scene(scene, at.as_deref())?;
            FrequencyResponse::Swept(
                crate::simulate::response::CompiledResponse::new(scene, &sys, set)?.run(over),
            )
        }
        _ => {
            return Err(
                Diagnostic::global("`qdot response` sweeps one frequency, `Omega`")
                    .with_hint(crate::scene::given::RESPONSE_OVER.hint)
                    .with_kind(ErrorKind::bad_option("--over")),
            )
        }
    };
    Ok(report(ctx, scene, study))
}

/// `--at`'s values in `scene`, when given.
fn at_values(
    scene: &Scene,
    opts: &CommandOptions,
) -> Result<Option<Vec<crate::expr::Expr>>, Diagnostic> {
    opts.at
        .as_deref()
        .map(|a| scene.coordinate_values(a))
        .transpose()
}

/// `floquet`: the scene linearized about `opts.at`, analysed at the `--set`
/// values, or at every point of the grid of `opts.over` (on every core).
pub(super) fn floquet(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<FloquetReport, Diagnostic> {
    let req = crate::floquet::FloquetRequest {
        at: opts.at.clone(),
        functions: opts.functions.clone(),
        period: opts.period,
        max_steps: opts.max_steps,
    };
    let over = &opts.over;
    if over.len() > 2 {
        return Err(Diagnostic::global(format!(
            "`qdot floquet` varies one or two parameters, not {}",
            over.len()
        ))
        .with_hint(crate::scene::given::FLOQUET_OVER.hint)
        .with_kind(ErrorKind::bad_option("--over")));
    }
    bounded_grid(over)?;
    let prepared = crate::floquet::prepare(scene, &req)?;
    let mut set = opts.set.clone();
    for a in over {
        if !scene.parameters.iter().any(|p| p.name == a.name) {
            let names: Vec<&str> = scene.parameters.iter().map(|p| p.name.as_str()).collect();
            return Err(Diagnostic::global(format!(
                "`--over {}=…`: `{}` is not a parameter of the scene",
                a.name, a.name
            ))
            .with_hint(format!("the parameters are {}", names.join(", ")))
            .with_kind(ErrorKind::bad_option("--over")));
        }
        set.insert(a.name.clone(), a.from);
    }
    let inertial = prepared.inertial_parameters(scene);
    let base = crate::scene::given::parameter_map(scene, &set, &inertial)?;
    if over.is_empty() {
        let f = prepared.analyse(&base)?;
        let run = FloquetRun {
            prepared,
            axes: Vec::new(),
            points: vec![(Vec::new(), Ok(f))],
        };
        return Ok(report(ctx, scene, run));
    }
    let vars: Vec<Var> = over
        .iter()
        .map(|a| crate::expr::atom::param(&a.name))
        .collect();
    let total: usize = over.iter().map(|a| a.count).product();
    let grid: Vec<Vec<f64>> = (0..total)
        .map(|i| {
            let first = i % over[0].count;
            let mut v = vec![over[0].value(first)];
            if let Some(b) = over.get(1) {
                v.push(b.value(i / over[0].count));
            }
            v
        })
        .collect();
    // every point's values checked as `--set` values are, before any run
    for v in &grid {
        for (a, x) in over.iter().zip(v) {
            set.insert(a.name.clone(), *x);
        }
        crate::scene::given::parameter_map(scene, &set, &inertial)
            .map_err(|d| over_value_error(d, over))?;
    }
    // `--threads`, as every parallel command takes it
    let pool = super::thread_pool(opts.threads, total)?;
    let points = pool.install(|| {
        grid.into_par_iter()
            .map(|v| {
                let mut values: FxHashMap<Var, f64> = base.clone();
                for (var, x) in vars.iter().zip(&v) {
                    values.insert(*var, *x);
                }
                let r = prepared.analyse(&values).map_err(|d| d.message.clone());
                (v, r)
            })
            .collect()
    });
    let run = FloquetRun {
        prepared,
        axes: over.clone(),
        points,
    };
    Ok(report(ctx, scene, run))
}

/// A grid point's values refused: the error, said of the `--over` ranges.
fn over_value_error(d: Diagnostic, over: &[GridAxis]) -> Diagnostic {
    let ranges: Vec<String> = over
        .iter()
        .map(|a| format!("{}={}:{}:{}", a.name, a.from, a.to, a.count))
        .collect();
    Diagnostic::global(format!(
        "`--over {}` reaches values qdot refuses: {}",
        ranges.join(","),
        d.message
    ))
    .with_hint(
        d.hint
            .as_deref()
            .unwrap_or("keep the ranges within the scene's assumptions"),
    )
    .with_kind(ErrorKind::bad_option("--over"))
}
