//! Closed-form inverse kinematics (Sect. 2.12): round trips FK(IK(x)) = x for every built-in with a
//! closed form, the reference data reproduced as sets modulo 2 pi, every degenerate case, targets
//! outside the workspace, bad targets, user-made arms of the same families, and the raw path.
//!
//! Solution counts implemented (generic targets, built-in limits): 2 for planar2, planar3, SCARA
//! and the spherical wrist; 4 for anthropomorphic3r; 2 for the spherical arm (d3 >= 0, the mirror
//! d3 < 0 is outside the limits); 1 for the cylindrical arm; 8 for the Puma 560 and the
//! anthropomorphic arm with spherical wrist; 4 for the Stanford manipulator (2 arm x 2 wrist).

use armlab::kinematics::dh::standard_to_modified;
use armlab::kinematics::ik::closed_form::{
    ArmKind, ClosedForm, Family, MAX_SOLUTIONS, RawSolutions, wrap_into_limits,
};
use armlab::kinematics::ik::{IkError, IkResult, IkStatus, Target};
use armlab::kinematics::models::built_in;
use armlab::kinematics::orientation::{wrap_angle, zyz_from_rotation, zyz_from_rotation_negative};
use armlab::kinematics::pose::{matrix_from_rows, pose_from_matrix, rot_x, rot_y, rot_z};
use armlab::kinematics::{Convention, DhRow, JointKind, Pose, Robot};
use nalgebra::{Translation3, Vector3};
use proptest::prelude::*;
use serde_json::Value;
use std::f64::consts::{FRAC_PI_2, PI};

const CLOSED_FORM: [&str; 10] = [
    "planar2",
    "planar3",
    "spherical_arm",
    "anthropomorphic3r",
    "spherical_wrist",
    "stanford",
    "anthropomorphic_spherical_wrist",
    "scara",
    "cylindrical",
    "puma560",
];

// ---------------------------------------------------------------- helpers

fn robot(name: &str) -> Robot {
    built_in(name).unwrap_or_else(|| panic!("built-in {name}"))
}

fn cf(robot: &Robot) -> ClosedForm {
    ClosedForm::detect(robot).unwrap_or_else(|| panic!("{}: no closed form", robot.name))
}

/// Same configuration modulo 2 pi for revolute joints.
fn same_q(robot: &Robot, a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len()
        && (0..a.len()).all(|j| {
            let d = a[j] - b[j];
            let d = if robot.dof_joint(j).kind == JointKind::Revolute {
                wrap_angle(d)
            } else {
                d
            };
            d.abs() < tol
        })
}

fn show(res: &IkResult) -> String {
    let mut s = format!("status {:?}\n", res.status);
    for x in &res.solutions {
        s += &format!(
            "  {:?} [{}] within={} pe={:.1e} oe={:.1e} free={:?}\n",
            x.q, x.posture, x.within_limits, x.position_error, x.orientation_error, x.free_joints
        );
    }
    s
}

fn solve(robot: &Robot, target: Target) -> IkResult {
    cf(robot).solve(robot, &target).expect("valid target")
}

/// Every solution reaches the target (position, and orientation when `orient`).
fn assert_verified(res: &IkResult, orient: bool, tol: f64) {
    for s in &res.solutions {
        assert!(
            s.position_error < tol && (!orient || s.orientation_error < tol),
            "not verified:\n{}",
            show(res)
        );
        assert!(s.q.iter().all(|v| v.is_finite()));
    }
}

fn q_in_limits(robot: &Robot, u: &[f64]) -> Vec<f64> {
    robot
        .limits()
        .iter()
        .zip(u)
        .map(|(l, &t)| l[0] + t * (l[1] - l[0]))
        .collect()
}

fn position_only(f: &Family) -> bool {
    matches!(
        f,
        Family::Planar2 | Family::Anthropomorphic | Family::SphericalArm | Family::Cylindrical
    )
}

fn vecf(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

fn reference(name: &str) -> Value {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/reference")
        .join(name);
    serde_json::from_str(&std::fs::read_to_string(path).expect("reference file")).expect("JSON")
}

fn pose_of(v: &Value) -> Pose {
    let rows: Vec<Vec<f64>> = v.as_array().expect("rows").iter().map(vecf).collect();
    let mut m = [[0.0; 4]; 4];
    for (r, row) in rows.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            m[r][c] = *x;
        }
    }
    pose_from_matrix(&matrix_from_rows(&m)).expect("rigid")
}

/// The reference solutions and ours are the same sets modulo 2 pi; returns, for each reference
/// solution, the index of ours.
fn match_sets(robot: &Robot, ours: &IkResult, refs: &[Vec<f64>], tol: f64) -> Vec<usize> {
    assert_eq!(
        ours.solutions.len(),
        refs.len(),
        "counts differ:\n{}",
        show(ours)
    );
    refs.iter()
        .map(|r| {
            ours.solutions
                .iter()
                .position(|s| same_q(robot, &s.q, r, tol))
                .unwrap_or_else(|| panic!("reference {r:?} not found in\n{}", show(ours)))
        })
        .collect()
}

