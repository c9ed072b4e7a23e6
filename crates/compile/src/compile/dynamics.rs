//! [`CompiledDynamics`]: M and f (or q̈) compiled, as a [`System`].

use crate::expr::atom;
use crate::expr::Expr;
use crate::mechanics::{Accelerations, Lagrange};
use crate::poly::Var;
use qdot_ode::System;
use rustc_hash::FxHashMap;

use super::builder::{compile_through, compile_with};
use super::engine::{Engine, EngineReport};
use super::error::CompileError;
use super::program::Program;
use super::solve_spd;

/// How [`CompiledDynamics`] gets q̈.
#[derive(Clone, Debug)]
enum Mode {
    /// Outputs: M's upper triangle (row by row) then f; solve each time.
    MassMatrix,
    /// Outputs: f; M was constant, factored once and its inverse kept
    /// (row-major), so q̈ = M⁻¹·f is one product with no division.
    ConstantMass(Vec<f64>),
    /// Outputs: the exact accelerations.
    Accelerations,
    /// Outputs: the accelerations by the articulated-body recursion.
    Articulated,
}

/// How a [`CompiledDynamics`] evaluates q̈.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluator {
    /// M (upper triangle) and f compiled, M·q̈ = f solved at each call
    /// (Cholesky, Golub & Van Loan 4.2.5): about n³/3 + 2n² flops, n
    /// square roots and n(n − 1)/2 + 2n divisions.
    MassMatrix,
    /// f compiled; the constant M factored once at compile time and M⁻¹
    /// kept, so each call is one product (n² multiplications).
    ConstantMass,
    /// The exact accelerations q̈ = M⁻¹·f (`Lagrange::accelerations`)
    /// compiled: no solve.
    Accelerations,
    /// The accelerations of a tree of rigid bodies by the articulated-body
    /// recursion (`Lagrange::articulated_accelerations`) compiled: O(n)
    /// operations, no solve.
    Articulated,
}

impl Evaluator {
    /// The name in `--stats` and JSON: `mass_matrix`, `constant_mass`,
    /// `accelerations`, `articulated`.
    pub fn name(self) -> &'static str {
        match self {
            Evaluator::MassMatrix => "mass_matrix",
            Evaluator::ConstantMass => "constant_mass",
            Evaluator::Accelerations => "accelerations",
            Evaluator::Articulated => "articulated",
        }
    }
}

/// The largest number of coordinates for which [`CompiledDynamics::best`]
/// derives the exact accelerations to compare: their expressions (Cramer's
/// rule, exact) grow quickly with n — for the pendulum chain ≈ 0.1 ms at
/// n = 2 and ≈ 5 ms at n = 3 to derive, and at n = 3 the compiled program
/// is already ≈ 1.3 times as slow as M, f and the solve.
pub const BEST_MAX_N: usize = 3;

/// Weights of [`CompiledDynamics::estimated_cost`], in additions: a
/// division and a function call (sin, cos, sin_cos, exp, …) take several
/// times the latency of an addition or a multiplication.
pub const DIVISION_COST: f64 = 4.0;
/// See `DIVISION_COST`.
pub const CALL_COST: f64 = 20.0;

/// What [`CompiledDynamics::best`] chose, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// The evaluator kept.
    pub evaluator: Evaluator,
    /// The estimated cost per right-hand side of M and f with their solve
    /// ([`CompiledDynamics::estimated_cost`]).
    pub mass_cost: f64,
    /// The estimated cost of the compiled exact accelerations; `None` when
    /// they were not derived (n > `BEST_MAX_N`, or no exact solution).
    pub accelerations_cost: Option<f64>,
    /// Why, in a few words for `--stats` (the estimated costs compared, or
    /// why the exact accelerations were not derived).
    pub reason: String,
}

