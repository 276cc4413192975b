//! One entry point for the exact self-motions: the structure of a robot picks the solver (SRS
//! arm angle, the offset-elbow arm's q7, the three-link planar arm's phi, the four-link planar
//! arm's phi_3), and the result is named, sampled and located the same way for each, so that the
//! CLI and the app's slider do not care which it is.

use super::four_link::FourLinkSelfMotion;
use super::locked::LockedSelfMotion;
use super::offset_elbow::OffsetElbowArm;
use super::srs::SrsArm;
use super::{BranchSolution, PlanarSelfMotion, RedundancyError};
use crate::kinematics::{Pose, Robot};
use nalgebra::Vector3;
use std::f64::consts::{PI, TAU};

/// The solver behind an [`ExactSelfMotion`].
#[derive(Debug, Clone)]
enum Solver {
    Srs(SrsArm),
    OffsetElbow(OffsetElbowArm),
    Planar(PlanarSelfMotion),
    FourLink(Box<FourLinkSelfMotion>),
    Locked(Box<LockedSelfMotion>),
}

/// The exact self-motion of a redundant arm holding its hand at one pose.
///
/// # Examples
///
/// The KUKA LWR-IV is an SRS arm: its self-motion is parameterised by the arm angle, the
/// elbow's rotation about the shoulder-wrist line. Every branch at every arm angle holds the
/// hand where it was:
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::redundancy::motion::ExactSelfMotion;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let lwr = built_in("lwr4").expect("a built-in model");
/// let q0 = [0.2, 0.6, -0.3, -1.4, 0.2, 0.7, 0.1];
/// let pose = lwr.fk(&q0)?;
/// let motion = ExactSelfMotion::new(&lwr, &pose)?;
/// assert_eq!(motion.parameter(), "arm angle");
/// assert_eq!(motion.names().len(), 8); // shoulder, elbow, wrist: two each
/// for psi in [-2.0, -0.5, 0.0, 1.0] {
///     for s in motion.solutions(&lwr, psi) {
///         assert!(s.position_error < 1e-9 && s.orientation_error < 1e-9, "{}", s.name);
///     }
/// }
/// // q0 lies on one branch, at its own arm angle.
/// let (branch, psi0) = motion.locate(&lwr, &q0).expect("on the self-motion");
/// let again = motion.solutions(&lwr, psi0);
/// let s = again.iter().find(|s| s.name == motion.names()[branch]).expect("the branch");
/// assert!(s.q.iter().zip(&q0).all(|(a, b)| (a - b).abs() < 1e-9));
/// println!("{} curves inside the limits", motion.manifolds());
/// # Ok(())
/// # }
/// ```
///
/// An arm that is not redundant has no self-motion:
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::redundancy::RedundancyError;
/// use armlab::redundancy::motion::ExactSelfMotion;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let pose = puma.fk(&[0.1, -0.5, 0.3, 0.0, 0.8, 0.0])?;
/// let err = ExactSelfMotion::new(&puma, &pose).unwrap_err();
/// assert!(matches!(err, RedundancyError::NoExactSelfMotion { .. }));
/// println!("{err}");
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone)]
pub struct ExactSelfMotion {
    solver: Solver,
    target: Pose,
    names: Vec<String>,
    feasible: Vec<Vec<[f64; 2]>>,
    manifolds: usize,
    singular: bool,
}

impl ExactSelfMotion {
    /// The exact self-motion of `robot` holding its (only) end-effector at `target`: SRS 7R
    /// arms by the arm angle, offset-elbow 7R arms (the Panda) by q7, three-link planar arms
    /// with a position task by phi, four-link planar arms with a position-and-phi task by phi_3.
    /// Any other seven-revolute arm locks one joint ([`LockedSelfMotion`]). Other arms are
    /// [`RedundancyError::NoExactSelfMotion`] (they have the numerical self-motion).
    pub fn new(robot: &Robot, target: &Pose) -> Result<Self, RedundancyError> {
        Self::with_lock(robot, target, None)
    }

