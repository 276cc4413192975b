//! Every representation of one rotation at once, for the command line and the app.

use super::{
    AngleAxisSolutions, EulerKind, EulerSolutions, angle_axis_solutions, euler_solutions,
    quaternion_from_rotation,
};
use nalgebra::{Rotation3, UnitQuaternion};

/// One rotation in every representation of Sect. 2.4, with both Euler solutions and the
/// singular cases as data.
#[derive(Debug, Clone, PartialEq)]
pub struct Representations {
    /// The rotation matrix.
    pub matrix: Rotation3<f64>,
    /// ZYZ Euler angles (2.18)-(2.20).
    pub zyz: EulerSolutions,
    /// ZXZ Euler angles (Problem 2.1).
    pub zxz: EulerSolutions,
    /// Roll-pitch-yaw angles (2.21)-(2.23).
    pub rpy: EulerSolutions,
    /// Angle and axis (2.27)-(2.28), with the cases of Problem 2.5.
    pub axis_angle: AngleAxisSolutions,
    /// The unit quaternion (2.34)-(2.35), eta >= 0.
    pub quaternion: UnitQuaternion<f64>,
}

impl Representations {
    /// Every representation of `r`.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::kinematics::orientation::Representations;
    /// use armlab::nalgebra::Vector3;
    ///
    /// let r = EulerKind::Zyz.to_rotation(&Vector3::new(0.5, 0.8, 1.0));
    /// let all = Representations::of(&r);
    /// assert_eq!(all.zyz.solutions.len(), 2);
    /// assert!((all.zyz.solutions[0] - Vector3::new(0.5, 0.8, 1.0)).amax() < 1e-15);
    /// assert!(all.quaternion.w >= 0.0);
    /// let back = EulerKind::Rpy.to_rotation(&all.rpy.solutions[1]);
    /// assert!((back.matrix() - r.matrix()).amax() < 1e-15);
    /// ```
    pub fn of(r: &Rotation3<f64>) -> Self {
        Representations {
            matrix: *r,
            zyz: euler_solutions(EulerKind::Zyz, r),
            zxz: euler_solutions(EulerKind::Zxz, r),
            rpy: euler_solutions(EulerKind::Rpy, r),
            axis_angle: angle_axis_solutions(r),
            quaternion: quaternion_from_rotation(r),
        }
    }

    /// The Euler solutions of one kind.
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::kinematics::orientation::Representations;
    /// use armlab::nalgebra::Rotation3;
    ///
    /// let all = Representations::of(&Rotation3::identity());
    /// assert_eq!(all.euler(EulerKind::Zxz).kind, EulerKind::Zxz);
    /// ```
    pub fn euler(&self, kind: EulerKind) -> &EulerSolutions {
        match kind {
            EulerKind::Zyz => &self.zyz,
            EulerKind::Zxz => &self.zxz,
            EulerKind::Rpy => &self.rpy,
        }
    }
}

/// An angle given in rad written in degrees for people: at most four decimals, trailing zeros
/// dropped, no "-0" (`75`, `35.2644`, `-120`). The unit sign is the caller's.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::degrees;
///
/// assert_eq!(degrees(75f64.to_radians()), "75");
/// assert_eq!(degrees(-1e-17), "0");
/// assert_eq!(degrees(0.5), "28.6479");
/// ```
pub fn degrees(rad: f64) -> String {
    let text = format!("{:.4}", rad.to_degrees());
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    if text == "-0" { "0".to_string() } else { text }
}
