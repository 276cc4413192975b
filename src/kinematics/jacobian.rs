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
    pub fn jacobian(&self, q: &[f64], ee: usize) -> Result<Matrix6xX<f64>, KinematicsError> {
        let mut frames = vec![Pose::identity(); self.joints().len()];
        let mut jac = Matrix6xX::zeros(self.dof());
        self.jacobian_into(q, ee, &mut frames, &mut jac)?;
        Ok(jac)
    }

    /// The analytical Jacobian `J_A = T_A(phi)^-1 J` (Sect. 3.6) for the orientation
    /// representation `kind`; an error where `T(phi)` is singular (ZYZ: sin(theta) = 0, RPY:
    /// cos(theta) = 0).
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
                },
                detail: format!("theta = {:.6} rad", phi[1]),
            })?;
        let mut ja = j.clone();
        let ang = inv * j.fixed_rows::<3>(3);
        ja.fixed_rows_mut::<3>(3).copy_from(&ang);
        Ok(ja)
    }

    /// The operational-space vector `x_e = [p_e; phi_e]` of (2.80)/(2.82) for end-effector `ee`.
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
