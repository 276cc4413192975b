//! The plain data of the app state: status messages, display toggles, reachability of a target,
//! the per-end-effector target, ghosts, readouts and the error type.

use super::DhField;
use super::units::{EntryError, MM_PER_M};
use crate::kinematics::ik::{IkResult, SolutionPosture};
use crate::kinematics::pose::Pose;
use crate::kinematics::singularity::SingularityReport;
use crate::kinematics::{EulerKind, KinematicsError};
use crate::model_file::LoadError;
use nalgebra::{Matrix4, Vector3};
use thiserror::Error;

/// Severity of a status message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Something happened as asked.
    Info,
    /// Something was adjusted or could not be done fully (clamped value, unreachable target).
    Warning,
    /// Something failed (model load).
    Error,
}

/// One line of the status bar.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StatusMessage {
    /// Severity.
    pub level: Level,
    /// Text.
    pub text: String,
}

/// What to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct DisplayToggles {
    /// DH frame triads.
    pub frames: bool,
    /// Frame labels.
    pub labels: bool,
    /// Ground grid.
    pub grid: bool,
    /// End-effector trail.
    pub trail: bool,
    /// Translucent ghost arms of the other IK solutions.
    pub ghosts: bool,
    /// Workspace overlay.
    pub workspace: bool,
    /// The self-motion's traced path (the elbow circle of an SRS arm).
    pub self_motion_path: bool,
    /// Label every frame (else a robot with many frames labels only its driven chain's).
    pub all_labels: bool,
    /// The reachability overlay (issue 49). Not remembered: its map is computed on request.
    #[serde(skip)]
    pub reachability: bool,
}

impl Default for DisplayToggles {
    fn default() -> Self {
        Self {
            frames: true,
            labels: true,
            grid: true,
            trail: true,
            ghosts: true,
            workspace: false,
            self_motion_path: true,
            all_labels: false,
            reachability: false,
        }
    }
}

/// Whether the arm reaches its target.
#[derive(Debug, Clone, PartialEq)]
pub enum Reach {
    /// The arm is at the target (or the target follows the arm).
    Reached,
    /// Outside the workspace by `distance` (m; infinite when unknown); the arm stays at its last
    /// reachable pose.
    Unreachable {
        /// Gap to the workspace (m).
        distance: f64,
    },
    /// The numerical solver did not converge from the current q: the best configuration found
    /// is still `distance` (m) and `angle` (rad) away. The arm stays put.
    NotConverged {
        /// Remaining position error (m).
        distance: f64,
        /// Remaining orientation error (rad).
        angle: f64,
    },
    /// Reachable only outside the joint limits (or, under the lock, only with another posture).
    OutsideLimits {
        /// The locked posture, if the lock caused it.
        posture: Option<SolutionPosture>,
    },
    /// The IK rejected the target (its message).
    Invalid {
        /// Why.
        reason: String,
    },
}

impl Reach {
    /// Whether the arm is at the target.
    pub fn is_reached(&self) -> bool {
        matches!(self, Reach::Reached)
    }

    /// A sentence for the UI, `None` when reached.
    pub fn message(&self) -> Option<String> {
        let stays = "the arm stays at its last reachable pose";
        match self {
            Reach::Reached => None,
            Reach::Unreachable { distance } if distance.is_finite() => Some(format!(
                "target unreachable: {:.1} mm outside the workspace; {stays}",
                distance * MM_PER_M
            )),
            Reach::Unreachable { .. } => Some(format!("target unreachable; {stays}")),
            Reach::NotConverged { distance, angle } => Some(format!(
                "target not reached by the numerical solver from the current configuration: \
                 {:.1} mm, {:.2}° away; {stays}",
                distance * MM_PER_M,
                angle.to_degrees()
            )),
            Reach::OutsideLimits { posture: Some(p) } => Some(format!(
                "the locked posture \"{p}\" is outside the joint limits here (unlock to switch \
                 posture); {stays}"
            )),
            Reach::OutsideLimits { posture: None } => Some(format!(
                "target reachable only outside the joint limits; {stays}"
            )),
            Reach::Invalid { reason } => Some(format!("target rejected: {reason}")),
        }
    }
}

/// The IK target of one end-effector.
#[derive(Debug, Clone, PartialEq)]
pub struct EeTarget {
    /// End-effector name.
    pub name: String,
    /// The desired `world_from_tool` (m, rad).
    pub world_from_tool: Pose,
    /// The last IK result (every closed-form solution, or the numerical one); `None` before any
    /// solve or after the target was synced for an arm without a closed form.
    pub result: Option<IkResult>,
    /// Index into the result's solutions of the one the arm is at.
    pub selected: Option<usize>,
    /// Selected posture (the lock keeps it).
    pub posture: Option<SolutionPosture>,
    /// Whether the arm reaches the target.
    pub reach: Reach,
}

/// One IK solution to draw as a translucent arm.
#[derive(Debug, Clone, PartialEq)]
pub struct Ghost {
    /// Joint vector (rad or m).
    pub q: Vec<f64>,
    /// What the ghost is: an IK solution's posture or a self-motion branch.
    pub posture: GhostLabel,
    /// Inside the joint limits (grey it out otherwise).
    pub within_limits: bool,
    /// The arm is at this solution.
    pub selected: bool,
    /// Its posture class (the workspace figures' colour index), if it has one.
    pub class: Option<u8>,
    /// What its posture hits, where collisions are checked (`None`: not checked).
    pub collision: Option<crate::collision::CollisionReport>,
}

