//! The interactive app's state, free of any GUI type so that it can be unit-tested: the model,
//! the joint vector q, one IK target per end-effector with its last result and selected posture,
//! the posture lock, the DH table editor, display toggles, the end-effector trail and status
//! messages. Every method takes `&mut self` and does its work at once (the app calls them from
//! its frame loop).
//!
//! Units: q and every stored value are in rad and m; the UI works in the [`AngleUnit`] (degrees by
//! default) and millimetres, through the `*_display` methods and the DH cells.
//!
//! Invariants: q always has `robot().dof()` finite entries inside the joint limits; the robot
//! always is the last valid model (a failed load or an invalid DH entry changes nothing); a
//! target that cannot be reached leaves q unchanged.
//!
//! # Targets and the posture lock
//!
//! Moving a slider, resetting or editing the DH table puts every target whose end-effector moved
//! at its end-effector (and, for closed-form arms, selects the posture the arm is in). Moving a
//! target ([`AppState::set_target`], [`AppState::move_target_by`]) solves IK at once:
//!
//! - arms with a closed form keep every solution (drawn as [`Ghost`]s); unlocked, the arm takes
//!   the within-limits solution closest in joint space to its q; locked ([`AppState::set_lock`]),
//!   the one with the selected posture label, except near a singularity, where a label can change
//!   meaning (theta5 crossing 0 turns "wrist no flip" into "wrist flip"): there the closest
//!   solution is taken if it is closer by more than [`BRANCH_SWITCH_MARGIN`] and the lock follows
//!   its label, with an info message. Degenerate solutions keep their free joints at the current
//!   values, so the arm never jumps more than the motion warrants;
//! - other arms use the numerical solver seeded with q; with several end-effectors the joints on
//!   the other end-effectors' chains (the humanoid's torso) are held;
//! - a target that cannot be reached (outside the workspace, only outside the limits, solver not
//!   converged) leaves q as it is and is flagged with a [`Reach`] saying how far out it is.

mod cell;
mod dh;
pub mod placement;
pub mod reachability;
mod select;
mod self_motion;
mod track;
mod types;
mod units;

pub use dh::{DH_FIELDS, DhCell, DhField, DhRowCells};
pub use self_motion::{
    SELF_MOTION_CELL_SCAN, SELF_MOTION_SAMPLES, SelfMotionView, TracedPath, full_task, tasks_for,
};
pub use track::{BRANCH_SWITCH_MARGIN, BRANCH_SWITCH_MEASURE, tracking_options};
pub use types::{
    DisplayToggles, EeTarget, Ghost, GhostLabel, Level, Reach, Readouts, StateError, StatusMessage,
};
pub use units::{
    AngleUnit, EntryError, MM_PER_M, Quantity, format_entry, format_number, parse_entry,
    without_negative_zero,
};

use crate::kinematics::end_effectors::{EndEffectorCatalog, catalog};
use crate::kinematics::ik::SolutionPosture;
use crate::kinematics::orientation::angle_axis_from_rotation;
use crate::kinematics::pose::Pose;
use crate::kinematics::singularity::SingularityAnalyzer;
use crate::kinematics::{EulerKind, Robot};
use crate::redundancy::report::{ArmReport, arm_report};
use nalgebra::{Rotation3, Translation3, Vector3};
use std::collections::VecDeque;

/// Most positions kept in each end-effector trail.
pub const TRAIL_CAPACITY: usize = 2000;
/// A trail point is added only when the end-effector moved more than this (m).
pub const TRAIL_MIN_STEP: f64 = 1e-6;
/// A step of the tool longer than this share of the arm's reach is a jump (a reset, a typed
/// value, another configuration): the trail breaks there instead of drawing a line across.
pub const TRAIL_JUMP_SHARE: f64 = 0.1;

/// One point of a trail.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrailPoint {
    /// The end-effector's position (m, world).
    pub p: Vector3<f64>,
    /// The arm jumped here from the previous point: no line joins them.
    pub after_jump: bool,
}
/// Most status messages kept.
pub const MESSAGE_CAPACITY: usize = 64;

