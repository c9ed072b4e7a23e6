//! qdot's mechanics: the scene a `.qd` file describes ([`scene`]: names,
//! kinematics, energies, loads, constraints, resolved and checked),
//! Lagrange's and Hamilton's equations derived from it ([`mechanics`]),
//! and what is solved exactly ([`solve`]: accelerations, reactions,
//! equilibria and their stability, natural frequencies and modes).

#![warn(missing_docs)]

pub mod mechanics;
pub mod scene;
pub mod solve;

// the lower layers, by the paths this crate's modules use
use qdot_exact::{algebra, budget, expr, limits, num, poly, rng};
use qdot_ode::dense;
use qdot_syntax::{diag, parse, spelling};

use diag::Diagnostic;
use mechanics::Lagrange;
use scene::Scene;

impl Scene {
    /// Derive Lagrange's equations.
    pub fn lagrange(&self) -> Result<Lagrange, Diagnostic> {
        Lagrange::derive(self)
    }
}