// ---------------------------------------------------------------- detection

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
    for name in ["parallelogram", "dlr", "humanoid", "lwr4", "panda"] {
        assert!(ClosedForm::detect(&robot(name)).is_none(), "{name}");
    }
}

#[test]
fn detection_ignores_the_name() {
    let mut r = robot("lwr4");
    r.name = "Puma 560".into();
    assert!(ClosedForm::detect(&r).is_none());
    let mut p = robot("puma560");
    p.name = "KUKA LWR-IV".into();
    assert!(ClosedForm::detect(&p).is_some());
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
                assert_eq!(ours.posture, expected, "{label}");
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
            assert_eq!(res.solutions[i].posture, expected);
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
            assert_eq!(res.solutions[i].posture, format!("{shoulder}, {elbow}"));
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
                    s.posture.contains("elbow up"),
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
                res.solutions[i].posture.ends_with("wrist no flip"),
                no_flip,
                "{label} vs {}",
                res.solutions[i].posture
            );
            assert_eq!(
                res.solutions[i].posture.starts_with("shoulder right"),
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
            let p = &ours.posture;
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
        assert_eq!(res.solutions[0].posture, "wrist no flip");
        assert_eq!(res.solutions[1].posture, "wrist flip");
        assert!(same_q(&r, &res.solutions[0].q, pos.as_slice(), 1e-12));
        assert!(same_q(&r, &res.solutions[1].q, neg.as_slice(), 1e-12));
        assert!(res.solutions[0].q[1] > 0.0 && res.solutions[1].q[1] < 0.0);
    }
}

// ---------------------------------------------------------------- degenerate cases

fn assert_singular(res: &IkResult, n: usize, free: &[usize]) {
    assert_eq!(res.status, IkStatus::Singular, "{}", show(res));
    assert_eq!(res.solutions.len(), n, "{}", show(res));
    for s in &res.solutions {
        let idx: Vec<usize> = s.free_joints.iter().map(|f| f.index).collect();
        assert_eq!(idx, free, "{}", show(res));
        assert!(s.free_joints.iter().all(|f| !f.reason.is_empty()));
    }
}

#[test]
fn shoulder_singularity_theta1_free() {
    // p_Wx = p_Wy = 0 (Sect. 2.12.4, Problem 2.18): theta1 free, theta2 and theta3 determined.
    let r = robot("anthropomorphic3r");
    let res = solve(&r, Target::Position(Vector3::new(0.0, 0.0, 1.2)));
    assert_singular(&res, 2, &[0]);
    assert_verified(&res, false, 1e-12);
    assert!(
        res.solutions
            .iter()
            .all(|s| s.posture.starts_with("shoulder on axis"))
    );
    let mut elbows: Vec<&str> = res
        .solutions
        .iter()
        .map(|s| s.posture.rsplit(", ").next().unwrap())
        .collect();
    elbows.sort();
    assert_eq!(elbows, ["elbow down", "elbow up"]);
    // Any theta1 works: the family really is free.
    for s in &res.solutions {
        let mut q = s.q.clone();
        q[0] = 1.234;
        let p = r.fk(&q).unwrap().translation.vector;
        assert!((p - Vector3::new(0.0, 0.0, 1.2)).norm() < 1e-12);
    }

    // The same with the spherical wrist: wrist point on z0, 2 elbows x 2 wrists.
    let r = robot("anthropomorphic_spherical_wrist");
    let rot = rot_z(0.4) * rot_y(1.1) * rot_z(-0.3);
    let pw = Vector3::new(0.0, 0.0, 0.6);
    let pe = pw + rot.rotation * Vector3::new(0.0, 0.0, 0.1);
    let t = Pose::from_parts(Translation3::from(pe), rot.rotation);
    let res = solve(&r, Target::Pose(t));
    assert_singular(&res, 4, &[0]);
    assert_verified(&res, true, 1e-10);
}

#[test]
fn elbow_stretched_merges_the_pair() {
    // s3 = 0: the elbow up/down pair merges; nothing is free.
    let r = robot("anthropomorphic3r");
    let q = [0.3, 0.4, 0.0];
    let res = solve(&r, Target::Position(r.fk(&q).unwrap().translation.vector));
    assert_singular(&res, 2, &[]);
    assert_verified(&res, false, 1e-12);
    assert!(
        res.solutions
            .iter()
            .all(|s| s.posture.ends_with("elbow stretched"))
    );
    assert!(res.solutions.iter().any(|s| same_q(&r, &s.q, &q, 1e-6)));

    // Anthropomorphic arm with spherical wrist: stretched when theta3 = pi/2.
    let r = robot("anthropomorphic_spherical_wrist");
    let q = [0.3, 0.4, FRAC_PI_2, 0.5, 0.6, 0.7];
    let res = solve(&r, Target::Pose(r.fk(&q).unwrap()));
    assert_singular(&res, 4, &[]);
    assert_verified(&res, true, 1e-10);
    assert!(res.solutions.iter().any(|s| same_q(&r, &s.q, &q, 1e-5)));

    // Planar arms: stretched and folded.
    let r = robot("planar2");
    let res = solve(
        &r,
        Target::Position(Vector3::new(2.0 * 0.3f64.cos(), 2.0 * 0.3f64.sin(), 0.0)),
    );
    assert_singular(&res, 1, &[]);
    assert_eq!(res.solutions[0].posture, "elbow stretched");
    assert!(same_q(&r, &res.solutions[0].q, &[0.3, 0.0], 1e-6));
    let r = robot("planar3");
    let q = [0.2, 0.0, 0.5];
    let t = r.fk(&q).unwrap();
    let res = solve(&r, Target::Pose(t));
    assert_singular(&res, 1, &[]);
    assert_verified(&res, true, 1e-12);
}

