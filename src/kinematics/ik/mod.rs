//! Inverse kinematics (Sect. 2.12): closed-form solvers chosen from the structure of the DH table,
//! returning every solution labelled with its posture, and a numerical solver for any chain.

pub mod branches;
pub mod closed_form;
pub mod numerical;
pub mod solver;

pub use closed_form::{ClosedForm, Family};

use super::pose::Pose;
use nalgebra::Vector3;
use thiserror::Error;

/// What the end-effector must reach, in the world frame (metres, radians).
///
/// # Examples
///
/// The three-link planar arm with the planar target (px, py, phi) of (2.83): the wrist point
/// `p - a3 (cos phi, sin phi)` is then a two-link problem with two solutions (Sect. 2.12.1).
///
/// ```
/// use armlab::kinematics::ik::{ClosedForm, Target};
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar3").expect("a built-in model");
/// let cf = ClosedForm::detect(&arm)?;
/// let (px, py, phi) = (0.6, 0.3, 0.5);
/// let result = cf.solve(&arm, &Target::Planar { px, py, phi })?;
/// assert_eq!(result.solutions.len(), 2);
/// for s in &result.solutions {
///     assert!((s.q.iter().sum::<f64>() - phi).abs() < 1e-12); // phi = q1 + q2 + q3
///     let p = arm.fk(&s.q)?.translation.vector;
///     assert!((p.x - px).abs() < 1e-12 && (p.y - py).abs() < 1e-12);
/// }
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// A full pose `world_from_tool`.
    Pose(Pose),
    /// A position only; orientation is free.
    Position(Vector3<f64>),
    /// A planar target (px, py, phi) for an arm moving in the base's x-y plane; phi is the angle
    /// of the end-effector x axis from x0 (2.83).
    Planar {
        /// x (m).
        px: f64,
        /// y (m).
        py: f64,
        /// Orientation angle (rad).
        phi: f64,
    },
}

/// A joint the closed form cannot determine (a degenerate family of solutions).
#[derive(Debug, Clone, PartialEq)]
pub struct FreeJoint {
    /// Zero-based index into q.
    pub index: usize,
    /// Why it is free, e.g. "wrist centre on the axis of joint 1 (p_Wx = p_Wy = 0)".
    pub reason: &'static str,
}

/// One inverse-kinematics solution.
#[derive(Debug, Clone, PartialEq)]
pub struct IkSolution {
    /// Joint vector (rad or m), angles wrapped into the joint limits where a 2*pi shift allows,
    /// otherwise into (-pi, pi].
    pub q: Vec<f64>,
    /// Posture label, e.g. "shoulder right, elbow up, wrist no flip", "elbow down", or
    /// "numerical".
    pub posture: String,
    /// Whether q lies inside the joint limits.
    pub within_limits: bool,
    /// |p(FK(q)) - p_target| (m).
    pub position_error: f64,
    /// Rotation angle of R(FK(q))^T R_target (rad); 0 for position-only targets.
    pub orientation_error: f64,
    /// Joints that are free at this target (a representative value was chosen for them).
    pub free_joints: Vec<FreeJoint>,
}

/// Overall outcome for one target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IkStatus {
    /// Solutions were found.
    Ok,
    /// The target is outside the workspace by `distance` metres (or, for an orientation that cannot
    /// be reached, by the angle in rad); `solutions` then holds the closest reachable configuration
    /// if one was computed.
    Unreachable {
        /// How far outside (m, or rad for orientation-only failures).
        distance: f64,
    },
    /// The target lies on a singularity with infinitely many solutions; each solution lists its
    /// free joints.
    Singular,
}

/// The result of an IK query: status and every solution found.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct IkResult {
    /// Overall status.
    pub status: IkStatus,
    /// Every distinct solution (closed form) or the converged one(s) (numerical).
    pub solutions: Vec<IkSolution>,
}

