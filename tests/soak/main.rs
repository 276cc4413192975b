//! The soak test of the app, in a test crate of its own: it runs the app in a private working
//! folder (`std::env::set_current_dir`), which would move every other test of a shared process.
//!
//! Needs the `app` feature (`required-features` in Cargo.toml).

mod app_soak;