#[test]
fn planar_target_at_the_base_theta1_free() {
    // a1 = a2 and p_W = 0: theta1 cannot be determined (Sect. 2.12.1).
    let r = robot("planar2");
    let res = solve(&r, Target::Position(Vector3::zeros()));
    assert_singular(&res, 1, &[0]);
    assert_eq!(res.solutions[0].posture, "elbow folded");
    assert_verified(&res, false, 1e-12);
}

#[test]
fn wrist_singularity_only_the_sum_is_determined() {
    for name in ["anthropomorphic_spherical_wrist", "puma560", "stanford"] {
        let r = robot(name);
        let q = [0.2, 0.5, 0.3, 0.7, 0.0, -0.4];
        let q = if name == "stanford" {
            [0.2, 0.5, 0.6, 0.7, 0.0, -0.4]
        } else {
            q
        };
        let res = solve(&r, Target::Pose(r.fk(&q).unwrap()));
        // The wrist is singular for the arm solutions whose z3 is along the approach axis (the
        // arm of q); the other arm solutions keep their two wrist solutions.
        assert_eq!(res.status, IkStatus::Singular, "{}", show(&res));
        assert_verified(&res, true, 1e-10);
        let generic = cf(&r).family().generic_solution_count();
        let singular = res
            .solutions
            .iter()
            .filter(|s| s.posture.ends_with("wrist singular"))
            .count();
        assert!(singular >= 1);
        assert_eq!(res.solutions.len(), generic - singular, "{}", show(&res));
        for s in &res.solutions {
            let idx: Vec<usize> = s.free_joints.iter().map(|f| f.index).collect();
            let expected: &[usize] = if s.posture.ends_with("wrist singular") {
                &[3]
            } else {
                &[]
            };
            assert_eq!(idx, expected);
        }
        // The solution with the same arm: theta4 + theta6 (or theta4 - theta6) preserved.
        let own = res
            .solutions
            .iter()
            .find(|s| same_q(&r, &s.q[..3], &q[..3], 1e-7))
            .unwrap_or_else(|| panic!("{name}\n{}", show(&res)));
        assert!(own.q[4].abs() < 1e-9 || (own.q[4].abs() - PI).abs() < 1e-9);
        let sum = wrap_angle(own.q[3] + own.q[5] - (q[3] + q[5]));
        let diff = wrap_angle(own.q[3] - own.q[5] - (q[3] - q[5]));
        assert!(
            sum.abs() < 1e-9 || diff.abs() < 1e-9,
            "{name}\n{}",
            show(&res)
        );
    }
    // The wrist alone.
    let r = robot("spherical_wrist");
    let res = solve(&r, Target::Pose(r.fk(&[0.4, 0.0, 0.9]).unwrap()));
    assert_singular(&res, 1, &[0]);
    assert_verified(&res, true, 1e-12);
}

#[test]
fn spherical_arm_zero_extension_theta2_free() {
    // d3 = 0 (Sect. 2.12.3: "if d3 = 0, theta2 cannot be uniquely determined"): the point is on
    // the circle of radius d2 in the plane z = 0; the solution lies outside the limits of d3.
    let r = robot("spherical_arm");
    let th1: f64 = 0.3;
    let p = Vector3::new(-0.5 * th1.sin(), 0.5 * th1.cos(), 0.0);
    let res = solve(&r, Target::Position(p));
    assert_singular(&res, 1, &[1]);
    assert_verified(&res, false, 1e-12);
    let s = &res.solutions[0];
    assert!(!s.within_limits);
    assert!(s.q[2].abs() < 1e-12 && wrap_angle(s.q[0] - th1).abs() < 1e-12);
    assert!(s.posture.contains("extension zero"));
}

#[test]
fn cylindrical_on_axis_theta1_free() {
    let r = robot("cylindrical");
    let res = solve(&r, Target::Position(Vector3::new(0.0, 0.0, 0.9)));
    assert_singular(&res, 1, &[0]);
    assert_verified(&res, false, 1e-12);
    assert!(!res.solutions[0].within_limits);
}

