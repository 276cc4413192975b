//! The interactive app (eframe/egui over wgpu). The shared state ([`state`]) has no GUI types
//! and is unit-tested; [`shell`] lays out the window and applies the [`action`]s that the side
//! [`panels`], the central [`tabs`], the [`lesson`] player and the [`shortcuts`] return (each
//! owns its own state and reads the shared one); [`files`] reads and writes the app's files;
//! [`layout`] keeps the 3D view the largest thing on screen; [`viewport`] renders the 3D scene
//! with the same renderer as the headless figures; [`screenshot`] renders the whole window
//! offscreen.

pub mod action;
pub mod cell;
pub mod class;
pub mod file_browser;
pub mod file_picker;
pub mod files;
pub mod gizmo;
pub mod inner;
pub mod layout;
pub mod lesson;
pub mod markdown;
pub mod panels;
pub mod probe;
pub mod reachability;
#[cfg(feature = "app")]
pub mod recorder;
pub mod screenshot;
pub mod settings;
pub mod shell;
pub mod shortcuts;
pub mod state;
pub mod tabs;
pub mod toolbar;
pub mod viewport;
pub mod window;
pub mod workspace_job;

use crate::render::Gpu;
use crate::ui_render::painter::UiPainter;
pub use shell::AppUi;
use viewport::Viewport3d;

/// The eframe application.
pub struct ArmlabApp {
    ui: AppUi,
    viewport: Option<Viewport3d>,
    probe: Option<probe::FrameProbe>,
    /// The widgets' own context, painted by our painter (None: eframe paints them).
    inner: Option<inner::InnerUi>,
    /// Remember the settings across runs (not while measuring frames).
    remember: bool,
    /// The window title last set (`armlab: <robot name>`), kept in step with the model.
    title: String,
    /// The window's device (screenshots in the browser, where no other can be opened).
    gpu: Option<Gpu>,
    /// Frames drawn so far.
    frames: u64,
    /// A screenshot whose pixels are on their way back from the GPU (browser), and its name.
    pending_screenshot: Option<(crate::render::PendingRead, String)>,
}

impl eframe::App for ArmlabApp {
    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if self.remember {
            let text = settings::Settings::capture(&self.ui).to_text();
            storage.set_string(settings::STORAGE_KEY, text);
        }
    }

    fn clear_color(&self, _visuals: &egui::Visuals) -> [f32; 4] {
        self.ui.background().to_normalized_gamma_f32()
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.frames += 1;
        self.take_files(ui.ctx());
        if let Some(p) = &mut self.probe {
            let [w, h] = self.ui.window_points;
            let ppp = ui.ctx().pixels_per_point();
            let size = [(w * ppp).round() as u32, (h * ppp).round() as u32];
            self.ui.state.drag_held = true;
            if p.frame(&mut self.ui.state, size) {
                ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
            }
            ui.ctx().request_repaint();
        }
        let image = match (frame.wgpu_render_state(), &mut self.viewport) {
            (Some(rs), Some(vp)) => {
                let mut renderer = rs.renderer.write();
                match (
                    &self.inner,
                    renderer.callback_resources.get_mut::<UiPainter>(),
                ) {
                    (Some(_), Some(painter)) => self.ui.render_viewport(vp, painter, false),
                    _ => self.ui.render_viewport(vp, &mut *renderer, false),
                }
            }
            _ => None,
        };
        if image.as_ref().is_some_and(|i| i.refine) {
            // Drawn at the fast quality while moving: one more frame draws it at full quality.
            ui.ctx().request_repaint();
        }
        match &mut self.inner {
            Some(inner) => {
                let app = &mut self.ui;
                let painted = inner.run(ui.ctx(), |ui| app.show(ui, image.clone()));
                let rect = ui.ctx().content_rect();
                ui.painter()
                    .add(egui_wgpu::Callback::new_paint_callback(rect, painted));
            }
            None => self.ui.show(ui, image),
        }
        let title = format!("armlab: {}", self.ui.state.robot().name);
        if title != self.title {
            ui.ctx()
                .send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
        #[cfg(feature = "app")]
        if self.ui.recorder.is_some() {
            // Recording: keep drawing the view (and offering its frames) while nothing moves.
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(100));
        }
        if std::mem::take(&mut self.ui.screenshot_requested) {
            self.save_screenshot();
        }
        self.poll_screenshot(ui.ctx());
        if self.ui.ik.reach.computing() {
            // The reachability map or a placement computes on a thread: its progress shown.
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(200));
        }
        if let Some(w) = &self.ui.tabs.workspace.job {
            let clock = self.ui.clock.unwrap_or(workspace_job::native_clock);
            let worked = w.step(self.gpu.as_ref(), &mut self.ui.offload, &clock);
            if worked {
                ui.ctx().request_repaint();
            } else if w.progress().is_some() {
                // Computed elsewhere (a thread, a web worker): a few frames a second show the
                // progress without taking the CPU from that computation.
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_millis(250));
            }
        }
    }

    #[cfg(target_arch = "wasm32")]
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(&mut *self)
    }
}

