//! Exact expressions compiled to a flat f64 register program.
//!
//! [`compile`] turns canonical expressions (`num/den` over atoms, see
//! [`crate::expr`]) into a [`Program`]: a straight-line list of register
//! instructions, in topological order, that evaluates all outputs at once
//! without allocating. The compiler
//!
//! * folds constants: π, √n, rational coefficients, parameters bound to
//!   numbers ([`compile_with`]) and every atom whose argument is constant
//!   become constants, multiplied into the coefficients of the terms;
//! * shares common subexpressions: every node is hash-consed (an atom is
//!   evaluated once, `sin u` and `cos u` of one angle by one `sin_cos`, a
//!   power product once for all outputs, an equal numerator or denominator
//!   once);
//! * evaluates each polynomial by a greedy multivariate Horner scheme
//!   (Ceberio & Kreinovich, "Greedy algorithms for optimizing multivariate
//!   Horner schemes", ACM SIGSAM Bull. 38 (2004)): the common monomial
//!   factor of all terms is split off, then the polynomial is written
//!   `v·q + r` in the variable `v` that occurs in most terms, recursively;
//!   the remaining power products are built by multiplying a shared prefix
//!   by one more factor (a trie of monomials);
//! * removes dead code and reuses registers (linear scan over the last
//!   uses, Poletto & Sarkar, TOPLAS 21 (1999)).
//!
//! [`CompiledDynamics`] evaluates M(q, t) (its upper triangle) and f(q, q̇, t)
//! of Lagrange's equations in one program and solves M·q̈ = f by
//! [`solve_spd`] ([`crate::dense`]: Cholesky, LU with partial pivoting as
//! fallback; Golub & Van Loan, Matrix Computations, 4.2 and 3.4), as a [`qdot_ode::System`] for the
//! integrators.
//!
//! [`CompiledDynamics::use_engine`] chooses what runs the program: the
//! interpreter ([`Program::run`]) or, with the `jit` feature, the whole
//! right-hand side compiled to machine code (`jit`, Cranelift), checked
//! against the interpreter bit for bit in the tests: the interpreter is the
//! fallback and the oracle.
//!
//! The stages, one file each: `builder` (expressions to a hash-consed
//! graph of nodes, with constant folding and Horner schemes), `passes`
//! (the named passes from that graph to a [`Program`]), `program` (the
//! instructions and their interpreter), `dynamics` ([`CompiledDynamics`]) and `error`
//! ([`CompileError`]).

mod builder;
mod dynamics;
mod engine;
mod error;
#[cfg(feature = "jit")]
pub mod jit;
mod passes;
mod program;

pub use builder::{compile, compile_through, compile_with, naive_op_count};
pub use dynamics::{
    estimated_cost_of, is_constant, state_inputs, Choice, CompiledDynamics, Evaluator, BEST_MAX_N,
};
pub use engine::{Engine, EngineReport, AUTO_JIT_AFTER_CALLS};
pub use error::CompileError;
#[doc(hidden)]
pub use program::Instr;
pub use program::Program;

/// Solve M·x = f in place for a symmetric M ([`crate::dense::solve_spd`]),
/// with the error as a [`CompileError`].
pub fn solve_spd(m: &mut [f64], f: &mut [f64], n: usize) -> Result<(), CompileError> {
    crate::dense::solve_spd(m, f, n).map_err(CompileError::from)
}
