//! The constructions behind the closed forms (Sect. 2.12): every quantity a figure or overlay
//! labels equals the quantity it names, computed independently here (forward kinematics, angles
//! between vectors, the DH table's own numbers).

use crate::common;

use armlab::construction::{ConstructionError, TwoLinkConstruction, WristPoint};
use armlab::kinematics::models::anthropomorphic_spherical_wrist;
use std::f64::consts::PI;

fn lcg(s: &mut u64) -> f64 {
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*s >> 11) as f64 / (1u64 << 53) as f64
}

/// The signed angle from `u` to `v` (rad), by atan2 of cross and dot.
fn signed(u: [f64; 2], v: [f64; 2]) -> f64 {
    (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1])
}

#[test]
fn the_two_link_triangle_labels_what_it_names() {
    let mut s = 7u64;
    let mut checked = 0;
    while checked < 5000 {
        let (a1, a2) = (0.3 + lcg(&mut s), 0.3 + lcg(&mut s));
        let r = (a1 - a2).abs() + (2.0 * a1.min(a2)) * (0.02 + 0.96 * lcg(&mut s));
        let t = -PI + 2.0 * PI * lcg(&mut s);
        let p = [r * t.cos(), r * t.sin()];
        let k = TwoLinkConstruction::new(a1, a2, p).unwrap();
        assert!((k.distance - r).abs() < 1e-12);
        assert!((k.alpha - p[1].atan2(p[0])).abs() < 1e-12);
        for pos in &k.postures {
            // Forward kinematics of the two-link arm (2.63 with two links).
            let x = a1 * pos.theta1.cos() + a2 * (pos.theta1 + pos.theta2).cos();
            let y = a1 * pos.theta1.sin() + a2 * (pos.theta1 + pos.theta2).sin();
            assert!((x - p[0]).hypot(y - p[1]) < 1e-12, "{pos:?}");
            // beta is the angle at O between O->W and link 1.
            let beta = signed(p, pos.elbow).abs();
            assert!((beta - k.beta).abs() < 1e-9, "{beta} vs {}", k.beta);
            // theta2 is the angle from link 1 to link 2 at the elbow.
            let link2 = [p[0] - pos.elbow[0], p[1] - pos.elbow[1]];
            assert!((signed(pos.elbow, link2) - pos.theta2).abs() < 1e-9);
            // Elbow up is theta2 in (-pi, 0), theta1 = alpha + beta.
            let up = pos.name == "elbow up";
            assert_eq!(up, pos.theta2 < 0.0);
            let t1 = if up {
                k.alpha + k.beta
            } else {
                k.alpha - k.beta
            };
            assert!((pos.theta1 - t1).abs() < 1e-12);
            assert!((k.c2 - pos.theta2.cos()).abs() < 1e-12);
        }
        checked += 1;
    }
    assert!(matches!(
        TwoLinkConstruction::new(1.0, 1.0, [2.5, 0.0]),
        Err(ConstructionError::OutOfReach { .. })
    ));
    assert!(TwoLinkConstruction::new(1.0, 0.5, [0.2, 0.0]).is_err());
}

/// (2.93) on the anthropomorphic arm with spherical wrist (d6 = 0.1 m in its DH table): the
/// wrist point is the origin of frame 4 (d4 along z3 from frame 3, on axes 4-6), d6 the table's.
#[test]
fn the_wrist_point_is_where_the_wrist_axes_meet() {
    let robot = anthropomorphic_spherical_wrist();
    let d6 = robot.dh_table().unwrap().1[5].1.d;
    assert!((d6 - 0.1).abs() < 1e-15);
    let mut s = 3u64;
    for _ in 0..1000 {
        let q: Vec<f64> = (0..6).map(|_| -PI + 2.0 * PI * lcg(&mut s)).collect();
        let w = WristPoint::of(&robot, &q).unwrap();
        let frames = robot.fk_frames(&q).unwrap();
        let o4 = frames[3].translation.vector;
        assert!((w.p_w - o4).norm() < 1e-12, "{q:?}");
        assert!((w.d6 - d6).abs() < 1e-12);
        let t = robot.fk(&q).unwrap();
        assert!((w.p_e - t.translation.vector).norm() < 1e-15);
        assert!((w.a_e - t.rotation * nalgebra::Vector3::z()).norm() < 1e-15);
    }
    // The Puma's wrist point exists too; a planar arm has none.
    assert!(
        WristPoint::of(
            &armlab::kinematics::models::puma560(),
            &[0.1, -0.4, 0.3, 0.5, -0.6, 0.2]
        )
        .is_ok()
    );
    assert!(WristPoint::of(&armlab::kinematics::models::planar3(), &[0.1, 0.2, 0.3]).is_err());
}