/// Lagrange's equations M(q, t)·q̈ = f(q, q̇, t) compiled for simulation:
/// the state is y = (q, q̇) and y' = (q̇, M⁻¹·f). The program's inputs are
/// `[t, q₁ … qₙ, q̇₁ … q̇ₙ]`; every parameter is bound at compile time.
#[derive(Clone, Debug)]
pub struct CompiledDynamics {
    n: usize,
    program: Program,
    mode: Mode,
    /// The register file, constants loaded (see [`Program::run`]).
    regs: Vec<f64>,
    m: Vec<f64>,
    f: Vec<f64>,
    /// The right-hand side as machine code, when [`Self::use_engine`] made it.
    #[cfg(feature = "jit")]
    jit: Option<super::jit::JitRhs>,
    /// `auto`'s compilation, until it is made or refused.
    #[cfg(feature = "jit")]
    tier: Option<super::engine::Tier>,
}

/// Whether no entry of `entries` depends on an input (M evaluated once):
/// an entry through `tape`'s intermediates is taken to move (the tape knows
/// what they depend on, the atom not).
pub fn is_constant(
    entries: &[Expr],
    inputs: &[Var],
    tape: Option<&crate::expr::tape::Tape>,
) -> bool {
    tape.is_none_or(|t| t.used_by(entries).is_empty())
        && entries
            .iter()
            .all(|e| inputs.iter().all(|&v| !e.depends_on(v)))
}

/// The input atoms `[t, q…, q̇…]` of a [`CompiledDynamics`] program.
pub fn state_inputs(coordinates: &[String]) -> Vec<Var> {
    let mut v = vec![atom::time()];
    v.extend(coordinates.iter().map(|c| atom::coord(c, 0)));
    v.extend(coordinates.iter().map(|c| atom::coord(c, 1)));
    v
}

impl CompiledDynamics {
    /// Compile M and f of `lagrange` with the parameter values `params`.
    pub fn new(lagrange: &Lagrange, params: &FxHashMap<Var, f64>) -> Result<Self, CompileError> {
        Self::from_parts_through(
            &lagrange.coordinates,
            &lagrange.mass_matrix,
            &lagrange.forcing,
            params,
            lagrange.intermediates.as_deref(),
        )
    }

    /// Compile a mass matrix (symmetric; its upper triangle is read) and a
    /// forcing vector over `coordinates`. When no entry of M depends on the
    /// coordinates, their velocities or t, M is evaluated and factored once.
    pub fn from_parts(
        coordinates: &[String],
        mass: &[Vec<Expr>],
        forcing: &[Expr],
        params: &FxHashMap<Var, f64>,
    ) -> Result<Self, CompileError> {
        Self::from_parts_through(coordinates, mass, forcing, params, None)
    }

