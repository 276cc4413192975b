//! Inverse kinematics speed. Run: `cargo bench --bench ik`.
//!
//! Besides criterion's timings, prints per-solve median and p95 and the success rate of the
//! numerical solver over 2000 random reachable poses (tolerance 1e-10), the figures the performance
//! table quotes.

use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::numerical::{NumericalOptions, solve};
use armlab::kinematics::models::built_in;
use criterion::{Criterion, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Instant;

/// `n` poses of `robot` at random joint vectors inside its limits (seeded).
fn targets_of(robot: &armlab::kinematics::Robot, n: usize) -> Vec<Target> {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    (0..n)
        .map(|_| {
            let q: Vec<f64> = robot
                .limits()
                .iter()
                .map(|l| rng.random_range(l[0]..=l[1]))
                .collect();
            Target::Pose(robot.fk(&q).expect("fk"))
        })
        .collect()
}

/// The seeds of the success and timing figures: "near" (the target's own q moved by up to
/// 0.1 rad or m per joint, then clamped), "zero", and "home" (the "ready" configuration).
fn seeds(robot: &armlab::kinematics::Robot, q_true: &[f64], rng: &mut ChaCha8Rng) -> [Vec<f64>; 3] {
    let near = q_true
        .iter()
        .zip(robot.limits())
        .map(|(v, l)| (v + rng.random_range(-0.1..0.1)).clamp(l[0], l[1]))
        .collect();
    let home = robot.config("ready").expect("ready").to_vec();
    [near, vec![0.0; robot.dof()], home]
}

fn numerical(c: &mut Criterion) {
    let opts = NumericalOptions::default();
    for name in ["puma560", "panda"] {
        let robot = built_in(name).expect("built-in");
        let mut rng = ChaCha8Rng::seed_from_u64(42);
        let n = 2000;
        let cases: Vec<(Target, [Vec<f64>; 3])> = (0..n)
            .map(|_| {
                let q: Vec<f64> = robot
                    .limits()
                    .iter()
                    .map(|l| rng.random_range(l[0]..=l[1]))
                    .collect();
                let t = Target::Pose(robot.fk(&q).expect("fk"));
                (t, seeds(&robot, &q, &mut rng))
            })
            .collect();
        // Per-solve distribution, per seed.
        for (k, seed_name) in ["near", "zero", "home"].iter().enumerate() {
            let mut times = Vec::with_capacity(n);
            let mut ok = 0;
            for (t, s) in &cases {
                let start = Instant::now();
                let rep = solve(&robot, 0, t, &s[k], &opts).expect("valid input");
                times.push(start.elapsed().as_secs_f64() * 1e6);
                ok += usize::from(rep.converged);
            }
            times.sort_by(f64::total_cmp);
            eprintln!(
                "ik/numerical/{name}/{seed_name}: success {:.2} %, median {:.1} us, p95 {:.1} us (n = {n}, tol 1e-10)",
                100.0 * ok as f64 / n as f64,
                times[n / 2],
                times[n * 95 / 100],
            );
        }
        let mut i = 0;
        c.bench_function(&format!("ik/numerical/{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % cases.len();
                let (t, s) = &cases[i];
                solve(&robot, 0, black_box(t), &s[2], &opts).expect("valid input")
            })
        });
    }
}

criterion_group!(benches, closed_form, locked7, numerical);
criterion_main!(benches);

/// The general arm of `tests/kinematics/ik_general6.rs` with 14 real solutions at one pose.
fn general6() -> armlab::kinematics::Robot {
    use armlab::kinematics::{Convention, DhJoint, DhRow, Pose, Robot};
    let arm = [
        (-0.16783737474333676, 1.0052561698243567, 0.2659782754010333),
        (
            -0.20021619228968035,
            -2.0083552205516653,
            0.5956370685537575,
        ),
        (0.2936438967887273, -1.0416631758468398, 0.5822396042478765),
        (-0.5561143422303767, 3.1085585463184633, 0.2553345078792291),
        (0.30384208036121435, -0.9355901363914724, 0.5776510034128405),
        (
            0.00958484907078212,
            1.9354200442639786,
            -0.13873531864068797,
        ),
    ];
    let joints: Vec<DhJoint> = arm
        .iter()
        .map(|&(a, alpha, d)| {
            let row = DhRow {
                a,
                alpha,
                d,
                theta: 0.0,
            };
            DhJoint::revolute(row).limits(-std::f64::consts::PI, std::f64::consts::PI)
        })
        .collect();
    Robot::from_dh(
        "general6",
        Convention::Standard,
        &joints,
        Pose::identity(),
        Pose::identity(),
    )
    .expect("general arm")
}

