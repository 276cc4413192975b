//! Holding joints (`kinematics::hold`): the smaller robot's forward kinematics equals the whole
//! robot's with the held variables at their values, for serial arms, coupled joints (the
//! humanoid's chest) and the other chains of a branched robot; the map back to the original q.

use armlab::kinematics::hold::{hold_joints, hold_other_chains};
use armlab::kinematics::models::built_in;
use armlab::kinematics::{Pose, Robot};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Largest gap between two poses: translation (m) plus the Frobenius norm of the rotation
/// difference.
fn gap(a: &Pose, b: &Pose) -> f64 {
    (a.translation.vector - b.translation.vector).norm()
        + (a.rotation.matrix() - b.rotation.matrix()).norm()
}

fn random_q(robot: &Robot, rng: &mut ChaCha8Rng) -> Vec<f64> {
    (0..robot.dof())
        .map(|k| {
            let [lo, hi] = robot.sampling_range(k);
            rng.random_range(lo..hi)
        })
        .collect()
}

#[test]
fn a_held_robot_moves_as_the_whole_one_with_those_joints_fixed() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for name in [
        "puma560",
        "dlr",
        "panda",
        "humanoid",
        "stanford",
        "slider_chain",
    ] {
        let robot = built_in(name).unwrap();
        for trial in 0..50 {
            let q = random_q(&robot, &mut rng);
            // Hold every other joint (a closed loop read from one held and one free joint has no
            // smaller robot: then nothing is returned, which is fine).
            let held: Vec<bool> = (0..robot.dof()).map(|k| (k + trial) % 2 == 0).collect();
            let Some(h) = hold_joints(&robot, &q, &held) else {
                assert!(name == "slider_chain", "{name}: nothing held?");
                continue;
            };
            assert_eq!(
                h.robot.dof(),
                held.iter().filter(|&&x| !x).count(),
                "{name}"
            );
            // Move the free joints; the whole robot moves the same.
            let free_q = random_q(&h.robot, &mut rng);
            let mut full = q.clone();
            h.expand(&free_q, &mut full);
            for (k, v) in full.iter().enumerate() {
                if held[k] {
                    assert_eq!(*v, q[k], "{name}: a held value moved");
                }
            }
            for ee in 0..robot.end_effectors().len() {
                let small = h.robot.fk_ee(&free_q, ee).unwrap();
                let whole = robot.fk_ee(&full, ee).unwrap();
                assert!(
                    gap(&small, &whole) < 1e-12,
                    "{name} ee {ee}: {}",
                    gap(&small, &whole)
                );
            }
        }
    }
}

#[test]
fn the_other_chains_of_a_branched_robot_are_held() {
    let robot = built_in("humanoid").unwrap();
    let q = robot.config("ready").unwrap().to_vec();
    for ee in 0..2 {
        let h = hold_other_chains(&robot, &q, ee).expect("the humanoid has two hands");
        // Holding the other arm holds the torso it hangs from too: 7 free joints of one arm.
        assert_eq!(h.robot.dof(), 7, "hand {ee}");
        let other = 1 - ee;
        let mut full = q.clone();
        h.expand(&[0.3; 7], &mut full);
        // The other hand stays where it was.
        let before = robot.fk_ee(&q, other).unwrap();
        let after = robot.fk_ee(&full, other).unwrap();
        assert!(gap(&before, &after) < 1e-12, "hand {other} moved");
    }
    // A single chain holds nothing.
    let puma = built_in("puma560").unwrap();
    assert!(hold_other_chains(&puma, &[0.0; 6], 0).is_none());
}
