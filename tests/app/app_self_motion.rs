//! The app's Redundancy panel and self-motion slider, as state logic (no GUI): the task the
//! gizmo obeys, n/m/r in words, the slider holding the hand exactly, its value read back from q
//! (never stale after a moved target or a new model), feasible stretches as walls, the numerical
//! case without drift.

use armlab::app::state::{AppState, Reach, StateError};
use armlab::kinematics::Pose;
use armlab::kinematics::redundancy::Task;
use armlab::redundancy::srs::SrsArm;
use nalgebra::{Rotation3, Translation3, Vector3};
use std::f64::consts::PI;

fn state(spec: &str) -> AppState {
    AppState::from_spec(spec).expect("built-in model")
}

fn fk(s: &AppState, ee: usize) -> Pose {
    s.robot().fk_ee(s.q(), ee).unwrap()
}

fn gap(a: &Pose, b: &Pose) -> (f64, f64) {
    (
        (a.translation.vector - b.translation.vector).norm(),
        (a.rotation.matrix() - b.rotation.matrix()).abs().max(),
    )
}

#[test]
fn redundancy_is_named_for_the_task_and_tasks_are_checked() {
    let mut s = state("planar3");
    assert_eq!(s.tasks(), vec![Task::Planar, Task::PlanarPhi]);
    assert_eq!(s.task(), Task::PlanarPhi);
    assert_eq!(s.redundancy().words(), "not redundant");
    let why = s.self_motion(0).unwrap_err();
    assert!(why.contains("no self-motion"), "{why}");
    s.set_task(Task::Planar).unwrap();
    let r = s.redundancy();
    assert_eq!((r.n, r.m, r.r), (3, 3, 2));
    assert_eq!(r.words(), "functionally redundant");
    assert_eq!(s.self_motion(0).unwrap().parameter, "phi");
    assert!(matches!(s.set_task(Task::Pose), Err(StateError::Task(_))));
    assert_eq!(s.task(), Task::Planar);
    // A new model starts with its full task.
    s.load_model("dlr").unwrap();
    assert_eq!(s.task(), Task::Pose);
    assert_eq!(s.redundancy().words(), "intrinsically redundant");
    s.load_model("planar4").unwrap();
    let r = s.redundancy();
    assert_eq!(
        (r.n, r.m, r.r, r.words()),
        (4, 3, 3, "intrinsically redundant")
    );
    assert_eq!(s.self_motion(0).unwrap().parameter, "phi");
}

#[test]
fn the_arm_angle_slider_holds_the_hand_and_reads_back_from_q() {
    let mut s = state("dlr");
    let held = fk(&s, 0);
    let v = s.self_motion(0).unwrap();
    assert!(v.exact && v.parameter == "arm angle");
    let arm = SrsArm::detect(s.robot()).unwrap();
    assert!((v.value - arm.arm_angle(s.q()).unwrap()).abs() < 1e-9);
    // Drag in small steps inside the feasible stretch, then back.
    let iv = v.feasible[v.branch]
        .iter()
        .find(|iv| v.value >= iv[0] && v.value <= iv[1])
        .copied()
        .unwrap();
    let mut want = v.value;
    for k in 0..400 {
        want = if k < 200 {
            (want + 0.003).min(iv[1])
        } else {
            (want - 0.003).max(iv[0])
        };
        let got = s.set_self_motion(0, want).unwrap();
        assert!((got - want).abs() < 1e-12);
        let now = s.self_motion(0).unwrap();
        assert!((now.value - want).abs() < 1e-9, "{} vs {want}", now.value);
        assert!((arm.arm_angle(s.q()).unwrap() - want).abs() < 1e-9);
        let (dp, dr) = gap(&fk(&s, 0), &held);
        assert!(dp < 1e-12 && dr < 1e-12, "hand moved {dp} m {dr}");
        assert!(now.position_error < 1e-12 && now.orientation_error < 1e-12);
        assert!(s.robot().within_limits(s.q(), 1e-12));
    }
    // Past the end of the stretch the arm stops at the wall, inside the limits.
    let got = s.set_self_motion(0, iv[1] + 1.0).unwrap();
    if iv[1] < PI {
        assert!((got - iv[1]).abs() < 1e-12, "{got} vs {}", iv[1]);
    }
    assert!(s.robot().within_limits(s.q(), 1e-12));
    // The path is the elbow circle: every traced point at one distance from the S-W axis.
    let v = s.self_motion(0).unwrap();
    let sh = arm.shoulder();
    let wc = arm.wrist_of(&held);
    let u = (wc - sh).normalize();
    let radius = |p: &Vector3<f64>| ((p - sh) - u * u.dot(&(p - sh))).norm();
    let pts: Vec<Vector3<f64>> = v.path.iter().filter_map(|(p, _)| *p).collect();
    assert!(pts.len() > 100);
    let r0 = radius(&pts[0]);
    assert!(
        pts.iter().all(|p| (radius(p) - r0).abs() < 1e-9),
        "not a circle"
    );
    // The other branches are ghosts at the same arm angle.
    let ghosts = s.self_motion_ghosts(0);
    assert!(!ghosts.is_empty() && ghosts.len() < 8);
}