#[test]
fn lateral_offset_boundary_merges_the_shoulder() {
    // Stanford arm: wrist point on the cylinder of radius d2 = 0.154 m: both theta1 coincide.
    let r = robot("stanford");
    let rot = rot_x(0.7) * rot_z(0.2);
    let pw = Vector3::new(0.154 * 0.5f64.cos(), 0.154 * 0.5f64.sin(), 0.6);
    let pe = pw + rot.rotation * Vector3::new(0.0, 0.0, 0.263);
    let res = solve(
        &r,
        Target::Pose(Pose::from_parts(Translation3::from(pe), rot.rotation)),
    );
    assert_eq!(res.status, IkStatus::Singular, "{}", show(&res));
    assert_eq!(res.solutions.len(), 2);
    assert!(
        res.solutions
            .iter()
            .all(|s| s.posture.starts_with("shoulder boundary"))
    );
    assert_verified(&res, true, 1e-10);
}

// ---------------------------------------------------------------- unreachable targets

fn unreachable_distance(res: &IkResult) -> f64 {
    assert!(res.solutions.is_empty());
    match res.status {
        IkStatus::Unreachable { distance } => distance,
        s => panic!("expected unreachable, got {s:?}\n{}", show(res)),
    }
}

#[test]
fn just_outside_the_workspace() {
    for delta in [1e-6, 0.1] {
        // Anthropomorphic arm: |p_W| - (a2 + a3).
        let r = robot("anthropomorphic3r");
        let dir = Vector3::new(0.3, -0.5, 0.4).normalize();
        let res = solve(&r, Target::Position(dir * (2.0 + delta)));
        assert!((unreachable_distance(&res) - delta).abs() < 1e-12);

        // Two-link planar arm: gap to the annulus, outside and inside (a1 = 1, a2 = 0.5).
        let r = robot("planar2");
        let res = solve(&r, Target::Position(Vector3::new(0.0, -(2.0 + delta), 0.0)));
        assert!((unreachable_distance(&res) - delta).abs() < 1e-12);
        let r = planar2_custom(1.0, 0.5, Pose::identity(), Pose::identity());
        let res = solve(&r, Target::Position(Vector3::new(0.5 - delta, 0.0, 0.0)));
        assert!((unreachable_distance(&res) - delta).abs() < 1e-12);

        // Three-link planar arm: wrist point p - a3 (cos phi, sin phi) out of reach.
        let r = robot("planar3");
        let res = solve(
            &r,
            Target::Planar {
                px: 1.0 + delta,
                py: 0.0,
                phi: 0.0,
            },
        );
        assert!((unreachable_distance(&res) - delta).abs() < 1e-12);

        // Anthropomorphic arm with spherical wrist: |p_W| = a2 + d4 + delta.
        let r = robot("anthropomorphic_spherical_wrist");
        let pw = Vector3::new(0.2, 0.7, -0.3).normalize() * (1.0 + delta);
        let rot = rot_y(0.3);
        let pe = pw + rot.rotation * Vector3::new(0.0, 0.0, 0.1);
        let res = solve(
            &r,
            Target::Pose(Pose::from_parts(Translation3::from(pe), rot.rotation)),
        );
        assert!((unreachable_distance(&res) - delta).abs() < 1e-12);

        // Puma 560: in the plane of the arm (frame 1), past a2 + sqrt(a3^2 + d4^2).
        let r = robot("puma560");
        let (d1, h, a2, a3, d4): (f64, f64, f64, f64, f64) =
            (0.67183, 0.15005, 0.4318, 0.0203, 0.4318);
        let reach = a2 + a3.hypot(d4) + delta;
        let g: f64 = 0.4;
        let (big_r, y1) = (reach * g.cos(), reach * g.sin());
        let rxy = big_r.hypot(h);
        let pw = Vector3::new(rxy * 0.7f64.cos(), rxy * 0.7f64.sin(), d1 + y1);
        let res = solve(
            &r,
            Target::Pose(Pose::from_parts(
                Translation3::from(pw),
                rot_x(0.3).rotation,
            )),
        );
        assert!((unreachable_distance(&res) - delta).abs() < 1e-9, "{delta}");

        // Spherical arm: inside the cylinder of radius d2 = 0.5.
        let r = robot("spherical_arm");
        let res = solve(&r, Target::Position(Vector3::new(0.0, 0.5 - delta, 0.3)));
        assert!((unreachable_distance(&res) - delta).abs() < 1e-12);
    }
    // Puma 560: wrist point on the axis of joint 1 is inside the shoulder-offset cylinder.
    let r = robot("puma560");
    let res = solve(&r, Target::Pose(Pose::translation(0.0, 0.0, 1.0)));
    assert!((unreachable_distance(&res) - 0.15005).abs() < 1e-12);
    // SCARA: an orientation it cannot take, distance = tilt angle (rad).
    let r = robot("scara");
    let t = r.fk(&[0.3, 0.5, 0.1, 0.2]).unwrap() * rot_x(0.1);
    let res = solve(&r, Target::Pose(t));
    assert!((unreachable_distance(&res) - 0.1).abs() < 1e-12);
}

