//! Numerical IK: success rate on random reachable poses, every answer verified by FK, the
//! teaching variants, task masks, the null-space objective, and reports instead of errors.

use armlab::kinematics::ik::numerical::{
    MaskFrame, Method, NumericalOptions, Secondary, TaskMask, solve,
};
use armlab::kinematics::ik::{IkError, Target};
use armlab::kinematics::models::built_in;
use armlab::kinematics::{Pose, Robot};
use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_q(r: &Robot, rng: &mut ChaCha8Rng) -> Vec<f64> {
    r.limits()
        .iter()
        .map(|l| rng.random_range(l[0]..=l[1]))
        .collect()
}

fn success_rate(name: &str, n: usize) -> f64 {
    let r = built_in(name).unwrap();
    let seed_q = r.config("ready").unwrap().to_vec();
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let opts = NumericalOptions::default();
    let mut ok = 0;
    for _ in 0..n {
        let goal = r.fk(&random_q(&r, &mut rng)).unwrap();
        let rep = solve(&r, 0, &Target::Pose(goal), &seed_q, &opts).unwrap();
        if rep.converged {
            // Verify independently of the solver's own bookkeeping.
            let t = r.fk(&rep.q).unwrap();
            let dp = (t.translation.vector - goal.translation.vector).norm();
            let dr = armlab::kinematics::orientation::angle_axis_from_rotation(
                &(t.rotation.inverse() * goal.rotation),
            )
            .angle;
            assert!(
                dp <= 1e-10 && dr <= 1e-10,
                "{name}: claimed convergence with {dp:e} m, {dr:e} rad"
            );
            assert!(
                r.within_limits(&rep.q, 0.0),
                "{name}: solution outside limits"
            );
            ok += 1;
        }
    }
    ok as f64 / n as f64
}

#[test]
fn lm_success_6dof_puma560() {
    let rate = success_rate("puma560", 10_000);
    assert!(rate >= 0.995, "success {rate}");
}

#[test]
fn lm_success_7dof_panda() {
    let rate = success_rate("panda", 10_000);
    assert!(rate >= 0.995, "success {rate}");
}

#[test]
fn lm_success_humanoid_right_hand() {
    let r = built_in("humanoid").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let seed_q = r.config("ready").unwrap().to_vec();
    for ee in 0..2 {
        let mut ok = 0;
        for _ in 0..200 {
            let goal = r.fk_ee(&random_q(&r, &mut rng), ee).unwrap();
            let rep = solve(
                &r,
                ee,
                &Target::Pose(goal),
                &seed_q,
                &NumericalOptions::default(),
            )
            .unwrap();
            ok += usize::from(rep.converged);
        }
        assert!(ok >= 198, "hand {ee}: {ok}/200");
    }
}

#[test]
fn teaching_variants_converge_on_an_easy_target() {
    let r = built_in("planar3").unwrap();
    let q_true = [0.3, 0.5, -0.4];
    let t = r.fk(&q_true).unwrap();
    let phi = q_true.iter().sum();
    let target = Target::Planar {
        px: t.translation.x,
        py: t.translation.y,
        phi,
    };
    for (method, iters) in [
        (Method::LevenbergMarquardt, 100),
        (Method::DampedLeastSquares, 2000),
        (Method::PseudoInverse, 100),
        (Method::Transpose, 20_000),
    ] {
        let opts = NumericalOptions {
            method,
            max_iterations: iters,
            restarts: 0,
            damping: 1e-3,
            tolerance: 1e-9,
            ..Default::default()
        };
        let rep = solve(&r, 0, &target, &[0.0, 0.1, 0.0], &opts).unwrap();
        assert!(rep.converged, "{method:?}: {rep:?}");
        let tt = r.fk(&rep.q).unwrap();
        assert!((tt.translation.vector - t.translation.vector).norm() < 1e-8);
    }
}

