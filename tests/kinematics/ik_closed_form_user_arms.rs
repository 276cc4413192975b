//! Closed-form inverse kinematics (Sect. 2.12) for arms a user makes (the same families with
//! base and tool offsets, modified DH, fixed rows, mirrored twists), arms that have no closed
//! form, and the allocation-free raw path.

use crate::common;

use common::closed_form::*;

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
        .map(|((t, m), l)| dj(t.0, *m, t.2, l))
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
    let mut ftable = vec![dj(
        JointKind::Fixed,
        DhRow {
            a: 0.0,
            alpha: 0.0,
            d: 0.1,
            theta: 0.2,
        },
        0.0,
        FULL,
    )];
    ftable.extend(
        table
            .iter()
            .zip(std_robot.limits())
            .map(|(t, l)| dj(t.0, t.1, t.2, l)),
    );
    ftable.push(dj(
        JointKind::Fixed,
        DhRow {
            a: 0.0,
            alpha: 0.0,
            d: 0.05,
            theta: 0.0,
        },
        0.0,
        FULL,
    ));
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
        dj(
            P,
            DhRow {
                a: 0.02,
                alpha: 0.0,
                d: 0.0,
                theta: 0.3,
            },
            0.1,
            [0.3, 1.2],
        ),
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
        dj(
            P,
            DhRow {
                a: 0.0,
                alpha: 0.0,
                d: 0.0,
                theta: 0.2,
            },
            0.05,
            [0.0, 0.3],
        ),
        dj(
            R,
            DhRow {
                a: 0.0,
                alpha: PI,
                d: 0.08,
                theta: 0.0,
            },
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
        dj(
            P,
            DhRow {
                a: 0.05,
                alpha: -FRAC_PI_2,
                d: 0.0,
                theta: FRAC_PI_2 + 0.2,
            },
            0.1,
            [0.0, 0.8],
        ),
        dj(
            P,
            DhRow {
                a: 0.02,
                alpha: 0.3,
                d: 0.0,
                theta: 0.1,
            },
            0.0,
            [0.1, 0.9],
        ),
    ];
    let r = Robot::from_dh("cyl", Convention::Standard, &rows, base_pose(), tool_pose()).unwrap();
    assert_eq!(*cf(&r).family(), Family::Cylindrical);
    user_round_trip(&r, &[1, 2], true, 10);
    // ... with alpha1 = pi.
    let rows = [
        rv(0.0, PI, 0.4, 0.0),
        dj(
            P,
            DhRow {
                a: 0.0,
                alpha: FRAC_PI_2,
                d: 0.0,
                theta: FRAC_PI_2,
            },
            0.0,
            [0.0, 0.8],
        ),
        dj(
            P,
            DhRow {
                a: 0.0,
                alpha: 0.0,
                d: 0.0,
                theta: 0.0,
            },
            0.0,
            [0.2, 0.6],
        ),
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
        dj(
            P,
            DhRow {
                a: 0.0,
                alpha: 0.0,
                d: 0.0,
                theta: 0.0,
            },
            0.05,
            [0.2, 1.0],
        ),
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
        dj(
            P,
            DhRow {
                a: 0.0,
                alpha: 0.0,
                d: 0.0,
                theta: 0.0,
            },
            0.0,
            [-1.0, 1.0],
        ),
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
            .filter(|s| s.posture.to_string().contains("extension reversed"))
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
    // No named family; the general six-revolute elimination solves it.
    let cf = ClosedForm::detect(&r).unwrap();
    assert_eq!(*cf.family(), Family::General6);
    assert!(cf.not_named().unwrap().contains("do not intersect"));
    // Five joints.
    let r = Robot::from_dh(
        "five",
        Convention::Standard,
        &rows[..5],
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap();
    assert!(ClosedForm::detect(&r).is_err());
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
    assert!(ClosedForm::detect(&r).is_err());
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
        assert_eq!(n, 8);
        assert!(n <= MAX_SOLUTIONS);
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
                    Err(
                        IkError::TargetKind { .. }
                        | IkError::TiltedOutOfPlane { .. }
                        | IkError::OffPlane { .. },
                    ) => {}
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
        let mut labels: Vec<String> = res
            .solutions
            .iter()
            .map(|s| s.posture.to_string())
            .collect();
        labels.sort();
        labels.dedup();
        assert_eq!(labels.len(), 8, "{}", show(&res));
        assert!(labels.contains(&"shoulder left, elbow down, wrist flip".to_string()));
    }
}