/// Invalid IK input (a solver that fails to converge is not an error: see the reports).
///
/// # Examples
///
/// ```
/// use armlab::kinematics::ik::{ClosedForm, IkError, Target};
/// use armlab::kinematics::models::built_in;
/// use armlab::nalgebra::Vector3;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let cf = ClosedForm::detect(&puma)?;
/// // A six-joint arm needs a pose, not a planar target.
/// let err = cf.solve(&puma, &Target::Planar { px: 0.5, py: 0.1, phi: 0.0 }).unwrap_err();
/// assert!(matches!(err, IkError::TargetKind { .. }));
/// println!("{err}");
/// // NaN never reaches a solver.
/// let nan = Target::Position(Vector3::new(f64::NAN, 0.0, 0.0));
/// assert_eq!(cf.solve(&puma, &nan).unwrap_err(), IkError::NonFiniteTarget);
/// // A closed form belongs to the arm it was detected for.
/// let planar2 = built_in("planar2").expect("a built-in model");
/// let other = cf.solve(&planar2, &Target::Position(Vector3::new(1.0, 0.0, 0.0)));
/// assert!(matches!(other, Err(IkError::OtherRobot { dof: 6, robot_dof: 2, .. })));
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone, PartialEq, Error)]
pub enum IkError {
    /// A target with NaN or infinite numbers.
    #[error("the target contains a non-finite number")]
    NonFiniteTarget,
    /// A target kind the solver cannot use (e.g. a planar target for a spatial arm).
    #[error("a {target} target does not fit the {solver}: {hint}")]
    TargetKind {
        /// The target's kind: "position", "planar (px, py, phi)", "pose".
        target: &'static str,
        /// The closed-form family's name.
        solver: &'static str,
        /// Why, and what to give instead.
        hint: &'static str,
    },
    /// A pose target whose orientation tilts out of a planar arm's plane.
    #[error(
        "the target orientation is tilted {tilt:.3e} rad out of the plane of this planar arm: give \
         a planar target or a pose whose z axis is along z0"
    )]
    TiltedOutOfPlane {
        /// Angle between the target's z axis and the plane's normal (rad).
        tilt: f64,
    },
    /// A target off the plane of a planar arm without a prismatic joint.
    #[error(
        "the target is {offset:.3e} m off the plane of this planar arm (z = {plane_z} in the base \
         frame)"
    )]
    OffPlane {
        /// Signed distance from the plane (m).
        offset: f64,
        /// The plane's z in the base frame (m).
        plane_z: f64,
    },
    /// No closed form exists for this arm's structure.
    #[error("no closed-form solver matches this arm's structure ({0})")]
    NoClosedForm(#[from] closed_form::NoClosedForm),
    /// A closed form applied to a robot it was not detected for.
    #[error("this closed form is for a {dof}-DOF {family}, the robot has {robot_dof} DOF")]
    OtherRobot {
        /// The closed form's joint count.
        dof: usize,
        /// Its family's name.
        family: &'static str,
        /// The robot's joint count.
        robot_dof: usize,
    },
    /// Bad joint vector (seed).
    #[error(transparent)]
    Kinematics(#[from] super::error::KinematicsError),
    /// The general six-revolute elimination cannot solve this arm or pose (a special structure
    /// it does not cover); no partial set is returned.
    #[error("the elimination for general six-revolute arms cannot solve this: {reason}")]
    Degenerate {
        /// Why, in words.
        reason: &'static str,
    },
    /// The end-effector has no arm of its own to solve (a frame fixed to the base).
    #[error("end-effector \"{ee}\": {reason}")]
    Arm {
        /// The end-effector's name.
        ee: String,
        /// Why.
        reason: String,
    },
}

/// Checks that a target has only finite numbers.
pub fn check_target(t: &Target) -> Result<(), IkError> {
    let ok = match t {
        Target::Pose(p) => p.to_homogeneous().iter().all(|v| v.is_finite()),
        Target::Position(p) => p.iter().all(|v| v.is_finite()),
        Target::Planar { px, py, phi } => px.is_finite() && py.is_finite() && phi.is_finite(),
    };
    if ok {
        Ok(())
    } else {
        Err(IkError::NonFiniteTarget)
    }
}
