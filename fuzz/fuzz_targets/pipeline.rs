#![no_main]
//! Fuzz target `pipeline`: see [`qdot_fuzz::pipeline::pipeline`].

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| qdot_fuzz::pipeline::pipeline(data));
