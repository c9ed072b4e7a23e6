//! The exact equations of a mechanism compiled for numbers: the
//! constraints and their Jacobian for the positions, the velocity and
//! acceleration equations, M and f for the kinetostatics, the frictions'
//! relative velocities and directions, and the points of the drawing.

use super::table::{Drawing, DrawnBody, DrawnJoint, JointKind};
use crate::compile::{compile_with, CompileError, Program};
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::{atom, Expr};
use crate::mechanics::Lagrange;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

/// One friction of the mechanism, for the iteration.
pub(super) struct FrictionModel {
    /// Its joint's name.
    pub joint: String,
    /// Pin (|R| = √(x² + y²)) or slider (|N|).
    pub kind: JointKind,
    /// The joint's constraint rows: its reaction's components.
    pub rows: Vec<usize>,
    /// The coefficient's value.
    pub coefficient: f64,
}

/// A program with its register file, evaluated in place.
pub(super) struct Evaluator {
    program: Program,
    regs: Vec<f64>,
}

impl Evaluator {
    fn new(program: Program) -> Evaluator {
        let regs = program.registers();
        Evaluator { program, regs }
    }

    /// The outputs at `inputs`, into `out`.
    pub fn eval(&mut self, inputs: &[f64], out: &mut [f64]) {
        let off = self.program.input_offset();
        self.regs[off..off + inputs.len()].copy_from_slice(inputs);
        self.program.run(&mut self.regs);
        for (o, &k) in out.iter_mut().zip(self.program.output_registers()) {
            *o = self.regs[k as usize];
        }
    }
}

/// The compiled mechanism.
pub(super) struct Model {
    /// The number of coordinates (and of constraints).
    pub n: usize,
    /// (q, t) ↦ (g, A row by row, b): the constraints at the level of
    /// the positions (a locked angle without its assembled constant),
    /// their Jacobian, and A·q̇ = −b.
    pub position: Evaluator,
    /// (q, q̇, t) ↦ (γ, M, f, v_rel, ∂s/∂q, points): A·q̈ = γ,
    /// M·q̈ = f + Aᵀ·λ + Σ F·∂s/∂q.
    pub motion: Evaluator,
    /// Constraint rows held at their assembled value (locked angles).
    pub locked: Vec<usize>,
    /// The frictions, in the order of the joints.
    pub frictions: Vec<FrictionModel>,
    /// The number of points of the drawing.
    pub points: usize,
    /// The drawing's bodies and joints.
    pub drawing: Drawing,
}

/// Where the outputs of [`Model::motion`] start.
pub(super) struct MotionLayout {
    pub gamma: usize,
    pub mass: usize,
    pub forcing: usize,
    pub relative: usize,
    pub direction: usize,
    pub points: usize,
    pub len: usize,
}

impl Model {
    /// The layout of the motion program's outputs.
    pub fn layout(&self) -> MotionLayout {
        let (n, nf) = (self.n, self.frictions.len());
        let gamma = 0;
        let mass = gamma + n;
        let forcing = mass + n * n;
        let relative = forcing + n;
        let direction = relative + nf;
        let points = direction + nf * n;
        MotionLayout {
            gamma,
            mass,
            forcing,
            relative,
            direction,
            points,
            len: points + 2 * self.points,
        }
    }

