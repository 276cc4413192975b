//! Direct kinematics speed: one 6-DOF pose, and a batch of 1000 (reported per pose).
//! Run: `cargo bench --bench fk`.

use armlab::kinematics::Pose;
use armlab::kinematics::models::built_in;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Matrix6xX;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

fn fk(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for name in ["puma560", "panda"] {
        let robot = built_in(name).expect("built-in");
        let limits = robot.limits();
        let batch: Vec<Vec<f64>> = (0..1000)
            .map(|_| {
                limits
                    .iter()
                    .map(|l| rng.random_range(l[0]..=l[1]))
                    .collect()
            })
            .collect();
        let q = batch[0].clone();
        c.bench_function(&format!("fk/{name}/one pose"), |b| {
            b.iter(|| robot.fk(black_box(&q)).unwrap())
        });
        let mut g = c.benchmark_group(format!("fk/{name}/batch"));
        g.throughput(Throughput::Elements(batch.len() as u64));
        let mut out = vec![Pose::identity(); batch.len()];
        g.bench_function("1000 poses", |b| {
            b.iter(|| {
                for (q, o) in batch.iter().zip(out.iter_mut()) {
                    *o = robot.fk(black_box(q)).unwrap();
                }
            })
        });
        g.finish();
        let mut frames = vec![Pose::identity(); robot.joints().len()];
        let mut jac = Matrix6xX::zeros(robot.dof());
        c.bench_function(&format!("jacobian/{name}"), |b| {
            b.iter(|| {
                robot
                    .jacobian_into(black_box(&q), 0, &mut frames, &mut jac)
                    .unwrap()
            })
        });
    }
}

criterion_group!(benches, fk);
criterion_main!(benches);
