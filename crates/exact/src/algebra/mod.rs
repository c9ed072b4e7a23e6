//! Exact algebra over canonical expressions that both the derivation and
//! the solvers need: linear systems, determinants, splitting a linear
//! expression into coefficients, signs. It sits below `mechanics` and
//! `solve` so that neither imports the other's helpers.

pub mod assume;
pub mod linear;
pub mod sign;
