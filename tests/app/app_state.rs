//! The interactive app's state logic (no GUI): sliders, DH editing, IK targets with ghosts,
//! posture selection and lock, unreachable targets, model loading, readouts and the naming of
//! singularities.

use armlab::app::state::{
    AngleUnit, AppState, DhField, EntryError, Level, Quantity, Reach, StateError, TRAIL_CAPACITY,
};
use armlab::kinematics::orientation::{angle_axis_from_rotation, wrap_angle};
use armlab::kinematics::singularity::{Proximity, SingularityKind};
use armlab::kinematics::{JointKind, Pose, Robot};
use nalgebra::{DMatrix, Rotation3, Translation3, Vector3};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

#[path = "app_state/singular.rs"]
mod singular;

const ASW: &str = "anthropomorphic_spherical_wrist";

fn state(spec: &str) -> AppState {
    AppState::from_spec(spec).expect("built-in model")
}

/// Largest joint motion between two configurations: revolute differences wrapped into
/// (-pi, pi] (the physical rotation), prismatic differences as they are.
fn max_step(robot: &Robot, a: &[f64], b: &[f64]) -> f64 {
    (0..robot.dof())
        .map(|k| match robot.dof_joint(k).kind {
            JointKind::Revolute => wrap_angle(a[k] - b[k]).abs(),
            _ => (a[k] - b[k]).abs(),
        })
        .fold(0.0, f64::max)
}

fn pose_gap(a: &Pose, b: &Pose) -> f64 {
    let dp = (a.translation.vector - b.translation.vector).norm();
    dp.max(angle_axis_from_rotation(&(a.rotation.inverse() * b.rotation)).angle)
}

fn fk(s: &AppState, ee: usize) -> Pose {
    s.robot().fk_ee(s.q(), ee).unwrap()
}

fn smallest_sv(robot: &Robot, q: &[f64]) -> f64 {
    let j = robot.jacobian(q, 0).unwrap();
    let m = DMatrix::from_column_slice(6, j.ncols(), j.as_slice());
    m.svd(false, false).singular_values.min()
}

#[test]
fn sliders_clamp_and_convert_units() {
    let mut s = state(ASW);
    assert_eq!(s.joint_quantity(1).unwrap(), Quantity::Angle);
    let v = s.set_joint_display(1, "90").unwrap();
    assert!((v - FRAC_PI_2).abs() < 1e-15 && s.q()[1] == v);
    assert!((s.joint_display(1).unwrap() - 90.0).abs() < 1e-12);
    assert_eq!(s.joint_display_limits(0).unwrap(), [-180.0, 180.0]);
    // Out of range: clamped, with a warning naming the limits.
    let v = s.set_joint_display(2, "400").unwrap();
    assert_eq!(v, PI);
    let m = s.last_message().unwrap();
    assert_eq!(m.level, Level::Warning);
    assert!(
        m.text.contains("400") && m.text.contains("180"),
        "{}",
        m.text
    );
    assert_eq!(s.set_joint(0, -10.0).unwrap(), -PI);
    // Radians, and explicit units whatever the display unit.
    s.set_angle_unit(AngleUnit::Radians);
    assert_eq!(s.set_joint_display(3, "0.5").unwrap(), 0.5);
    assert_eq!(s.set_joint_display(3, "pi/4").unwrap(), FRAC_PI_4);
    assert!((s.set_joint_display(3, "-30deg").unwrap() + 30f64.to_radians()).abs() < 1e-15);
    assert!((s.set_joint_display(3, "45°").unwrap() - FRAC_PI_4).abs() < 1e-15);
    // Invalid entries change nothing.
    let q = s.q().to_vec();
    for (text, nan) in [("abc", false), ("NaN", true), ("inf", true), ("", false)] {
        match s.set_joint_display(3, text) {
            Err(StateError::InvalidJointEntry { dof: 3, reason }) => {
                assert_eq!(matches!(reason, EntryError::NonFinite(_)), nan, "{text}");
            }
            other => panic!("{text}: {other:?}"),
        }
    }
    assert!(s.set_joint(3, f64::NAN).is_err());
    assert!(matches!(
        s.set_joint(6, 0.0),
        Err(StateError::NoSuchDof { index: 6, .. })
    ));
    assert_eq!(s.q(), &q[..]);
    // The target follows the end-effector.
    assert!(pose_gap(&s.target(0).unwrap().world_from_tool, &fk(&s, 0)) < 1e-12);

    // Prismatic joint of the Stanford arm: millimetres, limits [300, 1000] mm.
    let mut s = state("stanford");
    assert_eq!(s.joint_quantity(2).unwrap(), Quantity::Length);
    assert_eq!(s.set_joint_display(2, "500").unwrap(), 0.5);
    assert!((s.joint_display(2).unwrap() - 500.0).abs() < 1e-9);
    assert_eq!(s.joint_display_limits(2).unwrap(), [300.0, 1000.0]);
    assert_eq!(s.set_joint_display(2, "0.7 m").unwrap(), 0.7);
    assert_eq!(s.set_joint_display(2, "2000").unwrap(), 1.0);
    assert_eq!(s.set_joint_display(2, "25 cm").unwrap(), 0.3);
    assert!(s.robot().within_limits(s.q(), 0.0));
}

