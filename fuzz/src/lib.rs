//! The fuzz targets' bodies, in [`pipeline`] (shared with the main
//! package's tests/fuzz_regressions.rs).

pub mod pipeline;
