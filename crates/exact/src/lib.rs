//! qdot's exact algebra, the bottom of its layers: rationals ([`num`]),
//! sparse multivariate polynomials with their gcd, factors and square
//! roots ([`poly`]), canonical exact expressions over them ([`expr`]),
//! exact linear algebra and sign decisions ([`algebra`]), and the work
//! budget every exact computation runs under ([`budget`], [`limits`]).
//! [`rng`] is qdot's one pseudo-random generator, deterministic, for the
//! random choices here and in the layers above.
//!
//! Nothing here knows mechanics or the `.qd` language: an [`expr::Expr`]
//! is a quotient of polynomials in variables and function atoms, equal
//! when their canonical forms are.

#![warn(missing_docs)]

pub mod algebra;
pub mod budget;
pub mod cancel;
pub mod expr;
pub mod limits;
pub mod num;
pub mod poly;
pub mod rng;
