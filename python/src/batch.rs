//! Batch calls: many joint vectors or poses in one call, the GIL released and the rows spread
//! over every core (rayon), results written straight into the arrays NumPy takes over.

use crate::arrays::{checked, to_numpy, write_pose};
use crate::errors::{IkError, IntoPy, value_error};
use crate::robot::CoreRobot;
use armlab::kinematics::Pose;
use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::closed_form::{
    ArmKind, Elbow, Extension, Family, LIMIT_TOL, Posture, RawSolutions, Shoulder, WristFlip,
    wrap_into_limits,
};
use armlab::kinematics::ik::numerical::{self, NumericalOptions};
use armlab::kinematics::pose::{NotRigid, pose_from_matrix};
use armlab::nalgebra::{Matrix3, Matrix4, Rotation3, Translation3};
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use rayon::prelude::*;

/// Rows per rayon task: large enough that scheduling costs nothing next to the work.
const CHUNK: usize = 512;

/// `world_from_tool` of end-effector `ee` for every row of `Q` (N, dof): an (N, 4, 4) array;
/// with `frames`, every joint frame: (N, frames, 4, 4). With `out` (a C-contiguous float64
/// array of that shape) the poses are written into it and `out` is returned: no allocation,
/// no fresh pages for the kernel to fault in.
#[pyfunction]
#[pyo3(signature = (robot, qs, ee=0, frames=false, out=None))]
pub fn fk_batch<'py>(
    py: Python<'py>,
    robot: &Bound<'py, CoreRobot>,
    qs: PyReadonlyArrayDyn<'py, f64>,
    ee: usize,
    frames: bool,
    out: Option<Bound<'py, PyArrayDyn<f64>>>,
) -> PyResult<Bound<'py, PyAny>> {
    let r = robot.get();
    let n = r.robot.dof();
    let data = checked(
        &qs,
        "Q",
        &[None, Some(n)],
        "one row of joint values per configuration",
    )?;
    let rows = qs.shape()[0];
    let ee = r.ee(ee)?;
    let m = if frames { r.robot.joints().len() } else { 1 };
    let shape: Vec<usize> = if frames {
        vec![rows, m, 4, 4]
    } else {
        vec![rows, 4, 4]
    };
    let data: &[f64] = &data;
    let fill = |o: &mut [f64]| {
        o.par_chunks_mut(16 * m * CHUNK)
            .zip(data.par_chunks(n * CHUNK))
            .try_for_each(|(o, q)| {
                let mut scratch = vec![Pose::identity(); m];
                for (o, q) in o.chunks_exact_mut(16 * m).zip(q.chunks_exact(n)) {
                    if frames {
                        r.robot.fk_frames_into(q, &mut scratch)?;
                        for (f, oo) in scratch.iter().zip(o.chunks_exact_mut(16)) {
                            write_pose(f, oo);
                        }
                    } else {
                        write_pose(&r.robot.fk_ee(q, ee)?, o);
                    }
                }
                Ok::<(), armlab::kinematics::KinematicsError>(())
            })
    };
    match out {
        Some(array) => {
            {
                let mut w = array.try_readwrite().map_err(|e| {
                    value_error(format!("out cannot be written while Q is read: {e}"))
                })?;
                let got = w.shape().to_vec();
                let slice = w
                    .as_slice_mut()
                    .map_err(|_| value_error("out must be a C-contiguous float64 array"))?;
                if got != shape {
                    return Err(value_error(format!(
                        "out must have shape {shape:?}; got shape {got:?}"
                    )));
                }
                py.detach(|| fill(slice)).py_err()?;
            }
            Ok(array.into_any())
        }
        None => {
            let out = py
                .detach(|| {
                    let mut out = vec![0.0; rows * 16 * m];
                    fill(&mut out).map(|()| out)
                })
                .py_err()?;
            to_numpy(py, out, &shape)
        }
    }
}

/// A posture as one integer, stable across calls and robots: shoulder + 5 elbow + 25
/// extension + 100 wrist + 1000 branch, each part 0 when the family has none (the Python
/// package's `posture_label` reads it).
pub fn posture_code(p: &Posture) -> i32 {
    let s = match p.shoulder {
        None => 0,
        Some(Shoulder::Right) => 1,
        Some(Shoulder::Left) => 2,
        Some(Shoulder::OnAxis) => 3,
        Some(Shoulder::Boundary) => 4,
    };
    let e = match p.elbow {
        None => 0,
        Some(Elbow::Up) => 1,
        Some(Elbow::Down) => 2,
        Some(Elbow::Stretched) => 3,
        Some(Elbow::Folded) => 4,
    };
    let x = match p.extension {
        None => 0,
        Some(Extension::Forward) => 1,
        Some(Extension::Reversed) => 2,
        Some(Extension::Zero) => 3,
    };
    let w = match p.wrist {
        None => 0,
        Some(WristFlip::NoFlip) => 1,
        Some(WristFlip::Flip) => 2,
        Some(WristFlip::Singular) => 3,
        Some(WristFlip::Up) => 4,
        Some(WristFlip::Down) => 5,
    };
    s + 5 * e + 25 * x + 100 * w + 1000 * i32::from(p.branch.unwrap_or(0))
}

