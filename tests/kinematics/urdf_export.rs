//! URDF from DH and DH from URDF (issue: URDF robots as first-class citizens): every built-in
//! written as URDF and read back has the same forward kinematics; the DH table derived from the
//! read-back URDF (both conventions) has the same forward kinematics again and the same
//! closed-form family; random chains with skew, parallel and intersecting axes and prismatic
//! joints get a table whose FK matches to 1e-12; trees and mimic joints are refused in words.

use armlab::kinematics::dh_derive::{NoDhTable, derive_dh};
use armlab::kinematics::ik::closed_form::ClosedForm;
use armlab::kinematics::models::{BUILT_INS, built_in};
use armlab::kinematics::{
    Convention, Drive, EndEffector, Joint, JointGeometry, JointKind, Pose, Robot,
};
use armlab::urdf::{UrdfExportError, parse_urdf, to_urdf};
use nalgebra::{Unit, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

fn random_q(r: &Robot, rng: &mut ChaCha8Rng) -> Vec<f64> {
    (0..r.dof())
        .map(|k| {
            let [lo, hi] = r.sampling_range(k);
            rng.random_range(lo..=hi)
        })
        .collect()
}

/// Position error (m) and the largest element of the rotation matrices' difference.
fn gap(a: &Pose, b: &Pose) -> (f64, f64) {
    (
        (a.translation.vector - b.translation.vector).norm(),
        (a.rotation.matrix() - b.rotation.matrix()).amax(),
    )
}

fn assert_same_fk(a: &Robot, ea: usize, b: &Robot, eb: usize, rng: &mut ChaCha8Rng, what: &str) {
    assert_eq!(a.dof(), b.dof(), "{what}");
    for _ in 0..200 {
        let q = random_q(a, rng);
        let (dp, dr) = gap(&a.fk_ee(&q, ea).unwrap(), &b.fk_ee(&q, eb).unwrap());
        assert!(
            dp < 1e-12 && dr < 1e-12,
            "{what}: {dp:e} m, {dr:e} rad at {q:?}"
        );
    }
}

#[test]
fn every_built_in_round_trips_through_urdf_and_its_derived_dh_table() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let (mut written, mut closed_forms) = (0, 0);
    for b in BUILT_INS {
        let robot = (b.build)();
        let text = match to_urdf(&robot) {
            Ok(t) => t,
            Err(e @ UrdfExportError::NotExpressible { .. }) => {
                assert!(
                    matches!(b.name, "parallelogram" | "slider_chain" | "humanoid"),
                    "{}: {e}",
                    b.name
                );
                continue;
            }
            Err(e) => panic!("{}: {e}", b.name),
        };
        let back = parse_urdf(&text, Path::new("round-trip.urdf"))
            .unwrap_or_else(|e| panic!("{}: {e}\n{text}", b.name));
        for (i, e) in robot.end_effectors().iter().enumerate() {
            let k = back
                .end_effectors()
                .iter()
                .position(|x| x.name == e.name)
                .unwrap_or_else(|| panic!("{}: no end-effector {}", b.name, e.name));
            assert_same_fk(&robot, i, &back, k, &mut rng, b.name);
        }
        for k in 0..robot.dof() {
            let (a, c) = (robot.dof_joint(k), back.dof_joint(k));
            assert_eq!(a.name, c.name, "{}", b.name);
            if a.limits.iter().all(|v| v.is_finite()) {
                assert_eq!(a.limits, c.limits, "{} {}", b.name, a.name);
            }
        }
        // The DH table derived from the URDF's origins and axes, both conventions.
        if back.end_effectors().len() == 1 {
            for conv in [Convention::Standard, Convention::Modified] {
                let d = derive_dh(&back, 0, conv).unwrap_or_else(|e| panic!("{}: {e}", b.name));
                let dh = d.robot(b.name).unwrap();
                assert_same_fk(&robot, 0, &dh, 0, &mut rng, b.name);
            }
            let family = |r: &Robot| ClosedForm::detect(r).ok().map(|c| *c.family());
            assert_eq!(family(&robot), family(&back), "{}", b.name);
            closed_forms += usize::from(family(&back).is_some());
        }
        written += 1;
    }
    assert_eq!(written, BUILT_INS.len() - 3);
    // The URDF Puma, Stanford arm, SCARA, ... get their closed form from the derived table.
    assert!(closed_forms >= 10, "{closed_forms}");
}

