//! The interactive app (eframe/egui over wgpu). The state logic ([`state`], [`singularity`])
//! has no GUI types and is unit-tested; [`ui`] and [`panels`] draw it; [`viewport`] renders
//! the 3D scene with the same renderer as the headless figures; [`screenshot`] renders the
//! whole window offscreen.

pub mod gizmo;
pub mod panels;
pub mod screenshot;
pub mod singularity;
pub mod state;
pub mod ui;
pub mod viewport;
pub mod workspace_job;

use crate::render::Gpu;
use state::AppState;
use ui::AppUi;
use viewport::Viewport3d;

/// The eframe application.
pub struct ArmlabApp {
    ui: AppUi,
    viewport: Option<Viewport3d>,
}

impl eframe::App for ArmlabApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let texture = match (frame.wgpu_render_state(), &mut self.viewport) {
            (Some(rs), Some(vp)) => {
                let mut renderer = rs.renderer.write();
                self.ui.render_viewport(vp, &mut *renderer, false)
            }
            _ => None,
        };
        self.ui.show(ui, texture);
        if std::mem::take(&mut self.ui.screenshot_requested) {
            self.save_screenshot();
        }
        if self
            .ui
            .workspace
            .as_ref()
            .is_some_and(|w| w.progress().is_some())
        {
            ui.ctx().request_repaint();
        }
    }
}

impl ArmlabApp {
    /// Renders the current state offscreen at the window's size and saves it next to the
    /// working directory as `armlab-<model>-<n>.png`; the status says where (or why not).
    fn save_screenshot(&mut self) {
        let [w, h] = self.ui.window_points.map(|v| v.round().max(64.0) as u32);
        let stem = self.ui.state.robot().name.to_lowercase().replace(' ', "_");
        let path = (1..1000)
            .map(|n| std::path::PathBuf::from(format!("armlab-{stem}-{n}.png")))
            .find(|p| !p.exists());
        let opts = screenshot::ScreenshotOptions {
            projector: self.ui.projector,
            ..Default::default()
        };
        let result = screenshot::screenshot_with(&self.ui, [w, h], &opts)
            .map_err(|e| e.to_string())
            .and_then(|img| {
                let path = path.ok_or_else(|| "no free file name".to_string())?;
                crate::headless::write_png(&img, &path).map_err(|e| e.to_string())?;
                Ok(path)
            });
        match result {
            Ok(p) => self
                .ui
                .state
                .push_message(state::Level::Info, format!("saved {}", p.display())),
            Err(e) => self
                .ui
                .state
                .push_message(state::Level::Error, format!("screenshot failed: {e}")),
        }
    }
}

/// Opens the app window on the model `spec` (a built-in name or a .toml/.urdf path).
pub fn run(spec: &str) -> Result<(), AppError> {
    let state = AppState::from_spec(spec).map_err(|e| AppError::Model(e.to_string()))?;
    let options = eframe::NativeOptions {
        renderer: eframe::Renderer::Wgpu,
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_title(format!("armlab: {}", state.robot().name)),
        ..Default::default()
    };
    eframe::run_native(
        "armlab",
        options,
        Box::new(|cc| {
            let viewport = cc.wgpu_render_state.as_ref().and_then(|rs| {
                let gpu =
                    Gpu::from_parts(rs.device.clone(), rs.queue.clone(), rs.adapter.get_info());
                Viewport3d::new(gpu).ok()
            });
            Ok(Box::new(ArmlabApp {
                ui: AppUi::new(state),
                viewport,
            }))
        }),
    )
    .map_err(|e| AppError::Window(e.to_string()))
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
    /// Bad screenshot input.
    #[error("{0}")]
    Input(String),
}
