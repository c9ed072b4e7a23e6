//! Pictures of a mechanism's cycle (`qdot cycle --plot`, `--animate`):
//! the reaction diagrams as SVG, and the mechanism moving through its
//! cycle as a self-contained HTML page.
