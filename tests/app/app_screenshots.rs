//! The whole app window rendered offscreen (the `armlab view --screenshot` path) compared with
//! golden PNGs: the default robot, every posture of one target, and an unreachable target.
//! Needs a graphics adapter (Mesa's lavapipe without a GPU); fails without one.

use crate::common;
use armlab::app::screenshot::{ScreenshotOptions, screenshot};
use armlab::app::state::AppState;
use common::golden::assert_golden;

fn shot(spec: &str, opts: &ScreenshotOptions) -> image::RgbaImage {
    let state = AppState::from_spec(spec).unwrap();
    screenshot(state, [1280, 800], opts).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn default_robot() {
    let img = shot(
        "anthropomorphic_spherical_wrist",
        &ScreenshotOptions::default(),
    );
    assert_golden("app_default_robot", &img);
}

#[test]
fn all_postures_of_a_puma_pose() {
    let opts = ScreenshotOptions {
        q: Some(vec![0.3, 0.5, -1.2, 0.4, 0.8, -0.6]),
        all_postures: true,
        ..Default::default()
    };
    let img = shot("puma560", &opts);
    assert_golden("app_puma560_all_postures", &img);
}

#[test]
fn unreachable_target() {
    let opts = ScreenshotOptions {
        all_postures: true,
        target_position: Some([2.0, 0.0, 0.5]),
        ..Default::default()
    };
    let img = shot("anthropomorphic_spherical_wrist", &opts);
    assert_golden("app_unreachable_target", &img);
    // The status names how far out the target is; the arm did not move (no NaN anywhere).
    let state = AppState::from_spec("anthropomorphic_spherical_wrist").unwrap();
    let mut state = state;
    let q0 = state.q().to_vec();
    let mut t = state.robot().fk(&q0).unwrap();
    t.translation.vector = nalgebra::Vector3::new(2.0, 0.0, 0.5);
    let reach = state.set_target(0, t).unwrap().clone();
    assert!(!reach.is_reached());
    let msg = reach.message().unwrap();
    assert!(msg.contains("mm outside the workspace"), "{msg}");
    assert_eq!(state.q(), q0.as_slice());
}

/// Runs `armlab args...` on a virtual X server (needs `xvfb xauth`, which CI installs),
/// stopped by `timeout` after `seconds` (exit 124 then).
fn armlab_under_xvfb(seconds: u32, args: &[&str]) -> std::process::Output {
    // One at a time: xvfb-run started by two tests at once once ended with its own exit 5 ("problem
    // while cleaning up temporary directory") after the app ran its 6 s, and left its Xvfb running.
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = ONE_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let seconds = seconds.to_string();
    std::process::Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x900x24", "timeout", &seconds])
        .arg(env!("CARGO_BIN_EXE_armlab"))
        .args(args)
        .output()
        .unwrap_or_else(|e| {
            panic!("cannot run xvfb-run ({e}): install it with apt-get install xvfb xauth")
        })
}

/// The real window opens and runs under a virtual X server (needs `xvfb xauth`, which CI
/// installs): it must still be running when `timeout` stops it after 6 s (exit 124), not have
/// failed or crashed.
#[test]
fn real_window_runs_under_xvfb() {
    let o = armlab_under_xvfb(6, &["view", "puma560"]);
    assert_eq!(
        o.status.code(),
        Some(124),
        "the app exited early: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// `armlab view --measure-frames N` drives the real window (under a virtual X server), drags
/// the IK target for N frames, prints the frame times and exits by itself.
#[test]
fn the_real_window_measures_its_frames() {
    let o = armlab_under_xvfb(
        120,
        &[
            "view",
            "--measure-frames",
            "15",
            "--q",
            "0.4,0.7,0.5,0.6,0.8,0.3",
        ],
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.starts_with("15 frames at 1280x800 on "), "{out}");
    let median: f64 = out
        .split("median ")
        .nth(1)
        .and_then(|t| t.split(" ms").next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no median in {out}"));
    assert!(median > 0.0 && median.is_finite(), "{out}");
}

/// The Screenshot button's path: the live app's state and camera rendered offscreen.
#[test]
fn screenshot_button_renders_the_current_view() {
    use armlab::app::AppUi;
    use armlab::app::screenshot::screenshot_with;
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    app.state.set_q(&[0.2, 0.4, -0.3]).unwrap();
    let a = screenshot_with(&app, [960, 600], &ScreenshotOptions::default()).unwrap();
    let mut camera = app.tabs.view3d.camera;
    camera.set_preset(armlab::camera::Preset::Top);
    app.tabs.view3d.set_camera(camera);
    let b = screenshot_with(&app, [960, 600], &ScreenshotOptions::default()).unwrap();
    assert_eq!(a.dimensions(), (960, 600));
    assert!(a != b, "the camera of the live view is used");
}

/// The DLR arm holding its hand: the Redundancy panel (n, m, r, the arm-angle slider with its
/// feasible stretches), the elbow circle traced in the 3D view and the other branches as ghosts.
#[test]
fn dlr_self_motion_in_the_3d_view() {
    let mut state = AppState::from_spec("dlr").unwrap();
    let v = state.self_motion(0).unwrap().value;
    state.set_self_motion(0, v + 0.6).unwrap();
    let app = armlab::app::AppUi::new(state);
    let img =
        armlab::app::screenshot::screenshot_with(&app, [1280, 800], &ScreenshotOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
    assert_golden("app_dlr_self_motion", &img);
}

/// The Self-motion tab of the Panda: every joint against q7, every branch, limit bands, cursor.
#[test]
fn panda_self_motion_tab() {
    let state = AppState::from_spec("panda").unwrap();
    let mut app = armlab::app::AppUi::new(state);
    app.tab = armlab::app::tabs::SELF_MOTION;
    let img =
        armlab::app::screenshot::screenshot_with(&app, [1280, 800], &ScreenshotOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
    assert_golden("app_panda_self_motion_tab", &img);
}

/// "Show the construction" on the default robot (anthropomorphic arm with spherical wrist) at its
/// last step (every mark drawn, the wrist's in red), on the two-link arm (the triangle), and on
/// the other families' arms at their last steps.
#[test]
fn construction_overlay() {
    for (model, step, name) in [
        (
            "anthropomorphic_spherical_wrist",
            9,
            "app_construction_default_robot",
        ),
        ("planar2", 1, "app_construction_planar2"),
        ("stanford", 9, "app_construction_stanford"),
        ("scara", 9, "app_construction_scara"),
        // The UR family (issue 27): the planar three-link problem after joint 1, theta4 last.
        (
            "tests/data/urdf_corpus/ur5_robot.urdf",
            7,
            "app_construction_ur5",
        ),
    ] {
        let mut state = AppState::from_spec(model).unwrap();
        // The construction alone: no frames, no ghosts.
        state.display.frames = false;
        state.display.labels = false;
        state.display.ghosts = false;
        let mut app = armlab::app::AppUi::new(state);
        app.ik.construction.shown = true;
        app.ik.construction.step = step;
        // Framed for the window's 3D view, as the live app frames it on its first layout.
        app.tabs.view3d.viewport_px = [530, 720];
        app.tabs.view3d.fit(&app.state);
        let img = armlab::app::screenshot::screenshot_with(
            &app,
            [1280, 800],
            &ScreenshotOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_golden(name, &img);
    }
}

/// Issue 46, item 5: a lesson saved in the app replays the window it was saved from. The
/// teacher's setup (joints, a target with every posture as ghosts, labels off, the construction
/// at its third step, a camera looking at a point off the arm's centre from close by) is saved
/// with "Save as lesson", read back from the file and played on an app that remembered other
/// overlays (the workspace, the labels, no ghosts) and another model. The two windows agree
/// pixel for pixel above the status bar (whose last message differs: "saved" against "loaded"),
/// within rasteriser noise.
#[test]
fn a_saved_lesson_replays_the_window_it_was_saved_from() {
    use armlab::app::AppUi;
    use armlab::app::lesson::LessonPlayer;
    use armlab::app::screenshot::{lesson_frames, screenshot_with};
    use armlab::camera::{Camera, Projection};
    let dir = std::env::temp_dir().join(format!("armlab-replay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("lesson.toml");
    let mut live = AppUi::new(AppState::from_spec("puma560").unwrap());
    live.state.set_q(&[0.3, 0.5, -1.2, 0.4, 0.8, -0.6]).unwrap();
    let tool = live.state.robot().fk(live.state.q()).unwrap();
    live.state.set_target(0, tool).unwrap();
    live.state.display.ghosts = true;
    live.state.display.labels = false;
    live.ik.construction.shown = true;
    live.ik.construction.step = 2;
    live.tabs.view3d.set_camera(Camera {
        target: nalgebra::Point3::new(0.35, 0.1, 0.45),
        distance: 1.4,
        yaw: 0.7,
        pitch: 0.35,
        projection: Projection::Perspective {
            fov_y: Camera::default_fov(),
        },
    });
    let mut player = LessonPlayer::on(&live.state);
    player.file = file.to_string_lossy().into_owned();
    live.lesson = Some(player);
    live.save_as_lesson().unwrap();
    live.state.clear_trails();
    let saved = screenshot_with(&live, [1280, 800], &Default::default()).unwrap();
    // replayed from the file, on an app that remembers other overlays and shows another model
    let text = std::fs::read_to_string(&file).unwrap();
    let lesson = armlab::lesson::Lesson::parse(&text, "lesson.toml").unwrap();
    let mut other = AppState::from_spec("stanford").unwrap();
    other.display.workspace = true;
    other.display.ghosts = false;
    other.display.labels = true;
    let frames = lesson_frames(other, lesson, &file.to_string_lossy(), [1280, 800]).unwrap();
    let replayed = &frames[0];
    let (w, h) = saved.dimensions();
    assert_eq!(replayed.dimensions(), (w, h));
    let (mut differ, mut worst) = (0usize, 0u8);
    for y in 0..h - 60 {
        for x in 0..w {
            let (a, b) = (saved.get_pixel(x, y), replayed.get_pixel(x, y));
            let d = (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap();
            worst = worst.max(d);
            if d > 24 {
                differ += 1;
            }
        }
    }
    let share = differ as f64 / f64::from(w * (h - 60));
    if share > 1e-3 {
        saved.save(dir.join("saved.png")).unwrap();
        replayed.save(dir.join("replayed.png")).unwrap();
    }
    assert!(
        share <= 1e-3,
        "{:.3} % of the pixels differ (worst {worst}); see {}",
        share * 100.0,
        dir.display()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The median frame time (ms) `armlab view MODEL --measure-frames 30` prints.
fn median_frame_ms(model: &str) -> f64 {
    let o = armlab_under_xvfb(150, &["view", model, "--measure-frames", "30"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{model}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    out.split("median ")
        .nth(1)
        .and_then(|t| t.split(" ms").next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("no median in {out}"))
}

/// Issue 46, item 7: Baxter dragged at 111-197 ms a frame in the live window, 7-9 times the
/// Puma in the same runs (its arm's self-motion, a locked joint swept through a general
/// six-joint elimination, was recomputed every frame of the drag). Now it waits for the drag's
/// end, and Baxter's frame is at most twice the Puma's, measured in the real window one after
/// the other (best of three tries: these machines drift 20-40 % between runs). The two other
/// robots of the corpus that were over twice the Puma (Sawyer 2.4x, Romeo 3.1x, 2026-12-06)
/// are held to the same goal.
#[test]
fn big_robots_drag_at_most_twice_as_slowly_as_the_puma() {
    for name in ["baxter", "sawyer", "romeo"] {
        let path = format!(
            "{}/tests/data/urdf_corpus/{name}.urdf",
            env!("CARGO_MANIFEST_DIR")
        );
        let mut ratios = Vec::new();
        for _ in 0..3 {
            let (p, b) = (median_frame_ms("puma560"), median_frame_ms(&path));
            ratios.push(b / p);
            if b / p <= 2.0 {
                break;
            }
        }
        assert!(
            ratios.last().is_some_and(|r| *r <= 2.0),
            "{name}'s frame against the Puma's, three tries: {ratios:?}"
        );
    }
}

/// Every text of a figure's vector capture: (its size in pixels of the figure, the text).
fn figure_texts(page: &armlab::figure::vector::VectorPage) -> Vec<(f32, String)> {
    fn walk(shape: &egui::Shape, ppp: f32, out: &mut Vec<(f32, String)>) {
        match shape {
            egui::Shape::Vec(v) => v.iter().for_each(|s| walk(s, ppp, out)),
            egui::Shape::Text(t) if !t.galley.job.text.trim().is_empty() => {
                for s in &t.galley.job.sections {
                    out.push((s.format.font_id.size * ppp, t.galley.job.text.clone()));
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for p in &page.panels {
        for c in &p.capture.shapes {
            walk(&c.shape, p.capture.pixels_per_point, &mut out);
        }
    }
    out
}

/// Issue 46, item 4: in projector mode at 1280x800 the Workspace tab's figures (Fig. 2.30, a
/// workspace figure; Fig. 2.31, a drawing) keep every text at least 16 px at the size the tab
/// shows them (it was 7-10 px), and a recording's labels are sized for the frame they are
/// recorded into (about 9 px in a 640-pixel frame).
#[test]
fn projector_figures_and_recordings_have_readable_text() {
    use armlab::app::AppUi;
    use armlab::app::tabs::workspace::projector_text_scale;
    use armlab::app::workspace_job::WorkspaceJob;
    use armlab::figure::figures::Figures;
    use armlab::figure::workspace::WsView;
    // the width the tab shows its figure at, from the window's own layout
    let mut app = AppUi::new(AppState::from_spec("planar2_fig2_30").unwrap());
    app.layout.projector = true;
    app.tab = armlab::app::tabs::WORKSPACE;
    let mut h = egui_kittest::Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h.run();
    let shown = h.state().rects.central.width() - 16.0;
    let k = projector_text_scale(shown);
    assert!(k > 1.0, "{shown} px");
    let robot = armlab::kinematics::models::built_in("planar2_fig2_30").unwrap();
    let mut figs = Figures::new().unwrap();
    figs.capture_vectors(true);
    let size = [1200, 800];
    let opts = WorkspaceJob::options_for(&robot, WsView::Plane, size, Some("2.30")).scaled(k);
    armlab::headless::workspace_figure(&mut figs, &robot, "fig 2.30", &opts, &|_| {}).unwrap();
    let page = figs.take_vector().expect("the vectors");
    let mut small = Vec::new();
    for (px, text) in figure_texts(&page) {
        let seen = px * shown / size[0] as f32;
        if seen < 16.0 - 0.05 {
            small.push(format!("{seen:.1} px: {text:?}"));
        }
    }
    figs.text_scale = k;
    let img = armlab::headless::textbook_figure(&mut figs, "2.31", size, Default::default());
    assert!(img.is_ok());
    let page = figs.take_vector().expect("the drawing's vectors");
    for (px, text) in figure_texts(&page) {
        let seen = px * shown / size[0] as f32;
        if seen < 16.0 - 0.05 {
            small.push(format!("Fig. 2.31: {seen:.1} px: {text:?}"));
        }
    }
    // a recording's frame: the 3D view at 640 px (the recorder draws its frames with
    // Figures::scene), its frame labels sized for it
    figs.text_scale = 1.0;
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let q = [0.3, 0.5, -1.2, 0.4, 0.8, -0.6];
    let style = armlab::scene::ArmStyle {
        frames: true,
        frame_labels: true,
        ..Default::default()
    };
    let scene = armlab::scene::arm_scene(&puma, &q, &style).unwrap();
    assert!(!scene.labels.is_empty());
    let mut camera = armlab::camera::Camera::default();
    let points = armlab::scene::arm_points(&puma, &q).unwrap();
    camera.fit_points(&points, 640, 480, 0.75);
    let fig = armlab::figure::figures::Scene3d {
        title: String::new(),
        subtitle: String::new(),
        scene: &scene,
        camera,
        legend: Vec::new(),
        caption: String::new(),
    };
    figs.scene([640, 480], Default::default(), &fig).unwrap();
    let page = figs.take_vector().expect("the frame's vectors");
    let labels = figure_texts(&page);
    assert!(!labels.is_empty());
    // (the frame has no title nor caption: the recorder draws none)
    for (px, text) in labels {
        if px < 16.0 - 0.05 {
            small.push(format!("640-px frame: {px:.1} px: {text:?}"));
        }
    }
    assert!(small.is_empty(), "{}", small.join("\n"));
}
