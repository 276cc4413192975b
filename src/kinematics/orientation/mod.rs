//! The orientation of a rigid body, Sect. 2.2-2.5: elementary rotations (2.6)-(2.8), their
//! composition about current and fixed axes (2.14)-(2.16), the minimal representations and their
//! conversions in both directions (ZYZ Euler angles (2.18)-(2.20), ZXZ Euler angles (Problem
//! 2.1), roll-pitch-yaw (2.21)-(2.23), angle and axis (2.25)-(2.28), the unit quaternion
//! (2.30)-(2.37)), the inverse of a homogeneous transform (2.45), and infinitesimal rotations
//! (Problems 2.15, 2.16). Angles are in radians throughout.
//!
//! Two kinds of inverse conversion live side by side:
//! - the fast ones ([`zyz_from_rotation`], [`rpy_from_rotation`], [`angle_axis_from_rotation`],
//!   [`quaternion_from_rotation`], ...) return one solution, allocate nothing, and are total: at
//!   the representation singularities (Problems 2.2, 2.3, 2.5) they make a documented choice and
//!   say so in [`Orientation::singular`], never NaN;
//! - the teaching ones ([`euler_solutions`], [`angle_axis_solutions`], [`Representations::of`])
//!   return every solution and, at a singular case, the one-parameter family as data with its
//!   sentence in words ("only phi + psi is determined: 75°").

mod axis_angle;
mod compose;
mod elementary;
mod euler;
mod homogeneous;
mod infinitesimal;
mod quaternion;
mod representations;

pub use axis_angle::{
    AngleAxis, AngleAxisCase, AngleAxisSolutions, angle_axis_from_rotation, angle_axis_solutions,
    rotation_from_angle_axis,
};
pub use compose::{compose, partial_products};
pub use elementary::elementary;
pub(crate) use elementary::{rx, ry, rz};
pub use euler::{
    Combination, EulerSolutions, Family, euler_solutions, rotation_from_rpy, rotation_from_zxz,
    rotation_from_zyz, rpy_from_rotation, rpy_from_rotation_negative, zxz_from_rotation,
    zxz_from_rotation_negative, zyz_from_rotation, zyz_from_rotation_negative,
};
pub use homogeneous::inverse_homogeneous;
pub use infinitesimal::{
    SumComparison, commutator_norm, infinitesimal, infinitesimal_commutator_norm,
    infinitesimal_elementary, rotation_angle_between, sum_comparison,
};
pub use quaternion::{
    quaternion, quaternion_from_rotation, quaternion_inverse, quaternion_product,
    rotation_from_quaternion,
};
pub use representations::{Representations, degrees};

use nalgebra::{Matrix3, Rotation3, Vector3};
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
/// for kind in EulerKind::ALL {
///     let r = kind.to_rotation(&angles);
///     let back = kind.from_rotation(&r);
///     assert!((back.angles - angles).amax() < 1e-14, "{}", kind.as_str());
/// }
/// // The same three numbers are different rotations in the two representations.
/// let zyz = EulerKind::Zyz.to_rotation(&angles);
/// let rpy = EulerKind::Rpy.to_rotation(&angles);
/// assert!(zyz.angle_to(&rpy) > 0.1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EulerKind {
    /// ZYZ Euler angles `R = Rz(phi) Ry(theta) Rz(psi)`, (2.18).
    Zyz,
    /// Roll–pitch–yaw `R = Rz(phi) Ry(theta) Rx(psi)` (Siciliano's ZYX form), (2.21).
    Rpy,
    /// ZXZ Euler angles `R = Rz(phi) Rx(theta) Rz(psi)`, Problem 2.1.
    Zxz,
}

impl EulerKind {
    /// Every representation, in the order ZYZ, ZXZ, RPY.
    pub const ALL: [EulerKind; 3] = [EulerKind::Zyz, EulerKind::Zxz, EulerKind::Rpy];

