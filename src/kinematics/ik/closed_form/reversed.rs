//! Six-revolute arms that are a named family when read from the tool back to the base: a
//! spherical wrist at the base (axes 1-3 meet in one point) and three parallel axes at 3-5 (a
//! Universal Robots arm mounted by its flange). EAIK solves these by reversing the chain; so does
//! this module.
//!
//! With `A_i(theta_i) = Rz(theta_i) M_i`, `M_i = Tz(d_i) Tx(a_i) Rx(alpha_i)` (2.52), the chain
//! `T = A_1 ... A_6` has the inverse
//!
//! `T^-1 = M_6^-1 Rz(-theta_6) M_5^-1 Rz(-theta_5) ... M_1^-1 Rz(-theta_1)`,
//!
//! a serial chain of six revolute joints whose variables are `phi_k = -theta_(7-k)`. Its DH
//! table is derived from its axes ([`crate::kinematics::dh_derive`]) and its family detected as
//! for any other robot; a target `T` is solved as the pose `T^-1` of the reversed chain. The
//! posture labels are those of the reversed chain, its wrist at the base ("base wrist flip":
//! joints 1-3) and its shoulder at the tool ("tool shoulder left": joint 6).

use super::chain::Row;
use super::posture::Posture;
use super::{ClosedForm, Family, MAX_DOF, RawSolutions};
use crate::kinematics::ik::IkError;
use crate::kinematics::pose::{Pose, rot_x, trans_x, trans_z};
use crate::kinematics::robot::{Drive, Joint, JointGeometry, JointKind, Robot, UNBOUNDED};
use nalgebra::{Unit, Vector3};

/// The solver of the reversed chain.
#[derive(Debug, Clone)]
pub(super) struct Reversed {
    /// The closed form of the chain read from the tool back to the base.
    pub inner: ClosedForm,
}

impl Reversed {
    /// The reversed chain of six revolute DH rows (base and tool already removed), if it is a
    /// spherical-wrist arm or a three-parallel-axes arm.
    pub(super) fn detect(rows: &[Row]) -> Option<Self> {
        if rows.len() != MAX_DOF || !rows.iter().all(|r| r.revolute) {
            return None;
        }
        let robot = reversed_robot(rows)?;
        let inner = ClosedForm::detect_forward(&robot)?;
        match inner.family {
            Family::Decoupled6 { .. } | Family::ThreeParallel | Family::ThreeParallelGeneral => {
                Some(Self { inner })
            }
            _ => None,
        }
    }

    /// Every solution for the pose `frame` of DH frame 6 in DH frame 0 (DH angles theta,
    /// offsets not removed), into `out`.
    pub(super) fn solve(&self, frame: &Pose, out: &mut RawSolutions) -> Result<(), IkError> {
        let mut inner = RawSolutions::default();
        let goal = self.inner.goal_of_pose(&frame.inverse());
        self.inner.core_where(&goal, &mut inner, |_| true)?;
        out.unreachable = inner.unreachable;
        out.len = inner.len;
        for k in 0..inner.len {
            let (phi, p) = (&inner.q[k], &inner.postures[k]);
            let mut posture = Posture {
                reversed: true,
                ..*p
            };
            for i in 0..MAX_DOF {
                // theta_i = -phi_(7-i), one-based.
                out.q[k][i] = -phi[MAX_DOF - 1 - i];
                posture.free[i] = p.free[MAX_DOF - 1 - i];
            }
            out.postures[k] = posture;
        }
        Ok(())
    }
}

/// `M_i = Tz(d) Tx(a) Rx(alpha)`: DH frame i in frame i-1 after the rotation by theta_i.
fn link(r: &Row) -> Pose {
    trans_z(r.d) * trans_x(r.a) * rot_x(r.sa.atan2(r.ca))
}

/// The robot whose forward kinematics at `phi` is `T(theta)^-1`, `phi_k = -theta_(7-k)`:
/// joint k turns about z after the fixed `M_(7-k)^-1` (the first after `M_6^-1`).
fn reversed_robot(rows: &[Row]) -> Option<Robot> {
    let joints = (0..rows.len())
        .map(|k| Joint {
            name: format!("r{}", k + 1),
            kind: JointKind::Revolute,
            parent: k.checked_sub(1),
            pre: Pose::identity(),
            geometry: JointGeometry::Origin {
                parent_from_joint: link(&rows[rows.len() - 1 - k]).inverse(),
                axis: Unit::new_unchecked(Vector3::z()),
            },
            offset: 0.0,
            drive: Drive::Actuated(k),
            limits: UNBOUNDED,
        })
        .collect();
    Robot::new("reversed", Pose::identity(), joints, Vec::new()).ok()
}
