//! Minimal orientation representations of Sect. 2.4 and their conversions in both directions:
//! ZYZ Euler angles (2.18)–(2.20), roll–pitch–yaw (2.21)–(2.23), angle and axis (2.25)–(2.27),
//! and the unit quaternion (2.30)–(2.35).
//!
//! Every inverse conversion is total: at the representation singularities (Problems 2.2, 2.3,
//! 2.5) it makes a documented choice and says so in [`Orientation::singular`], never NaN.

use nalgebra::{Matrix3, Quaternion, Rotation3, Unit, UnitQuaternion, Vector3};
use std::f64::consts::PI;

/// Below this value of the sine of the middle angle (or of the rotation angle), a
/// representation is reported as singular and the documented choice is applied.
pub const SINGULAR_EPS: f64 = 1e-12;

/// A minimal orientation representation `phi` (3 numbers) with a singularity flag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orientation {
    /// The three angles (rad): (phi, theta, psi).
    pub angles: Vector3<f64>,
    /// True where the representation is singular (sine of the middle angle below
    /// [`SINGULAR_EPS`]) and only a combination of angles is determined; the first angle is then
    /// set to 0 and the round trip is exact to within [`SINGULAR_EPS`].
    pub singular: bool,
}

/// Which minimal representation of orientation an operational-space vector uses.
///
/// # Examples
///
/// Choosing the representation at run time, e.g. from a user's setting:
///
/// ```
/// use armlab::kinematics::EulerKind;
/// use armlab::nalgebra::Vector3;
///
/// let angles = Vector3::new(0.5, 0.8, -1.2);
/// for kind in [EulerKind::Zyz, EulerKind::Rpy] {
///     let r = kind.to_rotation(&angles);
///     let back = kind.from_rotation(&r);
///     assert!((back.angles - angles).amax() < 1e-14, "{}", kind.as_str());
/// }
/// // The same three numbers are different rotations in the two representations.
/// let zyz = EulerKind::Zyz.to_rotation(&angles);
/// let rpy = EulerKind::Rpy.to_rotation(&angles);
/// assert!(zyz.angle_to(&rpy) > 0.1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EulerKind {
    /// ZYZ Euler angles `R = Rz(phi) Ry(theta) Rz(psi)`, (2.18).
    Zyz,
    /// Roll–pitch–yaw `R = Rz(phi) Ry(theta) Rx(psi)` (Siciliano's ZYX form), (2.21).
    Rpy,
}

impl EulerKind {
    /// Lower-case name.
    pub fn as_str(self) -> &'static str {
        match self {
            EulerKind::Zyz => "zyz",
            EulerKind::Rpy => "rpy",
        }
    }

    /// Rotation of the angles.
    pub fn to_rotation(self, a: &Vector3<f64>) -> Rotation3<f64> {
        match self {
            EulerKind::Zyz => rotation_from_zyz(a),
            EulerKind::Rpy => rotation_from_rpy(a),
        }
    }

    /// Angles of the rotation (theta in (0, pi) for ZYZ, in (-pi/2, pi/2) for RPY).
    pub fn from_rotation(self, r: &Rotation3<f64>) -> Orientation {
        match self {
            EulerKind::Zyz => zyz_from_rotation(r),
            EulerKind::Rpy => rpy_from_rotation(r),
        }
    }
}

// Elementary rotations written out from sin/cos, (2.6)-(2.8) (nalgebra's axis-angle
// constructors round tiny angles to the identity).
pub(crate) fn rz(a: f64) -> Rotation3<f64> {
    let (s, c) = a.sin_cos();
    Rotation3::from_matrix_unchecked(Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0))
}
pub(crate) fn ry(a: f64) -> Rotation3<f64> {
    let (s, c) = a.sin_cos();
    Rotation3::from_matrix_unchecked(Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c))
}
pub(crate) fn rx(a: f64) -> Rotation3<f64> {
    let (s, c) = a.sin_cos();
    Rotation3::from_matrix_unchecked(Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c))
}