    /// Lower-case name: "zyz", "zxz" or "rpy".
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// assert_eq!(EulerKind::Zxz.as_str(), "zxz");
    /// ```
    pub fn as_str(self) -> &'static str {
        match self {
            EulerKind::Zyz => "zyz",
            EulerKind::Rpy => "rpy",
            EulerKind::Zxz => "zxz",
        }
    }

    /// Rotation of the angles (phi, theta, psi) in rad: (2.18), (2.21) or Problem 2.1.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::nalgebra::Vector3;
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // ZXZ with theta = 90 degrees turns z0 onto -y0 (the x axis is the middle one).
    /// let r = EulerKind::Zxz.to_rotation(&Vector3::new(0.0, FRAC_PI_2, 0.0));
    /// assert!((r * Vector3::z() + Vector3::y()).norm() < 1e-15);
    /// ```
    pub fn to_rotation(self, a: &Vector3<f64>) -> Rotation3<f64> {
        match self {
            EulerKind::Zyz => rotation_from_zyz(a),
            EulerKind::Rpy => rotation_from_rpy(a),
            EulerKind::Zxz => rotation_from_zxz(a),
        }
    }

    /// Angles of the rotation (theta in [0, pi] for ZYZ and ZXZ, in [-pi/2, pi/2] for RPY); no
    /// allocation.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::nalgebra::Vector3;
    ///
    /// let a = Vector3::new(0.2, 0.7, -0.4);
    /// let back = EulerKind::Zxz.from_rotation(&EulerKind::Zxz.to_rotation(&a));
    /// assert!(!back.singular && (back.angles - a).amax() < 1e-15);
    /// ```
    pub fn from_rotation(self, r: &Rotation3<f64>) -> Orientation {
        match self {
            EulerKind::Zyz => zyz_from_rotation(r),
            EulerKind::Rpy => rpy_from_rotation(r),
            EulerKind::Zxz => zxz_from_rotation(r),
        }
    }

    /// The second solution (the negative square root of (2.20)): theta in [-pi, 0] for ZYZ and
    /// ZXZ, in (pi/2, 3pi/2) wrapped to (-pi, pi] for RPY; no allocation.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::nalgebra::Vector3;
    ///
    /// let r = EulerKind::Rpy.to_rotation(&Vector3::new(0.2, 0.7, -0.4));
    /// let other = EulerKind::Rpy.from_rotation_negative(&r);
    /// assert!(other.angles[1].abs() > std::f64::consts::FRAC_PI_2);
    /// let again = EulerKind::Rpy.to_rotation(&other.angles);
    /// assert!((again.matrix() - r.matrix()).amax() < 1e-15);
    /// ```
    pub fn from_rotation_negative(self, r: &Rotation3<f64>) -> Orientation {
        match self {
            EulerKind::Zyz => zyz_from_rotation_negative(r),
            EulerKind::Rpy => rpy_from_rotation_negative(r),
            EulerKind::Zxz => zxz_from_rotation_negative(r),
        }
    }
}

/// A coordinate axis of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
    /// The z axis.
    Z,
}

/// About which frame's axis an elementary rotation of a sequence turns (Sect. 2.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StepFrame {
    /// About an axis of the current (already rotated) frame: post-multiplication, (2.14).
    Current,
    /// About an axis of the fixed (reference) frame: pre-multiplication, (2.16).
    Fixed,
}

/// One elementary rotation of a composed sequence: `{"frame": "current", "axis": "z",
/// "angle": 0.52}` in JSON (angle in rad).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Step {
    /// Current (post-multiply) or fixed (pre-multiply).
    pub frame: StepFrame,
    /// The axis turned about.
    pub axis: Axis,
    /// The angle (rad).
    pub angle: f64,
}

/// The matrix `T(phi)` with `omega = T(phi) phi_dot` (Sect. 3.6): columns are the axes of the
/// three elementary rotations expressed in the base frame. Used for the analytical Jacobian.
///
/// ZYZ: `[z0, Rz(phi) y, Rz(phi) Ry(theta) z]`; ZXZ: `[z0, Rz(phi) x, Rz(phi) Rx(theta) z]`;
/// RPY: `[z0, Rz(phi) y, Rz(phi) Ry(theta) x]`.
///
/// # Examples
///
/// For ZXZ the second column is the current x axis after the first turn, and the map is
/// singular where sin(theta) = 0, as for ZYZ:
///
/// ```
/// use armlab::kinematics::EulerKind;
/// use armlab::kinematics::orientation::angular_velocity_map;
/// use armlab::nalgebra::Vector3;
///
/// let t = angular_velocity_map(EulerKind::Zxz, &Vector3::new(0.3, 0.8, -0.2));
/// assert!((t[(0, 1)] - 0.3f64.cos()).abs() < 1e-15 && (t[(1, 1)] - 0.3f64.sin()).abs() < 1e-15);
/// let flat = angular_velocity_map(EulerKind::Zxz, &Vector3::new(0.3, 0.0, -0.2));
/// assert!(flat.determinant().abs() < 1e-15);
/// ```
pub fn angular_velocity_map(kind: EulerKind, a: &Vector3<f64>) -> Matrix3<f64> {
    let (sp, cp) = a[0].sin_cos();
    let (st, ct) = a[1].sin_cos();
    match kind {
        EulerKind::Zyz => Matrix3::new(0.0, -sp, cp * st, 0.0, cp, sp * st, 1.0, 0.0, ct),
        EulerKind::Rpy => Matrix3::new(0.0, -sp, cp * ct, 0.0, cp, sp * ct, 1.0, 0.0, -st),
        // Rz(phi) x = (c_phi, s_phi, 0); Rz(phi) Rx(theta) z = (s_phi s_theta, -c_phi s_theta,
        // c_theta).
        EulerKind::Zxz => Matrix3::new(0.0, cp, sp * st, 0.0, sp, -cp * st, 1.0, 0.0, ct),
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
