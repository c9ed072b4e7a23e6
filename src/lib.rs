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

// The public API: the modules along the data's path, and the names a
// user needs at the root. The modules marked `doc(hidden)` are the engine's
// internals: public for the tests, benches and fuzz targets of this
// repository, without a promise of stability.
pub use qdot_exact::{expr, limits, num};
pub use qdot_mechanics::{mechanics, scene, solve};
pub use qdot_syntax::{diag, parse};
pub mod app;
pub mod output;
pub mod simulate;

#[doc(hidden)]
pub use qdot_exact::{algebra, budget, cancel, poly};
#[doc(hidden)]
pub use qdot_ode::dense;
#[doc(hidden)]
pub mod gallery;
#[doc(hidden)]
pub mod repl;
#[doc(hidden)]
pub use qdot_syntax::unicode;

pub use diag::{Diagnostic, Severity, Span};
pub use expr::Expr;
pub use mechanics::{Accelerations, Equation, Lagrange};
pub use num::Q;
pub use output::{run, run_with, Command, CommandOptions, Format};
pub use scene::{Scene, Value};
pub use solve::equilibrium::{equilibria, Equilibria, Stability};
pub use solve::oscillations::{modes, Modes};

#[cfg(doctest)]
#[doc = include_str!("../book/src/library.md")]
pub struct BookLibraryChapter;

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeExamples;
