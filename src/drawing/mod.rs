//! Pictures of a mechanism's cycle (`qdot cycle --plot`, `--animate`):
//! the reaction diagrams as SVG, and the mechanism moving through its
//! cycle as a self-contained HTML page (or an animated SVG); and the look
//! and units every figure shares ([`style`], [`units`]).

pub mod animate;
pub mod floquet;
pub mod plot;
pub mod style;
pub mod units;

pub use animate::{animation_html, animation_svg};
pub use plot::reaction_diagrams;

#[cfg(test)]
mod fixture;