/// The app's state.
#[derive(Debug, Clone)]
pub struct AppState {
    spec: String,
    robot: Robot,
    q: Vec<f64>,
    targets: Vec<EeTarget>,
    lock: bool,
    dh: Vec<DhRowCells>,
    /// What to draw.
    pub display: DisplayToggles,
    /// What an exercise sheet asks for, hidden from the panels while it is being answered.
    pub hidden: Hidden,
    /// A drag is in progress (a pointer button held, or the frame probe's drag): a self-motion
    /// that takes long to compute (a locked joint swept) waits for its end.
    pub dragging: bool,
    /// The frame probe drags the target with no pointer: the state counts as dragged.
    pub drag_held: bool,
    angle_unit: AngleUnit,
    /// Orientation representation of the readouts (ZYZ or RPY).
    pub orientation: EulerKind,
    trails: Vec<VecDeque<TrailPoint>>,
    messages: VecDeque<StatusMessage>,
    analyzer: SingularityAnalyzer,
    /// Each end-effector's arm analysed (chain, closed form, n), and the end-effectors grouped
    /// by arm: computed when the robot changes.
    arms: ArmsOfRobot,
    /// Posture classes of the robot (the workspace figures' colours).
    classifier: crate::workspace::PostureClassifier,
    /// The task the gizmo's IK obeys.
    task: crate::kinematics::redundancy::Task,
    /// Counts model changes (loads, DH edits), so caches know when they are stale.
    generation: u64,
    /// Counts every change of q (sliders, IK, configurations, edits): a self-motion holds its
    /// pose only while q changed by nothing but the self-motion itself.
    q_epoch: u64,
    self_motion: Option<self_motion::SelfMotionCache>,
    /// The robot as it was opened (what "reset to the file's values" restores).
    opened: Robot,
    /// Messages pushed so far (a repeated one counts again): the status bar dates the newest.
    messages_pushed: u64,
    /// The robots before each model edit (undo) and the ones undone (redo).
    undo: Vec<Robot>,
    redo: Vec<Robot>,
    /// The cell: obstacles, the collision world, what the arm and the solutions hit.
    cell: cell::Cell,
}

/// A robot's end-effectors grouped by arm, and each one's arm analysed at q = 0 (the chain's
/// structure does not depend on q).
#[derive(Debug, Clone, Default)]
struct ArmsOfRobot {
    catalog: EndEffectorCatalog,
    reports: Vec<ArmReport>,
}

impl ArmsOfRobot {
    fn new(robot: &Robot) -> Self {
        let catalog = catalog(robot);
        let q = vec![0.0; robot.dof()];
        let reports = (0..robot.end_effectors().len())
            .map(|ee| arm_report(robot, &catalog, ee, &q))
            .collect();
        Self { catalog, reports }
    }
}

/// What the panels hide while an exercise sheet is answered (the answer would be in them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Hidden {
    /// The DH table (a dh-table sheet).
    pub dh_table: bool,
    /// The pose readouts (T) and the Jacobian (an fk sheet).
    pub pose: bool,
    /// The IK solutions (an ik sheet).
    pub solutions: bool,
    /// The workspace figure and overlay (a workspace sheet).
    pub workspace: bool,
    /// An exam (a student's sheet file, no key): besides, every way out of the answer is off
    /// (saving the model or a lesson, the symbols, figure export, screenshots and recordings).
    pub exam: bool,
}

