//! The loop over the cycle's positions: the time of each, the assembly
//! by Newton's method continued from the previous position, the
//! velocities and accelerations, and the kinetostatics.

use super::friction::{kinetostatics, Kinetostatics};
use super::model::Model;
use super::table::{CycleRow, CycleTable, Layout};
use super::{Over, Varied};
use crate::diag::Diagnostic;
use crate::scene::Scene;
use nalgebra::{DMatrix, DVector};

/// Newton's method gives up after this many steps at one position.
const MAX_NEWTON_STEPS: usize = 50;
/// A Jacobian whose smallest pivot is below this fraction of its largest
/// is singular: a dead point.
const SINGULAR_PIVOT_RATIO: f64 = 1e-10;

/// The state carried from one position to the next.
struct Carried {
    t: f64,
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    det_positive: Option<bool>,
}

/// Every position of `over`, in order.
pub(super) fn run(
    scene: &Scene,
    mut model: Model,
    mut varied: Varied,
    guess: Vec<f64>,
    over: &Over,
    layout: Layout,
) -> Result<CycleTable, Diagnostic> {
    let n = model.n;
    let mut offsets = vec![0.0; n];
    let mut out = vec![0.0; n + n * n + n];
    // a locked angle is held at its value in the guess
    let t0 = time_of(&mut varied, over.value(0), None).map_err(Diagnostic::global)?;
    let mut inputs: Vec<f64> = guess.iter().copied().chain([t0]).collect();
    model.position.eval(&inputs, &mut out);
    for &j in &model.locked {
        offsets[j] = out[j];
    }
    let mut carried: Option<Carried> = None;
    let mut rows = Vec::with_capacity(over.count);
    let ncols = layout.columns.len();
    let mut motion = vec![0.0; model.layout().len];
    for k in 0..over.count {
        let v = over.value(k);
        let mut row = CycleRow {
            values: vec![None; ncols],
            note: None,
            iterations: 0,
            points: Vec::new(),
        };
        row.values[0] = Some(v);
        let t = match time_of(&mut varied, v, carried.as_ref().map(|c| c.t)) {
            Ok(t) => t,
            Err(why) => {
                row.note = Some(why);
                rows.push(row);
                continue;
            }
        };
        let mut q = predict(carried.as_ref(), &guess, t);
        inputs.truncate(0);
        let assembled = newton(&mut model, &mut q, t, &offsets, &mut out);
        if let Err(residual) = assembled {
            if carried.is_none() {
                return Err(unassembled(scene, &residual, over, v));
            }
            row.note = Some(format!(
                "the mechanism cannot be assembled here: Newton's method did not close {}",
                worst(scene, &residual)
            ));
            rows.push(row);
            continue;
        }
        for (i, &x) in q.iter().enumerate() {
            row.values[1 + i] = Some(x);
        }
        let a = DMatrix::from_row_slice(n, n, &out[n..n + n * n]);
        let lu = a.clone().lu();
        let det_positive = lu.determinant() > 0.0;
        let previous = carried.as_ref().and_then(|c| c.det_positive);
        if let Some(ratio) = singular(&lu) {
            row.note = Some(format!("dead point: the constraint Jacobian is singular here (pivot ratio {ratio:.1e}), so the velocities, accelerations and reactions are not determined"));
            points_at(&mut model, &q, &vec![0.0; n], t, &mut motion, &mut row);
            carried = Some(Carried {
                t,
                q,
                qd: carried.map(|c| c.qd).unwrap_or(vec![0.0; n]),
                qdd: vec![0.0; n],
                det_positive: previous,
            });
            rows.push(row);
            continue;
        }
        let minus_b = DVector::from_iterator(n, out[n + n * n..].iter().map(|b| -b));
        let qd: Vec<f64> = lu
            .solve(&minus_b)
            .map(|x| x.iter().copied().collect())
            .unwrap_or(vec![f64::NAN; n]);
        let ins: Vec<f64> = q.iter().chain(&qd).copied().chain([t]).collect();
        model.motion.eval(&ins, &mut motion);
        let lay = model.layout();
        let gamma = DVector::from_column_slice(&motion[lay.gamma..lay.gamma + n]);
        let qdd: Vec<f64> = lu
            .solve(&gamma)
            .map(|x| x.iter().copied().collect())
            .unwrap_or(vec![f64::NAN; n]);
        for i in 0..n {
            row.values[1 + n + i] = Some(qd[i]);
            row.values[1 + 2 * n + i] = Some(qdd[i]);
        }
        if previous.is_some_and(|p| p != det_positive) {
            row.note = Some("the constraint Jacobian's determinant changed sign since the previous position: a dead point lies between them, and the assembly branch may have changed there".into());
        }
        match kinetostatics(&model, &a, &motion, &qd, &qdd) {
            Kinetostatics::Solved {
                lambda,
                friction,
                iterations,
            } => {
                for (j, &col) in layout.multiplier.iter().enumerate() {
                    row.values[col] = Some(lambda[j]);
                }
                for (f, &col) in friction.iter().zip(&layout.friction) {
                    row.values[col] = Some(*f);
                }
                row.iterations = iterations;
            }
            Kinetostatics::Refused(why) => row.note = Some(why),
        }
        row.points = points(&motion[lay.points..], model.points);
        carried = Some(Carried {
            t,
            q,
            qd,
            qdd,
            det_positive: Some(det_positive),
        });
        rows.push(row);
    }
    Ok(CycleTable {
        varied: over.name.clone(),
        columns: layout.columns,
        coordinates: n,
        joints: layout.joints,
        drives: layout.drives,
        rows,
        drawing: model.drawing,
    })
}

