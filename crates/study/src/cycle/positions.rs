//! The loop over the cycle's positions: the time of each, the assembly
//! by Newton's method continued from the previous position, the
//! velocities and accelerations, and the kinetostatics.

use super::diagnose::{self, dependency, nearest, nudged};
use super::friction::{kinetostatics, Kinetostatics, Position};
use super::model::Model;
use super::scale::Scales;
use super::table::{CycleRow, CycleTable, Layout, StickLimits};
use super::{Over, Varied};
use crate::diag::Diagnostic;
use crate::scene::Scene;
use nalgebra::{DMatrix, DVector};

/// Newton's method gives up after this many steps at one position.
const MAX_NEWTON_STEPS: usize = 50;
/// A Jacobian whose smallest pivot is below this fraction of its largest,
/// in the mechanism's natural units (`scale.rs`), is singular: a dead point. Not near the rounding error: at a dead
/// point g has a double root, which Newton's method finds only to about
/// √ε, so the pivot there is ~1e-9 of the largest rather than 0.
const SINGULAR_PIVOT_RATIO: f64 = 1e-6;
/// Newton's steps are at most this fraction of the position's size in
/// natural units.
const MAX_STEP: f64 = 0.5;
/// A position whose residuals are below this (in natural units, relative
/// to the position's size) is assembled even when Newton's method, slowed
/// by a singular Jacobian, did not converge.
const ASSEMBLED_RESIDUAL: f64 = 1e-9;

/// The state carried from one position to the next.
struct Carried {
    t: f64,
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    det_positive: Option<bool>,
    /// False once a position after it could not be assembled: the next
    /// one then starts from `q` itself, not from an extrapolation over
    /// the gap.
    adjacent: bool,
}

/// Every position of `over`, in order.
pub(super) fn run(
    scene: &Scene,
    model: &mut Model,
    varied: &mut Varied,
    guess: Vec<f64>,
    over: &Over,
    layout: &Layout,
) -> Result<CycleTable, Diagnostic> {
    let n = model.n;
    let mut offsets = vec![0.0; n];
    let mut out = vec![0.0; n + n * n + n];
    // a locked angle is held at its value in the guess
    let t0 = time_of(varied, over.value(0), None).map_err(Diagnostic::global)?;
    let inputs: Vec<f64> = guess.iter().copied().chain([t0]).collect();
    model.position.eval(&inputs, &mut out);
    for &j in &model.locked {
        offsets[j] = out[j];
    }
    let scales = Scales::new(scene, model, &guess, t0);
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
            limits: None,
        };
        row.values[0] = Some(v);
        let t = match time_of(varied, v, carried.as_ref().map(|c| c.t)) {
            Ok(t) => t,
            Err(why) => {
                row.add_note(why);
                rows.push(row);
                continue;
            }
        };
        let start = predict(carried.as_ref(), &guess, t);
        let q = match assemble(model, &scales, &start, t, &offsets, &mut out) {
            Ok(q) => q,
            Err(residual) => {
                if carried.is_none() {
                    return Err(diagnose::unassembled(
                        scene, model, &scales, &start, t, &residual, &mut out, over, v,
                    ));
                }
                row.add_note(format!(
                    "the mechanism cannot be assembled here: {}",
                    diagnose::cannot_hold(scene, &residual)
                ));
                if let Some(c) = carried.as_mut() {
                    c.adjacent = false;
                }
                rows.push(row);
                continue;
            }
        };
        for (i, &x) in q.iter().enumerate() {
            row.values[1 + i] = Some(x);
        }
        let a = DMatrix::from_row_slice(n, n, &out[n..n + n * n]);
        let lu = a.clone().lu();
        let det_positive = lu.determinant() > 0.0;
        let previous = carried.as_ref().and_then(|c| c.det_positive);
        if let Some(ratio) = singular(&scales.scaled(&a)) {
            if carried.is_none() {
                if let Some(d) = dependency(model, &scales, &q, t, &mut out) {
                    return Err(diagnose::dependent(scene, &d, over, v));
                }
            }
            row.add_note(format!("dead point: the constraint Jacobian is singular here (pivot ratio {ratio:.1e}), so the velocities, accelerations and reactions are not determined, and the position only to about 1e-8 of its scale (Newton's method at a double root); the assembly branch after it is compared with the one before"));
            points_at(model, &q, &vec![0.0; n], t, &mut motion, &mut row);
            carried = Some(Carried {
                t,
                q,
                qd: carried.map(|c| c.qd).unwrap_or(vec![0.0; n]),
                qdd: vec![0.0; n],
                det_positive: previous,
                adjacent: true,
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
            row.add_note("the constraint Jacobian's determinant changed sign since the previous regular position: a dead point lies between them, and the assembly branch changed there");
        } else if carried
            .as_ref()
            .is_some_and(|c| turned_back(&scales, c, &start, &q))
        {
            row.add_note("the position is far from the continuation of the previous one (Newton's method corrected more than half the step): a dead point may lie between them, where the mechanism turned back; take more positions there");
        }
        let at = Position {
            a: &a,
            motion: &motion,
            qd: &qd,
            qdd: &qdd,
            scales: &scales,
        };
        record(&mut row, layout, kinetostatics(model, &at));
        row.points = points(&motion[lay.points..], model.points);
        carried = Some(Carried {
            t,
            q,
            qd,
            qdd,
            det_positive: Some(det_positive),
            adjacent: true,
        });
        rows.push(row);
    }
    for row in &mut rows {
        leave_out_non_finite(row);
    }
    Ok(CycleTable {
        varied: over.name.clone(),
        columns: layout.columns.clone(),
        coordinates: n,
        joints: layout.joints.clone(),
        drives: layout.drives.clone(),
        rows,
        drawing: model.drawing.clone(),
    })
}