impl AppState {
    /// Counts the models loaded (a tab's cache of the model is stale when it changes).
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The state for `robot` (loaded from `spec`, a built-in name or a path): q at the "ready"
    /// configuration if the robot has one (else zero), clamped into the limits; each target at
    /// its end-effector; lock off; degrees.
    pub fn new(robot: Robot, spec: impl Into<String>) -> Self {
        let analyzer = SingularityAnalyzer::new(&robot);
        let arms = ArmsOfRobot::new(&robot);
        let dh = dh::build_cells(&robot, AngleUnit::default());
        let mut me = Self {
            spec: spec.into(),
            q: Vec::new(),
            targets: Vec::new(),
            lock: false,
            dh,
            display: DisplayToggles::default(),
            hidden: Hidden::default(),
            dragging: false,
            drag_held: false,
            angle_unit: AngleUnit::default(),
            orientation: EulerKind::Zyz,
            trails: Vec::new(),
            messages: VecDeque::new(),
            analyzer,
            arms,
            classifier: crate::workspace::PostureClassifier::new(&robot),
            task: full_task(&robot),
            generation: 0,
            q_epoch: 0,
            self_motion: None,
            opened: robot.clone(),
            messages_pushed: 0,
            undo: Vec::new(),
            redo: Vec::new(),
            cell: cell::Cell::default(),
            robot,
        };
        if let Some(note) = me.install_q() {
            me.push_message(Level::Info, note);
        }
        for w in me.robot.load_warnings.clone() {
            me.push_message(Level::Warning, w);
        }
        me
    }

    /// Loads a model by built-in name or `.toml`/`.urdf` path (see
    /// [`crate::model_file::load_model`]).
    pub fn from_spec(spec: &str) -> Result<Self, StateError> {
        crate::model_file::load_model(spec)
            .map(|r| Self::new(r, spec))
            .map_err(|source| StateError::Load {
                spec: spec.to_string(),
                source: Box::new(source),
            })
    }

    /// Replaces the model. On error the previous model, q and targets are kept and the error is
    /// also put in the status messages. Display settings, units and the lock flag are kept.
    pub fn load_model(&mut self, spec: &str) -> Result<(), StateError> {
        let loaded = crate::model_file::load_model(spec);
        self.install_model(spec, loaded)
    }

    /// Replaces the model with one read from the text of a file named `name` (`.toml` or
    /// `.urdf`), e.g. a file the browser's file picker or a drop handed over; errors as
    /// [`Self::load_model`].
    pub fn load_model_text(&mut self, name: &str, text: &str) -> Result<(), StateError> {
        let loaded = crate::model_file::parse_model_text(name, text);
        self.install_model(name, loaded)
    }

    fn install_model(
        &mut self,
        spec: &str,
        loaded: Result<Robot, crate::model_file::LoadError>,
    ) -> Result<(), StateError> {
        match loaded {
            Ok(robot) => {
                self.spec = spec.to_string();
                self.analyzer = SingularityAnalyzer::new(&robot);
                self.arms = ArmsOfRobot::new(&robot);
                self.classifier = crate::workspace::PostureClassifier::new(&robot);
                self.dh = dh::build_cells(&robot, self.angle_unit);
                self.task = full_task(&robot);
                self.opened = robot.clone();
                self.undo.clear();
                self.redo.clear();
                self.robot = robot;
                self.generation += 1;
                self.cell_model_changed();
                self.trails.clear();
                let note = self.install_q();
                let mut msg = format!("loaded {} ({} DOF)", self.robot.name, self.robot.dof());
                if let Some(note) = note {
                    msg = format!("{msg}; {note}");
                }
                self.push_message(Level::Info, msg);
                for w in self.robot.load_warnings.clone() {
                    self.push_message(Level::Warning, w);
                }
                Ok(())
            }
            Err(source) => {
                let err = StateError::Load {
                    spec: spec.to_string(),
                    source: Box::new(source),
                };
                self.push_message(Level::Error, format!("{err}; keeping {}", self.robot.name));
                Err(err)
            }
        }
    }

