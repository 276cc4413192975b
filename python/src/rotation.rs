//! Batch conversions between rotation matrices and the minimal representations of Sect. 2.4
//! (`armlab.rotation`): stacks of (N, 3, 3) matrices to (N, 3) Euler or RPY angles, (N, 4)
//! angle-axis `(theta, rx, ry, rz)` or unit quaternions `(eta, ex, ey, ez)`, and back. The GIL is
//! released and the rows spread over every core (rayon); each conversion is the library's fast
//! one (no allocation).

use crate::arrays::{checked, to_numpy};
use crate::errors::value_error;
use armlab::kinematics::EulerKind;
use armlab::kinematics::orientation::{
    angle_axis_from_rotation, quaternion, quaternion_from_rotation, rotation_from_angle_axis,
    rotation_from_quaternion,
};
use armlab::nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use rayon::prelude::*;

/// Rows per rayon task.
const CHUNK: usize = 4096;

/// Tolerance on `max |R^T R - I|` of an input matrix (as `armlab rotation --from matrix:`).
const ORTHONORMAL_TOLERANCE: f64 = 1e-6;

/// A representation of a rotation as a row of numbers.
#[derive(Clone, Copy)]
enum Rep {
    Euler(EulerKind),
    AxisAngle,
    Quaternion,
}

impl Rep {
    fn parse(name: &str) -> PyResult<Rep> {
        Ok(match name {
            "zyz" => Rep::Euler(EulerKind::Zyz),
            "zxz" => Rep::Euler(EulerKind::Zxz),
            "rpy" => Rep::Euler(EulerKind::Rpy),
            "axis_angle" | "axis-angle" => Rep::AxisAngle,
            "quaternion" => Rep::Quaternion,
            _ => {
                return Err(value_error(format!(
                    "unknown representation {name:?}: use \"zyz\", \"zxz\", \"rpy\", \
                     \"axis_angle\" or \"quaternion\""
                )));
            }
        })
    }

    /// Numbers per row.
    fn width(self) -> usize {
        match self {
            Rep::Euler(_) => 3,
            Rep::AxisAngle | Rep::Quaternion => 4,
        }
    }

    /// What a row holds, for messages.
    fn what(self) -> &'static str {
        match self {
            Rep::Euler(_) => "(phi, theta, psi) in rad",
            Rep::AxisAngle => "(theta, rx, ry, rz): the angle in rad and the axis",
            Rep::Quaternion => "(eta, ex, ey, ez)",
        }
    }
}

/// Why a row cannot be converted.
enum BadRow {
    NotRotation(f64),
    Reflection,
    Zero,
}

/// A row-major 3x3 block as a rotation, if it is one to [`ORTHONORMAL_TOLERANCE`] (NaN and
/// infinities fail the test). `R^T R - I` from the six dot products of the columns.
#[inline]
fn rotation_of(m: &[f64]) -> Result<Rotation3<f64>, BadRow> {
    let r = Matrix3::from_row_slice(m);
    let (c0, c1, c2) = (r.column(0), r.column(1), r.column(2));
    let error = (c0.dot(&c0) - 1.0)
        .abs()
        .max((c1.dot(&c1) - 1.0).abs())
        .max((c2.dot(&c2) - 1.0).abs())
        .max(c0.dot(&c1).abs())
        .max(c0.dot(&c2).abs())
        .max(c1.dot(&c2).abs());
    // f64::max ignores a NaN operand: each entry is tested too.
    if error > ORTHONORMAL_TOLERANCE || !m.iter().all(|v| v.is_finite()) {
        return Err(BadRow::NotRotation(error));
    }
    if c0.dot(&c1.cross(&c2)) < 0.0 {
        return Err(BadRow::Reflection);
    }
    Ok(Rotation3::from_matrix_unchecked(r))
}

