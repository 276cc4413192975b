//! Checks against the textbook's own formulas.

use armlab::kinematics::dh::{modified_to_standard, standard_to_modified};
use armlab::kinematics::models::{BUILT_INS, built_in};
use armlab::kinematics::{Convention, DhJoint, EulerKind, Robot};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_q(r: &Robot, rng: &mut ChaCha8Rng) -> Vec<f64> {
    r.limits()
        .iter()
        .map(|l| rng.random_range(l[0]..=l[1]))
        .collect()
}

/// (2.83): x_e = [a1 c1 + a2 c12 + a3 c123, a1 s1 + a2 s12 + a3 s123, theta1 + theta2 + theta3].
#[test]
fn three_link_operational_space_2_83() {
    let r = built_in("planar3").unwrap();
    let (a1, a2, a3) = (0.5, 0.3, 0.2);
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..1000 {
        let q = random_q(&r, &mut rng);
        let (t1, t12, t123) = (q[0], q[0] + q[1], q[0] + q[1] + q[2]);
        let px = a1 * t1.cos() + a2 * t12.cos() + a3 * t123.cos();
        let py = a1 * t1.sin() + a2 * t12.sin() + a3 * t123.sin();
        let x = r.operational(&q, 0, EulerKind::Zyz).unwrap();
        assert!((x[0] - px).abs() < 1e-15 && (x[1] - py).abs() < 1e-15 && x[2].abs() < 1e-15);
        // phi: the angle of x_3 from x_0 (ZYZ with theta = 0 reduces to phi + psi).
        let t = r.fk(&q).unwrap();
        let phi = t.rotation.matrix()[(1, 0)].atan2(t.rotation.matrix()[(0, 0)]);
        let d = armlab::kinematics::orientation::wrap_angle(phi - t123);
        assert!(d.abs() < 1e-14, "phi {phi} vs {t123}");
    }
}

/// (2.65): spherical arm p = [c1 s2 d3 - s1 d2, s1 s2 d3 + c1 d2, c2 d3].
#[test]
fn spherical_arm_position_2_65() {
    let r = built_in("spherical_arm").unwrap();
    let d2 = 0.5;
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for _ in 0..1000 {
        let q = random_q(&r, &mut rng);
        let (s1, c1, s2, c2, d3) = (q[0].sin(), q[0].cos(), q[1].sin(), q[1].cos(), q[2]);
        let p = r.fk(&q).unwrap().translation.vector;
        assert!((p.x - (c1 * s2 * d3 - s1 * d2)).abs() < 1e-15);
        assert!((p.y - (s1 * s2 * d3 + c1 * d2)).abs() < 1e-15);
        assert!((p.z - c2 * d3).abs() < 1e-15);
    }
}

/// (2.66): anthropomorphic arm p = [c1 (a2 c2 + a3 c23), s1 (a2 c2 + a3 c23), a2 s2 + a3 s23].
#[test]
fn anthropomorphic_position_2_66() {
    let r = built_in("anthropomorphic3r").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for _ in 0..1000 {
        let q = random_q(&r, &mut rng);
        let reach = q[1].cos() + (q[1] + q[2]).cos();
        let p = r.fk(&q).unwrap().translation.vector;
        assert!((p.x - q[0].cos() * reach).abs() < 1e-14);
        assert!((p.y - q[0].sin() * reach).abs() < 1e-14);
        assert!((p.z - (q[1].sin() + (q[1] + q[2]).sin())).abs() < 1e-14);
    }
}