#[test]
fn on_the_boundary_is_reachable() {
    // Exactly at full stretch (within rounding) is singular, not unreachable.
    let r = robot("anthropomorphic3r");
    let dir = Vector3::new(0.3, -0.5, 0.4).normalize();
    let res = solve(&r, Target::Position(dir * 2.0));
    assert_eq!(res.status, IkStatus::Singular);
    assert_verified(&res, false, 1e-12);
}

// ---------------------------------------------------------------- bad targets

#[test]
fn non_finite_targets_are_errors() {
    for name in CLOSED_FORM {
        let r = robot(name);
        let c = cf(&r);
        let bad = [
            Target::Position(Vector3::new(f64::NAN, 0.0, 0.0)),
            Target::Pose(Pose::translation(0.0, f64::INFINITY, 0.0)),
            Target::Planar {
                px: 0.1,
                py: 0.2,
                phi: f64::NAN,
            },
        ];
        for t in bad {
            assert_eq!(c.solve(&r, &t), Err(IkError::NonFiniteTarget), "{name}");
        }
    }
}

#[test]
fn wrong_target_kinds_are_errors() {
    let kind_err = |name: &str, t: Target| {
        let r = robot(name);
        match cf(&r).solve(&r, &t) {
            Err(IkError::TargetKind(msg)) => assert!(!msg.is_empty()),
            other => panic!("{name}: expected TargetKind, got {other:?}"),
        }
    };
    let p = Vector3::new(0.3, 0.2, 0.1);
    kind_err("planar3", Target::Position(Vector3::new(0.5, 0.2, 0.0)));
    kind_err("planar2", Target::Position(Vector3::new(0.5, 0.2, 1e-3)));
    kind_err(
        "planar3",
        Target::Pose(rot_x(0.2) * Pose::translation(0.5, 0.2, 0.0)),
    );
    kind_err("puma560", Target::Position(p));
    kind_err("stanford", Target::Position(p));
    kind_err("spherical_wrist", Target::Position(p));
    kind_err("scara", Target::Position(p));
    kind_err(
        "scara",
        Target::Planar {
            px: 0.3,
            py: 0.2,
            phi: 0.1,
        },
    );
    kind_err(
        "anthropomorphic3r",
        Target::Planar {
            px: 0.3,
            py: 0.2,
            phi: 0.1,
        },
    );
    // Within 1e-9 of the plane is accepted.
    let r = robot("planar2");
    let res = solve(&r, Target::Position(Vector3::new(0.5, 0.2, 1e-12)));
    assert_eq!(res.status, IkStatus::Ok);
    // A robot that does not match.
    let c = cf(&robot("puma560"));
    assert!(matches!(
        c.solve(&robot("planar2"), &Target::Position(p)),
        Err(IkError::NoClosedForm(_))
    ));
}

// ---------------------------------------------------------------- user-made arms

type Row = (JointKind, DhRow, f64, [f64; 2]);
const R: JointKind = JointKind::Revolute;
const P: JointKind = JointKind::Prismatic;
const FULL: [f64; 2] = [-PI, PI];

fn rv(a: f64, alpha: f64, d: f64, offset: f64) -> Row {
    (R, DhRow::new(a, alpha, d, 0.0), offset, FULL)
}

fn planar2_custom(a1: f64, a2: f64, base: Pose, tool: Pose) -> Robot {
    Robot::from_dh(
        "my planar",
        Convention::Standard,
        &[rv(a1, 0.0, 0.0, 0.2), rv(a2, 0.0, 0.0, -0.5)],
        base,
        tool,
    )
    .expect("valid")
}

/// Random configurations inside the limits: FK, solve, every solution verified, q among them.
fn user_round_trip(r: &Robot, counts: &[usize], position: bool, seed: u64) {
    let c = cf(r);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    use rand::{Rng, SeedableRng};
    for _ in 0..300 {
        let q: Vec<f64> = r
            .limits()
            .iter()
            .map(|l| rng.random_range(l[0]..=l[1]))
            .collect();
        let t = r.fk(&q).unwrap();
        let target = if position {
            Target::Position(t.translation.vector)
        } else {
            Target::Pose(t)
        };
        let res = c.solve(r, &target).unwrap();
        assert_eq!(res.status, IkStatus::Ok, "{q:?}\n{}", show(&res));
        assert!(
            counts.contains(&res.solutions.len()),
            "{q:?}\n{}",
            show(&res)
        );
        assert_verified(&res, !position, 1e-10);
        assert!(
            res.solutions.iter().any(|s| same_q(r, &s.q, &q, 1e-6)),
            "{q:?}\n{}",
            show(&res)
        );
    }
}

fn base_pose() -> Pose {
    Pose::translation(0.3, -0.2, 0.5) * rot_z(0.7) * rot_x(0.2)
}

fn tool_pose() -> Pose {
    Pose::translation(0.01, 0.02, 0.15) * rot_y(0.3)
}

