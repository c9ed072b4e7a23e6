//! Typed reports: what each command computed, before any format.
//! [`crate::output`] renders them as text, JSON or LaTeX.

use super::{Command, Context};
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::mechanics::{Accelerations, Hamiltonian, Integrals, Lagrange};
use crate::scene::dimension::DimensionReport;
use crate::scene::Scene;
use crate::solve::equilibrium::{Equilibria, Values};
use crate::solve::oscillations::{Modes, NumericFree};
use crate::solve::system::BlockSolution;
use std::sync::Arc;

/// A command's result on a scene: `result`, with the scene it came from,
/// the context it was computed in (its print order and assumptions, so
/// that [`Report::print`] writes what the CLI writes) and the scene's
/// warnings.
#[derive(Clone, Debug)]
pub struct Report<T> {
    /// What the command computed.
    pub result: T,
    scene: Arc<Scene>,
    context: Context,
    warnings: Vec<Diagnostic>,
}

impl<T> Report<T> {
    pub(crate) fn new(
        result: T,
        scene: Arc<Scene>,
        context: Context,
        warnings: Vec<Diagnostic>,
    ) -> Report<T> {
        Report {
            result,
            scene,
            context,
            warnings,
        }
    }

    pub(crate) fn add_warnings(&mut self, more: Vec<Diagnostic>) {
        self.warnings.extend(more);
    }

    /// The scene the report is about.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The context the report was computed in.
    pub fn context(&self) -> &Context {
        &self.context
    }

    /// The warnings to show beside the result (the scene's, and the
    /// command's own).
    pub fn warnings(&self) -> &[Diagnostic] {
        &self.warnings
    }

    /// `e` in qdot's input syntax, its terms in the scene's order: what the
    /// CLI's JSON writes.
    pub fn print(&self, e: &Expr) -> Result<String, Diagnostic> {
        self.context.print(e)
    }

    /// `e` as the CLI's text output writes it.
    pub fn print_unicode(&self, e: &Expr) -> Result<String, Diagnostic> {
        self.context.print_unicode(e)
    }
}

/// `derive`: Lagrange's equations.
#[derive(Clone, Debug)]
pub struct Derived {
    /// The equations, the mass matrix M and the forcing f.
    pub lagrange: Lagrange,
}

/// `solve`: the accelerations and the scene's `solve` blocks.
#[derive(Clone, Debug)]
pub struct Solved {
    /// Lagrange's equations and the accelerations, for a scene with
    /// dynamics.
    pub dynamics: Option<(Lagrange, Accelerations)>,
    /// The force of each `reaction` statement, by component.
    pub reactions: Vec<Vec<Expr>>,
    /// The solutions of the `solve` blocks.
    pub blocks: Vec<BlockSolution>,
    /// For a driven mechanism (as many joint and drive conditions as
    /// coordinates): its equations and its reactions from the
    /// kinetostatics, in place of `dynamics`.
    pub mechanism: Option<Box<(Lagrange, crate::solve::kinetostatic::MechanismReactions)>>,
}

impl Solved {
    /// The acceleration q̈ of `coordinate`.
    pub fn acceleration(&self, coordinate: &str) -> Option<&Expr> {
        self.dynamics.as_ref()?.1.get(coordinate)
    }
}

/// `forces`: the generalized forces Q_k.
#[derive(Clone, Debug)]
pub struct Forces {
    /// The coordinates, in declaration order.
    pub coordinates: Vec<String>,
    /// Q_k, parallel to `coordinates`.
    pub forces: Vec<Expr>,
}

/// `modes`: the small oscillations, with a free response when initial
/// conditions were given (exact, or numeric at the `--set` values).
#[derive(Clone, Debug)]
pub struct Oscillations {
    /// M, C, K, the frequencies and the modes.
    pub modes: Modes,
    /// The `--set` values the frequencies are evaluated at.
    pub set: Values,
    /// The exact free response q_k(t), with `--init`.
    pub free: Option<Vec<Expr>>,
    /// The numeric free response, when the exact one cannot be written.
    pub numeric: Option<NumericFree>,
    /// `latex --standalone`: the title of a whole document, else `None`.
    pub standalone: Option<String>,
}