    /// q at the model's opening pose ("ready", or a regular pose near it from which every
    /// posture can be shown: [`crate::kinematics::opening`]), targets synced, trails started.
    /// Returns why the pose is not "ready", if it is not.
    fn install_q(&mut self) -> Option<String> {
        let opening = crate::kinematics::opening::opening_pose(&self.robot);
        let mut q = opening.q;
        clamp_into(&mut q, &self.robot.limits());
        self.q = q;
        self.q_epoch += 1;
        self.targets = self
            .robot
            .end_effectors()
            .iter()
            .map(|e| EeTarget {
                name: e.name.clone(),
                world_from_tool: Pose::identity(),
                result: None,
                selected: None,
                posture: None,
                reach: Reach::Reached,
            })
            .collect();
        self.trails = vec![VecDeque::new(); self.targets.len()];
        for ee in 0..self.targets.len() {
            self.sync_target(ee);
        }
        self.recheck_arm();
        self.push_trail();
        opening.note
    }

    /// The model spec (built-in name or path) the robot came from.
    pub fn spec(&self) -> &str {
        &self.spec
    }

    /// The robot (its last valid shape).
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The joint vector (rad or m).
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// The singularity classifier of the current robot.
    pub fn analyzer(&self) -> &SingularityAnalyzer {
        &self.analyzer
    }

    /// The end-effectors grouped by arm (tools, their frames, other frames).
    pub fn ee_catalog(&self) -> &EndEffectorCatalog {
        &self.arms.catalog
    }

    /// End-effector `ee`'s arm analysed (chain, DH, closed form, n), if it exists.
    pub fn arm_report(&self, ee: usize) -> Option<&ArmReport> {
        self.arms.reports.get(ee)
    }

    /// The posture class of an IK solution's posture, as the workspace figures colour it
    /// (`None`: no class, e.g. a degenerate posture, the numerical solver's, or an arm without
    /// posture classes).
    pub fn posture_class(&self, posture: &SolutionPosture) -> Option<u8> {
        self.classifier.class_of_solution(posture)
    }

    /// Every target, one per end-effector.
    pub fn targets(&self) -> &[EeTarget] {
        &self.targets
    }

    /// Target of end-effector `ee`.
    pub fn target(&self, ee: usize) -> Result<&EeTarget, StateError> {
        self.targets.get(ee).ok_or(StateError::NoSuchEndEffector {
            index: ee,
            count: self.targets.len(),
        })
    }

    /// Whether the posture lock is on.
    pub fn lock(&self) -> bool {
        self.lock
    }

    /// The angle display unit.
    pub fn angle_unit(&self) -> AngleUnit {
        self.angle_unit
    }

    /// Changes the angle display unit; DH cells without errors are re-formatted.
    pub fn set_angle_unit(&mut self, unit: AngleUnit) {
        self.angle_unit = unit;
        self.refresh_dh_cells();
    }

    /// The status messages, oldest first (at most [`MESSAGE_CAPACITY`]).
    pub fn messages(&self) -> &VecDeque<StatusMessage> {
        &self.messages
    }

    /// How many messages were pushed so far (a repeated message counts again): a new number
    /// means a new (or repeated) newest message.
    pub fn messages_pushed(&self) -> u64 {
        self.messages_pushed
    }

    /// The newest status message.
    pub fn last_message(&self) -> Option<&StatusMessage> {
        self.messages.back()
    }

    /// The status bar's line: while a target is not reached, the same sentence the IK panel
    /// shows for it (one source, so the two can never disagree, e.g. on how far out a dragged
    /// target is), preferring end-effector `ee`; otherwise the newest message (the status bar
    /// shows [`AppState::collision_warning`] once that message has had its time).
    pub fn status_line(&self, ee: usize) -> Option<StatusMessage> {
        let unreached = |t: &EeTarget| {
            t.reach.message().map(|m| StatusMessage {
                level: Level::Warning,
                text: format!("{}: {m}", t.name),
            })
        };
        self.targets
            .get(ee)
            .and_then(unreached)
            .or_else(|| self.targets.iter().find_map(unreached))
            .or_else(|| self.last_message().cloned())
    }