#[test]
fn dh_edits_move_the_arm_and_invalid_text_is_kept_with_its_reason() {
    let mut s = state(ASW);
    let before = fk(&s, 0);
    // a2 from 500 mm to 600 mm: the arm follows, the target with it.
    s.edit_dh(1, DhField::A, "600").unwrap();
    let after = fk(&s, 0);
    assert!((after.translation.vector - before.translation.vector).norm() > 0.05);
    let expected = Robot::from_dh(
        "check",
        armlab::kinematics::Convention::Standard,
        &s.robot()
            .dh_table()
            .unwrap()
            .1
            .iter()
            .zip(s.robot().limits())
            .map(|(&(k, r, o), [lo, hi])| {
                armlab::kinematics::DhJoint::new(k, r)
                    .offset(o)
                    .limits(lo, hi)
            })
            .collect::<Vec<_>>(),
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    assert_eq!(expected.dh_table().unwrap().1[1].1.a, 0.6);
    assert!(pose_gap(&expected.fk(s.q()).unwrap(), &after) < 1e-12);
    assert!(pose_gap(&s.target(0).unwrap().world_from_tool, &after) < 1e-12);
    // Angles in the display unit or with explicit units.
    s.edit_dh(2, DhField::Alpha, "-90").unwrap();
    s.edit_dh(2, DhField::Alpha, "pi/2").unwrap();
    assert_eq!(s.dh_cell(2, DhField::Alpha).unwrap().text, "pi/2");

    // Invalid text: kept, marked, the robot keeps its last valid shape.
    let robot = s.robot().clone();
    let q = s.q().to_vec();
    for (text, want) in [
        ("0.6.1", EntryError::NotANumber("0.6.1".into())),
        ("NaN", EntryError::NonFinite("NaN".into())),
        ("-inf", EntryError::NonFinite("-inf".into())),
        ("  ", EntryError::Empty),
    ] {
        match s.edit_dh(1, DhField::A, text) {
            Err(StateError::InvalidEntry {
                joint: 1,
                field: DhField::A,
                reason,
            }) => assert_eq!(reason, want),
            other => panic!("{text}: {other:?}"),
        }
        let cell = s.dh_cell(1, DhField::A).unwrap();
        assert_eq!(cell.text, text);
        assert_eq!(cell.error.as_ref(), Some(&want));
        assert_eq!(s.robot(), &robot);
        assert_eq!(s.q(), &q[..]);
        assert!(s.dh_has_errors());
    }
    // A valid edit of another cell of the same joint still applies; the bad cell stays bad.
    s.edit_dh(1, DhField::D, "10").unwrap();
    assert_eq!(s.robot().dh_table().unwrap().1[1].1.d, 0.01);
    assert!(s.dh_cell(1, DhField::A).unwrap().error.is_some());
    s.edit_dh(1, DhField::A, "500").unwrap();
    assert!(!s.dh_has_errors());
    // theta is the variable of a revolute joint.
    assert!(matches!(
        s.edit_dh(0, DhField::Theta, "10"),
        Err(StateError::InvalidEntry {
            reason: EntryError::NotEditable(_),
            ..
        })
    ));
    assert!(!s.dh_cell(0, DhField::Theta).unwrap().editable);
    // Offsets move the arm like q does.
    let p0 = fk(&s, 0);
    s.edit_dh(0, DhField::Offset, "30").unwrap();
    let mut q1 = s.q().to_vec();
    q1[0] += 30f64.to_radians();
    let mut plain = state(ASW);
    plain.edit_dh(1, DhField::D, "10").unwrap();
    assert!(pose_gap(&plain.robot().fk(&q1).unwrap(), &fk(&s, 0)) < 1e-12);
    assert!(pose_gap(&p0, &fk(&s, 0)) > 0.01);
}

#[test]
fn dh_limits_lower_above_upper_are_rejected() {
    let mut s = state("puma560");
    let limits = s.robot().limits();
    let err = s.edit_dh(0, DhField::Lower, "200").unwrap_err();
    match &err {
        StateError::InvalidEntry {
            reason: EntryError::LimitsInverted { lower, upper },
            ..
        } => assert!(
            lower.starts_with("200") && upper.starts_with("160"),
            "{err}"
        ),
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("lower limit"), "{err}");
    assert_eq!(s.robot().limits(), limits);
    // Raising the upper limit makes the pending lower limit valid: both apply, q is clamped in.
    s.edit_dh(0, DhField::Upper, "250").unwrap();
    assert!(!s.dh_has_errors());
    let l = s.robot().limits()[0];
    assert!(
        (l[0] - 200f64.to_radians()).abs() < 1e-12 && (l[1] - 250f64.to_radians()).abs() < 1e-12
    );
    assert!(s.robot().within_limits(s.q(), 0.0));
    // Prismatic limits are in millimetres.
    let mut s = state("stanford");
    assert!(s.edit_dh(2, DhField::Upper, "200").is_err());
    s.edit_dh(2, DhField::Upper, "1200").unwrap();
    assert_eq!(s.robot().limits()[2], [0.3, 1.2]);
}

#[test]
fn model_load_error_keeps_the_previous_model() {
    let mut s = state(ASW);
    s.set_joint(0, 0.3).unwrap();
    let (robot, q) = (s.robot().clone(), s.q().to_vec());
    for spec in [
        "no_such_robot",
        "/definitely/missing/arm.toml",
        "/missing.urdf",
    ] {
        let err = s.load_model(spec).unwrap_err();
        assert!(matches!(err, StateError::Load { .. }), "{err:?}");
        assert_eq!(s.robot(), &robot);
        assert_eq!(s.q(), &q[..]);
        assert_eq!(s.spec(), ASW);
        let m = s.last_message().unwrap();
        assert_eq!(m.level, Level::Error);
        assert!(m.text.contains(spec), "{}", m.text);
    }
    s.load_model("puma560").unwrap();
    assert_eq!(s.robot().name, "Puma 560");
    assert_eq!(s.spec(), "puma560");
    // The Puma's "ready" is a wrist singularity: it opens at the regular pose near it, and the
    // message says why.
    let opening = armlab::kinematics::opening::opening_pose(s.robot());
    assert_eq!(s.q(), &opening.q[..]);
    assert!(s.last_message().unwrap().text.contains("singularity"));
    assert_eq!(s.dh_cells().len(), 6);
    assert!(AppState::from_spec("nope").is_err());
}

#[test]
fn reset_to_named_configurations() {
    let mut s = state(ASW);
    s.reset_to("figure").unwrap();
    assert_eq!(s.q(), s.robot().config("figure").unwrap());
    assert!(pose_gap(&s.target(0).unwrap().world_from_tool, &fk(&s, 0)) < 1e-12);
    let err = s.reset_to("dance").unwrap_err();
    assert!(err.to_string().contains("ready"), "{err}");
}

/// A generic configuration of the anthropomorphic arm with spherical wrist.
const Q_GENERIC: [f64; 6] = [0.4, 0.5, 0.8, 0.3, 0.9, -0.2];

#[test]
fn ghosts_list_every_solution_and_selection_moves_the_arm() {
    let mut s = state(ASW);
    let robot = s.robot().clone();
    let target = robot.fk(&Q_GENERIC).unwrap();
    assert!(s.set_target(0, target).unwrap().is_reached());
    let ghosts = s.ghosts(0);
    assert_eq!(ghosts.len(), 8);
    assert_eq!(ghosts.iter().filter(|g| g.selected).count(), 1);
    assert!(ghosts.iter().all(|g| g.within_limits));
    for (i, g) in ghosts.iter().enumerate() {
        s.select_solution(0, i).unwrap();
        assert_eq!(s.q(), &g.q[..]);
        assert!(pose_gap(&fk(&s, 0), &target) < 1e-9);
        assert_eq!(s.target(0).unwrap().posture.as_ref(), g.posture.posture());
        assert!(s.ghosts(0)[i].selected);
    }
    let label = ghosts[5]
        .posture
        .to_string()
        .replace(", ", "_")
        .to_uppercase();
    s.select_posture(0, &label).unwrap();
    assert_eq!(s.q(), &ghosts[5].q[..]);
    assert!(matches!(
        s.select_posture(0, "elbow sideways"),
        Err(StateError::NoSuchPosture { .. })
    ));
    assert!(matches!(
        s.select_solution(0, 8),
        Err(StateError::NoSuchSolution { count: 8, .. })
    ));

    // The Puma 560's limits exclude some postures: they are greyed and cannot be selected.
    let mut s = state("puma560");
    let q = [0.3, 0.6, -2.0, 0.4, 0.7, 0.2];
    s.set_target(0, s.robot().fk(&q).unwrap()).unwrap();
    let ghosts = s.ghosts(0);
    let out = ghosts
        .iter()
        .position(|g| !g.within_limits)
        .expect("a greyed ghost");
    let before = s.q().to_vec();
    assert!(matches!(
        s.select_solution(0, out),
        Err(StateError::SolutionOutsideLimits { .. })
    ));
    assert_eq!(s.q(), &before[..]);
}

#[test]
fn posture_lock_keeps_the_branch_when_the_target_jumps() {
    let mut s = state(ASW);
    let robot = s.robot().clone();
    s.set_target(0, robot.fk(&Q_GENERIC).unwrap()).unwrap();
    let ghosts = s.ghosts(0);
    // Lock a posture that is not the one the arm would pick by closeness.
    let chosen = ghosts.iter().position(|g| !g.selected).unwrap();
    let label = ghosts[chosen].posture.clone();
    s.select_solution(0, chosen).unwrap();
    s.set_lock(true);
    let far = robot.fk(&[-0.9, 1.1, 0.3, -0.6, 1.3, 0.7]).unwrap();
    assert!(s.set_target(0, far).unwrap().is_reached());
    assert!(pose_gap(&fk(&s, 0), &far) < 1e-9);
    let selected = s.ghosts(0).into_iter().find(|g| g.selected).unwrap();
    assert_eq!(selected.posture, label);
    assert_eq!(s.target(0).unwrap().posture.as_ref(), label.posture());

    // Unlocked, the arm takes the solution closest to where it is.
    s.set_lock(false);
    s.set_target(0, robot.fk(&Q_GENERIC).unwrap()).unwrap();
    let q_before = s.q().to_vec();
    s.set_target(0, far).unwrap();
    let d = |q: &[f64]| armlab::kinematics::ik::solver::joint_distance(&robot, q, &q_before);
    let best = s
        .ghosts(0)
        .iter()
        .map(|g| d(&g.q))
        .fold(f64::INFINITY, f64::min);
    assert!((d(s.q()) - best).abs() < 1e-12);
}

#[test]
fn unreachable_target_freezes_the_arm_with_a_message() {
    let mut s = state(ASW);
    let q = s.q().to_vec();
    let mut far = fk(&s, 0);
    far.translation.vector = Vector3::new(2.0, 0.5, 1.0);
    let reach = s.set_target(0, far).unwrap().clone();
    // Wrist centre = p - d6 z; the arm reaches |p_W| <= a2 + d4 = 1 m.
    let pw = far.translation.vector - far.rotation * Vector3::z() * 0.1;
    match reach {
        Reach::Unreachable { distance } => assert!((distance - (pw.norm() - 1.0)).abs() < 1e-9),
        other => panic!("{other:?}"),
    }
    assert_eq!(s.q(), &q[..]);
    assert!(s.ghosts(0).is_empty());
    let m = s.last_message().unwrap();
    assert_eq!(m.level, Level::Warning);
    assert!(m.text.contains("mm outside the workspace"), "{}", m.text);
    assert!(s.readouts(0).unwrap().p.iter().all(|v| v.is_finite()));
    // A non-finite target is refused outright.
    let mut bad = far;
    bad.translation.vector.x = f64::NAN;
    assert!(matches!(
        s.set_target(0, bad),
        Err(StateError::NonFiniteTarget)
    ));
    // Back inside: reached again.
    let home = s.robot().fk(&Q_GENERIC).unwrap();
    assert!(s.set_target(0, home).unwrap().is_reached());
    assert!(s.last_message().unwrap().text.contains("reached again"));
}

#[test]
fn humanoid_hands_have_independent_targets() {
    let mut s = state("humanoid");
    assert_eq!(s.targets().len(), 2);
    let (q0, left0) = (s.q().to_vec(), fk(&s, 1));
    let mut q_prev = q0.clone();
    for _ in 0..10 {
        let r = s.move_target_by(0, Vector3::new(0.0, 0.004, -0.003), Rotation3::identity());
        assert!(r.unwrap().is_reached());
        assert!(max_step(s.robot(), s.q(), &q_prev) < 0.05);
        q_prev = s.q().to_vec();
    }
    assert!(pose_gap(&fk(&s, 0), &s.target(0).unwrap().world_from_tool) < 1e-8);
    // The torso (q1-q3) and the left arm (q11-q17) are held: the left hand did not move.
    assert_eq!(&s.q()[..3], &q0[..3]);
    assert_eq!(&s.q()[10..], &q0[10..]);
    assert!(pose_gap(&fk(&s, 1), &left0) < 1e-12);
    assert_eq!(s.ghosts(0).len(), 1);
    assert_eq!(s.ghosts(0)[0].posture.to_string(), "numerical");
    // The left hand's own target works the same way and leaves the right hand alone.
    let right = fk(&s, 0);
    let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), 0.05);
    assert!(
        s.move_target_by(1, Vector3::zeros(), turn)
            .unwrap()
            .is_reached()
    );
    assert!(pose_gap(&fk(&s, 0), &right) < 1e-12);
    // Far away: frozen, flagged, how far.
    let q = s.q().to_vec();
    let r = s
        .move_target_by(1, Vector3::new(0.0, 0.0, 3.0), Rotation3::identity())
        .unwrap();
    assert!(
        matches!(r, Reach::NotConverged { distance, .. } if *distance > 1.0),
        "{r:?}"
    );
    assert!(r.message().unwrap().contains("mm"));
    assert_eq!(s.q(), &q[..]);
    // A slider on the torso moves both hands: both targets follow.
    s.set_joint(0, 0.2).unwrap();
    for ee in 0..2 {
        assert!(pose_gap(&s.target(ee).unwrap().world_from_tool, &fk(&s, ee)) < 1e-12);
        assert!(s.target(ee).unwrap().reach.is_reached());
    }
}

