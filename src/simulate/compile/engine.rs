//! Which engine runs a [`super::CompiledDynamics`]: the interpreter of the
//! register program, or the program compiled to machine code (`jit`).

/// What evaluates the compiled right-hand side (`qdot simulate
/// --evaluator`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Engine {
    /// Machine code when it compiles (the `jit` feature), else the
    /// interpreter.
    #[default]
    Auto,
    /// The interpreter of the register program ([`super::Program::run`]):
    /// the fallback and the oracle.
    Interpreter,
    /// Machine code (Cranelift); the interpreter, with the reason, when it
    /// cannot be had.
    Jit,
}

impl Engine {
    /// `auto`, `interpreter`, `jit`.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Auto => "auto",
            Engine::Interpreter => "interpreter",
            Engine::Jit => "jit",
        }
    }

    /// The engine named `s` (`auto`, `interpreter`, `jit`).
    pub fn by_name(s: &str) -> Option<Engine> {
        match s.to_ascii_lowercase().as_str() {
            "auto" => Some(Engine::Auto),
            "interpreter" => Some(Engine::Interpreter),
            "jit" => Some(Engine::Jit),
            _ => None,
        }
    }
}

/// What [`super::CompiledDynamics::use_engine`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct EngineReport {
    /// What was asked.
    pub requested: Engine,
    /// What runs: [`Engine::Interpreter`] or [`Engine::Jit`].
    pub ran: Engine,
    /// Wall time of the compilation to machine code (0 for the
    /// interpreter; also spent when it failed).
    pub compile_seconds: f64,
    /// The size of the machine code in bytes (0 for the interpreter).
    pub code_bytes: usize,
    /// Why the interpreter runs, when it does (`None` for the JIT).
    pub reason: Option<String>,
}

impl EngineReport {
    /// The interpreter, asked for or fallen back to.
    pub fn interpreter(requested: Engine, compile_seconds: f64, reason: impl Into<String>) -> Self {
        EngineReport {
            requested,
            ran: Engine::Interpreter,
            compile_seconds,
            code_bytes: 0,
            reason: Some(reason.into()),
        }
    }
}