#[test]
fn position_only_task_for_a_redundant_arm() {
    let r = built_in("panda").unwrap();
    let seed_q = r.config("ready").unwrap().to_vec();
    let p = Vector3::new(0.4, 0.2, 0.5);
    let rep = solve(
        &r,
        0,
        &Target::Position(p),
        &seed_q,
        &NumericalOptions::default(),
    )
    .unwrap();
    assert!(rep.converged);
    assert!((r.fk(&rep.q).unwrap().translation.vector - p).norm() < 1e-10);
    // A custom mask: position plus the z axis rotation only (r = 4 < m = 6).
    let goal = r.fk(&[0.2, 0.1, -0.3, -1.5, 0.2, 1.8, 0.4]).unwrap();
    let opts = NumericalOptions {
        mask: TaskMask([true, true, true, false, false, true], MaskFrame::World),
        ..Default::default()
    };
    let rep = solve(&r, 0, &Target::Pose(goal), &seed_q, &opts).unwrap();
    assert!(rep.converged, "{rep:?}");
}

#[test]
fn null_space_objective_moves_away_from_limits_without_losing_the_task() {
    let r = built_in("panda").unwrap();
    let seed_q = r.config("ready").unwrap().to_vec();
    let p = Vector3::new(0.5, 0.0, 0.4);
    let limits = r.limits();
    let spread = |q: &[f64]| -> f64 {
        q.iter()
            .zip(&limits)
            .map(|(v, l)| ((v - 0.5 * (l[0] + l[1])) / (l[1] - l[0])).powi(2))
            .sum()
    };
    let plain = NumericalOptions {
        restarts: 0,
        ..Default::default()
    };
    let a = solve(&r, 0, &Target::Position(p), &seed_q, &plain).unwrap();
    let with = NumericalOptions {
        secondary: Secondary::JointLimits { gain: 5.0 },
        ..plain
    };
    let b = solve(&r, 0, &Target::Position(p), &seed_q, &with).unwrap();
    assert!(a.converged && b.converged, "{a:?} {b:?}");
    assert!(
        spread(&b.q) < spread(&a.q),
        "{} !< {}",
        spread(&b.q),
        spread(&a.q)
    );
    let m = NumericalOptions {
        secondary: Secondary::Manipulability { gain: 1.0 },
        ..plain
    };
    let c = solve(&r, 0, &Target::Position(p), &seed_q, &m).unwrap();
    assert!(c.converged);
    let manip = |q: &[f64]| {
        let j = r.jacobian(q, 0).unwrap();
        let jp = j.fixed_rows::<3>(0);
        (jp * jp.transpose()).determinant().sqrt()
    };
    assert!(
        manip(&c.q) > manip(&a.q),
        "{} !> {}",
        manip(&c.q),
        manip(&a.q)
    );
}

#[test]
fn unreachable_target_is_a_report_not_an_error() {
    let r = built_in("puma560").unwrap();
    let far = Pose::translation(5.0, 0.0, 0.0);
    let opts = NumericalOptions {
        restarts: 3,
        ..Default::default()
    };
    let rep = solve(&r, 0, &Target::Pose(far), &[0.0; 6], &opts).unwrap();
    assert!(!rep.converged);
    assert!(rep.position_error > 3.0 && rep.position_error.is_finite());
    assert!(rep.q.iter().all(|v| v.is_finite()));
    assert!(r.within_limits(&rep.q, 0.0));
}

#[test]
fn invalid_input_is_an_error() {
    let r = built_in("puma560").unwrap();
    let bad = Target::Position(Vector3::new(f64::NAN, 0.0, 0.0));
    assert_eq!(
        solve(&r, 0, &bad, &[0.0; 6], &NumericalOptions::default()).unwrap_err(),
        IkError::NonFiniteTarget
    );
    let ok = Target::Position(Vector3::new(0.5, 0.0, 0.5));
    assert!(solve(&r, 0, &ok, &[0.0; 5], &NumericalOptions::default()).is_err());
    assert!(solve(&r, 4, &ok, &[0.0; 6], &NumericalOptions::default()).is_err());
}

/// The Puma with every joint's limits replaced (`None` = no limits).
fn puma_with_limits(limits: Option<[f64; 2]>) -> Robot {
    use armlab::kinematics::DhJoint;
    let p = built_in("puma560").unwrap();
    let (conv, table) = p.dh_table().unwrap();
    let rows: Vec<DhJoint> = table
        .iter()
        .map(|&(k, row, off)| {
            let j = DhJoint::new(k, row).offset(off);
            match limits {
                Some([lo, hi]) => j.limits(lo, hi),
                None => j.unbounded(),
            }
        })
        .collect();
    Robot::from_dh("puma", conv, &rows, p.base, p.end_effectors()[0].tool).unwrap()
}