#[test]
fn user_anthropomorphic_with_wrist_base_tool_offsets() {
    let rows = [
        rv(0.0, FRAC_PI_2, 0.4, 0.1),
        rv(0.6, 0.0, 0.0, FRAC_PI_2),
        rv(0.1, 1.0, 0.05, 0.3),
        rv(0.0, -FRAC_PI_2, 0.55, 0.0),
        rv(0.0, FRAC_PI_2, 0.0, 0.2),
        rv(0.0, 0.0, 0.12, -0.4),
    ];
    let r = Robot::from_dh(
        "mine",
        Convention::Standard,
        &rows,
        base_pose(),
        tool_pose(),
    )
    .unwrap();
    assert_eq!(
        *cf(&r).family(),
        Family::Decoupled6 {
            arm: ArmKind::Anthropomorphic
        }
    );
    user_round_trip(&r, &[8], false, 1);
    // A shoulder offset a1: one shoulder branch may be out of reach.
    let mut rows2 = rows;
    rows2[0] = rv(0.15, -FRAC_PI_2, 0.4, 0.1);
    let r = Robot::from_dh(
        "mine2",
        Convention::Standard,
        &rows2,
        base_pose(),
        tool_pose(),
    )
    .unwrap();
    user_round_trip(&r, &[4, 8], false, 2);
}

#[test]
fn user_wrist_with_equal_twist_signs_and_a6() {
    // alpha4 = alpha5 = pi/2 (the Rx(pi) case of the general wrist), a6 and alpha6 non-zero.
    let rows = [
        rv(0.0, FRAC_PI_2, 0.3, 0.0),
        rv(0.5, PI, 0.0, 0.0),
        rv(0.0, -FRAC_PI_2, 0.0, 0.0),
        rv(0.0, FRAC_PI_2, 0.45, 0.0),
        rv(0.0, FRAC_PI_2, 0.0, 0.0),
        rv(0.03, 0.5, 0.1, 0.0),
    ];
    let r = Robot::from_dh(
        "twists",
        Convention::Standard,
        &rows,
        Pose::identity(),
        tool_pose(),
    )
    .unwrap();
    user_round_trip(&r, &[8], false, 3);
}

#[test]
fn puma_in_modified_dh_and_with_fixed_rows() {
    let std_robot = robot("puma560");
    let (conv, table) = std_robot.dh_table().unwrap();
    assert_eq!(conv, Convention::Standard);
    let rows: Vec<DhRow> = table.iter().map(|r| r.1).collect();
    let (mrows, extra) = standard_to_modified(&rows);
    let mtable: Vec<Row> = table
        .iter()
        .zip(&mrows)
        .zip(std_robot.limits())
        .map(|((t, m), l)| (t.0, *m, t.2, l))
        .collect();
    let m = Robot::from_dh(
        "craig puma",
        Convention::Modified,
        &mtable,
        Pose::identity(),
        extra,
    )
    .unwrap();
    assert_eq!(
        *cf(&m).family(),
        Family::Decoupled6 {
            arm: ArmKind::Anthropomorphic
        }
    );
    user_round_trip(&m, &[8], false, 4);
    // Same solutions as the standard table.
    let t = std_robot.fk(&[0.1, 0.2, -0.3, 0.4, 0.5, 0.6]).unwrap();
    let a = solve(&std_robot, Target::Pose(t));
    let b = solve(&m, Target::Pose(t));
    let refs: Vec<Vec<f64>> = a.solutions.iter().map(|s| s.q.clone()).collect();
    match_sets(&std_robot, &b, &refs, 1e-9);

    // A pedestal and a flange as fixed rows.
    let mut ftable = vec![(JointKind::Fixed, DhRow::new(0.0, 0.0, 0.1, 0.2), 0.0, FULL)];
    ftable.extend(
        table
            .iter()
            .zip(std_robot.limits())
            .map(|(t, l)| (t.0, t.1, t.2, l)),
    );
    ftable.push((JointKind::Fixed, DhRow::new(0.0, 0.0, 0.05, 0.0), 0.0, FULL));
    let f = Robot::from_dh(
        "pedestal puma",
        Convention::Standard,
        &ftable,
        base_pose(),
        tool_pose(),
    )
    .unwrap();
    user_round_trip(&f, &[8], false, 5);
}

#[test]
fn user_stanford_like_arm() {
    let rows = [
        rv(0.1, -FRAC_PI_2, 0.3, 0.2),
        rv(0.05, FRAC_PI_2, 0.2, -0.1),
        (P, DhRow::new(0.02, 0.0, 0.0, 0.3), 0.1, [0.3, 1.2]),
        rv(0.0, -FRAC_PI_2, 0.05, 0.0),
        rv(0.0, FRAC_PI_2, 0.0, 0.0),
        rv(0.0, 0.0, 0.2, 0.0),
    ];
    let r = Robot::from_dh(
        "stan",
        Convention::Standard,
        &rows,
        base_pose(),
        tool_pose(),
    )
    .unwrap();
    assert_eq!(
        *cf(&r).family(),
        Family::Decoupled6 {
            arm: ArmKind::Spherical
        }
    );
    user_round_trip(&r, &[2, 4], false, 6);
}

