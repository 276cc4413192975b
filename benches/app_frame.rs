//! One frame of the app at 1280x800 on the software renderer: move the IK target, solve IK for
//! every solution, build the scene with all ghost arms, render the 3D view, lay out and paint the
//! whole window with egui, and wait for the GPU (the read-back makes the wait explicit; it is
//! included, so the figure is an upper bound). Run: `cargo bench --bench app_frame`.

use armlab::app::state::AppState;
use armlab::app::ui::AppUi;
use armlab::app::viewport::Viewport3d;
use armlab::figure::offscreen::Offscreen;
use armlab::render::Gpu;
use criterion::{Criterion, criterion_group, criterion_main};

fn frame(c: &mut Criterion) {
    let gpu = Gpu::new_headless()
        .expect("a graphics adapter (mesa-vulkan-drivers on machines without a GPU)");
    let mut offscreen = Offscreen::new(&gpu.device);
    let mut vp = Viewport3d::new(Gpu::from_parts(
        gpu.device.clone(),
        gpu.queue.clone(),
        gpu.adapter_info.clone(),
    ))
    .expect("renderer");
    let mut app =
        AppUi::new(AppState::from_spec("anthropomorphic_spherical_wrist").expect("model"));
    let start = app.state.robot().fk(app.state.q()).expect("fk");
    app.state.set_target(0, start).expect("target");
    offscreen
        .render(&gpu.device, &gpu.queue, [1280, 800], 1.0, |ui| {
            app.show(ui, None)
        })
        .expect("layout");
    app.fit();
    let mut k = 0u32;
    c.bench_function(
        "app/frame 1280x800 (IK all solutions + ghosts + 3D + egui)",
        |b| {
            b.iter(|| {
                k += 1;
                let mut t = start;
                t.translation.vector.y += 0.05 * (k as f64 * 0.1).sin();
                app.state.set_target(0, t).expect("target");
                let tex = app.render_viewport(&mut vp, offscreen.renderer_mut(), false);
                offscreen
                    .render(&gpu.device, &gpu.queue, [1280, 800], 1.0, |ui| {
                        app.show(ui, tex)
                    })
                    .expect("frame")
            })
        },
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = frame
}
criterion_main!(benches);
