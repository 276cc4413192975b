//! Geometric and analytical Jacobians, and what their singular values say (rank,
//! manipulability). The geometric Jacobian maps q_dot to the end-effector twist
//! `[p_dot; omega]` in the world frame; the analytical one maps q_dot to `x_dot = [p_dot; phi_dot]`.

use super::error::KinematicsError;
use super::orientation::{EulerKind, angular_velocity_map};
use super::pose::Pose;
use super::robot::{Drive, JointKind, Motion, Robot};
use nalgebra::{DVector, Matrix6xX, Vector3, Vector6};

/// Relative tolerance on singular values for the numerical rank.
pub const RANK_TOLERANCE: f64 = 1e-9;

/// Singular-value analysis of a Jacobian.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct JacobianAnalysis {
    /// Singular values, descending.
    pub singular_values: DVector<f64>,
    /// Number of singular values above `RANK_TOLERANCE * max(1, largest)`.
    pub rank: usize,
    /// Yoshikawa's manipulability `sqrt(det(J J^T))` = product of the singular values of the
    /// rows considered (0 at a singularity).
    pub manipulability: f64,
}

impl JacobianAnalysis {
    /// Smallest singular value (the distance to a singularity, in the Jacobian's units).
    pub fn min_singular_value(&self) -> f64 {
        self.singular_values
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }
}

/// SVD of any Jacobian (rows = task components).
///
/// # Examples
///
/// The positional rows x, y of the two-link planar arm's Jacobian: its manipulability
/// `sqrt(det(J J^T)) = |det J|` is `a1 a2 |s2|`, zero with the arm stretched out (q2 = 0).
///
/// ```
/// use armlab::kinematics::jacobian::analyze;
/// use armlab::kinematics::models::built_in;
/// use armlab::nalgebra::DMatrix;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar2").expect("a built-in model"); // a1 = a2 = 1 m
/// for q2 in [0.0, 0.5, 1.2] {
///     let j = arm.jacobian(&[0.3, q2], 0)?;
///     let xy = DMatrix::from_fn(2, 2, |r, c| j[(r, c)]);
///     let a = analyze(&xy);
///     assert!((a.manipulability - q2.sin().abs()).abs() < 1e-12);
///     assert_eq!(a.rank, if q2 == 0.0 { 1 } else { 2 });
/// }
/// # Ok(())
/// # }
/// ```
pub fn analyze(j: &nalgebra::DMatrix<f64>) -> JacobianAnalysis {
    let mut sv = j.clone().svd(false, false).singular_values;
    sv.as_mut_slice().sort_by(|a, b| b.total_cmp(a));
    let tol = RANK_TOLERANCE * sv.iter().copied().fold(1.0, f64::max);
    let rank = sv.iter().filter(|&&s| s > tol).count();
    let k = j.nrows().min(j.ncols());
    let manipulability = if k < j.nrows() {
        0.0
    } else {
        sv.iter().take(k).product()
    };
    JacobianAnalysis {
        singular_values: sv,
        rank,
        manipulability,
    }
}