#[test]
fn lm_converges_beside_the_elbow_singularity() {
    // The reported case: a goal 2.8 mrad from the Puma's folded-elbow singularity (q3 = pi/2 +
    // atan(a3/d4) = 1.61778), where the wrist centre is also 0.5 mm from the shoulder axis. Its
    // solutions have q3 = 1.6206 or 1.6150, outside the built-in Puma's q3 range [-225, 45] deg,
    // so the test uses the same arm with [-pi, pi] limits, with none, and with limits ignored.
    let pi = std::f64::consts::PI;
    let arms = [
        (puma_with_limits(Some([-pi, pi])), true),
        (puma_with_limits(None), true),
        (built_in("puma560").unwrap(), false),
    ];
    let seed = built_in("puma560")
        .unwrap()
        .config("ready")
        .unwrap()
        .to_vec();
    let mut cases = 0;
    for (robot, enforce) in &arms {
        let opts = NumericalOptions {
            enforce_limits: *enforce,
            ..NumericalOptions::default()
        };
        for q3 in [1.6206, 1.6190, 1.6230, 1.6150] {
            for (q1, q2, q4, q5, q6) in [
                (0.0, 0.0, 0.0, 0.0, 0.0),
                (0.3, 0.5, 0.4, 0.7, 0.2),
                (-0.5, 1.0, -0.4, 0.3, 1.2),
                (1.2, -0.3, 0.9, -1.1, -0.6),
            ] {
                let q = [q1, q2, q3, q4, q5, q6];
                let goal = robot.fk(&q).unwrap();
                let rep = solve(robot, 0, &Target::Pose(goal), &seed, &opts).unwrap();
                let t = robot.fk(&rep.q).unwrap();
                let dp = (t.translation.vector - goal.translation.vector).norm();
                assert!(
                    rep.converged && dp <= 1e-10 && rep.orientation_error <= 1e-10,
                    "q = {q:?}, enforce {enforce}: {rep:?}"
                );
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 48);
    // With the built-in limits no solution exists, and the solver says so.
    let puma = built_in("puma560").unwrap();
    let goal = puma.fk(&[0.3, 0.5, 1.6206, 0.4, 0.7, 0.2]).unwrap();
    let cf = armlab::kinematics::ik::ClosedForm::detect(&puma).unwrap();
    let all = cf.solve(&puma, &Target::Pose(goal)).unwrap();
    assert_eq!(all.solutions.len(), 8);
    assert!(all.solutions.iter().all(|s| !s.within_limits));
    let rep = solve(
        &puma,
        0,
        &Target::Pose(goal),
        &seed,
        &NumericalOptions::default(),
    )
    .unwrap();
    assert!(!rep.converged && rep.position_error > 1e-6, "{rep:?}");
}

#[test]
fn joints_without_limits_do_not_hurt_the_solver() {
    // A user who writes [-pi, pi] "to mean no limits", or gives none, gets a solver at least as
    // good from a fixed seed as with the arm's real limits: first-attempt success (no restarts)
    // over random reachable poses from the "ready" seed.
    let pi = std::f64::consts::PI;
    let puma = built_in("puma560").unwrap();
    let seed = puma.config("ready").unwrap().to_vec();
    let opts = NumericalOptions {
        restarts: 0,
        ..NumericalOptions::default()
    };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let goals: Vec<Pose> = (0..300)
        .map(|_| puma.fk(&random_q(&puma, &mut rng)).unwrap())
        .collect();
    let rate = |r: &Robot| {
        goals
            .iter()
            .filter(|g| {
                solve(r, 0, &Target::Pose(**g), &seed, &opts)
                    .unwrap()
                    .converged
            })
            .count() as f64
            / goals.len() as f64
    };
    let full = rate(&puma_with_limits(Some([-pi, pi])));
    let none = rate(&puma_with_limits(None));
    assert!(full >= 0.9, "[-pi, pi]: {full}");
    assert!(none >= 0.9, "unbounded: {none}");
    // Restarts of an unbounded arm draw from [-pi, pi] per revolute joint: finite answers.
    let free = puma_with_limits(None);
    let far = Pose::translation(5.0, 0.0, 0.0);
    let rep = solve(
        &free,
        0,
        &Target::Pose(far),
        &seed,
        &NumericalOptions::default(),
    )
    .unwrap();
    assert!(
        !rep.converged && rep.q.iter().all(|v| v.is_finite()),
        "{rep:?}"
    );
}
