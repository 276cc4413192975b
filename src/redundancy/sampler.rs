//! One self-motion sampler for every caller: the command line prints its samples, the app's
//! Self-motion tab plots them and the self-motion figure draws them. Exact self-motions (the SRS
//! arm angle, the offset-elbow arm's q7, the planar phi) are sampled on an even grid of their
//! parameter; any other redundant chain is walked numerically by arc length in joint space.

use super::collision::{CellScanOptions, CollisionFreeMotion};
use super::motion::ExactSelfMotion;
use super::numerical::NullSpaceMotion;
use super::{BranchSolution, RedundancyError};
use crate::collision::CollisionWorld;
use crate::kinematics::ik::Target;
use crate::kinematics::ik::numerical::{NumericalOptions, solve};
use crate::kinematics::redundancy::{Redundancy, Task};
use crate::kinematics::{Pose, Robot};
use std::f64::consts::{PI, TAU};

/// Largest arc-length step (rad of joint-space arc) of the numerical walk between samples.
const WALK_STEP: f64 = 0.01;

/// A self-motion sampled over its parameter: what every view of it is drawn from.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct SelfMotionSamples {
    /// The parameter's name: "psi", "q7", "phi", "phi_3" or "arc length".
    pub parameter: &'static str,
    /// What the parameter is, in a sentence.
    pub meaning: String,
    /// Exact (closed-form branches), or walked numerically.
    pub exact: bool,
    /// Branch names (one for a numerical walk).
    pub names: Vec<String>,
    /// Per sample: the parameter's value (rad) and every branch's solution there (a branch
    /// without a solution at that value is absent).
    pub samples: Vec<(f64, Vec<BranchSolution>)>,
    /// Per branch: the intervals of the parameter (rad) where it stays inside the joint limits
    /// (exact; for a numerical walk, the stretches of samples inside them).
    pub feasible: Vec<Vec<[f64; 2]>>,
    /// Disjoint self-motion curves inside the limits.
    pub manifolds: usize,
    /// An algorithmic singularity of the parameterization (the SRS shoulder-wrist line along
    /// axis 1).
    pub singular: bool,
    /// In a cell ([`sample_self_motion_in`]): the collision-free intervals and the colliding
    /// stretches with the pair named; `None` in empty space.
    pub collisions: Option<CollisionFreeMotion>,
}

/// `n` parameter values covering [-pi, pi) evenly (rad).
pub fn parameter_grid(n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |k| -PI + TAU * k as f64 / n as f64)
}

impl SelfMotionSamples {
    /// An exact self-motion at `n` values of its parameter ([`parameter_grid`]).
    pub fn exact(robot: &Robot, motion: &ExactSelfMotion, n: usize) -> Self {
        Self {
            parameter: motion.parameter(),
            meaning: motion.parameter_meaning().to_string(),
            exact: true,
            names: motion.names().to_vec(),
            samples: parameter_grid(n)
                .map(|v| (v, motion.solutions(robot, v)))
                .collect(),
            feasible: motion.feasible().to_vec(),
            manifolds: motion.manifolds(),
            singular: motion.singular(),
            collisions: None,
        }
    }

    /// The numerical self-motion through `start`'s configuration at `n` arc lengths covering
    /// [-pi, pi) (rad of joint-space arc), walked from s = 0 forwards and backwards in steps of at
    /// most `WALK_STEP` (0.01); a sample past a singularity has no branch. The feasible
    /// stretches come from the samples (not exact: the walk has no closed form).
    pub fn numerical(
        robot: &Robot,
        start: &NullSpaceMotion<'_>,
        n: usize,
    ) -> Result<Self, RedundancyError> {
        let name = "self-motion".to_string();
        let h = TAU / n as f64;
        let solution = |m: &NullSpaceMotion<'_>| -> Result<BranchSolution, RedundancyError> {
            let (position_error, orientation_error) = m.errors()?;
            Ok(BranchSolution {
                name: name.clone(),
                q: m.q().to_vec(),
                within_limits: robot.within_limits(m.q(), 1e-12),
                position_error,
                orientation_error,
            })
        };
        let mut samples: Vec<(f64, Vec<BranchSolution>)> = Vec::with_capacity(n);
        for forwards in [true, false] {
            let mut m = start.clone();
            let mut s = 0.0;
            let ks: Vec<usize> = if forwards {
                (n / 2..n).collect()
            } else {
                (0..n / 2).rev().collect()
            };
            for k in ks {
                let value = -PI + h * k as f64;
                while (value - s).abs() > 1e-12 {
                    let ds = (value - s).clamp(-WALK_STEP, WALK_STEP);
                    if m.step(ds).is_err() {
                        break;
                    }
                    s += ds;
                }
                let branch = if (value - s).abs() <= 1e-12 {
                    vec![solution(&m)?]
                } else {
                    Vec::new()
                };
                samples.push((value, branch));
            }
        }
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut feasible: Vec<[f64; 2]> = Vec::new();
        for (v, b) in &samples {
            if b.first().is_some_and(|x| x.within_limits) {
                match feasible.last_mut() {
                    Some(l) if (l[1] - (v - h)).abs() < 1e-9 => l[1] = *v,
                    _ => feasible.push([*v, *v]),
                }
            }
        }
        Ok(Self {
            parameter: "arc length",
            meaning: "arc length s walked in joint space along the null space (numerical: the \
                      curve through the IK solution; feasible stretches from the samples)"
                .into(),
            exact: false,
            names: vec![name],
            samples,
            feasible: vec![feasible],
            manifolds: 1,
            singular: false,
            collisions: None,
        })
    }

    /// Keeps branch `name` only; `Err` lists the branches when there is none of that name.
    pub fn keep_branch(&mut self, name: &str) -> Result<(), RedundancyError> {
        let Some(k) = self.names.iter().position(|n| n == name) else {
            return Err(RedundancyError::NoBranch {
                name: name.to_string(),
                branches: self.names.join("; "),
            });
        };
        for (_, s) in &mut self.samples {
            s.retain(|x| x.name == name);
        }
        self.names = vec![self.names[k].clone()];
        self.feasible = vec![self.feasible[k].clone()];
        if let Some(c) = &mut self.collisions {
            c.free = vec![c.free[k].clone()];
            c.colliding.retain(|s| s.branch == k);
            for s in &mut c.colliding {
                s.branch = 0;
            }
        }
        Ok(())
    }
}