#[test]
fn a_moved_target_or_a_new_model_leaves_no_stale_value() {
    let mut s = state("dlr");
    let before = s.self_motion(0).unwrap();
    let t = s.targets()[0].world_from_tool;
    let moved = Pose::from_parts(
        Translation3::from(t.translation.vector + Vector3::new(0.05, -0.04, 0.03)),
        Rotation3::from_euler_angles(0.2, -0.1, 0.3) * t.rotation,
    );
    assert!(matches!(s.set_target(0, moved).unwrap(), Reach::Reached));
    let after = s.self_motion(0).unwrap();
    let arm = SrsArm::detect(s.robot()).unwrap();
    assert!((after.value - arm.arm_angle(s.q()).unwrap()).abs() < 1e-9);
    assert_ne!(before.feasible, after.feasible);
    let (dp, _) = gap(&fk(&s, 0), &moved);
    assert!(dp < 1e-8);
    // A new model: the Panda's parameter is q7, read from q.
    s.load_model("panda").unwrap();
    let v = s.self_motion(0).unwrap();
    assert_eq!(v.parameter, "q7");
    assert!((v.value - s.q()[6]).abs() < 1e-12);
    let held = fk(&s, 0);
    let got = s.set_self_motion(0, v.value - 0.2).unwrap();
    assert!((s.q()[6] - got).abs() < 1e-12);
    let (dp, dr) = gap(&fk(&s, 0), &held);
    assert!(dp < 1e-12 && dr < 1e-12);
    // A DH edit (a new generation) rebuilds the self-motion too.
    s.load_model("planar3").unwrap();
    assert!(s.self_motion(0).is_err());
}

#[test]
fn the_humanoid_arm_with_its_torso_walks_without_drift() {
    let mut s = state("humanoid");
    let held = fk(&s, 0);
    let v = s.self_motion(0).unwrap();
    assert!(!v.exact && v.parameter == "arc length");
    let mut reached = 0.0;
    for k in 0..300 {
        let want = if (k / 50) % 2 == 0 {
            reached + 0.02
        } else {
            reached - 0.02
        };
        reached = s.set_self_motion(0, want).unwrap();
        let (dp, dr) = gap(&fk(&s, 0), &held);
        assert!(dp < 1e-12 && dr < 1e-12, "step {k}: {dp} m, {dr}");
    }
    let v = s.self_motion(0).unwrap();
    assert!((v.value - reached).abs() < 1e-12);
    assert!(v.position_error < 1e-12);
    assert!(!v.path.is_empty());
}

