//! The self-motion of a four-link planar arm holding its hand's position and orientation phi
//! (the excerpt's intrinsic redundancy, n = 4 > m = 3): phi fixes the point where the fourth link
//! starts, `p_W = p - R(phi - phi_0) u_4` (the planar counterpart of (2.84)), so the first
//! three links are the three-link arm with a position task holding p_W. Its free parameter is
//! the orientation of the third link's frame in the plane, phi_3; for each phi_3 the two-link
//! solution of Sect. 2.12.1 gives two branches (elbow down, elbow up), and joint 4 follows as
//! `q_4 = s_4 (phi - phi_0 - (phi_3 - phi_{3,0}))`.
//!
//! Joint 4's limits are an arc of phi_3 in closed form, so the feasible intervals stay exact:
//! the three-link arm's exact intervals intersected with that arc.

use super::{BranchSolution, PlanarSelfMotion, RedundancyError, wrap};
use crate::kinematics::{DhJoint, JointKind, Pose, Robot};
use crate::workspace::exact::chain::Range;
use nalgebra::{Point3, Translation3, Vector3};

/// The self-motion of a four-link planar arm holding its hand (see the module documentation).
#[derive(Debug, Clone)]
pub struct FourLinkSelfMotion {
    /// The first three links, their tool at joint 4's axis.
    arm: Robot,
    inner: PlanarSelfMotion,
    /// Sense of joint 4 along the plane normal (+1 or -1).
    sign: f64,
    range: Range,
    /// q4 = sign (c - phi_3).
    c: f64,
    target: Pose,
}

impl FourLinkSelfMotion {
    /// The self-motion of `robot` (four revolute joints of a serial DH table in one plane) holding
    /// its end-effector at `target`: the position in the plane and the orientation phi about the
    /// plane normal are used.
    pub fn new(robot: &Robot, target: &Pose) -> Result<Self, RedundancyError> {
        let not = |why: &str| RedundancyError::NoPlanarSelfMotion {
            robot: robot.name.clone(),
            kind: "four-link",
            why: why.to_string(),
        };
        let frame = crate::workspace::planar_frame(robot, 0).ok_or_else(|| not("not planar"))?;
        let (convention, rows) = robot
            .dh_table()
            .ok_or_else(|| not("not a serial DH table"))?;
        if rows.len() != 4 || rows.iter().any(|r| r.0 != JointKind::Revolute) {
            return Err(not("it needs four revolute joints"));
        }
        let q0 = [0.0; 4];
        let t0 = robot.fk(&q0)?;
        let jac = robot.jacobian(&q0, 0)?;
        let normal = frame.world_from_base.rotation * Vector3::z();
        let c4 = jac.column(3);
        let w4 = Vector3::new(c4[3], c4[4], c4[5]);
        let o4 = t0.translation.vector + w4.cross(&Vector3::new(c4[0], c4[1], c4[2]));
        let arm = first_three(robot, convention, &rows, &o4).map_err(|e| not(&e))?;
        let plane = |p: &Vector3<f64>| frame.to_plane([p.x, p.y, p.z]);
        let angle = |t: &Pose| {
            let x = frame.world_from_base.rotation.inverse() * t.rotation * Vector3::x();
            x.y.atan2(x.x)
        };
        // Hand orientation and the point where link 4 starts (rotated u_4 taken off p).
        let theta4 = angle(target) - angle(&t0);
        let u4 = {
            let (a, b) = (plane(&t0.translation.vector), plane(&o4));
            [a[0] - b[0], a[1] - b[1]]
        };
        let (s, c) = theta4.sin_cos();
        let p = plane(&target.translation.vector);
        let pw = [
            p[0] - (c * u4[0] - s * u4[1]),
            p[1] - (s * u4[0] + c * u4[1]),
        ];
        let inner = PlanarSelfMotion::new(&arm, pw)?;
        let phi30 = angle(&arm.fk(&[0.0; 3])?);
        Ok(Self {
            sign: w4.dot(&normal).signum(),
            range: Range::of(robot.joints()[3].limits),
            c: theta4 + phi30,
            target: *target,
            inner,
            arm,
        })
    }

