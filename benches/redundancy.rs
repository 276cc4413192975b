//! Redundancy (Sect. 2.10.2): all 8 SRS branches at one arm angle (goal <= 1 us), the feasible
//! arm angles of all branches (goal <= 20 us), a 360-sample manifold of all branches (goal
//! <= 0.5 ms), and the planar arm's exact feasible phi intervals.
//! Run: `cargo bench --bench redundancy`.

use armlab::kinematics::models::built_in;
use armlab::redundancy::PlanarSelfMotion;
use armlab::redundancy::srs::SrsArm;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn srs(c: &mut Criterion) {
    let robot = built_in("dlr").unwrap();
    let arm = SrsArm::detect(&robot).unwrap();
    let target = robot.fk(&[0.3, 0.6, -0.4, 1.1, 0.5, -0.7, 0.2]).unwrap();
    let mut out = [[0.0; 7]; 8];
    let mut g = c.benchmark_group("redundancy/srs");
    g.bench_function("dlr all 8 branches at one psi (solve_raw)", |b| {
        b.iter(|| arm.solve_raw(black_box(&target), black_box(0.4), &mut out))
    });
    g.bench_function("dlr feasible arm angles of all branches", |b| {
        b.iter(|| arm.feasible_intervals(black_box(&target)))
    });
    g.bench_function(
        "dlr 360-sample manifold, all branches (solve_raw each)",
        |b| {
            b.iter(|| {
                let mut n = 0u32;
                for k in 0..360 {
                    let psi = -std::f64::consts::PI + k as f64 * std::f64::consts::TAU / 360.0;
                    n += arm.solve_raw(&target, psi, &mut out).count_ones();
                }
                n
            })
        },
    );
    g.bench_function(
        "dlr 360-sample manifold, all branches (prepared once)",
        |b| {
            b.iter(|| {
                let p = arm.prepare(black_box(&target));
                let mut n = 0u32;
                for k in 0..360 {
                    let psi = -std::f64::consts::PI + k as f64 * std::f64::consts::TAU / 360.0;
                    n += arm.solve_prepared(&p, psi, &mut out).count_ones();
                }
                n
            })
        },
    );
    let p = arm.prepare(&target);
    g.bench_function(
        "dlr all 8 branches at one psi, target prepared (solve_prepared)",
        |b| b.iter(|| arm.solve_prepared(black_box(&p), black_box(0.4), &mut out)),
    );
    g.finish();
}

/// The Panda by q7: all 8 branches at one q7, and the feasible q7 intervals with the manifold
/// count (the limit crossings of joints 1-3, 5, 6 bracketed on 2048 steps).
fn panda(c: &mut Criterion) {
    use armlab::redundancy::offset_elbow::OffsetElbowArm;
    let robot = built_in("panda").unwrap();
    let arm = OffsetElbowArm::detect(&robot).unwrap();
    let target = robot.fk(&[0.4, 0.3, -0.5, -1.6, 0.8, 1.2, -0.3]).unwrap();
    let mut out = [[0.0; 7]; 8];
    let mut g = c.benchmark_group("redundancy/panda");
    g.bench_function("all 8 branches at one q7 (solve_raw)", |b| {
        b.iter(|| arm.solve_raw(black_box(&target), black_box(0.4), &mut out))
    });
    g.sample_size(20);
    g.bench_function("feasible q7 intervals and manifold count", |b| {
        b.iter(|| arm.feasible_and_manifolds(black_box(&target)))
    });
    g.finish();
}

fn planar(c: &mut Criterion) {
    let robot = built_in("planar3").unwrap();
    let m = PlanarSelfMotion::new(&robot, [0.6, 0.1]).unwrap();
    c.bench_function("redundancy/planar3 feasible phi intervals", |b| {
        b.iter(|| black_box(&m).feasible())
    });
}

/// One numerical self-motion step (tangent + Newton correction) of the humanoid's arm with its
/// torso (10 joints move the hand; goal <= 20 us).
fn numerical(c: &mut Criterion) {
    let robot = built_in("humanoid").unwrap();
    let q0 = robot
        .config("ready")
        .map_or_else(|| vec![0.1; robot.dof()], <[f64]>::to_vec);
    let mut m = armlab::redundancy::numerical::NullSpaceMotion::new(&robot, 0, &q0, None).unwrap();
    let mut sign = 1.0;
    c.bench_function("redundancy/humanoid arm+torso one self-motion step", |b| {
        b.iter(|| {
            sign = -sign;
            m.step(black_box(sign * 1e-3)).unwrap()
        })
    });
}

criterion_group!(benches, srs, panda, planar, numerical);
criterion_main!(benches);
