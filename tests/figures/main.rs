//! The renderer and the figures: golden images, vector figures (SVG, PDF), shader validation,
//! meshes.
//!
//! Needs the `app` feature (`required-features` in Cargo.toml).

#[path = "../common/mod.rs"]
mod common;

mod figures;
mod reachability;
mod render;
mod render_target;
mod shader_validation;
mod urdf_meshes;
mod vector_figures;
mod workspace_figures;
