//! Lessons a teacher prepares once and gives every year: a TOML file naming a robot and a list
//! of steps, each with the joint values, the IK target, the view, the overlays and a caption in
//! Markdown. The app plays them (`armlab lesson FILE`, `?lesson=URL` in the browser) and
//! renders them to PNG for slides; "Save as lesson" appends the app's current setup as a step.
//! Parsing and writing only: no graphics, no file system (the callers read and write).
//!
//! ```toml
//! title = "The anthropomorphic arm's four postures"
//! robot = "anthropomorphic3r"          # a built-in, a path (relative to the lesson), or a
//!                                      # [robot] table in the model-file schema
//! [[steps]]
//! caption = "Four postures reach the same point (Fig. 2.33)."
//! q_deg = [0, 45, -90]                 # or q = [...] in rad (m for prismatic joints)
//! target_position = [1.0, 0.0, 0.5]    # optional IK target (m), in the world frame
//! target_rpy_deg = [0, 0, 0]           # its orientation (roll, pitch, yaw)
//! view = "iso"                         # front, side, top, iso
//! overlays = ["ghosts", "frames", "labels"]
//! scene = "cell.toml"                  # optional: the cell's obstacles from this step on
//! ```
//!
//! A step's `scene` is a scene file's path (relative to the lesson) or the scene file's
//! obstacles written in the lesson itself, as `[[steps.scene.obstacle]]` tables with the keys of
//! the scene file's `[[obstacle]]` (see [`crate::collision::CellScene`]; "Save as lesson" writes
//! the app's cell so). Replaying the step makes it the cell; a step without `scene` leaves the
//! cell as it is, so a scene given on the first step holds for the whole lesson.

use crate::kinematics::Robot;
use serde::{Deserialize, Serialize};
use std::path::Path;
use thiserror::Error;

/// What can be drawn over a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Overlay {
    /// The workspace (Sect. 2.10.1).
    Workspace,
    /// The construction behind the closed-form solution (Sect. 2.12).
    Construction,
    /// Every IK solution of the target as a ghost arm.
    Ghosts,
    /// The DH frames.
    Frames,
    /// The frames' labels.
    Labels,
    /// The self-motion's traced path and its tab (Sect. 2.10.2).
    SelfMotion,
    /// The floor grid. Unlike the others, a step that names it in neither list leaves it as
    /// it is (lessons written before it existed keep the grid the viewer had).
    Grid,
    /// The tool's trail. Left as it is when neither list names it, as the grid.
    Trail,
}

impl Overlay {
    /// Every overlay, in the file's spelling order.
    pub const ALL: [Overlay; 8] = [
        Overlay::Workspace,
        Overlay::Construction,
        Overlay::Ghosts,
        Overlay::Frames,
        Overlay::Labels,
        Overlay::SelfMotion,
        Overlay::Grid,
        Overlay::Trail,
    ];
}

/// A camera given by angles instead of a preset.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// Azimuth about the world z axis (deg).
    pub azimuth_deg: f64,
    /// Elevation above the x-y plane (deg).
    pub elevation_deg: f64,
    /// Distance from the target point (m); absent: framed to fit the arm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance: Option<f64>,
    /// The point looked at (world frame, m); absent: the arm's centre.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<[f64; 3]>,
    /// An orthographic view showing this height of the world (m), instead of a perspective one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orthographic_height: Option<f64>,
}

/// The app's central tab a step shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LessonTab {
    /// The 3D view.
    View3d,
    /// The workspace figure (with `figure` naming which).
    Workspace,
    /// The self-motion plots.
    SelfMotion,
    /// Calibration.
    Calibration,
    /// The exercise sheet.
    Exercise,
    /// The orientation lab (Sects. 2.2-2.6).
    Orientation,
}

