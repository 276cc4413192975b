//! The SRS arm angle (Shimizu et al. 2008) on the DLR arm and the KUKA LWR4: every branch at any
//! psi reproduces the target pose by forward kinematics, the arm angle measured back from FK is
//! psi, and the configuration the pose came from is one of the branches at its own arm angle.

use armlab::kinematics::models::built_in;
use armlab::kinematics::{Pose, Robot};
use armlab::redundancy::srs::SrsArm;
use std::f64::consts::{PI, TAU};

fn lcg(s: &mut u64) -> f64 {
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*s >> 11) as f64 / (1u64 << 53) as f64
}

fn models() -> Vec<Robot> {
    vec![
        built_in("dlr").unwrap(),
        armlab::model_file::load_model(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/robots/lwr4.toml"
        ))
        .unwrap(),
    ]
}

/// A joint vector drawn uniformly within the limits.
fn random_q(lim: &[[f64; 2]], s: &mut u64) -> Vec<f64> {
    lim.iter().map(|l| l[0] + (l[1] - l[0]) * lcg(s)).collect()
}

fn pose_gap(a: &Pose, b: &Pose) -> (f64, f64) {
    let p = (a.translation.vector - b.translation.vector).norm();
    // Frobenius norm of the difference of the rotation matrices (about the angle for small ones).
    let r = (a.rotation.matrix() - b.rotation.matrix()).norm();
    (p, r)
}

fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

#[test]
fn every_branch_reaches_the_target_at_every_arm_angle() {
    for robot in models() {
        let arm = SrsArm::detect(&robot).expect("an SRS arm");
        let lim = robot.limits();
        let mut s = 5u64;
        let (mut poses, mut branches) = (0, 0);
        while poses < 10_000 {
            let q = random_q(&lim, &mut s);
            let target = robot.fk(&q).unwrap();
            if arm.singular(&target) {
                continue;
            }
            poses += 1;
            let psi = -PI + TAU * lcg(&mut s);
            let sols = arm.solve(&target, psi);
            assert!(sols.len() >= 2, "{}: {} branches", robot.name, sols.len());
            for b in &sols {
                let (p, r) = pose_gap(&robot.fk(&b.q).unwrap(), &target);
                assert!(
                    p < 1e-12 && r < 1e-11,
                    "{} {}: {p} m, {r} rad",
                    robot.name,
                    b.name
                );
                let back = arm.arm_angle(&b.q).unwrap();
                assert!(
                    angle_gap(back, psi) < 1e-9,
                    "{}: psi {psi} measured {back}",
                    b.name
                );
                branches += 1;
            }
            // The configuration the pose came from is a branch at its own arm angle.
            let own = arm.arm_angle(&q).unwrap();
            let found = arm
                .solve(&target, own)
                .iter()
                .any(|b| b.q.iter().zip(&q).all(|(a, c)| angle_gap(*a, *c) < 1e-8));
            assert!(
                found,
                "{}: q {q:?} not among the branches at psi {own}",
                robot.name
            );
        }
        assert!(branches >= 8 * 10_000 - 1000, "{}: {branches}", robot.name);
    }
}

