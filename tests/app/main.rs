//! The app's tests through its own code (egui_kittest with the real layout): tabs, panels,
//! settings, the viewport, the gizmo, the soak test and the web paths.
//!
//! Needs the `app` feature (`required-features` in Cargo.toml).

#[path = "../common/mod.rs"]
mod common;

mod app_calibration;
mod app_cell;
mod app_class;
mod app_exercise_orientation;
mod app_layout;
mod app_orientation;
mod app_reachability;
mod app_screenshots;
mod app_self_motion;
mod app_settings;
mod app_state;
mod app_ui;
mod app_viewport;
mod gizmo;
mod ui_painter;
mod web_paths;