/// The arc labelled `name` in the steps: its signed angle (rad) and label.
fn arc(steps: &[armlab::construction::steps::Step], name: &str) -> (f64, String) {
    use armlab::construction::steps::Mark;
    steps
        .iter()
        .flat_map(|s| &s.marks)
        .find_map(|m| match m {
            Mark::Arc { angle, label, .. } if label.starts_with(name) => {
                Some((*angle, label.clone()))
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no arc {name}"))
}

fn same_angle(a: f64, b: f64) -> bool {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d) < 1e-9
}

/// Every angle the construction draws is the joint it names, at random configurations of the
/// planar arms and the anthropomorphic arms, and the label prints that angle.
#[test]
fn construction_angles_are_the_joints_they_name() {
    use armlab::construction::steps::construction;
    use armlab::kinematics::models::built_in;
    let mut s = 11u64;
    for (model, names) in [
        ("planar2", &["θ1", "θ2"][..]),
        ("planar3", &["θ1", "θ2", "θ3"][..]),
        ("anthropomorphic3r", &["θ1", "θ2", "θ3"][..]),
        (
            "anthropomorphic_spherical_wrist",
            &["θ1", "θ2", "θ3", "θ5"][..],
        ),
    ] {
        let robot = built_in(model).unwrap();
        let lim = robot.limits();
        let mut done = 0;
        while done < 300 {
            let q: Vec<f64> = lim
                .iter()
                .map(|l| l[0].max(-PI) + (l[1].min(PI) - l[0].max(-PI)) * lcg(&mut s))
                .collect();
            let Ok(steps) = construction(&robot, &q) else {
                continue;
            };
            for (k, name) in names.iter().enumerate() {
                let joint = if *name == "θ5" { 4 } else { k };
                let (drawn, label) = arc(&steps, name);
                // The label's value (the joint); the arc may be turned by a DH constant.
                let value: f64 = label
                    .split("= ")
                    .nth(1)
                    .and_then(|t| t.trim_end_matches('°').parse::<f64>().ok())
                    .unwrap()
                    .to_radians();
                let angle = if (value - drawn).abs() < 1e-3 {
                    drawn
                } else {
                    value
                };
                // theta1 is drawn from x0 to the plane through p_W: q1 itself (shoulder right)
                // or q1 - pi (shoulder left, the drawn twin direction is dashed).
                let ok = if *name == "θ5" {
                    // Drawn: the angle between z3 and a_e, |theta5|; labelled: theta5 itself.
                    (drawn - q[joint].abs()).abs() < 1e-9 && (value - q[joint]).abs() < 1e-3
                } else if model.starts_with("anthropomorphic") && *name == "θ1" {
                    same_angle(angle, q[0]) || same_angle(angle + PI, q[0])
                } else if (value - drawn).abs() < 1e-3 {
                    same_angle(angle, q[joint])
                } else {
                    // One decimal of degrees in the label.
                    let d = (angle - q[joint]).rem_euclid(2.0 * PI);
                    d.min(2.0 * PI - d) < 1e-3
                };
                assert!(ok, "{model} {name}: drawn {angle}, q = {q:?}");
                // Printed without a sign on zero ("-0.0°" is "0.0°").
                let printed = format!("{:.1}°", angle.to_degrees()).replace("-0.0°", "0.0°");
                assert!(label.contains(&printed), "{label}");
            }
            done += 1;
        }
    }
    // A numerical arm has none, with the reason.
    let dlr = built_in("dlr").unwrap();
    let err = construction(&dlr, dlr.config("ready").unwrap()).unwrap_err();
    assert!(err.to_string().contains("no closed form"), "{err}");
}

/// The segment whose label starts with `name` ("d3 = 0.600 m"): its length and label.
fn segment(steps: &[armlab::construction::steps::Step], name: &str) -> (f64, String) {
    use armlab::construction::steps::Mark;
    steps
        .iter()
        .flat_map(|s| &s.marks)
        .find_map(|m| match m {
            Mark::Segment { a, b, label, .. } if label.starts_with(name) => {
                Some(((b - a).norm(), label.clone()))
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no segment {name}"))
}

/// The number after "= " in a label, in the label's unit (degrees or metres).
fn label_value(label: &str) -> f64 {
    label
        .split("= ")
        .nth(1)
        .and_then(|t| {
            t.trim_end_matches(" m")
                .trim_end_matches('°')
                .parse::<f64>()
                .ok()
        })
        .unwrap_or_else(|| panic!("no value in {label}"))
}

/// Every family with a construction: each labelled angle is drawn as the joint it names and
/// prints it (one decimal of degrees), each labelled length (d2, d3) is drawn as long as the
/// prismatic joint's value and prints it (millimetres); the joint values are those put in.
#[test]
fn every_family_draws_and_labels_its_joints() {
    use armlab::construction::steps::construction;
    use armlab::kinematics::models::built_in;
    let mut s = 5u64;
    for (model, angles, lengths) in [
        (
            "spherical_arm",
            &[("θ1", 0), ("θ2", 1)][..],
            &[("d3", 2)][..],
        ),
        (
            "stanford",
            &[("θ1", 0), ("θ2", 1), ("θ4", 3), ("θ5", 4), ("θ6", 5)][..],
            &[("d3", 2)][..],
        ),
        ("cylindrical", &[("θ1", 0)][..], &[("d2", 1), ("d3", 2)][..]),
        (
            "scara",
            &[("θ1", 0), ("θ2", 1), ("θ4", 3)][..],
            &[("d3", 2)][..],
        ),
        (
            "spherical_wrist",
            &[("θ4", 0), ("θ5", 1), ("θ6", 2)][..],
            &[][..],
        ),
        (
            "puma560",
            &[
                ("θ1", 0),
                ("θ2", 1),
                ("θ3", 2),
                ("θ4", 3),
                ("θ5", 4),
                ("θ6", 5),
            ][..],
            &[][..],
        ),
        (
            "anthropomorphic_spherical_wrist",
            &[("θ4", 3), ("θ6", 5)][..],
            &[][..],
        ),
    ] {
        let robot = built_in(model).unwrap();
        let lim = robot.limits();
        for _ in 0..300 {
            let q: Vec<f64> = lim
                .iter()
                .map(|l| l[0].max(-PI) + (l[1].min(PI) - l[0].max(-PI)) * lcg(&mut s))
                .collect();
            let steps = construction(&robot, &q).unwrap_or_else(|e| panic!("{model}: {e}"));
            for &(name, j) in angles {
                let (drawn, label) = arc(&steps, name);
                let value = label_value(&label).to_radians();
                let d = (value - q[j]).rem_euclid(2.0 * PI);
                assert!(
                    d.min(2.0 * PI - d) < 0.051_f64.to_radians(),
                    "{model} {name}: label {label}, q = {q:?}"
                );
                if name == "θ5" {
                    // Drawn as the angle between z3 and a_e: |theta5|.
                    assert!((drawn - q[j].abs()).abs() < 1e-9, "{model}: {drawn} {q:?}");
                } else if model == "puma560" && j < 3 {
                    // The Puma's frames differ from the drawn geometry by DH constants; the
                    // label carries the joint, checked above.
                } else {
                    assert!(
                        same_angle(drawn, q[j]),
                        "{model} {name}: drawn {drawn}, q {q:?}"
                    );
                }
            }
            for &(name, j) in lengths {
                let (len, label) = segment(&steps, name);
                assert!(
                    (len - q[j].abs()).abs() < 1e-9,
                    "{model} {name}: {len} vs {q:?}"
                );
                assert!(
                    (label_value(&label) - q[j]).abs() < 5.1e-4,
                    "{label} vs {q:?}"
                );
            }
        }
    }
}

/// The construction names its lengths as the DH table does, with the table's values: the Puma's
/// forearm is sqrt(a3^2 + d4^2) (a3 = 20.3 mm, d4 = 431.8 mm), never "a3 = 0.432 m"; the
/// textbook's arm's forearm is d4. No "-0.000" anywhere (the Puma's d6 = 0 once printed so).
#[test]
fn construction_lengths_carry_the_dh_tables_names_and_values() {
    let puma = armlab::kinematics::models::built_in("puma560").unwrap();
    let (_, rows) = puma.dh_table().unwrap();
    let (a2, a3, d4) = (rows[1].1.a, rows[2].1.a, rows[3].1.d);
    let q = armlab::kinematics::opening::opening_pose(&puma).q;
    let steps = armlab::construction::steps::construction(&puma, &q).unwrap();
    let (len, label) = segment(&steps, "sqrt(a3^2 + d4^2) = ");
    let expected = (a3 * a3 + d4 * d4).sqrt();
    assert!((len - expected).abs() < 1e-9, "{label}: drawn {len}");
    assert!((label_value(&label) - expected).abs() < 5e-4, "{label}");
    let (len2, label2) = segment(&steps, "a2 = ");
    assert!((len2 - a2).abs() < 1e-9, "{label2}");
    let all_text = |steps: &[armlab::construction::steps::Step]| -> String {
        use armlab::construction::steps::Mark;
        steps
            .iter()
            .flat_map(|s| {
                let mut t = vec![s.title.clone(), s.formula.clone()];
                t.extend(s.marks.iter().map(|m| match m {
                    Mark::Point { label, .. }
                    | Mark::Segment { label, .. }
                    | Mark::Arc { label, .. } => label.clone(),
                }));
                t
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let text = all_text(&steps);
    assert!(!text.contains("a3 = 0.43"), "{text}");
    assert!(!text.contains("-0.000"), "{text}");
    assert!(text.contains("with L3 = sqrt(a3^2 + d4^2)"), "{text}");
    let arm = anthropomorphic_spherical_wrist();
    let q = arm.config("ready").unwrap().to_vec();
    let steps = armlab::construction::steps::construction(&arm, &q).unwrap();
    let (len, label) = segment(&steps, "d4 = ");
    assert!(
        (len - 0.5).abs() < 1e-9 && label == "d4 = 0.500 m",
        "{label}"
    );
    assert!(!all_text(&steps).contains("-0.000"));
}

/// The vendor's UR5 DH table (d1, a2, a3, d4, d5, d6), alpha = (pi/2, 0, 0, pi/2, -pi/2, 0).
const UR5: [f64; 6] = [0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823];

/// The UR5 table as (a, alpha, d) rows.
fn ur5_rows() -> [(f64, f64, f64); 6] {
    let h = PI / 2.0;
    [
        (0.0, h, UR5[0]),
        (UR5[1], 0.0, 0.0),
        (UR5[2], 0.0, 0.0),
        (0.0, h, UR5[3]),
        (0.0, -h, UR5[4]),
        (0.0, 0.0, UR5[5]),
    ]
}

/// The origins of frames 1..6 of the UR5 table at q, by the product of (2.52) written here.
fn ur5_origins(q: &[f64]) -> Vec<nalgebra::Vector3<f64>> {
    let mut t = nalgebra::Matrix4::<f64>::identity();
    let mut out = Vec::new();
    for (k, (a, alpha, d)) in ur5_rows().into_iter().enumerate() {
        t *= common::closed_form::dh_matrix(a, alpha, d, q[k]);
        out.push(nalgebra::Vector3::new(t[(0, 3)], t[(1, 3)], t[(2, 3)]));
    }
    out
}

/// The point labelled `name`.
fn point(steps: &[armlab::construction::steps::Step], name: &str) -> nalgebra::Vector3<f64> {
    use armlab::construction::steps::Mark;
    steps
        .iter()
        .flat_map(|s| &s.marks)
        .find_map(|m| match m {
            Mark::Point { p, label } if label == name => Some(*p),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no point {name}"))
}

/// The UR family (issue 27): the construction after joint 1. On the vendor's UR5 table and on
/// the corpus URDF, at random configurations, every drawn angle is its joint up to the constant
/// it has at q = 0, and its label prints the joint. On the table, checked against a forward
/// kinematics written here: o5 and W are the origins of frames 5 and 4, the segments are the
/// table's lengths (d6, d5, D = d4, |a2|, |a3|), and the other shoulder's theta1 is the other root
/// of r sin(theta1 - Atan2(o5y, o5x)) = d4.
#[test]
fn the_ur_construction_reduces_to_the_planar_arm_after_joint_1() {
    use armlab::construction::steps::construction;
    use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
    let joints: Vec<DhJoint> = ur5_rows()
        .iter()
        .map(|&(a, alpha, d)| {
            DhJoint::revolute(DhRow {
                a,
                alpha,
                d,
                theta: 0.0,
            })
            .limits(-2.0 * PI, 2.0 * PI)
        })
        .collect();
    let table = Robot::from_dh(
        "ur5",
        Convention::Standard,
        &joints,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    let urdf = armlab::model_file::load_model("tests/data/urdf_corpus/ur5_robot.urdf").unwrap();
    let names = ["θ1", "θ2", "θ3", "θ4", "θ5", "θ6"];
    let mut s = 27u64;
    for robot in [&table, &urdf] {
        let zero = construction(robot, &[0.0; 6]).unwrap();
        for _ in 0..200 {
            let q: Vec<f64> = (0..6).map(|_| -PI + 2.0 * PI * lcg(&mut s)).collect();
            let steps = construction(robot, &q).unwrap();
            assert_eq!(steps.len(), 8);
            for (k, name) in names.iter().enumerate() {
                let (drawn, label) = arc(&steps, name);
                let (drawn0, _) = arc(&zero, name);
                assert!(
                    same_angle(drawn - drawn0, q[k]),
                    "{name}: drawn {drawn} - {drawn0} at q = {q:?}"
                );
                let d = (label_value(&label).to_radians() - q[k]).rem_euclid(2.0 * PI);
                assert!(d.min(2.0 * PI - d) < 1e-3, "{label} for q = {q:?}");
            }
            if std::ptr::eq(robot, &table) {
                let o = ur5_origins(&q);
                assert!((point(&steps, "o5") - o[4]).norm() < 1e-12);
                assert!((point(&steps, "W (axis 4)") - o[3]).norm() < 1e-12);
                for (name, want) in [
                    ("-d6 z6", UR5[5]),
                    ("d5 = ", UR5[4]),
                    ("D = ", UR5[3]),
                    ("a2 = ", -UR5[1]),
                    ("a3 = ", -UR5[2]),
                ] {
                    let (len, label) = segment(&steps, name);
                    assert!((len - want).abs() < 1e-12, "{label}: {len} for {want}");
                }
                // The two shoulders, from o5 written here.
                let (r, phi) = (o[4].x.hypot(o[4].y), o[4].y.atan2(o[4].x));
                let asin = (UR5[3] / r).asin();
                let roots = [phi + asin, phi + PI - asin];
                let mine = roots.iter().position(|t| same_angle(*t, q[0])).unwrap();
                let formula = &steps[1].formula;
                let other: f64 = formula
                    .rsplit(" or ")
                    .next()
                    .and_then(|t| t.split('°').next())
                    .and_then(|t| t.parse().ok())
                    .unwrap_or_else(|| panic!("{formula}"));
                let d = (other.to_radians() - roots[1 - mine]).rem_euclid(2.0 * PI);
                assert!(d.min(2.0 * PI - d) < 1e-3, "{formula}: {roots:?}");
            }
        }
    }
}

/// The Cartesian arm with a spherical wrist (the gantry of `assets/robots/gantry_wrist.toml`,
/// issue 27): d1, d2, d3 drawn along the three prismatic axes as long as the joints, labelled
/// with their values, then the wrist's angles as for the other decoupled arms.
#[test]
fn the_gantry_draws_its_three_extensions_and_its_wrist() {
    use armlab::construction::steps::construction;
    let robot = armlab::model_file::load_model("assets/robots/gantry_wrist.toml").unwrap();
    let lim = robot.limits();
    let mut s = 9u64;
    for _ in 0..200 {
        let q: Vec<f64> = lim
            .iter()
            .map(|l| l[0].max(-PI) + (l[1].min(PI) - l[0].max(-PI)) * lcg(&mut s))
            .collect();
        let steps = construction(&robot, &q).unwrap();
        assert_eq!(steps.len(), 3, "wrist point, extensions, wrist");
        for (name, j) in [("d1", 0), ("d2", 1), ("d3", 2)] {
            let (len, label) = segment(&steps, name);
            assert!((len - q[j]).abs() < 1e-9, "{name}: {len} vs {q:?}");
            assert!(
                (label_value(&label) - q[j]).abs() < 5.1e-4,
                "{label} vs {q:?}"
            );
        }
        for (name, j) in [("θ4", 3), ("θ6", 5)] {
            let (_, label) = arc(&steps, name);
            let d = (label_value(&label).to_radians() - q[j]).rem_euclid(2.0 * PI);
            assert!(
                d.min(2.0 * PI - d) < 0.051_f64.to_radians(),
                "{name}: {label}, {q:?}"
            );
        }
    }
}
