//! The app's layout and interaction: top bar, side panels, the 3D viewport with navigation and
//! the IK target gizmo, the workspace tab, projector mode and the shortcut help.

use super::state::{AppState, Level};
use super::viewport::{TextureRegistry, Viewport3d, ViewportImage, build_scene};
use super::workspace_job::WorkspaceJob;
use crate::camera::{Camera, Preset, Projection};
use crate::scene::arm_points;
use egui::{Key, RichText};

/// Which tab the central area shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tab {
    /// The 3D view.
    View3d,
    /// The 2D workspace figure.
    Workspace,
    /// The calibration sandbox (Sect. 2.11).
    Calibration,
    /// Every joint against the self-motion parameter (Sect. 2.10.2).
    SelfMotion,
}

/// The app: its state (no GUI types) plus what only the UI needs.
pub struct AppUi {
    /// The kinematic state.
    pub state: AppState,
    /// The viewport camera.
    pub camera: Camera,
    /// Large fonts and thick lines for a projector.
    pub projector: bool,
    /// The shortcut help window.
    pub show_help: bool,
    /// Central tab.
    pub tab: Tab,
    /// End-effector the readouts and target refer to.
    pub ee: usize,
    /// Model path typed in the left panel.
    pub load_path: String,
    /// File name typed in the left panel's "Save" row (.urdf or .toml).
    pub save_path: String,
    /// Viewport size in pixels, from the last layout (the 3D render uses it).
    pub viewport_px: [u32; 2],
    /// Where the viewport was laid out last (points, window coordinates).
    pub viewport_rect: egui::Rect,
    /// The IK target gizmo.
    pub gizmo: super::gizmo::Gizmo,
    /// The workspace computation running or done.
    pub workspace: Option<WorkspaceJob>,
    /// The Calibration tab.
    pub calibration: super::calibration_lab::CalibrationLab,
    calibration_maps: super::calibration_panel::MapTextures,
    workspace_texture: Option<egui::TextureHandle>,
    /// Labels of the scene rendered last (drawn by egui over the 3D view).
    scene_labels: Vec<crate::scene::Label>,
    camera_fitted: bool,
    /// Viewport size and camera right after the last framing: while the camera is untouched, a
    /// new viewport size (the first layout, a resized window) frames the arm again.
    framed: Option<([u32; 2], Camera)>,
    /// Set by the Screenshot button; the frame loop saves the window and clears it.
    pub screenshot_requested: bool,
    /// Window size in points, from the last layout (the screenshot button renders at it).
    pub window_points: [f32; 2],
    /// File dialogs: native in the window, none in tests and screenshots.
    pub file_picker: Box<dyn super::file_picker::FilePicker>,
    /// Where heavy computations go where the app has no threads (a browser's web worker).
    pub offload: Option<Box<dyn crate::offload::Offload>>,
    /// Draw the construction behind the closed-form solution (Sect. 2.12).
    pub construction: bool,
    /// The construction step shown (0-based; the steps before it stay drawn).
    pub construction_step: usize,
}

impl AppUi {
    /// The UI around a state.
    pub fn new(state: AppState) -> Self {
        Self {
            state,
            camera: Camera::default(),
            projector: false,
            show_help: false,
            tab: Tab::View3d,
            ee: 0,
            load_path: String::new(),
            save_path: String::new(),
            viewport_px: [800, 600],
            viewport_rect: egui::Rect::NOTHING,
            gizmo: super::gizmo::Gizmo::default(),
            workspace: None,
            calibration: Default::default(),
            calibration_maps: Default::default(),
            workspace_texture: None,
            scene_labels: Vec::new(),
            camera_fitted: false,
            framed: None,
            screenshot_requested: false,
            window_points: [1280.0, 800.0],
            file_picker: Box::new(super::file_picker::NoDialogs),
            offload: None,
            construction: false,
            construction_step: 0,
        }
    }

    /// "Open file...": a model chosen in the file dialog is loaded (its path shown in the path
    /// field); cancelling changes nothing.
    pub fn open_with_dialog(&mut self) {
        use super::file_picker::FileKind;
        if !self.file_picker.available() {
            self.state.push_message(
                Level::Info,
                "no file dialog here: type the model's path and press Open",
            );
            return;
        }
        if let Some(path) = self.file_picker.open(FileKind::Model) {
            self.load_path = path.to_string_lossy().into_owned();
            let spec = self.load_path.clone();
            self.load(&spec);
        }
    }

