//! One entry point for IK: the closed form when the arm's structure has one (every solution,
//! polished numerically where that helps), the numerical solver otherwise (seeded with the
//! caller's q); plus picking a solution by posture or by closeness to a configuration.

use super::closed_form::{ClosedForm, NoClosedForm};
use super::numerical::{self, NumericalOptions};
use super::{IkError, IkResult, IkSolution, IkStatus, Target};
use crate::kinematics::orientation::wrap_angle;
use crate::kinematics::robot::{JointKind, Robot};

/// Which solver to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SolverChoice {
    /// The closed form if the structure has one, else numerical.
    #[default]
    Auto,
    /// The closed form only (an error if there is none).
    ClosedForm,
    /// The numerical solver only.
    Numerical,
}

/// Which solver answered.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SolverUsed {
    /// A closed form of the named family.
    ClosedForm(&'static str),
    /// The numerical solver (method name).
    Numerical(&'static str),
}

impl std::fmt::Display for SolverUsed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SolverUsed::ClosedForm(n) => write!(f, "closed form ({n})"),
            SolverUsed::Numerical(m) => write!(f, "numerical ({m})"),
        }
    }
}

/// Below this error (m or rad) a closed-form solution is not polished.
pub const POLISH_THRESHOLD: f64 = 1e-12;

/// Solves IK for end-effector `ee`. `seed_q` seeds the numerical solver (default: the "ready"
/// configuration, else zero). A numerical solve that does not converge is reported as
/// [`IkStatus::Unreachable`] with the remaining position error as the distance and the best
/// configuration found as its only solution, posture "numerical (not converged)".
pub fn solve(
    robot: &Robot,
    ee: usize,
    target: &Target,
    seed_q: Option<&[f64]>,
    choice: SolverChoice,
    opts: &NumericalOptions,
) -> Result<(IkResult, SolverUsed), IkError> {
    super::check_target(target)?;
    let cf = if ee == 0 && robot.end_effectors().len() == 1 {
        ClosedForm::detect(robot)
    } else {
        Err(NoClosedForm::SeveralEndEffectors {
            ee,
            count: robot.end_effectors().len(),
        })
    };
    match (choice, cf) {
        (SolverChoice::ClosedForm, Err(why)) => Err(IkError::NoClosedForm(why)),
        (SolverChoice::Auto | SolverChoice::ClosedForm, Ok(cf)) => {
            let mut result = cf.solve(robot, target)?;
            polish(robot, target, &mut result, opts)?;
            Ok((result, SolverUsed::ClosedForm(cf.name())))
        }
        (_, _) => {
            let default_seed = robot
                .config("ready")
                .map_or_else(|| vec![0.0; robot.dof()], <[f64]>::to_vec);
            let seed = seed_q.unwrap_or(&default_seed);
            let rep = numerical::solve(robot, ee, target, seed, opts)?;
            let within_limits = robot.within_limits(&rep.q, 1e-12);
            let status = if rep.converged {
                IkStatus::Ok
            } else {
                IkStatus::Unreachable {
                    distance: rep.position_error.max(rep.orientation_error),
                }
            };
            let posture = if rep.converged {
                "numerical"
            } else {
                "numerical (not converged)"
            };
            let (position_error, orientation_error) =
                numerical::pose_errors(robot, ee, &rep.q, target)?;
            let solution = IkSolution {
                q: rep.q,
                posture: posture.into(),
                within_limits,
                position_error,
                orientation_error,
                free_joints: Vec::new(),
            };
            let name = match opts.method {
                numerical::Method::LevenbergMarquardt => "Levenberg-Marquardt",
                numerical::Method::DampedLeastSquares => "damped least squares",
                numerical::Method::PseudoInverse => "pseudo-inverse",
                numerical::Method::Transpose => "Jacobian transpose",
            };
            Ok((
                IkResult {
                    status,
                    solutions: vec![solution],
                },
                SolverUsed::Numerical(name),
            ))
        }
    }
}

/// Runs a few Levenberg–Marquardt iterations from every closed-form solution whose error
/// exceeds [`POLISH_THRESHOLD`] (near singularities the formulas lose digits), keeping the
/// polished q only if it is closer to the target and stays on the same side of the limits.
///
/// Only full-pose targets of arms with at least six joints are polished: a positioning arm
/// handed a pose reports its orientation mismatch honestly, and LM would trade position for it.
fn polish(
    robot: &Robot,
    target: &Target,
    result: &mut IkResult,
    opts: &NumericalOptions,
) -> Result<(), IkError> {
    if !matches!(target, Target::Pose(_)) || robot.dof() < 6 {
        return Ok(());
    }
    let local = NumericalOptions {
        restarts: 0,
        max_iterations: 20,
        enforce_limits: false,
        ..*opts
    };
    for s in &mut result.solutions {
        if s.position_error.max(s.orientation_error) <= POLISH_THRESHOLD
            || !s.free_joints.is_empty()
        {
            continue;
        }
        let rep = numerical::solve(robot, 0, target, &s.q, &local)?;
        let (pe, oe) = numerical::pose_errors(robot, 0, &rep.q, target)?;
        let within = robot.within_limits(&rep.q, 1e-12);
        let better = pe <= s.position_error
            && oe <= s.orientation_error
            && pe.max(oe) < s.position_error.max(s.orientation_error);
        if better && within == s.within_limits {
            s.q = rep.q;
            s.position_error = pe;
            s.orientation_error = oe;
        }
    }
    Ok(())
}

/// Distance between two joint vectors: revolute differences wrapped into (-pi, pi].
pub fn joint_distance(robot: &Robot, a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .enumerate()
        .map(|(k, (x, y))| {
            let d = if robot.dof_joint(k).kind == JointKind::Revolute {
                wrap_angle(x - y)
            } else {
                x - y
            };
            d * d
        })
        .sum::<f64>()
        .sqrt()
}

/// The solution closest to `q` (within-limits solutions first).
pub fn closest<'a>(
    robot: &Robot,
    solutions: &'a [IkSolution],
    q: &[f64],
) -> Option<&'a IkSolution> {
    solutions.iter().min_by(|a, b| {
        (!a.within_limits, joint_distance(robot, &a.q, q))
            .partial_cmp(&(!b.within_limits, joint_distance(robot, &b.q, q)))
            .unwrap_or(std::cmp::Ordering::Equal)
    })
}

/// The solution whose posture label equals `name` (case-insensitive; words may be separated by
/// spaces, commas, dashes or underscores).
pub fn by_posture<'a>(solutions: &'a [IkSolution], name: &str) -> Option<&'a IkSolution> {
    let norm = |s: &str| {
        s.to_lowercase()
            .split(|c: char| !c.is_alphanumeric())
            .filter(|w| !w.is_empty())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let want = norm(name);
    solutions.iter().find(|s| norm(&s.posture) == want)
}
