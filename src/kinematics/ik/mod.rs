//! Inverse kinematics (Sect. 2.12): closed-form solvers chosen from the structure of the DH table,
//! returning every solution labelled with its posture, and a numerical solver for any chain.

pub mod branches;
pub mod closed_form;
pub mod numerical;
pub mod solver;

pub use closed_form::{ClosedForm, Family};

use closed_form::{Posture, WristFlip};

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
    /// Which solution this is, as data; its `Display` is the posture label, e.g. "shoulder
    /// right, elbow up, wrist no flip", "elbow down", or "numerical".
    pub posture: SolutionPosture,
    /// Whether q lies inside the joint limits.
    pub within_limits: bool,
    /// |p(FK(q)) - p_target| (m).
    pub position_error: f64,
    /// Rotation angle of R(FK(q))^T R_target (rad); 0 for position-only targets.
    pub orientation_error: f64,
    /// Joints that are free at this target (a representative value was chosen for them).
    pub free_joints: Vec<FreeJoint>,
}

/// What an IK solution is, as data: the closed form's posture (shoulder, elbow, extension,
/// wrist, branch number, reversed chain, free joints), or the numerical solver's answer.
///
/// `Display` gives the label ("shoulder right, elbow up, wrist no flip", "wrist flip, branch 3",
/// "numerical", "numerical (not converged)"); nothing reads a label back. `Serialize` gives the
/// fields, tagged by `"solver"`: `{"solver": "closed_form", "shoulder": "right", "elbow": "up",
/// "extension": null, "wrist": "no_flip", "branch": null, "reversed": false, "free": [null, ...]}`
/// or `{"solver": "numerical", "converged": true}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "solver", rename_all = "snake_case")]
pub enum SolutionPosture {
    /// A closed-form solution's posture; also "branch k" of the numerical search where a general
    /// six-revolute arm's elimination finds nothing (a posture with only a branch number).
    ClosedForm(Posture),
    /// The one configuration of the numerical solver.
    Numerical {
        /// Whether it reached the tolerance.
        converged: bool,
    },
}

impl SolutionPosture {
    /// The closed-form posture, if this is one.
    pub fn closed_form(&self) -> Option<&Posture> {
        match self {
            SolutionPosture::ClosedForm(p) => Some(p),
            SolutionPosture::Numerical { .. } => None,
        }
    }

    /// The branch number (1-based) of a solution of a general arm ("branch k"), if it has one.
    pub fn branch(&self) -> Option<u8> {
        self.closed_form().and_then(|p| p.branch)
    }

    /// Whether the posture is the merged member of a pair ([`Posture::is_merged`]: "elbow
    /// stretched", "wrist singular", ...); false for the numerical solver's.
    pub fn is_merged(&self) -> bool {
        self.closed_form().is_some_and(Posture::is_merged)
    }

    /// Whether the wrist is named up/down (three parallel axes, the UR family) rather than
    /// flip/no flip.
    pub fn has_up_down_wrist(&self) -> bool {
        matches!(
            self.closed_form().and_then(|p| p.wrist),
            Some(WristFlip::Up | WristFlip::Down)
        )
    }

    /// Whether two postures have the same label (closed-form postures compared without their
    /// free joints, [`Posture::same_label`]).
    pub fn same_label(&self, other: &SolutionPosture) -> bool {
        match (self, other) {
            (SolutionPosture::ClosedForm(a), SolutionPosture::ClosedForm(b)) => a.same_label(b),
            _ => self == other,
        }
    }

    /// The short label ("R U N", [`Posture::short`]); the numerical solver's label as it is.
    pub fn short(&self) -> String {
        match self {
            SolutionPosture::ClosedForm(p) => p.short(),
            SolutionPosture::Numerical { .. } => self.to_string(),
        }
    }
}

impl std::fmt::Display for SolutionPosture {
    /// The posture label (padded to a width, `{:<42}`, as a string is).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolutionPosture::ClosedForm(p) => std::fmt::Display::fmt(p, f),
            SolutionPosture::Numerical { converged: true } => f.pad("numerical"),
            SolutionPosture::Numerical { converged: false } => f.pad("numerical (not converged)"),
        }
    }
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
