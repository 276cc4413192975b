//! Euler angles ZYZ (2.18)-(2.20) and ZXZ (Problem 2.1), roll-pitch-yaw angles (2.21)-(2.23):
//! the matrix of the angles, one solution fast, and both solutions with the singular family.

use super::{EulerKind, Orientation, SINGULAR_EPS, degrees, wrap_angle};
use crate::kinematics::trig::atan2;
use nalgebra::{Matrix3, Rotation3, Vector3};
use std::fmt;

/// `R = Rz(phi) Ry(theta) Rz(psi)`, eq. (2.18), multiplied out.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, elementary, rotation_from_zyz};
/// use armlab::nalgebra::Vector3;
///
/// let r = rotation_from_zyz(&Vector3::new(0.3, 1.1, -0.7));
/// let product = elementary(Axis::Z, 0.3) * elementary(Axis::Y, 1.1) * elementary(Axis::Z, -0.7);
/// assert!((r.matrix() - product.matrix()).amax() < 1e-15);
/// ```
pub fn rotation_from_zyz(a: &Vector3<f64>) -> Rotation3<f64> {
    let (sp, cp) = a[0].sin_cos();
    let (st, ct) = a[1].sin_cos();
    let (ss, cs) = a[2].sin_cos();
    // (2.18)
    Rotation3::from_matrix_unchecked(Matrix3::new(
        cp * ct * cs - sp * ss,
        -cp * ct * ss - sp * cs,
        cp * st,
        sp * ct * cs + cp * ss,
        -sp * ct * ss + cp * cs,
        sp * st,
        -st * cs,
        st * ss,
        ct,
    ))
}

/// `R = Rz(phi) Rx(theta) Rz(psi)` (Problem 2.1), multiplied out: `r11 = c_phi c_psi - s_phi
/// c_theta s_psi`, `r13 = s_phi s_theta`, `r23 = -c_phi s_theta`, `r31 = s_theta s_psi`,
/// `r32 = s_theta c_psi`, `r33 = c_theta`.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, elementary, rotation_from_zxz};
/// use armlab::nalgebra::Vector3;
///
/// let r = rotation_from_zxz(&Vector3::new(0.3, 1.1, -0.7));
/// let product = elementary(Axis::Z, 0.3) * elementary(Axis::X, 1.1) * elementary(Axis::Z, -0.7);
/// assert!((r.matrix() - product.matrix()).amax() < 1e-15);
/// ```
pub fn rotation_from_zxz(a: &Vector3<f64>) -> Rotation3<f64> {
    let (sp, cp) = a[0].sin_cos();
    let (st, ct) = a[1].sin_cos();
    let (ss, cs) = a[2].sin_cos();
    Rotation3::from_matrix_unchecked(Matrix3::new(
        cp * cs - sp * ct * ss,
        -cp * ss - sp * ct * cs,
        sp * st,
        sp * cs + cp * ct * ss,
        -sp * ss + cp * ct * cs,
        -cp * st,
        st * ss,
        st * cs,
        ct,
    ))
}

/// `R = Rz(phi) Ry(theta) Rx(psi)`, eq. (2.21), multiplied out.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{Axis, elementary, rotation_from_rpy};
/// use armlab::nalgebra::Vector3;
///
/// let r = rotation_from_rpy(&Vector3::new(0.3, 1.1, -0.7));
/// let product = elementary(Axis::Z, 0.3) * elementary(Axis::Y, 1.1) * elementary(Axis::X, -0.7);
/// assert!((r.matrix() - product.matrix()).amax() < 1e-15);
/// ```
pub fn rotation_from_rpy(a: &Vector3<f64>) -> Rotation3<f64> {
    let (sp, cp) = a[0].sin_cos();
    let (st, ct) = a[1].sin_cos();
    let (ss, cs) = a[2].sin_cos();
    // (2.21)
    Rotation3::from_matrix_unchecked(Matrix3::new(
        cp * ct,
        cp * st * ss - sp * cs,
        cp * st * cs + sp * ss,
        sp * ct,
        sp * st * ss + cp * cs,
        sp * st * cs - cp * ss,
        -st,
        ct * ss,
        ct * cs,
    ))
}

