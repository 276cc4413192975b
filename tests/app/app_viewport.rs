//! The app's 3D viewport: ghost arms drawn once per distinct body, the adaptive quality of
//! the live view on a software rasterizer (fast while moving, full when still, not redrawn
//! when nothing changed), the view shown texel for texel, and the UI painter drawing the same
//! pixels as an egui image. Needs a graphics adapter (Mesa's lavapipe without a GPU).

use armlab::app::AppUi;
use armlab::app::state::AppState;
use armlab::app::viewport::{Viewport3d, build_scene};
use armlab::render::Gpu;
use armlab::scene::{ArmStyle, MeshInstance, arm_scene};
use armlab::ui_render::offscreen::Offscreen;
use egui_kittest::Harness;

fn gpu() -> Gpu {
    Gpu::new_headless().unwrap_or_else(|e| panic!("{e}"))
}

fn same_body(a: &MeshInstance, b: &MeshInstance) -> bool {
    a.shape == b.shape
        && a.world_from_unit
            .iter()
            .flatten()
            .zip(b.world_from_unit.iter().flatten())
            .all(|(x, y)| (x - y).abs() < 1e-5)
}

/// At the ready pose of the default arm the shoulder-left postures put every link where a
/// shoulder-right one is (no shoulder offset) and the base is shared by all: those bodies
/// must appear once, not stacked translucent copies.
#[test]
fn ghost_arms_draw_each_distinct_body_once() {
    let mut state = AppState::from_spec("anthropomorphic_spherical_wrist").unwrap();
    let tool = state.robot().fk(state.q()).unwrap();
    state.set_target(0, tool).unwrap();
    let ghosts = state.ghosts(0);
    assert!(ghosts.len() >= 4, "{} postures", ghosts.len());
    let scene = build_scene(&state, 0, false);
    for (i, a) in scene.meshes.iter().enumerate() {
        for b in &scene.meshes[i + 1..] {
            assert!(!same_body(a, b), "a body is drawn twice: {a:?}");
        }
    }
    // Nothing is lost: at a generic pose (eight postures) every body of every ghost is in
    // the scene, once.
    state.set_q(&[0.4, 0.7, 0.5, 0.6, 0.8, 0.3]).unwrap();
    let tool = state.robot().fk(state.q()).unwrap();
    state.set_target(0, tool).unwrap();
    let ghosts = state.ghosts(0);
    assert_eq!(ghosts.len(), 8);
    let scene = build_scene(&state, 0, false);
    let style = ArmStyle::default();
    for g in &ghosts {
        for body in arm_scene(state.robot(), &g.q, &style).unwrap().meshes {
            let n = scene.meshes.iter().filter(|m| same_body(m, &body)).count();
            assert_eq!(n, 1, "posture {}: body {body:?} drawn {n} times", g.posture);
        }
    }
    let translucent = scene.meshes.iter().filter(|m| m.color[3] < 1.0).count();
    assert!(
        translucent >= 7,
        "{translucent} ghost bodies for seven ghosts"
    );
}

#[test]
fn the_live_view_is_fast_while_moving_full_when_still_and_not_redrawn_when_unchanged() {
    let gpu = gpu();
    assert_eq!(
        gpu.adapter_info.device_type,
        wgpu::DeviceType::Cpu,
        "this test expects the software rasterizer"
    );
    let mut offscreen = Offscreen::new(&gpu.device);
    let mut vp = Viewport3d::adaptive(gpu.clone()).unwrap();
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let mut frame = |app: &mut AppUi| app.render_viewport(&mut vp, offscreen.renderer_mut(), false);
    let first = frame(&mut app).unwrap();
    assert!(first.refine, "a new scene is drawn fast first");
    let still = frame(&mut app).unwrap();
    assert!(!still.refine, "the same scene again: drawn at full quality");
    assert!(
        first.view != still.view,
        "the full-quality frame has its own target"
    );
    let again = frame(&mut app).unwrap();
    assert!(!again.refine && again.view == still.view);
    let mut q = app.state.q().to_vec();
    q[0] += 0.1;
    app.state.set_q(&q).unwrap();
    let moved = frame(&mut app).unwrap();
    assert!(moved.refine, "a changed scene is drawn fast");
    assert_eq!(vp.draws(), 3, "the unchanged third frame was not drawn");
}

/// Fraction of `tex`'s pixels found unchanged in `window` with its top left corner near
/// `at` (the best of the placements within a pixel).
fn best_match(window: &image::RgbaImage, tex: &image::RgbaImage, at: [u32; 2]) -> f64 {
    let (tw, th) = tex.dimensions();
    let mut best = 0;
    for oy in at[1].saturating_sub(1)..=at[1] + 1 {
        for ox in at[0].saturating_sub(1)..=at[0] + 1 {
            let n = tex
                .enumerate_pixels()
                .filter(|(x, y, p)| window.get_pixel_checked(ox + x, oy + y) == Some(*p))
                .count();
            best = best.max(n);
        }
    }
    best as f64 / (tw * th) as f64
}

