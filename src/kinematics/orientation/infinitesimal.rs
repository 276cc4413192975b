//! Infinitesimal rotations (Problem 2.16) and the sum of minimal representations (Problem 2.15):
//! finite rotations do not commute, their commutator shrinks as the angle squared, and
//! infinitesimal ones commute to first order.

use super::{Axis, EulerKind, elementary};
use nalgebra::{Matrix3, Rotation3, Vector3};

/// The skew-symmetric matrix `S(w)` with `S(w) v = w x v`.
fn skew(w: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -w.z, w.y, w.z, 0.0, -w.x, -w.y, w.x, 0.0)
}

/// The infinitesimal rotation `R(dphi) = I + S(dphi)` of Problem 2.16, `dphi = (dphi_x,
/// dphi_y, dphi_z)` (rad): `Rx(dphi_x) Ry(dphi_y) Rz(dphi_z)` with `cos(d) = 1`, `sin(d) = d` and
/// the products of two small angles dropped. To first order, `R(dphi) R(dphi') = R(dphi +
/// dphi')` in either order. Not exactly orthonormal (it is a first-order approximation).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::infinitesimal;
/// use armlab::nalgebra::Vector3;
///
/// let (a, b) = (Vector3::new(1e-4, -2e-4, 3e-4), Vector3::new(-5e-5, 1e-4, 2e-4));
/// let ab = infinitesimal(&a) * infinitesimal(&b);
/// let ba = infinitesimal(&b) * infinitesimal(&a);
/// // Both orders agree with R(a + b) up to second-order terms (~1e-8 here).
/// assert!((ab - infinitesimal(&(a + b))).amax() < 1e-7);
/// assert!((ab - ba).amax() < 1e-7);
/// assert_eq!(infinitesimal(&a)[(1, 0)], 3e-4); // dphi_z below the diagonal
/// ```
pub fn infinitesimal(dphi: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::identity() + skew(dphi)
}

/// The elementary rotation about `axis` by a small `angle` (rad), to first order: (2.6)-(2.8)
/// with `cos(angle) = 1` and `sin(angle) = angle` (Problem 2.16's hint), `I + angle S(axis)`.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, infinitesimal_elementary};
///
/// let r = infinitesimal_elementary(Axis::X, 0.01);
/// assert_eq!((r[(1, 1)], r[(2, 1)], r[(1, 2)]), (1.0, 0.01, -0.01));
/// ```
pub fn infinitesimal_elementary(axis: Axis, angle: f64) -> Matrix3<f64> {
    infinitesimal(&(axis.unit() * angle))
}

/// Frobenius norm of the commutator `Ra(angle) Rb(angle) - Rb(angle) Ra(angle)` of two
/// elementary rotations (2.6)-(2.8) by the same angle (rad): 0 for the same axis, else it shrinks
/// as the angle squared, `sqrt(2) angle^2 + O(angle^3)` (the commutator is `angle^2 S(a x b)` to
/// second order).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, commutator_norm};
///
/// assert_eq!(commutator_norm(Axis::Z, Axis::Z, 0.7), 0.0);
/// let small = commutator_norm(Axis::X, Axis::Y, 1e-3);
/// assert!((small / 1e-6 - 2f64.sqrt()).abs() < 1e-5);
/// // Finite angles: about 0.82 for 45 degrees about x and y.
/// let n = commutator_norm(Axis::X, Axis::Y, std::f64::consts::FRAC_PI_4);
/// assert!((n - 0.8195).abs() < 1e-4);
/// ```
pub fn commutator_norm(a: Axis, b: Axis, angle: f64) -> f64 {
    let (ra, rb) = (elementary(a, angle), elementary(b, angle));
    ((ra * rb).matrix() - (rb * ra).matrix()).norm()
}