/// ZYZ angles with theta in [0, pi], eq. (2.19).
///
/// Singular case (Problem 2.2), sin(theta) = 0: only phi + psi (theta = 0) or phi - psi
/// (theta = pi) is determined; phi = 0 is chosen and psi carries the whole rotation about z.
/// psi is always computed from the residual `(Rz(phi) Ry(theta))^T R`, so that the round trip is
/// exact to rounding even close to the singularity. No allocation.
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
    zaz_branch(r.matrix(), Middle::Y, 1.0)
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
    zaz_branch(r.matrix(), Middle::Y, -1.0)
}

/// ZXZ angles with theta in [0, pi] (Problem 2.1): `theta = atan2(sqrt(r13^2 + r23^2), r33)`,
/// `phi = atan2(r13, -r23)`, psi from the residual `(Rz(phi) Rx(theta))^T R` (for a regular
/// matrix, `atan2(r31, r32)`). Singular case sin(theta) = 0 as for ZYZ: phi = 0 is chosen. No
/// allocation.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{rotation_from_zxz, zxz_from_rotation};
/// use armlab::nalgebra::Vector3;
///
/// let angles = Vector3::new(-2.0, 0.6, 2.9);
/// let back = zxz_from_rotation(&rotation_from_zxz(&angles));
/// assert!(!back.singular && (back.angles - angles).amax() < 1e-14);
/// ```
pub fn zxz_from_rotation(r: &Rotation3<f64>) -> Orientation {
    zaz_branch(r.matrix(), Middle::X, 1.0)
}

/// ZXZ angles with theta in [-pi, 0]: the second solution `(phi + pi, -theta, psi + pi)`.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{rotation_from_zxz, zxz_from_rotation_negative};
/// use armlab::nalgebra::Vector3;
///
/// let r = rotation_from_zxz(&Vector3::new(0.3, 1.1, -0.7));
/// let neg = zxz_from_rotation_negative(&r);
/// assert!((neg.angles[1] + 1.1).abs() < 1e-15);
/// assert!((rotation_from_zxz(&neg.angles).matrix() - r.matrix()).amax() < 1e-15);
/// ```
pub fn zxz_from_rotation_negative(r: &Rotation3<f64>) -> Orientation {
    zaz_branch(r.matrix(), Middle::X, -1.0)
}

/// The middle axis of a Z-?-Z set of Euler angles.
#[derive(Clone, Copy)]
enum Middle {
    Y,
    X,
}

