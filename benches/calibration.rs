//! Kinematic calibration speed. Run: `cargo bench --bench calibration`.
//!
//! The Puma 560's 24 DH parameters from 100 full-pose measurements (0.02 mm, 0.05 mrad noise) to
//! convergence, with the identifiability report at the nominal parameters and at the estimate and
//! the uncertainty: the whole `calibrate` call.

use armlab::calibration::{
    CalibrationOptions, ParameterModel, SimulationOptions, calibrate, simulate,
};
use armlab::kinematics::models::built_in;
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn puma_100_poses(c: &mut Criterion) {
    let puma = built_in("puma560").expect("built-in");
    let model = ParameterModel::new(&puma).expect("serial DH");
    let sim = simulate(
        &model,
        &SimulationOptions {
            poses: 100,
            noise_mm: 0.02,
            noise_mrad: 0.05,
            ..SimulationOptions::default()
        },
    )
    .expect("simulate");
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        orientation_sigma: 0.05e-3,
        ..CalibrationOptions::default()
    };
    let report = calibrate(&model, &sim.measurements, &opts).expect("calibrate");
    eprintln!(
        "calibration/puma560/100 poses: {} iterations, converged {}",
        report.iterations.len(),
        report.converged
    );
    c.bench_function("calibration/puma560_24_params_100_poses", |b| {
        b.iter(|| calibrate(&model, black_box(&sim.measurements), &opts).expect("calibrate"))
    });
}

/// The Puma's accuracy map (nominal vs a simulated real arm), 256 x 256 cells from 1,000,000
/// joint vectors: what `armlab calibrate --accuracy-map` computes per figure.
fn puma_accuracy_map(c: &mut Criterion) {
    let puma = built_in("puma560").expect("built-in");
    let model = ParameterModel::new(&puma).expect("serial DH");
    let sim = simulate(&model, &SimulationOptions::default()).expect("simulate");
    let nominal = model.nominal();
    let mut g = c.benchmark_group("calibration");
    g.sample_size(10);
    g.bench_function("puma560_accuracy_map_256x256_1M_samples", |b| {
        b.iter(|| {
            armlab::calibration::accuracy_map(
                &model,
                &nominal,
                black_box(&sim.truth),
                [256, 256],
                1_000_000,
                1,
            )
            .expect("map")
        })
    });
    g.finish();
}

criterion_group!(benches, puma_100_poses, puma_accuracy_map);
criterion_main!(benches);
