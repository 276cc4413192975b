//! Angle and axis, (2.25)-(2.28), both ways, with the cases sin(theta) = 0 (Problem 2.5).

use super::{SINGULAR_EPS, degrees};
use crate::kinematics::trig::atan2;
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use std::f64::consts::PI;
use std::fmt;

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

/// `R(theta, r)`, eq. (2.25), written out: `R = c I + (1 - c) r r^T + s S(r)`.
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
/// // And back, eqs. (2.27)-(2.28).
/// let aa = angle_axis_from_rotation(&r);
/// assert!((aa.angle - angle).abs() < 1e-15);
/// assert!((aa.axis.into_inner() - axis.into_inner()).norm() < 1e-15);
/// ```
pub fn rotation_from_angle_axis(angle: f64, axis: &Unit<Vector3<f64>>) -> Rotation3<f64> {
    let (s, c) = angle.sin_cos();
    let v = 1.0 - c;
    let (x, y, z) = (axis[0], axis[1], axis[2]);
    // (2.25)
    Rotation3::from_matrix_unchecked(Matrix3::new(
        x * x * v + c,
        x * y * v - z * s,
        x * z * v + y * s,
        x * y * v + z * s,
        y * y * v + c,
        y * z * v - x * s,
        x * z * v - y * s,
        y * z * v + x * s,
        z * z * v + c,
    ))
}

/// Angle and axis of a rotation, eqs. (2.27)–(2.28), robust at both ends. No allocation.
///
/// # Examples
///
/// A half turn (Problem 2.5), where (2.28) divides by sin(pi) = 0, and no turn at all:
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
/// component positive (where the skew part is rounding noise, below 16 machine epsilons).
/// Between pi/2 and pi the symmetric part is used too (better conditioned than (2.28)), with
/// the sign fixed by the skew part.
pub fn angle_axis_from_rotation(r: &Rotation3<f64>) -> AngleAxis {
    let m = r.matrix();
    // 2 sin(theta) r, (2.28)
    let v = Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    );
    let vn = v.norm(); // = 2 sin(theta)
    // (2.27), as atan2 of sine and cosine (acos loses half the digits near 0 and pi).
    let angle = atan2(vn, m.trace() - 1.0);
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
    AngleAxis {
        angle,
        axis: axis_from_symmetric_part(m, &v),
        singular: false,
    }
}

/// Below this length of the skew part `2 sin(theta) r` of a half turn, the skew part is rounding
/// noise and does not sign the axis (flipping r there changes the matrix by less than this).
const SKEW_NOISE: f64 = 16.0 * f64::EPSILON;

/// The axis of a rotation by more than pi/2 from `(R + R^T)/2 - cos(theta) I = (1 - cos(theta))
/// r r^T`: its column with the largest diagonal entry, signed by the skew part `v`, or, at a
/// half turn where `v` is rounding noise, with its largest component positive (the last of equal
/// ones).
fn axis_from_symmetric_part(m: &Matrix3<f64>, v: &Vector3<f64>) -> Unit<Vector3<f64>> {
    // cos(theta) = (r11 + r22 + r33 - 1)/2, (2.27).
    let c = 0.5 * (m.trace() - 1.0);
    let s: Matrix3<f64> = (m + m.transpose()) * 0.5 - Matrix3::identity() * c;
    let k = (0..3)
        .max_by(|&a, &b| s[(a, a)].total_cmp(&s[(b, b)]))
        .unwrap_or(0);
    let axis = Unit::new_normalize(s.column(k).into_owned());
    if v.norm() <= SKEW_NOISE {
        largest_positive(axis)
    } else if axis.dot(v) < 0.0 {
        -axis
    } else {
        axis
    }
}

/// `r` or `-r`, whichever has its largest component (the last of equal ones) positive.
fn largest_positive(r: Unit<Vector3<f64>>) -> Unit<Vector3<f64>> {
    let j = (0..3)
        .max_by(|&a, &b| r[a].abs().total_cmp(&r[b].abs()))
        .unwrap_or(0);
    if r[j] < 0.0 { -r } else { r }
}

