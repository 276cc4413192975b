//! Issue 26: arms in trees and near-miss geometry.
//!
//! - The arm of an end-effector is the chain to it alone: the Panda with its fingers is a 7-DOF
//!   arm of degree 1 with the exact q7 self-motion (every sample meets the held pose by a forward
//!   kinematics of the file written here); IK on a tree moves only that chain.
//! - End-effectors a user would pick: UR5's default is `tool0`, its `base` frame is an "other
//!   frame"; Baxter has two arms and its head frames are other frames.
//! - A CAD-rounded arm (`rpy = "1.5708"`, a wrist offset of 3e-7 m) gets the closed form of its
//!   ideal structure; every solution meets the target to 1e-12 by a forward kinematics written
//!   here, and a brute-force numerical search finds no solution it missed. Beyond the tolerance
//!   (a 1 mm offset) there is no closed form and the message gives the deviation.

#![allow(clippy::approx_constant)] // the CAD-rounded 1.5708 is the point of these tests

use crate::common;

use armlab::kinematics::end_effectors::catalog;
use armlab::kinematics::ik::solver::{SolverChoice, solve};
use armlab::kinematics::ik::{ClosedForm, Target, numerical::NumericalOptions};
use armlab::redundancy::report::arm_reports;
use nalgebra::{Matrix4, Vector3};
use std::f64::consts::PI;
use std::path::Path;

fn corpus(file: &str) -> armlab::kinematics::Robot {
    let p = Path::new("tests/data/urdf_corpus").join(file);
    armlab::model_file::load_model(p.to_str().unwrap()).unwrap()
}

#[test]
fn the_pandas_arm_excludes_its_fingers() {
    let robot = corpus("panda.urdf");
    assert_eq!(
        robot.dof(),
        8,
        "the file has 7 arm joints and a finger joint"
    );
    let reports = arm_reports(&robot, &[0.0; 8]);
    let tcp = &reports[0];
    assert_eq!(tcp.name, "panda_hand_tcp");
    assert_eq!(tcp.dof, 7);
    assert_eq!(tcp.redundancy_degree, 1);
    assert_eq!(tcp.self_motion, Some("q7"));
    assert!(tcp.dh.is_some(), "{:?}", tcp.dh_reason);
    // IK on the tree: the finger stays where it was, the target is met.
    let q_true = [0.3, 0.5, 0.2, -1.4, 0.4, 1.5, 0.5, 0.02];
    let target = robot.fk_ee(&q_true, 0).unwrap();
    let seed = [0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0, 0.03];
    let (res, _) = solve(
        &robot,
        0,
        &Target::Pose(target),
        Some(&seed),
        SolverChoice::Auto,
        &NumericalOptions::default(),
    )
    .unwrap();
    let s = &res.solutions[0];
    assert_eq!(s.q.len(), 8);
    assert_eq!(s.q[7], 0.03, "the finger is off the arm's chain");
    assert!(s.position_error < 1e-9, "{}", s.position_error);
}

#[test]
fn end_effectors_a_user_would_pick() {
    let ur5 = corpus("ur5_robot.urdf");
    let cat = catalog(&ur5);
    assert_eq!(ur5.end_effectors()[cat.default_ee()].name, "tool0");
    let other: Vec<&str> = cat
        .other
        .iter()
        .map(|&e| ur5.end_effectors()[e].name.as_str())
        .collect();
    assert_eq!(other, ["base"]);
    let baxter = corpus("baxter.urdf");
    // Its 28 meshes of a package that is not here are one warning naming the links, not 28.
    let missing: Vec<&String> = baxter
        .load_warnings
        .iter()
        .filter(|w| w.contains("not found"))
        .collect();
    assert_eq!(missing.len(), 1, "{missing:?}");
    assert!(missing[0].contains("28 meshes not drawn"), "{}", missing[0]);
    let cat = catalog(&baxter);
    let tools: Vec<&str> = cat
        .tools()
        .iter()
        .map(|&e| baxter.end_effectors()[e].name.as_str())
        .collect();
    assert_eq!(tools.len(), 2, "{tools:?}");
    assert!(tools.iter().all(|t| t.ends_with("_gripper")), "{tools:?}");
    for name in ["collision_head_link_1", "head_camera_link", "pedestal"] {
        let e = baxter
            .end_effectors()
            .iter()
            .position(|x| x.name == name)
            .unwrap();
        assert!(cat.other.contains(&e), "{name}");
    }
}

