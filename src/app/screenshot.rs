//! The whole app window rendered offscreen, with no display: the same layout and the same 3D
//! renderer as the live app, written to PNG by `armlab view MODEL --screenshot FILE.png`.

use super::AppError;
use super::lesson::LessonPlayer;
use super::shell::AppUi;
use super::state::AppState;
use super::viewport::Viewport3d;
use crate::render::Gpu;
use crate::ui_render::offscreen::Offscreen;

/// What to show in a screenshot.
#[derive(Debug, Clone, Default)]
pub struct ScreenshotOptions {
    /// Joint vector (default: the model's ready configuration).
    pub q: Option<Vec<f64>>,
    /// Put the IK target on the tool and draw every closed-form solution.
    pub all_postures: bool,
    /// A target position (m) to move the IK target to (e.g. outside the workspace).
    pub target_position: Option<[f64; 3]>,
    /// Projector mode.
    pub projector: bool,
    /// The end-effector the right panel, the gizmo and the target are on.
    pub ee: usize,
}

/// Renders the live app's current view (state, camera, tab, end-effector) at `size` pixels:
/// what the Screenshot button saves.
pub fn screenshot_with(
    live: &AppUi,
    size: [u32; 2],
    opts: &ScreenshotOptions,
) -> Result<image::RgbaImage, AppError> {
    let gpu = Gpu::new_headless().map_err(crate::figure::FigureError::from)?;
    screenshot_on(&gpu, live, size, opts)
}

/// [`screenshot_with`] on a device already open (the window's own: the only one in a browser).
pub fn screenshot_on(
    gpu: &Gpu,
    live: &AppUi,
    size: [u32; 2],
    opts: &ScreenshotOptions,
) -> Result<image::RgbaImage, AppError> {
    let (app, camera) = copy_of(live, opts);
    Ok(render_window(gpu, app, size, Some(camera), false)?.0)
}

/// [`screenshot_on`] without waiting for the pixels (a browser cannot wait for the GPU): they
/// come from the returned read-back on a later frame.
pub fn screenshot_deferred(
    gpu: &Gpu,
    live: &AppUi,
    size: [u32; 2],
    opts: &ScreenshotOptions,
) -> Result<crate::render::PendingRead, AppError> {
    let (app, camera) = copy_of(live, opts);
    render_window(gpu, app, size, Some(camera), true)?
        .1
        .ok_or_else(|| AppError::Input("the screenshot was not read back".into()))
}

/// A copy of the live app's view (state, camera, tab, end-effector) to render offscreen.
fn copy_of(live: &AppUi, opts: &ScreenshotOptions) -> (AppUi, crate::camera::Camera) {
    let mut app = AppUi::new(live.state.clone());
    app.layout = live.layout;
    app.layout.projector = opts.projector;
    app.tab = live.tab;
    app.tabs.calibration.lab = live.tabs.calibration.lab.clone();
    app.ik.ee = live.ik.ee;
    app.ik.construction = live.ik.construction;
    app.ik.reach = live.ik.reach.snapshot();
    // the lesson's bar, as the class sees it
    app.lesson = live.lesson.clone();
    (app, live.tabs.view3d.camera)
}

/// Renders the app for `state` at `size` pixels, after applying `opts`.
pub fn screenshot(
    state: AppState,
    size: [u32; 2],
    opts: &ScreenshotOptions,
) -> Result<image::RgbaImage, AppError> {
    let input = |e: super::state::StateError| AppError::Input(e.to_string());
    let mut app = AppUi::new(state);
    app.layout.projector = opts.projector;
    app.ik.ee = opts.ee;
    if let Some(q) = &opts.q {
        app.state.set_q(q).map_err(input)?;
    }
    if opts.all_postures || opts.target_position.is_some() {
        let mut t = app
            .state
            .robot()
            .fk_ee(app.state.q(), opts.ee)
            .map_err(|e| AppError::Input(e.to_string()))?;
        if let Some(p) = opts.target_position {
            t.translation.vector = nalgebra::Vector3::from(p);
        }
        app.state.set_target(opts.ee, t).map_err(input)?;
        app.state.display.ghosts = true;
    }
    app.state.clear_trails();
    let gpu = Gpu::new_headless().map_err(crate::figure::FigureError::from)?;
    Ok(render_window(&gpu, app, size, None, false)?.0)
}