/// Which case of (2.27)-(2.28) a rotation falls in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AngleAxisCase {
    /// 0 < theta < pi: one axis r (and the same rotation as (-theta, -r)).
    Regular,
    /// theta = 0 (sin(theta) below [`SINGULAR_EPS`], cos(theta) > 0): the identity; any axis
    /// serves.
    AnyAxis,
    /// theta = pi (sin(theta) below [`SINGULAR_EPS`], cos(theta) < 0): a half turn; r and -r
    /// give the same matrix.
    HalfTurn,
}

/// Every angle-axis pair of a rotation with the angle in [0, pi] (Problem 2.5).
#[derive(Debug, Clone, PartialEq)]
pub struct AngleAxisSolutions {
    /// The rotation angle theta in [0, pi] (rad), (2.27).
    pub angle: f64,
    /// The axes: one for a regular rotation, none where any axis serves, r and -r (r with its
    /// largest component positive) for a half turn. In the base frame, unit length.
    pub axes: Vec<Unit<Vector3<f64>>>,
    /// Which case this is.
    pub case: AngleAxisCase,
}

impl fmt::Display for AngleAxisSolutions {
    /// `theta = 120° about r = (0.57735, 0.57735, 0.57735)`, `theta = 0°: any axis serves`, or
    /// `theta = 180° about r = (...) or -r = (...)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = |a: &Unit<Vector3<f64>>| format!("({:.6}, {:.6}, {:.6})", a[0], a[1], a[2]);
        write!(f, "theta = {}°", degrees(self.angle))?;
        match (self.case, self.axes.as_slice()) {
            (AngleAxisCase::AnyAxis, _) | (_, []) => write!(f, ": any axis serves"),
            (AngleAxisCase::HalfTurn, [r, minus, ..]) => {
                write!(f, " about r = {} or -r = {} (a half turn)", v(r), v(minus))
            }
            (_, [r, ..]) => write!(f, " about r = {}", v(r)),
        }
    }
}

/// Angle and axis with the cases of Problem 2.5 as data: theta = 0, any axis; theta = pi, r and
/// -r. Allocates (one `Vec`); the batch path is [`angle_axis_from_rotation`].
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{AngleAxisCase, angle_axis_solutions, rotation_from_angle_axis};
/// use armlab::nalgebra::{Rotation3, Unit, Vector3};
/// use std::f64::consts::PI;
///
/// let none = angle_axis_solutions(&Rotation3::identity());
/// assert_eq!(none.case, AngleAxisCase::AnyAxis);
/// assert!(none.axes.is_empty());
///
/// let half = angle_axis_solutions(&rotation_from_angle_axis(PI, &Vector3::y_axis()));
/// assert_eq!(half.case, AngleAxisCase::HalfTurn);
/// assert_eq!(half.axes.len(), 2);
/// assert!((half.axes[0].into_inner() - Vector3::y()).norm() < 1e-15);
/// assert!((half.axes[1].into_inner() + Vector3::y()).norm() < 1e-15);
/// ```
pub fn angle_axis_solutions(r: &Rotation3<f64>) -> AngleAxisSolutions {
    let aa = angle_axis_from_rotation(r);
    let sin = aa.angle.sin();
    let case = match (sin < SINGULAR_EPS, aa.angle < PI / 2.0) {
        (false, _) => AngleAxisCase::Regular,
        (true, true) => AngleAxisCase::AnyAxis,
        (true, false) => AngleAxisCase::HalfTurn,
    };
    let axes = match case {
        AngleAxisCase::Regular => vec![aa.axis],
        AngleAxisCase::AnyAxis => Vec::new(),
        AngleAxisCase::HalfTurn => {
            // r with its largest component positive, then -r.
            let r = largest_positive(aa.axis);
            vec![r, -r]
        }
    };
    AngleAxisSolutions {
        angle: aa.angle,
        axes,
        case,
    }
}
