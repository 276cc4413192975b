//! One entry point for IK: the closed form when the arm's structure has one (every solution,
//! polished numerically where that helps), the numerical solver otherwise (seeded with the
//! caller's q); plus picking a solution by posture or by closeness to a configuration.

use super::closed_form::{ClosedForm, Family, NoClosedForm, Posture};
use super::numerical::{self, NumericalOptions};
use super::{FreeJoint, IkError, IkResult, IkSolution, IkStatus, SolutionPosture, Target};
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
///
/// # Examples
///
/// One call for any arm: the Puma 560 gets its eight closed-form solutions, the seven-joint
/// KUKA LWR-IV (no closed form for a pose) the numerical solver, seeded here with a nearby
/// configuration.
///
/// ```
/// use armlab::kinematics::ik::numerical::NumericalOptions;
/// use armlab::kinematics::ik::solver::{SolverChoice, SolverUsed, solve};
/// use armlab::kinematics::ik::{IkStatus, Target};
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let opts = NumericalOptions::default();
///
/// let puma = built_in("puma560").expect("a built-in model");
/// let target = Target::Pose(puma.fk(&[0.3, -0.5, 0.2, 0.4, 0.9, -0.1])?);
/// let (result, used) = solve(&puma, 0, &target, None, SolverChoice::Auto, &opts)?;
/// assert!(matches!(used, SolverUsed::ClosedForm(_)));
/// assert_eq!(result.solutions.len(), 8);
///
/// let lwr = built_in("lwr4").expect("a built-in model");
/// let goal = [0.2, 0.6, -0.3, -1.4, 0.2, 0.7, 0.1];
/// let target = Target::Pose(lwr.fk(&goal)?);
/// let seed = [0.0, 0.5, 0.0, -1.2, 0.0, 0.5, 0.0];
/// let (result, used) = solve(&lwr, 0, &target, Some(&seed), SolverChoice::Auto, &opts)?;
/// assert_eq!(used, SolverUsed::Numerical("Levenberg-Marquardt"));
/// assert_eq!(result.status, IkStatus::Ok);
/// let s = &result.solutions[0];
/// assert!(s.position_error < 1e-9 && s.orientation_error < 1e-9);
/// println!("{used}: {} q = {:?}", s.posture.to_string(), s.q);
/// # Ok(())
/// # }
/// ```
///
/// Asking for the closed form of an arm without one is an error that says why:
///
/// ```
/// use armlab::kinematics::ik::numerical::NumericalOptions;
/// use armlab::kinematics::ik::solver::{SolverChoice, solve};
/// use armlab::kinematics::ik::{IkError, Target};
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let lwr = built_in("lwr4").expect("a built-in model");
/// let target = Target::Pose(lwr.fk(&lwr.ready_or_zero())?);
/// let err = solve(&lwr, 0, &target, None, SolverChoice::ClosedForm, &NumericalOptions::default())
///     .unwrap_err();
/// assert!(matches!(err, IkError::NoClosedForm(_)));
/// println!("{err}"); // "no closed-form solver matches this arm's structure (7 joints: ...)"
/// # Ok(())
/// # }
/// ```
pub fn solve(
    robot: &Robot,
    ee: usize,
    target: &Target,
    seed_q: Option<&[f64]>,
    choice: SolverChoice,
    opts: &NumericalOptions,
) -> Result<(IkResult, SolverUsed), IkError> {
    super::check_target(target)?;
    if robot.end_effectors().len() > 1 {
        return solve_arm(robot, ee, target, seed_q, choice, opts);
    }
    let cf = if ee == 0 {
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
            if *cf.family() == Family::General6 && result.solutions.is_empty() {
                return singular_general(robot, &cf, target, seed_q, opts);
            }
            if cf.near_miss().is_some() {
                polish_near_miss(robot, target, &mut result, opts)?;
            } else {
                polish(robot, target, &mut result, opts)?;
            }
            Ok((result, SolverUsed::ClosedForm(cf.name())))
        }
        (_, _) => {
            let default_seed = robot.ready_or_zero();
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
            let posture = SolutionPosture::Numerical {
                converged: rep.converged,
            };
            let (position_error, orientation_error) =
                numerical::pose_errors(robot, ee, &rep.q, target)?;
            let solution = IkSolution {
                q: rep.q,
                posture,
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

/// Starts of the search at a pose where the general elimination finds no solution.
const SINGULAR_STARTS: usize = 24;

/// How the solutions of [`singular_general`] are found.
const SINGULAR_SOLVER: &str = "Levenberg-Marquardt from several starts: the elimination found \
                               no solution at this pose (its roots are multiple, the pose is \
                               singular, or out of reach)";

/// Why a joint of a [`singular_general`] solution is free.
const SINGULAR_FREE: &str = "a singular pose of a general arm: this joint and the ones it \
                             couples with move together without moving the hand";

/// A general six-revolute arm at a pose where the elimination finds no solution: its roots are
/// multiple, so that no null vector picks the other joints (the Unitree Z1 at every pose with
/// q5 = 0: each root of the eliminant is fourfold), the solutions form a continuum (a singular
/// pose), or the pose is out of reach. Levenberg-Marquardt tells them apart, started from the
/// elimination's solutions at slightly turned poses (a regular solution persists under a small
/// change of the pose, and there the roots are simple) and from spread configurations: its
/// converged solutions, one per family (two belong to one family when they differ along the
/// Jacobian's null direction), each singular one with the
/// joint that moves most along that direction marked free and the status
/// [`IkStatus::Singular`]; or, when none converges, out of reach by the least error found
/// (not the infinite distance the elimination alone would report).
fn singular_general(
    robot: &Robot,
    cf: &ClosedForm,
    target: &Target,
    seed_q: Option<&[f64]>,
    opts: &NumericalOptions,
) -> Result<(IkResult, SolverUsed), IkError> {
    let local = NumericalOptions {
        restarts: 0,
        max_iterations: 100,
        enforce_limits: false,
        tolerance: 1e-12,
        ..*opts
    };
    let n = robot.dof();
    let starts = singular_starts(robot, cf, target, seed_q);
    let mut found: Vec<(IkSolution, Option<Vec<f64>>)> = Vec::new();
    let mut least = f64::INFINITY;
    for start in &starts {
        let rep = numerical::solve(robot, 0, target, start, &local)?;
        let (pe, oe) = numerical::pose_errors(robot, 0, &rep.q, target)?;
        least = least.min(pe.max(oe));
        if pe.max(oe) > 1e-10 {
            continue;
        }
        let null = null_direction(robot, &rep.q)?;
        if found
            .iter()
            .any(|(s, dir)| same_family(&s.q, &rep.q, dir.as_deref()))
        {
            continue;
        }
        let free_joints = null
            .as_ref()
            .and_then(|u| (0..n).max_by(|&a, &b| u[a].abs().total_cmp(&u[b].abs())))
            .map(|index| FreeJoint {
                index,
                reason: SINGULAR_FREE,
            })
            .into_iter()
            .collect();
        let within_limits = robot.within_limits(&rep.q, 1e-12);
        found.push((
            IkSolution {
                q: rep.q,
                // Numbered by `labelled_branches` below.
                posture: SolutionPosture::ClosedForm(Posture::default()),
                within_limits,
                position_error: pe,
                orientation_error: oe,
                free_joints,
            },
            null,
        ));
    }
    let singular = found.iter().any(|(_, dir)| dir.is_some());
    let solutions = labelled_branches(found.into_iter().map(|(s, _)| s).collect());
    let status = if solutions.is_empty() {
        IkStatus::Unreachable { distance: least }
    } else if singular {
        IkStatus::Singular
    } else {
        IkStatus::Ok
    };
    Ok((
        IkResult { status, solutions },
        SolverUsed::Numerical(SINGULAR_SOLVER),
    ))
}

/// The starts of the singular search: the elimination's solutions at three slightly nudged
/// poses (where its roots separate), the seed, the ready pose and a fixed spread of
/// configurations within the limits (at most ±π), in joint space (rad or m).
fn singular_starts(
    robot: &Robot,
    cf: &ClosedForm,
    target: &Target,
    seed_q: Option<&[f64]>,
) -> Vec<Vec<f64>> {
    let n = robot.dof();
    let limits = robot.limits();
    let mut starts: Vec<Vec<f64>> = Vec::new();
    if let Target::Pose(t) = target {
        // Turned by 1e-5 and 3e-5 rad about two axes and moved by as many metres.
        for (k, e) in [1e-5, -3e-5, 2e-5].into_iter().enumerate() {
            let axis = nalgebra::Unit::new_normalize(nalgebra::Vector3::new(1.0, k as f64, 0.5));
            let nudge = crate::kinematics::Pose::from_parts(
                nalgebra::Translation3::new(e, -e, e),
                nalgebra::Rotation3::from_axis_angle(&axis, e),
            );
            if let Ok(near) = cf.solve(robot, &Target::Pose(nudge * t)) {
                starts.extend(near.solutions.into_iter().map(|s| s.q));
            }
        }
    }
    starts.extend(seed_q.map(<[f64]>::to_vec));
    starts.push(robot.ready_or_zero());
    let spread_end = starts.len() + SINGULAR_STARTS;
    // Spread starts, the same every time (a small linear congruential sequence).
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    while starts.len() < spread_end {
        starts.push(
            (0..n)
                .map(|k| {
                    state = state
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1_442_695_040_888_963_407);
                    let u = (state >> 11) as f64 / (1u64 << 53) as f64;
                    let [lo, hi] = limits[k];
                    let (lo, hi) = (lo.max(-std::f64::consts::PI), hi.min(std::f64::consts::PI));
                    lo + (hi - lo) * u
                })
                .collect(),
        );
    }
    starts
}

/// Whether configuration `b` lies on the same solution as `a`: equal up to angle wrapping, or
/// differing only along `dir`, the unit joint-space direction in which a singular solution's
/// hand stays still (to 1e-6).
fn same_family(a: &[f64], b: &[f64], dir: Option<&[f64]>) -> bool {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| wrap_angle(y - x)).collect();
    let along = dir.map_or(0.0, |u| d.iter().zip(u).map(|(x, y)| x * y).sum::<f64>());
    let off = d
        .iter()
        .enumerate()
        .map(|(k, x)| x - along * dir.map_or(0.0, |u| u[k]))
        .map(|x| x * x)
        .sum::<f64>();
    off.sqrt() < 1e-6
}

/// Sorts solutions by their wrapped joint values and names them "branch k" in that order.
fn labelled_branches(mut solutions: Vec<IkSolution>) -> Vec<IkSolution> {
    solutions.sort_by(|a, b| {
        let key = |s: &IkSolution| s.q.iter().map(|v| wrap_angle(*v)).collect::<Vec<_>>();
        key(a)
            .partial_cmp(&key(b))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for (k, s) in solutions.iter_mut().enumerate() {
        s.posture = SolutionPosture::ClosedForm(Posture {
            branch: Some(u8::try_from(k + 1).unwrap_or(u8::MAX)),
            ..Posture::default()
        });
    }
    solutions
}

/// The unit direction in joint space along which the hand does not move at q (the Jacobian's
/// right singular vector of its least singular value), where that value is below 1e-6 of the
/// largest; `None` at a regular configuration.
fn null_direction(robot: &Robot, q: &[f64]) -> Result<Option<Vec<f64>>, IkError> {
    let jac = robot.jacobian(q, 0)?;
    let svd = jac.svd(false, true);
    let sv = &svd.singular_values;
    let Some(v_t) = svd.v_t.as_ref() else {
        return Ok(None);
    };
    let (k, least) = sv
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(k, v)| (k, *v))
        .unwrap_or((0, f64::INFINITY));
    if least > 1e-6 * sv.max() {
        return Ok(None);
    }
    Ok(Some(v_t.row(k).iter().copied().collect()))
}

/// [`solve`] for end-effector `ee` of a robot with several: the arm to it is solved alone
/// ([`crate::kinematics::arm`]: the joints off its chain stay at their values in `seed_q`, or
/// in the "ready" configuration, or zero) and every solution is the whole robot's q.
fn solve_arm(
    robot: &Robot,
    ee: usize,
    target: &Target,
    seed_q: Option<&[f64]>,
    choice: SolverChoice,
    opts: &NumericalOptions,
) -> Result<(IkResult, SolverUsed), IkError> {
    robot.end_effector(ee)?;
    let base = match seed_q {
        Some(q) => q.to_vec(),
        None => robot.ready_or_zero(),
    };
    let arm = crate::kinematics::arm::arm_of(robot, ee, &base).map_err(|e| IkError::Arm {
        ee: robot.end_effectors()[ee].name.clone(),
        reason: e.to_string(),
    })?;
    let seed = arm.restrict(&base);
    let (mut result, used) = solve(&arm.robot, 0, target, Some(&seed), choice, opts)?;
    for s in &mut result.solutions {
        let mut full = base.clone();
        arm.expand(&s.q, &mut full);
        s.q = full;
        // The arm's own joints decide (the arm's solve set the flag on them): a joint off the
        // chain, a gripper's finger at 0 below its [0.015, 0.037] m, never makes an arm's
        // solution infeasible.
        s.within_limits = robot.within_limits_for(ee, &s.q, 1e-12);
        for f in &mut s.free_joints {
            f.index = arm.free[f.index];
        }
    }
    Ok((result, used))
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
        tolerance: POLISH_THRESHOLD / 10.0,
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
        // Better: the larger error falls, and neither grows above 1e-13 (an orientation error
        // at 1e-16 may rise to 1e-14 while the position falls from 3e-12: a calibrated arm
        // solved by the general 6R elimination was left at 3e-12 m before).
        let rounding = 1e-13;
        let better = pe <= s.position_error.max(rounding)
            && oe <= s.orientation_error.max(rounding)
            && pe.max(oe) < s.position_error.max(s.orientation_error);
        if better && within == s.within_limits {
            s.q = rep.q;
            s.position_error = pe;
            s.orientation_error = oe;
        }
    }
    Ok(())
}

/// Below this error (m or rad) a solution of a near-miss closed form counts as one of the
/// exact model.
pub const NEAR_MISS_CHECK: f64 = 1e-12;

/// Newton steps from a closed-form solution of a nearby structure: no restarts, no limits,
/// to a tenth of [`NEAR_MISS_CHECK`], little damping.
fn near_miss_options(opts: &NumericalOptions) -> NumericalOptions {
    NumericalOptions {
        restarts: 0,
        max_iterations: 30,
        enforce_limits: false,
        tolerance: NEAR_MISS_CHECK / 10.0,
        damping: opts.damping.min(1e-6),
        ..*opts
    }
}

/// A near-miss closed form's solutions are the ideal structure's: each is polished by Newton
/// (Levenberg-Marquardt without damping to speak of) on the exact model, whatever the target,
/// keeping its posture label, and only those whose forward kinematics then meets the target to
/// [`NEAR_MISS_CHECK`] are kept (a target reached only approximately, by a pose the family
/// cannot orient, keeps its honest error unpolished).
fn polish_near_miss(
    robot: &Robot,
    target: &Target,
    result: &mut IkResult,
    opts: &NumericalOptions,
) -> Result<(), IkError> {
    let local = near_miss_options(opts);
    // Only where the family controls the whole target can every solution be held to the check.
    let whole = match target {
        Target::Pose(_) => robot.dof() >= 6,
        Target::Position(_) => true,
        _ => false,
    };
    let mut kept = Vec::with_capacity(result.solutions.len());
    for mut s in std::mem::take(&mut result.solutions) {
        let before = s.position_error.max(s.orientation_error);
        if before > NEAR_MISS_CHECK && s.free_joints.is_empty() {
            let rep = numerical::solve(robot, 0, target, &s.q, &local)?;
            let (pe, oe) = numerical::pose_errors(robot, 0, &rep.q, target)?;
            if pe.max(oe) < before {
                s.within_limits = robot.within_limits(&rep.q, 1e-12);
                s.q = rep.q;
                s.position_error = pe;
                s.orientation_error = oe;
            }
        }
        // An unreachable target's best effort is kept as it is (its error is the distance).
        let reached = s.position_error.max(s.orientation_error) <= NEAR_MISS_CHECK;
        if reached || !whole || matches!(result.status, IkStatus::Unreachable { .. }) {
            kept.push(s);
        }
    }
    result.solutions = kept;
    Ok(())
}

/// IK of `robot` through the closed form of `reference`, a model of the same arm whose
/// structure has one (a calibrated arm and its nominal model, whose parallel or intersecting
/// axes the calibration moved by a fraction of a degree): every posture of the reference,
/// each polished by Newton steps on `robot`'s own FK until its pose error is at most
/// [`NEAR_MISS_CHECK`] (m and rad), labelled as the reference labels that configuration (the
/// label of its closed-form solution at `FK_reference(q)`). A posture that does not converge is
/// dropped (the target is out of the real arm's reach in that posture); two that converge to
/// one configuration are merged, the first label kept. Full-pose targets of a 6-joint arm.
pub fn solve_from_reference(
    robot: &Robot,
    reference: &Robot,
    target: &Target,
    opts: &NumericalOptions,
) -> Result<(IkResult, SolverUsed), IkError> {
    super::check_target(target)?;
    let cf = ClosedForm::detect(reference).map_err(IkError::NoClosedForm)?;
    if robot.dof() != reference.dof() || robot.end_effectors().len() != 1 {
        return Err(IkError::TargetKind {
            target: "pose",
            solver: cf.name(),
            hint: "the robot and its reference must be one arm with the same joints",
        });
    }
    let mut result = cf.solve(reference, target)?;
    polish(reference, target, &mut result, opts)?;
    let local = near_miss_options(opts);
    let mut kept: Vec<IkSolution> = Vec::with_capacity(result.solutions.len());
    let mut closest = f64::INFINITY;
    for s in result.solutions {
        if !s.free_joints.is_empty() {
            continue;
        }
        let rep = numerical::solve(robot, 0, target, &s.q, &local)?;
        let (pe, oe) = numerical::pose_errors(robot, 0, &rep.q, target)?;
        closest = closest.min(pe.max(oe));
        if pe.max(oe) > NEAR_MISS_CHECK
            || kept
                .iter()
                .any(|k| joint_distance(robot, &k.q, &rep.q) < 1e-9)
        {
            continue;
        }
        // The label the reference gives this configuration: near a singularity the polish may
        // cross to the other member of a pair (theta5 changing sign), and a controller running
        // the reference model, sent FK_reference(q), must find q under this label.
        let at = Target::Pose(reference.fk(&rep.q)?);
        let posture = cf
            .solve(reference, &at)?
            .solutions
            .into_iter()
            .find(|o| joint_distance(robot, &o.q, &rep.q) < 1e-6)
            .map_or(s.posture, |o| o.posture);
        kept.push(IkSolution {
            within_limits: robot.within_limits(&rep.q, 1e-12),
            q: rep.q,
            position_error: pe,
            orientation_error: oe,
            posture,
            ..s
        });
    }
    let status = if kept.is_empty() {
        IkStatus::Unreachable { distance: closest }
    } else {
        IkStatus::Ok
    };
    Ok((
        IkResult {
            status,
            solutions: kept,
        },
        SolverUsed::ClosedForm(cf.name()),
    ))
}

/// Distance between two joint vectors: revolute differences wrapped into (-pi, pi].
///
/// # Examples
///
/// ```
/// use armlab::kinematics::ik::solver::joint_distance;
/// use armlab::kinematics::models::built_in;
/// use std::f64::consts::TAU;
///
/// let scara = built_in("scara").expect("a built-in model"); // R-R-P-R
/// // A full turn of a revolute joint is no distance; a prismatic joint's metres count.
/// let d = joint_distance(&scara, &[0.1, 0.2, 0.05, 0.3], &[0.1 + TAU, 0.2, 0.02, 0.3]);
/// assert!((d - 0.03).abs() < 1e-12);
/// ```
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
///
/// # Examples
///
/// ```
/// use armlab::kinematics::ik::numerical::NumericalOptions;
/// use armlab::kinematics::ik::solver::{SolverChoice, closest, solve};
/// use armlab::kinematics::ik::Target;
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let current = [0.3, -0.5, 0.2, 0.4, 0.9, -0.1];
/// let target = Target::Pose(puma.fk(&current)?);
/// let opts = NumericalOptions::default();
/// let (result, _) = solve(&puma, 0, &target, None, SolverChoice::Auto, &opts)?;
/// let best = closest(&puma, &result.solutions, &current).expect("solutions");
/// assert!(best.q.iter().zip(&current).all(|(a, b)| (a - b).abs() < 1e-9));
/// # Ok(())
/// # }
/// ```
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

/// The solution whose posture label equals `name`, text a user typed (case-insensitive; words
/// may be separated by spaces, commas, dashes or underscores): compared with each posture's
/// `Display`.
pub fn by_posture<'a>(solutions: &'a [IkSolution], name: &str) -> Option<&'a IkSolution> {
    let norm = |s: &str| {
        s.to_lowercase()
            .split(|c: char| !c.is_alphanumeric())
            .filter(|w| !w.is_empty())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let want = norm(name);
    solutions
        .iter()
        .find(|s| norm(&s.posture.to_string()) == want)
}
