#![no_main]
//! Fuzz target `commands`: see [`qdot_fuzz::pipeline::commands`].

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| qdot_fuzz::pipeline::commands(data));
