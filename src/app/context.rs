//! The context a command runs under, passed explicitly.

use crate::algebra::assume::{self, Assumptions};
use crate::budget;
use crate::diag::{too_large, Diagnostic};
use crate::expr::{print, Expr};
use crate::scene::Scene;

/// What an exact computation runs under: the work budget, and for a scene
/// its assumptions (`assume …`) and the order its coordinates print in
/// (ÿ₃ before θ̈₃ when `y3` is declared first).
///
/// The engine keeps the assumptions and the print order in thread-locals
/// that only [`Context::run`] sets, for the time of one computation (the
/// engine's functions that decide signs check that the scene's
/// assumptions are in force; a library user who calls them directly runs
/// them in `Scene::assumptions_in_force`); a front end (the CLI, the REPL,
/// Python, a library user) makes a context and passes it, and a report
/// keeps the context it was computed in, so that what it prints is what
/// the CLI prints.
#[derive(Clone, Debug)]
pub struct Context {
    max_terms: usize,
    assumptions: Assumptions,
    coordinate_order: Vec<String>,
}

impl Default for Context {
    fn default() -> Context {
        Context::new()
    }
}

impl Context {
    /// The default budget ([`crate::limits::DEFAULT_MAX_TERMS`]), no scene.
    pub fn new() -> Context {
        Context {
            max_terms: crate::limits::DEFAULT_MAX_TERMS,
            assumptions: Assumptions::default(),
            coordinate_order: Vec::new(),
        }
    }

    /// This context with a budget of `max_terms` terms (0: the default).
    pub fn with_max_terms(mut self, max_terms: usize) -> Context {
        self.max_terms = match max_terms {
            0 => crate::limits::DEFAULT_MAX_TERMS,
            n => n,
        };
        self
    }

    /// This context's budget, in terms.
    pub fn max_terms(&self) -> usize {
        self.max_terms
    }

    /// This context for `scene`: its assumptions and its coordinates'
    /// print order, the same budget.
    pub fn for_scene(&self, scene: &Scene) -> Context {
        Context {
            max_terms: self.max_terms,
            assumptions: scene.assumptions.clone(),
            coordinate_order: scene.coordinates.iter().map(|c| c.name.clone()).collect(),
        }
    }

    /// The coordinates in the order they print.
    pub fn coordinate_order(&self) -> &[String] {
        &self.coordinate_order
    }

    /// Run `f` with this context in force: within the budget (past it, the
    /// error of [`too_large`]), under the assumptions, terms in the print
    /// order. Contexts nest: the inner one applies, the outer is restored.
    pub fn run<T>(&self, f: impl FnOnce() -> Result<T, Diagnostic>) -> Result<T, Diagnostic> {
        self.within(f).unwrap_or_else(|e| Err(too_large(&e)))
    }

    /// [`Context::run`] for a front end that words the exceeded budget
    /// itself (the REPL names its `:max-terms`).
    pub fn within<T>(&self, f: impl FnOnce() -> T) -> Result<T, budget::TooLarge> {
        budget::within(self.max_terms, || {
            print::with_coordinate_order(&self.coordinate_order, || {
                assume::assuming(&self.assumptions, f)
            })
        })
    }

    /// `e` in qdot's input syntax, as the CLI's JSON writes it (re-parses
    /// to `e`).
    pub fn print(&self, e: &Expr) -> Result<String, Diagnostic> {
        self.run(|| Ok(print::input(e)))
    }

    /// `e` as the CLI's text output writes it (Unicode names, `·`, `−`).
    pub fn print_unicode(&self, e: &Expr) -> Result<String, Diagnostic> {
        self.run(|| Ok(print::unicode(e)))
    }
}
