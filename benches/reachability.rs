//! Reachability maps (issue 49): every sample of a coarse map solved in closed form, for the
//! UR5, the Puma 560 and the default robot, reported per sample so that the full maps
//! (5 cm, 200 directions x 8 rolls: `armlab reachability ... --out map.npz` under
//! `/usr/bin/time -v`, README) can be read off. Goal: the UR5's full map in at most 60 s on two
//! cores.
//! Run: `cargo bench --no-default-features --bench reachability`.

use armlab::kinematics::Robot;
use armlab::kinematics::models::built_in;
use armlab::reachability::{MapControl, MapOptions, compute_reachability};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::Path;

/// The 200 directions x 8 rolls over a 25 cm grid (a few hundred voxels).
fn coarse() -> MapOptions {
    MapOptions {
        voxel_m: 0.25,
        ..MapOptions::default()
    }
}

fn bench_robot(c: &mut Criterion, name: &str, robot: &Robot) {
    let opts = coarse();
    let map = compute_reachability(robot, &opts, None, MapControl::default()).expect("a map");
    let centre = nalgebra::Vector3::from(map.reach_centre);
    // Voxels inside the reach sphere: the ones solved.
    let solved = (0..map.grid.len())
        .filter(|&v| {
            let c = nalgebra::Vector3::from(map.grid.centre(map.grid.ijk(v)));
            (c - centre).norm() <= map.reach_m
        })
        .count();
    let samples = (solved * map.per_voxel()) as u64;
    eprintln!(
        "{name}: {} voxels, {solved} solved, {samples} samples solved, {:.1} % reached",
        map.grid.len(),
        100.0 * map.reached_count() as f64 / map.reachable.len() as f64
    );
    let mut group = c.benchmark_group("reachability");
    group.sample_size(10);
    group.throughput(Throughput::Elements(samples));
    group.bench_function(format!("{name}: 25 cm, 200 x 8, every sample"), |b| {
        b.iter(|| {
            black_box(
                compute_reachability(robot, black_box(&opts), None, MapControl::default())
                    .expect("a map"),
            )
        })
    });
    group.finish();
}

fn maps(c: &mut Criterion) {
    let urdf = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/urdf_corpus/ur5_robot.urdf");
    let text = std::fs::read_to_string(&urdf).expect("the UR5 URDF");
    let ur5 = armlab::urdf::parse_urdf(&text, &urdf).expect("a URDF");
    bench_robot(c, "ur5", &ur5);
    bench_robot(c, "puma560", &built_in("puma560").expect("puma"));
    bench_robot(
        c,
        "anthropomorphic_spherical_wrist",
        &built_in("anthropomorphic_spherical_wrist").expect("default"),
    );
}

criterion_group!(benches, maps);
criterion_main!(benches);