/// A pose from 16 row-major numbers: as `pose_from_matrix` (which re-orthonormalises a
/// rotation within its tolerance of orthonormal, iteratively), but a rotation already
/// orthonormal to 1e-13 (the output of any FK) is taken as it is, which is what makes the
/// batch fast; the closed forms' FK check is unaffected at that level.
fn pose_of_row(t: &[f64]) -> Result<Pose, NotRigid> {
    let r = Matrix3::new(t[0], t[1], t[2], t[4], t[5], t[6], t[8], t[9], t[10]);
    let bottom = [t[12], t[13], t[14], t[15]] == [0.0, 0.0, 0.0, 1.0];
    if bottom
        && t.iter().all(|v| v.is_finite())
        && (r.transpose() * r - Matrix3::identity()).amax() <= 1e-13
        && r.determinant() > 0.0
    {
        let tr = Translation3::new(t[3], t[7], t[11]);
        return Ok(Pose::from_parts(tr, Rotation3::from_matrix_unchecked(r)));
    }
    pose_from_matrix(&Matrix4::from_row_slice(t))
}

/// The error of a row of `Ts` that is not a homogeneous transform.
fn not_a_pose(row: usize, why: &str) -> PyErr {
    value_error(format!("Ts[{row}] is not a homogeneous transform: {why}"))
}

/// Slots per pose: the family's generic count, twice that where a prismatic joint's reversed
/// extension gives mirror solutions.
fn slots(family: &Family) -> usize {
    let mirrored = matches!(
        family,
        Family::SphericalArm
            | Family::Cylindrical
            | Family::Decoupled6 {
                arm: ArmKind::Spherical | ArmKind::Cylindrical
            }
    );
    let k = family.generic_solution_count();
    if mirrored { 2 * k } else { k }
}

/// The per-chunk output of `ik_batch`.
struct Chunk<'a> {
    q: &'a mut [f64],
    valid: &'a mut [bool],
    within: &'a mut [bool],
    codes: &'a mut [i32],
}

/// Every closed-form solution of every pose in `Ts` (N, 4, 4): `(q (N, k, dof), valid (N, k),
/// within_limits (N, k), posture codes (N, k), labels [(code, label)], k)`. Slot j of a pose is
/// its j-th raw solution (angles wrapped into the limits where a 2 pi shift allows); unused
/// slots have `valid` false and NaN joints.
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn ik_batch<'py>(
    py: Python<'py>,
    robot: &Bound<'py, CoreRobot>,
    ts: PyReadonlyArrayDyn<'py, f64>,
) -> PyResult<(
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Vec<(i32, String)>,
)> {
    let r = robot.get();
    let cf = r
        .closed_form
        .as_ref()
        .map_err(|why| IkError::new_err(format!("no batch closed form: {why}")))?;
    let data = checked(&ts, "Ts", &[None, Some(4), Some(4)], "one pose per row")?;
    let rows = ts.shape()[0];
    let (n, k) = (r.robot.dof(), slots(cf.family()));
    let free = &r.arm_free;
    let limits: Vec<[f64; 2]> = (0..n).map(|j| r.robot.dof_joint(j).limits).collect();
    let data: &[f64] = &data;
    let solve_chunk = |start: usize, out: Chunk<'_>| -> PyResult<Vec<(i32, Posture)>> {
        let mut seen: Vec<(i32, Posture)> = Vec::new();
        let mut raw = RawSolutions::default();
        for (i, t) in data[start * 16..]
            .chunks_exact(16)
            .take(out.valid.len() / k)
            .enumerate()
        {
            let pose = pose_of_row(t).map_err(|e| not_a_pose(start + i, &e.to_string()))?;
            cf.solve_raw(&pose, &mut raw).py_err()?;
            for (j, (q, posture)) in raw.iter(free.len()).take(k).enumerate() {
                let slot = i * k + j;
                let dst = &mut out.q[slot * n..(slot + 1) * n];
                // The joints off the arm keep their values; the arm's are wrapped into the limits.
                dst.copy_from_slice(&r.arm_base);
                for (&v, &c) in q.iter().zip(free) {
                    let l = limits[c];
                    dst[c] = if r.revolute[c] {
                        wrap_into_limits(v, l)
                    } else {
                        v
                    };
                }
                let within = dst
                    .iter()
                    .zip(&limits)
                    .all(|(w, l)| *w >= l[0] - LIMIT_TOL && *w <= l[1] + LIMIT_TOL);
                out.valid[slot] = q.iter().all(|v| v.is_finite());
                out.within[slot] = out.valid[slot] && within;
                let code = posture_code(posture);
                out.codes[slot] = code;
                if !seen.iter().any(|(c, _)| *c == code) {
                    seen.push((code, *posture));
                }
            }
        }
        Ok(seen)
    };
    let (q, valid, within, codes, seen) = py.detach(|| -> PyResult<_> {
        let mut q = vec![f64::NAN; rows * k * n];
        let mut valid = vec![false; rows * k];
        let mut within = vec![false; rows * k];
        let mut codes = vec![-1i32; rows * k];
        let seen: Vec<Vec<(i32, Posture)>> = q
            .par_chunks_mut(CHUNK * k * n)
            .zip(valid.par_chunks_mut(CHUNK * k))
            .zip(within.par_chunks_mut(CHUNK * k))
            .zip(codes.par_chunks_mut(CHUNK * k))
            .enumerate()
            .map(|(c, (((q, valid), within), codes))| {
                solve_chunk(
                    c * CHUNK,
                    Chunk {
                        q,
                        valid,
                        within,
                        codes,
                    },
                )
            })
            .collect::<PyResult<_>>()?;
        Ok((q, valid, within, codes, seen))
    })?;
    let mut labels: Vec<(i32, String)> = Vec::new();
    for (code, posture) in seen.into_iter().flatten() {
        if !labels.iter().any(|(c, _)| *c == code) {
            labels.push((code, posture.to_string()));
        }
    }
    labels.sort_by_key(|(c, _)| *c);
    Ok((
        to_numpy(py, q, &[rows, k, n])?,
        to_numpy(py, valid, &[rows, k])?,
        to_numpy(py, within, &[rows, k])?,
        to_numpy(py, codes, &[rows, k])?,
        labels,
    ))
}

