//! Closed-form inverse kinematics (Sect. 2.12): round trips FK(IK(x)) = x for every built-in with a
//! closed form, the reference data reproduced as sets modulo 2 pi, every degenerate case, targets
//! outside the workspace, bad targets, user-made arms of the same families, and the raw path.
//!
//! Solution counts implemented (generic targets, built-in limits): 2 for planar2, planar3, SCARA
//! and the spherical wrist; 4 for anthropomorphic3r; 2 for the spherical arm (d3 >= 0, the mirror
//! d3 < 0 is outside the limits); 1 for the cylindrical arm; 8 for the Puma 560 and the
//! anthropomorphic arm with spherical wrist; 4 for the Stanford manipulator (2 arm x 2 wrist).
//!
//! This file: family detection, random round trips and the reference data; degenerate cases and
//! bad targets are in `ik_closed_form_degenerate.rs`, user-made arms and the raw path in
//! `ik_closed_form_user_arms.rs`.

use crate::common;

use common::closed_form::*;

#[test]
fn detects_the_families_of_the_built_ins() {
    let expect = [
        ("planar2", Family::Planar2),
        ("planar3", Family::Planar3),
        ("spherical_arm", Family::SphericalArm),
        ("anthropomorphic3r", Family::Anthropomorphic),
        ("spherical_wrist", Family::SphericalWrist),
        (
            "stanford",
            Family::Decoupled6 {
                arm: ArmKind::Spherical,
            },
        ),
        (
            "anthropomorphic_spherical_wrist",
            Family::Decoupled6 {
                arm: ArmKind::Anthropomorphic,
            },
        ),
        ("scara", Family::Scara),
        ("cylindrical", Family::Cylindrical),
        (
            "puma560",
            Family::Decoupled6 {
                arm: ArmKind::Anthropomorphic,
            },
        ),
    ];
    for (name, fam) in expect {
        let c = cf(&robot(name));
        assert_eq!(*c.family(), fam, "{name}");
        assert!(!c.name().is_empty());
        assert_eq!(c.dof(), robot(name).dof());
    }
    // Each arm without a closed form says why, naming the structural fact.
    for (name, why) in [
        ("parallelogram", "coupled"),
        ("dlr", "7 joints"),
        ("humanoid", "coupled"),
        ("lwr4", "redundant"),
        ("panda", "7 joints"),
    ] {
        let e = ClosedForm::detect(&robot(name))
            .expect_err(name)
            .to_string();
        assert!(e.contains(why), "{name}: {e}");
    }
}

/// A six-revolute arm outside the named families is solved by elimination; it says why no named
/// family applies.
fn not_named(r: &Robot) -> String {
    let cf = ClosedForm::detect(r).unwrap();
    assert_eq!(*cf.family(), armlab::kinematics::ik::Family::General6);
    cf.not_named().unwrap().to_string()
}

