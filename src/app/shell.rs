//! The app's window: the toolbar, the side panels ([`super::window`]), the central tabs and the
//! status bar, laid out for a classroom; and the one place where the actions of the panels, the
//! tabs, the lesson player and the keys ([`super::shortcuts`]) are applied to the state. Files
//! are read and written by [`super::files`].

use super::action::{Action, Actions};
use super::file_browser::FileBrowser;
use super::file_picker::{FileKind, FilePicker, NoDialogs};
use super::files::{self, Opening};
use super::layout::{self, Layout};
use super::lesson::{self, LessonPlayer};
use super::panels::ik::IkPanel;
use super::panels::model::ModelPanel;
use super::state::{AppState, Level, StateError};
use super::tabs::{self, TabContext, Tabs};
use super::viewport::{TextureRegistry, Viewport3d, ViewportImage, scene_of};
use super::{shortcuts, window};
use crate::lesson::{Lesson, RobotSource, resolve_spec};
pub use window::PanelRects;

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
    /// Heavy computations where the app has no threads: a browser's web workers (none here).
    pub offload: Vec<Box<dyn crate::offload::Offload>>,
    /// Seconds on the app's clock (a browser's; `None`: std's): the workspace job's frame budget.
    pub clock: Option<fn() -> f64>,
    /// The last layout's panel rectangles (points): left, right, central, toolbar, status bar.
    pub rects: PanelRects,
    /// The lesson being played, if any.
    pub lesson: Option<LessonPlayer>,
    /// The live class: teacher or student of a class server, or neither.
    pub class: super::class::ClassClient,
    /// The newest message seen and when it came (s, egui time).
    message_seen: (u64, f64),
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
            class: Default::default(),
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

    /// Applies one action of a panel, a tab, the lesson player, the toolbar or a key; what
    /// cannot be done is a warning in the status bar.
    pub fn apply(&mut self, action: Action) {
        if let Err(e) = self.try_apply(action) {
            self.state.push_message(Level::Warning, e.to_string());
        }
    }

    /// Applies every action collected in a frame, in order.
    pub fn apply_all(&mut self, actions: Actions) {
        actions.0.into_iter().for_each(|a| self.apply(a));
    }

    /// Applies one action; the state's refusal comes back (the model actions, which say more
    /// in the status bar themselves, and the view's actions never fail).
    fn try_apply(&mut self, action: Action) -> Result<(), StateError> {
        let s = &mut self.state;
        match action {
            Action::CommitDh { joint, field, text } => s.edit_dh(joint, field, &text)?,
            Action::Undo | Action::Redo => {
                let (done, what) = match action {
                    Action::Undo => (s.undo_edit(), "undo"),
                    _ => (s.redo_edit(), "redo"),
                };
                if !done {
                    s.push_message(Level::Info, format!("nothing to {what}"));
                }
            }
            Action::ResetEdits => s.reset_edits(),
            Action::SetJoint(k, v) => _ = s.set_joint(k, v)?,
            Action::SetQ(q) => s.set_q(&q)?,
            Action::ResetTo(name) => s.reset_to(&name)?,
            Action::SelectEe(k) => self.ik.ee = k,
            Action::SetLock(on) => s.set_lock(on),
            Action::SetTarget(ee, pose) => _ = s.set_target(ee, pose)?,
            Action::TargetToTool(ee) => s.set_target_from_tool(ee, None, None)?,
            Action::TargetFromTool {
                ee,
                position,
                rotation,
            } => s.set_target_from_tool(ee, position, rotation)?,
            Action::SelectSolution(ee, i) => s.select_solution(ee, i)?,
            Action::NextSolution => self.state.select_next_solution(self.ee())?,
            Action::SetTask(task) => {
                s.set_task(task)?;
                s.push_message(Level::Info, format!("task: {}", task.description()));
            }
            Action::SetSelfMotion(ee, v) => _ = s.set_self_motion(ee, v)?,
            Action::SelectBranch(ee, k) => s.select_self_motion_branch(ee, k)?,
            Action::SetDisplay(d) => s.display = d,
            Action::SetHidden(h) => s.hidden = h,
            Action::ClearTrails => s.clear_trails(),
            Action::ShowConstruction(on) => self.ik.construction.shown = on,
            Action::ConstructionStep(k) => self.ik.construction.step = k,
            Action::Orientation(o) => self.tabs.orientation.apply_lesson(&o),
            Action::Message(level, text) => s.push_message(level, text),
            Action::LessonStep(k) => self.go_to_step(k),
            _ => self.apply_other(action),
        }
        Ok(())
    }

    /// The view's, the window's, the files' and the lessons' actions (they never fail: what
    /// goes wrong is said in the status bar).
    fn apply_other(&mut self, action: Action) {
        if let Some(why) = action.refusal(&self.state.hidden) {
            return self.state.push_message(Level::Warning, why);
        }
        let (view, s) = (&mut self.tabs.view3d, &self.state);
        match action {
            Action::CameraPreset(p) => view.preset(p, s),
            Action::Fit => view.fit(s),
            Action::LookFrom {
                yaw,
                pitch,
                distance,
            } => view.look_from(yaw, pitch, distance, s),
            Action::SetCamera(c) => view.set_camera(c),
            Action::WorkspaceFigure(name) => {
                if let Err(e) = self.tabs.workspace.choose_figure(&name, &self.state) {
                    self.state.push_message(Level::Warning, e);
                }
            }
            Action::FitReach => view.fit_reach(s),
            Action::ToggleProjection => view.toggle_projection(s),
            Action::ToggleWorkspace => self.tabs.workspace.toggle_overlay(&mut self.state),
            Action::Screenshot => self.screenshot_requested = true,
            #[cfg(feature = "app")]
            Action::Record => {
                let stem = self.state.robot().name.to_lowercase().replace(' ', "_");
                let r = super::recorder::toggle(&mut self.recorder, &mut *self.file_picker, &stem);
                self.report(r);
            }
            Action::ToggleHelp => self.show_help ^= true,
            Action::ShowTab(k) => self.tab = k.min(Tabs::COUNT - 1),
            Action::Load(spec) => self.load(&spec),
            Action::OpenDialog => self.open_with_dialog(),
            Action::SaveDialog => self.save_with_dialog(),
            Action::SaveModel(path) => self.save_model(&path),
            Action::SaveAsLesson => {
                let saved = self.save_as_lesson();
                self.report(saved);
            }
            Action::CloseLesson => self.lesson = None,
            Action::Cell(c) => super::cell::apply(self, c),
            Action::Reachability(r) => super::reachability::apply(self, r),
            Action::OpenExercise(path) => self.open(&path, files::open_key(&path)),
            Action::CloseExercise => {
                let shown = self.tabs.exercise.close(&self.state);
                self.apply_all(shown);
            }
            Action::OpenText { name, text } => self.open_bytes(&name, text.as_bytes()),
            Action::Class(c) => self.class.apply(c, &mut self.tabs, &mut *self.file_picker),
            Action::SaveAnswer { path, text } => {
                let saved = files::write_answer(self.file_picker.as_mut(), &path, &text);
                self.report(saved);
            }
            // the layout's (P, V, F5, Esc); the state's are `try_apply`'s
            _ => self.layout.apply(&action),
        }
    }

    /// What was done (information) or why not (an error), for the status bar.
    fn report(&mut self, r: Result<String, String>) {
        match r {
            Ok(m) => self.state.push_message(Level::Info, m),
            Err(e) => self.state.push_message(Level::Error, e),
        }
    }

    /// Loads a model, a lesson or an exercise key (by its contents); on error keeps what it shows.
    pub fn load(&mut self, spec: &str) {
        if spec.is_empty() {
            let m = "type a model's path, or choose a built-in model";
            return self.state.push_message(Level::Warning, m);
        }
        self.open(spec, files::open_path(spec));
    }

    /// A file the browser handed over (dropped onto the window): opened like a path.
    pub fn open_bytes(&mut self, name: &str, bytes: &[u8]) {
        self.open(name, files::open_bytes(name, bytes));
    }

    /// Opens what the file `name` turned out to be; on error the app keeps its state and says why.
    fn open(&mut self, name: &str, opening: Opening) {
        let opened = match opening {
            Opening::Exercise(text) => self.open_exercise_text(name, &text),
            Opening::Lesson(lesson) => {
                let opened = lesson.and_then(|l| self.open_lesson(l, name));
                return self.report(opened.map(|()| format!("lesson {name}")));
            }
            Opening::Model(text) => {
                if text.is_some() {
                    self.model.load_path = name.to_string();
                }
                let loaded = self.load_model(name, text.as_deref());
                loaded.map_err(|e| e.to_string())
            }
            Opening::Scene(text) => return super::cell::open_text(self, name, &text),
            Opening::Unreadable(e) => Err(e),
        };
        if let Err(e) = opened {
            self.state.push_message(Level::Error, e);
        }
    }

    /// A file picked in the browser's file picker for `kind`: a model is opened, measurements
    /// are calibrated against the current robot.
    pub fn opened_file(&mut self, kind: FileKind, name: &str, bytes: &[u8]) {
        let (lab, robot) = (&mut self.tabs.calibration.lab, self.state.robot());
        match kind {
            FileKind::Measurements => lab.run_bytes(robot, name, bytes),
            _ => self.open_bytes(name, bytes),
        }
    }

    /// Loads a model by its `name` (a built-in model or a path), or from its `text`; then every
    /// tab drops what belonged to the old one (a running workspace job is cancelled), the view
    /// is framed again, the end-effector reset, and a job that was shown starts again at once.
    fn load_model(&mut self, name: &str, text: Option<&str>) -> Result<(), StateError> {
        match text {
            Some(text) => self.state.load_model_text(name, text)?,
            None => self.state.load_model(name)?,
        }
        let had_job = self.tabs.workspace.job.is_some();
        self.tabs.model_changed();
        self.ik.ee = 0;
        if had_job && (self.tab == tabs::WORKSPACE || self.state.display.workspace) {
            self.tabs.workspace.start(&self.state);
        }
        Ok(())
    }

    /// "Open file...": a model chosen in the desktop's file dialog is loaded; where there is no
    /// dialog, the in-app file browser opens instead (see [`files::ask_to_open`]).
    pub fn open_with_dialog(&mut self) {
        let picker = self.file_picker.as_mut();
        let (chosen, note) = files::ask_to_open(picker, &mut self.browser, &self.model.load_path);
        if let Some(m) = note {
            self.state.push_message(Level::Info, m);
        }
        if let Some(path) = chosen {
            self.model.load_path = path.clone();
            self.load(&path);
        }
    }

    /// "Save model as...": the current, edited robot written where the file dialog says (TOML,
    /// or URDF for a name ending in .urdf; no extension: .toml); the Save row's name where there
    /// is no dialog, a download in a browser.
    pub fn save_with_dialog(&mut self) {
        let picker = self.file_picker.as_mut();
        let path = if picker.downloads() || !picker.available() {
            Some(self.model.save_path.clone())
        } else {
            files::ask_to_save(picker, &self.state.robot().name)
        };
        if let Some(path) = path {
            self.model.save_path = path.clone();
            self.save_model(&path);
        }
    }

    /// Writes the model to `path` (a download in a browser); the status bar says where, or why not.
    fn save_model(&mut self, path: &str) {
        let saved = if self.file_picker.downloads() {
            self.model.save_path = path.to_string();
            files::download_model(self.file_picker.as_mut(), &self.state, path)
        } else {
            self.state.save_model(path)
        };
        self.report(saved);
    }

    /// Opens `lesson` (read from `file`): its robot, then its first step. The app's state is
    /// kept if the robot cannot be loaded.
    pub fn open_lesson(&mut self, lesson: Lesson, file: &str) -> Result<(), String> {
        let (name, text) = match lesson.robot_source()? {
            RobotSource::Spec(spec) => (resolve_spec(&spec, std::path::Path::new(file)), None),
            RobotSource::Embedded(text) => ("lesson robot.toml".into(), Some(text)),
        };
        let loaded = self.load_model(&name, text.as_deref());
        loaded.map_err(|e| format!("{file}: robot: {e}"))?;
        self.lesson = Some(LessonPlayer::new(lesson, file));
        self.go_to_step(0);
        Ok(())
    }

    /// Shows step `i` (clamped) of the lesson: joints, target, overlays, view; what cannot be
    /// set is a warning that names the step.
    pub fn go_to_step(&mut self, i: usize) {
        let ee = self.ee();
        let stepped = self
            .lesson
            .as_mut()
            .and_then(|p| p.go_to(i, &self.state, ee));
        let Some((step, actions)) = stepped else {
            return;
        };
        for a in actions.0 {
            if let Err(e) = self.try_apply(a) {
                self.state
                    .push_message(Level::Warning, format!("{step}: {e}"));
            }
        }
    }

    /// Appends the current setup to the lesson (a new lesson on this robot if none is open)
    /// and writes it: to the lesson's file, else `lesson.toml`; a download in a browser.
    pub fn save_as_lesson(&mut self) -> Result<String, String> {
        let seen = lesson::Seen::of(&self.tabs, self.tab, &self.ik.construction);
        let step = lesson::current_step(&self.state, self.ee(), &seen, "");
        let player = self
            .lesson
            .get_or_insert_with(|| LessonPlayer::on(&self.state));
        player.append(step);
        files::write_lesson(self.file_picker.as_mut(), player)
    }

    /// Opens a student's sheet (exam) or a teacher's key (practice) from its text (`name` for
    /// messages): loads its arm at its q (an orientation sheet has none: the arm stays),
    /// hides what the sheet asks for (in an exam every way out of the answer too), shows the
    /// Exercise tab. The app keeps its state on an error.
    pub fn open_exercise_text(&mut self, name: &str, text: &str) -> Result<(), String> {
        let opening = tabs::exercise::Opening::read(name, text)?;
        if let Some((model, arm)) = opening.arm() {
            let loaded = self.load_model(model, Some(arm));
            loaded.map_err(|e| format!("{name}: the sheet's arm: {e}"))?;
        }
        let opened = self.tabs.exercise.open(opening, name, &self.state);
        self.apply_all(opened);
        Ok(())
    }

    /// Where a user would grab the current target's gizmo ([`tabs::view3d::View3d::gizmo_grip`]).
    pub fn gizmo_grip(&self) -> Option<egui::Pos2> {
        self.tabs.view3d.gizmo_grip(&self.state, self.ee())
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
        let ee = self.ee();
        if self.tab == tabs::ORIENTATION {
            let (p, tab) = (self.layout.projector, &mut self.tabs.orientation);
            let image = tab.render(&self.state, ee, p, (vp, registry, dark));
            return image
                .map_err(|e| self.state.push_message(Level::Error, e))
                .ok();
        }
        let scene = scene_of(
            &mut self.state,
            (&self.tabs, &mut self.ik),
            ee,
            self.layout.projector,
        );
        #[cfg(feature = "app")]
        if let Some(rec) = &mut self.recorder {
            let view = &self.tabs.view3d;
            rec.offer(&scene, view.camera, view.viewport_px, dark);
        }
        let image = self.tabs.view3d.render(vp, registry, scene, dark);
        image
            .map_err(|e| self.state.push_message(Level::Error, e))
            .ok()
    }

    /// Lays out the whole window in `ui`; `viewport` is the image of the 3D view. The parts
    /// return what they want done, applied once all are laid out.
    pub fn show(&mut self, ui: &mut egui::Ui, viewport: Option<ViewportImage>) {
        let ctx = ui.ctx().clone();
        self.state.dragging = self.state.drag_held || ctx.input(|i| i.pointer.any_down());
        let r = ui.max_rect();
        self.window_points = [r.width(), r.height()];
        layout::apply_style(&ctx, &self.layout);
        // The window's ui was made with the previous frame's style: without this, the first
        // frame after P lays the panels out in the other mode's fonts, and they keep the width.
        ui.set_style(ctx.global_style());
        let mut out = Actions::default();
        let (step, c) = (
            self.lesson.as_ref().map(|p| p.step),
            &mut self.ik.construction,
        );
        shortcuts::read(&ctx, &mut self.state, c, step, &mut out);
        // The overlay on (remembered from the last session, or set by a lesson) computes the
        // workspace although W was not pressed in this one.
        if self.state.display.workspace {
            self.tabs.workspace.ensure_started(&self.state);
        }
        for path in files::dropped_paths(&ctx) {
            out.push(Action::Load(path));
        }
        if self.layout.present {
            self.rects = window::PanelRects::default();
        } else {
            #[cfg(feature = "app")]
            let rec = self.recorder.as_ref().map(super::recorder::Recorder::len);
            #[cfg(not(feature = "app"))]
            let rec = None;
            let tabs = (&mut self.tabs, self.tab);
            let top = super::toolbar::bar(ui, &self.layout, tabs, &mut self.state, rec, &mut out);
            self.rects.top = top;
            let (ee, job) = (self.ee(), self.tabs.workspace.job.as_ref());
            let status = (&self.state, ee, job.and_then(|j| j.progress()));
            let lesson = self.lesson.as_mut();
            self.rects.bottom =
                window::bottom_bars(ui, status, &mut self.message_seen, lesson, &mut out);
            let panels = (&mut self.model, &mut self.ik, &mut self.rects);
            window::side_panels(ui, &self.layout, panels, &mut self.state, &mut out);
        }
        let ee = self.ee();
        let sm = (self.tab == tabs::SELF_MOTION).then(|| self.state.self_motion(ee));
        let central = egui::CentralPanel::default().show(ui, |ui| {
            let mut cx = TabContext {
                ee,
                self_motion: sm,
                state: &self.state,
                layout: &self.layout,
                picker: self.file_picker.as_mut(),
                image: viewport,
            };
            if let Some(t) = self.tabs.get_mut(self.tab) {
                t.ui(&mut cx, ui, &mut out);
            }
        });
        self.rects.central = central.response.rect;
        self.class = std::mem::take(&mut self.class).frame(&ctx, self, &mut out);
        window::present_hint(&ctx, self.layout.present, self.layout.text_scale());
        shortcuts::help_window(&ctx, &mut self.show_help);
        if let Some(path) = self.browser.ui(&ctx) {
            self.model.load_path = path.to_string_lossy().into_owned();
            out.push(Action::Load(self.model.load_path.clone()));
        }
        self.apply_all(out);
    }
}