/// `R = Rz(phi) Ry(theta) Rz(psi)`, eq. (2.18).
pub fn rotation_from_zyz(a: &Vector3<f64>) -> Rotation3<f64> {
    rz(a[0]) * ry(a[1]) * rz(a[2])
}

/// ZYZ angles with theta in [0, pi], eq. (2.19).
///
/// Singular case (Problem 2.2), sin(theta) = 0: only phi + psi (theta = 0) or phi - psi
/// (theta = pi) is determined; phi = 0 is chosen and psi carries the whole rotation about z.
/// psi is always computed from the residual `(Rz(phi) Ry(theta))^T R`, so that the round trip is
/// exact to rounding even close to the singularity.
///
/// # Examples
///
/// A round trip through (2.18) and (2.19), and the singular case:
///
/// ```
/// use armlab::kinematics::orientation::{rotation_from_zyz, zyz_from_rotation};
/// use armlab::nalgebra::Vector3;
///
/// let angles = Vector3::new(0.3, 1.1, -0.7); // phi, theta, psi (rad), theta in (0, pi)
/// let r = rotation_from_zyz(&angles);
/// let back = zyz_from_rotation(&r);
/// assert!(!back.singular);
/// assert!((back.angles - angles).amax() < 1e-15);
///
/// // theta = 0: only phi + psi is determined; phi = 0 is chosen.
/// let flat = zyz_from_rotation(&rotation_from_zyz(&Vector3::new(0.4, 0.0, 0.5)));
/// assert!(flat.singular);
/// assert_eq!(flat.angles[0], 0.0);
/// assert!((flat.angles[2] - 0.9).abs() < 1e-15);
/// ```
pub fn zyz_from_rotation(r: &Rotation3<f64>) -> Orientation {
    zyz_branch(r, 1.0)
}

/// ZYZ angles with theta in [-pi, 0], eq. (2.20): the second solution of the spherical wrist.
///
/// # Examples
///
/// Both solutions describe the same rotation: `(phi + pi, -theta, psi + pi)`.
///
/// ```
/// use armlab::kinematics::orientation::{
///     rotation_from_zyz, zyz_from_rotation, zyz_from_rotation_negative,
/// };
/// use armlab::nalgebra::Vector3;
///
/// let r = rotation_from_zyz(&Vector3::new(0.3, 1.1, -0.7));
/// let (pos, neg) = (zyz_from_rotation(&r), zyz_from_rotation_negative(&r));
/// assert!((neg.angles[1] + pos.angles[1]).abs() < 1e-15);
/// let again = rotation_from_zyz(&neg.angles);
/// assert!((again.matrix() - r.matrix()).amax() < 1e-15);
/// ```
pub fn zyz_from_rotation_negative(r: &Rotation3<f64>) -> Orientation {
    zyz_branch(r, -1.0)
}

fn zyz_branch(r: &Rotation3<f64>, sign: f64) -> Orientation {
    let m = r.matrix();
    let s = m[(0, 2)].hypot(m[(1, 2)]);
    let singular = s < SINGULAR_EPS;
    // At (or within SINGULAR_EPS of) the singularity phi = 0; psi comes from the residual, so
    // the round trip error is at most ~SINGULAR_EPS there and rounding elsewhere.
    let phi = if singular {
        0.0
    } else {
        (sign * m[(1, 2)]).atan2(sign * m[(0, 2)])
    };
    let theta = (sign * s).atan2(m[(2, 2)]);
    let res = (rz(phi) * ry(theta)).inverse() * r;
    let psi = res.matrix()[(1, 0)].atan2(res.matrix()[(0, 0)]);
    Orientation {
        angles: Vector3::new(phi, theta, psi),
        singular,
    }
}

/// `R = Rz(phi) Ry(theta) Rx(psi)`, eq. (2.21).
pub fn rotation_from_rpy(a: &Vector3<f64>) -> Rotation3<f64> {
    rz(a[0]) * ry(a[1]) * rx(a[2])
}

