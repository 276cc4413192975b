//! The `armlab` command line (thin: parsing and dispatch live in `armlab::cli`).
fn main() {}