    /// [`CompiledDynamics::from_parts`] for M and f written through the
    /// intermediates of `tape` ([`compile_through`]).
    pub fn from_parts_through(
        coordinates: &[String],
        mass: &[Vec<Expr>],
        forcing: &[Expr],
        params: &FxHashMap<Var, f64>,
        tape: Option<&crate::expr::tape::Tape>,
    ) -> Result<Self, CompileError> {
        let n = coordinates.len();
        if mass.len() != n || mass.iter().any(|r| r.len() != n) || forcing.len() != n {
            return Err(CompileError::Shape(format!(
                "the mass matrix must be {n}×{n} and the forcing of length {n}"
            )));
        }
        let inputs = state_inputs(coordinates);
        let upper: Vec<Expr> = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| mass[i][j].clone())
            .collect();
        if is_constant(&upper, &inputs, tape) {
            let pm = compile_with(&upper, &inputs, params)?;
            let mut vals = vec![0.0; upper.len()];
            pm.eval(&vec![0.0; inputs.len()], &mut pm.registers(), &mut vals);
            let mut m = vec![0.0; n * n];
            // M⁻¹ column by column, once, at construction (Cholesky, else
            // Gaussian elimination when M is not numerically positive
            // definite): each step is then one product and no division.
            let mut inverse = vec![0.0; n * n];
            let mut col = vec![0.0; n];
            for j in 0..n {
                fill_symmetric(&vals, &mut m, n);
                col.fill(0.0);
                col[j] = 1.0;
                solve_spd(&mut m, &mut col, n).map_err(|e| match e {
                    CompileError::Singular { column, .. } => CompileError::Singular {
                        column,
                        constant_mass: true,
                    },
                    e => e,
                })?;
                for i in 0..n {
                    inverse[i * n + j] = col[i];
                }
            }
            let program = compile_through(forcing, &inputs, params, tape)?;
            return Ok(Self::with(n, program, Mode::ConstantMass(inverse)));
        }
        let mut outputs = upper;
        outputs.extend(forcing.iter().cloned());
        let program = compile_through(&outputs, &inputs, params, tape)?;
        Ok(Self::with(n, program, Mode::MassMatrix))
    }

    /// Compile the exact accelerations q̈ = M⁻¹·f of `lagrange` instead
    /// (cheaper for small systems, whose exact inverse is small).
    pub fn from_accelerations(
        lagrange: &Lagrange,
        params: &FxHashMap<Var, f64>,
    ) -> Result<Self, CompileError> {
        let acc = lagrange
            .accelerations()
            .map_err(|d| CompileError::NoAccelerations(d.message))?;
        let exprs: Vec<Expr> = acc.values().to_vec();
        let n = lagrange.coordinates.len();
        let inputs = state_inputs(&lagrange.coordinates);
        let program = compile_through(&exprs, &inputs, params, acc.intermediates())?;
        Ok(Self::with(n, program, Mode::Accelerations))
    }

    /// Compile accelerations of `lagrange`'s coordinates derived by the
    /// articulated-body recursion ([`Lagrange::articulated_accelerations`]).
    pub fn from_articulated(
        lagrange: &Lagrange,
        acc: &Accelerations,
        params: &FxHashMap<Var, f64>,
    ) -> Result<Self, CompileError> {
        let n = lagrange.coordinates.len();
        let inputs = state_inputs(&lagrange.coordinates);
        let program = compile_through(acc.values(), &inputs, params, acc.intermediates())?;
        Ok(Self::with(n, program, Mode::Articulated))
    }

    /// [`CompiledDynamics::best`] with the articulated-body recursion's
    /// accelerations as one more candidate, when the scene has them.
    pub fn best_among(
        lagrange: &Lagrange,
        params: &FxHashMap<Var, f64>,
        articulated: Option<&Accelerations>,
    ) -> Result<(Self, Choice), CompileError> {
        let (kept, mut choice) = Self::best(lagrange, params)?;
        let Some(acc) = articulated else {
            return Ok((kept, choice));
        };
        let rec = Self::from_articulated(lagrange, acc, params)?;
        let cost = rec.estimated_cost();
        let other = kept.estimated_cost();
        if cost < other {
            choice.reason = format!(
                "≈ {cost:.0} flops per RHS by the articulated-body recursion against ≈ {other:.0} for {}",
                choice.evaluator.name()
            );
            choice.evaluator = Evaluator::Articulated;
            return Ok((rec, choice));
        }
        choice.reason = format!(
            "{}; ≈ {cost:.0} flops by the articulated-body recursion",
            choice.reason
        );
        Ok((kept, choice))
    }

    /// The cheaper evaluator of q̈ for `lagrange`: M and f with their solve
    /// ([`CompiledDynamics::new`]) and, for n ≤ `BEST_MAX_N` coordinates,
    /// the exact accelerations ([`CompiledDynamics::from_accelerations`]);
    /// the one with the smaller [`CompiledDynamics::estimated_cost`] is
    /// kept, the exact accelerations on a tie. For n > `BEST_MAX_N`, or
    /// when the exact accelerations cannot be derived, M and f are used
    /// without deriving anything more. An error only when M and f do not
    /// compile.
    pub fn best(
        lagrange: &Lagrange,
        params: &FxHashMap<Var, f64>,
    ) -> Result<(Self, Choice), CompileError> {
        let via_m = Self::new(lagrange, params)?;
        let mass_cost = via_m.estimated_cost();
        let n = via_m.n;
        let what = |d: &Self| match d.evaluator() {
            Evaluator::ConstantMass => "f with the constant M inverted once",
            _ => "M and f with a Cholesky solve",
        };
        if n > BEST_MAX_N {
            let reason = format!(
                "{n} coordinates (more than {BEST_MAX_N}): the exact accelerations are not derived"
            );
            let evaluator = via_m.evaluator();
            return Ok((
                via_m,
                Choice {
                    evaluator,
                    mass_cost,
                    accelerations_cost: None,
                    reason,
                },
            ));
        }
        // the exact accelerations are an option: past the work budget, M
        // and f serve (the budget of the caller, nested so it unwinds here)
        let exact = crate::budget::probe(crate::budget::limit(), || {
            Self::from_accelerations(lagrange, params)
        });
        let exact = exact.unwrap_or_else(|e| {
            Err(CompileError::NoAccelerations(format!(
                "past the work budget ({})",
                e.message()
            )))
        });
        let via_acc = match exact {
            Ok(d) => d,
            Err(e) => {
                let reason = format!("no exact accelerations: {e}");
                let evaluator = via_m.evaluator();
                return Ok((
                    via_m,
                    Choice {
                        evaluator,
                        mass_cost,
                        accelerations_cost: None,
                        reason,
                    },
                ));
            }
        };
        let acc_cost = via_acc.estimated_cost();
        let (kept, reason) = if acc_cost <= mass_cost {
            let reason = format!(
                "≈ {acc_cost:.0} flops per RHS against ≈ {mass_cost:.0} for {}",
                what(&via_m)
            );
            (via_acc, reason)
        } else {
            let reason = format!(
                "≈ {mass_cost:.0} flops per RHS against ≈ {acc_cost:.0} for the exact accelerations"
            );
            (via_m, reason)
        };
        let evaluator = kept.evaluator();
        Ok((
            kept,
            Choice {
                evaluator,
                mass_cost,
                accelerations_cost: Some(acc_cost),
                reason,
            },
        ))
    }

    /// The estimated cost of one right-hand side, in flops: the program's
    /// additions and multiplications ([`Program::op_counts`]), divisions
    /// weighted by `DIVISION_COST` and function calls by `CALL_COST`,
    /// plus the solve. For a varying M: n³/3 + 2n² additions and
    /// multiplications (Cholesky and the two triangular solves),
    /// n(n − 1)/2 + 2n divisions and n square roots (weighted as divisions: they lie
    /// on the solve's critical path), and n² + n copies (M filled from its
    /// upper triangle, f). For a constant M: the product with the kept M⁻¹,
    /// n² multiplications and n(n − 1) additions. Nothing for the exact
    /// accelerations.
    pub fn estimated_cost(&self) -> f64 {
        estimated_cost_of(&self.program, self.evaluator(), self.n)
    }

    /// How q̈ is evaluated.
    pub fn evaluator(&self) -> Evaluator {
        match self.mode {
            Mode::MassMatrix => Evaluator::MassMatrix,
            Mode::ConstantMass(_) => Evaluator::ConstantMass,
            Mode::Accelerations => Evaluator::Accelerations,
            Mode::Articulated => Evaluator::Articulated,
        }
    }

    fn with(n: usize, program: Program, mode: Mode) -> Self {
        CompiledDynamics {
            n,
            regs: program.registers(),
            m: vec![0.0; n * n],
            f: vec![0.0; n],
            program,
            mode,
            #[cfg(feature = "jit")]
            jit: None,
            #[cfg(feature = "jit")]
            tier: None,
        }
    }

    /// Run the right-hand side ([`System::rhs`]) on `engine`: the
    /// interpreter; the whole right-hand side compiled to machine code now
    /// (`Jit`); or the interpreter until [`super::AUTO_JIT_AFTER_CALLS`]
    /// right-hand sides, machine code after (`Auto`: see
    /// [`Self::deferred_engine`]). The interpreter stays when compiling
    /// fails or the `jit` feature is off, with the reason in the report.
    /// Never panics.
    pub fn use_engine(&mut self, engine: Engine) -> EngineReport {
        #[cfg(feature = "jit")]
        {
            self.jit = None;
            self.tier = None;
            match engine {
                Engine::Interpreter => {
                    EngineReport::interpreter(engine, 0.0, "--evaluator interpreter")
                }
                Engine::Auto => {
                    self.tier = Some(super::engine::Tier::new());
                    EngineReport::interpreter(
                        engine,
                        0.0,
                        format!(
                            "auto: fewer than {} right-hand sides, too few to pay for machine code",
                            crate::budget::grouped(super::engine::AUTO_JIT_AFTER_CALLS as usize)
                        ),
                    )
                }
                Engine::Jit => {
                    let (jit, report) = self.compile_jit(engine);
                    self.jit = jit;
                    report
                }
            }
        }
        #[cfg(not(feature = "jit"))]
        match engine {
            Engine::Interpreter => {
                EngineReport::interpreter(engine, 0.0, "--evaluator interpreter")
            }
            _ => EngineReport::interpreter(engine, 0.0, "built without the `jit` feature"),
        }
    }

    /// The machine code of the right-hand side, or the report of why not.
    #[cfg(feature = "jit")]
    fn compile_jit(&self, engine: Engine) -> (Option<super::jit::JitRhs>, EngineReport) {
        let start = std::time::Instant::now();
        let tail = match &self.mode {
            Mode::MassMatrix => super::jit::Tail::MassMatrix,
            Mode::ConstantMass(inv) => super::jit::Tail::ConstantMass(inv),
            Mode::Accelerations | Mode::Articulated => super::jit::Tail::Accelerations,
        };
        // Cranelift reports its errors, but a panic inside it must not
        // end the run either: the interpreter takes over
        let compiled = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            super::jit::compile_rhs(&self.program, self.n, tail)
        }))
        .unwrap_or_else(|_| Err(super::jit::JitError("Cranelift panicked".into())));
        match compiled {
            Ok(j) => {
                let report = EngineReport {
                    requested: engine,
                    ran: Engine::Jit,
                    compile_seconds: j.compile_seconds(),
                    code_bytes: j.code_bytes(),
                    reason: None,
                };
                (Some(j), report)
            }
            Err(e) => (
                None,
                EngineReport::interpreter(
                    engine,
                    start.elapsed().as_secs_f64(),
                    format!("the JIT could not compile the program: {e}"),
                ),
            ),
        }
    }

    /// `auto`'s compilation made during the run, if the run was long enough
    /// (or a clone's was): its report, and whether this system spent the
    /// compile time (inside its integration's wall time).
    pub fn deferred_engine(&self) -> Option<(EngineReport, bool)> {
        #[cfg(feature = "jit")]
        if let Some(t) = &self.tier {
            return t.report();
        }
        None
    }

    /// Adopt `auto`'s machine code (compiling it if no clone has).
    #[cfg(feature = "jit")]
    #[cold]
    fn adopt_deferred(&mut self) {
        let Some(mut tier) = self.tier.take() else {
            return;
        };
        let (jit, _) = tier.outcome(|| self.compile_jit(Engine::Auto));
        self.jit = jit.clone();
        // kept for its report
        self.tier = Some(tier);
    }

    /// What runs [`System::rhs`]: [`Engine::Jit`] after a successful
    /// [`Self::use_engine`], else [`Engine::Interpreter`].
    pub fn engine(&self) -> Engine {
        #[cfg(feature = "jit")]
        if self.jit.is_some() {
            return Engine::Jit;
        }
        Engine::Interpreter
    }

    /// y' at (t, y) by the interpreter whatever [`Self::engine`] is (the
    /// oracle of the machine code).
    pub fn rhs_interpreted(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        if y.len() != 2 * n || dy.len() != 2 * n {
            dy.fill(f64::NAN);
            return;
        }
        let (dq, dqd) = dy.split_at_mut(n);
        copy_small(dq, &y[n..]);
        // y = (q, q̇) is the program's input after t: one copy
        let off = self.program.input_offset();
        self.regs[off] = t;
        copy_small(&mut self.regs[off + 1..off + 1 + 2 * n], y);
        self.program.run(&mut self.regs);
        if self.finish(dqd).is_err() {
            dqd.fill(f64::NAN);
        }
    }

    /// The number of coordinates.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The compiled program (inputs `[t, q…, q̇…]`).
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Whether M was found constant and factored once.
    pub fn constant_mass(&self) -> bool {
        matches!(self.mode, Mode::ConstantMass(_))
    }

    /// Evaluate M (full, row-major, n×n) and f at (t, q, q̇) — only for a
    /// program compiled from M and f (else an error).
    pub fn mass_and_forcing(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        m: &mut [f64],
        f: &mut [f64],
    ) -> Result<(), CompileError> {
        let n = self.n;
        if q.len() != n || qd.len() != n || m.len() != n * n || f.len() != n {
            return Err(CompileError::Shape(format!(
                "expected {n} coordinates and an {n}×{n} matrix"
            )));
        }
        self.load(t, q, qd);
        let (regs, outs) = (&self.regs, self.program.output_registers());
        match &self.mode {
            Mode::MassMatrix => {
                let k = n * (n + 1) / 2;
                let mut idx = 0;
                for i in 0..n {
                    for j in i..n {
                        let v = regs[outs[idx] as usize];
                        m[i * n + j] = v;
                        m[j * n + i] = v;
                        idx += 1;
                    }
                }
                for (fi, &o) in f.iter_mut().zip(&outs[k..]) {
                    *fi = regs[o as usize];
                }
                Ok(())
            }
            Mode::ConstantMass(_) => Err(CompileError::NoMassMatrix(
                "the mass matrix is constant and factored",
            )),
            Mode::Accelerations | Mode::Articulated => Err(CompileError::NoMassMatrix(
                "compiled from the accelerations",
            )),
        }
    }

    /// Write (t, q, q̇) into the input registers and run the program.
    #[inline]
    fn load(&mut self, t: f64, q: &[f64], qd: &[f64]) {
        let off = self.program.input_offset();
        let r = &mut self.regs[off..off + 1 + 2 * self.n];
        r[0] = t;
        let (rq, rqd) = r[1..].split_at_mut(self.n);
        copy_small(rq, q);
        copy_small(rqd, qd);
        self.program.run(&mut self.regs);
    }

    /// q̈ at (t, q, q̇), allocation-free. An error when M is singular there
    /// (or the slices have the wrong length).
    pub fn accelerations(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        qdd: &mut [f64],
    ) -> Result<(), CompileError> {
        let n = self.n;
        if q.len() != n || qd.len() != n || qdd.len() != n {
            return Err(CompileError::Shape(format!("expected {n} coordinates")));
        }
        self.load(t, q, qd);
        self.finish(qdd)
    }

    /// q̈ from the program's outputs (after [`Self::load`]), by the mode.
    #[inline]
    fn finish(&mut self, qdd: &mut [f64]) -> Result<(), CompileError> {
        let n = self.n;
        let (regs, outs) = (&self.regs, self.program.output_registers());
        match &self.mode {
            Mode::Accelerations | Mode::Articulated => {
                for (a, &o) in qdd.iter_mut().zip(outs) {
                    *a = regs[o as usize];
                }
            }
            Mode::ConstantMass(inv) => {
                // q̈ = M⁻¹·f, f read from its registers.
                for (a, row) in qdd.iter_mut().zip(inv.chunks_exact(n)) {
                    *a = row
                        .iter()
                        .zip(outs)
                        .map(|(m, &o)| m * regs[o as usize])
                        .sum();
                }
            }
            Mode::MassMatrix => {
                let k = n * (n + 1) / 2;
                let mut idx = 0;
                for i in 0..n {
                    for j in i..n {
                        let v = regs[outs[idx] as usize];
                        self.m[i * n + j] = v;
                        self.m[j * n + i] = v;
                        idx += 1;
                    }
                }
                for (fi, &o) in self.f.iter_mut().zip(&outs[k..]) {
                    *fi = regs[o as usize];
                }
                solve_spd(&mut self.m, &mut self.f, n)?;
                qdd.copy_from_slice(&self.f);
            }
        }
        Ok(())
    }
}