    /// "Save model as...": the current, edited robot written where the file dialog says (TOML,
    /// or URDF for a name ending in .urdf; no extension: .toml).
    pub fn save_with_dialog(&mut self) {
        use super::file_picker::{FileKind, suggested_model_name, with_model_extension};
        if self.file_picker.downloads() {
            self.download_model();
            return;
        }
        if !self.file_picker.available() {
            self.state.push_message(
                Level::Info,
                "no file dialog here: type a file name in the Save row and press Save",
            );
            return;
        }
        let suggested = suggested_model_name(&self.state.robot().name);
        if let Some(path) = self.file_picker.save(FileKind::ModelToSave, &suggested) {
            self.save_path = with_model_extension(path).to_string_lossy().into_owned();
            let path = self.save_path.clone();
            match self.state.save_model(&path) {
                Ok(m) => self.state.push_message(Level::Info, m),
                Err(e) => self.state.push_message(Level::Error, e),
            }
        }
    }

    /// Loads a model; on error the previous model stays and the status says why.
    pub fn load(&mut self, spec: &str) {
        match self.state.load_model(spec) {
            Ok(()) => self.model_changed(),
            Err(e) => self.state.push_message(Level::Error, e.to_string()),
        }
    }

    /// A new model: the view is framed again, the workspace overlay and end-effector reset.
    fn model_changed(&mut self) {
        self.camera_fitted = false;
        self.workspace = None;
        self.workspace_texture = None;
        self.ee = 0;
    }

    /// A model file the browser handed over (dropped onto the window): opened like a path.
    pub fn open_bytes(&mut self, name: &str, bytes: &[u8]) {
        let Ok(text) = std::str::from_utf8(bytes) else {
            let e = format!("{name}: not a text file (a model file is TOML or URDF text)");
            self.state.push_message(Level::Error, e);
            return;
        };
        self.load_path = name.to_string();
        match self.state.load_model_text(name, text) {
            Ok(()) => self.model_changed(),
            Err(e) => self.state.push_message(Level::Error, e.to_string()),
        }
    }

    /// A file picked in the browser's file picker for `kind`: a model is opened, measurements
    /// are calibrated against the current robot.
    pub fn opened_file(&mut self, kind: super::file_picker::FileKind, name: &str, bytes: &[u8]) {
        use super::file_picker::FileKind;
        match kind {
            FileKind::Measurements => match std::str::from_utf8(bytes) {
                Ok(text) => {
                    self.calibration.measurements_path = name.to_string();
                    self.calibration.run_text(self.state.robot(), name, text);
                }
                Err(_) => self.calibration.message = Some(format!("{name}: not a text file")),
            },
            _ => self.open_bytes(name, bytes),
        }
    }

    /// "Save model as..." in the browser: the edited robot offered as a download (TOML, or
    /// URDF when the Save row's name ends in .urdf).
    fn download_model(&mut self) {
        let name = match self.save_path.trim() {
            "" => super::file_picker::suggested_model_name(&self.state.robot().name),
            n => n.to_string(),
        };
        let mime = if name.to_ascii_lowercase().ends_with(".urdf") {
            "application/xml"
        } else {
            "application/toml"
        };
        let message = match self.state.model_text(&name) {
            Ok(text) if self.file_picker.download(&name, mime, text.as_bytes()) => {
                (Level::Info, format!("downloading {name}"))
            }
            Ok(_) => (
                Level::Error,
                format!("the browser refused the download of {name}"),
            ),
            Err(e) => (Level::Error, e),
        };
        self.state.push_message(message.0, message.1);
    }

    /// Where a user would grab the IK target's gizmo to drag it (in points, window
    /// coordinates): the first visible plane square (else arrow) of the current end-effector;
    /// `None` before the viewport was laid out. The web page's test drags it.
    pub fn gizmo_grip(&self) -> Option<egui::Pos2> {
        use super::gizmo::Handle;
        let rect = self.viewport_rect;
        let ppp = self.viewport_px[0] as f32 / rect.width();
        if !(ppp.is_finite() && ppp > 0.0) {
            return None;
        }
        let pose = self.state.target(self.ee).ok()?.world_from_tool;
        let handles = [0, 1, 2].map(Handle::Plane).into_iter();
        handles
            .chain([0, 1, 2].map(Handle::Axis))
            .find_map(|h| {
                self.gizmo
                    .grip_px(&self.camera, self.viewport_px, &pose, ppp as f64, h)
            })
            .map(|[x, y]| rect.min + egui::vec2(x as f32, y as f32) / ppp)
    }

