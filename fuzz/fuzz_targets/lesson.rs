//! Fuzz target: see `checks::lesson` (what must hold for every input).
#![no_main]

#[path = "../src/checks.rs"]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::lesson(data));
