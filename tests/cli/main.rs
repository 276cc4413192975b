//! The command line, run as a process, and its reference page.
//!
//! Needs the `app` feature (`required-features` in Cargo.toml).

mod cell_commands;
mod class_server;
mod cli;
mod cli_reference;
mod collisions;
mod exercise_orientation;
mod orientation_figures;
mod place;
mod reachability;
mod rotation;
mod view_scene;