/// One branch (`sign` = +1: theta in [0, pi], -1: [-pi, 0]) of ZYZ or ZXZ angles, (2.19)-(2.20)
/// and Problem 2.1. psi comes from the residual `(Rz(phi) R_middle(theta))^T R = Rz(psi)`,
/// built from the atan2 arguments of phi and theta (no sin/cos calls): off the singularity they
/// are `s_theta` times the cosine and sine of phi, and since atan2 is blind to a common positive
/// factor, the residual's entries are used scaled by `s_theta` too (no division).
fn zaz_branch(m: &Matrix3<f64>, middle: Middle, sign: f64) -> Orientation {
    let (r13, r23, r33) = (m[(0, 2)], m[(1, 2)], m[(2, 2)]);
    let (r11, r21, r31) = (m[(0, 0)], m[(1, 0)], m[(2, 0)]);
    let s2 = r13 * r13 + r23 * r23;
    let s = s2.sqrt();
    let theta = atan2(sign * s, r33);
    if s < SINGULAR_EPS {
        // phi = 0: the residual is R_middle(theta)^T R.
        let h = (s2 + r33 * r33).sqrt();
        let (ct, st) = (r33 / h, sign * s / h);
        let (c_psi, s_psi) = match middle {
            Middle::Y => (ct * r11 - st * r31, r21),
            Middle::X => (r11, ct * r21 + st * r31),
        };
        return Orientation {
            angles: Vector3::new(0.0, theta, atan2(s_psi, c_psi)),
            singular: true,
        };
    }
    // (x, y) = s_theta (c_phi, s_phi): the third column is ZYZ (c_phi s_theta, s_phi s_theta,
    // c_theta), (2.18); ZXZ (s_phi s_theta, -c_phi s_theta, c_theta).
    let (x, y) = match middle {
        Middle::Y => (sign * r13, sign * r23),
        Middle::X => (-sign * r23, sign * r13),
    };
    // Rows 0 and 1 of Rz(phi)^T R times s_theta, column 0; then R_middle(theta)^T, with
    // c_theta = r33 and s_theta = sign s.
    let (row0, row1) = (x * r11 + y * r21, -y * r11 + x * r21);
    let (c_psi, s_psi) = match middle {
        Middle::Y => (r33 * row0 - sign * s2 * r31, row1),
        Middle::X => (row0, r33 * row1 + sign * s2 * r31),
    };
    Orientation {
        angles: Vector3::new(atan2(y, x), theta, atan2(s_psi, c_psi)),
        singular: false,
    }
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
/// ZYZ. No allocation.
pub fn rpy_from_rotation(r: &Rotation3<f64>) -> Orientation {
    rpy_branch(r.matrix(), 1.0)
}

/// Roll–pitch–yaw angles with theta in (pi/2, 3pi/2), wrapped to (-pi, pi]: the second
/// solution of (2.22)-(2.23) (the negative square root), `(phi + pi, pi - theta, psi + pi)`.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::orientation::{rotation_from_rpy, rpy_from_rotation_negative};
/// use armlab::nalgebra::Vector3;
/// use std::f64::consts::PI;
///
/// let r = rotation_from_rpy(&Vector3::new(0.3, 0.4, -0.7));
/// let other = rpy_from_rotation_negative(&r);
/// assert!((other.angles[1] - (PI - 0.4)).abs() < 1e-15);
/// assert!((rotation_from_rpy(&other.angles).matrix() - r.matrix()).amax() < 1e-15);
/// ```
pub fn rpy_from_rotation_negative(r: &Rotation3<f64>) -> Orientation {
    rpy_branch(r.matrix(), -1.0)
}

/// One branch of RPY angles (`sign` = +1: c_theta >= 0; -1: c_theta <= 0), (2.22)-(2.23), with
/// psi from the residual `(Rz(phi) Ry(theta))^T R = Rx(psi)`, scaled by `c_theta` as in
/// `zaz_branch`.
fn rpy_branch(m: &Matrix3<f64>, sign: f64) -> Orientation {
    let (r11, r21, r31) = (m[(0, 0)], m[(1, 0)], m[(2, 0)]);
    let (r12, r22, r32) = (m[(0, 1)], m[(1, 1)], m[(2, 1)]);
    let c2 = r11 * r11 + r21 * r21;
    let c = c2.sqrt();
    let theta = atan2(-r31, sign * c);
    if c < SINGULAR_EPS {
        // phi = 0: the residual is Ry(theta)^T R.
        let h = (c2 + r31 * r31).sqrt();
        let (ct, st) = (sign * c / h, -r31 / h);
        let s_psi = st * r12 + ct * r32;
        return Orientation {
            angles: Vector3::new(0.0, theta, atan2(s_psi, r22)),
            singular: true,
        };
    }
    // (x, y) = c_theta (c_phi, s_phi): the first column is (c_phi c_theta, s_phi c_theta,
    // -s_theta), (2.21).
    let (x, y) = (sign * r11, sign * r21);
    // Rows 1 and 2 of Ry(theta)^T Rz(phi)^T R times c_theta, column 1, with s_theta = -r31 and
    // c_theta = sign c.
    let c_psi = -y * r12 + x * r22;
    let s_psi = -r31 * (x * r12 + y * r22) + sign * c2 * r32;
    Orientation {
        angles: Vector3::new(atan2(y, x), theta, atan2(s_psi, c_psi)),
        singular: false,
    }
}

/// The combination of the first and last angles that a singular rotation determines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Combination {
    /// `phi + psi`: ZYZ and ZXZ at theta = 0, RPY at theta = -pi/2.
    PhiPlusPsi,
    /// `phi - psi`: ZYZ and ZXZ at theta = pi, RPY at theta = +pi/2.
    PhiMinusPsi,
}