/// The time at which the varied quantity has the value `v`: `v` itself,
/// or the root of f(t) = v by Newton's method from the previous time.
fn time_of(varied: &mut Varied, v: f64, previous: Option<f64>) -> Result<f64, String> {
    let law = match varied {
        Varied::Time => return Ok(v),
        Varied::Drive(law) => law,
    };
    let mut t = previous.unwrap_or(0.0);
    let mut out = [0.0; 2];
    for _ in 0..MAX_NEWTON_STEPS {
        law.eval(&[t], &mut out);
        let (f, df) = (out[0] - v, out[1]);
        if !(df.is_finite() && df != 0.0) {
            return Err(format!("the drive law's rate is {df} at t = {t}, so the time of this position is not found"));
        }
        let step = f / df;
        t -= step;
        if step.abs() <= 1e-15 * (1.0 + t.abs()) {
            return Ok(t);
        }
    }
    Err("the drive law's equation for the time did not converge".into())
}

/// The starting point of Newton's method: the guess, or the previous
/// position moved on by its velocity and acceleration (which keeps the
/// branch).
fn predict(c: Option<&Carried>, guess: &[f64], t: f64) -> Vec<f64> {
    match c {
        None => guess.to_vec(),
        Some(c) => {
            let dt = t - c.t;
            (0..c.q.len())
                .map(|i| c.q[i] + c.qd[i] * dt + 0.5 * c.qdd[i] * dt * dt)
                .collect()
        }
    }
}

