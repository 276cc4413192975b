//! The unit quaternion `Q = {eta, epsilon}`, (2.30)-(2.37): both ways, the product and the
//! inverse.

use nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};

/// Unit quaternion `Q = {eta, epsilon}` of a rotation, eqs. (2.34)–(2.35), with eta >= 0
/// (rotation angle in [-pi, pi]); at eta = 0 (a half turn) the sign makes the largest component
/// of epsilon positive. Computed with Shepperd's method, accurate for every rotation. No
/// allocation.
///
/// # Examples
///
/// `eta = cos(theta/2)`, `epsilon = sin(theta/2) r`, (2.30)-(2.31), and back to the matrix:
///
/// ```
/// use armlab::kinematics::orientation::{
///     quaternion_from_rotation, rotation_from_angle_axis, rotation_from_quaternion,
/// };
/// use armlab::nalgebra::{Unit, Vector3};
///
/// let (theta, r) = (1.3, Unit::new_normalize(Vector3::new(2.0, -1.0, 2.0)));
/// let rot = rotation_from_angle_axis(theta, &r);
/// let q = quaternion_from_rotation(&rot);
/// assert!((q.w - (theta / 2.0).cos()).abs() < 1e-15);
/// assert!((q.imag() - r.into_inner() * (theta / 2.0).sin()).norm() < 1e-15);
/// let back = rotation_from_quaternion(&q);
/// assert!((back.matrix() - rot.matrix()).amax() < 1e-15);
/// ```
pub fn quaternion_from_rotation(r: &Rotation3<f64>) -> UnitQuaternion<f64> {
    let q = UnitQuaternion::from_rotation_matrix(r);
    let mut c = *q.quaternion();
    let flip = if c.w == 0.0 {
        let v = c.imag();
        let k = (0..3)
            .max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
            .unwrap_or(0);
        v[k] < 0.0
    } else {
        c.w < 0.0
    };
    if flip {
        c = -c;
    }
    UnitQuaternion::new_unchecked(c)
}

/// Rotation of a unit quaternion, eq. (2.33), written out in eta and epsilon.
///
/// # Examples
///
/// `Q = {cos(theta/2), sin(theta/2) z}` is the elementary rotation about z:
///
/// ```
/// use armlab::kinematics::orientation::{Axis, elementary, quaternion, rotation_from_quaternion};
/// use armlab::nalgebra::Vector3;
///
/// let q = quaternion(0.35f64.cos(), Vector3::z() * 0.35f64.sin());
/// let r = rotation_from_quaternion(&q);
/// assert!((r.matrix() - elementary(Axis::Z, 0.7).matrix()).amax() < 1e-15);
/// ```
pub fn rotation_from_quaternion(q: &UnitQuaternion<f64>) -> Rotation3<f64> {
    let (eta, ex, ey, ez) = (q.w, q.i, q.j, q.k);
    // (2.33)
    Rotation3::from_matrix_unchecked(Matrix3::new(
        2.0 * (eta * eta + ex * ex) - 1.0,
        2.0 * (ex * ey - eta * ez),
        2.0 * (ex * ez + eta * ey),
        2.0 * (ex * ey + eta * ez),
        2.0 * (eta * eta + ey * ey) - 1.0,
        2.0 * (ey * ez - eta * ex),
        2.0 * (ex * ez - eta * ey),
        2.0 * (ey * ez + eta * ex),
        2.0 * (eta * eta + ez * ez) - 1.0,
    ))
}

/// A unit quaternion from `eta` and `epsilon`, normalised.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::quaternion;
/// use armlab::nalgebra::Vector3;
///
/// let q = quaternion(2.0, Vector3::new(0.0, 0.0, 2.0)); // normalised to {1, (0, 0, 1)}/sqrt(2)
/// assert!((q.w - 0.5f64.sqrt()).abs() < 1e-15 && (q.k - 0.5f64.sqrt()).abs() < 1e-15);
/// ```
pub fn quaternion(eta: f64, eps: Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::from_parts(eta, eps))
}

/// The quaternion product `Q1 * Q2`, eq. (2.37), written out:
/// `{eta1 eta2 - epsilon1^T epsilon2, eta1 epsilon2 + eta2 epsilon1 + epsilon1 x epsilon2}`.
/// It corresponds to the matrix product `R(Q1) R(Q2)`. Not renormalised (the product of two unit
/// quaternions is one, to rounding); the sign of eta is kept as it comes.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{
///     quaternion_from_rotation, quaternion_product, rotation_from_quaternion, rotation_from_rpy,
/// };
/// use armlab::nalgebra::Vector3;
///
/// let (r1, r2) = (
///     rotation_from_rpy(&Vector3::new(0.3, -0.2, 1.0)),
///     rotation_from_rpy(&Vector3::new(-1.1, 0.5, 0.4)),
/// );
/// let q = quaternion_product(&quaternion_from_rotation(&r1), &quaternion_from_rotation(&r2));
/// assert!((rotation_from_quaternion(&q).matrix() - (r1 * r2).matrix()).amax() < 1e-15);
/// ```
pub fn quaternion_product(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
    let (eta1, eps1) = (a.w, a.imag());
    let (eta2, eps2) = (b.w, b.imag());
    // (2.37)
    let eta = eta1 * eta2 - eps1.dot(&eps2);
    let eps = eps2 * eta1 + eps1 * eta2 + eps1.cross(&eps2);
    UnitQuaternion::new_unchecked(Quaternion::from_parts(eta, eps))
}

/// The inverse `Q^-1 = {eta, -epsilon}`, eq. (2.36): the quaternion of `R^T`.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{quaternion, quaternion_inverse, quaternion_product};
/// use armlab::nalgebra::Vector3;
///
/// let q = quaternion(0.6, Vector3::new(0.0, 0.8, 0.0));
/// let one = quaternion_product(&q, &quaternion_inverse(&q));
/// assert!((one.w - 1.0).abs() < 1e-15 && one.imag().norm() < 1e-15);
/// ```
pub fn quaternion_inverse(q: &UnitQuaternion<f64>) -> UnitQuaternion<f64> {
    // (2.36)
    UnitQuaternion::new_unchecked(Quaternion::from_parts(q.w, -q.imag()))
}