/// `latex`: the scene's main result as a LaTeX document, written when it
/// is rendered.
#[derive(Clone, Debug)]
pub struct LatexRequest {
    /// `--steps`: the derivation line by line.
    pub steps: bool,
    /// `--standalone`: a whole document, not a fragment.
    pub standalone: bool,
    /// The title of a standalone document.
    pub title: String,
    /// The `--set` values.
    pub set: Values,
}

// the numeric commands
/// `simulate`: one run, with the request it ran.
#[derive(Clone, Debug)]
pub struct Simulation {
    /// The table, the integrator's work and how the run ended.
    pub run: crate::simulate::run::Run,
    /// What was run (the parameter values in its `set`).
    pub request: crate::simulate::run::Request,
}

/// `sweep`: the runs, with what they varied.
#[derive(Clone, Debug)]
pub struct SweepStudy {
    /// One summary row per run.
    pub sweep: crate::simulate::sweep::Sweep,
    /// The request every run starts from (the values that do not vary).
    pub base: crate::simulate::run::Request,
    /// The varied names and their ranges.
    pub axes: Vec<crate::simulate::sweep::Axis>,
}

/// `codegen`: the source code, with the request it answers.
#[derive(Clone, Debug)]
pub struct GeneratedCode {
    /// The code.
    pub code: String,
    /// What was asked (the constants in its `set`).
    pub request: crate::simulate::codegen::CodegenRequest,
}

/// `simulate`'s report.
pub type SimulateReport = Report<Simulation>;
/// `sweep`'s report.
pub type SweepReport = Report<SweepStudy>;
/// `codegen`'s report.
pub type CodegenReport = Report<GeneratedCode>;

/// `derive`'s report.
pub type DeriveReport = Report<Derived>;
/// `solve`'s report.
pub type SolveReport = Report<Solved>;
/// `forces`' report.
pub type ForcesReport = Report<Forces>;
/// `equilibrium`'s report.
pub type EquilibriaReport = Report<Equilibria>;
/// `modes`' report.
pub type ModesReport = Report<Oscillations>;
/// `hamilton`'s report.
pub type HamiltonReport = Report<Hamiltonian>;
/// `integrals`' report.
pub type IntegralsReport = Report<Integrals>;
/// `check`'s report: the dimension of every name and result.
pub type CheckReport = Report<DimensionReport>;
/// `latex`'s report.
pub type LatexReport = Report<LatexRequest>;

// ---- the numeric studies: cycle, response, floquet ----

/// `cycle`: a mechanism over its cycle.
#[derive(Clone, Debug)]
pub struct CycleRun {
    /// The whole table (the pictures draw it).
    pub table: crate::cycle::CycleTable,
    /// Whether the varied quantity is an angle (shown in degrees; its
    /// column holds radians).
    pub degrees: bool,
    /// The table with only the `--columns` asked for after the varied
    /// one (what the text, CSV and JSON write), when they were.
    pub shown: Option<crate::cycle::CycleTable>,
}

impl CycleRun {
    /// The table the text, CSV and JSON write: [`CycleRun::shown`], else
    /// the whole table.
    pub fn shown(&self) -> &crate::cycle::CycleTable {
        self.shown.as_ref().unwrap_or(&self.table)
    }
}

/// `response`: the frequency response to the scene's harmonic load.
#[derive(Clone, Debug)]
pub enum FrequencyResponse {
    /// Without `--over`: the exact receptance, with the small oscillations
    /// it comes from and the `--set` values its closed forms are
    /// evaluated at.
    Exact(
        Box<(
            Modes,
            crate::solve::response::Response,
            crate::solve::equilibrium::Values,
        )>,
    ),
    /// With `--over Omega=…`: amplitude and phase swept numerically.
    Swept(crate::simulate::response::ResponseTable),
}

