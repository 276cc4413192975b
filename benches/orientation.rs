//! Orientation conversions (Sect. 2.4): each direction of each representation over a batch of
//! 100,000 distinct random rotations, reported per conversion (criterion's time divided by
//! 100,000; its throughput line is conversions per second). Issue 47's goal: at most 50 ns each.
//! The batch is large on purpose: over 1000 rotations repeated, the branch predictor learns the
//! branches of libm's atan2 and a matrix to Euler angles looks about 30 % faster.
//! Run: `cargo bench --no-default-features --bench orientation` (`RAYON_NUM_THREADS=2` for the
//! parallel batch on two cores).

use armlab::kinematics::EulerKind;
use armlab::kinematics::orientation::{
    Representations, angle_axis_from_rotation, euler_solutions, quaternion_from_rotation,
    quaternion_product, rotation_from_angle_axis, rotation_from_quaternion,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Rotation3, Unit, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::hint::black_box;

const N: usize = 100_000;

fn rotations(n: usize, seed: u64) -> Vec<Rotation3<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let v = Vector3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            Rotation3::from_axis_angle(
                &Unit::new_normalize(v),
                rng.random_range(0.0..std::f64::consts::PI),
            )
        })
        .collect()
}

/// Runs `f` over every input, writing into `out`, as one criterion iteration of N conversions.
fn batch<I, O: Copy>(c: &mut Criterion, name: &str, input: &[I], out: O, f: impl Fn(&I) -> O) {
    let mut g = c.benchmark_group("orientation");
    g.throughput(Throughput::Elements(input.len() as u64));
    let mut outs = vec![out; input.len()];
    g.bench_function(name, |b| {
        b.iter(|| {
            for (i, o) in input.iter().zip(outs.iter_mut()) {
                *o = f(black_box(i));
            }
            black_box(&outs);
        })
    });
    g.finish();
}

fn euler(c: &mut Criterion, rs: &[Rotation3<f64>]) {
    for kind in EulerKind::ALL {
        let angles: Vec<Vector3<f64>> = rs.iter().map(|r| kind.from_rotation(r).angles).collect();
        let k = kind.as_str();
        batch(
            c,
            &format!("{k} to matrix"),
            &angles,
            Rotation3::identity(),
            |a| kind.to_rotation(a),
        );
        batch(c, &format!("matrix to {k}"), rs, Vector3::zeros(), |r| {
            kind.from_rotation(r).angles
        });
        batch(
            c,
            &format!("matrix to {k}, second solution"),
            rs,
            Vector3::zeros(),
            |r| kind.from_rotation_negative(r).angles,
        );
    }
}

fn others(c: &mut Criterion, rs: &[Rotation3<f64>]) {
    let aa: Vec<(f64, Unit<Vector3<f64>>)> = rs
        .iter()
        .map(|r| {
            let a = angle_axis_from_rotation(r);
            (a.angle, a.axis)
        })
        .collect();
    batch(c, "matrix to axis-angle", rs, 0.0, |r| {
        angle_axis_from_rotation(r).angle
    });
    batch(
        c,
        "axis-angle to matrix",
        &aa,
        Rotation3::identity(),
        |(t, a)| rotation_from_angle_axis(*t, a),
    );
    let qs: Vec<UnitQuaternion<f64>> = rs.iter().map(quaternion_from_rotation).collect();
    batch(
        c,
        "matrix to quaternion",
        rs,
        UnitQuaternion::identity(),
        quaternion_from_rotation,
    );
    batch(c, "quaternion to matrix", &qs, Rotation3::identity(), |q| {
        rotation_from_quaternion(q)
    });
    let pairs: Vec<(UnitQuaternion<f64>, UnitQuaternion<f64>)> = qs
        .iter()
        .zip(qs.iter().rev())
        .map(|(a, b)| (*a, *b))
        .collect();
    batch(
        c,
        "quaternion product",
        &pairs,
        UnitQuaternion::identity(),
        |(a, b)| quaternion_product(a, b),
    );
    // For scale: one call of the C library's atan2 (a matrix to Euler angles makes three).
    let yx: Vec<(f64, f64)> = rs.iter().map(|r| (r[(1, 2)], r[(0, 2)])).collect();
    batch(c, "atan2 (libm), for scale", &yx, 0.0, |(y, x)| y.atan2(*x));
    batch(
        c,
        "atan2 (armlab's, in the conversions)",
        &yx,
        0.0,
        |(y, x)| armlab::kinematics::trig::atan2(*y, *x),
    );
    // The teaching API: allocates one Vec per call.
    batch(c, "matrix to both zyz solutions (Vec)", rs, 0usize, |r| {
        euler_solutions(EulerKind::Zyz, r).solutions.len()
    });
    batch(
        c,
        "every representation (Representations::of)",
        rs,
        0.0,
        |r| Representations::of(r).quaternion.w,
    );
}

/// A batch of 1,000,000 matrices to ZYZ angles over every rayon thread (`RAYON_NUM_THREADS=2`
/// for two cores), in chunks and with the orthonormality check of each input, as the Python
/// package's `armlab.rotation` does.
fn parallel(c: &mut Criterion) {
    use rayon::prelude::*;
    let many = rotations(1_000_000, 4747);
    let mut out = vec![Vector3::zeros(); many.len()];
    let mut g = c.benchmark_group("orientation");
    g.throughput(Throughput::Elements(many.len() as u64));
    g.sample_size(10);
    g.bench_function("1,000,000 matrices to zyz, every rayon thread", |b| {
        b.iter(|| {
            out.par_chunks_mut(4096)
                .zip(many.par_chunks(4096))
                .for_each(|(o, r)| {
                    for (o, r) in o.iter_mut().zip(r) {
                        let m = black_box(r).matrix();
                        let error = (m.transpose() * m - nalgebra::Matrix3::identity()).amax();
                        assert!(error <= 1e-6 && m.determinant() > 0.0);
                        *o = EulerKind::Zyz.from_rotation(r).angles;
                    }
                });
            black_box(&out);
        })
    });
    g.finish();
}

fn orientation(c: &mut Criterion) {
    let rs = rotations(N, 47);
    euler(c, &rs);
    others(c, &rs);
    parallel(c);
}

criterion_group!(benches, orientation);
criterion_main!(benches);
