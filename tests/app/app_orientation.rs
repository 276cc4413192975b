//! The Orientation tab (issue 47) through its own code at 1280x800: composition playback
//! checked against rotations multiplied out here from hand-written elementary matrices, the
//! singular case said in words and drawn, reversing and switching a sequence, a lesson step
//! saved and replayed. (The layout rules, the 16 px floor in projector mode and the clipping
//! checks run on every tab, this one included, in `app_layout.rs`.)

use armlab::app::AppUi;
use armlab::app::state::AppState;
use armlab::app::tabs::ORIENTATION;
use armlab::app::tabs::orientation::Mode;
use armlab::app::tabs::orientation::lab::Rep;
use armlab::kinematics::EulerKind;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use nalgebra::Matrix3;

fn rz(d: f64) -> Matrix3<f64> {
    let (s, c) = d.to_radians().sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}
fn ry(d: f64) -> Matrix3<f64> {
    let (s, c) = d.to_radians().sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}
fn rx(d: f64) -> Matrix3<f64> {
    let (s, c) = d.to_radians().sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

fn harness(projector: bool) -> Harness<'static, AppUi> {
    let mut app = AppUi::new(AppState::from_spec("puma560").unwrap());
    app.tab = ORIENTATION;
    app.layout.projector = projector;
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut AppUi| app.show(ui, None), app);
    h.run();
    h
}

fn turned(h: &Harness<'static, AppUi>) -> Matrix3<f64> {
    *h.state().tabs.orientation.turned().matrix()
}

fn close(a: &Matrix3<f64>, b: &Matrix3<f64>) -> bool {
    (a - b).amax() < 1e-12
}

fn click(h: &mut Harness<'static, AppUi>, label: &str) {
    h.get_by_label(label).click();
    h.run();
}

/// The default sequence (current Rz(30), current Ry(45), fixed Rx(10)) played step by step:
/// each step's frame is the product of the hand-written matrices, post-multiplied for current
/// axes and pre-multiplied for fixed ones; the product is written out in the window.
#[test]
fn composition_plays_step_by_step_with_the_product_written_out() {
    for projector in [false, true] {
        let mut h = harness(projector);
        click(&mut h, "Compose");
        assert_eq!(h.state().tabs.orientation.mode, Mode::Compose);
        click(&mut h, "First");
        assert!(close(&turned(&h), &Matrix3::identity()));
        h.get_by_label("R = I");
        click(&mut h, "Step >");
        assert!(close(&turned(&h), &rz(30.0)));
        h.get_by_label("R = Rz(30°)");
        click(&mut h, "Step >");
        assert!(close(&turned(&h), &(rz(30.0) * ry(45.0))));
        h.get_by_label("R = Rz(30°) Ry(45°)");
        click(&mut h, "Step >");
        let all = rx(10.0) * rz(30.0) * ry(45.0);
        assert!(close(&turned(&h), &all));
        h.get_by_label("R = Rx(10°) Rz(30°) Ry(45°)");
        // the ghosts of the intermediate frames: two, at the partial products
        let picture = h.state().tabs.orientation.picture(None, projector);
        assert_eq!(picture.marks.len(), 2);
        assert!(close(
            picture.marks[1].rotation.matrix(),
            &(rz(30.0) * ry(45.0))
        ));
        click(&mut h, "< Step");
        assert!(close(&turned(&h), &(rz(30.0) * ry(45.0))));
        click(&mut h, "All");
        // Play runs through the steps on its own from the start
        click(&mut h, "Play");
        assert_eq!(h.state().tabs.orientation.composition.shown, 0);
        assert!(h.state().tabs.orientation.composition.playing.is_some());
    }
}

/// Switching current and fixed moves the end; reversing as well brings it back where it was
/// (all about the current frame, R = Rz Ry Rx; switched, all about the fixed frame, Rx Ry Rz;
/// and reversed too, Rz Ry Rx again). A mixed sequence (the default: current Rz(30) Ry(45),
/// fixed Rx(10), R = Rx Rz Ry) reversed and switched ends elsewhere, and the tab says by how
/// much.
#[test]
fn reversing_and_switching_a_sequence_ends_where_it_did() {
    use armlab::kinematics::orientation::{Axis, Step, StepFrame};
    let mut h = harness(false);
    click(&mut h, "Compose");
    let mixed = rx(10.0) * rz(30.0) * ry(45.0);
    assert!(close(&turned(&h), &mixed));
    click(&mut h, "Switch current and fixed");
    click(&mut h, "Reverse the order");
    // [current x10, fixed y45, fixed z30]: Rz Ry Rx
    assert!(close(&turned(&h), &(rz(30.0) * ry(45.0) * rx(10.0))));
    h.get_by_label_contains("Reversed and switched: the frame ends");
    assert!(h.query_by_label_contains("ends where the stated").is_none());
    // all about the current frame
    let c = &mut h.state_mut().tabs.orientation.composition;
    c.steps = [(Axis::Z, 30.0), (Axis::Y, 45.0), (Axis::X, 10.0)]
        .map(|(axis, d)| Step {
            frame: StepFrame::Current,
            axis,
            angle: f64::to_radians(d),
        })
        .to_vec();
    c.before = None;
    c.shown = 3;
    h.run();
    let stated = rz(30.0) * ry(45.0) * rx(10.0);
    assert!(close(&turned(&h), &stated));
    click(&mut h, "Switch current and fixed");
    assert!(close(&turned(&h), &(rx(10.0) * ry(45.0) * rz(30.0))));
    h.get_by_label_contains("Switched: the frame ends");
    click(&mut h, "Reverse the order");
    assert!(close(&turned(&h), &stated));
    h.get_by_label_contains(
        "Reversed and switched: the frame ends where the stated sequence ended",
    );
    click(&mut h, "Switch current and fixed");
    click(&mut h, "Reverse the order");
    assert!(h.state().tabs.orientation.composition.before.is_none());
    assert!(close(&turned(&h), &stated));
}