#[test]
fn numerical_arm_tracks_a_moving_target() {
    let mut s = state("lwr4");
    let mut q_prev = s.q().to_vec();
    for i in 0..20 {
        let dir = if i < 10 { 1.0 } else { -1.0 };
        let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.01 * dir);
        let r = s
            .move_target_by(0, Vector3::new(0.005 * dir, 0.002, 0.0), turn)
            .unwrap();
        assert!(r.is_reached(), "{r:?}");
        assert!(pose_gap(&fk(&s, 0), &s.target(0).unwrap().world_from_tool) < 1e-8);
        assert!(max_step(s.robot(), s.q(), &q_prev) < 0.1);
        assert!(s.robot().within_limits(s.q(), 1e-12));
        q_prev = s.q().to_vec();
    }
}

#[test]
fn planar_arm_targets_stay_in_the_plane() {
    let mut s = state("planar2");
    let mut t = fk(&s, 0);
    t.translation.vector += Vector3::new(-0.2, 0.1, 0.3);
    t.rotation = Rotation3::from_axis_angle(&Vector3::x_axis(), 0.4) * t.rotation;
    assert!(s.set_target(0, t).unwrap().is_reached());
    let stored = s.target(0).unwrap().world_from_tool;
    assert_eq!(stored.translation.vector.z, 0.0);
    assert!((stored.rotation * Vector3::z() - Vector3::z()).norm() < 1e-12);
    let p = fk(&s, 0).translation.vector;
    assert!((p - stored.translation.vector).norm() < 1e-9);
    assert_eq!(s.ghosts(0).len(), 2);
    // Stretched: one solution ("elbow stretched"), at the singularity.
    s.set_target(0, Pose::translation(2.0, 0.0, 0.0)).unwrap();
    let r = s.readouts(0).unwrap();
    let sing = r.singularity.expect("singular");
    assert_eq!(sing.kinds(), vec![SingularityKind::PlanarElbow]);
    assert_eq!((r.rank, r.task_rank), (1, 2));
    assert!(r.min_sv < 1e-9 && r.manipulability < 1e-9);
    // Yoshikawa's measure of the two-link arm: |a1 a2 sin theta2| (m^2).
    s.set_joint(1, 1.0).unwrap();
    assert!((s.readouts(0).unwrap().manipulability - 1f64.sin()).abs() < 1e-12);
    assert!(matches!(
        s.set_target(0, Pose::translation(2.5, 0.0, 0.0)).unwrap(),
        Reach::Unreachable { distance } if (distance - 0.5).abs() < 1e-12
    ));
}

