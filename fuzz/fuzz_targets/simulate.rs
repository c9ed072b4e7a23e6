#![no_main]
//! Fuzz target `simulate`: see [`qdot_fuzz::pipeline::simulate`].

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| qdot_fuzz::pipeline::simulate(data));