#[test]
fn the_gizmo_obeys_the_task() {
    // Position and approach axis on the Puma: a target turned about its own z is met with the
    // rotation about the tool axis left free.
    let mut s = state("puma560");
    s.set_q(&[0.3, -0.5, 0.4, 0.6, -0.7, 0.2]).unwrap();
    s.set_task(Task::PositionAxis).unwrap();
    let t = fk(&s, 0);
    let turned = Pose::from_parts(
        Translation3::from(t.translation.vector + Vector3::new(0.02, 0.01, -0.02)),
        t.rotation * Rotation3::from_axis_angle(&Vector3::z_axis(), 1.0),
    );
    let reach = s.set_target(0, turned).unwrap().clone();
    assert!(matches!(reach, Reach::Reached), "{reach:?}");
    let now = fk(&s, 0);
    assert!((now.translation.vector - turned.translation.vector).norm() < 1e-8);
    let z = |p: &Pose| p.rotation * Vector3::z();
    assert!((z(&now) - z(&turned)).norm() < 1e-8);
    // Not the whole rotation: the arm took the short way, not the full turn about z.
    let x = |p: &Pose| p.rotation * Vector3::x();
    assert!((x(&now) - x(&turned)).norm() > 0.1);
    // Position only on the three-link arm: a target turned in the plane keeps the arm's phi.
    let mut s = state("planar3");
    s.set_task(Task::Planar).unwrap();
    let t = fk(&s, 0);
    let moved = Pose::from_parts(
        Translation3::from(t.translation.vector + Vector3::new(-0.03, 0.02, 0.0)),
        Rotation3::from_axis_angle(&Vector3::z_axis(), 0.7) * t.rotation,
    );
    assert!(matches!(s.set_target(0, moved).unwrap(), Reach::Reached));
    let now = fk(&s, 0);
    assert!((now.translation.vector - moved.translation.vector).norm() < 1e-8);
    assert!((x(&now) - x(&moved)).norm() > 0.1);
}

/// A self-motion path with no points (exact case) draws nothing instead of overflowing
/// `n - 1` (found by the soak test, tests/soak/app_soak.rs, in the 3D view of a redundant arm).
#[test]
fn an_empty_traced_path_draws_nothing() {
    let mut s = state("dlr");
    let mut view = s.self_motion(0).unwrap();
    assert!(view.exact);
    for n in [0, 1, 2] {
        view.path = vec![(Some(Vector3::zeros()), true); n];
        let mut scene = armlab::scene::Scene::default();
        armlab::app::viewport::add_self_motion(&mut scene, s.robot(), &view, &[], true);
        assert_eq!(scene.lines.len(), n.saturating_sub(1));
    }
}

/// The laser-cutting task in the app: the Puma holding only its tool point and approach axis
/// has a self-motion slider (numerical, degree 1) that turns the hand about the axis; the
/// readouts give the task's errors, and FK shows the point and the axis held.
#[test]
fn a_partial_task_gets_a_self_motion_slider() {
    let mut s = state("puma560");
    s.set_q(&[0.3, -0.5, 0.4, 0.6, -0.7, 0.2]).unwrap();
    s.set_task(Task::PositionAxis).unwrap();
    let held = fk(&s, 0);
    let v = s.self_motion(0).unwrap();
    assert!(!v.exact && v.parameter == "arc length", "{}", v.meaning);
    assert!(v.meaning.contains("position+axis"));
    let mut reached = 0.0;
    for k in 0..200 {
        let want = if k < 100 {
            reached + 0.02
        } else {
            reached - 0.01
        };
        reached = s.set_self_motion(0, want).unwrap();
        let t = fk(&s, 0);
        let dp = (t.translation.vector - held.translation.vector).norm();
        let (za, zb) = (t.rotation * Vector3::z(), held.rotation * Vector3::z());
        assert!(dp < 1e-12, "step {k}: {dp} m");
        assert!(za.cross(&zb).norm().atan2(za.dot(&zb)) < 1e-12, "step {k}");
    }
    let (_, turned) = gap(&fk(&s, 0), &held);
    assert!(
        turned > 0.1,
        "the hand did not turn about its axis: {turned} rad"
    );
    let v = s.self_motion(0).unwrap();
    assert!(v.position_error < 1e-12 && v.orientation_error < 1e-12);
}

