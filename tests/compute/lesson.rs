//! Lessons: the shipped lessons parse, open in the app step by step, render to PNG; "Save as
//! lesson" appends the current setup; a lesson file dropped on the app opens as a lesson.

#![cfg(feature = "app")]

use armlab::app::AppUi;
use armlab::app::state::{AppState, Level};
use armlab::lesson::{Lesson, Overlay};

fn shipped() -> Vec<(String, String)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/lessons");
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p.to_string_lossy().into_owned(), text)
        })
        .collect();
    out.sort();
    out
}

#[test]
fn the_shipped_lessons_cover_the_sections_and_open_step_by_step() {
    let lessons = shipped();
    assert!(lessons.len() >= 6, "{} lessons", lessons.len());
    for (file, text) in &lessons {
        let lesson = Lesson::parse(text, file).unwrap();
        assert!(lesson.steps.len() >= 3, "{file}");
        let mut app = AppUi::new(AppState::from_spec("planar2").unwrap());
        app.open_lesson(lesson.clone(), file).unwrap();
        for i in 0..lesson.steps.len() {
            app.go_to_step(i);
            let errors: Vec<_> = app
                .state
                .messages()
                .iter()
                .filter(|m| m.level != Level::Info)
                .map(|m| m.text.clone())
                .collect();
            assert!(errors.is_empty(), "{file} step {}: {errors:?}", i + 1);
            if let Some(q) = lesson.step_q(i, app.state.robot(), file).unwrap() {
                for (a, b) in q.iter().zip(app.state.q()) {
                    assert!((a - b).abs() < 1e-9, "{file} step {}: q", i + 1);
                }
            }
            let ov = lesson.overlays(i);
            assert_eq!(app.state.display.ghosts, ov.contains(&Overlay::Ghosts));
            assert_eq!(
                app.ik.construction.shown,
                ov.contains(&Overlay::Construction)
            );
            assert_eq!(
                app.state.display.workspace,
                ov.contains(&Overlay::Workspace)
            );
        }
    }
}

#[test]
fn save_as_lesson_appends_the_current_setup_and_a_dropped_lesson_opens() {
    let dir = std::env::temp_dir().join(format!("armlab-lesson-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("mine.toml");
    let mut app = AppUi::new(AppState::from_spec("anthropomorphic3r").unwrap());
    app.state.set_q(&[0.1, 0.7, -1.2]).unwrap();
    app.lesson = Some(armlab::app::lesson::LessonPlayer {
        lesson: Lesson {
            title: "mine".into(),
            robot: "anthropomorphic3r".into(),
            steps: Vec::new(),
        },
        file: file.to_string_lossy().into_owned(),
        step: 0,
        editing: None,
        caption_view: Default::default(),
    });
    app.save_as_lesson().unwrap();
    app.state.set_q(&[0.4, 0.2, -0.5]).unwrap();
    app.save_as_lesson().unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    let saved = Lesson::parse(&text, "mine.toml").unwrap();
    assert_eq!(saved.steps.len(), 2);
    assert_eq!(saved.steps[0].q.as_deref(), Some(&[0.1, 0.7, -1.2][..]));
    assert!(saved.steps[1].camera.is_some() && saved.steps[1].target_position.is_some());
    // the saved lesson, dropped on an app showing another robot, plays from its first step
    let mut other = AppUi::new(AppState::from_spec("planar3").unwrap());
    other.open_bytes("mine.toml", text.as_bytes());
    assert_eq!(other.state.robot().dof(), 3);
    assert_eq!(other.lesson.as_ref().map(|p| p.lesson.steps.len()), Some(2));
    for (a, b) in other.state.q().iter().zip([0.1, 0.7, -1.2]) {
        assert!((a - b).abs() < 1e-12);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bad_lesson_is_one_clear_line_and_the_app_keeps_its_state() {
    let bad =
        "title = \"x\"\nrobot = \"anthropomorphic3r\"\n[[steps]]\nq_deg = [1, 2]\nview = \"up\"\n";
    let e = Lesson::parse(bad, "bad.toml").unwrap_err().to_string();
    assert!(
        e.starts_with("bad.toml: step 1:") && e.contains("view"),
        "{e}"
    );
    let no_robot = "title = \"x\"\nrobot = \"no_such_robot\"\n[[steps]]\ncaption = \"a\"\n";
    let mut app = AppUi::new(AppState::from_spec("planar3").unwrap());
    let lesson = Lesson::parse(no_robot, "l.toml").unwrap();
    assert!(app.open_lesson(lesson, "l.toml").is_err());
    assert_eq!(app.state.robot().dof(), 3, "the app's robot is kept");
}

/// Every shipped lesson renders to one PNG per step (the window as the class sees it).
#[test]
fn the_shipped_lessons_render_to_png() {
    let dir = std::env::temp_dir().join(format!("armlab-lesson-png-{}", std::process::id()));
    for (file, _) in shipped() {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_armlab"))
            .args([
                "lesson",
                &file,
                "--render",
                &dir.to_string_lossy(),
                "--size",
                "640x400",
            ])
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{file}: {} (a renderer needs Mesa's lavapipe: apt-get install mesa-vulkan-drivers libvulkan1)",
            String::from_utf8_lossy(&o.stderr)
        );
        let steps = Lesson::parse(&std::fs::read_to_string(&file).unwrap(), &file)
            .unwrap()
            .steps
            .len();
        let wrote = String::from_utf8_lossy(&o.stdout).lines().count();
        assert_eq!(wrote, steps, "{file}");
        let img = image::open(dir.join("step-01.png")).unwrap().to_rgba8();
        assert_eq!(img.dimensions(), (640, 400));
        let colours: std::collections::HashSet<_> = img.pixels().step_by(97).map(|p| p.0).collect();
        assert!(colours.len() > 20, "{file}: {} colours", colours.len());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A lesson's numbers must be finite (the fuzzer's lessons took `nan` and `inf` in q, the
/// target and the camera); overlays both on and off, and a construction step 0, are refused
/// too, each naming the step and the field.
#[test]
fn a_lesson_with_a_non_finite_number_or_a_contradiction_is_refused() {
    let head = "title = \"t\"\nrobot = \"planar2\"\n[[steps]]\n";
    for (step, field) in [
        ("q = [nan, 0.0]", "q"),
        ("q_deg = [0.0, inf]", "q_deg"),
        ("target_position = [1.0, -inf, 0.0]", "target_position"),
        (
            "camera = { azimuth_deg = nan, elevation_deg = 10.0 }",
            "camera",
        ),
        (
            "camera = { azimuth_deg = 0.0, elevation_deg = 10.0, target = [0.0, nan, 0.0] }",
            "camera",
        ),
    ] {
        let e = Lesson::parse(&format!("{head}{step}\n"), "l.toml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("l.toml: step 1: "), "{e}");
        assert!(e.contains(field) && e.contains("finite"), "{e}");
    }
    let both = format!("{head}overlays = [\"ghosts\"]\noverlays_off = [\"ghosts\"]\n");
    let e = Lesson::parse(&both, "l.toml").unwrap_err().to_string();
    assert!(e.contains("both in overlays and in overlays_off"), "{e}");
    let zero = format!("{head}construction_step = 0\n");
    let e = Lesson::parse(&zero, "l.toml").unwrap_err().to_string();
    assert!(e.contains("construction_step counts from 1"), "{e}");
}
