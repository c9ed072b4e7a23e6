//! # qdot — exact analytical mechanics
//!
//! qdot reads a *scene* (generalized coordinates, parameters, a kinematic
//! table, the kinetic energy, force function or potential, work of
//! non-conservative forces, dissipation) and derives Lagrange's equations in
//! closed form, then solves what can be solved exactly.
//!
//! ```
//! use qdot::Scene;
//! // Seed problem 21.2 / 23.4 style: a body on a spring.
//! let scene = Scene::parse("
//!     coordinates x
//!     parameters m, k, g
//!     kinetic E = 1/2*m*x'^2
//!     forcefunction U = m*g*x - 1/2*k*x^2
//! ").unwrap();
//! let acc = scene.lagrange().unwrap().accelerations().unwrap();
//! assert_eq!(acc["x"].to_string(), "-k*x/m + g");
//! ```
//!
//! The data's path: [`parse`] → [`scene`] → [`expr`] (canonical exact
//! expressions over [`poly`] and [`num`]) → [`mechanics`] → [`solve`] →
//! [`output`].

#![warn(missing_docs)]

// The public API: the modules along the data's path, the application
// layer, and the names a user needs at the root. The engine's internals
// are behind one hidden module, `engine`.
pub use qdot_exact::{budget, expr, limits, num};
pub use qdot_mechanics::{mechanics, scene, solve};
pub use qdot_study::{cycle, floquet};
pub use qdot_syntax::{diag, parse, spelling};
pub mod app;
#[cfg(feature = "drawing")]
pub mod drawing;
pub mod output;
pub mod repl;
pub mod simulate;

#[doc(hidden)]
pub mod engine;

// the engine's modules by the paths this crate's own code uses
use engine::gallery;
use qdot_exact::{algebra, poly};

pub use app::{AnyReport, Command, CommandOptions, Context, Format, Report};
pub use diag::{Diagnostic, Severity, Span};
pub use expr::Expr;
pub use mechanics::{Accelerations, Equation, Lagrange};
pub use num::Q;
pub use output::{render, run, run_with};
pub use scene::{Scene, Value};
pub use solve::equilibrium::{equilibria, Equilibria, Stability};
pub use solve::oscillations::{modes, Modes};

#[cfg(doctest)]
#[doc = include_str!("../book/src/library.md")]
pub struct BookLibraryChapter;

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeExamples;
