//! Exact solving: linear systems over rational functions (square, for
//! accelerations; of any shape, for `solve` blocks) equilibria and small oscillations.

pub mod certify;
mod characteristic;
mod condition;
pub mod constrained;
mod definite;
pub mod eigen;
pub mod equilibrium;
mod hurwitz;
pub mod integrable;
pub mod kinetostatic;
mod linear_stability;
pub mod linearize;
pub mod numeric;
pub mod oscillations;
pub mod response;
pub mod steady;
pub mod system;

pub use crate::algebra::linear;
