//! The task the gizmo's IK obeys (Sect. 2.10.2) and the self-motion slider: the hand held at its
//! pose while a free parameter moves the rest of the arm.
//!
//! The slider's value and branch are never stored apart from q: they are read back from q each
//! time ([`crate::redundancy::motion::ExactSelfMotion::locate`]), and the cached solver is
//! rebuilt whenever the robot (its generation) or the held pose changes, so a stale value cannot
//! survive a model edit or a moved target. The numerical case (any other redundant chain, full
//! pose) keeps the arc length walked since the pose was last changed and the last tangent, so
//! the direction never flips between drags.

use super::{AppState, Ghost, GhostLabel, Level, StateError};
use crate::kinematics::arm::{Arm, arm_of};
use crate::kinematics::redundancy::{Redundancy, Task};
use crate::kinematics::{Pose, Robot};
use crate::redundancy::BranchSolution;
use crate::redundancy::collision::{CellScanOptions, CollidingStretch};
use crate::redundancy::motion::ExactSelfMotion;
use crate::redundancy::numerical::NullSpaceMotion;
use crate::redundancy::sampler::SelfMotionSamples;
use nalgebra::Vector3;
use std::f64::consts::PI;

/// Samples of the parameter over [-pi, pi) for the curves of the Self-motion tab and the
/// traced path.
pub const SELF_MOTION_SAMPLES: usize = 360;
/// How the app looks for the self-motion's colliding stretches: every degree, the ends to
/// 1e-4 rad (the slider's pixels; `armlab self-motion --scene` refines them to 1e-6 rad).
pub const SELF_MOTION_CELL_SCAN: CellScanOptions = CellScanOptions {
    step: 0.017_453_292_519_943_295,
    tolerance: 1e-4,
};
/// Largest numerical self-motion sub-step (rad of arc length).
const ARC_STEP: f64 = 0.01;

/// Which self-motion a robot and task have.
#[derive(Debug, Clone)]
enum Kind {
    /// Exact (closed-form parameter).
    Exact(Box<ExactSelfMotion>),
    /// Numerical, by arc length: the arc length walked and the last tangent.
    Numerical { arc: f64, tangent: Option<Vec<f64>> },
    /// None, and why.
    None(String),
}

/// The robot a self-motion runs on: the whole robot when it has one end-effector, else the arm
/// of the end-effector alone ([`crate::kinematics::arm`]), so that fingers, a head or the other
/// arm never move and the exact parameter of the arm (the URDF Panda's q7) is found.
#[derive(Debug, Clone)]
struct Solo {
    arm: Option<Arm>,
}

impl Solo {
    fn new(robot: &Robot, ee: usize, q: &[f64]) -> Option<Self> {
        if robot.end_effectors().len() < 2 {
            return Some(Self { arm: None });
        }
        arm_of(robot, ee, q).ok().map(|a| Self { arm: Some(a) })
    }

    /// The robot the self-motion is computed on.
    fn robot<'a>(&'a self, whole: &'a Robot) -> &'a Robot {
        self.arm.as_ref().map_or(whole, |a| &a.robot)
    }

    /// The end-effector's index in [`Self::robot`].
    fn ee(&self, ee: usize) -> usize {
        if self.arm.is_some() { 0 } else { ee }
    }

    /// The self-motion robot's q from the whole robot's.
    fn local(&self, q: &[f64]) -> Vec<f64> {
        self.arm
            .as_ref()
            .map_or_else(|| q.to_vec(), |a| a.restrict(q))
    }

    /// The whole robot's q: `base` with the self-motion robot's `q` put in.
    fn whole(&self, q: &[f64], base: &[f64]) -> Vec<f64> {
        match &self.arm {
            None => q.to_vec(),
            Some(a) => {
                let mut full = base.to_vec();
                a.expand(q, &mut full);
                full
            }
        }
    }
}

