#![no_main]
//! Fuzz target `motions`: see [`qdot_fuzz::pipeline::motions`].

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| qdot_fuzz::pipeline::motions(data));