/// One matrix (9 numbers) to one row of `rep` (`second`: the other Euler solution).
#[inline]
fn to_row(rep: Rep, second: bool, m: &[f64], o: &mut [f64]) -> Result<(), BadRow> {
    let r = rotation_of(m)?;
    match rep {
        Rep::Euler(kind) => {
            let a = if second {
                kind.from_rotation_negative(&r)
            } else {
                kind.from_rotation(&r)
            };
            o.copy_from_slice(a.angles.as_slice());
        }
        Rep::AxisAngle => {
            let aa = angle_axis_from_rotation(&r);
            o[0] = aa.angle;
            o[1..4].copy_from_slice(aa.axis.as_slice());
        }
        Rep::Quaternion => {
            let q = quaternion_from_rotation(&r);
            o[0] = q.w;
            o[1..4].copy_from_slice(q.imag().as_slice());
        }
    }
    Ok(())
}

/// One row of `rep` to one matrix (9 numbers, row-major).
#[inline]
fn from_row(rep: Rep, x: &[f64], o: &mut [f64]) -> Result<(), BadRow> {
    let r = match rep {
        Rep::Euler(kind) => kind.to_rotation(&Vector3::new(x[0], x[1], x[2])),
        Rep::AxisAngle => {
            let axis = Unit::try_new(Vector3::new(x[1], x[2], x[3]), 0.0).ok_or(BadRow::Zero)?;
            rotation_from_angle_axis(x[0], &axis)
        }
        Rep::Quaternion => {
            if x.iter().all(|v| *v == 0.0) {
                return Err(BadRow::Zero);
            }
            rotation_from_quaternion(&quaternion(x[0], Vector3::new(x[1], x[2], x[3])))
        }
    };
    let m = r.matrix();
    for i in 0..3 {
        for j in 0..3 {
            o[3 * i + j] = m[(i, j)];
        }
    }
    Ok(())
}

/// Converts every row of `data` (rows of `w_in` numbers) into `out` (rows of `w_out`), in
/// parallel; on failure, the first bad row and why.
fn convert(
    data: &[f64],
    out: &mut [f64],
    (w_in, w_out): (usize, usize),
    f: impl Fn(&[f64], &mut [f64]) -> Result<(), BadRow> + Sync,
) -> Result<(), (usize, BadRow)> {
    let failed = out
        .par_chunks_mut(w_out * CHUNK)
        .zip(data.par_chunks(w_in * CHUNK))
        .map(|(o, x)| {
            for (o, x) in o.chunks_exact_mut(w_out).zip(x.chunks_exact(w_in)) {
                if f(x, o).is_err() {
                    return true;
                }
            }
            false
        })
        .reduce(|| false, |a, b| a || b);
    if !failed {
        return Ok(());
    }
    // The first bad row, found again in order for a stable message.
    let mut scratch = vec![0.0; w_out];
    for (row, x) in data.chunks_exact(w_in).enumerate() {
        if let Err(why) = f(x, &mut scratch) {
            return Err((row, why));
        }
    }
    Ok(())
}

/// The (N, ...) output array: `out` checked and written, or a new one.
fn write_out<'py>(
    py: Python<'py>,
    out: Option<Bound<'py, PyArrayDyn<f64>>>,
    shape: &[usize],
    fill: impl FnOnce(&mut [f64]) -> PyResult<()>,
) -> PyResult<Bound<'py, PyAny>> {
    match out {
        Some(array) => {
            {
                let mut w = array.try_readwrite().map_err(|e| {
                    value_error(format!(
                        "out cannot be written while the input is read: {e}"
                    ))
                })?;
                let got = w.shape().to_vec();
                if got != shape {
                    return Err(value_error(format!(
                        "out must have shape {shape:?}; got shape {got:?}"
                    )));
                }
                let slice = w
                    .as_slice_mut()
                    .map_err(|_| value_error("out must be a C-contiguous float64 array"))?;
                fill(slice)?;
            }
            Ok(array.into_any())
        }
        None => {
            let mut data = vec![0.0; shape.iter().product()];
            fill(&mut data)?;
            to_numpy(py, data, shape)
        }
    }
}

