//! Issue 27: a general six-revolute arm's "branch k" keeps its number while the target moves.
//!
//! The target follows a smooth joint path of a general arm (no two axes parallel or meeting);
//! at each step every solution is found by the closed form and renumbered from the step before
//! by `continue_numbers`. The check is written here, independently: a solution and a solution
//! at the step before that are each other's clearly nearest (by this file's wrapped joint
//! distance, the second nearest at least four times farther) must carry the same number. The plain
//! sorted numbers fail that check on the same path (so the test can fail).

use armlab::kinematics::ik::branches::continue_numbers;
use armlab::kinematics::ik::closed_form::Posture;
use armlab::kinematics::ik::{ClosedForm, IkSolution, SolutionPosture, Target};
use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
use std::f64::consts::PI;

/// A general arm: (a, alpha, d) per joint, no special geometry.
fn general_arm() -> Robot {
    let arm = [
        (-0.1678, 1.0053, 0.2660),
        (-0.2002, -2.0084, 0.5956),
        (0.2936, -1.0417, 0.5822),
        (-0.5561, 3.1086, 0.2553),
        (0.3038, -0.9356, 0.5777),
        (0.0096, 1.9354, -0.1387),
    ];
    let joints: Vec<DhJoint> = arm
        .iter()
        .map(|&(a, alpha, d)| {
            DhJoint::revolute(DhRow {
                a,
                alpha,
                d,
                theta: 0.0,
            })
            .limits(-PI, PI)
        })
        .collect();
    Robot::from_dh(
        "general",
        Convention::Standard,
        &joints,
        Pose::identity(),
        Pose::identity(),
    )
    .unwrap()
}

/// The joint distance written here: the norm of the differences wrapped into (-pi, pi].
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let d = (x - y + PI).rem_euclid(2.0 * PI) - PI;
            d * d
        })
        .sum::<f64>()
        .sqrt()
}

/// Along the path, the number of solutions that do not carry the number of the solution they
/// clearly continue (each the other's clearly nearest), and the number of those checked.
fn broken_continuations(steps: &[Vec<IkSolution>]) -> (usize, usize) {
    let (mut broken, mut checked) = (0, 0);
    for pair in steps.windows(2) {
        let (before, after) = (&pair[0], &pair[1]);
        for s in after {
            let mut near: Vec<(f64, &IkSolution)> =
                before.iter().map(|b| (distance(&s.q, &b.q), b)).collect();
            near.sort_by(|a, b| a.0.total_cmp(&b.0));
            let clear = match near.as_slice() {
                [one] => one.0 < 0.1,
                [first, second, ..] => first.0 < 0.1 && second.0 > 4.0 * first.0,
                [] => false,
            };
            // And the other way: s is clearly the nearest of the new solutions to that one (not
            // a pair born next to it).
            let back = |b: &IkSolution| {
                let mut d: Vec<f64> = after.iter().map(|a| distance(&a.q, &b.q)).collect();
                d.sort_by(f64::total_cmp);
                d.len() < 2 || d[1] > 4.0 * d[0]
            };
            if clear && back(near[0].1) {
                checked += 1;
                if s.posture.branch() != near[0].1.posture.branch() {
                    broken += 1;
                }
            }
        }
    }
    (broken, checked)
}

/// The solutions along the straight joint path from `q0` to `q1` in `n` steps, as the closed
/// form sorts them and as `continue_numbers` renumbers them from the step before; `check` sees
/// each step's renumbered solutions. Renumbering changes labels and order only (checked here):
/// the same joint vectors.
fn follow_path(
    robot: &Robot,
    q0: [f64; 6],
    q1: [f64; 6],
    n: usize,
    check: impl Fn(&[IkSolution]),
) -> (Vec<Vec<IkSolution>>, Vec<Vec<IkSolution>>) {
    let cf = ClosedForm::detect(robot).unwrap();
    let mut plain: Vec<Vec<IkSolution>> = Vec::new();
    let mut tracked: Vec<Vec<IkSolution>> = Vec::new();
    for i in 0..=n {
        let s = i as f64 / n as f64;
        let q: Vec<f64> = q0.iter().zip(&q1).map(|(a, b)| a + s * (b - a)).collect();
        let t = robot.fk(&q).unwrap();
        let sols = cf.solve(robot, &Target::Pose(t)).unwrap().solutions;
        let mut renumbered = sols.clone();
        if let Some(prev) = tracked.last() {
            continue_numbers(robot, prev, &mut renumbered);
        }
        assert_eq!(renumbered.len(), sols.len());
        for s in &sols {
            assert!(renumbered.iter().any(|r| distance(&r.q, &s.q) == 0.0));
        }
        check(&renumbered);
        plain.push(sols);
        tracked.push(renumbered);
    }
    (plain, tracked)
}

