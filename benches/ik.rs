//! Inverse kinematics speed. Run: `cargo bench --bench ik`.
//!
//! Besides criterion's timings, prints per-solve median and p95 and the success rate of the
//! numerical solver over 2000 random reachable poses (tolerance 1e-10), the figures the README's
//! performance table quotes.

use armlab::kinematics::ik::Target;
use armlab::kinematics::ik::numerical::{NumericalOptions, solve};
use armlab::kinematics::models::built_in;
use criterion::{Criterion, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;
use std::time::Instant;

fn targets(name: &str, n: usize) -> Vec<Target> {
    let robot = built_in(name).expect("built-in");
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

fn numerical(c: &mut Criterion) {
    let opts = NumericalOptions::default();
    for name in ["puma560", "panda"] {
        let robot = built_in(name).expect("built-in");
        let seed = robot.config("ready").expect("ready").to_vec();
        let ts = targets(name, 2000);
        // Per-solve distribution.
        let mut times = Vec::with_capacity(ts.len());
        let mut ok = 0;
        for t in &ts {
            let start = Instant::now();
            let rep = solve(&robot, 0, t, &seed, &opts).expect("valid input");
            times.push(start.elapsed().as_secs_f64() * 1e6);
            ok += usize::from(rep.converged);
        }
        times.sort_by(f64::total_cmp);
        eprintln!(
            "ik/numerical/{name}: success {:.2} %, median {:.1} us, p95 {:.1} us (n = {}, tol 1e-10)",
            100.0 * ok as f64 / ts.len() as f64,
            times[times.len() / 2],
            times[times.len() * 95 / 100],
            ts.len()
        );
        let mut i = 0;
        c.bench_function(&format!("ik/numerical/{name}"), |b| {
            b.iter(|| {
                i = (i + 1) % ts.len();
                solve(&robot, 0, black_box(&ts[i]), &seed, &opts).expect("valid input")
            })
        });
    }
}

criterion_group!(benches, closed_form, numerical);
criterion_main!(benches);

fn closed_form(c: &mut Criterion) {
    use armlab::kinematics::ik::ClosedForm;
    use armlab::kinematics::ik::closed_form::RawSolutions;
    for name in ["puma560", "anthropomorphic_spherical_wrist"] {
        let robot = built_in(name).expect("built-in");
        let cf = ClosedForm::detect(&robot).expect("closed form");
        let poses: Vec<_> = targets(name, 2000)
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
