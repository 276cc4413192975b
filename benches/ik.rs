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

criterion_group!(benches, closed_form, numerical);
criterion_main!(benches);

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