impl Robot {
    /// The geometric Jacobian (6 x dof) of end-effector `ee` into `jac`, using `frames` (length
    /// `joints().len()`) as scratch; returns `world_from_tool`. Allocation-free.
    ///
    /// Column for a revolute joint: `[z x (p_e - p); z]`, prismatic: `[z; 0]` (Sect. 3.1.3), with
    /// z and p the joint axis and its origin in the world frame. A coupled joint adds its column,
    /// times its factor, to the columns of the joints it follows (chain rule).
    pub fn jacobian_into(
        &self,
        q: &[f64],
        ee: usize,
        frames: &mut [Pose],
        jac: &mut Matrix6xX<f64>,
    ) -> Result<Pose, KinematicsError> {
        self.fk_frames_into(q, frames)?;
        let e = self.end_effector(ee)?;
        let world_from_tool = frames[e.parent] * e.tool;
        let pe = world_from_tool.translation.vector;
        assert_eq!(
            jac.ncols(),
            self.dof(),
            "Jacobian buffer has the wrong number of columns"
        );
        jac.fill(0.0);
        for &j in self.chain_to(e.parent) {
            let joint = &self.joints()[j];
            if joint.kind == JointKind::Fixed {
                continue;
            }
            let l = &self.lowered[j];
            let parent = l.parent.map_or(self.base, |p| frames[p]);
            let axis_frame = parent * l.pre;
            let local_axis = match l.motion {
                Motion::RotZ | Motion::TransZ => Vector3::z(),
                Motion::Rot(a) | Motion::Trans(a) => a.into_inner(),
                Motion::Fixed => continue,
            };
            let z = axis_frame.rotation * local_axis;
            let col: Vector6<f64> = match joint.kind {
                JointKind::Revolute => {
                    let p = axis_frame.translation.vector;
                    let v = z.cross(&(pe - p));
                    Vector6::new(v.x, v.y, v.z, z.x, z.y, z.z)
                }
                _ => Vector6::new(z.x, z.y, z.z, 0.0, 0.0, 0.0),
            };
            match &joint.drive {
                Drive::Actuated(k) => {
                    let mut c = jac.column_mut(*k);
                    c += col;
                }
                Drive::Coupled(terms) => {
                    for &(src, coef) in terms {
                        if let Drive::Actuated(k) = self.joints()[src].drive {
                            let mut c = jac.column_mut(k);
                            c += col * coef;
                        }
                    }
                }
                Drive::Closure(cl) => {
                    // Chain rule through the loop: d(value)/d(crank, arm) in closed form.
                    let m = &cl.mechanism;
                    let (tc, ta) = (self.joint_angle(m.crank, q), self.joint_angle(m.arm, q));
                    let (_, grad) = cl.value(tc, ta);
                    for (src, g) in [(m.crank, grad[0]), (m.arm, grad[1])] {
                        if let Drive::Actuated(k) = self.joints()[src].drive {
                            let mut c = jac.column_mut(k);
                            c += col * g;
                        }
                    }
                }
                Drive::None => {}
            }
        }
        Ok(world_from_tool)
    }

    /// The geometric Jacobian (6 x dof) of end-effector `ee` in the world frame.
    ///
    /// # Examples
    ///
    /// The two-link planar arm's Jacobian written out (Sect. 3.1.3): linear rows
    /// `[-a1 s1 - a2 s12, -a2 s12; a1 c1 + a2 c12, a2 c12; 0, 0]`, angular rows `[0, 0; 0, 0; 1, 1]`.
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar2").expect("a built-in model");
    /// let (a1, a2) = (1.0, 1.0);
    /// let q = [0.4, 0.9];
    /// let j = arm.jacobian(&q, 0)?;
    /// let (s1, c1) = q[0].sin_cos();
    /// let (s12, c12) = (q[0] + q[1]).sin_cos();
    /// let expected = [
    ///     [-a1 * s1 - a2 * s12, -a2 * s12],
    ///     [a1 * c1 + a2 * c12, a2 * c12],
    ///     [0.0, 0.0],
    ///     [0.0, 0.0],
    ///     [0.0, 0.0],
    ///     [1.0, 1.0],
    /// ];
    /// for (r, row) in expected.iter().enumerate() {
    ///     for (c, v) in row.iter().enumerate() {
    ///         assert!((j[(r, c)] - v).abs() < 1e-15, "J[{r}][{c}]");
    ///     }
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn jacobian(&self, q: &[f64], ee: usize) -> Result<Matrix6xX<f64>, KinematicsError> {
        let mut frames = vec![Pose::identity(); self.joints().len()];
        let mut jac = Matrix6xX::zeros(self.dof());
        self.jacobian_into(q, ee, &mut frames, &mut jac)?;
        Ok(jac)
    }