/// The cached self-motion of one end-effector's held pose.
#[derive(Debug, Clone)]
pub(super) struct SelfMotionCache {
    generation: u64,
    /// The q epoch the self-motion last left q at: any other change of q starts a new one.
    epoch: u64,
    ee: usize,
    task: Task,
    pose: Pose,
    /// The robot it runs on (the arm alone on a tree).
    solo: Solo,
    kind: Kind,
    /// Per sample of [`SELF_MOTION_SAMPLES`]: the parameter and every branch there.
    samples: Vec<(f64, Vec<BranchSolution>)>,
    /// Points visited by the numerical self-motion (world, m).
    visited: Vec<Vector3<f64>>,
    /// The colliding stretches of every branch in the cell, with the cell's epoch they were
    /// found at (`None`: not found yet).
    colliding: Option<(u64, Vec<CollidingStretch>)>,
    /// The traced path of each branch, computed when first shown.
    paths: Vec<Option<TracedPath>>,
}

/// A traced path: per sample, the point (none where the branch is missing) and whether the
/// branch is inside the limits there.
pub type TracedPath = Vec<(Option<Vector3<f64>>, bool)>;

/// What the slider, the readouts and the Self-motion tab show.
#[derive(Debug, Clone)]
pub struct SelfMotionView {
    /// The parameter's name: "arm angle", "q7", "phi" or "arc length".
    pub parameter: &'static str,
    /// The parameter in words.
    pub meaning: String,
    /// Exact (closed form) or numerical.
    pub exact: bool,
    /// Current value (rad): the parameter of q, or the arc length walked.
    pub value: f64,
    /// Slider range (rad).
    pub range: [f64; 2],
    /// Index of q's branch in `names`.
    pub branch: usize,
    /// Branch names.
    pub names: Vec<String>,
    /// Feasible intervals of each branch (rad; empty lists for the numerical case, which has
    /// none known).
    pub feasible: Vec<Vec<[f64; 2]>>,
    /// Disjoint self-motion curves inside the limits (exact case).
    pub manifolds: Option<usize>,
    /// At the arm angle's algorithmic singularity.
    pub singular: bool,
    /// |p(q) - p_held| (m) and the rotation angle between R(q) and the held R (rad).
    pub position_error: f64,
    /// See `position_error`.
    pub orientation_error: f64,
    /// Samples of every branch over the range: the Self-motion tab's curves.
    pub samples: Vec<(f64, Vec<BranchSolution>)>,
    /// Where the arm hits itself or the cell's obstacles, every branch (exact self-motion with
    /// collisions on; found when the self-motion or the cell changes, not during a drag).
    pub colliding: Vec<CollidingStretch>,
    /// The traced point over the range for the current branch (world, m; `None` where the
    /// branch does not exist), with whether each sample is within the limits; for the
    /// numerical case the points visited.
    pub path: TracedPath,
}

/// The tasks that make sense for a robot: planar tasks for a planar arm, spatial ones otherwise.
pub fn tasks_for(robot: &crate::kinematics::Robot) -> Vec<Task> {
    if crate::workspace::planar_frame(robot, 0).is_some() && robot.end_effectors().len() == 1 {
        vec![Task::Planar, Task::PlanarPhi]
    } else {
        vec![Task::Pose, Task::Position, Task::PositionAxis]
    }
}

/// The full task of a robot: position and phi for a planar arm of three or more joints,
/// position for a two-link one, the whole pose otherwise.
pub fn full_task(robot: &crate::kinematics::Robot) -> Task {
    crate::redundancy::report::full_task(robot)
}

impl AppState {
    /// The task the gizmo's IK obeys.
    pub fn task(&self) -> Task {
        self.task
    }

    /// The tasks offered for the current robot.
    pub fn tasks(&self) -> Vec<Task> {
        tasks_for(&self.robot)
    }

