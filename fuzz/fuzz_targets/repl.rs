#![no_main]
//! Fuzz target `repl`: see [`qdot_fuzz::pipeline::repl`].

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| qdot_fuzz::pipeline::repl(data));