/// Roll–pitch–yaw angles with theta in [-pi/2, pi/2], eq. (2.22).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{rotation_from_rpy, rpy_from_rotation};
/// use armlab::nalgebra::Vector3;
///
/// // phi about z, theta about y, psi about x: R = Rz(phi) Ry(theta) Rx(psi), (2.21).
/// let angles = Vector3::new(-2.0, 0.4, 2.5);
/// let back = rpy_from_rotation(&rotation_from_rpy(&angles));
/// assert!(!back.singular && (back.angles - angles).amax() < 1e-14);
///
/// // A pure yaw of 90 degrees takes x0 to y0.
/// let yaw = rotation_from_rpy(&Vector3::new(std::f64::consts::FRAC_PI_2, 0.0, 0.0));
/// assert!((yaw * Vector3::x() - Vector3::y()).norm() < 1e-15);
/// ```
///
/// Singular case (Problem 2.3), cos(theta) = 0: only phi - psi (theta = pi/2) or phi + psi
/// (theta = -pi/2) is determined; phi = 0 is chosen. psi is computed from the residual, as for
/// ZYZ.
pub fn rpy_from_rotation(r: &Rotation3<f64>) -> Orientation {
    let m = r.matrix();
    let c = m[(0, 0)].hypot(m[(1, 0)]);
    let singular = c < SINGULAR_EPS;
    let phi = if singular {
        0.0
    } else {
        m[(1, 0)].atan2(m[(0, 0)])
    };
    let theta = (-m[(2, 0)]).atan2(c);
    let res = (rz(phi) * ry(theta)).inverse() * r;
    let psi = res.matrix()[(2, 1)].atan2(res.matrix()[(1, 1)]);
    Orientation {
        angles: Vector3::new(phi, theta, psi),
        singular,
    }
}

/// A rotation by `angle` (rad) about the unit `axis`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleAxis {
    /// Rotation angle in [0, pi] (rad).
    pub angle: f64,
    /// Unit axis r.
    pub axis: Unit<Vector3<f64>>,
    /// True at angle 0, where any axis is valid (z is returned).
    pub singular: bool,
}

/// `R(theta, r)`, eq. (2.25).
///
/// # Examples
///
/// A third of a turn about the diagonal `(1, 1, 1)/sqrt(3)` permutes the axes: x to y, y to z.
///
/// ```
/// use armlab::kinematics::orientation::{angle_axis_from_rotation, rotation_from_angle_axis};
/// use armlab::nalgebra::{Unit, Vector3};
///
/// let axis = Unit::new_normalize(Vector3::new(1.0, 1.0, 1.0));
/// let angle = 2.0 * std::f64::consts::PI / 3.0;
/// let r = rotation_from_angle_axis(angle, &axis);
/// assert!((r * Vector3::x() - Vector3::y()).norm() < 1e-15);
/// assert!((r * Vector3::y() - Vector3::z()).norm() < 1e-15);
/// // And back, eqs. (2.26)-(2.27).
/// let aa = angle_axis_from_rotation(&r);
/// assert!((aa.angle - angle).abs() < 1e-15);
/// assert!((aa.axis.into_inner() - axis.into_inner()).norm() < 1e-15);
/// ```
pub fn rotation_from_angle_axis(angle: f64, axis: &Unit<Vector3<f64>>) -> Rotation3<f64> {
    Rotation3::from_axis_angle(axis, angle)
}