/// One step of a lesson.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Step {
    /// What the class reads (Markdown).
    #[serde(default)]
    pub caption: String,
    /// Joint values (rad; m for prismatic joints).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q: Option<Vec<f64>>,
    /// Joint values with revolute joints in degrees (prismatic still m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q_deg: Option<Vec<f64>>,
    /// The IK target's position (m, world frame).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_position: Option<[f64; 3]>,
    /// The IK target's orientation as roll, pitch, yaw (deg); absent: the tool's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_rpy_deg: Option<[f64; 3]>,
    /// A camera preset: front, side, top, iso.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub view: Option<String>,
    /// A camera by angles (wins over `view`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraSpec>,
    /// What is drawn; absent: the arm with its frames and labels.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overlays: Option<Vec<Overlay>>,
    /// What is explicitly not drawn ("Save as lesson" writes every overlay in one list or
    /// the other, so that nothing the app remembers from another session shows on replay).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overlays_off: Option<Vec<Overlay>>,
    /// The central tab shown; absent: the tab stays as it is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tab: Option<LessonTab>,
    /// The Workspace tab's figure: `this-model`, or an excerpt figure's number (`2.30`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub figure: Option<String>,
    /// The construction's step shown (1-based), with the construction overlay.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub construction_step: Option<usize>,
    /// The Orientation tab's setup (with `tab = "orientation"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<OrientationStep>,
    /// The cell's obstacles from this step on: a scene file's path (relative to the lesson),
    /// or a table holding the scene file's `obstacle` list; absent: the cell stays as it is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene: Option<toml::Value>,
}

/// Where a step's scene comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneSource {
    /// A scene file's path as written (resolve it against the lesson's folder with
    /// [`resolve_spec`]).
    Path(String),
    /// The obstacles written in the lesson, as a scene file's text (`[[obstacle]]` tables).
    Inline(String),
}

/// What the Orientation tab shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrientationMode {
    /// One representation edited, the others shown.
    #[default]
    Turn,
    /// A composition of elementary rotations, step by step.
    Compose,
    /// Problem 2.15: a sum of two orientations in both orders.
    Sum,
    /// Problem 2.16: the commutator against the angle.
    Small,
}

/// A representation the Orientation tab edits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrientationRep {
    /// ZYZ Euler angles (2.18).
    Zyz,
    /// ZXZ Euler angles (Problem 2.1).
    Zxz,
    /// Roll, pitch, yaw (2.21).
    Rpy,
    /// Angle and axis (2.25).
    AxisAngle,
    /// Unit quaternion (2.33).
    Quaternion,
}

impl OrientationRep {
    /// How many values it takes: 3 angles, or theta and r, or eta and epsilon.
    pub fn value_count(self) -> usize {
        match self {
            OrientationRep::AxisAngle | OrientationRep::Quaternion => 4,
            _ => 3,
        }
    }
}

/// One elementary rotation of a lesson's sequence, its angle in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SequenceStep {
    /// About the current or the fixed frame.
    pub frame: crate::kinematics::orientation::StepFrame,
    /// The axis.
    pub axis: crate::kinematics::orientation::Axis,
    /// The angle (deg).
    pub angle_deg: f64,
}

/// The Orientation tab's setup in a lesson step:
///
/// ```toml
/// [steps.orientation]
/// mode = "turn"                 # turn, compose, sum, small
/// edit = "zyz"                  # zyz, zxz, rpy, axis-angle, quaternion
/// values = [30, 45, 60]         # degrees for angles (theta of angle-axis too)
/// sequence = [{ frame = "current", axis = "z", angle_deg = 30 }]
/// shown = 1                     # the composition's steps applied
/// ```
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientationStep {
    /// What the tab shows.
    #[serde(default)]
    pub mode: OrientationMode,
    /// The representation edited.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edit: Option<OrientationRep>,
    /// Its values (degrees for angles).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<f64>>,
    /// The composition's sequence, in the order stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sequence: Option<Vec<SequenceStep>>,
    /// How many of its steps are applied (absent: all).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shown: Option<usize>,
}

impl OrientationStep {
    /// What is wrong with it, if anything.
    fn check(&self) -> Option<String> {
        let values = self.values.as_deref().unwrap_or_default();
        if let Some(v) = self.values.as_ref()
            && v.iter().any(|x| !x.is_finite())
        {
            return Some("orientation.values: every number must be finite".into());
        }
        if let Some(rep) = self.edit
            && self.values.is_some()
            && values.len() != rep.value_count()
        {
            return Some(format!(
                "orientation.values: {:?} takes {} values, {} given",
                rep,
                rep.value_count(),
                values.len()
            ));
        }
        if self.values.is_some() && self.edit.is_none() {
            return Some(
                "orientation.values: say which representation they are (edit = ...)".into(),
            );
        }
        let seq = self.sequence.as_deref().unwrap_or_default();
        if seq.iter().any(|s| !s.angle_deg.is_finite()) {
            return Some("orientation.sequence: every angle must be finite".into());
        }
        match self.shown {
            Some(k) if k > seq.len() => Some(format!(
                "orientation.shown: {k} steps shown of a sequence of {}",
                seq.len()
            )),
            _ => None,
        }
    }
}