#[test]
fn user_planar_scara_and_positioning_arms() {
    // Two-link planar arm in a tilted base with a tool offset.
    let r = planar2_custom(
        0.7,
        0.4,
        Pose::translation(1.0, 2.0, 3.0) * rot_x(0.5) * rot_z(0.3),
        Pose::translation(0.1, 0.05, 0.2) * rot_z(0.4),
    );
    assert_eq!(*cf(&r).family(), Family::Planar2);
    user_round_trip(&r, &[2], true, 7);

    // SCARA with the flip on joint 1, offsets and a tool off the last axis.
    let rows = [
        rv(0.35, PI, 0.5, 0.1),
        rv(0.25, 0.0, 0.0, -0.2),
        (P, DhRow::new(0.0, 0.0, 0.0, 0.2), 0.05, [0.0, 0.3]),
        (
            R,
            DhRow::new(0.0, PI, 0.08, 0.0),
            0.3,
            [-2.0 * PI, 2.0 * PI],
        ),
    ];
    let r = Robot::from_dh(
        "scara",
        Convention::Standard,
        &rows,
        base_pose(),
        Pose::translation(0.05, 0.0, -0.02) * rot_z(0.3),
    )
    .unwrap();
    assert_eq!(*cf(&r).family(), Family::Scara);
    user_round_trip(&r, &[2], false, 8);

    // Anthropomorphic arm 3R with a tool offset (a lateral offset for the position).
    let rows = [
        rv(0.0, FRAC_PI_2, 0.3, 0.0),
        rv(0.8, 0.0, 0.0, 0.4),
        rv(0.6, 0.0, 0.0, -0.2),
    ];
    let r = Robot::from_dh(
        "a3r",
        Convention::Standard,
        &rows,
        base_pose(),
        Pose::translation(0.1, 0.05, 0.08),
    )
    .unwrap();
    assert_eq!(*cf(&r).family(), Family::Anthropomorphic);
    user_round_trip(&r, &[4], true, 9);

    // Cylindrical arm with offsets and twists.
    let rows = [
        rv(0.1, 0.0, 0.4, 0.2),
        (
            P,
            DhRow::new(0.05, -FRAC_PI_2, 0.0, FRAC_PI_2 + 0.2),
            0.1,
            [0.0, 0.8],
        ),
        (P, DhRow::new(0.02, 0.3, 0.0, 0.1), 0.0, [0.1, 0.9]),
    ];
    let r = Robot::from_dh("cyl", Convention::Standard, &rows, base_pose(), tool_pose()).unwrap();
    assert_eq!(*cf(&r).family(), Family::Cylindrical);
    user_round_trip(&r, &[1, 2], true, 10);
    // ... with alpha1 = pi.
    let rows = [
        rv(0.0, PI, 0.4, 0.0),
        (
            P,
            DhRow::new(0.0, FRAC_PI_2, 0.0, FRAC_PI_2),
            0.0,
            [0.0, 0.8],
        ),
        (P, DhRow::new(0.0, 0.0, 0.0, 0.0), 0.0, [0.2, 0.6]),
    ];
    let r = Robot::from_dh(
        "cyl2",
        Convention::Standard,
        &rows,
        base_pose(),
        tool_pose(),
    )
    .unwrap();
    assert_eq!(*cf(&r).family(), Family::Cylindrical);
    user_round_trip(&r, &[1], true, 12);

    // Spherical arm with alpha1 = +pi/2, alpha2 = -pi/2, offsets and a tool offset.
    let rows = [
        rv(0.05, FRAC_PI_2, 0.2, 0.3),
        rv(0.0, -FRAC_PI_2, 0.15, -0.2),
        (P, DhRow::new(0.0, 0.0, 0.0, 0.0), 0.05, [0.2, 1.0]),
    ];
    let r = Robot::from_dh(
        "sph2",
        Convention::Standard,
        &rows,
        base_pose(),
        Pose::translation(0.02, 0.01, 0.1),
    )
    .unwrap();
    assert_eq!(*cf(&r).family(), Family::SphericalArm);
    user_round_trip(&r, &[1, 2], true, 13);
}