    /// Writes `img` as `armlab-<stem>-<n>.png` (the first free n) in the working directory, or
    /// offers it as the download `armlab-<stem>.png` where files are downloads (a browser); the
    /// message says which.
    pub fn deliver_png(&mut self, img: &image::RgbaImage, stem: &str) -> Result<String, String> {
        let mut png = Vec::new();
        crate::figure::encode_png(img, &mut png).map_err(|e| e.to_string())?;
        let name = format!("armlab-{stem}.png");
        if self.file_picker.download(&name, "image/png", &png) {
            return Ok(format!("downloading {name}"));
        }
        let path = (1..1000)
            .map(|n| std::path::PathBuf::from(format!("armlab-{stem}-{n}.png")))
            .find(|p| !p.exists())
            .ok_or_else(|| "no free file name".to_string())?;
        std::fs::write(&path, png).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        Ok(format!("saved {}", path.display()))
    }

    /// Uses `camera` as is (no automatic framing).
    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
        self.camera_fitted = true;
        self.framed = None;
    }

    /// Frames the arm in the viewport.
    pub fn fit(&mut self) {
        if let Ok(mut pts) = arm_points(self.state.robot(), self.state.q()) {
            // Keep the IK targets in view too (an unreachable one is the point of interest).
            pts.extend(
                self.state
                    .targets()
                    .iter()
                    .map(|t| crate::scene::point32(&t.world_from_tool.translation.vector)),
            );
            let [w, h] = self.viewport_px;
            self.camera.fit_points(&pts, w.max(16), h.max(16), 0.7);
        }
        self.camera_fitted = true;
        self.framed = Some((self.viewport_px, self.camera));
    }

    /// Frames the arm if it has not been framed yet, or if the viewport changed size since the
    /// last framing and the user has not moved the camera since (the live window renders its
    /// first 3D frame before the panels are laid out, at a guessed size).
    pub fn frame_if_needed(&mut self) {
        let resized = self
            .framed
            .is_some_and(|(size, camera)| size != self.viewport_px && camera == self.camera);
        if !self.camera_fitted || resized {
            self.fit();
        }
    }

    /// Renders the 3D scene for the viewport at its last size; returns the image to show.
    pub fn render_viewport(
        &mut self,
        vp: &mut Viewport3d,
        registry: &mut dyn TextureRegistry,
        dark: bool,
    ) -> Option<ViewportImage> {
        self.frame_if_needed();
        let dots = self.workspace.as_ref().and_then(|w| w.dots());
        let mut scene = build_scene(&self.state, dots, self.projector);
        if self.calibration.show_poses
            && let Some(r) = &self.calibration.result
            && r.model.nominal_robot().dof() == self.state.robot().dof()
        {
            super::viewport::add_measured_poses(&mut scene, self.state.robot(), &r.poses);
        }
        if self.construction
            && let Ok(steps) =
                crate::construction::steps::construction(self.state.robot(), self.state.q())
        {
            let current = self.construction_step.min(steps.len().saturating_sub(1));
            super::construction_panel::add_to_scene(&mut scene, &steps, current);
        }
        let ee = self.ee.min(self.state.targets().len().saturating_sub(1));
        if let Ok(view) = self.state.self_motion(ee) {
            let ghosts = if self.state.display.ghosts {
                self.state.self_motion_ghosts(ee)
            } else {
                Vec::new()
            };
            let path = self.state.display.self_motion_path;
            super::viewport::add_self_motion(&mut scene, self.state.robot(), &view, &ghosts, path);
        }
        let rendered = vp.render(registry, &scene, &self.camera, self.viewport_px, dark);
        self.scene_labels = std::mem::take(&mut scene.labels);
        match rendered {
            Ok(image) => Some(image),
            Err(e) => {
                self.state
                    .push_message(Level::Error, format!("3D view: {e}"));
                None
            }
        }
    }

    /// Applies the projector style (large fonts) or the normal one.
    pub fn apply_style(&self, ctx: &egui::Context) {
        let scale = if self.projector { 1.45 } else { 1.0 };
        ctx.global_style_mut(|s| {
            use egui::{FontId, TextStyle};
            s.text_styles
                .insert(TextStyle::Heading, FontId::proportional(18.0 * scale));
            s.text_styles
                .insert(TextStyle::Body, FontId::proportional(13.5 * scale));
            s.text_styles
                .insert(TextStyle::Button, FontId::proportional(13.5 * scale));
            s.text_styles
                .insert(TextStyle::Small, FontId::proportional(11.0 * scale));
            s.text_styles
                .insert(TextStyle::Monospace, FontId::monospace(12.5 * scale));
        });
        let mut v = egui::Visuals::light();
        if self.projector {
            v.override_text_color = Some(egui::Color32::BLACK);
        }
        // Panels are painted transparent over a window cleared to `background()`: the same
        // pixels, but a clear costs almost nothing where a window-sized egui rectangle costs
        // milliseconds per frame on a software rasterizer.
        v.panel_fill = egui::Color32::TRANSPARENT;
        // Square widgets: crisp on a projector, and a rounded corner is tessellated into a
        // fan of long thin triangles, which is what a software rasterizer pays for (the
        // window's ~14 000 triangles become ~6 500, 2-3 ms of lavapipe time a frame).
        let w = &mut v.widgets;
        for state in [
            &mut w.noninteractive,
            &mut w.inactive,
            &mut w.hovered,
            &mut w.active,
            &mut w.open,
        ] {
            state.corner_radius = egui::CornerRadius::ZERO;
        }
        ctx.set_visuals(v);
    }

    /// The window's background colour (what the panels show); the frame is cleared to it.
    pub fn background(&self) -> egui::Color32 {
        egui::Visuals::light().panel_fill
    }

    fn shortcuts(&mut self, ctx: &egui::Context) {
        // The desktop's own shortcuts first (consumed, so Ctrl+O does not also press O).
        let command = |k: Key| {
            let shortcut = egui::KeyboardShortcut::new(egui::Modifiers::COMMAND, k);
            ctx.input_mut(|i| i.consume_shortcut(&shortcut))
        };
        if command(Key::O) {
            self.open_with_dialog();
        }
        if command(Key::S) {
            self.save_with_dialog();
        }
        if command(Key::Q) {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let pressed = |k: Key| ctx.input(|i| i.key_pressed(k));
        let presets = [
            (Key::Num1, Preset::Top),
            (Key::Num2, Preset::Front),
            (Key::Num3, Preset::Side),
            (Key::Num4, Preset::Iso),
        ];
        for (k, p) in presets {
            if pressed(k) {
                self.camera.set_preset(p);
                self.fit();
            }
        }
        if pressed(Key::F) {
            self.fit();
        }
        if pressed(Key::O) {
            self.toggle_projection();
        }
        if pressed(Key::G) {
            self.state.display.grid ^= true;
        }
        if pressed(Key::D) {
            self.state.display.frames ^= true;
        }
        if pressed(Key::T) {
            self.state.display.trail ^= true;
        }
        if pressed(Key::P) {
            self.projector ^= true;
        }
        if pressed(Key::H) || pressed(Key::F1) {
            self.show_help ^= true;
        }
        if pressed(Key::C) {
            self.construction = !self.construction;
        }
        if pressed(Key::N) {
            self.construction_step += 1;
        }
        if pressed(Key::B) {
            self.construction_step = self.construction_step.saturating_sub(1);
        }
        if pressed(Key::L) {
            let l = self.state.lock();
            self.state.set_lock(!l);
        }
        if pressed(Key::W) {
            self.toggle_workspace();
        }
        if pressed(Key::R) {
            let name = if self.state.robot().config("ready").is_some() {
                "ready"
            } else {
                "zero"
            };
            let _ = self.state.reset_to(name);
        }
        if pressed(Key::Space) {
            self.next_solution();
        }
    }

    fn toggle_projection(&mut self) {
        self.camera.projection = match self.camera.projection {
            Projection::Perspective { .. } => Projection::Orthographic { height: 1.0 },
            Projection::Orthographic { .. } => Projection::Perspective {
                fov_y: 35f32.to_radians(),
            },
        };
        self.fit();
    }

    fn toggle_workspace(&mut self) {
        self.state.display.workspace ^= true;
        if self.state.display.workspace && self.workspace.is_none() {
            self.workspace = Some(WorkspaceJob::start(
                self.state.robot().clone(),
                self.state.spec().to_string(),
            ));
        }
    }

    fn next_solution(&mut self) {
        let ee = self.ee;
        if let Ok(t) = self.state.target(ee)
            && let Some(r) = &t.result
            && !r.solutions.is_empty()
        {
            let next = t.selected.map_or(0, |s| (s + 1) % r.solutions.len());
            if let Err(e) = self.state.select_solution(ee, next) {
                self.state.push_message(Level::Warning, e.to_string());
            }
        }
    }

    /// Lays out the whole window in `ui`; `viewport` is the image of the 3D view.
    pub fn show(&mut self, ui: &mut egui::Ui, viewport: Option<ViewportImage>) {
        let ctx = ui.ctx().clone();
        let r = ui.max_rect();
        self.window_points = [r.width(), r.height()];
        self.apply_style(&ctx);
        self.shortcuts(&ctx);
        let dropped: Vec<String> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().display().to_string())
                .filter(|p| !p.is_empty())
                .collect()
        });
        for path in dropped {
            self.load(&path);
        }
        egui::Panel::top("top").show(ui, |ui| self.top_bar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        let side = if self.projector { 380.0 } else { 300.0 };
        egui::Panel::left("left")
            .resizable(true)
            .default_size(side)
            .show(ui, |ui| super::panels::left(self, ui));
        egui::Panel::right("right")
            .resizable(true)
            .default_size(side)
            .show(ui, |ui| super::panels::right(self, ui));
        egui::CentralPanel::default().show(ui, |ui| match self.tab {
            Tab::View3d => self.viewport(ui, viewport),
            Tab::Workspace => self.workspace_tab(ui),
            Tab::Calibration => super::calibration_panel::show(
                &mut self.calibration,
                &mut self.calibration_maps,
                (self.state.robot(), self.state.q()),
                self.file_picker.as_mut(),
                ui,
            ),
            Tab::SelfMotion => super::redundancy_panel::tab(&mut self.state, ui, self.ee),
        });
        if self.show_help {
            egui::Window::new("Keyboard shortcuts")
                .collapsible(false)
                .show(&ctx, help);
        }
    }

    fn top_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            ui.strong(RichText::new("armlab").size(if self.projector { 22.0 } else { 16.0 }));
            ui.label(format!(
                "{} ({} DOF)",
                self.state.robot().name,
                self.state.robot().dof()
            ));
            ui.separator();
            ui.selectable_value(&mut self.tab, Tab::View3d, "3D view");
            ui.selectable_value(&mut self.tab, Tab::Workspace, "Workspace (2D)");
            ui.selectable_value(&mut self.tab, Tab::Calibration, "Calibration");
            ui.selectable_value(&mut self.tab, Tab::SelfMotion, "Self-motion");
            ui.separator();
            for (label, p) in [
                ("Top", Preset::Top),
                ("Front", Preset::Front),
                ("Side", Preset::Side),
                ("Iso", Preset::Iso),
            ] {
                if ui.button(label).clicked() {
                    self.camera.set_preset(p);
                    self.fit();
                }
            }
            if ui.button("Fit").clicked() {
                self.fit();
            }
            let ortho = matches!(self.camera.projection, Projection::Orthographic { .. });
            if ui.selectable_label(ortho, "Ortho").clicked() {
                self.toggle_projection();
            }
            ui.separator();
            let d = &mut self.state.display;
            ui.checkbox(&mut d.frames, "Frames");
            ui.checkbox(&mut d.labels, "Labels");
            ui.checkbox(&mut d.grid, "Grid");
            ui.checkbox(&mut d.trail, "Trail");
            ui.checkbox(&mut d.ghosts, "All postures");
            let mut ws = d.workspace;
            if ui.checkbox(&mut ws, "Workspace").changed() {
                self.toggle_workspace();
            }
            ui.separator();
            ui.checkbox(&mut self.projector, "Projector");
            if ui
                .button("Screenshot")
                .on_hover_text("Save the window as armlab-<model>-<n>.png in the current folder")
                .clicked()
            {
                self.screenshot_requested = true;
            }
            if ui.button("Help (H)").clicked() {
                self.show_help ^= true;
            }
        });
    }

    fn status_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            if let Some(job) = &self.workspace
                && let Some(f) = job.progress()
            {
                ui.add(egui::ProgressBar::new(f).desired_width(160.0).text("workspace"));
            }
            let ee = self.ee.min(self.state.targets().len().saturating_sub(1));
            match self.state.status_line(ee) {
                Some(m) => {
                    let color = match m.level {
                        Level::Info => ui.visuals().text_color(),
                        Level::Warning => egui::Color32::from_rgb(180, 90, 0),
                        Level::Error => egui::Color32::from_rgb(190, 0, 0),
                    };
                    ui.colored_label(color, &m.text);
                }
                None => {
                    ui.label("Drag the gizmo to move the IK target; drag empty space to orbit, right-drag to pan, scroll to zoom. H: help.");
                }
            }
        });
    }

    fn viewport(&mut self, ui: &mut egui::Ui, image: Option<ViewportImage>) {
        let rect = ui.available_rect_before_wrap();
        self.viewport_rect = rect;
        let ppp = ui.ctx().pixels_per_point();
        self.viewport_px = [
            ((rect.width() * ppp).round() as u32).max(16),
            ((rect.height() * ppp).round() as u32).max(16),
        ];
        let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
        if let Some(im) = image {
            // On whole pixels, the texture's size: a texel per pixel, no resampling.
            let [w, h] = self.viewport_px;
            let at = (rect.min.to_vec2() * ppp).round() / ppp;
            let rect =
                egui::Rect::from_min_size(at.to_pos2(), egui::vec2(w as f32, h as f32) / ppp);
            ui.painter().image(
                im.id,
                rect,
                egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
                egui::Color32::WHITE,
            );
        }
        // Labels of the scene, projected.
        let font = egui::FontId::proportional(if self.projector { 17.0 } else { 12.5 });
        crate::figure::labels::draw_labels(
            ui.painter(),
            rect,
            self.viewport_px,
            &self.camera,
            &self.scene_labels,
            &font,
        );
        // The IK target gizmo.
        let ee = self.ee.min(self.state.targets().len().saturating_sub(1));
        let mut gizmo_active = false;
        if let Ok(t) = self.state.target(ee) {
            let pose = t.world_from_tool;
            let unreachable = !t.reach.is_reached();
            let out = self
                .gizmo
                .ui(ui, &response, rect, &self.camera, &pose, unreachable);
            gizmo_active = out.active;
            if let Some(p) = out.new_pose
                && let Err(e) = self.state.set_target(ee, p)
            {
                self.state.push_message(Level::Warning, e.to_string());
            }
        }
        if !gizmo_active {
            if response.dragged_by(egui::PointerButton::Primary) {
                let d = response.drag_delta();
                self.camera.orbit(-d.x * 0.008, d.y * 0.008);
            } else if response.dragged_by(egui::PointerButton::Secondary)
                || response.dragged_by(egui::PointerButton::Middle)
            {
                let d = response.drag_delta();
                self.camera.pan(d.x / rect.height(), d.y / rect.height());
            }
        }
        if response.hovered() {
            let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
            if scroll != 0.0 {
                self.camera.zoom((-scroll * 0.002).exp());
            }
            if zoom != 1.0 {
                self.camera.zoom(1.0 / zoom);
            }
        }
        if response.double_clicked() {
            self.fit();
        } else if response.clicked()
            && !gizmo_active
            && let Some(pos) = response.interact_pointer_pos()
        {
            self.pick_ghost(ee, (pos - rect.min) * ppp);
        }
    }

    /// Selects the ghost arm nearest to a click (pixel position in the viewport): the one whose
    /// elbow or tool projects closest, within 40 px.
    fn pick_ghost(&mut self, ee: usize, at: egui::Vec2) {
        let robot = self.state.robot();
        let [w, h] = self.viewport_px;
        let chain = robot
            .chain_to(robot.end_effectors()[ee.min(robot.end_effectors().len() - 1)].parent)
            .to_vec();
        // Nearest joint within 40 px; a ghost within the limits wins over one outside them
        // (postures differing only at the wrist share their joint positions).
        let mut best: Option<(bool, f32, usize)> = None;
        let ghosts = self.state.ghosts(ee);
        let Ok(target) = self.state.target(ee) else {
            return;
        };
        let Some(result) = &target.result else { return };
        for g in ghosts.iter().filter(|g| !g.selected) {
            let Some(index) = result.solutions.iter().position(|s| s.q == g.q) else {
                continue;
            };
            let Ok(frames) = robot.fk_frames(&g.q) else {
                continue;
            };
            for &j in &chain {
                let p = crate::scene::point32(&frames[j].translation.vector);
                if let Some(px) = self.camera.project(&p, w, h) {
                    let d = (egui::vec2(px[0], px[1]) - at).length();
                    let key = (!g.within_limits, d);
                    if d < 40.0 && best.is_none_or(|b| key < (b.0, b.1)) {
                        best = Some((key.0, d, index));
                    }
                }
            }
        }
        if let Some((_, _, index)) = best
            && let Err(e) = self.state.select_solution(ee, index)
        {
            self.state.push_message(Level::Warning, e.to_string());
        }
    }

    fn workspace_tab(&mut self, ui: &mut egui::Ui) {
        if self.workspace.is_none() {
            self.workspace = Some(WorkspaceJob::start(
                self.state.robot().clone(),
                self.state.spec().to_string(),
            ));
        }
        let Some(job) = &self.workspace else { return };
        if let Some(f) = job.progress() {
            // The frame loop paces the repaints (it knows where the work is done).
            ui.centered_and_justified(|ui| {
                ui.add(egui::ProgressBar::new(f).text("computing the workspace..."))
            });
            return;
        }
        if let Some(err) = job.error() {
            ui.colored_label(egui::Color32::from_rgb(190, 0, 0), err);
            return;
        }
        if let Some(err) = job.figure_error() {
            let text = format!("no figure: {err}");
            ui.colored_label(egui::Color32::from_rgb(190, 0, 0), text);
        }
        if self.workspace_texture.is_none()
            && let Some(img) = job.figure()
        {
            let color = egui::ColorImage::from_rgba_unmultiplied(
                [img.width() as usize, img.height() as usize],
                img.as_raw(),
            );
            self.workspace_texture = Some(ui.ctx().load_texture(
                "workspace figure",
                color,
                egui::TextureOptions::LINEAR,
            ));
        }
        let save = ui
            .button("Save figure (PNG)")
            .on_hover_text("The figure at its full size, as `armlab workspace` writes it")
            .clicked();
        if let Some(t) = &self.workspace_texture {
            ui.centered_and_justified(|ui| ui.add(egui::Image::new(t).shrink_to_fit()));
        }
        if save && let Some(img) = self.workspace.as_ref().and_then(|j| j.figure()).cloned() {
            let stem = format!("{}-workspace", self.state.spec().replace(['/', '.'], "_"));
            match self.deliver_png(&img, &stem) {
                Ok(m) => self.state.push_message(Level::Info, m),
                Err(e) => self
                    .state
                    .push_message(Level::Error, format!("figure not saved: {e}")),
            }
        }
    }
}

fn help(ui: &mut egui::Ui) {
    egui::Grid::new("help").striped(true).show(ui, |ui| {
        for (k, what) in [
            ("1 / 2 / 3 / 4", "top / front / side / iso view"),
            ("F, double-click", "fit the robot in the view"),
            ("O", "perspective / orthographic"),
            ("drag, right-drag, scroll", "orbit, pan, zoom"),
            (
                "gizmo arrows / squares / rings",
                "move and turn the IK target",
            ),
            ("Space", "next IK solution (posture)"),
            ("L", "lock the posture while dragging"),
            ("C", "show the construction behind the solution"),
            ("N / B", "next / previous construction step"),
            ("R", "reset to the ready configuration"),
            ("D / G / T", "DH frames / grid / trail"),
            ("W", "workspace overlay"),
            ("P", "projector mode (large fonts, high contrast)"),
            ("H, F1", "this help"),
            (
                "Ctrl+O / Ctrl+S",
                "open a model / save the model as (file dialog)",
            ),
            ("Ctrl+Q", "quit (the settings are remembered)"),
        ] {
            ui.strong(k);
            ui.label(what);
            ui.end_row();
        }
    });
}
