//! Numerical IK: success rate on random reachable poses, every answer verified by FK, the
//! teaching variants, task masks, the null-space objective, and reports instead of errors.

use armlab::kinematics::ik::numerical::{Method, NumericalOptions, Secondary, TaskMask, solve};
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
        mask: TaskMask([true, true, true, false, false, true]),
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