/// The Kinova Gen3 (7 joints) with q3 locked: every solution at one value of q3, the work of one
/// step of the exact self-motion (issue 27).
fn locked7(c: &mut Criterion) {
    use armlab::kinematics::ik::closed_form::{LockedArm, MAX_LOCKED_SOLUTIONS};
    let full = armlab::model_file::load_model("tests/data/urdf_corpus/kinova_gen3_7dof.urdf")
        .expect("Gen3");
    let robot = armlab::kinematics::arm::arm_of(&full, 0, &full.ready_or_zero())
        .expect("arm")
        .robot;
    let locked = LockedArm::new(&robot, 2).expect("7R arm");
    // Poses at random joint vectors (continuous joints within one turn), q3 = 0.3 as locked.
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let poses: Vec<_> = (0..500)
        .map(|_| {
            let mut q: Vec<f64> = robot
                .limits()
                .iter()
                .map(|l| rng.random_range(l[0].max(-3.1)..=l[1].min(3.1)))
                .collect();
            q[2] = 0.3;
            robot.fk(&q).expect("fk")
        })
        .collect();
    let mut out = [[0.0; 7]; MAX_LOCKED_SOLUTIONS];
    let mut i = 0;
    c.bench_function("ik/locked_q3/kinova_gen3_7dof", |b| {
        b.iter(|| {
            i = (i + 1) % poses.len();
            locked
                .solve(black_box(&poses[i]), 0.3, &mut out)
                .unwrap_or(0)
        })
    });
}

fn closed_form(c: &mut Criterion) {
    use armlab::kinematics::ik::ClosedForm;
    use armlab::kinematics::ik::closed_form::{RawSolutions, Solutions, Verify};
    // The UR5 as its URDF (the corpus copy) gives, Universal Robots' family (issue 27).
    let ur5 = armlab::model_file::load_model("tests/data/urdf_corpus/ur5_robot.urdf").expect("UR5");
    let robots = [
        ("puma560", built_in("puma560").expect("built-in")),
        (
            "anthropomorphic_spherical_wrist",
            built_in("anthropomorphic_spherical_wrist").expect("built-in"),
        ),
        ("ur5_urdf", ur5),
        // A spherical wrist on a skewed three-revolute arm: Pieper's general case, a quartic
        // (issue 27).
        (
            "skewed_arm_wrist",
            armlab::model_file::load_model("assets/robots/skewed_arm_wrist.toml")
                .expect("skewed arm"),
        ),
        // A ball shoulder (axes 1-3 meet): the anthropomorphic arm with spherical wrist read from
        // the tool back to the base (issue 27).
        (
            "ball_shoulder_arm",
            armlab::model_file::load_model("assets/robots/ball_shoulder_arm.toml")
                .expect("ball-shoulder arm"),
        ),
        // Axes 2-4 parallel, the rest skewed: theta1 from a quartic (issue 27).
        (
            "three_parallel_arm",
            armlab::model_file::load_model("assets/robots/three_parallel_arm.toml")
                .expect("three-parallel arm"),
        ),
        // A general six-revolute arm (no two axes parallel or meeting): every real solution by
        // elimination (issue 27); this arm has up to 14.
        ("general6", general6()),
    ];
    for (name, robot) in robots {
        let cf = ClosedForm::detect(&robot).expect("closed form");
        let poses: Vec<_> = targets_of(&robot, 2000)
            .into_iter()
            .map(|t| match t {
                Target::Pose(p) => p,
                _ => unreachable!(),
            })
            .collect();
        let mut out = RawSolutions::default();
        let mut i = 0;
        c.bench_function(&format!("ik/closed_form_all/{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % poses.len();
                cf.solve_raw(black_box(&poses[i]), &mut out)
                    .expect("valid pose")
            })
        });
        // The labelled calls, in the same run as the raw one: postures, wrapping, limit flags and
        // duplicate removal (`Verify::Limits`); the same with every solution FK-verified
        // (`Verify::Fk`); and the allocating `solve` (Vec, String labels) built on the latter.
        let targets: Vec<Target> = poses.iter().map(|p| Target::Pose(*p)).collect();
        let mut sols = Solutions::default();
        for (label, verify) in [("labelled", Verify::Limits), ("labelled_fk", Verify::Fk)] {
            let mut i = 0;
            c.bench_function(&format!("ik/closed_form_{label}/{name}"), |b| {
                b.iter(|| {
                    i = (i + 1) % targets.len();
                    cf.solve_into(&robot, black_box(&targets[i]), verify, &mut sols)
                        .expect("valid pose");
                    sols.len()
                })
            });
        }
        let mut i = 0;
        c.bench_function(&format!("ik/closed_form_all_verified/{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % poses.len();
                cf.solve(&robot, black_box(&Target::Pose(poses[i])))
                    .expect("valid pose")
            })
        });
    }
}