/// The kinetostatics' outcome into the row: the reactions, or both
/// limits at a stick, or why not.
fn record(row: &mut CycleRow, layout: &Layout, k: Kinetostatics) {
    match k {
        Kinetostatics::Solved {
            lambda,
            friction,
            iterations,
        } => {
            reactions(&mut row.values, layout, &lambda, &friction);
            row.iterations = iterations;
        }
        Kinetostatics::Stick {
            joint,
            minus,
            plus,
            iterations,
            note,
        } => {
            let side = |(lambda, friction): (Vec<f64>, Vec<f64>)| {
                let mut values = row.values.clone();
                reactions(&mut values, layout, &lambda, &friction);
                values
            };
            row.limits = Some(Box::new(StickLimits {
                joint,
                minus: side(minus),
                plus: side(plus),
            }));
            row.iterations = iterations;
            row.add_note(note);
        }
        Kinetostatics::Refused(why) => row.add_note(why),
    }
}

/// The reactions `lambda` (by constraint) and the frictions into their
/// columns.
fn reactions(values: &mut [Option<f64>], layout: &Layout, lambda: &[f64], friction: &[f64]) {
    for (j, &col) in layout.multiplier.iter().enumerate() {
        values[col] = Some(lambda[j]);
    }
    for (f, &col) in friction.iter().zip(&layout.friction) {
        values[col] = Some(*f);
    }
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
        // converged when the law equals v to rounding: no unit of time in it
        if f.abs() <= 4.0 * f64::EPSILON * (out[0].abs() + v.abs()) {
            return Ok(t);
        }
        let step = f / df;
        t -= step;
        if step.abs() <= 1e-15 * t.abs() {
            return Ok(t);
        }
    }
    Err("the drive law's equation for the time did not converge".into())
}

/// The starting point of Newton's method: the guess, or the previous
/// position moved on by its velocity and acceleration (which keeps the
/// branch), or after positions that could not be assembled the last
/// assembled one itself.
fn predict(c: Option<&Carried>, guess: &[f64], t: f64) -> Vec<f64> {
    match c {
        None => guess.to_vec(),
        Some(c) if !c.adjacent => c.q.clone(),
        Some(c) => {
            let dt = t - c.t;
            (0..c.q.len())
                .map(|i| c.q[i] + c.qd[i] * dt + 0.5 * c.qdd[i] * dt * dt)
                .collect()
        }
    }
}

/// Newton's method on g(q, t) = 0 from `q`; `out` holds (g, A, b) at the
/// result. The residual g where it fails. Steps are measured in the
/// mechanism's natural units (`scales`).
fn newton(
    model: &mut Model,
    scales: &Scales,
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
        let size = scales.size(q);
        let step = scales.norm(dq.as_slice());
        // a step longer than half the size (from a poor guess, or near a
        // singular Jacobian) is shortened: an angle then does not jump by
        // whole turns, nor the assembly to a far branch
        let shorten = (MAX_STEP * size / step).min(1.0);
        for (x, d) in q.iter_mut().zip(dq.iter()) {
            *x += shorten * d;
        }
        // one more evaluation after the step that converged: `out` then
        // holds the Jacobian at the final position
        converged = step <= 1e-12 * size;
    }
    inputs[..n].copy_from_slice(q);
    inputs[n] = t;
    model.position.eval(&inputs, out);
    Err((0..n).map(|j| out[j] - offsets[j]).collect())
}