    /// Writes the current robot, with its edited DH table, to `path`: URDF when the name ends
    /// in `.urdf`, else a TOML model file. The message says what was written, or why not; the
    /// robot is left as it is either way.
    pub fn save_model(&mut self, path: &str) -> Result<String, String> {
        let path = path.trim();
        if self.dh_has_errors() {
            return Err(
                "not saved: red cells of the DH table hold values that are not applied; correct \
                 them (or Undo) first"
                    .into(),
            );
        }
        let text = self.model_text(path)?;
        std::fs::write(path, text).map_err(|e| format!("cannot write {path}: {e}"))?;
        let full = std::fs::canonicalize(path).unwrap_or_else(|_| path.into());
        Ok(format!("saved {}", full.display()))
    }

    /// The text [`Self::save_model`] writes for a file named `path`: URDF for a name ending in
    /// `.urdf`, else a TOML model file (the web build offers it as a download).
    pub fn model_text(&self, path: &str) -> Result<String, String> {
        if path.is_empty() {
            return Err("type a file name ending in .urdf or .toml".into());
        }
        if path.to_ascii_lowercase().ends_with(".urdf") {
            crate::urdf::to_urdf(&self.robot).map_err(|e| e.to_string())
        } else {
            crate::model_file::to_toml(&self.robot).ok_or_else(|| {
                "a TOML model file holds one serial DH table with one variable per joint; save \
                 this model as .urdf"
                    .to_string()
            })
        }
    }

    /// Adds a status message (an identical newest message is not repeated).
    pub fn push_message(&mut self, level: Level, text: impl Into<String>) {
        let m = StatusMessage {
            level,
            text: text.into(),
        };
        self.messages_pushed += 1;
        if self.messages.back() == Some(&m) {
            return;
        }
        if self.messages.len() == MESSAGE_CAPACITY {
            self.messages.pop_front();
        }
        self.messages.push_back(m);
    }

    /// Removes every status message.
    pub fn clear_messages(&mut self) {
        self.messages.clear();
    }

    /// Recent positions (m, world) of end-effector `ee`, oldest first, with the jumps marked.
    pub fn trail(&self, ee: usize) -> Option<&VecDeque<TrailPoint>> {
        self.trails.get(ee)
    }

    /// Empties every trail.
    pub fn clear_trails(&mut self) {
        for t in &mut self.trails {
            t.clear();
        }
    }

    fn push_trail(&mut self) {
        let jump = TRAIL_JUMP_SHARE * self.robot.longest_chain_length().max(1e-3);
        for (ee, trail) in self.trails.iter_mut().enumerate() {
            let Ok(t) = self.robot.fk_ee(&self.q, ee) else {
                continue;
            };
            let p = t.translation.vector;
            let step = trail.back().map(|b| (b.p - p).norm());
            if step.is_some_and(|d| d <= TRAIL_MIN_STEP) {
                continue;
            }
            if trail.len() == TRAIL_CAPACITY {
                trail.pop_front();
            }
            trail.push_back(TrailPoint {
                p,
                after_jump: step.is_some_and(|d| d > jump),
            });
        }
    }

    fn check_dof(&self, k: usize) -> Result<(), StateError> {
        if k < self.robot.dof() {
            Ok(())
        } else {
            Err(StateError::NoSuchDof {
                index: k,
                count: self.robot.dof(),
            })
        }
    }

    /// What `q[k]` measures: an angle (revolute) or a length (prismatic).
    pub fn joint_quantity(&self, k: usize) -> Result<Quantity, StateError> {
        self.check_dof(k)?;
        Ok(match self.robot.dof_joint(k).kind {
            crate::kinematics::JointKind::Prismatic => Quantity::Length,
            _ => Quantity::Angle,
        })
    }

    /// `q[k]` in display units (the angle unit, or mm).
    pub fn joint_display(&self, k: usize) -> Result<f64, StateError> {
        Ok(self
            .joint_quantity(k)?
            .to_display(self.q[k], self.angle_unit))
    }

    /// The limits of `q[k]` in display units (the slider's range).
    pub fn joint_display_limits(&self, k: usize) -> Result<[f64; 2], StateError> {
        let quantity = self.joint_quantity(k)?;
        // A joint without limits gets a slider over one turn (or the arm's scale for a slide).
        let [lo, hi] = self.robot.sampling_range(k);
        Ok([
            quantity.to_display(lo, self.angle_unit),
            quantity.to_display(hi, self.angle_unit),
        ])
    }

