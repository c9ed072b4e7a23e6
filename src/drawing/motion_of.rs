//! The motions [`super::motion`] draws: a simulated run
//! (`simulate --animate`) and each mode shape about the equilibrium
//! (`modes --animate`).

use super::motion::{page, page_data, thinned, Motion, Stage};
use crate::app::Oscillations;
use crate::diag::ErrorKind;
use crate::scene::Scene;
use crate::simulate::run::Run;
use crate::solve::equilibrium::Values;
use crate::Diagnostic;
use crate::Expr;
use serde_json::Value as Json;

/// Frames of one period of a mode.
const MODE_FRAMES: usize = 72;
/// A mode's largest displacement of a point, as a fraction of the
/// drawing's size.
const MODE_REACH: f64 = 0.12;

/// The data of `simulate --animate`'s page: the run's rows (its plot
/// rows when it has them: denser) drawn.
pub fn run_data(
    scene: &Scene,
    run: &Run,
    set: &Values,
    title: &str,
    subtitle: &str,
) -> Result<Json, Diagnostic> {
    let stage = Stage::of_scene(scene)?;
    let rows = if run.plot_rows.is_empty() {
        &run.rows
    } else {
        &run.plot_rows
    };
    let column = |name: &str| run.columns.iter().position(|c| c == name);
    let q: Vec<Option<usize>> = scene.coordinates.iter().map(|c| column(&c.name)).collect();
    let qd: Vec<Option<usize>> = scene
        .coordinates
        .iter()
        .map(|c| column(&format!("{}'", c.name)))
        .collect();
    let rows = thinned(rows);
    let pick = |row: &[f64], at: &[Option<usize>]| -> Vec<f64> {
        at.iter()
            .map(|i| i.and_then(|i| row.get(i).copied()).unwrap_or(f64::NAN))
            .collect()
    };
    let motion = Motion {
        label: "the run".to_string(),
        periodic: false,
        times: rows.iter().map(|r| r[0]).collect(),
        states: rows.iter().map(|r| (pick(r, &q), pick(r, &qd))).collect(),
        set,
    };
    page_data(&stage, scene, title, subtitle, &[motion])
}

/// `simulate --animate`'s page.
pub fn run_page(
    scene: &Scene,
    run: &Run,
    set: &Values,
    title: &str,
    subtitle: &str,
) -> Result<String, Diagnostic> {
    Ok(page(&run_data(scene, run, set, title, subtitle)?))
}

fn refuse(why: &str, hint: &str) -> Diagnostic {
    Diagnostic::global(format!("cannot animate the modes: {why}"))
        .with_hint(hint)
        .with_kind(ErrorKind::bad_option("--animate"))
}

/// Every numeric value of `e` at `set`.
fn numeric(e: &Expr, set: &Values) -> Option<f64> {
    e.eval_f64(&|a| match a {
        crate::expr::atom::Atom::Param(n) => set.get(&**n).copied(),
        _ => None,
    })
    .filter(|v| v.is_finite())
}

/// The data of `modes --animate`'s page: each mode's shape oscillating
/// about the equilibrium over one period, at the `--set` values.
pub fn modes_data(
    scene: &Scene,
    osc: &Oscillations,
    title: &str,
    subtitle: &str,
) -> Result<Json, Diagnostic> {
    let m = &osc.modes;
    if m.gyroscopic || m.steady.is_some() || !m.dependent.is_empty() {
        return Err(refuse(
            "the modes are about a steady motion, gyroscopic or constrained",
            "animate a motion with `qdot simulate FILE --animate run.html` instead",
        ));
    }
    let set = &osc.set;
    let matrix = |x: &[Vec<Expr>]| -> Option<Vec<Vec<f64>>> {
        x.iter()
            .map(|r| r.iter().map(|e| numeric(e, set)).collect())
            .collect()
    };
    let (Some(mass), Some(stiffness), Some(at)) = (
        matrix(&m.mass),
        matrix(&m.stiffness),
        m.at.iter()
            .map(|e| numeric(e, set))
            .collect::<Option<Vec<f64>>>(),
    ) else {
        return Err(refuse(
            "the mode shapes need every parameter's value",
            "give them with --set: --set m=1,l=1,g=9.81",
        ));
    };
    let eigen = crate::solve::eigen::generalized_symmetric(&stiffness, &mass)
        .map_err(|e| refuse(&e.to_string(), "check that M is positive definite there"))?;
    let stage = Stage::of_scene(scene)?;
    let names: Vec<&str> = scene.coordinates.iter().map(|c| &*c.name).collect();
    let index: Vec<Option<usize>> = names
        .iter()
        .map(|n| m.coordinates.iter().position(|c| c == n))
        .collect();
    let zeros = vec![0.0; names.len()];
    // q0 + s·v in the scene's coordinates
    let state = |v: &[f64], s: f64| -> Vec<f64> {
        index
            .iter()
            .map(|i| i.map_or(0.0, |i| at[i] + s * v[i]))
            .collect()
    };
    let rest = stage
        .pose(scene, set, &state(&zeros, 0.0), &zeros, 0.0)
        .ok_or_else(|| {
            refuse(
                "the equilibrium's positions have no finite value",
                "check the --set and --at values",
            )
        })?;
    let size = rest
        .points
        .iter()
        .flatten()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(1e-9);
    let mut motions = Vec::new();
    for (k, (w2, v)) in eigen.values.iter().zip(&eigen.vectors).enumerate() {
        let largest = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if largest == 0.0 {
            continue;
        }
        let unit: Vec<f64> = v.iter().map(|x| x / largest).collect();
        // how far the points move per unit of the mode, by a small step
        let h = 1e-6;
        let moved = stage.pose(scene, set, &state(&unit, h), &zeros, 0.0);
        let rate = moved.map_or(0.0, |p| {
            p.points
                .iter()
                .zip(&rest.points)
                .map(|(a, b)| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt())
                .fold(0.0, f64::max)
                / h
        });
        let amplitude = if rate > 0.0 {
            (MODE_REACH * size / rate).min(0.6)
        } else {
            0.3
        };
        let omega = w2.abs().sqrt();
        let period = if omega > 0.0 {
            2.0 * std::f64::consts::PI / omega
        } else {
            1.0
        };
        let times: Vec<f64> = (0..=MODE_FRAMES)
            .map(|j| period * j as f64 / MODE_FRAMES as f64)
            .collect();
        let states = times
            .iter()
            .map(|t| {
                let s = amplitude * (2.0 * std::f64::consts::PI * t / period).sin();
                (state(&unit, s), zeros.clone())
            })
            .collect();
        // rad/s and Hz where the scene's time is in seconds
        let (rad, hz) = if scene.dimensions_checked {
            (" rad/s", " Hz")
        } else {
            ("", "")
        };
        let label = if *w2 > 0.0 {
            format!(
                "mode {}: ω = {}{rad}, f = {}{hz}",
                k + 1,
                short(omega),
                short(omega / (2.0 * std::f64::consts::PI))
            )
        } else {
            format!("mode {}: ω² = {} (not an oscillation)", k + 1, short(*w2))
        };
        motions.push(Motion {
            label,
            periodic: true,
            times,
            states,
            set,
        });
    }
    page_data(&stage, scene, title, subtitle, &motions)
}

/// `modes --animate`'s page.
pub fn modes_page(
    scene: &Scene,
    osc: &Oscillations,
    title: &str,
    subtitle: &str,
) -> Result<String, Diagnostic> {
    Ok(page(&modes_data(scene, osc, title, subtitle)?))
}

/// A value with 4 significant digits.
fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}