    /// Name of the parameter: "phi" (the third link's orientation phi_3).
    pub fn parameter(&self) -> &'static str {
        "phi"
    }

    /// Branch names (elbow down, elbow up) in branch order.
    pub fn branch_names(&self) -> [String; 2] {
        self.inner.branch_names()
    }

    /// The third link's orientation phi_3 (rad) of configuration `q` (four joints).
    pub fn phi3_of(&self, q: &[f64]) -> Option<f64> {
        self.inner.phi_of(&self.arm, q.get(..3)?)
    }

    /// Joint 4 for third-link orientation `phi3` (rad).
    fn q4(&self, phi3: f64) -> f64 {
        let q = self.sign * (self.c - phi3);
        self.range.representative(q).unwrap_or_else(|| wrap(q))
    }

    /// Both branches at third-link orientation `phi3` (rad), each FK-checked against the hand
    /// pose (position in the plane and orientation about its normal).
    pub fn solutions(&self, robot: &Robot, phi3: f64) -> Vec<BranchSolution> {
        let q4 = self.q4(phi3);
        let limits = robot.limits();
        self.inner
            .solutions(&self.arm, phi3)
            .into_iter()
            .map(|b| {
                let mut q = b.q.clone();
                q.push(q4);
                let mut s = super::checked(robot, &self.target, b.name, &q, &limits);
                s.within_limits = b.within_limits && self.range.contains(q4);
                s
            })
            .collect()
    }

    /// The feasible intervals of phi_3 (rad) of each branch, pieces of [-pi, pi], and the values
    /// where the two branches merge: the three-link arm's exact intervals cut to the arc where
    /// joint 4 is within its limits.
    pub fn feasible(&self) -> ([Vec<[f64; 2]>; 2], Vec<f64>) {
        let (pieces, merges) = self.inner.feasible();
        if self.range.full {
            return (pieces, merges);
        }
        let (lo, hi) = (self.range.lo, self.range.hi);
        let start = if self.sign > 0.0 {
            self.c - hi
        } else {
            self.c + lo
        };
        let arc = super::split_at_pi(&[[start, start + (hi - lo)]], wrap);
        (pieces.map(|p| intersect(&p, &arc)), merges)
    }

    /// The number of disjoint self-motion curves inside the limits.
    pub fn manifolds(&self, robot: &Robot) -> usize {
        let (pieces, merges) = self.feasible();
        let names = self.branch_names();
        let same = |a: usize, b: usize, phi: f64| {
            let s = self.solutions(robot, phi);
            let q = |k: usize| s.iter().find(|x| x.name == names[k]).map(|x| x.q.clone());
            matches!((q(a), q(b)), (Some(x), Some(y)) if super::same_angles(&x, &y))
        };
        super::count_manifolds(&pieces, &merges, &same)
    }
}

/// The intersection of two lists of intervals.
fn intersect(a: &[[f64; 2]], b: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = a
        .iter()
        .flat_map(|x| b.iter().map(move |y| [x[0].max(y[0]), x[1].min(y[1])]))
        .filter(|iv| iv[1] > iv[0])
        .collect();
    out.sort_by(|p, q| p[0].total_cmp(&q[0]));
    out
}

/// The first three links of a four-link DH arm as a robot whose tool is at joint 4's axis `o4`
/// (world, m).
fn first_three(
    robot: &Robot,
    convention: crate::kinematics::Convention,
    rows: &[(JointKind, crate::kinematics::DhRow, f64)],
    o4: &Vector3<f64>,
) -> Result<Robot, String> {
    let joints: Vec<DhJoint> = rows[..3]
        .iter()
        .zip(robot.joints())
        .map(|((kind, row, offset), j)| DhJoint {
            kind: *kind,
            row: *row,
            offset: *offset,
            limits: j.limits,
            name: Some(j.name.clone()),
        })
        .collect();
    let bare = Robot::from_dh(
        "first three links",
        convention,
        &joints,
        robot.base,
        Pose::identity(),
    )
    .map_err(|e| e.to_string())?;
    let tip = bare
        .fk(&[0.0; 3])
        .map_err(|e| e.to_string())?
        .inverse_transform_point(&Point3::from(*o4));
    Robot::from_dh(
        format!("{} (links 1-3)", robot.name),
        convention,
        &joints,
        robot.base,
        Pose::from_parts(
            Translation3::from(tip.coords),
            nalgebra::Rotation3::identity(),
        ),
    )
    .map_err(|e| e.to_string())
}