/// The 3D view's texture lands in the window texel for texel (only the overlays drawn over it,
/// labels and the gizmo, change pixels): the image is placed on whole pixels at the texture's
/// size, so nothing is resampled.
#[test]
fn the_view_is_shown_texel_for_texel() {
    let gpu = gpu();
    let mut offscreen = Offscreen::new(&gpu.device);
    let mut vp = Viewport3d::new(gpu.clone()).unwrap();
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    // Fewer overlays (ghost names on plates, frame labels) over the view to look through.
    app.state.display.ghosts = false;
    app.state.display.labels = false;
    offscreen.set_background(Some(app.background()));
    let size = [1280, 800];
    offscreen
        .render(&gpu.device, &gpu.queue, size, 1.0, |ui| app.show(ui, None))
        .unwrap();
    let image = app
        .render_viewport(&mut vp, offscreen.renderer_mut(), false)
        .unwrap();
    let tex =
        armlab::render::read_texture_rgba(&gpu.device, &gpu.queue, image.view.texture()).unwrap();
    let [w, h] = app.tabs.view3d.viewport_px;
    assert_eq!(tex.dimensions(), (w, h));
    assert!(w > 300 && h > 300, "viewport {w}x{h}");
    let window = offscreen
        .render(&gpu.device, &gpu.queue, size, 1.0, |ui| {
            app.show(ui, Some(image.clone()))
        })
        .unwrap();
    let min = app.tabs.view3d.viewport_rect.min;
    let copied = best_match(&window, &tex, [min.x.round() as u32, min.y.round() as u32]);
    assert!(
        copied > 0.97,
        "only {:.1} % of the view is copied unchanged",
        copied * 100.0
    );
}

/// The window (widgets and the 3D view) painted by armlab's UI painter looks as egui-wgpu
/// paints it (same layout, fonts, clipping and blending), in few draw calls: what the live
/// window shows is what the screenshots and goldens show.
#[test]
fn the_ui_painter_paints_the_window_as_egui_wgpu_does() {
    use armlab::ui_render::offscreen::FIGURE_FORMAT;
    use armlab::ui_render::painter::{UiFrame, UiPainter};
    let gpu = gpu();
    let size = [1280u32, 800];
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let options = egui_wgpu::RendererOptions {
        dithering: false,
        ..Default::default()
    };
    let mut offscreen = Offscreen::with_options(&gpu.device, options);
    offscreen.set_background(Some(app.background()));
    let mut painter = UiPainter::new(&gpu.device, FIGURE_FORMAT);
    let mut vp = Viewport3d::new(gpu.clone()).unwrap();
    let ctx = egui::Context::default();
    for with_view in [false, true] {
        let (theirs, ours) = if with_view {
            // The same texture registered with each painter.
            let image = app
                .render_viewport(&mut vp, offscreen.renderer_mut(), false)
                .unwrap();
            let mut mine = image.clone();
            mine.id = painter.register_native(&gpu.device, &image.view);
            (Some(image), Some(mine))
        } else {
            (None, None)
        };
        let reference = offscreen
            .render(&gpu.device, &gpu.queue, size, 1.0, |ui| {
                app.show(ui, theirs.clone())
            })
            .unwrap();
        // The same layout passes in a context of our own (kept across the two rounds, as the
        // offscreen one is: panel sizes settle over frames), painted by our painter.
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(size[0] as f32, size[1] as f32),
            )),
            time: Some(0.0),
            ..Default::default()
        };
        let mut first = ctx.run_ui(input.clone(), |ui| app.show(ui, ours.clone()));
        let mut out = ctx.run_ui(input, |ui| app.show(ui, ours.clone()));
        let mut textures = std::mem::take(&mut first.textures_delta);
        textures.append(std::mem::take(&mut out.textures_delta));
        let frame = UiFrame {
            prims: ctx.tessellate(out.shapes, out.pixels_per_point),
            textures: std::sync::Mutex::new(textures),
            size_px: size,
            pixels_per_point: out.pixels_per_point,
        };
        let texture = armlab::ui_render::offscreen::canvas(&gpu.device, size, true);
        let view = texture.create_view(&Default::default());
        painter.render_frame(&gpu.device, &gpu.queue, &view, &frame, app.background());
        // Each draw call costs a software rasterizer about as much as a hundred widgets: the
        // window's meshes go in far fewer calls (each scrolled table and panel clips apart).
        let calls = painter.draw_calls();
        assert!(
            calls * 2 < frame.prims.len(),
            "{calls} draw calls for {} meshes",
            frame.prims.len()
        );
        let ours = armlab::render::read_texture_rgba(&gpu.device, &gpu.queue, &texture).unwrap();
        let differing = ours
            .pixels()
            .zip(reference.pixels())
            .filter(|(p, q)| p.0.iter().zip(q.0).any(|(x, y)| x.abs_diff(y) > 24))
            .count();
        let fraction = differing as f64 / (size[0] * size[1]) as f64;
        // Where they differ, to say which widget.
        let (mut lo, mut hi) = ([u32::MAX; 2], [0u32; 2]);
        for (x, y, p) in ours.enumerate_pixels() {
            let q = reference.get_pixel(x, y);
            if p.0.iter().zip(q.0).any(|(a, b)| a.abs_diff(b) > 24) {
                lo = [lo[0].min(x), lo[1].min(y)];
                hi = [hi[0].max(x), hi[1].max(y)];
            }
        }
        assert!(
            fraction < 0.001,
            "with the 3D view: {with_view}; {differing} pixels ({:.3} %) differ, within \
             {lo:?}-{hi:?}",
            fraction * 100.0
        );
        // Not trivially equal: the window has text and widgets on its background.
        let bg = app.background().to_array();
        let ink = ours.pixels().filter(|p| p.0 != bg).count();
        let least = if with_view { 300_000 } else { 50_000 };
        assert!(ink > least, "{ink} pixels drawn");
    }
}

