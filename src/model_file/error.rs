//! Errors of the model-file layer: every one names the field, and where in which file.

use crate::kinematics::ModelError;
use crate::kinematics::pose::NotRigid;
use std::fmt;
use std::path::PathBuf;
use thiserror::Error;

/// A position in a model file: the path as given, 1-based line and column (in characters).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file, as the caller named it (only used in messages).
    pub path: PathBuf,
    /// 1-based line number.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.path.display(), self.line, self.column)
    }
}

/// What kind of list holds a duplicate name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NameKind {
    /// `[[joints]]` names.
    Joint,
    /// `[[end_effectors]]` names.
    EndEffector,
    /// `[[configurations]]` names.
    Configuration,
}

impl fmt::Display for NameKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            NameKind::Joint => "joint",
            NameKind::EndEffector => "end-effector",
            NameKind::Configuration => "configuration",
        })
    }
}

/// Why a `couple` term is rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoupleProblem {
    /// The joint number is 0 or larger than the number of joints.
    NoSuchJoint,
    /// The joint is this joint itself or comes after it in the file.
    NotEarlier,
    /// The joint is fixed or itself coupled, so it has no `q` component.
    NotActuated,
}

impl fmt::Display for CoupleProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            CoupleProblem::NoSuchJoint => "there is no such joint",
            CoupleProblem::NotEarlier => "it must be a joint before this one in the file",
            CoupleProblem::NotActuated => "it must be an actuated joint (not fixed, not coupled)",
        })
    }
}

/// Everything that can be wrong with a TOML model file.
///
/// Every variant but [`ModelFileError::Read`] carries the dotted path of the offending field
/// (`joints[3].alpha`; array elements are numbered from 1, like the joint numbers in `couple`
/// and the default joint names `q1`, `q2`, ...) and its [`Location`]; the message ends with
/// `(path:line:column)`.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ModelFileError {
    /// The file could not be read.
    #[error("cannot read the model file: {source} ({})", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not valid TOML.
    #[error("TOML syntax error: {message} ({at})")]
    Syntax {
        /// The TOML parser's description.
        message: String,
        /// Where the parser stopped.
        at: Location,
    },
    /// A required field is absent.
    #[error("{field}: missing required field ({at})")]
    Missing {
        /// The absent field.
        field: String,
        /// The table that should hold it.
        at: Location,
    },
    /// A key the schema does not know.
    #[error("{field}: unknown key `{key}`; expected one of {allowed} ({at})")]
    UnknownKey {
        /// The full path of the unknown key.
        field: String,
        /// The key itself.
        key: String,
        /// The keys allowed in that table, comma-separated.
        allowed: String,
        /// The key.
        at: Location,
    },
    /// A value of the wrong TOML type.
    #[error("{field}: expected {expected}, found {found} ({at})")]
    WrongType {
        /// The field.
        field: String,
        /// What the schema wants.
        expected: &'static str,
        /// The TOML type that was found (with the text of a string).
        found: String,
        /// The value.
        at: Location,
    },
    /// A string that is not a valid angle.
    #[error(
        "{field}: \"{text}\" is not an angle; write radians as a number, or a string such as \"pi/2\", \"-2*pi/3\", \"-90deg\", \"45 deg\", \"1.2rad\" ({at})"
    )]
    BadAngle {
        /// The field.
        field: String,
        /// The string found.
        text: String,
        /// The value.
        at: Location,
    },
    /// NaN, an infinity, or a number too large for f64.
    #[error("{field}: expected a finite number, found {text} ({at})")]
    NonFinite {
        /// The field.
        field: String,
        /// The number as written.
        text: String,
        /// The value.
        at: Location,
    },
    /// `convention` is neither "standard" nor "modified".
    #[error(
        "{field}: unknown convention \"{value}\"; expected \"standard\" or \"modified\" ({at})"
    )]
    UnknownConvention {
        /// The field (`convention`).
        field: String,
        /// The string found.
        value: String,
        /// The value.
        at: Location,
    },
    /// A joint `type` other than revolute, prismatic or fixed.
    #[error(
        "{field}: unknown joint type \"{value}\"; expected \"revolute\", \"prismatic\" or \"fixed\" ({at})"
    )]
    UnknownJointType {
        /// The field (`joints[i].type`).
        field: String,
        /// The string found.
        value: String,
        /// The value.
        at: Location,
    },
    /// An array of the wrong length (limits, a matrix row, a couple term, ...).
    #[error("{field}: expected {expected}, found {found} element(s) ({at})")]
    WrongLength {
        /// The field.
        field: String,
        /// What the schema wants, e.g. "2 values [lower, upper]".
        expected: &'static str,
        /// How many elements there are.
        found: usize,
        /// The array.
        at: Location,
    },
    /// `lower > upper`.
    #[error("{field}: lower limit {lower} is above upper limit {upper} ({at})")]
    BadLimits {
        /// The field (`joints[i].limits`).
        field: String,
        /// Lower limit (rad or m).
        lower: f64,
        /// Upper limit (rad or m).
        upper: f64,
        /// The array.
        at: Location,
    },
    /// A 4x4 matrix that is not a rigid transform.
    #[error("{field}: not a rigid transform: {reason} ({at})")]
    NotRigid {
        /// The field (`base`, `tool`, `joints[i].pre`, `end_effectors[i].tool`).
        field: String,
        /// Why.
        reason: NotRigid,
        /// The matrix.
        at: Location,
    },
    /// `parent` names no earlier joint.
    #[error(
        "{field}: no joint before this one is named \"{name}\"; a parent must be \"base\" or an earlier joint ({at})"
    )]
    UnknownParent {
        /// The field (`joints[i].parent`).
        field: String,
        /// The name given.
        name: String,
        /// The value.
        at: Location,
    },
    /// An end-effector's `parent` names no joint.
    #[error("{field}: no joint is named \"{name}\" ({at})")]
    UnknownJoint {
        /// The field (`end_effectors[i].parent`).
        field: String,
        /// The name given.
        name: String,
        /// The value.
        at: Location,
    },
    /// Two joints, end-effectors or configurations with the same name.
    #[error("{field}: duplicate {kind} name \"{name}\" (first used on line {first_line}) ({at})")]
    DuplicateName {
        /// The field of the second use.
        field: String,
        /// Which list.
        kind: NameKind,
        /// The name.
        name: String,
        /// Line of the first use.
        first_line: usize,
        /// The second use.
        at: Location,
    },
    /// A `couple` term that names an unusable joint.
    #[error("{field}: joint {joint} cannot drive this joint: {problem} ({at})")]
    BadCouple {
        /// The field (`joints[i].couple[k]`).
        field: String,
        /// The 1-based joint number given.
        joint: i64,
        /// Why.
        problem: CoupleProblem,
        /// The term.
        at: Location,
    },
    /// A configuration whose length differs from the number of degrees of freedom.
    #[error("{field}: expected {expected} joint values (the robot's dof), found {found} ({at})")]
    ConfigLength {
        /// The field (`configurations[i].q`).
        field: String,
        /// The robot's dof.
        expected: usize,
        /// The length found.
        found: usize,
        /// The array.
        at: Location,
    },
    /// `joints = []`.
    #[error("{field}: a robot needs at least one joint ({at})")]
    EmptyJoints {
        /// The field (`joints`).
        field: String,
        /// The empty array.
        at: Location,
    },
    /// A field that the schema knows but that makes no sense here (e.g. `limits` on a fixed
    /// joint, a non-zero `theta` on a revolute joint, a top-level `tool` next to
    /// `[[end_effectors]]`).
    #[error("{field}: {reason} ({at})")]
    NotApplicable {
        /// The field.
        field: String,
        /// Why it does not apply.
        reason: &'static str,
        /// The field's key.
        at: Location,
    },
    /// A `[[disable_collisions]]` pair naming a link the robot does not have.
    #[error("{field}: the robot has no link \"{name}\" (its links: {available}) ({at})")]
    UnknownLink {
        /// The field (`disable_collisions[i].link1` or `.link2`).
        field: String,
        /// The name given.
        name: String,
        /// The robot's link names, comma-separated ("base", "link1", ...).
        available: String,
        /// The value.
        at: Location,
    },
    /// The robot assembled from the file was rejected by [`crate::kinematics::Robot::new`].
    #[error("{field}: {source} ({at})")]
    Model {
        /// The joint or field the error was traced back to.
        field: String,
        /// The kinematics layer's error.
        #[source]
        source: ModelError,
        /// Where.
        at: Location,
    },
}

