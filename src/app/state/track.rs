//! Solving IK for a moved target every frame, and the posture lock.
//!
//! Arms with a closed form (a family of [`crate::kinematics::ik::closed_form`], on a tree the
//! arm of the dragged end-effector alone) get every solution; one is chosen:
//!
//! - **unlocked**: the within-limits solution closest in joint space to the current q
//!   ([`joint_distance`]: revolute differences wrapped into (-pi, pi]);
//! - **locked**: the solution with the locked posture label (for a general six-revolute arm,
//!   whose "branch k" has no geometric meaning, the solution that continues from the current q;
//!   its number stays with it while the target moves, [`continue_numbers`]). Labels change
//!   meaning only at
//!   singularities (the wrist passing through sin(theta5) = 0 continues as the "flip" branch, for
//!   instance), so when the previous q is near a singularity (a singularity measure below
//!   [`BRANCH_SWITCH_MEASURE`], the conditioning ratio below [`NEAR_RATIO`], or a degenerate
//!   solution among the new ones) and another within-limits solution is closer by more than
//!   [`BRANCH_SWITCH_MARGIN`], that one is taken and the lock follows its label (an info
//!   message says so). Where the locked label is absent
//!   because the pair merged ("elbow stretched"), the closest within-limits solution is taken and
//!   the lock keeps its label. If the locked solution is outside the limits, the arm stays put.
//!
//! Degenerate solutions (a free joint) are moved along their family to the current values of the
//! free joints before the choice (the free joints held, a short Levenberg–Marquardt run for the
//! others), so crossing a
//! singularity does not snap the free joint to the closed form's representative value. Revolute
//! angles are shifted by 2 pi towards the current q where the limits allow.
//!
//! Other arms use the numerical solver (Levenberg–Marquardt, no restarts) seeded with the current
//! q, full pose if the task rank is 6, position otherwise. With several end-effectors the joints
//! on the other end-effectors' chains (the humanoid's torso) are held, so that dragging one hand
//! does not move the other.
//!
//! Whatever the solver, a target it cannot reach leaves q unchanged (no jump, no NaN) and flags
//! the target with a [`Reach`] that says how far out it is.

use super::{AppState, Level, Reach};
use crate::kinematics::Robot;
use crate::kinematics::hold::{Held, hold_joints, hold_other_chains};
use crate::kinematics::ik::branches::continue_numbers;
use crate::kinematics::ik::closed_form::Family;
use crate::kinematics::ik::numerical::{self, NumericalOptions};
use crate::kinematics::ik::solver::{self, SolverChoice, joint_distance};
use crate::kinematics::ik::{IkResult, IkSolution, IkStatus, SolutionPosture, Target};
use crate::kinematics::orientation::wrap_angle;
use crate::kinematics::pose::{Pose, rot_z};
use crate::kinematics::singularity::NEAR_RATIO;

/// A geometric singularity measure (see [`crate::kinematics::singularity`]: a sine, or a distance over
/// the robot's size) below which the previous configuration counts as near a singularity, where
/// a locked posture label may change meaning. The Jacobian's conditioning ratio below
/// [`NEAR_RATIO`] counts as well.
pub const BRANCH_SWITCH_MEASURE: f64 = 0.1;
/// How much closer (joint-space norm, rad / m) another solution must be than the locked one for
/// the lock to follow it near a singularity.
pub const BRANCH_SWITCH_MARGIN: f64 = 0.1;
/// Slack (rad or m) on the joint limits when shifting angles by 2 pi.
const LIMIT_SLACK: f64 = 1e-12;

/// Options of the numerical tracking solver: no restarts (a restart could jump to another
/// branch), 100 iterations, 1e-9 m / rad tolerance.
pub fn tracking_options() -> NumericalOptions {
    NumericalOptions {
        restarts: 0,
        max_iterations: 100,
        tolerance: 1e-9,
        ..NumericalOptions::default()
    }
}

/// The decision of one tracking step.
enum Choice {
    /// Adopt solution `index`; `follow` = the lock follows its label.
    Pick { index: usize, follow: bool },
    /// Stay put.
    Freeze(Reach),
}

/// Whether the closed-form family solves a full pose of the last frame (else a point).
fn solves_frame(family: Option<Family>) -> bool {
    family.is_some_and(|f| f.uses_frame())
}

