//! Exact solving: linear systems over rational functions (square, for
//! accelerations; of any shape, for `solve` blocks) and equilibria.

pub mod certify;
pub mod eigen;
pub mod equilibrium;
pub mod linear;
pub mod numeric;
pub mod system;