/// A URDF arm drawn only by its meshes: moving a joint is a new frame (the fingerprint that
/// decides "unchanged, not redrawn" covers the meshes), the moving frame offers coarse copies,
/// and the still frame draws the full meshes.
#[test]
fn mesh_only_scenes_are_redrawn_when_they_move() {
    let gpu = gpu();
    let mut offscreen = Offscreen::new(&gpu.device);
    let mut vp = Viewport3d::adaptive(gpu.clone()).unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/urdf_meshes/arm_with_meshes.urdf"
    );
    let robot = armlab::urdf::load_urdf(std::path::Path::new(path)).unwrap();
    let style = ArmStyle {
        frames: false,
        grid: false,
        ..ArmStyle::default()
    };
    let meshes_only = |q: &[f64]| {
        let mut s = arm_scene(&robot, q, &style).unwrap();
        s.meshes.clear();
        s.lines.clear();
        s.dots.clear();
        s
    };
    let camera = armlab::camera::Camera::default();
    let a = meshes_only(&[0.0, 0.0]);
    assert_eq!(a.custom_meshes.len(), 2);
    let coarse = a.with_coarse_meshes().expect("coarse copies offered");
    assert!(coarse.custom_meshes.iter().all(|m| m.coarse.is_none()));
    let mut render = |s: &armlab::scene::Scene| {
        vp.render(offscreen.renderer_mut(), s, &camera, [320, 240], false)
            .unwrap()
    };
    assert!(render(&a).refine);
    assert!(!render(&a).refine);
    let b = meshes_only(&[0.0, 0.7]);
    assert!(render(&b).refine, "the moved meshes are a new frame");
    assert_eq!(vp.draws(), 3);
}

/// On a tree (the humanoid's two arms) only the driven chain's frames are labelled, so the
/// labels of 17 frames do not pile up; "Labels of every frame" brings them all back.
#[test]
fn a_tree_labels_only_the_driven_chain_unless_asked() {
    let mut state = AppState::from_spec("humanoid").unwrap();
    state.display.frames = true;
    state.display.labels = true;
    let robot = state.robot().clone();
    assert!(robot.end_effectors().len() > 1);
    let frame_of = |text: &str| text.trim_start_matches(['x', 'y', 'z']).to_string();
    let frame_labels = |scene: &armlab::scene::Scene| -> Vec<String> {
        scene
            .labels
            .iter()
            .flat_map(|l| l.text.lines())
            .filter(|t| t.starts_with('x') || t.starts_with('z'))
            .map(frame_of)
            .collect()
    };
    for ee in 0..robot.end_effectors().len() {
        let chain: Vec<String> = robot
            .chain_to(robot.end_effectors()[ee].parent)
            .iter()
            .map(|j| (j + 1).to_string())
            .collect();
        let labels = frame_labels(&build_scene(&state, ee, false));
        assert!(!labels.is_empty());
        for f in &labels {
            assert!(
                f == "0" || chain.contains(f),
                "ee {ee}: frame {f} is not on the chain"
            );
        }
        for f in &chain {
            assert!(
                labels.contains(f),
                "ee {ee}: frame {f} of the chain is not labelled"
            );
        }
    }
    state.display.all_labels = true;
    let all = frame_labels(&build_scene(&state, 0, false));
    for j in 0..robot.dof() {
        assert!(
            all.contains(&(j + 1).to_string()),
            "frame {} unlabelled",
            j + 1
        );
    }
}

