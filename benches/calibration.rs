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

criterion_group!(benches, puma_100_poses);
criterion_main!(benches);