/// Sect. 2.9.9: theta4 = -theta2 - theta3 keeps the chest frame t parallel to frame 1, so the
/// torso end-effector frame only yaws with theta1.
#[test]
fn humanoid_coupled_joint_keeps_chest_upright() {
    let r = built_in("humanoid").unwrap();
    assert_eq!(r.dof(), 17);
    assert_eq!(r.end_effectors().len(), 2);
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for _ in 0..500 {
        let q = random_q(&r, &mut rng);
        let frames = r.fk_frames(&q).unwrap();
        let (f1, ft) = (frames[0], frames[3]);
        assert!((f1.rotation.matrix() - ft.rotation.matrix()).amax() < 1e-14);
        assert!((r.joint_variable(3, &q) + q[1] + q[2]).abs() < 1e-15);
        // T_t^3 = Rz(-(theta2 + theta3)), the matrix of Sect. 2.9.9.
        let t3_t = frames[2].inverse() * frames[3];
        let s23 = (q[1] + q[2]).sin();
        let c23 = (q[1] + q[2]).cos();
        let m = t3_t.to_homogeneous();
        assert!((m[(0, 0)] - c23).abs() < 1e-14 && (m[(0, 1)] - s23).abs() < 1e-14);
        assert!((m[(1, 0)] + s23).abs() < 1e-14 && m.fixed_view::<3, 1>(0, 3).amax() < 1e-14);
    }
    // The two hands are mirror images for mirrored arm angles.
    let mut q = r.config("ready").unwrap().to_vec();
    q[0] = 0.0;
    let hands = r.fk_all_ee(&q).unwrap();
    assert!((hands[0].translation.y + hands[1].translation.y).abs() < 1e-12);
    assert!((hands[0].translation.z - hands[1].translation.z).abs() < 1e-12);
}

/// Parallelogram arm: the chain closes (joint 3' frame lands on the tip of link 1'').
#[test]
fn parallelogram_closes() {
    let r = built_in("parallelogram").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for _ in 0..200 {
        let q = random_q(&r, &mut rng);
        let f = r.fk_frames(&q).unwrap();
        assert!((f[3].translation.vector - f[1].translation.vector).amax() < 1e-14);
    }
}

/// Problem 2.11 (the geometry chosen in `models::slider_chain`): at random crank and arm angles
/// the loop closes in the frames (the slider P on link 2' beyond A, link 3' orthogonal to link
/// 2', the arm's end C on link 3' at c = 0.25 m from P), and the end-effector is where the
/// direct kinematics written out here puts it, with link 2's direction found independently as
/// the tangent from A to the circle of radius c about C: phi = Atan2(v) - asin(c / |v|).
#[test]
fn problem_2_11_closed_chain_closes_and_its_fk_is_the_derivation() {
    let r = built_in("slider_chain").unwrap();
    let (a1p, a1pp, c, a4) = (0.2, 0.6, 0.25, 0.35);
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for _ in 0..2000 {
        let q = random_q(&r, &mut rng);
        let f = r.fk_frames(&q).unwrap();
        let t = r.fk(&q).unwrap();
        let (a, cc, p) = (
            f[0].translation.vector,
            f[1].translation.vector,
            f[3].translation.vector,
        );
        let u = f[2].rotation * nalgebra::Vector3::z();
        let x_e = t.rotation * nalgebra::Vector3::x();
        assert!((p - a).cross(&u).norm() < 1e-12 && (p - a).dot(&u) > 0.0);
        assert!(x_e.dot(&u).abs() < 1e-12);
        assert!((p + x_e * c - cc).norm() < 1e-12, "{q:?}");
        // The derivation: v = C - A, phi = Atan2(v) - asin(c/|v|), p_e = C + a4 n(phi).
        let (q1, q2) = (q[0], q[1]);
        let v = [
            a1pp * q2.cos() - a1p * q1.cos(),
            a1pp * q2.sin() - a1p * q1.sin(),
        ];
        let phi = v[1].atan2(v[0]) - (c / v[0].hypot(v[1])).asin();
        let n = [-phi.sin(), phi.cos()];
        let want = [a1pp * q2.cos() + a4 * n[0], a1pp * q2.sin() + a4 * n[1]];
        let got = t.translation.vector;
        assert!((got.x - want[0]).abs() < 1e-12 && (got.y - want[1]).abs() < 1e-12);
        assert!(got.z.abs() < 1e-15 && (x_e.x - n[0]).abs() < 1e-12);
        // The prismatic joint's value is the slide |P - A| = sqrt(|v|^2 - c^2).
        let d = r.joint_variable(3, &q);
        assert!((d - (p - a).norm()).abs() < 1e-12);
        assert!((d - (v[0] * v[0] + v[1] * v[1] - c * c).sqrt()).abs() < 1e-12);
    }
    // A crank whose DH row disagrees with the loop's length, or a loop that cannot close for
    // every angle, is refused with the reason (never a silently wrong chain).
    let mut joints = r.joints().to_vec();
    if let armlab::kinematics::JointGeometry::Dh { row, .. } = &mut joints[0].geometry {
        row.a = 0.3;
    }
    let err = Robot::new("x", r.base, joints, r.end_effectors().to_vec()).unwrap_err();
    assert!(err.to_string().contains("loop's link"), "{err}");
    let mut joints = r.joints().to_vec();
    if let armlab::kinematics::Drive::Closure(cl) = &mut joints[3].drive {
        cl.mechanism.offset = 0.5;
    }
    let err = Robot::new("x", r.base, joints, r.end_effectors().to_vec()).unwrap_err();
    assert!(err.to_string().contains("does not close"), "{err}");
}