    /// Compile the mechanism of `scene` (whose equations are `lag`) with
    /// the parameters' values.
    pub fn new(
        scene: &Scene,
        lag: &Lagrange,
        params: &FxHashMap<Var, f64>,
    ) -> Result<Model, Diagnostic> {
        let n = scene.coordinates.len();
        let q: Vec<Var> = scene
            .coordinates
            .iter()
            .map(|c| atom::coord(&c.name, 0))
            .collect();
        let qd: Vec<Var> = scene
            .coordinates
            .iter()
            .map(|c| atom::coord(&c.name, 1))
            .collect();
        let t = atom::time();
        let mut g = Vec::with_capacity(n + n * n);
        let mut locked = Vec::new();
        for (j, c) in scene.constraints.iter().enumerate() {
            let angle = scene
                .joints
                .iter()
                .find(|jt| jt.constraints.get(1) == Some(&j) && jt.locked_angle.is_some())
                .and_then(|jt| jt.locked_angle.clone());
            match (c.holonomic, angle) {
                (true, _) => g.push(c.expression.clone()),
                (false, Some(a)) => {
                    locked.push(j);
                    g.push(a);
                }
                (false, None) => {
                    return Err(Diagnostic::error(c.span, format!("the constraint {} restricts the velocities, so it has no equation for the positions", c.label(j)))
                        .with_hint(qdot_mechanics::solve::integrable::hint(c, &q, "`qdot cycle` solves the positions from holonomic constraints: joints, drives and constraints without velocities")).with_kind(ErrorKind::Constraints))
                }
            }
        }
        for c in &scene.constraints {
            g.extend(c.coefficients.iter().cloned());
        }
        g.extend(scene.constraints.iter().map(|c| c.rest.clone()));
        let mut inputs = q.clone();
        inputs.push(t);
        let position = compile_with(&g, &inputs, params).map_err(compile_error)?;

        let mut outs: Vec<Expr> = lag.constraints.forcing.to_vec();
        outs.extend(lag.mass_matrix.iter().flatten().cloned());
        outs.extend(lag.forcing.iter().cloned());
        let mut frictions = Vec::new();
        let mut directions = Vec::new();
        for jt in &scene.joints {
            if let Some(f) = &jt.friction {
                let coefficient = constant(&f.coefficient, params)
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| Diagnostic::error(f.span, "the friction coefficient has no finite value with the parameters given").with_kind(ErrorKind::Undefined))?;
                if coefficient < 0.0 {
                    return Err(Diagnostic::error(f.span, format!("the friction coefficient is negative ({coefficient}) with the parameters given"))
                        .with_hint("Coulomb friction opposes the motion: its coefficient is ≥ 0").with_kind(ErrorKind::Unphysical));
                }
                frictions.push(FrictionModel {
                    joint: jt.name.clone(),
                    kind: jt.kind,
                    rows: jt.constraints.clone(),
                    coefficient,
                });
                outs.push(f.relative_velocity.clone());
                directions.extend(f.direction.iter().cloned());
            }
        }
        outs.extend(directions);
        let (points, drawing) = drawing(scene);
        let npoints = points.len() / 2;
        outs.extend(points);
        let mut inputs = q;
        inputs.extend(qd);
        inputs.push(t);
        let motion = compile_with(&outs, &inputs, params).map_err(compile_error)?;
        Ok(Model {
            n,
            position: Evaluator::new(position),
            motion: Evaluator::new(motion),
            locked,
            frictions,
            points: npoints,
            drawing,
        })
    }
}

/// The drive law f(t) compiled as t ↦ (f, ḟ).
pub(super) fn law(f: &Expr, params: &FxHashMap<Var, f64>) -> Result<Evaluator, Diagnostic> {
    let outs = [f.clone(), f.dt()];
    let p = compile_with(&outs, &[atom::time()], params).map_err(compile_error)?;
    Ok(Evaluator::new(p))
}

/// The value of a constant expression with the parameters' values.
fn constant(e: &Expr, params: &FxHashMap<Var, f64>) -> Option<f64> {
    let p = compile_with(std::slice::from_ref(e), &[], params).ok()?;
    let mut out = [0.0];
    Evaluator::new(p).eval(&[], &mut out);
    Some(out[0])
}

fn compile_error(e: CompileError) -> Diagnostic {
    Diagnostic::global(format!(
        "the mechanism's equations cannot be evaluated: {e}"
    ))
    .with_kind(e.kind())
}

/// The drawing's points (x, y pairs, flattened) and its bodies and joints:
/// every body's centre, then each joint's P and Q, then a slider's guide
/// point P + Û.
fn drawing(scene: &Scene) -> (Vec<Expr>, Drawing) {
    let mut pts: Vec<Expr> = Vec::new();
    let mut bodies: Vec<DrawnBody> = Vec::new();
    for b in &scene.bodies {
        let c = &b.mass_properties.centre;
        let k = pts.len() / 2;
        pts.push(c.first().cloned().unwrap_or_else(Expr::zero));
        pts.push(c.get(1).cloned().unwrap_or_else(Expr::zero));
        bodies.push(DrawnBody {
            name: b.name.clone(),
            particle: b.kind == crate::parse::ast::BodyKind::Particle,
            points: vec![k],
        });
    }
    let mut joints = Vec::new();
    for jt in &scene.joints {
        let p = pts.len() / 2;
        pts.extend(jt.points[0].iter().cloned());
        pts.extend(jt.points[1].iter().cloned());
        let q = p + 1;
        for (side, k) in [(0, p), (1, q)] {
            if let Some(b) = jt.bodies[side] {
                bodies[b].points.push(k);
            }
        }
        let guide = jt.along.as_ref().map(|unit| {
            let k = pts.len() / 2;
            pts.extend(jt.points[0].iter().zip(unit).map(|(pi, ui)| pi.add(ui)));
            [p, k]
        });
        joints.push(DrawnJoint {
            name: jt.name.clone(),
            kind: jt.kind,
            point: q,
            grounded: jt.bodies.iter().any(Option::is_none),
            guide,
        });
    }
    (pts, Drawing { bodies, joints })
}