/// One point of a Floquet grid: the varied parameters' values, and the
/// analysis or why it failed.
pub type FloquetPoint = (Vec<f64>, Result<crate::floquet::Floquet, String>);

/// `floquet`: the Floquet stability at one point or over a grid.
#[derive(Clone, Debug)]
pub struct FloquetRun {
    /// The linearized scene.
    pub prepared: crate::floquet::Prepared,
    /// The axes (empty for one point).
    pub axes: Vec<crate::scene::given::GridAxis>,
    /// Without axes, the one point; else every grid point, the first
    /// axis varying fastest.
    pub points: Vec<FloquetPoint>,
}

/// `cycle`'s report.
pub type CycleReport = Report<CycleRun>;
/// `response`'s report.
pub type ResponseReport = Report<FrequencyResponse>;
/// `floquet`'s report.
pub type FloquetReport = Report<FloquetRun>;

/// The report of any command ([`super::run`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum AnyReport {
    /// `derive`.
    Derive(DeriveReport),
    /// `solve`.
    Solve(SolveReport),
    /// `forces`.
    Forces(ForcesReport),
    /// `equilibrium`.
    Equilibrium(EquilibriaReport),
    /// `modes`.
    Modes(ModesReport),
    /// `hamilton`.
    Hamilton(HamiltonReport),
    /// `integrals`.
    Integrals(IntegralsReport),
    /// `check`.
    Check(CheckReport),
    /// `latex`.
    Latex(LatexReport),
    /// `cycle`.
    Cycle(CycleReport),
    /// `response`.
    Response(ResponseReport),
    /// `floquet`.
    Floquet(FloquetReport),
    /// `simulate`.
    Simulate(SimulateReport),
    /// `sweep`.
    Sweep(SweepReport),
    /// `codegen`.
    Codegen(CodegenReport),
}

impl AnyReport {
    /// The command that made it.
    pub fn command(&self) -> Command {
        match self {
            AnyReport::Derive(_) => Command::Derive,
            AnyReport::Solve(_) => Command::Solve,
            AnyReport::Forces(_) => Command::Forces,
            AnyReport::Equilibrium(_) => Command::Equilibrium,
            AnyReport::Modes(_) => Command::Modes,
            AnyReport::Hamilton(_) => Command::Hamilton,
            AnyReport::Integrals(_) => Command::Integrals,
            AnyReport::Check(_) => Command::Check,
            AnyReport::Latex(_) => Command::Latex,
            AnyReport::Cycle(_) => Command::Cycle,
            AnyReport::Response(_) => Command::Response,
            AnyReport::Floquet(_) => Command::Floquet,
            AnyReport::Simulate(_) => Command::Simulate,
            AnyReport::Sweep(_) => Command::Sweep,
            AnyReport::Codegen(_) => Command::Codegen,
        }
    }

    /// The warnings to show beside the result.
    pub fn warnings(&self) -> &[Diagnostic] {
        match self {
            AnyReport::Derive(r) => r.warnings(),
            AnyReport::Solve(r) => r.warnings(),
            AnyReport::Forces(r) => r.warnings(),
            AnyReport::Equilibrium(r) => r.warnings(),
            AnyReport::Modes(r) => r.warnings(),
            AnyReport::Hamilton(r) => r.warnings(),
            AnyReport::Integrals(r) => r.warnings(),
            AnyReport::Check(r) => r.warnings(),
            AnyReport::Latex(r) => r.warnings(),
            AnyReport::Cycle(r) => r.warnings(),
            AnyReport::Response(r) => r.warnings(),
            AnyReport::Floquet(r) => r.warnings(),
            AnyReport::Simulate(r) => r.warnings(),
            AnyReport::Sweep(r) => r.warnings(),
            AnyReport::Codegen(r) => r.warnings(),
        }
    }
}
