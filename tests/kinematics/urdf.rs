//! URDF import: the planar2 URDF equals the built-in planar2, origins use URDF's roll-pitch-yaw,
//! mimic joints become couplings, and bad URDFs give errors naming the file and the joint.

use armlab::kinematics::models::built_in;
use armlab::kinematics::{Drive, JointKind, Robot};
use armlab::urdf::{CONTINUOUS_LIMITS, MimicProblem, UrdfError, load_urdf, parse_urdf};
use nalgebra::{Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

fn asset(name: &str) -> Robot {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/robots")
        .join(name);
    load_urdf(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn joint_id(r: &Robot, name: &str) -> usize {
    r.joints()
        .iter()
        .position(|j| j.name == name)
        .unwrap_or_else(|| panic!("no joint {name}"))
}

#[test]
fn planar2_urdf_equals_built_in() {
    let urdf = asset("planar2.urdf");
    let built = built_in("planar2").expect("planar2");
    assert_eq!(urdf.dof(), 2);
    assert_eq!(urdf.end_effectors().len(), 1);
    assert_eq!(urdf.end_effectors()[0].name, "tool");
    assert_eq!(urdf.limits(), built.limits());
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for _ in 0..200 {
        let q: Vec<f64> = (0..2).map(|_| rng.random_range(-3.2..3.2)).collect();
        let a = urdf.fk(&q).expect("fk").to_homogeneous();
        let b = built.fk(&q).expect("fk").to_homogeneous();
        assert!((a - b).amax() <= 1e-12, "q = {q:?}\n{a}\n{b}");
    }
}

#[test]
fn origin_uses_urdf_roll_pitch_yaw() {
    let text = r#"<robot name="rpy">
      <link name="a"/><link name="b"/>
      <joint name="j" type="continuous">
        <parent link="a"/><child link="b"/>
        <origin xyz="1 2 3" rpy="0.1 0.2 0.3"/>
        <axis xyz="0 0 2"/>
      </joint>
    </robot>"#;
    let r = parse_urdf(text, Path::new("rpy.urdf")).expect("valid URDF");
    assert_eq!(r.limits(), vec![CONTINUOUS_LIMITS]);
    assert_eq!(r.end_effectors()[0].name, "b");
    // URDF: R = Rz(yaw) Ry(pitch) Rx(roll), which is nalgebra's from_euler_angles(r, p, y).
    let rot = Rotation3::from_euler_angles(0.1, 0.2, 0.3);
    for q in [0.0, 0.7, -2.0] {
        let t = r.fk(&[q]).expect("fk");
        let want = rot * Rotation3::from_axis_angle(&Vector3::z_axis(), q);
        assert!((t.rotation.matrix() - want.matrix()).amax() < 1e-14);
        assert!((t.translation.vector - Vector3::new(1.0, 2.0, 3.0)).amax() < 1e-15);
    }
}

#[test]
fn mimic_gripper_fingers_move_symmetrically() {
    let r = asset("mimic_gripper.urdf");
    assert_eq!(r.dof(), 3);
    let names: Vec<&str> = r
        .actuated_joints()
        .iter()
        .map(|&j| r.joints()[j].name.as_str())
        .collect();
    assert_eq!(names, ["shoulder", "elbow", "left_finger_joint"]);
    let left = joint_id(&r, "left_finger_joint");
    let right = &r.joints()[joint_id(&r, "right_finger_joint")];
    assert_eq!(right.kind, JointKind::Prismatic);
    assert_eq!(right.drive, Drive::Coupled(vec![(left, -1.0)]));
    let ees: Vec<&str> = r.end_effectors().iter().map(|e| e.name.as_str()).collect();
    assert_eq!(ees, ["left_finger", "right_finger"]);
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for _ in 0..100 {
        let (q1, q2, s): (f64, f64, f64) = (
            rng.random_range(-3.0..3.0),
            rng.random_range(-2.5..2.5),
            rng.random_range(0.0..0.04),
        );
        let (c12, s12) = ((q1 + q2).cos(), (q1 + q2).sin());
        let palm = Vector3::new(q1.cos() + c12, q1.sin() + s12, 0.0);
        for (ee, sign) in [(0, 1.0), (1, -1.0)] {
            let t = r.fk_ee(&[q1, q2, s], ee).expect("fk");
            // finger = palm + R(q1 + q2) * (0.05, ±s, 0)
            let local = Vector3::new(0.05, sign * s, 0.0);
            let want = palm
                + Vector3::new(
                    c12 * local.x - s12 * local.y,
                    s12 * local.x + c12 * local.y,
                    0.0,
                );
            assert!((t.translation.vector - want).amax() < 1e-12, "ee {ee}");
        }
    }
}

/// Two branches from the base; the first declared joint mimics one in the other branch, with a
/// multiplier and an offset, so it must be moved after its source.
const MIMIC_ACROSS_BRANCHES: &str = r#"<robot name="branches">
  <link name="base"/><link name="a"/><link name="b"/>
  <joint name="follower" type="revolute">
    <parent link="base"/><child link="a"/>
    <origin xyz="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="leader" multiplier="2" offset="0.25"/>
  </joint>
  <joint name="leader" type="revolute">
    <parent link="base"/><child link="b"/>
    <origin xyz="0 1 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>"#;

#[test]
fn mimic_source_is_ordered_first_and_offset_applies() {
    let r = parse_urdf(MIMIC_ACROSS_BRANCHES, Path::new("branches.urdf")).expect("valid");
    assert_eq!(r.dof(), 1);
    assert_eq!(r.joints()[0].name, "leader");
    assert_eq!(r.joints()[1].name, "follower");
    assert_eq!(r.joints()[1].offset, 0.25);
    let ee = r
        .end_effectors()
        .iter()
        .position(|e| e.name == "a")
        .expect("ee a");
    for q in [-0.8, 0.0, 0.3] {
        let t = r.fk_ee(&[q], ee).expect("fk");
        let angle = t.rotation.matrix()[(1, 0)].atan2(t.rotation.matrix()[(0, 0)]);
        assert!((angle - (2.0 * q + 0.25)).abs() < 1e-12, "q = {q}");
    }
}

fn bad(text: &str) -> UrdfError {
    match parse_urdf(text, Path::new("robots/bad.urdf")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => {
            // "... (robots/bad.urdf)", or "robots/bad.urdf:LINE:COLUMN: ..." where the XML
            // itself is cut.
            let text = e.to_string();
            assert!(
                text.ends_with("(robots/bad.urdf)") || text.starts_with("robots/bad.urdf:"),
                "{e}"
            );
            e
        }
    }
}

fn two_links(joint: &str) -> String {
    format!(r#"<robot name="x"><link name="a"/><link name="b"/>{joint}</robot>"#)
}

#[test]
fn bad_urdfs_give_clear_errors() {
    let e = bad(&two_links(
        r#"<joint name="free" type="floating"><parent link="a"/><child link="b"/></joint>"#,
    ));
    assert!(
        matches!(&e, UrdfError::UnsupportedJoint { joint, kind: "floating", .. } if joint == "free"),
        "{e}"
    );
    assert!(
        e.to_string()
            .contains("joint \"free\": type floating is not supported"),
        "{e}"
    );

    // Cut short: the XML error names where the text ends.
    let e = bad(r#"<robot name="x"><link name="a"/><joint name="j" type="revolute">"#);
    assert!(
        matches!(
            e,
            UrdfError::Xml {
                line: 1,
                column: 65,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("not well-formed XML"), "{e}");

    let e = bad(&two_links(
        r#"<joint name="j" type="revolute"><parent link="a"/><child link="c"/></joint>"#,
    ));
    assert!(
        e.to_string()
            .contains("joint \"j\": link \"c\" is not declared"),
        "{e}"
    );

    let e = bad(&two_links(
        r#"<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
           <limit lower="-1" upper="1" effort="1" velocity="1"/>
           <mimic joint="ghost"/></joint>"#,
    ));
    assert!(
        matches!(
            &e,
            UrdfError::Mimic {
                problem: MimicProblem::NoSuchJoint,
                ..
            }
        ),
        "{e}"
    );
    assert!(
        e.to_string().contains("joint \"j\" mimics \"ghost\""),
        "{e}"
    );

    let e = bad(
        r#"<robot name="x"><link name="a"/><link name="b"/><link name="c"/>
        <joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>
        <joint name="m" type="revolute"><parent link="b"/><child link="c"/>
          <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="f"/></joint>
        </robot>"#,
    );
    assert!(
        matches!(
            &e,
            UrdfError::Mimic {
                problem: MimicProblem::NotActuated,
                ..
            }
        ),
        "{e}"
    );

    let e = bad(
        r#"<robot name="x"><link name="a"/><link name="b"/><link name="c"/>
        <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
          <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"#,
    );
    assert!(e.to_string().contains("found [a, c]"), "{e}");

    let e = bad(
        r#"<robot name="x" version="1.2"><link name="a"/><link name="b"/>
        <joint name="slide" type="prismatic"><parent link="a"/><child link="b"/>
          <axis xyz="1 0 0"/><limit effort="1" velocity="1"/></joint></robot>"#,
    );
    assert!(
        matches!(&e, UrdfError::BadLimits { joint, .. } if joint == "slide"),
        "{e}"
    );

    let e = bad(&two_links(
        r#"<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
           <axis xyz="0 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"#,
    ));
    assert!(matches!(e, UrdfError::ZeroAxis { .. }), "{e}");

    let e = bad(r#"<robot name="x"><link name="a"/></robot>"#);
    assert!(matches!(e, UrdfError::NoJoints { .. }), "{e}");
}

#[test]
fn missing_urdf_file_is_reported() {
    let e = load_urdf(Path::new("no/such/robot.urdf")).expect_err("missing");
    assert!(matches!(e, UrdfError::Read { .. }));
    assert!(e.to_string().contains("no/such/robot.urdf"), "{e}");
}

/// TALOS's grippers carry `<mimic>` on fixed joints; RViz and urdf-viz load them, and armlab
/// refused the whole file. Now the mimic is ignored with a warning naming the joint, the joint
/// stays fixed, and the actuated joint it names still drives its own finger.
#[test]
fn a_mimic_on_a_fixed_joint_is_a_warning() {
    let text = r#"<robot name="fixed_mimic">
      <link name="base"/><link name="finger"/><link name="pad"/>
      <joint name="gripper_joint" type="revolute">
        <parent link="base"/><child link="finger"/><axis xyz="0 0 1"/>
        <origin xyz="0 0 0.1"/><limit lower="0" upper="1" effort="1" velocity="1"/>
      </joint>
      <joint name="inner_double_joint" type="fixed">
        <parent link="finger"/><child link="pad"/><origin xyz="0.05 0 0"/>
        <mimic joint="gripper_joint" multiplier="-1" offset="0"/>
      </joint>
    </robot>"#;
    let r = parse_urdf(text, Path::new("fixed_mimic.urdf")).expect("loads");
    assert_eq!(r.dof(), 1);
    let pad = joint_id(&r, "inner_double_joint");
    assert_eq!(r.joints()[pad].kind, JointKind::Fixed);
    let w = r
        .load_warnings
        .iter()
        .find(|w| w.contains("inner_double_joint"))
        .expect("a warning names the joint");
    assert!(w.contains("mimic") && w.contains("gripper_joint"), "{w}");
    // The pad rides on the finger: 0.05 m along the finger's x, turned by q.
    let q = 0.7_f64;
    let frames = r.fk_frames(&[q]).unwrap();
    let p = frames[pad].translation.vector;
    assert!(
        (p - Vector3::new(0.05 * q.cos(), 0.05 * q.sin(), 0.1)).norm() < 1e-12,
        "{p:?}"
    );
}

/// Quirks of real files are read liberally and each named in a warning, never silently: a
/// revolute joint without `<limit>` turns freely (it was frozen at [0, 0]), a continuous joint's
/// limits are ignored, an axis that is not a unit vector is normalised; a zero axis is still an
/// error naming the joint.
#[test]
fn limit_and_axis_quirks_are_warnings_naming_the_joint() {
    let urdf = |axis: &str, j1: &str, j2_type: &str, j2: &str| {
        format!(
            r#"<robot name="q"><link name="base"/><link name="l1"/><link name="l2"/>
            <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
              <axis xyz="{axis}"/>{j1}</joint>
            <joint name="j2" type="{j2_type}"><parent link="l1"/><child link="l2"/>
              <origin xyz="0.1 0 0"/><axis xyz="0 0 1"/>{j2}</joint></robot>"#
        )
    };
    let lim = r#"<limit lower="-1" upper="1" effort="1" velocity="1"/>"#;
    let warn = |r: &Robot, joint: &str, what: &str| {
        let w = r
            .load_warnings
            .iter()
            .find(|w| w.contains(&format!("\"{joint}\"")));
        let w = w.unwrap_or_else(|| panic!("no warning names {joint}: {:?}", r.load_warnings));
        assert!(w.contains(what), "{w}");
    };
    // No <limit> on a revolute joint.
    let r = parse_urdf(&urdf("0 0 1", "", "revolute", lim), Path::new("q.urdf")).unwrap();
    assert_eq!(r.limits()[0], CONTINUOUS_LIMITS);
    warn(&r, "j1", "without a <limit>");
    // A continuous joint with limits.
    let r = parse_urdf(&urdf("0 0 1", lim, "continuous", lim), Path::new("q.urdf")).unwrap();
    assert_eq!(r.limits()[1], CONTINUOUS_LIMITS);
    warn(&r, "j2", "the limits are ignored");
    // An axis of length 2: normalised (the joint turns about z), with a warning.
    let r = parse_urdf(&urdf("0 0 2", lim, "revolute", lim), Path::new("q.urdf")).unwrap();
    warn(&r, "j1", "not a unit vector");
    let t = r.fk(&[0.5, 0.0]).unwrap();
    let p = t.translation.vector;
    assert!((p - Vector3::new(0.1 * 0.5_f64.cos(), 0.1 * 0.5_f64.sin(), 0.0)).norm() < 1e-12);
    // A well-formed file has no warnings; a zero axis is an error naming the joint.
    let r = parse_urdf(&urdf("0 0 1", lim, "revolute", lim), Path::new("q.urdf")).unwrap();
    assert!(r.load_warnings.is_empty(), "{:?}", r.load_warnings);
    let e = parse_urdf(&urdf("0 0 0", lim, "revolute", lim), Path::new("q.urdf")).unwrap_err();
    assert!(e.to_string().contains("\"j1\""), "{e}");
}

/// Issue 46, item 10: a truncated URDF names the line and column where the XML stops, not only
/// urdf-rs's "No elements found".
#[test]
fn a_truncated_urdf_names_its_line_and_column() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/urdf_corpus/ur5_robot.urdf"
    ))
    .unwrap();
    // Cut in the middle of a line, well inside the file.
    let cut = text.len() / 2;
    let cut = (cut..text.len())
        .find(|&i| text.is_char_boundary(i))
        .unwrap();
    let truncated = &text[..cut];
    let lines = truncated.lines().count() as u32;
    let e = armlab::urdf::parse_urdf(truncated, std::path::Path::new("cut.urdf")).unwrap_err();
    let msg = e.to_string();
    let armlab::urdf::UrdfError::Xml { line, column, .. } = e else {
        panic!("not an XML error: {msg}");
    };
    assert!(
        msg.starts_with(&format!("cut.urdf:{line}:{column}: not well-formed XML")),
        "{msg}"
    );
    // The parser stops at the end of what is there (or at the first element left open).
    assert!(
        line >= 1 && line <= lines + 1,
        "line {line} of {lines}: {msg}"
    );
    // A well-formed file that is not URDF keeps urdf-rs's message.
    let e = armlab::urdf::parse_urdf("<robot name=\"r\"><link/></robot>", "x.urdf".as_ref())
        .unwrap_err();
    assert!(!matches!(e, armlab::urdf::UrdfError::Xml { .. }), "{e}");
}