/// Near and at the ZYZ singularity the tab says which angles are lost, with the determined
/// combination's value, and draws the two axes phi and psi turn about; away from it nothing.
#[test]
fn the_singular_case_is_said_and_drawn() {
    let mut h = harness(false);
    h.state_mut()
        .tabs
        .orientation
        .set_values([30.0, 0.0, 45.0, 0.0]);
    h.run();
    h.get_by_label_contains("only phi + psi is determined: 75.0°");
    let p = h.state().tabs.orientation.picture(None, false);
    assert_eq!(p.axes.len(), 2);
    assert!(
        (p.axes[0].direction - p.axes[1].direction).norm() < 1e-12,
        "they coincide"
    );
    // theta = 5°: near, the axes 5° apart
    h.state_mut()
        .tabs
        .orientation
        .set_values([30.0, 5.0, 45.0, 0.0]);
    h.run();
    h.get_by_label_contains("5.0° from the singular case of ZYZ");
    let p = h.state().tabs.orientation.picture(None, false);
    let cos = p.axes[0].direction.dot(&p.axes[1].direction);
    assert!((cos - 5f64.to_radians().cos()).abs() < 1e-12);
    // RPY at theta = 90°: phi - psi
    h.state_mut()
        .tabs
        .orientation
        .set_rep(Rep::Euler(EulerKind::Rpy));
    h.state_mut()
        .tabs
        .orientation
        .set_values([30.0, 90.0, 45.0, 0.0]);
    h.run();
    h.get_by_label_contains("only phi - psi is determined: -15.0°");
    // away from it: no warning, no axes, and both solutions listed
    h.state_mut()
        .tabs
        .orientation
        .set_rep(Rep::Euler(EulerKind::Zyz));
    h.state_mut()
        .tabs
        .orientation
        .set_values([30.0, 45.0, 60.0, 0.0]);
    h.run();
    assert!(h.query_by_label_contains("singular case").is_none());
    assert!(
        h.state()
            .tabs
            .orientation
            .picture(None, false)
            .axes
            .is_empty()
    );
    h.get_by_label_contains("(30°, 45°, 60°) or (-150°, -45°, -120°)");
    // the other solution turns nothing
    let before = turned(&h);
    click(&mut h, "The other solution");
    let v = h.state().tabs.orientation.values;
    assert!((v[1] + 45.0).abs() < 1e-9, "{v:?}");
    h.state_mut().tabs.orientation.set_values(v);
    assert!(close(&turned(&h), &before));
}

/// Editing one representation changes the matrix, and every other representation follows:
/// a quaternion typed unnormalised is the rotation of its normalised self, an angle-axis pair
/// the matrix of (2.25) written out here, and a zero axis is refused with the old frame kept.
#[test]
fn every_representation_follows_the_one_edited() {
    let mut h = harness(false);
    click(&mut h, "angle-axis");
    h.state_mut()
        .tabs
        .orientation
        .set_values([90.0, 0.0, 0.0, 2.0]);
    h.run();
    assert!(close(&turned(&h), &rz(90.0)));
    h.get_by_label_contains("theta = 90° about r = (0.000000, 0.000000, 1.000000)");
    h.state_mut()
        .tabs
        .orientation
        .set_values([90.0, 0.0, 0.0, 0.0]);
    h.run();
    h.get_by_label_contains("the axis r is zero");
    assert!(close(&turned(&h), &rz(90.0)), "the old frame stays");
    click(&mut h, "quaternion");
    h.state_mut()
        .tabs
        .orientation
        .set_values([2.0, 0.0, 2.0, 0.0]);
    h.run();
    assert!(close(&turned(&h), &ry(90.0)));
}

/// A lesson step saved on the Orientation tab replays its mode, representation, values and
/// sequence in another app.
#[test]
fn an_orientation_lesson_step_replays() {
    use armlab::app::lesson::LessonPlayer;
    let dir = std::env::temp_dir().join(format!("armlab-orientation-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("o.toml");
    let mut live = AppUi::new(AppState::from_spec("puma560").unwrap());
    live.tab = ORIENTATION;
    live.tabs.orientation.mode = Mode::Compose;
    live.tabs.orientation.composition.shown = 1;
    let mut player = LessonPlayer::on(&live.state);
    player.file = file.to_string_lossy().into_owned();
    live.lesson = Some(player);
    live.save_as_lesson().unwrap();
    let mut replay = AppUi::new(AppState::from_spec("puma560").unwrap());
    replay.load(file.to_str().unwrap());
    assert_eq!(replay.tab, ORIENTATION);
    let (a, b) = (&replay.tabs.orientation, &live.tabs.orientation);
    assert_eq!(a.mode, Mode::Compose);
    assert_eq!(a.composition.steps, b.composition.steps);
    assert_eq!(a.composition.shown, 1);
    assert!(close(a.turned().matrix(), &rz(30.0)));
    let _ = std::fs::remove_dir_all(&dir);
}

/// During an exam the tab would compute an orientation sheet's answer: it is closed, and says
/// so.
#[test]
fn the_tab_is_closed_during_an_exam() {
    let mut h = harness(false);
    h.state_mut().state.hidden.exam = true;
    h.run();
    h.get_by_label_contains("closed during an exam");
    assert!(h.query_by_label("Compose").is_none());
}