/// The position at time `t`: Newton's method from `start`; when it
/// fails, from a point near `start` (off a singular Jacobian, such as a
/// start exactly at a dead point), then from the least-squares assembly
/// nearest `start`. Where none closes, the residuals of that nearest
/// assembly.
fn assemble(
    model: &mut Model,
    scales: &Scales,
    start: &[f64],
    t: f64,
    offsets: &[f64],
    out: &mut [f64],
) -> Result<Vec<f64>, Vec<f64>> {
    let mut q = start.to_vec();
    if closes(model, scales, &mut q, t, offsets, out) {
        return Ok(q);
    }
    let mut q = nudged(scales, start);
    if closes(model, scales, &mut q, t, offsets, out) {
        return Ok(q);
    }
    let (mut q, residual) = nearest(model, scales, start, t, offsets, out);
    if closes(model, scales, &mut q, t, offsets, out) {
        return Ok(q);
    }
    Err(residual)
}

/// Whether Newton's method from `q` assembles the mechanism (`q` then
/// holds the position, `out` its g, A and b): converged, or slowed down
/// by a dead point with its residuals vanishing all the same (each in its
/// constraint's natural unit).
fn closes(
    model: &mut Model,
    scales: &Scales,
    q: &mut [f64],
    t: f64,
    offsets: &[f64],
    out: &mut [f64],
) -> bool {
    match newton(model, scales, q, t, offsets, out) {
        Ok(()) => true,
        Err(residual) => {
            let n = model.n;
            let a = DMatrix::from_row_slice(n, n, &out[n..n + n * n]);
            let size = scales.size(q);
            residual
                .iter()
                .zip(scales.rows(&a))
                .all(|(r, unit)| (r / unit).abs() <= ASSEMBLED_RESIDUAL * size)
        }
    }
}

/// A value that overflowed (inf, NaN) is no answer: it is left out, and
/// the row says so.
fn leave_out_non_finite(row: &mut CycleRow) {
    let mut bad = false;
    for v in &mut row.values {
        if v.is_some_and(|x| !x.is_finite()) {
            *v = None;
            bad = true;
        }
    }
    if let Some(l) = row.limits.as_mut() {
        for v in l.minus.iter_mut().chain(l.plus.iter_mut()) {
            if v.is_some_and(|x| !x.is_finite()) {
                *v = None;
                bad = true;
            }
        }
    }
    if bad {
        row.add_note("some values are not finite here (an overflow in the velocities, accelerations or reactions): they are left out");
    }
}

/// Whether the assembled `q` is far from the continuation `start` of
/// the regular position `c`: a correction of more than half the step,
/// where a smooth motion's is of the order of the step cubed.
fn turned_back(scales: &Scales, c: &Carried, start: &[f64], q: &[f64]) -> bool {
    let dist = |a: &[f64], b: &[f64]| {
        let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
        scales.norm(&d)
    };
    let step = dist(start, &c.q);
    c.adjacent && c.det_positive.is_some() && step > 0.0 && dist(q, start) > 0.5 * step
}

/// The pivot ratio of the Jacobian `a` in natural units when it is
/// singular, `None` when regular.
fn singular(a: &DMatrix<f64>) -> Option<f64> {
    let u = a.clone().lu().u();
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

#[cfg(test)]
mod tests {
    use super::{turned_back, Carried, Scales};

    fn unit() -> Scales {
        Scales {
            coordinate: vec![1.0],
            length: 1.0,
        }
    }

    fn carried(q: f64) -> Carried {
        Carried {
            t: 0.0,
            q: vec![q],
            qd: vec![1.0],
            qdd: vec![0.0],
            det_positive: Some(true),
            adjacent: true,
        }
    }

    #[test]
    fn a_value_that_overflowed_is_left_out_and_said() {
        let mut row = super::CycleRow {
            values: vec![Some(1.0), Some(f64::INFINITY), Some(f64::NAN), None],
            note: None,
            iterations: 0,
            points: Vec::new(),
            limits: None,
        };
        super::leave_out_non_finite(&mut row);
        assert_eq!(row.values, vec![Some(1.0), None, None, None]);
        assert!(row
            .note
            .unwrap()
            .starts_with("some values are not finite here"));
    }

    #[test]
    fn a_motion_that_turns_back_is_told_from_a_smooth_one() {
        let c = carried(1.0);
        // the continuation predicted 1.1; a smooth motion lands near it
        assert!(!turned_back(&unit(), &c, &[1.1], &[1.1001]));
        // the mechanism went back to 0.95: it turned back at a dead point
        assert!(turned_back(&unit(), &c, &[1.1], &[0.95]));
        // after a gap, or from an irregular position, nothing is said
        let gap = Carried {
            adjacent: false,
            ..carried(1.0)
        };
        assert!(!turned_back(&unit(), &gap, &[1.1], &[0.95]));
        let dead = Carried {
            det_positive: None,
            ..carried(1.0)
        };
        assert!(!turned_back(&unit(), &dead, &[1.1], &[0.95]));
    }
}
