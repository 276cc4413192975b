//! Closed-form inverse kinematics (Sect. 2.12) at its degenerate cases: shoulder, elbow and
//! wrist singularities (free joints reported), targets just outside or on the workspace
//! boundary (how far out, no NaN), and targets that are not finite or of the wrong kind.

use crate::common;

use common::closed_form::*;

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
            .all(|s| s.posture.to_string().starts_with("shoulder on axis"))
    );
    let mut elbows: Vec<&str> = res
        .solutions
        .iter()
        .map(|s| s.posture.closed_form().unwrap().elbow_label().unwrap())
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
            .all(|s| s.posture.to_string().ends_with("elbow stretched"))
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
    assert_eq!(res.solutions[0].posture.to_string(), "elbow stretched");
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
    assert_eq!(res.solutions[0].posture.to_string(), "elbow folded");
    assert_verified(&res, false, 1e-12);
}

#[test]
fn next_to_the_base_the_folded_pair_stays_two_exact_solutions() {
    // Regression (CI, stop 43): a target 2e-8 m from the base of planar2 (a1 = a2 = 1) has
    // 1 + c2 = 2e-16, within COS_TOL of the folded elbow, but its two solutions differ by about
    // pi in theta1. They were merged into theta2 = pi, theta1 = 0, which missed by 2e-8 m.
    let r = robot("planar2");
    for (dist, angle) in [(2.2e-8, 0.7), (1e-6, -2.0), (3e-10, 2.9)] {
        // theta2 = pi - delta puts the tip at 2 sin(delta/2) from the base.
        let delta = 2.0 * (dist / 2.0f64).asin();
        // The tip e^{i t1} (1 + e^{i (pi - delta)}) lies at the angle t1 + (pi - delta) / 2.
        let t1 = angle - (PI - delta) / 2.0;
        let q = [t1, PI - delta];
        let t = r.fk(&q).unwrap();
        let p = t.translation.vector;
        assert!((p.norm() - dist).abs() < 1e-15, "{}", p.norm());
        let res = solve(&r, Target::Position(p));
        assert_eq!(res.status, IkStatus::Ok, "{dist}: {}", show(&res));
        assert_eq!(res.solutions.len(), 2, "{}", show(&res));
        assert_verified(&res, false, 1e-15);
        assert!(
            res.solutions.iter().any(|s| same_q(&r, &s.q, &q, 1e-7)),
            "{q:?}\n{}",
            show(&res)
        );
    }
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
            .filter(|s| s.posture.to_string().ends_with("wrist singular"))
            .count();
        assert!(singular >= 1);
        assert_eq!(res.solutions.len(), generic - singular, "{}", show(&res));
        for s in &res.solutions {
            let idx: Vec<usize> = s.free_joints.iter().map(|f| f.index).collect();
            let expected: &[usize] = if s.posture.to_string().ends_with("wrist singular") {
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
    assert!(s.posture.to_string().contains("extension zero"));
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
            .all(|s| s.posture.to_string().starts_with("shoulder boundary"))
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
            Err(
                e @ (IkError::TargetKind { .. }
                | IkError::OffPlane { .. }
                | IkError::TiltedOutOfPlane { .. }),
            ) => assert!(e.to_string().contains("target")),
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
        Err(IkError::OtherRobot { .. })
    ));
}
