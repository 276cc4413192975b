//! IK on the calibrated arm, and target correction: for each desired tool pose and each posture
//! of the nominal model's closed form, the joint vector that puts the real (calibrated) arm's
//! tool there, and the pose a controller running the nominal model must be sent to get the same
//! result (target filtering).

use super::CalibrationError;
use crate::kinematics::Robot;
use crate::kinematics::ik::numerical::NumericalOptions;
use crate::kinematics::ik::solver::{self, NEAR_MISS_CHECK};
use crate::kinematics::ik::{IkError, SolutionPosture, Target};
use crate::kinematics::pose::Pose;

/// One desired pose reached in one posture.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetCorrection {
    /// Index of the desired pose.
    pub pose: usize,
    /// The posture (from the nominal model's closed form); its `Display` is the label.
    pub posture: SolutionPosture,
    /// Joint vector that puts the calibrated arm's tool on the desired pose (rad, m), checked by
    /// the calibrated arm's FK to [`NEAR_MISS_CHECK`].
    pub q: Vec<f64>,
    /// Whether `q` lies within the joint limits.
    pub within_limits: bool,
    /// What to send a controller that runs the nominal model: `FK_nominal(q)`, so that its IK
    /// in this posture returns `q`.
    pub send: Pose,
    /// Position error of the calibrated FK at `q` (m).
    pub position_error: f64,
    /// Orientation error of the calibrated FK at `q` (rad).
    pub orientation_error: f64,
    /// Where the real arm's tool would be off without the correction: the position error of
    /// the calibrated FK at the nominal IK solution of the same posture (m).
    pub uncorrected_error: f64,
}

/// Target correction of `targets` (world_from_tool): every posture of `nominal`'s closed form
/// polished on `calibrated` ([`solver::solve_from_reference`]). A pose that a posture cannot
/// reach on the calibrated arm gives no row for that posture.
pub fn correct_targets(
    nominal: &Robot,
    calibrated: &Robot,
    targets: &[Pose],
) -> Result<Vec<TargetCorrection>, CalibrationError> {
    let opts = NumericalOptions::default();
    let ik_error = |e: IkError| CalibrationError::InvalidOption(format!("target correction: {e}"));
    let mut out = Vec::new();
    for (k, t) in targets.iter().enumerate() {
        let target = Target::Pose(*t);
        let (real, _) =
            solver::solve_from_reference(calibrated, nominal, &target, &opts).map_err(ik_error)?;
        let (ideal, _) = solver::solve(
            nominal,
            0,
            &target,
            None,
            solver::SolverChoice::ClosedForm,
            &opts,
        )
        .map_err(ik_error)?;
        for s in real.solutions {
            let uncorrected = ideal
                .solutions
                .iter()
                .find(|i| i.posture.same_label(&s.posture))
                .map(|i| calibrated.fk(&i.q))
                .transpose()?
                .map_or(f64::NAN, |p| {
                    (p.translation.vector - t.translation.vector).norm()
                });
            debug_assert!(s.position_error.max(s.orientation_error) <= NEAR_MISS_CHECK);
            out.push(TargetCorrection {
                pose: k,
                send: nominal.fk(&s.q)?,
                posture: s.posture,
                within_limits: s.within_limits,
                position_error: s.position_error,
                orientation_error: s.orientation_error,
                uncorrected_error: uncorrected,
                q: s.q,
            });
        }
    }
    Ok(out)
}
