//! Workspace speed (Sect. 2.10.1): sampled positions per second (goal: >= 20 M/s over two cores
//! for the three-link planar arm, positions only), with posture classes and manipulability, and
//! the closed-form region grids. Run: `cargo bench --bench workspace`; the sampler uses rayon's
//! global pool (set RAYON_NUM_THREADS=2 to compare with the goal).

use armlab::kinematics::models::built_in;
use armlab::model_file::load_model_file;
use armlab::workspace::{
    ExactPlanar, GridOptions, MapRequest, MapValues, MapView, PointQuery, SampleOptions,
    TrackedPoint, analyze_grid, compute_map, map_statistics, sample,
};
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

/// The exact maps behind the figures: Problem 2.17 at 1600 x 1200 cells (exact regions, edges
/// supersampled), the Puma 560's side view (wrist centre) at 1200 x 900, the dexterity side view
/// of the anthropomorphic arm with spherical wrist at 128 x 128, and the statistics.
fn maps(c: &mut Criterion) {
    let mut g = c.benchmark_group("workspace/map");
    g.sample_size(10);
    let planar3 = built_in("planar3").unwrap();
    let puma = built_in("puma560").unwrap();
    let arm = built_in("anthropomorphic_spherical_wrist").unwrap();
    let cases = [
        (
            "planar3 exact 1600x1200",
            &planar3,
            MapView::Plane,
            MapValues::Classes,
            [1600, 1200],
            TrackedPoint::Flange,
        ),
        (
            "planar3 dexterity 1600x1200",
            &planar3,
            MapView::Plane,
            MapValues::Dexterity,
            [1600, 1200],
            TrackedPoint::Flange,
        ),
        (
            "puma560 side 1200x900",
            &puma,
            MapView::Side,
            MapValues::Classes,
            [1200, 900],
            TrackedPoint::WristCentre,
        ),
        (
            "puma560 top 1200x900",
            &puma,
            MapView::Top,
            MapValues::Classes,
            [1200, 900],
            TrackedPoint::WristCentre,
        ),
        (
            "arm+wrist flange top 1200x900 (exact, wrist-centre workspace + sphere)",
            &arm,
            MapView::Top,
            MapValues::Classes,
            [1200, 900],
            TrackedPoint::Flange,
        ),
        (
            "arm+wrist flange side 1200x900 (exact, wrist-centre workspace + sphere)",
            &arm,
            MapView::Side,
            MapValues::Classes,
            [1200, 900],
            TrackedPoint::Flange,
        ),
        (
            "arm+wrist dexterity side 128x128",
            &arm,
            MapView::Side,
            MapValues::Dexterity,
            [128, 128],
            TrackedPoint::Flange,
        ),
    ];
    for (id, robot, view, values, cells, point) in cases {
        let req = MapRequest {
            view,
            values,
            cells,
            point,
            ..MapRequest::default()
        };
        g.bench_function(id, |b| {
            b.iter(|| compute_map(black_box(robot), &req).unwrap())
        });
    }
    g.bench_function("planar3 exact workspace (boundary arcs, areas)", |b| {
        b.iter(|| ExactPlanar::new(black_box(&planar3)).unwrap())
    });
    g.bench_function(
        "arm+wrist flange statistics (Pappus volume, exact reach)",
        |b| {
            b.iter(|| {
                map_statistics(black_box(&arm), TrackedPoint::Flange, &Default::default()).unwrap()
            })
        },
    );
    g.bench_function("puma560 statistics (Pappus volume)", |b| {
        b.iter(|| {
            map_statistics(
                black_box(&puma),
                TrackedPoint::WristCentre,
                &Default::default(),
            )
            .unwrap()
        })
    });
    g.finish();
}

/// Point queries of `armlab reach`: membership, postures and exact distance (planar3).
fn point_queries(c: &mut Criterion) {
    let q = PointQuery::new(&built_in("planar3").unwrap(), TrackedPoint::Flange).unwrap();
    let pts: Vec<[f64; 2]> = (0..1000)
        .map(|k| {
            let t = k as f64 * 0.618_033_988_75;
            [-0.4 + 1.45 * t.fract(), -1.05 + 2.1 * (t * 7.3).fract()]
        })
        .collect();
    let mut g = c.benchmark_group("workspace/reach");
    g.throughput(Throughput::Elements(pts.len() as u64));
    g.bench_function("planar3 1000 points", |b| {
        b.iter(|| {
            pts.iter()
                .map(|p| q.query(black_box(p)).distance)
                .sum::<f64>()
        })
    });
    g.finish();
}

criterion_group!(benches, sampling, grids, maps, point_queries);
criterion_main!(benches);