impl AppState {
    /// The closed-form family of end-effector `ee`'s arm: the robot's own for a single chain,
    /// the arm's alone on a tree (a Jaco's fingers do not take its closed form away).
    pub(super) fn family_of(&self, ee: usize) -> Option<Family> {
        if self.robot.end_effectors().len() == 1 {
            self.analyzer.family().filter(|_| ee == 0)
        } else {
            self.arm_report(ee).and_then(|r| r.family)
        }
    }

    /// Whether the closed-form path applies to end-effector `ee`.
    pub(super) fn uses_closed_form(&self, ee: usize) -> bool {
        self.family_of(ee).is_some() && self.task == super::full_task(&self.robot)
    }

    /// Solves IK for target `ee` and moves the arm (or freezes it).
    pub(super) fn solve_target(&mut self, ee: usize) {
        if self.uses_closed_form(ee) {
            self.track_closed_form(ee);
        } else {
            self.track_numerical(ee);
        }
    }

    /// Every closed-form solution of end-effector `ee` for `world_from_tool` (on a tree its arm
    /// alone moves), degenerate ones aligned with the current q and angles shifted towards it.
    pub(super) fn closed_form_solutions(
        &self,
        ee: usize,
        world_from_tool: &Pose,
    ) -> Result<IkResult, String> {
        let target = Target::Pose(*world_from_tool);
        let (mut result, _) = solver::solve(
            &self.robot,
            ee,
            &target,
            Some(&self.q),
            SolverChoice::ClosedForm,
            &tracking_options(),
        )
        .map_err(|e| e.to_string())?;
        for s in &mut result.solutions {
            if !s.free_joints.is_empty() {
                self.align(s, world_from_tool, ee);
            }
            self.shift_towards_q(&mut s.q);
        }
        // A general arm's branches keep their numbers while the target moves.
        if self.family_of(ee).is_some_and(|f| f.numbered_branches())
            && let Some(previous) = &self.targets[ee].result
        {
            continue_numbers(&self.robot, &previous.solutions, &mut result.solutions);
        }
        Ok(result)
    }

    fn track_closed_form(&mut self, ee: usize) {
        let t = self.targets[ee].world_from_tool;
        let result = match self.closed_form_solutions(ee, &t) {
            Ok(r) => r,
            Err(reason) => return self.freeze(ee, None, Reach::Invalid { reason }),
        };
        if let IkStatus::Unreachable { distance } = result.status {
            return self.freeze(ee, Some(result), Reach::Unreachable { distance });
        }
        let degenerate = result
            .solutions
            .iter()
            .any(|s| !s.free_joints.is_empty() || s.posture.is_merged());
        match self.choose(ee, &result.solutions, degenerate) {
            Choice::Pick { index, follow } => self.adopt(ee, result, index, follow),
            Choice::Freeze(reach) => self.freeze(ee, Some(result), reach),
        }
    }

    fn choose(&self, ee: usize, sols: &[IkSolution], degenerate: bool) -> Choice {
        let dist = |s: &IkSolution| joint_distance(&self.robot, &s.q, &self.q);
        let closest_in = sols
            .iter()
            .enumerate()
            .filter(|(_, s)| s.within_limits)
            .min_by(|a, b| dist(a.1).total_cmp(&dist(b.1)))
            .map(|(i, _)| i);
        let locked = if self.lock {
            self.targets[ee].posture
        } else {
            None
        };
        let pick = |index| Choice::Pick {
            index,
            follow: false,
        };
        let outside =
            |posture: Option<SolutionPosture>| Choice::Freeze(Reach::OutsideLimits { posture });
        let Some(label) = locked else {
            return closest_in.map_or_else(|| outside(None), pick);
        };
        // A general arm's "branch k" is not a geometric posture: its branch is the one that
        // continues from the current q (numbered by continuity in `closed_form_solutions`).
        if self.family_of(ee) == Some(Family::General6) {
            let closest =
                (0..sols.len()).min_by(|&a, &b| dist(&sols[a]).total_cmp(&dist(&sols[b])));
            return match closest {
                Some(c) if sols[c].within_limits => pick(c),
                _ => outside(Some(label)),
            };
        }
        let same = sols.iter().position(|s| s.posture.same_label(&label));
        let Some(i) = same else {
            return closest_in.map_or_else(|| outside(Some(label)), pick);
        };
        let near = degenerate || self.near_singularity(ee);
        if near
            && let Some(c) = closest_in
            && c != i
            && dist(&sols[c]) + BRANCH_SWITCH_MARGIN < dist(&sols[i])
        {
            return Choice::Pick {
                index: c,
                follow: true,
            };
        }
        if sols[i].within_limits {
            pick(i)
        } else {
            outside(Some(label))
        }
    }

