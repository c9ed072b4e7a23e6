//! The hostile-input suite: one module per class of input that once made
//! qdot wrong, panic, crash or hang. Every case asserts the exact outcome
//! (the value, or the error message and its position) and runs the binary
//! under a time and a memory bound (`bounded`).

pub(crate) mod bound;
mod budget;
mod cycle;
mod definite;
mod determinism;
mod eigen_bound;
mod exact;
mod exact_values;
mod hidden_zeros;
mod input;
mod mechanics;
mod numeric;
mod output;
mod round3;
mod round4_response;
mod round4_steady;
