//! Each command on a resolved scene, in its context: what it computes,
//! as a typed report.

use super::report::{AnyReport, Derived, Forces, LatexRequest, Oscillations, Report, Solved};
use super::{Command, CommandOptions, Context};
use crate::diag::{Diagnostic, ErrorKind};
use crate::scene::Scene;
use crate::solve::equilibrium::Values;
use crate::solve::oscillations as osc;
use std::sync::Arc;

/// `cmd` on `scene` (already in `ctx`).
pub(super) fn run_scene(
    ctx: &Context,
    cmd: Command,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<AnyReport, Diagnostic> {
    // `equilibrium` and `modes` check their `--set` themselves (they are
    // also called directly, by `app::equilibria` and `app::modes`); the
    // numeric studies check theirs as they read them; simulate, sweep and
    // codegen take any sign: a value is a number to compute with)
    if !matches!(
        cmd,
        Command::Equilibrium
            | Command::Modes
            | Command::Cycle
            | Command::Response
            | Command::Floquet
            | Command::Simulate
            | Command::Sweep
            | Command::Codegen
    ) {
        crate::scene::given::parameter_signs(scene, &opts.set)?;
    }
    Ok(match cmd {
        Command::Derive => AnyReport::Derive(derive(ctx, scene)?),
        Command::Solve => AnyReport::Solve(solve(ctx, scene)?),
        Command::Forces => AnyReport::Forces(forces(ctx, scene)?),
        Command::Equilibrium => AnyReport::Equilibrium(match &opts.steady {
            Some(list) => steady_motions(ctx, scene, list, &opts.set)?,
            None => equilibria(ctx, scene, &opts.set)?,
        }),
        Command::Modes => AnyReport::Modes(modes(ctx, scene, opts)?),
        Command::Hamilton => AnyReport::Hamilton(hamilton(ctx, scene)?),
        Command::Integrals => AnyReport::Integrals(integrals(ctx, scene)?),
        Command::Latex => {
            crate::scene::given::set_names_are_parameters(scene, &opts.set)?;
            AnyReport::Latex(report(
                ctx,
                scene,
                LatexRequest {
                    steps: opts.steps,
                    standalone: opts.standalone,
                    title: opts.title.clone(),
                    set: opts.set.clone(),
                },
            ))
        }
        Command::Check => AnyReport::Check(report(ctx, scene, scene.dimension_report()?)),
        Command::Cycle => AnyReport::Cycle(super::studies::cycle(ctx, scene, opts)?),
        Command::Response => AnyReport::Response(super::studies::response(ctx, scene, opts)?),
        Command::Floquet => AnyReport::Floquet(super::studies::floquet(ctx, scene, opts)?),
        Command::Simulate => AnyReport::Simulate(super::simulation::simulate(ctx, scene, opts)?),
        Command::Sweep => AnyReport::Sweep(super::simulation::sweep(ctx, scene, opts)?),
        Command::Codegen => AnyReport::Codegen(super::simulation::codegen(ctx, scene, opts)?),
    })
}

/// `result` as a report on `scene`, with the scene's warnings.
pub(super) fn report<T>(ctx: &Context, scene: &Arc<Scene>, result: T) -> Report<T> {
    Report::new(
        result,
        Arc::clone(scene),
        ctx.clone(),
        scene.warnings.clone(),
    )
}

pub(super) fn derive(ctx: &Context, scene: &Arc<Scene>) -> Result<Report<Derived>, Diagnostic> {
    let lagrange = scene.lagrange()?;
    Ok(report(ctx, scene, Derived { lagrange }))
}

/// `solve`: the accelerations (and multipliers, and the constraints'
/// reactions) and the `solve` blocks' solutions.
pub(super) fn solve(ctx: &Context, scene: &Arc<Scene>) -> Result<Report<Solved>, Diagnostic> {
    let has_dynamics = scene.has_dynamics();
    if !has_dynamics && scene.systems.is_empty() {
        // the usual error for a scene with nothing to solve
        scene.lagrange()?;
    }
    if has_dynamics && crate::solve::kinetostatic::is_driven_mechanism(scene) {
        let l = scene.lagrange()?;
        let reactions = crate::solve::kinetostatic::mechanism_reactions(scene, &l)?;
        let blocks = crate::solve::system::solve_scene(scene)?;
        return Ok(report(
            ctx,
            scene,
            Solved {
                dynamics: None,
                reactions: Vec::new(),
                blocks,
                mechanism: Some(Box::new((l, reactions))),
            },
        ));
    }
    let dynamics = if has_dynamics {
        let l = scene.lagrange()?;
        let acc = l.accelerations()?;
        Some((l, acc))
    } else {
        None
    };
    let reactions = match &dynamics {
        Some((_, acc)) => crate::solve::constrained::reaction_forces(scene, acc)?,
        None => Vec::new(),
    };
    let blocks = crate::solve::system::solve_scene(scene)?;
    Ok(report(
        ctx,
        scene,
        Solved {
            dynamics,
            reactions,
            blocks,
            mechanism: None,
        },
    ))
}

fn forces(ctx: &Context, scene: &Arc<Scene>) -> Result<Report<Forces>, Diagnostic> {
    let forces = crate::mechanics::expanded_generalized_forces(scene)?;
    if scene.coordinates.is_empty() {
        return Err(Diagnostic::global(
            "the scene declares no coordinates, so there are no generalized forces",
        )
        .with_hint("declare the generalized coordinates with `coordinates q1, q2, …`")
        .with_kind(ErrorKind::NothingToSolve));
    }
    let coordinates = scene.coordinates.iter().map(|c| c.name.clone()).collect();
    Ok(report(
        ctx,
        scene,
        Forces {
            coordinates,
            forces,
        },
    ))
}

pub(super) fn equilibria(
    ctx: &Context,
    scene: &Arc<Scene>,
    set: &Values,
) -> Result<Report<crate::solve::equilibrium::Equilibria>, Diagnostic> {
    crate::scene::given::parameter_signs(scene, set)?;
    crate::scene::given::set_names_are_parameters(scene, set)?;
    let eq = crate::solve::equilibrium::equilibria(scene, set)?;
    Ok(report(ctx, scene, eq))
}

/// `equilibrium --steady q,…`: the steady motions with those coordinates
/// turning.
fn steady_motions(
    ctx: &Context,
    scene: &Arc<Scene>,
    steady: &str,
    set: &Values,
) -> Result<Report<crate::solve::equilibrium::Equilibria>, Diagnostic> {
    crate::scene::given::parameter_signs(scene, set)?;
    crate::scene::given::set_names_are_parameters(scene, set)?;
    let steady = scene.steady_coordinates(steady)?;
    let eq = crate::solve::steady::steady_motions(scene, &steady, set)?;
    Ok(report(ctx, scene, eq))
}

/// `modes`: about `--at` (or the equilibrium qdot finds), with the free
/// response to `--init`, exact when it can be, else numeric at the `--set`
/// values.
pub(super) fn modes(
    ctx: &Context,
    scene: &Arc<Scene>,
    opts: &CommandOptions,
) -> Result<Report<Oscillations>, Diagnostic> {
    let set = &opts.set;
    crate::scene::given::parameter_signs(scene, set)?;
    crate::scene::given::set_names_are_parameters(scene, set)?;
    let reference = reference(scene, opts)?;
    // an equilibrium is a constant position
    if let Some(vals) = &reference.at {
        for (c, v) in scene.coordinates.iter().zip(vals) {
            if v.is_time_dependent() {
                return Err(Diagnostic::global(format!(
                    "`--at {}={}`: an equilibrium is a constant position, and this changes with time",
                    c.name,
                    crate::expr::print::input(v)
                ))
                .with_hint("give the coordinates constant values: --at theta=0 (the motion about a moving state is not small oscillations)")
                .with_kind(ErrorKind::bad_option("--at")));
            }
        }
    }
    let md = crate::solve::steady::hint_for_free_symbols(osc::modes_about(scene, &reference, set)?);
    let (free, numeric) = match &opts.init {
        Some(i) => {
            let (q0, v0) = scene.initial_conditions(i)?;
            match osc::free_response(&md, &q0, &v0) {
                Ok(f) => (Some(f), None),
                Err(_) if !md.gyroscopic && !set.is_empty() => {
                    (None, Some(osc::numeric_free_response(&md, set, &q0, &v0)?))
                }
                Err(e) => return Err(e),
            }
        }
        None => (None, None),
    };
    let mut r = report(
        ctx,
        scene,
        Oscillations {
            modes: md,
            set: set.clone(),
            free,
            numeric,
            standalone: opts.standalone.then(|| opts.title.clone()),
        },
    );
    let clashes = matrix_name_clashes(scene, &r.result.modes);
    r.add_warnings(clashes);
    Ok(r)
}

/// What `modes` linearizes about: `--at` (positions, and the rates of a
/// steady motion) and `--steady`.
fn reference(scene: &Scene, opts: &CommandOptions) -> Result<osc::Reference, Diagnostic> {
    let (at, rates) = match &opts.at {
        Some(a) => {
            let v = scene.motion_values(a)?;
            (Some(v.positions), v.rates)
        }
        None => (None, Vec::new()),
    };
    let mut steady: Vec<(usize, crate::expr::Expr)> = match &opts.steady {
        Some(s) => scene
            .steady_coordinates(s)?
            .into_iter()
            .map(|k| {
                (
                    k,
                    crate::solve::steady::rate_symbol(&scene.coordinates[k].name),
                )
            })
            .collect(),
        None => Vec::new(),
    };
    for (k, rate) in rates {
        match steady.iter_mut().find(|(i, _)| *i == k) {
            Some(s) => s.1 = rate,
            None => steady.push((k, rate)),
        }
    }
    steady.sort_by_key(|(k, _)| *k);
    Ok(osc::Reference::at(at.as_deref())
        .steady(steady)
        .with_values(&opts.set))
}

pub(super) fn hamilton(
    ctx: &Context,
    scene: &Arc<Scene>,
) -> Result<Report<crate::mechanics::Hamiltonian>, Diagnostic> {
    let h = crate::mechanics::Hamiltonian::derive(scene)?;
    Ok(report(ctx, scene, h))
}

pub(super) fn integrals(
    ctx: &Context,
    scene: &Arc<Scene>,
) -> Result<Report<crate::mechanics::Integrals>, Diagnostic> {
    let i = crate::mechanics::Integrals::find(scene)?;
    Ok(report(ctx, scene, i))
}

/// The names `modes` gives its own matrices: a parameter with one of them
/// would read as the matrix in M·q̈ + C·q̇ + K·q = f(t).
const MODES_MATRIX_NAMES: [(&str, &str); 3] = [("M", "mass"), ("C", "damping"), ("K", "stiffness")];

/// A warning for each parameter named like one of `modes`' matrices and
/// written in that matrix's entries: then the output reads as a matrix
/// defined by itself (the sleeping top's C = [[0, C·Ω], [−C·Ω, 0]], a
/// mass M whose M = [M]). Elsewhere the name is told apart by where it
/// stands (a top's mass M in K's entries, its axial moment C in a scene
/// whose C matrix is zero), and a warning on every gyroscope scene would
/// teach users to ignore it.
fn matrix_name_clashes(scene: &Scene, md: &osc::Modes) -> Vec<Diagnostic> {
    scene
        .parameters
        .iter()
        .filter_map(|p| {
            let (_, what) = MODES_MATRIX_NAMES.iter().find(|(n, _)| *n == p.name)?;
            let matrix = match p.name.as_str() {
                "M" => &md.mass,
                "C" => &md.damping,
                _ => &md.stiffness,
            };
            let v = crate::expr::atom::param(&p.name);
            if !matrix.iter().flatten().any(|e| e.depends_on(v)) {
                return None;
            }
            Some(
                Diagnostic::warning(
                    p.span,
                    format!(
                        "the parameter `{}` has the name of the {what} matrix {} of `modes`' output, and is in its entries",
                        p.name, p.name
                    ),
                )
                .with_hint(format!(
                    "the output writes M·q̈ + C·q̇ + K·q = f(t); a name like {}0 tells them apart",
                    p.name
                )),
            )
        })
        .collect()
}