/// A lesson as in its file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Lesson {
    /// Its title.
    pub title: String,
    /// A built-in name or a model file's path (relative to the lesson), or a model embedded as
    /// a table in the model-file schema.
    pub robot: toml::Value,
    /// The steps, in order.
    #[serde(default)]
    pub steps: Vec<Step>,
}

/// Where a lesson's robot comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum RobotSource {
    /// A built-in name or a path, as written (resolve paths against the lesson's folder).
    Spec(String),
    /// A model file's text, embedded.
    Embedded(String),
}

/// What is wrong with a lesson.
#[derive(Debug, Error, PartialEq)]
pub enum LessonError {
    /// Not a valid lesson file.
    #[error("{file}: line {line}: {message}")]
    Parse {
        /// The file.
        file: String,
        /// The line (1-based; 0 where unknown).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A step that does not fit the robot.
    #[error("{file}: step {step}: {message}")]
    Step {
        /// The file.
        file: String,
        /// The step (1-based).
        step: usize,
        /// What is wrong.
        message: String,
    },
}

impl Lesson {
    /// Parses a lesson's text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Lesson, LessonError> {
        let lesson: Lesson = toml::from_str(text).map_err(|e| LessonError::Parse {
            file: file.into(),
            line: e.span().map_or(0, |s| {
                text[..s.start.min(text.len())].matches('\n').count() + 1
            }),
            message: e.message().to_string(),
        })?;
        lesson
            .robot_source()
            .map_err(|message| LessonError::Parse {
                file: file.into(),
                line: 0,
                message,
            })?;
        for (i, s) in lesson.steps.iter().enumerate() {
            if s.q.is_some() && s.q_deg.is_some() {
                return Err(LessonError::Step {
                    file: file.into(),
                    step: i + 1,
                    message: "give q or q_deg, not both".into(),
                });
            }
            if let Some(v) = &s.view
                && !["front", "side", "top", "iso"].contains(&v.as_str())
            {
                return Err(LessonError::Step {
                    file: file.into(),
                    step: i + 1,
                    message: format!("view {v:?}: the views are front, side, top, iso"),
                });
            }
            let step_error = |message: String| LessonError::Step {
                file: file.into(),
                step: i + 1,
                message,
            };
            if let (Some(on), Some(off)) = (&s.overlays, &s.overlays_off)
                && let Some(o) = on.iter().find(|o| off.contains(o))
            {
                return Err(step_error(format!(
                    "overlay {o:?} is both in overlays and in overlays_off"
                )));
            }
            if let Some(field) = non_finite(s) {
                return Err(step_error(format!("{field}: every number must be finite")));
            }
            if s.construction_step == Some(0) {
                return Err(step_error("construction_step counts from 1".to_string()));
            }
            if let Some(message) = s.orientation.as_ref().and_then(OrientationStep::check) {
                return Err(step_error(message));
            }
            if let Some(Err(message)) = lesson.step_scene(i) {
                return Err(step_error(message));
            }
        }
        Ok(lesson)
    }

    /// Whether `text` is a lesson (a TOML file with a title and `[[steps]]`) rather than a
    /// model file: `None` if not, else the lesson or why it cannot be read (as text).
    pub fn detect(text: &str, file: &str) -> Option<Result<Lesson, String>> {
        let table: toml::Table = toml::from_str(text).ok()?;
        if !(table.contains_key("steps") && table.contains_key("title")) {
            return None;
        }
        Some(Lesson::parse(text, file).map_err(|e| e.to_string()))
    }

    /// The lesson as TOML (what "Save as lesson" writes).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// Where the robot comes from.
    pub fn robot_source(&self) -> Result<RobotSource, String> {
        match &self.robot {
            toml::Value::String(s) => Ok(RobotSource::Spec(s.clone())),
            toml::Value::Table(t) => toml::to_string(t)
                .map(RobotSource::Embedded)
                .map_err(|e| e.to_string()),
            _ => Err("robot: a built-in name, a path, or a [robot] table".into()),
        }
    }

