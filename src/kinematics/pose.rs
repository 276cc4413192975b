//! Rigid transforms: the elementary rotations and translations of chapter 2, and checks.

use nalgebra::{Matrix3, Matrix4, Rotation3, Translation3};

/// A rigid transform stored as rotation matrix + translation (metres).
///
/// Name values by their frames: `world_from_tool` maps tool coordinates into world coordinates,
/// and compose right to left, `world_from_tool = world_from_base * base_from_tool`.
///
/// # Examples
///
/// The elementary transforms of chapter 2 compose by `*`; a pose maps points of its right-hand
/// frame into its left-hand frame:
///
/// ```
/// use armlab::kinematics::Pose;
/// use armlab::kinematics::pose::{rot_z, trans_x, trans_z};
/// use armlab::nalgebra::Point3;
/// use std::f64::consts::FRAC_PI_2;
///
/// let world_from_base = trans_z(0.5);
/// let base_from_tool = rot_z(FRAC_PI_2) * trans_x(0.3);
/// let world_from_tool: Pose = world_from_base * base_from_tool;
/// let p = world_from_tool * Point3::origin();
/// assert!((p - Point3::new(0.0, 0.3, 0.5)).norm() < 1e-15);
/// // The inverse maps back: tool_from_world.
/// let back = world_from_tool.inverse() * p;
/// assert!(back.coords.norm() < 1e-15);
/// ```
pub type Pose = nalgebra::IsometryMatrix3<f64>;

/// Elementary rotation about x by `angle` (rad), eq. (2.6).
pub fn rot_x(angle: f64) -> Pose {
    Pose::from_parts(
        Translation3::identity(),
        crate::kinematics::orientation::rx(angle),
    )
}

/// Elementary rotation about y by `angle` (rad), eq. (2.7).
pub fn rot_y(angle: f64) -> Pose {
    Pose::from_parts(
        Translation3::identity(),
        crate::kinematics::orientation::ry(angle),
    )
}

/// Elementary rotation about z by `angle` (rad), eq. (2.8). Built from sin/cos directly.
pub fn rot_z(angle: f64) -> Pose {
    Pose::from_parts(
        Translation3::identity(),
        crate::kinematics::orientation::rz(angle),
    )
}

/// Translation by `d` metres along x.
pub fn trans_x(d: f64) -> Pose {
    Pose::translation(d, 0.0, 0.0)
}

/// Translation by `d` metres along y.
pub fn trans_y(d: f64) -> Pose {
    Pose::translation(0.0, d, 0.0)
}

/// Translation by `d` metres along z.
pub fn trans_z(d: f64) -> Pose {
    Pose::translation(0.0, 0.0, d)
}

/// Tolerance on orthonormality (the largest entry of `R^T R - I`) used when a 4x4 matrix is
/// accepted as a rigid transform. Entries rounded to six decimals are off by up to 5e-7 each,
/// which puts `R^T R - I` up to 1.7e-6: 1e-6 refused poses that `armlab info` itself printed
/// (found pasting one into `armlab ik`), so the tolerance is 1e-5.
pub const RIGID_TOLERANCE: f64 = 1e-5;

/// Why a 4x4 matrix is not a rigid transform.
#[derive(Debug, Clone, PartialEq)]
pub enum NotRigid {
    /// Some element is NaN or infinite.
    NonFinite,
    /// Bottom row differs from `[0 0 0 1]`.
    BottomRow,
    /// `R^T R` differs from the identity by more than the tolerance.
    NotOrthonormal(f64),
    /// `det R` is -1 (a reflection).
    Reflection,
}

impl std::fmt::Display for NotRigid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NotRigid::NonFinite => write!(f, "an element is not a finite number"),
            NotRigid::BottomRow => write!(f, "bottom row is not [0, 0, 0, 1]"),
            NotRigid::NotOrthonormal(e) => write!(
                f,
                "rotation part is not orthonormal: |R^T R - I| = {e:.3e} > {RIGID_TOLERANCE:e}"
            ),
            NotRigid::Reflection => write!(f, "rotation part has determinant -1 (a reflection)"),
        }
    }
}