    /// [`Self::new`], or with `locked = Some(k)` the self-motion of a seven-revolute arm with
    /// joint k (0-based) locked as the parameter, whatever its structure (an SRS arm too).
    ///
    /// # Examples
    ///
    /// The Franka Emika Panda's self-motion with q3 as the parameter instead of q7:
    ///
    /// ```
    /// use armlab::kinematics::models::built_in;
    /// use armlab::redundancy::motion::ExactSelfMotion;
    ///
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// let panda = built_in("panda").expect("a built-in model");
    /// let q0 = [0.3, -0.4, 0.2, -2.0, 0.1, 1.6, 0.5];
    /// let pose = panda.fk(&q0)?;
    /// let motion = ExactSelfMotion::with_lock(&panda, &pose, Some(2))?;
    /// assert_eq!(motion.locked_joint(), Some(2));
    /// assert_eq!(motion.parameter(), "q3 (locked)");
    /// let solutions = motion.solutions(&panda, q0[2]);
    /// assert!(solutions.iter().any(|s| s.q.iter().zip(&q0).all(|(a, b)| (a - b).abs() < 1e-8)));
    /// for s in &solutions {
    ///     assert!((s.q[2] - q0[2]).abs() < 1e-12);
    ///     assert!(s.position_error < 1e-9 && s.orientation_error < 1e-9);
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn with_lock(
        robot: &Robot,
        target: &Pose,
        locked: Option<usize>,
    ) -> Result<Self, RedundancyError> {
        if locked.is_some() {
            return Ok(Self::locked(
                LockedSelfMotion::new(robot, target, locked)?,
                target,
            ));
        }
        let (solver, names, feasible, manifolds, singular) =
            if let Some(arm) = SrsArm::detect(robot) {
                if arm.solve(target, 0.0).is_empty() && !arm.singular(target) {
                    return Err(RedundancyError::WristOutOfReach);
                }
                let f = arm.feasible_intervals(target).to_vec();
                let (m, s) = (arm.manifolds(target), arm.singular(target));
                (Solver::Srs(arm), SrsArm::branch_names().to_vec(), f, m, s)
            } else if let Some(arm) = OffsetElbowArm::detect(robot) {
                let (f, m) = arm.feasible_and_manifolds(target);
                let f = f.to_vec();
                let reach = (0..64).any(|k| {
                    let t = -PI + TAU * k as f64 / 64.0;
                    arm.solve_raw(target, t, &mut [[0.0; 7]; 8]) & 0xff != 0
                });
                if !reach && f.iter().all(Vec::is_empty) {
                    return Err(RedundancyError::OutOfReachForEveryQ7);
                }
                let names = OffsetElbowArm::branch_names().to_vec();
                (Solver::OffsetElbow(arm), names, f, m, false)
            } else if robot.dof() == 4 {
                let m = FourLinkSelfMotion::new(robot, target)?;
                let (f, _) = m.feasible();
                let k = m.manifolds(robot);
                (
                    Solver::FourLink(Box::new(m.clone())),
                    m.branch_names().to_vec(),
                    f.to_vec(),
                    k,
                    false,
                )
            } else if robot.dof() == 7 && LockedSelfMotion::pick(robot).is_some() {
                return Ok(Self::locked(
                    LockedSelfMotion::new(robot, target, None)?,
                    target,
                ));
            } else {
                let frame = crate::workspace::planar_frame(robot, 0).ok_or_else(|| {
                    RedundancyError::NoExactSelfMotion {
                        robot: robot.name.clone(),
                    }
                })?;
                let p = target.translation.vector;
                let m = PlanarSelfMotion::new(robot, frame.to_plane([p.x, p.y, p.z]))?;
                let (f, _) = m.feasible();
                let k = m.manifolds(robot);
                (
                    Solver::Planar(m.clone()),
                    m.branch_names().to_vec(),
                    f.to_vec(),
                    k,
                    false,
                )
            };
        Ok(Self {
            solver,
            target: *target,
            names,
            feasible,
            manifolds,
            singular,
        })
    }

    fn locked(m: LockedSelfMotion, target: &Pose) -> Self {
        Self {
            names: m.names().to_vec(),
            feasible: m.feasible().to_vec(),
            manifolds: m.manifolds(),
            singular: false,
            solver: Solver::Locked(Box::new(m)),
            target: *target,
        }
    }

    /// Whether it was computed by sweeping a locked joint over its whole turn through a general
    /// six-joint elimination (tens to hundreds of milliseconds, where the SRS and offset-elbow
    /// arms' closed forms take well under one): a live view recomputes it only after a drag.
    pub fn is_swept(&self) -> bool {
        matches!(self.solver, Solver::Locked(_))
    }

