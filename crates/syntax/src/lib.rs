//! qdot's syntax: the `.qd` language's lexer and parser ([`parse`], to an
//! AST with byte spans) and the diagnostics every later layer reports
//! with ([`diag`]: a position, a message, a hint, rendered with a caret).

#![warn(missing_docs)]

pub mod diag;
pub mod parse;
pub mod spelling;
pub mod unicode;

// the lower layers, by the paths this crate's modules use
use qdot_exact::{budget, limits};
