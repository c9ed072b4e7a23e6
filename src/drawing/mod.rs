//! Pictures of a mechanism's cycle (`qdot cycle --plot`, `--animate`):
//! the reaction diagrams as SVG, and the mechanism moving through its
//! cycle as a self-contained HTML page (or an animated SVG); any motion
//! in 3D (`simulate --animate`, `modes --animate`: [`motion`]); and the
//! look and units every figure shares ([`style`], [`units`]).

pub mod animate;
pub mod floquet;
pub mod motion;
pub mod motion_of;
pub mod plot;
pub mod style;
pub mod units;

pub use animate::{animation_html, animation_svg};
pub use motion_of::{modes_page, run_page};
pub use plot::reaction_diagrams;

#[cfg(test)]
mod fixture;
