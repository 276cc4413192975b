//! armlab's build script does nothing. It exists for its build-dependency (see Cargo.toml):
//! syn 3 with the features pyo3's macros turn on, so that `cargo test` and the Python
//! extension's build (python/test.sh) share one build of the proc-macros and all above them.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
}