    /// Chooses the task (it must be one of [`AppState::tasks`]); the target is solved again.
    pub fn set_task(&mut self, task: Task) -> Result<(), StateError> {
        if !self.tasks().contains(&task) {
            return Err(StateError::Task(format!(
                "the task \"{}\" does not apply to {} (its tasks: {})",
                task.name(),
                self.robot.name,
                self.tasks()
                    .iter()
                    .map(|t| t.name())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        self.task = task;
        self.self_motion = None;
        Ok(())
    }

    /// n, m, r of the robot for the current task.
    pub fn redundancy(&self) -> Redundancy {
        Redundancy::of(&self.robot, self.task)
    }

    /// n, m, r of end-effector `ee`'s arm for the current task: on a tree only the chain to it
    /// counts (not the fingers, the head or the other arm).
    pub fn redundancy_of(&self, ee: usize) -> Redundancy {
        let mut red = self.redundancy();
        if self.robot.end_effectors().len() > 1
            && let Some(r) = self.arm_report(ee)
        {
            red.n = r.variables;
        }
        red
    }

    /// The self-motion cache for `ee`. Its held pose is the end-effector's pose when the
    /// self-motion started, kept while q changes by the self-motion alone (never the current,
    /// possibly drifted, pose): a new one starts when the robot, the task or the end-effector
    /// changed, or when anything else moved q.
    /// Whether the self-motion of `ee` is stale and slow to recompute (its last one was swept
    /// over a locked joint, [`ExactSelfMotion::is_swept`]): Baxter's arm took 110-200 ms a
    /// frame while its target was dragged, 7-9 times the Puma's.
    fn self_motion_waits(&self, ee: usize) -> bool {
        self.self_motion.as_ref().is_some_and(|c| {
            c.generation == self.generation
                && c.ee == ee
                && c.task == self.task
                && c.epoch != self.q_epoch
                && matches!(&c.kind, Kind::Exact(m) if m.is_swept())
        })
    }

    fn self_motion_cache(&mut self, ee: usize) -> Option<&mut SelfMotionCache> {
        let fresh = self.self_motion.as_ref().is_some_and(|c| {
            c.generation == self.generation
                && c.ee == ee
                && c.task == self.task
                && c.epoch == self.q_epoch
        });
        if !fresh {
            let pose = self.robot.fk_ee(&self.q, ee).ok()?;
            let solo = Solo::new(&self.robot, ee, &self.q)?;
            let kind = self.self_motion_kind(ee, &solo, &pose);
            let samples = match &kind {
                Kind::Exact(m) => {
                    let mut samples =
                        SelfMotionSamples::exact(solo.robot(&self.robot), m, SELF_MOTION_SAMPLES)
                            .samples;
                    // The tab plots the whole robot's joints.
                    for b in samples.iter_mut().flat_map(|(_, s)| s.iter_mut()) {
                        b.q = solo.whole(&b.q, &self.q);
                    }
                    samples
                }
                _ => Vec::new(),
            };
            self.self_motion = Some(SelfMotionCache {
                generation: self.generation,
                epoch: self.q_epoch,
                ee,
                task: self.task,
                pose,
                solo,
                kind,
                samples,
                visited: Vec::new(),
                paths: Vec::new(),
                colliding: None,
            });
        }
        self.self_motion.as_mut()
    }

    /// Which self-motion the robot (the arm of `ee` on a tree) has for the task at `pose`.
    fn self_motion_kind(&self, ee: usize, solo: &Solo, pose: &Pose) -> Kind {
        let red = self.redundancy_of(ee);
        let robot = solo.robot(&self.robot);
        if red.degree() <= 0 {
            return Kind::None(format!(
                "no self-motion for this task (degree n - r = {})",
                red.degree()
            ));
        }
        if let Ok(m) = ExactSelfMotion::new(robot, pose) {
            let task = match m.parameter() {
                "phi" if robot.dof() == 3 => Task::Planar,
                "phi" => Task::PlanarPhi,
                _ => Task::Pose,
            };
            if task == self.task && solo.ee(ee) == 0 {
                return Kind::Exact(Box::new(m));
            }
        }
        // Any other task with freedom left (the exact parameter holds another task, or there is
        // none): the numerical self-motion holding what the task holds.
        Kind::Numerical {
            arc: 0.0,
            tangent: None,
        }
    }

    /// What the self-motion slider of `ee` shows, or why there is none.
    // Over 80 lines: the slider's one decision (wait while dragging, exact or numerical, the
    // cell's colliding stretches) in the order the view needs them.
    pub fn self_motion(&mut self, ee: usize) -> Result<SelfMotionView, String> {
        if self.dragging && self.self_motion_waits(ee) {
            return Err("the self-motion follows when the drag ends".into());
        }
        let q = self.q.clone();
        let robot = self.robot.clone();
        self.self_motion_cache(ee)
            .ok_or_else(|| "no end-effector pose".to_string())?;
        let colliding = self.self_motion_collisions();
        let cache = self.self_motion.as_mut().expect("made above");
        let (pe, oe) = errors(&robot, (ee, cache.task), &q, &cache.pose);
        let local_q = cache.solo.local(&q);
        let solo_robot = cache.solo.robot(&robot).clone();
        if let Kind::Exact(m) = &cache.kind
            && let Some((branch, _)) = m.locate(&solo_robot, &local_q)
        {
            cache.paths.resize(m.names().len(), None);
            if cache.paths[branch].is_none() {
                let name = &m.names()[branch];
                cache.paths[branch] = Some(
                    cache
                        .samples
                        .iter()
                        .map(|(_, s)| match s.iter().find(|b| &b.name == name) {
                            Some(b) => (
                                m.traced_point(&solo_robot, &cache.solo.local(&b.q)),
                                b.within_limits,
                            ),
                            None => (None, false),
                        })
                        .collect(),
                );
            }
        }
        match &cache.kind {
            Kind::None(why) => Err(why.clone()),
            Kind::Exact(m) => {
                let (branch, value) = m
                    .locate(&solo_robot, &local_q)
                    .ok_or_else(|| "the arm is not on its self-motion (moved?)".to_string())?;
                let path = cache.paths[branch].clone().unwrap_or_default();
                Ok(SelfMotionView {
                    parameter: m.parameter(),
                    meaning: m.parameter_meaning(),
                    exact: true,
                    value,
                    range: [-PI, PI],
                    branch,
                    names: m.names().to_vec(),
                    feasible: m.feasible().to_vec(),
                    manifolds: Some(m.manifolds()),
                    singular: m.singular(),
                    position_error: pe,
                    orientation_error: oe,
                    samples: cache.samples.clone(),
                    path,
                    colliding,
                })
            }
            Kind::Numerical { arc, .. } => Ok(SelfMotionView {
                parameter: "arc length",
                meaning: format!(
                    "arc length s walked in joint space along the null space (numerical: tangent \
                     step, then Newton back onto the task \"{}\")",
                    cache.task.name()
                ),
                exact: false,
                value: *arc,
                range: [-PI, PI],
                branch: 0,
                names: vec!["self-motion".into()],
                feasible: vec![Vec::new()],
                manifolds: None,
                singular: false,
                position_error: pe,
                orientation_error: oe,
                samples: Vec::new(),
                path: cache.visited.iter().map(|p| (Some(*p), true)).collect(),
                colliding: Vec::new(),
            }),
        }
    }

    /// The colliding stretches of the cached exact self-motion in the cell
    /// ([`ExactSelfMotion::collision_free`], at [`SELF_MOTION_CELL_SCAN`]): found once per
    /// self-motion and cell, not while a drag goes on (the self-motion is then new every
    /// frame: they come when it ends). None on a tree (the world is the whole robot's).
    fn self_motion_collisions(&mut self) -> Vec<CollidingStretch> {
        let epoch = self.cell_epoch();
        let Some(c) = &self.self_motion else {
            return Vec::new();
        };
        if let Some((k, found)) = &c.colliding
            && *k == epoch
        {
            return found.clone();
        }
        let world = self.collision_world().filter(|_| self.collisions_on());
        let found = match (&c.kind, world) {
            _ if self.dragging => return Vec::new(),
            (Kind::Exact(m), Some(w)) if c.solo.arm.is_none() => {
                m.collision_free(&self.robot, w, SELF_MOTION_CELL_SCAN)
                    .colliding
            }
            _ => Vec::new(),
        };
        if let Some(c) = &mut self.self_motion {
            c.colliding = Some((epoch, found.clone()));
        }
        found
    }

    /// Moves the self-motion parameter of `ee` to `value` (rad), the hand held. An exact
    /// self-motion stays on q's branch and stops at the end of its feasible interval (the arm
    /// never leaves its limits); the numerical one walks the arc length in steps of 0.01 rad and
    /// stops where a step would leave the limits or fail. Returns the value reached.
    pub fn set_self_motion(&mut self, ee: usize, value: f64) -> Result<f64, StateError> {
        let view = self.self_motion(ee).map_err(StateError::Task)?;
        if !value.is_finite() {
            return Err(StateError::Task(
                "the self-motion value is not a number".into(),
            ));
        }
        if view.exact {
            self.set_exact(ee, &view, value)
        } else {
            self.walk_numerical(ee, value)
        }
    }

    fn set_exact(
        &mut self,
        ee: usize,
        view: &SelfMotionView,
        value: f64,
    ) -> Result<f64, StateError> {
        let Some(Kind::Exact(m)) = self.self_motion.as_ref().map(|c| c.kind.clone()) else {
            return Err(StateError::Task("no exact self-motion".into()));
        };
        let feasible = &view.feasible[view.branch];
        let here = feasible
            .iter()
            .find(|iv| view.value >= iv[0] - 1e-9 && view.value <= iv[1] + 1e-9)
            .copied();
        let target = match here {
            Some([lo, hi]) => value.clamp(lo, hi),
            None => view.value,
        };
        let name = &view.names[view.branch];
        let solo = self.solo()?;
        let sols = m.solutions(solo.robot(&self.robot), target);
        let Some(sol) = sols.iter().find(|s| &s.name == name && s.within_limits) else {
            return Ok(view.value);
        };
        let mut q = solo.whole(&sol.q, &self.q);
        self.shift_towards_q(&mut q);
        if (target - value).abs() > 1e-9 {
            self.push_message(
                Level::Info,
                format!(
                    "{} stops at {:.2} deg: the end of the feasible stretch of \"{name}\"",
                    view.parameter,
                    target.to_degrees()
                ),
            );
        }
        self.move_along_self_motion(q, ee);
        Ok(target)
    }

    fn walk_numerical(&mut self, ee: usize, value: f64) -> Result<f64, StateError> {
        let Some(cache) = self.self_motion.as_ref() else {
            return Err(StateError::Task("no self-motion".into()));
        };
        let Kind::Numerical { arc, tangent } = cache.kind.clone() else {
            return Err(StateError::Task("no numerical self-motion".into()));
        };
        let mask = crate::kinematics::ik::numerical::TaskMask::of_task(self.task);
        let solo = cache.solo.clone();
        let (robot, local_ee) = (solo.robot(&self.robot), solo.ee(ee));
        let local_q = solo.local(&self.q);
        let mut m = NullSpaceMotion::for_task(robot, local_ee, &local_q, tangent.as_deref(), mask)
            .map_err(|e| StateError::Task(e.to_string()))?;
        m.hold(cache.pose);
        let mut s = arc;
        let mut visited = Vec::new();
        while (value - s).abs() > 1e-12 {
            let ds = (value - s).clamp(-ARC_STEP, ARC_STEP);
            let before = m.clone();
            if m.step(ds).is_err() || !robot.within_limits(m.q(), 1e-12) {
                m = before;
                break;
            }
            s += ds;
            if let Some(p) = robot
                .fk_ee(m.q(), local_ee)
                .ok()
                .map(|t| t.translation.vector)
            {
                visited.push(p);
            }
        }
        let (q, t) = (solo.whole(m.q(), &self.q), m.tangent().to_vec());
        if let Some(c) = self.self_motion.as_mut() {
            c.kind = Kind::Numerical {
                arc: s,
                tangent: Some(t),
            };
            c.visited.extend(visited);
        }
        self.move_along_self_motion(q, ee);
        Ok(s)
    }

    /// Moves the arm to branch `k` of the exact self-motion at the current parameter (the hand
    /// held); refused, q unchanged, when that branch does not exist there or is outside the
    /// limits.
    pub fn select_self_motion_branch(&mut self, ee: usize, k: usize) -> Result<(), StateError> {
        let view = self.self_motion(ee).map_err(StateError::Task)?;
        let Some(Kind::Exact(m)) = self.self_motion.as_ref().map(|c| c.kind.clone()) else {
            return Err(StateError::Task(
                "the numerical self-motion has one branch".into(),
            ));
        };
        let name = view.names.get(k).ok_or(StateError::NoSuchSolution {
            index: k,
            count: view.names.len(),
        })?;
        let solo = self.solo()?;
        let sols = m.solutions(solo.robot(&self.robot), view.value);
        let Some(sol) = sols.iter().find(|s| &s.name == name) else {
            return Err(StateError::Task(format!(
                "no branch \"{name}\" at {} = {:.2} deg",
                view.parameter,
                view.value.to_degrees()
            )));
        };
        if !sol.within_limits {
            return Err(StateError::SolutionOutsideLimits {
                index: k,
                posture: name.clone(),
            });
        }
        let mut q = solo.whole(&sol.q, &self.q);
        self.shift_towards_q(&mut q);
        self.move_along_self_motion(q, ee);
        Ok(())
    }

    /// The robot the cached self-motion runs on.
    fn solo(&self) -> Result<Solo, StateError> {
        self.self_motion
            .as_ref()
            .map(|c| c.solo.clone())
            .ok_or_else(|| StateError::Task("no self-motion".into()))
    }

    /// Moves the arm to `q`, a configuration of the self-motion of `ee`: the held pose stays the
    /// one the self-motion started with.
    fn move_along_self_motion(&mut self, q: Vec<f64>, ee: usize) {
        self.apply_q(q, Some(ee));
        if let Some(c) = self.self_motion.as_mut() {
            c.epoch = self.q_epoch;
        }
    }

    /// The other branches at the current parameter, as ghosts (exact self-motion only).
    pub fn self_motion_ghosts(&mut self, ee: usize) -> Vec<Ghost> {
        let Ok(view) = self.self_motion(ee) else {
            return Vec::new();
        };
        let Some(Kind::Exact(m)) = self.self_motion.as_ref().map(|c| &c.kind) else {
            return Vec::new();
        };
        let Ok(solo) = self.solo() else {
            return Vec::new();
        };
        m.solutions(solo.robot(&self.robot), view.value)
            .into_iter()
            .filter(|s| s.name != view.names[view.branch])
            .map(|s| Ghost {
                q: solo.whole(&s.q, &self.q),
                posture: GhostLabel::SelfMotion(s.name),
                within_limits: s.within_limits,
                selected: false,
                class: None,
                collision: None,
            })
            .map(|g| self.with_collision(g))
            .collect()
    }
}

/// Position (m) and orientation (rad) error of `q`'s end-effector `ee` from `pose`.
/// The hand's position and orientation errors from the held pose over what `task` holds (a
/// partial task lets the other components move).
fn errors(
    robot: &crate::kinematics::Robot,
    (ee, task): (usize, Task),
    q: &[f64],
    pose: &Pose,
) -> (f64, f64) {
    use crate::kinematics::ik::numerical::{TaskMask, task_errors};
    match robot.fk_ee(q, ee) {
        Ok(t) => task_errors(pose, &t, &TaskMask::of_task(task)),
        Err(_) => (f64::INFINITY, f64::INFINITY),
    }
}
