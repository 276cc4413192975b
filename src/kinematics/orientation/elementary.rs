//! Elementary rotations about the coordinate axes, (2.6)-(2.8), and the display of axes,
//! frames and steps.

use super::{Axis, Step, StepFrame};
use nalgebra::{Matrix3, Rotation3};
use std::fmt;

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

/// The elementary rotation by `angle` (rad) about a coordinate axis, `Rz`, `Ry` or `Rx` of
/// (2.6)-(2.8), written out from sin and cos (exact for tiny angles).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, elementary};
/// use armlab::nalgebra::Vector3;
/// use std::f64::consts::FRAC_PI_2;
///
/// // A quarter turn about z takes x to y; about x it takes y to z; about y, z to x.
/// assert!((elementary(Axis::Z, FRAC_PI_2) * Vector3::x() - Vector3::y()).norm() < 1e-15);
/// assert!((elementary(Axis::X, FRAC_PI_2) * Vector3::y() - Vector3::z()).norm() < 1e-15);
/// assert!((elementary(Axis::Y, FRAC_PI_2) * Vector3::z() - Vector3::x()).norm() < 1e-15);
/// // The entry below the diagonal of Rz is +sin.
/// assert_eq!(elementary(Axis::Z, 0.3).matrix()[(1, 0)], 0.3f64.sin());
/// ```
pub fn elementary(axis: Axis, angle: f64) -> Rotation3<f64> {
    match axis {
        Axis::X => rx(angle),
        Axis::Y => ry(angle),
        Axis::Z => rz(angle),
    }
}

impl Axis {
    /// The three axes, x first.
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// The unit vector of the axis in its own frame.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::orientation::Axis;
    /// assert_eq!(Axis::Y.unit(), armlab::nalgebra::Vector3::y());
    /// ```
    pub fn unit(self) -> nalgebra::Vector3<f64> {
        match self {
            Axis::X => nalgebra::Vector3::x(),
            Axis::Y => nalgebra::Vector3::y(),
            Axis::Z => nalgebra::Vector3::z(),
        }
    }
}

impl fmt::Display for Axis {
    /// "x", "y" or "z".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Axis::X => "x",
            Axis::Y => "y",
            Axis::Z => "z",
        })
    }
}

impl fmt::Display for StepFrame {
    /// "current" or "fixed".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            StepFrame::Current => "current",
            StepFrame::Fixed => "fixed",
        })
    }
}

impl Step {
    /// The step's elementary rotation, (2.6)-(2.8), without regard to its frame.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::orientation::{Axis, Step, StepFrame, elementary};
    ///
    /// let s = Step { frame: StepFrame::Fixed, axis: Axis::X, angle: 0.4 };
    /// assert_eq!(s.rotation(), elementary(Axis::X, 0.4));
    /// ```
    pub fn rotation(&self) -> Rotation3<f64> {
        elementary(self.axis, self.angle)
    }
}

impl fmt::Display for Step {
    /// `current Rz(30°)`: the frame, the axis and the angle in degrees.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} R{}({}°)",
            self.frame,
            self.axis,
            super::degrees(self.angle)
        )
    }
}
