//! Playing a lesson ([`crate::lesson`]) in the app: each step sets the joints, the IK target,
//! the view and the overlays (as actions, which the shell applies); the caption is shown large
//! under the 3D view with Previous and Next (Page Up / Page Down); "Save as lesson" appends the
//! current setup as a step (the shell writes the file, a download in a browser).

use super::action::{Action, Actions};
use super::state::{AppState, Level};
use crate::camera::{Camera, Preset};
use crate::kinematics::orientation::{rotation_from_rpy, rpy_from_rotation};
use crate::lesson::{CameraSpec, Lesson, Overlay, Step};
use egui::RichText;
use nalgebra::Vector3;

/// The lesson being played: its text, where it came from, the step shown.
#[derive(Debug, Clone)]
pub struct LessonPlayer {
    /// The lesson.
    pub lesson: Lesson,
    /// Its file (or URL): errors name it, "Save as lesson" writes it.
    pub file: String,
    /// The step shown (0-based).
    pub step: usize,
    /// The step whose caption is being written: its editor stays until Done, whatever the
    /// caption holds (it once vanished after the first character, and the keys that followed
    /// ran as shortcuts).
    pub editing: Option<usize>,
}

/// The camera preset a step names.
fn preset(name: &str) -> Option<Preset> {
    match name {
        "front" => Some(Preset::Front),
        "side" => Some(Preset::Side),
        "top" => Some(Preset::Top),
        "iso" => Some(Preset::Iso),
        _ => None,
    }
}

impl LessonPlayer {
    /// `lesson`, read from `file`, at its first step.
    pub fn new(lesson: Lesson, file: &str) -> Self {
        Self {
            lesson,
            file: file.to_string(),
            step: 0,
            editing: None,
        }
    }

    /// A new lesson on the robot of `state`, without steps, to be written to `lesson.toml`.
    pub fn on(state: &AppState) -> Self {
        let lesson = Lesson {
            title: format!("{}: a lesson", state.robot().name),
            robot: toml::Value::String(state.spec().to_string()),
            steps: Vec::new(),
        };
        Self::new(lesson, "lesson.toml")
    }

    /// Goes to step `i` (clamped) and returns what it sets up, in order: the joints, the IK
    /// target of `ee`, the overlays, the view; with the step's name (`file: step n`) for the
    /// warnings of these actions. `None` where the lesson has no steps.
    pub fn go_to(&mut self, i: usize, state: &AppState, ee: usize) -> Option<(String, Actions)> {
        let n = self.lesson.steps.len();
        if n == 0 {
            return None;
        }
        let i = i.min(n - 1);
        self.step = i;
        let (lesson, file) = (&self.lesson, &self.file);
        let step = &lesson.steps[i];
        let mut out = Actions::default();
        match lesson.step_q(i, state.robot(), file) {
            Ok(Some(q)) => out.push(Action::SetQ(q)),
            Ok(None) => {}
            Err(e) => out.message(Level::Warning, e.to_string()),
        }
        // The step's target, or the tool's pose (at the step's joints).
        let (position, rotation) = match step.target_position {
            Some(p) => (
                Some(Vector3::from(p)),
                step.target_rpy_deg
                    .map(|r| rotation_from_rpy(&Vector3::from(r).map(f64::to_radians))),
            ),
            None => (None, None),
        };
        out.push(Action::TargetFromTool {
            ee,
            position,
            rotation,
        });
        let overlays = lesson.overlays(i);
        overlay_actions(&overlays, state, &mut out);
        out.push(
            match (&step.camera, step.view.as_deref().and_then(preset)) {
                (Some(c), _) => Action::LookFrom {
                    yaw: c.azimuth_deg.to_radians() as f32,
                    pitch: c.elevation_deg.to_radians() as f32,
                    distance: c.distance.map(|d| d as f32),
                },
                (None, Some(p)) => Action::CameraPreset(p),
                (None, None) => Action::Fit,
            },
        );
        if self.frames_reach() {
            out.push(Action::FitReach);
        }
        out.push(Action::ClearTrails);
        Some((format!("{file}: step {}", i + 1), out))
    }

    /// Whether the current step is framed for its overlays rather than for the arm alone: it
    /// shows the workspace and names no camera distance.
    pub fn frames_reach(&self) -> bool {
        let i = self.step.min(self.lesson.steps.len().saturating_sub(1));
        !self.lesson.steps.is_empty()
            && self.lesson.overlays(i).contains(&Overlay::Workspace)
            && self.lesson.steps[i]
                .camera
                .is_none_or(|c| c.distance.is_none())
    }

    /// Appends `step` to the lesson and shows it.
    pub fn append(&mut self, step: Step) {
        self.lesson.steps.push(step);
        self.step = self.lesson.steps.len() - 1;
    }