/// [`CompiledDynamics::estimated_cost`] of `program` evaluated as
/// `evaluator` for `n` coordinates (the program's outputs as
/// [`CompiledDynamics`] lays them out: M's upper triangle then f, f alone,
/// or q̈): also the yardstick of `simulate::codegen`'s choice.
pub fn estimated_cost_of(program: &Program, evaluator: Evaluator, n: usize) -> f64 {
    let (add, mul, div, call) = program.op_counts();
    let n = n as f64;
    let solve = match evaluator {
        Evaluator::MassMatrix => {
            n * n * n / 3.0
                + 2.0 * n * n
                + DIVISION_COST * (n * (n - 1.0) / 2.0 + 3.0 * n)
                + n * n
                + n
        }
        Evaluator::ConstantMass => 2.0 * n * n - n,
        Evaluator::Accelerations | Evaluator::Articulated => 0.0,
    };
    (add + mul) as f64 + DIVISION_COST * div as f64 + CALL_COST * call as f64 + solve
}

/// The full symmetric matrix from its upper triangle, row by row.
fn fill_symmetric(upper: &[f64], m: &mut [f64], n: usize) {
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            m[i * n + j] = upper[k];
            m[j * n + i] = upper[k];
            k += 1;
        }
    }
}

impl System for CompiledDynamics {
    fn dim(&self) -> usize {
        2 * self.n
    }

