//! Playing a lesson ([`crate::lesson`]) in the app: each step sets the joints, the IK target,
//! the view and the overlays; the caption is shown large under the 3D view with Previous and
//! Next (Page Up / Page Down); "Save as lesson" appends the current setup as a step and writes
//! the file (a download in a browser).

use super::action::{Action, Actions};
use super::shell::AppUi;
use super::state::Level;
use crate::camera::Preset;
use crate::kinematics::Pose;
use crate::kinematics::orientation::{rotation_from_rpy, rpy_from_rotation};
use crate::lesson::{CameraSpec, Lesson, Overlay, RobotSource, Step, resolve_spec};
use egui::RichText;
use nalgebra::{Translation3, Vector3};

/// The lesson being played: its text, where it came from, the step shown.
#[derive(Debug, Clone)]
pub struct LessonPlayer {
    /// The lesson.
    pub lesson: Lesson,
    /// Its file (or URL): errors name it, "Save as lesson" writes it.
    pub file: String,
    /// The step shown (0-based).
    pub step: usize,
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

impl AppUi {
    /// Opens `lesson` (read from `file`): its robot, then its first step. The app's state is
    /// kept if the robot cannot be loaded.
    pub fn open_lesson(&mut self, lesson: Lesson, file: &str) -> Result<(), String> {
        let loaded = match lesson.robot_source()? {
            RobotSource::Spec(spec) => {
                let spec = resolve_spec(&spec, std::path::Path::new(file));
                self.state.load_model(&spec)
            }
            RobotSource::Embedded(text) => self.state.load_model_text("lesson robot.toml", &text),
        };
        loaded.map_err(|e| format!("{file}: robot: {e}"))?;
        self.model_changed();
        self.lesson = Some(LessonPlayer {
            lesson,
            file: file.to_string(),
            step: 0,
        });
        self.go_to_step(0);
        Ok(())
    }

    /// Opens the lesson file at `path` (desktop).
    pub fn open_lesson_file(&mut self, path: &str) -> Result<(), String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
        let lesson = Lesson::parse(&text, path).map_err(|e| e.to_string())?;
        self.open_lesson(lesson, path)
    }

    /// Shows step `i` (clamped): joints, target, overlays, view.
    pub fn go_to_step(&mut self, i: usize) {
        let Some(player) = &mut self.lesson else {
            return;
        };
        if player.lesson.steps.is_empty() {
            return;
        }
        let i = i.min(player.lesson.steps.len() - 1);
        player.step = i;
        let (lesson, file) = (player.lesson.clone(), player.file.clone());
        let step = &lesson.steps[i];
        match lesson.step_q(i, self.state.robot(), &file) {
            Ok(Some(q)) => {
                if let Err(e) = self.state.set_q(&q) {
                    self.state
                        .push_message(Level::Warning, format!("{file}: step {}: {e}", i + 1));
                }
            }
            Ok(None) => {}
            Err(e) => self.state.push_message(Level::Warning, e.to_string()),
        }
        self.step_target(step, i, &file);
        self.step_overlays(&lesson.overlays(i));
        match (&step.camera, step.view.as_deref().and_then(preset)) {
            (Some(c), _) => self.step_camera(c),
            (None, Some(p)) => self.tabs.view3d.preset(p, &self.state),
            (None, None) => self.tabs.view3d.fit(&self.state),
        }
        let framed = step.camera.is_none_or(|c| c.distance.is_none());
        if framed && lesson.overlays(i).contains(&Overlay::Workspace) {
            self.frame_reach();
        }
        self.state.clear_trails();
    }

    /// The step's IK target, or the tool's pose.
    fn step_target(&mut self, step: &Step, i: usize, file: &str) {
        let ee = self.ee();
        let Ok(tool) = self.state.robot().fk_ee(self.state.q(), ee) else {
            return;
        };
        let target = match step.target_position {
            Some(p) => {
                let rotation = match step.target_rpy_deg {
                    Some(r) => rotation_from_rpy(&Vector3::from(r).map(f64::to_radians)),
                    None => tool.rotation,
                };
                Pose::from_parts(Translation3::from(Vector3::from(p)), rotation)
            }
            None => tool,
        };
        if let Err(e) = self.state.set_target(ee, target) {
            self.state
                .push_message(Level::Warning, format!("{file}: step {}: {e}", i + 1));
        }
    }

    /// The overlays a step asks for, and no others.
    fn step_overlays(&mut self, overlays: &[Overlay]) {
        let has = |o| overlays.contains(&o);
        let d = &mut self.state.display;
        d.ghosts = has(Overlay::Ghosts);
        d.frames = has(Overlay::Frames);
        d.labels = has(Overlay::Labels);
        d.self_motion_path = has(Overlay::SelfMotion);
        if d.workspace != has(Overlay::Workspace) {
            self.apply(Action::ToggleWorkspace);
        }
        self.ik.construction.shown = has(Overlay::Construction);
    }