impl Combination {
    /// The name used in JSON: "phi+psi" or "phi-psi".
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::orientation::Combination;
    /// assert_eq!(Combination::PhiMinusPsi.as_str(), "phi-psi");
    /// ```
    pub fn as_str(self) -> &'static str {
        match self {
            Combination::PhiPlusPsi => "phi+psi",
            Combination::PhiMinusPsi => "phi-psi",
        }
    }

    /// The value of the combination for the angles `(phi, theta, psi)` (rad), wrapped to
    /// (-pi, pi].
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::orientation::Combination;
    /// use armlab::nalgebra::Vector3;
    ///
    /// let a = Vector3::new(0.5, 0.0, 0.25);
    /// assert_eq!(Combination::PhiPlusPsi.of(&a), 0.75);
    /// assert_eq!(Combination::PhiMinusPsi.of(&a), 0.25);
    /// ```
    pub fn of(self, angles: &Vector3<f64>) -> f64 {
        match self {
            Combination::PhiPlusPsi => wrap_angle(angles[0] + angles[2]),
            Combination::PhiMinusPsi => wrap_angle(angles[0] - angles[2]),
        }
    }
}

impl fmt::Display for Combination {
    /// "phi + psi" or "phi - psi".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Combination::PhiPlusPsi => "phi + psi",
            Combination::PhiMinusPsi => "phi - psi",
        })
    }
}

/// The one-parameter family of a singular rotation: every `(phi, theta, psi)` with the singular
/// theta and `combination = value` (mod 2 pi) gives the same matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Family {
    /// Which combination is determined.
    pub combination: Combination,
    /// Its value (rad), in (-pi, pi].
    pub value: f64,
}

impl fmt::Display for Family {
    /// "only phi + psi is determined: 75°".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "only {} is determined: {}°",
            self.combination,
            degrees(self.value)
        )
    }
}

/// Every set of angles of a rotation in one representation: two solutions where the
/// representation is regular, one representative (phi = 0) and the family where it is singular.
#[derive(Debug, Clone, PartialEq)]
pub struct EulerSolutions {
    /// The representation.
    pub kind: EulerKind,
    /// The solutions `(phi, theta, psi)` (rad): the first with theta in [0, pi] (ZYZ, ZXZ) or
    /// [-pi/2, pi/2] (RPY), the second with theta in [-pi, 0] or (pi/2, 3pi/2) wrapped; one
    /// representative with phi = 0 in the singular case.
    pub solutions: Vec<Vector3<f64>>,
    /// Where sin(theta) = 0 (ZYZ, ZXZ) or cos(theta) = 0 (RPY) to within [`SINGULAR_EPS`]: the
    /// combination of phi and psi that is determined; `None` where the rotation is regular.
    pub family: Option<Family>,
}

impl EulerSolutions {
    /// True at the representation's singularity (Problems 2.2, 2.3).
    ///
    /// # Examples
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::kinematics::orientation::euler_solutions;
    /// use armlab::nalgebra::Rotation3;
    ///
    /// assert!(euler_solutions(EulerKind::Zyz, &Rotation3::identity()).singular());
    /// assert!(!euler_solutions(EulerKind::Rpy, &Rotation3::identity()).singular());
    /// ```
    pub fn singular(&self) -> bool {
        self.family.is_some()
    }
}

