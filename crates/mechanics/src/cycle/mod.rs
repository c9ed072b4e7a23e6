//! Planar mechanisms over a cycle: the positions by Newton's method on
//! the joints' constraints, continued position by position on one
//! assembly branch; the velocities and accelerations from the exact
//! linear equations; then every joint's reaction and every drive's
//! force from the kinetostatic equations, with Coulomb friction by
//! iteration.

mod table;

pub use table::*;