/// A serial chain of URDF-style joints with random origins and axes: skew, and some exactly
/// parallel or intersecting with the previous axis, some prismatic, a fixed joint between.
fn random_chain(rng: &mut ChaCha8Rng, n: usize) -> Robot {
    let mut joints = Vec::new();
    let mut prev_axis = Vector3::z();
    for i in 0..n {
        let case = rng.random_range(0..4);
        let axis = match case {
            0 => prev_axis,
            _ => Vector3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize(),
        };
        let xyz = if case == 1 {
            Vector3::zeros()
        } else {
            Vector3::new(
                rng.random_range(-0.3..0.3),
                rng.random_range(-0.3..0.3),
                rng.random_range(-0.3..0.3),
            )
        };
        let rot = nalgebra::Rotation3::from_euler_angles(
            rng.random_range(-3.0..3.0),
            rng.random_range(-1.5..1.5),
            rng.random_range(-3.0..3.0),
        );
        let kind = if rng.random_bool(0.25) {
            JointKind::Prismatic
        } else {
            JointKind::Revolute
        };
        joints.push(Joint {
            name: format!("j{i}"),
            kind,
            parent: i.checked_sub(1),
            pre: Pose::identity(),
            geometry: JointGeometry::Origin {
                parent_from_joint: Pose::from_parts(nalgebra::Translation3::from(xyz), rot),
                axis: Unit::new_normalize(axis),
            },
            offset: 0.0,
            drive: Drive::Actuated(i),
            limits: [-1.0, 1.0],
        });
        prev_axis = axis;
    }
    let ee = EndEffector {
        name: "tool".into(),
        parent: n - 1,
        tool: Pose::from_parts(
            nalgebra::Translation3::new(0.1, -0.05, 0.2),
            nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 1.1),
        ),
    };
    let base = Pose::from_parts(
        nalgebra::Translation3::new(0.2, 0.1, -0.3),
        nalgebra::Rotation3::from_euler_angles(-0.4, 0.2, 0.9),
    );
    Robot::new("random", base, joints, vec![ee]).unwrap()
}

#[test]
fn random_chains_get_an_equivalent_dh_table() {
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    for trial in 0..300 {
        let n = rng.random_range(1..=7);
        let chain = random_chain(&mut rng, n);
        for conv in [Convention::Standard, Convention::Modified] {
            let d = derive_dh(&chain, 0, conv).unwrap_or_else(|e| panic!("trial {trial}: {e}"));
            assert_eq!(d.joints.len(), n);
            let dh = d.robot("dh").unwrap();
            assert!(dh.dh_table().is_some());
            assert_same_fk(&chain, 0, &dh, 0, &mut rng, &format!("trial {trial}"));
        }
    }
}

#[test]
fn trees_and_mimic_joints_have_no_dh_table_and_say_why() {
    let humanoid = built_in("humanoid").unwrap();
    let err = derive_dh(&humanoid, 0, Convention::Standard).unwrap_err();
    assert!(
        matches!(err, NoDhTable::Coupled { .. } | NoDhTable::Tree { .. }),
        "{err}"
    );
    let urdf = |second: &str| {
        format!(
            r#"<robot name="t"><link name="a"/><link name="b"/><link name="c"/>
            <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
              <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
            <joint name="j2" type="revolute"><parent link="{second}"/><child link="c"/>
              <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
              <limit lower="-1" upper="1" effort="1" velocity="1"/>{}</joint></robot>"#,
            if second == "b" {
                r#"<mimic joint="j1" multiplier="2"/>"#
            } else {
                ""
            }
        )
    };
    // A mimic joint: one variable for two rows.
    let r = parse_urdf(&urdf("b"), Path::new("mimic.urdf")).unwrap();
    let e = derive_dh(&r, 0, Convention::Standard).unwrap_err();
    assert!(
        matches!(e, NoDhTable::Coupled { ref joint } if joint == "j2"),
        "{e}"
    );
    // Two joints on the root link: a tree with two leaves.
    let r = parse_urdf(&urdf("a"), Path::new("tree.urdf")).unwrap();
    let e = derive_dh(&r, 0, Convention::Standard).unwrap_err();
    assert!(matches!(e, NoDhTable::Tree { .. }), "{e}");
    assert!(e.to_string().contains("the robot is a tree"), "{e}");
    let parallelogram = built_in("parallelogram").unwrap();
    let err = derive_dh(&parallelogram, 0, Convention::Standard).unwrap_err();
    assert!(
        matches!(err, NoDhTable::Coupled { .. } | NoDhTable::Tree { .. }),
        "{err}"
    );
}