    /// Sets `q[k]` (rad or m), clamped into its limits; targets follow the end-effectors.
    /// Returns the value applied.
    pub fn set_joint(&mut self, k: usize, value: f64) -> Result<f64, StateError> {
        self.check_dof(k)?;
        if !value.is_finite() {
            return Err(StateError::InvalidJointEntry {
                dof: k,
                reason: EntryError::NonFinite(value.to_string()),
            });
        }
        let [lo, hi] = self.robot.dof_joint(k).limits;
        let v = value.clamp(lo, hi);
        if v != self.q[k] {
            let mut q = self.q.clone();
            q[k] = v;
            self.apply_q(q, None);
        }
        Ok(v)
    }

    /// Sets `q[k]` from typed text in display units (degrees or radians, millimetres; explicit
    /// units accepted, see [`parse_entry`]). A value outside the limits is clamped and a warning
    /// says so. Returns the value applied (rad or m).
    pub fn set_joint_display(&mut self, k: usize, text: &str) -> Result<f64, StateError> {
        let quantity = self.joint_quantity(k)?;
        let v = parse_entry(text, quantity, self.angle_unit)
            .map_err(|reason| StateError::InvalidJointEntry { dof: k, reason })?;
        let applied = self.set_joint(k, v)?;
        if applied != v {
            let unit = self.angle_unit;
            let sym = quantity.symbol(unit);
            let [lo, hi] = self.joint_display_limits(k)?;
            let msg = format!(
                "q{} = {} {sym} is outside [{}, {}] {sym}; set to {} {sym}",
                k + 1,
                format_entry(v, quantity, unit),
                format_entry(quantity.from_display(lo, unit), quantity, unit),
                format_entry(quantity.from_display(hi, unit), quantity, unit),
                format_entry(applied, quantity, unit),
            );
            self.push_message(Level::Warning, msg);
        }
        Ok(applied)
    }

    /// Sets the whole joint vector (rad or m), clamped into the limits.
    pub fn set_q(&mut self, q: &[f64]) -> Result<(), StateError> {
        self.robot.check_q(q)?;
        let mut q = q.to_vec();
        clamp_into(&mut q, &self.robot.limits());
        self.apply_q(q, None);
        Ok(())
    }

