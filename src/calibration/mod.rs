//! Kinematic calibration (Sect. 2.11): estimate the DH parameters of a real arm from measured
//! poses by iterative least squares, and say which parameters the measurements can identify.
//! Pure compute over [`crate::kinematics`]; no graphics, no I/O (files come in as text).
//!
//! - [`ParameterModel`]: the parameter vector zeta = [a; alpha; d; theta] of (2.84) for every
//!   row of a serial DH table (standard or modified), joint offsets included as theta (revolute)
//!   or d (prismatic), any subset fixed; the pose `k(zeta, q)` it predicts and the robot it
//!   describes ([`ParameterModel::robot_with`]).
//! - [`ParameterModel::calibration_matrix`]: Phi(zeta) of (2.86) in closed form (each parameter
//!   moves the end-effector like a joint: a translation along or a rotation about a DH frame's
//!   axis), stacked over the poses as (2.87); full-pose or position-only measurements.
//! - [`calibrate`]: (2.88)-(2.89) iterated, with a rank-revealing SVD of the column-scaled,
//!   noise-weighted Phi, a record per iteration, the identifiability report and the uncertainty
//!   of the estimate.
//! - [`Setup`]: measurements without a tracker (distances, pivot points, planes, spheres, a
//!   tracker of unknown pose), each with the unknowns it estimates with the robot
//!   ([`Unknowns`]) and what it cannot see.
//! - [`select_poses`]: l poses out of candidates maximising O1 or O4 (DETMAX-style exchange);
//!   [`parse_measurements`] / [`write_measurements`]: the measurement file format.
//! - [`dh_form`] / [`with_calibrated_origins`]: a URDF chain calibrated through its derived DH
//!   table, the result carried back into its joint origins.
//! - [`correct_targets`]: IK on the calibrated arm in every posture of the nominal closed form,
//!   and the poses to send a controller that runs the nominal model (target filtering).
//! - [`accuracy_map`]: the position deviation between two models over the top view of the
//!   workspace (Sect. 2.10.1).
//! - [`Experiment`] / [`run`]: one experiment end to end (setup, data from files' text or a
//!   simulation, options, identifiability at the nominal point and at the estimate, held-out
//!   check, target correction); its [`Report`] prints as text and serialises to the JSON of
//!   `armlab calibrate --format json`. The command line, the app and Python all call it.
//! - [`simulate`]: a "real" robot (the nominal plus seeded deviations) and measurements with
//!   seeded noise, for teaching and for tests.
//!
//! Units: metres and radians; errors of a pose are `[p_measured - p_model; delta phi]` with
//! `R_measured R_model^T = Rot(delta phi)` (world frame).

mod accuracy;
mod chain;
mod correct;
mod doubt;
mod experiment;
mod file;
mod identify;
mod model;
mod report;
mod select;
mod setup;
mod simulate;
mod solve;
mod yaml;

pub use accuracy::{AccuracyMap, accuracy_map};
pub use chain::{dh_form, with_calibrated_origins};
pub use correct::{TargetCorrection, correct_targets};
pub use doubt::{Doubt, DoubtfulParameter, doubt_header, doubtful_parameters};
pub use experiment::{
    Corrections, Experiment, ExperimentError, ModelOptions, NamedText, Selection, Simulation,
    Source, dh_robot, measurement_template, run,
};
pub use file::{
    JointColumns, MeasurementFileError, ParsedFile, parse_measurements, parse_setup, parse_targets,
    template, write_corrections, write_measurements,
};
pub use identify::{Identifiability, Observability, identifiability};
pub use model::{Kind, Measurement, Parameter, ParameterModel};
pub use report::Report;
pub use select::{Criterion, select_poses};
pub use setup::{Linearised, PlaneUnknown, Setup, Unknowns, linearise, register_tracker};
pub use simulate::{
    SIMULATED_COMPLIANCE, SetupScene, Simulated, SimulationOptions, nominal_examples, simulate,
    simulate_setup,
};
pub use solve::{
    CalibrationOptions, CalibrationReport, Fit, Iteration, Unidentifiable, calibrate, fit,
};

use thiserror::Error;

/// Why a calibration could not run (a calibration that does not converge is a report, not an
/// error).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CalibrationError {
    /// The robot is not one serial chain of DH rows with one variable per joint.
    #[error("calibration needs a serial DH chain: {0}")]
    NotSerialDh(&'static str),
    /// A measurement has the wrong number of joint values.
    #[error("measurement {index}: {got} joint values, the robot has {expected}")]
    JointCount {
        /// Zero-based measurement index.
        index: usize,
        /// The robot's DOF.
        expected: usize,
        /// What the measurement has.
        got: usize,
    },
    /// A non-finite number in a measurement.
    #[error("measurement {index}: a value is not a finite number")]
    NonFinite {
        /// Zero-based measurement index.
        index: usize,
    },
    /// Measurements of both kinds (pose and position) mixed.
    #[error("measurement {index} is a {found}, the first one a {first}: all must be of one kind")]
    MixedKinds {
        /// Zero-based measurement index.
        index: usize,
        /// Kind of the first measurement.
        first: &'static str,
        /// Kind of this one.
        found: &'static str,
    },
    /// Fewer equations than parameters to estimate.
    #[error(
        "{equations} equations from {poses} poses for {parameters} free parameters: measure at \
         least {needed} poses, or fix parameters"
    )]
    TooFewEquations {
        /// Rows of the stacked system.
        equations: usize,
        /// Poses measured.
        poses: usize,
        /// Free parameters.
        parameters: usize,
        /// Poses needed.
        needed: usize,
    },
    /// An option out of range.
    #[error("invalid calibration option: {0}")]
    InvalidOption(String),
    /// Forward kinematics failed.
    #[error(transparent)]
    Kinematics(#[from] crate::kinematics::KinematicsError),
    /// The estimated parameters do not make a valid robot.
    #[error(transparent)]
    Model(#[from] crate::kinematics::ModelError),
}