/// Frobenius norm of the commutator of the first-order elementary rotations
/// ([`infinitesimal_elementary`]) about `a` and `b` by `angle` (rad). Its first-order terms
/// cancel: what is left is the second-order `angle^2 S(a x b)`, of norm `sqrt(2) angle^2` for
/// two different axes, which the first-order approximation neglects. This is Problem 2.16:
/// infinitesimal rotations commute.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, infinitesimal_commutator_norm};
///
/// let n = infinitesimal_commutator_norm(Axis::Y, Axis::Z, 1e-3);
/// assert!((n - 2f64.sqrt() * 1e-6).abs() < 1e-18); // no first-order term
/// ```
pub fn infinitesimal_commutator_norm(a: Axis, b: Axis, angle: f64) -> f64 {
    let (ra, rb) = (
        infinitesimal_elementary(a, angle),
        infinitesimal_elementary(b, angle),
    );
    (ra * rb - rb * ra).norm()
}

/// The angle (rad, in [0, pi]) of the rotation that takes `a` to `b`, `a^T b`, from (2.27) as
/// atan2 of its sine and cosine (accurate for small angles too).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, elementary, rotation_angle_between};
///
/// let d = rotation_angle_between(&elementary(Axis::Z, 0.1), &elementary(Axis::Z, 0.1 + 1e-9));
/// assert!((d - 1e-9).abs() < 1e-16); // acos of the trace gives 0 here
/// ```
pub fn rotation_angle_between(a: &Rotation3<f64>, b: &Rotation3<f64>) -> f64 {
    super::angle_axis_from_rotation(&(a.inverse() * b)).angle
}

/// Problem 2.15: the sum of two minimal representations, defined by the composition of their
/// rotations, and how far it is from commuting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SumComparison {
    /// The angles (rad) of `R(phi1) R(phi2)`: the sum `phi1 (+) phi2`.
    pub sum: Vector3<f64>,
    /// The angles (rad) of `R(phi2) R(phi1)`: the sum in the other order, `phi2 (+) phi1`.
    pub reversed: Vector3<f64>,
    /// The rotation angle (rad) between the two products: 0 where the sum commutes.
    pub order_angle: f64,
    /// The rotation angle (rad) between `R(phi1 + phi2)` (the angles added as numbers) and
    /// `R(phi1) R(phi2)`: 0 only in special cases (e.g. both turns about the same fixed axis).
    pub naive_angle: f64,
}

/// The sum of two minimal representations `phi1`, `phi2` (rad) of kind `kind` in both orders
/// (Problem 2.15): `phi1 (+) phi2` is the representation of `R(phi1) R(phi2)`. The two orders
/// differ in general, and neither is `phi1 + phi2`.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::EulerKind;
/// use armlab::kinematics::orientation::sum_comparison;
/// use armlab::nalgebra::Vector3;
/// use std::f64::consts::FRAC_PI_2;
///
/// // Roll then pitch against pitch then roll, 90 degrees each: the frames end 120 degrees apart.
/// let (roll, pitch) = (Vector3::new(0.0, 0.0, FRAC_PI_2), Vector3::new(0.0, FRAC_PI_2, 0.0));
/// let c = sum_comparison(EulerKind::Rpy, &roll, &pitch);
/// assert!((c.order_angle - 2.0 * std::f64::consts::FRAC_PI_3).abs() < 1e-12);
/// // Two yaws commute and add.
/// let yaw = Vector3::new(0.4, 0.0, 0.0);
/// let c = sum_comparison(EulerKind::Rpy, &yaw, &yaw);
/// assert!(c.order_angle < 1e-15 && c.naive_angle < 1e-15);
/// ```
pub fn sum_comparison(kind: EulerKind, phi1: &Vector3<f64>, phi2: &Vector3<f64>) -> SumComparison {
    let (r1, r2) = (kind.to_rotation(phi1), kind.to_rotation(phi2));
    let (ab, ba) = (r1 * r2, r2 * r1);
    SumComparison {
        sum: kind.from_rotation(&ab).angles,
        reversed: kind.from_rotation(&ba).angles,
        order_angle: rotation_angle_between(&ab, &ba),
        naive_angle: rotation_angle_between(&kind.to_rotation(&(phi1 + phi2)), &ab),
    }
}