    /// The lesson bar under the 3D view: title, step, caption (large), Previous and Next, the
    /// caption of the step being written, "Save as lesson".
    pub fn bar(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        let n = self.lesson.steps.len();
        let i = self.step;
        let size = egui::TextStyle::Body.resolve(ui.style()).size * 1.35;
        ui.horizontal(|ui| {
            ui.label(RichText::new(&self.lesson.title).strong());
            ui.label(format!("step {} of {n}", (i + 1).min(n)));
            if ui.button("< Previous (PgUp)").clicked() {
                out.push(Action::LessonStep(i.saturating_sub(1)));
            }
            if ui.button("Next (PgDn) >").clicked() {
                out.push(Action::LessonStep((i + 1).min(n.saturating_sub(1))));
            }
            if ui.button("Save as lesson").clicked() {
                out.push(Action::SaveAsLesson);
            }
            if ui.button("Close lesson").clicked() {
                out.push(Action::CloseLesson);
            }
        });
        self.caption(ui, i, size);
        self.step_tools(ui, i, out);
    }

    /// Step `i`'s caption: large text with "Edit caption", or its editor, which keeps the
    /// keyboard (and so the shortcuts off) until Done or Escape.
    fn caption(&mut self, ui: &mut egui::Ui, i: usize, size: f32) {
        let Some(step) = self.lesson.steps.get_mut(i) else {
            return;
        };
        if step.caption.is_empty() {
            self.editing = Some(i);
        }
        if self.editing == Some(i) {
            let edit = ui.add(
                egui::TextEdit::multiline(&mut step.caption)
                    .id_salt(("lesson caption", i))
                    .hint_text("caption of this step (Markdown), saved with the next Save")
                    .desired_rows(2)
                    .desired_width(f32::INFINITY),
            );
            // Escape also leaves the field (egui drops its focus in the same frame).
            let escape = (edit.has_focus() || edit.lost_focus())
                && ui.input(|inp| inp.key_pressed(egui::Key::Escape));
            if ui.button("Done").clicked() || escape {
                self.editing = None;
                edit.surrender_focus();
            }
        } else {
            ui.horizontal_wrapped(|ui| {
                ui.add(egui::Label::new(RichText::new(&step.caption).size(size)).wrap());
                if ui.small_button("Edit caption").clicked() {
                    self.editing = Some(i);
                }
            });
        }
    }

    /// The step's order in the lesson: earlier, later, delete (the lesson's own state; the shell
    /// shows the step that is then current).
    fn step_tools(&mut self, ui: &mut egui::Ui, i: usize, out: &mut Actions) {
        let n = self.lesson.steps.len();
        if n == 0 {
            return;
        }
        ui.horizontal(|ui| {
            let steps = &mut self.lesson.steps;
            if ui
                .add_enabled(i > 0, egui::Button::new("Move step earlier"))
                .clicked()
            {
                steps.swap(i, i - 1);
                self.step = i - 1;
                self.editing = None;
            }
            if ui
                .add_enabled(i + 1 < n, egui::Button::new("Move step later"))
                .clicked()
            {
                steps.swap(i, i + 1);
                self.step = i + 1;
                self.editing = None;
            }
            if ui.button("Delete step").clicked() {
                steps.remove(i);
                self.editing = None;
                if !steps.is_empty() {
                    out.push(Action::LessonStep(i.min(steps.len() - 1)));
                }
                self.step = i.min(steps.len().saturating_sub(1));
            }
        });
    }
}

/// The overlays a step asks for, and no others.
fn overlay_actions(overlays: &[Overlay], state: &AppState, out: &mut Actions) {
    let has = |o| overlays.contains(&o);
    let mut d = state.display;
    d.ghosts = has(Overlay::Ghosts);
    d.frames = has(Overlay::Frames);
    d.labels = has(Overlay::Labels);
    d.self_motion_path = has(Overlay::SelfMotion);
    out.push(Action::SetDisplay(d));
    if d.workspace != has(Overlay::Workspace) {
        out.push(Action::ToggleWorkspace);
    }
    out.push(Action::ShowConstruction(has(Overlay::Construction)));
}

/// The app's current setup as a lesson step (what "Save as lesson" appends): the joints, the
/// target of `ee`, the overlays shown (`construction`: the construction overlay), the camera.
pub fn current_step(
    state: &AppState,
    ee: usize,
    construction: bool,
    cam: &Camera,
    caption: &str,
) -> Step {
    let d = &state.display;
    let mut overlays = Vec::new();
    for (on, o) in [
        (d.workspace, Overlay::Workspace),
        (construction, Overlay::Construction),
        (d.ghosts, Overlay::Ghosts),
        (d.frames, Overlay::Frames),
        (d.labels, Overlay::Labels),
        (d.self_motion_path, Overlay::SelfMotion),
    ] {
        if on {
            overlays.push(o);
        }
    }
    let target = state.target(ee).ok().map(|t| t.world_from_tool);
    Step {
        caption: caption.to_string(),
        q: Some(state.q().to_vec()),
        q_deg: None,
        target_position: target.map(|t| t.translation.vector.into()),
        target_rpy_deg: target.map(|t| {
            let a = rpy_from_rotation(&t.rotation).angles.map(f64::to_degrees);
            [a.x, a.y, a.z]
        }),
        view: None,
        camera: Some(CameraSpec {
            azimuth_deg: (cam.yaw as f64).to_degrees(),
            elevation_deg: (cam.pitch as f64).to_degrees(),
            distance: Some(cam.distance as f64),
        }),
        overlays: Some(overlays),
    }
}
