//! Exact solving: linear systems over rational functions.

pub mod linear;
