//! What a panel, a tab, the lesson player or a key asks the app to do. They read the shared
//! state and return actions; [`super::shell::AppUi::apply`] applies them in one place, so no
//! panel reaches into another's state and every change of the model goes through one door.

use super::state::{DhField, DisplayToggles, Hidden, Level};
use crate::camera::Preset;
use crate::kinematics::Pose;
use crate::kinematics::redundancy::Task;
use nalgebra::{Rotation3, Vector3};

/// One thing to do.
#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// Open a model: a built-in name or a path to a .toml or .urdf file.
    Load(String),
    /// "Open file...": the file dialog, or the in-app file browser where there is none.
    OpenDialog,
    /// "Save model as...": the file dialog, or a download in a browser.
    SaveDialog,
    /// Write the model to this file (.toml, or .urdf by its name).
    SaveModel(String),
    /// Commit the text of a DH table cell (on Enter or when the cell loses focus).
    CommitDh {
        /// Row (joint index in [`crate::kinematics::Robot::joints`]).
        joint: usize,
        /// Column.
        field: DhField,
        /// The text typed.
        text: String,
    },
    /// Undo the last model edit.
    Undo,
    /// Redo the last undone model edit.
    Redo,
    /// Back to the model as it was opened.
    ResetEdits,
    /// Set joint `k` (rad or m).
    SetJoint(usize, f64),
    /// Move the arm to `q` (rad, m), clamped into the limits; the targets follow.
    SetQ(Vec<f64>),
    /// Move to a named configuration.
    ResetTo(String),
    /// Make end-effector `k` the one the readouts and the target refer to.
    SelectEe(usize),
    /// Lock the posture while dragging.
    SetLock(bool),
    /// Move IK target `ee` (world, m).
    SetTarget(usize, Pose),
    /// Put target `ee` on the tool.
    TargetToTool(usize),
    /// Put target `ee` on the tool with its position (world, m) or its rotation (world from
    /// tool) replaced where given.
    TargetFromTool {
        /// The end-effector.
        ee: usize,
        /// The target's position instead of the tool's.
        position: Option<Vector3<f64>>,
        /// The target's rotation instead of the tool's.
        rotation: Option<Rotation3<f64>>,
    },
    /// Take solution `index` (0-based) of target `ee`.
    SelectSolution(usize, usize),
    /// Show the next solution of the current target.
    NextSolution,
    /// The task the gizmo obeys.
    SetTask(Task),
    /// Move the self-motion parameter of `ee` to a value (rad).
    SetSelfMotion(usize, f64),
    /// Take branch `k` of the exact self-motion of `ee`.
    SelectBranch(usize, usize),
    /// Show the construction overlay.
    ShowConstruction(bool),
    /// Show construction step `k` (0-based).
    ConstructionStep(usize),
    /// Set the Orientation tab up as a lesson step says.
    Orientation(Box<crate::lesson::OrientationStep>),
    /// What the 3D view draws.
    SetDisplay(DisplayToggles),
    /// What the panels hide while an exercise sheet is answered.
    SetHidden(Hidden),
    /// Clear the end-effector trails.
    ClearTrails,
    /// A camera preset, then fit.
    CameraPreset(Preset),
    /// Look from azimuth `yaw` and elevation `pitch` (rad) at `distance` (m), or framed to fit
    /// where no distance is given.
    LookFrom {
        /// Azimuth (rad).
        yaw: f32,
        /// Elevation (rad).
        pitch: f32,
        /// Distance from the camera's centre (m).
        distance: Option<f32>,
    },
    /// Show this figure in the Workspace tab: `this-model` or an excerpt figure's number.
    WorkspaceFigure(String),
    /// The whole camera, as a lesson saved it (look-at point, distance, angles, projection).
    SetCamera(crate::camera::Camera),
    /// Frame everything the arm can reach (a workspace overlay seen whole).
    FitReach,
    /// Fit the robot (and its ghosts and targets) in the view.
    Fit,
    /// Perspective / orthographic.
    ToggleProjection,
    /// The workspace overlay in the 3D view.
    ToggleWorkspace,
    /// Large fonts and thick lines, side panels collapsed to what a lesson needs.
    ToggleProjector,
    /// Show or hide both side panels.
    ToggleSidePanels,
    /// Enter or leave "present this figure" (F5; Escape leaves).
    TogglePresent,
    /// Leave "present this figure" (Escape).
    EndPresent,
    /// Save the window as a PNG.
    Screenshot,
    /// Start recording the 3D view, or stop and save the recording as a GIF.
    Record,
    /// The shortcut help.
    ToggleHelp,
    /// Show a central tab by its index.
    ShowTab(usize),
    /// Show step `k` (0-based) of the lesson being played.
    LessonStep(usize),
    /// Append the current setup to the lesson as a step and write the lesson file.
    SaveAsLesson,
    /// Stop playing the lesson (the state stays as it is).
    CloseLesson,
    /// Open an exercise sheet's key file (the Exercise tab).
    OpenExercise(String),
    /// Close the exercise sheet: the panels show everything again.
    CloseExercise,
    /// Write an exam's answer (`text`) to `path` (a download in a browser).
    SaveAnswer {
        /// The file (`student-NN.toml` or `.txt`).
        path: String,
        /// Its contents.
        text: String,
    },
    /// Open a file handed over as text (a model file, an exercise sheet), as a dropped file
    /// is opened: by its contents, `name` for messages.
    OpenText {
        /// The file's name (its extension tells a model's format).
        name: String,
        /// Its contents.
        text: String,
    },
    /// Something for the live class's client (the toolbar's "Start class", the class
    /// window, the Exercise tab's "Send answer").
    Class(super::class::ClassAction),
    /// A message for the status bar.
    Message(Level, String),
    /// Something about the cell's obstacles (the Cell menu, the cell panel, the gizmo).
    Cell(super::cell::CellAction),
    /// Something about the reachability overlay or base placement (the Show menu, the
    /// Reachability section, the 3D view).
    Reachability(super::reachability::ReachabilityAction),
}

/// Collects the actions of one frame.
#[derive(Debug, Default)]
pub struct Actions(pub Vec<Action>);

impl Actions {
    /// Adds an action.
    pub fn push(&mut self, a: Action) {
        self.0.push(a);
    }

    /// Adds a message for the status bar.
    pub fn message(&mut self, level: Level, text: impl Into<String>) {
        self.0.push(Action::Message(level, text.into()));
    }
}

impl Action {
    /// Why this action is refused while a sheet hides what `hidden` says: in an exam,
    /// everything that would carry the arm or its answer out of the app (saving the model or a
    /// lesson, pictures); the workspace overlay on a workspace sheet; the reachability overlay
    /// on a sheet that hides the workspace or the IK solutions.
    pub fn refusal(&self, hidden: &Hidden) -> Option<&'static str> {
        let carries_out = matches!(
            self,
            Action::SaveDialog
                | Action::SaveModel(_)
                | Action::SaveAsLesson
                | Action::Screenshot
                | Action::Record
        );
        if hidden.exam && carries_out {
            return Some("off during the exam: close the sheet in the Exercise tab first");
        }
        if hidden.workspace && matches!(self, Action::ToggleWorkspace) {
            return Some("the workspace is what the sheet asks for: it stays hidden");
        }
        use super::reachability::ReachabilityAction::{Compute, Show};
        let shows_reach = matches!(self, Action::Reachability(Show(true) | Compute(_)));
        if (hidden.workspace || hidden.solutions) && shows_reach {
            return Some("the sheet asks for what the reachability map shows: it stays hidden");
        }
        None
    }
}