/// Feasible arm angles against 10^5 samples of psi: away from the interval ends, a sample is
/// inside an interval exactly when the branch there is within every joint limit (checked here
/// on the joint values the solver returns, wrapped by 2 pi).
#[test]
fn feasible_arm_angles_match_dense_sampling() {
    for robot in models() {
        let arm = SrsArm::detect(&robot).unwrap();
        let lim = robot.limits();
        let within = |q: &[f64; 7]| {
            q.iter().zip(&lim).all(|(v, l)| {
                [*v, v - TAU, v + TAU]
                    .iter()
                    .any(|x| *x >= l[0] - 1e-12 && *x <= l[1] + 1e-12)
            })
        };
        let mut s = 17u64;
        let mut poses = 0;
        let mut partial = 0;
        while poses < 6 {
            let q = random_q(&lim, &mut s);
            let target = robot.fk(&q).unwrap();
            if arm.singular(&target) {
                continue;
            }
            poses += 1;
            let feasible = arm.feasible_intervals(&target);
            let n = 100_000;
            let mut raw = [[0.0; 7]; 8];
            let mut measure = [0.0f64; 8];
            for k in 0..n {
                let psi = -PI + TAU * (k as f64 + 0.5) / n as f64;
                let mask = arm.solve_raw(&target, psi, &mut raw);
                for b in 0..8 {
                    let ok = mask >> b & 1 == 1 && within(&raw[b]);
                    measure[b] += if ok { TAU / n as f64 } else { 0.0 };
                    let inside = feasible[b].iter().any(|iv| psi >= iv[0] && psi <= iv[1]);
                    let near = feasible[b]
                        .iter()
                        .any(|iv| (psi - iv[0]).abs() < 1e-4 || (psi - iv[1]).abs() < 1e-4);
                    assert!(
                        near || ok == inside,
                        "{} branch {b} psi {psi}: {ok} vs {inside}",
                        robot.name
                    );
                }
            }
            for b in 0..8 {
                let total: f64 = feasible[b].iter().map(|iv| iv[1] - iv[0]).sum();
                partial += usize::from(total > 1e-3 && total < TAU - 1e-3);
                assert!(
                    (total - measure[b]).abs() < 1e-3,
                    "{} branch {b}: {total} vs {}",
                    robot.name,
                    measure[b]
                );
                for iv in &feasible[b] {
                    assert!(-PI <= iv[0] && iv[0] <= iv[1] && iv[1] <= PI);
                }
            }
        }
        // The limits cut the arm angle: most branches have some infeasible stretch.
        assert!(
            partial >= 12,
            "{}: only {partial} partial branches",
            robot.name
        );
    }
}

/// Newton's method on the six free joints (the locked one held at `q[k]`) from `q`, with a
/// finite-difference Jacobian of `robot.fk` and the rotation error from the skew part: the
/// brute force's own solver, independent of armlab's IK. The solution, if it converges.
fn newton_locked(robot: &Robot, target: &Pose, k: usize, mut q: Vec<f64>) -> Option<Vec<f64>> {
    let residual = |q: &[f64]| -> [f64; 6] {
        let p = robot.fk(q).unwrap();
        let dp = target.translation.vector - p.translation.vector;
        let d = (target.rotation * p.rotation.inverse()).into_inner();
        [
            dp.x,
            dp.y,
            dp.z,
            0.5 * (d[(2, 1)] - d[(1, 2)]),
            0.5 * (d[(0, 2)] - d[(2, 0)]),
            0.5 * (d[(1, 0)] - d[(0, 1)]),
        ]
    };
    let free: Vec<usize> = (0..7).filter(|&i| i != k).collect();
    for _ in 0..60 {
        let r = residual(&q);
        let norm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm < 1e-12 {
            // The skew part vanishes at a half turn too: the rotation itself must agree.
            let p = robot.fk(&q).unwrap();
            let (dp, dr) = pose_gap(&p, target);
            return (dp < 1e-9 && dr < 1e-9).then_some(q);
        }
        let mut j = nalgebra::Matrix6::zeros();
        for (c, &i) in free.iter().enumerate() {
            let h = 1e-7;
            let mut qh = q.clone();
            qh[i] += h;
            let rh = residual(&qh);
            for row in 0..6 {
                j[(row, c)] = (rh[row] - r[row]) / h;
            }
        }
        let e = nalgebra::Vector6::from_row_slice(&r);
        // Damped least squares: steady near singular configurations.
        let jt = j.transpose();
        let step = (jt * j + nalgebra::Matrix6::identity() * 1e-10)
            .lu()
            .solve(&(jt * e))?;
        // Newton on the residual r(q) = 0: q <- q - J_r^-1 r.
        for (c, &i) in free.iter().enumerate() {
            q[i] -= step[c].clamp(-0.5, 0.5);
        }
    }
    None
}