/// 10,000 slider steps sweeping back and forth over the whole slider range (past the ends of
/// the feasible stretches, where the slider stops at the wall): the hand stays on the pose held
/// when the self-motion started, to 1e-12 m and 1e-12 (rotation-matrix entries), measured by FK
/// here, and the readout's errors are against that held pose too.
#[test]
fn ten_thousand_slider_steps_never_move_the_hand() {
    for spec in ["dlr", "lwr4", "panda", "humanoid"] {
        let mut s = state(spec);
        let held = fk(&s, 0);
        let v = s.self_motion(0).unwrap();
        let [lo, hi] = v.range;
        let step = (hi - lo) / 400.0;
        let mut want = v.value;
        let mut dir = 1.0;
        let mut worst = (0.0f64, 0.0f64);
        for k in 0..10_000 {
            want += dir * step;
            if want > hi || want < lo {
                dir = -dir;
                want = want.clamp(lo, hi);
            }
            let got = s.set_self_motion(0, want).unwrap();
            // Where the slider stopped at a wall, the next step starts from there.
            if (got - want).abs() > 1e-9 && k % 2 == 0 {
                want = got;
            }
            let (dp, dr) = gap(&fk(&s, 0), &held);
            worst = (worst.0.max(dp), worst.1.max(dr));
            assert!(
                dp < 1e-12 && dr < 1e-12,
                "{spec}: step {k} (parameter {want:.4}): the hand moved {dp:e} m, {dr:e}"
            );
            assert!(s.robot().within_limits(s.q(), 1e-9), "{spec}: step {k}");
        }
        let now = s.self_motion(0).unwrap();
        assert!(
            now.position_error < 1e-12 && now.orientation_error < 1e-12,
            "{spec}: readout {} m, {} rad",
            now.position_error,
            now.orientation_error
        );
        eprintln!(
            "{spec}: worst over 10,000 steps {:.1e} m, {:.1e}",
            worst.0, worst.1
        );
    }
}

/// The live window's path: the self-motion slider dragged back and forth with the mouse, four
/// sweeps, as a teacher would (egui_kittest, the window's own layout). The hand stays where it
/// was when the self-motion started (it once drifted by 0.3 mm and 0.4 deg a sweep while the
/// readout said 0 and the target followed the hand), and the target stays put.
#[test]
fn dragging_the_slider_in_the_window_never_moves_the_hand() {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;
    for name in ["dlr", "lwr4", "panda"] {
        let app = armlab::app::AppUi::new(state(name));
        let mut h = Harness::builder()
            .with_size(egui::vec2(1280.0, 800.0))
            .build_ui_state(|ui, app: &mut armlab::app::AppUi| app.show(ui, None), app);
        h.state_mut().tab = armlab::app::tabs::SELF_MOTION;
        for _ in 0..4 {
            h.step();
        }
        let held = fk(&h.state().state, 0);
        let target = h.state().state.target(0).unwrap().world_from_tool;
        // The tab's own slider (the Redundancy panel has the same one).
        let sliders: Vec<egui::Rect> = h
            .get_all_by_label("self-motion slider")
            .map(|n| n.rect())
            .collect();
        assert_eq!(sliders.len(), 2, "the tab's and the panel's sliders");
        let track = sliders
            .into_iter()
            .find(|r| h.state().rects.central.contains_rect(*r))
            .expect("the tab's slider");
        let y = track.center().y;
        let xs: Vec<f32> = (0..=40)
            .map(|k| track.left() + 2.0 + (track.width() - 4.0) * k as f32 / 40.0)
            .collect();
        for _sweep in 0..4 {
            h.drag_at(egui::pos2(track.center().x, y));
            h.step();
            for &x in xs.iter().rev().chain(xs.iter()) {
                h.hover_at(egui::pos2(x, y));
                h.step();
            }
            h.drop_at(egui::pos2(track.center().x, y));
            h.step();
        }
        h.step();
        let s = &h.state().state;
        let (dp, dr) = gap(&fk(s, 0), &held);
        assert!(
            dp < 1e-12 && dr < 1e-12,
            "{name}: the hand moved {dp} m, {dr} rad"
        );
        let (tp, tr) = gap(&s.target(0).unwrap().world_from_tool, &target);
        assert!(
            tp < 1e-12 && tr < 1e-12,
            "{name}: the target moved {tp} m, {tr} rad"
        );
    }
}

