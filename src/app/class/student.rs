//! The student's side: the teacher's states applied as lesson steps are (the robot loaded
//! when it changes), and the student's own moves noticed: a q, a target, a camera or a robot
//! that differs from what was applied makes the app explore on its own until "Follow the
//! teacher".

use super::ClassClient;
use crate::app::action::{Action, Actions};
use crate::app::files::{Opening, open_bytes};
use crate::app::lesson::step_actions;
use crate::app::shell::AppUi;
use crate::app::state::Level;
use crate::camera::Camera;
use crate::class::protocol::{ClassState, RobotRef};
use crate::kinematics::Pose;
use crate::lesson::Lesson;

/// Model files the teacher sent that are kept (the newest).
const MODELS_KEPT: usize = 4;

/// A joint value applied and the one the app then shows differ by at most this (rad, m): more
/// is a student's own move made before the setup was taken.
const APPLIED_Q_TOLERANCE: f64 = 1e-9;

/// What a student's app keeps of the teacher.
#[derive(Debug, Default)]
pub(super) struct Follower {
    /// The teacher's latest state and its number.
    latest: Option<(ClassState, u64)>,
    /// Model files the teacher sent: id, name, contents (newest last).
    models: Vec<(String, String, String)>,
    /// What was applied last.
    applied: Option<Applied>,
    /// Apply the latest state at the next frame (following again, a robot just loaded).
    pub(super) reapply: bool,
    /// An exercise question is being answered: the teacher's view waits.
    pub(super) answering: bool,
}

/// A state applied, and the setup it left (once settled).
#[derive(Debug)]
struct Applied {
    /// The state's number.
    seq: u64,
    /// The robot it named.
    robot: RobotRef,
    /// The joints it set.
    q: Vec<f64>,
    /// The setup it left, taken in the next frame (the actions are applied at the end of the
    /// frame that made them).
    check: Check,
}

#[derive(Debug)]
enum Check {
    /// Applied in this frame: the setup is taken in the next.
    Applied,
    /// The setup the state left.
    Holding(Setup),
}

/// What a student's own move changes.
#[derive(Debug, Clone, PartialEq)]
struct Setup {
    generation: u64,
    q: Vec<f64>,
    targets: Vec<Pose>,
    camera: Camera,
}

impl Setup {
    fn of(app: &AppUi) -> Self {
        Self {
            generation: app.state.generation(),
            q: app.state.q().to_vec(),
            targets: app
                .state
                .targets()
                .iter()
                .map(|t| t.world_from_tool)
                .collect(),
            camera: app.tabs.view3d.camera,
        }
    }

    /// Whether `now` is another setup than this one (beyond rounding).
    fn moved_from(&self, now: &Setup) -> bool {
        let close = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12)
        };
        let pose_close = |a: &Pose, b: &Pose| {
            close(a.to_homogeneous().as_slice(), b.to_homogeneous().as_slice())
        };
        self.generation != now.generation
            || !close(&self.q, &now.q)
            || self.targets.len() != now.targets.len()
            || !self
                .targets
                .iter()
                .zip(&now.targets)
                .all(|(a, b)| pose_close(a, b))
            || self.camera != now.camera
    }
}

impl Follower {
    /// The teacher's state number `seq` arrived (an older one than the latest is dropped).
    pub(super) fn arrived(&mut self, state: ClassState, seq: u64) {
        if self.latest.as_ref().is_some_and(|(_, s)| *s > seq) {
            return;
        }
        self.latest = Some((state, seq));
    }

    /// Joined again (after a reconnection): the state numbers start afresh, and the state the
    /// server sends at once is applied (while following).
    pub(super) fn rejoined(&mut self) {
        self.latest = None;
        self.applied = None;
    }

    /// The student follows again after a class question's sheet: the teacher's view is applied
    /// again (the sheet's arm replaced by the teacher's robot).
    pub(super) fn done_answering(&mut self) {
        if self.answering {
            self.answering = false;
            self.applied = None;
            self.reapply = true;
        }
    }

    /// A model file the teacher sent.
    pub(super) fn model_arrived(&mut self, id: String, name: String, text: String) {
        self.models.retain(|(i, _, _)| *i != id);
        self.models.push((id, name, text));
        if self.models.len() > MODELS_KEPT {
            self.models.remove(0);
        }
    }
}

/// Whether the app shows the robot `robot` names already (a built-in by its name, unedited).
fn has_robot(app: &AppUi, robot: &RobotRef) -> bool {
    let s = &app.state;
    matches!(robot, RobotRef::Builtin(name) if s.spec() == name && !s.is_edited())
}

/// Actions a student's own move makes (any of them in a frame: exploring).
fn own_move(a: &Action) -> bool {
    matches!(
        a,
        Action::SetJoint(..)
            | Action::SetQ(_)
            | Action::ResetTo(_)
            | Action::SetTarget(..)
            | Action::TargetToTool(_)
            | Action::TargetFromTool { .. }
            | Action::SelectSolution(..)
            | Action::NextSolution
            | Action::SetSelfMotion(..)
            | Action::SelectBranch(..)
            | Action::CameraPreset(_)
            | Action::LookFrom { .. }
            | Action::SetCamera(_)
            | Action::Fit
            | Action::FitReach
            | Action::Load(_)
            | Action::OpenText { .. }
            | Action::CommitDh { .. }
    )
}