/// The brute force: `starts` Newton starts from random joint vectors with joint `k` held at
/// `value`; every distinct configuration it finds must be among `ours` (armlab's). Returns how
/// many it found.
fn brute_force_within(
    robot: &Robot,
    target: &Pose,
    (k, value): (usize, f64),
    ours: &[[f64; 7]],
    starts: usize,
    seed: &mut u64,
) -> usize {
    let mut brute: Vec<Vec<f64>> = Vec::new();
    for _ in 0..starts {
        let mut start: Vec<f64> = (0..7).map(|_| (2.0 * lcg(seed) - 1.0) * PI).collect();
        start[k] = value;
        if let Some(q) = newton_locked(robot, target, k, start)
            && !brute.iter().any(|b| same_configuration(b, &q, 1e-5))
        {
            brute.push(q);
        }
    }
    for b in &brute {
        assert!(
            ours.iter().any(|q| same_configuration(q, b, 1e-6)),
            "{} q{} locked at {value}: the brute force found {b:?}, armlab gave {ours:?}",
            robot.name,
            k + 1
        );
    }
    brute.len()
}

/// Whether two joint vectors are the same configuration (angles modulo 2 pi).
fn same_configuration(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| angle_gap(*x, *y) < tol)
}

/// The KUKA iiwa 14's URDF, its arm alone (the chain to its default end-effector), as
/// `armlab self-motion --ee` makes it.
fn iiwa14() -> Robot {
    let whole = armlab::model_file::load_model(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/urdf_corpus/kuka_iiwa14.urdf"
    ))
    .unwrap();
    let q = whole.ready_or_zero();
    armlab::kinematics::arm::arm_of(&whole, 0, &q)
        .unwrap()
        .robot
}

/// Issue 46, item 12: with q3 (or q5) locked, an SRS arm is a six-joint arm with a spherical
/// wrist, and every value of the locked joint gives every solution. Checked against a brute
/// force written here: 300 Newton starts per pose and value; every configuration it finds is
/// among armlab's, and each of armlab's meets the pose by forward kinematics. Values beyond the
/// locked joint's limits give their solutions too (flagged by the self-motion).
#[test]
fn a_locked_srs_arm_gives_every_solution_at_every_value() {
    use armlab::kinematics::ik::closed_form::{LockedArm, MAX_LOCKED_SOLUTIONS};
    let iiwa = iiwa14();
    let mut seed = 46u64;
    for robot in [models().remove(1), iiwa] {
        let lim = robot.limits();
        for k in [2usize, 4] {
            let arm = LockedArm::new(&robot, k).unwrap();
            let (mut total, mut found) = (0, 0);
            for _ in 0..3 {
                let q0 = random_q(&lim, &mut seed);
                let target = robot.fk(&q0).unwrap();
                // The pose's own value, one elsewhere inside the limits, one beyond them.
                for value in [q0[k], 0.6 * lim[k][0] + 0.1, lim[k][1] + 0.05] {
                    let mut out = [[0.0; 7]; MAX_LOCKED_SOLUTIONS];
                    let n = arm.solve_exact(&robot, &target, value, &mut out).unwrap();
                    let ours = &out[..n];
                    for q in ours {
                        let (dp, dr) = pose_gap(&robot.fk(q).unwrap(), &target);
                        assert!(
                            dp < 1e-10 && dr < 1e-9,
                            "{}: {q:?} misses by {dp}, {dr}",
                            robot.name
                        );
                        assert_eq!(q[k], value);
                    }
                    total += brute_force_within(&robot, &target, (k, value), ours, 300, &mut seed);
                    found += n;
                }
            }
            assert!(
                total >= 9,
                "{}: the brute force found only {total}",
                robot.name
            );
            assert!(found >= total);
        }
    }
}