#[test]
fn no_closed_form_names_the_failed_condition() {
    // A Puma whose wrist axes do not meet: a5 = 0.1 m.
    let puma = robot("puma560");
    let (conv, table) = puma.dh_table().unwrap();
    let rows = |edit: &dyn Fn(usize, &mut DhRow)| -> Vec<DhJoint> {
        table
            .iter()
            .enumerate()
            .map(|(i, &(kind, mut row, offset))| {
                edit(i, &mut row);
                DhJoint::new(kind, row).offset(offset)
            })
            .collect()
    };
    let build = |rows: Vec<DhJoint>| {
        Robot::from_dh("edited", conv, &rows, Pose::identity(), Pose::identity()).unwrap()
    };
    let e = not_named(&build(rows(&|i, r| {
        if i == 4 {
            r.a = 0.1
        }
    })));
    assert!(
        e.contains("do not intersect") && e.contains("a5 = 0.1 m"),
        "{e}"
    );
    assert!(e.contains("no spherical wrist"), "{e}");
    // Axes 4 and 5 not perpendicular.
    let e = not_named(&build(rows(&|i, r| {
        if i == 3 {
            r.alpha = 1.0
        }
    })));
    assert!(e.contains("axes 4 and 5 are not perpendicular"), "{e}");
    // Axes 2 and 3 not parallel: the wrist is fine, the arm is none of the named ones, so the
    // arm is Pieper's general case (issue 27), solved by its quartic, not by elimination.
    let skewed = ClosedForm::detect(&build(rows(&|i, r| {
        if i == 1 {
            r.alpha = 0.3
        }
    })))
    .unwrap();
    assert_eq!(
        *skewed.family(),
        Family::Decoupled6 {
            arm: ArmKind::General3R
        }
    );
    assert!(skewed.name().contains("Pieper") && skewed.not_named().is_none());
    // Five joints.
    let five: Vec<DhJoint> = rows(&|_, _| {}).into_iter().take(5).collect();
    let e = ClosedForm::detect(&build(five)).unwrap_err().to_string();
    assert!(e.starts_with("5 joints"), "{e}");
    // A planar arm with a twisted axis.
    let r = Robot::from_dh(
        "twisted",
        Convention::Standard,
        &[rv(1.0, 0.0, 0.0, 0.0), rv(1.0, 0.4, 0.0, 0.0)],
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    let e = ClosedForm::detect(&r).unwrap_err().to_string();
    assert!(
        e.contains("not a two-link planar arm") || e.contains("alpha"),
        "{e}"
    );
}

#[test]
fn detection_ignores_the_name() {
    let mut r = robot("lwr4");
    r.name = "Puma 560".into();
    assert!(ClosedForm::detect(&r).is_err());
    let mut p = robot("puma560");
    p.name = "KUKA LWR-IV".into();
    assert!(ClosedForm::detect(&p).is_ok());
}

// ---------------------------------------------------------------- round trips (proptest)

fn round_trip(name: &str, u: &[f64]) -> Result<(), TestCaseError> {
    let robot = robot(name);
    let c = cf(&robot);
    let q = q_in_limits(&robot, u);
    let t = robot.fk(&q).expect("fk");
    let fam = *c.family();
    let mut targets = vec![(Target::Pose(t), !position_only(&fam))];
    if position_only(&fam) {
        targets.push((Target::Position(t.translation.vector), false));
    }
    if matches!(fam, Family::Planar2 | Family::Planar3) {
        let phi = t.rotation.matrix()[(1, 0)].atan2(t.rotation.matrix()[(0, 0)]);
        let p = t.translation.vector;
        targets.push((
            Target::Planar {
                px: p.x,
                py: p.y,
                phi,
            },
            fam == Family::Planar3,
        ));
    }
    for (target, orient) in targets {
        let res = c.solve(&robot, &target).expect("valid target");
        if res.status == IkStatus::Singular {
            // A sample within about 1e-6 rad of a singular configuration: the solver merges the
            // pair there (cosines within COS_TOL of +-1). Accept it only where the sample really is
            // that close to a singularity, measured in the test by a finite-difference Jacobian,
            // and one merged solution sits next to the sample.
            let sigma = smallest_singular_value(&robot, &q, orient);
            prop_assert!(
                sigma < 1e-5,
                "sigma_min {sigma:.1e}, q = {q:?}\n{}",
                show(&res)
            );
            prop_assert!(
                res.solutions
                    .iter()
                    .any(|s| same_q(&robot, &s.q, &q, 1e-5) && s.position_error < 1e-6),
                "q = {q:?}\n{}",
                show(&res)
            );
            continue;
        }
        prop_assert_eq!(res.status, IkStatus::Ok, "{}", show(&res));
        prop_assert_eq!(
            res.solutions.len(),
            fam.generic_solution_count(),
            "{}",
            show(&res)
        );
        for s in &res.solutions {
            prop_assert!(s.position_error < 1e-10, "{}", show(&res));
            if orient {
                prop_assert!(s.orientation_error < 1e-10, "{}", show(&res));
            }
            prop_assert_eq!(s.within_limits, robot.within_limits(&s.q, 1e-12));
            // Honest errors: recompute.
            let fk = robot.fk(&s.q).expect("fk");
            let pe = (fk.translation.vector - t.translation.vector).norm();
            prop_assert!((pe - s.position_error).abs() < 1e-12);
            prop_assert!(s.free_joints.is_empty());
        }
        let own = res
            .solutions
            .iter()
            .find(|s| same_q(&robot, &s.q, &q, 1e-7));
        prop_assert!(own.is_some(), "q = {:?} missing:\n{}", q, show(&res));
        let own = own.expect("checked");
        prop_assert!(own.within_limits, "{}", show(&res));
        if matches!(target, Target::Pose(_)) {
            // The configuration q itself also has the right orientation, even for position-only
            // families (whose other solutions report an honest orientation error).
            prop_assert!(own.orientation_error < 1e-9, "{}", show(&res));
        }
        // No two solutions are the same configuration.
        for (i, a) in res.solutions.iter().enumerate() {
            for b in &res.solutions[i + 1..] {
                prop_assert!(!same_q(&robot, &a.q, &b.q, 1e-9));
            }
        }
    }
    Ok(())
}

/// Smallest singular value of the end-effector Jacobian at `q` by central differences of the
/// forward kinematics: position rows, plus the rotation rows when `orient`.
fn smallest_singular_value(robot: &Robot, q: &[f64], orient: bool) -> f64 {
    let rows = if orient { 6 } else { 3 };
    let h = 1e-6;
    let mut j = nalgebra::DMatrix::<f64>::zeros(rows, q.len());
    for k in 0..q.len() {
        let (mut qp, mut qm) = (q.to_vec(), q.to_vec());
        qp[k] += h;
        qm[k] -= h;
        let (tp, tm) = (robot.fk(&qp).expect("fk"), robot.fk(&qm).expect("fk"));
        let dp = (tp.translation.vector - tm.translation.vector) / (2.0 * h);
        j.fixed_view_mut::<3, 1>(0, k).copy_from(&dp);
        if orient {
            // R(q + h) R(q - h)^T = I + [w] 2h + O(h^2): w from the skew part.
            let m = tp.rotation.matrix() * tm.rotation.matrix().transpose();
            let w = Vector3::new(
                m[(2, 1)] - m[(1, 2)],
                m[(0, 2)] - m[(2, 0)],
                m[(1, 0)] - m[(0, 1)],
            ) / (4.0 * h);
            j.fixed_view_mut::<3, 1>(3, k).copy_from(&w);
        }
    }
    j.singular_values().min()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn round_trip_planar2(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("planar2", &u)?;
    }

    #[test]
    fn round_trip_planar3(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("planar3", &u)?;
    }

    #[test]
    fn round_trip_spherical_arm(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("spherical_arm", &u)?;
    }

    #[test]
    fn round_trip_anthropomorphic3r(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("anthropomorphic3r", &u)?;
    }

    #[test]
    fn round_trip_spherical_wrist(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("spherical_wrist", &u)?;
    }

    #[test]
    fn round_trip_stanford(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("stanford", &u)?;
    }

    #[test]
    fn round_trip_anthropomorphic_spherical_wrist(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("anthropomorphic_spherical_wrist", &u)?;
    }

    #[test]
    fn round_trip_scara(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("scara", &u)?;
    }

    #[test]
    fn round_trip_cylindrical(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("cylindrical", &u)?;
    }

    #[test]
    fn round_trip_puma560(u in prop::collection::vec(0.0..=1.0f64, 6)) {
        round_trip("puma560", &u)?;
    }

    #[test]
    fn wrap_into_limits_is_a_2pi_shift(q in -20.0..20.0f64, lo in -7.0..3.0f64, w in 0.0..8.0f64) {
        let lim = [lo, lo + w];
        let v = wrap_into_limits(q, lim);
        prop_assert!(wrap_angle(v - q).abs() < 1e-9);
        let fits = ((lim[0] - q) / std::f64::consts::TAU).ceil() <= ((lim[1] - q) / std::f64::consts::TAU).floor();
        if fits {
            prop_assert!(v >= lim[0] - 1e-9 && v <= lim[1] + 1e-9);
        } else {
            prop_assert!(v > -PI - 1e-12 && v <= PI + 1e-12);
        }
    }
}

// ---------------------------------------------------------------- reference data

#[test]
fn reference_planar2() {
    let r = robot("planar2");
    let data = reference("ik_planar2_closed_form.json");
    for e in data["targets"].as_array().expect("targets") {
        let (px, py, phi) = (
            e["px"].as_f64().unwrap(),
            e["py"].as_f64().unwrap(),
            e["phi"].as_f64().unwrap(),
        );
        let sols = e["solutions"].as_array().unwrap();
        let refs: Vec<Vec<f64>> = sols.iter().map(|s| vecf(&s["q"])).collect();
        for target in [
            Target::Planar { px, py, phi },
            Target::Position(Vector3::new(px, py, 0.0)),
        ] {
            let res = solve(&r, target);
            assert_eq!(res.status, IkStatus::Ok);
            assert_verified(&res, false, 1e-12);
            let idx = match_sets(&r, &res, &refs, 1e-9);
            for (s, &i) in sols.iter().zip(&idx) {
                let ours = &res.solutions[i];
                assert_eq!(ours.within_limits, s["within_limits"].as_bool().unwrap());
                let label = s["label"].as_str().unwrap();
                let expected = if label.starts_with("s2>0") {
                    "elbow down"
                } else {
                    "elbow up"
                };
                assert_eq!(ours.posture.to_string(), expected, "{label}");
                if matches!(target, Target::Planar { .. }) {
                    // phi is not controlled by a two-link arm: its error is reported.
                    let phi_err = s["phi_err"].as_f64().unwrap();
                    assert!((ours.orientation_error - phi_err).abs() < 1e-9);
                }
            }
        }
    }
}

#[test]
fn reference_planar3_with_limit_flags() {
    let r = robot("planar3");
    let data = reference("ik_planar3_closed_form.json");
    for e in data["targets"].as_array().expect("targets") {
        let (px, py, phi) = (
            e["px"].as_f64().unwrap(),
            e["py"].as_f64().unwrap(),
            e["phi"].as_f64().unwrap(),
        );
        let sols = e["solutions"].as_array().unwrap();
        let refs: Vec<Vec<f64>> = sols.iter().map(|s| vecf(&s["q"])).collect();
        let res = solve(&r, Target::Planar { px, py, phi });
        assert_eq!(res.status, IkStatus::Ok);
        assert_verified(&res, true, 1e-12);
        let idx = match_sets(&r, &res, &refs, 1e-9);
        for (s, &i) in sols.iter().zip(&idx) {
            assert_eq!(
                res.solutions[i].within_limits,
                s["within_limits"].as_bool().unwrap(),
                "{}",
                show(&res)
            );
            let expected = if s["label"].as_str().unwrap().starts_with("s2>0") {
                "elbow down"
            } else {
                "elbow up"
            };
            assert_eq!(res.solutions[i].posture.to_string(), expected);
        }
    }
}

#[test]
fn reference_anthropomorphic3r() {
    let r = robot("anthropomorphic3r");
    let data = reference("ik_anthropomorphic3r_closed_form.json");
    for e in data["positions"].as_array().expect("positions") {
        let p = vecf(&e["p"]);
        let sols = e["solutions"].as_array().unwrap();
        let refs: Vec<Vec<f64>> = sols.iter().map(|s| vecf(&s["q"])).collect();
        let res = solve(&r, Target::Position(Vector3::new(p[0], p[1], p[2])));
        assert_eq!(res.status, IkStatus::Ok);
        assert_verified(&res, false, 1e-12);
        let idx = match_sets(&r, &res, &refs, 1e-9);
        for (s, &i) in sols.iter().zip(&idx) {
            let label = s["label"].as_str().unwrap();
            let right = label.starts_with("th1_I,");
            let s3_pos = label.ends_with("s3>0");
            let shoulder = if right {
                "shoulder right"
            } else {
                "shoulder left"
            };
            // Elbow above the shoulder-wrist line: s3 < 0 on the right, s3 > 0 on the left.
            let elbow = if right != s3_pos {
                "elbow up"
            } else {
                "elbow down"
            };
            assert_eq!(
                res.solutions[i].posture.to_string(),
                format!("{shoulder}, {elbow}")
            );
        }
    }
}

#[test]
fn elbow_up_is_geometrically_up() {
    // "elbow up": the elbow lies above the line from the shoulder to the wrist point, for both
    // shoulder solutions (the arm plane contains z0 for these arms), whatever the sign of alpha1.
    let flipped = Robot::from_dh(
        "alpha1 = -pi/2",
        Convention::Standard,
        &[
            rv(0.0, -FRAC_PI_2, 0.3, 0.0),
            rv(0.8, 0.0, 0.0, 0.0),
            rv(0.6, 0.0, 0.0, 0.0),
        ],
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    for (r, elbow_frame, wrist_frame) in [
        (robot("anthropomorphic3r"), 1, 2),
        (robot("anthropomorphic_spherical_wrist"), 1, 3),
        (flipped, 1, 2),
    ] {
        let mut q6 = [0.3, 0.9, -1.1, 0.2, 0.5, 0.1];
        for k in 0..20 {
            q6[0] = -3.0 + 0.3 * k as f64;
            q6[1] = 1.7 - 0.2 * k as f64;
            q6[2] = -2.45 + 0.25 * k as f64;
            let q = &q6[..r.dof()];
            let t = r.fk(q).unwrap();
            let target = if r.dof() == 3 {
                Target::Position(t.translation.vector)
            } else {
                Target::Pose(t)
            };
            let res = solve(&r, target);
            assert_eq!(res.status, IkStatus::Ok, "{}", show(&res));
            assert_eq!(res.solutions.len(), if r.dof() == 3 { 4 } else { 8 });
            for s in &res.solutions {
                let f = r.fk_frames(&s.q).unwrap();
                let sh = f[0].translation.vector;
                let e = f[elbow_frame].translation.vector - sh;
                let w = f[wrist_frame].translation.vector - sh;
                let u = w.xy().normalize();
                let (du, dz) = (w.xy().norm(), w.z);
                let eu = e.xy().dot(&u);
                let above = -dz * eu + du * e.z > 0.0;
                assert_eq!(
                    s.posture.to_string().contains("elbow up"),
                    above,
                    "{} {}",
                    r.name,
                    s.posture
                );
            }
        }
    }
}

#[test]
fn reference_anthropomorphic_spherical_wrist() {
    let r = robot("anthropomorphic_spherical_wrist");
    let data = reference("ik_anthropomorphic_spherical_wrist_closed_form.json");
    for e in data["poses"].as_array().expect("poses") {
        let t = pose_of(&e["T"]);
        let sols = e["solutions"].as_array().unwrap();
        let refs: Vec<Vec<f64>> = sols.iter().map(|s| vecf(&s["q"])).collect();
        let res = solve(&r, Target::Pose(t));
        assert_eq!(res.status, IkStatus::Ok);
        assert_verified(&res, true, 1e-10);
        let idx = match_sets(&r, &res, &refs, 1e-8);
        for (s, &i) in sols.iter().zip(&idx) {
            let label = s["label"].as_str().unwrap();
            let no_flip = label.ends_with("theta5 in (0, pi)");
            assert_eq!(
                res.solutions[i]
                    .posture
                    .to_string()
                    .ends_with("wrist no flip"),
                no_flip,
                "{label} vs {}",
                res.solutions[i].posture
            );
            assert_eq!(
                res.solutions[i]
                    .posture
                    .to_string()
                    .starts_with("shoulder right"),
                label.starts_with("th1_I,")
            );
        }
        assert!(
            res.solutions
                .iter()
                .any(|s| same_q(&r, &s.q, &vecf(&e["q_true"]), 1e-8))
        );
    }
}

#[test]
fn reference_puma560_with_config_letters_and_limits() {
    let r = robot("puma560");
    let data = reference("ik_puma560_analytic.json");
    for e in data["poses"].as_array().expect("poses") {
        let t = pose_of(&e["T"]);
        let sols = e["solutions"].as_array().unwrap();
        let refs: Vec<Vec<f64>> = sols.iter().map(|s| vecf(&s["q"])).collect();
        let res = solve(&r, Target::Pose(t));
        assert_eq!(res.status, IkStatus::Ok);
        assert_verified(&res, true, 1e-10);
        let idx = match_sets(&r, &res, &refs, 1e-8);
        for (s, &i) in sols.iter().zip(&idx) {
            let ours = &res.solutions[i];
            assert_eq!(
                ours.within_limits,
                s["within_limits_mod_2pi"].as_bool().unwrap(),
                "{}",
                show(&res)
            );
            let p = &ours.posture.to_string();
            let letters: String = [
                if p.contains("shoulder left") {
                    'l'
                } else {
                    'r'
                },
                if p.contains("elbow up") { 'u' } else { 'd' },
                if p.contains("wrist no flip") {
                    'n'
                } else {
                    'f'
                },
            ]
            .iter()
            .collect();
            assert_eq!(letters, s["config"].as_str().unwrap(), "{p}");
        }
        let n_lim = res.solutions.iter().filter(|s| s.within_limits).count();
        assert_eq!(
            n_lim as u64,
            e["n_distinct_within_limits_mod_2pi"].as_u64().unwrap()
        );
    }
}

#[test]
fn spherical_wrist_matches_the_zyz_functions() {
    // Table 2.5: theta4, theta5, theta6 are the ZYZ angles of R_6^3 (2.111)-(2.112).
    let r = robot("spherical_wrist");
    for q in [[0.3, 0.7, -1.2], [2.5, -2.0, 0.4], [-1.0, 3.0, 3.0]] {
        let t = r.fk(&q).unwrap();
        let res = solve(&r, Target::Pose(t));
        assert_eq!(res.solutions.len(), 2);
        let pos = zyz_from_rotation(&t.rotation).angles;
        let neg = zyz_from_rotation_negative(&t.rotation).angles;
        assert_eq!(res.solutions[0].posture.to_string(), "wrist no flip");
        assert_eq!(res.solutions[1].posture.to_string(), "wrist flip");
        assert!(same_q(&r, &res.solutions[0].q, pos.as_slice(), 1e-12));
        assert!(same_q(&r, &res.solutions[1].q, neg.as_slice(), 1e-12));
        assert!(res.solutions[0].q[1] > 0.0 && res.solutions[1].q[1] < 0.0);
    }
}

// ---------------------------------------------------------------- degenerate cases

// ---------------------------------------------------------------- the allocation-free labelled call

#[test]
fn solve_into_matches_solve_and_an_independent_check() {
    use armlab::kinematics::ik::closed_form::{Solutions, Verify};
    let mut sols = Solutions::default();
    let mut labels_only = Solutions::default();
    for name in CLOSED_FORM {
        let r = robot(name);
        let c = cf(&r);
        let mut rng = 0x1234_5678_u64;
        for _ in 0..200 {
            let u: Vec<f64> = (0..r.dof())
                .map(|_| {
                    rng = rng
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    (rng >> 11) as f64 / (1u64 << 53) as f64
                })
                .collect();
            let q = q_in_limits(&r, &u);
            let pose = r.fk(&q).unwrap();
            let target = if position_only(c.family()) {
                Target::Position(pose.translation.vector)
            } else {
                Target::Pose(pose)
            };
            let old = c.solve(&r, &target).unwrap();
            c.solve_into(&r, &target, Verify::Fk, &mut sols).unwrap();
            c.solve_into(&r, &target, Verify::Limits, &mut labels_only)
                .unwrap();
            assert_eq!(sols.status, old.status, "{name}");
            assert_eq!(sols.len(), old.solutions.len(), "{name}");
            assert_eq!(labels_only.len(), sols.len(), "{name}");
            for ((s, o), l) in sols.iter().zip(&old.solutions).zip(&labels_only) {
                assert_eq!(s.q(), o.q.as_slice(), "{name}");
                assert_eq!(s.posture.to_string(), o.posture.to_string(), "{name}");
                assert_eq!(s.within_limits, o.within_limits, "{name}");
                assert_eq!(l.q(), s.q(), "{name}");
                assert!(l.errors.is_none(), "{name}: Limits does not verify");
                // The errors against an FK and an angle computed here, independently.
                let e = s.errors.expect("verified");
                let t = r.fk(s.q()).unwrap();
                let dp = match target {
                    Target::Pose(p) => (t.translation.vector - p.translation.vector).norm(),
                    Target::Position(p) => (t.translation.vector - p).norm(),
                    Target::Planar { .. } => unreachable!(),
                };
                assert!(
                    (e.position - dp).abs() < 1e-15,
                    "{name}: {} vs {dp}",
                    e.position
                );
                if let Target::Pose(p) = target {
                    let m = t.rotation.matrix().transpose() * p.rotation.matrix();
                    let angle = ((m.trace() - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
                    // acos loses half the digits near 0: compare to 1e-7.
                    assert!((e.orientation - angle).abs() < 1e-7, "{name}");
                }
                assert!(e.position < 1e-9, "{name}: {e:?}");
                assert_eq!(
                    s.within_limits,
                    r.within_limits(s.q(), armlab::kinematics::ik::closed_form::LIMIT_TOL),
                    "{name}"
                );
            }
        }
    }
}

#[test]
fn posture_labels_are_the_documented_text() {
    use armlab::kinematics::ik::closed_form::{Elbow, Posture, Shoulder, WristFlip};
    let p = Posture {
        shoulder: Some(Shoulder::Right),
        elbow: Some(Elbow::Up),
        wrist: Some(WristFlip::NoFlip),
        ..Posture::default()
    };
    assert_eq!(p.to_string(), "shoulder right, elbow up, wrist no flip");
    assert_eq!(p.label(), p.to_string());
    assert_eq!(Posture::default().to_string(), "");
    let q = Posture {
        elbow: Some(Elbow::Down),
        ..Posture::default()
    };
    assert_eq!(format!("{q}"), "elbow down");
}

#[test]
fn wrapping_into_limits_picks_the_shift_nearest_to_zero() {
    // Against a brute-force search over shifts written here.
    let tol = armlab::kinematics::ik::closed_form::LIMIT_TOL;
    let reference = |q: f64, lo: f64, hi: f64| -> f64 {
        let w = wrap_angle(q);
        (-20..=20)
            .map(|k| w + k as f64 * 2.0 * PI)
            .filter(|c| *c >= lo - tol && *c <= hi + tol)
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(w)
    };
    let mut rng = 99u64;
    let mut next = || {
        rng = rng
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..20_000 {
        let q = (next() - 0.5) * 40.0;
        let lo = (next() - 0.7) * 20.0;
        let hi = lo + next() * 15.0;
        let got = wrap_into_limits(q, [lo, hi]);
        let want = reference(q, lo, hi);
        assert!(
            (got - want).abs() < 1e-12,
            "q {q}, [{lo}, {hi}]: {got} vs {want}"
        );
    }
    // Open sides.
    assert_eq!(
        wrap_into_limits(7.0, [f64::NEG_INFINITY, f64::INFINITY]),
        wrap_angle(7.0)
    );
    assert!((wrap_into_limits(-3.0, [0.0, f64::INFINITY]) - (-3.0 + 2.0 * PI)).abs() < 1e-15);
}

/// Issue 45: a solution's posture is data, and its `Display` is the label text it always had.
/// Every family's postures, built from their fields, print as the labels written out here.
#[test]
fn posture_labels_of_every_family_are_the_text_written_here() {
    use armlab::kinematics::ik::SolutionPosture;
    use armlab::kinematics::ik::closed_form::{
        Elbow, Extension, FreeReason, Posture, Shoulder, WristFlip,
    };
    let p = Posture::default;
    let cases: Vec<(Posture, &str)> = vec![
        // Planar arms and the SCARA.
        (
            Posture {
                elbow: Some(Elbow::Down),
                ..p()
            },
            "elbow down",
        ),
        (
            Posture {
                elbow: Some(Elbow::Folded),
                ..p()
            },
            "elbow folded",
        ),
        // Anthropomorphic arm.
        (
            Posture {
                shoulder: Some(Shoulder::Left),
                elbow: Some(Elbow::Up),
                ..p()
            },
            "shoulder left, elbow up",
        ),
        (
            Posture {
                shoulder: Some(Shoulder::OnAxis),
                elbow: Some(Elbow::Stretched),
                free: [Some(FreeReason::ShoulderAxis), None, None, None, None, None],
                ..p()
            },
            "shoulder on axis, elbow stretched",
        ),
        // Spherical and cylindrical arms.
        (
            Posture {
                shoulder: Some(Shoulder::Right),
                extension: Some(Extension::Reversed),
                ..p()
            },
            "shoulder right, extension reversed",
        ),
        (
            Posture {
                extension: Some(Extension::Zero),
                ..p()
            },
            "extension zero",
        ),
        // The wrist alone.
        (
            Posture {
                wrist: Some(WristFlip::Flip),
                ..p()
            },
            "wrist flip",
        ),
        // Six joints with a spherical wrist (Puma 560, Stanford arm).
        (
            Posture {
                shoulder: Some(Shoulder::Right),
                elbow: Some(Elbow::Up),
                wrist: Some(WristFlip::NoFlip),
                ..p()
            },
            "shoulder right, elbow up, wrist no flip",
        ),
        (
            Posture {
                shoulder: Some(Shoulder::Boundary),
                extension: Some(Extension::Forward),
                wrist: Some(WristFlip::Singular),
                ..p()
            },
            "shoulder boundary, extension forward, wrist singular",
        ),
        // Three parallel axes (UR).
        (
            Posture {
                shoulder: Some(Shoulder::Left),
                elbow: Some(Elbow::Down),
                wrist: Some(WristFlip::Up),
                ..p()
            },
            "shoulder left, elbow down, wrist up",
        ),
        // The chain read from the tool.
        (
            Posture {
                shoulder: Some(Shoulder::Right),
                elbow: Some(Elbow::Down),
                wrist: Some(WristFlip::Down),
                reversed: true,
                ..p()
            },
            "tool shoulder right, elbow down, base wrist down",
        ),
        // General six-revolute arm, Pieper's general case, general three-parallel arm.
        (
            Posture {
                branch: Some(7),
                ..p()
            },
            "branch 7",
        ),
        (
            Posture {
                branch: Some(17),
                ..p()
            },
            "branch 17",
        ),
        (
            Posture {
                wrist: Some(WristFlip::Flip),
                branch: Some(3),
                ..p()
            },
            "wrist flip, branch 3",
        ),
        (
            Posture {
                elbow: Some(Elbow::Up),
                branch: Some(2),
                ..p()
            },
            "elbow up, branch 2",
        ),
    ];
    for (posture, label) in cases {
        assert_eq!(posture.to_string(), label);
        assert_eq!(SolutionPosture::ClosedForm(posture).to_string(), label);
        // A width pads the label as it pads a string.
        assert_eq!(format!("{:<60}|", posture), format!("{label:<60}|"));
    }
    assert_eq!(
        SolutionPosture::Numerical { converged: true }.to_string(),
        "numerical"
    );
    assert_eq!(
        SolutionPosture::Numerical { converged: false }.to_string(),
        "numerical (not converged)"
    );
    // And the solvers' own solutions print so: the Puma 560 at a generic pose has the eight
    // labels of shoulder x elbow x wrist.
    let r = robot("puma560");
    let c = ClosedForm::detect(&r).unwrap();
    let t = r.fk(&[0.3, 0.5, -1.2, 0.4, 0.8, -0.6]).unwrap();
    let mut labels: Vec<String> = c
        .solve(&r, &Target::Pose(t))
        .unwrap()
        .solutions
        .iter()
        .map(|s| s.posture.to_string())
        .collect();
    labels.sort();
    let mut want = Vec::new();
    for s in ["left", "right"] {
        for e in ["down", "up"] {
            for w in ["flip", "no flip"] {
                want.push(format!("shoulder {s}, elbow {e}, wrist {w}"));
            }
        }
    }
    assert_eq!(labels, want);
}

/// Nothing in `src/` reads a posture label back (issue 45): the label parsers are gone and no
/// code splits or searches a posture's text; colours, locks, legends and branch numbers read
/// the fields.
#[test]
fn no_posture_label_is_parsed_in_src() {
    fn rust_files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let path = e.unwrap().path();
            if path.is_dir() {
                rust_files(&path, out);
            } else if path.extension().is_some_and(|x| x == "rs") {
                out.push(path);
            }
        }
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    rust_files(&root.join("python/src"), &mut files);
    assert!(files.len() > 50, "{} files", files.len());
    let banned = [
        "fn branch_number(",
        "fn other_parts(",
        "fn with_number(",
        "fn class_of_label(",
        "fn is_degenerate_label(",
        "fn short_label(",
        "posture.split(",
        "posture.contains(",
        "posture.starts_with(",
        "posture.ends_with(",
        "BRANCH_LABELS",
    ];
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for b in banned {
            assert!(!text.contains(b), "{} has {b:?}", f.display());
        }
    }
}