    /// The parameter's name: "arm angle", "q7", "phi", or for a locked joint e.g. "q3
    /// (locked)".
    pub fn parameter(&self) -> &'static str {
        match &self.solver {
            Solver::Srs(_) => "arm angle",
            Solver::OffsetElbow(_) => "q7",
            Solver::Planar(_) | Solver::FourLink(_) => "phi",
            Solver::Locked(m) => m.parameter(),
        }
    }

    /// The locked joint (0-based) of a seven-joint arm's self-motion by locking.
    pub fn locked_joint(&self) -> Option<usize> {
        match &self.solver {
            Solver::Locked(m) => Some(m.locked()),
            _ => None,
        }
    }

    /// The parameter in words (what it measures; for a locked joint, which and why).
    pub fn parameter_meaning(&self) -> String {
        let text = match &self.solver {
            Solver::Locked(m) => return m.why().to_string(),
            Solver::Srs(_) => {
                "arm angle psi: the elbow's rotation about the shoulder-wrist axis from the plane \
                 it spans with joint 3 at zero"
            }
            Solver::OffsetElbow(_) => "q7: the last joint's angle, every other joint solved for it",
            Solver::Planar(_) => "phi: the end-effector's orientation in the plane (2.83)",
            Solver::FourLink(_) => {
                "phi_3: the third link's orientation in the plane (the hand's own phi is held)"
            }
        };
        text.to_string()
    }

    /// The hand pose held (world, m).
    pub fn target(&self) -> &Pose {
        &self.target
    }

    /// Branch names in branch order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Feasible intervals of the parameter (rad) of each branch inside the joint limits, pieces
    /// of [-pi, pi], in branch order.
    pub fn feasible(&self) -> &[Vec<[f64; 2]>] {
        &self.feasible
    }

    /// The number of disjoint self-motion curves inside the limits.
    pub fn manifolds(&self) -> usize {
        self.manifolds
    }

    /// At the algorithmic singularity of the arm angle (the shoulder-wrist line along axis 1).
    pub fn singular(&self) -> bool {
        self.singular
    }

    /// Every branch at parameter `value` (rad), FK-checked against the target.
    pub fn solutions(&self, robot: &Robot, value: f64) -> Vec<BranchSolution> {
        match &self.solver {
            Solver::Srs(a) => a.branch_solutions(robot, &self.target, value),
            Solver::OffsetElbow(a) => a.branch_solutions(robot, &self.target, value),
            Solver::Planar(m) => m.solutions(robot, value),
            Solver::FourLink(m) => m.solutions(robot, value),
            Solver::Locked(m) => m.solutions(robot, value),
        }
    }

    /// The parameter (rad, in [-pi, pi)) of configuration `q` and the index of its branch, when
    /// `q` holds the target (to 1e-6 in joint space).
    pub fn locate(&self, robot: &Robot, q: &[f64]) -> Option<(usize, f64)> {
        let value = match &self.solver {
            Solver::Srs(a) => a.arm_angle(q)?,
            Solver::OffsetElbow(_) => q[6],
            Solver::Planar(m) => m.phi_of(robot, q)?,
            Solver::FourLink(m) => m.phi3_of(q)?,
            Solver::Locked(m) => q[m.locked()],
        };
        let value = super::wrap(value);
        let sols = self.solutions(robot, value);
        let k = sols
            .iter()
            .filter(|s| super::same_angles(&s.q, q))
            .find_map(|s| self.names.iter().position(|n| *n == s.name))?;
        Some((k, value))
    }

    /// The point the app traces while the parameter moves (world, m): the elbow of a 7R arm (the
    /// point of axis 4 nearest the shoulder), the start of the last link of the three-link arm,
    /// and that of the third link of the four-link arm (both on a circle).
    pub fn traced_point(&self, robot: &Robot, q: &[f64]) -> Option<Vector3<f64>> {
        let axis = |k: usize| -> Option<(Vector3<f64>, Vector3<f64>)> {
            let pe = robot.fk(q).ok()?.translation.vector;
            let j = robot.jacobian(q, 0).ok()?;
            let c = j.column(k);
            let w = Vector3::new(c[3], c[4], c[5]);
            Some((pe + w.cross(&Vector3::new(c[0], c[1], c[2])), w))
        };
        let elbow = |s: Vector3<f64>| {
            let (o, w) = axis(3)?;
            Some(o + w * w.dot(&(s - o)))
        };
        match &self.solver {
            Solver::Srs(a) => elbow(a.shoulder()),
            Solver::OffsetElbow(a) => elbow(a.shoulder()),
            Solver::Planar(_) | Solver::FourLink(_) => axis(2).map(|(o, _)| o),
            // The origin of the axis of joint 4 (the elbow of a seven-joint arm).
            Solver::Locked(_) => axis(3).map(|(o, _)| o),
        }
    }
}