    /// Whether the current q is near a singularity in the sense of [`BRANCH_SWITCH_MEASURE`].
    fn near_singularity(&self, ee: usize) -> bool {
        let (robot, q) = (&self.robot, &self.q);
        let ratio = self.analyzer.conditioning(robot, q, ee).unwrap_or(0.0);
        let measure = self
            .analyzer
            .measures(robot, q, ee)
            .ok()
            .and_then(|m| m.first().map(|c| c.measure))
            .unwrap_or(f64::INFINITY);
        ratio < NEAR_RATIO || measure < BRANCH_SWITCH_MEASURE
    }

    /// Moves the arm to solution `index` of `result` for target `ee`.
    fn adopt(&mut self, ee: usize, result: IkResult, index: usize, follow: bool) {
        let sol = &result.solutions[index];
        let q = sol.q.clone();
        let label = sol.posture;
        let lock = self.lock;
        let t = &mut self.targets[ee];
        let mut note = None;
        if !label.is_merged() {
            let old = t.posture.replace(label);
            if let Some(old) = old
                && !old.same_label(&label)
                && !old.is_merged()
            {
                note = if follow && lock {
                    Some(format!(
                        "posture lock: through the singularity the branch continues as \
                         \"{label}\" (was \"{old}\")"
                    ))
                } else if !lock {
                    // the closest solution is another posture: said, never silent
                    Some(format!(
                        "the posture changed to \"{label}\" (was \"{old}\"), the closest \
                         solution; L locks the posture"
                    ))
                } else {
                    None
                };
            }
        }
        let was_reached = t.reach.is_reached();
        t.selected = Some(index);
        t.result = Some(result);
        t.reach = Reach::Reached;
        let name = t.name.clone();
        self.recheck_solutions(ee);
        if let Some(n) = note {
            self.push_message(Level::Info, n);
        }
        if !was_reached {
            self.push_message(Level::Info, format!("{name}: target reached again"));
        }
        self.apply_q(q, Some(ee));
    }

    /// Keeps q; flags target `ee`.
    fn freeze(&mut self, ee: usize, result: Option<IkResult>, reach: Reach) {
        let t = &mut self.targets[ee];
        let announce = std::mem::discriminant(&t.reach) != std::mem::discriminant(&reach);
        t.result = result;
        t.selected = None;
        t.reach = reach;
        if announce && let Some(m) = t.reach.message() {
            let m = format!("{}: {m}", t.name);
            self.push_message(Level::Warning, m);
        }
        self.recheck_solutions(ee);
    }

    /// Moves the free joints of a degenerate solution to their current values and re-solves the
    /// other joints (free ones held) by a short Levenberg–Marquardt run; kept only if it still
    /// reaches the target.
    fn align(&self, s: &mut IkSolution, world_from_tool: &Pose, ee: usize) {
        let frame = solves_frame(self.family_of(ee));
        let target = if frame {
            Target::Pose(*world_from_tool)
        } else {
            Target::Position(world_from_tool.translation.vector)
        };
        let mut start = s.q.clone();
        let mut held = vec![false; start.len()];
        for f in &s.free_joints {
            start[f.index] = self.q[f.index];
            held[f.index] = true;
        }
        let Some(Held {
            robot: reduced,
            free,
        }) = hold_joints(&self.robot, &start, &held)
        else {
            return;
        };
        let seed: Vec<f64> = free.iter().map(|&k| start[k]).collect();
        let opts = NumericalOptions {
            restarts: 0,
            max_iterations: 50,
            tolerance: 1e-12,
            enforce_limits: false,
            ..NumericalOptions::default()
        };
        let Ok(rep) = numerical::solve(&reduced, ee, &target, &seed, &opts) else {
            return;
        };
        let mut q = start;
        for (i, &k) in free.iter().enumerate() {
            q[k] = rep.q[i];
        }
        let Ok((pe, oe)) = numerical::pose_errors(&self.robot, 0, &q, &target) else {
            return;
        };
        let limit = |e: f64| e.max(1e-9);
        if pe <= limit(s.position_error) && (!frame || oe <= limit(s.orientation_error)) {
            let full = Target::Pose(*world_from_tool);
            if let Ok((pe, oe)) = numerical::pose_errors(&self.robot, 0, &q, &full) {
                s.position_error = pe;
                s.orientation_error = oe;
            }
            s.within_limits = self.robot.within_limits_for(0, &q, LIMIT_SLACK);
            s.q = q;
        }
    }