    /// Frames the lesson's current step for its overlays where the arm alone is not the
    /// picture (a workspace); false where the usual framing applies.
    pub fn frame_lesson_step(&mut self) -> bool {
        let Some(p) = &self.lesson else {
            return false;
        };
        let i = p.step.min(p.lesson.steps.len().saturating_sub(1));
        let wanted = !p.lesson.steps.is_empty()
            && p.lesson.overlays(i).contains(&Overlay::Workspace)
            && p.lesson.steps[i]
                .camera
                .is_none_or(|c| c.distance.is_none());
        if wanted {
            self.frame_reach();
        }
        wanted
    }

    /// Frames everything the arm can reach (a box of its longest chain around the base), so
    /// that a workspace overlay is seen whole.
    fn frame_reach(&mut self) {
        let reach = self.state.robot().longest_chain_length() as f32;
        let o = self.state.robot().base.translation.vector.map(|v| v as f32);
        let corners: Vec<nalgebra::Point3<f32>> = (0..8)
            .map(|c| {
                let s = |bit: i32| if c & bit == 0 { -reach } else { reach };
                nalgebra::Point3::new(o.x + s(1), o.y + s(2), o.z + s(4))
            })
            .collect();
        let [w, h] = self.tabs.view3d.viewport_px;
        let mut camera = self.tabs.view3d.camera;
        camera.fit_points(&corners, w, h, 0.9);
        self.tabs.view3d.set_camera(camera);
    }

    /// A camera by angles; framed to fit when no distance is given.
    fn step_camera(&mut self, c: &CameraSpec) {
        let cam = &mut self.tabs.view3d.camera;
        cam.yaw = c.azimuth_deg.to_radians() as f32;
        cam.pitch = (c.elevation_deg.to_radians() as f32).clamp(-1.55, 1.55);
        match c.distance {
            Some(d) => {
                let cam = *cam;
                self.tabs.view3d.set_camera(crate::camera::Camera {
                    distance: d as f32,
                    ..cam
                });
            }
            None => self.tabs.view3d.fit(&self.state),
        }
    }

    /// The app's current setup as a lesson step (what "Save as lesson" appends).
    pub fn current_step(&self, caption: &str) -> Step {
        let d = &self.state.display;
        let mut overlays = Vec::new();
        for (on, o) in [
            (d.workspace, Overlay::Workspace),
            (self.ik.construction.shown, Overlay::Construction),
            (d.ghosts, Overlay::Ghosts),
            (d.frames, Overlay::Frames),
            (d.labels, Overlay::Labels),
            (d.self_motion_path, Overlay::SelfMotion),
        ] {
            if on {
                overlays.push(o);
            }
        }
        let target = self.state.target(self.ee()).ok().map(|t| t.world_from_tool);
        let cam = self.tabs.view3d.camera;
        Step {
            caption: caption.to_string(),
            q: Some(self.state.q().to_vec()),
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

    /// Appends the current setup to the lesson (a new lesson on this robot if none is open)
    /// and writes it: to the lesson's file, else `lesson.toml`; a download in a browser.
    pub fn save_as_lesson(&mut self) -> Result<String, String> {
        let step = self.current_step("");
        let spec = self.state.spec().to_string();
        let title = format!("{}: a lesson", self.state.robot().name);
        let player = self.lesson.get_or_insert_with(|| LessonPlayer {
            lesson: Lesson {
                title,
                robot: toml::Value::String(spec),
                steps: Vec::new(),
            },
            file: "lesson.toml".into(),
            step: 0,
        });
        player.lesson.steps.push(step);
        player.step = player.lesson.steps.len() - 1;
        let text = player.lesson.to_toml();
        let name = std::path::Path::new(&player.file)
            .file_name()
            .map_or("lesson.toml".into(), |n| n.to_string_lossy().into_owned());
        if self
            .file_picker
            .download(&name, "application/toml", text.as_bytes())
        {
            return Ok(format!("downloading {name}"));
        }
        let file = player.file.clone();
        std::fs::write(&file, text).map_err(|e| format!("cannot write {file}: {e}"))?;
        Ok(format!(
            "step {} saved in {}",
            self.lesson.as_ref().map_or(0, |p| p.lesson.steps.len()),
            super::file_picker::full_path(std::path::Path::new(&file)).display()
        ))
    }

    /// The lesson bar under the 3D view: title, step, caption (large), Previous and Next, the
    /// caption of the step being written, "Save as lesson".
    pub(super) fn lesson_bar(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        let Some(player) = &mut self.lesson else {
            return;
        };
        let n = player.lesson.steps.len();
        let i = player.step;
        let size = egui::TextStyle::Body.resolve(ui.style()).size * 1.35;
        ui.horizontal(|ui| {
            ui.label(RichText::new(&player.lesson.title).strong());
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
        if let Some(step) = player.lesson.steps.get_mut(i) {
            if step.caption.is_empty() {
                ui.add(
                    egui::TextEdit::multiline(&mut step.caption)
                        .hint_text("caption of this step (Markdown), saved with the next Save")
                        .desired_rows(2)
                        .desired_width(f32::INFINITY),
                );
            } else {
                ui.add(egui::Label::new(RichText::new(&step.caption).size(size)).wrap());
            }
        }
    }
}