/// The numerical solver on every pose of `Ts` (N, 4, 4), for arms without a closed form: one
/// slot per pose, `(q (N, 1, dof), converged (N, 1), within_limits (N, 1), posture codes (N, 1),
/// labels, position errors (N,), orientation errors (N,))`. Each pose starts from `seeds` (one
/// row per pose, or one q for all; default the "ready" configuration, else zero) and the
/// solver's random restarts (seeded, so the same call gives the same answer).
#[pyfunction]
#[pyo3(signature = (robot, ts, seeds=None, ee=0, tolerance=1e-10, max_iterations=100, restarts=50))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub fn ik_batch_numerical<'py>(
    py: Python<'py>,
    robot: &Bound<'py, CoreRobot>,
    ts: PyReadonlyArrayDyn<'py, f64>,
    seeds: Option<PyReadonlyArrayDyn<'py, f64>>,
    ee: usize,
    tolerance: f64,
    max_iterations: usize,
    restarts: usize,
) -> PyResult<(
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Vec<(i32, String)>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
)> {
    let r = robot.get();
    let ee = r.ee(ee)?;
    let n = r.robot.dof();
    let data = checked(&ts, "Ts", &[None, Some(4), Some(4)], "one pose per row")?;
    let rows = ts.shape()[0];
    let seeds: Vec<f64> = match &seeds {
        None => r.robot.ready_or_zero(),
        Some(s) if s.shape().len() == 1 => {
            checked(s, "seed", &[Some(n)], "one q for all")?.into_owned()
        }
        Some(s) => checked(s, "seed", &[Some(rows), Some(n)], "one q per pose")?.into_owned(),
    };
    if !(tolerance > 0.0 && tolerance.is_finite()) || max_iterations == 0 {
        return Err(value_error(
            "tolerance must be positive and max_iterations at least 1",
        ));
    }
    let opts = NumericalOptions {
        tolerance,
        max_iterations,
        restarts,
        ..NumericalOptions::default()
    };
    let targets: Vec<Pose> = data
        .chunks_exact(16)
        .enumerate()
        // As the single call reads its target (the numerical solver costs far more than this).
        .map(|(i, t)| {
            pose_from_matrix(&Matrix4::from_row_slice(t)).map_err(|e| not_a_pose(i, &e.to_string()))
        })
        .collect::<PyResult<_>>()?;
    let limits: Vec<[f64; 2]> = (0..n).map(|j| r.robot.dof_joint(j).limits).collect();
    let reports: Vec<_> = py
        .detach(|| {
            targets
                .par_iter()
                .enumerate()
                .map(|(i, t)| {
                    let seed = if seeds.len() == n {
                        &seeds[..]
                    } else {
                        &seeds[i * n..(i + 1) * n]
                    };
                    numerical::solve(&r.robot, ee, &Target::Pose(*t), seed, &opts)
                })
                .collect::<Result<Vec<_>, _>>()
        })
        .py_err()?;
    let mut q = Vec::with_capacity(rows * n);
    let (mut valid, mut within, mut pe, mut oe) = (vec![], vec![], vec![], vec![]);
    for rep in &reports {
        q.extend_from_slice(&rep.q);
        valid.push(rep.converged);
        within.push(
            rep.q
                .iter()
                .zip(&limits)
                .all(|(w, l)| *w >= l[0] - LIMIT_TOL && *w <= l[1] + LIMIT_TOL),
        );
        pe.push(rep.position_error);
        oe.push(rep.orientation_error);
    }
    Ok((
        to_numpy(py, q, &[rows, 1, n])?,
        to_numpy(py, valid, &[rows, 1])?,
        to_numpy(py, within, &[rows, 1])?,
        to_numpy(py, vec![0i32; rows], &[rows, 1])?,
        vec![(0, "numerical".to_string())],
        to_numpy(py, pe, &[rows])?,
        to_numpy(py, oe, &[rows])?,
    ))
}
