#![no_main]
//! Fuzz target `parse`: see [`qdot_fuzz::pipeline::parse`].

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| qdot_fuzz::pipeline::parse(data));