/// Newton's method on g(q, t) = 0 from `q`; `out` holds (g, A, b) at the
/// result. The residual g where it fails.
fn newton(
    model: &mut Model,
    q: &mut [f64],
    t: f64,
    offsets: &[f64],
    out: &mut [f64],
) -> Result<(), Vec<f64>> {
    let n = model.n;
    let mut inputs = vec![0.0; n + 1];
    let mut converged = false;
    for _ in 0..MAX_NEWTON_STEPS {
        inputs[..n].copy_from_slice(q);
        inputs[n] = t;
        model.position.eval(&inputs, out);
        let g: Vec<f64> = (0..n).map(|j| out[j] - offsets[j]).collect();
        if converged {
            return Ok(());
        }
        let a = DMatrix::from_row_slice(n, n, &out[n..n + n * n]);
        let Some(dq) = a
            .lu()
            .solve(&DVector::from_iterator(n, g.iter().map(|x| -x)))
        else {
            return Err(g);
        };
        if dq.iter().any(|x| !x.is_finite()) {
            return Err(g);
        }
        let scale = 1.0 + q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (x, d) in q.iter_mut().zip(dq.iter()) {
            *x += d;
        }
        // one more evaluation after the step that converged: `out` then
        // holds the Jacobian at the final position
        converged = dq.amax() <= 1e-12 * scale;
    }
    inputs[..n].copy_from_slice(q);
    inputs[n] = t;
    model.position.eval(&inputs, out);
    Err((0..n).map(|j| out[j] - offsets[j]).collect())
}

/// The pivot ratio of a singular LU factorization, `None` when regular.
fn singular(lu: &nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>) -> Option<f64> {
    let u = lu.u();
    let d = u.diagonal();
    let (lo, hi) = d.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
        (lo.min(x.abs()), hi.max(x.abs()))
    });
    let ratio = if hi > 0.0 { lo / hi } else { 0.0 };
    (ratio < SINGULAR_PIVOT_RATIO || !ratio.is_finite()).then_some(ratio)
}

/// The drawing's points from the motion program's tail.
fn points(tail: &[f64], count: usize) -> Vec<[f64; 2]> {
    (0..count).map(|i| [tail[2 * i], tail[2 * i + 1]]).collect()
}

/// The points of a row whose velocities are unknown (they do not depend
/// on them).
fn points_at(
    model: &mut Model,
    q: &[f64],
    qd: &[f64],
    t: f64,
    motion: &mut [f64],
    row: &mut CycleRow,
) {
    let ins: Vec<f64> = q.iter().chain(qd).copied().chain([t]).collect();
    model.motion.eval(&ins, motion);
    let lay = model.layout();
    row.points = points(&motion[lay.points..], model.points);
}

/// The constraint that stays open: the joint (or drive) with the largest
/// residual, for messages.
fn worst(scene: &Scene, residual: &[f64]) -> String {
    let (j, r) = residual
        .iter()
        .enumerate()
        .fold((0, 0.0f64), |(bj, br), (j, r)| {
            if r.abs() > br {
                (j, r.abs())
            } else {
                (bj, br)
            }
        });
    match owner(scene, j) {
        Some(what) => format!("{what} (its residual is {r:.3e})"),
        None => format!(
            "the constraint {} (its residual is {r:.3e})",
            scene.constraints[j].label(j)
        ),
    }
}

/// "the joint `A`" / "the drive `M`" for constraint `j`.
fn owner(scene: &Scene, j: usize) -> Option<String> {
    if let Some(jt) = scene.joints.iter().find(|jt| jt.constraints.contains(&j)) {
        return Some(format!("the joint `{}`", jt.name));
    }
    scene
        .drives
        .iter()
        .find(|d| d.constraint == j)
        .map(|d| format!("the drive `{}`", d.name))
}

/// The error when the first position cannot be assembled, at the
/// statement of the constraint that stays open.
fn unassembled(scene: &Scene, residual: &[f64], over: &Over, v: f64) -> Diagnostic {
    let j = residual.iter().enumerate().fold(
        0,
        |bj, (j, r)| if r.abs() > residual[bj].abs() { j } else { bj },
    );
    let span = scene.constraints[j].span;
    Diagnostic::error(
        span,
        format!(
            "the mechanism cannot be assembled at the first position ({} = {v}): from the guess, Newton's method does not close {}",
            over.name,
            worst(scene, residual)
        ),
    )
    .with_hint("check the lengths (a loop closes only when its links can reach), or give `--guess` values of an assembly near the first position")
}