#[test]
fn readouts_trail_and_toggles() {
    let mut s = state(ASW);
    let r = s.readouts(0).unwrap();
    let t = fk(&s, 0);
    assert_eq!(r.t, t.to_homogeneous());
    assert_eq!(r.p, t.translation.vector);
    assert_eq!(r.rank, 6);
    assert_eq!(r.task_rank, 6);
    assert!(r.singularity.is_none() && r.min_sv > 1e-3 && r.manipulability > 0.0);
    let back = armlab::kinematics::EulerKind::Zyz.to_rotation(&r.phi);
    assert!((back.matrix() - t.rotation.matrix()).amax() < 1e-12);
    s.orientation = armlab::kinematics::EulerKind::Rpy;
    assert_eq!(
        s.readouts(0).unwrap().phi_kind,
        armlab::kinematics::EulerKind::Rpy
    );
    // At the wrist singularity: rank 5 of 6, smallest singular value 0, named warning.
    s.set_joint(4, 0.0).unwrap();
    let r = s.readouts(0).unwrap();
    assert_eq!(r.rank, 5);
    assert!(r.min_sv < 1e-12);
    let w = r.singularity.unwrap();
    assert_eq!(
        (w.proximity, w.kinds()),
        (Proximity::At, vec![SingularityKind::Wrist])
    );
    assert!(s.readouts(3).is_err());
    // The trail records each new end-effector position, and is bounded.
    let n = s.trail(0).unwrap().len();
    s.set_joint(0, 0.1).unwrap();
    assert_eq!(s.trail(0).unwrap().len(), n + 1);
    assert_eq!(
        s.trail(0).unwrap().back().unwrap().p,
        fk(&s, 0).translation.vector
    );
    assert!(!s.trail(0).unwrap().back().unwrap().after_jump);
    // A reset far away is a jump: the trail breaks there instead of drawing a line across.
    s.set_q(&vec![0.0; s.robot().dof()]).unwrap();
    s.set_joint(1, 1.5).unwrap();
    assert!(s.trail(0).unwrap().back().unwrap().after_jump);
    s.set_joint(1, 1.501).unwrap();
    assert!(!s.trail(0).unwrap().back().unwrap().after_jump);
    for i in 0..(TRAIL_CAPACITY + 10) {
        s.set_joint(0, (i % 500) as f64 * 1e-3).unwrap();
    }
    assert_eq!(s.trail(0).unwrap().len(), TRAIL_CAPACITY);
    s.clear_trails();
    assert!(s.trail(0).unwrap().is_empty());
    s.display.ghosts = false;
    assert!(!s.display.ghosts && s.display.grid && !s.display.workspace);
}

