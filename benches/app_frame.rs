//! One frame of the app at 1280x800 while the IK target is dragged, done as the live window
//! does it on the software renderer: move the target, solve IK for every closed-form solution,
//! build the scene with the ghost arms, render the 3D view (1x multisampling while moving, as
//! the app does on a CPU adapter), lay the window out once with egui, paint it with the app's
//! UI painter into a persistent 1280x800 texture, and wait until the GPU (lavapipe) has
//! finished. Presenting to a window is not included (`armlab view --measure-frames N` measures
//! the real window). For comparison, the same frame painted by egui-wgpu's renderer.
//! Run: `cargo bench --bench app_frame`. With `ARMLAB_BENCH_URDF=path/to/model.urdf` (a URDF
//! with mesh files, e.g. a KUKA iiwa's) the same frame is also measured for that robot, drawn
//! with its meshes, at its "zero" configuration turned a little.

use armlab::app::AppUi;
use armlab::app::state::AppState;
use armlab::app::viewport::Viewport3d;
use armlab::render::Gpu;
use armlab::ui_render::offscreen::{FIGURE_FORMAT, Offscreen};
use armlab::ui_render::painter::{UiFrame, UiPainter};
use criterion::{Criterion, criterion_group, criterion_main};

const SIZE: [u32; 2] = [1280, 800];

/// A pose with eight distinct closed-form solutions (no singularity, no coinciding postures).
const Q: [f64; 6] = [0.4, 0.7, 0.5, 0.6, 0.8, 0.3];

struct Frame {
    gpu: Gpu,
    offscreen: Offscreen,
    painter: UiPainter,
    ctx: egui::Context,
    /// Paint with egui-wgpu (as `ARMLAB_EGUI_PAINTER=1` does in the window).
    egui_wgpu: bool,
    vp: Viewport3d,
    app: AppUi,
    view: wgpu::TextureView,
    start: nalgebra::IsometryMatrix3<f64>,
    k: u32,
}

impl Frame {
    fn new() -> Self {
        let mut app = AppUi::new(AppState::from_spec("anthropomorphic_spherical_wrist").unwrap());
        app.state.set_q(&Q).unwrap();
        let f = Self::with(app);
        assert_eq!(f.app.state.ghosts(0).len(), 8, "eight postures on screen");
        f
    }

    /// The frame of `app` at its current q, the IK target on the tool.
    fn with(mut app: AppUi) -> Self {
        let gpu = Gpu::new_headless()
            .expect("a graphics adapter (mesa-vulkan-drivers on machines without a GPU)");
        // As eframe's painter: default options (hardware texture filtering, dithering).
        let mut offscreen =
            Offscreen::with_options(&gpu.device, egui_wgpu::RendererOptions::default());
        let vp = Viewport3d::adaptive(gpu.clone()).expect("renderer");
        let start = app.state.robot().fk(app.state.q()).unwrap();
        app.state.set_target(0, start).unwrap();
        offscreen.set_background(Some(app.background()));
        let texture = armlab::ui_render::offscreen::canvas(&gpu.device, SIZE, false);
        let view = texture.create_view(&Default::default());
        let painter = UiPainter::new(&gpu.device, FIGURE_FORMAT);
        let mut f = Self {
            gpu,
            offscreen,
            painter,
            ctx: egui::Context::default(),
            egui_wgpu: false,
            vp,
            app,
            view,
            start,
            k: 0,
        };
        f.paint(None);
        f.app.tabs.view3d.fit(&f.app.state);
        f
    }

    /// Drags the target one step along a small circle (IK for every solution).
    fn drag(&mut self) {
        self.k += 1;
        let a = self.k as f64 * 0.05;
        let mut t = self.start;
        t.translation.vector.y += 0.03 * a.sin();
        t.translation.vector.z += 0.03 * (1.0 - a.cos());
        self.app.state.set_target(0, t).expect("target");
    }

    fn viewport(&mut self) -> Option<armlab::app::viewport::ViewportImage> {
        if self.egui_wgpu {
            self.app
                .render_viewport(&mut self.vp, self.offscreen.renderer_mut(), false)
        } else {
            self.app
                .render_viewport(&mut self.vp, &mut self.painter, false)
        }
    }

    fn paint(&mut self, image: Option<armlab::app::viewport::ViewportImage>) {
        let app = &mut self.app;
        if self.egui_wgpu {
            self.offscreen
                .frame(
                    &self.gpu.device,
                    &self.gpu.queue,
                    &self.view,
                    SIZE,
                    1.0,
                    |ui| app.show(ui, image.clone()),
                )
                .expect("frame");
            return;
        }
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(SIZE[0] as f32, SIZE[1] as f32),
            )),
            ..Default::default()
        };
        let out = self.ctx.run_ui(input, |ui| app.show(ui, image.clone()));
        let frame = UiFrame {
            prims: self.ctx.tessellate(out.shapes, out.pixels_per_point),
            textures: std::sync::Mutex::new(out.textures_delta),
            size_px: SIZE,
            pixels_per_point: out.pixels_per_point,
        };
        let bg = app.background();
        self.painter
            .render_frame(&self.gpu.device, &self.gpu.queue, &self.view, &frame, bg);
    }

    /// One whole frame of a drag, waited for.
    fn whole_frame(&mut self) {
        self.drag();
        let image = self.viewport();
        self.paint(image);
        self.wait();
    }

    fn wait(&self) {
        self.gpu
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("device");
    }
}

fn frame(c: &mut Criterion) {
    if let Ok(path) = std::env::var("ARMLAB_BENCH_URDF") {
        let mut app = AppUi::new(AppState::from_spec(&path).expect("ARMLAB_BENCH_URDF loads"));
        let q: Vec<f64> = (0..app.state.robot().dof())
            .map(|k| 0.3 + 0.1 * k as f64)
            .collect();
        app.state.set_q(&q).unwrap();
        let mut f = Frame::with(app);
        c.bench_function("app/frame 1280x800, the URDF of ARMLAB_BENCH_URDF", |b| {
            b.iter(|| f.whole_frame())
        });
    }
    let mut f = Frame::new();
    c.bench_function(
        "app/frame 1280x800 (drag: IK all solutions + ghosts + 3D + egui)",
        |b| b.iter(|| f.whole_frame()),
    );
    c.bench_function("app/part: IK for every solution", |b| b.iter(|| f.drag()));
    c.bench_function("app/part: 3D view of a moving scene", |b| {
        b.iter(|| {
            f.drag();
            let image = f.viewport();
            f.wait();
            image
        })
    });
    let image = f.viewport();
    c.bench_function("app/part: egui layout + paint of the window", |b| {
        b.iter(|| {
            f.paint(image.clone());
            f.wait();
        })
    });
    f.egui_wgpu = true;
    // The viewport's texture id belongs to the registry it was made with: start afresh.
    f.vp = Viewport3d::adaptive(f.gpu.clone()).expect("renderer");
    f.paint(None);
    c.bench_function(
        "app/frame, widgets painted by egui-wgpu (for comparison)",
        |b| b.iter(|| f.whole_frame()),
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30);
    targets = frame
}
criterion_main!(benches);