impl ArmlabApp {
    /// The app on the window eframe opened (`cc`): the 3D viewport and our UI painter on the
    /// window's wgpu device, the remembered settings restored when `remember`.
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        mut ui: AppUi,
        mut probe: Option<probe::FrameProbe>,
        remember: bool,
        model_given: bool,
    ) -> Self {
        let gpu = cc.wgpu_render_state.as_ref().map(|rs| {
            let info = rs.adapter.get_info();
            if let Some(p) = &mut probe {
                p.adapter = format!("{} ({}, {:?})", info.name, info.driver_info, info.backend);
            }
            UiPainter::new(&rs.device, rs.target_format)
                .install(&mut rs.renderer.write().callback_resources);
            Gpu::from_parts(rs.device.clone(), rs.queue.clone(), info)
        });
        let viewport = gpu.clone().and_then(|g| Viewport3d::adaptive(g).ok());
        // Our painter for the widgets when the window has a wgpu device (always with the
        // wgpu renderer); ARMLAB_EGUI_PAINTER=1 leaves them to egui-wgpu (for comparison).
        let inner = (viewport.is_some() && !egui_painter_asked()).then(inner::InnerUi::default);
        if remember {
            let stored = cc.storage.and_then(|s| s.get_string(settings::STORAGE_KEY));
            let file = storage_file();
            settings::restore(&mut ui, stored, file.as_deref(), model_given);
        }
        Self {
            ui,
            viewport,
            probe,
            inner,
            remember,
            title: String::new(),
            gpu,
            frames: 0,
            pending_screenshot: None,
        }
    }

    /// The app's state and UI (read by the web page's test hooks).
    pub fn app_ui(&self) -> &AppUi {
        &self.ui
    }

    /// Applies one action as the window's buttons do (the web page's test hooks).
    pub fn apply(&mut self, action: action::Action) {
        self.ui.apply(action);
    }

    /// The graphics backend the window draws with (`"BrowserWebGpu"`, `"Gl"` for WebGL2,
    /// `"Vulkan"`, ...), `None` without a wgpu device.
    pub fn graphics_backend(&self) -> Option<String> {
        self.gpu
            .as_ref()
            .map(|g| format!("{:?}", g.adapter_info.backend))
    }

    /// Frames drawn so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Files the browser handed over (picked or dropped onto the window) are opened.
    fn take_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<egui::DroppedFileHandle> = ctx.input(|i| i.raw.dropped_files.clone());
        for f in dropped {
            // In a browser the picker reads the bytes (asynchronously) and hands them over below.
            if !self.ui.file_picker.take_dropped(&f) {
                self.ui.load(&f.path().to_string_lossy());
            }
        }
        while let Some((kind, name, bytes)) = self.ui.file_picker.poll_opened() {
            self.ui.opened_file(kind, &name, &bytes);
        }
    }

    /// Renders the current state offscreen at the window's size and saves it: next to the
    /// working directory as `armlab-<model>-<n>.png` on the desktop, as a download in the
    /// browser; the status says where (or why not).
    fn save_screenshot(&mut self) {
        let [w, h] = self.ui.window_points.map(|v| v.round().max(64.0) as u32);
        let stem = self.ui.state.robot().name.to_lowercase().replace(' ', "_");
        let opts = screenshot::ScreenshotOptions {
            projector: self.ui.layout.projector,
            ..Default::default()
        };
        let image = match &self.gpu {
            // In a browser: the window's device, and the pixels on a later frame.
            Some(gpu) if cfg!(target_arch = "wasm32") => {
                match screenshot::screenshot_deferred(gpu, &self.ui, [w, h], &opts) {
                    Ok(read) => {
                        self.pending_screenshot = Some((read, stem));
                        return;
                    }
                    Err(e) => Err(e),
                }
            }
            _ => screenshot::screenshot_with(&self.ui, [w, h], &opts),
        };
        self.report_screenshot(image.map_err(|e| e.to_string()), &stem);
    }

    /// Delivers a deferred screenshot once its pixels are back.
    fn poll_screenshot(&mut self, ctx: &egui::Context) {
        let (Some((read, stem)), Some(gpu)) = (&self.pending_screenshot, &self.gpu) else {
            return;
        };
        match read.poll(&gpu.device) {
            Some(image) => {
                let stem = stem.clone();
                self.pending_screenshot = None;
                self.report_screenshot(image.map_err(|e| e.to_string()), &stem);
            }
            None => ctx.request_repaint(),
        }
    }

    fn report_screenshot(&mut self, image: Result<image::RgbaImage, String>, stem: &str) {
        let picker = self.ui.file_picker.as_mut();
        let result = image.and_then(|img| files::deliver_png(picker, &img, stem));
        match result {
            Ok(m) => self.ui.state.push_message(state::Level::Info, m),
            Err(e) => self
                .ui
                .state
                .push_message(state::Level::Error, format!("screenshot failed: {e}")),
        }
    }
}

fn egui_painter_asked() -> bool {
    !cfg!(target_arch = "wasm32") && std::env::var_os("ARMLAB_EGUI_PAINTER").is_some()
}

