//! Why a position cannot be computed: the joints, drives and constraints
//! impose one condition twice (a drive on a coordinate the joints already
//! fix), or they cannot all hold at once (a loop whose links cannot reach).

use super::model::Model;
use super::scale::Scales;
use super::Over;
use crate::diag::{Diagnostic, ErrorKind};
use crate::scene::Scene;
use nalgebra::{DMatrix, DVector};

/// A relative singular value (of the Jacobian in natural units) below
/// this is a dependency among the rows.
const DEPENDENT_RATIO: f64 = 1e-10;
/// The least-squares search for the nearest assembly stops after this
/// many steps.
const MAX_NEAREST_STEPS: usize = 400;

/// The constraint Jacobian A at (q, t).
fn jacobian(model: &mut Model, q: &[f64], t: f64, out: &mut [f64]) -> DMatrix<f64> {
    let n = model.n;
    let inputs: Vec<f64> = q.iter().copied().chain([t]).collect();
    model.position.eval(&inputs, out);
    DMatrix::from_row_slice(n, n, &out[n..n + n * n])
}

/// The residuals g(q, t) (a locked angle less its assembled value).
fn residual(model: &mut Model, q: &[f64], t: f64, offsets: &[f64], out: &mut [f64]) -> Vec<f64> {
    let inputs: Vec<f64> = q.iter().copied().chain([t]).collect();
    model.position.eval(&inputs, out);
    (0..model.n).map(|j| out[j] - offsets[j]).collect()
}

/// Conditions that repeat one another: singular at `q` and at a point
/// near it, so not a dead point of the motion but the same condition
/// imposed twice. The constraints of the dependent combination and the
/// coordinates the missing condition leaves free.
pub(super) struct Dependency {
    pub constraints: Vec<usize>,
    pub free: Vec<usize>,
}

/// A point near `q`, the same for every call: off a singular Jacobian,
/// by a thousandth of each coordinate's natural scale.
pub(super) fn nudged(scales: &Scales, q: &[f64]) -> Vec<f64> {
    q.iter()
        .zip(&scales.coordinate)
        .enumerate()
        .map(|(i, (x, s))| x + 1e-3 * (s + x.abs()) * (1.7 * i as f64 + 0.3).sin())
        .collect()
}

/// The dependency among the rows of the Jacobian near `q`, if any.
pub(super) fn dependency(
    model: &mut Model,
    scales: &Scales,
    q: &[f64],
    t: f64,
    out: &mut [f64],
) -> Option<Dependency> {
    let near = nudged(scales, q);
    let mut last = None;
    for point in [q, &near[..]] {
        let svd = scales
            .scaled(&jacobian(model, point, t, out))
            .svd(true, true);
        let s = &svd.singular_values;
        let (k, lo) =
            s.iter().enumerate().fold(
                (0, f64::INFINITY),
                |b, (i, &x)| {
                    if x < b.1 {
                        (i, x)
                    } else {
                        b
                    }
                },
            );
        let hi = s.max();
        if !(hi > 0.0 && lo <= DEPENDENT_RATIO * hi) {
            return None;
        }
        last = Some((svd, k));
    }
    let (svd, k) = last?;
    let significant = |v: Vec<f64>| -> Vec<usize> {
        let top = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        (0..v.len()).filter(|&i| v[i].abs() > 1e-6 * top).collect()
    };
    let u = svd.u.as_ref()?.column(k).iter().copied().collect();
    let v = svd.v_t.as_ref()?.row(k).iter().copied().collect();
    Some(Dependency {
        constraints: significant(u),
        free: significant(v),
    })
}

/// The least-squares assembly nearest `q` (Levenberg–Marquardt on
/// |g|², each condition and coordinate in its natural unit) and its
/// residuals: where the mechanism cannot close, the conditions left open
/// there are the ones that cannot all hold.
pub(super) fn nearest(
    model: &mut Model,
    scales: &Scales,
    q: &[f64],
    t: f64,
    offsets: &[f64],
    out: &mut [f64],
) -> (Vec<f64>, Vec<f64>) {
    let n = model.n;
    let units = scales.rows(&jacobian(model, q, t, out));
    let scaled = |g: &[f64]| -> Vec<f64> { g.iter().zip(&units).map(|(x, u)| x / u).collect() };
    let mut q = q.to_vec();
    let mut g = residual(model, &q, t, offsets, out);
    let mut cost: f64 = scaled(&g).iter().map(|x| x * x).sum();
    let mut damping = 1e-3;
    for _ in 0..MAX_NEAREST_STEPS {
        // A·dq = −g in natural units: rows over T_i, columns times S_j
        let raw = jacobian(model, &q, t, out);
        let a = DMatrix::from_fn(n, n, |i, j| raw[(i, j)] * scales.coordinate[j] / units[i]);
        let ata = a.transpose() * &a;
        let atg = a.transpose() * DVector::from_column_slice(&scaled(&g));
        let mut lhs = ata.clone();
        for i in 0..n {
            lhs[(i, i)] += damping * (ata[(i, i)] + 1e-12);
        }
        let Some(dq) = lhs.lu().solve(&(-atg)) else {
            break;
        };
        let trial: Vec<f64> = q
            .iter()
            .zip(dq.iter())
            .zip(&scales.coordinate)
            .map(|((x, d), s)| x + d * s)
            .collect();
        let gt = residual(model, &trial, t, offsets, out);
        let ct: f64 = scaled(&gt).iter().map(|x| x * x).sum();
        if ct.is_finite() && ct < cost {
            let small = cost - ct <= 1e-15 * cost || dq.amax() <= 1e-14 * scales.size(&q);
            (q, g, cost) = (trial, gt, ct);
            damping = (damping / 3.0).max(1e-12);
            if small {
                break;
            }
        } else {
            damping *= 4.0;
            if damping > 1e12 {
                break;
            }
        }
    }
    (q, g)
}

