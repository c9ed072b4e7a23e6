//! Pictures of a mechanism's cycle (`qdot cycle --plot`, `--animate`):
//! the reaction diagrams as SVG, and the mechanism moving through its
//! cycle as a self-contained HTML page (or an animated SVG).

pub mod animate;
pub mod floquet;
pub mod plot;

pub use animate::{animation_html, animation_svg};
pub use plot::reaction_diagrams;

#[cfg(test)]
mod fixture;