    /// y = (q, q̇), y' = (q̇, M⁻¹·f); NaN accelerations where M is singular
    /// (the integrators stop with `Status::NotFinite`). By the machine code
    /// after [`CompiledDynamics::use_engine`], by the interpreter where its
    /// Cholesky factorization fails (M not numerically positive definite:
    /// `solve_spd` goes on by Gaussian elimination) or without it.
    #[inline]
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        #[cfg(feature = "jit")]
        {
            if self.jit.is_none() && self.tier.as_mut().is_some_and(|t| t.tick()) {
                self.adopt_deferred();
            }
            if let Some(j) = &self.jit {
                if y.len() == 2 * self.n && dy.len() == 2 * self.n && j.rhs(t, y, dy) {
                    return;
                }
            }
        }
        self.rhs_interpreted(t, y, dy)
    }
}

/// `dst.copy_from_slice(src)` (equal lengths), as plain moves for the
/// lengths of small systems: a right-hand side of a few flops would
/// otherwise spend a good part of its time in `memcpy` calls.
#[inline(always)]
fn copy_small(dst: &mut [f64], src: &[f64]) {
    macro_rules! fixed {
        ($($k:literal)*) => {
            match src.len() {
                $($k => dst[..$k].copy_from_slice(&src[..$k]),)*
                _ => dst.copy_from_slice(src),
            }
        };
    }
    fixed!(1 2 3 4 5 6 7 8)
}
