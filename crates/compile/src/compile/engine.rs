//! Which engine runs a [`super::CompiledDynamics`]: the interpreter of the
//! register program, or the program compiled to machine code (`jit`).

/// What evaluates the compiled right-hand side (`qdot simulate
/// --evaluator`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Engine {
    /// With the `jit` feature, the interpreter for the first
    /// [`AUTO_JIT_AFTER_CALLS`] right-hand sides, then machine code where
    /// it compiles; without it, the interpreter.
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

/// `--evaluator auto` runs the interpreter for this many right-hand sides
/// before it compiles to machine code. Cranelift (built unoptimized, see
/// Cargo.toml) takes about 2 ms for a pendulum and 40 ms for a 10-link
/// chain, the time the interpreter takes for about 28,000 and 22,000 of
/// their right-hand sides (measured 2026-11-26): compiling once the
/// interpreter has spent what the compilation costs is never worse than
/// twice the better choice made in hindsight (the ski-rental rule), and
/// keeps short runs from paying for a compilation they cannot recoup.
pub const AUTO_JIT_AFTER_CALLS: u64 = 25_000;

/// The deferred compilation of `auto`, shared by the clones of one compiled
/// system (a sweep's runs count their calls together and compile once).
#[cfg(feature = "jit")]
#[derive(Clone, Debug)]
pub(super) struct Tier {
    shared: std::sync::Arc<TierShared>,
    /// Calls not yet added to the shared count (added in batches: an atomic
    /// add per call would cost a small system's right-hand side a third).
    local: u32,
    /// This clone ran the compilation (its time is not integration time).
    compiled_here: bool,
}

#[cfg(feature = "jit")]
#[derive(Debug, Default)]
struct TierShared {
    calls: std::sync::atomic::AtomicU64,
    outcome: std::sync::OnceLock<(Option<super::jit::JitRhs>, EngineReport)>,
}

#[cfg(feature = "jit")]
impl Tier {
    const BATCH: u32 = 1024;

    pub(super) fn new() -> Tier {
        Tier {
            shared: Default::default(),
            local: 0,
            compiled_here: false,
        }
    }

    /// Count one right-hand side; true when the machine code is due (or
    /// was already made by a clone).
    #[inline]
    pub(super) fn tick(&mut self) -> bool {
        self.local += 1;
        if self.local < Self::BATCH {
            return false;
        }
        self.local = 0;
        let before = self
            .shared
            .calls
            .fetch_add(Self::BATCH as u64, std::sync::atomic::Ordering::Relaxed);
        before + Self::BATCH as u64 >= AUTO_JIT_AFTER_CALLS || self.shared.outcome.get().is_some()
    }

    /// The machine code and its report, compiled by the first clone to ask.
    pub(super) fn outcome(
        &mut self,
        compile: impl FnOnce() -> (Option<super::jit::JitRhs>, EngineReport),
    ) -> &(Option<super::jit::JitRhs>, EngineReport) {
        let mut ran = false;
        let out = self.shared.outcome.get_or_init(|| {
            ran = true;
            compile()
        });
        // (later calls, after a failed compilation, must not clear it)
        self.compiled_here |= ran;
        out
    }

    /// The report of the deferred compilation, if it happened, and whether
    /// this clone ran it.
    pub(super) fn report(&self) -> Option<(EngineReport, bool)> {
        let (_, r) = self.shared.outcome.get()?;
        Some((r.clone(), self.compiled_here))
    }
}