#[test]
fn a_branch_keeps_its_number_along_a_path_and_new_branches_take_free_numbers() {
    let robot = general_arm();
    let (q0, q1) = (
        [0.3, -1.1, 0.7, 2.0, -0.4, 1.2],
        [2.9, 0.9, -1.6, -2.7, 1.9, -2.2],
    );
    let (plain, tracked) = follow_path(&robot, q0, q1, 1500, |renumbered| {
        // Numbers are distinct and in order.
        let numbers: Vec<u8> = renumbered
            .iter()
            .map(|s| s.posture.branch().unwrap())
            .collect();
        assert!(numbers.windows(2).all(|w| w[0] < w[1]), "{numbers:?}");
    });
    let (broken, checked) = broken_continuations(&tracked);
    assert!(checked > 5000, "only {checked} clear continuations");
    assert_eq!(broken, 0, "{broken} of {checked} continuations renumbered");
    // The path is a real test: the sorted numbers swap somewhere along it.
    let (plain_broken, _) = broken_continuations(&plain);
    assert!(
        plain_broken > 0,
        "the sorted order never changed on this path"
    );
    // A branch born along the path takes a number no live branch has (checked by the
    // distinctness above); the counts vary along the path, so branches are born and die.
    let counts: Vec<usize> = tracked.iter().map(Vec::len).collect();
    assert!(
        counts.iter().min() != counts.iter().max(),
        "the number of branches never changed: {counts:?}"
    );
}

/// The posture "branch k" of a general arm.
fn branch(k: usize) -> SolutionPosture {
    SolutionPosture::ClosedForm(Posture {
        branch: Some(u8::try_from(k).unwrap()),
        ..Posture::default()
    })
}

/// A jump (no previous solution within a step) keeps the sorted numbers, the same as for a
/// target given alone; where the previous solutions are the same ones renumbered and one is
/// missing (it was born since), the others keep their numbers and it takes the lowest free one.
#[test]
fn a_jump_keeps_the_sorted_numbers_and_a_new_branch_takes_the_lowest_free_number() {
    let robot = general_arm();
    let cf = ClosedForm::detect(&robot).unwrap();
    let t = robot.fk(&[0.3, -1.1, 0.7, 2.0, -0.4, 1.2]).unwrap();
    let sols = cf.solve(&robot, &Target::Pose(t)).unwrap().solutions;
    let m = sols.len();
    assert!(m >= 4, "{m} solutions");
    let labels = |s: &[IkSolution]| s.iter().map(|x| x.posture.to_string()).collect::<Vec<_>>();
    // Far away: every previous q turned by 2 rad at joint 1, numbers reversed.
    let mut far = sols.clone();
    for (k, s) in far.iter_mut().enumerate() {
        s.q[0] += 2.0;
        s.posture = branch(m - k);
    }
    let mut renumbered = sols.clone();
    continue_numbers(&robot, &far, &mut renumbered);
    assert_eq!(labels(&renumbered), labels(&sols));
    // The same solutions, numbered 2..=m in reverse, without the first one.
    let mut previous: Vec<IkSolution> = sols[1..].to_vec();
    for (k, s) in previous.iter_mut().enumerate() {
        s.posture = branch(m - k);
    }
    let mut renumbered = sols.clone();
    continue_numbers(&robot, &previous, &mut renumbered);
    for r in &renumbered {
        let want = match previous.iter().find(|p| distance(&p.q, &r.q) == 0.0) {
            Some(p) => p.posture.to_string(),
            // The one not there before: 1 is the lowest number no other has.
            None => "branch 1".to_string(),
        };
        assert_eq!(r.posture.to_string(), want);
    }
}

/// Pieper's general case (a spherical wrist on a skewed three-revolute arm) labels "wrist no
/// flip, branch k" and "wrist flip, branch k": along a path whose theta1 passes pi (where the
/// sorted order of the arm's branches changes), each branch keeps its number, and both wrist
/// postures of one arm solution keep one number.
#[test]
fn pieper_branches_keep_their_numbers_and_both_wrists_share_one() {
    let robot = armlab::model_file::load_model("assets/robots/skewed_arm_wrist.toml").unwrap();
    assert!(
        ClosedForm::detect(&robot)
            .unwrap()
            .family()
            .numbered_branches()
    );
    let (q0, q1) = (
        [2.6, -0.6, 0.9, 0.3, 0.8, -0.4],
        [3.9, -0.2, 1.3, -0.5, 1.1, 0.6],
    );
    let (plain, tracked) = follow_path(&robot, q0, q1, 600, |renumbered| {
        for a in renumbered {
            let wrist = |s: &IkSolution| s.posture.closed_form().and_then(|p| p.wrist);
            assert!(wrist(a).is_some() && a.posture.branch().is_some());
            for b in renumbered {
                let same_arm = distance(&a.q[..3], &b.q[..3]) < 1e-9;
                let same_number = a.posture.branch() == b.posture.branch();
                let same_wrist = wrist(a) == wrist(b);
                // One arm solution, one number; one number per wrist group, one arm solution.
                assert_eq!(same_arm, same_number, "{} / {}", a.posture, b.posture);
                if same_number && same_wrist {
                    assert!(distance(&a.q, &b.q) < 1e-9);
                }
            }
        }
    });
    let (broken, checked) = broken_continuations(&tracked);
    assert!(checked > 1000, "only {checked} clear continuations");
    assert_eq!(broken, 0, "{broken} of {checked} continuations renumbered");
    let (plain_broken, _) = broken_continuations(&plain);
    assert!(
        plain_broken > 0,
        "the sorted order never changed on this path"
    );
}