/// A Puma-like 6R arm written as a CAD export would: twists as `1.5708`, and the wrist's
/// middle axis `offset` m off the others.
fn rounded_arm(offset: f64) -> String {
    let j = |name: &str, parent: &str, child: &str, xyz: [f64; 3], rpy: [f64; 3]| {
        format!(
            r#"<joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>
<origin xyz="{} {} {}" rpy="{} {} {}"/><axis xyz="0 0 1"/>
<limit lower="-6.2831853" upper="6.2831853" effort="1" velocity="1"/></joint>
"#,
            xyz[0], xyz[1], xyz[2], rpy[0], rpy[1], rpy[2]
        )
    };
    let mut s = String::from(r#"<robot name="rounded">"#);
    for l in ["base", "l1", "l2", "l3", "l4", "l5", "l6", "tool"] {
        s += &format!(r#"<link name="{l}"/>"#);
    }
    s += &j("j1", "base", "l1", [0.0, 0.0, 0.5], [0.0, 0.0, 0.0]);
    s += &j("j2", "l1", "l2", [0.0, 0.0, 0.0], [1.5708, 0.0, 0.0]);
    s += &j("j3", "l2", "l3", [0.4, 0.0, 0.0], [0.0, 0.0, 0.0]);
    s += &j("j4", "l3", "l4", [0.03, 0.4, 0.0], [-1.5708, 0.0, 0.0]);
    s += &j("j5", "l4", "l5", [offset, 0.0, 0.0], [1.5708, 0.0, 0.0]);
    s += &j("j6", "l5", "l6", [0.0, 0.0, 0.0], [-1.5708, 0.0, 0.0]);
    s += r#"<joint name="flange" type="fixed"><parent link="l6"/><child link="tool"/>
<origin xyz="0 0 0.1" rpy="0 0 0"/></joint></robot>"#;
    s
}

/// A URDF chain's forward kinematics, written here: for each joint its origin (xyz, then
/// R = Rz(y) Ry(p) Rx(r)) then its rotation about z by q; then the fixed `tail` origins.
type Origin = ([f64; 3], [f64; 3]);
fn fk_chain(origins: &[Origin], q: &[f64], tail: &[Origin]) -> Matrix4<f64> {
    let rx = |a: f64| {
        let (s, c) = a.sin_cos();
        Matrix4::new(1., 0., 0., 0., 0., c, -s, 0., 0., s, c, 0., 0., 0., 0., 1.)
    };
    let ry = |a: f64| {
        let (s, c) = a.sin_cos();
        Matrix4::new(c, 0., s, 0., 0., 1., 0., 0., -s, 0., c, 0., 0., 0., 0., 1.)
    };
    let rz = |a: f64| {
        let (s, c) = a.sin_cos();
        Matrix4::new(c, -s, 0., 0., s, c, 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.)
    };
    let origin = |(xyz, rpy): &Origin| {
        Matrix4::new_translation(&Vector3::new(xyz[0], xyz[1], xyz[2]))
            * rz(rpy[2])
            * ry(rpy[1])
            * rx(rpy[0])
    };
    let mut t: Matrix4<f64> = Matrix4::identity();
    for (o, &v) in origins.iter().zip(q) {
        t = t * origin(o) * rz(v);
    }
    for o in tail {
        t *= origin(o);
    }
    t
}

/// The rounded arm's forward kinematics ([`rounded_arm`]'s numbers).
fn fk_here(offset: f64, q: &[f64]) -> Matrix4<f64> {
    let origins = [
        ([0.0, 0.0, 0.5], [0.0, 0.0, 0.0]),
        ([0.0, 0.0, 0.0], [1.5708, 0.0, 0.0]),
        ([0.4, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ([0.03, 0.4, 0.0], [-1.5708, 0.0, 0.0]),
        ([offset, 0.0, 0.0], [1.5708, 0.0, 0.0]),
        ([0.0, 0.0, 0.0], [-1.5708, 0.0, 0.0]),
    ];
    fk_chain(&origins, q, &[([0.0, 0.0, 0.1], [0.0; 3])])
}

/// `panda.urdf`'s chain to `panda_hand_tcp`, as the file writes it.
fn fk_panda(q: &[f64]) -> Matrix4<f64> {
    use std::f64::consts::FRAC_PI_2 as H;
    let origins = [
        ([0.0, 0.0, 0.333], [0.0, 0.0, 0.0]),
        ([0.0, 0.0, 0.0], [-H, 0.0, 0.0]),
        ([0.0, -0.316, 0.0], [H, 0.0, 0.0]),
        ([0.0825, 0.0, 0.0], [H, 0.0, 0.0]),
        ([-0.0825, 0.384, 0.0], [-H, 0.0, 0.0]),
        ([0.0, 0.0, 0.0], [H, 0.0, 0.0]),
        ([0.088, 0.0, 0.0], [H, 0.0, 0.0]),
    ];
    let tail = [
        ([0.0, 0.0, 0.107], [0.0; 3]),
        ([0.0; 3], [0.0, 0.0, -PI / 4.0]),
        ([0.0, 0.0, 0.1034], [0.0; 3]),
    ];
    fk_chain(&origins, q, &tail)
}

#[test]
fn the_urdf_pandas_self_motion_is_the_exact_q7_one() {
    let robot = corpus("panda.urdf");
    let arm = armlab::kinematics::arm::arm_of(&robot, 0, &[0.0; 8]).unwrap();
    let q_true = [0.3, 0.5, 0.2, -1.4, 0.4, 1.5, 0.5];
    let m = fk_panda(&q_true);
    let armlab_m = arm.robot.fk(&q_true).unwrap().to_homogeneous();
    assert!((armlab_m - m).amax() < 1e-14, "{}", (armlab_m - m).amax());
    let pose = armlab::kinematics::pose::pose_from_matrix(&m).unwrap();
    let motion = armlab::redundancy::sampler::sample_self_motion(&arm.robot, 0, &pose, 90).unwrap();
    assert!(motion.exact);
    assert_eq!(motion.parameter, "q7");
    let mut checked = 0;
    for (q7, sols) in &motion.samples {
        for s in sols {
            assert!((s.q[6] - q7).abs() < 1e-12, "q7 is the parameter");
            let e = (fk_panda(&s.q) - m).amax();
            assert!(e < 1e-9, "{} at q7 = {q7}: {e:e}", s.name);
            checked += 1;
        }
    }
    assert!(checked > 90, "{checked} solutions along the self-motion");
}

fn load_text(text: &str) -> armlab::kinematics::Robot {
    armlab::urdf::parse_urdf(text, Path::new("rounded.urdf")).unwrap()
}

#[test]
fn a_cad_rounded_arm_is_solved_in_closed_form_and_polished_to_1e_12() {
    let offset = 3e-7;
    let robot = load_text(&rounded_arm(offset));
    let cf = ClosedForm::detect(&robot).expect("a near miss has a closed form");
    let dev = cf.near_miss().expect("it is a near miss");
    assert!(dev.angle > 1e-6 && dev.angle < 1e-5, "{dev:?}");
    assert!(cf.describe().contains("within"), "{}", cf.describe());
    let q_true = [0.4, -0.7, 0.9, 0.5, 1.1, -0.3];
    let m = fk_here(offset, &q_true);
    // Our FK and armlab's agree (the URDF is read as written).
    let t = robot.fk(&q_true).unwrap().to_homogeneous();
    assert!((t - m).amax() < 1e-14, "{}", (t - m).amax());
    let target = Target::Pose(armlab::kinematics::pose::pose_from_matrix(&m).unwrap());
    let opts = NumericalOptions::default();
    let (res, used) = solve(&robot, 0, &target, None, SolverChoice::Auto, &opts).unwrap();
    assert!(used.to_string().contains("closed form"), "{used}");
    assert_eq!(
        res.solutions.len(),
        8,
        "all eight postures of a Puma-like arm"
    );
    for s in &res.solutions {
        let e = (fk_here(offset, &s.q) - m).amax();
        assert!(e < 1e-12, "{}: {e:e}", s.posture);
    }
    // Brute force: numerical IK from 60 spread seeds finds nothing the closed form missed.
    let wrap = |a: f64| (a + PI).rem_euclid(2.0 * PI) - PI;
    for k in 0..60 {
        let seed: Vec<f64> = (0..6)
            .map(|i| ((k * 7 + i * 13) % 29) as f64 / 29.0 * 2.0 * PI - PI)
            .collect();
        let rep =
            armlab::kinematics::ik::numerical::solve(&robot, 0, &target, &seed, &opts).unwrap();
        if !rep.converged {
            continue;
        }
        let found = res.solutions.iter().any(|s| {
            s.q.iter()
                .zip(&rep.q)
                .all(|(a, b)| wrap(a - b).abs() < 1e-6)
        });
        assert!(
            found,
            "seed {k}: {:?} is not among the closed-form solutions",
            rep.q
        );
    }
}

#[test]
fn beyond_the_tolerance_there_is_no_named_family_and_the_message_gives_the_deviation() {
    let robot = load_text(&rounded_arm(1e-3));
    // No named family (the general six-revolute elimination solves it), and it says why.
    let cf = ClosedForm::detect(&robot).unwrap();
    assert!(cf.near_miss().is_none());
    let why = cf.not_named().unwrap();
    assert!(why.contains("0.001"), "{why}");
}

/// TALOS-like: a wrist F/T sensor's `*_tool_link` carrying a gripper whose finger parts hang by
/// fixed joints (their mimics ignored) or move; the tool is the `tool` link, never a fingertip or
/// the gripper's motor link, and the file's xacro calls left in comments are no obstacle.
#[test]
fn the_tool_is_not_a_part_of_the_gripper() {
    let text = r#"<robot name="wristy">
      <!-- <xacro:gripper_virtual_transmission name="g"/> -->
      <link name="base"/><link name="l1"/><link name="l2"/><link name="wrist_ft_tool_link"/>
      <link name="gripper_base_link"/><link name="gripper_motor_link"/>
      <link name="gripper_fingertip_1_link"/><link name="gripper_fingertip_2_link"/>
      <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
        <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
        <origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="ft" type="fixed"><parent link="l2"/><child link="wrist_ft_tool_link"/>
        <origin xyz="0.2 0 0"/></joint>
      <joint name="gb" type="fixed"><parent link="wrist_ft_tool_link"/>
        <child link="gripper_base_link"/><origin xyz="0.05 0 0"/></joint>
      <joint name="gm" type="revolute"><parent link="gripper_base_link"/>
        <child link="gripper_motor_link"/><axis xyz="1 0 0"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="f1" type="fixed"><parent link="gripper_base_link"/>
        <child link="gripper_fingertip_1_link"/><mimic joint="gm"/></joint>
      <joint name="f2" type="fixed"><parent link="gripper_motor_link"/>
        <child link="gripper_fingertip_2_link"/></joint>
    </robot>"#;
    let robot = load_text(text);
    let cat = catalog(&robot);
    let name = |e: usize| robot.end_effectors()[e].name.as_str();
    assert_eq!(name(cat.default_ee()), "wrist_ft_tool_link");
    assert_eq!(cat.arms.len(), 1, "the fingers join the arm");
    assert_eq!(cat.arms[0].dof, 2);
}

/// The Kinova Gen3 lite's URDF chain written out here: each joint's `<origin xyz rpy>` as in the
/// file (rpy = Rz(y) Ry(p) Rx(r)), then Rz(q) about its axis z; the default end-effector is the
/// link END_EFFECTOR, J5's child.
fn fk_gen3_lite(q: &[f64]) -> Matrix4<f64> {
    let origins: [([f64; 3], [f64; 3]); 6] = [
        ([0.0, 0.0, 0.12825], [0.0, 0.0, 0.0]),
        ([0.0, -0.03, 0.115], [1.5708, 0.0, 0.0]),
        ([0.0, 0.28, 0.0], [-3.1416, 0.0, 0.0]),
        ([0.0, -0.14, 0.02], [1.5708, 0.0, 0.0]),
        ([0.0285, 0.0, 0.105], [0.0, 1.5708, 0.0]),
        ([-0.105, 0.0, 0.0285], [0.0, -1.5708, 0.0]),
    ];
    let frame = |xyz: [f64; 3], rpy: [f64; 3]| {
        let r = nalgebra::Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]);
        nalgebra::Isometry3::from_parts(
            nalgebra::Translation3::new(xyz[0], xyz[1], xyz[2]),
            nalgebra::UnitQuaternion::from_rotation_matrix(&r),
        )
        .to_homogeneous()
    };
    let mut t = Matrix4::<f64>::identity();
    for (k, (xyz, rpy)) in origins.iter().enumerate() {
        t *= frame(*xyz, *rpy) * frame([0.0; 3], [0.0, 0.0, q[k]]);
    }
    t
}

/// Regression: the Gen3 lite's axes 2 and 3 are 3.7e-6 rad from parallel (rpy = "-3.1416"), so
/// its exact chain has no DH table (the common normal 38 km away) and it got no closed form at
/// all. The elimination now runs on its ideal structure and every solution is polished on the
/// exact model: each meets the pose to 1e-12 by the forward kinematics written here, the pose's
/// own q is among them, and a Newton search over all six joints finds nothing else.
#[test]
fn the_gen3_lites_rounded_axes_get_all_solutions_polished_on_the_exact_model() {
    use common::closed_form::{newton_on, pose_from_matrix};
    use rand::{Rng, SeedableRng};
    let robot = corpus("kinova_gen3_lite.urdf");
    let opts = NumericalOptions::default();
    let wrap = |a: f64| (a + PI).rem_euclid(2.0 * PI) - PI;
    let same =
        |a: &[f64], b: &[f64], tol: f64| a.iter().zip(b).all(|(x, y)| wrap(x - y).abs() < tol);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let mut total = 0;
    for _ in 0..20 {
        let q: Vec<f64> = (0..6).map(|_| rng.random_range(-2.5..2.5)).collect();
        // Our FK and armlab's agree (the URDF is read as written).
        let m = fk_gen3_lite(&q);
        let d = (robot.fk(&q).unwrap().to_homogeneous() - m).amax();
        assert!(
            d < 1e-14,
            "{d:e} {:?}",
            robot
                .end_effectors()
                .iter()
                .map(|e| &e.name)
                .collect::<Vec<_>>()
        );
        let t = pose_from_matrix(&m).unwrap();
        let (res, used) =
            solve(&robot, 0, &Target::Pose(t), None, SolverChoice::Auto, &opts).unwrap();
        assert!(used.to_string().contains("closed form"), "{used}");
        assert!(res.solutions.len() <= 16);
        total += res.solutions.len();
        for s in &res.solutions {
            let e = (fk_gen3_lite(&s.q) - m).amax();
            assert!(e < 1e-12, "{}: {e:e}", s.posture);
        }
        assert!(
            res.solutions.iter().any(|s| same(&s.q, &q, 1e-7)),
            "{q:?} missing"
        );
        for _ in 0..100 {
            let start: Vec<f64> = (0..6).map(|_| rng.random_range(-PI..PI)).collect();
            if let Some(found) = newton_on(fk_gen3_lite, &t, start) {
                assert!(
                    res.solutions.iter().any(|s| same(&s.q, &found, 1e-6)),
                    "Newton found {found:?}"
                );
            }
        }
    }
    assert!(total >= 40, "{total} solutions over 20 poses");
}

/// A WidowX-like arm written here: six revolute joints (a spherical wrist), `ee_gripper_link`,
/// two prismatic fingers limited to [0.015, 0.037] m, and sensor frames: a wrist camera, a
/// force-torque frame, a status LED, a depth camera's optical frame.
const WIDOWX_LIKE: &str = r#"<robot name="widowx_like">
  <link name="base_link"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l4"/>
  <link name="l5"/><link name="l6"/><link name="ee_gripper_link"/><link name="left_finger_link"/>
  <link name="right_finger_link"/><link name="wrist_cam_link"/><link name="wrist_ft_frame"/>
  <link name="status_led_link"/><link name="d435_rgb_optical_frame"/>
  <joint name="waist" type="revolute"><parent link="base_link"/><child link="l1"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-1.9" upper="1.9" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.05 0 0.25"/><axis xyz="0 1 0"/><limit lower="-2.1" upper="1.6" effort="1" velocity="1"/></joint>
  <joint name="forearm_roll" type="revolute"><parent link="l3"/><child link="l4"/>
    <origin xyz="0.1 0 0"/><axis xyz="1 0 0"/><limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint>
  <joint name="wrist_angle" type="revolute"><parent link="l4"/><child link="l5"/>
    <origin xyz="0.15 0 0"/><axis xyz="0 1 0"/><limit lower="-1.7" upper="2.1" effort="1" velocity="1"/></joint>
  <joint name="wrist_rotate" type="revolute"><parent link="l5"/><child link="l6"/>
    <origin xyz="0 0 0"/><axis xyz="1 0 0"/><limit lower="-3.1" upper="3.1" effort="1" velocity="1"/></joint>
  <joint name="ee" type="fixed"><parent link="l6"/><child link="ee_gripper_link"/><origin xyz="0.09 0 0"/></joint>
  <joint name="left_finger" type="prismatic"><parent link="ee_gripper_link"/><child link="left_finger_link"/>
    <axis xyz="0 1 0"/><limit lower="0.015" upper="0.037" effort="1" velocity="1"/></joint>
  <joint name="right_finger" type="prismatic"><parent link="ee_gripper_link"/><child link="right_finger_link"/>
    <axis xyz="0 -1 0"/><limit lower="0.015" upper="0.037" effort="1" velocity="1"/></joint>
  <joint name="cam" type="fixed"><parent link="l5"/><child link="wrist_cam_link"/><origin xyz="0.02 0 0.04"/></joint>
  <joint name="ft" type="fixed"><parent link="l6"/><child link="wrist_ft_frame"/><origin xyz="0.01 0 0"/></joint>
  <joint name="led" type="fixed"><parent link="l3"/><child link="status_led_link"/><origin xyz="0 0 0.03"/></joint>
  <joint name="d435" type="fixed"><parent link="l2"/><child link="d435_rgb_optical_frame"/><origin xyz="0 0 0.1"/></joint>
</robot>"#;

/// Issue 46, item 11: real robots' frames. The sensor frames are "other frames", not tools; the
/// default configuration is within every limit (the fingers at 0.015 m, not 0); and a joint off
/// the arm's chain never makes the arm's IK solution infeasible: the flag is checked against the
/// limits of the file, read here joint by joint.
#[test]
fn sensor_frames_fingers_and_limits_of_a_real_robot_s_frames() {
    let robot = load_text(WIDOWX_LIKE);
    let cat = catalog(&robot);
    let name = |e: usize| robot.end_effectors()[e].name.clone();
    assert_eq!(name(cat.default_ee()), "ee_gripper_link");
    let other: Vec<String> = cat.other.iter().map(|&e| name(e)).collect();
    for sensor in [
        "wrist_cam_link",
        "wrist_ft_frame",
        "status_led_link",
        "d435_rgb_optical_frame",
    ] {
        assert!(
            other.iter().any(|o| o == sensor),
            "{sensor} not among {other:?}"
        );
        assert!(
            !cat.tools().iter().any(|&t| name(t) == sensor),
            "{sensor} offered as a tool"
        );
    }
    // The joint limits as the file states them, by joint name (q follows the file's order).
    let limits: Vec<(&str, f64, f64)> = vec![
        ("waist", -3.1, 3.1),
        ("shoulder", -1.9, 1.9),
        ("elbow", -2.1, 1.6),
        ("forearm_roll", -3.1, 3.1),
        ("wrist_angle", -1.7, 2.1),
        ("wrist_rotate", -3.1, 3.1),
        ("left_finger", 0.015, 0.037),
        ("right_finger", 0.015, 0.037),
    ];
    assert_eq!(robot.dof(), limits.len());
    let ready = robot.ready_or_zero();
    for (k, (joint, lo, hi)) in limits.iter().enumerate() {
        assert!(
            ready[k] >= *lo && ready[k] <= *hi,
            "{joint} starts at {}",
            ready[k]
        );
    }
    assert_eq!(&ready[6..], &[0.015, 0.015]);
    assert!(robot.within_limits(&ready, 0.0));
    // IK of poses the arm reaches within its limits: every solution whose six arm joints are
    // inside their limits is flagged feasible, whatever the fingers hold.
    let ee = cat.default_ee();
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(46);
    let mut feasible = 0;
    for _ in 0..20 {
        let mut q = ready.clone();
        for (k, (_, lo, hi)) in limits.iter().take(6).enumerate() {
            q[k] = rng.random_range(lo * 0.9..hi * 0.9);
        }
        let t = robot.fk_ee(&q, ee).unwrap();
        let (result, _) = solve(
            &robot,
            ee,
            &Target::Pose(t),
            None,
            SolverChoice::Auto,
            &NumericalOptions::default(),
        )
        .unwrap();
        assert!(!result.solutions.is_empty());
        for s in &result.solutions {
            let arm_inside = limits
                .iter()
                .take(6)
                .enumerate()
                .all(|(k, (_, lo, hi))| s.q[k] >= lo - 1e-9 && s.q[k] <= hi + 1e-9);
            assert_eq!(s.within_limits, arm_inside, "{:?} {}", s.q, s.posture);
            feasible += usize::from(arm_inside);
        }
    }
    assert!(feasible >= 20, "{feasible} feasible solutions in 20 poses");
}
