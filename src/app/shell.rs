//! The app's window: the toolbar, the two side panels, the central tabs and the status bar,
//! laid out for a classroom (the 3D view keeps most of the window, wide content scrolls inside
//! its panel), and the one place where the actions of the panels and tabs are applied.

use super::action::{Action, Actions};
use super::file_browser::FileBrowser;
use super::file_picker::{FileKind, FilePicker, NoDialogs};
use super::layout::{self, Layout};
use super::panels::ik::IkPanel;
use super::panels::model::ModelPanel;
use super::state::{AppState, Level};
use super::tabs::{self, TabContext, Tabs};
use super::viewport::{TextureRegistry, Viewport3d, ViewportImage, build_scene};
use crate::camera::Preset;
use egui::Key;

/// How long a status message stays (s) before the bar shows the usual hint again: information,
/// warnings, errors.
const MESSAGE_SECONDS: [f64; 3] = [6.0, 12.0, 30.0];

/// The app's window model: the shared state and the parts that show it.
pub struct AppUi {
    /// The kinematic state shared by every part.
    pub state: AppState,
    /// Panel widths, collapsed panels, projector mode.
    pub layout: Layout,
    /// The central tabs (the 3D view first).
    pub tabs: Tabs,
    /// The tab shown (index into [`Tabs`]).
    pub tab: usize,
    /// The left panel: model, joints, DH table.
    pub model: ModelPanel,
    /// The right panel: readouts, IK, construction, redundancy.
    pub ik: IkPanel,
    /// The shortcut help window.
    pub show_help: bool,
    /// Set by the Screenshot button; the frame loop saves the window and clears it.
    pub screenshot_requested: bool,
    /// The 3D view being recorded (the toolbar's Record button).
    #[cfg(feature = "app")]
    pub recorder: Option<super::recorder::Recorder>,
    /// Window size in points, from the last layout (the screenshot button renders at it).
    pub window_points: [f32; 2],
    /// File dialogs: native in the window, none in tests and screenshots.
    pub file_picker: Box<dyn FilePicker>,
    /// The in-app file browser (where the desktop has no file dialog).
    pub browser: FileBrowser,
    /// Where heavy computations go where the app has no threads: a browser's pool of web
    /// workers (empty on the desktop, which has threads).
    pub offload: Vec<Box<dyn crate::offload::Offload>>,
    /// Seconds on a clock that runs where the app does (a browser's; `None`: the standard
    /// library's), for the sliced workspace job's budget per frame.
    pub clock: Option<fn() -> f64>,
    /// The panel rectangles of the last layout (points): left, right, central, toolbar,
    /// status bar (tests check them).
    pub rects: PanelRects,
    /// The lesson being played, if any.
    pub lesson: Option<super::lesson::LessonPlayer>,
    /// The newest message seen and when it came (s, egui time).
    message_seen: (u64, f64),
}

/// Where the parts of the window were laid out last (points, window coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanelRects {
    /// The left panel (`None` when collapsed).
    pub left: Option<egui::Rect>,
    /// The right panel (`None` when collapsed).
    pub right: Option<egui::Rect>,
    /// The central area (the tabs).
    pub central: egui::Rect,
    /// The toolbar.
    pub top: egui::Rect,
    /// The status bar.
    pub bottom: egui::Rect,
}

impl Default for PanelRects {
    fn default() -> Self {
        Self {
            left: None,
            right: None,
            central: egui::Rect::NOTHING,
            top: egui::Rect::NOTHING,
            bottom: egui::Rect::NOTHING,
        }
    }
}

impl AppUi {
    /// The window around a state.
    pub fn new(state: AppState) -> Self {
        Self {
            state,
            layout: Layout::default(),
            tabs: Tabs::default(),
            tab: tabs::VIEW3D,
            model: ModelPanel::default(),
            ik: IkPanel::default(),
            show_help: false,
            screenshot_requested: false,
            #[cfg(feature = "app")]
            recorder: None,
            window_points: [1280.0, 800.0],
            file_picker: Box::new(NoDialogs),
            browser: FileBrowser::default(),
            offload: Vec::new(),
            clock: None,
            rects: PanelRects::default(),
            lesson: None,
            message_seen: (0, 0.0),
        }
    }

    /// The end-effector the readouts and the 3D view's target refer to.
    pub fn ee(&self) -> usize {
        self.ik.ee.min(self.state.targets().len().saturating_sub(1))
    }

