//! armlab: robot-manipulator kinematics for learning, teaching and making figures.
//!
//! Layers, with one-way dependencies: [`kinematics`] (pure f64 math) → [`model_file`] and
//! [`urdf`] (text formats into robots) → [`cli`] (the scriptable command line). See the README.

pub mod app;
pub mod camera;
pub mod cli;
pub mod figure;
pub mod headless;
pub mod kinematics;
pub mod model_file;
pub mod render;
pub mod scene;
pub mod urdf;
pub mod workspace;
