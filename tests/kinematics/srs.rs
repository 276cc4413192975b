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
