//! The one self-motion sampler (`redundancy::sampler`): every sample of every branch holds the
//! hand, checked here by forward kinematics; exact arms give their closed-form parameter, others
//! the numerical walk; a branch can be kept alone; a non-redundant arm is refused.

use armlab::kinematics::models::built_in;
use armlab::kinematics::{Pose, Robot};
use armlab::redundancy::RedundancyError;
use armlab::redundancy::sampler::{parameter_grid, sample_self_motion};

fn gap(a: &Pose, b: &Pose) -> (f64, f64) {
    let dp = (a.translation.vector - b.translation.vector).norm();
    // ||R_a - R_b||_F / sqrt(2) is the angle for small angles, to rounding (acos is not).
    let dr = (a.rotation.matrix() - b.rotation.matrix()).norm() / 2f64.sqrt();
    (dp, dr)
}

fn check_holds(
    robot: &Robot,
    ee: usize,
    pose: &Pose,
    samples: &[(f64, Vec<armlab::redundancy::BranchSolution>)],
) -> usize {
    let mut n = 0;
    for (_, branches) in samples {
        for b in branches {
            let (dp, dr) = gap(&robot.fk_ee(&b.q, ee).unwrap(), pose);
            assert!(
                dp < 1e-9 && dr < 1e-9,
                "{}: {} off by {dp:e} m, {dr:e} rad",
                robot.name,
                b.name
            );
            n += 1;
        }
    }
    n
}

#[test]
fn exact_self_motions_hold_the_hand_at_every_sample() {
    for (name, q) in [
        ("dlr", vec![0.3, 0.6, -0.2, 1.2, 0.4, -0.5, 0.2]),
        ("lwr4", vec![0.2, 0.5, 0.1, -1.1, 0.3, 0.6, -0.2]),
        ("panda", vec![0.1, -0.4, 0.2, -2.0, 0.1, 1.7, 0.6]),
    ] {
        let robot = built_in(name).unwrap();
        let pose = robot.fk(&q).unwrap();
        let m = sample_self_motion(&robot, 0, &pose, 72).unwrap();
        assert!(m.exact, "{name}");
        assert_eq!(m.samples.len(), 72);
        for ((v, _), g) in m.samples.iter().zip(parameter_grid(72)) {
            assert_eq!(*v, g);
        }
        assert_eq!(m.names.len(), m.feasible.len());
        let n = check_holds(&robot, 0, &pose, &m.samples);
        assert!(n > 72, "{name}: {n} solutions");
        // One branch alone.
        let mut one = m.clone();
        let first = m.names[0].clone();
        one.keep_branch(&first).unwrap();
        assert_eq!(one.names, vec![first.clone()]);
        assert!(
            one.samples
                .iter()
                .all(|(_, b)| b.iter().all(|x| x.name == first))
        );
        assert!(matches!(
            one.keep_branch("no such branch"),
            Err(RedundancyError::NoBranch { .. })
        ));
    }
}

#[test]
fn other_redundant_chains_are_walked_numerically() {
    let robot = built_in("humanoid").unwrap();
    let q = robot.config("ready").unwrap().to_vec();
    let pose = robot.fk_ee(&q, 0).unwrap();
    let m = sample_self_motion(&robot, 0, &pose, 36).unwrap();
    assert!(!m.exact);
    assert_eq!(m.parameter, "arc length");
    let n = check_holds(&robot, 0, &pose, &m.samples);
    assert!(n >= 18, "{n} samples reached");
}

#[test]
fn a_non_redundant_arm_has_no_self_motion() {
    let robot = built_in("puma560").unwrap();
    let pose = robot.fk(&[0.3, 0.8, -1.0, 0.4, 0.6, 0.2]).unwrap();
    let e = sample_self_motion(&robot, 0, &pose, 10).unwrap_err();
    assert!(matches!(e, RedundancyError::NotRedundant { .. }), "{e}");
    assert!(e.to_string().contains("no self-motion"), "{e}");
}
