//! Reachability maps and base placement (issue 49): where an arm reaches in six dimensions,
//! with which postures, and where to put its base so that it reaches a set of task poses.
//!
//! - [`sampling`]: the sample poses, exactly as the issue defines them (Fibonacci directions,
//!   rolls about each, voxel centres), so that other tools can compare.
//! - [`map`]: the map itself, every sample solved by the closed-form IK (or the numerical solver
//!   from several seeds for arms without one), within the joint limits and, with a cell,
//!   free of collision.
//! - [`mod@place`]: base placement, every task pose solved exactly at every base position and yaw.

pub mod map;
pub mod place;
pub mod sampling;

pub use map::*;
pub use place::*;
pub use sampling::*;
