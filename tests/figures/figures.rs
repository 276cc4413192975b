//! Figures made headlessly with the app's renderer: golden images and pixel checks that do not
//! depend on goldens. These tests need a graphics adapter; on a machine without a GPU that is
//! Mesa's software Vulkan (`apt-get install mesa-vulkan-drivers libvulkan1`), and they fail, not
//! skip, without it.

use crate::common;
use armlab::camera::{Camera, Preset, Projection};
use armlab::figure::Theme;
use armlab::figure::figures::{Figures, Scene3d};
use armlab::kinematics::models::built_in;
use armlab::scene::{ArmStyle, Dot, Scene, arm_points, arm_scene};
use common::golden::assert_golden;

fn figures() -> Figures {
    Figures::new().unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn arm_snapshot_with_dh_frames() {
    let robot = built_in("anthropomorphic_spherical_wrist").unwrap();
    let q = robot.config("ready").unwrap().to_vec();
    let scene = arm_scene(&robot, &q, &ArmStyle::default()).unwrap();
    let mut camera = Camera::default();
    camera.set_preset(Preset::Iso);
    camera.fit_points(&arm_points(&robot, &q).unwrap(), 800, 600, 0.75);
    let fig = Scene3d {
        title: robot.name.clone(),
        subtitle: "ready configuration".into(),
        scene: &scene,
        camera,
        legend: vec![],
        caption: String::new(),
    };
    let mut f = figures();
    let img = f.scene([800, 600], Theme::Light, &fig).unwrap();
    assert_golden("arm_anthropomorphic_spherical_wrist_frames", &img);
    // The same inputs give the same pixels.
    let again = f.scene([800, 600], Theme::Light, &fig).unwrap();
    assert!(img == again, "rendering is not deterministic");
}

/// The end-effector of a known pose lands at the pixel the camera predicts.
#[test]
fn end_effector_lands_at_the_projected_pixel() {
    let robot = built_in("planar2").unwrap();
    let q = [0.4, 0.9];
    let ee = robot.fk(&q).unwrap().translation.vector;
    let style = ArmStyle {
        frames: false,
        grid: false,
        ..ArmStyle::default()
    };
    let mut scene = arm_scene(&robot, &q, &style).unwrap();
    let marker = [1.0, 0.0, 1.0, 1.0];
    scene.dots.push(Dot {
        p: [ee.x as f32, ee.y as f32, ee.z as f32 + 0.2],
        color: marker,
        size_px: 14.0,
    });
    let mut camera = Camera {
        projection: Projection::Orthographic { height: 5.0 },
        ..Camera::default()
    };
    camera.set_preset(Preset::Top);
    camera.target = nalgebra::Point3::origin();
    camera.distance = 5.0;
    let fig = Scene3d {
        title: String::new(),
        subtitle: String::new(),
        scene: &scene,
        camera,
        legend: vec![],
        caption: String::new(),
    };
    let img = figures().scene([640, 640], Theme::Light, &fig).unwrap();
    let p = camera
        .project(
            &nalgebra::Point3::new(ee.x as f32, ee.y as f32, ee.z as f32 + 0.2),
            640,
            640,
        )
        .unwrap();
    // Orthographic top view: world (x, y) maps linearly to pixels.
    let expect = [
        320.0 + ee.x as f32 / 5.0 * 640.0,
        320.0 - ee.y as f32 / 5.0 * 640.0,
    ];
    assert!(
        (p[0] - expect[0]).abs() < 0.5 && (p[1] - expect[1]).abs() < 0.5,
        "{p:?} vs {expect:?}"
    );
    let px = img.get_pixel(p[0] as u32, p[1] as u32).0;
    assert!(
        px[0] > 200 && px[1] < 60 && px[2] > 200,
        "marker colour at {p:?}: {px:?}"
    );
    // Far from the arm: background.
    let bg = img.get_pixel(5, 630).0;
    assert!(
        bg[0] > 240 && bg[1] > 240 && bg[2] > 240,
        "background {bg:?}"
    );
}

#[test]
fn empty_scene_and_bad_size() {
    let mut f = figures();
    let scene = Scene::default();
    let fig = Scene3d {
        title: "t".into(),
        subtitle: String::new(),
        scene: &scene,
        camera: Camera::default(),
        legend: vec![],
        caption: String::new(),
    };
    assert!(f.scene([0, 100], Theme::Dark, &fig).is_err());
    let img = f.scene([320, 200], Theme::Dark, &fig).unwrap();
    let px = img.get_pixel(10, 190).0;
    assert!(
        px[0] < 60 && px[1] < 60 && px[2] < 60,
        "dark background {px:?}"
    );
}

/// Every figure of `armlab figure` as a golden image (looked at before committing), at 1000x750.
#[test]
fn the_excerpts_figures() {
    use armlab::construction::textbook::FIGURES;
    use armlab::headless::textbook_figure;
    let mut f = figures();
    for (name, _) in FIGURES {
        let img = textbook_figure(&mut f, name, [1000, 750], Theme::Light)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(img.dimensions(), (1000, 750));
        assert_golden(&format!("textbook_fig_{}", name.replace('.', "_")), &img);
    }
    assert!(textbook_figure(&mut f, "2.99", [400, 300], Theme::Light).is_err());
}