/// The app window at every step of a lesson, as the class sees it (the caption under the 3D
/// view): `armlab lesson FILE --render DIR`.
pub fn lesson_frames(
    state: AppState,
    lesson: crate::lesson::Lesson,
    file: &str,
    size: [u32; 2],
) -> Result<Vec<image::RgbaImage>, AppError> {
    let gpu = Gpu::new_headless().map_err(crate::figure::FigureError::from)?;
    let mut app = AppUi::new(state);
    app.open_lesson(lesson, file).map_err(AppError::Input)?;
    let n = app.lesson.as_ref().map_or(0, |p| p.lesson.steps.len());
    let mut frames = Vec::with_capacity(n);
    for i in 0..n {
        let mut copy = AppUi::new(app.state.clone());
        copy.lesson = app.lesson.clone();
        copy.go_to_step(i);
        if let Some(w) = &copy.tabs.workspace.job {
            // the workspace overlay: computed to the end before the picture is taken
            while w.progress().is_some() {
                w.step(Some(&gpu), &mut [], &super::workspace_job::native_clock);
            }
        }
        let explicit = copy
            .lesson
            .as_ref()
            .and_then(|p| p.lesson.steps[i].camera)
            .is_some_and(|c| c.distance.is_some());
        let camera = explicit.then_some(copy.tabs.view3d.camera);
        frames.push(render_window(&gpu, copy, size, camera, false)?.0);
    }
    Ok(frames)
}

/// An app's window laid out offscreen frame after frame, then rendered: for an app that waits
/// on something before its picture is taken (a class link's messages, which arrive as frames
/// run), as `armlab class demo --screenshot` does.
pub struct OffscreenWindow {
    gpu: Gpu,
    offscreen: Offscreen,
    size: [u32; 2],
}

impl OffscreenWindow {
    /// A window of `size` pixels on `gpu`.
    pub fn new(gpu: &Gpu, size: [u32; 2]) -> Self {
        let mut offscreen = Offscreen::new(&gpu.device);
        // a quarter second a pass: the class's windows have faded in when the picture is taken
        offscreen.set_clock_step(0.25);
        Self {
            gpu: gpu.clone(),
            offscreen,
            size,
        }
    }

    /// Lays `app` out once (a frame: its class client reads and sends, its actions apply).
    pub fn frame(&mut self, app: &mut AppUi) -> Result<(), AppError> {
        self.offscreen
            .layout(&self.gpu.device, self.size, 1.0, |ui| app.show(ui, None))?;
        Ok(())
    }

    /// Renders `app`'s window as it is now, keeping what the frames before laid out (window
    /// places and sizes): with `keep_camera` the 3D view as the app has it (a following
    /// student's is the teacher's; framing it anew would read as the student's own move), else
    /// framing the arm.
    pub fn render(mut self, app: AppUi, keep_camera: bool) -> Result<image::RgbaImage, AppError> {
        let (gpu, size) = (self.gpu.clone(), self.size);
        let camera = keep_camera.then_some(app.tabs.view3d.camera);
        Ok(render_window_on(&gpu, &mut self.offscreen, app, size, camera, false)?.0)
    }
}

/// Lays the window out once to learn the viewport size, renders the 3D view (with `camera`, or
/// framing the arm), and paints the window with it, all on `gpu`. With `defer`, the image is
/// blank and the pixels come from the read-back returned with it.
fn render_window(
    gpu: &Gpu,
    app: AppUi,
    size: [u32; 2],
    camera: Option<crate::camera::Camera>,
    defer: bool,
) -> Result<(image::RgbaImage, Option<crate::render::PendingRead>), AppError> {
    let mut offscreen = Offscreen::new(&gpu.device);
    render_window_on(gpu, &mut offscreen, app, size, camera, defer)
}

/// [`render_window`] on an offscreen window already laid out before.
fn render_window_on(
    gpu: &Gpu,
    offscreen: &mut Offscreen,
    mut app: AppUi,
    size: [u32; 2],
    camera: Option<crate::camera::Camera>,
    defer: bool,
) -> Result<(image::RgbaImage, Option<crate::render::PendingRead>), AppError> {
    offscreen.set_background(Some(app.background()));
    let mut vp = Viewport3d::new(gpu.clone()).map_err(crate::figure::FigureError::from)?;
    offscreen.layout(&gpu.device, size, 1.0, |ui| app.show(ui, None))?;
    match camera {
        Some(c) => app.tabs.view3d.set_camera(c),
        None => {
            // A lesson's step that shows the workspace is framed for all the arm can reach.
            if app.lesson.as_ref().is_some_and(LessonPlayer::frames_reach) {
                app.tabs.view3d.fit_reach(&app.state);
            } else {
                app.tabs.view3d.fit(&app.state);
            }
        }
    }
    let texture = app.render_viewport(&mut vp, offscreen.renderer_mut(), false);
    if defer {
        offscreen.defer_readback();
    }
    let image = offscreen.render(&gpu.device, &gpu.queue, size, 1.0, |ui| {
        app.show(ui, texture.clone())
    })?;
    Ok((image, offscreen.take_deferred()))
}