/// On a tree the slider moves the chosen arm alone, by that arm's exact parameter: the URDF
/// Panda with its fingers (issue 26) gets the q7 slider of the built-in Panda; the finger never
/// moves, and Baxter's exact self-motion of one arm (q3 locked) leaves the other arm and the head still.
#[test]
fn on_a_tree_the_slider_moves_the_chosen_arm_alone() {
    let mut s = state("tests/data/urdf_corpus/panda.urdf");
    assert_eq!(s.robot().dof(), 8);
    let red = s.redundancy_of(0);
    assert_eq!((red.n, red.degree()), (7, 1));
    let view = s.self_motion(0).expect("a self-motion");
    assert!(view.exact, "exact, not the numerical walk");
    assert_eq!(view.parameter, "q7");
    let held = fk(&s, 0);
    let finger = s.q()[7];
    let target = view.value + 0.05;
    let reached = s.set_self_motion(0, target).unwrap();
    assert!((reached - view.value).abs() > 1e-3, "the slider moved");
    let (dp, dr) = gap(&held, &fk(&s, 0));
    assert!(
        dp < 1e-9 && dr < 1e-9,
        "the hand is held: {dp:e} m, {dr:e} rad"
    );
    assert_eq!(s.q()[7], finger, "the finger is off the arm");

    let mut b = state("tests/data/urdf_corpus/baxter.urdf");
    let ee = 0;
    let chain: Vec<usize> = b
        .robot()
        .chain_to(b.robot().end_effectors()[ee].parent)
        .to_vec();
    let on_arm: Vec<bool> = b
        .robot()
        .actuated_joints()
        .iter()
        .map(|j| chain.contains(j))
        .collect();
    let before = b.q().to_vec();
    let held = fk(&b, ee);
    // Baxter's arm is a 7R arm neither SRS nor offset-elbow: its exact self-motion locks q3
    // (issue 27).
    let view = b.self_motion(ee).expect("an exact self-motion");
    assert!(view.exact);
    assert_eq!(view.parameter, "q3 (locked)");
    b.set_self_motion(ee, view.value + 0.05).unwrap();
    let moved = b
        .q()
        .iter()
        .zip(&before)
        .zip(&on_arm)
        .filter(|((a, c), _)| a != c);
    assert!(moved.clone().count() > 0, "the arm moved");
    assert!(
        moved.clone().all(|(_, &arm)| arm),
        "only the chosen arm moved"
    );
    let (dp, dr) = gap(&held, &fk(&b, ee));
    assert!(
        dp < 1e-9 && dr < 1e-9,
        "the hand is held: {dp:e} m, {dr:e} rad"
    );
}

/// Issue 46, item 7: during a drag a self-motion swept over a locked joint (Baxter's arm) is
/// not recomputed at every move (it cost 110-200 ms a frame); it is after the drag. One that
/// the closed form gives at once (the DLR arm's arm angle) follows the drag live.
#[test]
fn a_swept_self_motion_waits_for_the_end_of_a_drag() {
    let mut b = AppState::from_spec("tests/data/urdf_corpus/baxter.urdf").unwrap();
    assert!(b.self_motion(0).is_ok());
    let q = b.q().to_vec();
    let mut moved = q.clone();
    moved[0] += 0.05;
    b.dragging = true;
    b.set_q(&moved).unwrap();
    let t = std::time::Instant::now();
    let during = b.self_motion(0);
    assert!(during.is_err(), "recomputed during the drag");
    assert!(t.elapsed().as_millis() < 20, "{:?}", t.elapsed());
    b.dragging = false;
    let after = b.self_motion(0).expect("after the drag");
    assert!(after.exact);
    let mut d = AppState::from_spec("dlr").unwrap();
    assert!(d.self_motion(0).is_ok());
    let mut q = d.q().to_vec();
    q[0] += 0.05;
    d.dragging = true;
    d.set_q(&q).unwrap();
    assert!(d.self_motion(0).is_ok(), "the closed form follows the drag");
}