    /// The analytical Jacobian `J_A = T_A(phi)^-1 J` (Sect. 3.6) for the orientation
    /// representation `kind`; an error where `T(phi)` is singular (ZYZ and ZXZ: sin(theta) = 0,
    /// RPY: cos(theta) = 0).
    ///
    /// # Examples
    ///
    /// A planar arm turns its tool about z only: in roll-pitch-yaw angles the first angle's
    /// rate is `q1_dot + q2_dot`, while ZYZ angles are singular at every configuration
    /// (theta = 0).
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    /// use armlab::kinematics::{EulerKind, KinematicsError};
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar2").expect("a built-in model");
    /// let q = [0.4, 0.9];
    /// let ja = arm.analytical_jacobian(&q, 0, EulerKind::Rpy)?;
    /// assert!((ja[(3, 0)] - 1.0).abs() < 1e-15 && (ja[(3, 1)] - 1.0).abs() < 1e-15);
    /// assert!(ja[(4, 0)].abs() < 1e-15 && ja[(5, 1)].abs() < 1e-15);
    /// let zyz = arm.analytical_jacobian(&q, 0, EulerKind::Zyz);
    /// assert!(matches!(zyz, Err(KinematicsError::RepresentationSingular { .. })));
    /// # Ok(())
    /// # }
    /// ```
    pub fn analytical_jacobian(
        &self,
        q: &[f64],
        ee: usize,
        kind: EulerKind,
    ) -> Result<Matrix6xX<f64>, KinematicsError> {
        let j = self.jacobian(q, ee)?;
        let t = self.fk_ee(q, ee)?;
        let phi = kind.from_rotation(&t.rotation).angles;
        let tm = angular_velocity_map(kind, &phi);
        let inv = tm
            .try_inverse()
            .filter(|_| !kind.from_rotation(&t.rotation).singular)
            .ok_or_else(|| KinematicsError::RepresentationSingular {
                representation: match kind {
                    EulerKind::Zyz => "ZYZ Euler",
                    EulerKind::Rpy => "roll-pitch-yaw",
                    EulerKind::Zxz => "ZXZ Euler",
                },
                detail: format!("theta = {:.6} rad", phi[1]),
            })?;
        let mut ja = j.clone();
        let ang = inv * j.fixed_rows::<3>(3);
        ja.fixed_rows_mut::<3>(3).copy_from(&ang);
        Ok(ja)
    }

    /// The operational-space vector `x_e = [p_e; phi_e]` of (2.80)/(2.82) for end-effector `ee`.
    ///
    /// # Examples
    ///
    /// For the three-link planar arm the first roll-pitch-yaw angle is the orientation
    /// `phi = q1 + q2 + q3` of (2.83):
    ///
    /// ```
    /// use armlab::kinematics::EulerKind;
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let arm = built_in("planar3").expect("a built-in model");
    /// let q = [0.2, 0.5, -0.3];
    /// let x = arm.operational(&q, 0, EulerKind::Rpy)?;
    /// let p = arm.fk(&q)?.translation.vector;
    /// assert!((x[0] - p.x).abs() < 1e-15 && (x[1] - p.y).abs() < 1e-15);
    /// assert!((x[3] - (q[0] + q[1] + q[2])).abs() < 1e-15);
    /// # Ok(())
    /// # }
    /// ```
    pub fn operational(
        &self,
        q: &[f64],
        ee: usize,
        kind: EulerKind,
    ) -> Result<Vector6<f64>, KinematicsError> {
        let t = self.fk_ee(q, ee)?;
        let p = t.translation.vector;
        let phi = kind.from_rotation(&t.rotation).angles;
        Ok(Vector6::new(p.x, p.y, p.z, phi.x, phi.y, phi.z))
    }

    /// Rank, singular values and manipulability of the geometric Jacobian.
    ///
    /// # Examples
    ///
    /// The Puma 560 has full rank at a generic configuration and loses one at the wrist
    /// singularity q5 = 0 (axes 4 and 6 aligned, Sect. 3.3):
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let puma = built_in("puma560").expect("a built-in model");
    /// let generic = puma.analyze_jacobian(&[0.1, -0.6, 0.4, 0.3, 0.8, -0.2], 0)?;
    /// assert_eq!(generic.rank, 6);
    /// assert!(generic.manipulability > 1e-4);
    /// let wrist = puma.analyze_jacobian(&[0.1, -0.6, 0.4, 0.3, 0.0, -0.2], 0)?;
    /// assert_eq!(wrist.rank, 5);
    /// assert!(wrist.manipulability < 1e-12 && wrist.min_singular_value() < 1e-12);
    /// # Ok(())
    /// # }
    /// ```
    pub fn analyze_jacobian(
        &self,
        q: &[f64],
        ee: usize,
    ) -> Result<JacobianAnalysis, KinematicsError> {
        let j = self.jacobian(q, ee)?;
        Ok(analyze(&nalgebra::DMatrix::from_column_slice(
            6,
            j.ncols(),
            j.as_slice(),
        )))
    }
}