/// eframe's settings file on the desktop (`None` in the browser: local storage).
fn storage_file() -> Option<std::path::PathBuf> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        eframe::storage_dir(APP_ID).map(|d| d.join("app.ron"))
    }
    #[cfg(target_arch = "wasm32")]
    {
        None
    }
}

/// How to run the window.
#[cfg(feature = "app")]
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Drag the IK target for this many frames (after a warm-up), time them, close the window
    /// and return the timings; vsync is off so that frames are not held to the display rate.
    pub measure_frames: Option<usize>,
    /// Joint vector (rad, m) to open at; the IK target is put on the tool.
    pub q: Option<Vec<f64>>,
    /// The model was named on the command line: it wins over the one remembered from the last
    /// run (the other remembered settings still apply).
    pub model_given: bool,
    /// The end-effector the right panel starts on.
    pub ee: usize,
    /// A lesson to play (and the file it came from).
    pub lesson: Option<(crate::lesson::Lesson, String)>,
    /// The cell's obstacles to open with (`armlab view --scene FILE`).
    pub scene: Option<crate::collision::CellScene>,
    /// A class to join as its teacher, by the teacher link (`armlab class demo`), the Class
    /// window open.
    pub class_teacher: Option<String>,
}

/// The name eframe stores the settings under (`~/.local/share/armlab/app.ron` on Linux).
pub const APP_ID: &str = "armlab";

/// Opens the app window on the model `spec` (a built-in name or a .toml/.urdf path).
#[cfg(feature = "app")]
pub fn run(spec: &str) -> Result<(), AppError> {
    run_with(spec, &RunOptions::default()).map(|_| ())
}

/// Opens the app window with `opts`; returns the frame timings when they were asked for.
#[cfg(feature = "app")]
pub fn run_with(spec: &str, opts: &RunOptions) -> Result<Option<probe::FrameReport>, AppError> {
    let mut state = state::AppState::from_spec(spec).map_err(|e| AppError::Model(e.to_string()))?;
    if let Some(scene) = &opts.scene {
        state
            .set_scene(Some(scene.clone()))
            .map_err(AppError::Input)?;
    }
    if let Some(q) = &opts.q {
        let input = |e: state::StateError| AppError::Input(e.to_string());
        state.set_q(q).map_err(input)?;
        let tool = state
            .robot()
            .fk_ee(state.q(), opts.ee)
            .map_err(|e| AppError::Input(e.to_string()))?;
        state.set_target(opts.ee, tool).map_err(input)?;
        state.clear_trails();
    }
    let ee = opts.ee;
    let mut options = eframe::NativeOptions {
        renderer: eframe::Renderer::Wgpu,
        viewport: egui::ViewportBuilder::default()
            .with_app_id(APP_ID)
            .with_inner_size([1280.0, 800.0])
            .with_title(format!("armlab: {}", state.robot().name)),
        // The window has flat colours only: nothing to dither.
        dithering: false,
        ..Default::default()
    };
    let probe = opts.measure_frames.map(probe::FrameProbe::new);
    let report = probe.as_ref().map(|p| p.report.clone());
    // Measured runs neither read nor write the remembered settings and window size.
    let remember = probe.is_none();
    options.persist_window = remember;
    let model_given = opts.model_given || opts.q.is_some() || opts.lesson.is_some();
    let lesson = opts.lesson.clone();
    let class_teacher = opts.class_teacher.clone();
    if probe.is_some() {
        options.wgpu_options.surface.present_mode = wgpu::PresentMode::AutoNoVsync;
    }
    eframe::run_native(
        APP_ID,
        options,
        Box::new(move |cc| {
            let mut ui = AppUi::new(state);
            ui.ik.ee = ee;
            if let Some((lesson, file)) = lesson
                && let Err(e) = ui.open_lesson(lesson, &file)
            {
                ui.state.push_message(state::Level::Error, e);
            }
            ui.file_picker = Box::new(file_picker::NativeDialogs);
            if let Some(link) = class_teacher {
                ui.apply(action::Action::Class(class::ClassAction::JoinTeacher(link)));
                ui.class.window = true;
            }
            Ok(Box::new(ArmlabApp::new(
                cc,
                ui,
                probe,
                remember,
                model_given,
            )))
        }),
    )
    .map_err(|e| AppError::Window(e.to_string()))?;
    Ok(report.and_then(|r| r.lock().ok().and_then(|r| r.clone())))
}

/// Why the app could not run.
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    /// The model could not be loaded.
    #[error("{0}")]
    Model(String),
    /// No window could be opened (no display, no GPU adapter).
    #[error(
        "cannot open the app window: {0} (on a machine without a display, use --screenshot, or run under xvfb-run)"
    )]
    Window(String),
    /// Headless rendering failed.
    #[error(transparent)]
    Figure(#[from] crate::figure::FigureError),
    /// Painting the window offscreen failed.
    #[error(transparent)]
    UiRender(#[from] crate::ui_render::UiRenderError),
    /// Bad screenshot input.
    #[error("{0}")]
    Input(String),
}