/// Angle and axis of a rotation, eqs. (2.26)–(2.27), robust at both ends.
///
/// # Examples
///
/// A half turn (Problem 2.5), where (2.27) divides by sin(pi) = 0, and no turn at all:
///
/// ```
/// use armlab::kinematics::orientation::{angle_axis_from_rotation, rotation_from_angle_axis};
/// use armlab::nalgebra::{Rotation3, Unit, Vector3};
/// use std::f64::consts::PI;
///
/// let axis = Unit::new_normalize(Vector3::new(0.0, 3.0, 4.0));
/// let half = angle_axis_from_rotation(&rotation_from_angle_axis(PI, &axis));
/// assert!((half.angle - PI).abs() < 1e-15);
/// assert!((half.axis.into_inner() - axis.into_inner()).norm() < 1e-15);
///
/// let none = angle_axis_from_rotation(&Rotation3::identity());
/// assert!(none.singular && none.angle == 0.0);
/// ```
///
/// angle = 0: the axis is undefined; z is returned and `singular` is set. angle = pi
/// (Problem 2.5): r and -r describe the same rotation; r is taken from the symmetric part
/// `(R + R^T)/2 = cos(theta) I + (1 - cos(theta)) r r^T`, with the sign that makes its largest
/// component positive. Between pi/2 and pi the symmetric part is used too (better conditioned
/// than (2.27)), with the sign fixed by the skew part.
pub fn angle_axis_from_rotation(r: &Rotation3<f64>) -> AngleAxis {
    let m = r.matrix();
    let v = Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    );
    let vn = v.norm(); // = 2 sin(theta)
    let angle = vn.atan2(m.trace() - 1.0);
    if vn == 0.0 && angle < PI / 2.0 {
        return AngleAxis {
            angle: 0.0,
            axis: Vector3::z_axis(),
            singular: true,
        };
    }
    if angle < PI / 2.0 {
        return AngleAxis {
            angle,
            axis: Unit::new_unchecked(v / vn),
            singular: false,
        };
    }
    let c = angle.cos();
    let s: Matrix3<f64> = (m + m.transpose()) * 0.5 - Matrix3::identity() * c;
    let k = (0..3)
        .max_by(|&a, &b| s[(a, a)].total_cmp(&s[(b, b)]))
        .unwrap_or(0);
    let mut axis = s.column(k).into_owned();
    let n = axis.norm();
    axis /= n;
    let dot = axis.dot(&v);
    if dot < 0.0 || (dot == 0.0 && axis[k] < 0.0) {
        axis = -axis;
    }
    AngleAxis {
        angle,
        axis: Unit::new_normalize(axis),
        singular: false,
    }
}

/// Unit quaternion `Q = {eta, epsilon}` of a rotation, eqs. (2.34)–(2.35), with eta >= 0
/// (rotation angle in [-pi, pi]); at eta = 0 (a half turn) the sign makes the largest component
/// of epsilon positive. Computed with Shepperd's method, accurate for every rotation.
///
/// # Examples
///
/// `eta = cos(theta/2)`, `epsilon = sin(theta/2) r`, (2.30), and back to the matrix:
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

/// Rotation of a unit quaternion, eq. (2.33).
pub fn rotation_from_quaternion(q: &UnitQuaternion<f64>) -> Rotation3<f64> {
    q.to_rotation_matrix()
}

/// A unit quaternion from `eta` and `epsilon`, normalised.
pub fn quaternion(eta: f64, eps: Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::from_parts(eta, eps))
}

/// The matrix `T(phi)` with `omega = T(phi) phi_dot` (Sect. 3.6): columns are the axes of the
/// three elementary rotations expressed in the base frame. Used for the analytical Jacobian.
pub fn angular_velocity_map(kind: EulerKind, a: &Vector3<f64>) -> Matrix3<f64> {
    let (sp, cp) = a[0].sin_cos();
    let (st, ct) = a[1].sin_cos();
    match kind {
        EulerKind::Zyz => Matrix3::new(0.0, -sp, cp * st, 0.0, cp, sp * st, 1.0, 0.0, ct),
        EulerKind::Rpy => Matrix3::new(0.0, -sp, cp * ct, 0.0, cp, sp * ct, 1.0, 0.0, -st),
    }
}

/// Wraps an angle into (-pi, pi].
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::wrap_angle;
/// use std::f64::consts::{FRAC_PI_2, PI};
///
/// assert!((wrap_angle(3.0 * FRAC_PI_2) + FRAC_PI_2).abs() < 1e-15);
/// assert_eq!(wrap_angle(-PI), PI); // the interval is open at -pi
/// assert_eq!(wrap_angle(0.25), 0.25); // inside: returned as is
/// ```
pub fn wrap_angle(a: f64) -> f64 {
    if a > -PI && a <= PI {
        // Already inside: returned as is (the shifted form below would round tiny angles).
        return a;
    }
    let w = (a + PI).rem_euclid(2.0 * PI) - PI;
    if w == -PI { PI } else { w }
}