    /// The window's background colour; the frame is cleared to it.
    pub fn background(&self) -> egui::Color32 {
        layout::background()
    }

    /// Applies one action of a panel, a tab, the toolbar or a key.
    pub fn apply(&mut self, action: Action) {
        let warn = |state: &mut AppState, r: Result<(), String>| {
            if let Err(e) = r {
                state.push_message(Level::Warning, e);
            }
        };
        match action {
            Action::Load(spec) => self.load(&spec),
            Action::OpenDialog => self.open_with_dialog(),
            Action::SaveDialog => self.save_with_dialog(),
            Action::SaveModel(path) => self.save_model(&path),
            Action::CommitDh { joint, field, text } => {
                let r = self.state.edit_dh(joint, field, &text);
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::Undo => self.undo_redo(true),
            Action::Redo => self.undo_redo(false),
            Action::ResetEdits => self.state.reset_edits(),
            Action::SetJoint(k, v) => {
                let r = self.state.set_joint(k, v).map(|_| ());
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::ResetTo(name) => {
                let r = self.state.reset_to(&name);
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::SelectEe(k) => self.ik.ee = k,
            Action::SetLock(on) => self.state.set_lock(on),
            Action::SetTarget(ee, pose) => {
                let r = self.state.set_target(ee, pose).map(|_| ());
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::TargetToTool(ee) => {
                if let Ok(t) = self.state.robot().fk_ee(self.state.q(), ee) {
                    let r = self.state.set_target(ee, t).map(|_| ());
                    warn(&mut self.state, r.map_err(|e| e.to_string()));
                }
            }
            Action::SelectSolution(ee, i) => {
                let r = self.state.select_solution(ee, i);
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::NextSolution => self.next_solution(),
            Action::SetTask(task) => match self.state.set_task(task) {
                Ok(()) => self
                    .state
                    .push_message(Level::Info, format!("task: {}", task.description())),
                Err(e) => self.state.push_message(Level::Warning, e.to_string()),
            },
            Action::SetSelfMotion(ee, v) => {
                let r = self.state.set_self_motion(ee, v).map(|_| ());
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::SelectBranch(ee, k) => {
                let r = self.state.select_self_motion_branch(ee, k);
                warn(&mut self.state, r.map_err(|e| e.to_string()));
            }
            Action::ShowConstruction(on) => self.ik.construction.shown = on,
            Action::ConstructionStep(k) => self.ik.construction.step = k,
            Action::CameraPreset(_)
            | Action::Fit
            | Action::ToggleProjection
            | Action::ToggleWorkspace
            | Action::ToggleProjector
            | Action::ToggleSidePanels
            | Action::Screenshot
            | Action::Record
            | Action::ToggleHelp
            | Action::ShowTab(_) => self.apply_view(action),
            Action::Message(level, text) => self.state.push_message(level, text),
            Action::LessonStep(_)
            | Action::SaveAsLesson
            | Action::CloseLesson
            | Action::OpenExercise(_)
            | Action::CloseExercise => self.apply_lesson(action),
        }
    }

    /// Undo (or redo) the last model edit, saying so when there is none.
    fn undo_redo(&mut self, undo: bool) {
        let done = if undo {
            self.state.undo_edit()
        } else {
            self.state.redo_edit()
        };
        if !done {
            let what = if undo { "undo" } else { "redo" };
            self.state
                .push_message(Level::Info, format!("nothing to {what}"));
        }
    }

    /// The view's and the window's actions.
    fn apply_view(&mut self, action: Action) {
        match action {
            Action::CameraPreset(p) => self.tabs.view3d.preset(p, &self.state),
            Action::Fit => self.tabs.view3d.fit(&self.state),
            Action::ToggleProjection => self.tabs.view3d.toggle_projection(&self.state),
            Action::ToggleWorkspace => self.toggle_workspace(),
            Action::ToggleProjector => self.layout.projector ^= true,
            Action::ToggleSidePanels => self.layout.toggle_side_panels(),
            Action::Screenshot => self.screenshot_requested = true,
            Action::Record => self.toggle_recording(),
            Action::ToggleHelp => self.show_help ^= true,
            Action::ShowTab(k) => self.tab = k.min(Tabs::COUNT - 1),
            _ => {}
        }
    }

    /// The lesson bar's and the Exercise tab's actions.
    fn apply_lesson(&mut self, action: Action) {
        match action {
            Action::LessonStep(k) => self.go_to_step(k),
            Action::SaveAsLesson => match self.save_as_lesson() {
                Ok(m) => self.state.push_message(Level::Info, m),
                Err(e) => self.state.push_message(Level::Error, e),
            },
            Action::CloseLesson => self.lesson = None,
            Action::OpenExercise(path) => {
                let opened = std::fs::read_to_string(&path)
                    .map_err(|e| format!("{path}: {e}"))
                    .and_then(|text| self.open_exercise_text(&path, &text));
                if let Err(e) = opened {
                    self.state.push_message(Level::Error, e);
                }
            }
            Action::CloseExercise => self.close_exercise(),
            _ => {}
        }
    }

    /// Applies every action collected in a frame, in order.
    pub fn apply_all(&mut self, actions: Actions) {
        for a in actions.0 {
            self.apply(a);
        }
    }

    /// Loads a model; on error the previous model stays and the status says why.
    pub fn load(&mut self, spec: &str) {
        if spec.is_empty() {
            self.state.push_message(
                Level::Warning,
                "type a model's path, or choose a built-in model",
            );
            return;
        }
        let text = lesson_or_key_text(spec);
        if let Some(text) = text
            .as_deref()
            .filter(|t| t.contains(crate::exercise::KEY_FORMAT))
        {
            if let Err(e) = self.open_exercise_text(spec, text) {
                self.state.push_message(Level::Error, e);
            }
            return;
        }
        let lesson = text.and_then(|text| crate::lesson::Lesson::detect(&text, spec));
        if let Some(lesson) = lesson {
            match lesson.and_then(|l| self.open_lesson(l, spec)) {
                Ok(()) => self
                    .state
                    .push_message(Level::Info, format!("lesson {spec}")),
                Err(e) => self.state.push_message(Level::Error, e),
            }
            return;
        }
        match self.state.load_model(spec) {
            Ok(()) => self.model_changed(),
            Err(e) => self.state.push_message(Level::Error, e.to_string()),
        }
    }

    /// A new model: every tab drops what belonged to the old one (a running workspace job is
    /// cancelled), the view is framed again, the end-effector reset; a job that was shown starts
    /// again for the new model at once.
    pub(super) fn model_changed(&mut self) {
        let had_job = self.tabs.workspace.job.is_some();
        for t in self.tabs.all_mut() {
            t.model_changed();
        }
        self.ik.ee = 0;
        if had_job && (self.tab == tabs::WORKSPACE || self.state.display.workspace) {
            self.tabs.workspace.start(&self.state);
        }
    }

    /// "Open file...": a model chosen in the desktop's file dialog is loaded. Where there is no
    /// desktop dialog (no xdg-desktop-portal answers at once, or none is built in), the in-app
    /// file browser opens instead.
    pub fn open_with_dialog(&mut self) {
        if !self.file_picker.available() {
            let dir = std::path::Path::new(&self.model.load_path)
                .parent()
                .map(std::path::Path::to_path_buf)
                .unwrap_or_default();
            if cfg!(target_arch = "wasm32") {
                self.state.push_message(
                    Level::Info,
                    "no file dialog here: drop a model file on the page",
                );
            } else {
                self.browser.show_dir(&dir);
            }
            return;
        }
        if cfg!(target_arch = "wasm32") {
            // The browser's picker answers later (`FilePicker::poll_opened`).
            let _ = self.file_picker.open(FileKind::Model);
            return;
        }
        let asked = std::time::Instant::now();
        match self.file_picker.open(FileKind::Model) {
            Some(path) => {
                self.model.load_path = path.to_string_lossy().into_owned();
                let spec = self.model.load_path.clone();
                self.load(&spec);
            }
            // A dialog that closed before anyone could answer it was never shown.
            None if asked.elapsed() < std::time::Duration::from_millis(300) => {
                self.state.push_message(
                    Level::Info,
                    "no desktop file dialog answered (it needs xdg-desktop-portal): choose the \
                     file here",
                );
                self.browser.show_dir(std::path::Path::new(""));
            }
            None => {}
        }
    }

    /// "Save model as...": the current, edited robot written where the file dialog says (TOML,
    /// or URDF for a name ending in .urdf; no extension: .toml); the Save row's name where there
    /// is no dialog.
    pub fn save_with_dialog(&mut self) {
        use super::file_picker::{suggested_model_name, with_model_extension};
        if self.file_picker.downloads() {
            self.download_model();
            return;
        }
        if !self.file_picker.available() {
            let path = self.model.save_path.clone();
            self.save_model(&path);
            return;
        }
        let suggested = suggested_model_name(&self.state.robot().name);
        if let Some(path) = self.file_picker.save(FileKind::ModelToSave, &suggested) {
            let path = with_model_extension(path).to_string_lossy().into_owned();
            self.model.save_path = path.clone();
            self.save_model(&path);
        }
    }

    /// Writes the model to `path`; the status bar shows the full path written, or why not.
    fn save_model(&mut self, path: &str) {
        if self.file_picker.downloads() {
            self.model.save_path = path.to_string();
            self.download_model();
            return;
        }
        match self.state.save_model(path) {
            Ok(m) => self.state.push_message(Level::Info, m),
            Err(e) => self.state.push_message(Level::Error, e),
        }
    }

    /// A model file the browser handed over (dropped onto the window): opened like a path.
    pub fn open_bytes(&mut self, name: &str, bytes: &[u8]) {
        let Ok(text) = std::str::from_utf8(bytes) else {
            let e = format!("{name}: not a text file (a model file is TOML or URDF text)");
            self.state.push_message(Level::Error, e);
            return;
        };
        if text.contains(crate::exercise::KEY_FORMAT) {
            if let Err(e) = self.open_exercise_text(name, text) {
                self.state.push_message(Level::Error, e);
            }
            return;
        }
        if let Some(lesson) = crate::lesson::Lesson::detect(text, name) {
            match lesson.and_then(|l| self.open_lesson(l, name)) {
                Ok(()) => self
                    .state
                    .push_message(Level::Info, format!("lesson {name}")),
                Err(e) => self.state.push_message(Level::Error, e),
            }
            return;
        }
        self.model.load_path = name.to_string();
        match self.state.load_model_text(name, text) {
            Ok(()) => self.model_changed(),
            Err(e) => self.state.push_message(Level::Error, e.to_string()),
        }
    }

    /// A file picked in the browser's file picker for `kind`: a model is opened, measurements
    /// are calibrated against the current robot.
    pub fn opened_file(&mut self, kind: FileKind, name: &str, bytes: &[u8]) {
        match kind {
            FileKind::Measurements => {
                let lab = &mut self.tabs.calibration.lab;
                match std::str::from_utf8(bytes) {
                    Ok(text) => {
                        lab.measurements_path = name.to_string();
                        lab.run_text(self.state.robot(), name, text);
                    }
                    Err(_) => lab.message = Some(format!("{name}: not a text file")),
                }
            }
            _ => self.open_bytes(name, bytes),
        }
    }

    /// "Save model as..." in the browser: the edited robot offered as a download (TOML, or
    /// URDF when the Save row's name ends in .urdf).
    fn download_model(&mut self) {
        let name = match self.model.save_path.trim() {
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

    /// Writes a PNG (a screenshot, a figure) and says where: see
    /// [`super::file_picker::deliver_png`].
    pub fn deliver_png(&mut self, img: &image::RgbaImage, stem: &str) -> Result<String, String> {
        super::file_picker::deliver_png(self.file_picker.as_mut(), img, stem)
    }

    /// Where a user would grab the current target's gizmo (see
    /// [`tabs::view3d::View3d::gizmo_grip`]).
    pub fn gizmo_grip(&self) -> Option<egui::Pos2> {
        self.tabs.view3d.gizmo_grip(&self.state, self.ee())
    }

    /// Starts recording the 3D view, or stops and saves what was recorded as
    /// `armlab-<model>-<n>.gif` (a download in a browser); the result is said in the status bar.
    fn toggle_recording(&mut self) {
        #[cfg(feature = "app")]
        match self.recorder.take() {
            None => {
                self.recorder = Some(super::recorder::Recorder::default());
                self.state.push_message(
                    Level::Info,
                    "recording the 3D view: press Stop to save it as a GIF",
                );
            }
            Some(rec) => {
                let n = rec.len();
                let stem = self.state.robot().name.to_lowercase().replace(' ', "_");
                let saved = rec.finish().and_then(|gif| {
                    super::file_picker::deliver_bytes(
                        self.file_picker.as_mut(),
                        &gif,
                        &stem,
                        ("gif", "image/gif"),
                    )
                });
                match saved {
                    Ok(m) => self
                        .state
                        .push_message(Level::Info, format!("{m} ({n} frames)")),
                    Err(e) => self
                        .state
                        .push_message(Level::Error, format!("recording failed: {e}")),
                }
            }
        }
    }

    /// Frames the arm in the 3D view.
    pub fn fit(&mut self) {
        self.tabs.view3d.fit(&self.state);
    }

    /// Renders the 3D scene (the arm, its ghosts and targets, and every overlay the tabs and
    /// panels add) for the viewport at its last size; returns the image to show.
    pub fn render_viewport(
        &mut self,
        vp: &mut Viewport3d,
        registry: &mut dyn TextureRegistry,
        dark: bool,
    ) -> Option<ViewportImage> {
        self.tabs.view3d.frame_if_needed(&self.state);
        let mut scene = build_scene(&self.state, self.ee(), self.layout.projector);
        for t in self.tabs.all() {
            t.decorate(&self.state, &mut scene);
        }
        self.ik.construction.decorate(&self.state, &mut scene);
        let ee = self.ee();
        self.ik.symbols.decorate(&self.state, ee, &mut scene);
        if let Ok(view) = self.state.self_motion(ee) {
            let ghosts = if self.state.display.ghosts {
                self.state.self_motion_ghosts(ee)
            } else {
                Vec::new()
            };
            let path = self.state.display.self_motion_path;
            super::viewport::add_self_motion(&mut scene, self.state.robot(), &view, &ghosts, path);
        }
        #[cfg(feature = "app")]
        if let Some(rec) = &mut self.recorder {
            let view = &self.tabs.view3d;
            rec.offer(&scene, view.camera, view.viewport_px, dark);
        }
        match self.tabs.view3d.render(vp, registry, scene, dark) {
            Ok(image) => Some(image),
            Err(e) => {
                self.state.push_message(Level::Error, e);
                None
            }
        }
    }

    fn toggle_workspace(&mut self) {
        self.state.display.workspace ^= true;
        if self.state.display.workspace {
            self.tabs.workspace.ensure_started(&self.state);
        }
    }

    fn next_solution(&mut self) {
        let ee = self.ee();
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

    /// The keyboard: the desktop's shortcuts (consumed, so Ctrl+O does not also press O), then
    /// single keys unless a text field has the keyboard.
    fn shortcuts(&mut self, ctx: &egui::Context, out: &mut Actions) {
        command_shortcuts(ctx, out);
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let pressed = |k: Key| ctx.input(|i| i.key_pressed(k));
        for (k, p) in [
            (Key::Num1, Preset::Top),
            (Key::Num2, Preset::Front),
            (Key::Num3, Preset::Side),
            (Key::Num4, Preset::Iso),
        ] {
            if pressed(k) {
                out.push(Action::CameraPreset(p));
            }
        }
        let keys = [
            (Key::F, Action::Fit),
            (Key::O, Action::ToggleProjection),
            (Key::P, Action::ToggleProjector),
            (Key::V, Action::ToggleSidePanels),
            (Key::W, Action::ToggleWorkspace),
            (Key::Space, Action::NextSolution),
        ];
        for (k, a) in keys {
            if pressed(k) {
                out.push(a);
            }
        }
        if let Some(p) = &self.lesson {
            if pressed(Key::PageDown) {
                out.push(Action::LessonStep(p.step + 1));
            }
            if pressed(Key::PageUp) {
                out.push(Action::LessonStep(p.step.saturating_sub(1)));
            }
        }
        if pressed(Key::H) || pressed(Key::F1) {
            out.push(Action::ToggleHelp);
        }
        let d = &mut self.state.display;
        for (k, flag) in [
            (Key::G, &mut d.grid),
            (Key::D, &mut d.frames),
            (Key::T, &mut d.trail),
        ] {
            if pressed(k) {
                *flag ^= true;
            }
        }
        let c = &mut self.ik.construction;
        if pressed(Key::C) {
            c.shown ^= true;
        }
        if pressed(Key::N) {
            c.step += 1;
        }
        if pressed(Key::B) {
            c.step = c.step.saturating_sub(1);
        }
        if pressed(Key::L) {
            out.push(Action::SetLock(!self.state.lock()));
        }
        if pressed(Key::R) {
            let name = if self.state.robot().config("ready").is_some() {
                "ready"
            } else {
                "zero"
            };
            out.push(Action::ResetTo(name.into()));
        }
    }

    /// Lays out the whole window in `ui`; `viewport` is the image of the 3D view.
    pub fn show(&mut self, ui: &mut egui::Ui, viewport: Option<ViewportImage>) {
        let ctx = ui.ctx().clone();
        let r = ui.max_rect();
        self.window_points = [r.width(), r.height()];
        layout::apply_style(&ctx, &self.layout);
        // The window's ui was made with the previous frame's style: without this, the first
        // frame after P lays the panels out in the other mode's fonts, and they keep the width.
        ui.set_style(ctx.global_style());
        let mut out = Actions::default();
        self.shortcuts(&ctx, &mut out);
        // The overlay on (remembered from the last session, or set by a lesson) computes the
        // workspace although W was not pressed in this one.
        if self.state.display.workspace {
            self.tabs.workspace.ensure_started(&self.state);
        }
        let dropped: Vec<String> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().display().to_string())
                .filter(|p| !p.is_empty())
                .collect()
        });
        for path in dropped {
            out.push(Action::Load(path));
        }
        let top = egui::Panel::top("top").show(ui, |ui| {
            let robot = self.state.robot();
            let (name, dof) = (robot.name.clone(), robot.dof());
            let mut cx = super::toolbar::ToolbarContext {
                layout: &self.layout,
                tabs: (
                    self.tabs.all().iter().map(|t| t.title()).collect(),
                    self.tab,
                ),
                model: (&name, dof),
                projection: self.tabs.view3d.camera.projection,
                display: &mut self.state.display,
                follow: &mut self.tabs.view3d.follow,
                #[cfg(feature = "app")]
                recording: self.recorder.as_ref().map(super::recorder::Recorder::len),
            };
            super::toolbar::show(&mut cx, ui, &mut out);
        });
        self.rects.top = top.response.rect;
        let bottom = egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        self.rects.bottom = bottom.response.rect;
        if self.lesson.is_some() {
            egui::Panel::bottom("lesson").show(ui, |ui| self.lesson_bar(ui, &mut out));
        }
        self.side_panels(ui, &mut out);
        let central = egui::CentralPanel::default().show(ui, |ui| {
            let ee = self.ee();
            let mut cx = TabContext {
                state: &mut self.state,
                layout: &self.layout,
                ee,
                picker: self.file_picker.as_mut(),
                image: viewport,
            };
            if let Some(t) = self.tabs.get_mut(self.tab) {
                t.ui(&mut cx, ui, &mut out);
            }
        });
        self.rects.central = central.response.rect;
        if self.show_help {
            let mut open = true;
            egui::Window::new("Keyboard shortcuts")
                .open(&mut open)
                .collapsible(false)
                .show(&ctx, help);
            self.show_help = open;
        }
        if let Some(path) = self.browser.ui(&ctx) {
            self.model.load_path = path.to_string_lossy().into_owned();
            out.push(Action::Load(self.model.load_path.clone()));
        }
        self.apply_all(out);
    }

    /// The left and right panels of the current mode: resizable with visible edges, never so
    /// wide that the central area loses its share of the window, their content scrolling
    /// inside them.
    fn side_panels(&mut self, ui: &mut egui::Ui, out: &mut Actions) {
        let width = ui.max_rect().width();
        let window = ui.ctx().content_rect().width();
        let sides = self.layout.sides();
        let (left_id, right_id) = self.layout.panel_ids();
        let (left_default, right_default) = self.layout.default_widths(width, window);
        let right_w = egui::PanelState::load(ui.ctx(), ui.scope_id().with(right_id))
            .map_or(right_default, |s| s.size().x);
        self.rects.left = None;
        self.rects.right = None;
        if sides.left {
            let other = if sides.right { right_w } else { 0.0 };
            let r = egui::Panel::left(left_id)
                .resizable(true)
                .default_size(left_default)
                .size_range(Layout::width_range(width, window, other))
                .show(ui, |ui| {
                    fit_to_panel(ui);
                    self.model.ui(&self.state, ui, self.layout.projector, out);
                });
            self.rects.left = Some(r.response.rect);
        }
        if sides.right {
            let other = self.rects.left.map_or(0.0, |r| r.width());
            let r = egui::Panel::right(right_id)
                .resizable(true)
                .default_size(right_default)
                .size_range(Layout::width_range(width, window, other))
                .show(ui, |ui| {
                    fit_to_panel(ui);
                    self.ik.ui(&mut self.state, ui, out);
                });
            self.rects.right = Some(r.response.rect);
        }
    }

    /// The status bar: the workspace job's progress, and the newest message until it expires
    /// (or the reason a target is not reached, or the usual hint).
    fn status_bar(&mut self, ui: &mut egui::Ui) {
        let now = ui.input(|i| i.time);
        if self.state.messages_pushed() != self.message_seen.0 {
            self.message_seen = (self.state.messages_pushed(), now);
        }
        ui.horizontal(|ui| {
            if let Some(job) = &self.tabs.workspace.job
                && let Some(f) = job.progress()
            {
                ui.add(
                    egui::ProgressBar::new(f)
                        .desired_width(160.0)
                        .text("workspace"),
                );
            }
            let ee = self.ee();
            let line = self.state.status_line(ee).filter(|m| {
                let is_newest = self.state.last_message() == Some(m);
                let ttl = MESSAGE_SECONDS[m.level as usize];
                !is_newest || now - self.message_seen.1 < ttl
            });
            match line {
                Some(m) => {
                    let color = match m.level {
                        Level::Info => ui.visuals().text_color(),
                        Level::Warning => egui::Color32::from_rgb(180, 90, 0),
                        Level::Error => egui::Color32::from_rgb(190, 0, 0),
                    };
                    ui.colored_label(color, &m.text);
                    // The bar is redrawn when the message is due to go.
                    ui.ctx()
                        .request_repaint_after(std::time::Duration::from_secs(1));
                }
                None => {
                    ui.label(
                        "Drag the gizmo to move the IK target; drag empty space to orbit, \
                         right-drag to pan, scroll to zoom. H: help.",
                    );
                }
            }
        });
    }
}

/// The Ctrl (Cmd) shortcuts: open, save, undo, redo, quit; they work while a text field has
/// the keyboard.
fn command_shortcuts(ctx: &egui::Context, out: &mut Actions) {
    let command = |k: Key, shift: bool| {
        let mut m = egui::Modifiers::COMMAND;
        m.shift = shift;
        ctx.input_mut(|i| i.consume_shortcut(&egui::KeyboardShortcut::new(m, k)))
    };
    if command(Key::O, false) {
        out.push(Action::OpenDialog);
    }
    if command(Key::S, false) {
        out.push(Action::SaveDialog);
    }
    if command(Key::Z, true) {
        out.push(Action::Redo);
    }
    if command(Key::Z, false) {
        out.push(Action::Undo);
    }
    if command(Key::Q, false) {
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

/// Keeps a side panel's content inside it: text wraps at the panel's width instead of widening
/// it (wide tables scroll sideways inside their own area).
fn fit_to_panel(ui: &mut egui::Ui) {
    ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Wrap);
    let w = ui.available_width();
    ui.set_max_width(w);
}

fn help(ui: &mut egui::Ui) {
    egui::Grid::new("help").striped(true).show(ui, |ui| {
        for (k, what) in [
            ("1 / 2 / 3 / 4", "top / front / side / iso view"),
            (
                "F, double-click",
                "fit the robot (and its ghosts) in the view",
            ),
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
            ("PgDn / PgUp", "next / previous lesson step"),
            ("R", "reset to the ready configuration"),
            ("D / G / T", "DH frames / grid / trail"),
            ("W", "workspace overlay"),
            ("V", "hide / show both side panels"),
            ("P", "projector mode (large fonts, the 3D view large)"),
            ("H, F1", "this help"),
            ("Ctrl+Z / Ctrl+Shift+Z", "undo / redo a model edit"),
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

/// The text of `path` if it may be a lesson (.toml) or an exercise key (.json): a regular file
/// of at most 4 MB (never `/dev/zero` read to the end); `None` otherwise.
fn lesson_or_key_text(path: &str) -> Option<String> {
    let ext = std::path::Path::new(path)
        .extension()?
        .to_str()?
        .to_ascii_lowercase();
    let meta = std::fs::metadata(path).ok()?;
    let small = meta.is_file() && meta.len() <= 4 << 20;
    (small && (ext == "toml" || ext == "json"))
        .then(|| std::fs::read_to_string(path).ok())
        .flatten()
}