/// The conditions a least-squares residual leaves open (above 1e-6 of
/// the largest), and the one most open.
fn open(residual: &[f64]) -> (Vec<usize>, usize) {
    // a condition that cannot be evaluated (not finite) is the one to name
    let bad: Vec<usize> = (0..residual.len())
        .filter(|&j| !residual[j].is_finite())
        .collect();
    if let Some(&first) = bad.first() {
        return (bad, first);
    }
    let top = residual.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let worst = residual
        .iter()
        .position(|x| x.abs() == top)
        .unwrap_or_default();
    let open = (0..residual.len())
        .filter(|&j| residual[j].abs() > 1e-6 * top)
        .collect::<Vec<_>>();
    if open.is_empty() {
        return (vec![worst], worst);
    }
    (open, worst)
}

/// "the joint `A`" / "the drive `M`" / "the constraint `c`" for
/// constraint `j`.
fn owner(scene: &Scene, j: usize) -> String {
    if let Some(jt) = scene.joints.iter().find(|jt| jt.constraints.contains(&j)) {
        return format!("the joint `{}`", jt.name);
    }
    if let Some(d) = scene.drives.iter().find(|d| d.constraint == j) {
        return format!("the drive `{}`", d.name);
    }
    format!("the constraint {}", scene.constraints[j].label(j))
}

/// The owners of `rows`, each once, in order: "the joint `O`, the joint
/// `A` and the drive `M`".
fn owners(scene: &Scene, rows: &[usize]) -> String {
    let mut names: Vec<String> = Vec::new();
    for &j in rows {
        let o = owner(scene, j);
        if !names.contains(&o) {
            names.push(o);
        }
    }
    match names.len() {
        0 => String::new(),
        1 => names.remove(0),
        k => format!("{} and {}", names[..k - 1].join(", "), names[k - 1]),
    }
}

/// Which conditions cannot all hold, from the residuals of the
/// least-squares assembly nearest the start: "the joint `A` and the drive `M` cannot all
/// hold (…)".
pub(super) fn cannot_hold(scene: &Scene, residual: &[f64]) -> String {
    let (rows, worst) = open(residual);
    let gap = residual[worst].abs();
    if !gap.is_finite() {
        let who = if rows.len() <= 1 {
            owner(scene, worst)
        } else {
            owners(scene, &rows)
        };
        return format!("{who} cannot be evaluated there (not finite: a division by zero or an overflow in its condition)");
    }
    if rows.len() <= 1 {
        return format!(
            "{} cannot hold (the nearest assembly leaves it open by {gap:.3e})",
            owner(scene, worst)
        );
    }
    format!(
        "{} cannot all hold (the nearest assembly leaves them open by up to {gap:.3e})",
        owners(scene, &rows),
    )
}

/// The error when the first position cannot be assembled, at the
/// statement of the condition left most open.
#[allow(clippy::too_many_arguments)]
pub(super) fn unassembled(
    scene: &Scene,
    model: &mut Model,
    scales: &Scales,
    start: &[f64],
    t: f64,
    residual: &[f64],
    out: &mut [f64],
    over: &Over,
    v: f64,
) -> Diagnostic {
    if let Some(d) = dependency(model, scales, start, t, out) {
        return dependent(scene, &d, over, v);
    }
    let why = cannot_hold(scene, residual);
    // the gap spreads evenly over a loop: the error is at its first
    // condition, the others labelled
    let (rows, _) = open(residual);
    let spans = statements(scene, &rows);
    let mut diag = Diagnostic::error(
        spans[0],
        format!(
            "the mechanism cannot be assembled at the first position ({} = {v}): {why}",
            over.name,
        ),
    )
    .with_hint("check the lengths (a loop closes only when its links can reach), or give `--guess` values of an assembly near the first position").with_kind(ErrorKind::Constraints);
    for &span in &spans[1..] {
        diag = diag.with_label(span, "open too");
    }
    diag
}

/// The statements of the constraints `rows`, each once, in order.
fn statements(scene: &Scene, rows: &[usize]) -> Vec<crate::parse::ast::Span> {
    let mut spans = Vec::new();
    for &j in rows {
        let span = scene.constraints[j].span;
        if !spans.contains(&span) {
            spans.push(span);
        }
    }
    spans
}

/// The error when the conditions repeat one another: at the drive among
/// them (the likeliest extra), the others labelled.
pub(super) fn dependent(scene: &Scene, d: &Dependency, over: &Over, v: f64) -> Diagnostic {
    let at = d
        .constraints
        .iter()
        .copied()
        .find(|&j| scene.drives.iter().any(|dr| dr.constraint == j))
        .unwrap_or(d.constraints[d.constraints.len() - 1]);
    let free: Vec<&str> = d
        .free
        .iter()
        .map(|&k| scene.coordinates[k].name.as_str())
        .collect();
    let mut diag = Diagnostic::error(
        scene.constraints[at].span,
        format!(
            "{} impose one condition twice (their rows of the constraint Jacobian are dependent at and near the first position, {} = {v}), so they leave a motion of {} free",
            owners(scene, &d.constraints),
            over.name,
            free.join(", ")
        ),
    )
    .with_hint("a drive prescribes a coordinate the joints and constraints leave free: drive another coordinate, or remove the condition that repeats another").with_kind(ErrorKind::Constraints);
    let mut labelled = vec![scene.constraints[at].span];
    for &j in &d.constraints {
        let span = scene.constraints[j].span;
        if !labelled.contains(&span) {
            labelled.push(span);
            diag = diag.with_label(span, "dependent with it");
        }
    }
    diag
}
