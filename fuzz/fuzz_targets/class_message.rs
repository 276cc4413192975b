//! Fuzz target: see `checks::class_message` (what must hold for every input).
#![no_main]

#[path = "../src/checks.rs"]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::class_message(data));