/// Standard <-> modified DH conversions are exact: same end-effector pose.
#[test]
fn dh_conversions_preserve_fk() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    for b in BUILT_INS {
        let r = (b.build)();
        let Some((conv, rows)) = r.dh_table() else {
            continue;
        };
        let spec: Vec<_> = rows
            .iter()
            .map(|(k, row, off)| DhJoint::new(*k, *row).offset(*off).limits(-1.0, 1.0))
            .collect();
        let dh: Vec<_> = rows.iter().map(|x| x.1).collect();
        let tool = r.end_effectors()[0].tool;
        let other = match conv {
            Convention::Standard => {
                let (m, extra) = standard_to_modified(&dh);
                let spec: Vec<_> = spec
                    .iter()
                    .zip(m)
                    .map(|(s, row)| DhJoint { row, ..s.clone() })
                    .collect();
                Robot::from_dh("m", Convention::Modified, &spec, r.base, extra * tool).unwrap()
            }
            Convention::Modified => {
                let (extra, s) = modified_to_standard(&dh);
                let spec: Vec<_> = spec
                    .iter()
                    .zip(s)
                    .map(|(s, row)| DhJoint { row, ..s.clone() })
                    .collect();
                Robot::from_dh("s", Convention::Standard, &spec, r.base * extra, tool).unwrap()
            }
        };
        for _ in 0..100 {
            let q = random_q(&r, &mut rng);
            let d = (r.fk(&q).unwrap().to_homogeneous() - other.fk(&q).unwrap().to_homogeneous())
                .amax();
            assert!(d < 1e-14, "{}: {d:e}", b.name);
        }
    }
}

/// Every built-in builds, has a description, and its named configurations fit.
#[test]
fn built_ins_are_complete() {
    assert!(BUILT_INS.len() >= 14);
    for b in BUILT_INS {
        let r = (b.build)();
        assert!(!r.description.is_empty(), "{}", b.name);
        for name in ["zero", "ready"] {
            assert!(r.config(name).is_some(), "{} lacks {name}", b.name);
        }
        for c in &r.configurations {
            assert_eq!(c.q.len(), r.dof(), "{} {}", b.name, c.name);
            if c.name != "zero" {
                assert!(
                    r.within_limits(&c.q, 1e-12),
                    "{} {} outside limits",
                    b.name,
                    c.name
                );
            }
            assert!(r.fk(&c.q).is_ok());
        }
    }
}

/// Wrong length and NaN are errors, never a pose.
#[test]
fn bad_joint_vectors_are_errors() {
    let r = built_in("puma560").unwrap();
    assert!(
        r.fk(&[0.0; 5])
            .unwrap_err()
            .to_string()
            .contains("expected 6 joint values, got 5")
    );
    let e = r
        .fk(&[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0])
        .unwrap_err()
        .to_string();
    assert!(e.contains("joint value 1") && e.contains("NaN"), "{e}");
    assert!(r.jacobian(&[f64::INFINITY; 6], 0).is_err());
    assert!(
        r.fk_ee(&[0.0; 6], 3)
            .unwrap_err()
            .to_string()
            .contains("end-effector")
    );
}