impl ClassClient {
    /// Student: the teacher's latest state.
    pub fn teacher_state(&self) -> Option<&ClassState> {
        self.student.latest.as_ref().map(|(s, _)| s)
    }

    /// Student: an exercise question is being answered (the teacher's view waits meanwhile).
    pub fn student_answering(&self) -> bool {
        self.student.answering
    }

    /// A student's frame: notices their own moves, applies the teacher's latest state while
    /// following.
    pub(super) fn follow(&mut self, app: &AppUi, out: &mut Actions) {
        if !self.following || self.student.answering {
            return;
        }
        // Following again after a class question: its sheet closes (the panels show everything).
        let sheet = app.tabs.exercise.sheet.as_ref();
        if sheet.is_some_and(|s| s.class.is_some()) && !out.0.contains(&Action::CloseExercise) {
            out.push(Action::CloseExercise);
        }
        let moved_now = out.0.iter().any(own_move);
        let f = &mut self.student;
        let mut explored = moved_now;
        if let Some(a) = &mut f.applied {
            let now = Setup::of(app);
            match &a.check {
                // Joints other than those applied: the student moved before this frame (a robot
                // just loaded is applied once more, exactly, before it is checked).
                Check::Applied if !f.reapply => {
                    let off = now.q.len() != a.q.len()
                        || now
                            .q
                            .iter()
                            .zip(&a.q)
                            .any(|(x, y)| (x - y).abs() > APPLIED_Q_TOLERANCE);
                    explored |= off;
                    a.check = Check::Holding(now);
                }
                Check::Applied => {}
                Check::Holding(setup) => explored |= setup.moved_from(&now),
            }
        }
        if explored {
            self.following = false;
            f.applied = None;
            self.note(Level::Info, "class: exploring on your own".into());
            return;
        }
        let fresh = match (&f.latest, &f.applied) {
            (Some((_, seq)), Some(a)) => *seq != a.seq || f.reapply,
            (Some(_), None) => true,
            (None, _) => false,
        };
        if fresh {
            self.apply_latest(app, out);
        }
    }

    /// Applies the teacher's latest state: the robot where it changed (then once more in the
    /// next frame, on the loaded robot), the joints, the rest as a one-step lesson, the joints
    /// again (the step's IK target may have moved them by rounding).
    fn apply_latest(&mut self, app: &AppUi, out: &mut Actions) {
        let f = &mut self.student;
        let Some((state, seq)) = f.latest.clone() else {
            return;
        };
        let same_robot = f.applied.as_ref().is_some_and(|a| {
            a.robot == state.robot
                && match &a.check {
                    Check::Holding(s) => s.generation == app.state.generation(),
                    Check::Applied => true,
                }
        }) || (f.applied.is_none() && has_robot(app, &state.robot));
        f.reapply = false;
        let mut actions = Actions::default();
        if !same_robot {
            match self.load_robot(&state.robot) {
                Ok(a) => actions.push(a),
                Err(e) => {
                    self.note(Level::Warning, format!("class: {e}"));
                    self.student.latest = None;
                    return;
                }
            }
            self.student.reapply = true;
        }
        let ee = if same_robot { app.ee() } else { 0 };
        actions.push(Action::SetQ(state.q.clone()));
        let mut view = state.view.clone();
        view.q = None;
        if view.scene.as_ref().is_some_and(toml::Value::is_str) {
            view.scene = None; // a path on the teacher's computer: only inline cells travel
        }
        let lesson = Lesson {
            title: "the teacher's view".into(),
            robot: toml::Value::String(String::new()),
            steps: vec![view],
        };
        let steps = step_actions(&lesson, 0, "the teacher's view", &app.state, ee);
        let keep = |a: &Action| !same_robot || *a != Action::ClearTrails;
        actions.0.extend(steps.0.into_iter().filter(keep));
        if same_robot {
            actions.push(Action::SetQ(state.q.clone()));
        }
        out.0.extend(actions.0);
        self.student.applied = Some(Applied {
            seq,
            robot: state.robot,
            q: state.q,
            check: Check::Applied,
        });
    }

    /// The action loading the teacher's robot: a built-in by its name (only a built-in's: a
    /// name is never opened as a path), a model file the teacher sent by its contents.
    fn load_robot(&self, robot: &RobotRef) -> Result<Action, String> {
        match robot {
            RobotRef::Builtin(name) => match crate::kinematics::models::built_in(name) {
                Some(_) => Ok(Action::Load(name.clone())),
                None => Err(format!("the teacher's robot {name:?} is no built-in model")),
            },
            RobotRef::Model { id, name } => {
                let (_, _, text) = self
                    .student
                    .models
                    .iter()
                    .find(|(i, _, _)| i == id)
                    .ok_or_else(|| format!("the teacher's model {name} has not arrived"))?;
                let ext = if name.to_ascii_lowercase().ends_with(".urdf") {
                    "urdf"
                } else {
                    "toml"
                };
                let name = format!("teacher's model.{ext}");
                match open_bytes(&name, text.as_bytes()) {
                    Opening::Model(_) => Ok(Action::OpenText {
                        name,
                        text: text.clone(),
                    }),
                    _ => Err(format!("the teacher's {name} is not a model file")),
                }
            }
        }
    }
}