#[test]
fn mirror_extension_returned_when_inside_the_limits() {
    // Spherical arm whose d3 may be negative: four solutions, two with the reversed extension.
    let rows = [
        rv(0.0, -FRAC_PI_2, 0.0, 0.0),
        rv(0.0, FRAC_PI_2, 0.5, 0.0),
        (P, DhRow::new(0.0, 0.0, 0.0, 0.0), 0.0, [-1.0, 1.0]),
    ];
    let r = Robot::from_dh(
        "sph",
        Convention::Standard,
        &rows,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    let res = solve(&r, Target::Position(Vector3::new(0.3, 0.7, 0.2)));
    assert_eq!(res.solutions.len(), 4, "{}", show(&res));
    assert_eq!(
        res.solutions
            .iter()
            .filter(|s| s.posture.contains("extension reversed"))
            .count(),
        2
    );
    assert_verified(&res, false, 1e-12);
    // The built-in (d3 in [0.25, 1]) keeps only d3 >= 0.
    let b = robot("spherical_arm");
    let res = solve(&b, Target::Position(Vector3::new(0.3, 0.7, 0.2)));
    assert_eq!(res.solutions.len(), 2);
    assert!(res.solutions.iter().all(|s| s.q[2] > 0.0));
}

#[test]
fn arms_without_a_family() {
    // a4 != 0: the wrist axes do not intersect.
    let rows = [
        rv(0.0, FRAC_PI_2, 0.3, 0.0),
        rv(0.5, 0.0, 0.0, 0.0),
        rv(0.0, FRAC_PI_2, 0.0, 0.0),
        rv(0.05, -FRAC_PI_2, 0.45, 0.0),
        rv(0.0, FRAC_PI_2, 0.0, 0.0),
        rv(0.0, 0.0, 0.1, 0.0),
    ];
    let r = Robot::from_dh(
        "no",
        Convention::Standard,
        &rows,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    assert!(ClosedForm::detect(&r).is_none());
    // Five joints.
    let r = Robot::from_dh(
        "five",
        Convention::Standard,
        &rows[..5],
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    assert!(ClosedForm::detect(&r).is_none());
    // A twist of 1 rad between joints 1 and 2 of a 3R arm.
    let r = Robot::from_dh(
        "odd",
        Convention::Standard,
        &[
            rv(0.0, 1.0, 0.3, 0.0),
            rv(0.5, 0.0, 0.0, 0.0),
            rv(0.4, 0.0, 0.0, 0.0),
        ],
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    assert!(ClosedForm::detect(&r).is_none());
}

// ---------------------------------------------------------------- raw path

#[test]
fn raw_path_gives_all_eight_puma_solutions() {
    let r = robot("puma560");
    let c = cf(&r);
    let mut out = RawSolutions::default();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    use rand::{Rng, SeedableRng};
    let poses: Vec<Pose> = (0..2000)
        .map(|_| {
            let q: Vec<f64> = r
                .limits()
                .iter()
                .map(|l| rng.random_range(l[0]..=l[1]))
                .collect();
            r.fk(&q).unwrap()
        })
        .collect();
    for t in &poses[..200] {
        let n = c.solve_raw(t, &mut out).unwrap();
        assert_eq!(n, MAX_SOLUTIONS);
        for (q, posture) in out.iter(6) {
            let fk = r.fk(q).unwrap();
            assert!((fk.translation.vector - t.translation.vector).norm() < 1e-10);
            assert!(!posture.label().is_empty());
        }
    }
    // Rough timing (debug profile; the benchmark measures the release build).
    let start = std::time::Instant::now();
    let mut total = 0;
    for t in &poses {
        total += c.solve_raw(std::hint::black_box(t), &mut out).unwrap();
    }
    let ns = start.elapsed().as_nanos() as f64 / poses.len() as f64;
    eprintln!("solve_raw puma560: {ns:.0} ns per pose (debug build), {total} solutions");
}

#[test]
fn absurd_targets_never_give_nan() {
    for name in CLOSED_FORM {
        let r = robot(name);
        let c = cf(&r);
        for p in [
            Vector3::new(1e200, 0.0, 0.0),
            Vector3::new(1e200, -1e200, 1e200),
            Vector3::new(0.0, 0.0, -1e300),
            Vector3::new(1e-300, 1e-300, 0.0),
        ] {
            for t in [
                Target::Position(p),
                Target::Pose(Pose::from_parts(Translation3::from(p), rot_x(0.3).rotation)),
                Target::Planar {
                    px: p.x,
                    py: p.y,
                    phi: 0.2,
                },
            ] {
                match c.solve(&r, &t) {
                    Err(IkError::TargetKind(_)) => {}
                    Err(e) => panic!("{name}: {e}"),
                    Ok(res) => {
                        if let IkStatus::Unreachable { distance } = res.status {
                            assert!(!distance.is_nan() && distance >= 0.0, "{name}");
                        }
                        for s in &res.solutions {
                            assert!(s.q.iter().all(|v| v.is_finite()), "{name}");
                            assert!(!s.position_error.is_nan() && !s.orientation_error.is_nan());
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn eight_distinct_labels_for_the_six_dof_arms() {
    for name in ["puma560", "anthropomorphic_spherical_wrist"] {
        let r = robot(name);
        let res = solve(
            &r,
            Target::Pose(r.fk(&[0.3, 0.2, -0.4, 0.5, 0.6, 0.7]).unwrap()),
        );
        let mut labels: Vec<&str> = res.solutions.iter().map(|s| s.posture.as_str()).collect();
        labels.sort();
        labels.dedup();
        assert_eq!(labels.len(), 8, "{}", show(&res));
        assert!(labels.contains(&"shoulder left, elbow down, wrist flip"));
    }
}