/// Ghosts carry the posture class the workspace figures colour them by: the class of the label
/// is the class the classifier gives the ghost's own configuration, and short labels spell the
/// label's parts ("R U N").
#[test]
fn ghosts_are_coloured_by_the_workspace_posture_classes() {
    use armlab::app::state::GhostLabel;
    use armlab::kinematics::ik::SolutionPosture;
    use armlab::kinematics::ik::closed_form::{Elbow, Posture, Shoulder, WristFlip};
    use armlab::workspace::PostureClassifier;
    let mut s = state("puma560");
    s.set_q(&[0.3, 0.5, -1.2, 0.4, 0.8, -0.6]).unwrap();
    let t = fk(&s, 0);
    s.set_target(0, t).unwrap();
    let classifier = PostureClassifier::new(s.robot());
    let ghosts = s.ghosts(0);
    assert_eq!(ghosts.len(), 8);
    for g in &ghosts {
        let class = g.class.expect("a class");
        let by_q = classifier.classify(&g.q, &t);
        assert_eq!(class, by_q, "{}", g.posture);
        let name = &classifier.class_names()[class as usize];
        assert!(
            g.posture.to_string().starts_with(name.as_str()),
            "{} vs {name}",
            g.posture
        );
    }
    // Short labels from the posture's fields, against the letters written here.
    let posture = |shoulder, elbow, wrist| Posture {
        shoulder,
        elbow,
        wrist,
        ..Posture::default()
    };
    let run = posture(
        Some(Shoulder::Right),
        Some(Elbow::Up),
        Some(WristFlip::NoFlip),
    );
    assert_eq!(run.short(), "R U N");
    let ldf = posture(
        Some(Shoulder::Left),
        Some(Elbow::Down),
        Some(WristFlip::Flip),
    );
    assert_eq!(ldf.short(), "L D F");
    assert_eq!(
        posture(None, Some(Elbow::Stretched), Some(WristFlip::Singular)).short(),
        "S !"
    );
    let reversed = Posture {
        reversed: true,
        ..posture(Some(Shoulder::Left), None, Some(WristFlip::Up))
    };
    assert_eq!(reversed.short(), "tL bW+");
    let numbered = Posture {
        branch: Some(3),
        ..posture(None, Some(Elbow::Up), None)
    };
    assert_eq!(numbered.short(), "U branch 3");
    // Labels with no short form stay as they are.
    assert_eq!(
        SolutionPosture::Numerical { converged: true }.short(),
        "numerical"
    );
    assert_eq!(
        GhostLabel::SelfMotion("elbow up".into()).short(),
        "elbow up"
    );
    // A planar arm: elbow up and down.
    let mut s = state("planar2");
    let t = fk(&s, 0);
    s.set_target(0, t).unwrap();
    let classes: Vec<Option<u8>> = s.ghosts(0).iter().map(|g| g.class).collect();
    assert_eq!(classes.len(), 2);
    assert!(classes.iter().all(Option::is_some) && classes[0] != classes[1]);
}