/// The message of a bad row.
fn bad_row(name: &str, rep: Rep, row: usize, why: BadRow) -> PyErr {
    match why {
        BadRow::NotRotation(error) => value_error(format!(
            "{name}[{row}] is not a rotation matrix: the largest entry of R^T R - I is \
             {error:.3e} (tolerance {ORTHONORMAL_TOLERANCE:e})"
        )),
        BadRow::Reflection => value_error(format!(
            "{name}[{row}] is a reflection (det R = -1), not a rotation"
        )),
        BadRow::Zero => value_error(format!(
            "{name}[{row}] has a zero {}: it cannot be normalized",
            match rep {
                Rep::AxisAngle => "axis",
                _ => "quaternion",
            }
        )),
    }
}

/// Every matrix of `R` (N, 3, 3) in the representation `to` ("zyz", "zxz", "rpy": (N, 3) angles
/// (phi, theta, psi) in rad, the second solution with `second`; "axis_angle": (N, 4) rows
/// (theta, rx, ry, rz), theta in [0, pi]; "quaternion": (N, 4) rows (eta, ex, ey, ez), eta >= 0).
/// Each matrix must be orthonormal to 1e-6 with det +1.
#[pyfunction]
#[pyo3(signature = (rs, to, second=false, out=None))]
pub fn rotation_to<'py>(
    py: Python<'py>,
    rs: PyReadonlyArrayDyn<'py, f64>,
    to: &str,
    second: bool,
    out: Option<Bound<'py, PyArrayDyn<f64>>>,
) -> PyResult<Bound<'py, PyAny>> {
    let rep = Rep::parse(to)?;
    let shape = rs.shape().to_vec();
    if shape.len() != 3 || shape[1..] != [3, 3] {
        return Err(value_error(format!(
            "R must have shape (N, 3, 3) (rotation matrices); got shape {shape:?}"
        )));
    }
    // Finiteness is checked with orthonormality, in the parallel pass (one read of R).
    let data: std::borrow::Cow<[f64]> = match rs.as_slice() {
        Ok(s) => s.into(),
        Err(_) => rs.as_array().iter().copied().collect::<Vec<_>>().into(),
    };
    let w = rep.width();
    let data: &[f64] = &data;
    write_out(py, out, &[shape[0], w], |o| {
        py.detach(|| convert(data, o, (9, w), |x, o| to_row(rep, second, x, o)))
            .map_err(|(row, why)| {
                if data[9 * row..9 * row + 9].iter().all(|v| v.is_finite()) {
                    bad_row("R", rep, row, why)
                } else {
                    // The message of every other array argument with a NaN.
                    checked(&rs, "R", &[None, Some(3), Some(3)], "rotation matrices")
                        .err()
                        .unwrap_or_else(|| bad_row("R", rep, row, why))
                }
            })
    })
}

/// The matrices (N, 3, 3) of the rows of `X` in the representation `kind` ("zyz", "zxz", "rpy":
/// (N, 3) angles in rad; "axis_angle": (N, 4) rows (theta, rx, ry, rz), the axis normalized;
/// "quaternion": (N, 4) rows (eta, ex, ey, ez), normalized).
#[pyfunction]
#[pyo3(signature = (xs, kind, out=None))]
pub fn rotation_from<'py>(
    py: Python<'py>,
    xs: PyReadonlyArrayDyn<'py, f64>,
    kind: &str,
    out: Option<Bound<'py, PyArrayDyn<f64>>>,
) -> PyResult<Bound<'py, PyAny>> {
    let rep = Rep::parse(kind)?;
    let w = rep.width();
    let data = checked(&xs, "X", &[None, Some(w)], rep.what())?;
    let n = xs.shape()[0];
    let data: &[f64] = &data;
    write_out(py, out, &[n, 3, 3], |o| {
        py.detach(|| convert(data, o, (w, 9), |x, o| from_row(rep, x, o)))
            .map_err(|(row, why)| bad_row("X", rep, row, why))
    })
}
