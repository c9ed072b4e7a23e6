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
//! assert_eq!(acc[0].1.to_string(), "-k*x/m + g");
//! ```
//!
//! The data's path: [`parse`] → [`scene`] → [`expr`] (canonical exact
//! expressions over [`poly`] and [`num`]) → [`mechanics`] → [`solve`] →
//! [`output`].

pub mod algebra;
pub mod budget;
pub mod cancel;
pub mod diag;
pub mod expr;
pub mod gallery;
pub mod limits;
pub mod mechanics;
pub mod num;
pub mod output;
pub mod parse;
pub mod poly;
pub mod repl;
pub mod scene;
pub mod simulate;
pub mod solve;
pub mod unicode;

pub use diag::Diagnostic;
pub use expr::Expr;
pub use mechanics::Lagrange;
pub use scene::Scene;

impl Scene {
    /// Derive Lagrange's equations.
    pub fn lagrange(&self) -> Result<Lagrange, Diagnostic> {
        Lagrange::derive(self)
    }
}

#[cfg(doctest)]
#[doc = include_str!("../book/src/library.md")]
pub struct BookLibraryChapter;
