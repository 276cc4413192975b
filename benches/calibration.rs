//! Kinematic calibration speed. Run: `cargo bench --bench calibration`.
//!
//! The Puma 560's 24 DH parameters from 100 full-pose measurements (0.02 mm, 0.05 mrad noise) to
//! convergence, with the identifiability report at the nominal parameters and at the estimate and
//! the uncertainty: the whole `calibrate` call. Also a distance-setup calibration (100 pairs) and
//! the target correction of one pose in its 8 postures.

use armlab::calibration::{
    CalibrationOptions, ParameterModel, Setup, SetupScene, SimulationOptions, calibrate,
    correct_targets, simulate, simulate_setup,
};
use armlab::kinematics::models::built_in;
use armlab::kinematics::pose::Pose;
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Rotation3, Translation3};
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

/// The Puma 560 with a tool 100 mm off the flange: 24 parameters (Hayati's beta2 for d2), 100
/// pairs of joint vectors 300 mm apart (a two-socket artefact), 0.02 mm noise; `calibrate` to
/// convergence with both identifiability reports (3 parameters are kept nominal: 21 estimated).
fn puma_distance_100_pairs(c: &mut Criterion) {
    let mut puma = built_in("puma560").expect("built-in");
    puma.set_tool(
        0,
        Pose::from_parts(Translation3::new(0.05, 0.03, 0.1), Rotation3::identity()),
    )
    .expect("tool");
    let model = ParameterModel::new(&puma)
        .expect("serial DH")
        .with_hayati()
        .expect("standard DH");
    let sim = simulate_setup(
        &model,
        &SetupScene {
            setup: Setup::Distance,
            ..SetupScene::default()
        },
        &SimulationOptions {
            poses: 100,
            validation_poses: 0,
            noise_mm: 0.02,
            ..SimulationOptions::default()
        },
    )
    .expect("simulate");
    let opts = CalibrationOptions {
        position_sigma: 0.02e-3,
        ..CalibrationOptions::default()
    };
    let report = calibrate(&model, &sim.measurements, &opts).expect("calibrate");
    eprintln!(
        "calibration/distance: {} parameters, {} estimated, {} iterations, converged {}",
        model.parameters().len(),
        report.at_estimate.parameter_count,
        report.iterations.len(),
        report.converged
    );
    c.bench_function("calibration/puma560_distance_24_params_100_pairs", |b| {
        b.iter(|| calibrate(&model, black_box(&sim.measurements), &opts).expect("calibrate"))
    });
}

/// Target correction on a calibrated Puma 560: one desired pose, its 8 postures (closed form on
/// the nominal model, Newton on the calibrated one to 1e-12, relabelled, the pose to send).
/// Per pose and posture: the time / 8.
fn puma_target_correction(c: &mut Criterion) {
    let puma = built_in("puma560").expect("built-in");
    let model = ParameterModel::new(&puma)
        .expect("serial DH")
        .with_hayati()
        .expect("standard DH");
    let sim = simulate(&model, &SimulationOptions::default()).expect("simulate");
    let calibrated = model.robot_with(&sim.truth).expect("robot");
    let target = puma.fk(&[0.3, -0.5, 0.4, 0.6, -0.7, 0.2]).expect("fk");
    let rows = correct_targets(&puma, &calibrated, &[target]).expect("correct");
    eprintln!(
        "calibration/target correction: {} postures per pose",
        rows.len()
    );
    c.bench_function(
        "calibration/puma560_target_correction_one_pose_all_postures",
        |b| b.iter(|| correct_targets(&puma, &calibrated, black_box(&[target])).expect("correct")),
    );
}

criterion_group!(
    benches,
    puma_100_poses,
    puma_accuracy_map,
    puma_distance_100_pairs,
    puma_target_correction
);
criterion_main!(benches);
