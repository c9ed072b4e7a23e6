//! qdot's compilation of exact equations of motion for numbers: the
//! scene's given functions and constraints prepared for integration
//! ([`given`], [`constrained`]), register programs and machine code
//! ([`compile`]), and source code in C, Rust, Python and Julia
//! ([`codegen`]). The numeric studies built on them (`cycle`,
//! `floquet`) are the crate `qdot-study`.

#![warn(missing_docs)]

pub mod codegen;
pub mod compile;
pub mod constrained;
pub mod given;

// the lower layers, by the paths this crate's modules use
use qdot_exact::{algebra, budget, expr, poly};
use qdot_mechanics::{mechanics, scene};
use qdot_ode::dense;
use qdot_syntax::diag;
