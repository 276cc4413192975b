//! The inverse of a homogeneous transformation, (2.45).

use nalgebra::{Matrix3, Matrix4, Vector3};

/// The inverse of a homogeneous transformation `A = [R o; 0 1]`, eq. (2.45), written out from
/// the transpose: `A^-1 = [R^T  -R^T o; 0 1]` (Problem 2.10). `R` is read from the upper-left
/// block and `o` (metres) from the last column; the bottom row is taken to be `(0, 0, 0, 1)` and
/// `R` orthonormal, neither checked (for a general matrix, `Matrix4::try_inverse`).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::Pose;
/// use armlab::kinematics::orientation::inverse_homogeneous;
/// use armlab::kinematics::pose::{rot_z, trans_x};
/// use armlab::nalgebra::Matrix4;
///
/// let a: Pose = rot_z(0.8) * trans_x(0.3);
/// let t = a.to_homogeneous();
/// let inv = inverse_homogeneous(&t);
/// assert!((inv * t - Matrix4::identity()).amax() < 1e-15);
/// assert!((inv - a.inverse().to_homogeneous()).amax() < 1e-15);
/// ```
pub fn inverse_homogeneous(a: &Matrix4<f64>) -> Matrix4<f64> {
    let r: Matrix3<f64> = a.fixed_view::<3, 3>(0, 0).into_owned();
    let o: Vector3<f64> = a.fixed_view::<3, 1>(0, 3).into_owned();
    let rt = r.transpose();
    let p = -(rt * o);
    // (2.45)
    let mut inv = Matrix4::identity();
    inv.fixed_view_mut::<3, 3>(0, 0).copy_from(&rt);
    inv.fixed_view_mut::<3, 1>(0, 3).copy_from(&p);
    inv
}