    /// The joint values of step `i` for `robot` (rad, m), if the step gives them; checked
    /// against the robot's number of joints.
    pub fn step_q(
        &self,
        i: usize,
        robot: &Robot,
        file: &str,
    ) -> Result<Option<Vec<f64>>, LessonError> {
        let s = &self.steps[i];
        let q = match (&s.q, &s.q_deg) {
            (Some(q), _) => q.clone(),
            (None, Some(q)) => q
                .iter()
                .enumerate()
                .map(|(k, v)| {
                    if k < robot.dof()
                        && robot.dof_joint(k).kind == crate::kinematics::JointKind::Revolute
                    {
                        v.to_radians()
                    } else {
                        *v
                    }
                })
                .collect(),
            (None, None) => return Ok(None),
        };
        if q.len() != robot.dof() {
            return Err(LessonError::Step {
                file: file.into(),
                step: i + 1,
                message: format!(
                    "{} joint values for a robot with {} joints",
                    q.len(),
                    robot.dof()
                ),
            });
        }
        Ok(Some(q))
    }

    /// Where the scene of step `i` comes from (`None`: the step leaves the cell as it is), or
    /// why its `scene` is not usable.
    pub fn step_scene(&self, i: usize) -> Option<Result<SceneSource, String>> {
        let scene = self.steps.get(i)?.scene.as_ref()?;
        Some(match scene {
            toml::Value::String(path) => Ok(SceneSource::Path(path.clone())),
            toml::Value::Table(t) if t.keys().all(|k| k == "obstacle") => match t.get("obstacle") {
                None | Some(toml::Value::Array(_)) => toml::to_string(t)
                    .map(SceneSource::Inline)
                    .map_err(|e| format!("scene: {e}")),
                Some(_) => {
                    Err("scene.obstacle: a list of [[steps.scene.obstacle]] tables".to_string())
                }
            },
            toml::Value::Table(_) => Err(
                "scene: a scene file's path, or [[steps.scene.obstacle]] tables (no other keys)"
                    .to_string(),
            ),
            _ => Err("scene: a scene file's path, or [[steps.scene.obstacle]] tables".to_string()),
        })
    }

    /// The overlays step `i` turns off explicitly (`overlays_off`; none when absent).
    pub fn overlays_off(&self, i: usize) -> Vec<Overlay> {
        self.steps[i].overlays_off.clone().unwrap_or_default()
    }

    /// The overlays of step `i` (default: frames and labels).
    pub fn overlays(&self, i: usize) -> Vec<Overlay> {
        self.steps[i]
            .overlays
            .clone()
            .unwrap_or_else(|| vec![Overlay::Frames, Overlay::Labels])
    }
}

/// The first field of `step` holding a number that is not finite (NaN or infinite), if any.
fn non_finite(step: &Step) -> Option<&'static str> {
    let bad = |v: &[f64]| v.iter().any(|x| !x.is_finite());
    let camera = step.camera.map(|c| {
        let mut v = vec![c.azimuth_deg, c.elevation_deg];
        v.extend(c.distance);
        v.extend(c.target.into_iter().flatten());
        v.extend(c.orthographic_height);
        v
    });
    [
        ("q", step.q.clone()),
        ("q_deg", step.q_deg.clone()),
        ("target_position", step.target_position.map(|p| p.to_vec())),
        ("target_rpy_deg", step.target_rpy_deg.map(|p| p.to_vec())),
        ("camera", camera),
    ]
    .into_iter()
    .find(|(_, v)| v.as_deref().is_some_and(bad))
    .map(|(name, _)| name)
}

/// Resolves a robot spec written in a lesson at `lesson_path`: a built-in name stays, a
/// relative path is taken from the lesson's folder.
pub fn resolve_spec(spec: &str, lesson_path: &Path) -> String {
    if crate::kinematics::models::built_in(spec).is_some() || Path::new(spec).is_absolute() {
        return spec.to_string();
    }
    match lesson_path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(spec).to_string_lossy().into_owned(),
        _ => spec.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lesson_round_trips_and_errors_name_the_line() {
        let text = "title = \"t\"\nrobot = \"planar2\"\n[[steps]]\ncaption = \"a\"\nq_deg = [0, 90]\noverlays = [\"ghosts\"]\n";
        let l = Lesson::parse(text, "l.toml").unwrap();
        assert_eq!(l.steps[0].overlays, Some(vec![Overlay::Ghosts]));
        assert_eq!(Lesson::parse(&l.to_toml(), "again").unwrap(), l);
        let bad = "title = \"t\"\nrobot = \"planar2\"\n[[steps]]\ncaptoin = \"a\"\n";
        let e = Lesson::parse(bad, "l.toml").unwrap_err();
        assert!(e.to_string().starts_with("l.toml: line 4"), "{e}");
    }
}