/// "Save": the edited DH table written as URDF and as TOML loads back with the same forward
/// kinematics; a URDF robot loaded in the app has its closed form (from the derived DH table)
/// and refuses to be saved as TOML in words, keeping its state.
#[test]
fn save_as_urdf_or_toml_and_load_back() {
    let dir = std::env::temp_dir().join(format!("armlab-app-save-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut s = state("puma560");
    s.edit_dh(1, DhField::A, "450").expect("a2 = 450 mm");
    let q = vec![0.3, -0.4, 0.5, 0.2, 0.7, -0.1];
    for (k, v) in q.iter().enumerate() {
        s.set_joint(k, *v).unwrap();
    }
    let want = s.robot().fk(&q).unwrap();
    let urdf = dir.join("edited.urdf");
    let toml = dir.join("edited.toml");
    let msg = s.save_model(urdf.to_str().unwrap()).unwrap();
    assert!(msg.contains("saved"), "{msg}");
    s.save_model(toml.to_str().unwrap()).unwrap();
    for path in [&urdf, &toml] {
        let back = AppState::from_spec(path.to_str().unwrap()).unwrap();
        let got = back.robot().fk(&q).unwrap();
        assert!((got.translation.vector - want.translation.vector).norm() < 1e-12);
        assert!((got.rotation.matrix() - want.rotation.matrix()).amax() < 1e-12);
    }
    let mut u = AppState::from_spec(urdf.to_str().unwrap()).unwrap();
    assert!(armlab::kinematics::ik::ClosedForm::detect(u.robot()).is_ok());
    let before = u.q().to_vec();
    let err = u
        .save_model(dir.join("x.toml").to_str().unwrap())
        .unwrap_err();
    assert!(err.contains("save this model as .urdf"), "{err}");
    assert_eq!(u.q(), before.as_slice());
    assert!(u.save_model("  ").is_err());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Messages count solutions from 1, as the list does: choosing the first solution when it is
/// outside the limits says "IK solution 1", not "IK solution 0".
#[test]
fn a_solution_outside_the_limits_is_named_as_the_list_counts() {
    let err = armlab::app::state::StateError::SolutionOutsideLimits {
        index: 0,
        posture: "shoulder right, elbow down".into(),
    };
    assert_eq!(
        err.to_string(),
        "IK solution 1 (\"shoulder right, elbow down\") is outside the joint limits"
    );
}

/// Issue 26: a tree whose arm has a closed form is dragged in closed form: the Jaco 2 with its
/// finger frames (CAD-rounded) lists every posture of the arm and follows the target exactly;
/// the xArm6 with its gripper (no closed form) keeps its gripper joints still while dragged.
#[test]
fn a_tree_whose_arm_has_a_closed_form_is_dragged_in_closed_form() {
    let mut s = state("tests/data/urdf_corpus/kinova_j2s6s200.urdf");
    assert!(s.robot().end_effectors().len() > 1, "a tree");
    let ee = 0;
    assert_eq!(s.robot().end_effectors()[ee].name, "j2s6s200_end_effector");
    let start = s.robot().fk_ee(s.q(), ee).unwrap();
    let moved = Translation3::new(0.0, 0.03, -0.02) * start;
    s.set_target(ee, moved).unwrap();
    let t = &s.targets()[ee];
    let result = t.result.as_ref().expect("the closed-form solutions");
    assert!(
        result.solutions.len() >= 4,
        "every posture listed, not one numerical answer: {}",
        result.solutions.len()
    );
    let now = s.robot().fk_ee(s.q(), ee).unwrap();
    let dp = (now.translation.vector - moved.translation.vector).norm();
    assert!(dp < 1e-10, "the arm follows exactly: {dp:e} m");

    let mut x = state("tests/data/urdf_corpus/xarm6_with_gripper.urdf");
    assert_eq!(x.robot().dof(), 7, "6 arm joints and the gripper's drive");
    let gripper = x.q()[6];
    let start = x.robot().fk_ee(x.q(), 0).unwrap();
    x.set_target(0, Translation3::new(0.0, 0.02, 0.0) * start)
        .unwrap();
    let now = x.robot().fk_ee(x.q(), 0).unwrap();
    assert!(
        (now.translation.vector - start.translation.vector).norm() > 0.01,
        "it moved"
    );
    assert_eq!(x.q()[6], gripper, "the gripper stays");
}

/// Issue 27: an arm whose branches are numbered (the Unitree Z1: axes 2-4 parallel, the general
/// three-parallel family, "elbow up, branch k") is dragged with every solution; under the
/// posture lock its branch is the one that continues from the current q and keeps its number,
/// and the hand follows the target exactly.
#[test]
fn a_general_arm_under_the_posture_lock_keeps_its_branch_by_continuity() {
    let mut s = state("tests/data/urdf_corpus/unitree_z1.urdf");
    let ee = 0;
    s.set_q(&[0.3, 1.0, -0.8, 0.4, 0.6, 0.2, 0.0]).unwrap();
    s.set_lock(true);
    let start = s.robot().fk_ee(s.q(), ee).unwrap();
    let mut prev = s.q().to_vec();
    let mut first_label = None;
    for k in 1..=20 {
        let moved =
            Translation3::new(0.004 * k as f64, -0.003 * k as f64, 0.002 * k as f64) * start;
        s.set_target(ee, moved).unwrap();
        let result = s.targets()[ee]
            .result
            .as_ref()
            .expect("the general solutions");
        assert!(result.solutions.len() >= 2, "every branch listed");
        assert!(result.solutions[0].posture.branch().is_some());
        let now = s.robot().fk_ee(s.q(), ee).unwrap();
        let dp = (now.translation.vector - moved.translation.vector).norm();
        assert!(dp < 1e-10, "step {k}: the hand follows exactly: {dp:e} m");
        let step = max_step(s.robot(), s.q(), &prev);
        assert!(
            step < 0.1,
            "step {k}: the branch continues (largest joint step {step} rad)"
        );
        // The branch keeps its number (the lock's label) while the target moves.
        let label = s.targets()[ee].posture;
        assert!(label.is_some_and(|l| l.branch().is_some()));
        if let Some(first) = &first_label {
            assert_eq!(&label, first, "step {k}: the branch was renumbered");
        }
        first_label.get_or_insert(label);
        prev = s.q().to_vec();
    }
}

/// Issue 46, item 10: a drag through the wrist singularity (q5 from +0.05 to -0.05 rad on the
/// Puma) makes the closest solution another posture: unlocked, the arm takes it and the status
/// bar says so, naming L; dragging on within the posture says nothing more.
#[test]
fn a_posture_replaced_during_a_drag_is_announced_with_the_lock_key() {
    let mut s = state("puma560");
    let robot = s.robot().clone();
    let q = [0.2, -0.6, 0.4, 0.3, 0.05, 0.1];
    s.set_q(&q).unwrap();
    s.set_target(0, robot.fk(&q).unwrap()).unwrap();
    let before = s.target(0).unwrap().posture;
    let said = |s: &AppState| {
        s.messages()
            .iter()
            .filter(|m| m.text.contains("L locks"))
            .count()
    };
    assert_eq!(said(&s), 0);
    // the drag, in small steps across q5 = 0
    for k in 1..=10 {
        let mut p = q;
        p[5] = 0.1 + 0.01 * f64::from(k);
        p[4] = 0.05 - 0.01 * f64::from(k);
        p[3] = 0.3;
        s.set_target(0, robot.fk(&p).unwrap()).unwrap();
    }
    let after = s.target(0).unwrap().posture;
    assert!(
        !before.unwrap().same_label(&after.unwrap()),
        "{before:?} -> {after:?}: the drag did not change the posture"
    );
    assert_eq!(said(&s), 1, "{:?}", s.messages());
    // the same drag with the lock on: no silent change, and no such message
    let mut s = state("puma560");
    s.set_q(&q).unwrap();
    s.set_target(0, robot.fk(&q).unwrap()).unwrap();
    s.set_lock(true);
    for k in 1..=10 {
        let mut p = q;
        p[4] = 0.05 - 0.01 * f64::from(k);
        s.set_target(0, robot.fk(&p).unwrap()).unwrap();
    }
    // locked, the branch continues through the singularity and says so in its own words
    assert_eq!(said(&s), 0);
    let locked = |s: &AppState| {
        s.messages()
            .iter()
            .any(|m| m.text.starts_with("posture lock"))
    };
    assert!(
        before
            .unwrap()
            .same_label(&s.target(0).unwrap().posture.unwrap())
            || locked(&s),
        "{:?}",
        s.messages()
    );
}

/// Issue 46, item 9: every robot description opens at a regular pose, as the built-ins do
/// (the Panda opened at its near-singular zero pose). Checked independently: the Jacobian by
/// finite differences of the tool pose, linear rows over the arm's reach, and its smallest
/// singular value against its largest (above 1e-2, the app's "near" threshold).
#[test]
fn every_robot_description_opens_at_a_regular_pose() {
    let mut bad = Vec::new();
    for entry in std::fs::read_dir("tests/data/urdf_corpus").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "urdf") {
            continue;
        }
        let s = AppState::from_spec(path.to_str().unwrap()).unwrap();
        let robot = s.robot();
        for tool in armlab::kinematics::end_effectors::catalog(robot).tools() {
            let arm = armlab::kinematics::arm::arm_of(robot, tool, s.q()).unwrap();
            let n = arm.robot.dof();
            if n < 6 {
                continue; // a hand or gripper: no six-dimensional task
            }
            let q: Vec<f64> = arm.free.iter().map(|&k| s.q()[k]).collect();
            let reach = arm.robot.longest_chain_length().max(0.1);
            let at = |q: &[f64]| arm.robot.fk(q).unwrap();
            let t0 = at(&q);
            let h = 1e-6;
            let mut jac = nalgebra::DMatrix::<f64>::zeros(6, n);
            for k in 0..n {
                let mut qp = q.clone();
                qp[k] += h;
                let t = at(&qp);
                let dp = (t.translation.vector - t0.translation.vector) / (h * reach);
                let dr = (t.rotation * t0.rotation.inverse()).scaled_axis() / h;
                for r in 0..3 {
                    jac[(r, k)] = dp[r];
                    jac[(r + 3, k)] = dr[r];
                }
            }
            let sv = jac.svd(false, false).singular_values;
            let ratio = sv.min() / sv.max();
            if ratio < 1e-2 {
                let name = &robot.end_effectors()[tool].name;
                bad.push(format!(
                    "{} ({name}): ratio {ratio:.1e} at {q:?}",
                    path.display()
                ));
            }
        }
    }
    assert!(bad.is_empty(), "{bad:#?}");
}