    /// Shifts every revolute angle by a multiple of 2 pi towards the current q when the shifted
    /// value stays inside the limits.
    pub(super) fn shift_towards_q(&self, q: &mut [f64]) {
        let limits = self.robot.limits();
        for (k, v) in q.iter_mut().enumerate() {
            if self.robot.dof_joint(k).kind != crate::kinematics::JointKind::Revolute {
                continue;
            }
            let cand = self.q[k] + wrap_angle(*v - self.q[k]);
            let [lo, hi] = limits[k];
            if cand >= lo - LIMIT_SLACK && cand <= hi + LIMIT_SLACK {
                *v = cand;
            }
        }
    }

    fn track_numerical(&mut self, ee: usize) {
        let t = self.targets[ee].world_from_tool;
        let mut options = tracking_options();
        let target = if self.task != super::full_task(&self.robot) {
            // A task that leaves components free, in the tool frame (Sect. 2.10.2).
            options.mask = numerical::TaskMask::of_task(self.task);
            Target::Pose(t)
        } else if self.analyzer.task_rank(ee) >= 6 {
            Target::Pose(t)
        } else {
            Target::Position(t.translation.vector)
        };
        let reduced = hold_other_chains(&self.robot, &self.q, ee);
        let (robot, free): (&Robot, Vec<usize>) = match &reduced {
            Some(Held { robot: r, free }) => (r, free.clone()),
            None => (&self.robot, (0..self.robot.dof()).collect()),
        };
        let seed: Vec<f64> = free.iter().map(|&k| self.q[k]).collect();
        let rep = match numerical::solve(robot, ee, &target, &seed, &options) {
            Ok(r) => r,
            Err(e) => {
                let reason = e.to_string();
                return self.freeze(ee, None, Reach::Invalid { reason });
            }
        };
        if !rep.converged {
            let distance = rep.position_error;
            let result = IkResult {
                status: IkStatus::Unreachable {
                    distance: distance.max(rep.orientation_error),
                },
                solutions: Vec::new(),
            };
            let reach = Reach::NotConverged {
                distance,
                angle: rep.orientation_error,
            };
            return self.freeze(ee, Some(result), reach);
        }
        let mut q = self.q.clone();
        for (i, &k) in free.iter().enumerate() {
            q[k] = rep.q[i];
        }
        let (position_error, orientation_error) = if self.task == super::full_task(&self.robot) {
            numerical::pose_errors(&self.robot, ee, &q, &Target::Pose(t)).unwrap_or((0.0, 0.0))
        } else {
            // The errors of the components the task constrains.
            (rep.position_error, rep.orientation_error)
        };
        let sol = IkSolution {
            within_limits: self.robot.within_limits_for(ee, &q, LIMIT_SLACK),
            q,
            posture: SolutionPosture::Numerical { converged: true },
            position_error,
            orientation_error,
            free_joints: Vec::new(),
        };
        let result = IkResult {
            status: IkStatus::Ok,
            solutions: vec![sol],
        };
        self.adopt(ee, result, 0, false);
    }

    /// The target the arm can actually follow: planar arms keep the plane and only turn about the
    /// base z axis, the SCARA only turns about z (other targets would be rejected or unreachable
    /// by construction).
    pub(super) fn constrain_target(&self, ee: usize, pose: Pose) -> Pose {
        let family = if self.uses_closed_form(ee) {
            self.family_of(ee)
        } else {
            None
        };
        let (keep_z, yaw_only) = match family {
            Some(Family::Planar2 | Family::Planar3) => (true, true),
            Some(Family::Scara) => (false, true),
            _ => return pose,
        };
        let Ok(fk) = self.robot.fk_ee(&self.q, ee) else {
            return pose;
        };
        let base_inv = self.robot.base.inverse();
        let mut local = base_inv * pose;
        let now = base_inv * fk;
        if keep_z {
            local.translation.vector.z = now.translation.vector.z;
        }
        if yaw_only {
            let rel = (local.rotation * now.rotation.inverse()).into_inner();
            let psi = (rel[(1, 0)] - rel[(0, 1)]).atan2(rel[(0, 0)] + rel[(1, 1)]);
            local.rotation = rot_z(psi).rotation * now.rotation;
        }
        self.robot.base * local
    }
}
