//! Workspace speed (Sect. 2.10.1): sampled positions per second (goal: >= 20 M/s over two cores
//! for the three-link planar arm, positions only), with posture classes and manipulability, and
//! the closed-form region grids. Run: `cargo bench --bench workspace`; the sampler uses rayon's
//! global pool (set RAYON_NUM_THREADS=2 to compare with the goal).

use armlab::kinematics::models::built_in;
use armlab::model_file::load_model_file;
use armlab::workspace::{GridOptions, SampleOptions, analyze_grid, sample};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use std::path::PathBuf;

fn none(_: usize) {}

fn sampling(c: &mut Criterion) {
    let n = 1_000_000;
    let cases = [
        ("planar3", false, false),
        ("planar3", true, false),
        ("planar3", false, true),
        ("puma560", false, false),
        ("puma560", true, false),
    ];
    let mut g = c.benchmark_group("workspace/sample");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    for (name, classes, manipulability) in cases {
        let robot = built_in(name).expect("built-in");
        let opts = SampleOptions {
            samples: n,
            seed: 1,
            classes,
            manipulability,
            ..SampleOptions::default()
        };
        let id = format!(
            "{name}{}{}",
            if classes { " +classes" } else { "" },
            if manipulability {
                " +manipulability"
            } else {
                ""
            }
        );
        g.bench_function(id, |b| {
            b.iter(|| sample(black_box(&robot), &opts, &none).unwrap())
        });
    }
    g.finish();
}

fn grids(c: &mut Criterion) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/robots/planar2_limited.toml");
    let limited = load_model_file(&path).expect("model file");
    let mut g = c.benchmark_group("workspace/grid");
    g.sample_size(10);
    let cases = [
        ("planar2_limited 400x400", limited, 400, 64),
        (
            "planar3 200x200 x 64 phi",
            built_in("planar3").unwrap(),
            200,
            64,
        ),
        (
            "anthropomorphic_spherical_wrist 24^3 x 64 approach",
            built_in("anthropomorphic_spherical_wrist").unwrap(),
            24,
            64,
        ),
    ];
    for (id, robot, resolution, orientations) in cases {
        let opts = GridOptions {
            resolution,
            orientations,
            samples: 100_000,
            ..GridOptions::default()
        };
        g.bench_function(id, |b| {
            b.iter(|| analyze_grid(black_box(&robot), &opts, &none).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, sampling, grids);
criterion_main!(benches);
