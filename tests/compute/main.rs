//! The compute layer's tests: workspaces, calibration, redundancy and self-motion,
//! constructions, exercises, lessons and animations. One test crate (one link of the crate).

#[path = "../common/mod.rs"]
mod common;

mod animation;
mod calibration;
mod calibration_files;
mod calibration_setups;
mod class_protocol;
mod collision;
mod collision_matrix;
mod collision_self_motion;
mod collision_workspace;
mod construction;
mod exercise;
mod exercise_orientation;
mod lesson;
mod placement;
mod reachability;
mod redundancy;
mod self_motion_locked;
mod self_motion_sampler;
mod workspace;
mod workspace_exact;
mod workspace_figure_data;
mod workspace_flange;
mod workspace_maps;
