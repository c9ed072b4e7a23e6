//! qdot's numeric studies on the compiled equations of a scene, above
//! the compilation (`qdot-compile`): a planar mechanism over its cycle
//! ([`cycle`], `qdot cycle`) and the Floquet stability of a motion whose
//! linearized equations have periodic coefficients ([`floquet`], `qdot
//! floquet`), and the frequency response swept over Ω ([`response`],
//! `qdot response --over`). Floating point throughout; the exact
//! equations come from `qdot-mechanics`.

#![warn(missing_docs)]

pub mod cycle;
pub mod floquet;
pub mod response;

use qdot_compile::{compile, given};
use qdot_exact::{algebra, budget, expr, limits, poly};
use qdot_mechanics::{mechanics, scene, solve};
use qdot_syntax::{diag, parse};