/// Whether the robot has the shape of an exact self-motion (an SRS arm, an offset-elbow arm, a
/// planar arm of 2 to 4 joints), so that a failure there is the pose's, not a reason to fall
/// back on the numerical walk.
pub fn has_exact_shape(robot: &Robot) -> bool {
    super::srs::SrsArm::detect(robot).is_some()
        || super::offset_elbow::OffsetElbowArm::detect(robot).is_some()
        || (crate::workspace::planar_frame(robot, 0).is_some() && matches!(robot.dof(), 2..=4))
}

/// The self-motion of end-effector `ee` holding `pose` (world, m), at `n` samples: exact where
/// the arm has an exact self-motion (end-effector 0), else the numerical walk through the
/// configuration that numerical IK finds from the "ready" configuration (or zero).
pub fn sample_self_motion(
    robot: &Robot,
    ee: usize,
    pose: &Pose,
    n: usize,
) -> Result<SelfMotionSamples, RedundancyError> {
    sample_self_motion_locked(robot, ee, pose, n, None)
}

/// [`sample_self_motion`] with joint `locked` (0-based) of a seven-revolute arm as the
/// parameter ([`ExactSelfMotion::with_lock`]); `None` as [`sample_self_motion`].
pub fn sample_self_motion_locked(
    robot: &Robot,
    ee: usize,
    pose: &Pose,
    n: usize,
    locked: Option<usize>,
) -> Result<SelfMotionSamples, RedundancyError> {
    sample_self_motion_in(robot, ee, pose, n, locked, None)
}

/// [`sample_self_motion_locked`] in a cell: with `world` (the robot and a cell's obstacles),
/// the samples carry the collision-free intervals ([`ExactSelfMotion::collision_free`] with
/// the default [`CellScanOptions`]). A self-motion walked numerically has none to refine:
/// [`RedundancyError::CellNeedsExact`].
pub fn sample_self_motion_in(
    robot: &Robot,
    ee: usize,
    pose: &Pose,
    n: usize,
    locked: Option<usize>,
    world: Option<&CollisionWorld>,
) -> Result<SelfMotionSamples, RedundancyError> {
    let in_cell = |m: &ExactSelfMotion| {
        let mut s = SelfMotionSamples::exact(robot, m, n);
        s.collisions = world.map(|w| m.collision_free(robot, w, CellScanOptions::default()));
        s
    };
    if locked.is_some() {
        let m = ExactSelfMotion::with_lock(robot, pose, locked)?;
        return Ok(in_cell(&m));
    }
    if ee == 0 {
        match ExactSelfMotion::new(robot, pose) {
            Ok(m) => return Ok(in_cell(&m)),
            Err(e) if e.unsupported() && !has_exact_shape(robot) => {}
            Err(e) => return Err(e),
        }
    }
    if world.is_some() {
        return Err(RedundancyError::CellNeedsExact {
            robot: robot.name.clone(),
        });
    }
    let red = Redundancy::of(robot, Task::Pose);
    if red.degree() <= 0 {
        return Err(RedundancyError::NotRedundant {
            robot: robot.name.clone(),
            redundancy: red.to_string(),
        });
    }
    let seed = robot.ready_or_zero();
    let rep = solve(
        robot,
        ee,
        &Target::Pose(*pose),
        &seed,
        &NumericalOptions::default(),
    )?;
    if !rep.converged {
        return Err(RedundancyError::NotReached {
            position_error: rep.position_error,
            orientation_error: rep.orientation_error,
        });
    }
    let start = NullSpaceMotion::new(robot, ee, &rep.q, None)?;
    SelfMotionSamples::numerical(robot, &start, n)
}