impl fmt::Display for EulerSolutions {
    /// `(phi, theta, psi) = (30°, 45°, 60°) or (-150°, -45°, -120°)`, or in the singular case
    /// `singular (theta = 0°): only phi + psi is determined: 90°; with phi = 0: (0°, 0°, 90°)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let triple = |a: &Vector3<f64>| {
            format!(
                "({}°, {}°, {}°)",
                degrees(a[0]),
                degrees(a[1]),
                degrees(a[2])
            )
        };
        let all: Vec<String> = self.solutions.iter().map(triple).collect();
        match (&self.family, self.solutions.first()) {
            (Some(family), Some(first)) => write!(
                f,
                "singular (theta = {}°): {family}; with phi = 0: {}",
                degrees(first[1]),
                all.join(" or ")
            ),
            _ => write!(f, "(phi, theta, psi) = {}", all.join(" or ")),
        }
    }
}

/// Both inverse solutions of a rotation in one representation (2.19)-(2.20), (2.22)-(2.23),
/// Problem 2.1; in the singular case (Problems 2.2, 2.3) one representative with phi = 0 and the
/// family: ZYZ and ZXZ determine phi + psi at theta = 0 and phi - psi at theta = pi; RPY, from
/// (2.21) multiplied out, depends on phi - psi at theta = pi/2 (`r12 = -sin(phi - psi)`,
/// `r22 = cos(phi - psi)`) and on phi + psi at theta = -pi/2 (`r22 = cos(phi + psi)`,
/// `r23 = -sin(phi + psi)`). Allocates (one `Vec`); the batch path is
/// [`EulerKind::from_rotation`].
///
/// # Examples
///
/// ```
/// use armlab::kinematics::EulerKind;
/// use armlab::kinematics::orientation::{Combination, euler_solutions};
/// use armlab::nalgebra::Vector3;
///
/// let deg = |d: f64| d.to_radians();
/// let r = EulerKind::Zyz.to_rotation(&Vector3::new(deg(30.0), deg(0.0), deg(45.0)));
/// let s = euler_solutions(EulerKind::Zyz, &r);
/// let family = s.family.expect("theta = 0 is singular");
/// assert_eq!(family.combination, Combination::PhiPlusPsi);
/// assert!((family.value - deg(75.0)).abs() < 1e-15);
/// assert_eq!(family.to_string(), "only phi + psi is determined: 75°");
///
/// let r = EulerKind::Zyz.to_rotation(&Vector3::new(deg(30.0), deg(45.0), deg(60.0)));
/// let s = euler_solutions(EulerKind::Zyz, &r);
/// assert_eq!(s.solutions.len(), 2);
/// assert!(s.solutions.iter().all(|a| (EulerKind::Zyz.to_rotation(a).matrix() - r.matrix()).amax() < 1e-15));
/// ```
pub fn euler_solutions(kind: EulerKind, r: &Rotation3<f64>) -> EulerSolutions {
    let first = kind.from_rotation(r);
    if !first.singular {
        let second = kind.from_rotation_negative(r);
        return EulerSolutions {
            kind,
            solutions: vec![first.angles, second.angles],
            family: None,
        };
    }
    let a = first.angles;
    let combination = match kind {
        EulerKind::Zyz | EulerKind::Zxz if a[1].cos() > 0.0 => Combination::PhiPlusPsi,
        EulerKind::Zyz | EulerKind::Zxz => Combination::PhiMinusPsi,
        EulerKind::Rpy if a[1] > 0.0 => Combination::PhiMinusPsi,
        EulerKind::Rpy => Combination::PhiPlusPsi,
    };
    EulerSolutions {
        kind,
        solutions: vec![a],
        family: Some(Family {
            combination,
            value: combination.of(&a),
        }),
    }
}
