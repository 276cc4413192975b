//! The app's Calibration tab: its state (simulated runs, the two lessons, files, saving) and the
//! tab driven through egui (kittest, no GPU).

use armlab::app::AppUi;
use armlab::app::state::AppState;
use armlab::app::tabs::calibration::lab::{CalibrationLab, PoseChoice};
use armlab::kinematics::models::built_in;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

fn lengths_off(r: &armlab::app::tabs::calibration::lab::LabResult) -> f64 {
    r.report
        .parameters
        .iter()
        .zip(&r.report.estimate)
        .filter(|(p, _)| !p.kind.is_angle())
        .map(|(p, v)| (v - p.nominal).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_simulated_run_calibrates_and_validates() {
    let puma = built_in("puma560").unwrap();
    let mut lab = CalibrationLab::default();
    lab.run_simulated(&puma, &[0.0; 6]);
    let r = lab.result.as_ref().expect("a result");
    assert!(lab.message().is_none());
    assert!(r.report.converged);
    let (before, after) = r.validation.unwrap();
    assert!(
        after.position_rms < 0.05 * before.position_rms,
        "{before:?} -> {after:?}"
    );
    assert_eq!(r.poses.len(), lab.settings.poses);
}

#[test]
fn the_two_lessons_show_what_they_promise() {
    let puma = built_in("puma560").unwrap();
    let q = puma.config("ready").unwrap().to_vec();
    let mut lab = CalibrationLab::default();
    // Converged is not accurate: the poses' own residual is the noise, the held-out one is not.
    lab.lesson_alike(&puma, &q);
    assert_eq!(lab.settings.choice, PoseChoice::Alike);
    let r = lab.result.as_ref().unwrap();
    let (_, held_out) = r.validation.unwrap();
    assert!(r.report.converged);
    assert!(
        held_out.position_rms > 10.0 * r.report.after.position_rms,
        "{held_out:?}"
    );
    // Parallel axes: plain DH names d2 + d3 and runs a length off; beta does not.
    lab.lesson_parallel(&puma, &q, false);
    let plain = lab.result.clone().unwrap();
    assert!(
        plain
            .report
            .nominal
            .combinations
            .iter()
            .any(|c| c.contains("d2 and d3 only as d2 + d3"))
    );
    lab.lesson_parallel(&puma, &q, true);
    let beta = lab.result.clone().unwrap();
    assert_eq!(beta.model.hayati_rows(), vec![2]);
    assert_eq!(
        beta.report.nominal.rank,
        beta.report.nominal.parameter_count
    );
    assert!(lengths_off(&plain) > 0.05 && lengths_off(&beta) < 0.005);
}

#[test]
fn file_errors_keep_the_last_result_and_the_model_saves() {
    let puma = built_in("puma560").unwrap();
    let dir = std::env::temp_dir().join(format!("armlab-lab-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut lab = CalibrationLab::default();
    lab.run_simulated(&puma, &[0.0; 6]);
    let estimate = lab.result.as_ref().unwrap().report.estimate.clone();
    lab.measurements_path = dir.join("missing.csv").display().to_string();
    lab.run_file(&puma);
    assert!(lab.message().unwrap().contains("cannot read"));
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "0,0,0\n").unwrap();
    lab.measurements_path = bad.display().to_string();
    lab.run_file(&puma);
    assert!(lab.message().unwrap().contains(":1:"), "{:?}", lab.said);
    assert_eq!(
        lab.result.as_ref().unwrap().report.estimate,
        estimate,
        "the result is kept"
    );
    let out = dir.join("calibrated.toml");
    lab.save_path = out.display().to_string();
    lab.save_model();
    assert!(lab.message().unwrap().starts_with("saved"));
    let back = armlab::model_file::load_model(out.to_str().unwrap()).unwrap();
    let r = lab.result.as_ref().unwrap();
    let q = [0.2, 0.4, -0.6, 0.8, -1.0, 1.2];
    let (_, t) = r.model.frames(&r.report.estimate, &q).unwrap();
    assert!((back.fk(&q).unwrap().to_homogeneous() - t.to_homogeneous()).amax() < 1e-12);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_tab_runs_from_its_buttons() {
    let app = AppUi::new(AppState::from_spec("puma560").unwrap());
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h.get_by_label("Calibration").click();
    h.run();
    assert_eq!(h.state().tab, armlab::app::tabs::CALIBRATION);
    h.get_by_label("Run").click();
    h.run();
    assert!(h.state().tabs.calibration.lab.result.is_some());
    h.run();
    assert!(h.query_by_label_contains("held-out after").is_some());
}

#[test]
fn accuracy_maps_before_and_after() {
    let puma = built_in("puma560").unwrap();
    let mut lab = CalibrationLab::default();
    lab.compute_maps(32, 5_000);
    assert!(
        lab.maps.is_none() && lab.message().is_some(),
        "no result yet"
    );
    lab.run_simulated(&puma, &[0.0; 6]);
    lab.compute_maps(32, 20_000);
    let (before, after) = lab.maps.as_ref().unwrap();
    let before = before
        .as_ref()
        .expect("simulated: nominal against the real arm");
    assert!(
        after.rms < 0.1 * before.rms,
        "{} vs {}",
        after.rms,
        before.rms
    );
    assert_eq!(lab.maps_generation, 1);
    // A new run drops the maps of the old one.
    lab.run_simulated(&puma, &[0.0; 6]);
    assert!(lab.maps.is_none());
}

#[test]
fn the_map_button_computes_the_maps() {
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.tab = armlab::app::tabs::CALIBRATION;
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h.get_by_label("Run").click();
    h.run();
    h.get_by_label("Accuracy map (before / after)").click();
    h.run();
    h.run();
    assert!(h.state().tabs.calibration.lab.maps.is_some());
    assert!(
        h.query_by_label_contains("Accuracy after calibration")
            .is_some()
    );
}

#[test]
fn measured_poses_are_drawn_as_tool_points_and_a_few_ghosts() {
    use armlab::app::viewport::{MAX_POSE_GHOSTS, add_measured_poses, build_scene};
    let state = AppState::from_spec("puma560").unwrap();
    let mut lab = CalibrationLab::default();
    lab.run_simulated(state.robot(), state.q());
    let poses = &lab.result.as_ref().unwrap().poses;
    let mut scene = build_scene(&state, 0, false);
    let (dots, meshes) = (scene.dots.len(), scene.meshes.len());
    add_measured_poses(&mut scene, state.robot(), poses);
    assert_eq!(scene.dots.len() - dots, poses.len());
    // Each tool point where FK puts it.
    for (d, q) in scene.dots[dots..].iter().zip(poses) {
        let p = state.robot().fk(q).unwrap().translation.vector;
        assert!((d.p[0] as f64 - p.x).abs() < 1e-5 && (d.p[2] as f64 - p.z).abs() < 1e-5);
    }
    let one_arm = armlab::scene::arm_scene(state.robot(), state.q(), &Default::default())
        .unwrap()
        .meshes
        .len();
    let ghosts = (scene.meshes.len() - meshes) / one_arm;
    assert!((1..=MAX_POSE_GHOSTS).contains(&ghosts), "{ghosts} ghosts");
}

#[test]
fn the_tab_offers_the_setups_the_files_the_template_and_target_correction() {
    use armlab::calibration::Setup;
    let puma = built_in("puma560").unwrap();
    let mut lab = CalibrationLab::default();
    // Every setup simulates and calibrates; the report says what it cannot see.
    for setup in [Setup::Distance, Setup::Sphere, Setup::Tracker, Setup::Pivot] {
        lab.settings.setup = setup;
        lab.settings.poses = 80;
        lab.run_simulated(&puma, &[0.0; 6]);
        assert!(lab.message().is_none(), "{setup:?}: {:?}", lab.said);
        let r = lab.result.as_ref().unwrap();
        assert_eq!(r.setup, setup);
        assert!(r.report.converged, "{setup:?}");
        let (before, after) = r.validation.unwrap();
        assert!(after.position_rms < 0.2 * before.position_rms, "{setup:?}");
        // The bare Puma's tool point is its wrist centre: no point setup sees the wrist, and the
        // base pose trades with the scene; both are kept nominal and said.
        assert!(
            r.report.auto_fixed.iter().any(|(n, _)| n == "d1"),
            "{setup:?}"
        );
    }
    // The cell's headered CSV (degrees, millimetres, quaternions, extra columns).
    lab.settings.setup = Setup::Pose;
    let path = format!(
        "{}/tests/data/calibration/cell_puma_fit.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    lab.measurements_path = path;
    lab.run_file(&puma);
    assert!(lab.message().is_none(), "{:?}", lab.said);
    let r = lab.result.as_ref().unwrap();
    assert!(r.warnings.iter().any(|w| w.contains("timestamp")));
    assert!(r.report.after.position_rms < 0.05e-3);
    // The template of a setup reads back as that setup's file.
    lab.settings.setup = Setup::Distance;
    let t = lab.template_text(&puma).unwrap();
    assert!(t.contains("_a [deg]") && t.contains("distance [mm]"));
    let parsed = armlab::calibration::parse_setup(
        &t,
        "template",
        &armlab::calibration::JointColumns::of(&puma),
        Setup::Distance,
        None,
    )
    .unwrap();
    assert_eq!(parsed.measurements.len(), 4);
    // Target correction on the calibrated cell arm: eight postures for a pose inside.
    lab.correct_text(
        &puma,
        "targets",
        "x [mm], y [mm], z [mm], roll [deg], pitch [deg], yaw [deg]\n450, 150, 400, 180, 0, 0\n",
    );
    assert!(lab.message().is_none(), "{:?}", lab.said);
    let rows = lab.corrections.as_ref().unwrap();
    assert_eq!(rows.len(), 8);
    assert!(rows.iter().all(|r| r.position_error <= 1e-12));
    let csv = lab.corrections_text(&puma).unwrap();
    assert_eq!(csv.lines().filter(|l| !l.starts_with('#')).count(), 9);
    // A bad targets file is a message; the corrections stay.
    lab.correct_text(&puma, "bad", "x, y, z\n1, 2, 3\n");
    assert!(lab.message().unwrap().contains("orientation"));
    assert!(lab.corrections.is_some());
}

#[test]
fn the_compliance_lesson_shows_the_error_no_dh_parameter_absorbs() {
    let puma = built_in("puma560").unwrap();
    let q = puma.config("ready").unwrap().to_vec();
    let mut lab = CalibrationLab::default();
    lab.lesson_compliance(&puma, &q, false);
    assert!(lab.message().is_none(), "{:?}", lab.said);
    let (_, geometric) = lab.result.as_ref().unwrap().validation.unwrap();
    lab.lesson_compliance(&puma, &q, true);
    let r = lab.result.as_ref().unwrap();
    let (_, with) = r.validation.unwrap();
    // The tracker's floor: sqrt(3) x 2 um.
    let floor = 3f64.sqrt() * 0.002e-3;
    assert!(geometric.position_rms > 3.0 * floor, "{geometric:?}");
    assert!(with.position_rms < 1.3 * floor, "{with:?}");
    assert!(r.report.parameters.iter().any(|p| p.name == "c2"));
    assert!(lab.lesson.unwrap().contains("compliance"));
}

#[test]
fn an_empty_path_says_what_to_type_and_keeps_the_result() {
    let puma = built_in("puma560").unwrap();
    let mut lab = CalibrationLab::default();
    lab.run_simulated(&puma, &[0.0; 6]);
    lab.run_file(&puma);
    assert!(lab.message().unwrap().contains("type the path"));
    lab.correct(&puma);
    assert!(lab.message().unwrap().contains("desired tool poses"));
    assert!(lab.result.is_some());
}

/// Issue 46, item 3: the parallel-axes lesson is a sandbox. Its settings (plain DH, estimate
/// the unidentifiable) come back to the user's when it ends, and its result goes. Its d2 and d3
/// are red in the table with the reason the lesson's text gives, and saving such a model asks
/// first, then writes the warning at the top of the file. No CLI flag is in the tab's words.
#[test]
fn a_calibration_lesson_leaves_nothing_behind_and_an_absurd_model_is_not_saved_unwarned() {
    use armlab::app::tabs::calibration::lab::Said;
    let puma = built_in("puma560").unwrap();
    let q = puma.config("ready").unwrap().to_vec();
    let mut lab = CalibrationLab::default();
    lab.settings.poses = 30;
    let mine = lab.settings;
    lab.lesson_parallel(&puma, &q, false);
    assert!(!lab.settings.hayati && lab.settings.minimum_norm);
    assert!(lab.lesson.unwrap().contains("not identifiable"));
    // the doubtful estimates, checked independently: d2 and d3 ran a length off their nominal
    // values, and the nominal analysis names their combination
    let r = lab.result.clone().unwrap();
    let doubts = lab.doubts();
    let names: Vec<&str> = doubts.iter().map(|d| d.name.as_str()).collect();
    for name in ["d2", "d3"] {
        let k = r
            .report
            .parameters
            .iter()
            .position(|p| p.name == name)
            .unwrap();
        assert!((r.report.estimate[k] - r.report.parameters[k].nominal).abs() > 0.05);
        assert!(names.contains(&name), "{name} not doubtful: {doubts:?}");
    }
    for d in &doubts {
        assert!(d.reason().contains("not identifiable"), "{d}");
        assert!(!d.reason().contains("--"), "a CLI flag in {d}");
    }
    // saving asks first; "Don't save" writes nothing
    let dir = std::env::temp_dir().join(format!("armlab-sandbox-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("lesson.toml");
    lab.save_path = out.display().to_string();
    assert!(!lab.request_save(), "saving an absurd model must ask first");
    assert!(lab.confirm_save);
    lab.cancel_save();
    assert!(!out.exists());
    // asked and answered yes: the file names them in a warning at its top, the message is
    // not a plain "saved"
    assert!(!lab.request_save());
    lab.save_model();
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("# WARNING"), "{text}");
    assert!(text.lines().take(4).any(|l| l.contains("d2 =")), "{text}");
    assert!(matches!(lab.said, Some(Said::Warned(_))), "{:?}", lab.said);
    assert!(armlab::model_file::load_model(out.to_str().unwrap()).is_ok());
    // the lesson ends: the user's settings are back, the lesson's result is gone
    lab.end_lesson();
    assert_eq!(lab.settings, mine);
    assert!(lab.result.is_none() && lab.lesson.is_none());
    // a lesson, then real data: the file is read with the user's settings
    lab.lesson_parallel(&puma, &q, false);
    lab.measurements_path = dir.join("missing.csv").display().to_string();
    lab.run_file(&puma);
    assert_eq!(lab.settings, mine);
    // and a plain run's model saves at once, in green
    lab.run_simulated(&puma, &q);
    assert!(lab.doubts().is_empty(), "{:?}", lab.doubts());
    assert!(lab.request_save());
    lab.save_model();
    assert!(matches!(lab.said, Some(Said::Done(_))), "{:?}", lab.said);
    assert!(!std::fs::read_to_string(&out).unwrap().contains("WARNING"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 46, item 6: the Calibration tab calibrates a URDF arm of a robot with several arms
/// (Baxter's left arm) through its derived DH table, as `armlab calibrate --ee` does; the
/// calibrated model saves back as a URDF of the arm's own chain, whose FK is the calibrated
/// DH model's (checked at random joint vectors). The refusal it gave before is gone, and a
/// message never outlives the model it was about.
#[test]
fn the_tab_calibrates_a_urdf_arm_of_a_tree_and_writes_it_back() {
    let mut app = AppUi::new(AppState::from_spec("tests/data/urdf_corpus/baxter.urdf").unwrap());
    let ee = app
        .state
        .robot()
        .end_effectors()
        .iter()
        .position(|e| e.name == "left_gripper")
        .expect("Baxter's left gripper");
    app.apply(armlab::app::action::Action::SelectEe(ee));
    app.tabs.calibration.lab.settings.poses = 30;
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h.get_by_label("Calibration").click();
    h.run();
    h.get_by_label("Run").click();
    h.run();
    let lab = &h.state().tabs.calibration.lab;
    assert!(lab.message().is_none(), "{:?}", lab.said);
    let r = lab.result.as_ref().expect("a result");
    assert!(r.report.parameters.len() >= 28);
    let (before, after) = r.validation.unwrap();
    assert!(after.position_rms < 0.05 * before.position_rms);
    // the tab's words cite no command-line flag (the derived table's warning did)
    assert!(
        r.warnings.iter().all(|w| !w.contains("--")),
        "{:?}",
        r.warnings
    );
    let chain = r
        .chain
        .clone()
        .expect("calibrated through the derived table");
    assert_eq!(chain.dof(), 7);
    // written back as a URDF of the arm's chain
    let dir = std::env::temp_dir().join(format!("armlab-cal-urdf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("left_arm.urdf");
    let lab = &mut h.state_mut().tabs.calibration.lab;
    lab.save_path = out.display().to_string();
    assert!(lab.request_save(), "{:?}", lab.doubts());
    lab.save_model();
    assert!(out.is_file(), "{:?}", lab.said);
    let back = armlab::model_file::load_model(out.to_str().unwrap()).unwrap();
    let calibrated = lab.result.as_ref().unwrap().calibrated_robot().unwrap();
    assert_eq!(back.dof(), 7);
    let mut seed = 7u64;
    for _ in 0..10 {
        let q: Vec<f64> = (0..7)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed % 2000) as f64 / 1000.0 - 1.0
            })
            .collect();
        let a = back.fk(&q).unwrap().to_homogeneous();
        let b = calibrated.fk(&q).unwrap().to_homogeneous();
        assert!((a - b).amax() < 1e-9, "{a} vs {b}");
    }
    // another model: the message about Baxter goes
    lab.fail("a message about Baxter".into());
    h.state_mut().load("puma560");
    h.run();
    assert!(h.state().tabs.calibration.lab.message().is_none());
    let _ = std::fs::remove_dir_all(&dir);
}