/// What a ghost arm is labelled with.
#[derive(Debug, Clone, PartialEq)]
pub enum GhostLabel {
    /// One of the IK solutions of the target.
    Solution(SolutionPosture),
    /// Another branch of the self-motion, by its name (e.g. "elbow up", "branch 2").
    SelfMotion(String),
}

impl GhostLabel {
    /// The IK solution's posture, if the ghost is one.
    pub fn posture(&self) -> Option<&SolutionPosture> {
        match self {
            GhostLabel::Solution(p) => Some(p),
            GhostLabel::SelfMotion(_) => None,
        }
    }

    /// The short label drawn at the ghost ("R U N", [`SolutionPosture::short`]); a self-motion
    /// branch's name as it is.
    pub fn short(&self) -> String {
        match self {
            GhostLabel::Solution(p) => p.short(),
            GhostLabel::SelfMotion(name) => name.clone(),
        }
    }
}

impl std::fmt::Display for GhostLabel {
    /// The full label: the posture label or the branch name.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GhostLabel::Solution(p) => std::fmt::Display::fmt(p, f),
            GhostLabel::SelfMotion(name) => f.pad(name),
        }
    }
}

/// The numbers shown next to the 3D view for one end-effector.
#[derive(Debug, Clone, PartialEq)]
pub struct Readouts {
    /// `world_from_tool` as a homogeneous 4x4 matrix (m).
    pub t: Matrix4<f64>,
    /// Tool position (m).
    pub p: Vector3<f64>,
    /// Orientation angles (rad) in the representation `phi_kind`.
    pub phi: Vector3<f64>,
    /// ZYZ or RPY.
    pub phi_kind: EulerKind,
    /// The representation is singular here (only a combination of angles is defined).
    pub phi_singular: bool,
    /// Numerical rank of the task Jacobian: the rows the arm controls of the geometric Jacobian
    /// in the base frame ([`crate::kinematics::singularity::SingularityAnalyzer::task_jacobian`]; all
    /// six rows for a six-DOF arm, x and y for the two-link planar arm).
    pub rank: usize,
    /// Task rank of the structure (the rank at generic configurations).
    pub task_rank: usize,
    /// Product of the first `task_rank` singular values of the task Jacobian (Yoshikawa's
    /// measure `sqrt(det(J J^T))` for the controlled task; |a1 a2 sin theta2| m^2 for the two-link
    /// planar arm; mixed units in general).
    pub manipulability: f64,
    /// The `task_rank`-th singular value of the task Jacobian (0 at a singularity; m/rad or
    /// dimensionless, mixed units).
    pub min_sv: f64,
    /// The singularity warning, if at or near one.
    pub singularity: Option<SingularityReport>,
}

/// What a state method can refuse.
#[derive(Debug, Error)]
pub enum StateError {
    /// The model could not be loaded; the previous model is kept.
    #[error("could not load model \"{spec}\": {source}")]
    Load {
        /// What was asked.
        spec: String,
        /// Why (boxed: the loader's error is large).
        #[source]
        source: Box<LoadError>,
    },
    /// No named configuration by that name.
    #[error("no configuration \"{name}\" (available: {available})")]
    UnknownConfiguration {
        /// Name asked.
        name: String,
        /// Names available, comma-separated.
        available: String,
    },
    /// End-effector index out of range.
    #[error("no end-effector {index} (the robot has {count})")]
    NoSuchEndEffector {
        /// Index asked.
        index: usize,
        /// Number of end-effectors.
        count: usize,
    },
    /// Joint index out of range (DH table rows).
    #[error("no joint {index} (the robot has {count})")]
    NoSuchJoint {
        /// Index asked.
        index: usize,
        /// Number of joints.
        count: usize,
    },
    /// q index out of range.
    #[error("no joint variable q{} (the robot has {count})", index + 1)]
    NoSuchDof {
        /// Zero-based index asked.
        index: usize,
        /// dof.
        count: usize,
    },
    /// Solution index out of range.
    #[error("no IK solution {index} ({count} available)")]
    NoSuchSolution {
        /// Index asked.
        index: usize,
        /// Number of solutions.
        count: usize,
    },
    /// No solution with that posture label.
    #[error("no IK solution with posture \"{label}\" (available: {available})")]
    NoSuchPosture {
        /// Label asked.
        label: String,
        /// Labels available, separated by "; ".
        available: String,
    },
    /// A task or self-motion request that does not apply (the reason in words).
    #[error("{0}")]
    Task(String),
    /// The chosen solution violates the joint limits.
    #[error("IK solution {} (\"{posture}\") is outside the joint limits", index + 1)]
    SolutionOutsideLimits {
        /// Index (0-based; the message counts from 1, as the list does).
        index: usize,
        /// Its posture.
        posture: String,
    },
    /// A DH cell entry was not applied (the text stays in the cell with this reason).
    #[error("joint {} {}: {reason}", joint + 1, field.name())]
    InvalidEntry {
        /// Zero-based joint index.
        joint: usize,
        /// Column.
        field: DhField,
        /// Why.
        #[source]
        reason: EntryError,
    },
    /// A joint value entry was not applied.
    #[error("q{}: {reason}", dof + 1)]
    InvalidJointEntry {
        /// Zero-based q index.
        dof: usize,
        /// Why.
        #[source]
        reason: EntryError,
    },
    /// A target with NaN or infinite numbers.
    #[error("the target contains a non-finite number")]
    NonFiniteTarget,
    /// Forward kinematics refused (should not happen: q is kept valid).
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}
