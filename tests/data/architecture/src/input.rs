//! The input layer may read files (fixture: nothing here is a breach).
fn read(path: &str) -> std::io::Result<String> { std::fs::read_to_string(path) }
