//! The Franka Panda's self-motion with q7 as the free parameter (offset elbow, not SRS): every
//! branch at any q7 reproduces the target pose by a forward kinematics written out in this test
//! (Craig's modified DH product of the Franka table), the configuration a pose came from is one
//! of the branches at its own q7, and the feasible q7 intervals agree with dense sampling.

use armlab::kinematics::models::built_in;
use armlab::redundancy::offset_elbow::OffsetElbowArm;
use nalgebra::{Matrix4, Vector3};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

fn lcg(s: &mut u64) -> f64 {
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*s >> 11) as f64 / (1u64 << 53) as f64
}

/// The Franka table (a_{i-1}, alpha_{i-1}, d_i) and the gripper tool, written out here.
fn fk(q: &[f64]) -> Matrix4<f64> {
    let rows = [
        (0.0, 0.0, 0.333),
        (0.0, -FRAC_PI_2, 0.0),
        (0.0, FRAC_PI_2, 0.316),
        (0.0825, FRAC_PI_2, 0.0),
        (-0.0825, -FRAC_PI_2, 0.384),
        (0.0, FRAC_PI_2, 0.0),
        (0.088, FRAC_PI_2, 0.107),
    ];
    let mut t = Matrix4::<f64>::identity();
    for (k, &(a, al, d)) in rows.iter().enumerate() {
        let (sa, ca) = f64::sin_cos(al);
        let (st, ct) = q[k].sin_cos();
        // Craig: Rot_x(alpha) Trans_x(a) Rot_z(theta) Trans_z(d).
        t *= Matrix4::new(
            ct,
            -st,
            0.0,
            a,
            st * ca,
            ct * ca,
            -sa,
            -sa * d,
            st * sa,
            ct * sa,
            ca,
            ca * d,
            0.0,
            0.0,
            0.0,
            1.0,
        );
    }
    let (s, c) = (-FRAC_PI_4).sin_cos();
    t * Matrix4::new(
        c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.103, 0.0, 0.0, 0.0, 1.0,
    )
}

fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

#[test]
fn the_panda_is_an_offset_elbow_arm_and_the_srs_arms_are_not() {
    assert!(OffsetElbowArm::detect(&built_in("panda").unwrap()).is_some());
    for name in ["dlr", "puma560", "humanoid", "planar3"] {
        assert!(
            OffsetElbowArm::detect(&built_in(name).unwrap()).is_none(),
            "{name}"
        );
    }
}

#[test]
fn every_branch_reaches_the_target_at_every_q7() {
    let robot = built_in("panda").unwrap();
    let arm = OffsetElbowArm::detect(&robot).unwrap();
    let lim = robot.limits();
    let mut s = 11u64;
    let (mut found, mut branches, mut counts) = (0, 0, [0usize; 9]);
    for _ in 0..10_000 {
        let q: Vec<f64> = lim
            .iter()
            .map(|l| l[0] + (l[1] - l[0]) * lcg(&mut s))
            .collect();
        let target = robot.fk(&q).unwrap();
        let want = fk(&q);
        let p_want = Vector3::new(want[(0, 3)], want[(1, 3)], want[(2, 3)]);
        assert!((target.translation.vector - p_want).norm() < 1e-12);
        // At its own q7 the configuration is one of the branches.
        let own = arm.branch_solutions(&robot, &target, q[6]);
        assert!(
            own.iter()
                .any(|b| b.q.iter().zip(&q).all(|(x, y)| angle_gap(*x, *y) < 1e-8)),
            "{q:?} not among {own:?}"
        );
        found += 1;
        // At another q7 every branch holds the pose.
        let q7 = -PI + TAU * lcg(&mut s);
        let sols = arm.branch_solutions(&robot, &target, q7);
        counts[sols.len()] += 1;
        for b in &sols {
            let t = fk(&b.q);
            let gap = (t - want).abs().max();
            assert!(gap < 1e-12, "q7 {q7}: {b:?} off by {gap}");
            assert!(b.position_error < 1e-12 && b.orientation_error < 1e-12);
            assert!(angle_gap(b.q[6], q7) < 1e-15);
            branches += 1;
        }
    }
    assert_eq!(found, 10_000);
    // Branch counts come in pairs (the shoulder's two solutions); eight is the most.
    assert!(
        counts
            .iter()
            .enumerate()
            .all(|(k, &c)| k % 2 == 0 || c == 0),
        "{counts:?}"
    );
    assert!(counts[8] > 1000, "{counts:?}");
    assert!(branches > 30_000, "{branches}");
}

/// Feasible q7 intervals against 10^5 samples of q7, the limits checked in the test on the
/// solutions' joint values.
#[test]
fn feasible_q7_intervals_match_dense_sampling() {
    let robot = built_in("panda").unwrap();
    let arm = OffsetElbowArm::detect(&robot).unwrap();
    let lim = robot.limits();
    let names = OffsetElbowArm::branch_names();
    for q in [
        robot.config("ready").unwrap().to_vec(),
        vec![0.4, 0.3, -0.5, -1.6, 0.8, 1.2, -0.3],
        vec![-1.2, -0.9, 1.1, -2.4, -1.3, 2.6, 1.9],
    ] {
        let target = robot.fk(&q).unwrap();
        let feasible = arm.feasible_intervals(&target);
        let n = 100_000;
        let mut hits = [0usize; 8];
        for k in 0..n {
            let q7 = -PI + TAU * (k as f64 + 0.5) / n as f64;
            let sols = arm.branch_solutions(&robot, &target, q7);
            for (b, name) in names.iter().enumerate() {
                let ok = sols.iter().find(|x| &x.name == name).is_some_and(|x| {
                    x.q.iter()
                        .zip(&lim)
                        .all(|(v, l)| *v >= l[0] - 1e-12 && *v <= l[1] + 1e-12)
                });
                let inside = feasible[b].iter().any(|iv| q7 >= iv[0] && q7 <= iv[1]);
                let near_end = feasible[b]
                    .iter()
                    .any(|iv| (q7 - iv[0]).abs() < 1e-4 || (q7 - iv[1]).abs() < 1e-4);
                if !near_end {
                    assert_eq!(ok, inside, "{q:?} {name} q7 {q7}");
                }
                hits[b] += usize::from(ok);
            }
        }
        for b in 0..8 {
            let measure: f64 = feasible[b].iter().map(|iv| iv[1] - iv[0]).sum();
            let sampled = hits[b] as f64 / n as f64 * TAU;
            assert!(
                (measure - sampled).abs() < 1e-3,
                "{}: {measure} vs {sampled}",
                names[b]
            );
            for iv in &feasible[b] {
                assert!(-PI <= iv[0] && iv[0] <= iv[1] && iv[1] <= PI, "{iv:?}");
            }
        }
        // The configuration's own branch is feasible at its q7, so one manifold at least.
        assert!(
            feasible
                .iter()
                .any(|f| f.iter().any(|iv| q[6] >= iv[0] && q[6] <= iv[1]))
        );
        assert!(arm.manifolds(&target) >= 1);
    }
}
