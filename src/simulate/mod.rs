//! Numerical simulation: the exact equations compiled to f64 and integrated.
//!
//! The data's path ends here: [`crate::mechanics`] gives M(q, t)·q̈ = f(q, q̇, t)
//! exactly; [`compile`] turns it into a register program (or machine code),
//! and the integrators of `qdot-ode` (re-exported here: [`System`],
//! [`integrate`], [`explicit`], [`implicit`]) integrate the first-order
//! system y = (q, q̇). Everything here is floating point, and nothing from
//! it ever flows back into an exact result.
//!
//! * [`run`]: one simulation of a scene, as `qdot simulate` runs it.
//! * [`sweep`]: many runs over a grid of parameters and initial values.
//! * [`codegen`]: the compiled equations as C, Rust, Python or Julia source.

pub use qdot_compile::{codegen, compile, constrained, given};
pub use qdot_ode::*;

pub mod cycle;
pub mod floquet;
#[cfg(feature = "drawing")]
pub mod plot;
#[doc(hidden)]
pub mod problems;
#[cfg(feature = "cli")]
pub mod progress;
pub mod response;
#[cfg(feature = "drawing")]
pub mod response_plot;
pub mod run;
pub mod sweep;