/// Accepts a homogeneous 4x4 matrix as a rigid transform, re-orthonormalising the rotation part
/// when it is within [`RIGID_TOLERANCE`] of orthonormal (so that 6-digit data in files works).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::pose::{NotRigid, matrix_from_rows, pose_from_matrix};
///
/// // A quarter turn about z, 1 m up.
/// let rows = [
///     [0.0, -1.0, 0.0, 0.0],
///     [1.0, 0.0, 0.0, 0.0],
///     [0.0, 0.0, 1.0, 1.0],
///     [0.0, 0.0, 0.0, 1.0],
/// ];
/// let pose = pose_from_matrix(&matrix_from_rows(&rows)).expect("rigid");
/// assert_eq!(pose.translation.vector.z, 1.0);
///
/// // A mirror is not a rigid transform.
/// let mut mirror = rows;
/// mirror[2][2] = -1.0;
/// assert_eq!(pose_from_matrix(&matrix_from_rows(&mirror)), Err(NotRigid::Reflection));
/// ```
pub fn pose_from_matrix(m: &Matrix4<f64>) -> Result<Pose, NotRigid> {
    if m.iter().any(|v| !v.is_finite()) {
        return Err(NotRigid::NonFinite);
    }
    if m[(3, 0)] != 0.0 || m[(3, 1)] != 0.0 || m[(3, 2)] != 0.0 || m[(3, 3)] != 1.0 {
        return Err(NotRigid::BottomRow);
    }
    let r: Matrix3<f64> = m.fixed_view::<3, 3>(0, 0).into_owned();
    let err = (r.transpose() * r - Matrix3::identity()).amax();
    if err > RIGID_TOLERANCE {
        return Err(NotRigid::NotOrthonormal(err));
    }
    if r.determinant() < 0.0 {
        return Err(NotRigid::Reflection);
    }
    let rot = if err == 0.0 {
        Rotation3::from_matrix_unchecked(r)
    } else {
        Rotation3::from_matrix_eps(&r, 1e-15, 100, Rotation3::identity())
    };
    let t = Translation3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]);
    Ok(Pose::from_parts(t, rot))
}

/// Row-major nested arrays `T[row][col]` of a pose, as in the JSON outputs.
pub fn pose_to_rows(p: &Pose) -> [[f64; 4]; 4] {
    let m = p.to_homogeneous();
    let mut out = [[0.0; 4]; 4];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = m[(r, c)];
        }
    }
    out
}

/// The matrix of row-major nested arrays.
pub fn matrix_from_rows(rows: &[[f64; 4]; 4]) -> Matrix4<f64> {
    Matrix4::from_fn(|r, c| rows[r][c])
}

/// `a * b` written out element by element (the FK hot path; nalgebra's generic product is
/// slower for 3x3 rotations). Same result as `a * b` to rounding.
#[inline(always)]
pub fn compose(a: &Pose, b: &Pose) -> Pose {
    let ra = a.rotation.matrix();
    let rb = b.rotation.matrix();
    let tb = &b.translation.vector;
    let mut r = Matrix3::zeros();
    for i in 0..3 {
        let (a0, a1, a2) = (ra[(i, 0)], ra[(i, 1)], ra[(i, 2)]);
        r[(i, 0)] = a0 * rb[(0, 0)] + a1 * rb[(1, 0)] + a2 * rb[(2, 0)];
        r[(i, 1)] = a0 * rb[(0, 1)] + a1 * rb[(1, 1)] + a2 * rb[(2, 1)];
        r[(i, 2)] = a0 * rb[(0, 2)] + a1 * rb[(1, 2)] + a2 * rb[(2, 2)];
    }
    let ta = &a.translation.vector;
    let t = Translation3::new(
        ra[(0, 0)] * tb.x + ra[(0, 1)] * tb.y + ra[(0, 2)] * tb.z + ta.x,
        ra[(1, 0)] * tb.x + ra[(1, 1)] * tb.y + ra[(1, 2)] * tb.z + ta.y,
        ra[(2, 0)] * tb.x + ra[(2, 1)] * tb.y + ra[(2, 2)] * tb.z + ta.z,
    );
    Pose::from_parts(t, Rotation3::from_matrix_unchecked(r))
}