/// No two scene labels overlap, and none leaves the 3D view, in the live window at 1280x800:
/// every built-in, and the biggest robots of the real-robot corpus (Baxter, PR2, Romeo), whose
/// views label the driven chain only. The labels are those the placer drew this frame.
#[test]
fn scene_labels_never_overlap_in_the_window() {
    let corpus = ["baxter", "pr2", "romeo"].map(|n| {
        format!(
            "{}/tests/data/urdf_corpus/{n}.urdf",
            env!("CARGO_MANIFEST_DIR")
        )
    });
    let specs: Vec<String> = armlab::kinematics::models::BUILT_INS
        .iter()
        .map(|b| b.name.to_string())
        .chain(corpus)
        .collect();
    let gpu = gpu();
    let mut offscreen = Offscreen::new(&gpu.device);
    let mut vp = Viewport3d::adaptive(gpu.clone()).unwrap();
    let mut total = 0;
    for spec in &specs {
        let state = AppState::from_spec(spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
        let mut h = Harness::builder()
            .with_size(egui::vec2(1280.0, 800.0))
            .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), AppUi::new(state));
        h.run();
        // The scene's labels come with a rendered frame, as in the window.
        h.state_mut()
            .render_viewport(&mut vp, offscreen.renderer_mut(), false)
            .unwrap_or_else(|| panic!("{spec}: the view was not rendered"));
        h.run();
        let app = h.state();
        let view = app.tabs.view3d.viewport_rect;
        let placed = &app.tabs.view3d.placed_labels;
        assert!(!placed.is_empty(), "{spec}: no labels were drawn");
        total += placed.len();
        for (i, a) in placed.iter().enumerate() {
            assert!(
                view.expand(0.5).contains_rect(*a),
                "{spec}: label {a:?} leaves the view {view:?}"
            );
            for b in &placed[i + 1..] {
                let overlap = a.intersect(*b);
                assert!(
                    !overlap.is_positive(),
                    "{spec}: labels {a:?} and {b:?} overlap"
                );
            }
        }
    }
    assert!(total > 5 * specs.len(), "{total} labels in all");
}

/// The Record button's path: what the 3D view draws is kept (at most ten frames a second),
/// drawn again and written as a GIF with the view's size and the recording's timing.
#[test]
fn recording_the_view_saves_its_frames_as_a_gif() {
    use armlab::app::recorder::{FPS, Recorder};
    let gpu = gpu();
    let mut offscreen = Offscreen::new(&gpu.device);
    let mut vp = Viewport3d::adaptive(gpu.clone()).unwrap();
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.tabs.view3d.viewport_px = [321, 240];
    app.recorder = Some(Recorder::default());
    for k in 0..4 {
        app.state.set_q(&[0.3 * k as f64, 0.5, -0.4]).unwrap();
        // One frame each, a frame's period apart: each is kept however slow the drawing is
        // (a second draw right after would be kept too on a loaded machine, where the drawing
        // itself takes longer than a period: the period is checked on the clock below).
        app.render_viewport(&mut vp, offscreen.renderer_mut(), false)
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1000 / u64::from(FPS) + 10));
    }
    let rec = app.recorder.take().unwrap();
    assert_eq!(rec.len(), 4);
    // A frame offered sooner than a period after the last kept one is not kept.
    let mut clocked = Recorder::default();
    let (scene, camera) = (armlab::scene::Scene::default(), app.tabs.view3d.camera);
    let period = 1.0 / f64::from(FPS);
    for (now, kept) in [
        (0.0, true),
        (0.3 * period, false),
        (period, true),
        (1.5 * period, false),
    ] {
        assert_eq!(
            clocked.offer_at(&scene, camera, [320, 240], false, now),
            kept,
            "a frame offered at {now} s"
        );
    }
    let gif_bytes = rec.finish().unwrap();
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut dec = opts.read_info(gif_bytes.as_slice()).unwrap();
    assert_eq!((dec.width(), dec.height()), (320, 240), "an even size");
    let mut frames = 0;
    let mut centis = 0;
    let mut changed = 0;
    while let Some(f) = dec.read_next_frame().unwrap() {
        frames += 1;
        centis += u32::from(f.delay);
        if frames > 1 && f.width > 1 {
            changed += 1;
        }
    }
    assert_eq!(frames, 4);
    assert_eq!(centis, 40, "ten frames a second");
    assert_eq!(changed, 3, "the arm moved between every two frames");
}