/// Issue 46, item 12: `self-motion --lock 3` and `--lock 5` on an SRS arm at the FK of
/// configurations within the limits: never "out of reach for every value", and the
/// configuration the pose came from lies on a branch.
#[test]
fn the_locked_self_motion_of_an_srs_arm_reaches_every_pose_it_came_from() {
    use armlab::redundancy::sampler::sample_self_motion_locked;
    let robot = iiwa14();
    let lim = robot.limits();
    let mut seed = 4646u64;
    for k in [2usize, 4] {
        for _ in 0..6 {
            let q0 = random_q(&lim, &mut seed);
            let target = robot.fk(&q0).unwrap();
            let m = sample_self_motion_locked(&robot, 0, &target, 721, Some(k))
                .unwrap_or_else(|e| panic!("q{} locked, q0 {q0:?}: {e}", k + 1));
            let mut nearest = f64::INFINITY;
            for (_, sols) in &m.samples {
                for s in sols {
                    let (dp, dr) = pose_gap(&robot.fk(&s.q).unwrap(), &target);
                    assert!(dp < 1e-9 && dr < 1e-8);
                    if angle_gap(s.q[k], q0[k]) < 0.005 {
                        let d =
                            s.q.iter()
                                .zip(&q0)
                                .map(|(a, b)| angle_gap(*a, *b))
                                .fold(0.0, f64::max);
                        nearest = nearest.min(d);
                    }
                }
            }
            assert!(
                nearest < 0.2,
                "q{} locked: no branch passes near q0 ({nearest})",
                k + 1
            );
        }
    }
}

/// Issue 46, item 12: any locked joint of a seven-joint arm gives every solution, on an SRS
/// arm (the iiwa 14) and on the Panda (an offset elbow, no SRS), at each joint 1 to 7 but the
/// SRS arm's elbow (q4, which the pose fixes: locking it is refused with that reason). The
/// same brute force as above: 200 Newton starts per pose and value, each configuration it finds
/// among armlab's; values beyond the joint's limits included.
#[test]
fn any_locked_joint_of_a_seven_joint_arm_gives_every_solution() {
    use armlab::kinematics::ik::closed_form::{LockedArm, MAX_LOCKED_SOLUTIONS};
    use armlab::redundancy::RedundancyError;
    use armlab::redundancy::locked::LockedSelfMotion;
    let mut seed = 4612u64;
    for robot in [iiwa14(), built_in("panda").unwrap()] {
        let lim = robot.limits();
        let srs = robot.name.contains("iiwa");
        for k in 0..7usize {
            let q0 = random_q(&lim, &mut seed);
            let target = robot.fk(&q0).unwrap();
            if srs && k == 3 {
                match LockedSelfMotion::new(&robot, &target, Some(k)) {
                    Err(RedundancyError::LockedJointFixedByPose { value_deg, .. }) => {
                        // the elbow's angle, on one branch or the other
                        let v = value_deg.to_radians().abs();
                        assert!((v - q0[3].abs()).abs() < 1e-6, "{value_deg} vs {}", q0[3]);
                    }
                    other => panic!("q4 of an SRS arm: {:?}", other.map(|_| ())),
                }
                continue;
            }
            let arm = LockedArm::new(&robot, k)
                .unwrap_or_else(|| panic!("{}: q{} cannot be locked", robot.name, k + 1));
            let (mut total, mut found) = (0, 0);
            for value in [q0[k], 0.5 * lim[k][0] + 0.2, lim[k][1] + 0.05] {
                let mut out = [[0.0; 7]; MAX_LOCKED_SOLUTIONS];
                let n = arm.solve_exact(&robot, &target, value, &mut out).unwrap();
                let ours = &out[..n];
                for q in ours {
                    let (dp, dr) = pose_gap(&robot.fk(q).unwrap(), &target);
                    assert!(
                        dp < 1e-9 && dr < 1e-8,
                        "{}: {q:?} misses by {dp}, {dr}",
                        robot.name
                    );
                }
                total += brute_force_within(&robot, &target, (k, value), ours, 200, &mut seed);
                found += n;
            }
            assert!(
                total >= 1,
                "{} q{}: the brute force found nothing",
                robot.name,
                k + 1
            );
            assert!(
                found >= total,
                "{} q{}: {found} < {total}",
                robot.name,
                k + 1
            );
        }
    }
}