    /// Moves the arm to a named configuration ("zero", "ready", "figure", ...), clamped into the
    /// limits; targets follow.
    pub fn reset_to(&mut self, name: &str) -> Result<(), StateError> {
        let q = self
            .robot
            .config(name)
            .ok_or_else(|| StateError::UnknownConfiguration {
                name: name.to_string(),
                available: self
                    .robot
                    .configurations
                    .iter()
                    .map(|c| c.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })?
            .to_vec();
        self.set_q(&q)?;
        self.push_message(Level::Info, format!("reset to \"{name}\""));
        Ok(())
    }

    /// Sets q, extends the trails, and re-syncs every target other than `solved` whose
    /// end-effector moved.
    fn apply_q(&mut self, q: Vec<f64>, solved: Option<usize>) {
        self.q = q;
        self.q_epoch += 1;
        self.recheck_arm();
        self.push_trail();
        for ee in 0..self.targets.len() {
            if Some(ee) == solved {
                continue;
            }
            let Ok(fk) = self.robot.fk_ee(&self.q, ee) else {
                continue;
            };
            let t = &self.targets[ee].world_from_tool;
            let moved = (fk.translation.vector - t.translation.vector).norm() > 1e-9
                || angle_axis_from_rotation(&(fk.rotation.inverse() * t.rotation)).angle > 1e-9;
            if moved {
                self.sync_target(ee);
            }
        }
    }

    /// Puts target `ee` at its end-effector; for closed-form arms also lists every solution for
    /// that pose and selects the one the arm is at (its label becomes the selected posture).
    fn sync_target(&mut self, ee: usize) {
        let Ok(fk) = self.robot.fk_ee(&self.q, ee) else {
            return;
        };
        let result = if self.uses_closed_form(ee) {
            self.closed_form_solutions(ee, &fk).ok()
        } else {
            None
        };
        let selected = result.as_ref().and_then(|r| {
            r.solutions
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    (
                        i,
                        crate::kinematics::ik::solver::joint_distance(&self.robot, &s.q, &self.q),
                    )
                })
                .filter(|&(_, d)| d < 1e-6)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(i, _)| i)
        });
        let t = &mut self.targets[ee];
        if let (Some(r), Some(i)) = (&result, selected) {
            let posture = r.solutions[i].posture;
            if !posture.is_merged() {
                t.posture = Some(posture);
            }
        }
        t.world_from_tool = fk;
        t.result = result;
        t.selected = selected;
        t.reach = Reach::Reached;
        self.recheck_solutions(ee);
    }

    /// After a successful DH edit: q clamped into the (maybe new) limits, solvers rebuilt,
    /// targets synced.
    fn after_model_edit(&mut self) {
        self.analyzer = SingularityAnalyzer::new(&self.robot);
        self.arms = ArmsOfRobot::new(&self.robot);
        self.classifier = crate::workspace::PostureClassifier::new(&self.robot);
        self.generation += 1;
        let mut q = self.q.clone();
        clamp_into(&mut q, &self.robot.limits());
        self.q = q;
        self.q_epoch += 1;
        for ee in 0..self.targets.len() {
            self.sync_target(ee);
        }
        self.cell_model_changed();
        self.push_trail();
    }

    /// Sets the target of end-effector `ee` (`world_from_tool`, m) and solves IK at once: the
    /// arm moves to the chosen solution, or stays put with the target flagged (see [`Reach`]).
    /// Planar arms keep the target in their plane and turn it only about the base z axis; the
    /// SCARA only turns it about z.
    pub fn set_target(&mut self, ee: usize, world_from_tool: Pose) -> Result<&Reach, StateError> {
        self.target(ee)?;
        if !world_from_tool
            .to_homogeneous()
            .iter()
            .all(|v| v.is_finite())
        {
            return Err(StateError::NonFiniteTarget);
        }
        let pose = self.constrain_target(ee, world_from_tool);
        self.targets[ee].world_from_tool = pose;
        self.solve_target(ee);
        Ok(&self.targets[ee].reach)
    }

    /// Puts the target of `ee` on the tool (at the current q), with its position (world, m) or
    /// its rotation (world from tool) replaced where given, and solves as
    /// [`AppState::set_target`]; nothing where the tool has no pose.
    pub fn set_target_from_tool(
        &mut self,
        ee: usize,
        position: Option<Vector3<f64>>,
        rotation: Option<Rotation3<f64>>,
    ) -> Result<(), StateError> {
        if let Ok(tool) = self.robot.fk_ee(&self.q, ee) {
            let at = position.map_or(tool.translation, Translation3::from);
            self.set_target(ee, Pose::from_parts(at, rotation.unwrap_or(tool.rotation)))?;
        }
        Ok(())
    }

    /// Moves the target of `ee` by `translation` (m, world frame) and turns it by `rotation`
    /// (world frame, about the target's origin), then solves as [`AppState::set_target`].
    pub fn move_target_by(
        &mut self,
        ee: usize,
        translation: Vector3<f64>,
        rotation: Rotation3<f64>,
    ) -> Result<&Reach, StateError> {
        let t = self.target(ee)?.world_from_tool;
        let pose = Pose::from_parts(
            Translation3::from(t.translation.vector + translation),
            rotation * t.rotation,
        );
        self.set_target(ee, pose)
    }
}

fn clamp_into(q: &mut [f64], limits: &[[f64; 2]]) {
    for (v, [lo, hi]) in q.iter_mut().zip(limits) {
        *v = v.clamp(*lo, *hi);
    }
}
