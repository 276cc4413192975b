//! Helpers shared by the integration tests: reading the reference data.
#![allow(dead_code)]

pub mod closed_form;
#[cfg(feature = "app")]
pub mod golden;
#[cfg(feature = "app")]
pub mod render;

use armlab::kinematics::Pose;
use nalgebra::Matrix4;
use serde_json::Value;
use std::path::PathBuf;

/// Path of a file under tests/data/reference (copied verbatim from shared/reference).
pub fn reference_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/reference")
        .join(name)
}

/// Parsed JSON of a reference file.
pub fn reference(name: &str) -> Value {
    let text = std::fs::read_to_string(reference_path(name)).expect("reference file");
    serde_json::from_str(&text).expect("reference JSON")
}

/// A JSON array of numbers.
pub fn vec_f64(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// A JSON 4x4 row-major matrix.
pub fn mat4(v: &Value) -> Matrix4<f64> {
    let rows = v.as_array().expect("rows");
    Matrix4::from_fn(|r, c| rows[r][c].as_f64().expect("number"))
}

/// Largest element-wise difference between a pose and a 4x4 matrix.
pub fn max_diff(p: &Pose, m: &Matrix4<f64>) -> f64 {
    (p.to_homogeneous() - m).amax()
}
