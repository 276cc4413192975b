//! Errors of the kinematics layer.

use thiserror::Error;

/// What can go wrong when a kinematic function is handed bad input.
///
/// A solver that merely fails to converge is not an error (see the IK reports); only input that
/// cannot be evaluated is.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum KinematicsError {
    /// The joint vector has the wrong length.
    #[error("expected {expected} joint values, got {got}")]
    DofMismatch {
        /// Degrees of freedom of the robot.
        expected: usize,
        /// Length of the vector that was given.
        got: usize,
    },
    /// A joint value is NaN or infinite.
    #[error("joint value {index} ({name}) is not a finite number: {value}")]
    NonFinite {
        /// Zero-based index of the offending joint value.
        index: usize,
        /// Name of the joint.
        name: String,
        /// The value itself.
        value: f64,
    },
    /// An end-effector index that the robot does not have.
    #[error("the robot has {count} end-effector(s); index {index} does not exist")]
    NoSuchEndEffector {
        /// Requested index.
        index: usize,
        /// Number of end-effectors the robot has.
        count: usize,
    },
    /// The minimal orientation representation is singular at this pose, so the quantity asked
    /// for (e.g. the analytical Jacobian) does not exist there.
    #[error("the {representation} representation is singular here ({detail})")]
    RepresentationSingular {
        /// Name of the representation (e.g. "ZYZ Euler").
        representation: &'static str,
        /// Which angle makes it singular.
        detail: String,
    },
}

/// What is wrong with a robot description (a DH table, a tree, a coupling).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ModelError {
    /// A numeric parameter is NaN or infinite.
    #[error("joint {joint}: field `{field}` is not a finite number ({value})")]
    NonFiniteParameter {
        /// Zero-based joint index.
        joint: usize,
        /// Field name (`a`, `alpha`, `d`, `theta`, `offset`, ...).
        field: &'static str,
        /// The value.
        value: f64,
    },
    /// Lower limit above upper limit, or a non-finite limit.
    #[error(
        "joint {joint}: limits [{lower}, {upper}] are not an interval (need lower <= upper, not NaN; an infinite bound means no limit on that side)"
    )]
    BadLimits {
        /// Zero-based joint index.
        joint: usize,
        /// Lower limit (rad or m).
        lower: f64,
        /// Upper limit (rad or m).
        upper: f64,
    },
    /// A parent that is not an earlier joint.
    #[error("joint {joint}: parent {parent} must be an earlier joint")]
    BadParent {
        /// Zero-based joint index.
        joint: usize,
        /// The parent index given.
        parent: usize,
    },
    /// A coupling that names itself, a later joint, a non-actuated joint, or a non-finite factor.
    #[error("joint {joint}: coupling term on joint {source_joint} is invalid ({reason})")]
    BadCoupling {
        /// Zero-based joint index of the coupled joint.
        joint: usize,
        /// The joint the term refers to.
        source_joint: usize,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// A 4x4 matrix that is not a rigid transform.
    #[error("{what} is not a rigid transform ({reason})")]
    NotRigid {
        /// Which transform (e.g. "base", "tool of end-effector 0").
        what: String,
        /// Why (e.g. "rotation part not orthonormal within 1e-6").
        reason: String,
    },
    /// A robot with no actuated joint, or an end-effector on a missing joint.
    #[error("{0}")]
    Structure(&'static str),
    /// A finite parameter too large to be a robot's (a length over [`MAX_LENGTH`] m, an angle
    /// over [`MAX_ANGLE`] rad): a typo or an attack, refused before it overflows a figure.
    ///
    /// [`MAX_LENGTH`]: crate::kinematics::robot::MAX_LENGTH
    /// [`MAX_ANGLE`]: crate::kinematics::robot::MAX_ANGLE
    #[error("joint {joint}: field `{field}` = {value:e} is out of range (|value| <= {bound})")]
    OutOfRange {
        /// Zero-based joint index.
        joint: usize,
        /// Field name (`a`, `d`, `limits`, `origin`, ...).
        field: &'static str,
        /// The value.
        value: f64,
        /// Which bound it exceeds.
        bound: Bound,
    },
    /// More joints than armlab handles.
    #[error("{count} joints: armlab handles at most {max}")]
    TooManyJoints {
        /// Joints in the model.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// A joint axis of zero length.
    #[error("joint {joint}: axis has zero length")]
    ZeroAxis {
        /// Zero-based joint index.
        joint: usize,
    },
}

/// The largest magnitude a robot's parameter may have (see [`ModelError::OutOfRange`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// A length: [`crate::kinematics::robot::MAX_LENGTH`] m.
    Length,
    /// An angle: [`crate::kinematics::robot::MAX_ANGLE`] rad.
    Angle,
}

impl std::fmt::Display for Bound {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::kinematics::robot::{MAX_ANGLE, MAX_LENGTH};
        match self {
            Bound::Length => write!(f, "{MAX_LENGTH:e} m"),
            Bound::Angle => write!(f, "{MAX_ANGLE:e} rad"),
        }
    }
}