impl ModelFileError {
    /// The file position of the error (`None` for [`ModelFileError::Read`]).
    pub fn location(&self) -> Option<&Location> {
        use ModelFileError as E;
        match self {
            E::Read { .. } => None,
            E::Syntax { at, .. }
            | E::Missing { at, .. }
            | E::UnknownKey { at, .. }
            | E::WrongType { at, .. }
            | E::BadAngle { at, .. }
            | E::NonFinite { at, .. }
            | E::UnknownConvention { at, .. }
            | E::UnknownJointType { at, .. }
            | E::WrongLength { at, .. }
            | E::BadLimits { at, .. }
            | E::NotRigid { at, .. }
            | E::UnknownParent { at, .. }
            | E::UnknownJoint { at, .. }
            | E::DuplicateName { at, .. }
            | E::BadCouple { at, .. }
            | E::ConfigLength { at, .. }
            | E::EmptyJoints { at, .. }
            | E::NotApplicable { at, .. }
            | E::UnknownLink { at, .. }
            | E::Model { at, .. } => Some(at),
        }
    }

    /// The dotted path of the offending field (`None` for read and syntax errors).
    pub fn field(&self) -> Option<&str> {
        use ModelFileError as E;
        match self {
            E::Read { .. } | E::Syntax { .. } => None,
            E::Missing { field, .. }
            | E::UnknownKey { field, .. }
            | E::WrongType { field, .. }
            | E::BadAngle { field, .. }
            | E::NonFinite { field, .. }
            | E::UnknownConvention { field, .. }
            | E::UnknownJointType { field, .. }
            | E::WrongLength { field, .. }
            | E::BadLimits { field, .. }
            | E::NotRigid { field, .. }
            | E::UnknownParent { field, .. }
            | E::UnknownJoint { field, .. }
            | E::DuplicateName { field, .. }
            | E::BadCouple { field, .. }
            | E::ConfigLength { field, .. }
            | E::EmptyJoints { field, .. }
            | E::NotApplicable { field, .. }
            | E::UnknownLink { field, .. }
            | E::Model { field, .. } => Some(field),
        }
    }
}
