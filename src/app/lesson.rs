//! Playing a lesson ([`crate::lesson`]) in the app: each step sets the joints, the IK target,
//! the view and the overlays (as actions, which the shell applies); the caption is shown large
//! under the 3D view with Previous and Next (Page Up / Page Down); "Save as lesson" appends the
//! current setup as a step (the shell writes the file, a download in a browser).

use super::action::{Action, Actions};
use super::state::{AppState, Level};
use crate::camera::{Camera, Preset, Projection};
use crate::kinematics::orientation::{rotation_from_rpy, rpy_from_rotation};
use crate::lesson::{CameraSpec, Lesson, LessonTab, Overlay, Step};
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
    /// The caption's rendered Markdown, kept between frames.
    pub caption_view: super::markdown::MarkdownCache,
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
            caption_view: Default::default(),
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
    /// target of `ee`, the overlays, the view (see [`step_actions`]); with the step's name
    /// (`file: step n`) for the warnings of these actions. `None` where the lesson has no steps.
    pub fn go_to(&mut self, i: usize, state: &AppState, ee: usize) -> Option<(String, Actions)> {
        let n = self.lesson.steps.len();
        if n == 0 {
            return None;
        }
        let i = i.min(n - 1);
        self.step = i;
        let out = step_actions(&self.lesson, i, &self.file, state, ee);
        Some((format!("{}: step {}", self.file, i + 1), out))
    }

    /// Whether the current step is framed for its overlays rather than for the arm alone: it
    /// shows the workspace and names no camera distance.
    pub fn frames_reach(&self) -> bool {
        let i = self.step.min(self.lesson.steps.len().saturating_sub(1));
        frames_reach(&self.lesson, i)
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
            // The caption (Markdown) beside its Edit button, wrapping in the width left.
            ui.horizontal_top(|ui| {
                let width = (ui.available_width() - 110.0).max(120.0);
                ui.vertical(|ui| {
                    ui.set_max_width(width);
                    super::markdown::show(ui, &mut self.caption_view, &step.caption, size);
                });
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

/// What showing step `i` of `lesson` (read from `file`) sets up, in order: the joints, the IK
/// target of `ee` (the step's, else the tool's at the step's joints), the overlays, the cell, the
/// construction's step, the figure, the tab, the orientation lab, the camera, and the trails
/// cleared. The lesson player and the live class's students (a one-step lesson made of the
/// teacher's setup) share it. What cannot be read is a warning naming the step.
pub fn step_actions(lesson: &Lesson, i: usize, file: &str, state: &AppState, ee: usize) -> Actions {
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
    let overlays = (lesson.overlays(i), lesson.overlays_off(i));
    overlay_actions(&overlays, state, &mut out);
    scene_action(lesson, i, file, state, &mut out);
    view_actions(step, &mut out);
    if frames_reach(lesson, i) {
        out.push(Action::FitReach);
    }
    out.push(Action::ClearTrails);
    out
}

/// The step's construction, figure, tab, orientation lab and camera.
fn view_actions(step: &Step, out: &mut Actions) {
    if let Some(k) = step.construction_step {
        out.push(Action::ShowConstruction(true));
        out.push(Action::ConstructionStep(k.saturating_sub(1)));
    }
    if let Some(f) = &step.figure {
        out.push(Action::WorkspaceFigure(f.clone()));
    }
    if let Some(t) = step.tab {
        out.push(Action::ShowTab(tab_index(t)));
    }
    if let Some(o) = &step.orientation {
        out.push(Action::Orientation(Box::new(o.clone())));
    }
    out.push(
        match (&step.camera, step.view.as_deref().and_then(preset)) {
            (Some(c), _) => camera_action(c),
            (None, Some(p)) => Action::CameraPreset(p),
            (None, None) => Action::Fit,
        },
    );
}

/// Whether step `i` of `lesson` is framed for its overlays rather than for the arm alone: it
/// shows the workspace and names no camera distance.
fn frames_reach(lesson: &Lesson, i: usize) -> bool {
    !lesson.steps.is_empty()
        && lesson.overlays(i).contains(&Overlay::Workspace)
        && lesson.steps[i].camera.is_none_or(|c| c.distance.is_none())
}

/// The camera a step names: the whole camera where it gives the look-at point and the
/// distance (as "Save as lesson" writes it), else its angles around the arm.
fn camera_action(c: &CameraSpec) -> Action {
    let (yaw, pitch) = (
        c.azimuth_deg.to_radians() as f32,
        c.elevation_deg.to_radians() as f32,
    );
    match (c.target, c.distance) {
        (Some(t), Some(distance)) => Action::SetCamera(Camera {
            target: nalgebra::Point3::new(t[0] as f32, t[1] as f32, t[2] as f32),
            distance: distance as f32,
            yaw,
            pitch,
            projection: match c.orthographic_height {
                Some(height) => Projection::Orthographic {
                    height: height as f32,
                },
                None => Projection::Perspective {
                    fov_y: Camera::default_fov(),
                },
            },
        }),
        _ => Action::LookFrom {
            yaw,
            pitch,
            distance: c.distance.map(|d| d as f32),
        },
    }
}

/// The app's tab index of a lesson's tab.
fn tab_index(t: LessonTab) -> usize {
    use super::tabs;
    match t {
        LessonTab::View3d => tabs::VIEW3D,
        LessonTab::Workspace => tabs::WORKSPACE,
        LessonTab::SelfMotion => tabs::SELF_MOTION,
        LessonTab::Calibration => tabs::CALIBRATION,
        LessonTab::Exercise => tabs::EXERCISE,
        LessonTab::Orientation => tabs::ORIENTATION,
    }
}

/// The lesson's name of the app's tab `index`.
fn lesson_tab(index: usize) -> LessonTab {
    use super::tabs;
    match index {
        tabs::WORKSPACE => LessonTab::Workspace,
        tabs::SELF_MOTION => LessonTab::SelfMotion,
        tabs::CALIBRATION => LessonTab::Calibration,
        tabs::EXERCISE => LessonTab::Exercise,
        tabs::ORIENTATION => LessonTab::Orientation,
        _ => LessonTab::View3d,
    }
}

/// The overlays a step asks for (`on`), and no others; the grid and the trail as the step
/// names them in `on` or `off`, else as they are.
fn overlay_actions((on, off): &(Vec<Overlay>, Vec<Overlay>), state: &AppState, out: &mut Actions) {
    let has = |o| on.contains(&o);
    let named = |o, now: bool| has(o) || (now && !off.contains(&o));
    let mut d = state.display;
    d.ghosts = has(Overlay::Ghosts);
    d.frames = has(Overlay::Frames);
    d.labels = has(Overlay::Labels);
    d.self_motion_path = has(Overlay::SelfMotion);
    d.grid = named(Overlay::Grid, d.grid);
    d.trail = named(Overlay::Trail, d.trail);
    out.push(Action::SetDisplay(d));
    if d.workspace != has(Overlay::Workspace) {
        out.push(Action::ToggleWorkspace);
    }
    out.push(Action::ShowConstruction(has(Overlay::Construction)));
}

/// What the class sees besides the state: the 3D view's camera, the tab, the Workspace tab's
/// figure, the construction's step (`None`: the construction is not shown).
#[derive(Debug, Clone)]
pub struct Seen {
    /// The 3D view's camera.
    pub camera: Camera,
    /// The central tab's index.
    pub tab: usize,
    /// The Workspace tab's figure (`this-model`, `2.30`).
    pub figure: String,
    /// The construction's step shown (0-based), if the construction is.
    pub construction: Option<usize>,
    /// The Orientation tab's setup, when it is the tab shown.
    pub orientation: Option<crate::lesson::OrientationStep>,
}

impl Seen {
    /// What the window shows: `tabs` with tab `tab` open, and the construction panel.
    pub fn of(
        tabs: &super::tabs::Tabs,
        tab: usize,
        construction: &super::panels::construction::ConstructionPanel,
    ) -> Self {
        Self {
            camera: tabs.view3d.camera,
            tab,
            figure: tabs.workspace.figure_name(),
            construction: construction.shown.then_some(construction.step),
            orientation: (tab == super::tabs::ORIENTATION).then(|| tabs.orientation.lesson_step()),
        }
    }
}

/// The app's current setup as a lesson step (what "Save as lesson" appends): the joints, the
/// target of `ee`, every overlay on or off, the construction's step, the tab and its figure,
/// the whole camera.
pub fn current_step(state: &AppState, ee: usize, seen: &Seen, caption: &str) -> Step {
    let (cam, construction) = (&seen.camera, seen.construction.is_some());
    let d = &state.display;
    let (mut overlays, mut off) = (Vec::new(), Vec::new());
    for (on, o) in [
        (d.workspace, Overlay::Workspace),
        (construction, Overlay::Construction),
        (d.ghosts, Overlay::Ghosts),
        (d.frames, Overlay::Frames),
        (d.labels, Overlay::Labels),
        (d.self_motion_path, Overlay::SelfMotion),
        (d.grid, Overlay::Grid),
        (d.trail, Overlay::Trail),
    ] {
        if on {
            overlays.push(o);
        } else {
            off.push(o);
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
            target: Some(cam.target.coords.map(f64::from).into()),
            orthographic_height: match cam.projection {
                Projection::Orthographic { height } => Some(height.into()),
                Projection::Perspective { .. } => None,
            },
        }),
        overlays: Some(overlays),
        overlays_off: Some(off),
        tab: Some(lesson_tab(seen.tab)),
        figure: Some(seen.figure.to_string()),
        construction_step: seen.construction.map(|k| k + 1),
        orientation: seen.orientation.clone(),
        scene: state.cell_scene().and_then(inline_scene),
    }
}

/// The cell's obstacles as a lesson step writes them: the scene file's `obstacle` tables.
fn inline_scene(scene: &crate::collision::CellScene) -> Option<toml::Value> {
    toml::from_str::<toml::Table>(&scene.to_toml())
        .ok()
        .map(toml::Value::Table)
}

/// The cell of step `i` of `lesson` (read from `file`), where it names one that differs from
/// the app's (a scene file read relative to the lesson, or the obstacles the step writes); what
/// cannot be read is a warning naming the step, the file, the line and the obstacle, and the
/// cell stays as it is.
fn scene_action(lesson: &Lesson, i: usize, file: &str, state: &AppState, out: &mut Actions) {
    use super::cell::CellAction;
    use crate::collision::CellScene;
    use crate::lesson::SceneSource;
    let step = format!("{file}: step {}", i + 1);
    let read = match lesson.step_scene(i) {
        None => return,
        Some(Err(e)) => Err(e),
        Some(Ok(SceneSource::Path(p))) => {
            let path = crate::lesson::resolve_spec(&p, std::path::Path::new(file));
            CellScene::read(std::path::Path::new(&path)).map_err(|e| e.to_string())
        }
        Some(Ok(SceneSource::Inline(text))) => {
            // The lines of the text made from the step's tables are not the lesson's: the
            // message names the step and the obstacle instead.
            CellScene::parse(&text, std::path::Path::new(file)).map_err(|e| match e {
                crate::collision::CollisionError::Obstacle {
                    obstacle, problem, ..
                } => format!("scene: obstacle \"{obstacle}\": {problem}"),
                other => format!("scene: {other}"),
            })
        }
    };
    match read {
        Ok(scene) => {
            let same = state
                .cell_scene()
                .is_some_and(|c| c.obstacles == scene.obstacles);
            if !same {
                out.push(Action::Cell(CellAction::Use(Some(Box::new(scene)))));
            }
        }
        Err(e) => out.message(Level::Warning, format!("{step}: {e}")),
    }
}
