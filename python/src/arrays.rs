//! NumPy arrays in and out: shapes and finiteness checked with messages that name the argument
//! and the offending index, poses as row-major 4x4 blocks.

use crate::errors::value_error;
use armlab::kinematics::Pose;
use armlab::nalgebra::Matrix4;
use numpy::{PyArray, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::borrow::Cow;

/// The array's numbers in row-major order (borrowed when contiguous) after checking that its
/// shape is `shape` (`None` = any length on that axis) and that every entry is finite.
pub fn checked<'a>(
    a: &'a PyReadonlyArrayDyn<'_, f64>,
    name: &str,
    shape: &[Option<usize>],
    what: &str,
) -> PyResult<Cow<'a, [f64]>> {
    let got = a.shape();
    let fits = got.len() == shape.len()
        && got
            .iter()
            .zip(shape)
            .all(|(g, want)| want.is_none_or(|w| *g == w));
    if !fits {
        let want: Vec<String> = shape
            .iter()
            .map(|s| s.map_or("N".to_string(), |v| v.to_string()))
            .collect();
        return Err(value_error(format!(
            "{name} must have shape ({}) ({what}); got shape {got:?}",
            want.join(", ")
        )));
    }
    let data: Cow<'a, [f64]> = match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    };
    if let Some(i) = data.iter().position(|v| !v.is_finite()) {
        return Err(value_error(format!(
            "{name} contains a non-finite number ({}) at index {:?}",
            data[i],
            unravel(i, got)
        )));
    }
    Ok(data)
}

/// The multi-index of flat index `i` in an array of shape `shape`.
fn unravel(mut i: usize, shape: &[usize]) -> Vec<usize> {
    let mut idx = vec![0; shape.len()];
    for (k, &n) in shape.iter().enumerate().rev() {
        if n > 0 {
            idx[k] = i % n;
            i /= n;
        }
    }
    idx
}

/// A pose from 16 row-major numbers, or a `ValueError` when its rotation is not one.
pub fn pose_of(m: &[f64], name: &str) -> PyResult<Pose> {
    armlab::kinematics::pose::pose_from_matrix(&Matrix4::from_row_slice(m))
        .map_err(|e| value_error(format!("{name} is not a homogeneous transform: {e}")))
}

/// `pose` as 16 row-major numbers into `out`.
#[inline]
pub fn write_pose(pose: &Pose, out: &mut [f64]) {
    let r = pose.rotation.matrix();
    let t = &pose.translation.vector;
    for i in 0..3 {
        out[4 * i] = r[(i, 0)];
        out[4 * i + 1] = r[(i, 1)];
        out[4 * i + 2] = r[(i, 2)];
        out[4 * i + 3] = t[i];
    }
    out[12] = 0.0;
    out[13] = 0.0;
    out[14] = 0.0;
    out[15] = 1.0;
}

/// A NumPy array of shape `shape` that takes over `data` (no copy).
pub fn to_numpy<'py, T: numpy::Element>(
    py: Python<'py>,
    data: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let flat = PyArray::from_vec(py, data);
    Ok(flat.reshape(shape.to_vec())?.into_any())
}
