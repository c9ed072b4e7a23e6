//! The engine's internals, for this repository's tests, benches and fuzz
//! targets: public without a promise of stability (the crates they come
//! from are the stable way in).

pub use qdot_exact::{algebra, cancel, poly};
pub use qdot_ode::dense;
pub use qdot_syntax::unicode;

pub mod gallery;
