//! armlab: robot-manipulator kinematics for learning, teaching and making figures, after chapter 2
//! of Siciliano, Sciavicco, Villani, Oriolo, *Robotics: Modelling, Planning and Control*.
//!
//! The layers have one-way dependencies: [`kinematics`] (pure f64 math: DH tables, FK,
//! Jacobians, orientation, closed-form and numerical IK) → [`model_file`] and [`urdf`] (text
//! formats into robots), [`workspace`] and [`calibration`] (pure compute) → with the `app` feature (on by
//! default) `scene` (f32 draw lists), `render` (wgpu), `figure` and `headless` (figures to PNG),
//! `app` (egui/eframe) and `cli` (the command line).
//!
//! # Use as a library
//!
//! Without default features the crate is graphics-free (nalgebra, serde, toml, urdf-rs,
//! thiserror, rayon):
//!
//! ```toml
//! [dependencies]
//! armlab = { version = "0.1", default-features = false }
//! ```
//!
//! A short tour. Build a robot from its DH table, read row by row as in the textbook's tables
//! (a, alpha, d, theta), and compute its forward kinematics, eq. (2.50):
//!
//! ```
//! use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
//! use std::f64::consts::FRAC_PI_2;
//!
//! // The anthropomorphic arm of Table 2.4 (a2 = a3 = 1 m).
//! let robot = Robot::from_dh(
//!     "anthropomorphic arm",
//!     Convention::Standard,
//!     &[
//!         DhJoint::revolute(DhRow { a: 0.0, alpha: FRAC_PI_2, d: 0.0, theta: 0.0 }),
//!         DhJoint::revolute(DhRow { a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 }),
//!         DhJoint::revolute(DhRow { a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 })
//!             .limits(-2.5, 2.5),
//!     ],
//!     Pose::identity(),
//!     Pose::identity(),
//! )?;
//! let world_from_tool = robot.fk(&[0.0, 0.3, -0.6])?;
//! // In the arm's plane: a2 cos(q2) + a3 cos(q2 + q3) = 2 cos(0.3) from the shoulder.
//! assert!((world_from_tool.translation.vector.norm() - 2.0 * 0.3f64.cos()).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Every closed-form inverse-kinematics solution, each labelled with its posture and checked by
//! forward kinematics (Sect. 2.12), without allocating:
//!
//! ```
//! use armlab::kinematics::ik::closed_form::{ClosedForm, Solutions, Verify};
//! use armlab::kinematics::ik::Target;
//! use armlab::kinematics::models::built_in;
//!
//! let puma = built_in("puma560").expect("a built-in model");
//! let solver = ClosedForm::detect(&puma)?; // Err says why there is no closed form
//! let target = Target::Pose(puma.fk(&[0.3, 0.8, -1.0, 0.4, 0.6, 0.2])?);
//! let mut solutions = Solutions::default();
//! solver.solve_into(&puma, &target, Verify::Fk, &mut solutions)?;
//! assert_eq!(solutions.len(), 8);
//! for s in solutions.iter() {
//!     println!("{:<45} q = {:?} within limits: {}", s.posture, s.q(), s.within_limits);
//!     assert!(s.errors.expect("verified").position < 1e-12);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Numerical IK for any chain ([`kinematics::ik::numerical`]), model files
//! ([`model_file::load_model`]), URDF ([`urdf`]) and workspaces ([`workspace`]) follow the same
//! pattern: plain data in, a result or a typed error out. The `examples/` folder has complete
//! programs. Units are SI and radians throughout; transforms are named by their frames
//! (`world_from_tool`).

/// The linear-algebra crate of the public API ([`kinematics::Pose`] is a
/// `nalgebra::Isometry3<f64>`), re-exported so that users name the same types.
pub use nalgebra;

/// The serialization crate whose traits [`kinematics::DhRow`] and [`kinematics::Convention`]
/// implement, re-exported for the same reason.
pub use serde;

pub mod animation;
#[cfg(feature = "gui")]
pub mod app;
pub mod calibration;
#[cfg(feature = "gui")]
pub mod camera;
pub mod class;
#[cfg(feature = "app")]
pub mod class_server;
#[cfg(feature = "app")]
pub mod cli;
pub mod collision;
pub mod construction;
pub mod exercise;
#[cfg(feature = "gui")]
pub mod figure;
#[cfg(feature = "gui")]
pub mod headless;
pub mod input;
pub mod kinematics;
pub mod lesson;
pub mod mesh;
pub mod model_file;
#[cfg(feature = "app")]
pub mod npz;
pub mod offload;
pub mod reachability;
pub mod redundancy;
#[cfg(feature = "gui")]
pub mod render;
#[cfg(feature = "gui")]
pub mod scene;
#[cfg(feature = "gui")]
pub mod ui_render;
pub mod urdf;
#[cfg(all(feature = "gui", target_arch = "wasm32"))]
pub mod web;
pub mod workspace;
